//! Joint limits: the range of one joint ([`JointLimits`]) and the limits a solve enforces, as
//! one borrowed view over a chain's joints ([`Bounds`]).
//!
//! A solve decides once whether it respects the chain's limits (it does unless its
//! [`LimitMode`](crate::LimitMode) is [`Ignore`](crate::LimitMode::Ignore)) and passes the
//! view to every step: a joint without a bound is free, and an empty view frees them all.

use crate::number::Num;
use thiserror::Error;

use crate::angle;

/// A closed range `[min, max]` of allowed joint angles, in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointLimits {
    min: f64,
    max: f64,
}

impl JointLimits {
    /// Builds a range, checking that both ends are finite and `min ≤ max`.
    pub fn new(min: f64, max: f64) -> Result<Self, LimitsError> {
        if !min.is_finite() {
            return Err(LimitsError::NonFinite { end: "min", value: min });
        }
        if !max.is_finite() {
            return Err(LimitsError::NonFinite { end: "max", value: max });
        }
        if min > max {
            return Err(LimitsError::Inverted { min, max });
        }
        Ok(Self { min, max })
    }

    /// The lower end, in radians.
    #[must_use]
    pub fn min(&self) -> f64 {
        self.min
    }

    /// The upper end, in radians.
    #[must_use]
    pub fn max(&self) -> f64 {
        self.max
    }

    /// Whether `angle` lies in `[min, max]`.
    #[must_use]
    pub fn contains(&self, angle: f64) -> bool {
        self.min <= angle && angle <= self.max
    }

    /// `angle` moved to the nearest end of the range if it lies outside.
    #[must_use]
    pub fn clamp(&self, angle: f64) -> f64 {
        angle.clamp(self.min, self.max)
    }

    /// The 2π-equivalent of `angle` inside the range nearest `reference` (clamped onto the
    /// range, since the shift can round a hair past an end), or `None` if no equivalent lies
    /// inside. See [`angle::nearest_equivalent_in`].
    #[inline]
    #[must_use]
    pub fn nearest_equivalent(&self, angle: f64, reference: f64) -> Option<f64> {
        angle::nearest_equivalent_in(angle, reference, self.min, self.max).map(|a| self.clamp(a))
    }

    /// The end of the range nearer `angle` around the circle; `min` on a tie. See
    /// [`angle::nearer_end`].
    #[inline]
    #[must_use]
    pub fn nearer_end(&self, angle: f64) -> f64 {
        angle::nearer_end(angle, self.min, self.max)
    }
}

/// Why a [`JointLimits`] could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum LimitsError {
    /// One end of the range is NaN or infinite.
    #[error("{end} must be a finite number, got {}", Num(*.value))]
    NonFinite {
        /// `"min"` or `"max"`.
        end: &'static str,
        /// The offending value.
        value: f64,
    },
    /// `min > max`.
    #[error("min must not exceed max, got [{}, {}]", Num(*.min), Num(*.max))]
    Inverted {
        /// The lower end given.
        min: f64,
        /// The upper end given.
        max: f64,
    },
}
/// The limits a computation enforces: the chain's [`JointLimits`], or none.
///
/// Build it with [`Chain::bounds`](crate::Chain::bounds) (every limited joint enforced) or [`Bounds::free`] (none).
/// Indexing past the end gives no bound, so the free view works for chains of any length.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Bounds<'a> {
    limits: &'a [Option<JointLimits>],
}

impl<'a> Bounds<'a> {
    /// No joint is bounded.
    #[must_use]
    pub fn free() -> Self {
        Self { limits: &[] }
    }

    /// A view over per-joint limits (joint `i` bounded by `limits[i]`).
    #[must_use]
    pub fn new(limits: &'a [Option<JointLimits>]) -> Self {
        Self { limits }
    }

    /// Whether no joint is bounded.
    #[must_use]
    pub fn is_free(&self) -> bool {
        self.limits.is_empty()
    }

    /// The bound of joint `i`, if any.
    #[inline]
    #[must_use]
    pub fn get(&self, i: usize) -> Option<JointLimits> {
        self.limits.get(i).copied().flatten()
    }

    /// `angle` clamped into the bound of joint `i` (unchanged when it has none).
    #[inline]
    #[must_use]
    pub fn clamp(&self, i: usize, angle: f64) -> f64 {
        match self.get(i) {
            Some(lim) => lim.clamp(angle),
            None => angle,
        }
    }

    /// Where `values` (one per joint, from the first) first break these bounds: a value that is
    /// not finite, or one outside its joint's range. The one walk behind the validation of a
    /// chain's poses and a skeleton's, each of which names what it finds in its own words
    /// (`links[i]`, `bones[i] ("name")`).
    pub(crate) fn first_violation(&self, values: &[f64]) -> Option<Violation> {
        for (index, &value) in values.iter().enumerate() {
            if !value.is_finite() {
                return Some(Violation::NonFinite { index, value });
            }
            if let Some(limits) = self.get(index) {
                if !limits.contains(value) {
                    return Some(Violation::Outside { index, value, limits });
                }
            }
        }
        None
    }

    /// Every angle of `angles` clamped into its joint's bound.
    #[inline]
    pub fn clamp_into(&self, angles: &mut [f64]) {
        for (a, lim) in angles.iter_mut().zip(self.limits) {
            if let Some(lim) = lim {
                *a = lim.clamp(*a);
            }
        }
    }
}

/// The first joint value that [`Bounds::first_violation`] found wrong.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Violation {
    /// Joint `index`'s value is NaN or infinite.
    NonFinite { index: usize, value: f64 },
    /// Joint `index`'s value lies outside its `limits`.
    Outside { index: usize, value: f64, limits: JointLimits },
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::{Chain, Link};

    #[test]
    fn a_view_of_the_chain_or_nothing() {
        let lim = JointLimits::new(-0.5, 0.5).unwrap();
        let chain = Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0).with_limits(lim), Link::new(1.0, 0.0)]).unwrap();
        let b = chain.bounds();
        assert!(!b.is_free());
        assert_eq!((b.get(0), b.get(1), b.get(7)), (Some(lim), None, None));
        assert_eq!((b.clamp(0, 2.0), b.clamp(1, 2.0)), (0.5, 2.0));
        let mut angles = [-3.0, -3.0];
        b.clamp_into(&mut angles);
        assert_eq!(angles, [-0.5, -3.0]);
        let free = Bounds::free();
        assert!(free.is_free() && free.get(0).is_none() && free.clamp(0, 9.0) == 9.0);
        assert!(chain.without_limits().bounds().is_free());
    }

    #[test]
    fn the_first_violation_is_the_first_joint_that_breaks_its_bound() {
        let lim = JointLimits::new(-0.5, 0.5).unwrap();
        let limits = [Some(lim), None, Some(lim)];
        let b = Bounds::new(&limits);
        assert_eq!(b.first_violation(&[0.5, 9.0, -0.5]), None);
        assert_eq!(b.first_violation(&[0.5, 9.0, 0.7]), Some(Violation::Outside { index: 2, value: 0.7, limits: lim }));
        // A value that is not finite is named as such even where it is also outside a bound,
        // and an earlier joint comes first.
        let nan = b.first_violation(&[0.0, f64::INFINITY, f64::NAN]);
        assert_eq!(nan, Some(Violation::NonFinite { index: 1, value: f64::INFINITY }));
        assert!(matches!(b.first_violation(&[f64::NAN]), Some(Violation::NonFinite { index: 0, .. })));
        assert_eq!(Bounds::free().first_violation(&[1e300, -1e300]), None);
    }
}
