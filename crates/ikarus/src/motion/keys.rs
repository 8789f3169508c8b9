//! Keyframes in time: a series of values (a target's `x` and `y`, any number of coordinates)
//! keyed at times, each key with the ease that shapes the segment from it to the next, as an
//! animator's keys on one track are.

use thiserror::Error;

use super::spline::Spline;
use crate::ease::Ease;
use crate::number::Num;

/// A track of keys: `n` coordinates keyed at strictly increasing times, interpolated by the
/// monotone cubic spline of [`Interpolation::Spline`](super::Interpolation) (PCHIP,
/// Fritsch–Carlson tangents, per coordinate, knots at the key times) and re-timed per segment by
/// the segment's first key's ease.
///
/// Between keys `i` and `i + 1`, at local progress `u = (t − tᵢ)/(tᵢ₊₁ − tᵢ)`, the value is the
/// spline at time `tᵢ + easeᵢ(u)·(tᵢ₊₁ − tᵢ)`; with two keys the spline is the straight segment
/// between them. At a key's time the value is the key, bit for bit; between two keys each
/// coordinate stays within their two values (the spline is monotone on every segment and the
/// ease stays in [0, 1]). Before the first key the track holds the first, after the last the
/// last; a one-key track holds its key. The last key's ease is unused.
#[derive(Debug, Clone)]
pub struct KeyTrack {
    n: usize,
    times: Vec<f64>,
    keys: Vec<f64>,
    eases: Vec<Ease>,
    spline: Option<Spline>,
}

/// Why keys cannot make a [`KeyTrack`].
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum KeyTrackError {
    /// No key, or no coordinate.
    #[error("a key track needs at least one key of at least one coordinate")]
    Empty,
    /// The values, times and eases do not come `n`, 1 and 1 per key.
    #[error("{times} times, {values} values of {n} coordinates and {eases} eases do not make keys")]
    Shape {
        /// Times given.
        times: usize,
        /// Values given.
        values: usize,
        /// Coordinates per key.
        n: usize,
        /// Eases given.
        eases: usize,
    },
    /// A time that is not finite or not after the previous key's.
    #[error("key {index}: time {} must be finite and after the previous key's", Num(*.time))]
    Time {
        /// The key's index.
        index: usize,
        /// Its time.
        time: f64,
    },
    /// A value that is not finite.
    #[error("key {index}: value {} is not finite", Num(*.value))]
    Value {
        /// The key's index.
        index: usize,
        /// The value.
        value: f64,
    },
}

impl KeyTrack {
    /// The track of `times.len()` keys of `n` coordinates each, `values` stored key after key,
    /// `eases[i]` shaping the segment from key `i` to key `i + 1`.
    ///
    /// # Errors
    /// [`KeyTrackError`] for an empty track, lengths that do not match, times not finite or not
    /// strictly increasing, values not finite.
    pub fn new(n: usize, times: Vec<f64>, values: Vec<f64>, eases: Vec<Ease>) -> Result<Self, KeyTrackError> {
        if n == 0 || times.is_empty() {
            return Err(KeyTrackError::Empty);
        }
        if values.len() != n * times.len() || eases.len() != times.len() {
            return Err(KeyTrackError::Shape { times: times.len(), values: values.len(), n, eases: eases.len() });
        }
        for (index, &time) in times.iter().enumerate() {
            if !time.is_finite() || (index > 0 && time <= times[index - 1]) {
                return Err(KeyTrackError::Time { index, time });
            }
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(KeyTrackError::Value { index: i / n, value: values[i] });
        }
        let spline = Spline::new(n, times.clone(), values.clone());
        Ok(Self { n, times, keys: values, eases, spline })
    }

    /// The time of the last key.
    #[must_use]
    pub fn end(&self) -> f64 {
        self.times[self.times.len() - 1]
    }

    /// The keys' times, in increasing order.
    #[must_use]
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The coordinates at time `t` into `out` (cleared first): see [`KeyTrack`].
    pub fn at(&self, t: f64, out: &mut Vec<f64>) {
        let last = self.times.len() - 1;
        // The segment [t_k, t_{k+1}] holding t; before the first key or from the last on, a key.
        let k = self.times.partition_point(|&x| x <= t);
        if k == 0 || k > last {
            let key = if k == 0 { 0 } else { last };
            out.clear();
            out.extend_from_slice(&self.keys[key * self.n..(key + 1) * self.n]);
            return;
        }
        let k = k - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let h = t1 - t0;
        let s = self.eases[k].position((t - t0) / h);
        match &self.spline {
            Some(spline) => spline.on_segment(k, t0 + s * h, out),
            None => {
                let (a, b) = (&self.keys[..self.n], &self.keys[self.n..]);
                out.clear();
                out.extend(a.iter().zip(b).map(|(&a, &b)| lerp(a, b, s)));
            }
        }
    }
}

/// `a + (b − a)·s`: exactly `a` at 0 and `b` at 1, and between them.
fn lerp(a: f64, b: f64, s: f64) -> f64 {
    if s <= 0.0 {
        return a;
    }
    if s >= 1.0 {
        return b;
    }
    (a + (b - a) * s).clamp(a.min(b), a.max(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn track(times: &[f64], xy: &[[f64; 2]], eases: &[Ease]) -> KeyTrack {
        let values = xy.iter().flatten().copied().collect();
        KeyTrack::new(2, times.to_vec(), values, eases.to_vec()).unwrap()
    }

    fn at(t: &KeyTrack, time: f64) -> Vec<f64> {
        let mut out = Vec::new();
        t.at(time, &mut out);
        out
    }

    fn eases() -> Vec<Ease> {
        vec![
            Ease::Linear,
            Ease::Sine,
            Ease::Smoothstep,
            Ease::parent(0.2, 0.8).unwrap(),
            Ease::parent(0.0, 0.5).unwrap(),
        ]
    }

    /// A walk-like cycle of four keys plus the return, with every ease.
    fn cycle(ease: Ease) -> (Vec<f64>, Vec<[f64; 2]>, KeyTrack) {
        let times = vec![0.0, 1.0 / 3.0, 0.5, 0.9, 1.2];
        let xy = vec![[0.1, -0.9], [0.35, -0.75], [0.3, -0.9], [-0.2, -0.88], [0.1, -0.9]];
        let t = track(&times, &xy, &[ease; 5]);
        (times, xy, t)
    }

    #[test]
    fn at_each_key_time_the_value_is_the_key_bit_for_bit() {
        for ease in eases() {
            let (times, xy, t) = cycle(ease);
            for (time, key) in times.iter().zip(&xy) {
                let v = at(&t, *time);
                assert_eq!([v[0].to_bits(), v[1].to_bits()], [key[0].to_bits(), key[1].to_bits()], "{ease:?} {time}");
            }
        }
    }

    #[test]
    fn between_keys_each_coordinate_stays_within_its_two_keys() {
        for ease in eases() {
            let (times, xy, t) = cycle(ease);
            for k in 0..times.len() - 1 {
                for i in 0..=200 {
                    let time = times[k] + (times[k + 1] - times[k]) * f64::from(i) / 200.0;
                    let v = at(&t, time);
                    for c in 0..2 {
                        let (lo, hi) = (xy[k][c].min(xy[k + 1][c]), xy[k][c].max(xy[k + 1][c]));
                        assert!(
                            (lo..=hi).contains(&v[c]),
                            "{ease:?} segment {k} t {time}: {} not in [{lo}, {hi}]",
                            v[c]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn linear_ease_with_two_keys_is_a_straight_line_at_constant_speed() {
        let t = track(&[0.0, 0.8], &[[1.0, -2.0], [3.0, 2.0]], &[Ease::Linear, Ease::Sine]);
        for i in 0..=80 {
            let time = 0.01 * f64::from(i);
            let v = at(&t, time);
            let u = time / 0.8;
            assert!((v[0] - (1.0 + 2.0 * u)).abs() < 1e-14, "{time}: {v:?}");
            assert!((v[1] - (-2.0 + 4.0 * u)).abs() < 1e-14, "{time}: {v:?}");
        }
    }

    #[test]
    fn sine_and_parent_eases_shape_the_segment_as_the_library_s_ease() {
        for ease in [Ease::Sine, Ease::parent(0.2, 0.8).unwrap(), Ease::parent(0.3, 0.6).unwrap()] {
            let t = track(&[0.0, 0.5], &[[0.0, 1.0], [2.0, -1.0]], &[ease, Ease::Linear]);
            for i in 1..50 {
                let time = 0.01 * f64::from(i);
                let s = ease.position(time / 0.5);
                let v = at(&t, time);
                assert!((v[0] - 2.0 * s).abs() < 1e-14 && (v[1] - (1.0 - 2.0 * s)).abs() < 1e-14, "{ease:?} {time}");
            }
        }
        // With more keys, the ease re-times the spline: the value at local progress u is the
        // linear-eased track's at the eased progress.
        let (times, _, sine) = cycle(Ease::Sine);
        let (_, _, linear) = cycle(Ease::Linear);
        let (t0, t1) = (times[1], times[2]);
        for u in [0.1, 0.25, 0.5, 0.9] {
            let s = Ease::Sine.position(u);
            let (a, b) = (at(&sine, t0 + u * (t1 - t0)), at(&linear, t0 + s * (t1 - t0)));
            assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12, "{u}: {a:?} {b:?}");
        }
    }

    #[test]
    fn three_keys_follow_the_motion_s_monotone_cubic_not_a_polyline() {
        // Keys 0, 1, 3 at times 0, 1, 2: secants 1 and 2, PCHIP slopes 1/2 at the first key
        // (the limited three-point estimate) and 4/3 at the middle one (the weighted harmonic
        // mean); the cubic at t = 0.5 is 1/2 + (1/2)/8 − (4/3)/8 = 19/48, not the line's 1/2.
        let t = KeyTrack::new(1, vec![0.0, 1.0, 2.0], vec![0.0, 1.0, 3.0], vec![Ease::Linear; 3]).unwrap();
        let v = at(&t, 0.5);
        assert!((v[0] - 19.0 / 48.0).abs() < 1e-15, "{v:?}");
    }

    #[test]
    fn a_track_holds_its_first_key_before_it_and_its_last_after_it() {
        let one = track(&[0.0], &[[0.5, 0.25]], &[Ease::Sine]);
        assert_eq!(at(&one, 0.0), vec![0.5, 0.25]);
        assert_eq!(at(&one, 3.0), vec![0.5, 0.25]);
        let (_, xy, t) = cycle(Ease::Sine);
        assert_eq!(at(&t, 5.0), xy[4].to_vec());
        assert_eq!(at(&t, -1.0), xy[0].to_vec());
        assert_eq!(t.end(), 1.2);
    }

    #[test]
    fn bad_keys_are_refused() {
        let e = |times: &[f64], values: &[f64]| {
            KeyTrack::new(1, times.to_vec(), values.to_vec(), vec![Ease::Sine; times.len()]).unwrap_err()
        };
        assert_eq!(e(&[], &[]), KeyTrackError::Empty);
        assert_eq!(
            e(&[0.0, 0.0], &[1.0, 2.0]).to_string(),
            "key 1: time 0 must be finite and after the previous key's"
        );
        assert_eq!(e(&[0.0, 1.0], &[1.0, f64::NAN]).to_string(), "key 1: value NaN is not finite");
        assert!(matches!(e(&[0.0], &[1.0, 2.0]), KeyTrackError::Shape { .. }));
    }
}
