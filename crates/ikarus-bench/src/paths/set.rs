//! The path sets of `ikarus bench --paths`: for each arm and limits setting, `--path-count`
//! seeded paths of `--samples` samples each, cycling through the kinds of [`PATTERN`].
//!
//! Most paths are the tips of smooth joint trajectories (forward kinematics, so a continuous
//! solution exists by construction, and its own largest joint step is known): every joint a
//! sum of three low-frequency sinusoids inside its range (`wave`), the arm stretching straight
//! at one sample so that the tip touches the outer reach (`boundary`), one or two joints
//! touching an end of their range at one sample (`limits`). The others are shapes, whose
//! continuity is not known in advance: a short `line` between the tips of two nearby poses, a
//! `circle` and a `figure8` around the tip of a random pose, and `beyond`, a line from the tip
//! of a random pose radially out to 1.3 times the arm's reach, whose outer samples no pose
//! reaches.
//!
//! Every trajectory stays inside the arm's ranges (all three shipped arms limit every joint),
//! with the limits enforced or not, and never steps a joint more than [`GEN_MAX_STEP_DEG`] per
//! sample (amplitudes are scaled down for short paths), well under the flip bound of 10°.

use std::f64::consts::{PI, TAU};

use ikarus::kinematics::end_effector;
use ikarus::rng::SplitMix64;
use ikarus::solve::wrap_angle;
use ikarus::track::Path;
use ikarus::{Chain, Goal};
use serde::Serialize;

use crate::sets::stable_hash;

/// The generating trajectories never move a joint more than this per sample, degrees.
pub const GEN_MAX_STEP_DEG: f64 = 4.0;

/// `beyond` paths end this many reaches from the base.
const BEYOND: f64 = 1.3;

ikarus::listed_enum! {
    /// The kinds of path.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
    #[serde(rename_all = "lowercase")]
    pub enum Kind {
        /// Forward kinematics of three sinusoids per joint.
        Wave,
        /// Forward kinematics of a trajectory that stretches the arm straight at one sample.
        Boundary,
        /// Forward kinematics of a trajectory that touches joint limits.
        Limits,
        /// A short segment between the tips of two nearby poses.
        Line,
        /// A circle around the tip of a random pose.
        Circle,
        /// A figure-8 around the tip of a random pose.
        Figure8,
        /// A line out of the reachable region.
        Beyond,
    }
}

/// The kinds of paths `0, 1, 2, …` of a set, cyclically: six FK paths in ten.
pub const PATTERN: [Kind; 10] = [
    Kind::Wave,
    Kind::Boundary,
    Kind::Limits,
    Kind::Line,
    Kind::Wave,
    Kind::Circle,
    Kind::Boundary,
    Kind::Figure8,
    Kind::Limits,
    Kind::Beyond,
];

impl Kind {
    /// The kind's name in the output.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Wave => "wave",
            Kind::Boundary => "boundary",
            Kind::Limits => "limits",
            Kind::Line => "line",
            Kind::Circle => "circle",
            Kind::Figure8 => "figure8",
            Kind::Beyond => "beyond",
        }
    }

    /// Whether paths of this kind are made by forward kinematics (a continuous solution exists).
    pub fn fk(self) -> bool {
        matches!(self, Kind::Wave | Kind::Boundary | Kind::Limits)
    }
}

/// One path of a set.
#[derive(Debug, Clone)]
pub struct BenchPath {
    /// Its kind.
    pub kind: Kind,
    /// The goals (positions only).
    pub path: Path,
    /// For FK paths: the generating trajectory's largest joint step, radians.
    pub truth_step: Option<f64>,
    /// Samples farther from the base than the arm's reach (plus 1e-9): no pose reaches them.
    pub beyond: usize,
}

/// The paths of one arm with its limits enforced or not.
#[derive(Debug, Clone)]
pub struct PathSet {
    /// The arm's name.
    pub arm: &'static str,
    /// Whether the limits are enforced (and judged).
    pub limited: bool,
    /// The arm's chain, with its limits.
    pub chain: Chain,
    /// The start pose: the arm's, clamped into the limits when they are enforced.
    pub start: Vec<f64>,
    /// The paths, in order.
    pub paths: Vec<BenchPath>,
}

impl PathSet {
    /// `ARM-limits` or `ARM-free`.
    pub fn name(&self) -> String {
        format!("{}-{}", self.arm, if self.limited { "limits" } else { "free" })
    }

    /// `a − b` for joint `i` as the set measures steps: plain for an enforced limit (the joint
    /// cannot pass through its excluded range), the short way round otherwise.
    pub fn delta(&self, i: usize, a: f64, b: f64) -> f64 {
        if self.limited && self.chain.limits()[i].is_some() { a - b } else { wrap_angle(a - b) }
    }

    /// The largest joint change from `from` to `to`, radians.
    pub fn step(&self, to: &[f64], from: &[f64]) -> f64 {
        to.iter().zip(from).enumerate().map(|(i, (&a, &b))| self.delta(i, a, b).abs()).fold(0.0, f64::max)
    }
}

/// Generates the `count` paths of `samples` samples of the arm `arm` with limits enforced or
/// not, from its own generator (seeded with `seed` and the arm's name and limits setting).
pub fn generate(arm: &'static str, chain: &Chain, limited: bool, count: usize, samples: usize, seed: u64) -> PathSet {
    let mut rng = SplitMix64(seed ^ stable_hash(arm, if limited { "paths-limits" } else { "paths-free" }));
    let mut start = chain.start_pose().angles().to_vec();
    if limited {
        for (a, lim) in start.iter_mut().zip(chain.limits()) {
            if let Some(l) = lim {
                *a = l.clamp(*a);
            }
        }
    }
    let mut set = PathSet { arm, limited, chain: chain.clone(), start, paths: Vec::with_capacity(count) };
    for k in 0..count {
        let kind = PATTERN[k % PATTERN.len()];
        let (path, truth) = make(chain, kind, samples, &mut rng);
        let truth_step = truth.map(|q| q.windows(2).map(|w| set.step(&w[1], &w[0])).fold(0.0, f64::max));
        let base = chain.base();
        let beyond = path.goals().iter().filter(|g| (g.target() - base).norm() > chain.max_reach() + 1e-9).count();
        set.paths.push(BenchPath { kind, path, truth_step, beyond });
    }
    set
}

/// A path of `kind`, and for FK paths the joint trajectory that generated it.
fn make(chain: &Chain, kind: Kind, samples: usize, rng: &mut SplitMix64) -> (Path, Option<Vec<Vec<f64>>>) {
    let ranges = ranges(chain);
    let reach = chain.max_reach();
    let tip = |q: &[f64]| {
        let p = end_effector(chain, q).position;
        [p.x, p.y]
    };
    let shape = match kind {
        Kind::Wave | Kind::Boundary | Kind::Limits => {
            let q = trajectory(&ranges, kind, samples, rng);
            let points: Vec<[f64; 2]> = q.iter().map(|p| tip(p)).collect();
            return (Path::from_points(&points).expect("finite tips"), Some(q));
        }
        Kind::Line => {
            let a = pose(&ranges, rng);
            let b: Vec<f64> =
                a.iter().zip(&ranges).map(|(&x, &(lo, hi))| (x + rng.range(-0.5, 0.5)).clamp(lo, hi)).collect();
            Path::line(tip(&a), tip(&b), samples)
        }
        Kind::Circle => Path::circle(tip(&pose(&ranges, rng)), rng.range(0.08, 0.2) * reach, samples),
        Kind::Figure8 => Path::figure8(tip(&pose(&ranges, rng)), rng.range(0.1, 0.25) * reach, samples),
        Kind::Beyond => {
            let from = tip(&pose(&ranges, rng));
            let base = chain.base();
            let (dx, dy) = (from[0] - base.x, from[1] - base.y);
            let d = dx.hypot(dy).max(1e-9);
            Path::line(from, [base.x + BEYOND * reach * dx / d, base.y + BEYOND * reach * dy / d], samples)
        }
    };
    (shape.expect("finite shapes of at least 2 samples"), None)
}

/// Each joint's range: its limits, or [−π, π] for a free joint.
fn ranges(chain: &Chain) -> Vec<(f64, f64)> {
    chain.limits().iter().map(|l| l.map_or((-PI, PI), |l| (l.min(), l.max()))).collect()
}

/// A pose drawn uniformly from the middle 80 % of every range.
fn pose(ranges: &[(f64, f64)], rng: &mut SplitMix64) -> Vec<f64> {
    ranges.iter().map(|&(lo, hi)| rng.range(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo))).collect()
}

/// The `samples` poses of a trajectory of `kind` (an FK kind), at `t = k / (samples − 1)`.
///
/// `wave`: joint `i` is `cᵢ + Aᵢ Σ_m w_m sin(2π f_m t + φ_m)` with three frequencies
/// `f_m ∈ [0.3, 1.5]` cycles per path, weights summing to 1, inside the middle 90 % of its
/// range. `boundary`: joint 0 a wave, every other joint `bᵢ e(t)` with
/// `e(t) = (1 − cos 2π(t − t₀)) / 2`, which is 0 (the arm straight) at sample `t₀`.
/// `limits`: a wave, with one or two joints `L ∓ B e(t)` touching their range's end `L` at
/// `t₀`. Amplitudes are scaled so that no joint steps more than [`GEN_MAX_STEP_DEG`].
fn trajectory(ranges: &[(f64, f64)], kind: Kind, samples: usize, rng: &mut SplitMix64) -> Vec<Vec<f64>> {
    let n = ranges.len();
    let last = (samples - 1) as f64;
    let max_step = GEN_MAX_STEP_DEG.to_radians();
    let k0 = (rng.range(0.2, 0.8) * last).round();
    let t0 = k0 / last;
    // The envelope e(t) changes by at most π/(samples − 1) per sample times its amplitude.
    let envelope = move |t: f64| (1.0 - (TAU * (t - t0)).cos()) / 2.0;
    let cap = max_step * last / PI;
    let mut joints: Vec<Box<dyn Fn(f64) -> f64>> = Vec::with_capacity(n);
    let touching: Vec<usize> = if kind == Kind::Limits {
        let a = (rng.unit() * n as f64) as usize % n;
        let b = (rng.unit() * n as f64) as usize % n;
        vec![a, b]
    } else {
        Vec::new()
    };
    for (i, &(lo, hi)) in ranges.iter().enumerate() {
        if kind == Kind::Boundary && i > 0 {
            let b = rng.range(10f64, 35.0).to_radians().min(cap) * if rng.chance(0.5) { 1.0 } else { -1.0 };
            let b = b.clamp(lo, hi);
            joints.push(Box::new(move |t| b * envelope(t)));
        } else if touching.contains(&i) {
            let upper = rng.chance(0.5);
            let depth = (rng.range(0.3, 0.8) * (hi - lo)).min(cap);
            let (end, sign) = if upper { (hi, -1.0) } else { (lo, 1.0) };
            joints.push(Box::new(move |t| end + sign * depth * envelope(t)));
        } else {
            joints.push(wave(lo, hi, last, max_step, rng));
        }
    }
    (0..samples).map(|k| joints.iter().map(|q| q(k as f64 / last)).collect()).collect()
}

/// One joint's wave inside the middle 90 % of `[lo, hi]`, stepping at most `max_step` per
/// sample over `last + 1` samples.
fn wave(lo: f64, hi: f64, last: f64, max_step: f64, rng: &mut SplitMix64) -> Box<dyn Fn(f64) -> f64> {
    let (lo, hi) = (lo + 0.05 * (hi - lo), hi - 0.05 * (hi - lo));
    let centre = rng.range(lo + 0.25 * (hi - lo), hi - 0.25 * (hi - lo));
    let mut terms = [(0.0, 0.0, 0.0); 3];
    for term in &mut terms {
        *term = (rng.range(0.2, 1.0), rng.range(0.3, 1.5), rng.range(0.0, TAU));
    }
    let total: f64 = terms.iter().map(|t| t.0).sum();
    for term in &mut terms {
        term.0 /= total;
    }
    // |q'(t)| ≤ A · 2π Σ w f, per sample divided by `last`.
    let speed: f64 = terms.iter().map(|t| t.0 * TAU * t.1).sum::<f64>() / last;
    let room = (centre - lo).min(hi - centre);
    let amplitude = (rng.range(0.4, 1.0) * room).min(max_step / speed);
    Box::new(move |t| centre + amplitude * terms.iter().map(|&(w, f, p)| w * (TAU * f * t + p).sin()).sum::<f64>())
}

/// The goal of each sample as `(x, y)`.
pub fn points(path: &Path) -> impl Iterator<Item = (f64, f64)> + '_ {
    path.goals().iter().map(|g: &Goal| (g.target().x, g.target().y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sets::ArmName;

    fn all(seed: u64, count: usize, samples: usize) -> Vec<PathSet> {
        let mut out = Vec::new();
        for arm in ArmName::ALL {
            let chain = arm.load().unwrap().chain;
            for limited in [false, true] {
                out.push(generate(arm.name(), &chain, limited, count, samples, seed));
            }
        }
        out
    }

    fn bits(set: &PathSet) -> Vec<u64> {
        set.paths.iter().flat_map(|p| points(&p.path).flat_map(|(x, y)| [x.to_bits(), y.to_bits()])).collect()
    }

    #[test]
    fn sets_are_reproducible_and_well_formed() {
        let (a, b) = (all(3, 20, 50), all(3, 20, 50));
        for (a, b) in a.iter().zip(&b) {
            assert_eq!(bits(a), bits(b), "{}", a.name());
        }
        assert_ne!(bits(&a[0]), bits(&all(4, 20, 50)[0]));
        for set in &a {
            assert_eq!(set.paths.len(), 20);
            for (k, p) in set.paths.iter().enumerate() {
                assert_eq!(p.kind, PATTERN[k % 10]);
                assert_eq!(p.path.len(), 50);
                assert_eq!(p.truth_step.is_some(), p.kind.fk());
                if let Some(s) = p.truth_step {
                    assert!(s > 0.0 && s <= GEN_MAX_STEP_DEG.to_radians() * 1.000_001, "{}: {s}", set.name());
                }
                // Beyond paths leave the reach; FK paths never do (shapes may stick out).
                if p.kind == Kind::Beyond {
                    assert!(p.beyond > 0, "{} path {k}", set.name());
                } else if p.kind.fk() {
                    assert_eq!(p.beyond, 0, "{} path {k}", set.name());
                }
            }
        }
    }

    #[test]
    fn fk_trajectories_stay_in_range_and_graze_what_they_should() {
        let chain = ArmName::Seven.load().unwrap().chain;
        let ranges = ranges(&chain);
        let mut rng = SplitMix64(9);
        for kind in [Kind::Wave, Kind::Boundary, Kind::Limits] {
            for _ in 0..20 {
                let q = trajectory(&ranges, kind, 100, &mut rng);
                for pose in &q {
                    for (a, &(lo, hi)) in pose.iter().zip(&ranges) {
                        assert!((lo - 1e-12..=hi + 1e-12).contains(a), "{kind:?}: {a}");
                    }
                }
                let touches_end = q
                    .iter()
                    .any(|p| p.iter().zip(&ranges).any(|(a, r)| (a - r.0).abs() < 1e-9 || (a - r.1).abs() < 1e-9));
                assert_eq!(touches_end, kind == Kind::Limits, "{kind:?}");
                let straight = q.iter().any(|p| p[1..].iter().all(|a| a.abs() < 1e-12));
                assert_eq!(straight, kind == Kind::Boundary, "{kind:?}");
            }
        }
    }
}
