//! Motion of a skeleton through rig tasks: solve each [`RigTask`] in order, each from the pose
//! the previous solve ended at, then time the joint-space path through the start pose and the
//! solved poses with one ease — the same loop and the same path, spline and timing as a
//! chain's motion through goals ([`through_goals`](super::through_goals)), on a [`Skeleton`].

use super::through::solve_in_turn;
use super::{Animation, GoalMotionError, MotionOptions, Route, animate_with};
use crate::skeleton::Skeleton;
use crate::solve::{EffectorOutcome, LimitMode, Outcome, RigTask, Solver, Status};

/// How the solve of one rig task of a motion ended.
#[derive(Debug, Clone, PartialEq)]
pub struct RigSolveOutcome {
    /// Overall: [`Status::Reached`] only if every effector is.
    pub status: Status,
    /// Iterations of the solve (over all its attempts).
    pub iterations: u32,
    /// The largest effector distance at the end.
    pub error: f64,
    /// Each effector: the task's goals in order, then its pins.
    pub effectors: Vec<EffectorOutcome>,
    /// The pose the solve ended at, radians, one angle per bone: the motion's keyframe.
    pub angles: Vec<f64>,
}

/// A motion of a skeleton through rig tasks: one outcome per task, and the timed frames (each
/// frame's points are the base, then every bone's tip in the skeleton's order).
#[derive(Debug, Clone, PartialEq)]
pub struct RigMotion {
    /// How each task's solve ended, in the order of the tasks.
    pub solves: Vec<RigSolveOutcome>,
    /// The timed frames.
    pub animation: Animation,
}

/// Solves each of `tasks` in order with [`Solver::solve_rig_into`], the first from `start`
/// (radians, one angle per bone in the skeleton's order) and each later one from the pose the
/// previous solve ended at, then times the poses `route` names with `options`, as
/// [`through_goals`](super::through_goals) does for a chain: the frames start at `start` and
/// end at the last solved pose, passing through every solved pose in turn (the keyframes), and
/// every bone's angle follows the spline (or polyline) of [`Interpolation`](super::Interpolation).
///
/// A pin holds its tip where it is at the start of its task's solve, so a pin kept through
/// every task stays where the motion began. The motion obeys the same limits as the solves:
/// with [`LimitMode::Ignore`] every bone moves freely. A task not met is not an error: its
/// [`RigSolveOutcome::status`] says so and the motion continues from the best pose found.
///
/// # Errors
/// [`GoalMotionError::Solve`] when a solve cannot start (a method that solves chains only, a
/// task naming a bone the skeleton lacks, a start pose that does not fit), and
/// [`GoalMotionError::Motion`] when the poses cannot be timed (no tasks is not one of them: the
/// motion then stays at `start`).
pub fn through_rig_tasks(
    solver: &mut Solver,
    skeleton: &Skeleton,
    start: &[f64],
    tasks: &[RigTask],
    route: Route,
    options: MotionOptions,
) -> Result<RigMotion, GoalMotionError> {
    let mut solves = Vec::with_capacity(tasks.len());
    let solve = |from: &[f64], task: &RigTask, out: &mut Outcome| solver.solve_rig_into(skeleton, from, task, out);
    let record = |_: &RigTask, out: &Outcome| {
        solves.push(RigSolveOutcome {
            status: out.status,
            iterations: out.iterations,
            error: out.error,
            effectors: out.effectors.clone(),
            angles: out.pose.angles().to_vec(),
        });
    };
    let poses = solve_in_turn(start, tasks, route, solve, record)?;
    let animation = match solver.options().limits {
        LimitMode::Ignore => animate_with(&skeleton.without_limits(), &poses, None, options)?,
        LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => {
            animate_with(skeleton, &poses, None, options)?
        }
    };
    Ok(RigMotion { solves, animation })
}

#[cfg(test)]
mod tests;
