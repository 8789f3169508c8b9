//! The track workflow shared by `ikarus track` and `POST /api/track`, one for both bodies
//! ([`TrackJob`]): the tip of an arm follows a path (a line, a circle, a figure-8 or given
//! goals), online or planned; or the tip of one bone of a rig follows it online while the rig's
//! other goals hold and its pins stay where they start (the library's
//! [`ikarus::track::follow_rig`]). What differs — who follows and the library's entry point — is
//! the body's [`TrackBody`] impl. The job, its JSON shapes and its picture layers.

use ikarus::number::Num;
use ikarus::track::{self, Path, PathError, Track, TrackError, TrackMode, TrackOptions};
use ikarus::{Goal, RigTask, SolveOptions};
use serde::Serialize;

use crate::arm::Arm;
use crate::error::Error;
use crate::report::{ByName, Extensions, degrees, points, relative_degrees};
use crate::rig::Rig;

/// Samples of a shape unless `--samples` says otherwise.
pub const DEFAULT_SAMPLES: usize = 100;
/// The default bound on a joint's change between samples, degrees.
pub const DEFAULT_MAX_STEP_DEG: f64 = 10.0;
/// A shape sampled into a path.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// A straight line `[x0, y0, x1, y1]`, from the first point to the second.
    Line([f64; 4]),
    /// A circle `[cx, cy, r]`: centre and radius.
    Circle([f64; 3]),
    /// A figure-8 lying on its side `[cx, cy, a]`: centre, and `a` for `2a` wide and `a` high.
    Figure8([f64; 3]),
}

impl Shape {
    /// The shape's name, as the flag and the API field.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Line(_) => "line",
            Shape::Circle(_) => "circle",
            Shape::Figure8(_) => "figure8",
        }
    }

    /// The path of `samples` points on the shape.
    pub fn path(self, samples: usize) -> Result<Path, PathError> {
        match self {
            Shape::Line([x0, y0, x1, y1]) => Path::line([x0, y0], [x1, y1], samples),
            Shape::Circle([cx, cy, r]) => Path::circle([cx, cy], r, samples),
            Shape::Figure8([cx, cy, a]) => Path::figure8([cx, cy], a, samples),
        }
    }
}

/// A body that follows a path: who follows it, and the library's entry point.
pub trait TrackBody {
    /// Who follows: an arm's tip, online or planned ([`TrackMode`]); a rig's effector bone
    /// with the goals it holds ([`RigFollower`]).
    type Follower;

    /// Tracks `path` from `start`; a problem is bad input, in the library's words.
    fn follow(
        &self,
        start: &[f64],
        follower: &Self::Follower,
        path: &Path,
        options: &TrackOptions,
    ) -> Result<Track, Error>;
}

impl TrackBody for Arm {
    type Follower = TrackMode;

    /// The bound in a problem is in the edge's degrees, `max_step_deg`.
    fn follow(&self, start: &[f64], mode: &TrackMode, path: &Path, options: &TrackOptions) -> Result<Track, Error> {
        track::track(&self.chain, start, path, *mode, options).map_err(|e| Error::input(match e {
            TrackError::OffPathCap { max_step, needed, cap } => format!(
                "max_step_deg = {}: bridging the plan's gaps in steps this small needs {needed} poses off the path, more than the cap of {cap} ({} per sample); raise it or sample the path more finely",
                Num(max_step.to_degrees()),
                track::MAX_OFF_PATH_PER_SAMPLE
            ),
            other => other.to_string(),
        }))
    }
}

/// Who follows a rig's path: the tip of `bone`, while `task`'s goals hold and its pins stay.
pub struct RigFollower {
    /// The bone whose tip follows the path.
    pub bone: usize,
    /// The goals held and the pins, without the effector.
    pub task: RigTask,
}

impl TrackBody for Rig {
    type Follower = RigFollower;

    fn follow(&self, start: &[f64], f: &RigFollower, path: &Path, options: &TrackOptions) -> Result<Track, Error> {
        track::follow_rig(&self.skeleton, start, f.bone, &f.task, path, options)
            .map_err(|e| Error::input(e.to_string()))
    }
}

/// One track: the workflow of `ikarus track` and `POST /api/track`.
pub struct TrackJob<'a, B: TrackBody> {
    /// The arm or rig that follows the path.
    pub body: &'a B,
    /// The pose it starts from, radians, one angle per joint.
    pub start: Vec<f64>,
    /// Who follows: the arm's mode, or the rig's effector bone and the goals it holds.
    pub follower: B::Follower,
    /// The goals to follow, one per sample.
    pub path: Path,
    /// The solver's options and the bound on a step between samples (radians inside).
    pub options: TrackOptions,
}

/// The tracking options: the solver's `solve`, the bound in degrees, and whether follow bounds
/// the first sample too.
pub fn track_options(solve: SolveOptions, max_step_deg: f64, bound_first: bool) -> TrackOptions {
    TrackOptions { max_step: max_step_deg.to_radians(), solve, bound_first, ..TrackOptions::default() }
}

impl<B: TrackBody> TrackJob<'_, B> {
    /// Tracks the path; a problem is bad input, in the library's words.
    pub fn run(&self) -> Result<Track, Error> {
        self.body.follow(&self.start, &self.follower, &self.path, &self.options)
    }
}

impl TrackJob<'_, Arm> {
    /// The picture's layer: the wanted path, the tip's trace, the flips.
    pub fn layer(&self, t: &Track) -> ikarus_render::PathLayer {
        let tip = |s: &track::TrackSample| ikarus::kinematics::end_effector(&self.body.chain, &s.angles).position;
        ikarus_render::PathLayer {
            goals: self.path.goals().iter().map(Goal::target).collect(),
            trace: t.samples.iter().map(tip).collect(),
            flips: t.summary.flips.iter().map(|&k| tip(&t.samples[k])).collect(),
        }
    }

    /// A one-line caption for pictures.
    pub fn caption(&self, t: &Track) -> String {
        let s = &t.summary;
        let off = if s.off_path > 0 { format!(" · {} off path", s.off_path) } else { String::new() };
        format!(
            "{} · {} · {} of {} reached{off} · {} flips · largest step {:.1}°",
            self.body.name,
            self.follower.name(),
            s.reached,
            s.samples,
            s.flips.len(),
            s.max_step.to_degrees()
        )
    }
}

/// One sample of an arm track in JSON: the goal, how it ended, the pose and the step.
#[derive(Serialize)]
pub struct TrackSampleJson {
    /// The sample's goal position.
    pub goal: [f64; 2],
    /// The goal's orientation, degrees; only when the path gives one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
    /// How the sample ended: `reached`, `limited`, `unreachable`, `stalled`, … or `off_path`.
    pub status: &'static str,
    /// Distance from the tip to the goal's position.
    pub error: f64,
    /// The pose, degrees, one angle per joint (free joints unwrapped along the path).
    pub angles_deg: Vec<f64>,
    /// The joint positions of the pose, base first, tip last.
    pub joints: Vec<[f64; 2]>,
    /// The largest joint change from the previous sample, degrees; 0 for the first.
    pub step_deg: f64,
}

/// The summary of a track in JSON: counts by status, flips, the largest step, error and rates.
#[derive(Serialize)]
pub struct TrackSummaryJson {
    /// Samples in the path (the off-path poses not counted).
    pub samples: usize,
    /// Samples that reached their goal.
    pub reached: usize,
    /// Samples that stopped at a joint limit.
    pub limited: usize,
    /// Samples out of reach.
    pub unreachable: usize,
    /// Stalled or at the iteration cap.
    pub stalled: usize,
    /// Poses plan inserted off the path, between two samples whose poses lie further apart
    /// than the bound (status `off_path`; not counted in `samples`).
    pub off_path: usize,
    /// The number of flips: steps larger than `step_bound_deg`.
    pub flips: usize,
    /// The indices of the samples whose step is a flip.
    pub flip_samples: Vec<usize>,
    /// The bound: a larger step is a flip.
    pub step_bound_deg: f64,
    /// The largest step of the track, degrees.
    pub max_step_deg: f64,
    /// The largest position error of the path's samples.
    pub max_error: f64,
    /// The largest joint velocity, degrees per sample.
    pub max_velocity_deg_per_sample: f64,
    /// The largest joint acceleration, degrees per sample².
    pub max_acceleration_deg_per_sample2: f64,
    /// The largest joint jerk, degrees per sample³.
    pub max_jerk_deg_per_sample3: f64,
}

/// A track: `ikarus track --format json` and `POST /api/track`.
#[derive(Serialize)]
pub struct TrackJson<'a> {
    /// The arm's name.
    pub arm: &'a str,
    /// How it tracked: `follow` (online) or `plan`.
    pub mode: &'static str,
    /// Every sample in order, with the poses `plan` inserted off the path.
    pub samples: Vec<TrackSampleJson>,
    /// Flips, errors and rates.
    pub summary: TrackSummaryJson,
}

impl<'a> TrackJson<'a> {
    /// The JSON of `t`, tracked by `job`: angles and steps in degrees.
    pub fn new(job: &TrackJob<'a, Arm>, t: &Track) -> Self {
        let chain = &job.body.chain;
        let samples = t
            .samples
            .iter()
            .map(|s| {
                let p = s.goal.target();
                TrackSampleJson {
                    goal: [p.x, p.y],
                    angle_deg: s.goal.orientation().map(f64::to_degrees),
                    status: s.status.as_str(),
                    error: s.error,
                    angles_deg: degrees(&s.angles),
                    joints: points(&ikarus::kinematics::joint_positions(chain, &s.angles)),
                    step_deg: s.step.to_degrees(),
                }
            })
            .collect();
        let summary = TrackSummaryJson::new(&t.summary, job.options.max_step);
        Self { arm: &job.body.name, mode: job.follower.name(), samples, summary }
    }
}

impl TrackSummaryJson {
    /// The summary of a track whose flip bound was `max_step` radians.
    pub fn new(s: &track::TrackSummary, max_step: f64) -> Self {
        TrackSummaryJson {
            samples: s.samples,
            reached: s.reached,
            limited: s.limited,
            unreachable: s.unreachable,
            stalled: s.stalled,
            off_path: s.off_path,
            flips: s.flips.len(),
            flip_samples: s.flips.clone(),
            step_bound_deg: max_step.to_degrees(),
            max_step_deg: s.max_step.to_degrees(),
            max_error: s.max_error,
            max_velocity_deg_per_sample: s.max_velocity.to_degrees(),
            max_acceleration_deg_per_sample2: s.max_acceleration.to_degrees(),
            max_jerk_deg_per_sample3: s.max_jerk.to_degrees(),
        }
    }
}

/// The index of the effector bone `name`, which must exist and have neither a goal nor a pin
/// in `task`; a problem starts with `field` and the name (`--effector hand`).
pub fn effector_index(rig: &Rig, name: &str, task: &RigTask, field: &str) -> Result<usize, Error> {
    let bone = crate::goal::index(&rig.skeleton, name).map_err(|m| Error::input(format!("{field} {name}: {m}")))?;
    if task.goals.iter().any(|g| g.bone == bone) {
        return Err(Error::input(format!("{field} {name}: the bone also has a goal; the effector's goal is the path")));
    }
    if task.pins.iter().any(|p| p.bone == bone) {
        return Err(Error::input(format!(
            "{field} {name}: the bone is also pinned; a pinned tip cannot follow a path"
        )));
    }
    Ok(bone)
}

impl TrackJob<'_, Rig> {
    /// A one-line caption for pictures.
    pub fn caption(&self, t: &Track) -> String {
        let s = &t.summary;
        format!(
            "{} · {} follows · {} of {} reached · {} flips · largest step {:.1}°",
            self.body.name,
            self.body.skeleton.name(self.follower.bone),
            s.reached,
            s.samples,
            s.flips.len(),
            s.max_step.to_degrees()
        )
    }

    /// The JSON object of a finished track.
    pub fn json<'a>(&'a self, t: &Track) -> RigTrackJson<'a> {
        let s = &self.body.skeleton;
        let names = s.names();
        let samples = t
            .samples
            .iter()
            .map(|x| {
                let p = x.goal.target();
                let tips = crate::report::tips(self.body, &x.angles);
                RigTrackSampleJson {
                    goal: [p.x, p.y],
                    angle_deg: x.goal.orientation().map(f64::to_degrees),
                    status: x.status.as_str(),
                    error: x.error,
                    angles_deg: ByName { names, values: relative_degrees(s, &x.angles) },
                    extensions: Extensions::of(s, &x.angles),
                    joints: ByName { names, values: tips.iter().map(|p| [p.x, p.y]).collect() },
                    step_deg: x.step.to_degrees(),
                }
            })
            .collect();
        RigTrackJson {
            rig: &self.body.name,
            effector: s.name(self.follower.bone),
            mode: TrackMode::Follow.name(),
            samples,
            summary: TrackSummaryJson::new(&t.summary, self.options.max_step),
        }
    }
}

/// One sample of a rig track: as an arm's, with angles and tips keyed by bone name.
#[derive(Serialize)]
pub struct RigTrackSampleJson<'a> {
    /// The sample's goal position.
    pub goal: [f64; 2],
    /// The goal's orientation, degrees; only when the path gives one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
    /// How the sample ended: `reached`, `limited`, `unreachable`, `stalled`, …
    pub status: &'static str,
    /// The largest effector error: the followed tip's, the held goals' and the pins'.
    pub error: f64,
    /// Bone name → its angle from its parent's direction, degrees.
    pub angles_deg: ByName<'a, f64>,
    /// Prismatic bone name → its displacement; only when the rig has prismatic joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    /// Bone name → the position of its tip.
    pub joints: ByName<'a, [f64; 2]>,
    /// The largest joint change from the previous sample, degrees; 0 for the first.
    pub step_deg: f64,
}

/// A rig track: `ikarus track --rig --format json` and `POST /api/track` with `rig`.
#[derive(Serialize)]
pub struct RigTrackJson<'a> {
    /// The rig's name.
    pub rig: &'a str,
    /// The bone whose tip followed the path.
    pub effector: &'a str,
    /// How it tracked: always `follow` (a rig follows online).
    pub mode: &'static str,
    /// Every sample in order.
    pub samples: Vec<RigTrackSampleJson<'a>>,
    /// Flips, errors and rates.
    pub summary: TrackSummaryJson,
}
