//! Keys with Bézier curves fitted to a sampled channel, as Spine's runtime plays them.
//!
//! A segment between two keys is a Spine 4 Bézier per channel, `[cx1, cy1, cx2, cy2]` in the
//! keys' own time and value, with the control times at a third and two thirds of the segment
//! and the control values from the channel's slopes at the two keys (a cubic Hermite segment:
//! exactly a cubic in time, as ikarus's PCHIP segments are before their ease). The fit is
//! checked as the runtime plays it ([`value_at`]: the cubic sampled at tenths, linear between,
//! every number a 32-bit float) at [`CHECKS`] times inside the segment; where it strays past
//! the tolerance the segment is split by a key halfway (a 32-bit time strictly between), at
//! most [`MAX_DEPTH`] times deep and while the export's budget of added keys lasts. A straight
//! line that fits is written without a curve. Spine 3.8 files, whose curve is one for every
//! channel, get straight lines only (split as needed).

use super::read_time;
use crate::error::Error;

/// Times checked inside a segment (evenly spread, the keys excluded).
pub(super) const CHECKS: usize = 29;

/// How many times a segment is halved at most (a key every 1/2¹² of the gap between two
/// neighbouring key times at the finest).
const MAX_DEPTH: u32 = 12;

/// What a fit makes of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Shape {
    /// Bézier curves (Spine 4).
    Bezier,
    /// Straight lines only (Spine 3.8).
    Linear,
}

/// A channel's value at a time, and how far (in the file's units) one unit of error in it
/// moves the bones it carries.
#[derive(Debug, Clone, Copy)]
pub(super) struct Sample {
    /// The channel's values (the second unused for a one-value timeline).
    pub values: [f64; 2],
    /// World units per unit of the values.
    pub weight: f64,
}

/// One key written: its time (a 32-bit float), values and curve toward the next key.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct FittedKey {
    /// Seconds, as the runtime reads them.
    pub time: f64,
    /// The values.
    pub values: [f64; 2],
    /// Per channel `[cx1, cy1, cx2, cy2]` toward the next key, or a straight line.
    pub curve: Option<[[f64; 4]; 2]>,
}

/// The fit of one timeline.
pub(super) struct Fitter<'a> {
    /// How many values a key holds (1 or 2).
    pub channels: usize,
    /// Whether values are angles in degrees (each sample unwrapped to within 180° of the last
    /// key's value).
    pub period: Option<f64>,
    /// Curves or lines.
    pub shape: Shape,
    /// The largest error allowed, in world units.
    pub tolerance: f64,
    /// Keys that may still be added (shared by every timeline of the export).
    pub budget: &'a mut usize,
}

impl Fitter<'_> {
    /// Keys at every time of `anchors` (32-bit times, increasing) and wherever a segment needs
    /// one, the channel read by `sample`.
    pub(super) fn fit(
        &mut self,
        anchors: &[f64],
        sample: &mut dyn FnMut(f64) -> Result<Sample, Error>,
    ) -> Result<Vec<FittedKey>, Error> {
        let mut out: Vec<FittedKey> = Vec::with_capacity(anchors.len());
        let mut last: Option<(f64, [f64; 2])> = None;
        for &t in anchors {
            let mut s = sample(t)?;
            if let Some(prev) = last {
                s.values = self.unwrapped(s.values, prev.1);
                self.segment(prev, (t, s.values), 0, sample, &mut out)?;
            }
            last = Some((t, s.values));
        }
        if let Some((time, values)) = last {
            out.push(FittedKey { time, values, curve: None });
        }
        Ok(out)
    }

    /// `v` unwrapped to within half a turn of `near` (angles only).
    fn unwrapped(&self, mut v: [f64; 2], near: [f64; 2]) -> [f64; 2] {
        if let Some(turn) = self.period {
            for k in 0..self.channels {
                v[k] = near[k] + wrap(v[k] - near[k], turn);
            }
        }
        v
    }

    /// Pushes the key at `a` (and those the segment to `b` needs, not `b`).
    fn segment(
        &mut self,
        a: (f64, [f64; 2]),
        b: (f64, [f64; 2]),
        depth: u32,
        sample: &mut dyn FnMut(f64) -> Result<Sample, Error>,
        out: &mut Vec<FittedKey>,
    ) -> Result<(), Error> {
        let h = b.0 - a.0;
        let mut checks = Vec::with_capacity(CHECKS);
        for j in 1..=CHECKS {
            let t = read_time(a.0 + h * j as f64 / (CHECKS + 1) as f64);
            if t > a.0 && t < b.0 {
                let mut s = sample(t)?;
                s.values = self.unwrapped(s.values, a.1);
                checks.push((t, s));
            }
        }
        let line = None;
        let curve = match self.shape {
            Shape::Linear => None,
            Shape::Bezier => Some(self.hermite(a, b, sample)?),
        };
        let mut best = (f64::INFINITY, None);
        for candidate in [line, curve] {
            if candidate.is_none() && best.1.is_some() {
                continue;
            }
            let err = self.error(a, b, candidate.as_ref(), &checks);
            if err < best.0 {
                best = (err, candidate);
            }
            if err <= self.tolerance {
                out.push(FittedKey { time: a.0, values: a.1, curve: candidate });
                return Ok(());
            }
        }
        let mid = read_time(a.0 + h / 2.0);
        if depth >= MAX_DEPTH || *self.budget == 0 || mid <= a.0 || mid >= b.0 {
            out.push(FittedKey { time: a.0, values: a.1, curve: best.1 });
            return Ok(());
        }
        *self.budget -= 1;
        let mut m = sample(mid)?;
        m.values = self.unwrapped(m.values, a.1);
        self.segment(a, (mid, m.values), depth + 1, sample, out)?;
        self.segment((mid, m.values), b, depth + 1, sample, out)
    }

    /// The cubic Hermite segment from `a` to `b` with the channel's slopes at both ends
    /// (one-sided second-order differences inside the segment), as Bézier control points.
    fn hermite(
        &mut self,
        a: (f64, [f64; 2]),
        b: (f64, [f64; 2]),
        sample: &mut dyn FnMut(f64) -> Result<Sample, Error>,
    ) -> Result<[[f64; 4]; 2], Error> {
        let h = b.0 - a.0;
        let e = h / 64.0;
        let mut at = |t: f64, near: [f64; 2]| -> Result<[f64; 2], Error> {
            let s = sample(t)?;
            Ok(self.unwrapped(s.values, near))
        };
        let (a1, a2) = (at(a.0 + e, a.1)?, at(a.0 + 2.0 * e, a.1)?);
        let (b1, b2) = (at(b.0 - e, b.1)?, at(b.0 - 2.0 * e, b.1)?);
        let mut curve = [[0.0; 4]; 2];
        for k in 0..self.channels {
            let m0 = (-3.0 * a.1[k] + 4.0 * a1[k] - a2[k]) / (2.0 * e);
            let m1 = (3.0 * b.1[k] - 4.0 * b1[k] + b2[k]) / (2.0 * e);
            curve[k] = [a.0 + h / 3.0, a.1[k] + m0 * h / 3.0, b.0 - h / 3.0, b.1[k] - m1 * h / 3.0];
        }
        Ok(curve)
    }

    /// The largest error, in world units, of the segment from `a` to `b` (with `curve`, or a
    /// straight line) against the samples `checks`.
    fn error(
        &self,
        a: (f64, [f64; 2]),
        b: (f64, [f64; 2]),
        curve: Option<&[[f64; 4]; 2]>,
        checks: &[(f64, Sample)],
    ) -> f64 {
        let mut worst: f64 = 0.0;
        for (t, s) in checks {
            let mut d = [0.0; 2];
            for k in 0..self.channels {
                let v = value_at(curve.map(|c| c[k]), (a.0, a.1[k]), (b.0, b.1[k]), *t);
                d[k] = v - s.values[k];
            }
            worst = worst.max(d[0].hypot(d[1]) * s.weight);
        }
        if worst.is_nan() { f64::INFINITY } else { worst }
    }
}

/// `v` less the whole turns that bring it into [−turn/2, turn/2].
pub(super) fn wrap(v: f64, turn: f64) -> f64 {
    v - turn * (v / turn).round()
}

/// A value rounded to the runtime's 32-bit float.
fn f32ed(v: f64) -> f64 {
    f64::from(v as f32)
}

/// The value at `time` of the segment from `(t0, v0)` to `(t1, v1)` with the Bézier `curve`
/// (`[cx1, cy1, cx2, cy2]`) or a straight line, as Spine's runtime plays it: every number a
/// 32-bit float, the cubic sampled at u = 0.1 … 0.9 by forward differences, linear in time
/// between the samples (the library's clip reader does the same).
pub(super) fn value_at(curve: Option<[f64; 4]>, (t0, v0): (f64, f64), (t1, v1): (f64, f64), time: f64) -> f64 {
    let (t0, v0, t1, v1) = (f32ed(t0), f32ed(v0), f32ed(t1), f32ed(v1));
    let Some([cx1, cy1, cx2, cy2]) = curve else {
        return v0 + (time - t0) / (t1 - t0) * (v1 - v0);
    };
    let mut samples = [[0.0; 2]; 11];
    samples[0] = [t0, v0];
    samples[10] = [t1, v1];
    for (k, q) in [[t0, cx1, cx2, t1], [v0, cy1, cy2, v1]].into_iter().enumerate() {
        for (s, v) in samples[1..10].iter_mut().zip(tenths(q)) {
            s[k] = v;
        }
    }
    for w in samples.windows(2) {
        if w[1][0] >= time {
            let span = w[1][0] - w[0][0];
            return if span > 0.0 { w[0][1] + (time - w[0][0]) / span * (w[1][1] - w[0][1]) } else { w[1][1] };
        }
    }
    v1
}

/// The runtime's nine samples of one coordinate of a cubic Bézier `q` (end, control, control,
/// end) at u = 0.1 … 0.9, by forward differences, each a 32-bit float: for a curve's time
/// coordinate, the times where the runtime's piecewise-linear playback of it bends.
pub(super) fn tenths(q: [f64; 4]) -> [f64; 9] {
    let (q0, q1, q2, q3) = (f32ed(q[0]), f32ed(q[1]), f32ed(q[2]), f32ed(q[3]));
    let quad = (q0 - 2.0 * q1 + q2) * 0.03;
    let third = ((q1 - q2) * 3.0 - q0 + q3) * 0.006;
    let mut second = quad * 2.0 + third;
    let mut first = (q1 - q0) * 0.3 + quad + third / 6.0;
    let mut v = q0 + first;
    let mut out = [0.0; 9];
    for s in &mut out {
        *s = f32ed(v);
        first += second;
        second += third;
        v += first;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cubic_is_fitted_by_one_curve_and_a_kink_by_more_keys() {
        let mut budget = 100;
        let mut fitter =
            Fitter { channels: 1, period: None, shape: Shape::Bezier, tolerance: 1e-2, budget: &mut budget };
        // A cubic in time over one second: its Hermite segment is exact, up to the runtime's
        // playback as ten chords (at most 6 · 0.1² / 8 = 7.5e-3 off here).
        let mut cubic = |t: f64| Ok(Sample { values: [3.0 * t * t - 2.0 * t * t * t, 0.0], weight: 1.0 });
        let keys = fitter.fit(&[0.0, 1.0], &mut cubic).unwrap();
        assert_eq!(keys.len(), 2);
        assert!(keys[0].curve.is_some());
        // |t − 0.3| has a kink no cubic follows: keys are added near it, the rest is lines.
        let mut kink = |t: f64| Ok(Sample { values: [(t - 0.3).abs(), 0.0], weight: 1.0 });
        let keys = fitter.fit(&[0.0, 1.0], &mut kink).unwrap();
        assert!(keys.len() > 2 && keys.len() < 30, "{}", keys.len());
        for w in keys.windows(2) {
            for j in 1..10 {
                let t = w[0].time + (w[1].time - w[0].time) * j as f64 / 10.0;
                let v = value_at(w[0].curve.map(|c| c[0]), (w[0].time, w[0].values[0]), (w[1].time, w[1].values[0]), t);
                assert!((v - (t - 0.3).abs()).abs() < 1.1e-2, "at {t}: {v}");
            }
        }
    }

    #[test]
    fn angles_are_unwrapped_across_the_half_turn() {
        let mut budget = 100;
        let mut fitter =
            Fitter { channels: 1, period: Some(360.0), shape: Shape::Linear, tolerance: 1e-6, budget: &mut budget };
        // 170° to 190° (written as −170°) is 20° the short way, a straight line.
        let mut turn = |t: f64| Ok(Sample { values: [wrap(170.0 + 20.0 * t, 360.0), 0.0], weight: 1.0 });
        let keys = fitter.fit(&[0.0, 1.0], &mut turn).unwrap();
        assert_eq!(keys.len(), 2);
        assert!((keys[1].values[0] - 190.0).abs() < 1e-9);
    }
}
