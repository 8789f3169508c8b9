//! A transform constraint's timeline: keys of its six mixes, each channel with its own curve,
//! sampled as [`super::timeline`] samples the others (times and values rounded to `f32`, Bézier
//! segments through nine samples). Before the first key the setup mixes stay.

use super::Interpolation;
use super::timeline::segment;
use super::transform::TransformSettings;

/// One key of a transform constraint's timeline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransformKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The mixes at this key (Spine's defaults for an absent one: 1, `mixY` as `mixX`,
    /// `mixScaleY` as `mixScaleX`).
    pub settings: TransformSettings,
    /// Per mix, in [`TransformSettings::to_array`]'s order, toward the next key.
    pub curves: [Interpolation; 6],
}

/// A transform constraint's timeline, keys in increasing time.
#[derive(Debug, Clone, PartialEq)]
pub struct TransformTimeline {
    /// The transform constraint's index (in [`super::Character::transforms`]).
    pub constraint: usize,
    /// The keys, in increasing time.
    pub keys: Vec<TransformKey>,
}

/// A value rounded to the runtime's `f32`.
fn f32ed(v: f64) -> f64 {
    v as f32 as f64
}

/// The mixes of `keys` at `time`, each channel interpolated with its curve; `None` before the
/// first key (the setup mixes stay).
pub(crate) fn transform_settings_at(keys: &[TransformKey], time: f64) -> Option<TransformSettings> {
    let i = keys.partition_point(|k| f32ed(k.time) <= time).checked_sub(1)?;
    let k = &keys[i];
    let here = k.settings.to_array().map(f32ed);
    let Some(n) = keys.get(i + 1) else { return Some(TransformSettings::from_array(here)) };
    let there = n.settings.to_array().map(f32ed);
    let (t0, t1) = (f32ed(k.time), f32ed(n.time));
    let mut out = here;
    for ch in 0..6 {
        out[ch] = segment(k.curves[ch], (t0, here[ch]), (t1, there[ch]), time);
    }
    Some(TransformSettings::from_array(out))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(time: f64, mix: f64, curve: Interpolation) -> TransformKey {
        TransformKey { time, settings: TransformSettings::from_array([mix; 6]), curves: [curve; 6] }
    }

    #[test]
    fn mixes_interpolate_per_channel_and_hold_outside_the_keys() {
        let mut keys = vec![key(0.5, 0.0, Interpolation::Linear), key(1.5, 1.0, Interpolation::Linear)];
        keys[0].curves[2] = Interpolation::Stepped;
        assert_eq!(transform_settings_at(&keys, 0.25), None);
        let s = transform_settings_at(&keys, 1.0).unwrap().to_array();
        assert_eq!(s, [0.5, 0.5, 0.0, 0.5, 0.5, 0.5]);
        assert_eq!(transform_settings_at(&keys, 9.0).unwrap().to_array(), [1.0; 6]);
    }
}
