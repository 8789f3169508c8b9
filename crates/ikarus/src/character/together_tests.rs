//! Solving a character's constraints together, checked on hand-made legs against what it
//! promises: the runtime's own answer where that is exact, both of two fighting constraints
//! met, a three-bone limb reaching where two bones cannot, the bend side, limits, pins, mix 0,
//! and a parent scaled unevenly.

use crate::character::{BoneRule, Placement};
use crate::character::{
    Character, CharacterBone, CharacterParts, Constraint, IkBones, IkConstraint, IkRule, IkSettings, Inherit, LimbRule,
    LocalTransform, PoseRequest, Posed, Together,
};
use crate::math;
use crate::solve::{Method, SolveOptions, Solver};
use std::f64::consts::FRAC_PI_2;

fn bone(name: &str, parent: Option<usize>, length: f64, setup: LocalTransform) -> CharacterBone {
    CharacterBone { name: name.into(), parent, length, setup, inherit: Inherit::Normal }
}

fn at(x: f64, y: f64, rotation: f64) -> LocalTransform {
    LocalTransform { x, y, rotation, ..LocalTransform::default() }
}

fn constraint(name: &str, order: u32, parent: usize, child: usize, target: usize) -> IkConstraint {
    IkConstraint {
        name: name.into(),
        order,
        bones: IkBones::Two { parent, child },
        target,
        setup: IkSettings::default(),
        uniform: false,
        rule: IkRule::Spine,
    }
}

/// root, hip (length 0), thigh 10 down, shin 8, foot 4, and two targets under the root
/// (bones 5 and 6); no constraint yet.
fn leg() -> CharacterParts {
    CharacterParts {
        bones: vec![
            bone("root", None, 0.0, at(0.0, 0.0, 0.0)),
            bone("hip", Some(0), 0.0, at(0.0, 20.0, 0.0)),
            bone("thigh", Some(1), 10.0, at(0.0, 0.0, -FRAC_PI_2)),
            bone("shin", Some(2), 8.0, at(10.0, 0.0, 0.3)),
            bone("foot", Some(3), 4.0, at(8.0, 0.0, 0.2)),
            bone("knee-target", Some(0), 0.0, at(0.0, 0.0, 0.0)),
            bone("foot-target", Some(0), 0.0, at(0.0, 0.0, 0.0)),
        ],
        ..CharacterParts::default()
    }
}

fn solver() -> Solver {
    Solver::new(SolveOptions { method: Method::LevenbergMarquardt, ..SolveOptions::default() }).unwrap()
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    math::hypot(p[0] - q[0], p[1] - q[1])
}

fn both(c: &Character, targets: &[(usize, [f64; 2])], rules: &Together) -> (Posed, Posed) {
    let request = PoseRequest { clip: None, targets, bends: &[], turns: &[], skin: None };
    let mut runtime = Posed::default();
    c.pose(&request, &mut runtime).unwrap();
    let mut together = Posed::default();
    c.pose_together(&request, rules, &mut solver(), &mut together).unwrap();
    (runtime, together)
}

#[test]
fn one_reachable_two_bone_limb_is_the_runtimes_answer_on_either_bend() {
    for bend_positive in [true, false] {
        let mut parts = leg();
        let mut k = constraint("knee", 0, 2, 3, 5);
        k.setup.bend_positive = bend_positive;
        parts.constraints = [k].map(Constraint::from).into();
        let c = Character::new(parts).unwrap();
        for target in [[5.0, 8.0], [-6.0, 10.0], [3.0, 4.0]] {
            let (runtime, together) = both(&c, &[(5, target)], &Together::default());
            for i in 0..7 {
                assert!(dist(runtime.origin(i), together.origin(i)) < 1e-6, "bone {i} origin, bend {bend_positive}");
                assert!(dist(runtime.tip(i), together.tip(i)) < 1e-6, "bone {i} tip, bend {bend_positive}");
            }
            assert!(dist(together.tip(3), target) < 1e-6);
        }
    }
}

#[test]
fn two_constraints_that_fight_in_the_runtime_are_both_met() {
    // Targets from a pose the leg can take with both bends positive: the shin's tip at T1 (the
    // knee bent counter-clockwise), the foot's tip at T2, the foot turned 0.5 rad
    // counter-clockwise from the shin (its direction worked out by the law of cosines).
    let mut parts = leg();
    // The ankle first, then the knee, which turns the shin and the foot with it.
    parts.constraints = [constraint("knee", 1, 2, 3, 5), constraint("ankle", 0, 3, 4, 6)].map(Constraint::from).into();
    let c = Character::new(parts).unwrap();
    let t1 = [6.0, 6.0];
    let (d, a, b) = (math::hypot(6.0, -14.0), 10.0, 8.0);
    let knee = math::acos((d * d - a * a - b * b) / (2.0 * a * b));
    let thigh = math::atan2(-14.0, 6.0) - math::atan2(b * math::sin(knee), a + b * math::cos(knee));
    let (s, co) = math::sin_cos(thigh + knee + 0.5);
    let t2 = [6.0 + 4.0 * co, 6.0 + 4.0 * s];
    let targets = [(5, t1), (6, t2)];
    let (runtime, together) = both(&c, &targets, &Together::default());
    let ankle_runtime = dist(runtime.tip(4), t2);
    assert!(ankle_runtime > 0.5, "the runtime's knee undoes its ankle: {ankle_runtime}");
    assert!(dist(runtime.tip(3), t1) < 1e-9, "the runtime meets the last constraint");
    assert!(dist(together.tip(3), t1) < 1e-6, "knee: {}", dist(together.tip(3), t1));
    assert!(dist(together.tip(4), t2) < 1e-6, "ankle: {}", dist(together.tip(4), t2));
}

#[test]
fn a_limb_of_three_bones_reaches_where_its_two_cannot() {
    let mut parts = leg();
    parts.constraints = [constraint("ankle", 0, 3, 4, 6)].map(Constraint::from).into();
    let c = Character::new(parts).unwrap();
    // 14.1 from the shin's start (0, 10), beyond 8 + 4; 18.4 from the hip, within 10 + 8 + 4.
    let target = [14.0, 8.0];
    let (runtime, own) = both(&c, &[(6, target)], &Together::default());
    assert!(dist(runtime.tip(4), target) > 1.0 && dist(own.tip(4), target) > 1.0);
    let three = Together {
        limbs: vec![LimbRule { constraint: 0, bones: Some(3), weight: 1.0, secondary: false }],
        ..Together::default()
    };
    let (_, together) = both(&c, &[(6, target)], &three);
    assert!(dist(together.tip(4), target) < 1e-6, "{}", dist(together.tip(4), target));
    // Its hip stays: the limb starts there.
    assert!(dist(together.origin(2), [0.0, 20.0]) < 1e-12);
}

#[test]
fn limits_on_a_local_rotation_hold_and_bind() {
    let mut parts = leg();
    parts.constraints = [constraint("knee", 0, 2, 3, 5)].map(Constraint::from).into();
    let c = Character::new(parts).unwrap();
    let target = [4.0, 8.0];
    let (_, free) = both(&c, &[(5, target)], &Together::default());
    let knee = free.local(3).rotation;
    assert!(knee > 0.5, "the free knee bends {knee}");
    let limited = Together {
        bones: vec![BoneRule { bone: 3, limits: Some([-0.1, 0.4]), stiffness: 0.0 }],
        ..Together::default()
    };
    let (_, held) = both(&c, &[(5, target)], &limited);
    let r = held.local(3).rotation;
    assert!((-0.1 - 1e-9..=0.4 + 1e-9).contains(&r), "{r}");
    assert!((r - 0.4).abs() < 1e-6, "the limit binds: {r}");
    assert!(dist(held.tip(3), target) > 1e-3);
}

#[test]
fn a_pinned_bone_keeps_its_tip_and_mix_zero_leaves_a_constraint_out() {
    let mut parts = leg();
    let mut ankle = constraint("ankle", 1, 3, 4, 6);
    ankle.setup.mix = 0.0;
    parts.constraints = [constraint("knee", 0, 2, 3, 5), ankle].map(Constraint::from).into();
    let c = Character::new(parts).unwrap();
    let targets = [(5, [5.0, 9.0]), (6, [30.0, 30.0])];
    let (runtime, together) = both(&c, &targets, &Together::default());
    for i in 0..7 {
        assert!(dist(runtime.tip(i), together.tip(i)) < 1e-6, "bone {i}: mix 0 is out, as in the runtime");
    }
    let report = c
        .pose_together(
            &PoseRequest { clip: None, targets: &targets, bends: &[], turns: &[], skin: None },
            &Together::default(),
            &mut solver(),
            &mut Posed::default(),
        )
        .unwrap();
    assert!(report.limbs[0].active && !report.limbs[1].active && report.limbs[0].error < 1e-6);

    // Pin the thigh and extend the ankle's limb over it: the thigh's tip stays where the
    // runtime's pose has it.
    let pinned = Together { pins: vec![2], ..Together::default() };
    let (runtime, held) = both(&c, &targets, &pinned);
    assert!(dist(held.tip(2), runtime.tip(2)) < 1e-9 && (held.rotation(2) - runtime.rotation(2)).abs() < 1e-9);
    let (_, free) = both(&c, &targets, &Together::default());
    assert!(dist(free.tip(2), runtime.tip(2)) < 1e-9, "the knee alone is the runtime's exact answer too");
}

#[test]
fn a_parent_scaled_unevenly_is_solved_in_the_runtimes_own_world() {
    let mut parts = leg();
    parts.bones[1].setup.scale_x = 1.15;
    parts.bones[1].setup.scale_y = 0.9;
    parts.bones[1].setup.rotation = 0.4;
    parts.constraints = [constraint("ankle", 0, 3, 4, 6)].map(Constraint::from).into();
    parts.placement = Placement { position: [3.0, -2.0], scale: [1.0, 1.0] };
    let c = Character::new(parts.clone()).unwrap();
    let three = Together {
        limbs: vec![LimbRule { constraint: 0, bones: Some(3), weight: 1.0, secondary: false }],
        ..Together::default()
    };
    // A target the leg can reach: its foot's tip in another pose (the thigh turned, the shin and
    // the foot 0.1 rad each), taken in the runtime's world; the first turn of the thigh that
    // puts it out of the shin's and the foot's reach where the thigh is now.
    let reach = |turn: f64| {
        let mut turned = CharacterParts { constraints: Vec::new(), ..parts.clone() };
        for (i, r) in [(2, turn), (3, 0.7), (4, 0.7)] {
            turned.bones[i].setup.rotation += r;
        }
        let mut there = Posed::default();
        Character::new(turned).unwrap().pose(&PoseRequest::default(), &mut there).unwrap();
        let target = there.tip(4);
        let mut runtime = Posed::default();
        c.pose(&PoseRequest { clip: None, targets: &[(6, target)], bends: &[], turns: &[], skin: None }, &mut runtime)
            .unwrap();
        (target, dist(runtime.tip(4), target))
    };
    let tries = [0.6, -0.6, 1.2, -1.2, 2.0, -2.0].map(reach);
    let (target, _) = tries.into_iter().find(|&(_, miss)| miss > 1.0).unwrap_or_else(|| panic!("{tries:?}"));
    let mut out = Posed::default();
    let report = c
        .pose_together(
            &PoseRequest { clip: None, targets: &[(6, target)], bends: &[], turns: &[], skin: None },
            &three,
            &mut solver(),
            &mut out,
        )
        .unwrap();
    let miss = dist(out.tip(4), target);
    assert!(miss < 1e-6, "{miss} after {} rounds: {:?}", report.rounds, report.outcome.map(|o| (o.status, o.error)));
    assert!((report.limbs[0].error - miss).abs() < 1e-12);
    assert!(
        report.rounds >= 2,
        "a rotation under an uneven scale is not rigid: solved again ({} rounds)",
        report.rounds
    );
}

fn tip_goal(bone: usize, goal: crate::goal::Goal, bones: usize) -> crate::character::TipGoal {
    crate::character::TipGoal { goal: crate::solve::RigGoal::new(bone, goal), bones }
}

/// A goal on the shin's tip turning two bones is the runtime's two-bone answer for a
/// constraint with its target there, on the side its bend names; the bones above stay.
#[test]
fn a_goal_on_two_bones_is_the_runtimes_two_bone_answer() {
    use crate::goal::Goal;
    use crate::solve::Bend;
    for (bend_positive, bend) in [(true, Bend::Positive), (false, Bend::Negative)] {
        let mut parts = leg();
        let mut k = constraint("knee", 0, 2, 3, 5);
        k.setup.bend_positive = bend_positive;
        parts.constraints = [k].map(Constraint::from).into();
        let with_constraint = Character::new(parts).unwrap();
        let free = Character::new(leg()).unwrap();
        for target in [[5.0, 8.0], [-6.0, 10.0], [3.0, 4.0]] {
            let (runtime, _) = both(&with_constraint, &[(5, target)], &Together::default());
            let mut g = tip_goal(3, Goal::position(target[0], target[1]).unwrap(), 2);
            g.goal = g.goal.with_bend(bend);
            let rules = Together { goals: vec![g], ..Together::default() };
            let mut posed = Posed::default();
            let report = free
                .pose_together(
                    &PoseRequest { clip: None, targets: &[], bends: &[], turns: &[], skin: None },
                    &rules,
                    &mut solver(),
                    &mut posed,
                )
                .unwrap();
            for i in 0..5 {
                assert!(dist(runtime.tip(i), posed.tip(i)) < 1e-6, "bone {i}, bend {bend_positive}, {target:?}");
            }
            assert!(report.goals[0].error < 1e-6 && report.goals[0].angle_error.is_none(), "{:?}", report.goals);
            assert!(report.rounds >= 1 && report.limbs.is_empty());
        }
    }
}

/// `bones` says how far up a goal moves the body: one bone only aims; three reach with a
/// direction; the bones above the last one counted never move.
#[test]
fn a_goals_bone_count_bounds_what_moves() {
    use crate::goal::Goal;
    let c = Character::new(leg()).unwrap();
    let mut setup = Posed::default();
    c.pose(&PoseRequest { clip: None, targets: &[], bends: &[], turns: &[], skin: None }, &mut setup).unwrap();
    let solve = |g: crate::character::TipGoal| {
        let mut posed = Posed::default();
        let rules = Together { goals: vec![g], ..Together::default() };
        let r = c
            .pose_together(
                &PoseRequest { clip: None, targets: &[], bends: &[], turns: &[], skin: None },
                &rules,
                &mut solver(),
                &mut posed,
            )
            .unwrap();
        (posed, r)
    };
    // The foot alone turns toward (12, 0): its tip on the ray, not on the point.
    let (aimed, r) = solve(tip_goal(4, Goal::position(12.0, 0.0).unwrap(), 1));
    for i in 0..4 {
        assert!(dist(aimed.tip(i), setup.tip(i)) < 1e-12, "bone {i} moved");
    }
    let [ox, oy] = aimed.origin(4);
    let toward = math::atan2(0.0 - oy, 12.0 - ox);
    assert!((aimed.rotation(4) - toward).abs() < 1e-6, "{} vs {toward}", aimed.rotation(4));
    assert!((r.goals[0].error - (math::hypot(12.0 - ox, -oy) - 4.0)).abs() < 1e-6);
    // Three bones put the foot's tip at (9, 6) pointing down-right; the hip stays.
    let down_right = -0.6;
    let (placed, r) = solve(tip_goal(4, Goal::with_orientation(9.0, 6.0, down_right).unwrap(), 3));
    assert!(r.goals[0].error < 1e-6, "{:?}", r.goals[0]);
    assert!(r.goals[0].angle_error.is_some_and(|a| a.abs() < 1e-6), "{:?}", r.goals[0]);
    assert!(dist(placed.origin(2), setup.origin(2)) < 1e-12);
    // A goal on a constraint's last bone replaces the constraint's; another constraint stays met.
    let mut parts = leg();
    parts.constraints = [constraint("knee", 0, 2, 3, 5)].map(Constraint::from).into();
    let both_c = Character::new(parts).unwrap();
    let g = tip_goal(3, Goal::position(4.0, 9.0).unwrap(), 2);
    let rules = Together { goals: vec![g], ..Together::default() };
    let mut posed = Posed::default();
    let r = both_c
        .pose_together(
            &PoseRequest { clip: None, targets: &[(5, [-20.0, -20.0])], bends: &[], turns: &[], skin: None },
            &rules,
            &mut solver(),
            &mut posed,
        )
        .unwrap();
    assert!(dist(posed.tip(3), [4.0, 9.0]) < 1e-6 && r.goals[0].error < 1e-6);
}

#[test]
fn a_goal_names_a_bone_and_a_count_it_has() {
    use crate::goal::Goal;
    let c = Character::new(leg()).unwrap();
    let g = |bone, bones| Together {
        goals: vec![tip_goal(bone, Goal::position(1.0, 1.0).unwrap(), bones)],
        ..Together::default()
    };
    let e = c.check_together(&g(4, 6)).unwrap_err().to_string();
    assert_eq!(e, "goal on \"foot\": bones must be from 1 (the bone alone) to 5 (up to its root), got 6");
    assert!(c.check_together(&g(4, 0)).is_err() && c.check_together(&g(4, 5)).is_ok());
    assert_eq!(c.check_together(&g(9, 1)).unwrap_err().to_string(), "goal: no bone 9");
}
