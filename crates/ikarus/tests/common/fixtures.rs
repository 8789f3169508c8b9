//! Fixtures shared by the library's unit tests, its integration tests and its benchmarks: the
//! seed arm, the seven-link arm, a forked rig, random chains, poses and goals, and a character's
//! bones, IK constraint and clip.
//!
//! One file, included three ways: as `crate::fixtures` in the unit tests (`lib.rs` includes it
//! with `#[path]` under `cfg(test)`, and `extern crate self as ikarus` makes the `ikarus::`
//! paths below resolve inside the crate), as `common::fixtures` in the integration tests (as
//! `fixtures` alone in `alloc.rs`, which needs nothing else of `common`), and through
//! `tests/common/mod.rs` in the benchmarks. Plain inclusion rather than a `pub` module
//! behind a feature: nothing test-only enters the library's API or its feature set, and every
//! user sees the same, public-API-only code.
#![allow(dead_code)]

use std::f64::consts::{FRAC_PI_2, PI};

use ikarus::character::{
    BoneKey, BoneProperty, BoneTimeline, CharacterBone, Clip, ConstraintTimeline, IkBones, IkConstraint, IkRule,
    IkSettings, Inherit, Interpolation, LocalTransform,
};
use ikarus::kinematics::end_effector;
use ikarus::rng::SplitMix64;
use ikarus::{Bone, Chain, Goal, JointLimits, Link, Skeleton};

/// Degrees to radians.
pub fn deg(d: f64) -> f64 {
    d.to_radians()
}

/// An arm based at the origin with links of `lengths`, every joint at 5° (the seed's start).
pub fn arm(lengths: &[f64]) -> Chain {
    let links: Vec<Link> = lengths.iter().map(|&l| Link::new(l, deg(5.0))).collect();
    Chain::new([0.0, 0.0], &links).expect("valid arm")
}

/// The seed program's arm: lengths 3, 2, 1, every joint at 5°, no limits.
pub fn seed_arm() -> Chain {
    arm(&[3.0, 2.0, 1.0])
}

/// The seed arm with the seed's ranges: ±45°, ±90°, ±170°.
pub fn seed_arm_limited() -> Chain {
    let lim = |r: f64| JointLimits::new(deg(-r), deg(r)).expect("valid limits");
    let links = [(3.0, 45.0), (2.0, 90.0), (1.0, 170.0)].map(|(l, r)| Link::new(l, deg(5.0)).with_limits(lim(r)));
    Chain::new([0.0, 0.0], &links).expect("valid arm")
}

/// A 7-link arm with ranges on every joint, every joint at 10°, like
/// `examples/arms/seven.toml`.
pub fn seven_link_arm() -> Chain {
    let lengths = [2.0, 1.7, 1.4, 1.2, 1.0, 0.8, 0.6];
    let ranges = [90.0, 120.0, 120.0, 135.0, 135.0, 150.0, 150.0];
    let links: Vec<Link> = lengths
        .iter()
        .zip(ranges)
        .map(|(&l, r)| Link::new(l, deg(10.0)).with_limits(JointLimits::new(deg(-r), deg(r)).expect("valid limits")))
        .collect();
    Chain::new([0.0, 0.0], &links).expect("valid arm")
}

/// Issue 24's arm: 64 links whose lengths spread evenly in magnitude from 1e-9 (base) to 1e9
/// (tip), each joint limited to ±90°. Its exact region has no end of pieces: without a work
/// cap it took minutes to build.
pub fn spread_arm() -> Chain {
    spread_arm_at([0.0, 0.0])
}

/// [`spread_arm`] based at `base`: another chain for the process's memo of built regions.
pub fn spread_arm_at(base: [f64; 2]) -> Chain {
    let lim = JointLimits::new(deg(-90.0), deg(90.0)).expect("valid limits");
    let links: Vec<Link> =
        (0..64).map(|k| Link::new(libm::pow(10.0, -9.0 + 18.0 * f64::from(k) / 63.0), 0.0).with_limits(lim)).collect();
    Chain::new(base, &links).expect("valid arm")
}

/// An arm based at the origin with links of `(length, min°, max°)`, every joint at the middle
/// of its range.
pub fn limited_arm(links: &[(f64, f64, f64)]) -> Chain {
    let links: Vec<Link> = links
        .iter()
        .map(|&(l, lo, hi)| {
            let limits = JointLimits::new(deg(lo), deg(hi)).expect("valid limits");
            Link::new(l, 0.5 * (deg(lo) + deg(hi))).with_limits(limits)
        })
        .collect();
    Chain::new([0.0, 0.0], &links).expect("valid arm")
}

/// A random chain of `n` links of length 0.5..2, each joint limited to a random range around 0
/// when `limited`, based within 1 of the origin.
pub fn random_chain(rng: &mut SplitMix64, n: usize, limited: bool) -> Chain {
    let links: Vec<Link> = (0..n)
        .map(|_| {
            let l = rng.range(0.5, 2.0);
            if limited {
                let (lo, hi) = (-rng.range(0.3, 2.5), rng.range(0.3, 2.5));
                Link::new(l, 0.0).with_limits(JointLimits::new(lo, hi).expect("valid limits"))
            } else {
                Link::new(l, 0.0)
            }
        })
        .collect();
    Chain::new([rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)], &links).expect("valid chain")
}

/// A random pose inside the limits (free joints in [−π, π)).
pub fn random_pose(rng: &mut SplitMix64, chain: &Chain) -> Vec<f64> {
    chain.limits().iter().map(|l| l.map_or((-PI, PI), |l| (l.min(), l.max()))).map(|(a, b)| rng.range(a, b)).collect()
}

/// The tip of a random pose inside the limits, with its orientation when `oriented`:
/// a goal some pose reaches.
pub fn random_goal(rng: &mut SplitMix64, chain: &Chain, oriented: bool) -> Goal {
    let truth = random_pose(rng, chain);
    let ee = end_effector(chain, &truth);
    if oriented {
        Goal::with_orientation(ee.position.x, ee.position.y, ee.orientation).expect("finite tip")
    } else {
        Goal::position(ee.position.x, ee.position.y).expect("finite tip")
    }
}

/// `chain` written by hand as a one-branch rig (bones `upper0`, `upper1`, ..., each on the one
/// before), built by [`Skeleton::new`] from its links and not taken from the chain
/// ([`Chain::skeleton`]): the rig a user would write for the arm, against which the chain's
/// answers are compared.
pub fn chain_written_as_rig(chain: &Chain) -> Skeleton {
    let bones: Vec<Bone> = chain
        .links()
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let bone = Bone::new(format!("upper{i}"), link.length, link.angle);
            let bone = if i > 0 { bone.with_parent(format!("upper{}", i - 1)) } else { bone };
            match link.limits {
                Some(l) => bone.with_limits(l),
                None => bone,
            }
        })
        .collect();
    let base = chain.base();
    Skeleton::new([base.x, base.y], &bones).expect("a valid chain written as a rig")
}

/// A trunk standing up from the base with two arms of two bones each (`left_upper`,
/// `left_lower`, `right_upper`, `right_lower`), the elbows limited to ±2.5 rad.
pub fn fork() -> Skeleton {
    let elbow = JointLimits::new(-2.5, 2.5).expect("valid limits");
    Skeleton::new(
        [0.0, 0.0],
        &[
            Bone::new("trunk", 1.0, FRAC_PI_2),
            Bone::new("left_upper", 1.0, 1.2).with_parent("trunk"),
            Bone::new("left_lower", 1.0, 0.3).with_parent("left_upper").with_limits(elbow),
            Bone::new("right_upper", 1.0, -1.2).with_parent("trunk"),
            Bone::new("right_lower", 1.0, -0.3).with_parent("right_upper").with_limits(elbow),
        ],
    )
    .expect("a valid rig")
}

/// A shipped rig, `examples/rigs/{name}.toml`, read with `toml` (the CLI's reader, with its
/// error messages, is not available to the library's tests): bones' name, parent, length,
/// angle and limits in degrees, stiffness and rest angle, and the base.
pub fn rig(name: &str) -> Skeleton {
    let path = format!("{}/../../examples/rigs/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("a shipped rig");
    let doc: toml::Table = text.parse().expect("valid TOML");
    let base = doc
        .get("base")
        .and_then(|b| b.as_array())
        .map_or([0.0, 0.0], |b| [b[0].as_float().expect("base x"), b[1].as_float().expect("base y")]);
    let number = |v: &toml::Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)).expect("a number");
    let bones: Vec<Bone> = doc["bones"]
        .as_array()
        .expect("bones")
        .iter()
        .map(|b| {
            let mut bone =
                Bone::new(b["name"].as_str().expect("name"), number(&b["length"]), deg(number(&b["angle_deg"])));
            if let Some(parent) = b.get("parent") {
                bone = bone.with_parent(parent.as_str().expect("parent"));
            }
            if let Some(l) = b.get("limits_deg") {
                let l = l.as_array().expect("limits");
                bone = bone.with_limits(JointLimits::new(deg(number(&l[0])), deg(number(&l[1]))).expect("limits"));
            }
            if let Some(s) = b.get("stiffness") {
                bone = bone.with_stiffness(number(s));
            }
            if let Some(r) = b.get("rest_deg") {
                bone = bone.with_rest(deg(number(r)));
            }
            bone
        })
        .collect();
    Skeleton::new(base, &bones).expect("a valid rig")
}

/// A pose of `skeleton` drawn uniformly inside its limits (±π around the start angle for a
/// free bone).
pub fn random_rig_pose(skeleton: &Skeleton, rng: &mut SplitMix64) -> Vec<f64> {
    skeleton
        .limits()
        .iter()
        .zip(skeleton.start_angles())
        .map(|(l, &a)| match l {
            Some(l) => rng.range(l.min(), l.max()),
            None => rng.range(a - PI, a + PI),
        })
        .collect()
}

/// A character's bone of length 10 inheriting normally, its origin at (`x`, 0) in its parent's
/// frame, turned by `rotation` radians.
pub fn character_bone(name: &str, parent: Option<usize>, x: f64, rotation: f64) -> CharacterBone {
    CharacterBone {
        name: name.into(),
        parent,
        length: 10.0,
        setup: LocalTransform { x, rotation, ..LocalTransform::default() },
        inherit: Inherit::Normal,
    }
}

/// An IK constraint posed by Spine's rules, not uniform: `bones` toward the origin of `target`.
pub fn spine_ik(name: &str, order: u32, bones: IkBones, target: usize, setup: IkSettings) -> IkConstraint {
    IkConstraint { name: name.into(), order, bones, target, setup, uniform: false, rule: IkRule::Spine }
}

/// A clip `walk` of 1 s: one rotate timeline on `bone` with a key at each `(time, value)` (both
/// channels `value`, both curves `curve`), and the IK timelines `constraints`.
pub fn rotate_clip(
    bone: usize,
    keys: [(f64, f64); 2],
    curve: Interpolation,
    constraints: Vec<ConstraintTimeline>,
) -> Clip {
    Clip {
        name: "walk".into(),
        duration: 1.0,
        bones: vec![BoneTimeline {
            bone,
            property: BoneProperty::Rotate,
            keys: keys.iter().map(|&(time, value)| BoneKey { time, values: [value; 2], curves: [curve; 2] }).collect(),
        }],
        constraints,
    }
}
