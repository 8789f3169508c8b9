//! The JSON requests of the API, in the names of the command line and the arm files (degrees
//! at the edge). Every field is optional unless said otherwise; unknown fields are refused.

use ikarus::EaseKind;
use serde::Deserialize;

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
    pub from_solve: bool,
}

/// `POST /api/workspace`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkspaceReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub limits: Option<bool>,
    #[serde(default)]
    pub resolution: Option<u32>,
    #[serde(default)]
    pub samples: Option<u32>,
    #[serde(default)]
    pub seed: Option<u64>,
}

/// `POST /api/render`: the figure, and the inputs of that figure.
#[derive(Debug, Deserialize)]
#[serde(tag = "figure", rename_all = "lowercase")]
pub enum RenderReq {
    /// An arm in one pose.
    Arm(ArmFigureReq),
    /// A motion (the fields of `/api/animate`): animated as a GIF, overlaid in PNG and SVG.
    Motion(Box<MotionFigureReq>),
    /// The reachable area (the fields of `/api/workspace`).
    Workspace(WorkspaceFigureReq),
    /// An ease curve.
    Ease(EaseFigureReq),
}

/// Figure `arm`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmFigureReq {
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
    /// Also shade the reachable area, sampled with the workspace fields below.
    #[serde(default)]
    pub workspace: bool,
    #[serde(default)]
    pub limits: Option<bool>,
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
    pub from_solve: bool,
}

/// Figure `workspace`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkspaceFigureReq {
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
        }
    }
}
