//! Jacobian pseudoinverse step: `Δθ = J⁺ e = Jᵀ (J Jᵀ)⁺ e`.
//!
//! `A = J Jᵀ` is symmetric positive semi-definite with eigenvalues σₖ², the squared singular
//! values of `J`. Writing `A = U diag(σ²) Uᵀ`, `A⁺ = Σ uₖ uₖᵀ / σₖ²` over the σₖ above the
//! threshold; dropping the rest is the truncated-SVD pseudoinverse, which keeps the step
//! bounded in directions the chain cannot move in (a stretched or folded arm).

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// `y = A⁺ e`, ignoring directions whose singular value is below `threshold`.
pub(super) fn task_step(a: &Matrix3<f64>, e: &Vector3<f64>, threshold: f64) -> Vector3<f64> {
    let eig = SymmetricEigen::new(*a);
    let floor = threshold * threshold;
    let mut y = Vector3::zeros();
    for (k, &mu) in eig.eigenvalues.iter().enumerate() {
        if mu > floor {
            let u = eig.eigenvectors.column(k);
            y += u * (u.dot(e) / mu);
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverts_a_regular_matrix() {
        let a = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let e = Vector3::new(1.0, -2.0, 0.5);
        let y = task_step(&a, &e, 1e-9);
        assert!((a * y - e).norm() < 1e-12);
    }

    #[test]
    fn drops_singular_directions() {
        // Rank one: only the x direction is movable; the y part of e is ignored.
        let a = Matrix3::new(2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-20);
        let y = task_step(&a, &Vector3::new(1.0, 5.0, 3.0), 1e-6);
        assert!((y - Vector3::new(0.5, 0.0, 0.0)).norm() < 1e-12, "{y}");
    }
}
