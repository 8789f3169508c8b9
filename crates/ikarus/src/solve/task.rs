//! What a skeleton solve is asked: a [`RigTask`] of goals on bone tips ([`RigGoal`], each with
//! a weight, a [`Priority`] and the animator's controls [`Bend`] and softness), pins
//! ([`Pin`]: a tip held where it is) and a mix; and what it answers per effector
//! ([`EffectorOutcome`], in [`Outcome::effectors`](super::Outcome::effectors)).
//!
//! All goals and pins are solved together, by the same loop, step rules, line search, limit
//! modes and restarts as a chain's goal (see the [module docs](super)), on the stacked task of
//! every effector. Priorities are strict, by null-space projection: the secondary goals move
//! only in what the pins and primary goals leave free (see [`Priority`]).

use thiserror::Error;

use super::Status;
use crate::goal::Goal;
use crate::math;
use crate::number::Num;
use crate::skeleton::Skeleton;
use nalgebra::Point2;

/// How strongly a goal is held against others.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Priority {
    /// Solved first, together with the pins.
    #[default]
    Primary,
    /// Solved in what the primary goals and pins leave free: it never pulls them away (to
    /// first order, and the line search keeps the whole task's error falling).
    Secondary,
}

/// Which of the two ways a two-bone limb bends: the sign of the goal bone's own angle (its
/// joint with its parent, the elbow or knee).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bend {
    /// Counter-clockwise: the bone's angle stays in [0, π].
    Positive,
    /// Clockwise: the bone's angle stays in [−π, 0].
    Negative,
}

/// A goal on the tip of one bone.
#[derive(Debug, Clone, PartialEq)]
pub struct RigGoal {
    /// The bone whose tip should reach the goal (index in the skeleton's order).
    pub bone: usize,
    /// Where, and optionally at which absolute direction (radians from +x).
    pub goal: Goal,
    /// Its weight in the weighted least-squares task, > 0 (1 by default): when goals conflict,
    /// the heavier one is met more closely.
    pub weight: f64,
    /// Primary (default) or secondary.
    pub priority: Priority,
    /// For a bone with a parent: which way their joint bends (`None`: either).
    pub bend: Option<Bend>,
    /// Softness, ≥ 0, in length units (0 by default): when the goal is farther from the start
    /// of the bone's parent than the two bones' reach minus the softness, the goal is drawn in
    /// smoothly, so that the limb slows its approach to full stretch instead of snapping
    /// straight (see [`RigGoal::softened_target`]).
    pub softness: f64,
}

impl RigGoal {
    /// A primary goal of weight 1 for the tip of `bone`, without bend or softness.
    #[must_use]
    pub fn new(bone: usize, goal: Goal) -> Self {
        Self { bone, goal, weight: 1.0, priority: Priority::Primary, bend: None, softness: 0.0 }
    }

    /// The same goal with weight `weight`.
    #[must_use]
    pub fn with_weight(mut self, weight: f64) -> Self {
        self.weight = weight;
        self
    }

    /// The same goal with priority `priority`.
    #[must_use]
    pub fn with_priority(mut self, priority: Priority) -> Self {
        self.priority = priority;
        self
    }

    /// The same goal bending its limb `bend`'s way.
    #[must_use]
    pub fn with_bend(mut self, bend: Bend) -> Self {
        self.bend = Some(bend);
        self
    }

    /// The same goal with softness `softness`.
    #[must_use]
    pub fn with_softness(mut self, softness: f64) -> Self {
        self.softness = softness;
        self
    }

    /// The target the solve aims at: the goal's, or with softness `s > 0` and a bone with a
    /// parent, the goal drawn in toward the parent's start `root` once its distance `d` from it
    /// passes `r − s`, `r` the two bones' lengths together: `d' = r − s·e^{−(d − (r − s))/s}`,
    /// which is continuous with a continuous slope at `r − s` and never reaches `r`.
    #[must_use]
    pub fn softened_target(&self, root: Point2<f64>, reach: f64) -> Point2<f64> {
        let target = self.goal.target();
        let s = self.softness;
        if s <= 0.0 {
            return target;
        }
        let v = target - root;
        let d = math::distance(v.x, v.y);
        let knee = reach - s;
        if !(d > knee && d > 0.0) {
            return target;
        }
        let soft = reach - s * math::exp(-(d - knee) / s);
        root + v * (soft / d)
    }
}

/// A tip held where it is at the start of the solve (a planted foot): its position, and with
/// `orientation` its direction too.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pin {
    /// The bone whose tip is held.
    pub bone: usize,
    /// Whether the bone's direction is held as well (true by default: a planted foot stays
    /// flat).
    pub orientation: bool,
}

impl Pin {
    /// Holds the tip of `bone` and its direction.
    #[must_use]
    pub fn new(bone: usize) -> Self {
        Self { bone, orientation: true }
    }

    /// Holds only the position of the tip of `bone`.
    #[must_use]
    pub fn position(bone: usize) -> Self {
        Self { bone, orientation: false }
    }
}

/// A bend on a bone's joint with its parent, whether or not the bone has a goal (a knee at the
/// start of the shin while the goal is on the foot's tip): the same rule as a goal's
/// [`RigGoal::bend`] — the joint's range intersected with that half-turn, and the start pose
/// turned to that side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoneBend {
    /// The bone at whose start the joint bends (index in the skeleton's order).
    pub bone: usize,
    /// Which way.
    pub bend: Bend,
}

/// Everything one skeleton solve is asked.
#[derive(Debug, Clone, PartialEq)]
pub struct RigTask {
    /// Goals on bone tips, at most one per bone.
    pub goals: Vec<RigGoal>,
    /// Tips held where they start (at most one per bone, and not on a bone with a goal).
    pub pins: Vec<Pin>,
    /// How much of the IK result to take, in [0, 1] (1 by default): the answer's angles are
    /// `start + mix·(solved − start)`, joint by joint.
    pub mix: f64,
    /// Bends on joints besides the goals' own ([`BoneBend`]); at most one per bone.
    pub bends: Vec<BoneBend>,
}

impl Default for RigTask {
    fn default() -> Self {
        Self { goals: Vec::new(), pins: Vec::new(), mix: 1.0, bends: Vec::new() }
    }
}

impl RigTask {
    /// A task of `goals` and `pins`, mix 1.
    #[must_use]
    pub fn new(goals: Vec<RigGoal>, pins: Vec<Pin>) -> Self {
        Self { goals, pins, mix: 1.0, bends: Vec::new() }
    }

    /// Every bend of the task on its bone: the goals' (in order), then [`RigTask::bends`].
    pub fn all_bends(&self) -> impl Iterator<Item = BoneBend> + '_ {
        let goals = self.goals.iter().filter_map(|g| g.bend.map(|bend| BoneBend { bone: g.bone, bend }));
        goals.chain(self.bends.iter().copied())
    }

    /// Checks the task against `skeleton`: bones that exist, at most one goal or pin per bone,
    /// at least one goal or pin, weights > 0, softness ≥ 0 and finite, bend only on a bone with a
    /// parent (a goal's and [`RigTask::bends`], at most one of the latter per bone), mix in [0, 1].
    pub fn validate(&self, skeleton: &Skeleton) -> Result<(), RigTaskError> {
        let n = skeleton.len();
        if self.goals.is_empty() && self.pins.is_empty() {
            return Err(RigTaskError::Empty);
        }
        if !(0.0..=1.0).contains(&self.mix) {
            return Err(RigTaskError::Mix { value: self.mix });
        }
        // Pairwise, without a table: tasks hold a handful of effectors, and a solve that
        // validates its task allocates nothing.
        let bones = || self.goals.iter().map(|g| (g.bone, "goal")).chain(self.pins.iter().map(|p| (p.bone, "pin")));
        for (k, (bone, what)) in bones().enumerate() {
            if bone >= n {
                return Err(RigTaskError::NoSuchBone { what, bone, bones: n });
            }
            if let Some((_, first)) = bones().take(k).find(|&(b, _)| b == bone) {
                return Err(RigTaskError::Twice { name: skeleton.name(bone).to_owned(), first, second: what });
            }
        }
        for g in &self.goals {
            let name = || skeleton.name(g.bone).to_owned();
            if !(g.weight > 0.0 && g.weight.is_finite()) {
                return Err(RigTaskError::Weight { name: name(), value: g.weight });
            }
            if !(g.softness >= 0.0 && g.softness.is_finite()) {
                return Err(RigTaskError::Softness { name: name(), value: g.softness });
            }
            if g.bend.is_some() && skeleton.parent(g.bone).is_none() {
                return Err(RigTaskError::BendOnRoot { name: name() });
            }
        }
        for (k, b) in self.bends.iter().enumerate() {
            if b.bone >= n {
                return Err(RigTaskError::NoSuchBone { what: "bend", bone: b.bone, bones: n });
            }
            let name = || skeleton.name(b.bone).to_owned();
            if self.bends[..k].iter().any(|e| e.bone == b.bone) {
                return Err(RigTaskError::Twice { name: name(), first: "bend", second: "bend" });
            }
            if skeleton.parent(b.bone).is_none() {
                return Err(RigTaskError::BendOnRoot { name: name() });
            }
        }
        Ok(())
    }
}

/// Why a [`RigTask`] cannot be solved on a skeleton. Bones are named by their names.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RigTaskError {
    /// Neither a goal nor a pin.
    #[error("goals: a rig solve needs at least one goal or pin, got none")]
    Empty,
    /// A goal or pin names a bone index past the skeleton's.
    #[error("{what}: bone {bone} does not exist (the rig has {bones} bones)")]
    NoSuchBone {
        /// `"goal"` or `"pin"`.
        what: &'static str,
        /// The index given.
        bone: usize,
        /// Bones in the skeleton.
        bones: usize,
    },
    /// Two goals or pins on one bone.
    #[error("{second} {name:?}: the bone already has a {first}; one goal or pin per bone")]
    Twice {
        /// The bone's name.
        name: String,
        /// What came first.
        first: &'static str,
        /// What came second.
        second: &'static str,
    },
    /// A weight that is not a positive finite number.
    #[error("goal {name:?}.weight: must be a finite number > 0, got {}", Num(*.value))]
    Weight {
        /// The bone's name.
        name: String,
        /// The value given.
        value: f64,
    },
    /// A negative or non-finite softness.
    #[error("goal {name:?}.softness: must be a finite number >= 0, got {}", Num(*.value))]
    Softness {
        /// The bone's name.
        name: String,
        /// The value given.
        value: f64,
    },
    /// A bend on a root bone, which has no joint with a parent.
    #[error("goal {name:?}.bend: the bone has no parent, so no two-bone limb to bend")]
    BendOnRoot {
        /// The bone's name.
        name: String,
    },
    /// A bend whose side of the joint lies outside the joint's limits.
    #[error("goal {name:?}.bend: the joint's limits leave no angle on that side")]
    BendOutsideLimits {
        /// The bone's name.
        name: String,
    },
    /// A bend asked of a bone whose joint slides: it has no side to bend to.
    #[error("goal {name:?}.bend: the bone's joint is prismatic; a bend needs a revolute joint")]
    BendOnPrismatic {
        /// The bone's name.
        name: String,
    },
    /// A mix outside [0, 1].
    #[error("mix: must be from 0 to 1, got {}", Num(*.value))]
    Mix {
        /// The value given.
        value: f64,
    },
}

/// How one effector of a skeleton solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EffectorOutcome {
    /// The bone whose tip it is.
    pub bone: usize,
    /// Whether it is a pin (held where it started) rather than a goal.
    pub pinned: bool,
    /// `Reached` if within the tolerances; `Unreachable` if its target is out of the reach of
    /// the bones from the base to it (limits ignored); otherwise the solve's status.
    pub status: Status,
    /// Distance from the tip to its target (a pin's: to where it started).
    pub error: f64,
    /// Absolute direction error in radians, wrapped to [0, π]; 0 without an orientation.
    pub angle_error: f64,
    /// The tip's position.
    pub tip: Point2<f64>,
    /// The bone's absolute direction, radians from +x.
    pub orientation: f64,
    /// The target it aimed at (the goal's, drawn in by softness; a pin's start).
    pub target: Point2<f64>,
}
