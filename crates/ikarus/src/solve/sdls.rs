//! Selectively damped least squares (Buss & Kim 2005, "Selectively damped least squares for
//! inverse kinematics").
//!
//! With the singular value decomposition `J = Σ σₖ uₖ vₖᵀ`, the pseudoinverse step is the sum
//! of `φₖ = σₖ⁻¹ (uₖ · e) vₖ`. SDLS clamps each `φₖ` separately, to at most
//!
//! `γₖ = min(1, Nₖ / Mₖ) γ_max`,  `Nₖ = ‖uₖ‖`,  `Mₖ = σₖ⁻¹ Σⱼ |vⱼₖ| ‖Jⱼ‖`,
//!
//! in its largest component: `Mₖ` bounds how far the tip moves per unit of `φₖ`, so a
//! direction whose singular value is small (near a singularity) gets a small joint change,
//! while well-conditioned directions keep their full pseudoinverse step. The sum is clamped to
//! `γ_max` = π/4 as well. The norms are taken per task block: the position rows and the
//! orientation row count as two end-effector blocks, as in the paper's multi-effector sums.
//!
//! The `uₖ` and `σₖ²` come from the eigen-decomposition of `A = J Jᵀ` (3×3), and
//! `vₖ = Jᵀ uₖ / σₖ`, so no N×N decomposition is needed.

use nalgebra::{Matrix3, Matrix3xX, SymmetricEigen, Vector3};

use crate::math;

/// The paper's bound on any joint change in one step, radians.
const GAMMA_MAX: f64 = std::f64::consts::FRAC_PI_4;

/// Writes the SDLS joint step for task error `e` into `out`. `a` is `J Jᵀ` (with a unit
/// diagonal entry in the unused orientation row when there is no orientation goal; that
/// direction has `uₖ · e = 0` and adds nothing). Singular values below `threshold` are dropped.
pub(super) fn joint_step(a: &Matrix3<f64>, j: &Matrix3xX<f64>, e: &Vector3<f64>, threshold: f64, out: &mut [f64]) {
    out.fill(0.0);
    let eig = SymmetricEigen::new(*a);
    let floor = threshold * threshold;
    let block_norm = |v: nalgebra::VectorView3<f64>| math::hypot(v[0], v[1]) + v[2].abs();
    for (k, &mu) in eig.eigenvalues.iter().enumerate() {
        if mu <= floor {
            continue;
        }
        let u: Vector3<f64> = eig.eigenvectors.column(k).into();
        let alpha = u.dot(e);
        if alpha == 0.0 {
            continue;
        }
        let sigma = mu.sqrt();
        // vⱼₖ = (Jⱼ · uₖ) / σₖ; φₖ = α vₖ / σₖ.
        let mut m = 0.0;
        let mut largest: f64 = 0.0;
        for col in j.column_iter() {
            let v = col.dot(&u) / sigma;
            m += v.abs() * block_norm(col);
            largest = largest.max((alpha * v / sigma).abs());
        }
        m /= sigma;
        let n = math::hypot(u[0], u[1]) + u[2].abs();
        let gamma = if m > n { GAMMA_MAX * n / m } else { GAMMA_MAX };
        let shrink = if largest > gamma { gamma / largest } else { 1.0 };
        for (o, col) in out.iter_mut().zip(j.column_iter()) {
            *o += shrink * alpha * col.dot(&u) / mu;
        }
    }
    let largest = out.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest > GAMMA_MAX {
        let shrink = GAMMA_MAX / largest;
        out.iter_mut().for_each(|x| *x *= shrink);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn jjt(j: &Matrix3xX<f64>) -> Matrix3<f64> {
        j * j.transpose()
    }

    #[test]
    fn equals_the_pseudoinverse_step_when_nothing_is_clamped() {
        // A well-conditioned 3×3 J and a small error: no clamp is active, so the step solves
        // J Δθ = e exactly.
        let j = Matrix3xX::from_column_slice(&[1.0, 0.2, 0.0, -0.3, 1.1, 0.1, 0.2, 0.1, 0.9]);
        let e = Vector3::new(0.01, -0.02, 0.005);
        let mut out = [0.0; 3];
        joint_step(&jjt(&j), &j, &e, 1e-9, &mut out);
        let moved = &j * nalgebra::DVector::from_column_slice(&out);
        assert!((moved - e).norm() < 1e-12, "{moved}");
    }

    #[test]
    fn clamps_a_nearly_singular_direction() {
        // The second column is almost parallel to the first: σ₂ is tiny, the pseudoinverse
        // step is huge, SDLS keeps every component within π/4.
        let j = Matrix3xX::from_column_slice(&[1.0, 0.0, 0.0, 1.0, 1e-4, 0.0]);
        let mut a = jjt(&j);
        a[(2, 2)] = 1.0;
        let e = Vector3::new(0.0, 1.0, 0.0);
        let mut out = [0.0; 2];
        joint_step(&a, &j, &e, 1e-9, &mut out);
        // The pseudoinverse step would turn the joints by ±10⁴ rad; here the tip moves at most
        // σ₂ per radian along that direction, so Mₖ ≈ 2·10⁴ and γₖ = (π/4)/Mₖ ≈ 4·10⁻⁵ (plus the
        // small share of e along the well-conditioned direction).
        let largest = out.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(largest <= 1e-4 && largest > 1e-5, "{out:?}");
        // It moves the tip toward the goal.
        let moved = &j * nalgebra::DVector::from_column_slice(&out);
        assert!(moved.dot(&e) > 0.0);
    }
}
