//! Which request a body is: `POST /api/solve`, `/api/animate` and `/api/track` take an arm's
//! request or a rig's. A body is read once for its keys, then as the request it is, so that an
//! error names the field in the words of that request.

use serde::Deserialize;
use serde::de::IgnoredAny;

use super::requests::{AnimateReq, SolveReq, TrackReq};
use super::rig_motion::{RigAnimateReq, RigTrackReq};
use super::rig_requests::{RigGoalReq, RigSolveReq};
use super::{Problem, parse_json};
use crate::arm::ArmFile;
use crate::rig::{Rig, RigFile};

/// What a body has, read without judging anything else.
#[derive(Debug, Deserialize)]
#[serde(expecting = "struct SolveReq")]
pub struct Keys {
    #[serde(default)]
    pub arm: Option<IgnoredAny>,
    #[serde(default)]
    pub rig: Option<IgnoredAny>,
    #[serde(default)]
    pub goal: Option<IgnoredAny>,
    #[serde(default)]
    pub goals: Option<IgnoredAny>,
}

impl Keys {
    /// Whether the body is a rig's request: it has `rig`, and no field of an arm's.
    pub fn rig(&self) -> Result<bool, Problem> {
        match (self.arm.is_some(), self.rig.is_some()) {
            (true, true) => Err(Problem::invalid("arm, rig: give one or the other, not both")),
            (_, true) if self.goal.is_some() => {
                Err(Problem::invalid("goal: a rig takes goals, a list of {\"bone\", \"x\", \"y\"}"))
            }
            (_, true) => Ok(true),
            (_, false) if self.goals.is_some() => {
                Err(Problem::invalid("goals: only with rig (an arm takes one goal, {\"x\", \"y\"})"))
            }
            (_, false) => Ok(false),
        }
    }
}

/// The body of `POST /api/solve`: an arm's request or a rig's.
#[derive(Debug)]
pub enum SolveBody {
    Arm(Box<SolveReq>),
    Rig(Box<RigSolveReq>),
}

impl SolveBody {
    /// The body as an arm's request or a rig's, told apart by its keys.
    /// An arm with offsets or slides is a rig's request: its goal on the last link.
    pub fn parse(body: &[u8]) -> Result<Self, Problem> {
        let keys: Keys = parse_json(body)?;
        if keys.rig()? {
            return Ok(SolveBody::Rig(parse_json(body)?));
        }
        let req: Box<SolveReq> = parse_json(body)?;
        Ok(match req.arm.as_ref().filter(|a| a.joint_key().is_some()) {
            Some(arm) => SolveBody::Rig(Box::new(rig_of_arm(arm, &req)?)),
            None => SolveBody::Arm(req),
        })
    }
}

/// The body of `POST /api/animate`: an arm's request or a rig's.
#[derive(Debug)]
pub enum AnimateBody {
    Arm(Box<AnimateReq>),
    Rig(Box<RigAnimateReq>),
}

/// The body of `POST /api/track`: an arm's request or a rig's.
#[derive(Debug)]
pub enum TrackBody {
    Arm(Box<TrackReq>),
    Rig(Box<RigTrackReq>),
}

impl AnimateBody {
    /// The body as an arm's request or a rig's, told apart by its keys.
    pub fn parse(body: &[u8]) -> Result<Self, Problem> {
        let keys: Keys = parse_json(body)?;
        Ok(if keys.rig()? {
            AnimateBody::Rig(parse_json(body)?)
        } else {
            AnimateBody::Arm(Box::new(parse_json(body)?))
        })
    }
}

impl TrackBody {
    /// The body as an arm's request or a rig's, told apart by its keys.
    pub fn parse(body: &[u8]) -> Result<Self, Problem> {
        let keys: Keys = parse_json(body)?;
        Ok(if keys.rig()? { TrackBody::Rig(parse_json(body)?) } else { TrackBody::Arm(Box::new(parse_json(body)?)) })
    }
}

/// An arm's request whose arm has offsets or slides ([`ArmFile::joint_key`]) as the request of
/// its one-branch rig ([`RigFile::from_arm`]): the goal on the last link (`link{n-1}`). The arm
/// is checked first as an arm, so that a problem names the link (`arm: links[2].limits = …`).
fn rig_of_arm(arm: &ArmFile, req: &SolveReq) -> Result<RigSolveReq, Problem> {
    let rig = Rig::from_arm(arm, "arm")?;
    let tip = rig.tip.map_or_else(String::new, |t| rig.skeleton.name(t).to_owned());
    let g = &req.goal;
    let goal = RigGoalReq {
        bone: tip,
        x: g.x,
        y: g.y,
        angle_deg: g.angle_deg,
        weight: None,
        priority: None,
        bend: None,
        softness: None,
    };
    Ok(RigSolveReq {
        rig: RigFile::from_arm(arm),
        start_deg: req.start_deg.clone(),
        goals: vec![goal],
        pins: Vec::new(),
        mix: None,
        options: req.options.clone(),
    })
}
