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
//!
//! A body with a rest-pose preference (a skeleton whose bones have a stiffness, see
//! [`Bone::stiffness`](crate::Bone::stiffness)) weights its columns the same way, joint `i` by
//! `kᵢ = 1/√(1 + sᵢ)` for stiffness `sᵢ`, so that the step is the one of least
//! `Σ (1 + sᵢ) Δθᵢ²` (stiff joints turn less); and the first try of each step adds a pull toward
//! the rest angles in the null space of the task (see [`pull_to_rest`]).

use super::LimitMode;
use super::algebra::{Algebra, Columns};
use super::model::Problem;
use super::model::{Model, Posture, ScratchOf};
use super::step::Rule;
use crate::math;

/// Per iteration, [`LimitMode::NullSpace`] asks each limited joint to cover this share of its
/// distance to the middle of its range (before the projection into the null space).
const NULLSPACE_GAIN: f64 = 0.3;

/// The null-space push fades linearly once the task error is below this share of the reach.
const NULLSPACE_FADE: f64 = 0.1;

/// Per step, a joint with a rest-pose preference is asked to cover this share of its
/// stiffness-weighted distance to its rest angle (before the projection into the null space,
/// and the cap of [`pull_to_rest`]).
const REST_GAIN: f64 = 0.5;

/// The pull of a step may turn a joint by up to this much (radians, about 3°) even when the
/// goals' own step turns them by less (see [`pull_to_rest`]).
const REST_FLOOR: f64 = 0.05;

/// Fills `s.delta` with the joint step of `rule` under the problem's limit mode, scaled by the
/// gain and the rates, and returns the factor that brings it within
/// [`SolveOptions::max_step`](super::SolveOptions::max_step). `mu` is Levenberg–Marquardt's
/// damping; the task error `e` and `J` are in `s.alg`. With `pull` and a body with a rest-pose
/// preference, the step carries the pull toward the rest pose ([`pull_to_rest`]).
#[inline]
pub(super) fn compute_delta<M: Model>(
    p: &Problem<'_, M>,
    rule: Rule,
    mu: f64,
    pull: bool,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) -> f64 {
    let (model, opts, mode) = (p.model, p.opts, p.mode);
    let n = model.len();
    let posture = model.posture();
    match posture {
        Some(post) => s.scale.copy_from_slice(post.scale),
        None => s.scale.fill(1.0),
    }
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
        let columns = if round == 0 && !weighing && posture.is_none() { Columns::Plain } else { Columns::Weighted };
        if columns == Columns::Weighted {
            for i in 0..n {
                let k = if s.locked[i] { 0.0 } else { s.scale[i] };
                s.alg.set_weighted(i, k);
            }
        }
        s.alg.gram(columns);
        s.alg.method_step(columns, rule, opts, mu, &mut s.step);
        for i in 0..n {
            if !s.locked[i] {
                let rate = opts.rates.get(i).copied().unwrap_or(1.0);
                s.delta[i] = opts.gain * rate * s.scale[i] * s.step[i];
            }
        }
        if let (true, Some(post)) = (pull, posture) {
            pull_to_rest(p, post, columns, angles, s);
        }
        if pushing {
            push_to_the_middle(p, fade, columns, angles, s);
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
                s.scale[i] *= w.sqrt();
            }
        }
    }
}

/// The null-space push: `z` pulls limited joints toward the middle; remove what the task would
/// see of it ([`project_free`]) and add it to the step. `columns` says whether this round's
/// weighted Jacobian is `J` itself ([`Columns::Plain`]); the algebra holds its Gram matrix.
#[inline]
fn push_to_the_middle<M: Model>(p: &Problem<'_, M>, fade: f64, columns: Columns, angles: &[f64], s: &mut ScratchOf<M>) {
    for (i, lim) in p.model.limits().iter().enumerate() {
        s.step[i] = match lim {
            Some(l) if !s.locked[i] => -NULLSPACE_GAIN * fade * (angles[i] - 0.5 * (l.min() + l.max())),
            _ => 0.0,
        };
    }
    project_free(p, columns, s);
    for (d, (&q, &locked)) in s.delta.iter_mut().zip(s.pull.iter().zip(&s.locked)) {
        if !locked {
            *d += q;
        }
    }
}

/// The joint motion `z` (in `s.step`) less what the task would see of it, into `s.pull`, in the
/// metric of the weighted step (`K` the column weights, 1 unless weighted; `Ĵ = J K`):
/// `K (z' − Ĵᵀ (Ĵ Ĵᵀ)⁺ Ĵ z')` with `z' = K⁻¹ z`, so that `J` of it is 0; the locked joints (and
/// those of weight 0) are left out. With every weight 1 this is `z − Jᵀ (J Jᵀ)⁺ J z`.
#[inline]
fn project_free<M: Model>(p: &Problem<'_, M>, columns: Columns, s: &mut ScratchOf<M>) {
    for i in 0..s.step.len() {
        let k = s.scale[i];
        s.step[i] = if k > 0.0 && !s.locked[i] { s.step[i] / k } else { 0.0 };
    }
    s.pull.fill(0.0);
    s.alg.project_push(columns, p.opts.singular_threshold, &s.step, &s.locked, &mut s.pull);
    for (q, &k) in s.pull.iter_mut().zip(&s.scale) {
        *q *= k;
    }
}

/// The pull toward the rest pose: joint `i` is asked to turn by
/// `zᵢ = −REST_GAIN · pullᵢ · (θᵢ − restᵢ)`, the natural gradient of `½ Σ sᵢ (θᵢ − restᵢ)²` in
/// the metric of the weighted step; what the task would see of it is removed in that same
/// metric (`K` the column weights, `Ĵ = J K`, `z' = K⁻¹ z`):
/// `Δθ += c · K (z' − Ĵᵀ (Ĵ Ĵᵀ)⁺ Ĵ z')`, over the free joints, so that to first order the pull
/// moves no goal and no pin. It is capped (`c ≤ 1`) at the largest turn of the task's own step
/// or [`REST_FLOOR`], whichever is larger, so that it never outruns the goals by much: far from
/// them the body is pulled home as fast as the limbs move. The line search judges the step with
/// its pull on the task's error alone, and tries it once: a step whose pull costs too much (near
/// the goals, where the pull's second-order error outweighs the step's gain) is tried again
/// without it, which keeps the final convergence the rule's own.
#[inline]
fn pull_to_rest<M: Model>(
    p: &Problem<'_, M>,
    post: Posture<'_>,
    columns: Columns,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) {
    let largest = s.delta.iter().zip(&s.locked).filter(|(_, l)| !**l).fold(0.0f64, |m, (d, _)| m.max(d.abs()));
    for (z, ((a, r), f)) in s.step.iter_mut().zip(angles.iter().zip(post.rest).zip(post.pull)) {
        *z = -REST_GAIN * f * (a - r);
    }
    if !(largest > 0.0 && largest.is_finite()) {
        return;
    }
    project_free(p, columns, s);
    let size = s.pull.iter().fold(0.0f64, |m, q| m.max(q.abs()));
    if !(size > 0.0 && size.is_finite()) {
        return;
    }
    let c = (largest.max(REST_FLOOR) / size).min(1.0);
    for (d, (&q, &locked)) in s.delta.iter_mut().zip(s.pull.iter().zip(&s.locked)) {
        if !locked {
            *d += c * q;
        }
    }
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
