//! The JSON requests of the API about rigs: `rig` in place of `arm` (a rig file's fields, as
//! [`RigFile`] reads them), `goals` on named bones and `pins` (bone names). Unknown fields
//! are refused.
//!
//! `POST /api/solve` takes an arm's request or a rig's: [`SolveBody`] reads the body once,
//! looks at which of `arm`/`rig` (and `goal`/`goals`) it has, then reads it as that request,
//! so that an error names the field in the words of the request it is.

use serde::Deserialize;
use serde::de::IgnoredAny;

use crate::picture::PictureFormat;
use crate::rig::RigFile;
use crate::settings::SolverSettings;

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

/// A goal on the tip of the bone `bone`.
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

/// `POST /api/solve` with `rig`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigSolveReq {
    pub rig: RigFile,
    /// One angle per bone, in the rig's order [default: the rig's start angles].
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    #[serde(default)]
    pub goals: Vec<RigGoalReq>,
    #[serde(default)]
    pub pins: Vec<String>,
    /// From 0 to 1 [default: 1].
    #[serde(default)]
    pub mix: Option<f64>,
    #[serde(default)]
    pub options: Option<SolverSettings>,
}

/// Figure `rig` of `POST /api/render` (also figure `arm` with `rig` in place of `arm`): the
/// rig in a pose, with goals and pins marked, and its limit wedges with `limits`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigFigureReq {
    /// Read by the first pass.
    #[serde(default, rename = "figure")]
    pub _figure: IgnoredAny,
    #[serde(default)]
    pub format: Option<PictureFormat>,
    #[serde(default)]
    pub width: Option<u32>,
    #[serde(default)]
    pub height: Option<u32>,
    pub rig: RigFile,
    /// The pose drawn, one angle per bone in the rig's order [default: the rig's start angles].
    #[serde(default)]
    pub pose_deg: Option<Vec<f64>>,
    #[serde(default)]
    pub goals: Vec<RigGoalReq>,
    #[serde(default)]
    pub pins: Vec<String>,
    /// Draw each limited bone's range as a wedge at its joint.
    #[serde(default)]
    pub limits: bool,
    /// Write each bone's name beside it.
    #[serde(default)]
    pub labels: bool,
}
