//! The goal of a solve: where the end effector should be, and optionally the absolute
//! orientation of the last link. A description of the problem, shared by the closed forms, the
//! iterative solvers and the reachability checks.

use crate::math;
use crate::number::Num;
use nalgebra::Point2;
use thiserror::Error;

use crate::chain::{Chain, annulus_inner};

/// How many reaches from the base a goal is at most where a solve aims ([`Goal::stand_in`]).
pub(crate) const FAR_GOAL_REACHES: f64 = 1e6;

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

    /// The goal an iterative solve aims at instead of this one when this one is so far from
    /// `base` (more than [`FAR_GOAL_REACHES`] times `reach`, and by more than `tolerance`) that
    /// the loop cannot see its own progress: the same orientation, at that distance in the same
    /// direction. `None` for a goal nearer than that.
    ///
    /// From a goal `D` away, a step that brings the tip `δ` nearer lowers `|e|²` by about
    /// `2Dδ`: below the last bit of `D²` once `D` is some 10¹⁶ reaches, so that every step
    /// looked useless and the solve stalled at its start pose (a goal at (1e300, 0) left the
    /// seed arm folded at 5°, 5°, 5°). Past `reach`, the pose nearest a far goal points the arm
    /// at it; at 10⁶ reaches the stand-in's direction is the goal's to the last bit that
    /// matters, and every step shows. The error reported is still the goal's own distance.
    #[must_use]
    pub(crate) fn stand_in(&self, base: Point2<f64>, reach: f64, tolerance: f64) -> Option<Self> {
        let far = FAR_GOAL_REACHES * reach;
        // A quarter of the offset, so that neither the difference nor its length overflows
        // (a goal at 1e308 from a base at −1e308 is 2e308 away, beyond the f64 range).
        let (qx, qy) = (0.25 * self.position.x - 0.25 * base.x, 0.25 * self.position.y - 0.25 * base.y);
        let quarter = math::hypot(qx, qy);
        // (Finite goals and bases: no NaN here.)
        if quarter <= 0.25 * (far + tolerance) || far <= 0.0 {
            return None;
        }
        let position = Point2::new(base.x + qx / quarter * far, base.y + qy / quarter * far);
        Some(Self { position, ..*self })
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
            None => self.position_out_of(chain, Annulus::of(chain, tolerance)),
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

impl Goal {
    /// Whether the position lies outside `annulus` around `chain`'s base (what
    /// [`Goal::is_out_of_reach`] asks of a goal without an orientation; the batch solver asks it
    /// of every goal with the annulus measured once).
    pub(crate) fn position_out_of(&self, chain: &Chain, annulus: Annulus) -> bool {
        let d = length(self.position - chain.base());
        d > annulus.outer || d < annulus.inner
    }
}

/// The distances from a chain's base within which its tip reaches, widened by a tolerance.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Annulus {
    inner: f64,
    outer: f64,
}

impl Annulus {
    /// `chain`'s reach without limits, widened by `tolerance` on both sides.
    pub(crate) fn of(chain: &Chain, tolerance: f64) -> Self {
        Annulus { inner: chain.min_reach() - tolerance, outer: chain.max_reach() + tolerance }
    }
}

/// `|v|`, without overflow (a goal 1e200 away from the base of a chain of reach 3e200 is
/// within reach, not infinitely far) or underflow: [`math::distance`].
fn length(v: nalgebra::Vector2<f64>) -> f64 {
    math::distance(v.x, v.y)
}

fn finite(field: &'static str, value: f64) -> Result<(), GoalError> {
    if value.is_finite() { Ok(()) } else { Err(GoalError::NonFinite { field, value }) }
}
