//! One solve from one start pose: the iteration loop of the [module docs](super).

use super::algebra::Algebra;
use super::fast::Taken;
use super::line_search::jacobian_step;
use super::lm::Damping;
use super::model::Problem;
use super::model::{Model, ScratchOf};
use super::step::Stepper;
use super::{Outcome, Status};

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
pub(super) fn attempt<M: Model>(p: &Problem<'_, M>, start: &[f64], s: &mut ScratchOf<M>, out: &mut Outcome) -> Status {
    let resume = match M::fast_attempt(p, start, s, out) {
        Taken::Done(status) => return status,
        Taken::Resume(r) => Some(r),
        Taken::No => None,
    };
    let (model, goal, opts) = (p.model, p.goal, p.opts);
    let n = model.len();
    // The pose is moved out of `out` while the loop measures into `out`, and moved back after.
    let mut pose = std::mem::take(out.pose.angles_mut());
    let angles = &mut pose;
    angles.clear();
    // Where the fast path left off, the pose it stood on is in `s.best`.
    angles.extend_from_slice(if resume.is_some() { &s.best } else { start });
    p.bounds.clamp_into(angles);
    out.frames.start(n, opts.record_every, opts.max_iterations);

    let stepper = Stepper::of(opts.method);
    let mut phi = model.forward_into(angles, &mut s.joints);
    let r = resume.unwrap_or_default();
    let mut iteration: u32 = r.iteration;
    let mut still: u32 = r.still;
    let mut prev_merit = f64::INFINITY;
    let mut flat = false;
    let mut damping = if resume.is_some() { Damping::resume(r.mu, r.nu) } else { Damping::new(opts.lambda) };
    let mut skip_damped = r.damped_failed;
    let mut best_error = f64::INFINITY;
    let status = loop {
        model.measure(goal, opts, &s.joints, phi, out, &mut s.alg);
        if let Some(k) = opts.record_every {
            if iteration % k == 0 {
                out.frames.push(iteration, angles, M::frame_points(&s.joints));
            }
        }
        if let Some(status) = stop(p, out.error, out.angle_error, still, iteration) {
            break status;
        }

        let trial_phi = match stepper {
            Stepper::Jacobian(rule) => {
                model.jacobian(goal, opts, &s.joints, &mut s.alg);
                let current = s.alg.e_norm_squared();
                if let Some(floor) = M::PROGRESS_FLOOR {
                    flat = prev_merit - current <= floor * prev_merit;
                    prev_merit = current;
                }
                // Where the fast path handed over after every damped try of this iteration
                // failed, the line search goes on from there, with the transpose step.
                let damped_failed = std::mem::take(&mut skip_damped);
                let Some(trial_phi) = jacobian_step(p, rule, damped_failed, current, &mut damping, angles, s) else {
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
        iteration += 1;
        match opts.stall {
            Some(st) if moved <= st.epsilon || flat => still += 1,
            _ => still = 0,
        }
    };
    *out.pose.angles_mut() = pose;

    if !matches!(stepper, Stepper::Jacobian(_)) && status != Status::Reached {
        end_on_best(p, best_error, s, out);
    }
    out.iterations = iteration;
    if opts.record_every.is_some() {
        out.frames.push_final(iteration, out.pose.angles(), M::frame_points(&s.joints));
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
