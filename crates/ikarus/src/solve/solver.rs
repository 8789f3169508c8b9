//! [`Solver`]: validated options plus the scratch buffers reused across iterations and
//! solves; checks a solve's input, takes the closed form where it applies, and hands the rest
//! to the restart driver.

use super::algebra::Fixed3;
use super::algebra::dynamic::Dynamic;
use super::model::Problem;
use super::model::{Model, ScratchOf};
use super::restarts::solve_with_restarts_seeded;
use super::scratch::Scratch;
use super::skeleton_model::RigPoints;
use super::verdict::ReachCache;
use super::{Method, OptionsError, Outcome, SolveError, SolveOptions, Status, fast};
use crate::angle::wrap_angle;
use crate::chain::{Chain, Pose};
use crate::closed_form::{self, ClosedForm};
use crate::goal::{Annulus, Goal};
use crate::kinematics::{EndEffector, joint_positions_into};
use crate::math::distance;
use nalgebra::Point2;

/// A solver: validated options plus scratch buffers. Reuse one value for many solves; once
/// its buffers have grown to the chain's size, a solve without frame recording allocates
/// only its [`Outcome`] (and nothing with [`Solver::solve_into`]).
#[derive(Debug, Clone)]
pub struct Solver {
    pub(super) options: SolveOptions,
    scratch: Scratch<Vec<nalgebra::Point2<f64>>, Fixed3>,
    /// A skeleton's scratch, sized by its first skeleton solve.
    pub(super) rig_scratch: Scratch<RigPoints, Dynamic>,
    /// The scratch of a skeleton's first priority level solved again alone (its own, so that
    /// neither is resized back and forth).
    pub(super) first_level_scratch: Scratch<RigPoints, Dynamic>,
    /// A skeleton solve's per-solve data (effectors, targets, limits), reused.
    pub(super) rig_work: super::skeleton_model::RigWork,
    /// The chain view of the last chain-shaped skeleton solved (see `Solver::solve_rig`), kept
    /// so that solving it again allocates nothing (boxed: a chain holds its whole skeleton,
    /// and it is moved out and back in on every such solve).
    pub(super) rig_chain: Option<Box<Chain>>,
    /// The exact regions of the last chain solved with limits, for the verdict.
    pub(super) reach: ReachCache,
    /// The batch's lanes ([`Solver::solve_batch`]).
    lanes: fast::BatchBuffers,
    /// The goals of a batch left to the scalar solver.
    pending: Vec<usize>,
}

impl Solver {
    /// Validates `options` and builds a solver.
    pub fn new(options: SolveOptions) -> Result<Self, OptionsError> {
        options.validate()?;
        Ok(Self {
            options,
            scratch: Scratch::default(),
            rig_scratch: Scratch::default(),
            rig_chain: None,
            first_level_scratch: Scratch::default(),
            rig_work: Default::default(),
            reach: ReachCache::default(),
            lanes: fast::BatchBuffers::default(),
            pending: Vec::new(),
        })
    }

    /// The options this solver runs with.
    #[must_use]
    pub fn options(&self) -> &SolveOptions {
        &self.options
    }

    /// Solves for `goal` starting from `start`.
    pub fn solve(&mut self, chain: &Chain, start: &Pose, goal: &Goal) -> Result<Outcome, SolveError> {
        let mut out = Outcome::default();
        self.solve_into(chain, start.angles(), goal, &mut out)?;
        Ok(out)
    }

    /// Like [`Solver::solve`], but writes into `out`, reusing its buffers: after the first
    /// call with a chain of this size, no further memory is allocated (frame recording
    /// reuses the frame buffers, which grow only if a solve records more frames than any
    /// before it).
    pub fn solve_into(
        &mut self,
        chain: &Chain,
        start: &[f64],
        goal: &Goal,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        let opts = &self.options;
        check_input(chain, start, opts)?;
        let began = opts.restarts.and_then(|r| r.time_budget).map(|_| web_time::Instant::now());
        let s = &mut self.scratch;
        Model::fit(chain, s);
        let p = Problem::new(chain, goal, opts);
        // A goal too far for the loop (or the region's nearest point) to see a difference is
        // aimed at through its stand-in (same direction, 10⁶ reaches away), and the outcome
        // measured against the goal itself at the end ([`Goal::stand_in`]).
        let stand_in = goal.stand_in(chain.base(), chain.max_reach(), opts.tolerance);
        let aimed = stand_in.as_ref().map(|aim| Problem::new(chain, aim, opts));
        let (aim, q) = (stand_in.as_ref().unwrap_or(goal), aimed.as_ref().unwrap_or(&p));
        let far = |s: &mut ScratchOf<Chain>, out: &mut Outcome| {
            if stand_in.is_some() {
                measure(&p, s, out);
                // The goal's distance from the region: from the point nearest it, where the
                // tip is (to every digit a goal this far has).
                out.reach_distance = out.reach_distance.map(|_| out.error);
            }
        };
        out.reach_distance = None;
        let mut judged = false;
        // (A solve interrupted before it starts ends interrupted, as it always has.)
        if opts.reach_verdict && !p.bounds.is_free() && !crate::interrupt::is_set(opts.interrupt.as_ref()) {
            let tolerances = (opts.tolerance, opts.angle_tolerance);
            let found = self.reach.judge(chain, aim, tolerances, opts.interrupt.as_ref(), &mut s.trial);
            if let Some(found) = found {
                judged = true;
                out.reach_distance = Some(found.distance);
                if found.unreachable {
                    out_of_reach(q, start, s, out);
                    far(s, out);
                    return Ok(());
                }
            }
        }
        if opts.closed_form || opts.method == Method::Analytic {
            match closed_form::solve(chain, aim, start, q.bounds, &mut s.trial) {
                ClosedForm::Solved => {
                    if reached_in_closed_form(q, start, s, out) {
                        finish(q, s, out);
                        return Ok(());
                    }
                }
                ClosedForm::NotApplicable if opts.method == Method::Analytic => {
                    let goal = if goal.orientation().is_some() { "an orientation goal" } else { "a position goal" };
                    return Err(SolveError::NoClosedForm { links: chain.len(), goal });
                }
                ClosedForm::NotApplicable | ClosedForm::OutOfReach | ClosedForm::OutsideLimits => {}
            }
        }
        // A goal the region judged reachable restarts first from the pose it reads off.
        let reach = &self.reach;
        let seed = |pose: &mut Vec<f64>| reach.seed_pose(chain, aim, pose);
        solve_with_restarts_seeded(q, start, began, judged.then_some(&seed), s, out);
        finish(q, s, out);
        far(s, out);
        Ok(())
    }

    /// Solves every goal of `goals` from `start` on one chain: `out` is resized to
    /// `goals.len()` and `out[i]` is the outcome of `goals[i]`, the same, bit for bit, as
    /// [`Solver::solve_into`] gives for it alone. The outcomes' buffers are reused, so a
    /// caller that keeps `out` across batches allocates nothing once it has grown.
    ///
    /// Where the position-only fast path applies (Levenberg–Marquardt, the default; position
    /// goals; no limits enforced; no rates; no frames) the goals are solved several at a time
    /// in SIMD lanes (eight, two groups of four AVX2 lanes, where the processor has AVX2; else
    /// four), a lane taking the next goal as soon as its own is reached; a goal that is
    /// not reached on its first attempt (it needs restarts), a goal out of reach and every
    /// other goal is solved by [`Solver::solve_into`]. The lanes run the scalar solver's
    /// arithmetic operation for operation, so which path a goal takes does not change its
    /// outcome; the tests compare the two on thousands of goals.
    ///
    /// The start pose and the options are checked once, as [`Solver::solve_into`] checks them;
    /// an error leaves `out` as it was. One thread: split large batches across threads, one
    /// `Solver` each.
    ///
    /// ```
    /// use ikarus::{Chain, Goal, Link, Outcome, SolveOptions, Solver, Status};
    ///
    /// let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.0), Link::new(2.0, 0.0), Link::new(1.0, 0.0)])?;
    /// let goals: Vec<Goal> = (0..1000)
    ///     .map(|i| {
    ///         let t = f64::from(i) * 0.01;
    ///         Goal::position(4.0 * t.cos(), 4.0 * t.sin())
    ///     })
    ///     .collect::<Result<_, _>>()?;
    /// let mut solver = Solver::new(SolveOptions::default())?;
    /// let mut out: Vec<Outcome> = Vec::new();
    /// solver.solve_batch(&chain, chain.start_pose().angles(), &goals, &mut out)?;
    /// assert!(out.iter().all(|o| o.status == Status::Reached));
    /// // The same as solving each goal alone, bit for bit.
    /// let alone = solver.solve(&chain, chain.start_pose(), &goals[7])?;
    /// assert_eq!(out[7], alone);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn solve_batch(
        &mut self,
        chain: &Chain,
        start: &[f64],
        goals: &[Goal],
        out: &mut Vec<Outcome>,
    ) -> Result<(), SolveError> {
        check_input(chain, start, &self.options)?;
        out.resize_with(goals.len(), Outcome::default);
        let opts = &self.options;
        // The closed form answers a two-link chain's position goals first.
        let closed_form = (opts.closed_form || opts.method == Method::Analytic) && chain.len() == 2;
        let lanes = !closed_form && fast::applies(chain, opts, false);
        let mut rest = std::mem::take(&mut self.pending);
        rest.clear();
        if lanes {
            let n = chain.len();
            // The lanes take the position goals within reach; the others (oriented, or out of
            // reach, which the lanes could only hand back after a whole attempt) go straight
            // to the scalar solver.
            let annulus = Annulus::of(chain, opts.tolerance);
            let in_lanes = |g: &Goal| g.orientation().is_none() && !g.position_out_of(chain, annulus);
            let position_goals =
                goals.iter().enumerate().filter(|(_, g)| in_lanes(g)).map(|(i, g)| (i, g.target().x, g.target().y));
            rest.extend(goals.iter().enumerate().filter(|(_, g)| !in_lanes(g)).map(|(i, _)| i));
            let max_iterations = opts.max_iterations;
            fast::run_lanes(chain, opts, start, &mut self.lanes, position_goals, |i, end| {
                if end.status == Some(Status::Reached) {
                    let o = &mut out[i];
                    o.frames.start(n, None, max_iterations);
                    let angles = o.pose.angles_mut();
                    angles.clear();
                    angles.extend_from_slice(end.angles);
                    o.status = Status::Reached;
                    o.iterations = end.iterations;
                    o.restarts = 0;
                    o.error = end.error;
                    o.angle_error = 0.0;
                    o.end_effector = EndEffector { position: Point2::new(end.tip.0, end.tip.1), orientation: end.phi };
                    o.effectors.clear();
                    o.reach_distance = None;
                } else {
                    rest.push(i);
                }
            });
            rest.sort_unstable();
        } else {
            rest.extend(0..goals.len());
        }
        for &i in &rest {
            self.solve_into(chain, start, &goals[i], &mut out[i])?;
        }
        self.pending = rest;
        Ok(())
    }
}

/// The end of every solve: an outcome that the loop ended as `reached` was measured by it on
/// exactly the angles it returns (the Jacobian loop and FABRIK measure every pose they take,
/// CCD recomputes its joints by forward kinematics at the end of every sweep, the closed form
/// measures its answer), so it is returned as it is: measuring it again cost 5 % of every
/// solve. Debug builds, and so every test, check that claim after every solve. Any other
/// outcome (a stalled, limited or interrupted one, which ran its whole budget anyway, or the best of
/// several attempts) is measured again by [`measure`].
pub(super) fn finish<M: Model>(p: &Problem<'_, M>, s: &mut ScratchOf<M>, out: &mut Outcome) {
    if out.status == Status::Reached {
        #[cfg(debug_assertions)]
        {
            let reported = (out.end_effector, out.error, out.angle_error);
            measure_pose(p, s, out);
            debug_assert_eq!(reported, (out.end_effector, out.error, out.angle_error), "{out:?}");
            debug_assert_eq!(out.status, Status::Reached, "{out:?}");
        }
        // Each effector's status (a rig's; nothing for a chain). Debug builds measure without
        // judging above, so that the tests see what release builds return.
        p.model.judge(p.goal, p.opts, out);
    } else {
        measure(p, s, out);
    }
}

/// The end of every solve, whatever its method: the tip, `error` and `angle_error` of the
/// returned angles by a fresh forward-kinematics pass, and the status judged from them, so that
/// an outcome always describes its own pose. `reached` exactly when both errors are within
/// their tolerances; a pose that is not, though the loop stopped there as reached, is
/// `stalled`; a goal out of reach even without limits, not reached, is `unreachable`; an
/// interrupted solve not within them stays `interrupted`.
///
/// The loops measure their poses with the same forward kinematics, so today this changes
/// nothing but guards against any step rule that tracks the tip by itself (as CCD's sweep
/// once did, and reported `reached` 3.9e-6 away with a tolerance of 1e-6).
pub(super) fn measure<M: Model>(p: &Problem<'_, M>, s: &mut ScratchOf<M>, out: &mut Outcome) {
    measure_pose(p, s, out);
    p.model.judge(p.goal, p.opts, out);
}

/// [`measure`] without the effectors' own statuses.
fn measure_pose<M: Model>(p: &Problem<'_, M>, s: &mut ScratchOf<M>, out: &mut Outcome) {
    let (model, goal, opts) = (p.model, p.goal, p.opts);
    let phi = model.forward_into(out.pose.angles(), &mut s.joints);
    model.measure(goal, opts, &s.joints, phi, out, &mut s.alg);
    let within = out.error <= opts.tolerance && out.angle_error <= opts.angle_tolerance;
    out.status = match out.status {
        _ if within => Status::Reached,
        Status::Interrupted => Status::Interrupted,
        _ if model.is_out_of_reach(goal, opts.tolerance) => Status::Unreachable,
        Status::Reached => Status::Stalled,
        other @ (Status::Unreachable | Status::Stalled | Status::IterationLimit) => other,
    };
}

/// A goal the verdict found out of reach: the pose reaching the nearest reachable point (in
/// `s.trial`) is the answer, as one step without a search (as the closed form's answers are);
/// frames, if recorded, are the start pose (clamped into the bounds) and the answer.
///
/// The start pose stays the answer if its task error (distance and weighted orientation
/// error, squared and summed, as the line search measures) is lower: for a position goal only
/// where rounding puts the region's nearest point a hair beyond the start's tip, for an
/// orientation goal where the start trades distance for orientation more cheaply than the
/// pose that points the last link exactly as asked.
fn out_of_reach(p: &Problem, start: &[f64], s: &mut ScratchOf<Chain>, out: &mut Outcome) {
    let chain = p.model;
    let n = chain.len();
    s.restart.copy_from_slice(start);
    p.bounds.clamp_into(&mut s.restart);
    // The region's pose can round an ulp or two past a limit it lies on (its angles are
    // recovered from points): the answer keeps within the limits, as every solve's does.
    p.bounds.clamp_into(&mut s.trial);
    let task_error = |angles: &[f64], joints: &mut Vec<nalgebra::Point2<f64>>| {
        let phi = joint_positions_into(chain, angles, joints);
        let tip = joints[n];
        let d = distance(p.goal.target().x - tip.x, p.goal.target().y - tip.y);
        let turn = p.goal.orientation().map_or(0.0, |g| p.opts.orientation_weight * wrap_angle(g - phi));
        d * d + turn * turn
    };
    if task_error(&s.restart, &mut s.joints) < task_error(&s.trial, &mut s.trial_joints) {
        s.trial.copy_from_slice(&s.restart);
        joint_positions_into(chain, &s.trial, &mut s.trial_joints);
    }
    out.frames.start(n, p.opts.record_every, 1);
    if p.opts.record_every.is_some() {
        out.frames.push(0, &s.restart, &s.joints);
        out.frames.push(1, &s.trial, &s.trial_joints);
    }
    let angles = out.pose.angles_mut();
    angles.clear();
    angles.extend_from_slice(&s.trial);
    out.status = Status::Unreachable;
    out.iterations = 1;
    out.restarts = 0;
    measure(p, s, out);
}

/// The start pose must hold one finite angle per joint, and the rates one per joint or none
/// ([`SolveOptions::validate_for`]).
fn check_input(chain: &Chain, start: &[f64], opts: &SolveOptions) -> Result<(), SolveError> {
    let n = chain.len();
    if start.len() != n {
        return Err(SolveError::PoseLength { expected: n, got: start.len() });
    }
    if let Some((index, &value)) = start.iter().enumerate().find(|(_, a)| !a.is_finite()) {
        return Err(SolveError::NonFiniteAngle { index, value });
    }
    opts.validate_for(chain)
}

/// The closed form's answer is in `s.trial`: if it is within the tolerances, writes it into
/// `out` as a one-step solve (frames: the start pose, clamped into the bounds, and the answer)
/// and returns `true`.
fn reached_in_closed_form(p: &Problem, start: &[f64], s: &mut ScratchOf<Chain>, out: &mut Outcome) -> bool {
    let (chain, goal, opts) = (p.model, p.goal, p.opts);
    let n = chain.len();
    let phi = joint_positions_into(chain, &s.trial, &mut s.trial_joints);
    let tip = s.trial_joints[n];
    let error = distance(goal.target().x - tip.x, goal.target().y - tip.y);
    let angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - phi).abs());
    if !(error <= opts.tolerance && angle_error <= opts.angle_tolerance) {
        return false;
    }
    // One step, from the start pose straight to the solution.
    out.frames.start(n, opts.record_every, 1);
    if opts.record_every.is_some() {
        let start_joints = &mut s.joints;
        s.restart.copy_from_slice(start);
        p.bounds.clamp_into(&mut s.restart);
        joint_positions_into(chain, &s.restart, start_joints);
        out.frames.push(0, &s.restart, start_joints);
        out.frames.push(1, &s.trial, &s.trial_joints);
    }
    let angles = out.pose.angles_mut();
    angles.clear();
    angles.extend_from_slice(&s.trial);
    out.status = Status::Reached;
    out.iterations = 1;
    out.restarts = 0;
    out.error = error;
    out.angle_error = angle_error;
    out.end_effector = EndEffector { position: tip, orientation: phi };
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::Link;
    use crate::kinematics::end_effector;
    use crate::math;
    use crate::rng::SplitMix64;
    use crate::solve::{LimitMode, Restarts};

    /// A chain whose lengths run from 1e-9 to 1e9, mixed (log-uniform), and goals at the tips
    /// of random poses (reachable, a tolerance of 1e-6 being a relative 1e-15 of the reach).
    fn mixed_chain(rng: &mut SplitMix64, n: usize) -> Chain {
        let links: Vec<Link> =
            (0..n).map(|_| Link::new(math::powf(10.0, rng.range(-9.0, 9.0)), rng.range(-3.0, 3.0))).collect();
        Chain::new([0.0, 0.0], &links).unwrap()
    }

    /// Issue 11: CCD tracked its tip by rotating the joint positions, drifting from the forward
    /// kinematics of its angles by ε·reach per sweep; on chains of mixed magnitudes it reported
    /// `reached` with an error of 7.9e-7 where its pose was 3.9e-6 away (or 0.0 where it was
    /// 0.019 away). Every method's outcome is now its own pose's, bit for bit: error, angle
    /// error and tip from a fresh forward-kinematics pass, and the status from them.
    #[test]
    fn every_outcome_is_measured_on_its_own_pose() {
        let mut rng = SplitMix64(11);
        let (mut reached, mut total) = (0, 0);
        for case in 0..120 {
            let n = 2 + (rng.next_u64() % 12) as usize;
            let chain = mixed_chain(&mut rng, n);
            let truth: Vec<f64> = (0..n).map(|_| rng.range(-3.0, 3.0)).collect();
            let tip = end_effector(&chain, &truth);
            let goal = if case % 3 == 0 {
                Goal::with_orientation(tip.position.x, tip.position.y, tip.orientation).unwrap()
            } else {
                Goal::position(tip.position.x, tip.position.y).unwrap()
            };
            for method in Method::ALL {
                let opts = SolveOptions {
                    method,
                    limits: LimitMode::Ignore,
                    max_iterations: 200,
                    restarts: Some(Restarts { attempts: 2, ..Restarts::default() }),
                    ..SolveOptions::default()
                };
                let Ok(out) = Solver::new(opts.clone()).unwrap().solve(&chain, chain.start_pose(), &goal) else {
                    continue;
                };
                let fresh = end_effector(&chain, out.pose.angles());
                let d = goal.target() - fresh.position;
                let error = distance(d.x, d.y);
                let angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - fresh.orientation).abs());
                assert_eq!(out.end_effector, fresh, "case {case}, {method:?}");
                assert_eq!((out.error, out.angle_error), (error, angle_error), "case {case}, {method:?}");
                let within = error <= opts.tolerance && angle_error <= opts.angle_tolerance;
                assert_eq!(out.status == Status::Reached, within, "case {case}, {method:?}: {:?}", out.status);
                total += 1;
                reached += usize::from(within);
            }
        }
        println!("mixed magnitudes: {reached} of {total} solves reached");
        assert!(reached > 0);
    }

    /// Distances stay finite and exact far beyond where the sum of squares overflows or
    /// underflows.
    #[test]
    fn distance_neither_overflows_nor_underflows() {
        assert_eq!(distance(3.0, 4.0), 5.0);
        // Powers of two keep the 3-4-5 triangle exact.
        let (big, small) = (math::powf(2.0, 700.0), math::powf(2.0, -600.0));
        assert_eq!(distance(3.0 * big, 4.0 * big), 5.0 * big);
        assert_eq!(distance(3.0 * small, 4.0 * small), 5.0 * small);
        assert_eq!(distance(f64::MAX, f64::MAX), f64::MAX);
        assert_eq!(distance(f64::INFINITY, 0.0), f64::MAX);
    }

    /// Issue 24: a goal at (1e300, 0) left the seed arm folded at its start pose, 0 iterations:
    /// from that far, a step toward the goal lowers `|e|²` by less than its last bit, so every
    /// step looked useless. Every method now points the arm at a far goal, in any direction, with
    /// or without limits (the same pose as for a goal 10⁵ away in the same direction, where the
    /// loop sees its steps), and reports the goal's own distance, finite.
    #[test]
    fn a_far_goal_stretches_the_arm_toward_it() {
        let lim = crate::chain::JointLimits::new(-1.5, 1.5).unwrap();
        let free = Chain::new([1.0, -2.0], &[Link::new(3.0, 0.1), Link::new(2.0, 0.1), Link::new(1.0, 0.1)]).unwrap();
        let limited =
            Chain::new([1.0, -2.0], &[Link::new(3.0, 0.1).with_limits(lim), Link::new(2.0, 0.1).with_limits(lim)])
                .unwrap();
        for (chain, mode) in [(&free, LimitMode::Ignore), (&limited, LimitMode::Lock)] {
            let base = chain.base();
            for (dx, dy) in [(1.0, 0.0), (0.0, -1.0), (-0.6, 0.8), (-1.0, -1.0)] {
                for method in Method::ALL.into_iter().filter(|&m| m != Method::Analytic) {
                    let opts = SolveOptions { method, limits: mode, ..SolveOptions::default() };
                    let mut solver = Solver::new(opts).unwrap();
                    let near = Goal::position(base.x + 1e5 * dx, base.y + 1e5 * dy).unwrap();
                    let near = solver.solve(chain, chain.start_pose(), &near).unwrap();
                    for far in [1e17, 1e100, 1e300, 1e308] {
                        let goal = Goal::position(far * dx, far * dy).unwrap();
                        let out = solver.solve(chain, chain.start_pose(), &goal).unwrap();
                        let at = format!("{mode:?} {method:?} ({dx}, {dy})·{far:e}");
                        assert_eq!(out.status, Status::Unreachable, "{at}");
                        let tip = out.end_effector.position;
                        let d = distance(goal.target().x - tip.x, goal.target().y - tip.y);
                        assert!(out.error.is_finite() && out.error == d, "{at}: error {} vs {d}", out.error);
                        if let Some(r) = out.reach_distance {
                            assert_eq!(r, out.error, "{at}");
                        }
                        // Pointed at the goal as at the near one in its direction: the tip
                        // within a hundredth of the reach of the near goal's.
                        let gap = distance(tip.x - near.end_effector.position.x, tip.y - near.end_effector.position.y);
                        assert!(gap < 1e-2 * chain.max_reach(), "{at}: tip {tip} vs {}", near.end_effector.position);
                    }
                }
            }
        }
        // The stand-in: the same direction and orientation, 10⁶ reaches out; none for a goal
        // nearer than that, or one a tolerance that large would count as reached.
        let goal = Goal::with_orientation(3e200, -4e200, 0.5).unwrap();
        let aim = goal.stand_in(free.base(), free.max_reach(), 1e-6).unwrap();
        let away = aim.target() - free.base();
        assert!((away.norm() / (6e6) - 1.0).abs() < 1e-12 && aim.orientation() == Some(0.5), "{aim:?}");
        assert!((away.x / away.norm() - 0.6).abs() < 1e-12, "{aim:?}");
        assert_eq!(Goal::position(1e6, 0.0).unwrap().stand_in(free.base(), free.max_reach(), 1e-6), None);
        assert_eq!(goal.stand_in(free.base(), free.max_reach(), 1e300), None);
        // From a base at −1e308 to a goal at 1e308: 2e308 apart, beyond the f64 range; the
        // stand-in is still a finite point (10⁶ from the base is the base itself, that far out).
        let base = crate::Point2::new(-1e308, 0.0);
        let aim = Goal::position(1e308, 1.0).unwrap().stand_in(base, 1.0, 1e-6).unwrap();
        assert!(aim.target().x.is_finite() && aim.target().y.is_finite(), "{aim:?}");
    }

    /// Issue 11: a 100-link limited arm, a goal at (1e99, 1e99), transpose without line search
    /// returned NaN angles, error and tip. Now every number is finite and the angles are inside
    /// the limits; so for chains of lengths 1e52 and beyond, where the transpose step
    /// overflowed and stalled after 0 iterations even on reachable goals.
    #[test]
    fn huge_goals_and_lengths_give_finite_outcomes() {
        let lim = crate::chain::JointLimits::new(-1.0, 1.0).unwrap();
        let links: Vec<Link> = (0..100).map(|_| Link::new(1.0, 0.1).with_limits(lim)).collect();
        let chain = Chain::new([0.0, 0.0], &links).unwrap();
        for method in Method::ALL {
            let opts = SolveOptions { method, backtrack: 0, limits: LimitMode::Lock, ..SolveOptions::default() };
            let goal = Goal::position(1e99, 1e99).unwrap();
            let Ok(out) = Solver::new(opts).unwrap().solve(&chain, chain.start_pose(), &goal) else { continue };
            assert!(out.pose.angles().iter().all(|a| a.is_finite() && lim.contains(*a)), "{method:?}: {out:?}");
            assert!(out.error.is_finite() && out.end_effector.position.x.is_finite(), "{method:?}: {out:?}");
            assert_eq!(out.status, Status::Unreachable, "{method:?}");
        }
        // Found by the fuzz (seed 1, case 926): one link of 1.6e67, DLS with λ = 7e66 and no
        // line search took a NaN step; the outcome was NaN. The step is refused: stalled.
        let chain = Chain::new([0.0, 0.0], &[Link::new(1.6e67, -0.36)]).unwrap();
        let goal = Goal::position(-7.3e66, 5.9e66).unwrap();
        for method in [Method::DampedLeastSquares, Method::LevenbergMarquardt] {
            let opts =
                SolveOptions { method, lambda: 7e66, backtrack: 0, closed_form: false, ..SolveOptions::default() };
            let out = Solver::new(opts).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
            assert!(out.pose.angles()[0].is_finite() && out.error.is_finite(), "{method:?}: {out:?}");
        }
        for scale in [1e52, 1e100] {
            let chain = Chain::new([0.0, 0.0], &[Link::new(scale, 0.3), Link::new(scale, 0.3)]).unwrap();
            let goal = Goal::position(0.5 * scale, 1.2 * scale).unwrap();
            let opts = SolveOptions {
                method: Method::Transpose,
                closed_form: false,
                tolerance: 1e-9 * scale,
                max_iterations: 10_000,
                ..SolveOptions::default()
            };
            let out = Solver::new(opts).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
            assert_eq!(out.status, Status::Reached, "{scale:e}: {out:?}");
        }
        // Three lengths of 3.3e151, a reach just under the largest a chain may have
        // (MAX_REACH): every method reaches the goal.
        let scale = 3.3e151;
        let chain =
            Chain::new([0.0, 0.0], &[Link::new(scale, 0.1), Link::new(scale, 0.1), Link::new(scale, 0.1)]).unwrap();
        let goal = Goal::position(scale, 1.5 * scale).unwrap();
        assert!(!goal.is_out_of_reach(&chain, 1.0));
        for method in Method::ALL.into_iter().filter(|&m| m != Method::Analytic) {
            let opts = SolveOptions { method, tolerance: 1e-9 * scale, closed_form: false, ..SolveOptions::default() };
            let out = Solver::new(opts).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
            assert!(out.error.is_finite() && out.pose.angles().iter().all(|a| a.is_finite()), "{method:?}: {out:?}");
            assert_eq!(out.status, Status::Reached, "{method:?}: {out:?}");
        }
    }
}
