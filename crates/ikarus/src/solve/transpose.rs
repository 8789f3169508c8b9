//! Jacobian transpose step (Buss 2004, "Introduction to inverse kinematics with Jacobian
//! transpose, pseudoinverse and damped least squares methods", eq. 6).
//!
//! `Δθ = α Jᵀ e`. The linearised tip change is `J Δθ = α A e` with `A = J Jᵀ`; the α that
//! brings it closest to `e` minimises `‖e − α A e‖²`, giving `α = ⟨e, A e⟩ / ⟨A e, A e⟩`.

use nalgebra::{Matrix3, Vector3};

/// `y = α e` with the error-minimising α; `y = 0` when `A e = 0` (the error is orthogonal to
/// every direction the tip can move in) or when `A` or `e` is not finite.
///
/// Computed scale-free where it must be: with `s` the largest entry of `|A|` and `m` the largest of `|e|`,
/// `Â = A / s` and `ê = e / m` are of order one and `α = ⟨ê, Â ê⟩ / (s ‖Â ê‖²)`, so that
/// `‖A e‖²`, of order `reach⁴ · error²`, never overflows (it did for lengths of 1e52, and the
/// step was then 0: a reachable goal stalled after 0 iterations).
pub(super) fn task_step(a: &Matrix3<f64>, e: &Vector3<f64>) -> Vector3<f64> {
    // The plain formula where `‖A e‖²` is a normal finite number (every chain of ordinary
    // size), the scaled one only where it overflowed or underflowed.
    let ae = a * e;
    let denom = ae.norm_squared();
    if denom.is_finite() && denom >= f64::MIN_POSITIVE {
        let alpha = e.dot(&ae) / denom;
        if alpha.is_finite() {
            return e * alpha;
        }
    }
    scaled_step(a, e)
}

/// [`task_step`] on `A` and `e` scaled to order one, for the rare chain where `‖A e‖²` leaves
/// the range of normal f64 numbers.
#[cold]
#[inline(never)]
fn scaled_step(a: &Matrix3<f64>, e: &Vector3<f64>) -> Vector3<f64> {
    let s = a.amax();
    let m = e.amax();
    if !(s > 0.0 && s.is_finite() && m > 0.0 && m.is_finite()) {
        return Vector3::zeros();
    }
    let (a_hat, e_hat) = (a / s, e / m);
    let ae = a_hat * e_hat;
    let denom = ae.norm_squared();
    if denom > 0.0 { e * (e_hat.dot(&ae) / denom / s) } else { Vector3::zeros() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_length_minimises_the_linearised_error() {
        let a = Matrix3::new(4.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0);
        let e = Vector3::new(0.3, -0.7, 0.0);
        let y = task_step(&a, &e);
        let alpha = y.x / e.x;
        let residual = |t: f64| (e - t * (a * e)).norm_squared();
        assert!(residual(alpha) < residual(alpha * 1.01));
        assert!(residual(alpha) < residual(alpha * 0.99));
        assert_eq!(task_step(&Matrix3::zeros(), &e), Vector3::zeros());
    }

    /// The same step, to rounding, whatever the scale: `A` of a chain of lengths 1e60 (entries
    /// of 1e120) and an error of 1e60 gave `‖A e‖² = ∞` and a step of 0 before.
    #[test]
    fn step_is_scale_free() {
        let a = Matrix3::new(4.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0);
        let e = Vector3::new(0.3, -0.7, 0.0);
        let y = task_step(&a, &e);
        for k in [1e-150, 1e-60, 1e60, 1e100] {
            let big = task_step(&(a * (k * k)), &(e * k));
            // y scales as e / A: by 1 / k.
            let want = y / k;
            assert!((big - want).norm() <= 1e-14 * want.norm(), "{k:e}: {big} vs {want}");
        }
        assert_eq!(task_step(&(a * f64::INFINITY), &e), Vector3::zeros());
    }
}
