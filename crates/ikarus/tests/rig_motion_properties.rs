//! Properties of motion and tracking on skeletons (issue 12), over random trees of bones:
//!
//! - a skeleton's animation starts on its first keyframe bit for bit, ends on its last, keeps
//!   every limited bone inside its range, and each frame's points are the base and every
//!   bone's tip by forward kinematics of the frame's angles;
//! - a skeleton's effector following a path never turns a bone more than the bound per sample
//!   after the first, holds its pin where it started wherever a sample is reached, measures
//!   every sample's error as the largest of its effectors', and repeats bit for bit.

use std::f64::consts::PI;

use ikarus::motion::{Interpolation, MotionOptions, Timing, animate_with};
use ikarus::track::{Path, SampleStatus, TrackOptions, follow_rig};
use ikarus::{Bone, Ease, JointLimits, Pin, Point2, RigTask, Skeleton};
use proptest::prelude::*;

/// A tree of 2 to 7 bones: bone 0 a root, each later one on an earlier bone (or, now and then,
/// another root); lengths 0.3 to 1.5, start angles within ±1, a range around the start angle
/// on about half of them.
fn skeleton() -> impl Strategy<Value = Skeleton> {
    prop::collection::vec((0.3..1.5f64, -1.0..1.0f64, 0usize..100, prop::option::of((0.2..2.0f64, 0.2..2.0f64))), 2..8)
        .prop_map(|specs| {
            let bones: Vec<Bone> = specs
                .iter()
                .enumerate()
                .map(|(i, &(length, angle, parent, range))| {
                    let mut bone = Bone::new(format!("b{i}"), length, angle);
                    if i > 0 && parent % 8 != 0 {
                        bone = bone.with_parent(format!("b{}", parent % i));
                    }
                    if let Some((below, above)) = range {
                        bone = bone.with_limits(JointLimits::new(angle - below, angle + above).unwrap());
                    }
                    bone
                })
                .collect();
            Skeleton::new([0.0, 0.0], &bones).unwrap()
        })
}

/// Bones that no other bone hangs from.
fn leaves(s: &Skeleton) -> Vec<usize> {
    (0..s.len()).filter(|&i| s.children(i).len() == 0).collect()
}

/// Every bone's tip at `angles`, by the skeleton's own forward kinematics.
fn tips(s: &Skeleton, angles: &[f64]) -> Vec<Point2<f64>> {
    let n = s.len();
    let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
    s.forward_into(angles, &mut starts, &mut tips, &mut dirs);
    tips
}

/// 128 cases (well under a second in a debug build) unless `PROPTEST_CASES` says otherwise.
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(128);
    ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn a_skeleton_animation_runs_from_key_to_key_inside_the_limits(
        s in skeleton(),
        offsets in prop::collection::vec(prop::collection::vec(-PI..PI, 7), 1..4),
        frames in 2usize..40,
        linear in any::<bool>(),
    ) {
        // Keyframes: the start pose, then offsets from it, clamped into each bone's range.
        let start = s.start_angles().to_vec();
        let mut keys = vec![start.clone()];
        for o in &offsets {
            let key = start
                .iter()
                .zip(o)
                .zip(s.limits())
                .map(|((&a, &d), lim)| lim.map_or(a + d, |l| (a + d).clamp(l.min(), l.max())))
                .collect();
            keys.push(key);
        }
        let interpolation = if linear { Interpolation::Linear } else { Interpolation::Spline };
        let options = MotionOptions::new(Timing::Frames(frames), Ease::Sine).with_interpolation(interpolation);
        let anim = animate_with(&s, &keys, None, options).unwrap();
        prop_assert_eq!(anim.frames.len(), frames);
        prop_assert_eq!(&anim.frames[0].angles, &keys[0]);
        for (i, f) in anim.frames.iter().enumerate() {
            prop_assert_eq!(f.joints.len(), s.len() + 1);
            prop_assert_eq!(f.joints[0], s.base());
            prop_assert_eq!(&f.joints[1..], &tips(&s, &f.angles)[..], "frame {}", i);
            prop_assert!(s.check_angles(&f.angles).is_ok(), "frame {} leaves a range: {:?}", i, f.angles);
        }
        // The last frame is the last keyframe (limited bones exactly; free ones up to turns).
        let last = &anim.frames[frames - 1].angles;
        for (i, (&a, &k)) in last.iter().zip(&keys[keys.len() - 1]).enumerate() {
            let turns = (a - k) / (2.0 * PI);
            prop_assert!((turns - turns.round()).abs() < 1e-9, "bone {}: {} vs {}", i, a, k);
            if s.limits()[i].is_some() {
                prop_assert_eq!(a, k);
            }
        }
    }

    #[test]
    fn a_skeleton_effector_follows_continuously_and_its_pin_holds(
        s in skeleton(),
        pick in 0usize..100,
        radius in 0.02..0.4f64,
        samples in 3usize..16,
        max_step_deg in 3.0..20.0f64,
    ) {
        let leaves = leaves(&s);
        let effector = leaves[pick % leaves.len()];
        let pinned = leaves.iter().copied().find(|&b| b != effector);
        let start = s.start_angles().to_vec();
        let at_start = tips(&s, &start);
        let centre = at_start[effector];
        let path = Path::circle([centre.x - radius, centre.y], radius, samples).unwrap();
        let task = RigTask::new(vec![], pinned.map(Pin::position).into_iter().collect());
        let options = TrackOptions { max_step: max_step_deg.to_radians(), ..TrackOptions::default() };
        let t = follow_rig(&s, &start, effector, &task, &path, &options).unwrap();
        prop_assert_eq!(t.samples.len(), samples);
        for (k, sample) in t.samples.iter().enumerate() {
            if k > 0 {
                prop_assert!(sample.step <= options.max_step * (1.0 + 1e-9), "sample {}: step {}", k, sample.step);
            }
            let now = tips(&s, &sample.angles);
            let goal = path.goals()[k].target();
            let mut largest = (now[effector] - goal).norm();
            if let Some(p) = pinned {
                largest = largest.max((now[p] - at_start[p]).norm());
            }
            prop_assert!((sample.error - largest).abs() <= 1e-12 * (1.0 + largest), "sample {}: {} vs {}", k, sample.error, largest);
            if sample.status == SampleStatus::Reached {
                prop_assert!(largest <= 1e-6 * (1.0 + 1e-9), "sample {}: reached, yet an effector is {} away", k, largest);
            }
            prop_assert!(s.check_angles(&sample.angles).is_ok() || options.solve.limits == ikarus::LimitMode::Ignore);
        }
        prop_assert_eq!(follow_rig(&s, &start, effector, &task, &path, &options).unwrap(), t);
    }
}
