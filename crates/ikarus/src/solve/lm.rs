//! Levenberg–Marquardt step (Levenberg 1944; Marquardt 1963), with Nielsen's damping update
//! (Nielsen 1999): `Δθ = Jᵀ (J Jᵀ + μ I)⁻¹ e`.
//!
//! The step is the damped least-squares step with λ² = μ, but μ adapts after every trial: a
//! step that passes the sufficient-decrease test multiplies μ by
//! `max(1/3, 1 − (2ρ − 1)³)`, where `ρ` is the achieved over the predicted decrease, and resets
//! the growth factor ν to 2; a rejected step multiplies μ by ν and doubles ν. Far from the goal
//! μ grows and the step turns towards steepest descent; near it μ shrinks and the step becomes
//! Gauss–Newton's, which converges quadratically. μ starts at
//! [`SolveOptions::lambda`](super::SolveOptions::lambda)².

use nalgebra::{Matrix3, Vector3};

use super::dls;

/// Levenberg–Marquardt's damping state: μ and its growth factor ν.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Damping {
    mu: f64,
    nu: f64,
}

impl Damping {
    /// μ = λ², ν = 2.
    #[inline]
    pub(super) fn new(lambda: f64) -> Self {
        Self { mu: lambda * lambda, nu: 2.0 }
    }

    /// The damping `mu` with growth factor `nu`, where an attempt left off.
    #[inline]
    pub(super) fn resume(mu: f64, nu: f64) -> Self {
        Self { mu, nu }
    }

    /// The damping μ.
    #[inline]
    pub(super) fn mu(&self) -> f64 {
        self.mu
    }

    /// An accepted step that lowered the error by `decrease` where the linearisation predicted
    /// `expected`: μ shrinks by Nielsen's rule, ν resets.
    #[inline]
    pub(super) fn accept(&mut self, decrease: f64, expected: f64) {
        let rho = if expected > 0.0 { decrease / expected } else { 1.0 };
        // (2ρ − 1)³ as two multiplications: powi leaves its lowering to the compiler.
        let r = 2.0 * rho - 1.0;
        self.mu *= (1.0 - r * r * r).max(1.0 / 3.0);
        self.nu = 2.0;
    }

    /// A rejected step: μ grows by ν, and ν doubles.
    #[inline]
    pub(super) fn reject(&mut self) {
        self.mu *= self.nu;
        self.nu *= 2.0;
    }
}

/// `y = (A + μ I)⁻¹ e` (see [`dls::task_step`], called with λ = √μ).
#[inline]
pub(super) fn task_step(a: &Matrix3<f64>, e: &Vector3<f64>, mu: f64, threshold: f64) -> Vector3<f64> {
    dls::task_step(a, e, mu.sqrt(), threshold)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nielsen_update() {
        let mut d = Damping::new(0.1);
        assert!((d.mu() - 0.01).abs() < 1e-17);
        d.reject();
        d.reject();
        // μ · 2 · 4
        assert!((d.mu() - 0.08).abs() < 1e-15);
        // ρ = 1: the largest shrink, by 3.
        d.accept(1.0, 1.0);
        assert!((d.mu() - 0.08 / 3.0).abs() < 1e-15);
        d.reject();
        assert!((d.mu() - 0.16 / 3.0).abs() < 1e-15, "ν was reset to 2");
        // ρ = 1/2: the factor is 1.
        let before = d.mu();
        d.accept(0.5, 1.0);
        assert_eq!(d.mu(), before);
    }

    #[test]
    fn the_step_is_dls_with_lambda_squared_mu() {
        let a = Matrix3::new(4.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0);
        let e = Vector3::new(0.3, -0.7, 0.0);
        let y = task_step(&a, &e, 0.25, 1e-9);
        assert!(((a + Matrix3::identity() * 0.25) * y - e).norm() < 1e-12);
    }
}
