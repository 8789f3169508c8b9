//! The [`Chain`] as a [`Model`] of the solver core: every method is the chain's own function,
//! inlined, so the chain path is the same machine code as before the abstraction.

use nalgebra::{Point2, Vector3};

use super::algebra::Fixed3;
use super::model::{Model, Problem, ScratchOf};
use super::{Outcome, SolveOptions, ccd, fabrik, fast};
use crate::angle::wrap_angle;
use crate::chain::{Chain, JointLimits};
use crate::goal::Goal;
use crate::kinematics::{EndEffector, jacobian_from_joints, joint_positions_into};
use crate::limits::Bounds;
use crate::math;
use crate::math::distance;

impl Model for Chain {
    type Goal = Goal;
    type Points = Vec<Point2<f64>>;
    type Alg = Fixed3;
    const PROGRESS_FLOOR: Option<f64> = None;
    const GIVES_UP_PINNED: bool = true;

    #[inline]
    fn len(&self) -> usize {
        Chain::len(self)
    }

    fn fit(&self, s: &mut ScratchOf<Self>) {
        let points = Chain::len(self) + 1;
        s.joints.resize(points, Point2::origin());
        s.trial_joints.resize(points, Point2::origin());
        s.fit_joints(Chain::len(self));
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
    fn forward_into(&self, angles: &[f64], points: &mut Self::Points) -> f64 {
        joint_positions_into(self, angles, points)
    }

    #[inline]
    fn frame_points(points: &Self::Points) -> &[Point2<f64>] {
        points
    }

    #[inline]
    fn measure(
        &self,
        goal: &Goal,
        opts: &SolveOptions,
        points: &Self::Points,
        phi: f64,
        out: &mut Outcome,
        alg: &mut Fixed3,
    ) {
        let tip = points[Chain::len(self)];
        let target = goal.target();
        let (dx, dy) = (target.x - tip.x, target.y - tip.y);
        let turn = goal.orientation().map(|g| wrap_angle(g - phi));
        out.error = distance(dx, dy);
        out.angle_error = turn.map_or(0.0, f64::abs);
        out.end_effector = EndEffector { position: tip, orientation: phi };
        alg.e = Vector3::new(dx, dy, turn.map_or(0.0, |t| opts.orientation_weight * t));
    }

    #[inline]
    fn jacobian(&self, goal: &Goal, opts: &SolveOptions, points: &Self::Points, alg: &mut Fixed3) {
        jacobian_from_joints(points, &mut alg.jacobian);
        let oriented = goal.orientation().is_some();
        alg.oriented = oriented;
        let row_scale = if oriented { opts.orientation_weight } else { 0.0 };
        for mut col in alg.jacobian.column_iter_mut() {
            col[2] *= row_scale;
        }
    }

    #[inline]
    fn trial_error(&self, goal: &Goal, opts: &SolveOptions, points: &Self::Points, phi: f64) -> f64 {
        let target = goal.target();
        let tip = points[Chain::len(self)];
        let turn = goal.orientation().map_or(0.0, |g| opts.orientation_weight * wrap_angle(g - phi));
        math::square(target.x - tip.x) + math::square(target.y - tip.y) + turn * turn
    }

    #[inline]
    fn best_key(&self, opts: &SolveOptions, out: &Outcome, _alg: &Fixed3) -> f64 {
        out.error * out.error + math::square(opts.orientation_weight * out.angle_error)
    }

    #[inline]
    fn is_out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool {
        goal.is_out_of_reach(self, tolerance)
    }

    #[inline]
    fn judge(&self, _goal: &Goal, _opts: &SolveOptions, _out: &mut Outcome) {}

    #[inline]
    fn settle_restart(&self, _: &Problem<'_, Self>, _: u32, _: &Outcome, _: &mut [f64], _: &mut [bool]) {}

    #[inline]
    fn fast_attempt(p: &Problem<'_, Self>, start: &[f64], s: &mut ScratchOf<Self>, out: &mut Outcome) -> fast::Taken {
        let (chain, opts) = (p.model, p.opts);
        if !p.bounds.is_free() || !fast::applies(chain, opts, p.goal.orientation().is_some()) {
            return fast::Taken::No;
        }
        let target = p.goal.target();
        let end = fast::run_one(chain, opts, p.max_iterations, start, &mut s.fast, (target.x, target.y));
        match end.status {
            Some(status) => {
                out.frames.start(chain.len(), None, opts.max_iterations);
                let angles = out.pose.angles_mut();
                angles.clear();
                angles.extend_from_slice(s.fast.angles());
                let (x, y) = s.fast.tip();
                out.iterations = end.iterations;
                out.error = end.error;
                out.angle_error = 0.0;
                out.end_effector = EndEffector { position: Point2::new(x, y), orientation: end.phi };
                fast::Taken::Done(status)
            }
            None => {
                s.best.copy_from_slice(s.fast.angles());
                fast::Taken::Resume(end.resume)
            }
        }
    }

    #[inline]
    fn ccd_sweep(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &Self::Points,
        trial: &mut [f64],
        trial_points: &mut Self::Points,
    ) -> f64 {
        ccd::sweep(p, angles, points, trial, trial_points)
    }

    #[inline]
    fn fabrik_iterate(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &Self::Points,
        trial: &mut [f64],
        trial_points: &mut Self::Points,
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
    fn inner<'p>(p: &Problem<'p, Delegate<'_>>) -> Problem<'p, Chain> {
        Problem::with_bounds(p.model.0, p.goal, p.opts, p.bounds)
    }

    impl<'a> Model for Delegate<'a> {
        type Goal = Goal;
        type Points = Vec<Point2<f64>>;
        type Alg = Fixed3;
        const PROGRESS_FLOOR: Option<f64> = None;
        fn len(&self) -> usize {
            Model::len(self.0)
        }
        fn fit(&self, s: &mut ScratchOf<Self>) {
            Model::fit(self.0, s);
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
        fn forward_into(&self, angles: &[f64], points: &mut Self::Points) -> f64 {
            self.0.forward_into(angles, points)
        }
        fn frame_points(points: &Self::Points) -> &[Point2<f64>] {
            points
        }
        fn measure(
            &self,
            goal: &Goal,
            opts: &SolveOptions,
            points: &Self::Points,
            phi: f64,
            out: &mut Outcome,
            alg: &mut Fixed3,
        ) {
            self.0.measure(goal, opts, points, phi, out, alg);
        }
        fn jacobian(&self, goal: &Goal, opts: &SolveOptions, points: &Self::Points, alg: &mut Fixed3) {
            self.0.jacobian(goal, opts, points, alg);
        }
        fn trial_error(&self, goal: &Goal, opts: &SolveOptions, points: &Self::Points, phi: f64) -> f64 {
            self.0.trial_error(goal, opts, points, phi)
        }
        fn best_key(&self, opts: &SolveOptions, out: &Outcome, alg: &Fixed3) -> f64 {
            self.0.best_key(opts, out, alg)
        }
        fn is_out_of_reach(&self, goal: &Goal, tolerance: f64) -> bool {
            self.0.is_out_of_reach(goal, tolerance)
        }
        fn judge(&self, goal: &Goal, opts: &SolveOptions, out: &mut Outcome) {
            self.0.judge(goal, opts, out);
        }
        fn settle_restart(
            &self,
            p: &Problem<'_, Self>,
            k: u32,
            out: &Outcome,
            restart: &mut [f64],
            scratch: &mut [bool],
        ) {
            self.0.settle_restart(&inner(p), k, out, restart, scratch);
        }
        fn ccd_sweep(
            p: &Problem<'_, Self>,
            angles: &[f64],
            points: &Self::Points,
            trial: &mut [f64],
            trial_points: &mut Self::Points,
        ) -> f64 {
            Chain::ccd_sweep(&inner(p), angles, points, trial, trial_points)
        }
        fn fabrik_iterate(
            p: &Problem<'_, Self>,
            angles: &[f64],
            points: &Self::Points,
            trial: &mut [f64],
            trial_points: &mut Self::Points,
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
                    reach_verdict: false,
                    ..SolveOptions::default()
                };
                let Ok(mut solver) = Solver::new(opts.clone()) else { continue };
                for goal in &goals {
                    let start = chain.start_pose();
                    let Ok(expected) = solver.solve(&chain, start, goal) else { continue };
                    let model = Delegate(&chain);
                    let p = Problem::new(&model, goal, &opts);
                    let mut s = Scratch::default();
                    Model::fit(&model, &mut s);
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

    /// The options the position-only fast path takes, in several variants.
    fn fast_variants() -> Vec<SolveOptions> {
        let base = SolveOptions { limits: LimitMode::Ignore, reach_verdict: false, ..SolveOptions::default() };
        vec![
            base.clone(),
            SolveOptions { max_step: None, ..base.clone() },
            SolveOptions { stall: None, max_iterations: 40, ..base.clone() },
            SolveOptions { gain: 0.7, lambda: 1.0, ..base.clone() },
            SolveOptions { tolerance: 1e-12, backtrack: 1, ..base.clone() },
            SolveOptions { lambda: 0.0, max_iterations: 7, restarts: None, ..base },
        ]
    }

    /// The fast path against the general loop (the delegating model has none, so it runs the
    /// general loop): every outcome the same bit for bit, on reachable goals, goals out of
    /// reach, goals at the base and near the outer rim, for 3-, 7- and 20-link chains and every
    /// option variant the fast path takes — through restarts, stalls and iteration caps.
    #[test]
    fn the_fast_path_gives_the_general_loops_outcome_bit_for_bit() {
        let mut rng = crate::rng::SplitMix64(2026);
        let chains = [
            crate::fixtures::seed_arm(),
            crate::fixtures::random_chain(&mut rng, 7, false),
            crate::fixtures::random_chain(&mut rng, 20, false),
        ];
        let mut compared = 0;
        for opts in fast_variants() {
            let mut solver = Solver::new(opts.clone()).unwrap();
            for chain in &chains {
                let reach = chain.max_reach();
                for k in 0..150 {
                    let goal = match k % 5 {
                        0 => Goal::position(1.5 * reach * (rng.unit() - 0.5), 1.5 * reach * (rng.unit() - 0.5)),
                        1 => Goal::position(0.0, 0.0),
                        2 => Goal::position(reach * (1.0 + 1e-9), 0.0),
                        _ => Ok(crate::fixtures::random_goal(&mut rng, chain, false)),
                    }
                    .unwrap();
                    let start = chain.start_pose();
                    let expected = {
                        let model = Delegate(chain);
                        let p = Problem::new(&model, &goal, &opts);
                        let mut s = Scratch::default();
                        Model::fit(&model, &mut s);
                        let mut out = Outcome::default();
                        solve_with_restarts(&p, start.angles(), None, &mut s, &mut out);
                        finish(&p, &mut s, &mut out);
                        out
                    };
                    let got = solver.solve(chain, start, &goal).unwrap();
                    assert_eq!(got, expected, "{opts:?} {goal:?}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 6 * 3 * 150);
    }

    /// `solve_batch` gives what `solve_into` gives goal by goal, bit for bit, whichever path a
    /// goal takes (lanes, or the scalar solver after them): reachable, unreachable and oriented
    /// goals mixed, batches of every size around the lane counts (four, and eight in two AVX2
    /// groups), the outcomes reused across batches, with limits on and off, a two-link chain (the closed form) and non-default
    /// options.
    #[test]
    fn a_batch_gives_every_goal_its_single_solve() {
        let mut rng = crate::rng::SplitMix64(99);
        let chains = [
            crate::fixtures::seed_arm(),
            crate::fixtures::seed_arm_limited(),
            crate::fixtures::arm(&[2.0, 1.0]),
            crate::fixtures::random_chain(&mut rng, 9, false),
            // The shipped seven and (in lengths) tentacle.
            crate::fixtures::seven_link_arm(),
            crate::fixtures::arm(&[0.5; 20]),
        ];
        let mut out = Vec::new();
        let mut variants = fast_variants();
        variants.push(SolveOptions::default());
        variants.push(SolveOptions { method: Method::DampedLeastSquares, ..SolveOptions::default() });
        for opts in variants {
            let mut solver = Solver::new(opts.clone()).unwrap();
            let mut alone = Solver::new(opts.clone()).unwrap();
            for chain in &chains {
                let reach = chain.max_reach();
                for size in [0, 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 64] {
                    let goals: Vec<Goal> = (0..size)
                        .map(|k| match k % 7 {
                            0 => Goal::position(2.0 * reach * (rng.unit() - 0.5), 2.0 * reach * (rng.unit() - 0.5))
                                .unwrap(),
                            1 => crate::fixtures::random_goal(&mut rng, chain, true),
                            _ => crate::fixtures::random_goal(&mut rng, chain, false),
                        })
                        .collect();
                    let start = chain.start_pose().angles();
                    solver.solve_batch(chain, start, &goals, &mut out).unwrap();
                    assert_eq!(out.len(), size);
                    for (goal, got) in goals.iter().zip(&out) {
                        let mut expected = Outcome::default();
                        alone.solve_into(chain, start, goal, &mut expected).unwrap();
                        assert_eq!(got, &expected, "{opts:?} {goal:?}");
                    }
                }
            }
        }
        // Bad input is refused before anything is written.
        let chain = crate::fixtures::seed_arm();
        let mut solver = Solver::new(SolveOptions::default()).unwrap();
        let before = out.clone();
        assert!(
            solver.solve_batch(&chain, &[0.0, f64::NAN, 0.0], &[Goal::position(1.0, 1.0).unwrap()], &mut out).is_err()
        );
        assert!(solver.solve_batch(&chain, &[0.0], &[], &mut out).is_err());
        assert_eq!(out, before);
    }
}
