//! [`Model`]: what the solver core asks of the body it moves — forward kinematics into its
//! scratch, the Jacobian, the limits, the reach, the reachability of a goal and the
//! non-Jacobian steppers — so that one core can serve chains and, later, skeletons.
//!
//! The core is generic over the model and monomorphised per model: for a [`Chain`] every
//! method is today's chain function, inlined, so the chain path is the same machine code as
//! before the abstraction (no dynamic dispatch, no branch on the kind of body).

use nalgebra::{Matrix3xX, Point2};

use super::problem::Problem;
use super::{ccd, fabrik};
use crate::chain::{Chain, JointLimits};
use crate::goal::Goal;
use crate::kinematics::{jacobian_from_joints, joint_positions_into};
use crate::limits::Bounds;

/// A kinematic body the solver core can move: angles in, joint points and a Jacobian out.
///
/// `points` is the model's point buffer (for a chain: the `len() + 1` joint positions, base
/// first, tip last); the core sizes it with [`Model::points`] and only passes it back.
pub(super) trait Model: Sized {
    /// The number of angles (joints).
    fn len(&self) -> usize;
    /// The number of points [`Model::forward_into`] writes.
    fn points(&self) -> usize;
    /// The largest distance from the base any point can reach.
    fn max_reach(&self) -> f64;
    /// The joint limits, one entry per angle.
    fn limits(&self) -> &[Option<JointLimits>];
    /// The limits as [`Bounds`].
    fn bounds(&self) -> Bounds<'_>;
    /// Forward kinematics of `angles` into `points`; returns the end effector's orientation.
    fn forward_into(&self, angles: &[f64], points: &mut [Point2<f64>]) -> f64;
    /// The end effector's position among `points` written by [`Model::forward_into`].
    fn tip(&self, points: &[Point2<f64>]) -> Point2<f64>;
    /// The 3×N Jacobian (x, y, orientation) at the pose whose `points` are given.
    fn jacobian_into(&self, points: &[Point2<f64>], out: &mut Matrix3xX<f64>);
    /// Whether `goal` is out of reach even without limits (by more than `tolerance`).
    fn is_out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool;
    /// One CCD sweep (see [`ccd::sweep`]); returns the trial pose's end orientation.
    fn ccd_sweep(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &[Point2<f64>],
        trial: &mut [f64],
        trial_points: &mut [Point2<f64>],
    ) -> f64;
    /// One FABRIK iteration (see [`fabrik::iterate`]); returns the trial pose's end orientation.
    fn fabrik_iterate(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &[Point2<f64>],
        trial: &mut [f64],
        trial_points: &mut [Point2<f64>],
    ) -> f64;
}

impl Model for Chain {
    #[inline]
    fn len(&self) -> usize {
        Chain::len(self)
    }

    #[inline]
    fn points(&self) -> usize {
        Chain::len(self) + 1
    }

    #[inline]
    fn max_reach(&self) -> f64 {
        Chain::max_reach(self)
    }

    #[inline]
    fn limits(&self) -> &[Option<JointLimits>] {
        Chain::limits(self)
    }

    #[inline]
    fn bounds(&self) -> Bounds<'_> {
        Chain::bounds(self)
    }

    #[inline]
    fn forward_into(&self, angles: &[f64], points: &mut [Point2<f64>]) -> f64 {
        joint_positions_into(self, angles, points)
    }

    #[inline]
    fn tip(&self, points: &[Point2<f64>]) -> Point2<f64> {
        points[Chain::len(self)]
    }

    #[inline]
    fn jacobian_into(&self, points: &[Point2<f64>], out: &mut Matrix3xX<f64>) {
        jacobian_from_joints(points, out);
    }

    #[inline]
    fn is_out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool {
        goal.is_out_of_reach(self, tolerance)
    }

    #[inline]
    fn ccd_sweep(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &[Point2<f64>],
        trial: &mut [f64],
        trial_points: &mut [Point2<f64>],
    ) -> f64 {
        ccd::sweep(p, angles, points, trial, trial_points)
    }

    #[inline]
    fn fabrik_iterate(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &[Point2<f64>],
        trial: &mut [f64],
        trial_points: &mut [Point2<f64>],
    ) -> f64 {
        fabrik::iterate(p, angles, points, trial, trial_points)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::restarts::solve_with_restarts;
    use crate::solve::scratch::Scratch;
    use crate::solve::solver::finish;
    use crate::solve::{LimitMode, Method, Outcome, Restarts, SolveOptions, Solver};

    /// A model that is not a `Chain` but moves like one: every method delegates to it. Solving
    /// through it exercises the core's generic path (a new monomorphisation), which must give
    /// the chain path's outcome bit for bit.
    struct Delegate<'a>(&'a Chain);

    /// The chain problem of a delegate's problem: same goal, options and bounds.
    fn inner<'a>(p: &Problem<'a, Delegate<'a>>) -> Problem<'a, Chain> {
        Problem::with_bounds(p.model.0, p.goal, p.opts, p.bounds)
    }

    impl<'a> Model for Delegate<'a> {
        fn len(&self) -> usize {
            Model::len(self.0)
        }
        fn points(&self) -> usize {
            Model::points(self.0)
        }
        fn max_reach(&self) -> f64 {
            Model::max_reach(self.0)
        }
        fn limits(&self) -> &[Option<JointLimits>] {
            Model::limits(self.0)
        }
        fn bounds(&self) -> Bounds<'_> {
            Model::bounds(self.0)
        }
        fn forward_into(&self, angles: &[f64], points: &mut [Point2<f64>]) -> f64 {
            self.0.forward_into(angles, points)
        }
        fn tip(&self, points: &[Point2<f64>]) -> Point2<f64> {
            self.0.tip(points)
        }
        fn jacobian_into(&self, points: &[Point2<f64>], out: &mut Matrix3xX<f64>) {
            self.0.jacobian_into(points, out);
        }
        fn is_out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool {
            self.0.is_out_of_reach(goal, tolerance)
        }
        fn ccd_sweep(
            p: &Problem<'_, Self>,
            angles: &[f64],
            points: &[Point2<f64>],
            trial: &mut [f64],
            trial_points: &mut [Point2<f64>],
        ) -> f64 {
            Chain::ccd_sweep(&inner(p), angles, points, trial, trial_points)
        }
        fn fabrik_iterate(
            p: &Problem<'_, Self>,
            angles: &[f64],
            points: &[Point2<f64>],
            trial: &mut [f64],
            trial_points: &mut [Point2<f64>],
        ) -> f64 {
            Chain::fabrik_iterate(&inner(p), angles, points, trial, trial_points)
        }
    }

    /// Every method and limit mode, with restarts and frames, on reachable, oriented and
    /// unreachable goals: the core run on a delegating model gives the `Solver`'s chain outcome
    /// bit for bit (pose, status, iterations, restarts, errors, tip, frames): the same restart
    /// driver and final measurement as [`Solver::solve_into`] after its closed form.
    #[test]
    fn the_core_is_generic_and_a_delegating_model_solves_like_the_chain() {
        let chain = crate::fixtures::seed_arm_limited();
        let goals = [
            Goal::position(2.0, 3.0).unwrap(),
            Goal::with_orientation(-1.0, 1.5, 0.7).unwrap(),
            Goal::position(-3.0, -1.0).unwrap(),
            Goal::position(40.0, 0.0).unwrap(),
        ];
        let mut compared = 0;
        for method in Method::ALL.into_iter().filter(|&m| m != Method::Analytic) {
            for limits in LimitMode::ALL {
                let opts = SolveOptions {
                    method,
                    limits,
                    closed_form: false,
                    record_every: Some(3),
                    restarts: Some(Restarts { attempts: 3, ..Restarts::default() }),
                    ..SolveOptions::default()
                };
                let Ok(mut solver) = Solver::new(opts.clone()) else { continue };
                for goal in &goals {
                    let start = chain.start_pose();
                    let Ok(expected) = solver.solve(&chain, start, goal) else { continue };
                    let model = Delegate(&chain);
                    let p = Problem::new(&model, goal, &opts);
                    let mut s = Scratch::default();
                    s.fit(model.len(), model.points());
                    let mut out = Outcome::default();
                    solve_with_restarts(&p, start.angles(), None, &mut s, &mut out);
                    finish(&p, &mut s, &mut out);
                    assert_eq!(out, expected, "{method:?} {limits:?} {goal:?}");
                    compared += 1;
                }
            }
        }
        assert!(compared >= 40, "{compared}");
    }
}
