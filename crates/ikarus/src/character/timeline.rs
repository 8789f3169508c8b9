//! Sampling a clip's timelines at a time, as Spine's runtime does.
//!
//! Key times and values are held as 32-bit floats by the runtime, so they are rounded to `f32`
//! here before use. A Bézier segment is not evaluated exactly: the cubic from `(t₀, v₀)` through
//! the control points `c1`, `c2` to `(t₁, v₁)` is sampled at the parameters u = 0.1, 0.2, …, 0.9
//! by forward differences (the samples rounded to `f32`), and the value at a time is the linear
//! interpolation in time between the neighbouring samples (the keys count as the samples at
//! u = 0 and u = 1). Before the first key a timeline gives the setup value, after the last key
//! the last key's value.

use super::{
    BoneKey, BoneProperty, BoneTimeline, ChannelKey, Clip, IkKey, IkSettings, Interpolation, LocalTransform,
    MAX_CHANNELS,
};

/// A value rounded to the runtime's `f32`.
pub(crate) fn f32ed(v: f64) -> f64 {
    v as f32 as f64
}

/// The nine samples of a Bézier segment, `[time, value]` at u = 0.1 … 0.9, by forward
/// differences with step h = 0.1 on `B(u) = P₀ + 3(P₁ − P₀)u + 3(P₀ − 2P₁ + P₂)u² +
/// (P₃ − P₀ + 3(P₁ − P₂))u³`: first difference `3(P₁ − P₀)h + 3(P₀ − 2P₁ + P₂)h² + C₃h³`,
/// second `6(P₀ − 2P₁ + P₂)h² + 6C₃h³`, third `6C₃h³`.
fn bezier_samples(p0: [f64; 2], c1: [f64; 2], c2: [f64; 2], p3: [f64; 2]) -> [[f64; 2]; 9] {
    let mut out = [[0.0; 2]; 9];
    for k in 0..2 {
        let (q0, q1, q2, q3) = (p0[k], f32ed(c1[k]), f32ed(c2[k]), p3[k]);
        let quad = (q0 - 2.0 * q1 + q2) * 0.03;
        let third = ((q1 - q2) * 3.0 - q0 + q3) * 0.006;
        let mut second = quad * 2.0 + third;
        let mut first = (q1 - q0) * 0.3 + quad + third / 6.0;
        let mut v = q0 + first;
        for s in out.iter_mut() {
            s[k] = f32ed(v);
            first += second;
            second += third;
            v += first;
        }
    }
    out
}

/// The nine samples of every Bézier segment of a character's clips, computed once when the
/// character is made, exactly as [`bezier_samples`] computes them when a pose needs them.
#[derive(Clone, Default, PartialEq)]
pub(crate) struct Curves {
    /// Per clip, per bone timeline then per constraint timeline: its channels per key and, per
    /// key and channel (`channels·key + ch`), the index of the segment's samples in `samples`,
    /// or `NONE` for a segment that is not a Bézier one (and the last key's).
    slots: Vec<Vec<(usize, Vec<u32>)>>,
    samples: Vec<[[f64; 2]; 9]>,
}

/// No Bézier samples.
const NONE: u32 = u32::MAX;

impl std::fmt::Debug for Curves {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Curves({} Bézier segments)", self.samples.len())
    }
}

impl Curves {
    /// The samples of every Bézier segment of `clips`.
    pub(crate) fn of(clips: &[Clip]) -> Curves {
        let mut out = Curves::default();
        for clip in clips {
            let mut per_clip = Vec::with_capacity(clip.bones.len() + clip.constraints.len());
            for t in &clip.bones {
                per_clip.push(out.timeline(t.keys.len(), 2, |i, ch| {
                    let (k, n) = (&t.keys[i], &t.keys[i + 1]);
                    (k.curves[ch], [k.time, k.values[ch]], [n.time, n.values[ch]])
                }));
            }
            for t in &clip.constraints {
                let keys = &t.keys;
                per_clip.push(out.timeline(keys.len(), keys.channels(), |i, ch| {
                    let ((curve, v0), (_, v1)) = (keys.channel(i, ch), keys.channel(i + 1, ch));
                    (curve, [keys.time(i), v0], [keys.time(i + 1), v1])
                }));
            }
            out.slots.push(per_clip);
        }
        out
    }

    /// One timeline's slots; `segment(i, ch)` is key `i`'s curve on channel `ch` and the two
    /// keys' `[time, value]`, not yet rounded.
    fn timeline(
        &mut self,
        keys: usize,
        channels: usize,
        segment: impl Fn(usize, usize) -> (Interpolation, [f64; 2], [f64; 2]),
    ) -> (usize, Vec<u32>) {
        let mut slots = vec![NONE; channels * keys];
        for i in 0..keys.saturating_sub(1) {
            for ch in 0..channels {
                if let (Interpolation::Bezier { c1, c2 }, p0, p1) = segment(i, ch) {
                    slots[channels * i + ch] = self.samples.len() as u32;
                    let f = |p: [f64; 2]| [f32ed(p[0]), f32ed(p[1])];
                    self.samples.push(bezier_samples(f(p0), c1, c2, f(p1)));
                }
            }
        }
        (channels, slots)
    }

    /// Clip `clip`'s curves (none for a clip the curves do not know).
    pub(crate) fn clip(&self, clip: usize) -> ClipCurves<'_> {
        ClipCurves { samples: &self.samples, slots: self.slots.get(clip).map_or(&[][..], |c| c.as_slice()) }
    }
}

/// One clip's curves: [`Curves`] with the clip looked up once.
#[derive(Clone, Copy)]
pub(crate) struct ClipCurves<'a> {
    samples: &'a [[[f64; 2]; 9]],
    /// Per timeline, its channels per key and its segments' slots.
    slots: &'a [(usize, Vec<u32>)],
}

/// Where a timeline is read: the character's precomputed curves, the clip and the timeline's
/// index in it (bone timelines first), and the timeline's last key, cached across poses (the
/// number of keys at or before the last time asked, a hint checked before it is used).
pub(crate) struct Reader<'a> {
    samples: &'a [[[f64; 2]; 9]],
    /// The timeline's channels per key.
    channels: usize,
    /// Per key and channel, the index of its segment's samples (see [`Curves`]).
    slots: &'a [u32],
    last: &'a mut u32,
}

impl<'a> Reader<'a> {
    /// The reader of timeline `timeline` of a clip (bone timelines first), its last key cached
    /// in `last`: the timeline's slots are looked up once, not per segment.
    pub(crate) fn new(curves: ClipCurves<'a>, timeline: usize, last: &'a mut u32) -> Reader<'a> {
        let (channels, slots) = curves.slots.get(timeline).map_or((0, &[][..]), |(ch, s)| (*ch, s.as_slice()));
        Reader { samples: curves.samples, channels, slots, last }
    }

    /// The samples of the timeline's segment from key `key` on channel `ch`, if that segment
    /// is a Bézier one.
    fn samples(&self, key: usize, ch: usize) -> Option<&'a [[f64; 2]; 9]> {
        let slot = *self.slots.get(self.channels * key + ch)?;
        self.samples.get(slot as usize)
    }
    /// The index of the last key whose (f32) time is at or before `time`, or `None` before
    /// the first key: the cached key if it still is that key, else the next one if that is it,
    /// else by binary search (which the answer does not depend on: the number of keys at or
    /// before `time` is the one `n` with key `n − 1` at or before and key `n` after it).
    fn key_at(&mut self, times: impl Fn(usize) -> f64, len: usize, time: f64) -> Option<usize> {
        let fits =
            |n: usize| n <= len && (n == 0 || f32ed(times(n - 1)) <= time) && (n == len || f32ed(times(n)) > time);
        let hint = *self.last as usize;
        let n = if fits(hint) {
            hint
        } else if fits(hint + 1) {
            hint + 1
        } else {
            key_at(&times, len, time).map_or(0, |i| i + 1)
        };
        *self.last = n as u32;
        n.checked_sub(1)
    }

    /// The value at `time` on key `key`'s segment of channel `ch`, from `(t0, v0)` to
    /// `(t1, v1)` (f32-rounded already), `t0 <= time < t1`.
    fn segment(&self, key: usize, ch: usize, curve: Interpolation, p0: (f64, f64), p1: (f64, f64), time: f64) -> f64 {
        match curve {
            Interpolation::Bezier { .. } => match self.samples(key, ch) {
                Some(samples) => on_samples(samples, p0, p1, time),
                None => segment(curve, p0, p1, time),
            },
            _ => segment(curve, p0, p1, time),
        }
    }
}

/// The value at `time` on the segment from `(t0, v0)` to `(t1, v1)` (f32-rounded already),
/// `t0 <= time < t1`, with the curve `curve` toward the next key.
pub(crate) fn segment(curve: Interpolation, (t0, v0): (f64, f64), (t1, v1): (f64, f64), time: f64) -> f64 {
    match curve {
        Interpolation::Stepped => v0,
        Interpolation::Linear => v0 + (time - t0) / (t1 - t0) * (v1 - v0),
        Interpolation::Bezier { c1, c2 } => {
            on_samples(&bezier_samples([t0, v0], c1, c2, [t1, v1]), (t0, v0), (t1, v1), time)
        }
    }
}

/// The value at `time` between a Bézier segment's samples (the keys `(t0, v0)`, `(t1, v1)` count
/// as the samples at u = 0 and u = 1): linear in time between the neighbouring samples.
fn on_samples(samples: &[[f64; 2]; 9], (t0, v0): (f64, f64), (t1, v1): (f64, f64), time: f64) -> f64 {
    let mut prev = [t0, v0];
    for s in samples.iter().chain(std::iter::once(&[t1, v1])) {
        if s[0] >= time {
            let span = s[0] - prev[0];
            return if span > 0.0 { prev[1] + (time - prev[0]) / span * (s[1] - prev[1]) } else { s[1] };
        }
        prev = *s;
    }
    v1
}

/// The index of the last key whose (f32) time is at or before `time`, or `None` before the
/// first key. Binary search.
pub(crate) fn key_at(times: impl Fn(usize) -> f64, len: usize, time: f64) -> Option<usize> {
    let (mut lo, mut hi) = (0, len);
    while lo < hi {
        let mid = (lo + hi) / 2;
        if f32ed(times(mid)) <= time {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo.checked_sub(1)
}

/// The value of channel `ch` of `keys` from key `i` at `time`.
fn channel(r: &Reader, keys: &[BoneKey], i: usize, ch: usize, time: f64) -> f64 {
    let k = &keys[i];
    let v0 = f32ed(k.values[ch]);
    match keys.get(i + 1) {
        None => v0,
        Some(n) => r.segment(i, ch, k.curves[ch], (f32ed(k.time), v0), (f32ed(n.time), f32ed(n.values[ch])), time),
    }
}

/// Applies a bone timeline at `time` to `local` (the bone's pose, reset to `setup` before the
/// clip): rotation, translation and shear add their values to the setup ones, scale multiplies
/// the setup scale. Before the first key the setup value stays.
pub(crate) fn apply_bone_at(
    r: &mut Reader,
    t: &BoneTimeline,
    setup: &LocalTransform,
    local: &mut LocalTransform,
    time: f64,
) {
    let Some(i) = r.key_at(|i| t.keys[i].time, t.keys.len(), time) else { return };
    let v0 = channel(r, &t.keys, i, 0, time);
    let v1 = if t.property.channels() == 2 { channel(r, &t.keys, i, 1, time) } else { 0.0 };
    match t.property {
        BoneProperty::Rotate => local.rotation = setup.rotation + v0,
        BoneProperty::Translate => {
            local.x = setup.x + v0;
            local.y = setup.y + v1;
        }
        BoneProperty::TranslateX => local.x = setup.x + v0,
        BoneProperty::TranslateY => local.y = setup.y + v0,
        BoneProperty::Scale => {
            local.scale_x = setup.scale_x * v0;
            local.scale_y = setup.scale_y * v1;
        }
        BoneProperty::ScaleX => local.scale_x = setup.scale_x * v0,
        BoneProperty::ScaleY => local.scale_y = setup.scale_y * v0,
        BoneProperty::Shear => {
            local.shear_x = setup.shear_x + v0;
            local.shear_y = setup.shear_y + v1;
        }
        BoneProperty::ShearX => local.shear_x = setup.shear_x + v0,
        BoneProperty::ShearY => local.shear_y = setup.shear_y + v0,
    }
}

/// An IK constraint's settings at `time` from its keys: mix and softness interpolated with
/// their curves, the flags those of the key at or before `time`; `None` before the first key
/// (the setup settings stay).
pub(crate) fn ik_settings_at(r: &mut Reader, keys: &[IkKey], time: f64) -> Option<IkSettings> {
    let i = r.key_at(|i| keys[i].time, keys.len(), time)?;
    let k = &keys[i];
    let mut s = k.settings;
    s.mix = f32ed(s.mix);
    s.softness = f32ed(s.softness);
    if let Some(n) = keys.get(i + 1) {
        let (t0, t1) = (f32ed(k.time), f32ed(n.time));
        s.mix = r.segment(i, 0, k.curves[0], (t0, s.mix), (t1, f32ed(n.settings.mix)), time);
        s.softness = r.segment(i, 1, k.curves[1], (t0, s.softness), (t1, f32ed(n.settings.softness)), time);
    }
    Some(s)
}

/// A numeric constraint timeline's first `channels` values at `time`, each interpolated with
/// its curve; `None` before the first key (the setup settings stay).
pub(crate) fn channels_at(
    r: &mut Reader,
    keys: &[ChannelKey],
    channels: usize,
    time: f64,
) -> Option<[f64; MAX_CHANNELS]> {
    let i = r.key_at(|i| keys[i].time, keys.len(), time)?;
    let k = &keys[i];
    let mut values = k.values.map(f32ed);
    if let Some(n) = keys.get(i + 1) {
        let (t0, t1) = (f32ed(k.time), f32ed(n.time));
        for (ch, v) in values.iter_mut().enumerate().take(channels) {
            *v = r.segment(i, ch, k.curves[ch], (t0, *v), (t1, f32ed(n.values[ch])), time);
        }
    }
    Some(values)
}

/// [`apply_bone_at`] without precomputed curves nor a cached key.
#[cfg(test)]
fn apply_bone(t: &BoneTimeline, setup: &LocalTransform, local: &mut LocalTransform, time: f64) {
    let mut last = 0;
    let curves = Curves::default();
    apply_bone_at(&mut Reader::new(curves.clip(0), 0, &mut last), t, setup, local, time);
}

/// [`ik_settings_at`] without precomputed curves nor a cached key.
#[cfg(test)]
fn ik_settings(keys: &[IkKey], time: f64) -> Option<IkSettings> {
    let mut last = 0;
    let curves = Curves::default();
    ik_settings_at(&mut Reader::new(curves.clip(0), 0, &mut last), keys, time)
}

#[cfg(test)]
#[path = "timeline_cache_tests.rs"]
mod cache_tests;

#[cfg(test)]
mod tests {
    use super::*;

    fn key(time: f64, v: f64, curve: Interpolation) -> BoneKey {
        BoneKey { time, values: [v, 2.0 * v], curves: [curve; 2] }
    }

    #[test]
    fn bezier_samples_are_the_cubic_at_tenths() {
        let (p0, c1, c2, p3) = ([0.0, 0.0], [0.25, 1.0], [0.5, -1.0], [1.0, 3.0]);
        let s = bezier_samples(p0, c1, c2, p3);
        for (k, got) in s.iter().enumerate() {
            let u = (k + 1) as f64 / 10.0;
            let w = [
                (1.0 - u) * (1.0 - u) * (1.0 - u),
                3.0 * u * (1.0 - u) * (1.0 - u),
                3.0 * u * u * (1.0 - u),
                u * u * u,
            ];
            for ch in 0..2 {
                let exact = w[0] * p0[ch] + w[1] * c1[ch] + w[2] * c2[ch] + w[3] * p3[ch];
                assert!((got[ch] - exact).abs() < 1e-6, "u {u} ch {ch}: {} vs {exact}", got[ch]);
            }
        }
    }

    #[test]
    fn a_bezier_value_is_linear_between_samples() {
        // By hand: time control points 1/3 and 2/3 make the time linear in u (t = u), so the
        // sample at u = 0.5 is at t = 0.5 and its value is B(0.5) = (0 + 3·1 + 3·(−1) + 3)/8
        // = 0.375; the sample at u = 0.4: B(0.4) = 3·0.4·0.36 − 3·0.16·0.6 + 3·0.064
        // = 0.432 − 0.288 + 0.192 = 0.336.
        let curve = Interpolation::Bezier { c1: [1.0 / 3.0, 1.0], c2: [2.0 / 3.0, -1.0] };
        let b = |u: f64| 3.0 * u * (1.0 - u) * (1.0 - u) - 3.0 * u * u * (1.0 - u) + 3.0 * u * u * u;
        assert!((b(0.4) - 0.336).abs() < 1e-12);
        let at = |t: f64| segment(curve, (0.0, 0.0), (1.0, 3.0), t);
        assert!((at(0.5) - 0.375).abs() < 1e-6);
        // Halfway between the samples at 0.4 and 0.5: their mean, not the cubic's value there.
        let mid = at(0.45);
        assert!((mid - (b(0.4) + b(0.5)) / 2.0).abs() < 1e-6, "{mid}");
        assert!((mid - b(0.45)).abs() > 1e-4);
        // Past the last sample, toward the key.
        assert!((at(0.95) - (b(0.9) + 3.0) / 2.0).abs() < 1e-6);
    }

    #[test]
    fn timelines_hold_the_setup_before_and_the_last_key_after() {
        let setup = LocalTransform { rotation: 0.5, scale_x: 2.0, ..LocalTransform::default() };
        let rot = BoneTimeline {
            bone: 0,
            property: BoneProperty::Rotate,
            keys: vec![key(1.0, 0.25, Interpolation::Linear), key(2.0, 0.75, Interpolation::Linear)],
        };
        let mut local = setup;
        apply_bone(&rot, &setup, &mut local, 0.5);
        assert_eq!(local.rotation, 0.5);
        apply_bone(&rot, &setup, &mut local, 1.5);
        assert!((local.rotation - 1.0).abs() < 1e-7, "{}", local.rotation);
        apply_bone(&rot, &setup, &mut local, 9.0);
        assert!((local.rotation - (0.5 + 0.75f32 as f64)).abs() < 1e-12);
        let scale = BoneTimeline {
            bone: 0,
            property: BoneProperty::Scale,
            keys: vec![key(0.0, 1.5, Interpolation::Stepped), key(1.0, 3.0, Interpolation::Linear)],
        };
        apply_bone(&scale, &setup, &mut local, 0.99);
        assert_eq!((local.scale_x, local.scale_y), (3.0, 3.0));
        apply_bone(&scale, &setup, &mut local, 1.0);
        assert_eq!((local.scale_x, local.scale_y), (6.0, 6.0));
    }

    #[test]
    fn ik_keys_interpolate_mix_and_step_the_flags() {
        let k = |time: f64, mix: f64, bend: bool| IkKey {
            time,
            settings: IkSettings { mix, softness: 10.0 * mix, bend_positive: bend, ..IkSettings::default() },
            curves: [Interpolation::Linear; 2],
        };
        let keys = [k(0.0, 0.0, true), k(1.0, 1.0, false)];
        let s = ik_settings(&keys, 0.25).unwrap();
        assert!((s.mix - 0.25).abs() < 1e-7 && (s.softness - 2.5).abs() < 1e-6);
        assert!(s.bend_positive);
        assert!(!ik_settings(&keys, 1.0).unwrap().bend_positive);
        assert_eq!(ik_settings(&keys[1..], 0.5), None);
    }
}
