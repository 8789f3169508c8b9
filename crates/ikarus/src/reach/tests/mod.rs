//! Tests of the reachable workspace: the pieces (sample plans, sectors, the reduced chain, the
//! annulus) in `parts`, whole grids against references in `grid`; shared chains and reference
//! computations here.

use std::f64::consts::{PI, TAU};

use nalgebra::Point2;

use super::region::Sector;
use super::sampling::{Plan, Range, Reduced, Segment, splitmix64};
use super::{Annulus, Workspace, WorkspaceOptions, run, sample, sample_with_progress};
use crate::angle::direction as dir;
use crate::chain::{Chain, JointLimits, Link};
use crate::kinematics::end_effector;
use crate::math;

mod grid;
mod parts;
mod skeleton;

/// Uniform in `[0, 1)` from a SplitMix64 stream.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(1);
        (splitmix64(self.0) >> 11) as f64 / 9_007_199_254_740_992.0
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

fn lim(min_deg: f64, max_deg: f64) -> JointLimits {
    JointLimits::new(min_deg.to_radians(), max_deg.to_radians()).unwrap()
}

fn free(lengths: &[f64]) -> Chain {
    let links: Vec<Link> = lengths.iter().map(|&l| Link::new(l, 0.0)).collect();
    Chain::new([0.0, 0.0], &links).unwrap()
}

/// The seed arm: lengths 3, 2, 1, limits ±45°, ±90°, ±170°, every joint at 5°.
fn seed_arm() -> Chain {
    let s = 5f64.to_radians();
    Chain::new(
        [0.0, 0.0],
        &[
            Link::new(3.0, s).with_limits(lim(-45.0, 45.0)),
            Link::new(2.0, s).with_limits(lim(-90.0, 90.0)),
            Link::new(1.0, s).with_limits(lim(-170.0, 170.0)),
        ],
    )
    .unwrap()
}

/// The seven-link arm of `examples/arms/seven.toml`.
fn seven() -> Chain {
    let spec = [(2.0, 90.0), (1.7, 120.0), (1.4, 120.0), (1.2, 135.0), (1.0, 135.0), (0.8, 150.0), (0.6, 150.0)];
    let links: Vec<Link> = spec.iter().map(|&(l, m)| Link::new(l, 0.0).with_limits(lim(-m, m))).collect();
    Chain::new([0.0, 0.0], &links).unwrap()
}

fn options(resolution: u32) -> WorkspaceOptions {
    WorkspaceOptions { resolution, ..WorkspaceOptions::default() }
}

/// A pose drawn uniformly within each joint's limits (a full turn without).
fn random_pose(chain: &Chain, rng: &mut Rng) -> Vec<f64> {
    chain
        .limits()
        .iter()
        .map(|l| l.map_or((-PI, PI), |l| (l.min(), l.max())))
        .map(|(lo, hi)| rng.range(lo, hi))
        .collect()
}

/// Whether `angle + 2πk ∈ [lo, hi]` for some `k`, and how far (radians) it is from the
/// nearest end (infinite for a full turn).
fn in_range(angle: f64, lo: f64, hi: f64) -> (bool, f64) {
    if hi - lo >= TAU {
        return (true, f64::INFINITY);
    }
    let a = angle + TAU * ((lo - angle) / TAU).ceil();
    if a <= hi { (true, (a - lo).min(hi - a)) } else { (false, (a - hi).min(lo + TAU - a)) }
}

/// Reference membership for two links from `p` (lengths `a`, `b`, the first link's absolute
/// direction in `r1`, the second joint's angle in `r2`) by `acos` and `atan2`, with how far
/// the decision is from flipping: radial distance to the rims, or angle to a range end times
/// its lever.
fn reference(p: [f64; 2], a: f64, b: f64, r1: (f64, f64), r2: (f64, f64), q: [f64; 2]) -> (bool, f64) {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let r = math::hypot(dx, dy);
    let rim = (r - (a + b)).abs().min((r - (a - b).abs()).abs());
    if r > a + b || r < (a - b).abs() {
        return (false, rim);
    }
    let t = math::acos(((r * r - a * a - b * b) / (2.0 * a * b)).clamp(-1.0, 1.0));
    let (mut hit, mut margin) = (false, rim);
    for theta in [t, -t] {
        let (in2, m2) = in_range(theta, r2.0, r2.1);
        let psi = math::atan2(dy, dx) - math::atan2(b * math::sin(theta), a + b * math::cos(theta));
        let (in1, m1) = in_range(psi, r1.0, r1.1);
        margin = margin.min(m2 * b).min(m1 * r);
        hit |= in1 && in2;
    }
    (hit, margin)
}
