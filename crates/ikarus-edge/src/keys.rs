//! Keyframes per effector (`ikarus animate --rig FILE --keys KEYS.json`, `POST /api/animate`
//! with `keys`): the KEYS shape, one for the command line's file, the API's field and the
//! playground's project file, its checks ([`KeysFile::check`], every problem naming the field
//! `keys.…` and the value), and the plan they make ([`KeyPlan`]): per tracked bone a
//! [`KeyTrack`] of its targets, per bent bone its step keys, the pinned bones, the frames.
//! The motion itself, one rig solve per frame, is [`motion`].
//!
//! ```json
//! {"fps": 30,
//!  "tracks": {"left_foot": [{"time": 0.0, "x": 0.1, "y": -0.9, "ease": "sine"}, …]},
//!  "bends": {"left_shin": [{"time": 0.0, "bend": "ccw"}, {"time": 0.5, "bend": "cw"}]},
//!  "pins": ["right_foot"],
//!  "duration": 2.0}
//! ```
//!
//! `duration` (seconds, optional) is the motion's length: the frames run to it, each track
//! holding its last key after its end (and a character's clip under the keys playing on); it is
//! at least the last key's time and on a frame. Without it the motion ends at the last key. A
//! character's keys may also turn bones by hand ([`rotations`]): `"rotations": {"BONE":
//! [{"time": 0.2, "angle_deg": 30}]}`.

use std::collections::BTreeMap;

use ikarus::motion::KeyTrack;
use ikarus::number::Num;
use ikarus::{Bend, Ease, EaseKind, Joint, Skeleton};
use serde::Deserialize;

use crate::ease_args::{EaseProblem, choose_ease};
use crate::error::Error;
use crate::names::cell;

pub mod character;
pub mod motion;
pub mod rotations;

pub use rotations::RotationKeyReq;

/// Frames per second when the keys give none.
pub const DEFAULT_KEY_FPS: f64 = 30.0;
/// The largest `fps`.
pub const MAX_KEY_FPS: f64 = 240.0;
/// Most tracks and pins together.
pub const MAX_TRACKS: usize = 64;
/// Most keys of one track (and of one bone's bends).
pub const MAX_KEYS: usize = 1000;

/// The KEYS shape as read (see the module docs); every field is checked by [`KeysFile::check`].
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeysFile {
    /// Frames per second [default: 30], in (0, 240].
    #[serde(default)]
    pub fps: Option<f64>,
    /// Bone name → its tip's target keys.
    #[serde(default)]
    pub tracks: BTreeMap<String, Vec<KeyReq>>,
    /// Bone name → the bend keys of its joint with its parent.
    #[serde(default)]
    pub bends: BTreeMap<String, Vec<BendKeyReq>>,
    /// Bones whose tips hold where the start pose has them (position and direction).
    #[serde(default)]
    pub pins: Vec<String>,
    /// The motion's length, seconds (see the module docs); none: the last key's time.
    #[serde(default)]
    pub duration: Option<f64>,
    /// Bone name → its local rotation's keys (a character's only: [`rotations`]).
    #[serde(default)]
    pub rotations: BTreeMap<String, Vec<RotationKeyReq>>,
}

/// One key of a track: the target of the bone's tip at `time` seconds, and the ease of the
/// segment from this key to the next.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyReq {
    /// When the target holds, seconds: 0 for a track's first key, on a frame, increasing.
    pub time: f64,
    /// The target's x.
    pub x: f64,
    /// The target's y.
    pub y: f64,
    /// The bone's absolute direction at the key, degrees (on every key of a track or on none).
    #[serde(default)]
    pub angle_deg: Option<f64>,
    /// `linear`, `sine` (the default), `parent` or `smoothstep`.
    #[serde(default)]
    pub ease: Option<EaseKind>,
    /// The `parent` ease's end of acceleration (see `k2`).
    #[serde(default)]
    pub k1: Option<f64>,
    /// The `parent` ease's start of deceleration (with `k1`: `0 ≤ k1 ≤ k2 ≤ 1`).
    #[serde(default)]
    pub k2: Option<f64>,
}

/// Which way a joint bends from `time` on: `ccw` or `cw`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BendKeyReq {
    /// The time the bend takes effect, seconds: 0 for a bone's first key, on a frame, increasing.
    pub time: f64,
    /// Which way the joint bends from then on.
    pub bend: BendName,
}

/// `ccw` (the joint's angle in [0°, 180°]) or `cw` (in [−180°, 0°]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BendName {
    /// Counter-clockwise: the joint's angle in [0°, 180°].
    Ccw,
    /// Clockwise: the joint's angle in [−180°, 0°].
    Cw,
}

impl BendName {
    /// The library's bend.
    pub fn bend(self) -> Bend {
        match self {
            BendName::Ccw => Bend::Positive,
            BendName::Cw => Bend::Negative,
        }
    }

    /// As written.
    pub fn name(self) -> &'static str {
        match self {
            BendName::Ccw => "ccw",
            BendName::Cw => "cw",
        }
    }
}

/// One tracked bone: its keys as a track of `x`, `y` (and the direction in radians when its
/// keys give one).
#[derive(Debug, Clone)]
pub struct KeyedBone {
    /// The bone's index in the skeleton.
    pub bone: usize,
    /// Its keys' values with their eases: per key `x`, `y` (and the direction, radians) for a
    /// tracked tip; the local rotation, degrees, for a bone turned by hand.
    pub track: KeyTrack,
    /// Whether its keys give a direction (`angle_deg`).
    pub oriented: bool,
}

/// Bends by bone (or constraint): `(index, [(first frame, bend)])`, in time order.
pub type Bends = Vec<(usize, Vec<(usize, Bend)>)>;

/// The checked keys of a character ([`KeysFile::check_character`]).
#[derive(Debug, Clone)]
pub struct CharacterKeys {
    /// Frames per second, in (0, 240].
    pub fps: f64,
    /// The target bones' tracks.
    pub tracks: Vec<KeyedBone>,
    /// The two-bone IK constraints' bends, by constraint.
    pub bends: Bends,
    /// The bones turned by hand: each one's local rotation track (one value, degrees).
    pub rotations: Vec<KeyedBone>,
    /// The motion's length, seconds: `duration`, else the last key's time.
    pub duration: f64,
}

/// The checked keys of a rig: what each frame solves.
#[derive(Debug, Clone)]
pub struct KeyPlan {
    /// Frames per second, in (0, 240].
    pub fps: f64,
    /// Frames `0..=last` at `k / fps` seconds.
    pub last: usize,
    /// The tracked bones in the keys' order (by name).
    pub tracks: Vec<KeyedBone>,
    /// Bone → its bends by first frame, in time order.
    pub bends: Bends,
    /// The pinned bones, in the keys' order.
    pub pins: Vec<usize>,
}

impl KeyPlan {
    /// The number of frames.
    pub fn frames(&self) -> usize {
        self.last + 1
    }

    /// The time of frame `k`, seconds: `k / fps`.
    pub fn time(&self, k: usize) -> f64 {
        k as f64 / self.fps
    }

    /// The duration: the last frame's time.
    pub fn duration(&self) -> f64 {
        self.time(self.last)
    }
}

/// The index of the frame at `time` if the time lies on one at `fps`:
/// `|time·fps − round(time·fps)| ≤ 1e-9·max(1, time·fps)`; else the message after the value.
fn frame_of(time: f64, fps: f64) -> Result<usize, Error> {
    let f = time * fps;
    let k = f.round();
    if (f - k).abs() <= 1e-9 * f.max(1.0) {
        return Ok(k as usize);
    }
    let (below, above) = (f.floor() / fps, f.ceil() / fps);
    let nearest = if f - f.floor() <= f.ceil() - f { below } else { above };
    Err(Error::input(format!("not on a frame at {} fps (nearest frame time {})", Num(fps), Num(nearest))))
}

/// Checks the key times of one track (`field` is `keys.tracks.NAME` or `keys.bends.NAME`): at
/// least one key, at most [`MAX_KEYS`], the first at 0, strictly increasing, finite, each on a
/// frame; their frame indices.
pub(crate) fn key_frames(
    field: &str,
    times: impl ExactSizeIterator<Item = f64>,
    fps: f64,
) -> Result<Vec<usize>, Error> {
    let n = times.len();
    if n == 0 {
        return Err(Error::input(format!("{field}: a track needs at least one key, at time 0")));
    }
    if n > MAX_KEYS {
        return Err(Error::input(format!("{field}: {n} keys, more than the cap of {MAX_KEYS}")));
    }
    let mut frames = Vec::with_capacity(n);
    let mut previous = f64::NEG_INFINITY;
    for (i, time) in times.enumerate() {
        let at = || format!("{field}[{i}].time = {}", Num(time));
        if !time.is_finite() || time < 0.0 {
            return Err(Error::input(format!("{}: must be a finite number of seconds >= 0", at())));
        }
        if i == 0 && time != 0.0 {
            return Err(Error::input(format!("{}: a track's first key is at time 0", at())));
        }
        if time <= previous {
            return Err(Error::input(format!("{}: must be after the previous key's time {}", at(), Num(previous))));
        }
        let frame = frame_of(time, fps).map_err(|m| Error::input(format!("{}: {m}", at())))?;
        if frames.last() == Some(&frame) {
            return Err(Error::input(format!("{}: on the same frame at {} fps as the previous key", at(), Num(fps))));
        }
        frames.push(frame);
        previous = time;
    }
    Ok(frames)
}

impl KeysFile {
    /// Reads the KEYS JSON `text`; a problem names the field (`tracks.left_foot[0].ease: …`).
    pub fn parse(text: &str) -> Result<Self, Error> {
        crate::api::wire::read_json(text.as_bytes())
    }

    /// The plan of these keys on `skeleton`, at most `max_frames` frames (`cap` names the cap:
    /// `--max-frames`); every problem names its field (`keys.tracks.left_foot[2].x`) and value.
    pub fn check(&self, skeleton: &Skeleton, max_frames: usize, cap: &str) -> Result<KeyPlan, Error> {
        let bone = |field: &str, name: &str| -> Result<usize, Error> {
            crate::goal::index(skeleton, name).map_err(|m| Error::input(format!("{field}: {m}")))
        };
        if !self.rotations.is_empty() {
            return Err(Error::input(
                "keys.rotations: for a character only (a rig's bones are turned by its solve; key their tips in keys.tracks)",
            ));
        }
        let (fps, mut last, tracks) = self.tracks(&bone)?;
        let joint = |field: &str, name: &str| -> Result<usize, Error> {
            let index = bone(field, name)?;
            if skeleton.parent(index).is_none() {
                return Err(Error::input(format!("{field}: the bone has no parent, so no joint to bend")));
            }
            if let Joint::Prismatic { .. } = skeleton.joint(index) {
                return Err(Error::input(format!(
                    "{field}: the bone's joint is prismatic; a bend needs a revolute joint"
                )));
            }
            Ok(index)
        };
        let bends = self.bend_keys(&joint, fps, &mut last)?;
        let mut pins = Vec::with_capacity(self.pins.len());
        for (i, name) in self.pins.iter().enumerate() {
            let field = format!("keys.pins[{i}]");
            let index = bone(&field, name)?;
            if self.tracks.contains_key(name) {
                return Err(Error::input(format!(
                    "{field} = {}: the bone is also keyed in keys.tracks; a pinned tip holds still",
                    cell(name)
                )));
            }
            if pins.contains(&index) {
                return Err(Error::input(format!("{field} = {}: pinned twice", cell(name))));
            }
            pins.push(index);
        }
        let last = self.length(fps, last)?;
        frames_within(last, max_frames, cap)?;
        Ok(KeyPlan { fps, last, tracks, bends, pins })
    }

    /// The bends, each bone found (and checked) by `joint` (its problem after the field), as
    /// `(index, [(first frame, bend)])`; `last` raised to their last key's frame.
    fn bend_keys(
        &self,
        joint: &dyn Fn(&str, &str) -> Result<usize, Error>,
        fps: f64,
        last: &mut usize,
    ) -> Result<Bends, Error> {
        let mut bends = Vec::with_capacity(self.bends.len());
        for (name, keys) in &self.bends {
            let field = format!("keys.bends.{}", cell(name));
            let index = joint(&field, name)?;
            let frames = key_frames(&field, keys.iter().map(|k| k.time), fps)?;
            *last = (*last).max(*frames.last().expect("a track has a key"));
            bends.push((index, frames.into_iter().zip(keys.iter().map(|k| k.bend.bend())).collect()));
        }
        Ok(bends)
    }

    /// The keys of a character's target bones (`bone` finds one by name, its problem after
    /// the field): tracks without directions, and bends of the two-bone IK constraints
    /// (`constraint` finds the one whose lower bone a bend names); pins refused.
    pub fn check_character(
        &self,
        bone: &dyn Fn(&str, &str) -> Result<usize, Error>,
        constraint: &dyn Fn(&str, &str) -> Result<usize, Error>,
        max_frames: usize,
        cap: &str,
    ) -> Result<CharacterKeys, Error> {
        if !self.pins.is_empty() {
            return Err(Error::input(
                "keys.pins: not for a character (pins hold a rig's tips; a character's target bones are keyed)",
            ));
        }
        let (fps, mut last, tracks) = self.tracks(bone)?;
        if let Some((name, _)) = self.tracks.iter().find(|(_, keys)| keys.iter().any(|k| k.angle_deg.is_some())) {
            return Err(Error::input(format!(
                "keys.tracks.{}: angle_deg is not for a character (a target is a bone's origin)",
                cell(name)
            )));
        }
        let bends = self.bend_keys(constraint, fps, &mut last)?;
        let rotations = rotations::check(&self.rotations, bone, fps, &mut last)?;
        let last = self.length(fps, last)?;
        frames_within(last, max_frames, cap)?;
        Ok(CharacterKeys { fps, tracks, bends, rotations, duration: last as f64 / fps })
    }

    /// The motion's last frame: `duration`'s when given (finite, on a frame, not before the last
    /// key's frame `last`), else `last`.
    fn length(&self, fps: f64, last: usize) -> Result<usize, Error> {
        let Some(d) = self.duration else { return Ok(last) };
        let at = || format!("keys.duration = {}", Num(d));
        if !d.is_finite() || d < 0.0 {
            return Err(Error::input(format!("{}: must be a finite number of seconds >= 0", at())));
        }
        let frame = frame_of(d, fps).map_err(|m| Error::input(format!("{}: {m}", at())))?;
        if frame < last {
            return Err(Error::input(format!(
                "{}: before the last key's time {}; the motion runs at least to its last key",
                at(),
                Num(last as f64 / fps)
            )));
        }
        Ok(frame)
    }

    /// The fps, the last key's frame over the tracks, and the tracks (bones found by `bone`);
    /// at most [`MAX_TRACKS`] tracks and pins together.
    fn tracks(&self, bone: &dyn Fn(&str, &str) -> Result<usize, Error>) -> Result<(f64, usize, Vec<KeyedBone>), Error> {
        // A character's keys may turn bones alone; anything else keys a track.
        if self.tracks.is_empty() && self.rotations.is_empty() {
            return Err(Error::input(
                "keys.tracks: at least one track, bone name → keys [{\"time\": 0, \"x\": …, \"y\": …}, …]",
            ));
        }
        let fps = self.fps.unwrap_or(DEFAULT_KEY_FPS);
        if !(fps > 0.0 && fps <= MAX_KEY_FPS) {
            return Err(Error::input(format!(
                "keys.fps = {}: must be greater than 0 and at most {MAX_KEY_FPS}",
                Num(fps)
            )));
        }
        let effectors = self.tracks.len() + self.pins.len();
        if effectors > MAX_TRACKS {
            return Err(Error::input(format!(
                "keys.tracks, keys.pins: {effectors} tracks and pins, more than the cap of {MAX_TRACKS}"
            )));
        }
        let mut last = 0;
        let mut tracks = Vec::with_capacity(self.tracks.len());
        for (name, keys) in &self.tracks {
            let field = format!("keys.tracks.{}", cell(name));
            let index = bone(&field, name)?;
            let frames = key_frames(&field, keys.iter().map(|k| k.time), fps)?;
            last = last.max(*frames.last().expect("a track has a key"));
            tracks.push(keyed_bone(&field, index, keys, &frames, fps)?);
        }
        Ok((fps, last, tracks))
    }
}

/// At most `max_frames` frames `0..=last`.
fn frames_within(last: usize, max_frames: usize, cap: &str) -> Result<(), Error> {
    if last >= max_frames {
        return Err(Error::input(format!(
            "keys: {} frames, more than the cap of {max_frames} ({cap})",
            last.saturating_add(1)
        )));
    }
    Ok(())
}

/// A key's ease by the one rule of `--ease/--k1/--k2` ([`choose_ease`], sine by default); a
/// problem names the key's field `at` (`keys.tracks.foot[2]`).
pub(crate) fn key_ease(at: &str, ease: Option<EaseKind>, k1: Option<f64>, k2: Option<f64>) -> Result<Ease, Error> {
    choose_ease(ease, k1, k2, EaseKind::Sine).map_err(|p| {
        Error::input(match p {
            EaseProblem::KWithoutParent { k1 } => {
                format!("{at}.{}: only applies with \"ease\": \"parent\"", if k1 { "k1" } else { "k2" })
            }
            EaseProblem::Invalid(e) => format!("{at}.{e}"),
        })
    })
}

/// The track of one bone's keys: finite values, the direction on every key or none, each key's
/// ease by the one rule of `--ease/--k1/--k2` ([`choose_ease`]); its knots at the keys' frame
/// times `frame / fps`, so that a frame on a key takes the key bit for bit.
fn keyed_bone(field: &str, bone: usize, keys: &[KeyReq], frames: &[usize], fps: f64) -> Result<KeyedBone, Error> {
    let oriented = keys[0].angle_deg.is_some();
    let mut values = Vec::with_capacity(keys.len() * 3);
    let mut eases = Vec::with_capacity(keys.len());
    for (i, k) in keys.iter().enumerate() {
        for (name, v) in [("x", k.x), ("y", k.y)].into_iter().chain(k.angle_deg.map(|a| ("angle_deg", a))) {
            if !v.is_finite() {
                return Err(Error::input(format!("{field}[{i}].{name} = {}: must be a finite number", Num(v))));
            }
        }
        if k.angle_deg.is_some() != oriented {
            return Err(Error::input(format!(
                "{field}[{i}].angle_deg: give it on every key of a track or on none (key 0 {} one)",
                if oriented { "has" } else { "has no" }
            )));
        }
        values.extend([k.x, k.y]);
        values.extend(k.angle_deg.map(f64::to_radians));
        eases.push(key_ease(&format!("{field}[{i}]"), k.ease, k.k1, k.k2)?);
    }
    let n = if oriented { 3 } else { 2 };
    let times = frames.iter().map(|&f| f as f64 / fps).collect();
    let track = KeyTrack::new(n, times, values, eases).map_err(|e| Error::input(format!("{field}: {e}")))?;
    Ok(KeyedBone { bone, track, oriented })
}
