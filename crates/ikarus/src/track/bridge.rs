//! Bridging a plan's gaps: where the poses [`plan`](super::plan) chose for two consecutive
//! samples lie further apart than the bound — the path leaves what the arm can reach (with its
//! limits) and comes back elsewhere, or the arm must change branch — the arm moves from one to
//! the other by a straight line in joint space, in equal steps within the bound, off the path.
//!
//! A straight line in joint space is continuous and stays inside the limits (each joint's range
//! is an interval holding both ends); free joints take the short way round (the poses are
//! unwrapped along the path). The inserted poses are [`SampleStatus::OffPath`], so the summary
//! and the pictures can show where the arm left the path.

use crate::limits::Bounds;

use super::{SampleStatus, TrackError, is_flip, joint_step};

/// At most this many off-path poses per sample of the path, in all: a gap of half a turn at
/// the default bound of 10° takes 17, and a limited joint's whole range of 340° at 10° takes
/// 33. A bound so small that the gaps need more is refused ([`TrackError::OffPathCap`]) rather
/// than answered with a path many times longer than asked for.
pub const MAX_OFF_PATH_PER_SAMPLE: usize = 64;

/// The chosen poses with the gaps bridged: every pose, its status and the index of the path
/// sample whose goal it carries (an off-path pose carries the next sample's).
#[derive(Debug, Default)]
pub(super) struct Bridged {
    pub poses: Vec<Vec<f64>>,
    pub status: Vec<SampleStatus>,
    pub goal: Vec<usize>,
}

/// The number of equal steps within `max_step` that a move of `step` takes: 1 unless it is a
/// flip ([`is_flip`]), else `⌈step / max_step⌉` (saturating for an absurdly small bound).
fn pieces(step: f64, max_step: f64) -> usize {
    if is_flip(step, max_step) {
        let m = (step / max_step).ceil();
        if m < usize::MAX as f64 { m as usize } else { usize::MAX }
    } else {
        1
    }
}

/// `poses` (one per sample, unwrapped along the path, with their `status`) with the gaps over
/// `max_step` bridged: between samples `k` and `k + 1` whose largest joint change `s` exceeds
/// the bound, `m − 1` poses `q_k + (j/m)(q_{k+1} − q_k)`, `j = 1 … m − 1`, `m = ⌈s / max_step⌉`,
/// so that every step is `s / m ≤ max_step`.
///
/// # Errors
/// [`TrackError::OffPathCap`] when the gaps need more than [`MAX_OFF_PATH_PER_SAMPLE`] poses
/// per sample (a bound far smaller than the path's gaps).
pub(super) fn bridge(
    poses: Vec<Vec<f64>>,
    status: &[SampleStatus],
    bounds: Bounds<'_>,
    max_step: f64,
) -> Result<Bridged, TrackError> {
    let gaps: Vec<usize> = poses.windows(2).map(|w| pieces(joint_step(bounds, &w[1], &w[0]), max_step)).collect();
    let needed = gaps.iter().fold(0usize, |sum, &m| sum.saturating_add(m - 1));
    let cap = MAX_OFF_PATH_PER_SAMPLE.saturating_mul(poses.len());
    if needed > cap {
        return Err(TrackError::OffPathCap { max_step, needed, cap });
    }
    let total = poses.len() + needed;
    let mut out = Bridged {
        poses: Vec::with_capacity(total),
        status: Vec::with_capacity(total),
        goal: Vec::with_capacity(total),
    };
    let mut previous: Option<Vec<f64>> = None;
    for (k, pose) in poses.into_iter().enumerate() {
        if let Some(from) = &previous {
            let m = gaps[k - 1];
            for j in 1..m {
                let t = j as f64 / m as f64;
                out.poses.push(from.iter().zip(&pose).map(|(&a, &b)| a + t * (b - a)).collect());
                out.status.push(SampleStatus::OffPath);
                out.goal.push(k);
            }
        }
        out.status.push(status[k]);
        out.goal.push(k);
        previous = Some(pose.clone());
        out.poses.push(pose);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gap_is_bridged_in_equal_steps_within_the_bound() {
        let bound = 10f64.to_radians();
        let poses = vec![vec![0.0, 0.0], vec![0.05, 0.0], vec![0.05 + std::f64::consts::PI, -0.3], vec![3.2, -0.3]];
        let status = [SampleStatus::Reached, SampleStatus::Unreachable, SampleStatus::Reached, SampleStatus::Reached];
        let b = bridge(poses, &status, Bounds::free(), bound).unwrap();
        // 180° at 10°: 18 steps, 17 poses between.
        assert_eq!(b.poses.len(), 4 + 17);
        assert_eq!(b.status.iter().filter(|&&s| s == SampleStatus::OffPath).count(), 17);
        assert!(b.status[2..19].iter().all(|&s| s == SampleStatus::OffPath));
        assert_eq!((b.goal[1], b.goal[2], b.goal[18], b.goal[19], b.goal[20]), (1, 2, 2, 2, 3));
        for w in b.poses.windows(2) {
            assert!(!is_flip(joint_step(Bounds::free(), &w[1], &w[0]), bound), "{w:?}");
        }
    }

    #[test]
    fn a_bound_too_small_for_the_gaps_is_refused() {
        let poses = vec![vec![0.0], vec![3.0]];
        let e = bridge(poses, &[SampleStatus::Reached; 2], Bounds::free(), 1e-300).unwrap_err();
        assert!(matches!(e, TrackError::OffPathCap { cap: 128, .. }), "{e}");
        assert!(e.to_string().starts_with("max_step = 1e-300 rad: "), "{e}");
    }
}
