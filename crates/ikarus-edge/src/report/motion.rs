//! The answer of a motion (`ikarus animate --format json`, `POST /api/animate`): each stop's
//! solve and the eased frames, an arm's angles by joint, a rig's keyed by bone name.

use ikarus::motion::GoalMotion;
use serde::Serialize;

use super::{ByName, EffectorJson, Extensions, degrees, points, relative_degrees};
use crate::arm::Arm;
use crate::motion::Motion;
use crate::rig::Rig;

/// One goal of a motion: where it was, and how its solve ended.
#[derive(Serialize)]
pub struct MotionSolveJson {
    /// The goal's position.
    pub goal: [f64; 2],
    /// How its solve ended: `reached`, `unreachable`, `stalled`, `iteration_limit` or
    /// `interrupted`.
    pub status: &'static str,
    /// Iterations of its solve, over all its attempts.
    pub iterations: u32,
    /// The distance from the tip to the goal after its solve.
    pub error: f64,
}

/// One eased frame of an arm motion: its time, pose and joint positions.
#[derive(Serialize)]
pub struct MotionFrameJson {
    /// When the frame is shown: seconds with a duration, else normalised time in [0, 1].
    pub time: f64,
    /// The pose, degrees, one angle per joint.
    pub angles_deg: Vec<f64>,
    /// The joint positions of the pose, base first, tip last.
    pub joints: Vec<[f64; 2]>,
}

/// A motion: `ikarus animate` (JSON) and `POST /api/animate`.
#[derive(Serialize)]
pub struct AnimateJson<'a> {
    /// The arm's name.
    pub arm: &'a str,
    /// The easing between the poses (`ikarus animate --help` lists them).
    pub ease: &'static str,
    /// The time of the last frame: the seconds with a duration, else 1.
    pub duration: f64,
    /// One per goal: the vias, then the final goal.
    pub solves: Vec<MotionSolveJson>,
    /// The eased frames, in time order.
    pub frames: Vec<MotionFrameJson>,
}

impl<'a> AnimateJson<'a> {
    /// The JSON object of a motion of `arm`.
    pub fn new(arm: &'a Arm, motion: &GoalMotion) -> Self {
        AnimateJson {
            arm: &arm.name,
            ease: motion.animation.ease.name(),
            duration: motion.animation.duration,
            solves: motion
                .solves
                .iter()
                .map(|s| {
                    let target = s.goal.target();
                    MotionSolveJson {
                        goal: [target.x, target.y],
                        status: s.status.as_str(),
                        iterations: s.iterations,
                        error: s.error,
                    }
                })
                .collect(),
            frames: motion
                .animation
                .frames
                .iter()
                .map(|f| MotionFrameJson { time: f.time, angles_deg: degrees(&f.angles), joints: points(&f.joints) })
                .collect(),
        }
    }
}

impl Motion<Rig> {
    /// The JSON object of the motion.
    pub fn json<'a>(&'a self, rig: &'a Rig) -> RigAnimateJson<'a> {
        let s = &rig.skeleton;
        let animation = &self.motion.animation;
        RigAnimateJson {
            rig: &rig.name,
            ease: animation.ease.name(),
            duration: animation.duration,
            solves: self
                .motion
                .solves
                .iter()
                .map(|r| RigMotionSolveJson {
                    status: r.status.as_str(),
                    iterations: r.iterations,
                    error: r.error,
                    effectors: r.effectors.iter().map(|e| EffectorJson::of(s, e)).collect(),
                })
                .collect(),
            frames: animation.frames.iter().map(|f| RigFrameJson::of(s, f)).collect(),
        }
    }
}

/// How one goal set of a rig motion was solved.
#[derive(Serialize)]
pub struct RigMotionSolveJson<'a> {
    /// `reached` only if every effector is.
    pub status: &'static str,
    /// Iterations of the set's solve, over all its attempts.
    pub iterations: u32,
    /// The largest effector error.
    pub error: f64,
    /// The set's goals in order, then its pins.
    pub effectors: Vec<EffectorJson<'a>>,
}

/// One frame of a rig motion: bone name → angle (degrees, from its parent's direction), prismatic
/// bone name → displacement (only when the rig has prismatic joints), bone name → tip.
#[derive(Serialize)]
pub struct RigFrameJson<'a> {
    /// When the frame is shown: seconds with a duration, else normalised time in [0, 1].
    pub time: f64,
    /// Bone name → its angle from its parent's direction, degrees.
    pub angles_deg: ByName<'a, f64>,
    /// Prismatic bone name → its displacement; only when the rig has prismatic joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    /// Bone name → its tip.
    pub joints: ByName<'a, [f64; 2]>,
}

impl<'a> RigFrameJson<'a> {
    /// A frame whose `joints` are the base, then every bone's tip ([`ikarus::motion::Body`]).
    pub fn of(s: &'a ikarus::Skeleton, f: &ikarus::AnimationFrame) -> Self {
        let names = s.names();
        Self {
            time: f.time,
            angles_deg: ByName { names, values: relative_degrees(s, &f.angles) },
            extensions: Extensions::of(s, &f.angles),
            joints: ByName { names, values: f.joints[1..].iter().map(|p| [p.x, p.y]).collect() },
        }
    }
}

/// A rig motion: `ikarus animate --rig` (JSON) and `POST /api/animate` with `rig`.
#[derive(Serialize)]
pub struct RigAnimateJson<'a> {
    /// The rig's name.
    pub rig: &'a str,
    /// The easing between the poses (`ikarus animate --help` lists them).
    pub ease: &'static str,
    /// The time of the last frame: the seconds with a duration, else 1.
    pub duration: f64,
    /// One per goal set: the via sets, then the final one.
    pub solves: Vec<RigMotionSolveJson<'a>>,
    /// The eased frames, in time order.
    pub frames: Vec<RigFrameJson<'a>>,
}
