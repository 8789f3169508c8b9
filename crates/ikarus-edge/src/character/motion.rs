//! The motion of a character, shared by `ikarus animate --rig FILE.json`, `ikarus track --rig
//! FILE.json`, `POST /api/animate` and `POST /api/track` with a character: bones' world origins
//! moved over time, every instant posed as the runtime does ([`crate::pose::pose_into`], the
//! target bones put at their points, then the file's IK constraints in their order).
//!
//! Three courses: [`Course::Eased`], each target bone's origin eased from where the setup pose
//! has it to its end point over the duration (ikarus's ease curves); [`Course::Path`], one
//! bone's origin along a traced path, one sample per frame at the frame rate, in a straight
//! line between samples; [`Course::Keyed`], target bones on keyed tracks ([`crate::keys`]),
//! optionally over a clip. The motion is sampled at the frame rate for its frames (JSON) and at
//! any time for the Spine export ([`super::export`]).
//!
//! The frames are a game's frames: a character's physics constraints step from one frame to
//! the next (`motion_play.rs`; [`Motion::physics`] off poses each on its own, as
//! [`Motion::pose_at`] poses any time).

use ikarus::character::Posed;
use ikarus::motion::KeyTrack;
use ikarus::{Bend, Ease};
use serde::Serialize;

use super::Loaded;
use crate::error::Error;
use crate::keys::KeysFile;
use crate::keys::character::{bend_constraint, bend_positive};
pub use crate::names::count_text;
use crate::names::{Quoted, cell};
use crate::pose::{IkChoice, PhysicsAsk, PoseAsk, PoseReport, PosedBoneJson, pose_into, pose_into_until};
use crate::report::character::UnsupportedJson;
use ikarus::Interrupt;

/// The frame rate without one asked for.
pub const DEFAULT_FPS: f64 = 30.0;
/// The duration of an eased motion without one asked for, seconds.
pub const DEFAULT_DURATION: f64 = 1.0;
/// The most frames of a character's motion timed by a duration and a frame rate (an eased
/// course's, a keyed one's): the arms' cap ([`ikarus::motion::MAX_FRAMES`]). A path's motion has
/// one frame per sample, capped where its samples are (`--max-samples`).
pub const MAX_FRAMES: usize = ikarus::motion::MAX_FRAMES;

/// How many frames `duration` seconds at `fps` make (k / fps up to the duration, and the
/// duration itself last), counted in floating point so that no duration overflows the count:
/// `Err` with the count (perhaps infinite or NaN) when it is more than `cap`.
pub fn frames_within(duration: f64, fps: f64, cap: usize) -> Result<usize, f64> {
    let n = (duration * fps - 1e-9).ceil().max(0.0) + 1.0;
    // NaN fails the comparison too.
    if n <= cap as f64 { Ok(n as usize) } else { Err(n) }
}

/// How the target bones move.
#[derive(Debug, Clone)]
pub enum Course {
    /// Each `(bone, end)`: the bone's origin eased from its setup pose's place to `end`.
    Eased {
        /// The bones and their end points, applied in this order.
        targets: Vec<(String, [f64; 2])>,
        /// The ease of every target.
        ease: Ease,
        /// Seconds.
        duration: f64,
    },
    /// `bone`'s origin at `points[k]` at time k / fps, in a straight line between.
    Path {
        /// The bone that follows the path.
        bone: String,
        /// The samples, at least one.
        points: Vec<[f64; 2]>,
    },
    /// Each `(bone, track)`: the bone's origin on its keyed track ([`crate::keys`], made by
    /// [`keyed`]), over the clip `animation` posed at the same time (looping when the keys run
    /// longer than it), or over the setup pose, for `duration` seconds (each track holding its
    /// last key after its end, the clip playing on).
    Keyed {
        /// The bones and their tracks, applied in this order.
        tracks: Vec<(String, KeyTrack)>,
        /// Each `(constraint, keys)`: the constraint's `bendPositive` from each key's time
        /// (seconds) on, in time order, the first at 0.
        bends: Vec<(usize, Vec<(f64, bool)>)>,
        /// Each `(bone, track)`: the bone's local rotation (degrees, one value) on its keyed
        /// track, in place of the clip's ([`crate::keys::rotations`]).
        rotations: Vec<(usize, KeyTrack)>,
        /// The clip under the keys.
        animation: Option<String>,
        /// The motion's length, seconds: the keys' `duration`, else their last key's time.
        duration: f64,
    },
}

/// The keyed course of `keys` on the character `loaded` over the clip `animation`, and its fps:
/// the keys checked as a character's ([`KeysFile::check_character`]: tracks on its bones,
/// bends on the lower bones of its two-bone IK constraints, no pins or directions), at most
/// `max_frames` frames (`cap` names the cap).
///
/// A bend key sets the constraint's `bendPositive` from its time on, the side the key names as
/// the setup pose sees it: `ccw` bends the lower bone counter-clockwise from the upper one
/// (`bendPositive` true in Spine, whose y points up; false in DragonBones, whose y points down),
/// `cw` the other way. Under a mirrored parent (a negative scale) the runtime mirrors the side,
/// and so does ikarus.
pub fn keyed(
    loaded: &Loaded,
    keys: &KeysFile,
    animation: Option<String>,
    max_frames: usize,
    cap: &str,
) -> Result<(Course, f64), Error> {
    let c = &loaded.character;
    let bone = |field: &str, name: &str| {
        c.bone_index(name)
            .ok_or_else(|| Error::input(format!("{field}: no bone named {} in the character", Quoted(name))))
    };
    let constraint = |field: &str, name: &str| bend_constraint(loaded, field, name);
    let checked = keys.check_character(&bone, &constraint, max_frames, cap)?;
    let duration = checked.duration;
    if let Some(name) = &animation {
        crate::pose::clip_at(c, Some(name), None)?;
    }
    let fps = checked.fps;
    let tracks = checked.tracks.into_iter().map(|t| (c.bones()[t.bone].name.clone(), t.track)).collect();
    let positive = |bend: Bend| bend_positive(loaded, bend);
    let bends = checked
        .bends
        .into_iter()
        .map(|(k, keys)| (k, keys.into_iter().map(|(frame, bend)| (frame as f64 / fps, positive(bend))).collect()))
        .collect();
    let rotations = checked.rotations.into_iter().map(|r| (r.bone, r.track)).collect();
    Ok((Course::Keyed { tracks, bends, rotations, animation, duration }, fps))
}

/// A character's motion, checked: every name resolved, every number finite.
#[derive(Debug)]
pub struct Motion<'a> {
    /// The character.
    pub loaded: &'a Loaded,
    /// Frames per second (and, for a path, samples per second).
    pub fps: f64,
    /// Seconds.
    pub duration: f64,
    /// Where each eased target starts (an eased course's).
    starts: Vec<[f64; 2]>,
    course: Course,
    /// Whose rules solve the IK constraints in every frame (the runtime's by default).
    pub ik: IkChoice,
    /// When set, every pose of the motion stops (refused `interrupted`): a server's deadline,
    /// Ctrl-C. `None` by default.
    pub interrupt: Option<Interrupt>,
    /// What the frames do with the character's physics constraints: played as a game's frames
    /// by default (see `motion_play.rs`).
    pub physics: Physics,
    /// The skin every frame is posed (and its art drawn) with, by name; `None`: the file's
    /// `default` skin, if it has one.
    pub skin: Option<String>,
}

/// What a motion does with the character's physics constraints (a character without any moves
/// the same either way).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Physics {
    /// The frames are a game's frames, the physics stepping from one to the next (the
    /// default; `--physics on`, `"physics": true`).
    #[default]
    Played,
    /// They do nothing: every frame is posed on its own (Spine's `Physics.none`; `--physics
    /// off`, `"physics": false`).
    Off,
}

/// A game's state along a motion, for posing it at any time in increasing order
/// ([`Motion::play_at`]): the last frame played and the one before (a time between two
/// frames is posed from the earlier one, even after the later one was played).
#[derive(Debug, Default)]
pub struct Playhead {
    /// The last frame played: its index and clock.
    pub(super) last: Option<(usize, f64)>,
    pub(super) last_posed: Posed,
    /// The frame before it.
    pub(super) previous: Option<(usize, f64)>,
    pub(super) previous_posed: Posed,
    /// A pose between frames.
    pub(super) between: Posed,
}

/// One frame: the time and every bone as `ikarus pose --format json` gives it.
#[derive(Debug, Serialize)]
pub struct FrameJson {
    /// The frame's time, seconds from the motion's start.
    pub time: f64,
    /// Every bone, posed.
    pub bones: Vec<PosedBoneJson>,
}

/// Why a motion's frames stopped before the end: a frame that could not be posed (a one-line
/// refusal without a label), or the writer's error.
#[derive(Debug)]
pub enum StreamError {
    /// A frame could not be posed.
    Motion(Error),
    /// The writer failed.
    Io(std::io::Error),
}

/// `{"frames": [{"time", "bones": […]}, …], "unsupported": […]}`.
#[derive(Debug, Serialize)]
pub struct FramesJson {
    /// The motion's frames, in time order.
    pub frames: Vec<FrameJson>,
    /// What the file has and ikarus does not use.
    pub unsupported: Vec<UnsupportedJson>,
}

impl<'a> Motion<'a> {
    /// The motion of `loaded` along `course` at `fps` frames per second. Refusals are one line
    /// naming the field (`fps`, `duration`, `target "toe"`, `path`), without a label.
    pub fn new(loaded: &'a Loaded, course: Course, fps: f64) -> Result<Self, Error> {
        if !(fps.is_finite() && fps > 0.0) {
            return Err(Error::input(format!("fps: must be a positive number, got {fps}")));
        }
        let c = &loaded.character;
        let mut setup = Posed::default();
        pose_into(loaded, &PoseAsk::default(), &mut setup)?;
        let bone = |name: &str| {
            c.bone_index(name).ok_or_else(|| Error::input(format!("target {}: no bone of that name", Quoted(name))))
        };
        let (starts, duration) = match &course {
            Course::Eased { targets, duration, .. } => {
                if !(duration.is_finite() && *duration > 0.0) {
                    return Err(Error::input(format!(
                        "duration: must be a positive number of seconds, got {duration}"
                    )));
                }
                if targets.is_empty() {
                    return Err(Error::input("target: give at least one BONE=X,Y"));
                }
                let mut starts = Vec::with_capacity(targets.len());
                for (name, [x, y]) in targets {
                    if !(x.is_finite() && y.is_finite()) {
                        return Err(Error::input(format!(
                            "target {}: the point must be finite, got ({x}, {y})",
                            Quoted(name)
                        )));
                    }
                    starts.push(setup.origin(bone(name)?));
                }
                (starts, *duration)
            }
            Course::Path { bone: name, points } => {
                bone(name).map_err(|_| Error::input(format!("effector {}: no bone of that name", Quoted(name))))?;
                if points.is_empty() {
                    return Err(Error::input("path: no samples"));
                }
                if let Some((k, p)) = points.iter().enumerate().find(|(_, p)| !(p[0].is_finite() && p[1].is_finite())) {
                    return Err(Error::input(format!("path[{k}]: the point must be finite, got ({}, {})", p[0], p[1])));
                }
                (Vec::new(), (points.len() - 1) as f64 / fps)
            }
            Course::Keyed { duration, .. } => (Vec::new(), *duration),
        };
        // Checked before any frame is made: a path has one frame per sample (capped with its
        // samples), the others at most MAX_FRAMES.
        let cap = match &course {
            Course::Path { points, .. } => points.len().max(MAX_FRAMES),
            Course::Eased { .. } | Course::Keyed { .. } => MAX_FRAMES,
        };
        if let Err(n) = frames_within(duration, fps, cap) {
            return Err(Error::input(format!(
                "duration, fps: {} s at {} fps is {} frames, more than the cap of {cap}",
                count_text(duration),
                count_text(fps),
                count_text(n)
            )));
        }
        let (physics, skin) = (Physics::default(), None);
        Ok(Motion { loaded, fps, duration, starts, course, ik: IkChoice::Runtime, interrupt: None, physics, skin })
    }

    /// The frame times: k / fps up to the duration, and the duration itself last.
    #[must_use]
    pub fn frame_times(&self) -> Vec<f64> {
        (0..self.frame_count()).map(|k| self.frame_time(k)).collect()
    }

    /// Frame `k`'s time: k / fps, the last frame's the duration.
    #[must_use]
    pub fn frame_time(&self, k: usize) -> f64 {
        if k + 1 >= self.frame_count() { self.duration } else { k as f64 / self.fps }
    }

    /// The number of frames (for caps, before any is posed; [`Motion::new`] refused a motion
    /// of more than its cap).
    #[must_use]
    pub fn frame_count(&self) -> usize {
        frames_within(self.duration, self.fps, usize::MAX).unwrap_or(usize::MAX)
    }

    /// The times the course is keyed at, in increasing order, within the motion: a keyed
    /// course's keys and bend keys, an eased course's start and end, a path's samples; 0 and
    /// the duration always.
    #[must_use]
    pub fn key_times(&self) -> Vec<f64> {
        let mut times = vec![0.0, self.duration];
        match &self.course {
            Course::Eased { .. } => {}
            Course::Path { points, .. } => times.extend((0..points.len()).map(|k| k as f64 / self.fps)),
            Course::Keyed { tracks, bends, rotations, .. } => {
                times.extend(tracks.iter().flat_map(|(_, t)| t.times().iter().copied()));
                times.extend(bends.iter().flat_map(|(_, keys)| keys.iter().map(|k| k.0)));
                times.extend(rotations.iter().flat_map(|(_, t)| t.times().iter().copied()));
            }
        }
        times.retain(|t| (0.0..=self.duration).contains(t));
        times.sort_by(f64::total_cmp);
        times.dedup();
        times
    }

    /// The clip under a keyed course, by name.
    #[must_use]
    pub fn clip(&self) -> Option<&str> {
        match &self.course {
            Course::Keyed { animation, .. } => animation.as_deref(),
            Course::Eased { .. } | Course::Path { .. } => None,
        }
    }

    /// A keyed course's bend keys: per constraint, `(time, bend_positive)` in time order.
    #[must_use]
    pub fn bend_keys(&self) -> &[(usize, Vec<(f64, bool)>)] {
        match &self.course {
            Course::Keyed { bends, .. } => bends,
            Course::Eased { .. } | Course::Path { .. } => &[],
        }
    }

    /// The targets at `time` (clamped into the motion).
    #[must_use]
    pub fn targets_at(&self, time: f64) -> Vec<(String, [f64; 2])> {
        let time = time.clamp(0.0, self.duration);
        match &self.course {
            Course::Eased { targets, ease, duration } => {
                let s = ease.position(time / duration);
                targets
                    .iter()
                    .zip(&self.starts)
                    .map(|((name, end), start)| (name.clone(), [0, 1].map(|k| start[k] + (end[k] - start[k]) * s)))
                    .collect()
            }
            Course::Path { bone, points } => {
                let u = time * self.fps;
                let i = (u.floor() as usize).min(points.len() - 1);
                let (a, b) = (points[i], points[(i + 1).min(points.len() - 1)]);
                let f = if i + 1 < points.len() { u - i as f64 } else { 0.0 };
                vec![(bone.clone(), [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f])]
            }
            Course::Keyed { tracks, .. } => {
                let mut v = Vec::with_capacity(2);
                tracks
                    .iter()
                    .map(|(name, track)| {
                        track.at(time, &mut v);
                        (name.clone(), [v[0], v[1]])
                    })
                    .collect()
            }
        }
    }

    /// The clip under the motion and its time at `time`: a keyed course's clip, looping when
    /// the keys run longer than it.
    fn clip_at(&self, time: f64) -> (Option<String>, Option<f64>) {
        let Course::Keyed { animation: Some(name), .. } = &self.course else { return (None, None) };
        (Some(name.clone()), Some(self.clip_time(time.clamp(0.0, self.duration))))
    }

    /// The time of the clip under a keyed course at the motion's `time`: `time`, or past the
    /// clip's end, looped (`time % length`).
    pub(crate) fn clip_time(&self, time: f64) -> f64 {
        let Course::Keyed { animation: Some(name), .. } = &self.course else { return time };
        let c = &self.loaded.character;
        let length = c.clip_index(name).map_or(0.0, |i| c.clips()[i].duration);
        if length > 0.0 && time > length { time % length } else { time }
    }

    /// What posing the motion at `time` asks: `ikarus pose [--animation A --time T] --target …`.
    #[must_use]
    pub fn ask_at(&self, time: f64) -> PoseAsk {
        let (animation, clip_time) = self.clip_at(time);
        PoseAsk {
            animation,
            time: clip_time,
            targets: self.targets_at(time),
            ik: self.ik.clone(),
            bends: self.bends_at(time),
            turns: self.turns_at(time),
            // One time on its own: physics is left out ([`Motion::play_at`] plays it).
            physics: PhysicsAsk::Off,
            skin: self.skin.clone(),
        }
    }

    /// The bones a keyed course turns by hand (its rotation keys), in the keys' order.
    #[must_use]
    pub fn turned_bones(&self) -> Vec<usize> {
        match &self.course {
            Course::Keyed { rotations, .. } => rotations.iter().map(|(bone, _)| *bone).collect(),
            Course::Eased { .. } | Course::Path { .. } => Vec::new(),
        }
    }

    /// The keyed bones' local rotations at `time`, degrees (a keyed course's), each in place of
    /// the clip's.
    #[must_use]
    pub fn turns_at(&self, time: f64) -> Vec<(usize, f64)> {
        let Course::Keyed { rotations, .. } = &self.course else { return Vec::new() };
        let time = time.clamp(0.0, self.duration);
        let mut v = Vec::with_capacity(1);
        rotations
            .iter()
            .map(|(bone, track)| {
                track.at(time, &mut v);
                (*bone, v[0])
            })
            .collect()
    }

    /// The keyed constraints' `bendPositive` at `time`: each one's last key at or before it.
    fn bends_at(&self, time: f64) -> Vec<(usize, bool)> {
        let Course::Keyed { bends, .. } = &self.course else { return Vec::new() };
        // A key's time is its frame / fps, as the frame's time is: the frame is on it.
        bends.iter().map(|(k, keys)| (*k, keys.iter().rev().find(|(t, _)| *t <= time).unwrap_or(&keys[0]).1)).collect()
    }

    /// The character posed at `time` into `out`, on its own: physics left out (Spine's
    /// `Physics.none`); [`Motion::play_at`] plays it.
    pub fn pose_at(&self, time: f64, out: &mut Posed) -> Result<(), Error> {
        // Checked here too: a character without constraints never asks it while posing.
        if self.interrupt.as_ref().is_some_and(Interrupt::is_interrupted) {
            return Err(Error::input("interrupted"));
        }
        pose_into_until(self.loaded, &self.ask_at(time), out, self.interrupt.as_ref()).map(|_| ())
    }

    /// Every frame posed in order and handed to `sink` with its index and time: one `Posed`
    /// reused and one report at a time, so that a long motion is written as it is posed
    /// ([`super::motion_files::write_json`], [`super::motion_files::write_csv`]) and nothing
    /// holds more than one frame. Stops at the first frame that cannot be posed, or at the first
    /// error of `sink`.
    pub fn each_frame(
        &self,
        sink: &mut dyn FnMut(usize, f64, &PoseReport) -> std::io::Result<()>,
    ) -> Result<(), StreamError> {
        let mut posed = Posed::default();
        let mut clock = None;
        for k in 0..self.frame_count() {
            let time = self.frame_time(k);
            self.frame_into(k, &mut clock, &mut posed).map_err(StreamError::Motion)?;
            sink(k, time, &PoseReport::of(&self.loaded.character, &posed)).map_err(StreamError::Io)?;
        }
        Ok(())
    }

    /// Frame `k` posed into `out`, the frames posed in order from 0 into the same `out`: with
    /// [`Motion::plays_physics`], as the game's frame after the one at `clock` (`None` before
    /// the first), which it advances; otherwise on its own ([`Motion::pose_at`]).
    pub(super) fn frame_into(&self, k: usize, clock: &mut Option<f64>, out: &mut Posed) -> Result<(), Error> {
        if self.plays_physics() {
            *clock = Some(self.step(k, *clock, out)?);
            Ok(())
        } else {
            self.pose_at(self.frame_time(k), out)
        }
    }

    /// Every frame posed (its time and report), for what needs them all at once (a picture).
    pub fn poses(&self) -> Result<Vec<(f64, PoseReport)>, Error> {
        let mut posed = Posed::default();
        let mut clock = None;
        (0..self.frame_count())
            .map(|k| {
                let time = self.frame_time(k);
                self.frame_into(k, &mut clock, &mut posed)?;
                Ok((time, PoseReport::of(&self.loaded.character, &posed)))
            })
            .collect()
    }

    /// Every frame posed, as JSON.
    pub fn frames(&self) -> Result<FramesJson, Error> {
        let mut unsupported = Vec::new();
        let mut frames = Vec::new();
        for (time, report) in self.poses()? {
            unsupported = report.unsupported;
            frames.push(FrameJson { time, bones: report.bones });
        }
        Ok(FramesJson { frames, unsupported })
    }

    /// What the motion is, for a picture's caption: `spine character · keys over "walk" · 28
    /// frames at 30 fps`.
    #[must_use]
    pub fn caption(&self) -> String {
        let course = match &self.course {
            Course::Eased { targets, .. } => format!("{} targets", targets.len()),
            Course::Path { bone, .. } => format!("{} on a path", cell(bone)),
            Course::Keyed { animation: Some(a), .. } => format!("keys over {}", Quoted(a)),
            Course::Keyed { animation: None, .. } => "keys".to_owned(),
        };
        format!(
            "{} character · {course} · {} frames at {} fps",
            self.loaded.format.as_str(),
            self.frame_count(),
            self.fps
        )
    }
}
