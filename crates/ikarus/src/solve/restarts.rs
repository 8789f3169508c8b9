//! The restart driver: a solve that stalled or ran out of iterations starts again from other
//! poses (see [`Restarts`]), and the outcome is relabelled [`Status::Unreachable`] when no pose
//! could reach the goal.

use std::time::Instant;

use super::attempt::attempt;
use super::problem::Problem;
use super::scratch::Scratch;
use super::{Outcome, Restarts, SolveOptions, Status};
use crate::kinematics::joint_positions_into;
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
pub(super) fn solve_with_restarts(
    p: &Problem,
    start: &[f64],
    began: Option<Instant>,
    s: &mut Scratch,
    out: &mut Outcome,
) {
    let (chain, goal, opts) = (p.chain, p.goal, p.opts);
    let status = attempt(p, start, s, out);
    let mut tally = Tally { status, iterations: out.iterations, restarts: 0 };
    // A solve that stalled or ran out of iterations restarts (one crawling at the cap, as
    // weighted least norm does against a limit, is as stuck as one standing still); restarts
    // go on until one reaches the goal. Goals out of reach even without limits do not.
    if let Some(r) = opts.restarts {
        let go_on = !matches!(tally.status, Status::Reached | Status::Interrupted);
        if go_on && !goal.is_out_of_reach(chain, opts.tolerance) {
            restart(p, r, began, start, s, out, &mut tally);
        }
    }
    out.iterations = tally.iterations;
    out.restarts = tally.restarts;
    let judged = !matches!(tally.status, Status::Reached | Status::Interrupted);
    out.status = if judged && goal.is_out_of_reach(chain, opts.tolerance) { Status::Unreachable } else { tally.status };
}

/// The restarts after a first attempt that did not reach the goal, counted into `tally`.
fn restart(
    p: &Problem,
    r: Restarts,
    began: Option<Instant>,
    start: &[f64],
    s: &mut Scratch,
    out: &mut Outcome,
    tally: &mut Tally,
) {
    let stuck = |st| st != Status::Reached;
    let mut best = (task_error(p.opts, out), 0);
    let mut last = 0;
    for k in 1..=r.attempts {
        if let (Some(began), Some(budget)) = (began, r.time_budget) {
            if began.elapsed() >= budget {
                break;
            }
        }
        restart_pose(p.bounds, start, r, k, &mut s.restart);
        tally.status = attempt_from_restart(p, s, out);
        tally.iterations += out.iterations;
        tally.restarts = k;
        last = k;
        // An interrupted solve ends at once, on the pose it has (running the best attempt
        // again would be interrupted too).
        if !stuck(tally.status) || tally.status == Status::Interrupted {
            break;
        }
        let err = task_error(p.opts, out);
        if err < best.0 {
            best = (err, k);
        }
    }
    if stuck(tally.status) && tally.status != Status::Interrupted && best.1 != last {
        // No attempt reached the goal: run the best one again (solves are deterministic, so
        // this reproduces it) to leave its pose in `out`.
        if best.1 == 0 {
            s.restart.copy_from_slice(start);
        } else {
            restart_pose(p.bounds, start, r, best.1, &mut s.restart);
        }
        tally.status = attempt_from_restart(p, s, out);
    }
    if tally.restarts > 0 && p.opts.record_every.is_some() {
        join_frames(p, start, tally.iterations, s, out);
    }
}

/// One attempt from the pose in `s.restart`.
fn attempt_from_restart(p: &Problem, s: &mut Scratch, out: &mut Outcome) -> Status {
    let from = std::mem::take(&mut s.restart);
    let status = attempt(p, &from, s, out);
    s.restart = from;
    status
}

/// The frames of a restart begin elsewhere: keep the motion from the caller's start pose to
/// the result, without the jump, numbered by the `iterations` of every attempt.
fn join_frames(p: &Problem, start: &[f64], iterations: u32, s: &mut Scratch, out: &mut Outcome) {
    let n_frames = out.frames.len();
    let last = out.frames.get(n_frames - 1).expect("the last frame is always recorded");
    let (end_angles, end_joints) = (last.angles.to_vec(), last.joints.to_vec());
    out.frames.start(p.chain.len(), p.opts.record_every, 1);
    let mut start_angles = start.to_vec();
    p.bounds.clamp_into(&mut start_angles);
    joint_positions_into(p.chain, &start_angles, &mut s.joints);
    out.frames.push(0, &start_angles, &s.joints);
    out.frames.push_final(iterations, &end_angles, &end_joints);
}

/// The squared task error of an outcome, as the solvers minimise it.
fn task_error(opts: &SolveOptions, out: &Outcome) -> f64 {
    out.error * out.error + (opts.orientation_weight * out.angle_error).powi(2)
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
