//! [`Interpolation`] (how the path runs through the keyframes) and [`MotionOptions`] (timing,
//! ease and interpolation together), see the [module docs](super).

use super::Timing;
use crate::ease::Ease;
use crate::listed_enum;

listed_enum! {
    /// How the joint-space path runs through the keyframes.
    ///
    /// # Spline (the default)
    ///
    /// Each joint is interpolated on its own by a **monotone piecewise cubic Hermite** curve
    /// (PCHIP: Fritsch & Carlson 1980, with Fritsch & Butland's 1984 tangents, as in SciPy's
    /// `PchipInterpolator`), over the same knots for every joint:
    ///
    /// * **Knots.** Without explicit times, the cumulative joint-space chord lengths `C_k` of the
    ///   polyline (see the [module docs](super)), so that every joint's tangent is in radians per
    ///   radian of path and the curve runs through joint space in consistent units; keyframes that
    ///   repeat the one before (a zero-length segment) are dropped. With explicit times, the times.
    /// * **Tangents.** With `h_k = C_{k+1} − C_k` and secants `δ_k = (q_{k+1} − q_k) / h_k`, an
    ///   inner keyframe gets `m_k = 0` where `δ_{k−1}` and `δ_k` differ in sign or one is 0 (the
    ///   joint turns back or rests there), and otherwise the weighted harmonic mean
    ///   `m_k = (w₁ + w₂) / (w₁/δ_{k−1} + w₂/δ_k)`, `w₁ = 2h_k + h_{k−1}`, `w₂ = h_k + 2h_{k−1}`.
    ///   The two end keyframes get the three-point estimate `((2h₀ + h₁)δ₀ − h₀δ₁) / (h₀ + h₁)`
    ///   (mirrored at the end), set to 0 if its sign differs from `δ₀`'s and cut to `3δ₀` if
    ///   `δ₀, δ₁` differ in sign and it is larger.
    /// * **Segments.** On `[C_k, C_{k+1}]`, with `τ = (u − C_k) / h_k`,
    ///   `q(u) = q_k + (q_{k+1} − q_k)(3τ² − 2τ³) + h_k·(m_k(τ − 2τ² + τ³) + m_{k+1}(τ³ − τ²))`.
    ///
    /// **Continuity.** The value and the first derivative are continuous at every keyframe (C¹):
    /// both segments meeting at a keyframe take its value and its tangent `m_k`. The second
    /// derivative may jump there (it does not for a C² spline, which cannot be shape-preserving
    /// as well).
    ///
    /// **No overshoot.** The harmonic mean lies between 0 and `3·min(|δ_{k−1}|, |δ_k|)`, with the
    /// sign of both; the end tangents between 0 and `3|δ₀|`. So on every segment
    /// `α = m_k/δ_k` and `β = m_{k+1}/δ_k` lie in `[0, 3]`, a square inside Fritsch and Carlson's
    /// region of monotone cubics: every segment of every joint runs monotonically from one keyframe
    /// value to the next and never leaves the interval between them (each evaluated value is also
    /// clamped to it, against rounding). A joint with limits therefore stays inside them, and a
    /// free joint, unwrapped first, moves steadily one way by at most π per segment, as with
    /// [`Interpolation::Linear`]. The price of monotonicity: where a joint turns back at a keyframe
    /// its velocity there is 0 (still continuous).
    ///
    /// **Timing.** Without times, frame `i` is the point of the curve at parameter
    /// `u = e(u_i)·L`, `L = C_{K−1}`: the polyline's arc length, eased once over the whole path, so
    /// keyframe `k` is reached at the same moment as on the polyline and the ease alone sets the
    /// pace. The joint velocity `q′(u)·L·e′(t)/T` is continuous wherever the ease's is, at every
    /// keyframe too; it dips where the path turns (a joint that turns back slows to 0 and comes
    /// back), as a real arm slows in a turn. The joint acceleration `q″(u)·(L·e′/T)² + q′(u)·L·e″/T²`
    /// stays bounded, so a frame step changes no more at a keyframe than the largest `q″` and `e″`
    /// allow elsewhere. (Timing by the curve's *own* arc length instead would keep the joint-space
    /// speed constant through a turn and squeeze the turn into a few frames: on the issue-10 example,
    /// `--goal -2,3 --via 4,2 --via 1,4 --frames 120 --ease parent --k1 0.2 --k2 0.8`, a step changed
    /// 8.8× more at the first via point than anywhere else, against 1.06× this way and 10.9× for the
    /// polyline.) With times, frame `i` is the point at parameter `e(u_i)·T` of the spline over the
    /// times, continuous in velocity in the same way.
    ///
    /// With only two (distinct) keyframes the spline is the straight segment, and the frames are
    /// those of [`Interpolation::Linear`], bit for bit.
    ///
    /// # Linear
    ///
    /// The polyline through the keyframes, as before there was a spline: corners at every keyframe
    /// (see the [module docs](super)).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
    pub enum Interpolation {
        /// Monotone cubic spline (PCHIP): velocity continuous at every keyframe, no overshoot.
        #[default]
        Spline,
        /// Straight lines in joint space: velocity jumps at every keyframe.
        Linear,
    }
}

impl Interpolation {
    /// The short name used at the edges: `spline`, `linear`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Interpolation::Spline => "spline",
            Interpolation::Linear => "linear",
        }
    }

    /// A label for people.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Interpolation::Spline => "Spline",
            Interpolation::Linear => "Linear",
        }
    }

    /// One line saying what the interpolation does.
    #[must_use]
    pub fn summary(self) -> &'static str {
        match self {
            Interpolation::Spline => {
                "Monotone cubic spline through the keyframes: no corners, never past a keyframe value"
            }
            Interpolation::Linear => "Straight lines in joint space between keyframes: corners at via points",
        }
    }
}

crate::names::by_name!(Interpolation, "interpolation");

/// How keyframes become frames: how many and when ([`Timing`]), the speed profile ([`Ease`]),
/// and the shape of the path through the keyframes ([`Interpolation`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionOptions {
    /// Frame count and times.
    pub timing: Timing,
    /// The ease applied once to the whole path.
    pub ease: Ease,
    /// Spline (the default) or polyline.
    pub interpolation: Interpolation,
}

impl MotionOptions {
    /// `timing` and `ease` with the default [`Interpolation::Spline`].
    #[must_use]
    pub fn new(timing: Timing, ease: Ease) -> Self {
        Self { timing, ease, interpolation: Interpolation::default() }
    }

    /// The same options with `interpolation`.
    #[must_use]
    pub fn with_interpolation(self, interpolation: Interpolation) -> Self {
        Self { interpolation, ..self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    #[test]
    fn names_round_trip_and_spline_is_the_default() {
        for i in Interpolation::ALL {
            assert_eq!(Interpolation::from_name(i.name()), Some(i));
            assert_eq!(i.to_string(), i.name());
        }
        assert_eq!(Interpolation::default(), Interpolation::Spline);
        let err = "cubic".parse::<Interpolation>().unwrap_err();
        assert_eq!(err.to_string(), "unknown interpolation 'cubic' (expected one of: spline, linear)");
        let o = MotionOptions::new(Timing::Frames(5), Ease::Sine);
        assert_eq!(o.interpolation, Interpolation::Spline);
        assert_eq!(o.with_interpolation(Interpolation::Linear).interpolation, Interpolation::Linear);
    }
}
