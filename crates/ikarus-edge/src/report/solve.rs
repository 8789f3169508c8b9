//! The answer of a solve: an arm's (`ikarus solve --format json`, `POST /api/solve`), angles by
//! joint; a rig's (with `--rig`, or `rig`), angles and tips keyed by bone name and every
//! effector's outcome.

use ikarus::{Goal, Outcome, SolveOptions};
use serde::Serialize;

use super::{ByName, Extensions, degrees, points, relative_degrees, tips};
use crate::arm::Arm;
use crate::rig::Rig;

#[derive(Serialize)]
pub struct GoalJson {
    pub x: f64,
    pub y: f64,
    pub angle_deg: Option<f64>,
}

#[derive(Serialize)]
pub struct TipJson {
    pub x: f64,
    pub y: f64,
    pub angle_deg: f64,
}

#[derive(Serialize)]
pub struct FrameJson<'a> {
    pub iteration: u32,
    pub angles_deg: Vec<f64>,
    /// A rig's prismatic bones' displacements at this frame; only when it has any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    pub joints: Vec<[f64; 2]>,
}

/// One solve: `ikarus solve --format json` and `POST /api/solve`.
#[derive(Serialize)]
pub struct SolveJson<'a> {
    pub arm: &'a str,
    pub method: &'static str,
    pub limits: bool,
    /// `ignore` when limits are off.
    pub limit_mode: &'static str,
    pub goal: GoalJson,
    pub status: &'static str,
    pub iterations: u32,
    /// Restarts used (0 when the first attempt ended the solve).
    pub restarts: u32,
    pub error: f64,
    pub angle_error_deg: f64,
    pub tolerance: f64,
    /// With limits on: the distance from the goal to the exact reachable region (0 inside);
    /// `null` when no verdict was made.
    pub reach_distance: Option<f64>,
    pub solve_us: f64,
    pub end_effector: TipJson,
    pub angles_deg: Vec<f64>,
    pub joints: Vec<[f64; 2]>,
    pub frames: Vec<FrameJson<'a>>,
}

/// A finished single solve and what it needs to be described.
pub struct SolveReport<'a> {
    pub arm: &'a Arm,
    pub options: &'a SolveOptions,
    pub goal: &'a Goal,
    pub outcome: &'a Outcome,
    pub micros: f64,
}

impl<'a> SolveReport<'a> {
    /// The JSON object of one solve.
    pub fn json(&self) -> SolveJson<'a> {
        let o = self.outcome;
        let target = self.goal.target();
        let joints = points(&ikarus::kinematics::joint_positions(&self.arm.chain, o.pose.angles()));
        SolveJson {
            arm: &self.arm.name,
            method: self.options.method.name(),
            limits: self.options.limits != ikarus::LimitMode::Ignore,
            limit_mode: self.options.limits.name(),
            goal: GoalJson { x: target.x, y: target.y, angle_deg: self.goal.orientation().map(f64::to_degrees) },
            status: o.status.as_str(),
            iterations: o.iterations,
            restarts: o.restarts,
            error: o.error,
            angle_error_deg: o.angle_error.to_degrees(),
            tolerance: self.options.tolerance,
            reach_distance: o.reach_distance,
            solve_us: self.micros,
            end_effector: TipJson {
                x: o.end_effector.position.x,
                y: o.end_effector.position.y,
                angle_deg: o.end_effector.orientation.to_degrees(),
            },
            angles_deg: degrees(o.pose.angles()),
            joints,
            frames: o
                .frames
                .iter()
                .map(|f| FrameJson {
                    iteration: f.iteration,
                    angles_deg: degrees(f.angles),
                    extensions: None,
                    joints: points(f.joints),
                })
                .collect(),
        }
    }
}

/// One effector of a rig solve: a goal, or a pin (held where it started).
#[derive(serde::Serialize)]
pub struct EffectorJson<'a> {
    pub name: &'a str,
    pub pinned: bool,
    pub status: &'static str,
    pub error: f64,
    pub angle_error_deg: f64,
    pub tip: [f64; 2],
    pub target: [f64; 2],
}

impl<'a> EffectorJson<'a> {
    /// The JSON of effector `e` of a solve on `skeleton`.
    pub fn of(skeleton: &'a ikarus::Skeleton, e: &ikarus::EffectorOutcome) -> Self {
        EffectorJson {
            name: skeleton.name(e.bone),
            pinned: e.pinned,
            status: e.status.as_str(),
            error: e.error,
            angle_error_deg: e.angle_error.to_degrees(),
            tip: [e.tip.x, e.tip.y],
            target: [e.target.x, e.target.y],
        }
    }
}

/// One rig solve: `ikarus solve --rig … --format json` and `POST /api/solve` with `rig`.
#[derive(serde::Serialize)]
pub struct RigSolveJson<'a> {
    pub rig: &'a str,
    pub method: &'static str,
    pub limits: bool,
    /// `ignore` when limits are off.
    pub limit_mode: &'static str,
    /// `reached` only if every effector is.
    pub status: &'static str,
    pub iterations: u32,
    pub restarts: u32,
    /// The largest effector error.
    pub error: f64,
    /// The largest effector orientation error, degrees.
    pub angle_error_deg: f64,
    pub tolerance: f64,
    pub solve_us: f64,
    /// Goals in the task's order, then pins.
    pub effectors: Vec<EffectorJson<'a>>,
    /// Bone name → its angle (relative to its parent), degrees (a prismatic bone's fixed one).
    pub angles_deg: ByName<'a, f64>,
    /// Prismatic bone name → its displacement; only when the rig has prismatic joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    /// Bone name → its tip.
    pub joints: ByName<'a, [f64; 2]>,
    /// Recorded frames (empty unless recording is asked): angles in bone order, and the base
    /// then every bone's tip.
    pub frames: Vec<FrameJson<'a>>,
}

/// A finished rig solve and what it needs to be described.
pub struct RigSolveReport<'a> {
    pub rig: &'a Rig,
    pub options: &'a SolveOptions,
    pub outcome: &'a Outcome,
    pub micros: f64,
}

impl<'a> RigSolveReport<'a> {
    /// The JSON object of one rig solve.
    pub fn json(&self) -> RigSolveJson<'a> {
        let o = self.outcome;
        let s = &self.rig.skeleton;
        let names = s.names();
        RigSolveJson {
            rig: &self.rig.name,
            method: self.options.method.name(),
            limits: self.options.limits != ikarus::LimitMode::Ignore,
            limit_mode: self.options.limits.name(),
            status: o.status.as_str(),
            iterations: o.iterations,
            restarts: o.restarts,
            error: o.error,
            angle_error_deg: o.angle_error.to_degrees(),
            tolerance: self.options.tolerance,
            solve_us: self.micros,
            effectors: o.effectors.iter().map(|e| EffectorJson::of(s, e)).collect(),
            angles_deg: ByName { names, values: relative_degrees(s, o.pose.angles()) },
            extensions: Extensions::of(s, o.pose.angles()),
            joints: ByName { names, values: points(&tips(self.rig, o.pose.angles())) },
            frames: o
                .frames
                .iter()
                .map(|f| FrameJson {
                    iteration: f.iteration,
                    angles_deg: relative_degrees(s, f.angles),
                    extensions: Extensions::of(s, f.angles),
                    joints: points(f.joints),
                })
                .collect(),
        }
    }
}
