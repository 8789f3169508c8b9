//! The line search of the Jacobian methods (see the [module docs](super)): a step is accepted
//! only if it lowers the task error `‖e‖²` by at least a tenth of what the linearisation
//! `J Δθ` predicts (an Armijo test). Pinv, DLS and SDLS try their own full step once; LM
//! raises its damping and tries again; if that fails, the steepest-descent (transpose) step is
//! tried instead, halved up to [`SolveOptions::backtrack`](super::SolveOptions::backtrack)
//! times. The trial pose's forward kinematics is the next iteration's, so an accepted first try
//! costs nothing extra.

use super::algebra::Algebra;
use super::limit_modes::compute_delta;
use super::lm::Damping;
use super::model::Problem;
use super::model::{Model, ScratchOf};
use super::step::Rule;

/// The share of the linearly predicted error decrease a backtracking step must achieve.
const SUFFICIENT_DECREASE: f64 = 0.1;

/// One step of a Jacobian method with its line search, from the pose whose task error `e` (in
/// `s.alg`) has `‖e‖² = current` (`damped_failed`: see the body). On success the new pose is in
/// `s.trial` and `s.trial_joints` and its tip orientation is returned; `None` means no step
/// lowers the error enough.
#[inline]
pub(super) fn jacobian_step<M: Model>(
    p: &Problem<'_, M>,
    method: Rule,
    damped_failed: bool,
    current: f64,
    damping: &mut Damping,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) -> Option<f64> {
    let backtrack = p.opts.backtrack;
    // `damped_failed`: Levenberg–Marquardt's tries of this iteration were already made and all
    // rejected (by the fast path, which hands over here): on to the transpose step.
    let mut rule = if damped_failed { Rule::Transpose } else { method };
    loop {
        let found = if rule == Rule::LevenbergMarquardt {
            damped_search(p, current, damping, angles, s)
        } else {
            // Gauss–Newton directions get one full try; the transpose step is halved.
            let halvings = if rule == method && rule != Rule::Transpose { 0 } else { backtrack };
            halving_search(p, rule, halvings, current, damping.mu(), angles, s)
        };
        if found.is_some() {
            return found;
        }
        if rule == Rule::Transpose || backtrack == 0 {
            return None;
        }
        // The method's own step falls short: Gauss–Newton directions (pinv, DLS with small λ)
        // are poor where J is nearly singular, as on the way to a goal out of reach. Search the
        // steepest-descent (transpose) direction instead.
        rule = Rule::Transpose;
    }
}

/// Levenberg–Marquardt's search: a rejected step raises the damping instead of halving.
#[inline]
fn damped_search<M: Model>(
    p: &Problem<'_, M>,
    current: f64,
    damping: &mut Damping,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) -> Option<f64> {
    let backtrack = p.opts.backtrack;
    // The rest pose's pull rides on the first try only: a step it spoils is tried again
    // without it, at the same damping.
    let mut pulled = p.model.posture().is_some();
    let mut tries = 0;
    while tries <= backtrack {
        let scale = compute_delta(p, Rule::LevenbergMarquardt, damping.mu(), pulled, angles, s);
        let (trial_error, expected, trial_phi) = try_pose(p, scale, angles, s);
        if backtrack == 0 {
            return Some(trial_phi);
        }
        let decrease = current - trial_error;
        if trial_error < current && decrease >= SUFFICIENT_DECREASE * expected {
            damping.accept(decrease, expected);
            return Some(trial_phi);
        }
        if std::mem::take(&mut pulled) {
            continue;
        }
        damping.reject();
        tries += 1;
    }
    None
}

/// The search of the other rules: the step, then up to `halvings` halvings of it.
#[inline]
fn halving_search<M: Model>(
    p: &Problem<'_, M>,
    rule: Rule,
    halvings: u32,
    current: f64,
    mu: f64,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) -> Option<f64> {
    let mut scale = compute_delta(p, rule, mu, true, angles, s);
    // Whether the step carries the rest pose's pull: its first try does; if that fails, the
    // step without the pull is tried at full length, and then halved.
    let mut pulled = p.model.posture().is_some();
    let mut attempt = 0;
    while attempt <= halvings {
        let (trial_error, expected, trial_phi) = try_pose(p, scale, angles, s);
        if p.opts.backtrack == 0 {
            return Some(trial_phi);
        }
        if trial_error < current && current - trial_error >= SUFFICIENT_DECREASE * expected {
            return Some(trial_phi);
        }
        if std::mem::take(&mut pulled) {
            scale = compute_delta(p, rule, mu, false, angles, s);
            continue;
        }
        if attempt < halvings {
            scale *= 0.5;
        }
        attempt += 1;
    }
    None
}

/// Tries `angles + scale·Δθ` (clamped into the problem's bounds): the trial pose goes to
/// `s.trial` and `s.trial_joints`. Returns its squared task error, the decrease the
/// linearisation `J Δθ` predicts, and its tip orientation.
#[inline]
pub(super) fn try_pose<M: Model>(
    p: &Problem<'_, M>,
    scale: f64,
    angles: &[f64],
    s: &mut ScratchOf<M>,
) -> (f64, f64, f64) {
    s.alg.predict_from_e();
    for (i, ((t, a), d)) in s.trial.iter_mut().zip(angles).zip(&s.delta).enumerate() {
        let next = p.bounds.clamp(i, a + scale * d);
        s.alg.predict_sub_column(i, next - a);
        *t = next;
    }
    let trial_phi = p.model.forward_into(&s.trial, &mut s.trial_joints);
    let trial_error = p.model.trial_error(p.goal, p.opts, &s.trial_joints, trial_phi);
    let expected = (s.alg.e_norm_squared() - s.alg.predicted_norm_squared()).max(0.0);
    (trial_error, expected, trial_phi)
}
