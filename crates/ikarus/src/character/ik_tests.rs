//! The IK rules, checked through [`Character::pose`] on small hand-made limbs against what the
//! rules promise: the tip on a reachable target, the bend side, straight toward an unreachable
//! target, the softness band, stretch, compress, mix, and the cases the rules leave alone.

use crate::character::{
    Character, CharacterBone, CharacterParts, Constraint, IkBones, IkConstraint, IkRule, IkSettings, Inherit,
    LocalTransform, Placement, PoseRequest, Posed,
};
use crate::math;
use std::f64::consts::FRAC_PI_2;

fn bone(name: &str, parent: Option<usize>, length: f64, setup: LocalTransform) -> CharacterBone {
    CharacterBone { name: name.into(), parent, length, setup, inherit: Inherit::Normal }
}

fn at(x: f64, y: f64, rotation: f64) -> LocalTransform {
    LocalTransform { x, y, rotation, ..LocalTransform::default() }
}

/// root (at 1, 2), thigh (length 10, pointing down), shin (length 8, offset `shin_y` off the
/// thigh's axis), target (child of root); one two-bone constraint.
fn leg(settings: IkSettings, rule: IkRule, shin_y: f64) -> CharacterParts {
    CharacterParts {
        bones: vec![
            bone("root", None, 0.0, at(1.0, 2.0, 0.0)),
            bone("thigh", Some(0), 10.0, at(0.0, 0.0, -FRAC_PI_2)),
            bone("shin", Some(1), 8.0, at(10.0, shin_y, 0.2)),
            bone("target", Some(0), 0.0, at(0.0, 0.0, 0.0)),
        ],
        constraints: vec![Constraint::Ik(IkConstraint {
            name: "leg".into(),
            order: 0,
            bones: IkBones::Two { parent: 1, child: 2 },
            target: 3,
            setup: settings,
            uniform: false,
            rule,
        })],
        ..CharacterParts::default()
    }
}

/// Poses `parts` with the target bone's origin put at `(x, y)` in the world.
fn pose(parts: &CharacterParts, x: f64, y: f64) -> Posed {
    let c = Character::new(parts.clone()).unwrap();
    let mut out = Posed::default();
    c.pose(&PoseRequest { clip: None, targets: &[(3, [x, y])], bends: &[], turns: &[], skin: None }, &mut out).unwrap();
    out
}

/// The angle between two directions, radians, in [0, π].
fn turn(a: f64, b: f64) -> f64 {
    let (s, c) = math::sin_cos(a - b);
    math::atan2(s, c).abs()
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    math::hypot(p[0] - q[0], p[1] - q[1])
}

/// Which side of the line from the thigh's origin to the tip the knee is on: +1 left
/// (counter-clockwise), −1 right.
fn knee_side(p: &Posed) -> f64 {
    let (o, k, t) = (p.origin(1), p.origin(2), p.tip(2));
    let cross = (t[0] - o[0]) * (k[1] - o[1]) - (t[1] - o[1]) * (k[0] - o[0]);
    cross.signum()
}

#[test]
fn a_reachable_target_gets_the_tip_with_the_bend_asked_for() {
    for rule in [IkRule::Spine, IkRule::DragonBones] {
        for (bend, shin_y) in [(true, 0.0), (false, 0.0), (true, 1.5), (false, -2.0)] {
            let settings = IkSettings { bend_positive: bend, ..IkSettings::default() };
            for (x, y) in [(7.0, -10.0), (-3.0, -6.0), (12.0, 5.0), (1.0, 14.0)] {
                let p = pose(&leg(settings, rule, shin_y), x, y);
                assert!(dist(p.tip(2), [x, y]) < 1e-9, "{rule:?} bend {bend} y {shin_y} ({x}, {y}): {:?}", p.tip(2));
                // Spine's bendPositive turns the child counter-clockwise: the knee is on the
                // right of the line from the hip to the foot. DragonBones' (y down in its
                // files) is the mirror.
                let right = if rule == IkRule::Spine { bend } else { !bend };
                if shin_y == 0.0 {
                    assert_eq!(knee_side(&p), if right { -1.0 } else { 1.0 }, "{rule:?} bend {bend} ({x}, {y})");
                }
            }
        }
    }
}

#[test]
fn an_unreachable_target_gets_the_limb_pointing_straight_at_it() {
    for rule in [IkRule::Spine, IkRule::DragonBones] {
        for (x, y) in [(25.0, -20.0), (-30.0, 2.0)] {
            let p = pose(&leg(IkSettings::default(), rule, 0.0), x, y);
            let o = p.origin(1);
            let want = math::atan2(y - o[1], x - o[0]);
            assert!(turn(p.rotation(1), want) < 1e-9, "{rule:?}");
            assert!(turn(p.rotation(2), want) < 1e-9, "{rule:?}: {} vs {want}", p.rotation(2));
            assert!((dist(p.tip(2), o) - 18.0).abs() < 1e-9);
        }
    }
}

#[test]
fn stretch_reaches_an_unreachable_target() {
    let settings = IkSettings { stretch: true, ..IkSettings::default() };
    let p = pose(&leg(settings, IkRule::Spine, 0.0), 25.0, -20.0);
    assert!(dist(p.tip(2), [25.0, -20.0]) < 1e-9, "{:?}", p.tip(2));
    assert!(p.local(1).scale_x > 1.0);
}

#[test]
fn softness_straightens_the_limb_continuously_over_its_band() {
    // Full reach 18 from the hip at (1, 2); softness 2 → s′ = 2·1·(1 + 1)/2 = 2, a band from
    // 16 to 20 over which the foot falls short by sd²/(4s′), sd = d − 16.
    let settings = IkSettings { softness: 2.0, ..IkSettings::default() };
    let parts = leg(settings, IkRule::Spine, 0.0);
    let mut last: Option<f64> = None;
    for i in 0..=400 {
        let d = 14.0 + 8.0 * i as f64 / 400.0;
        let p = pose(&parts, 1.0 + d, 2.0);
        let reached = dist(p.tip(2), p.origin(1));
        let sd = d - 16.0;
        let want = if sd <= 0.0 {
            d
        } else if sd < 4.0 {
            d - sd * sd / 8.0
        } else {
            18.0
        };
        assert!((reached - want).abs() < 1e-9, "d {d}: {reached} vs {want}");
        if let Some(l) = last {
            assert!(reached >= l - 1e-12 && reached - l < 0.021, "d {d}: jump from {l} to {reached}");
        }
        last = Some(reached);
    }
}

#[test]
fn mix_zero_leaves_the_pose_and_mix_blends() {
    let none = pose(&leg(IkSettings { mix: 0.0, ..IkSettings::default() }, IkRule::Spine, 0.0), 7.0, -10.0);
    assert_eq!(none.local(1), at(0.0, 0.0, -FRAC_PI_2));
    assert_eq!(none.local(2).rotation, 0.2);
    let full = pose(&leg(IkSettings::default(), IkRule::Spine, 0.0), 7.0, -10.0);
    let half = pose(&leg(IkSettings { mix: 0.5, ..IkSettings::default() }, IkRule::Spine, 0.0), 7.0, -10.0);
    let mid = (full.local(1).rotation - FRAC_PI_2) / 2.0;
    assert!((half.local(1).rotation - mid).abs() < 1e-12);
}

#[test]
fn two_bones_do_nothing_unless_both_inherit_normally() {
    let mut parts = leg(IkSettings::default(), IkRule::Spine, 0.0);
    parts.bones[2].inherit = Inherit::NoScale;
    let p = pose(&parts, 7.0, -10.0);
    assert_eq!(p.local(1).rotation, -FRAC_PI_2);
    assert_eq!(p.local(2).rotation, 0.2);
}

#[test]
fn scaled_and_mirrored_limbs_still_reach() {
    // Negative parent scales (π offsets and sign flips), a non-uniform parent scale (the
    // ellipse), a mirrored skeleton.
    for (sx, sy) in [(-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (1.3, 0.7), (0.8, 1.6), (2.0, 2.0)] {
        let mut parts = leg(IkSettings::default(), IkRule::Spine, 0.0);
        parts.bones[1].setup.scale_x = sx;
        parts.bones[1].setup.scale_y = sy;
        let p = pose(&parts, 6.0, -9.0);
        assert!(dist(p.tip(2), [6.0, -9.0]) < 1e-9, "scale ({sx}, {sy}): {:?}", p.tip(2));
    }
    for bend in [true, false] {
        let settings = IkSettings { bend_positive: bend, ..IkSettings::default() };
        let mut parts = leg(settings, IkRule::Spine, 0.0);
        let plain = pose(&parts, 6.0, -9.0);
        parts.placement = Placement { position: [0.0, 0.0], scale: [-1.0, 1.0] };
        let mirrored = pose(&parts, -6.0, -9.0);
        assert!(dist(mirrored.tip(2), [-6.0, -9.0]) < 1e-9);
        // The mirror image of the plain pose: the knee on the other side.
        let (k, m) = (plain.origin(2), mirrored.origin(2));
        assert!((k[0] + m[0]).abs() < 1e-9 && (k[1] - m[1]).abs() < 1e-9, "{k:?} {m:?}");
        assert_eq!(knee_side(&plain), -knee_side(&mirrored));
    }
}

/// A single bone of length 10 at the origin aiming at the target.
fn arm(settings: IkSettings, uniform: bool, inherit: Inherit) -> CharacterParts {
    let mut parts = leg(settings, IkRule::Spine, 0.0);
    parts.bones[1].setup = LocalTransform { rotation: 0.9, scale_x: 1.5, scale_y: 0.5, ..LocalTransform::default() };
    parts.bones[2].inherit = inherit;
    parts.bones[2].setup = LocalTransform { x: 4.0, y: 1.0, rotation: 0.3, shear_x: 0.1, ..LocalTransform::default() };
    let ik = parts.constraints[0].ik_mut().unwrap();
    ik.bones = IkBones::One(2);
    ik.uniform = uniform;
    parts
}

#[test]
fn one_bone_aims_at_the_target_under_any_inherit_mode_but_no_scale() {
    for inherit in [Inherit::Normal, Inherit::OnlyTranslation, Inherit::NoRotationOrReflection] {
        let p = pose(&arm(IkSettings::default(), false, inherit), -4.0, 9.0);
        let o = p.origin(2);
        let want = math::atan2(9.0 - o[1], -4.0 - o[0]);
        assert!((p.rotation(2) - want).abs() < 1e-9, "{inherit:?}: {} vs {want}", p.rotation(2));
    }
}

#[test]
fn compress_and_stretch_make_one_bone_reach() {
    for (settings, uniform, x, y) in [
        (IkSettings { stretch: true, ..IkSettings::default() }, true, -20.0, 30.0),
        (IkSettings { compress: true, ..IkSettings::default() }, false, 3.0, 6.0),
    ] {
        let p = pose(&arm(settings, uniform, Inherit::Normal), x, y);
        assert!(dist(p.tip(2), [x, y]) < 1e-9, "{settings:?}: {:?}", p.tip(2));
        let l = p.local(2);
        assert_eq!(l.scale_y == l.scale_x, uniform);
    }
    // Without them, the length stays.
    let p = pose(&arm(IkSettings::default(), false, Inherit::Normal), -20.0, 30.0);
    assert_eq!(p.local(2).scale_x, 1.0);
}

#[test]
fn a_later_constraint_undoes_an_earlier_one() {
    // Two one-bone constraints on the shin, toward two targets: the one of higher order wins,
    // whatever order they are listed in.
    for (first, second) in [(0, 1), (1, 0)] {
        let mut parts = leg(IkSettings::default(), IkRule::Spine, 0.0);
        parts.bones.push(bone("other", Some(0), 0.0, at(-10.0, 0.0, 0.0)));
        let one = |target: usize, order: u32| IkConstraint {
            name: format!("aim{target}"),
            order,
            bones: IkBones::One(2),
            target,
            setup: IkSettings::default(),
            uniform: false,
            rule: IkRule::Spine,
        };
        parts.constraints = vec![one(3, first).into(), one(4, second).into()];
        let p = pose(&parts, 30.0, 2.0);
        let o = p.origin(2);
        let winner = if first > second { p.origin(3) } else { p.origin(4) };
        let want = math::atan2(winner[1] - o[1], winner[0] - o[0]);
        assert!((p.rotation(2) - want).abs() < 1e-9);
    }
}
