//! The step rules that use the Jacobian, and what they share: `A = J Jᵀ` and the joint step
//! `Δθ = J_wᵀ y` from a rule's task-space vector `y` (see the [module docs](super)).

use nalgebra::{Matrix3, Matrix3xX, Vector3};

use super::{Method, SolveOptions, dls, lm, pinv, sdls, transpose};

/// A Jacobian step rule: one file each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Rule {
    /// [`transpose`]: `y = α e`.
    Transpose,
    /// [`pinv`]: `y = A⁺ e`.
    PseudoInverse,
    /// [`dls`]: `y = (A + λ² I)⁻¹ e`.
    DampedLeastSquares,
    /// [`sdls`]: each singular direction clamped separately.
    SelectivelyDamped,
    /// [`lm`]: `y = (A + μ I)⁻¹ e`, μ adapted.
    LevenbergMarquardt,
}

/// How the loop moves the chain: a Jacobian rule with the line search, or one of the methods
/// that work without `J`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Stepper {
    /// A Jacobian rule.
    Jacobian(Rule),
    /// One CCD sweep per iteration.
    Ccd,
    /// One FABRIK iteration.
    Fabrik,
}

impl Stepper {
    /// The iteration of `method`. [`Method::Analytic`] iterates with damped least squares where
    /// its closed form has no answer (within the limits, or at all).
    #[inline]
    pub(super) fn of(method: Method) -> Self {
        match method {
            Method::Transpose => Stepper::Jacobian(Rule::Transpose),
            Method::PseudoInverse => Stepper::Jacobian(Rule::PseudoInverse),
            Method::DampedLeastSquares => Stepper::Jacobian(Rule::DampedLeastSquares),
            Method::SelectivelyDamped => Stepper::Jacobian(Rule::SelectivelyDamped),
            Method::LevenbergMarquardt => Stepper::Jacobian(Rule::LevenbergMarquardt),
            Method::Analytic => Stepper::Jacobian(Rule::DampedLeastSquares),
            Method::CyclicCoordinateDescent => Stepper::Ccd,
            Method::Fabrik => Stepper::Fabrik,
        }
    }
}

/// `A = J Jᵀ`, summed column by column (the 3×3 product written out: this runs every iteration
/// and nalgebra's general product of a 3×N matrix with its transpose is several times slower).
/// Without an orientation goal the third row of `J` is zero and `A`'s unused diagonal entry is
/// set to 1, so that every rule's third component of `y` is exactly 0.
#[inline]
pub(super) fn gram(j: &Matrix3xX<f64>, oriented: bool) -> Matrix3<f64> {
    let (mut xx, mut xy, mut xz, mut yy, mut yz, mut zz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for c in j.column_iter() {
        let (x, y, z) = (c[0], c[1], c[2]);
        xx += x * x;
        xy += x * y;
        xz += x * z;
        yy += y * y;
        yz += y * z;
        zz += z * z;
    }
    if !oriented {
        zz = 1.0;
    }
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// The linear system a step solves: the weighted Jacobian `J_w`, `A = J_w J_wᵀ` (see
/// [`gram`]) and the task error `e`.
#[derive(Clone, Copy)]
pub(super) struct System<'a> {
    pub(super) a: &'a Matrix3<f64>,
    pub(super) weighted: &'a Matrix3xX<f64>,
    pub(super) e: &'a Vector3<f64>,
}

/// The step of a Jacobian `rule` in weighted joint coordinates: `J_wᵀ y` for the task-space
/// rules, the selectively damped step for SDLS. `mu` is Levenberg–Marquardt's damping.
#[inline]
pub(super) fn method_step(rule: Rule, opts: &SolveOptions, oriented: bool, sys: System<'_>, mu: f64, out: &mut [f64]) {
    let System { a, weighted, e } = sys;
    // A position goal: the damped rules solve the 2×2 system of the x and y rows.
    let damping = match rule {
        Rule::DampedLeastSquares => Some(opts.lambda * opts.lambda),
        Rule::LevenbergMarquardt => Some(mu),
        Rule::Transpose | Rule::PseudoInverse | Rule::SelectivelyDamped => None,
    };
    if let (false, Some(damping)) = (oriented, damping) {
        if let Some((y0, y1)) = damped_2x2(a[(0, 0)], a[(0, 1)], a[(1, 1)], e[0], e[1], damping) {
            for (o, col) in out.iter_mut().zip(weighted.column_iter()) {
                *o = col[0] * y0 + col[1] * y1;
            }
            return;
        }
    }
    let y = match rule {
        Rule::Transpose => transpose::task_step(a, e),
        Rule::PseudoInverse => pinv::task_step(a, e, opts.singular_threshold),
        Rule::DampedLeastSquares => dls::task_step(a, e, opts.lambda, opts.singular_threshold),
        Rule::LevenbergMarquardt => lm::task_step(a, e, mu, opts.singular_threshold),
        Rule::SelectivelyDamped => return sdls::joint_step(a, weighted, e, opts.singular_threshold, out),
    };
    for (o, col) in out.iter_mut().zip(weighted.column_iter()) {
        *o = col.dot(&y);
    }
}

/// `y = (A + d I)⁻¹ e` for a position goal's 2×2 `A = [[xx, xy], [xy, yy]]`, by Cramer's rule,
/// or `None` where the damped least-squares rule takes the pseudoinverse instead: `d` at most
/// `1e-12·trace(A)` (the damping is then no damping at all), or a zero determinant.
///
/// The position-only fast path of every damped solve (the 3×3 system with the orientation row
/// set to the identity has the same solution in exact arithmetic; this one is a third of the
/// work and rounds differently in the last bits). [`super::fast`] runs these same operations.
#[inline(always)]
pub(super) fn damped_2x2(xx: f64, xy: f64, yy: f64, e0: f64, e1: f64, d: f64) -> Option<(f64, f64)> {
    // (Written so that a NaN declines too.)
    if d.partial_cmp(&(1e-12 * (xx + yy))) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let (a, c) = (xx + d, yy + d);
    let det = a * c - xy * xy;
    if det == 0.0 {
        return None;
    }
    Some(((c * e0 - xy * e1) / det, (a * e1 - xy * e0) / det))
}
