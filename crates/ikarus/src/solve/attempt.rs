//! One solve from one start pose: the iteration loop of the [module docs](super).

use super::algebra::Algebra;
use super::fast::Taken;
use super::line_search::jacobian_step;
use super::loop_state::LoopState;
use super::model::Problem;
use super::model::{Model, ScratchOf};
use super::step::Stepper;
use super::{Outcome, Status};
use crate::limits::Bounds;

/// An iteration is hopeless when a joint is held at an end of its range and the task's merit
/// (the squared error) has fallen by less than this share of it since the last iteration. At
/// that rate the merit needs over 20,000 iterations to fall from 1 to the default tolerance's
/// 1e-12, twenty times the default cap.
pub(super) const HOPELESS_SHARE: f64 = 1e-3;

/// How many hopeless iterations in a row end an attempt that may give up.
pub(super) const HOPELESS_WINDOW: u32 = 3;

/// One solve from `start` (clamped into the bounds); writes everything in `out` except the
/// final status relabelling and the restart count, and returns how it ended.
///
/// Every iteration measures the tip against the goal, records a frame when due, stops when the
/// goal is reached, the pose has stood still for the stall window, or at the iteration cap,
/// and otherwise takes one step of the method. CCD and FABRIK do not check for descent: they
/// end on the best pose they visited. A step that would leave a non-finite angle (the tip
/// orientation, their sum, is then not finite either: an overflow on a chain or goal near the
/// end of the f64 range) is not taken: the attempt keeps its last finite pose and ends
/// [`Status::Stalled`].
///
/// Pinned and hopeless: where the problem asks ([`Problem::gives_up_pinned`]) and the body
/// allows it ([`Model::GIVES_UP_PINNED`]), an attempt of a Jacobian method that stands
/// [`HOPELESS_WINDOW`] iterations in a row with a joint held at a limit and its merit falling by
/// less than [`HOPELESS_SHARE`] ends [`Status::Stalled`] at once, with `s.gave_up` set, rather
/// than after the stall window.
///
/// Paused: where the problem asks ([`Problem::pauses`]), an attempt of a Jacobian method that
/// stops at its iteration cap or gives up keeps its state in `s.paused` (and its pose in
/// `s.paused_pose`), and [`resume`] goes on from there.
pub(super) fn attempt<M: Model>(p: &Problem<'_, M>, start: &[f64], s: &mut ScratchOf<M>, out: &mut Outcome) -> Status {
    run(p, start, false, s, out)
}

/// Goes on with the attempt paused in `s` (see [`attempt`]) under `p` (a larger cap, or
/// without giving up), as if it had not stopped: the same steps, bit for bit, and
/// `out.iterations` counts them from its start. Without a paused attempt, the attempt runs
/// from `start`.
pub(super) fn resume<M: Model>(p: &Problem<'_, M>, start: &[f64], s: &mut ScratchOf<M>, out: &mut Outcome) -> Status {
    run(p, start, true, s, out)
}

/// [`attempt`], or [`resume`] when `resuming`.
fn run<M: Model>(p: &Problem<'_, M>, start: &[f64], resuming: bool, s: &mut ScratchOf<M>, out: &mut Outcome) -> Status {
    s.gave_up = false;
    // Only an attempt that may pause (or goes on) forgets the paused one: the attempts run
    // between a pause and its resumption keep it.
    let paused = if resuming || p.pauses { s.paused.take() } else { None };
    let paused = paused.filter(|_| resuming);
    let resume = if paused.is_some() {
        None
    } else {
        match M::fast_attempt(p, start, s, out) {
            Taken::Done(status) => return status,
            Taken::Resume(r) => Some(r),
            Taken::No => None,
        }
    };
    let (model, goal, opts) = (p.model, p.goal, p.opts);
    let n = model.len();
    // The pose is moved out of `out` while the loop measures into `out`, and moved back after.
    let mut pose = std::mem::take(out.pose.angles_mut());
    let angles = &mut pose;
    angles.clear();
    // Where the fast path left off, the pose it stood on is in `s.best`.
    angles.extend_from_slice(if paused.is_some() {
        &s.paused_pose
    } else if resume.is_some() {
        &s.best
    } else {
        start
    });
    p.bounds.clamp_into(angles);
    out.frames.start(n, opts.record_every, opts.max_iterations);

    let stepper = Stepper::of(opts.method);
    let mut phi = model.forward_into(angles, &mut s.joints);
    let mut st = paused.or(resume).unwrap_or_else(|| LoopState::start(opts.lambda));
    let mut flat = false;
    let mut best_error = f64::INFINITY;
    let watch = M::GIVES_UP_PINNED && p.gives_up_pinned;
    let status = loop {
        model.measure(goal, opts, &s.joints, phi, out, &mut s.alg);
        if let Some(k) = opts.record_every {
            if st.iteration % k == 0 {
                out.frames.push(st.iteration, angles, M::frame_points(&s.joints));
            }
        }
        if let Some(status) = stop(p, out.error, out.angle_error, st.still, st.iteration) {
            if status == Status::IterationLimit && p.pauses {
                st.merit = s.alg.e_norm_squared();
                pause(&st, angles, s);
            }
            break status;
        }

        let trial_phi = match stepper {
            Stepper::Jacobian(rule) => {
                model.jacobian(goal, opts, &s.joints, &mut s.alg);
                let current = s.alg.e_norm_squared();
                if let Some(floor) = M::PROGRESS_FLOOR {
                    flat = st.prev_merit - current <= floor * st.prev_merit;
                    st.prev_merit = current;
                }
                if watch {
                    let slow = current >= st.last_merit * (1.0 - HOPELESS_SHARE);
                    st.hopeless = if slow && pinned(p.bounds, angles) { st.hopeless + 1 } else { 0 };
                    st.last_merit = current;
                    if st.hopeless >= HOPELESS_WINDOW {
                        s.gave_up = true;
                        if p.pauses {
                            st.merit = current;
                            pause(&st, angles, s);
                        }
                        break Status::Stalled;
                    }
                }
                // Where the fast path handed over after every damped try of this iteration
                // failed, the line search goes on from there, with the transpose step.
                let damped_failed = std::mem::take(&mut st.skip_damped);
                let Some(trial_phi) = jacobian_step(p, rule, damped_failed, current, &mut st.damping, angles, s) else {
                    // No step along this direction lowers the error: the pose cannot move, and
                    // the same pose would give the same direction again.
                    break Status::Stalled;
                };
                trial_phi
            }
            Stepper::Ccd => {
                remember_best(model.best_key(opts, out, &s.alg), &mut best_error, angles, &mut s.best);
                M::ccd_sweep(p, angles, &s.joints, &mut s.trial, &mut s.trial_joints)
            }
            Stepper::Fabrik => {
                remember_best(model.best_key(opts, out, &s.alg), &mut best_error, angles, &mut s.best);
                M::fabrik_iterate(p, angles, &s.joints, &mut s.trial, &mut s.trial_joints)
            }
        };
        if !trial_phi.is_finite() {
            // Some angle of the step is NaN or infinite: keep the last finite pose.
            break Status::Stalled;
        }
        let moved = angles.iter().zip(&s.trial).fold(0.0f64, |m, (a, t)| m.max((t - a).abs()));
        std::mem::swap(angles, &mut s.trial);
        std::mem::swap(&mut s.joints, &mut s.trial_joints);
        phi = trial_phi;
        st.iteration += 1;
        match opts.stall {
            Some(stall) if moved <= stall.epsilon || flat => st.still += 1,
            _ => st.still = 0,
        }
    };
    *out.pose.angles_mut() = pose;

    if !matches!(stepper, Stepper::Jacobian(_)) && status != Status::Reached {
        end_on_best(p, best_error, s, out);
    }
    out.iterations = st.iteration;
    if opts.record_every.is_some() {
        out.frames.push_final(st.iteration, out.pose.angles(), M::frame_points(&s.joints));
    }
    status
}

/// Keeps the loop's state `st` and its pose `angles` in `s` for [`resume`].
#[cold]
fn pause<P, A>(st: &LoopState, angles: &[f64], s: &mut super::scratch::Scratch<P, A>) {
    s.paused = Some(*st);
    s.paused_pose.copy_from_slice(angles);
}

/// Whether a joint of `angles` is held at an end of its range in `bounds` (where lock and
/// clamp modes put it, exactly).
pub(super) fn pinned(bounds: Bounds<'_>, angles: &[f64]) -> bool {
    angles.iter().enumerate().any(|(i, &a)| bounds.get(i).is_some_and(|l| a == l.min() || a == l.max()))
}

/// Why the loop stops at this iteration, if it does.
#[inline]
fn stop<M: Model>(p: &Problem<'_, M>, error: f64, angle_error: f64, still: u32, iteration: u32) -> Option<Status> {
    let opts = p.opts;
    if error <= opts.tolerance && angle_error <= opts.angle_tolerance {
        Some(Status::Reached)
    } else if opts.stall.is_some_and(|st| still >= st.window) {
        Some(Status::Stalled)
    } else if iteration >= p.max_iterations {
        Some(Status::IterationLimit)
    } else if crate::interrupt::is_set(opts.interrupt.as_ref()) {
        Some(Status::Interrupted)
    } else {
        None
    }
}

/// CCD and FABRIK keep the best pose they visit: `angles`, if its squared task error `key` is
/// below `best_error`.
#[inline]
fn remember_best(key: f64, best_error: &mut f64, angles: &[f64], best: &mut [f64]) {
    if key < *best_error {
        *best_error = key;
        best.copy_from_slice(angles);
    }
}

/// CCD and FABRIK: if the pose they end on is worse than the best they visited (squared task
/// error `best_error`, pose in `s.best`), end on that one, with its error and tip (the
/// restarts compare attempts by them).
fn end_on_best<M: Model>(p: &Problem<'_, M>, best_error: f64, s: &mut ScratchOf<M>, out: &mut Outcome) {
    let model = p.model;
    let final_error = model.best_key(p.opts, out, &s.alg);
    if best_error < final_error {
        let angles = out.pose.angles_mut();
        angles.copy_from_slice(&s.best);
        let phi = model.forward_into(angles, &mut s.joints);
        model.measure(p.goal, p.opts, &s.joints, phi, out, &mut s.alg);
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::Chain;
    use crate::goal::Goal;
    use crate::rng::SplitMix64;
    use crate::solve::scratch::Scratch;
    use crate::solve::{LimitMode, Method, Restarts, SolveOptions, Solver};

    /// `examples/arms/seven.toml`'s start pose, radians.
    fn seven_start() -> Vec<f64> {
        [30.0f64, -15.0, -15.0, -10.0, -10.0, -5.0, -5.0].iter().map(|d| d.to_radians()).collect()
    }

    /// One attempt from `start`, locked at the limits, watched (may give up pinned and
    /// hopeless) or not; and whether it gave up.
    fn one(chain: &Chain, start: &[f64], goal: &Goal, method: Method, watched: bool) -> (Status, Outcome, bool) {
        let opts = SolveOptions {
            method,
            limits: LimitMode::Lock,
            restarts: Some(Restarts::default()),
            ..SolveOptions::default()
        };
        let p = Problem { gives_up_pinned: watched, ..Problem::new(chain, goal, &opts) };
        let mut s = Scratch::default();
        Model::fit(chain, &mut s);
        let mut out = Outcome::default();
        let status = attempt(&p, start, &mut s, &mut out);
        (status, out, s.gave_up)
    }

    /// A goal of the seven-link arm whose first attempt crawls to a pose with three joints at
    /// their limits, 1.0 from the goal, by iteration 30, and then stands there until the stall
    /// window ends it at iteration 66: watched, it gives up by iteration 35, and the default
    /// solve (probe, the watched attempt, the region's seed) reaches the goal in fewer
    /// iterations than the stuck attempt alone took.
    #[test]
    fn a_pinned_hopeless_attempt_is_abandoned_early_and_a_restart_reaches() {
        let chain = crate::fixtures::seven_link_arm();
        let start = seven_start();
        let goal = Goal::position(-4.457868754474337, 0.6171882605183886).unwrap();
        for method in [Method::LevenbergMarquardt, Method::DampedLeastSquares] {
            let (alone, kept, idle) = one(&chain, &start, &goal, method, false);
            let (watched, ended, gave_up) = one(&chain, &start, &goal, method, true);
            assert_eq!((alone, watched), (Status::Stalled, Status::Stalled), "{method:?}");
            assert!(gave_up && !idle, "{method:?}");
            assert!(
                kept.iterations >= 60 && ended.iterations <= 35,
                "{method:?}: {} and {}",
                kept.iterations,
                ended.iterations
            );
            assert!(pinned(chain.bounds(), ended.pose.angles()), "{method:?}");
            let opts = SolveOptions { method, ..SolveOptions::default() };
            let out = Solver::new(opts).unwrap().solve(&chain, &chain.pose(start.clone()).unwrap(), &goal).unwrap();
            assert_eq!(out.status, Status::Reached, "{method:?}");
            assert!(out.iterations < kept.iterations, "{method:?}: {}", out.iterations);
        }
    }

    /// Goals drawn inside the limits of the seed arm and the seven-link arm, first attempts
    /// from the start pose: an attempt that reaches its goal unwatched reaches it watched too, in the same iterations and to the same pose, bit for bit, unless the rule
    /// ended it on a plateau (held at a limit, the error all but still for three iterations)
    /// that it would have left later; the solve then still reaches the goal. The rule ends some
    /// attempts that would not have reached (it is not idle).
    #[test]
    fn converging_attempts_run_as_before_and_goals_left_on_a_plateau_are_still_reached() {
        for (name, chain, start) in [
            ("seed", crate::fixtures::seed_arm_limited(), None),
            ("seven", crate::fixtures::seven_link_arm(), Some(seven_start())),
        ] {
            let start = start.unwrap_or_else(|| chain.start_pose().angles().to_vec());
            let from = chain.pose(start.clone()).unwrap();
            let mut rng = SplitMix64(27);
            let (mut same, mut plateaus, mut ended_early) = (0, 0, 0);
            for _ in 0..300 {
                let angles = super::super::test_support::pose_within_limits(&chain, &mut rng);
                let tip = crate::kinematics::end_effector(&chain, &angles);
                let goal = if rng.unit() < 0.5 {
                    Goal::with_orientation(tip.position.x, tip.position.y, tip.orientation).unwrap()
                } else {
                    Goal::position(tip.position.x, tip.position.y).unwrap()
                };
                for method in [Method::LevenbergMarquardt, Method::DampedLeastSquares] {
                    let (alone, kept, _) = one(&chain, &start, &goal, method, false);
                    let (watched, out, _) = one(&chain, &start, &goal, method, true);
                    if alone == Status::Reached && watched == Status::Reached {
                        same += 1;
                        assert_eq!((out.iterations, out.pose.angles()), (kept.iterations, kept.pose.angles()));
                    } else if alone == Status::Reached {
                        plateaus += 1;
                        assert_eq!(watched, Status::Stalled, "{name} {method:?} {goal:?}");
                        assert!(pinned(chain.bounds(), out.pose.angles()), "{name} {method:?} {goal:?}");
                        let opts = SolveOptions { method, ..SolveOptions::default() };
                        let solved = Solver::new(opts).unwrap().solve(&chain, &from, &goal).unwrap();
                        assert_eq!(solved.status, Status::Reached, "{name} {method:?} {goal:?}");
                    } else if out.iterations < kept.iterations {
                        ended_early += 1;
                    }
                }
            }
            assert!(same >= 500, "{name}: {same} reached alike ({plateaus} left on a plateau)");
            assert!(ended_early >= 5, "{name}: {ended_early} ended early");
        }
    }

    /// Goals drawn inside the limits of the seven-link arm: an attempt paused at iteration
    /// `k` (its cap, watched or not) and resumed under the whole cap, unwatched, ends as the
    /// attempt run whole does, bit for bit (pose, status, iterations); so does one that gave up
    /// pinned and hopeless, resumed. A resumed attempt that lost any of the loop's state (the
    /// damping, the stall count) would not.
    #[test]
    fn a_paused_attempt_goes_on_as_if_it_had_not_stopped() {
        let chain = crate::fixtures::seven_link_arm();
        let start = seven_start();
        let mut rng = SplitMix64(5);
        let (mut resumed, mut gave_up) = (0, 0);
        // The goal of `a_pinned_hopeless_attempt_is_abandoned_early_and_a_restart_reaches`
        // first (its watched attempt gives up), then goals drawn inside the limits.
        for i in 0..200 {
            let goal = if i == 0 {
                Goal::position(-4.457868754474337, 0.6171882605183886).unwrap()
            } else {
                let angles: Vec<f64> =
                    chain.limits().iter().map(|l| rng.range(l.unwrap().min(), l.unwrap().max())).collect();
                let tip = crate::kinematics::end_effector(&chain, &angles);
                Goal::with_orientation(tip.position.x, tip.position.y, tip.orientation).unwrap()
            };
            let k = if i == 0 { 1000 } else { 2 + (rng.unit() * 12.0) as u32 };
            for method in [Method::LevenbergMarquardt, Method::DampedLeastSquares] {
                let watched = i == 0 || rng.unit() < 0.5;
                let opts = SolveOptions { method, limits: LimitMode::Lock, ..SolveOptions::default() };
                let whole = Problem::new(&chain, &goal, &opts);
                let mut s = Scratch::default();
                Model::fit(&chain, &mut s);
                let mut kept = Outcome::default();
                let alone = attempt(&whole, &start, &mut s, &mut kept);
                let paused = Problem { max_iterations: k, gives_up_pinned: watched, pauses: true, ..whole };
                let mut out = Outcome::default();
                let first = attempt(&paused, &start, &mut s, &mut out);
                if first != Status::IterationLimit && !s.gave_up {
                    continue;
                }
                gave_up += u32::from(s.gave_up);
                // Another attempt in between (as the seed's) leaves the paused one alone.
                let mut other = Outcome::default();
                attempt(&whole, chain.start_pose().angles(), &mut s, &mut other);
                let went_on = resume(&whole, &start, &mut s, &mut out);
                assert_eq!(
                    (went_on, out.iterations, out.pose.angles()),
                    (alone, kept.iterations, kept.pose.angles()),
                    "{method:?} {goal:?} paused at {k}"
                );
                resumed += 1;
            }
        }
        assert!(resumed >= 40 && gave_up >= 2, "{resumed} resumed, {gave_up} of them after giving up");
    }

    /// The probe's new early exit, on a goal of the seven-link arm's bench set: a probe cut
    /// short crawling (not [`LoopState::converging`]) with no joint at a limit goes to the
    /// region's seed pose at once; the solve reaches the goal within the probe and the seed's
    /// few iterations, where the first attempt alone (which the solve used to run on first)
    /// stands pinned far from it.
    #[test]
    fn a_crawling_probe_goes_to_the_seed_at_once() {
        use crate::solve::restarts::PROBE_ITERATIONS;
        let chain = crate::fixtures::seven_link_arm();
        let start = seven_start();
        // A goal of seed 1's limits-position set whose probe crawls from 12.0 to 0.94 (the
        // last step kept 0.78 of the merit), unpinned at iteration 12; its first attempt alone
        // stands pinned at 0.28 from the goal.
        let crawling = Goal::position(-3.8603198272538197, 1.1539168931101147).unwrap();
        let opts = SolveOptions { limits: LimitMode::Lock, ..SolveOptions::default() };
        let probe = Problem {
            max_iterations: PROBE_ITERATIONS,
            gives_up_pinned: true,
            pauses: true,
            ..Problem::new(&chain, &crawling, &opts)
        };
        let mut s = Scratch::default();
        Model::fit(&chain, &mut s);
        let mut out = Outcome::default();
        assert_eq!(attempt(&probe, &start, &mut s, &mut out), Status::IterationLimit);
        assert!(!pinned(chain.bounds(), out.pose.angles()) && !s.paused.unwrap().converging());
        let (alone, kept, _) = one(&chain, &start, &crawling, Method::LevenbergMarquardt, false);
        assert!(alone != Status::Reached && kept.error > 0.1, "{alone:?} {}", kept.error);
        let mut solver = Solver::new(SolveOptions::default()).unwrap();
        let from = chain.pose(start.clone()).unwrap();
        let solved = solver.solve(&chain, &from, &crawling).unwrap();
        assert_eq!((solved.status, solved.restarts), (Status::Reached, 1));
        assert!(solved.iterations <= PROBE_ITERATIONS + 8, "{}", solved.iterations);
    }
}
