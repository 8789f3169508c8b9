//! The answer of a solve: an arm's (`ikarus solve --format json`, `POST /api/solve`), angles by
//! joint; a rig's (with `--rig`, or `rig`), angles and tips keyed by bone name and every
//! effector's outcome.

use ikarus::{Goal, Outcome, SolveOptions};
use serde::Serialize;

use super::{ByName, Extensions, degrees, points, relative_degrees, tips};
use crate::arm::Arm;
use crate::rig::Rig;

/// The goal of an arm solve: its position, and its orientation in degrees if it has one.
#[derive(Serialize)]
pub struct GoalJson {
    /// The goal's x.
    pub x: f64,
    /// The goal's y.
    pub y: f64,
    /// The tip's wanted direction, degrees; `null` for a position-only goal.
    pub angle_deg: Option<f64>,
}

/// Where the tip ended: its position and direction.
#[derive(Serialize)]
pub struct TipJson {
    /// The tip's x.
    pub x: f64,
    /// The tip's y.
    pub y: f64,
    /// The tip's direction, degrees.
    pub angle_deg: f64,
}

/// One recorded iteration of a solve: the pose and where its joints were.
#[derive(Serialize)]
pub struct FrameJson<'a> {
    /// The solver's iteration this frame was recorded at.
    pub iteration: u32,
    /// The pose, degrees: an arm's one angle per joint, a rig's per bone relative to its parent.
    pub angles_deg: Vec<f64>,
    /// A rig's prismatic bones' displacements at this frame; only when it has any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    /// The joint positions: an arm's base first and tip last; a rig's base, then every bone's tip.
    pub joints: Vec<[f64; 2]>,
}

/// What a solve ran with, in every solve's answer (an arm's and a rig's).
#[derive(Serialize)]
pub struct RunJson {
    /// The solver's name (`ikarus methods` lists them).
    pub method: &'static str,
    /// Whether joint limits were applied.
    pub limits: bool,
    /// `ignore` when limits are off.
    pub limit_mode: &'static str,
}

impl RunJson {
    /// What `options` says a solve runs with.
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
    /// Iterations the solver ran, over every attempt.
    pub iterations: u32,
    /// Restarts used (0 when the first attempt ended the solve).
    pub restarts: u32,
    /// The distance to the goal (a rig's: the largest effector error).
    pub error: f64,
    /// The orientation error, degrees (a rig's: the largest effector's).
    pub angle_error_deg: f64,
    /// The largest error that counts as reached.
    pub tolerance: f64,
}

impl EndJson {
    /// How `o` ended, with the tolerance from `options`.
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
    /// The arm's name.
    pub arm: &'a str,
    /// The solver and the limits it ran with.
    #[serde(flatten)]
    pub run: RunJson,
    /// The goal aimed at.
    pub goal: GoalJson,
    /// How the solve ended: status, iterations, restarts, errors and the tolerance.
    #[serde(flatten)]
    pub end: EndJson,
    /// With limits on: the distance from the goal to the exact reachable region (0 inside);
    /// `null` when no verdict was made.
    pub reach_distance: Option<f64>,
    /// How long the solve took, microseconds.
    pub solve_us: f64,
    /// Where the tip ended.
    pub end_effector: TipJson,
    /// The pose, degrees, one angle per joint.
    pub angles_deg: Vec<f64>,
    /// The joint positions of the pose, base first, tip last.
    pub joints: Vec<[f64; 2]>,
    /// The recorded frames; empty unless recording is asked.
    pub frames: Vec<FrameJson<'a>>,
}

/// A finished solve of `body` and what it needs to be described: an arm and its goal
/// ([`SolveReport`]) or a rig ([`RigSolveReport`], whose goals are in the outcome's effectors).
pub struct Solved<'a, B> {
    /// The arm and its goal, or the rig.
    pub body: B,
    /// The options the solve ran with.
    pub options: &'a SolveOptions,
    /// What the solver returned.
    pub outcome: &'a Outcome,
    /// How long the solve took, microseconds.
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
    /// The bone's name.
    pub name: &'a str,
    /// Whether it is a pin (held where it started) rather than a goal.
    pub pinned: bool,
    /// How it ended: `reached` when its tip is within tolerance of its target.
    pub status: &'static str,
    /// The distance from its tip to its target.
    pub error: f64,
    /// Its orientation error, degrees; 0 without an orientation goal.
    pub angle_error_deg: f64,
    /// Where its tip ended.
    pub tip: [f64; 2],
    /// Where it was wanted: the goal's position, or the pin's start.
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
    /// The rig's name.
    pub rig: &'a str,
    /// The solver and the limits it ran with.
    #[serde(flatten)]
    pub run: RunJson,
    /// How the solve ended: status (`reached` only if every effector is), iterations, errors.
    #[serde(flatten)]
    pub end: EndJson,
    /// How long the solve took, microseconds.
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
