//! The spline through the keyframes: a monotone cubic Hermite curve per joint (PCHIP) and the
//! pose at a point of it. The scheme, its timing, its continuity and why it cannot overshoot
//! are documented on [`Interpolation`](super::Interpolation).

use super::path::Path;

/// A monotone cubic Hermite spline through keyframes, one per joint over shared knots.
#[derive(Debug, Clone)]
pub(super) struct Spline {
    /// Joints per pose.
    n: usize,
    /// Knots `u_k`, strictly increasing, one per keyframe.
    knots: Vec<f64>,
    /// Keyframe values, `n` per knot, stored flat.
    keys: Vec<f64>,
    /// Tangents `dq/du` at the knots, `n` per knot, stored flat.
    slopes: Vec<f64>,
}

impl Spline {
    /// The spline over the cumulative chord lengths `C_k` of `path` (so that [`Spline::at`]
    /// takes the polyline's arc length); keyframes that repeat the previous one are dropped. `None` with fewer than three
    /// distinct keyframes: the spline would be the straight segment of the polyline.
    pub(super) fn by_length(path: &Path) -> Option<Self> {
        let cumulative = path.cumulative();
        let mut knots = Vec::with_capacity(cumulative.len());
        let mut keys = Vec::with_capacity(cumulative.len() * path.joints());
        for (k, &c) in cumulative.iter().enumerate() {
            if knots.last().is_none_or(|&last| c > last) {
                knots.push(c);
                keys.extend_from_slice(path.key(k));
            }
        }
        Self::new(path.joints(), knots, keys)
    }

    /// The spline over `times` (one per keyframe, strictly increasing). `None` with fewer than three keyframes.
    pub(super) fn by_times(path: &Path, times: &[f64]) -> Option<Self> {
        let keys = (0..times.len()).flat_map(|k| path.key(k).iter().copied()).collect();
        Self::new(path.joints(), times.to_vec(), keys)
    }

    /// The spline over `knots` (strictly increasing) of `keys` (`n` per knot, stored flat).
    /// `None` with fewer than three knots.
    pub(super) fn new(n: usize, knots: Vec<f64>, keys: Vec<f64>) -> Option<Self> {
        if knots.len() < 3 {
            return None;
        }
        let slopes = slopes(n, &knots, &keys);
        Some(Self { n, knots, keys, slopes })
    }

    /// The pose at parameter `u` (clamped to the knots): exactly keyframe `k` at `u = u_k`.
    pub(super) fn at(&self, u: f64, out: &mut Vec<f64>) {
        let k = self.knots.partition_point(|&x| x <= u).clamp(1, self.knots.len() - 1) - 1;
        self.on_segment(k, u, out);
    }

    /// The pose at parameter `u` of segment `k` (the Hermite form on
    /// [`Interpolation`](super::Interpolation)), each angle clamped to its two keyframe values.
    pub(super) fn on_segment(&self, k: usize, u: f64, out: &mut Vec<f64>) {
        let (u0, u1) = (self.knots[k], self.knots[k + 1]);
        let h = u1 - u0;
        let t = ((u - u0) / h).clamp(0.0, 1.0);
        let (a, b) = (self.at_knot(&self.keys, k), self.at_knot(&self.keys, k + 1));
        let (ma, mb) = (self.at_knot(&self.slopes, k), self.at_knot(&self.slopes, k + 1));
        out.clear();
        out.extend((0..self.n).map(|i| hermite(a[i], b[i], h * ma[i], h * mb[i], t)));
    }

    fn at_knot<'a>(&self, flat: &'a [f64], k: usize) -> &'a [f64] {
        &flat[k * self.n..(k + 1) * self.n]
    }
}

/// The cubic from `a` (at `t = 0`, tangent `da`) to `b` (at `t = 1`, tangent `db`), per unit
/// `t`: exactly `a` at 0 and `b` at 1, and clamped to the interval between them (it lies there
/// in exact arithmetic for monotone tangents; rounding could step over a limit by an ulp).
fn hermite(a: f64, b: f64, da: f64, db: f64, t: f64) -> f64 {
    if t <= 0.0 {
        return a;
    }
    if t >= 1.0 {
        return b;
    }
    let (t2, t3) = (t * t, t * t * t);
    let v = a + (b - a) * (3.0 * t2 - 2.0 * t3) + da * (t3 - 2.0 * t2 + t) + db * (t3 - t2);
    v.clamp(a.min(b), a.max(b))
}

/// The PCHIP tangents of every joint at every knot (see
/// [`Interpolation`](super::Interpolation)): 0 where the secants differ in sign, their
/// weighted harmonic mean otherwise, and the limited three-point estimate at both ends.
fn slopes(n: usize, knots: &[f64], keys: &[f64]) -> Vec<f64> {
    let count = knots.len();
    let h: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
    let mut out = vec![0.0; count * n];
    for i in 0..n {
        let delta: Vec<f64> = (0..count - 1).map(|k| (keys[(k + 1) * n + i] - keys[k * n + i]) / h[k]).collect();
        for k in 1..count - 1 {
            out[k * n + i] = harmonic(h[k - 1], h[k], delta[k - 1], delta[k]);
        }
        out[i] = end(h[0], h[1], delta[0], delta[1]);
        let last = count - 2;
        out[(count - 1) * n + i] = end(h[last], h[last - 1], delta[last], delta[last - 1]);
    }
    out
}

/// Fritsch–Butland's weighted harmonic mean of two secants, 0 unless both have the same sign.
/// It lies between 0 and `3·min(|d0|, |d1|)`.
fn harmonic(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    if d0 * d1 <= 0.0 || d0.signum() != d1.signum() {
        return 0.0;
    }
    let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
    let m = (w1 + w2) / (w1 / d0 + w2 / d1);
    if m.is_finite() { m } else { 0.0 }
}

/// The end tangent from the end segment (`h0`, `d0`) and its neighbour (`h1`, `d1`): the
/// three-point estimate, 0 if it points against `d0`, at most `3·|d0|` if the secants differ
/// in sign (SciPy's `PchipInterpolator`). It lies between 0 and `3·d0`.
fn end(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if !m.is_finite() || m.signum() != d0.signum() || d0 == 0.0 {
        0.0
    } else if d0.signum() != d1.signum() && m.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangents_stay_in_the_monotone_square() {
        // Harmonic mean: same sign as the secants, at most 3 × the smaller.
        for (h0, h1, d0, d1) in [(1.0, 1.0, 1.0, 1.0), (0.1, 5.0, 4.0, 0.01), (5.0, 0.1, -0.01, -4.0)] {
            let m: f64 = harmonic(h0, h1, d0, d1);
            assert!(m * d0 > 0.0 && m.abs() <= 3.0 * d0.abs().min(d1.abs()), "{m}");
        }
        assert_eq!(harmonic(1.0, 1.0, 1.0, -1.0), 0.0);
        assert_eq!(harmonic(1.0, 1.0, 0.0, 1.0), 0.0);
        // End: never against the end secant, never more than 3 × it.
        for (h0, h1, d0, d1) in
            [(1.0, 1.0, 1.0, 1.0), (1.0, 0.1, 1.0, -5.0), (0.1, 10.0, 1.0, 9.0), (1.0, 1.0, 1.0, 4.0)]
        {
            let m: f64 = end(h0, h1, d0, d1);
            assert!((0.0..=3.0).contains(&(m / d0)), "{h0} {h1} {d0} {d1}: {m}");
        }
        // Equal secants give the secant: the straight line.
        assert_eq!(end(1.0, 2.0, 0.5, 0.5), 0.5);
        assert_eq!(harmonic(1.0, 2.0, 0.5, 0.5), 0.5);
    }

    #[test]
    fn hermite_is_exact_at_the_ends_and_stays_between_them() {
        assert_eq!(hermite(0.3, 1.7, 4.2, 4.2, 0.0).to_bits(), 0.3f64.to_bits());
        assert_eq!(hermite(0.3, 1.7, 4.2, 4.2, 1.0).to_bits(), 1.7f64.to_bits());
        for i in 0..=100 {
            let v = hermite(-1.0, 1.0, 6.0, 6.0, f64::from(i) / 100.0);
            assert!((-1.0..=1.0).contains(&v), "{v}");
        }
    }
}
