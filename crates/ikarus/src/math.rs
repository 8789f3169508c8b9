//! The transcendental functions the library computes, from one implementation on every target.
//!
//! The library promises the same output, bit for bit, for the same input, wherever it runs.
//! `f64::sin`, `f64::atan2`, `f64::hypot`, … call the platform's maths library (glibc on Linux,
//! the system's on macOS and Windows, a port of musl's on wasm32), and those differ in the last
//! bit on some arguments (glibc's `sin_cos` and the [`libm`] crate's `sincos` differ on 250 of
//! 4096 arguments tried). So every such function goes through here, to the `libm` crate (the
//! Rust port of musl's and FreeBSD's msun maths, in plain Rust arithmetic), whose results
//! depend only on the argument, on every target. `clippy.toml` beside the crate's `Cargo.toml` forbids the `f64`
//! methods in the crate, so that none slips back in.
//!
//! What stays with `f64`: `sqrt`, `abs`, `floor`, `ceil`, `round`, `trunc`, `mul_add`,
//! `min`, `max`, `copysign`, `rem_euclid`, `to_degrees`, `to_radians` give the same bits on
//! every target (IEEE 754 requires `sqrt`, `mul_add`, `%` and the four operations correctly
//! rounded; the rest are bit operations or one such operation). `powi` does not: its lowering
//! is the compiler's to choose, so squares are [`square`] and other powers use [`powf`].

/// Sine and cosine of `x` (radians) from one argument reduction: `(sin x, cos x)`.
///
/// Arguments of any size are reduced exactly modulo `π/2` (Payne–Hanek for the large ones),
/// so `sin_cos(1e22)` is the sine and cosine of that double itself, not of its distance to a
/// rounded multiple of `π`.
#[inline]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// Sine of `x` (radians). Where the cosine is needed too, [`sin_cos`] shares the reduction.
#[inline]
pub(crate) fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// Cosine of `x` (radians).
#[inline]
pub(crate) fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// The angle of the point `(x, y)` from the positive x axis, in `[−π, π]`: `atan2(y, x)`,
/// the argument order of `f64::atan2` called as `y.atan2(x)`.
#[inline]
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// Arcsine of `x`, in `[−π/2, π/2]`; NaN outside `[−1, 1]`.
#[inline]
pub(crate) fn asin(x: f64) -> f64 {
    libm::asin(x)
}

/// Arccosine of `x`, in `[0, π]`; NaN outside `[−1, 1]`.
#[inline]
pub(crate) fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// `√(x² + y²)` without overflow or underflow in the squares: the length of `(x, y)` for any
/// finite components (infinite if either is infinite, even with a NaN).
#[inline]
pub(crate) fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// The length of `(dx, dy)`: `√(dx² + dy²)`, or [`hypot`] where the sum of squares would
/// overflow or lose precision below the smallest normal number (so that a goal 1e200 away is
/// 1e200 away, not infinitely far, and 1e-170 away is not 0). Saturates at `f64::MAX` if the
/// length itself is beyond the f64 range, so that it is always a finite number. Every distance
/// the library reports (a solve's, a track sample's error) is this one.
#[inline]
pub(crate) fn distance(dx: f64, dy: f64) -> f64 {
    let squared = dx * dx + dy * dy;
    let d = if squared.is_finite() && squared >= f64::MIN_POSITIVE { squared.sqrt() } else { hypot(dx, dy) };
    d.min(f64::MAX)
}

/// [`distance`] from `a` to `b`.
#[inline]
pub(crate) fn distance_between(a: nalgebra::Point2<f64>, b: nalgebra::Point2<f64>) -> f64 {
    distance(b.x - a.x, b.y - a.y)
}

/// `eˣ`.
#[inline]
pub(crate) fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// `xʸ` for real `y`, with C's rules for the special cases (`x⁰ = 1`, negative `x` only with
/// an integer `y`).
#[inline]
pub(crate) fn powf(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// `x²`, as the one multiplication `x · x` (correctly rounded, so the same everywhere), where
/// `x.powi(2)` leaves the lowering to the compiler.
#[inline]
pub(crate) fn square(x: f64) -> f64 {
    x * x
}

#[cfg(test)]
mod tests {
    //! The expected values are the correctly rounded results (the nearest double to the exact
    //! value of the function at the double argument, computed with 300-bit arithmetic), except
    //! where a comment says otherwise, compared bit for bit: a change of implementation that
    //! moves any of them by one ulp is noticed here first.

    use super::*;

    #[test]
    fn sine_and_cosine_are_the_correctly_rounded_values() {
        assert_eq!(sin_cos(1.0), (0.8414709848078965, 0.5403023058681398));
        assert_eq!((sin(1.0), cos(1.0)), sin_cos(1.0));
        assert_eq!(sin_cos(0.5), (0.479425538604203, 0.8775825618903728));
        assert_eq!(sin_cos(-2.0), (-0.9092974268256817, -0.4161468365471424));
        // Large arguments: the reduction modulo π/2 must be exact to get these.
        assert_eq!(sin_cos(1e6), (-0.34999350217129294, 0.9367521275331447));
        assert_eq!(sin_cos(1e22), (-0.8522008497671888, 0.523214785395139));
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert!(sin(-0.0).is_sign_negative());
    }

    #[test]
    fn inverse_functions_are_the_correctly_rounded_values() {
        assert_eq!(atan2(1.0, 2.0), 0.4636476090008061);
        assert_eq!(atan2(-1.0, -1.0), -3.0 * std::f64::consts::FRAC_PI_4);
        assert_eq!(atan2(0.0, -1.0), std::f64::consts::PI);
        assert_eq!(asin(0.5), std::f64::consts::FRAC_PI_6);
        assert_eq!(acos(0.5), std::f64::consts::FRAC_PI_3);
        assert_eq!(acos(-1.0), std::f64::consts::PI);
    }

    #[test]
    fn length_exponential_and_power_are_pinned() {
        assert_eq!(hypot(3.0, 4.0), 5.0);
        assert_eq!(hypot(1.0, 1.0), std::f64::consts::SQRT_2);
        assert_eq!(hypot(1e300, 1e300), 1.4142135623730952e300);
        // libm's `exp` is faithful (error below one ulp), not correctly rounded: e¹ comes out
        // one ulp above the double nearest e (glibc's gives that one). Pinned as it is.
        assert_eq!(exp(1.0), 2.7182818284590455);
        assert_eq!(exp(1.0), f64::from_bits(std::f64::consts::E.to_bits() + 1));
        assert_eq!(exp(-1.0), 0.36787944117144233);
        assert_eq!(powf(10.0, 0.5), 3.1622776601683795);
        assert_eq!(powf(2.0, -3.0), 0.125);
        assert_eq!(powf(3.0, 1.0 / 3.0), 1.4422495703074083);
    }
}
