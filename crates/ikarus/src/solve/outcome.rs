//! What a solve returns: the [`Outcome`] with its [`Status`], or a [`SolveError`] when it
//! could not start.

use crate::number::Num;
use nalgebra::Point2;
use thiserror::Error;

use super::Frames;
use super::task::{EffectorOutcome, RigTaskError};
use crate::chain::Pose;
use crate::kinematics::EndEffector;

crate::listed_enum! {
    /// Why a solve ended.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Status {
        /// The tip is within tolerance of the goal (and of its orientation, if any).
        Reached,
        /// No pose can reach the goal: it is out of reach even with limits ignored (the pose is
        /// then the best found: for a position goal, the arm stretched towards it), or, with limits
        /// enforced, outside the exact reachable region (the pose then reaches the nearest
        /// reachable point, found at once without a search; see
        /// [`SolveOptions::reach_verdict`](super::SolveOptions::reach_verdict)).
        Unreachable,
        /// The pose stopped moving before reaching the goal: a local minimum, or joints held at
        /// their limits.
        Stalled,
        /// The iteration cap was hit while the pose was still moving.
        IterationLimit,
        /// The solve's [`interrupt`](super::SolveOptions::interrupt) was set; the pose is where
        /// it stopped.
        Interrupted,
    }
}

impl Status {
    /// `reached`, `unreachable`, `stalled`, `iteration_limit` or `interrupted`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Reached => "reached",
            Status::Unreachable => "unreachable",
            Status::Stalled => "stalled",
            Status::IterationLimit => "iteration_limit",
            Status::Interrupted => "interrupted",
        }
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The result of a solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// The final pose. With backtracking on (the default) every accepted step lowers the
    /// error, so it is also the best pose of the solve; with `backtrack: 0` it is simply where
    /// the last step landed.
    pub pose: Pose,
    /// Why the solve ended.
    pub status: Status,
    /// Steps taken, over every attempt.
    pub iterations: u32,
    /// Restarts used (see [`SolveOptions::restarts`](super::SolveOptions::restarts)); 0 when the first attempt ended it.
    pub restarts: u32,
    /// Final distance from the tip to the goal position.
    pub error: f64,
    /// Final absolute orientation error in radians, wrapped to [0, π]; 0 without an
    /// orientation goal.
    pub angle_error: f64,
    /// Final tip position and orientation.
    pub end_effector: EndEffector,
    /// Recorded frames (empty unless [`SolveOptions::record_every`](super::SolveOptions::record_every) is set).
    /// A skeleton's frames hold the base and then every bone's tip, in the skeleton's order.
    pub frames: Frames,
    /// A skeleton solve's effectors: its goals in the task's order, then its pins. Empty for a
    /// chain. `error` and `angle_error` above are then the largest of theirs, and
    /// `end_effector` the first one's tip.
    pub effectors: Vec<EffectorOutcome>,
    /// With limits enforced and [`reach_verdict`](super::SolveOptions::reach_verdict) on: the
    /// distance from the goal to the exact reachable region (0 inside; for an orientation
    /// goal, from its wrist point to the wrist's region). `None` when no verdict was made
    /// (limits ignored or absent, a skeleton, or the verdict turned off).
    pub reach_distance: Option<f64>,
}

impl Default for Outcome {
    fn default() -> Self {
        Self {
            pose: Pose::default(),
            status: Status::IterationLimit,
            iterations: 0,
            restarts: 0,
            error: f64::INFINITY,
            angle_error: 0.0,
            end_effector: EndEffector { position: Point2::origin(), orientation: 0.0 },
            frames: Frames::default(),
            effectors: Vec::new(),
            reach_distance: None,
        }
    }
}

/// Why a solve could not start.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SolveError {
    /// The start pose has a different number of angles than the chain has joints.
    #[error("start: expected {expected} angles (one per joint), got {got}")]
    PoseLength {
        /// Joints in the chain.
        expected: usize,
        /// Angles given.
        got: usize,
    },
    /// A start angle is NaN or infinite.
    #[error("start[{index}]: must be a finite number, got {}", Num(*.value))]
    NonFiniteAngle {
        /// Joint index, from 0.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// [`Method::Analytic`](super::Method::Analytic) was asked for a chain and goal without a closed form.
    #[error(
        "method analytic: needs 2 links with a position goal or 3 links with an orientation goal, \
         got {links} links with {goal}"
    )]
    NoClosedForm {
        /// Links in the chain.
        links: usize,
        /// `"a position goal"` or `"an orientation goal"`.
        goal: &'static str,
    },
    /// A skeleton solve's task does not fit its skeleton.
    #[error(transparent)]
    Rig(#[from] RigTaskError),
    /// A method that does not solve skeletons was asked to.
    #[error("method {method}: solves chains only; a rig needs transpose, pinv, dls, sdls or lm")]
    ChainOnly {
        /// The method's name.
        method: &'static str,
    },
    /// A method cannot move one of the body's joints ([`Method::moves`](super::Method::moves)).
    #[error("method {method} cannot move {kind} joint {name:?} (bones[{index}])")]
    JointKind {
        /// The method's name.
        method: &'static str,
        /// The joint's kind: `prismatic`, …
        kind: &'static str,
        /// The bone's name.
        name: String,
        /// The bone's index, from 0.
        index: usize,
    },
    /// [`SolveOptions::rates`](super::SolveOptions::rates) is neither empty nor one per joint.
    #[error("rates: expected {expected} values (one per joint) or none, got {got}")]
    RatesLength {
        /// Joints in the chain.
        expected: usize,
        /// Rates given.
        got: usize,
    },
}
