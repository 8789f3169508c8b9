//! The goal of a solve: where the end effector should be, and optionally the absolute
//! orientation of the last link. A description of the problem, shared by the closed forms, the
//! iterative solvers and the reachability checks.

use crate::math;
use crate::number::Num;
use nalgebra::Point2;
use thiserror::Error;

use crate::chain::{Chain, annulus_inner};

/// What the end effector should reach: a position, and optionally an absolute orientation
/// of the last link.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    position: Point2<f64>,
    orientation: Option<f64>,
}

/// Why a [`Goal`] is invalid.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GoalError {
    /// A coordinate or the angle is NaN or infinite.
    #[error("goal.{field}: must be a finite number, got {}", Num(*.value))]
    NonFinite {
        /// `"x"`, `"y"` or `"angle"`.
        field: &'static str,
        /// The offending value.
        value: f64,
    },
}

impl Goal {
    /// A position goal `(x, y)`.
    pub fn position(x: f64, y: f64) -> Result<Self, GoalError> {
        finite("x", x)?;
        finite("y", y)?;
        Ok(Self { position: Point2::new(x, y), orientation: None })
    }

    /// A position goal with an absolute orientation `angle` (radians from +x) for the last link.
    pub fn with_orientation(x: f64, y: f64, angle: f64) -> Result<Self, GoalError> {
        let mut g = Self::position(x, y)?;
        finite("angle", angle)?;
        g.orientation = Some(angle);
        Ok(g)
    }

    /// The target position.
    #[must_use]
    pub fn target(&self) -> Point2<f64> {
        self.position
    }

    /// The target orientation, if any, radians.
    #[must_use]
    pub fn orientation(&self) -> Option<f64> {
        self.orientation
    }

    /// Whether no pose of `chain` can reach this goal even with its limits ignored, by more
    /// than `tolerance`.
    ///
    /// Free joints reach exactly the annulus `min_reach ≤ |p − base| ≤ max_reach`. With an
    /// orientation φ the last link is fixed, so the wrist `p − l_N (cos φ, sin φ)` must lie in
    /// the annulus of the other links (or on the base, for a single link).
    #[must_use]
    pub fn is_out_of_reach(&self, chain: &Chain, tolerance: f64) -> bool {
        let base = chain.base();
        match self.orientation {
            None => {
                let d = length(self.position - base);
                d > chain.max_reach() + tolerance || d < chain.min_reach() - tolerance
            }
            Some(phi) => {
                let lengths = chain.lengths();
                let (last, rest) = lengths.split_last().expect("a chain has at least one link");
                let wrist = self.position - *last * nalgebra::Vector2::new(math::cos(phi), math::sin(phi));
                let d = length(wrist - base);
                let outer: f64 = rest.iter().sum();
                let inner = if rest.is_empty() { 0.0 } else { annulus_inner(rest) };
                d > outer + tolerance || d < inner - tolerance
            }
        }
    }
}

/// `|v|`, by `hypot` where the sum of squares overflows (a goal 1e200 away from the base of a
/// chain of reach 3e200 is within reach, not infinitely far) or is subnormal.
fn length(v: nalgebra::Vector2<f64>) -> f64 {
    let squared = v.norm_squared();
    if squared.is_finite() && squared >= f64::MIN_POSITIVE { squared.sqrt() } else { math::hypot(v.x, v.y) }
}

fn finite(field: &'static str, value: f64) -> Result<(), GoalError> {
    if value.is_finite() { Ok(()) } else { Err(GoalError::NonFinite { field, value }) }
}
