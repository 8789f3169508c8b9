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

/// What a solve ran with, in every solve's answer (an arm's and a rig's).
#[derive(Serialize)]
pub struct RunJson {
    pub method: &'static str,
    pub limits: bool,
    /// `ignore` when limits are off.
    pub limit_mode: &'static str,
}

impl RunJson {
    pub fn of(options: &SolveOptions) -> Self {
        RunJson {
            method: options.method.name(),
            limits: options.limits != ikarus::LimitMode::Ignore,
            limit_mode: options.limits.name(),
        }
    }
}

/// How a solve ended, in every solve's answer (an arm's and a rig's).
#[derive(Serialize)]
pub struct EndJson {
    /// A rig's is `reached` only if every effector is.
    pub status: &'static str,
    pub iterations: u32,
    /// Restarts used (0 when the first attempt ended the solve).
    pub restarts: u32,
    /// The distance to the goal (a rig's: the largest effector error).
    pub error: f64,
    /// The orientation error, degrees (a rig's: the largest effector's).
    pub angle_error_deg: f64,
    pub tolerance: f64,
}

impl EndJson {
    pub fn of(options: &SolveOptions, o: &Outcome) -> Self {
        EndJson {
            status: o.status.as_str(),
            iterations: o.iterations,
            restarts: o.restarts,
            error: o.error,
            angle_error_deg: o.angle_error.to_degrees(),
            tolerance: options.tolerance,
        }
    }
}

/// The recorded frames of `o`, each frame's angles and extensions as `angles` and
/// `extensions` give them.
fn frames_of<'a>(
    o: &Outcome,
    angles: impl Fn(&[f64]) -> Vec<f64>,
    extensions: impl Fn(&[f64]) -> Option<Extensions<'a>>,
) -> Vec<FrameJson<'a>> {
    o.frames
        .iter()
        .map(|f| FrameJson {
            iteration: f.iteration,
            angles_deg: angles(f.angles),
            extensions: extensions(f.angles),
            joints: points(f.joints),
        })
        .collect()
}

/// One solve: `ikarus solve --format json` and `POST /api/solve`. The groups
/// [`RunJson`] and [`EndJson`] are written as if their fields were this object's own.
#[derive(Serialize)]
pub struct SolveJson<'a> {
    pub arm: &'a str,
    #[serde(flatten)]
    pub run: RunJson,
    pub goal: GoalJson,
    #[serde(flatten)]
    pub end: EndJson,
    /// With limits on: the distance from the goal to the exact reachable region (0 inside);
    /// `null` when no verdict was made.
    pub reach_distance: Option<f64>,
    pub solve_us: f64,
    pub end_effector: TipJson,
    pub angles_deg: Vec<f64>,
    pub joints: Vec<[f64; 2]>,
    pub frames: Vec<FrameJson<'a>>,
}

/// A finished solve of `body` and what it needs to be described: an arm and its goal
/// ([`SolveReport`]) or a rig ([`RigSolveReport`], whose goals are in the outcome's effectors).
pub struct Solved<'a, B> {
    pub body: B,
    pub options: &'a SolveOptions,
    pub outcome: &'a Outcome,
    pub micros: f64,
}

/// A finished single solve of an arm, aimed at a goal.
pub type SolveReport<'a> = Solved<'a, (&'a Arm, &'a Goal)>;

/// A finished rig solve.
pub type RigSolveReport<'a> = Solved<'a, &'a Rig>;

impl<'a> SolveReport<'a> {
    /// The JSON object of one solve.
    pub fn json(&self) -> SolveJson<'a> {
        let o = self.outcome;
        let (arm, goal) = self.body;
        let target = goal.target();
        let joints = points(&ikarus::kinematics::joint_positions(&arm.chain, o.pose.angles()));
        SolveJson {
            arm: &arm.name,
            run: RunJson::of(self.options),
            goal: GoalJson { x: target.x, y: target.y, angle_deg: goal.orientation().map(f64::to_degrees) },
            end: EndJson::of(self.options, o),
            reach_distance: o.reach_distance,
            solve_us: self.micros,
            end_effector: TipJson {
                x: o.end_effector.position.x,
                y: o.end_effector.position.y,
                angle_deg: o.end_effector.orientation.to_degrees(),
            },
            angles_deg: degrees(o.pose.angles()),
            joints,
            frames: frames_of(o, degrees, |_| None),
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
    #[serde(flatten)]
    pub run: RunJson,
    #[serde(flatten)]
    pub end: EndJson,
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

impl<'a> RigSolveReport<'a> {
    /// The JSON object of one rig solve.
    pub fn json(&self) -> RigSolveJson<'a> {
        let o = self.outcome;
        let rig = self.body;
        let s = &rig.skeleton;
        let names = s.names();
        RigSolveJson {
            rig: &rig.name,
            run: RunJson::of(self.options),
            end: EndJson::of(self.options, o),
            solve_us: self.micros,
            effectors: o.effectors.iter().map(|e| EffectorJson::of(s, e)).collect(),
            angles_deg: ByName { names, values: relative_degrees(s, o.pose.angles()) },
            extensions: Extensions::of(s, o.pose.angles()),
            joints: ByName { names, values: points(&tips(rig, o.pose.angles())) },
            frames: frames_of(o, |q| relative_degrees(s, q), |q| Extensions::of(s, q)),
        }
    }
}
