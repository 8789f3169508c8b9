//! Any valid skeleton draws: over random trees (bones given in any order, lengths from 1e-3 to
//! 1e3 mixed, optional limits), poses, goals (near, far, with and without a direction), pins,
//! ranges, names and picture sizes, the SVG is made without a panic, parses, is the same twice,
//! and every bone's tip lies inside the plot.

use std::f64::consts::PI;

use ikarus::{Bone, JointLimits, Point2, Skeleton};
use ikarus_render::{BoneGoal, SkeletonFigure, skeleton_svg};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence};

/// A tree of up to `max` bones: bone k hangs on one of the bones before it (or starts at the
/// base), then the list is rotated so that children may come before their parents.
fn skeleton(max: usize) -> impl Strategy<Value = Skeleton> {
    let bone = (-3.0f64..3.0, -PI..PI, prop::option::of((-3.0f64..3.0, 0.0f64..4.0)), any::<prop::sample::Index>());
    (prop::collection::vec(bone, 1..=max), any::<prop::sample::Index>(), -1.0f64..1.0, -1.0f64..1.0).prop_map(
        |(specs, turn, x, y)| {
            let n = specs.len();
            let mut bones: Vec<Bone> = specs
                .iter()
                .enumerate()
                .map(|(k, &(e, angle, limits, parent))| {
                    // One parent choice in k + 1: a bone before this one, or the base.
                    let p = parent.index(k + 1);
                    let mut bone = match limits {
                        None => Bone::new(format!("b{k}"), 10f64.powf(e), angle),
                        Some((lo, width)) => {
                            let lim = JointLimits::new(lo, lo + width).unwrap();
                            Bone::new(format!("b{k}"), 10f64.powf(e), lim.clamp(angle)).with_limits(lim)
                        }
                    };
                    if p < k {
                        bone = bone.with_parent(format!("b{p}"));
                    }
                    bone
                })
                .collect();
            bones.rotate_left(turn.index(n));
            let reach: f64 = bones.iter().map(|b| b.length).sum();
            Skeleton::new([x * reach, y * reach], &bones).unwrap()
        },
    )
}

#[derive(Debug, Clone)]
struct Picture {
    skeleton: Skeleton,
    pose: Vec<f64>,
    goals: Vec<(prop::sample::Index, f64, f64, Option<f64>)>,
    pins: Vec<prop::sample::Index>,
    ranges: bool,
    labels: bool,
    size: (u32, u32),
}

fn picture() -> impl Strategy<Value = Picture> {
    skeleton(16).prop_flat_map(|skeleton| {
        let n = skeleton.len();
        let goal = (any::<prop::sample::Index>(), -5.0f64..5.0, -5.0f64..5.0, prop::option::of(-10.0f64..10.0));
        (
            prop::collection::vec(-10.0f64..10.0, n),
            prop::collection::vec(goal, 0..4),
            prop::collection::vec(any::<prop::sample::Index>(), 0..3),
            any::<bool>(),
            any::<bool>(),
            (16u32..900, 16u32..900),
        )
            .prop_map(move |(pose, goals, pins, ranges, labels, size)| Picture {
                skeleton: skeleton.clone(),
                pose,
                goals,
                pins,
                ranges,
                labels,
                size,
            })
    })
}

fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(64);
    Config { cases, failure_persistence: Some(Box::new(FileFailurePersistence::Off)), ..Config::default() }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn any_valid_skeleton_draws_with_every_tip_in_view(p in picture()) {
        let s = &p.skeleton;
        let n = s.len();
        let reach = s.max_reach();
        let base = s.base();
        let figure = SkeletonFigure {
            // Goals within a few reaches of the base, so some are inside and some beyond the view.
            goals: p
                .goals
                .iter()
                .map(|&(bone, x, y, angle)| BoneGoal {
                    bone: bone.index(n),
                    position: Point2::new(base.x + x * reach, base.y + y * reach),
                    angle,
                })
                .collect(),
            pins: p.pins.iter().map(|i| i.index(n)).collect(),
            ranges: p.ranges,
            labels: p.labels,
            caption: Some("a <random> tree & co".into()),
            ..SkeletonFigure::new(s, &p.pose)
        };
        let (w, h) = p.size;
        let svg = skeleton_svg(&figure, w, h).unwrap();
        let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default());
        prop_assert!(tree.is_ok(), "the SVG does not parse: {:?}", tree.err());
        prop_assert_eq!(&skeleton_svg(&figure, w, h).unwrap(), &svg);
        let view = figure.view(w, h);
        let plot = view.plot_area();
        let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
        s.forward_into(&p.pose, &mut starts, &mut tips, &mut dirs);
        for (i, t) in tips.iter().enumerate() {
            let (x, y) = view.world_to_pixel(*t);
            prop_assert!(plot.contains(x, y), "tip of {} at ({}, {}) outside {:?}", s.name(i), x, y, plot);
        }
    }
}
