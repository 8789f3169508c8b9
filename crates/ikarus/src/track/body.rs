//! [`TrackBody`]: what following a path needs of the body that follows it — its angles and
//! bounds, one solve for a sample's goal, whether a goal is out of reach, and the error at a
//! pose — so that one [`Follower`](super::Follower) follows paths with a chain's tip or with
//! one effector of a skeleton ([`RigEffector`]).
//!
//! A sealed trait that the follower is generic over, rather than an enum of bodies: the
//! follower is monomorphised per body, so a chain's follow is the same code as before
//! skeletons existed (same operations, same bits, no branch on the kind of body per sample).

use nalgebra::Point2;

use super::{TrackError, TrackOptions, bounds};
use crate::chain::{Chain, Link};
use crate::goal::Goal;
use crate::kinematics::end_effector;
use crate::limits::Bounds;
use crate::math;
use crate::skeleton::Skeleton;
use crate::solve::{LimitMode, Outcome, RigGoal, RigTask, SolveError, SolveOptions, Solver};

mod sealed {
    pub trait Sealed {}
    impl Sealed for crate::chain::Chain {}
    impl Sealed for super::RigEffector {}
}

/// A body whose effector can follow a path: a [`Chain`] (its tip) or a [`RigEffector`] (one
/// bone tip of a skeleton, the rig's other goals and pins held).
pub trait TrackBody: sealed::Sealed + Clone + std::fmt::Debug {
    /// The number of angles of a pose.
    fn angle_count(&self) -> usize;
    /// The limits a track with `options` enforces: the body's, or none when they are ignored.
    fn track_bounds(&self, options: &SolveOptions) -> Bounds<'_>;
    /// A solver for this body: `options` checked against it and `start`, with the solver's own
    /// restarts and recording off (tracking runs its own restarts).
    fn track_solver(&self, options: &TrackOptions, start: &[f64]) -> Result<Solver, TrackError>;
    /// Solves for `goal` (the effector's) from `from` into `out`.
    fn solve_from(
        &mut self,
        solver: &mut Solver,
        from: &[f64],
        goal: &Goal,
        out: &mut Outcome,
    ) -> Result<(), SolveError>;
    /// Whether `goal` is out of the effector's reach even without limits.
    fn out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool;
    /// The position and orientation errors at `pose` with the effector's goal `goal`.
    fn errors(&mut self, pose: &[f64], goal: &Goal) -> (f64, f64);
}

impl TrackBody for Chain {
    #[inline]
    fn angle_count(&self) -> usize {
        self.len()
    }

    #[inline]
    fn track_bounds(&self, options: &SolveOptions) -> Bounds<'_> {
        bounds(self, options)
    }

    fn track_solver(&self, options: &TrackOptions, start: &[f64]) -> Result<Solver, TrackError> {
        options.solver(self, start)
    }

    #[inline]
    fn solve_from(
        &mut self,
        solver: &mut Solver,
        from: &[f64],
        goal: &Goal,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        solver.solve_into(self, from, goal, out)
    }

    #[inline]
    fn out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool {
        goal.is_out_of_reach(self, tolerance)
    }

    #[inline]
    fn errors(&mut self, pose: &[f64], goal: &Goal) -> (f64, f64) {
        let tip = end_effector(self, pose);
        let error = math::distance_between(tip.position, goal.target());
        let angle_error = goal.orientation().map_or(0.0, |g| crate::angle::wrap_angle(g - tip.orientation).abs());
        (error, angle_error)
    }
}

/// One effector of a skeleton following a path while the rest of a rig task holds: the tip of
/// bone `bone` takes each sample's goal, the task's other goals stay as given, and each pin
/// holds its tip (and direction) where it was at the start pose, over the whole path.
///
/// Each sample is one [`Solver::solve_rig_into`] of the whole task, warm-started from the
/// previous sample's pose, as a chain's sample is. A pin is solved as a goal at its tip's place
/// (and direction) in the start pose rather than as a [`Pin`](crate::solve::Pin), which holds
/// a tip where *that solve* starts: re-anchored at every sample, a pin could creep by up to the
/// tolerance per sample; anchored once, it stays where it started. A sample's error is the
/// largest of every effector's (the tracked tip's, the held goals', the pins'), so a pin pulled
/// away shows in it.
#[derive(Debug, Clone)]
pub struct RigEffector {
    skeleton: Skeleton,
    /// The tracked goal first (its goal replaced per sample), then the held goals and pins.
    task: RigTask,
    /// The bones from the base to the tracked tip as a chain without limits: its reach.
    limb: Chain,
    /// Forward kinematics scratch: the base and every tip, and every direction.
    points: Vec<Point2<f64>>,
    directions: Vec<f64>,
}

impl RigEffector {
    /// The tip of `bone` of `skeleton` following a path from `start` (radians, one per bone)
    /// while `task`'s goals and pins hold (its mix is used as given).
    ///
    /// # Errors
    /// [`TrackError::Solve`] with [`SolveError::PoseLength`] or [`SolveError::NonFiniteAngle`]
    /// for a start pose that does not fit, and [`SolveError::Rig`] for a task that does not
    /// (a bone that does not exist, `bone` given a goal or pin of its own too, …).
    pub fn new(skeleton: &Skeleton, start: &[f64], bone: usize, task: &RigTask) -> Result<Self, TrackError> {
        check_start(skeleton, start)?;
        let n = skeleton.len();
        let mut points = vec![Point2::origin(); n + 1];
        let mut directions = vec![0.0; n];
        // Validate the task as the caller gave it, with the tracked tip as one more goal (at
        // its own place for now), so that a bone named twice is reported as such.
        let mut whole = RigTask { goals: Vec::with_capacity(task.goals.len() + task.pins.len() + 1), ..task.clone() };
        if bone < n {
            skeleton.points_into(start, &mut points, &mut directions);
            let here = Goal::position(points[bone + 1].x, points[bone + 1].y).expect("a tip is finite");
            whole.goals.push(RigGoal::new(bone, here));
        } else {
            whole.goals.push(RigGoal::new(bone, Goal::position(0.0, 0.0).expect("finite")));
        }
        whole.goals.extend(task.goals.iter().cloned());
        whole.validate(skeleton).map_err(SolveError::from)?;
        for pin in &task.pins {
            let tip = points[pin.bone + 1];
            let here = if pin.orientation {
                Goal::with_orientation(tip.x, tip.y, directions[pin.bone])
            } else {
                Goal::position(tip.x, tip.y)
            };
            whole.goals.push(RigGoal::new(pin.bone, here.expect("a tip and a direction are finite")));
        }
        whole.pins.clear();
        let links: Vec<Link> = skeleton.path(bone).iter().map(|&j| Link::new(skeleton.lengths()[j], 0.0)).collect();
        let base = skeleton.base();
        let limb = Chain::new([base.x, base.y], &links).expect("a skeleton's bones make a valid chain");
        Ok(Self { skeleton: skeleton.clone(), task: whole, limb, points, directions })
    }

    /// The skeleton.
    #[must_use]
    pub fn skeleton(&self) -> &Skeleton {
        &self.skeleton
    }

    /// The tracked bone.
    #[must_use]
    pub fn bone(&self) -> usize {
        self.task.goals[0].bone
    }

    /// The task solved at every sample: the tracked goal first (as last set), then the held
    /// goals, then the pins as goals at their start places.
    #[must_use]
    pub fn task(&self) -> &RigTask {
        &self.task
    }
}

/// One finite angle per bone.
fn check_start(skeleton: &Skeleton, start: &[f64]) -> Result<(), SolveError> {
    if start.len() != skeleton.len() {
        return Err(SolveError::PoseLength { expected: skeleton.len(), got: start.len() });
    }
    match start.iter().position(|a| !a.is_finite()) {
        Some(index) => Err(SolveError::NonFiniteAngle { index, value: start[index] }),
        None => Ok(()),
    }
}

impl TrackBody for RigEffector {
    fn angle_count(&self) -> usize {
        self.skeleton.len()
    }

    fn track_bounds(&self, options: &SolveOptions) -> Bounds<'_> {
        match options.limits {
            LimitMode::Ignore => Bounds::free(),
            LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => self.skeleton.bounds(),
        }
    }

    fn track_solver(&self, options: &TrackOptions, start: &[f64]) -> Result<Solver, TrackError> {
        options.validate()?;
        let solve = &options.solve;
        if !solve.method.solves_rigs() {
            return Err(SolveError::ChainOnly { method: solve.method.name() }.into());
        }
        let n = self.skeleton.len();
        if !solve.rates.is_empty() && solve.rates.len() != n {
            return Err(SolveError::RatesLength { expected: n, got: solve.rates.len() }.into());
        }
        check_start(&self.skeleton, start)?;
        Ok(Solver::new(SolveOptions { restarts: None, record_every: None, ..solve.clone() })?)
    }

    fn solve_from(
        &mut self,
        solver: &mut Solver,
        from: &[f64],
        goal: &Goal,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        self.task.goals[0].goal = *goal;
        solver.solve_rig_into(&self.skeleton, from, &self.task, out)
    }

    fn out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool {
        // The limb's annulus of lengths holds only where bones start at their parents' tips
        // and turn: with offsets or slides no claim is made (as the rig solve's own test).
        self.skeleton.is_plain() && goal.is_out_of_reach(&self.limb, tolerance)
    }

    fn errors(&mut self, pose: &[f64], goal: &Goal) -> (f64, f64) {
        self.task.goals[0].goal = *goal;
        self.skeleton.points_into(pose, &mut self.points, &mut self.directions);
        let (mut error, mut angle_error) = (0.0f64, 0.0f64);
        for g in &self.task.goals {
            let tip = self.points[g.bone + 1];
            error = error.max(math::distance_between(tip, g.goal.target()));
            if let Some(phi) = g.goal.orientation() {
                angle_error = angle_error.max(crate::angle::wrap_angle(phi - self.directions[g.bone]).abs());
            }
        }
        (error, angle_error)
    }
}
