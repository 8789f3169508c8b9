//! The exact two-joint region: what the last two joints reach with the others fixed (a
//! [`Slice`]), the test whether a point lies in it, and the [`Sampler`] that builds the slice of
//! each joint-space sample.

use std::f64::consts::{PI, TAU};

use super::sampling::{Plan, Range, Reduced};
use crate::angle::direction as dir;
use crate::math;

/// `u × v`, the z component of the 3D cross product.
fn cross(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

/// `u · v`.
fn dot(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[0] + u[1] * v[1]
}

/// A set of directions `{e^{iα} : α ∈ lo + [0, span]}`, tested without trigonometry.
///
/// For `span ≤ π` a vector `v` lies in it iff `lo × v ≥ 0`, `v × hi ≥ 0` and `mid · v ≥ 0`
/// (the last only rules out `−lo` when `span = 0`); for `π < span < 2π` iff it is not in the
/// open complement `hi × v > 0 ∧ v × lo > 0`, a sector narrower than π. `v` need not be a unit
/// vector; the zero vector counts as inside.
#[derive(Debug, Clone, Copy)]
pub(super) enum Sector {
    Full,
    Narrow { lo: [f64; 2], hi: [f64; 2], mid: [f64; 2] },
    Wide { lo: [f64; 2], hi: [f64; 2] },
}

impl Sector {
    pub(super) fn new(lo: f64, span: f64) -> Sector {
        if span >= TAU {
            Sector::Full
        } else if span <= PI {
            Sector::Narrow { lo: dir(lo), hi: dir(lo + span), mid: dir(lo + 0.5 * span) }
        } else {
            Sector::Wide { lo: dir(lo), hi: dir(lo + span) }
        }
    }

    fn of(range: Range, offset: f64) -> Sector {
        if range.full { Sector::Full } else { Sector::new(range.lo + offset, range.span) }
    }

    #[inline]
    pub(super) fn contains(&self, v: [f64; 2]) -> bool {
        match *self {
            Sector::Full => true,
            Sector::Narrow { lo, hi, mid } => cross(lo, v) >= 0.0 && cross(v, hi) >= 0.0 && dot(mid, v) >= 0.0,
            Sector::Wide { lo, hi } => !(cross(hi, v) > 0.0 && cross(v, lo) > 0.0),
        }
    }
}

/// Turns a sample index into the slice of the last two movable joints.
#[derive(Debug)]
pub(super) struct Sampler<'a> {
    reduced: &'a Reduced,
    pub(super) plan: Plan,
    /// Lengths of the last two segments' vectors, `a = |w_j|`, `b = |w_k|`.
    a: f64,
    b: f64,
    /// `arg w_j`: the shoulder direction is `φ + θ_j + alpha`.
    alpha: f64,
    /// Elbow angles `θ_k + γ_j + arg w_k − arg w_j`, constant over samples.
    elbow: Sector,
    /// `asin(b/a)` (slightly widened) if `b < a`: then `arg(a + b e^{iθ}) ∈ [−spread, spread]`,
    /// because `a + b e^{iθ}` runs on a circle of radius `b` about `a`.
    spread: Option<f64>,
}

impl<'a> Sampler<'a> {
    /// `None` when fewer than two joints move, or the last two segments have a zero-length
    /// vector (then every slice is a curve).
    pub(super) fn new(reduced: &'a Reduced, samples: u64, seed: u64) -> Option<Sampler<'a>> {
        let n = reduced.segments.len();
        if n < 2 {
            return None;
        }
        let (j, k) = (&reduced.segments[n - 2], &reduced.segments[n - 1]);
        let a = math::hypot(j.w[0], j.w[1]);
        let b = math::hypot(k.w[0], k.w[1]);
        if !(a > 0.0 && b > 0.0) {
            return None;
        }
        let alpha = math::atan2(j.w[1], j.w[0]);
        let beta = j.gamma + math::atan2(k.w[1], k.w[0]);
        let elbow = Sector::of(k.range, beta - alpha);
        let spread = (b < a).then(|| math::asin(b / a) + 1e-9);
        Some(Sampler { reduced, plan: Plan::new(&reduced.segments, samples, seed), a, b, alpha, elbow, spread })
    }

    pub(super) fn count(&self) -> u64 {
        self.plan.count()
    }

    /// The slice of sample `i`: forward kinematics of the sampled joints gives the shoulder
    /// `P = J_j` and the reference direction `φ = Φ_{j−1} + γ_{j−1}`.
    pub(super) fn slice(&self, i: u64) -> Slice {
        let segments = &self.reduced.segments;
        let sampled = &segments[..segments.len() - 2];
        let [mut x, mut y] = self.reduced.start;
        let mut phi = self.reduced.phi0;
        for (k, seg) in sampled.iter().enumerate() {
            phi += self.plan.angle(seg.range, k, i);
            let (s, c) = math::sin_cos(phi);
            x += c * seg.w[0] - s * seg.w[1];
            y += s * seg.w[0] + c * seg.w[1];
            phi += seg.gamma;
        }
        let (a, b) = (self.a, self.b);
        let range = segments[segments.len() - 2].range;
        let reach = a + b;
        // The directions of `q − P`: shoulder directions widened by the spread of `arg w`.
        let (cone, bounds) = match self.spread {
            Some(spread) if !range.full && range.span + 2.0 * spread < TAU => {
                let lo = range.lo + phi + self.alpha - spread;
                let hi = lo + range.span + 2.0 * spread;
                let cone = Sector::new(lo, hi - lo);
                // Extremes of cos and sin over the cone: at an axis inside it, else at an end.
                let extreme = |axis: [f64; 2], f: fn(f64) -> f64| {
                    if cone.contains(axis) { 1.0 } else { f(lo).max(f(hi)) }
                };
                let right = extreme([1.0, 0.0], math::cos).max(0.0);
                let left = extreme([-1.0, 0.0], |t| -math::cos(t)).max(0.0);
                let up = extreme([0.0, 1.0], math::sin).max(0.0);
                let down = extreme([0.0, -1.0], |t| -math::sin(t)).max(0.0);
                (cone, [x - reach * left, x + reach * right, y - reach * down, y + reach * up])
            }
            _ => (Sector::Full, [x - reach, x + reach, y - reach, y + reach]),
        };
        Slice {
            p: [x, y],
            a,
            b,
            inv_two_ab: 0.5 / (a * b),
            a2b2: a * a + b * b,
            rmin2: (a - b) * (a - b),
            rmax2: reach * reach,
            shoulder: Sector::of(range, phi + self.alpha),
            elbow: self.elbow,
            cone,
            bounds,
        }
    }
}

/// The points `P + e^{iψ}(a + b e^{iθ})` for shoulder directions `ψ` and elbow angles `θ` in
/// their sectors: what the last two joints reach with the others fixed.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slice {
    pub(super) p: [f64; 2],
    pub(super) a: f64,
    pub(super) b: f64,
    inv_two_ab: f64,
    a2b2: f64,
    rmin2: f64,
    rmax2: f64,
    shoulder: Sector,
    elbow: Sector,
    /// A sector of directions from `P` holding the slice, to reject cells cheaply.
    cone: Sector,
    /// A box holding the slice: `[x_min, x_max, y_min, y_max]`.
    pub(super) bounds: [f64; 4],
}

impl Slice {
    /// Whether `q` lies in the slice.
    ///
    /// With `d = q − P` and `r = |d|`: the law of cosines `r² = a² + b² + 2ab cos θ` gives
    /// `cos θ = (r² − a² − b²)/(2ab) =: c`, so the elbow direction is `e = (c, ±√(1 − c²))`
    /// (none if `|c| > 1`, i.e. `r ∉ [|a − b|, a + b]`). For each sign with `e` in the elbow
    /// sector, `w = a + b e` has `|w| = r` and `d = e^{iψ} w`, so `e^{iψ} ∝ d · conj(w)`,
    /// which must lie in the shoulder sector.
    #[inline]
    pub(super) fn contains(&self, q: [f64; 2]) -> bool {
        let d = [q[0] - self.p[0], q[1] - self.p[1]];
        let r2 = dot(d, d);
        if r2 > self.rmax2 || r2 < self.rmin2 || !self.cone.contains(d) {
            return false;
        }
        let c = ((r2 - self.a2b2) * self.inv_two_ab).clamp(-1.0, 1.0);
        let s = (1.0 - c * c).max(0.0).sqrt();
        [s, -s].into_iter().any(|s| {
            if !self.elbow.contains([c, s]) {
                return false;
            }
            let w = [self.a + self.b * c, self.b * s];
            self.shoulder.contains([d[0] * w[0] + d[1] * w[1], d[1] * w[0] - d[0] * w[1]])
        })
    }
}
