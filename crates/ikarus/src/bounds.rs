//! [`Bounds`]: the joint limits a solve enforces, as one borrowed view.
//!
//! A solve decides once whether it respects the chain's limits (it does unless its
//! [`LimitMode`](crate::LimitMode) is [`Ignore`](crate::LimitMode::Ignore)) and passes the
//! view to every step: a joint without a bound is free, and an empty view frees them all.

use crate::chain::{Chain, JointLimits};

/// The limits a computation enforces: the chain's [`JointLimits`], or none.
///
/// Build it with [`Chain::bounds`] (every limited joint enforced) or [`Bounds::free`] (none).
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

    /// The limits of `chain`, or [`Bounds::free`] if no joint of it has limits.
    #[must_use]
    pub fn of(chain: &'a Chain) -> Self {
        if chain.has_limits() { Self { limits: chain.limits() } } else { Self::free() }
    }

    /// A view over per-joint limits (for a chain under construction).
    pub(crate) fn of_limits(limits: &'a [Option<JointLimits>]) -> Self {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::Link;

    #[test]
    fn a_view_of_the_chain_or_nothing() {
        let lim = JointLimits::new(-0.5, 0.5).unwrap();
        let chain = Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0).with_limits(lim), Link::new(1.0, 0.0)]).unwrap();
        let b = Bounds::of(&chain);
        assert!(!b.is_free());
        assert_eq!((b.get(0), b.get(1), b.get(7)), (Some(lim), None, None));
        assert_eq!((b.clamp(0, 2.0), b.clamp(1, 2.0)), (0.5, 2.0));
        let mut angles = [-3.0, -3.0];
        b.clamp_into(&mut angles);
        assert_eq!(angles, [-0.5, -3.0]);
        let free = Bounds::free();
        assert!(free.is_free() && free.get(0).is_none() && free.clamp(0, 9.0) == 9.0);
        assert!(Bounds::of(&chain.without_limits()).is_free());
    }
}
