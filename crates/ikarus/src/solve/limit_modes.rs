//! How a Jacobian step treats the joint limits before the final clamp: the [`LimitMode`]s.
//!
//! - [`LimitMode::Ignore`] and [`LimitMode::Clamp`] take the rule's step as it is (the clamp
//!   into the limits happens when the trial pose is formed).
//! - [`LimitMode::Lock`]: a free joint whose step crosses its limit goes only to the limit and
//!   is held there; the rest of the task is solved again by the other joints, until no new
//!   joint locks.
//! - [`LimitMode::NullSpace`]: lock, plus a push `z` of each limited joint toward the middle
//!   of its range, projected into the null space of `J`: `Δθ += z − Jᵀ (J Jᵀ)⁺ J z`. It fades
//!   as the goal nears, so that it does not slow the final convergence.
//! - [`LimitMode::Weighted`] (weighted least norm, Chan & Dubey 1995): each joint's column is
//!   weighted by how near its limit the task moves it, `W Jᵀ (J W Jᵀ)⁻¹` with `W` diagonal,
//!   computed as the rule's step on `J W^½`.

use super::LimitMode;
use super::algebra::Algebra;
use super::model::{Model, ScratchOf};
use super::problem::Problem;
use super::step::Rule;
use crate::math;

/// Per iteration, [`LimitMode::NullSpace`] asks each limited joint to cover this share of its
/// distance to the middle of its range (before the projection into the null space).
const NULLSPACE_GAIN: f64 = 0.3;

/// The null-space push fades linearly once the task error is below this share of the reach.
const NULLSPACE_FADE: f64 = 0.1;

/// Fills `s.delta` with the joint step of `rule` under the problem's limit mode, scaled by the
/// gain and the rates, and returns the factor that brings it within
/// [`SolveOptions::max_step`](super::SolveOptions::max_step). `mu` is Levenberg–Marquardt's
/// damping; the task error `e` and `J` are in `s.alg`.
#[inline]
pub(super) fn compute_delta<M: Model>(
    p: &Problem<'_, M>,
    rule: Rule,
    mu: f64,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) -> f64 {
    let (model, opts, mode) = (p.model, p.opts, p.mode);
    let n = model.len();
    s.scale.fill(1.0);
    let (locking, weighing, pushing) = match mode {
        LimitMode::Ignore | LimitMode::Clamp => (false, false, false),
        LimitMode::Lock => (true, false, false),
        LimitMode::NullSpace => (true, false, true),
        LimitMode::Weighted => (false, true, false),
    };
    if weighing {
        weigh(model, angles, s);
    }
    s.locked.fill(false);
    s.alg.reset_task();
    let fade = if pushing { (s.alg.e_norm() / (NULLSPACE_FADE * model.max_reach())).min(1.0) } else { 0.0 };
    for round in 0..=n {
        // Until a joint is locked or weighted, J itself is the weighted Jacobian.
        let plain = round == 0 && !weighing;
        if !plain {
            for i in 0..n {
                let k = if s.locked[i] { 0.0 } else { s.scale[i] };
                s.alg.set_weighted(i, k);
            }
        }
        s.alg.gram(plain);
        s.alg.method_step(plain, rule, opts, mu, &mut s.step);
        for i in 0..n {
            if !s.locked[i] {
                let rate = opts.rates.get(i).copied().unwrap_or(1.0);
                s.delta[i] = opts.gain * rate * s.scale[i] * s.step[i];
            }
        }
        if pushing {
            push_to_the_middle(p, fade, plain, angles, s);
        }
        if !locking || !lock_crossing(model, angles, s) {
            break;
        }
    }
    let largest = s.delta.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    match opts.max_step {
        Some(cap) if largest > cap => cap / largest,
        _ => 1.0,
    }
}

/// Weighted least norm: `s.scale[i] = √wᵢ`, slowing down a joint that the task moves toward a
/// limit, with `wᵢ = 1 / (1 + |∂H/∂θᵢ|)` of the joint-limit measure
/// `H = Σ (max − min)² / (4 (max − θ)(θ − min))`, and 0 at or beyond a limit.
#[inline]
fn weigh<M: Model>(model: &M, angles: &[f64], s: &mut ScratchOf<M>) {
    for (i, lim) in model.limits().iter().enumerate() {
        if let Some(lim) = lim {
            let (lo, hi, th) = (lim.min(), lim.max(), angles[i]);
            let g = s.alg.column_dot_e(i);
            let toward = (g > 0.0 && 2.0 * th > lo + hi) || (g < 0.0 && 2.0 * th < lo + hi);
            if toward {
                let gap = (hi - th) * (th - lo);
                let w = if gap > 0.0 {
                    let dh = math::square(hi - lo) * (2.0 * th - hi - lo) / (4.0 * gap * gap);
                    1.0 / (1.0 + dh.abs())
                } else {
                    0.0
                };
                s.scale[i] = w.sqrt();
            }
        }
    }
}

/// The null-space push: `z` pulls limited joints toward the middle; remove what the task would
/// see of it: `Δθ += z − Jᵀ (J Jᵀ)⁺ J z`, over the free (unlocked) joints. `plain` says whether
/// this round's weighted Jacobian is `J` itself, whose Gram matrix the algebra holds.
#[inline]
fn push_to_the_middle<M: Model>(p: &Problem<'_, M>, fade: f64, plain: bool, angles: &[f64], s: &mut ScratchOf<M>) {
    for (i, lim) in p.model.limits().iter().enumerate() {
        s.step[i] = match lim {
            Some(l) if !s.locked[i] => -NULLSPACE_GAIN * fade * (angles[i] - 0.5 * (l.min() + l.max())),
            _ => 0.0,
        };
    }
    s.alg.project_push(plain, p.opts.singular_threshold, &s.step, &s.locked, &mut s.delta);
}

/// Clamp and lock: a free joint whose step crosses its limit goes only to the limit and is
/// held there, and what it no longer does is taken out of the task. Whether any joint locked.
#[inline]
fn lock_crossing<M: Model>(model: &M, angles: &[f64], s: &mut ScratchOf<M>) -> bool {
    let mut newly = false;
    for (i, lim) in model.limits().iter().enumerate() {
        let Some(l) = lim else { continue };
        if s.locked[i] {
            continue;
        }
        let next = angles[i] + s.delta[i];
        if next > l.max() || next < l.min() {
            let d = l.clamp(next) - angles[i];
            s.delta[i] = d;
            s.locked[i] = true;
            s.alg.task_sub_column(i, d);
            newly = true;
        }
    }
    newly
}
