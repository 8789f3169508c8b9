//! The restart driver: a solve that stalled or ran out of iterations starts again from other
//! poses (see [`Restarts`]), and the outcome is relabelled [`Status::Unreachable`] when no pose
//! could reach the goal.

use web_time::Instant;

use super::attempt::{attempt, pinned, resume};
use super::model::Problem;
use super::model::{Model, ScratchOf};
use super::{Method, Outcome, Restarts, Status};
use crate::limits::Bounds;
use crate::rng::SplitMix64;

/// How a solve has gone so far, over its attempts.
#[derive(Debug, Clone, Copy)]
struct Tally {
    /// How the last attempt ended.
    status: Status,
    /// Iterations of every attempt.
    iterations: u32,
    /// Restarts used.
    restarts: u32,
}

/// Runs the first attempt and, when the options ask for them and the goal is not out of reach,
/// the restarts; leaves the final outcome in `out` with the iterations of every attempt, the
/// restart count and the final status.
pub(super) fn solve_with_restarts<M: Model>(
    p: &Problem<'_, M>,
    start: &[f64],
    began: Option<Instant>,
    s: &mut ScratchOf<M>,
    out: &mut Outcome,
) {
    solve_with_restarts_seeded(p, start, began, None, s, out);
}

/// A source of the first restart's start pose: writes a pose (one angle per joint) into the
/// buffer and returns `true`, or returns `false` when it has none to give (restart 1 then
/// starts from [`restart_pose`] as the others do).
pub(super) type Seed<'a> = &'a dyn Fn(&mut Vec<f64>) -> bool;

/// The iteration cap of a seeded solve's first attempt, the probe (see
/// [`solve_with_restarts_seeded`]).
///
/// On the bench's `limits-*` position and oriented sets (1000 goals each), the first
/// attempts from the start pose that reach their goal after more than 12 iterations are 5.1 %
/// (seed arm), 0.9 % and 1.6 % (seven) and 3.7 % and 2.5 % (tentacle); most that do not reach
/// it (4 % to 12 % of the goals) run longer, up to 87 iterations on the seed arm, where an
/// attempt pinned at a limit crawls to its stall at about 0.4 µs an iteration, and up to the
/// cap of 1000 on the tentacle. With the probe, every goal of these sets that restarts is
/// reached by restart 1, from the seed pose; the longest solves take 25 iterations (seed arm,
/// probe included) and 30 (tentacle). On seven, whose slow first attempts are often not yet
/// held at a limit at iteration 12, the longest took 86 while a probe cut short unpinned ran
/// whole before the seed; now that only a converging one goes on (see
/// [`LoopState::converging`](super::loop_state::LoopState::converging)), 18 (seeds 1 and 7).
pub(super) const PROBE_ITERATIONS: u32 = 12;

/// Whether a seeded solve with `method` starts with a probe: Levenberg–Marquardt and damped
/// least squares, whose first attempts reach their goal within [`PROBE_ITERATIONS`] nearly
/// always. The other methods take more iterations to converge (selectively damped least
/// squares: 12 to 19 on average on the bench's `limits-*` sets with restarts, where a probe
/// raised its mean on the seed arm from 11.8 to 15.9 iterations and its p99 from 9 to 16 µs);
/// they get the seed pose without a probe.
fn probes(method: Method) -> bool {
    match method {
        Method::LevenbergMarquardt | Method::DampedLeastSquares => true,
        Method::Transpose
        | Method::PseudoInverse
        | Method::SelectivelyDamped
        | Method::CyclicCoordinateDescent
        | Method::Fabrik
        | Method::Analytic => false,
    }
}

/// [`solve_with_restarts`], seeded: with a `seed` (the [`Solver`](super::Solver) passes the
/// pose the exact region reads off for a goal it judged reachable, see
/// [`ReachCache::seed_pose`](super::verdict::ReachCache::seed_pose)) and restarts asked for,
/// the first attempt is (for the methods that [`probes`] names) a probe of at most
/// [`PROBE_ITERATIONS`], watched (it gives up once pinned and hopeless, see
/// [`attempt`](super::attempt::attempt)) and paused where it stops, and restart 1 starts from
/// the seed. A probe cut short by its cap converging (see
/// [`LoopState::converging`](super::loop_state::LoopState::converging)) with no joint held at a limit
/// goes on at once from where it stopped, still watched, as the first attempt runs unseeded.
/// One that gave up, or was cut short pinned at a limit or crawling, is the tail this is for,
/// and so is a first attempt that goes on and then gives up: the seed's attempt goes first,
/// with the cap less the first attempt's iterations so far, and if it does not reach, the
/// first attempt goes on from where it stopped, unwatched, within restart 1 (its steps are
/// the unseeded attempt's, bit for bit, none taken twice). Restart `k ≥ 2` takes the pose
/// [`restart_pose`] gives for `k − 1`. The iteration bound ((1 + attempts) caps) holds, no
/// solve ends worse than its first attempt alone, every pose an unseeded solve tries is still
/// tried (but the last), and an animation still starts by looking near the
/// start pose. Without a seed, this is [`solve_with_restarts`].
pub(super) fn solve_with_restarts_seeded<M: Model>(
    p: &Problem<'_, M>,
    start: &[f64],
    began: Option<Instant>,
    seed: Option<Seed<'_>>,
    s: &mut ScratchOf<M>,
    out: &mut Outcome,
) {
    let (model, goal, opts) = (p.model, p.goal, p.opts);
    let probe = seed.is_some() && opts.restarts.is_some() && p.max_iterations > PROBE_ITERATIONS && probes(opts.method);
    // The probe is the first attempt watched (it gives up once pinned and hopeless) and paused
    // at its cap or where it gives up, so that it can go on from there (`resume`).
    let first = if probe {
        Problem { max_iterations: PROBE_ITERATIONS, gives_up_pinned: true, pauses: true, ..*p }
    } else {
        *p
    };
    let status = attempt(&first, start, s, out);
    let cut = probe && (status == Status::IterationLimit || s.gave_up);
    let mut tally = Tally { status, iterations: out.iterations, restarts: 0 };
    // The first attempt's iterations so far, taken out of restart 1's cap when the rest of it is
    // owed (the probe gave up, or was cut short while pinned at a limit), so that
    // (1 + attempts) caps still bound the solve.
    let mut spent = if cut { out.iterations } else { 0 };
    let mut owed = cut;
    let converging = s.paused.is_some_and(|paused| paused.converging());
    if cut && !s.gave_up && !pinned(p.bounds, out.pose.angles()) && converging {
        // Cut short converging (see `LoopState::converging`), no joint held at a limit: the first
        // attempt goes on from where the probe stopped, as it would have run unseeded, but
        // still watched: one that comes to stand pinned at a limit, its error all but still,
        // gives up (see `attempt`) and the rest of it is then owed, as after a probe cut
        // short while pinned or crawling.
        let watched = Problem { gives_up_pinned: true, pauses: true, ..*p };
        tally.status = resume(&watched, start, s, out);
        tally.iterations = out.iterations;
        owed = s.gave_up;
        spent = if owed { out.iterations } else { 0 };
    }
    // A solve that stalled or ran out of iterations restarts (one crawling at the cap, as
    // weighted least norm does against a limit, is as stuck as one standing still); restarts
    // go on until one reaches the goal. Goals out of reach even without limits do not.
    if let Some(r) = opts.restarts {
        let go_on = !matches!(tally.status, Status::Reached | Status::Interrupted);
        if go_on && !model.is_out_of_reach(goal, opts.tolerance) {
            let plan = Plan { r, began, seed, spent, owed };
            restart(p, plan, start, s, out, &mut tally);
        } else if owed {
            // (Not seen: a goal the region holds is within the reach.) No restarts follow, so
            // the first attempt goes on to the whole cap, as it would unseeded.
            tally.status = resume(p, start, s, out);
            tally.iterations += out.iterations - spent;
        }
    }
    if cut && tally.restarts == 0 && opts.record_every.is_some() {
        // The first attempt went on after its probe: as after restarts, the frames run from
        // the start pose to the outcome's, numbered by every iteration.
        join_frames(p, start, tally.iterations, s, out);
    }
    out.iterations = tally.iterations;
    out.restarts = tally.restarts;
    let judged = !matches!(tally.status, Status::Reached | Status::Interrupted);
    out.status = if judged && model.is_out_of_reach(goal, opts.tolerance) { Status::Unreachable } else { tally.status };
}

/// What the restarts of a solve go by, set once the first attempt (or the probe) has run:
/// the options' restarts, when the solve began (for the time budget), the seed of restart 1,
/// and what the probe left behind.
#[derive(Clone, Copy)]
struct Plan<'a> {
    r: Restarts,
    began: Option<Instant>,
    seed: Option<Seed<'a>>,
    /// The first attempt's iterations so far when the rest of it is owed, taken out of
    /// restart 1's cap (else 0).
    spent: u32,
    /// The rest of the first attempt is owed: it gave up pinned and hopeless, or its probe was
    /// cut short while pinned at a limit; it goes on from where it stopped (`resume`).
    owed: bool,
}

/// The restarts after a first attempt that did not reach the goal, counted into `tally`.
fn restart<M: Model>(
    p: &Problem<'_, M>,
    plan: Plan<'_>,
    start: &[f64],
    s: &mut ScratchOf<M>,
    out: &mut Outcome,
    tally: &mut Tally,
) {
    let Plan { r, began, seed, spent, owed } = plan;
    // The best attempt so far: its task error, status and final pose (in `s.best_attempt`).
    let mut best = (p.model.best_key(p.opts, out, &s.alg), tally.status);
    s.best_attempt.copy_from_slice(out.pose.angles());
    let mut last_is_best = true;
    // The seed pose (and, without one, the rest of the first attempt) comes first (see
    // `solve_with_restarts_seeded`); the schedule of `restart_pose` moves along by one.
    let mut shift = 0;
    for k in 1..=r.attempts {
        if let (Some(began), Some(budget)) = (began, r.time_budget) {
            if began.elapsed() >= budget {
                break;
            }
        }
        let seeded = k == 1 && seed.is_some_and(|seed| seed(&mut s.restart));
        if seeded {
            debug_assert_eq!(s.restart.len(), p.model.len());
            shift = 1;
        } else if k == 1 && owed {
            shift = 1;
        } else {
            restart_pose(p.bounds, start, r, k - shift, &mut s.restart);
        }
        // (Restart 1 is the rest of the first attempt itself when it is owed and there is no
        // seed.)
        let goes_on = k == 1 && owed && !seeded;
        if !goes_on {
            p.model.settle_restart(p, k, out, &mut s.restart, &mut s.locked);
        }
        tally.restarts = k;
        // When the rest of the first attempt is owed, restart 1 has what it left of the cap,
        // and the first attempt goes on next, within the same restart: every solve stays
        // within (1 + attempts) caps, and none ends worse than its first attempt would alone.
        let rest_of_first = seeded && owed;
        let q = if seeded { Problem { max_iterations: p.max_iterations - spent, ..*p } } else { *p };
        let first = goes_on.then_some((start, spent));
        match try_once(&q, first, s, out, tally, &mut best, &mut last_is_best) {
            Next::Reached => return join(p, start, tally, s, out),
            Next::Stop => break,
            Next::Go => {}
        }
        if rest_of_first {
            match try_once(p, Some((start, spent)), s, out, tally, &mut best, &mut last_is_best) {
                Next::Reached => return join(p, start, tally, s, out),
                Next::Stop => break,
                Next::Go => {}
            }
        }
    }
    let interrupted = tally.status == Status::Interrupted;
    if !last_is_best {
        // No attempt reached the goal: end on the best one's pose, kept when it ended (not
        // run again, so that `iterations` counts every step taken).
        out.pose.angles_mut().copy_from_slice(&s.best_attempt);
        tally.status = if interrupted { Status::Interrupted } else { best.1 };
    }
    join(p, start, tally, s, out);
}

/// What follows an attempt of the restarts.
enum Next {
    /// It reached the goal: the solve ends on it.
    Reached,
    /// It was interrupted: the solve ends on the best attempt so far.
    Stop,
    /// The next attempt runs.
    Go,
}

/// One attempt of the restarts from the pose in `s.restart`, or, given `first` (the start
/// pose and the iterations it has taken), the rest of the paused first attempt; counted into
/// `tally`; remembers it in `best` (task error and status, pose in `s.best_attempt`) if it is
/// the best so far.
fn try_once<M: Model>(
    q: &Problem<'_, M>,
    first: Option<(&[f64], u32)>,
    s: &mut ScratchOf<M>,
    out: &mut Outcome,
    tally: &mut Tally,
    best: &mut (f64, Status),
    last_is_best: &mut bool,
) -> Next {
    if let Some((start, spent)) = first {
        tally.status = resume(q, start, s, out);
        tally.iterations += out.iterations - spent;
    } else {
        tally.status = attempt_from_restart(q, s, out);
        tally.iterations += out.iterations;
    }
    if tally.status == Status::Reached {
        return Next::Reached;
    }
    let err = q.model.best_key(q.opts, out, &s.alg);
    *last_is_best = err < best.0;
    if *last_is_best {
        *best = (err, tally.status);
        s.best_attempt.copy_from_slice(out.pose.angles());
    }
    // An interrupted solve ends at once, on the best pose so far.
    if tally.status == Status::Interrupted { Next::Stop } else { Next::Go }
}

/// With frames recorded and restarts taken, the frames run from the caller's start pose to the
/// outcome's pose ([`join_frames`]).
fn join<M: Model>(p: &Problem<'_, M>, start: &[f64], tally: &Tally, s: &mut ScratchOf<M>, out: &mut Outcome) {
    if tally.restarts > 0 && p.opts.record_every.is_some() {
        join_frames(p, start, tally.iterations, s, out);
    }
}

/// One attempt from the pose in `s.restart`.
fn attempt_from_restart<M: Model>(p: &Problem<'_, M>, s: &mut ScratchOf<M>, out: &mut Outcome) -> Status {
    let from = std::mem::take(&mut s.restart);
    let status = attempt(p, &from, s, out);
    s.restart = from;
    status
}

/// The frames of a restart begin elsewhere: keep the motion from the caller's start pose to
/// the result (the outcome's pose), without the jump, numbered by the `iterations` of every
/// attempt.
fn join_frames<M: Model>(p: &Problem<'_, M>, start: &[f64], iterations: u32, s: &mut ScratchOf<M>, out: &mut Outcome) {
    out.frames.start(p.model.len(), p.opts.record_every, 1);
    s.restart.copy_from_slice(start);
    p.bounds.clamp_into(&mut s.restart);
    p.model.forward_into(&s.restart, &mut s.joints);
    out.frames.push(0, &s.restart, M::frame_points(&s.joints));
    p.model.forward_into(out.pose.angles(), &mut s.joints);
    out.frames.push_final(iterations, out.pose.angles(), M::frame_points(&s.joints));
}

/// The start pose of restart `k` (see [`Restarts`]): `start + (k / attempts)·(r − start)`,
/// clamped into `bounds`, `r` drawn uniformly inside the bounds (within ±π of the start angle
/// for an unbounded joint).
pub(super) fn restart_pose(bounds: Bounds<'_>, start: &[f64], r: Restarts, k: u32, out: &mut [f64]) {
    use std::f64::consts::PI;
    let mut rng = SplitMix64(r.seed ^ u64::from(k).wrapping_mul(0xA076_1D64_78BD_642F));
    let f = f64::from(k) / f64::from(r.attempts);
    for (i, (o, &a)) in out.iter_mut().zip(start).enumerate() {
        let u = rng.unit();
        let limits = bounds.get(i);
        let (lo, hi) = limits.map_or((a - PI, a + PI), |l| (l.min(), l.max()));
        let target = lo + u * (hi - lo);
        let next = a + f * (target - a);
        *o = limits.map_or(next, |l| l.clamp(next));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::goal::Goal;
    use crate::math;
    use crate::solve::{LimitMode, Method, SolveOptions, Solver};

    /// When no attempt reaches the goal, the outcome is the best attempt's pose, kept when it
    /// ended (it used to be run a second time, whose steps `iterations` left out): every
    /// attempt's steps are counted once, and the pose, status and error are the best one's.
    #[test]
    fn failed_restarts_end_on_the_best_attempt_counting_every_step() {
        let chain = crate::fixtures::seed_arm_limited();
        let goal = Goal::position(-3.0, -1.0).unwrap();
        let mut best_was_not_last = 0;
        for seed in 0..40 {
            let r = Restarts { attempts: 4, seed, time_budget: None };
            let opts = SolveOptions {
                method: Method::LevenbergMarquardt,
                limits: LimitMode::Lock,
                restarts: Some(r),
                record_every: Some(5),
                reach_verdict: false,
                ..SolveOptions::default()
            };
            let out = Solver::new(opts.clone()).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
            // Each attempt alone, from its start pose.
            let once = SolveOptions { restarts: None, record_every: None, ..opts.clone() };
            let start = chain.start_pose().angles().to_vec();
            let attempts: Vec<Outcome> = (0..=r.attempts)
                .map(|k| {
                    let mut from = start.clone();
                    if k > 0 {
                        restart_pose(chain.bounds(), &start, r, k, &mut from);
                    }
                    Solver::new(once.clone()).unwrap().solve(&chain, &chain.pose(from).unwrap(), &goal).unwrap()
                })
                .collect();
            if attempts.iter().any(|a| a.status == Status::Reached) {
                continue;
            }
            assert_ne!(out.status, Status::Reached, "seed {seed}");
            assert_eq!(out.iterations, attempts.iter().map(|a| a.iterations).sum::<u32>(), "seed {seed}");
            assert_eq!(out.restarts, r.attempts);
            let err = |o: &Outcome| o.error * o.error + math::square(opts.orientation_weight * o.angle_error);
            let best = attempts.iter().min_by(|a, b| err(a).total_cmp(&err(b))).unwrap();
            assert_eq!(out.pose, best.pose, "seed {seed}");
            assert_eq!((out.error, out.status), (best.error, best.status), "seed {seed}");
            // The frames run from the start to the outcome's pose.
            let last = out.frames.get(out.frames.len() - 1).unwrap();
            assert_eq!((last.iteration, last.angles), (out.iterations, out.pose.angles()));
            if best.pose != attempts[attempts.len() - 1].pose {
                best_was_not_last += 1;
            }
        }
        assert!(best_was_not_last > 0, "no case where the best attempt was not the last");
    }

    /// Goals drawn inside the limits of the seed arm and the seven-link arm, solved from the
    /// start pose: the ones whose first attempt stalls against a limit (3 to 6 in 100) are
    /// reached by restart 1, from the pose the exact region reads off (see
    /// [`ReachCache::seed_pose`](super::super::verdict::ReachCache::seed_pose)); without it
    /// (`reach_verdict: false`) the same goals took up to 9 (seed) and 5 (seven) restarts. Both solve every goal.
    #[test]
    fn the_region_seed_reaches_a_goal_on_the_first_restart() {
        for (name, chain) in
            [("seed", crate::fixtures::seed_arm_limited()), ("seven", crate::fixtures::seven_link_arm())]
        {
            let mut rng = SplitMix64(11);
            let mut seeded = Solver::new(SolveOptions::default()).unwrap();
            let mut plain = Solver::new(SolveOptions { reach_verdict: false, ..SolveOptions::default() }).unwrap();
            let (mut restarted, mut plain_restarts) = (0, 0);
            for _ in 0..400 {
                let angles = super::super::test_support::pose_within_limits(&chain, &mut rng);
                let tip = crate::kinematics::end_effector(&chain, &angles).position;
                let goal = Goal::position(tip.x, tip.y).unwrap();
                let out = seeded.solve(&chain, chain.start_pose(), &goal).unwrap();
                assert_eq!(out.status, Status::Reached, "{name} {goal:?}: {out:?}");
                let again = plain.solve(&chain, chain.start_pose(), &goal).unwrap();
                assert_eq!(again.status, Status::Reached, "{name} {goal:?}: {again:?}");
                if out.restarts > 0 {
                    restarted += 1;
                    plain_restarts = plain_restarts.max(again.restarts);
                    assert_eq!(out.restarts, 1, "{name} {goal:?}: {out:?}");
                }
            }
            assert!(restarted >= 10, "{name}: {restarted} goals restarted");
            assert!(plain_restarts >= 5, "{name}: unseeded, at most {plain_restarts} restarts");
        }
    }

    /// A seeded solve whose probe is cut short by [`PROBE_ITERATIONS`] (or gives up) and whose
    /// seed gives nothing goes on with the first attempt from where the probe stopped: at once
    /// if it was converging with no joint held at a limit, else as restart 1. Either way it
    /// ends where the unseeded solve ends, in as many iterations: none is taken twice.
    #[test]
    fn a_cut_probe_without_a_seed_pose_runs_the_first_attempt_again() {
        use crate::solve::scratch::Scratch;
        use crate::solve::solver::finish;
        let chain = crate::fixtures::seed_arm_limited();
        let opts = SolveOptions { reach_verdict: false, ..SolveOptions::default() };
        let mut plain = Solver::new(opts.clone()).unwrap();
        let mut rng = SplitMix64(3);
        let (mut checked, mut pinned_cuts) = (0, 0);
        while checked < 20 {
            let angles: Vec<f64> =
                chain.limits().iter().map(|l| l.map_or(0.0, |l| rng.range(l.min(), l.max()))).collect();
            let tip = crate::kinematics::end_effector(&chain, &angles).position;
            let goal = Goal::position(tip.x, tip.y).unwrap();
            let expected = plain.solve(&chain, chain.start_pose(), &goal).unwrap();
            if expected.restarts > 0 || expected.iterations <= PROBE_ITERATIONS {
                continue;
            }
            let p = Problem::new(&chain, &goal, &opts);
            let mut s = Scratch::default();
            Model::fit(&chain, &mut s);
            let mut out = Outcome::default();
            let nothing = |_: &mut Vec<f64>| false;
            solve_with_restarts_seeded(&p, chain.start_pose().angles(), None, Some(&nothing), &mut s, &mut out);
            finish(&p, &mut s, &mut out);
            assert_eq!((out.pose.angles(), out.status), (expected.pose.angles(), Status::Reached), "{goal:?}");
            // Not converging when cut, the first attempt goes on as restart 1; else at once.
            assert_eq!(out.iterations, expected.iterations, "{goal:?}");
            assert!(out.restarts <= 1, "{goal:?}: {out:?}");
            pinned_cuts += out.restarts;
            checked += 1;
        }
        assert!(pinned_cuts > 0 && pinned_cuts < checked, "{pinned_cuts} of {checked} cut while pinned");
    }
}
