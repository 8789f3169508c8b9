//! The requests of `POST /api/render`: the figure, and the inputs of that figure, in the names
//! of the command line and the arm and rig files (degrees at the edge). Unknown fields are
//! refused.

use serde::Deserialize;
use serde::de::IgnoredAny;

use super::bodies::{BodyKind, fields_of};
use super::requests::{EaseReq, GoalReq, RigGoalReq};
use super::{Problem, parse_json};
use crate::arm::ArmFile;
use crate::picture::PictureFormat;
use crate::rig::RigFile;
use crate::settings::SolverSettings;
use ikarus::motion::Interpolation;

/// `POST /api/render`: the figure, and the inputs of that figure. Read in two passes, so that an
/// error names its field like the other endpoints' errors: first `figure` alone ([`FigureTag`]),
/// then that figure's own struct, which refuses the fields of other figures. Of two faults in
/// one body, a fault of `figure` or of the JSON syntax is the one reported.
#[derive(Debug)]
pub enum RenderReq {
    /// An arm or a rig in one pose (figure `arm`, or `rig`; `arm` with `rig` draws the rig).
    Body(BodyKind, Box<BodyFigureReq>),
    /// A motion (the fields of `/api/animate`): animated as a GIF, overlaid in PNG and SVG.
    Motion(Box<MotionFigureReq>),
    /// The reachable area (the fields of `/api/workspace`).
    Workspace(Box<WorkspaceFigureReq>),
    /// An ease curve.
    Ease(EaseFigureReq),
}

/// The names of the figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
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
}

impl RenderReq {
    /// The body read in two passes: `figure`, then that figure's fields.
    pub fn parse(body: &[u8]) -> Result<Self, Problem> {
        let FigureTag { figure } = parse_json(body)?;
        Ok(match figure {
            Figure::Arm | Figure::Rig => {
                let req: Box<BodyFigureReq> = parse_json(body)?;
                RenderReq::Body(req.kind(figure, body)?, req)
            }
            Figure::Motion => RenderReq::Motion(parse_json(body)?),
            Figure::Workspace => RenderReq::Workspace(parse_json(body)?),
            Figure::Ease => RenderReq::Ease(parse_json(body)?),
        })
    }
}

/// Figure `arm` (or `rig`): the body in one pose, an arm (the built-in arm without `arm`) with
/// its goal and, with `workspace`, its reachable area; or a rig (`rig`) with its goals and
/// pins marked, its limit wedges with `limits` and its bones' names with `labels`. Which
/// fields a body takes is checked in one place, [`super::bodies`].
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyFigureReq {
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
    pub rig: Option<RigFile>,
    /// The pose drawn, one angle per joint [default: the body's start pose].
    #[serde(default)]
    pub pose_deg: Option<Vec<f64>>,
    /// An arm's goal.
    #[serde(default)]
    pub goal: Option<GoalReq>,
    /// A rig's goals.
    #[serde(default)]
    pub goals: Option<Vec<RigGoalReq>>,
    /// A rig's pins.
    #[serde(default)]
    pub pins: Option<Vec<String>>,
    /// An arm's: also shade the reachable area with the workspace fields below: the exact
    /// region, or the sampled grid (as `/api/workspace`).
    #[serde(default)]
    pub workspace: Option<bool>,
    /// An arm's area within the limits; a rig's limit wedges [default: false].
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
    /// A rig's: write each bone's name beside it.
    #[serde(default)]
    pub labels: Option<bool>,
}

impl BodyFigureReq {
    /// Which body the figure draws (a rig with figure `rig`, or with `rig`), its fields for
    /// the other body refused.
    pub fn kind(&self, figure: Figure, body: &[u8]) -> Result<BodyKind, Problem> {
        let kind = if figure == Figure::Rig || self.rig.is_some() { BodyKind::Rig } else { BodyKind::Arm };
        let arm_only = [
            ("arm", self.arm.is_some()),
            ("goal", self.goal.is_some()),
            ("workspace", self.workspace.is_some()),
            ("grid", self.grid.is_some()),
            ("resolution", self.resolution.is_some()),
            ("samples", self.samples.is_some()),
            ("seed", self.seed.is_some()),
        ];
        let rig_only =
            [("goals", self.goals.is_some()), ("pins", self.pins.is_some()), ("labels", self.labels.is_some())];
        let rig = ("rig", kind == BodyKind::Arm || self.rig.is_some());
        fields_of(kind, &arm_only, &rig_only, rig, body)?;
        Ok(kind)
    }
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
            RenderReq::Body(_, r) => (r.format, r.width, r.height),
            RenderReq::Motion(r) => (r.format, r.width, r.height),
            RenderReq::Workspace(r) => (r.format, r.width, r.height),
            RenderReq::Ease(r) => (r.format, r.width, r.height),
        }
    }
}
