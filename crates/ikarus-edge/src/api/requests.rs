//! The JSON requests of the API's jobs, in the names of the command line and the arm and rig
//! files (degrees at the edge). Every field is optional unless said otherwise; unknown fields
//! are refused.
//!
//! `POST /api/solve`, `/api/animate` and `/api/track` each take one request that carries the
//! body, `arm` (the built-in arm without one) or `rig`, and the fields of both: an arm takes
//! one `goal`, a rig `goals` on named bones, `pins` and `mix`. Which fields a body takes is
//! checked in one place, [`super::bodies`].

use ikarus::EaseKind;
use ikarus::motion::Interpolation;
use serde::Deserialize;

use crate::arm::ArmFile;
use crate::rig::RigFile;
use crate::settings::SolverSettings;

/// A goal: position, and optionally the orientation of the last link.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalReq {
    pub x: f64,
    pub y: f64,
    #[serde(default)]
    pub angle_deg: Option<f64>,
}

/// A goal's priority: `primary` (the default) or `secondary`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PriorityReq {
    Primary,
    Secondary,
}

/// Which way a limb bends: `ccw` or `cw`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BendReq {
    Ccw,
    Cw,
}

/// A rig's goal on the tip of the bone `bone`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigGoalReq {
    pub bone: String,
    pub x: f64,
    pub y: f64,
    #[serde(default)]
    pub angle_deg: Option<f64>,
    #[serde(default)]
    pub weight: Option<f64>,
    #[serde(default)]
    pub priority: Option<PriorityReq>,
    #[serde(default)]
    pub bend: Option<BendReq>,
    #[serde(default)]
    pub softness: Option<f64>,
}

/// `POST /api/solve`: an arm's tip to `goal` (required with an arm), or a rig's `goals` and
/// `pins` solved together.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub rig: Option<RigFile>,
    /// One angle per joint (a rig's bones in its order) [default: the body's start pose].
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// An arm's goal.
    #[serde(default)]
    pub goal: Option<GoalReq>,
    /// A rig's goals.
    #[serde(default)]
    pub goals: Option<Vec<RigGoalReq>>,
    /// A rig's pinned bones.
    #[serde(default)]
    pub pins: Option<Vec<String>>,
    /// A rig's mix, from 0 to 1 [default: 1].
    #[serde(default)]
    pub mix: Option<f64>,
    #[serde(default)]
    pub options: Option<SolverSettings>,
}

/// An ease curve: `kind` (default sine for a motion, parent for the ease figure), `k1`, `k2`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseReq {
    #[serde(default)]
    pub kind: Option<EaseKind>,
    #[serde(default)]
    pub k1: Option<f64>,
    #[serde(default)]
    pub k2: Option<f64>,
}

/// `POST /api/animate`: the solves of [`SolveReq`] in turn, through `via`, eased into frames.
/// `V` is what one `via` entry is for the body: an arm's point `[x, y]`, a rig's goal set
/// (a list of goals, the pins held in each); the body is told apart before the request is read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnimateReq<V> {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub rig: Option<RigFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// An arm's final goal.
    #[serde(default)]
    pub goal: Option<GoalReq>,
    /// A rig's final goal set.
    #[serde(default)]
    pub goals: Option<Vec<RigGoalReq>>,
    /// A rig's bones held where they are, in every goal set.
    #[serde(default)]
    pub pins: Option<Vec<String>>,
    #[serde(default)]
    pub mix: Option<f64>,
    /// What to pass through first, in order.
    #[serde(default = "Vec::new")]
    pub via: Vec<V>,
    #[serde(default)]
    pub options: Option<SolverSettings>,
    #[serde(default)]
    pub ease: Option<EaseReq>,
    #[serde(default)]
    pub frames: Option<u32>,
    #[serde(default)]
    pub duration: Option<f64>,
    #[serde(default)]
    pub fps: Option<f64>,
    #[serde(default)]
    pub interpolation: Option<Interpolation>,
    #[serde(default)]
    pub from_solve: bool,
}

/// `POST /api/track`: exactly one of `path`, `line`, `circle`, `figure8`, followed by an arm's
/// tip, or by the tip of a rig's `effector` while its `goals` hold and its `pins` stay.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub rig: Option<RigFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// A rig's bone whose tip follows the path (required with a rig).
    #[serde(default)]
    pub effector: Option<String>,
    #[serde(default)]
    pub goals: Option<Vec<RigGoalReq>>,
    #[serde(default)]
    pub pins: Option<Vec<String>>,
    #[serde(default)]
    pub mix: Option<f64>,
    /// The samples, `[[x, y], …]`, used as given.
    #[serde(default)]
    pub path: Option<Vec<[f64; 2]>>,
    /// `[x0, y0, x1, y1]`.
    #[serde(default)]
    pub line: Option<[f64; 4]>,
    /// `[cx, cy, r]`.
    #[serde(default)]
    pub circle: Option<[f64; 3]>,
    /// `[cx, cy, a]`.
    #[serde(default)]
    pub figure8: Option<[f64; 3]>,
    /// Samples of a shape [default: 100].
    #[serde(default)]
    pub samples: Option<usize>,
    /// `follow` or `plan` [default: plan for an arm; follow, the only mode, for a rig].
    #[serde(default)]
    pub mode: Option<ikarus::TrackMode>,
    /// The bound on a joint's change between samples, degrees [default: 10].
    #[serde(default)]
    pub max_step_deg: Option<f64>,
    /// With `mode: "follow"`: bound the first sample's step from `start_deg` too, as every
    /// later one (a pointer followed one request at a time) [default: false, the first sample
    /// is placed on the path].
    #[serde(default)]
    pub bound_first: bool,
    #[serde(default)]
    pub options: Option<SolverSettings>,
}

/// `POST /api/workspace`: the exact region, or with `grid: true` (or any of `resolution`,
/// `samples`, `seed`) the sampled grid.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkspaceReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    /// A rig in place of `arm`: the region of `bone`'s tip (sampled unless the rig is a chain).
    #[serde(default)]
    pub rig: Option<crate::rig::RigFile>,
    /// The rig's bone [default: the last].
    #[serde(default)]
    pub bone: Option<String>,
    #[serde(default)]
    pub limits: Option<bool>,
    #[serde(default)]
    pub grid: Option<bool>,
    #[serde(default)]
    pub resolution: Option<u32>,
    #[serde(default)]
    pub samples: Option<u32>,
    #[serde(default)]
    pub seed: Option<u64>,
}

impl WorkspaceReq {
    /// The area a picture shades (figures `arm`, `motion`, `workspace`): the arm is the
    /// picture's, so none here.
    pub fn area(
        limits: Option<bool>,
        grid: Option<bool>,
        resolution: Option<u32>,
        samples: Option<u32>,
        seed: Option<u64>,
    ) -> Self {
        Self { arm: None, rig: None, bone: None, limits, grid, resolution, samples, seed }
    }
}

/// `POST /api/reach`: exactly one of `point` and `points`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReachReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub limits: Option<bool>,
    /// Distance that still counts as reachable [default: the arm's `solver.tolerance`, else 1e-6].
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// One point: the answer is one object.
    #[serde(default)]
    pub point: Option<[f64; 2]>,
    /// Many points: the answer is an array of objects, in order.
    #[serde(default)]
    pub points: Option<Vec<[f64; 2]>>,
}
