//! One solve from one start pose: the iteration loop of the [module docs](super).

use nalgebra::Vector3;

use super::line_search::{Residual, jacobian_step};
use super::lm::Damping;
use super::model::Model;
use super::problem::Problem;
use super::scratch::Scratch;
use super::step::{Rule, Stepper};
use super::{Outcome, Status};
use crate::angle::wrap_angle;
use crate::kinematics::EndEffector;

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
pub(super) fn attempt<M: Model>(p: &Problem<'_, M>, start: &[f64], s: &mut Scratch, out: &mut Outcome) -> Status {
    let (model, goal, opts) = (p.model, p.goal, p.opts);
    let n = model.len();
    let angles = out.pose.angles_mut();
    angles.clear();
    angles.extend_from_slice(start);
    p.bounds.clamp_into(angles);
    out.frames.start(n, opts.record_every, opts.max_iterations);

    let stepper = Stepper::of(opts.method);
    let target = goal.target();
    let weight = opts.orientation_weight;
    let mut phi = model.forward_into(angles, &mut s.joints);
    let mut iteration: u32 = 0;
    let mut still: u32 = 0;
    let mut damping = Damping::new(opts.lambda);
    let mut best_error = f64::INFINITY;
    let status = loop {
        let tip = model.tip(&s.joints);
        let (dx, dy) = (target.x - tip.x, target.y - tip.y);
        let turn = goal.orientation().map(|g| wrap_angle(g - phi));
        let error = distance(dx, dy);
        let angle_error = turn.map_or(0.0, f64::abs);
        out.error = error;
        out.angle_error = angle_error;
        out.end_effector = EndEffector { position: tip, orientation: phi };
        if let Some(k) = opts.record_every {
            if iteration % k == 0 {
                out.frames.push(iteration, angles, &s.joints);
            }
        }
        if let Some(status) = stop(p, error, angle_error, still, iteration) {
            break status;
        }

        let trial_phi = match stepper {
            Stepper::Jacobian(rule) => {
                let e = Vector3::new(dx, dy, turn.map_or(0.0, |t| weight * t));
                let Some(trial_phi) = jacobian_iteration(p, rule, e, &mut damping, angles, s) else {
                    // No step along this direction lowers the error: the pose cannot move, and
                    // the same pose would give the same direction again.
                    break Status::Stalled;
                };
                trial_phi
            }
            Stepper::Ccd => {
                remember_best(weight, error, angle_error, &mut best_error, angles, &mut s.best);
                M::ccd_sweep(p, angles, &s.joints, &mut s.trial, &mut s.trial_joints)
            }
            Stepper::Fabrik => {
                remember_best(weight, error, angle_error, &mut best_error, angles, &mut s.best);
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
        iteration += 1;
        match opts.stall {
            Some(st) if moved <= st.epsilon => still += 1,
            _ => still = 0,
        }
    };

    if !matches!(stepper, Stepper::Jacobian(_)) && status != Status::Reached {
        end_on_best(p, best_error, s, out);
    }
    out.iterations = iteration;
    if opts.record_every.is_some() {
        out.frames.push_final(iteration, out.pose.angles(), &s.joints);
    }
    status
}

/// Why the loop stops at this iteration, if it does.
#[inline]
fn stop<M: Model>(p: &Problem<'_, M>, error: f64, angle_error: f64, still: u32, iteration: u32) -> Option<Status> {
    let opts = p.opts;
    if error <= opts.tolerance && angle_error <= opts.angle_tolerance {
        Some(Status::Reached)
    } else if opts.stall.is_some_and(|st| still >= st.window) {
        Some(Status::Stalled)
    } else if iteration >= opts.max_iterations {
        Some(Status::IterationLimit)
    } else if crate::interrupt::is_set(opts.interrupt.as_ref()) {
        Some(Status::Interrupted)
    } else {
        None
    }
}

/// CCD and FABRIK keep the best pose they visit: `angles`, if its squared task error (from
/// `error` and `angle_error`, weighted by `weight`) is below `best_error`.
#[inline]
fn remember_best(weight: f64, error: f64, angle_error: f64, best_error: &mut f64, angles: &[f64], best: &mut [f64]) {
    let e2 = error * error + (weight * angle_error).powi(2);
    if e2 < *best_error {
        *best_error = e2;
        best.copy_from_slice(angles);
    }
}

/// One iteration of a Jacobian rule for the task error `e`: `J`, embedded in three dimensions
/// like `e` (without an orientation goal the third row of `J` and `e` is zero), then the step
/// with its line search.
#[inline]
fn jacobian_iteration<M: Model>(
    p: &Problem<'_, M>,
    rule: Rule,
    e: Vector3<f64>,
    damping: &mut Damping,
    angles: &[f64],
    s: &mut Scratch,
) -> Option<f64> {
    let weight = p.opts.orientation_weight;
    p.model.jacobian_into(&s.joints, &mut s.jacobian);
    let row_scale = if p.goal.orientation().is_some() { weight } else { 0.0 };
    for mut col in s.jacobian.column_iter_mut() {
        col[2] *= row_scale;
    }
    let current = e.norm_squared();
    jacobian_step(p, rule, &Residual { e, current }, damping, angles, s)
}

/// CCD and FABRIK: if the pose they end on is worse than the best they visited (squared task
/// error `best_error`, pose in `s.best`), end on that one, with its error and tip (the
/// restarts compare attempts by them).
fn end_on_best<M: Model>(p: &Problem<'_, M>, best_error: f64, s: &mut Scratch, out: &mut Outcome) {
    let (model, goal) = (p.model, p.goal);
    let weight = p.opts.orientation_weight;
    let final_error = out.error.powi(2) + (weight * out.angle_error).powi(2);
    if best_error < final_error {
        let angles = out.pose.angles_mut();
        angles.copy_from_slice(&s.best);
        let phi = model.forward_into(angles, &mut s.joints);
        let tip = model.tip(&s.joints);
        out.error = distance(goal.target().x - tip.x, goal.target().y - tip.y);
        out.angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - phi).abs());
        out.end_effector = EndEffector { position: tip, orientation: phi };
    }
}

/// The length of `(dx, dy)`: `√(dx² + dy²)`, or `hypot` where the sum of squares would overflow
/// or lose precision below the smallest normal number (so that a goal 1e200 away is 1e200
/// away, not infinitely far, and 1e-170 away is not 0). Saturates at `f64::MAX` if the length
/// itself is beyond the f64 range, so that it is always a finite number.
#[inline]
pub(super) fn distance(dx: f64, dy: f64) -> f64 {
    let squared = dx * dx + dy * dy;
    let d = if squared.is_finite() && squared >= f64::MIN_POSITIVE { squared.sqrt() } else { dx.hypot(dy) };
    d.min(f64::MAX)
}
