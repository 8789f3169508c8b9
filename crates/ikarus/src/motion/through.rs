//! Motion through goals: solve for each goal in order, each from the pose the previous solve
//! ended at, then time the joint-space path with one ease (see the [module docs](super)).

use thiserror::Error;

use super::{Animation, MotionError, MotionOptions, animate_with};
use crate::chain::Chain;
use crate::solve::{Goal, LimitMode, Outcome, SolveError, Solver, Status};

/// Which poses the motion passes through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Route {
    /// Straight (in joint space) from the start to each solved pose in turn: the keyframes are
    /// the start and the pose each solve ended at.
    #[default]
    Keyframes,
    /// The solver's own path: every frame each solve recorded (see
    /// [`SolveOptions::record_every`](crate::SolveOptions::record_every)), re-timed as one path.
    Recorded,
}

/// How the solve for one goal of a motion ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GoalOutcome {
    /// The goal.
    pub goal: Goal,
    /// Why the solve stopped.
    pub status: Status,
    /// Iterations of the solve (over all its attempts).
    pub iterations: u32,
    /// Distance from the tip to the goal at the end.
    pub error: f64,
}

/// A motion through goals: one outcome per goal, and the timed frames.
#[derive(Debug, Clone, PartialEq)]
pub struct GoalMotion {
    /// How each goal's solve ended, in the order of the goals.
    pub solves: Vec<GoalOutcome>,
    /// The timed frames.
    pub animation: Animation,
}

/// Why a motion through goals could not be made.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GoalMotionError {
    /// A solve could not start.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// The poses could not be timed.
    #[error(transparent)]
    Motion(#[from] MotionError),
}

/// Solves for each of `goals` in order with `solver`, the first from `start` (radians, one
/// angle per joint) and each later one from the pose the previous solve ended at, then times
/// the poses `route` names with `options`: timing, ease and interpolation ([`animate_with`]).
/// [`Route::Recorded`] uses the same interpolation through the solver's recorded poses.
///
/// The motion obeys the same limits as the solves: when the solver ignores limits, every joint
/// moves freely (and so wraps the short way round); otherwise limited joints stay inside their
/// ranges. A goal that is not reached is not an error: its [`GoalOutcome::status`] says so and
/// the motion continues from the best pose found.
pub fn through_goals(
    solver: &mut Solver,
    chain: &Chain,
    start: &[f64],
    goals: &[Goal],
    route: Route,
    options: MotionOptions,
) -> Result<GoalMotion, GoalMotionError> {
    let mut solves = Vec::with_capacity(goals.len());
    let solve = |from: &[f64], goal: &Goal, out: &mut Outcome| solver.solve_into(chain, from, goal, out);
    let record = |goal: &Goal, out: &Outcome| {
        solves.push(GoalOutcome { goal: *goal, status: out.status, iterations: out.iterations, error: out.error });
    };
    let poses = solve_in_turn(start, goals, route, solve, record)?;
    let animation = match solver.options().limits {
        LimitMode::Ignore => animate_with(&chain.without_limits(), &poses, None, options)?,
        LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => {
            animate_with(chain, &poses, None, options)?
        }
    };
    Ok(GoalMotion { solves, animation })
}

/// Solves for each of `steps` in order, the first from `start` and each later one from the
/// pose the previous solve ended at, telling `record` how each ended; returns the poses
/// `route` names (the start and every solved pose, or the start and every recorded pose). The
/// one loop of [`through_goals`] and [`through_rig_tasks`](super::through_rig_tasks).
pub(super) fn solve_in_turn<T>(
    start: &[f64],
    steps: &[T],
    route: Route,
    mut solve: impl FnMut(&[f64], &T, &mut Outcome) -> Result<(), SolveError>,
    mut record: impl FnMut(&T, &Outcome),
) -> Result<Vec<Vec<f64>>, SolveError> {
    let mut keyframes = vec![start.to_vec()];
    let mut recorded: Vec<Vec<f64>> = vec![start.to_vec()];
    let mut outcome = Outcome::default();
    for step in steps {
        let from = keyframes.last().expect("the start pose is a keyframe").clone();
        solve(&from, step, &mut outcome)?;
        // The solver's recorded path, without repeating the pose it started from (kept only
        // when the motion follows it: it can be large).
        if matches!(route, Route::Recorded) {
            recorded.extend(outcome.frames.iter().skip(1).map(|f| f.angles.to_vec()));
        }
        keyframes.push(outcome.pose.angles().to_vec());
        record(step, &outcome);
    }
    Ok(match route {
        Route::Keyframes => keyframes,
        Route::Recorded => recorded,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Timing;
    use crate::{Ease, Link, SolveOptions};

    fn options(frames: usize, ease: Ease) -> MotionOptions {
        MotionOptions::new(Timing::Frames(frames), ease)
    }

    fn seed() -> Chain {
        Chain::new([0.0, 0.0], &[Link::new(3.0, 0.1), Link::new(2.0, 0.1), Link::new(1.0, 0.1)]).unwrap()
    }

    #[test]
    fn passes_each_goal_in_order_and_ends_at_the_last() {
        let chain = seed();
        let goals = [Goal::position(3.0, -1.0).unwrap(), Goal::position(2.0, 3.0).unwrap()];
        let mut solver = Solver::new(SolveOptions::default()).unwrap();
        let start = chain.start_pose().angles().to_vec();
        let m = through_goals(&mut solver, &chain, &start, &goals, Route::Keyframes, options(9, Ease::Sine)).unwrap();
        assert_eq!(m.solves.len(), 2);
        assert!(m.solves.iter().all(|s| s.status == Status::Reached));
        assert_eq!(m.animation.frames.len(), 9);
        assert_eq!(m.animation.frames[0].angles, start);
        let tip = *m.animation.frames[8].joints.last().unwrap();
        assert!((tip.x - 2.0).abs() < 1e-5 && (tip.y - 3.0).abs() < 1e-5, "{tip:?}");
    }

    #[test]
    fn a_recorded_path_needs_recorded_frames_and_bad_options_are_errors() {
        let chain = seed();
        let goals = [Goal::position(2.0, 3.0).unwrap()];
        let start = chain.start_pose().angles().to_vec();
        let every = SolveOptions { record_every: Some(1), ..SolveOptions::default() };
        let mut solver = Solver::new(every).unwrap();
        let m = through_goals(&mut solver, &chain, &start, &goals, Route::Recorded, options(5, Ease::Linear)).unwrap();
        assert_eq!(m.animation.frames.len(), 5);
        let rates = SolveOptions { rates: vec![1.0], ..SolveOptions::default() };
        let mut solver = Solver::new(rates).unwrap();
        let e = through_goals(&mut solver, &chain, &start, &goals, Route::Keyframes, options(5, Ease::Sine));
        assert_eq!(e, Err(GoalMotionError::Solve(SolveError::RatesLength { expected: 3, got: 1 })));
    }
}
