//! `POST /api/animate` and `POST /api/track` with a character: `rig` holding a character file's
//! text (Spine or DragonBones JSON, told by [`is_json`] as `/api/pose` tells it). The motion of
//! [`crate::character::motion`], answered as its frames (`"format": "json"`, the default,
//! `{"frames": [{"time", "bones": […]}], "unsupported": […]}`), as CSV (`"format": "csv"`, one
//! row per bone per frame, the bytes of `ikarus animate --rig FILE.json --format csv`) or as the
//! exported Spine document (`"format": "spine"`, the file with the motion added as animation
//! `animation_name`).
//!
//! The work is bounded: the character's bones by `--max-bones` (counted first), the frames by
//! `--max-frames`, and frames × bones by [`MAX_BONE_FRAMES`].

use ikarus::{EaseKind, Interrupt};
use serde::Deserialize;

use super::fields::{refuse_given, stopped, track_path};
use super::requests::TargetReq;
use super::requests::{MotionFormat, request};
use super::wire::{Limits, Problem, Reply};
use crate::character::motion::{Course, DEFAULT_DURATION, DEFAULT_FPS, Motion, Physics};
use crate::character::store::Stored;
use crate::character::{Loaded, export, is_json};
use crate::ease_args::{EaseProblem, choose_ease};
use crate::error::Error;
use crate::pose::ik_choice;
use crate::track::Shape;

/// Most frames × bones of one request's motion (the Spine export poses each frame a few times
/// more where it bisects).
pub const MAX_BONE_FRAMES: usize = 200_000;

request! {
    /// `POST /api/animate` with a character: `{"rig": "<text>", "targets": [{"bone", "x", "y"}],
    /// "duration": 1.0, "fps": 30, "ease": "sine", "k1", "k2", "format": "json"|"csv"|"spine",
    /// "animation_name": "ikarus", "ik": "runtime"|"ikarus", "ik_file": "<TOML>", "physics": true}`, every field but
    /// `rig` and `targets` optional.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct AnimateCharacterReq {
        /// The character file's text; or `character`.
        pub rig: Option<String>,
        /// The id `/api/rig/parse` answered ([`crate::character::store`]).
        pub character: Option<String>,
        /// Required unless `keys` is given.
        pub targets: Vec<TargetReq>,
        /// Target bones keyed over time ([`crate::keys`]), instead of `targets`.
        pub keys: Option<crate::keys::KeysFile>,
        /// With `keys`: the clip posed under them, at the same time (looping).
        pub animation: Option<String>,
        /// The motion's length, seconds [default: 1].
        pub duration: Option<f64>,
        /// Frames a second [default: 30].
        pub fps: Option<f64>,
        /// The targets' ease from the pose to their points [default: sine].
        pub ease: Option<EaseKind>,
        /// The ease's `k1` (the parent curve's end of acceleration).
        pub k1: Option<f64>,
        /// The ease's `k2` (the parent curve's start of deceleration).
        pub k2: Option<f64>,
        /// `false` leaves the character's physics constraints out; otherwise the frames are
        /// played as a game's frames at the motion's fps, the physics stepping (as `/api/pose`
        /// plays a pose at a time).
        pub physics: Option<bool>,
        ..export,
    }
}

request! {
    /// `POST /api/track` with a character: `{"rig": "<text>", "effector": "BONE"`, exactly one of
    /// `path`, `line`, `circle`, `figure8`, `"samples"`, `"fps": 30, "format", "animation_name", "ik",
    /// "ik_file", "physics"}`.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct TrackCharacterReq {
        /// The character file's text; or `character`.
        pub rig: Option<String>,
        /// The id `/api/rig/parse` answered.
        pub character: Option<String>,
        /// The bone whose origin follows the path (required).
        required effector: Option<String>,
        /// The samples, `[[x, y], …]`, used as given.
        pub path: Option<Vec<[f64; 2]>>,
        /// `[x0, y0, x1, y1]`.
        pub line: Option<[f64; 4]>,
        /// `[cx, cy, r]`.
        pub circle: Option<[f64; 3]>,
        /// `[cx, cy, a]`.
        pub figure8: Option<[f64; 3]>,
        /// Samples of a shape [default: 100].
        pub samples: Option<usize>,
        /// Frames a second, one sample a frame [default: 30].
        pub fps: Option<f64>,
        /// As [`AnimateCharacterReq::physics`].
        pub physics: Option<bool>,
        ..export,
    }
}

/// Whether a job's body carries a character: `rig` is a string of JSON text, or `character`
/// (a kept character's id) is given.
#[must_use]
pub fn is_character(body: &[u8]) -> bool {
    #[derive(Deserialize)]
    struct Peek {
        #[serde(default)]
        rig: Option<serde_json::Value>,
        #[serde(default)]
        character: Option<serde::de::IgnoredAny>,
    }
    serde_json::from_slice::<Peek>(body)
        .ok()
        .is_some_and(|p| p.character.is_some() || p.rig.is_some_and(|r| r.as_str().is_some_and(is_json)))
}

/// `POST /api/animate` with a character, `stored` the one `req` names.
pub fn animate(
    req: AnimateCharacterReq,
    stored: &Stored,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Reply, Problem> {
    let (loaded, text) = (&stored.loaded, stored.text.as_str());
    if let Some(keys) = &req.keys {
        return keyed(loaded, keys, &req, (limits, interrupt), text);
    }
    if req.animation.is_some() {
        return Err(Problem::invalid("animation: only with keys (the clip under the keyed targets)"));
    }
    if req.targets.is_empty() {
        return Err(Problem::invalid("targets: give at least one {\"bone\", \"x\", \"y\"}"));
    }
    if req.targets.len() > loaded.character.bones().len() {
        return Err(Problem::invalid(format!(
            "targets: {} targets for {} bones; at most one per bone",
            req.targets.len(),
            loaded.character.bones().len()
        )));
    }
    let ease = choose_ease(req.ease, req.k1, req.k2, EaseKind::Sine).map_err(|p| match p {
        EaseProblem::KWithoutParent { k1 } => {
            Problem::invalid(format!("{}: only applies with ease parent", if k1 { "k1" } else { "k2" }))
        }
        EaseProblem::Invalid(e) => Problem::invalid(e.to_string()),
    })?;
    let targets = req.targets.into_iter().map(|t| (t.bone, [t.x, t.y])).collect();
    let course = Course::Eased { targets, ease, duration: req.duration.unwrap_or(DEFAULT_DURATION) };
    let mut motion = Motion::new(loaded, course, req.fps.unwrap_or(DEFAULT_FPS)).map_err(Problem::from)?;
    motion.ik = ik_choice(req.ik.as_deref(), req.ik_file.as_deref(), "ik_file", &loaded.character)?;
    motion.physics = physics(req.physics);
    motion.interrupt = Some(interrupt.clone());
    answer(loaded, &motion, (req.format, req.animation_name.as_deref(), export::Form::asked(req.bake)), text, limits)
}

/// What a motion request's `physics` asks: `false`, [`Physics::Off`]; else [`Physics::Played`].
#[must_use]
pub fn physics(asked: Option<bool>) -> Physics {
    match asked {
        Some(false) => Physics::Off,
        Some(true) | None => Physics::Played,
    }
}

/// `POST /api/animate` with a character and `keys`: its target bones keyed, over the clip
/// `animation` if given; the eased course's fields refused, naming them.
fn keyed(
    loaded: &Loaded,
    keys: &crate::keys::KeysFile,
    req: &AnimateCharacterReq,
    (limits, interrupt): (&Limits, &Interrupt),
    text: &str,
) -> Result<Reply, Problem> {
    let given = [
        ("targets", !req.targets.is_empty()),
        ("duration", req.duration.is_some()),
        ("fps", req.fps.is_some()),
        ("ease", req.ease.is_some()),
        ("k1", req.k1.is_some()),
        ("k2", req.k2.is_some()),
    ];
    refuse_given(&given, "not with keys (the keys give the targets, their eases and the fps)")?;
    let ik = (req.ik.as_deref(), req.ik_file.as_deref());
    let mut motion = keyed_motion(loaded, keys, req.animation.clone(), ik, (limits, interrupt))?;
    motion.physics = physics(req.physics);
    answer(loaded, &motion, (req.format, req.animation_name.as_deref(), export::Form::asked(req.bake)), text, limits)
}

/// The keyed motion of `loaded` by `keys` over the clip `animation`, under the IK rules `ik`
/// (`ik`, `ik_file`), within the caps: `/api/animate`'s and `/api/render`'s (figure `motion`).
pub(super) fn keyed_motion<'a>(
    loaded: &'a Loaded,
    keys: &crate::keys::KeysFile,
    animation: Option<String>,
    (ik, ik_file): (Option<&str>, Option<&str>),
    (limits, interrupt): (&Limits, &Interrupt),
) -> Result<Motion<'a>, Problem> {
    let (course, fps) = crate::character::motion::keyed(loaded, keys, animation, limits.max_frames, "--max-frames")
        .map_err(Problem::from)?;
    let mut motion = Motion::new(loaded, course, fps).map_err(Problem::from)?;
    motion.ik = ik_choice(ik, ik_file, "ik_file", &loaded.character)?;
    motion.interrupt = Some(interrupt.clone());
    within_caps(loaded, &motion, limits)?;
    Ok(motion)
}

/// `POST /api/track` with a character, `stored` the one `req` names.
pub fn track(
    req: TrackCharacterReq,
    stored: &Stored,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Reply, Problem> {
    let (loaded, text) = (&stored.loaded, stored.text.as_str());
    let Some(bone) = req.effector else {
        return Err(Problem::invalid("effector: required with a character: the bone whose origin follows the path"));
    };
    let shapes = [req.line.map(Shape::Line), req.circle.map(Shape::Circle), req.figure8.map(Shape::Figure8)];
    let path = track_path(req.path.as_deref(), shapes, req.samples, limits)?;
    let points = path.goals().iter().map(|g| [g.target().x, g.target().y]).collect();
    let mut motion =
        Motion::new(loaded, Course::Path { bone, points }, req.fps.unwrap_or(DEFAULT_FPS)).map_err(Problem::from)?;
    motion.ik = ik_choice(req.ik.as_deref(), req.ik_file.as_deref(), "ik_file", &loaded.character)?;
    motion.physics = physics(req.physics);
    motion.interrupt = Some(interrupt.clone());
    answer(loaded, &motion, (req.format, req.animation_name.as_deref(), export::Form::asked(req.bake)), text, limits)
}

/// The motion's frames or its Spine document, within the caps.
fn answer(
    loaded: &Loaded,
    motion: &Motion<'_>,
    (format, name, form): (MotionFormat, Option<&str>, export::Form),
    text: &str,
    limits: &Limits,
) -> Result<Reply, Problem> {
    within_caps(loaded, motion, limits)?;
    match format {
        MotionFormat::Json | MotionFormat::Csv if name.is_some() => {
            Err(Problem::invalid("animation_name: only with format spine"))
        }
        MotionFormat::Json | MotionFormat::Csv if form == export::Form::Bake => {
            Err(Problem::invalid("bake: only with format spine"))
        }
        MotionFormat::Json => Ok(Reply {
            content_type: "application/json",
            body: posed(crate::character::motion_files::json(motion), motion)?,
        }),
        MotionFormat::Csv => Ok(Reply {
            content_type: "text/csv; charset=utf-8",
            body: posed(crate::character::motion_files::csv(motion), motion)?,
        }),
        MotionFormat::Spine => {
            let ask = export::Export { name: name.unwrap_or(export::DEFAULT_NAME), form };
            let doc = posed(export::spine(motion, text, &ask), motion)?;
            Ok(Reply { content_type: "application/json", body: doc.into_bytes() })
        }
    }
}

/// What posing `motion`'s frames gave: 503 when its interrupt was set (an `interrupted`
/// refusal is the deadline's, not the request's fault), else the result, a refusal a 422.
pub(super) fn posed<T>(result: Result<T, Error>, motion: &Motion<'_>) -> Result<T, Problem> {
    if let Some(interrupt) = &motion.interrupt {
        stopped(interrupt)?;
    }
    result.map_err(Problem::from)
}

/// The motion's frames within `--max-frames` and frames × bones within [`MAX_BONE_FRAMES`].
fn within_caps(loaded: &Loaded, motion: &Motion<'_>, limits: &Limits) -> Result<(), Problem> {
    let frames = motion.frame_count();
    let bones = loaded.character.bones().len();
    if frames > limits.max_frames {
        return Err(Problem::invalid(format!(
            "duration, fps: {frames} frames, more than the cap of {} (--max-frames)",
            limits.max_frames
        )));
    }
    if frames * bones > MAX_BONE_FRAMES {
        return Err(Problem::invalid(format!(
            "duration, fps: {frames} frames × {bones} bones, more than the cap of {MAX_BONE_FRAMES}"
        )));
    }
    Ok(())
}
