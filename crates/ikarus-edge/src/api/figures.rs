//! The requests of `POST /api/render`: the figure, and the inputs of that figure, in the names
//! of the command line and the arm and rig files (degrees at the edge). Unknown fields are
//! refused.

use serde::Deserialize;

use super::bodies::{BodyKind, fields_of};
use super::requests::{EaseReq, GoalReq, request};
use super::wire::{Problem, parse_json};
use crate::arm::ArmFile;
use crate::picture::PictureFormat;

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
    /// A character's keyed motion (figure `motion` with `rig` holding a character's text).
    CharacterMotion(Box<CharacterFigureReq>),
    /// A character in one pose (figure `pose`), with its art given an atlas.
    Pose(Box<PoseFigureReq>),
    /// The reachable area (the fields of `/api/workspace`).
    Workspace(Box<WorkspaceFigureReq>),
    /// An ease curve.
    Ease(EaseFigureReq),
}

/// The names of the figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Figure {
    /// `arm`: an arm or a rig in one pose.
    Arm,
    /// `motion`: a body's or a character's motion, its frames overlaid.
    Motion,
    /// `workspace`: an arm's or a rig bone's reachable area.
    Workspace,
    /// `ease`: an ease curve.
    Ease,
    /// `rig`: figure `arm`, its body read as a rig.
    Rig,
    /// `pose`: a character posed as `/api/pose` poses it.
    Pose,
}

/// The first pass over a render request: `figure` (required), other fields skipped. Its
/// messages speak of the whole request (`expected struct RenderReq`).
#[derive(Debug, Deserialize)]
#[serde(expecting = "struct RenderReq")]
pub struct FigureTag {
    /// Which figure the request draws.
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
            Figure::Motion if super::character_motion::is_character(body) => {
                RenderReq::CharacterMotion(parse_json(body)?)
            }
            Figure::Motion => RenderReq::Motion(parse_json(body)?),
            Figure::Workspace => RenderReq::Workspace(parse_json(body)?),
            Figure::Ease => RenderReq::Ease(parse_json(body)?),
            Figure::Pose => RenderReq::Pose(parse_json(body)?),
        })
    }
}

request! {
    /// Figure `arm` (or `rig`): the body in one pose, an arm (the built-in arm without `arm`)
    /// with its goal and, with `workspace`, its reachable area; or a rig (`rig`) with its goals
    /// and pins marked, its limit wedges with `limits` and its bones' names with `labels`. Which
    /// fields a body takes is checked in one place, [`super::bodies`].
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct BodyFigureReq {
        ..picture,
        ..body,
        /// The pose drawn, one angle per joint [default: the body's start pose].
        pub pose_deg: Option<Vec<f64>>,
        /// An arm's goal.
        pub goal: Option<GoalReq>,
        ..rig_goals,
        /// An arm's: also shade the reachable area with the area's fields: the exact region,
        /// or the sampled grid (as `/api/workspace`).
        pub workspace: Option<bool>,
        ..area,
        /// A rig's: write each bone's name beside it.
        pub labels: Option<bool>,
    }
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

request! {
    /// Figure `motion`: the fields of `/api/animate` for an arm (`goal` required, checked after
    /// parsing to name it in the figure's words), or a rig and its `keys` (the keyed motion), and with `workspace` the reachable area, as
    /// the playground shows it: the exact region, or the sampled grid with the area's fields
    /// (as `/api/workspace`; its `limits` default to the options' `limits`).
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct MotionFigureReq {
        ..picture,
        /// The arm [default: the built-in arm].
        pub arm: Option<ArmFile>,
        /// A rig, drawn in its keyed motion (with `keys`, as `/api/animate` takes them).
        pub rig: Option<crate::rig::RigFile>,
        /// A rig's keyframes per effector ([`crate::keys`]).
        pub keys: Option<crate::keys::KeysFile>,
        /// One start angle per joint, degrees [default: the arm's start pose].
        pub start_deg: Option<Vec<f64>>,
        /// The arm's goal (required with an arm).
        pub goal: Option<GoalReq>,
        /// Points the tip passes through first, in order.
        pub via: Vec<[f64; 2]>,
        ..motion,
        /// Shade the reachable area behind the motion.
        pub workspace: bool,
        ..area,
        /// Draw the joints' traces, as lines as the playground's screen does [default: true].
        pub traces: Option<bool>,
        /// Draw earlier poses as ghosts in a GIF, as the playground's screen does [default: false].
        pub ghosts: bool,
    }
}

request! {
    /// Figure `motion` with a character: `rig` holding a Spine or DragonBones file's text (as
    /// `/api/animate` takes it), its target bones keyed by `keys` over the clip `animation`, under
    /// the IK rules `ik` and `ik_file`; drawn as `ikarus animate --rig FILE.json --keys K.json
    /// --out` draws it (its frames overlaid, or a GIF at the keys' fps).
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct CharacterFigureReq {
        ..picture,
        /// The character file's text; or `character`.
        pub rig: Option<String>,
        /// The id `/api/rig/parse` answered ([`crate::character::store`]).
        pub character: Option<String>,
        /// The target bones' keys ([`crate::keys`]; required).
        required keys: crate::keys::KeysFile,
        /// The clip posed under the keys, at the same time (looping).
        pub animation: Option<String>,
        /// `false` leaves the character's physics constraints out; otherwise the frames are
        /// played as a game's frames, as `/api/animate` plays them.
        pub physics: Option<bool>,
        /// The skin every frame is posed and drawn with, by name [default: `default`].
        pub skin: Option<String>,
        /// The id `/api/atlas/parse` answered for the character's atlas (sent with its page
        /// images): every frame drawn with its art under its bones.
        pub atlas: Option<String>,
        /// With `atlas`: the art alone on a transparent background, one fit for the whole
        /// motion [default: false].
        pub art_only: Option<bool>,
        ..character_ik,
    }
}

request! {
    /// Figure `pose`: a character posed as `/api/pose` poses it (the same fields), drawn as
    /// `ikarus pose --out x.png|svg` draws it: its bones and targets; with `atlas` (an atlas
    /// sent to `/api/atlas/parse` with its page images) its art under them; with `art_only` the
    /// art alone on a transparent background, fitted at 90 %.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct PoseFigureReq {
        ..picture,
        ..pose,
        /// With `atlas`: the art alone [default: false].
        pub art_only: Option<bool>,
    }
}

impl PoseFigureReq {
    /// The pose's request, and `art_only`.
    #[must_use]
    pub fn into_pose(self) -> (super::pose::PoseReq, bool) {
        let Self {
            _figure,
            format: _,
            width: _,
            height: _,
            rig,
            character,
            animation,
            time,
            targets,
            bends,
            rotations,
            physics,
            fps,
            skin,
            atlas,
            ik,
            ik_file,
            goals,
            pins,
            art_only,
        } = self;
        let req = super::pose::PoseReq {
            rig,
            character,
            animation,
            time,
            targets,
            bends,
            rotations,
            physics,
            fps,
            skin,
            atlas,
            ik,
            ik_file,
            goals,
            pins,
        };
        (req, art_only.unwrap_or(false))
    }
}

request! {
    /// Figure `workspace`.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct WorkspaceFigureReq {
        ..picture,
        /// The arm whose reachable area is drawn [default: the built-in arm].
        pub arm: Option<ArmFile>,
        ..area,
    }
}

request! {
    /// Figure `ease`.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct EaseFigureReq {
        ..picture,
        /// The curve drawn [default: parent, with its default `k1` and `k2`].
        pub ease: Option<EaseReq>,
    }
}

impl RenderReq {
    /// The picture's format (PNG by default) and size (800 × 800 by default), unchecked.
    pub fn picture(&self) -> (Option<PictureFormat>, Option<u32>, Option<u32>) {
        match self {
            RenderReq::Body(_, r) => (r.format, r.width, r.height),
            RenderReq::Motion(r) => (r.format, r.width, r.height),
            RenderReq::CharacterMotion(r) => (r.format, r.width, r.height),
            RenderReq::Pose(r) => (r.format, r.width, r.height),
            RenderReq::Workspace(r) => (r.format, r.width, r.height),
            RenderReq::Ease(r) => (r.format, r.width, r.height),
        }
    }

    /// Whether the figure animates (a GIF can be asked of it): a motion's.
    pub fn animates(&self) -> bool {
        matches!(self, RenderReq::Motion(_) | RenderReq::CharacterMotion(_))
    }
}
