//! Easing curves: how far along a motion (s, from 0 to 1) the animation is at normalised time t.
//!
//! Every curve maps [0, 1] onto [0, 1] monotonically with `s(0) = 0` and `s(1) = 1` exactly, and
//! gives its velocity `ds/dt` too; t outside [0, 1] is clamped. The velocity is continuous for
//! every curve but [`Ease::Linear`] (which has none to speak of: it is constant 1).
//!
//! | curve | s(t) | ds/dt at 0 and 1 | continuity |
//! | --- | --- | --- | --- |
//! | [`Ease::Linear`] | t | 1, 1 | C^∞ |
//! | [`Ease::Sine`] | (sin(πt − π/2) + 1) / 2 | 0, 0 | C^∞ |
//! | [`Ease::Smoothstep`] | 3t² − 2t³ | 0, 0 | C¹ |
//! | [`Ease::Parent`] | sine pieces around a constant-velocity middle (below) | 0, 0 (if k1 > 0, k2 < 1) | C¹ |

use crate::listed_enum;
use crate::math;
use crate::number::Num;
use std::f64::consts::{FRAC_2_PI, FRAC_PI_2, PI};

use thiserror::Error;

/// An easing curve. Build [`Ease::Parent`] with [`Ease::parent`], which validates k1 and k2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ease {
    /// Constant speed: `s = t`.
    Linear,
    /// Sine ease-in/ease-out: `s = (sin(πt − π/2) + 1) / 2`, `ds/dt = (π/2) sin(πt)`.
    Sine,
    /// Parent's sine ease with a constant-velocity middle ([`ParentEase`]).
    Parent(ParentEase),
    /// Cubic smoothstep: `s = 3t² − 2t³`, `ds/dt = 6t(1 − t)`.
    Smoothstep,
}

/// Parent's sine ease-in/ease-out with a constant-velocity middle (*Computer Animation*, 3rd
/// ed., eq. 3.19), with the seed report's errors corrected: `docs/src/solving/ease.md` derives it.
///
/// Accelerate along a quarter sine until `k1`, cruise at constant speed until `k2`, decelerate
/// along a quarter sine until 1. Before normalisation:
///
/// ```text
/// t ≤ k1:       s = k1·(2/π)·(sin((t/k1)·π/2 − π/2) + 1)
/// k1 ≤ t ≤ k2:  s = 2·k1/π + t − k1
/// t ≥ k2:       s = 2·k1/π + k2 − k1 + (1 − k2)·(2/π)·sin(((t − k2)/(1 − k2))·π/2)
/// ```
///
/// and everything is divided by the total `f = 2·k1/π + (k2 − k1) + 2·(1 − k2)/π`, so s runs
/// from 0 to 1. The unnormalised velocity is `sin(πt / 2k1)`, then 1, then
/// `cos(((t − k2)/(1 − k2))·π/2)`: 1 on both sides of k1 and of k2, so the curve is C¹.
/// `k1 = 0` (no acceleration phase) and `k2 = 1` (no deceleration phase) are handled without
/// dividing by zero; `k1 = 0, k2 = 1` is linear.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParentEase {
    k1: f64,
    k2: f64,
    total: f64,
}

/// Why an ease's parameters are invalid.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum EaseError {
    /// A parameter is NaN, infinite or outside [0, 1].
    #[error("{field}: must be a number in [0, 1], got {}", Num(*.value))]
    OutOfRange {
        /// `"k1"` or `"k2"`.
        field: &'static str,
        /// The offending value.
        value: f64,
    },
    /// `k1 > k2`.
    #[error("k1: must not exceed k2, got k1 = {}, k2 = {}", Num(*.k1), Num(*.k2))]
    Order {
        /// The acceleration end given.
        k1: f64,
        /// The deceleration start given.
        k2: f64,
    },
}

impl ParentEase {
    /// Validates `0 ≤ k1 ≤ k2 ≤ 1`.
    pub fn new(k1: f64, k2: f64) -> Result<Self, EaseError> {
        for (field, value) in [("k1", k1), ("k2", k2)] {
            if !(0.0..=1.0).contains(&value) {
                return Err(EaseError::OutOfRange { field, value });
            }
        }
        if k1 > k2 {
            return Err(EaseError::Order { k1, k2 });
        }
        let total = 2.0 * k1 / PI + (k2 - k1) + 2.0 * (1.0 - k2) / PI;
        Ok(Self { k1, k2, total })
    }

    /// End of the acceleration phase.
    #[must_use]
    pub fn k1(&self) -> f64 {
        self.k1
    }

    /// Start of the deceleration phase.
    #[must_use]
    pub fn k2(&self) -> f64 {
        self.k2
    }

    fn position(&self, t: f64) -> f64 {
        let (k1, k2) = (self.k1, self.k2);
        let s = if t < k1 {
            k1 * FRAC_2_PI * (math::sin(t / k1 * FRAC_PI_2 - FRAC_PI_2) + 1.0)
        } else if t <= k2 {
            2.0 * k1 / PI + t - k1
        } else {
            2.0 * k1 / PI + k2 - k1 + (1.0 - k2) * FRAC_2_PI * math::sin((t - k2) / (1.0 - k2) * FRAC_PI_2)
        };
        s / self.total
    }

    fn velocity(&self, t: f64) -> f64 {
        let (k1, k2) = (self.k1, self.k2);
        let v = if t < k1 {
            math::sin(t / k1 * FRAC_PI_2)
        } else if t <= k2 {
            1.0
        } else {
            math::cos((t - k2) / (1.0 - k2) * FRAC_PI_2)
        };
        v / self.total
    }
}

listed_enum! {
    /// The kinds of [`Ease`], without their parameters: what the edges name.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum EaseKind {
        /// [`Ease::Linear`].
        Linear,
        /// [`Ease::Sine`].
        Sine,
        /// [`Ease::Parent`], with [`DEFAULT_K1`] and [`DEFAULT_K2`] unless told otherwise.
        Parent,
        /// [`Ease::Smoothstep`].
        Smoothstep,
    }
}

/// Parent's ease's default end of acceleration: the seed report's Figures 13 and 14 used 0.3.
pub const DEFAULT_K1: f64 = 0.3;
/// Parent's ease's default start of deceleration: the seed report's Figures 13 and 14 used 0.7.
pub const DEFAULT_K2: f64 = 0.7;

impl EaseKind {
    /// The short name used at the edges: `linear`, `sine`, `parent`, `smoothstep`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            EaseKind::Linear => "linear",
            EaseKind::Sine => "sine",
            EaseKind::Parent => "parent",
            EaseKind::Smoothstep => "smoothstep",
        }
    }

    /// A label for people.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            EaseKind::Linear => "Linear",
            EaseKind::Sine => "Sine",
            EaseKind::Parent => "Parent (k1, k2)",
            EaseKind::Smoothstep => "Smoothstep",
        }
    }

    /// One line saying what the curve does.
    #[must_use]
    pub fn summary(self) -> &'static str {
        match self {
            EaseKind::Linear => "Constant speed",
            EaseKind::Sine => "Sine ease-in/ease-out",
            EaseKind::Parent => "Parent's sine ease with a constant-speed middle between k1 and k2",
            EaseKind::Smoothstep => "Cubic smoothstep",
        }
    }

    /// The curve of this kind; `k1`, `k2` (Parent's alone) default to [`DEFAULT_K1`] and
    /// [`DEFAULT_K2`], and are ignored by the other kinds.
    pub fn ease(self, k1: Option<f64>, k2: Option<f64>) -> Result<Ease, EaseError> {
        Ok(match self {
            EaseKind::Linear => Ease::Linear,
            EaseKind::Sine => Ease::Sine,
            EaseKind::Smoothstep => Ease::Smoothstep,
            EaseKind::Parent => Ease::parent(k1.unwrap_or(DEFAULT_K1), k2.unwrap_or(DEFAULT_K2))?,
        })
    }
}

crate::names::by_name!(EaseKind, "ease");

impl Ease {
    /// The kind of this curve.
    #[must_use]
    pub fn kind(&self) -> EaseKind {
        match self {
            Ease::Linear => EaseKind::Linear,
            Ease::Sine => EaseKind::Sine,
            Ease::Parent(_) => EaseKind::Parent,
            Ease::Smoothstep => EaseKind::Smoothstep,
        }
    }

    /// Parent's ease with acceleration until `k1` and deceleration from `k2`.
    pub fn parent(k1: f64, k2: f64) -> Result<Self, EaseError> {
        ParentEase::new(k1, k2).map(Ease::Parent)
    }

    /// The short name used at the edges: `linear`, `sine`, `parent`, `smoothstep`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }

    /// Position `s(t)` in [0, 1]; `t` is clamped into [0, 1], and `s(0) = 0`, `s(1) = 1` exactly.
    #[must_use]
    pub fn position(&self, t: f64) -> f64 {
        if t.is_nan() || t <= 0.0 {
            return 0.0;
        }
        if t >= 1.0 {
            return 1.0;
        }
        let s = match self {
            Ease::Linear => t,
            Ease::Sine => (math::sin(PI * t - FRAC_PI_2) + 1.0) / 2.0,
            Ease::Parent(p) => p.position(t),
            Ease::Smoothstep => t * t * (3.0 - 2.0 * t),
        };
        s.clamp(0.0, 1.0)
    }

    /// Velocity `ds/dt` at `t` (clamped into [0, 1]).
    #[must_use]
    pub fn velocity(&self, t: f64) -> f64 {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        match self {
            Ease::Linear => 1.0,
            Ease::Sine => FRAC_PI_2 * math::sin(PI * t),
            Ease::Parent(p) => p.velocity(t),
            Ease::Smoothstep => 6.0 * t * (1.0 - t),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curves() -> Vec<Ease> {
        let mut v = vec![Ease::Linear, Ease::Sine, Ease::Smoothstep];
        for (k1, k2) in
            [(0.3, 0.75), (0.2, 0.8), (0.0, 1.0), (0.0, 0.5), (0.5, 1.0), (0.4, 0.4), (0.0, 0.0), (1.0, 1.0)]
        {
            v.push(Ease::parent(k1, k2).unwrap());
        }
        v
    }

    #[test]
    fn endpoints_are_exact() {
        for e in curves() {
            assert_eq!(e.position(0.0), 0.0, "{e:?}");
            assert_eq!(e.position(1.0), 1.0, "{e:?}");
            assert_eq!(e.position(-3.0), 0.0);
            assert_eq!(e.position(7.0), 1.0);
            assert_eq!(e.position(f64::NAN), 0.0);
        }
    }

    #[test]
    fn monotone_and_within_the_unit_interval() {
        for e in curves() {
            let mut last = 0.0;
            for i in 0..=10_000 {
                let s = e.position(f64::from(i) / 10_000.0);
                assert!((0.0..=1.0).contains(&s) && s >= last, "{e:?} at {i}: {s} after {last}");
                last = s;
            }
        }
    }

    /// The reference values of `docs/src/solving/ease.md`, computed there from the formulas.
    #[test]
    fn errata_reference_values() {
        let e = Ease::parent(0.3, 0.75).unwrap();
        for (t, want) in [(0.25, 0.176913), (0.5, 0.488646), (0.9, 0.962012)] {
            assert!((e.position(t) - want).abs() < 5e-7, "ease({t}) = {} vs {want}", e.position(t));
        }
        assert!((Ease::parent(0.2, 0.8).unwrap().position(0.5) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn velocity_is_the_derivative_and_continuous() {
        for e in curves() {
            let h = 1e-6;
            for i in 1..1000 {
                let t = f64::from(i) / 1000.0;
                let fd = (e.position(t + h) - e.position(t - h)) / (2.0 * h);
                assert!((fd - e.velocity(t)).abs() < 1e-5, "{e:?} at {t}: {fd} vs {}", e.velocity(t));
            }
        }
        // Continuity at the joins of Parent's pieces, from both sides.
        let e = Ease::parent(0.3, 0.75).unwrap();
        for k in [0.3, 0.75] {
            let (left, right) = (e.velocity(k - 1e-9), e.velocity(k + 1e-9));
            assert!((left - right).abs() < 1e-7, "jump at {k}: {left} vs {right}");
        }
        // It starts and ends at rest; the middle cruises at 1/f.
        assert_eq!(e.velocity(0.0), 0.0);
        assert!(e.velocity(1.0).abs() < 1e-15);
        let f = 2.0 * 0.3 / PI + 0.45 + 2.0 * 0.25 / PI;
        assert!((e.velocity(0.5) - 1.0 / f).abs() < 1e-15);
    }

    #[test]
    fn degenerate_parameters_do_not_divide_by_zero() {
        let linear = Ease::parent(0.0, 1.0).unwrap();
        for i in 0..=100 {
            let t = f64::from(i) / 100.0;
            assert!((linear.position(t) - t).abs() < 1e-15);
            assert!((linear.velocity(t) - 1.0).abs() < 1e-15);
        }
        for (k1, k2) in [(0.0, 0.0), (1.0, 1.0), (0.0, 0.3), (0.7, 1.0)] {
            let e = Ease::parent(k1, k2).unwrap();
            for i in 0..=100 {
                let t = f64::from(i) / 100.0;
                assert!(e.position(t).is_finite() && e.velocity(t).is_finite(), "k1={k1} k2={k2} t={t}");
            }
        }
    }

    #[test]
    fn invalid_parameters_name_the_field() {
        assert_eq!(Ease::parent(0.8, 0.2).unwrap_err().to_string(), "k1: must not exceed k2, got k1 = 0.8, k2 = 0.2");
        assert_eq!(Ease::parent(-0.1, 0.5).unwrap_err().to_string(), "k1: must be a number in [0, 1], got -0.1");
        assert_eq!(Ease::parent(0.1, 1.5).unwrap_err().to_string(), "k2: must be a number in [0, 1], got 1.5");
        assert!(matches!(Ease::parent(f64::NAN, 0.5), Err(EaseError::OutOfRange { field: "k1", .. })));
        assert!(matches!(Ease::parent(0.1, f64::INFINITY), Err(EaseError::OutOfRange { field: "k2", .. })));
    }
}
