//! What a solve together is asked ([`Together`]: the rules per constraint and per bone, pins,
//! goals on any bone), what it reports ([`TogetherReport`]) and how it refuses
//! ([`TogetherError`]); the solve itself is in [`super`].

use super::super::PoseError;
use crate::solve::{Outcome, RigGoal};
use thiserror::Error;

/// How one constraint is solved (constraints without a rule take the defaults: the
/// constraint's own bones, weight 1, primary).
#[derive(Debug, Clone, PartialEq)]
pub struct LimbRule {
    /// The constraint's index.
    pub constraint: usize,
    /// How many bones move for it, counted up from its last bone (`None`: its own one or two):
    /// 3 makes a three-bone leg of a two-bone constraint, its parent's parent moving too.
    pub bones: Option<usize>,
    /// Its goal's weight, > 0, when goals conflict.
    pub weight: f64,
    /// Met only in what the primary goals and the pins leave free.
    pub secondary: bool,
}

/// What a bone adds to the solve.
#[derive(Debug, Clone, PartialEq)]
pub struct BoneRule {
    /// The bone's index.
    pub bone: usize,
    /// The range of its local rotation, radians (the runtime's `rotation`), when it moves.
    pub limits: Option<[f64; 2]>,
    /// How much it resists turning, ≥ 0 (see [`crate::skeleton::Bone::stiffness`]).
    pub stiffness: f64,
}

/// How ikarus solves a character's constraints: rules per limb and per bone, and pinned bones
/// (their tips held where the runtime's pose has them). Empty: every constraint as the file
/// has it, nothing pinned, no limits.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Together {
    /// Per constraint.
    pub limbs: Vec<LimbRule>,
    /// Per bone.
    pub bones: Vec<BoneRule>,
    /// Bones whose tip (position and direction) stays where it starts.
    pub pins: Vec<usize>,
    /// Goals on bones' tips besides the file's constraints (`ikarus solve --rig
    /// CHARACTER.json --goal BONE=X,Y`), solved with them; after them, so that a goal on a
    /// constraint's last bone replaces the constraint's.
    pub goals: Vec<TipGoal>,
}

/// A goal on a bone's tip that is none of the file's constraints: the goal (its `bone` the
/// character's bone index; its bend, softness, weight and priority as a rig's goal has them),
/// and how far up the hierarchy it moves the body.
#[derive(Debug, Clone, PartialEq)]
pub struct TipGoal {
    /// The goal, on the character's bone `goal.bone`.
    pub goal: RigGoal,
    /// How many bones turn for it, counted up from its bone: 1, the bone alone; 2 (the
    /// default, [`TIP_GOAL_BONES`]), the bone and its parent, as a two-bone constraint and a
    /// pose tool turn them; more, up to its depth plus one, the whole way to its root.
    pub bones: usize,
}

/// How many bones a [`TipGoal`] turns unless told: the bone and its parent.
pub const TIP_GOAL_BONES: usize = 2;

/// How one constraint ended: how far it misses its target, in world units: a two-bone one, its
/// child's tip's distance from the target; a one-bone one (an aim), the target's distance from
/// the bone's ray (for a bone of length 0, aimed by the runtime's rule: 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimbEnd {
    /// The constraint's index.
    pub constraint: usize,
    /// Whether it took part (mix > 0).
    pub active: bool,
    /// Tip to target.
    pub error: f64,
}

/// How one [`TipGoal`] ended: its bone's tip's distance from the goal, world units, and with
/// an orientation goal, the bone's world direction's difference from it, radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GoalEnd {
    /// The character's bone.
    pub bone: usize,
    /// Tip to goal.
    pub error: f64,
    /// Direction to goal's (`None` without one), in (−π, π].
    pub angle_error: Option<f64>,
}

/// What a solve together did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TogetherReport {
    /// Per constraint, in the character's order.
    pub limbs: Vec<LimbEnd>,
    /// Per goal of [`Together::goals`], in their order.
    pub goals: Vec<GoalEnd>,
    /// How many times the skeleton was solved (1 to [`super::ROUNDS`]; 0 when no constraint was
    /// active and there was no goal).
    pub rounds: usize,
    /// The last solve's outcome (status, iterations), when there was one.
    pub outcome: Option<Outcome>,
}

/// A solve together that cannot be done.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum TogetherError {
    /// The pose request itself (see [`PoseError`]).
    #[error(transparent)]
    Pose(#[from] PoseError),
    /// A rule names a constraint or a bone that does not exist, or gives a bad value.
    #[error("{0}")]
    Rule(String),
    /// The skeleton or the solve refused (a message naming what).
    #[error("{0}")]
    Solve(String),
    /// A bone's limits (the rules' [`BoneRule::limits`], an IK file's `limits_deg`) leave no
    /// angle on the side its two-bone IK constraint bends it to (the constraint's
    /// `bendPositive`, as the setup, the clip or a bend key has it).
    #[error(
        "bones.{bone}.limits_deg: the IK rules' limits of bone {bone:?} leave no angle on the side its IK constraint bends it to (bendPositive): widen them, or bend the other way"
    )]
    BendOutsideLimits {
        /// The bone's name.
        bone: String,
    },
}
