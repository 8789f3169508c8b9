//! The position-only fast path: Levenberg–Marquardt on a chain, for a goal without an
//! orientation, with no limits to enforce and no per-joint rates — the commonest solve — as
//! one lean loop. Its arithmetic ([`try_step`] and the forward kinematics) is written once over
//! [`Lanes`]: [`run_one`] drives it for one goal (`f64`, inside
//! [`attempt`](super::attempt::attempt)), [`run`] for several side by side (eight AVX2 lanes
//! in two groups, or four `Quad`s, in [`Solver::solve_batch`](super::Solver::solve_batch),
//! through [`run_lanes`]).
//!
//! It runs exactly the arithmetic of the general loop for that case (the loop in `attempt.rs`,
//! the line search, `compute_delta`, the 2×2 [`damped_2x2`](super::step::damped_2x2) and
//! Nielsen's damping update), in the same order, so it returns the general loop's result bit
//! for bit; the tests run both on thousands of goals and compare. Where the general loop would
//! leave the common case (the damped step falls back to the pseudoinverse, every damped try
//! fails and the line search turns to the transpose direction, a step or a distance leaves the
//! normal numbers), [`run_one`] hands the attempt to the general loop at the start of that
//! iteration (a [`LoopState`]), and [`run`] gives the goal back for `solve_into` to solve whole.
//!
//! Per iteration it keeps, per goal, only the angles, the joint points and the task error: no
//! Jacobian matrix (its columns are differences of joint points, formed where they are used),
//! no temporary vectors, no dynamic dispatch.

use super::lm::Damping;
use super::loop_state::LoopState;
use super::{LimitMode, Method, SolveOptions, Status};
use crate::chain::Chain;
#[cfg(target_arch = "x86_64")]
use crate::lanes::{Avx, Pair};
use crate::lanes::{Lanes, Quad, sin_cos};

/// The share of the linearly predicted decrease a step must achieve (the line search's).
const SUFFICIENT_DECREASE: f64 = 0.1;

/// Whether a solve of `chain` under `opts` for a goal with (`oriented`) or without an
/// orientation can take the fast path: Levenberg–Marquardt, a position goal, no limits
/// enforced, no rates, no frames, a line search.
pub(super) fn applies(chain: &Chain, opts: &SolveOptions, oriented: bool) -> bool {
    opts.method == Method::LevenbergMarquardt
        && !oriented
        && (opts.limits == LimitMode::Ignore || !chain.has_limits())
        && opts.rates.is_empty()
        && opts.record_every.is_none()
        && opts.backtrack > 0
}

/// How one goal's attempt ended on the fast path.
pub(super) struct End<'a> {
    /// The status the loop stopped with, or `None`: the fast path left the common case.
    pub(super) status: Option<Status>,
    /// The final angles.
    pub(super) angles: &'a [f64],
    /// Iterations taken.
    pub(super) iterations: u32,
    /// Distance from the tip to the goal.
    pub(super) error: f64,
    /// The tip.
    pub(super) tip: (f64, f64),
    /// The tip's orientation (the sum of the angles).
    pub(super) phi: f64,
}

/// What the fast path did with an attempt.
pub(super) enum Taken {
    /// It does not apply: the general loop runs the attempt.
    No,
    /// It ran the attempt to its end, with this status.
    Done(Status),
    /// It left the common case at the start of an iteration: the general loop goes on from
    /// there (the pose is in the scratch's `best`).
    Resume(LoopState),
}

/// The state of the goals in the lanes, struct of arrays (one `L` per joint), kept between
/// solves so that the fast path allocates nothing once it has grown.
#[derive(Debug, Clone)]
pub(super) struct Buffers<L> {
    angles: Vec<L>,
    trial: Vec<L>,
    /// Joint points x and y, base first: `n + 1` each.
    xs: Vec<L>,
    ys: Vec<L>,
    trial_xs: Vec<L>,
    trial_ys: Vec<L>,
    delta: Vec<L>,
    /// One lane's angles, handed to `emit`.
    lane_angles: Vec<f64>,
    /// The start pose's joint points, x and y, which every goal's lane starts from.
    start_xs: Vec<f64>,
    start_ys: Vec<f64>,
}

impl<L> Default for Buffers<L> {
    fn default() -> Self {
        let none = Vec::new;
        Buffers {
            angles: none(),
            trial: none(),
            xs: none(),
            ys: none(),
            trial_xs: none(),
            trial_ys: none(),
            delta: none(),
            lane_angles: Vec::new(),
            start_xs: Vec::new(),
            start_ys: Vec::new(),
        }
    }
}

impl<L: Lanes> Buffers<L> {
    fn fit(&mut self, n: usize) {
        let zero = L::splat(0.0);
        for v in [&mut self.angles, &mut self.trial, &mut self.delta] {
            v.resize(n, zero);
        }
        for v in [&mut self.xs, &mut self.ys, &mut self.trial_xs, &mut self.trial_ys] {
            v.resize(n + 1, zero);
        }
        self.lane_angles.resize(n, 0.0);
        self.start_xs.resize(n + 1, 0.0);
        self.start_ys.resize(n + 1, 0.0);
    }
}

/// Per-lane bookkeeping that is not arithmetic.
#[derive(Clone, Copy, Default)]
struct Slot {
    /// The goal in this lane, if any.
    goal: Option<usize>,
    iteration: u32,
    still: u32,
    /// Damped tries at this iteration (each rejection raises the damping).
    tries: u32,
    /// The pose was just measured and not yet stepped from.
    measured: bool,
}

/// Forward kinematics of every lane's `angles` into the points; returns the tips' orientation.
#[inline(always)]
fn forward<L: Lanes>(chain: &Chain, angles: &[L], xs: &mut [L], ys: &mut [L]) -> L {
    let base = chain.base();
    let (mut x, mut y, mut phi) = (L::splat(base.x), L::splat(base.y), L::splat(0.0));
    xs[0] = x;
    ys[0] = y;
    for (((&l, &a), px), py) in chain.lengths().iter().zip(angles).zip(&mut xs[1..]).zip(&mut ys[1..]) {
        phi = phi + a;
        let (s, c) = sin_cos(phi);
        x = x + L::splat(l) * c;
        y = y + L::splat(l) * s;
        *px = x;
        *py = y;
    }
    phi
}

/// Runs the fast path on `goals` (index, target x, target y), each from `start` with an
/// iteration cap of `max_iterations`, `L::LANES` at a time (a lane that finishes takes the next goal), and hands every goal's end to `emit`.
#[inline(always)]
pub(super) fn run<L: Lanes>(
    chain: &Chain,
    opts: &SolveOptions,
    max_iterations: u32,
    start: &[f64],
    st: &mut Buffers<L>,
    mut goals: impl Iterator<Item = (usize, f64, f64)>,
    mut emit: impl FnMut(usize, End<'_>),
) {
    let n = chain.len();
    let zero = L::splat(0.0);
    st.fit(n);
    let mut slots = [Slot::default(); 16];
    let slots = &mut slots[..L::LANES];
    let (mut tx, mut ty) = (zero, zero);
    let mut phi = zero;
    let lambda_sq = opts.lambda * opts.lambda;
    let mut mu = L::splat(lambda_sq);
    let mut nu = L::splat(2.0);
    let gain = L::splat(opts.gain);
    let cap = opts.max_step;
    let stall = opts.stall;
    let tolerance = opts.tolerance;
    // The start pose's points, once: a lane's forward kinematics computes the same bits as
    // the one-lane forward kinematics, so a fresh lane takes them instead of a pass over all.
    let start_phi = forward(chain, start, &mut st.start_xs, &mut st.start_ys);

    loop {
        // Lanes without a goal take the next one, at the start pose.
        for (k, slot) in slots.iter_mut().enumerate() {
            if slot.goal.is_none() {
                if let Some((i, x, y)) = goals.next() {
                    *slot = Slot { goal: Some(i), ..Slot::default() };
                    for (a, &s0) in st.angles.iter_mut().zip(start) {
                        *a = a.with_lane(k, s0);
                    }
                    for (p, &s0) in st.xs.iter_mut().zip(&st.start_xs) {
                        *p = p.with_lane(k, s0);
                    }
                    for (p, &s0) in st.ys.iter_mut().zip(&st.start_ys) {
                        *p = p.with_lane(k, s0);
                    }
                    phi = phi.with_lane(k, start_phi);
                    tx = tx.with_lane(k, x);
                    ty = ty.with_lane(k, y);
                    mu = mu.with_lane(k, lambda_sq);
                    nu = nu.with_lane(k, 2.0);
                }
            }
        }
        if slots.iter().all(|s| s.goal.is_none()) {
            return;
        }

        // Measure the lanes standing on a new pose, and stop those that are done.
        let tip_x = st.xs[n];
        let tip_y = st.ys[n];
        let dx = tx - tip_x;
        let dy = ty - tip_y;
        let current = dx * dx + dy * dy;
        let mut finished = false;
        for (k, slot) in slots.iter_mut().enumerate() {
            if slot.goal.is_none() {
                continue;
            }
            if slot.measured {
                continue;
            }
            slot.measured = true;
            let squared = current.lane(k);
            if !(squared.is_finite() && squared >= f64::MIN_POSITIVE) {
                // The general loop measures this with `hypot`: leave it to it.
                finish(st, k, None, slot, phi, f64::NAN, &mut emit);
                finished = true;
                continue;
            }
            let error = squared.sqrt();
            let status = if error <= tolerance {
                Some(Status::Reached)
            } else if stall.is_some_and(|s| slot.still >= s.window) {
                Some(Status::Stalled)
            } else if slot.iteration >= max_iterations {
                Some(Status::IterationLimit)
            } else if crate::interrupt::is_set(opts.interrupt.as_ref()) {
                Some(Status::Interrupted)
            } else {
                None
            };
            if let Some(status) = status {
                finish(st, k, Some(status), slot, phi, error, &mut emit);
                finished = true;
            }
        }
        if finished {
            continue;
        }

        // One damped try in every lane: the step, the trial pose, its error.
        let t = try_step(chain, st, n, Miss { target: (tx, ty), e: (dx, dy), current }, (mu, nu), gain, cap);
        let (trial_phi, accepted, damped, det) = (t.trial_phi, t.accepted, t.damped, t.det);
        let (accepted_mu, rejected_mu) = (t.accepted_mu, t.rejected_mu);

        // Lanes whose step the fast path cannot take as the general loop would: the damped
        // step declined (the general loop takes the pseudoinverse), or a step accepted onto a
        // pose that is not finite (the general loop ends it stalled there).
        let step_ok = L::and(damped, L::or(det.lt(zero), det.gt(zero)));
        let finite = trial_phi.abs().le(L::splat(f64::MAX));
        // (Lanes without a goal are left alone: their stale numbers would drift to infinity.)
        let active = L::mask_from(|k| slots[k].goal.is_some());
        let take = L::and(L::and(L::and(accepted, finite), step_ok), active);
        let reject = L::and(L::and(step_ok, L::select_mask(accepted, L::no(), L::yes())), active);
        let mut moved = zero;
        for (a, &t) in st.angles.iter_mut().zip(&st.trial) {
            let m = (t - *a).abs();
            moved = L::select(m.gt(moved), m, moved);
            *a = L::select(take, t, *a);
        }
        for (x, &t) in st.xs.iter_mut().zip(&st.trial_xs) {
            *x = L::select(take, t, *x);
        }
        for (y, &t) in st.ys.iter_mut().zip(&st.trial_ys) {
            *y = L::select(take, t, *y);
        }
        phi = L::select(take, trial_phi, phi);
        let two = L::splat(2.0);
        mu = L::select(take, accepted_mu, L::select(reject, rejected_mu, mu));
        nu = L::select(take, two, L::select(reject, nu * two, nu));

        for (k, slot) in slots.iter_mut().enumerate() {
            if slot.goal.is_none() {
                continue;
            }
            if L::mask_lane(take, k) {
                slot.iteration += 1;
                slot.tries = 0;
                slot.measured = false;
                match stall {
                    Some(s) if moved.lane(k) <= s.epsilon => slot.still += 1,
                    _ => slot.still = 0,
                }
            } else if L::mask_lane(reject, k) {
                slot.tries += 1;
                if slot.tries > opts.backtrack {
                    // Every damped try failed: the general loop turns to the transpose step.
                    finish(st, k, None, slot, phi, f64::NAN, &mut emit);
                }
            } else {
                finish(st, k, None, slot, phi, f64::NAN, &mut emit);
            }
        }
    }
}

/// One damped try of every lane, from the pose in `st` (angles and points) whose tip misses
/// its target as `miss` says, with damping `(μ, ν)`: the step
/// into `st.delta`, the trial pose into `st.trial` and its points, and what the line search
/// decides from them. The arithmetic of `compute_delta`, `damped_2x2`, `try_pose` and
/// `damped_search`, operation for operation; [`run`] and [`run_one`] share it.
struct Try<L: Lanes> {
    trial_phi: L,
    /// The sufficient-decrease test passed.
    accepted: L::Mask,
    /// The damped step was taken (not the pseudoinverse's case).
    damped: L::Mask,
    det: L,
    /// μ after an accepted and after a rejected try.
    accepted_mu: L,
    rejected_mu: L,
}

/// Where every lane's tip stands against its target at the start of a try: the target
/// `(tx, ty)`, the miss `e = (dx, dy)` (target less tip) and `current = ‖e‖²`.
#[derive(Clone, Copy)]
struct Miss<L> {
    target: (L, L),
    e: (L, L),
    current: L,
}

#[inline(always)]
fn try_step<L: Lanes>(
    chain: &Chain,
    st: &mut Buffers<L>,
    n: usize,
    miss: Miss<L>,
    (mu, nu): (L, L),
    gain: L,
    cap: Option<f64>,
) -> Try<L> {
    let Miss { target: (tx, ty), e: (dx, dy), current } = miss;
    let zero = L::splat(0.0);
    let (tip_x, tip_y) = (st.xs[n], st.ys[n]);
    let mut xx = zero;
    let mut xy = zero;
    let mut yy = zero;
    for (&px, &py) in st.xs[..n].iter().zip(&st.ys[..n]) {
        let cx = -(tip_y - py);
        let cy = tip_x - px;
        xx = xx + cx * cx;
        xy = xy + cx * cy;
        yy = yy + cy * cy;
    }
    // (A + μI)⁻¹ e, exactly as `damped_2x2`; where that declines the fast path is left.
    let d = mu;
    let a = xx + d;
    let c = yy + d;
    let det = a * c - xy * xy;
    let y0 = (c * dx - xy * dy) / det;
    let y1 = (a * dy - xy * dx) / det;
    let damped = d.gt(L::splat(1e-12) * (xx + yy));
    let mut largest = zero;
    for ((&px, &py), delta) in st.xs[..n].iter().zip(&st.ys[..n]).zip(&mut st.delta) {
        let cx = -(tip_y - py);
        let cy = tip_x - px;
        let step = cx * y0 + cy * y1;
        let dj = gain * L::splat(1.0) * L::splat(1.0) * step;
        *delta = dj;
        let m = dj.abs();
        largest = L::select(m.gt(largest), m, largest);
    }
    let scale = match cap {
        Some(cap) => L::select(largest.gt(L::splat(cap)), L::splat(cap) / largest, L::splat(1.0)),
        None => L::splat(1.0),
    };
    let mut p0 = dx;
    let mut p1 = dy;
    for ((((&px, &py), &a), &delta), trial) in
        st.xs[..n].iter().zip(&st.ys[..n]).zip(&st.angles).zip(&st.delta).zip(&mut st.trial)
    {
        let cx = -(tip_y - py);
        let cy = tip_x - px;
        let next = a + scale * delta;
        let moved = next - a;
        p0 = p0 - cx * moved;
        p1 = p1 - cy * moved;
        *trial = next;
    }
    let trial_phi = forward(chain, &st.trial, &mut st.trial_xs, &mut st.trial_ys);
    let ex = tx - st.trial_xs[n];
    let ey = ty - st.trial_ys[n];
    let trial_error = ex * ex + ey * ey;
    let predicted = p0 * p0 + p1 * p1;
    let expected = current - predicted;
    let expected = L::select(expected.gt(zero), expected, zero);
    let decrease = current - trial_error;
    let accepted = L::and(trial_error.lt(current), L::le(L::splat(SUFFICIENT_DECREASE) * expected, decrease));
    // Nielsen's update, as `Damping::accept` and `Damping::reject`.
    let rho = L::select(expected.gt(zero), decrease / expected, L::splat(1.0));
    let r = L::splat(2.0) * rho - L::splat(1.0);
    let shrink = L::splat(1.0) - r * r * r;
    let third = L::splat(1.0 / 3.0);
    let shrink = L::select(shrink.gt(third), shrink, third);
    Try { trial_phi, accepted, damped, det, accepted_mu: mu * shrink, rejected_mu: mu * nu }
}

/// How [`run_one`] ended: the status, or `None` with where the general loop takes over.
pub(super) struct OneEnd {
    pub(super) status: Option<Status>,
    pub(super) iterations: u32,
    pub(super) error: f64,
    pub(super) phi: f64,
    /// Where the general loop goes on from, if it must.
    pub(super) resume: LoopState,
}

/// One goal's attempt on the fast path: [`run`]'s arithmetic (the same [`try_step`] and
/// forward kinematics) without its lanes' bookkeeping. The final angles and points are in
/// `st` (`angles()`, `tip()`).
pub(super) fn run_one(
    chain: &Chain,
    opts: &SolveOptions,
    max_iterations: u32,
    start: &[f64],
    st: &mut Buffers<f64>,
    (tx, ty): (f64, f64),
) -> OneEnd {
    let n = chain.len();
    st.fit(n);
    st.angles.copy_from_slice(start);
    let mut phi = forward(chain, &st.angles, &mut st.xs, &mut st.ys);
    let (mut iteration, mut still) = (0u32, 0u32);
    let (mut mu, mut nu) = (opts.lambda * opts.lambda, 2.0);
    loop {
        let (dx, dy) = (tx - st.xs[n], ty - st.ys[n]);
        let current = dx * dx + dy * dy;
        // The general loop goes on from this iteration (built only where it must).
        let leave = |mu, nu, damped_failed| OneEnd {
            status: None,
            iterations: iteration,
            error: f64::NAN,
            phi,
            resume: LoopState::at(iteration, still, Damping::resume(mu, nu), damped_failed),
        };
        if !(current.is_finite() && current >= f64::MIN_POSITIVE) {
            return leave(mu, nu, false);
        }
        let error = current.sqrt();
        let status = if error <= opts.tolerance {
            Some(Status::Reached)
        } else if opts.stall.is_some_and(|s| still >= s.window) {
            Some(Status::Stalled)
        } else if iteration >= max_iterations {
            Some(Status::IterationLimit)
        } else if crate::interrupt::is_set(opts.interrupt.as_ref()) {
            Some(Status::Interrupted)
        } else {
            None
        };
        if status.is_some() {
            return OneEnd { status, error, ..leave(mu, nu, false) };
        }
        let mut tries = 0;
        loop {
            let t = try_step(
                chain,
                st,
                n,
                Miss { target: (tx, ty), e: (dx, dy), current },
                (mu, nu),
                opts.gain,
                opts.max_step,
            );
            if !t.damped || t.det == 0.0 {
                return leave(mu, nu, false);
            }
            if t.accepted {
                if !t.trial_phi.is_finite() {
                    return leave(mu, nu, false);
                }
                let moved = st.angles.iter().zip(&st.trial).fold(0.0f64, |m, (a, t)| m.max((t - a).abs()));
                std::mem::swap(&mut st.angles, &mut st.trial);
                std::mem::swap(&mut st.xs, &mut st.trial_xs);
                std::mem::swap(&mut st.ys, &mut st.trial_ys);
                phi = t.trial_phi;
                (mu, nu) = (t.accepted_mu, 2.0);
                iteration += 1;
                match opts.stall {
                    Some(s) if moved <= s.epsilon => still += 1,
                    _ => still = 0,
                }
                break;
            }
            (mu, nu) = (t.rejected_mu, nu * 2.0);
            tries += 1;
            if tries > opts.backtrack {
                return leave(mu, nu, true);
            }
        }
    }
}

impl Buffers<f64> {
    /// The angles [`run_one`] ended on.
    pub(super) fn angles(&self) -> &[f64] {
        &self.angles
    }

    /// The tip [`run_one`] ended on.
    pub(super) fn tip(&self) -> (f64, f64) {
        (self.xs[self.xs.len() - 1], self.ys[self.ys.len() - 1])
    }
}

/// Hands lane `k`'s goal to `emit` and frees the lane. The lane's angles and points in `st`
/// are the pose it ends on (a lane that finishes has not taken this iteration's step), and
/// lane `k` of `phi` is that pose's orientation.
#[inline(never)]
fn finish<L: Lanes>(
    st: &mut Buffers<L>,
    k: usize,
    status: Option<Status>,
    slot: &mut Slot,
    phi: L,
    error: f64,
    emit: &mut impl FnMut(usize, End<'_>),
) {
    let Some(goal) = slot.goal else { return };
    let n = st.angles.len();
    for (o, a) in st.lane_angles.iter_mut().zip(&st.angles) {
        *o = a.lane(k);
    }
    emit(
        goal,
        End {
            status,
            angles: &st.lane_angles,
            iterations: slot.iteration,
            error,
            tip: (st.xs[n].lane(k), st.ys[n].lane(k)),
            phi: phi.lane(k),
        },
    );
    *slot = Slot::default();
}

/// The buffers of [`run_lanes`]: AVX2 lanes where the processor has them, else [`Quad`]s.
/// Only the kind that runs grows.
#[derive(Debug, Clone, Default)]
pub(super) struct BatchBuffers {
    #[cfg(target_arch = "x86_64")]
    avx: Buffers<Pair<Avx>>,
    quad: Buffers<Quad>,
}

/// [`run`] several goals at a time: eight, in two groups of four [`Avx`] lanes ([`Pair`]), in a
/// function compiled for AVX2 where the processor has it (checked at run time), else four on
/// [`Quad`] lanes compiled for the target's baseline (SSE2 on x86-64). Both run the same IEEE
/// operations per lane, so the results do not depend on which one runs. (Two groups: each
/// step's dependency chain, the sines of the joints and the 2×2 solve, leaves the floating-point
/// units idle part of the time, and the second group's independent chain fills them; see the
/// [lanes' module docs](crate::lanes) for what it measured.)
pub(super) fn run_lanes(
    chain: &Chain,
    opts: &SolveOptions,
    start: &[f64],
    st: &mut BatchBuffers,
    goals: impl Iterator<Item = (usize, f64, f64)>,
    emit: impl FnMut(usize, End<'_>),
) {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        fn avx2(
            chain: &Chain,
            opts: &SolveOptions,
            start: &[f64],
            st: &mut Buffers<Pair<Avx>>,
            goals: impl Iterator<Item = (usize, f64, f64)>,
            emit: impl FnMut(usize, End<'_>),
        ) {
            run(chain, opts, opts.max_iterations, start, st, goals, emit);
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            #[allow(unsafe_code)]
            unsafe {
                avx2(chain, opts, start, &mut st.avx, goals, emit);
            }
            return;
        }
    }
    run(chain, opts, opts.max_iterations, start, &mut st.quad, goals, emit);
}

#[cfg(test)]
#[path = "fast_tests.rs"]
mod tests;
