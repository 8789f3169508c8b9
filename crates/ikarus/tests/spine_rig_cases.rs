//! Issue 41: [`SpineRig`] on the cases the add-on meets beyond a walking arm: every inherit mode
//! in the chain, a flipped and moved skeleton, a root bone in the chain, limits, a pin under a
//! goal's bones, a goal out of reach swept around, bad input. Each expectation is derived with
//! the library's own posing from local transforms ([`world_transform`], bone after bone, as the
//! runtime's `updateWorldTransform` does), not with the rig's.

use ikarus::Goal;
use ikarus::character::{
    Affine, Character, Inherit, LocalTransform, Placement, PoseRequest, Posed, SPINE_BONE_NUMBERS, SpineBone,
    SpineFrame, SpineRig, TipGoal, spine_bone_numbers, world_transform,
};
use ikarus::solve::{Method, Priority, RigGoal, SolveOptions, Solver};

fn solver() -> Solver {
    Solver::new(SolveOptions { method: Method::LevenbergMarquardt, ..SolveOptions::default() }).unwrap()
}

/// Every bone's world transform from the local ones, parents first.
fn worlds(bones: &[SpineBone], locals: &[LocalTransform], placement: Placement) -> Vec<Affine> {
    let mut w: Vec<Affine> = Vec::with_capacity(bones.len());
    for (b, l) in bones.iter().zip(locals) {
        let parent = b.parent.map(|p| w[p]);
        w.push(world_transform(l, b.inherit, parent.as_ref(), placement));
    }
    w
}

/// The frame's numbers: world then local, degrees.
fn numbers(worlds: &[Affine], locals: &[LocalTransform]) -> Vec<f64> {
    let mut out = Vec::with_capacity(worlds.len() * SPINE_BONE_NUMBERS);
    for (w, l) in worlds.iter().zip(locals) {
        out.extend(spine_bone_numbers(w, l));
    }
    out
}

fn tip(w: &Affine, length: f64) -> [f64; 2] {
    [w.x + w.a * length, w.y + w.c * length]
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    libm::hypot(p[0] - q[0], p[1] - q[1])
}

/// The locals with the rig's rotations (degrees) put in.
fn with_rotations(locals: &[LocalTransform], rotations: &[f64]) -> Vec<LocalTransform> {
    locals.iter().zip(rotations).map(|(l, r)| LocalTransform { rotation: r.to_radians(), ..*l }).collect()
}

/// A root and five bones in a line, one per inherit mode after the first, scaled and sheared
/// so that each mode makes a difference.
fn six_bones() -> (Vec<SpineBone>, Vec<LocalTransform>) {
    let modes = [
        Inherit::Normal,
        Inherit::Normal,
        Inherit::OnlyTranslation,
        Inherit::NoRotationOrReflection,
        Inherit::NoScale,
        Inherit::NoScaleOrReflection,
    ];
    let bones = modes
        .iter()
        .enumerate()
        .map(|(i, &inherit)| SpineBone {
            parent: i.checked_sub(1),
            length: [30.0, 50.0, 40.0, 35.0, 30.0, 25.0][i],
            inherit,
            limits_deg: None,
        })
        .collect();
    let locals = (0..6)
        .map(|i| LocalTransform {
            x: if i == 0 { 10.0 } else { [30.0, 50.0, 40.0, 35.0, 30.0][i - 1] },
            y: if i == 0 { -5.0 } else { 2.0 },
            rotation: [10.0f64, 25.0, -30.0, 40.0, -20.0, 15.0][i].to_radians(),
            scale_x: [1.2, 0.9, 1.1, 1.0, 1.3, 0.8][i],
            scale_y: [0.8, 1.1, 1.0, 1.2, 0.9, 1.0][i],
            shear_x: 0.0,
            shear_y: if i == 2 { 5f64.to_radians() } else { 0.0 },
        })
        .collect();
    (bones, locals)
}

#[test]
fn every_inherit_mode_in_the_chain_a_flipped_moved_skeleton_and_a_root_bone_meet_the_goal_posed_again() {
    let (bones, locals) = six_bones();
    for placement in [
        Placement { position: [0.0, 0.0], scale: [1.0, 1.0] },
        Placement { position: [120.0, -40.0], scale: [-1.0, 1.0] },
        Placement { position: [-60.0, 15.0], scale: [1.25, -1.25] },
    ] {
        for chain in [5, 6] {
            let mut rig = SpineRig::new(bones.clone()).unwrap();
            let w = worlds(&bones, &locals, placement);
            let nums = numbers(&w, &locals);
            // A target the chain reaches: its tip with every bone of the chain turned a little.
            let mut turned = locals.clone();
            for (i, l) in turned.iter_mut().enumerate().skip(6 - chain) {
                l.rotation += (8.0 + i as f64).to_radians();
            }
            let target = tip(&worlds(&bones, &turned, placement)[5], 25.0);
            let goals =
                [TipGoal { goal: RigGoal::new(5, Goal::position(target[0], target[1]).unwrap()), bones: chain }];
            let frame = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[] };
            let mut rotations = vec![0.0; 6];
            rig.solve(&frame, &mut solver(), &mut rotations).unwrap();
            let moved: Vec<usize> = (6 - chain..6).collect();
            assert_eq!(rig.moved(), moved);
            let again = worlds(&bones, &with_rotations(&locals, &rotations), placement);
            let miss = dist(tip(&again[5], 25.0), target);
            assert!(miss < 1e-3, "{placement:?}, {chain} bones: missed by {miss}");
            assert!((miss - rig.errors()[0]).abs() < 1e-9, "the rig's error {} vs {miss} posed again", rig.errors()[0]);
            for i in 0..6 - chain {
                assert_eq!(rotations[i].to_bits(), locals[i].rotation.to_degrees().to_bits(), "bone {i}");
            }
            assert!(dist(tip(&w[5], 25.0), target) > 5.0, "the goal is away from the start");
        }
    }
}

#[test]
fn limits_hold_on_the_local_rotation_under_each_inherit_mode() {
    let (mut bones, locals) = six_bones();
    // Each moving bone within 6° of its own rotation; the goal wants more than that.
    for (b, l) in bones.iter_mut().zip(&locals).skip(1) {
        let r = l.rotation.to_degrees();
        b.limits_deg = Some([r - 6.0, r + 6.0]);
    }
    let placement = Placement { position: [30.0, 10.0], scale: [-1.0, 1.0] };
    let w = worlds(&bones, &locals, placement);
    let nums = numbers(&w, &locals);
    let t = tip(&w[5], 25.0);
    let target = [t[0] + 60.0, t[1] + 60.0];
    let goals = [TipGoal { goal: RigGoal::new(5, Goal::position(target[0], target[1]).unwrap()), bones: 5 }];
    let frame = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[] };
    let mut rotations = vec![0.0; 6];
    let mut rig = SpineRig::new(bones.clone()).unwrap();
    rig.solve(&frame, &mut solver(), &mut rotations).unwrap();
    let mut at_a_limit = 0;
    for i in 1..6 {
        let [lo, hi] = bones[i].limits_deg.unwrap();
        assert!(
            rotations[i] >= lo - 1e-9 && rotations[i] <= hi + 1e-9,
            "bone {i}: {} outside [{lo}, {hi}]",
            rotations[i]
        );
        at_a_limit += usize::from((rotations[i] - lo).abs() < 1e-6 || (rotations[i] - hi).abs() < 1e-6);
    }
    assert!(at_a_limit >= 1, "the limits bound the solve");
    let again = worlds(&bones, &with_rotations(&locals, &rotations), placement);
    let error = dist(tip(&again[5], 25.0), target);
    assert!((error - rig.errors()[0]).abs() < 1e-9, "{error} vs {}", rig.errors()[0]);
    assert!(error < dist(t, target) - 1.0, "nearer than the start: {error}");
}

fn spineboy() -> Character {
    let file = "spine-spineboy-pro.json";
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    ikarus_edge::character::load(&std::fs::read_to_string(path).unwrap(), file).unwrap().character
}

/// Spineboy's bones and its walk's locals at `time` (the runtime's, constraints applied).
fn spineboy_at(c: &Character, time: f64) -> (Vec<SpineBone>, Vec<LocalTransform>) {
    let mut posed = Posed::default();
    let clip = Some((c.clip_index("walk").unwrap(), time));
    c.pose(&PoseRequest { clip, targets: &[], bends: &[], turns: &[], skin: None }, &mut posed).unwrap();
    let bones = c
        .bones()
        .iter()
        .map(|b| SpineBone { parent: b.parent, length: b.length, inherit: b.inherit, limits_deg: None })
        .collect();
    (bones, (0..posed.len()).map(|i| posed.local(i)).collect())
}

fn named(c: &Character, name: &str) -> usize {
    c.bones().iter().position(|b| b.name == name).unwrap()
}

#[test]
fn a_pin_holds_when_a_goal_turns_the_bones_above_it() {
    // A goal on the torso's tip turning the torso, the hip and the root; the rear foot pinned
    // below the hip (the thigh and the shin between do not move). Without the pin the foot
    // swings with the hip; with it, it stays (position and direction).
    let c = spineboy();
    let (bones, locals) = spineboy_at(&c, 0.4);
    let placement = c.placement();
    let (torso, foot) = (named(&c, "torso"), named(&c, "rear-foot"));
    let w = worlds(&bones, &locals, placement);
    let nums = numbers(&w, &locals);
    let t = tip(&w[torso], bones[torso].length);
    let target = [t[0] - 40.0, t[1] - 10.0];
    let mut goal = RigGoal::new(torso, Goal::position(target[0], target[1]).unwrap());
    goal.priority = Priority::Secondary;
    let goals = [TipGoal { goal, bones: 3 }];
    let foot_tip = tip(&w[foot], bones[foot].length);
    let mut moves = [0.0; 2];
    for (k, pins) in [&[][..], &[foot][..]].into_iter().enumerate() {
        let mut rig = SpineRig::new(bones.clone()).unwrap();
        let frame = SpineFrame { numbers: &nums, placement, goals: &goals, pins };
        let mut rotations = vec![0.0; bones.len()];
        rig.solve(&frame, &mut solver(), &mut rotations).unwrap();
        let again = worlds(&bones, &with_rotations(&locals, &rotations), placement);
        moves[k] = dist(tip(&again[foot], bones[foot].length), foot_tip);
        let turn = (again[foot].rotation() - w[foot].rotation()).abs();
        let error = dist(tip(&again[torso], bones[torso].length), target);
        assert!((error - rig.errors()[0]).abs() < 1e-9, "{error} vs {}", rig.errors()[0]);
        assert!(error < 40.0, "the torso moved toward its goal: {error}");
        if k == 1 {
            assert!(moves[1] < 1e-3 && turn < 1e-6, "the pinned foot moved {} and turned {turn}", moves[1]);
        }
    }
    assert!(moves[0] > 1.0, "without the pin the foot moves ({})", moves[0]);
}

#[test]
fn a_pin_under_moving_bones_holds_where_each_frame_of_the_walk_puts_it() {
    // Frame after frame of walk, the torso's goal turns the hip over the pinned rear foot: the
    // foot stays where each frame has it, not where the solve before left it.
    let c = spineboy();
    let placement = c.placement();
    let (torso, foot) = (named(&c, "torso"), named(&c, "rear-foot"));
    let (bones, _) = spineboy_at(&c, 0.0);
    let mut rig = SpineRig::new(bones.clone()).unwrap();
    let mut rotations = vec![0.0; bones.len()];
    let mut worst: f64 = 0.0;
    for f in 0..30 {
        let (_, locals) = spineboy_at(&c, f as f64 / 60.0);
        let w = worlds(&bones, &locals, placement);
        let nums = numbers(&w, &locals);
        let t = tip(&w[torso], bones[torso].length);
        let mut goal = RigGoal::new(torso, Goal::position(t[0] - 40.0, t[1] - 10.0).unwrap());
        goal.priority = Priority::Secondary;
        let goals = [TipGoal { goal, bones: 3 }];
        let frame = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[foot] };
        rig.solve(&frame, &mut solver(), &mut rotations).unwrap();
        let again = worlds(&bones, &with_rotations(&locals, &rotations), placement);
        worst = worst.max(dist(tip(&again[foot], bones[foot].length), tip(&w[foot], bones[foot].length)));
    }
    assert!(worst < 1e-3, "the pinned foot strayed {worst} from a frame's");
}

#[test]
fn a_goal_out_of_reach_swept_around_ends_nearest_and_never_flips() {
    let c = spineboy();
    let (bones, locals) = spineboy_at(&c, 0.4);
    let placement = c.placement();
    let [upper, bracer, fist] = ["front-upper-arm", "front-bracer", "front-fist"].map(|n| named(&c, n));
    let w = worlds(&bones, &locals, placement);
    let nums = numbers(&w, &locals);
    let origin = |i: usize| [w[i].x, w[i].y];
    let reach = dist(origin(bracer), origin(upper))
        + dist(origin(fist), origin(bracer))
        + bones[fist].length * libm::hypot(w[fist].a, w[fist].c);
    let mut rig = SpineRig::new(bones.clone()).unwrap();
    let mut solver = solver();
    let mut rotations = vec![0.0; bones.len()];
    let mut last: Option<[f64; 3]> = None;
    for frame in 0..90 {
        // Twice the arm's reach from the shoulder, a quarter turn over the sweep.
        let a = -0.8 + frame as f64 * 0.02;
        let s = origin(upper);
        let target = [s[0] + 2.0 * reach * libm::cos(a), s[1] + 2.0 * reach * libm::sin(a)];
        let goals = [TipGoal { goal: RigGoal::new(fist, Goal::position(target[0], target[1]).unwrap()), bones: 3 }];
        let f = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[] };
        rig.solve(&f, &mut solver, &mut rotations).unwrap();
        let nearest = 2.0 * reach - reach;
        assert!(
            (rig.errors()[0] - nearest).abs() < 1e-3,
            "frame {frame}: {} from the goal, nearest {nearest}",
            rig.errors()[0]
        );
        let now = [rotations[upper], rotations[bracer], rotations[fist]];
        if let Some(before) = last {
            for (b, n) in before.iter().zip(&now) {
                let step = (n - b + 180.0).rem_euclid(360.0) - 180.0;
                assert!(step.abs() < 3.0, "frame {frame}: a bone turned {step}° for a 1.1° sweep");
            }
        }
        last = Some(now);
    }
}

#[test]
fn bad_frames_and_goals_are_refused_in_one_line_naming_the_field_and_the_value() {
    let (bones, locals) = six_bones();
    let placement = Placement::default();
    let w = worlds(&bones, &locals, placement);
    let mut rig = SpineRig::new(bones).unwrap();
    let mut rotations = vec![0.0; 6];
    let mut nums = numbers(&w, &locals);
    let goal =
        |bone: usize, bones: usize| TipGoal { goal: RigGoal::new(bone, Goal::position(1.0, 2.0).unwrap()), bones };
    let mut solve = |nums: &[f64], goals: &[TipGoal], pins: &[usize]| {
        let f = SpineFrame { numbers: nums, placement, goals, pins };
        rig.solve(&f, &mut solver(), &mut rotations).map(|_| ()).unwrap_err().to_string()
    };
    assert_eq!(solve(&nums, &[goal(6, 1)], &[]), "goal: no bone 6");
    assert_eq!(solve(&nums, &[goal(5, 0)], &[]), "goal on bone 5: bones must be from 1 to 6 (up to its root), got 0");
    assert_eq!(solve(&nums, &[goal(5, 7)], &[]), "goal on bone 5: bones must be from 1 to 6 (up to its root), got 7");
    assert_eq!(solve(&nums, &[goal(5, 2)], &[9]), "pin: no bone 9");
    let mut light = goal(5, 2);
    light.goal.weight = 0.0;
    let e = solve(&nums, &[light], &[]);
    assert!(e.contains("weight") && e.contains('0') && !e.contains('\n'), "{e}");
    nums[2 * SPINE_BONE_NUMBERS + 4] = f64::NAN;
    assert_eq!(solve(&nums, &[goal(5, 2)], &[]), "frame[2].worldX: must be finite, got NaN");
    nums[2 * SPINE_BONE_NUMBERS + 4] = 0.0;
    nums[3 * SPINE_BONE_NUMBERS + 12] = f64::INFINITY;
    assert_eq!(solve(&nums, &[goal(5, 2)], &[]), "frame[3].shearY: must be finite, got inf");
}

#[test]
fn an_unevenly_scaled_skeleton_is_refused_naming_both_scales() {
    let (bones, locals) = six_bones();
    let placement = Placement { position: [0.0, 0.0], scale: [1.5, -0.75] };
    let w = worlds(&bones, &locals, placement);
    let mut rig = SpineRig::new(bones.clone()).unwrap();
    let nums = numbers(&w, &locals);
    let goals = [TipGoal { goal: RigGoal::new(5, Goal::position(1.0, 2.0).unwrap()), bones: 2 }];
    let f = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[] };
    let e = rig.solve(&f, &mut solver(), &mut [0.0; 6]).map(|_| ()).unwrap_err().to_string();
    assert_eq!(
        e,
        "skeleton scale: must be even (|scaleX| = |scaleY|, either may be negative), got scaleX 1.5, scaleY -0.75"
    );
    // A flip is even: solved.
    let placement = Placement { position: [0.0, 0.0], scale: [-1.25, 1.25] };
    let w = worlds(&bones, &locals, placement);
    let nums = numbers(&w, &locals);
    let f = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[] };
    assert!(rig.solve(&f, &mut solver(), &mut [0.0; 6]).is_ok());
}

#[test]
fn a_bend_picks_the_side_the_joint_bends_and_the_goal_is_met_on_either() {
    // The bracer and the fist (2 bones) to a point 70% of their reach from the elbow: once
    // bending counter-clockwise, once clockwise, measured on the pose made again.
    let c = spineboy();
    let (bones, locals) = spineboy_at(&c, 0.4);
    let placement = c.placement();
    let [bracer, fist] = ["front-bracer", "front-fist"].map(|n| named(&c, n));
    let w = worlds(&bones, &locals, placement);
    let nums = numbers(&w, &locals);
    let elbow = [w[bracer].x, w[bracer].y];
    let reach = dist([w[fist].x, w[fist].y], elbow) + bones[fist].length * libm::hypot(w[fist].a, w[fist].c);
    let target = [elbow[0] + 0.5 * reach, elbow[1] - 0.5 * reach];
    for (bend, sign) in [(ikarus::solve::Bend::Positive, 1.0), (ikarus::solve::Bend::Negative, -1.0)] {
        let goal = RigGoal::new(fist, Goal::position(target[0], target[1]).unwrap()).with_bend(bend);
        let goals = [TipGoal { goal, bones: 2 }];
        let frame = SpineFrame { numbers: &nums, placement, goals: &goals, pins: &[] };
        let mut rotations = vec![0.0; bones.len()];
        SpineRig::new(bones.clone()).unwrap().solve(&frame, &mut solver(), &mut rotations).unwrap();
        let again = worlds(&bones, &with_rotations(&locals, &rotations), placement);
        let miss = dist(tip(&again[fist], bones[fist].length), target);
        assert!(miss < 1e-3, "{bend:?}: missed by {miss}");
        let turn = libm::remainder(again[fist].rotation() - again[bracer].rotation(), std::f64::consts::TAU);
        assert!(turn * sign > 0.05, "{bend:?}: the fist turned {turn} from the bracer");
    }
}
