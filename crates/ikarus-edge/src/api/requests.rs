//! The JSON requests of the API, in the names of the command line and the arm files (degrees
//! at the edge). Every field is optional unless said otherwise; unknown fields are refused.

use ikarus::EaseKind;
use ikarus::motion::Interpolation;
use serde::Deserialize;
use serde::de::IgnoredAny;

use super::rig_requests::RigFigureReq;
use super::{Problem, parse_json};
use crate::arm::ArmFile;
use crate::picture::PictureFormat;
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

/// `POST /api/solve`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// Required.
    pub goal: GoalReq,
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

/// `POST /api/animate`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnimateReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// Required.
    pub goal: GoalReq,
    #[serde(default)]
    pub via: Vec<[f64; 2]>,
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

/// `POST /api/track`: exactly one of `path`, `line`, `circle`, `figure8`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
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
    /// `follow` or `plan` [default: plan].
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

/// `POST /api/render`: the figure, and the inputs of that figure. Read in two passes, so that an
/// error names its field like the other endpoints' errors: first `figure` alone ([`FigureTag`]),
/// then that figure's own struct, which refuses the fields of other figures. Of two faults in
/// one body, a fault of `figure` or of the JSON syntax is the one reported.
#[derive(Debug)]
pub enum RenderReq {
    /// An arm in one pose.
    Arm(ArmFigureReq),
    /// A motion (the fields of `/api/animate`): animated as a GIF, overlaid in PNG and SVG.
    Motion(Box<MotionFigureReq>),
    /// The reachable area (the fields of `/api/workspace`).
    Workspace(WorkspaceFigureReq),
    /// An ease curve.
    Ease(EaseFigureReq),
    /// A rig in one pose (figure `rig`, or `arm` with `rig` in place of `arm`).
    Rig(Box<RigFigureReq>),
}

/// The names of the figures.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Figure {
    Arm,
    Motion,
    Workspace,
    Ease,
    Rig,
}

/// The first pass over a render request: `figure` (required), other fields skipped. Its
/// messages speak of the whole request (`expected struct RenderReq`).
#[derive(Debug, Deserialize)]
#[serde(expecting = "struct RenderReq")]
pub struct FigureTag {
    pub figure: Figure,
    /// Whether the body has a `rig` (figure `arm` then draws it).
    #[serde(default)]
    pub rig: Option<IgnoredAny>,
}

impl RenderReq {
    /// The body read in two passes: `figure`, then that figure's fields.
    pub fn parse(body: &[u8]) -> Result<Self, Problem> {
        let FigureTag { figure, rig } = parse_json(body)?;
        Ok(match figure {
            Figure::Arm if rig.is_some() => RenderReq::Rig(parse_json(body)?),
            Figure::Rig => RenderReq::Rig(parse_json(body)?),
            Figure::Arm => RenderReq::Arm(parse_json(body)?),
            Figure::Motion => RenderReq::Motion(parse_json(body)?),
            Figure::Workspace => RenderReq::Workspace(parse_json(body)?),
            Figure::Ease => RenderReq::Ease(parse_json(body)?),
        })
    }
}

/// Figure `arm`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmFigureReq {
    /// Read by the first pass.
    #[serde(default, rename = "figure")]
    pub _figure: IgnoredAny,
    #[serde(default)]
    pub format: Option<PictureFormat>,
    #[serde(default)]
    pub width: Option<u32>,
    #[serde(default)]
    pub height: Option<u32>,
    #[serde(default)]
    pub arm: Option<ArmFile>,
    /// The pose drawn [default: the arm's start pose].
    #[serde(default)]
    pub pose_deg: Option<Vec<f64>>,
    #[serde(default)]
    pub goal: Option<GoalReq>,
    /// Also shade the reachable area with the workspace fields below: the exact region, or
    /// the sampled grid (as `/api/workspace`).
    #[serde(default)]
    pub workspace: bool,
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

/// Figure `motion`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionFigureReq {
    /// Read by the first pass.
    #[serde(default, rename = "figure")]
    pub _figure: IgnoredAny,
    #[serde(default)]
    pub format: Option<PictureFormat>,
    #[serde(default)]
    pub width: Option<u32>,
    #[serde(default)]
    pub height: Option<u32>,
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// Required (checked after parsing, to name it in the figure's words).
    #[serde(default)]
    pub goal: Option<GoalReq>,
    #[serde(default)]
    pub via: Vec<[f64; 2]>,
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
    /// Also shade the reachable area, as the playground shows it: the exact region, or the
    /// sampled grid with the workspace fields below (as `/api/workspace`).
    #[serde(default)]
    pub workspace: bool,
    /// The area's limits [default: the options' `limits`].
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
    /// Draw the joints' traces, as lines as the playground's screen does [default: true].
    #[serde(default)]
    pub traces: Option<bool>,
    /// Draw earlier poses as ghosts in a GIF, as the playground's screen does [default: false].
    #[serde(default)]
    pub ghosts: bool,
}

/// Figure `workspace`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkspaceFigureReq {
    /// Read by the first pass.
    #[serde(default, rename = "figure")]
    pub _figure: IgnoredAny,
    #[serde(default)]
    pub format: Option<PictureFormat>,
    #[serde(default)]
    pub width: Option<u32>,
    #[serde(default)]
    pub height: Option<u32>,
    #[serde(default)]
    pub arm: Option<ArmFile>,
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

/// Figure `ease`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseFigureReq {
    /// Read by the first pass.
    #[serde(default, rename = "figure")]
    pub _figure: IgnoredAny,
    #[serde(default)]
    pub format: Option<PictureFormat>,
    #[serde(default)]
    pub width: Option<u32>,
    #[serde(default)]
    pub height: Option<u32>,
    #[serde(default)]
    pub ease: Option<EaseReq>,
}

impl RenderReq {
    /// The picture's format (PNG by default) and size (800 × 800 by default), unchecked.
    pub fn picture(&self) -> (Option<PictureFormat>, Option<u32>, Option<u32>) {
        match self {
            RenderReq::Arm(r) => (r.format, r.width, r.height),
            RenderReq::Motion(r) => (r.format, r.width, r.height),
            RenderReq::Workspace(r) => (r.format, r.width, r.height),
            RenderReq::Ease(r) => (r.format, r.width, r.height),
            RenderReq::Rig(r) => (r.format, r.width, r.height),
        }
    }
}
