//! Jacobian transpose step (Buss 2004, "Introduction to inverse kinematics with Jacobian
//! transpose, pseudoinverse and damped least squares methods", eq. 6).
//!
//! `Δθ = α Jᵀ e`. The linearised tip change is `J Δθ = α A e` with `A = J Jᵀ`; the α that
//! brings it closest to `e` minimises `‖e − α A e‖²`, giving `α = ⟨e, A e⟩ / ⟨A e, A e⟩`.

use nalgebra::{Matrix3, Vector3};

/// `y = α e` with the error-minimising α; `y = 0` when `A e = 0` (the error is orthogonal to
/// every direction the tip can move in).
pub(super) fn task_step(a: &Matrix3<f64>, e: &Vector3<f64>) -> Vector3<f64> {
    let ae = a * e;
    let denom = ae.norm_squared();
    if denom > 0.0 { e * (e.dot(&ae) / denom) } else { Vector3::zeros() }
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
}
