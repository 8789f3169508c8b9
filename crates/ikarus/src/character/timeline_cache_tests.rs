//! The cached last key and the precomputed Bézier samples change no answer: every value, bit for
//! bit, is the one computed from scratch, for times going forward, backward, jumping, on keys,
//! between f32-equal key times, before the first key and after the last.

use super::*;
use crate::rng::SplitMix64;

fn timeline() -> BoneTimeline {
    let bezier = |a: f64| Interpolation::Bezier { c1: [0.1 + a, 0.7], c2: [0.3 + a, -2.0] };
    let times = [0.0, 0.25, 0.5, 0.5000000001, 1.0, 1.75, 3.0];
    let keys = times
        .iter()
        .enumerate()
        .map(|(i, &time)| {
            let curve = match i % 3 {
                0 => bezier(time),
                1 => Interpolation::Linear,
                _ => Interpolation::Stepped,
            };
            BoneKey { time: time + 0.5, values: [i as f64 * 0.3 - 1.0, 2.0 - i as f64], curves: [curve, bezier(time)] }
        })
        .collect();
    BoneTimeline { bone: 0, property: BoneProperty::Translate, keys }
}

fn clip(t: BoneTimeline) -> Clip {
    let ik = ConstraintTimeline {
        constraint: 0,
        keys: ConstraintKeys::Ik(
            (0..5)
                .map(|i| IkKey {
                    time: i as f64 * 0.8,
                    settings: IkSettings {
                        mix: 0.2 * i as f64,
                        softness: 3.0 - i as f64 * 0.5,
                        ..IkSettings::default()
                    },
                    curves: [Interpolation::Bezier { c1: [0.2, 0.1], c2: [0.5, 0.9] }; 2],
                })
                .collect(),
        ),
    };
    Clip { name: "c".to_owned(), duration: 4.0, bones: vec![t], constraints: vec![ik] }
}

use super::super::{ConstraintKeys, ConstraintTimeline};

#[test]
fn cached_keys_and_precomputed_curves_give_the_same_bits() {
    let c = clip(timeline());
    let curves = Curves::of(std::slice::from_ref(&c));
    let setup = LocalTransform::default();
    let mut rng = SplitMix64(7);
    let (mut last_bone, mut last_ik) = (0u32, 5u32);
    let mut time = -0.3;
    for step in 0..4000 {
        // Forward in small steps, with jumps back, far ahead and onto keys now and then.
        time = match step % 97 {
            0 => -0.5,
            13 => 0.75,
            29 => 1.0000000001,
            41 => 9.0,
            _ if rng.chance(0.05) => rng.range(-0.5, 3.5),
            _ => time + 0.0137,
        };
        let (mut cached, mut plain) = (setup, setup);
        let mut r = Reader::new(curves.clip(0), 0, &mut last_bone);
        apply_bone_at(&mut r, &c.bones[0], &setup, &mut cached, time);
        apply_bone(&c.bones[0], &setup, &mut plain, time);
        assert_eq!((cached.x.to_bits(), cached.y.to_bits()), (plain.x.to_bits(), plain.y.to_bits()), "time {time}");
        let mut r = Reader::new(curves.clip(0), 1, &mut last_ik);
        let keys = c.constraints[0].keys.ik().unwrap();
        let a = ik_settings_at(&mut r, keys, time);
        let b = ik_settings(keys, time);
        assert_eq!(
            a.map(|s| (s.mix.to_bits(), s.softness.to_bits())),
            b.map(|s| (s.mix.to_bits(), s.softness.to_bits()))
        );
    }
}

#[test]
fn the_samples_are_kept_for_bezier_segments_only() {
    let c = clip(timeline());
    let curves = Curves::of(std::slice::from_ref(&c));
    // Bone timeline: channel 0 is a Bézier on keys 0 and 3 (not on the last, 6), channel 1 on
    // every key but the last; the IK timeline: both channels of its 4 segments.
    assert_eq!(curves.samples.len(), 2 + 6 + 8);
    let mut last = 0;
    let mut get =
        |clip, timeline, key, ch| Reader::new(curves.clip(clip), timeline, &mut last).samples(key, ch).is_some();
    assert!(get(0, 0, 0, 0) && !get(0, 0, 1, 0));
    assert!(!get(0, 0, 6, 1) && get(0, 1, 3, 1));
    assert!(!get(1, 0, 0, 0));
}
