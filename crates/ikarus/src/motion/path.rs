//! The path of a motion: the polyline through the unwrapped keyframes in joint space, and the
//! pose at any point of it (see the [module docs](super)).

use std::f64::consts::{PI, TAU};

use super::MotionError;
use crate::limits::JointLimits;
use crate::math;

/// The polyline through the unwrapped keyframes.
pub(super) struct Path {
    /// Joints per pose.
    n: usize,
    /// Unwrapped keyframes, `n` angles each, stored flat.
    keys: Vec<f64>,
    /// Cumulative lengths `C_k`, one per keyframe; `C₀ = 0`.
    cumulative: Vec<f64>,
}

impl Path {
    /// Unwraps validated poses (one angle per entry of `limits`) and measures the path.
    pub(super) fn new<'a>(
        limits: &[Option<JointLimits>],
        poses: impl ExactSizeIterator<Item = &'a [f64]>,
        field: &'static str,
    ) -> Result<Self, MotionError> {
        let n = limits.len();
        let mut keys = Vec::with_capacity(poses.len() * n);
        let mut cumulative = Vec::with_capacity(poses.len());
        for (index, pose) in poses.enumerate() {
            if index == 0 {
                keys.extend_from_slice(pose);
                cumulative.push(0.0);
                continue;
            }
            let start = keys.len() - n;
            for (joint, (&angle, limits)) in pose.iter().zip(limits).enumerate() {
                let a = if limits.is_some() { angle } else { unwrap_near(angle, keys[start + joint]) };
                keys.push(a);
            }
            let (previous, current) = keys[start..].split_at(n);
            let length = cumulative[index - 1] + distance(previous, current);
            if !length.is_finite() {
                return Err(MotionError::PathTooLong { field, index, length });
            }
            cumulative.push(length);
        }
        Ok(Self { n, keys, cumulative })
    }

    /// Joints per pose.
    pub(super) fn joints(&self) -> usize {
        self.n
    }

    pub(super) fn key(&self, k: usize) -> &[f64] {
        &self.keys[k * self.n..(k + 1) * self.n]
    }

    pub(super) fn last(&self) -> &[f64] {
        self.key(self.cumulative.len() - 1)
    }

    /// The cumulative lengths `C_k`, one per keyframe.
    pub(super) fn cumulative(&self) -> &[f64] {
        &self.cumulative
    }

    pub(super) fn length(&self) -> f64 {
        self.cumulative[self.cumulative.len() - 1]
    }

    /// The pose at parameter `x` of the piecewise-linear map `marks[k] ↦ key(k)`, where `marks`
    /// is non-decreasing with one entry per keyframe (the cumulative lengths, or the times).
    /// Among equal marks the last wins, so zero-length pieces are skipped.
    pub(super) fn at(&self, marks: &[f64], x: f64, out: &mut Vec<f64>) {
        // The first mark greater than x; marks[0] ≤ x for every x ≥ 0, so k ≥ 1 unless x < 0.
        let k = marks.partition_point(|&m| m <= x);
        out.clear();
        if k == 0 {
            out.extend_from_slice(self.key(0));
        } else if k >= marks.len() {
            out.extend_from_slice(self.last());
        } else {
            // marks[k − 1] ≤ x < marks[k], so the denominator is positive.
            let w = (x - marks[k - 1]) / (marks[k] - marks[k - 1]);
            out.extend(self.key(k - 1).iter().zip(self.key(k)).map(|(&a, &b)| lerp(a, b, w)));
        }
    }
}

/// `a + w·(b − a)` for `w` in [0, 1], exactly `a` at 0 and `b` at 1, and never outside the
/// interval between `a` and `b` (rounding could otherwise step over a joint limit by an ulp).
fn lerp(a: f64, b: f64, w: f64) -> f64 {
    if w <= 0.0 {
        a
    } else if w >= 1.0 {
        b
    } else {
        (a + w * (b - a)).clamp(a.min(b), a.max(b))
    }
}

/// `angle` moved by whole turns to within `(−π, π]` of `previous` (up to rounding); unchanged,
/// bit for bit, if it already is.
fn unwrap_near(angle: f64, previous: f64) -> f64 {
    let turns = ((angle - previous - PI) / TAU).ceil();
    if turns == 0.0 { angle } else { angle - turns * TAU }
}

/// Euclidean distance `‖b − a‖₂`, scaled by the largest difference so that the squares neither
/// overflow nor underflow.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().zip(b).map(|(x, y)| (y - x).abs()).fold(0.0, f64::max);
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    scale * a.iter().zip(b).map(|(x, y)| math::square((y - x) / scale)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;

    #[test]
    fn half_turn_goes_counter_clockwise() {
        assert_eq!(unwrap_near(PI, 0.0), PI);
        assert_eq!(unwrap_near(-PI, 0.0), PI);
        assert_eq!(unwrap_near(0.3, 0.0).to_bits(), 0.3f64.to_bits());
        assert!((unwrap_near(3.0 * FRAC_PI_2, 0.0) + FRAC_PI_2).abs() <= 1e-15);
        assert!((unwrap_near(-3.0 * FRAC_PI_2, 0.0) - FRAC_PI_2).abs() <= 1e-15);
        assert!((unwrap_near(0.1 + 5.0 * TAU, 0.0) - 0.1).abs() <= 1e-14);
    }
}
