//! Angle arithmetic, in one place: wrapping into `[−π, π)`, the 2π-equivalent of an angle
//! nearest a reference (optionally inside a range), the end of a range nearer an angle around
//! the circle, the unit vector of a direction, and degrees from the edges turned into radians
//! without losing the angle ([`radians_from_degrees`], [`degrees_within`]).
//!
//! A joint angle and every `angle + 2πk` put the link in the same place; the solvers pick the
//! equivalent that keeps a joint within its limits, or nearest where it was, so that it never
//! jumps by a whole turn. Every function here is the single home of its formula: the closed
//! form, CCD, FABRIK, the solver loop and the workspace sampler all call these.

use std::f64::consts::{PI, TAU};

use crate::math;

/// `angle` wrapped into [−π, π).
#[inline]
#[must_use]
pub fn wrap_angle(angle: f64) -> f64 {
    // `(angle + π).rem_euclid(2π) − π`, bit for bit, without the division where `angle + π` is
    // within a turn of [0, 2π): there the remainder is exact (`fmod` is; `y − 2π` is exact by
    // Sterbenz's lemma for y in [2π, 4π)), and for y in (−2π, 0) `rem_euclid` itself adds 2π
    // to y. `fmod` was a third of a 20-link plan's time, spent in this function.
    let y = angle + PI;
    let r = if (0.0..TAU).contains(&y) {
        y
    } else if (TAU..2.0 * TAU).contains(&y) {
        y - TAU
    } else if y > -TAU && y < 0.0 {
        y + TAU
    } else {
        y.rem_euclid(TAU)
    };
    r - PI
}

/// The equivalent `angle + 2πk` (k an integer) nearest `reference`.
///
/// Infinite when the shift overflows (only for angles near the end of the f64 range); callers
/// that must stay finite fall back on `angle` then.
#[inline]
#[must_use]
pub fn nearest_equivalent(angle: f64, reference: f64) -> f64 {
    angle + TAU * ((reference - angle) / TAU).round()
}

/// The equivalent `angle + 2πk` inside `[lo, hi]` nearest `reference`, or `None` if no
/// equivalent lies inside (also for NaN, which only absurdly large angles can produce).
///
/// `k` is the integer nearest `(reference − angle) / 2π`, clamped to the integers whose
/// equivalents lie in the range; the result can round a hair past an end, so callers with a
/// [`JointLimits`](crate::JointLimits) clamp it (as
/// [`JointLimits::nearest_equivalent`](crate::JointLimits::nearest_equivalent) does).
#[inline]
#[must_use]
pub fn nearest_equivalent_in(angle: f64, reference: f64, lo: f64, hi: f64) -> Option<f64> {
    let lowest = ((lo - angle) / TAU).ceil();
    let highest = ((hi - angle) / TAU).floor();
    // `lowest <= highest` is also false for NaN.
    if lowest <= highest {
        Some(angle + TAU * ((reference - angle) / TAU).round().max(lowest).min(highest))
    } else {
        None
    }
}

/// The end of `[lo, hi]` nearer `angle` around the circle (each distance wrapped into
/// `[−π, π)` before comparing); `lo` on a tie.
///
/// Where no equivalent of `angle` lies in the range, a cost that grows with the circular
/// distance from `angle` is lowest at this end.
#[inline]
#[must_use]
pub fn nearer_end(angle: f64, lo: f64, hi: f64) -> f64 {
    if wrap_angle(lo - angle).abs() <= wrap_angle(hi - angle).abs() { lo } else { hi }
}

/// The unit vector `(cos angle, sin angle)`.
#[inline]
#[must_use]
pub fn direction(angle: f64) -> [f64; 2] {
    let (s, c) = math::sin_cos(angle);
    [c, s]
}

/// `degrees` wrapped into (−180°, 180°], exactly.
///
/// The remainder `degrees % 360` of two floats is exact, and so is the one shift by 360 that
/// may follow (Sterbenz), so every finite angle keeps its direction: 1e20° is 1e20 − 360k for
/// the right integer k, which a reduction in radians by an inexact 2π would miss by far more
/// than a degree. NaN and infinities stay NaN.
#[inline]
#[must_use]
pub fn wrap_degrees(degrees: f64) -> f64 {
    let r = degrees % 360.0;
    if r > 180.0 {
        r - 360.0
    } else if r <= -180.0 {
        r + 360.0
    } else {
        r
    }
}

/// An angle from the edges (flags, files, requests), in degrees, as radians in (−π, π]:
/// [`wrap_degrees`] first, exactly, then the conversion. For angles whose turn means nothing
/// (orientations of a goal, joints without limits); a joint with limits takes
/// [`degrees_within`] first.
#[inline]
#[must_use]
pub fn radians_from_degrees(degrees: f64) -> f64 {
    wrap_degrees(degrees).to_radians()
}

/// The angle, in degrees, that a joint limited to `[lo, hi]` degrees takes for `degrees`:
/// `degrees` itself if it lies inside (the range says which turn it is on), else its
/// 360°-equivalent inside the range nearest it, or `None` if no equivalent lies inside.
///
/// Computed from [`wrap_degrees`] plus a whole number of turns, so it is exact for any
/// `degrees` and ranges of ordinary size (1e20° with limits [0°, 45°] is its own 1e20 mod 360).
#[must_use]
pub fn degrees_within(degrees: f64, lo: f64, hi: f64) -> Option<f64> {
    if lo <= degrees && degrees <= hi {
        return Some(degrees);
    }
    let w = wrap_degrees(degrees);
    let lowest = ((lo - w) / 360.0).ceil();
    let highest = ((hi - w) / 360.0).floor();
    // `lowest <= highest` is also false for NaN.
    if lowest <= highest {
        let k = ((degrees - w) / 360.0).round().max(lowest).min(highest);
        Some((w + 360.0 * k).clamp(lo, hi))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degrees_wrap_exactly() {
        for (d, want) in [
            (0.0, 0.0),
            (180.0, 180.0),
            (-180.0, 180.0),
            (190.0, -170.0),
            (-190.0, 170.0),
            (360.0, 0.0),
            (725.5, 5.5),
            (-725.5, -5.5),
            // 1e20 = 360 · 277777777777777777 + 280, and 280° is −80°.
            (1e20, -80.0),
            (-1e20, 80.0),
        ] {
            assert_eq!(wrap_degrees(d), want, "{d}");
        }
        let w = wrap_degrees(1e300);
        assert!(w > -180.0 && w <= 180.0, "{w}");
        assert!(wrap_degrees(f64::NAN).is_nan() && wrap_degrees(f64::INFINITY).is_nan());
        assert_eq!(radians_from_degrees(-180.0), PI);
        assert_eq!(radians_from_degrees(1e20), (-80f64).to_radians());
    }

    #[test]
    fn degrees_within_a_range_keep_their_turn_or_take_the_one_inside() {
        // Inside: as written, even on another turn.
        assert_eq!(degrees_within(400.0, -720.0, 720.0), Some(400.0));
        assert_eq!(degrees_within(5.0, 10.0, 45.0), None);
        // Outside: the equivalent inside, nearest the angle as written.
        assert_eq!(degrees_within(370.0, 0.0, 45.0), Some(10.0));
        assert_eq!(degrees_within(-350.0, 0.0, 45.0), Some(10.0));
        assert_eq!(degrees_within(1e20, -90.0, 0.0), Some(-80.0));
        assert_eq!(degrees_within(1e20, 200.0, 300.0), Some(280.0));
        assert_eq!(degrees_within(1000.0, -720.0, 720.0), Some(640.0));
        assert_eq!(degrees_within(1e300, 10.0, 20.0).is_some(), (10.0..=20.0).contains(&wrap_degrees(1e300)));
        assert_eq!(degrees_within(f64::NAN, 0.0, 45.0), None);
    }

    #[test]
    fn wrap_angle_is_the_remainder_bit_for_bit() {
        let reference = |a: f64| (a + PI).rem_euclid(TAU) - PI;
        let mut rng = crate::rng::SplitMix64(7);
        let mut cases: Vec<f64> = (0..200_000).map(|_| (rng.unit() - 0.5) * 40.0).collect();
        for edge in [-3.0 * TAU, -2.0 * TAU, -TAU, -PI, 0.0, PI, TAU, 2.0 * TAU - PI, 3.0 * TAU, 1e300, -1e300] {
            for d in [-1e-12, 0.0, 1e-12] {
                cases.push(edge + d);
                cases.push(f64::from_bits((edge + d).to_bits() + 1));
                cases.push(f64::from_bits((edge + d).to_bits().saturating_sub(1)));
            }
        }
        cases.extend([-0.0, f64::INFINITY, f64::NEG_INFINITY]);
        for a in cases {
            assert_eq!(wrap_angle(a).to_bits(), reference(a).to_bits(), "{a:e}");
        }
        assert!(wrap_angle(f64::NAN).is_nan());
    }

    #[test]
    fn wrap_angle_lands_in_half_open_range() {
        for a in [-10.0, -PI, -1.0, 0.0, 1.0, PI, 10.0, 3.0 * TAU + 0.5] {
            let w = wrap_angle(a);
            assert!((-PI..PI).contains(&w), "{a} -> {w}");
            assert!(((a - w) / TAU - ((a - w) / TAU).round()).abs() < 1e-12, "{a} -> {w}");
        }
        assert_eq!(wrap_angle(PI), -PI);
    }

    #[test]
    fn nearest_equivalents() {
        assert!((nearest_equivalent(0.5, 13.0) - (0.5 + 2.0 * TAU)).abs() < 1e-12);
        assert!((nearest_equivalent(0.5 + TAU, -0.2) - 0.5).abs() < 1e-12);
        // Inside a range far from [−π, π), and nearest the reference when several are.
        assert!((nearest_equivalent_in(-0.5, 0.0, 5.0, 6.0).unwrap() - (TAU - 0.5)).abs() < 1e-12);
        assert!((nearest_equivalent_in(0.5, 6.0, -10.0, 10.0).unwrap() - (0.5 + TAU)).abs() < 1e-12);
        assert_eq!(nearest_equivalent_in(3.0, 0.0, -3.0, 1.0), None);
        assert_eq!(nearest_equivalent_in(f64::NAN, 0.0, -3.0, 1.0), None);
    }

    #[test]
    fn nearer_end_goes_around_the_circle() {
        // 3.0 is nearer −3.0 (0.28 apart across ±π) than 1.0.
        assert_eq!(nearer_end(3.0, -3.0, 1.0), -3.0);
        assert_eq!(nearer_end(1.5, -3.0, 1.0), 1.0);
        assert_eq!(nearer_end(-1.0, -2.0, 0.0), -2.0);
    }

    #[test]
    fn direction_is_a_unit_vector() {
        let [x, y] = direction(PI / 2.0);
        assert!(x.abs() < 1e-15 && (y - 1.0).abs() < 1e-15);
    }
}
