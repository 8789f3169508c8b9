//! Properties over random chains, keyframes, timings and eases.

use std::f64::consts::TAU;

use proptest::prelude::*;

use super::*;

/// A chain of 1–4 joints, some limited; 1–5 keyframes inside the limits; a timing; an ease.
fn scenario() -> impl Strategy<Value = (Chain, Vec<Vec<f64>>, Timing, Ease)> {
    let joint = (0.1f64..3.0, prop::option::of((-3.0f64..0.0, 0.0f64..3.0)));
    let timing = prop_oneof![
        (2usize..300).prop_map(Timing::Frames),
        (0.05f64..5.0, 1.0f64..120.0).prop_map(|(s, fps)| Timing::Duration { seconds: s.max(0.6 / fps), fps }),
    ];
    let ease = prop_oneof![
        Just(Ease::Linear),
        Just(Ease::Sine),
        Just(Ease::Smoothstep),
        (0.0f64..=1.0, 0.0f64..=1.0).prop_map(|(a, b)| Ease::parent(a.min(b), a.max(b)).unwrap()),
    ];
    (prop::collection::vec(joint, 1..=4), 1usize..=5, timing, ease).prop_flat_map(|(joints, k, timing, ease)| {
        let c = chain(&joints);
        let per_joint: Vec<BoxedStrategy<f64>> = joints
            .iter()
            .map(|(_, lim)| match *lim {
                Some((lo, hi)) => prop_oneof![Just(lo), Just(hi), lo..=hi].boxed(),
                None => (-10.0f64..10.0).boxed(),
            })
            .collect();
        (Just(c), prop::collection::vec(per_joint, k), Just(timing), Just(ease))
    })
}

/// The keyframes unwrapped the short way round, computed independently of the library.
fn unwrapped(chain: &Chain, keys: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut out: Vec<Vec<f64>> = vec![keys[0].clone()];
    for key in &keys[1..] {
        let prev = out.last().unwrap();
        let next = key
            .iter()
            .zip(prev)
            .zip(chain.limits())
            .map(|((&a, &p), lim)| if lim.is_some() { a } else { p + wrap_angle(a - p) })
            .collect();
        out.push(next);
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// The polyline: frame count, exact first frame, last frame a whole number of turns from the last
    /// keyframe, limits respected, every frame on the unwrapped path and never moving backwards.
    #[test]
    fn frames_follow_the_path((c, keys, timing, ease) in scenario()) {
        let linear = MotionOptions::new(timing, ease).with_interpolation(Interpolation::Linear);
        let anim = animate_with(&c, &keys, None, linear).unwrap();
        check_frames(&c, &anim);
        let n = timing.frame_count().unwrap();
        prop_assert_eq!(anim.frames.len(), n);
        prop_assert_eq!(bits(&anim.frames[0].angles), bits(&keys[0]));
        let last = &anim.frames[n - 1].angles;
        for (j, (a, b)) in last.iter().zip(&keys[keys.len() - 1]).enumerate() {
            let turns = ((a - b) / TAU).round();
            prop_assert!((a - b - turns * TAU).abs() <= 1e-12, "joint {}: {} vs {}", j, a, b);
            if c.limits()[j].is_some() {
                prop_assert_eq!(a.to_bits(), b.to_bits());
            }
        }
        let path = unwrapped(&c, &keys);
        let arc = arc_positions(&path, &angles(&anim));
        prop_assert!(arc.windows(2).all(|w| w[1] >= w[0] - 1e-12), "{:?}", arc);
        for (a, b) in last.iter().zip(&path[path.len() - 1]) {
            prop_assert!((a - b).abs() <= 1e-12, "{} vs {}", a, b);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// The spline, with and without times: frame count, exact first frame, last frame the
    /// polyline's (a whole number of turns from the last keyframe, exactly it for limited
    /// joints), every frame inside the limits and inside the range of its joint's unwrapped
    /// keyframes, the same bits when run again.
    #[test]
    fn the_spline_stays_inside((c, keys, timing, ease) in scenario(), even in any::<bool>()) {
        let duration = timing.duration();
        let times: Option<Vec<f64>> = (even && keys.len() > 1).then(|| {
            let last = keys.len() - 1;
            (0..=last).map(|k| if k == last { duration } else { duration * k as f64 / last as f64 }).collect()
        });
        let options = MotionOptions::new(timing, ease);
        let anim = animate_with(&c, &keys, times.as_deref(), options).unwrap();
        check_frames(&c, &anim);
        let n = timing.frame_count().unwrap();
        prop_assert_eq!(anim.frames.len(), n);
        prop_assert_eq!(bits(&anim.frames[0].angles), bits(&keys[0]));
        let linear = animate_with(&c, &keys, times.as_deref(), options.with_interpolation(Interpolation::Linear)).unwrap();
        prop_assert_eq!(bits(&anim.frames[n - 1].angles), bits(&linear.frames[n - 1].angles));
        let path = unwrapped(&c, &keys);
        for (i, f) in anim.frames.iter().enumerate() {
            for (j, a) in f.angles.iter().enumerate() {
                let lo = path.iter().map(|k| k[j]).fold(f64::INFINITY, f64::min);
                let hi = path.iter().map(|k| k[j]).fold(f64::NEG_INFINITY, f64::max);
                prop_assert!((lo - 1e-12..=hi + 1e-12).contains(a), "frame {} joint {}: {} outside [{}, {}]", i, j, a, lo, hi);
            }
        }
        let again = animate_with(&c, &keys, times.as_deref(), options).unwrap();
        prop_assert_eq!(anim, again);
    }
}
