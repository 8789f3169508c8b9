//! Issue 41: the add-on's solver core on raw numbers ([`SpineRig`]), checked on spineboy's walk:
//! the numbers are read from the library's own pose (which matches the runtime's within 1e-3),
//! the solved rotations are held and the character posed again by the library, and the goals,
//! pins, limits and untouched bones are measured on that pose.

use ikarus::Goal;
use ikarus::character::{
    Character, Placement, PoseRequest, Posed, SPINE_BONE_NUMBERS, SpineBone, SpineFrame, SpineRig, TipGoal,
};
use ikarus::solve::{Method, RigGoal, SolveOptions, Solver};

fn spineboy() -> Character {
    let file = "spine-spineboy-pro.json";
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    ikarus_edge::character::load(&text, file).unwrap().character
}

fn bone(c: &Character, name: &str) -> usize {
    c.bones().iter().position(|b| b.name == name).unwrap()
}

fn walk(c: &Character, time: f64, turns: &[(usize, f64)]) -> Posed {
    let clip = Some((c.clip_index("walk").unwrap(), time));
    let mut out = Posed::default();
    c.pose(&PoseRequest { clip, targets: &[], bends: &[], turns, skin: None }, &mut out).unwrap();
    out
}

/// The runtime's numbers of every bone, as the add-on copies them from the skeleton.
fn numbers(posed: &Posed, out: &mut Vec<f64>) {
    out.clear();
    for i in 0..posed.len() {
        let w = posed.world(i);
        let l = posed.local(i);
        out.extend([w.a, w.b, w.c, w.d, w.x, w.y, l.x, l.y]);
        out.extend([l.rotation.to_degrees(), l.scale_x, l.scale_y, l.shear_x.to_degrees(), l.shear_y.to_degrees()]);
    }
    assert_eq!(out.len(), posed.len() * SPINE_BONE_NUMBERS);
}

fn rig(c: &Character, limits: &[(usize, [f64; 2])]) -> SpineRig {
    let bones = c
        .bones()
        .iter()
        .enumerate()
        .map(|(i, b)| SpineBone {
            parent: b.parent,
            length: b.length,
            inherit: b.inherit,
            limits_deg: limits.iter().find(|l| l.0 == i).map(|l| l.1),
        })
        .collect();
    SpineRig::new(bones).unwrap()
}

fn solver() -> Solver {
    Solver::new(SolveOptions { method: Method::LevenbergMarquardt, ..SolveOptions::default() }).unwrap()
}

fn goal(bone: usize, x: f64, y: f64, bones: usize) -> TipGoal {
    TipGoal { goal: RigGoal::new(bone, Goal::position(x, y).unwrap()), bones }
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    libm::hypot(p[0] - q[0], p[1] - q[1])
}

/// The turns that hold the rig's answer when posing again: each moved bone's local rotation
/// turned by what the solve turned it.
fn turns(rig: &SpineRig, posed: &Posed, rotations: &[f64]) -> Vec<(usize, f64)> {
    rig.moved().iter().map(|&m| (m, rotations[m].to_radians())).filter(|&(m, r)| r != posed.local(m).rotation).collect()
}

#[test]
fn a_three_bone_goal_and_a_pin_on_spineboys_walk_are_met_on_the_pose_made_again() {
    let c = spineboy();
    let posed = walk(&c, 0.4, &[]);
    let (fist, bracer, upper, foot) =
        (bone(&c, "front-fist"), bone(&c, "front-bracer"), bone(&c, "front-upper-arm"), bone(&c, "rear-foot"));
    // Limits 25° either side of the bracer's walk rotation: the goal below needs the elbow to bend.
    let r0 = posed.local(bracer).rotation.to_degrees();
    let limits = [r0 - 25.0, r0 + 25.0];
    let mut rig = rig(&c, &[(bracer, limits)]);
    let tip = posed.tip(fist);
    let target = [tip[0] - 40.0, tip[1] + 30.0];
    let mut nums = Vec::new();
    numbers(&posed, &mut nums);
    let goals = [goal(fist, target[0], target[1], 3)];
    let pins = [foot];
    let frame = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &goals, pins: &pins };
    let mut rotations = vec![0.0; c.bones().len()];
    let outcome = rig.solve(&frame, &mut solver(), &mut rotations).unwrap();
    assert!(outcome.is_some());
    // The pinned foot hangs under no moving bone: it cannot move, and stays out of the solve.
    assert_eq!(rig.moved(), [upper, bracer, fist]);
    assert!(rig.errors()[0] < 1e-3, "the rig's own error: {}", rig.errors()[0]);
    let again = walk(&c, 0.4, &turns(&rig, &posed, &rotations));
    let miss = dist(again.tip(fist), target);
    assert!(miss < 1e-3, "goal missed by {miss}");
    assert!(dist(again.tip(foot), posed.tip(foot)) < 1e-3, "pin");
    let r = again.local(bracer).rotation.to_degrees();
    assert!(r >= limits[0] - 1e-9 && r <= limits[1] + 1e-9, "bracer {r} outside {limits:?}");
    let turned = rig.moved().iter().filter(|&&m| (rotations[m].to_radians() - posed.local(m).rotation).abs() > 1e-3);
    assert!(turned.count() >= 2, "the arm bent");
    // Every bone neither moved nor below a moved bone keeps its world transform exactly.
    let mut below = vec![false; c.bones().len()];
    for (i, b) in c.bones().iter().enumerate() {
        below[i] = rig.moved().contains(&i) || b.parent.is_some_and(|p| below[p]);
    }
    let untouched = (0..below.len()).filter(|&i| !below[i]).count();
    assert!(untouched > 40, "{untouched}");
    for i in (0..below.len()).filter(|&i| !below[i]) {
        assert_eq!(again.world(i), posed.world(i), "bone {:?}", c.bones()[i].name);
    }
    // Bones the rig did not move keep their rotation, bit for bit.
    for i in (0..below.len()).filter(|i| !rig.moved().contains(i)) {
        assert_eq!(rotations[i], posed.local(i).rotation.to_degrees());
    }
}

#[test]
fn a_goal_out_of_reach_ends_nearest_and_frame_after_frame_nothing_flips() {
    let c = spineboy();
    let fist = bone(&c, "front-fist");
    let mut rig = rig(&c, &[]);
    let mut solver = solver();
    let mut nums = Vec::new();
    let mut rotations = vec![0.0; c.bones().len()];
    let mut last: Option<Vec<f64>> = None;
    for frame in 0..30 {
        let time = 0.4 + frame as f64 / 60.0;
        let posed = walk(&c, time, &[]);
        numbers(&posed, &mut nums);
        // A goal circling in front of the shoulder, slowly, 100 to 150 from it (reach 175); the
        // walk moves the arm under it (the upper arm turns ~4° a frame here). Without the start
        // from the answer before, a bone turned 28° in one frame at frame 6.
        let a = frame as f64 * 0.05;
        let s = posed.origin(bone(&c, "front-upper-arm"));
        let target = [s[0] + 110.0 + 20.0 * libm::cos(a), s[1] - 60.0 + 20.0 * libm::sin(a)];
        let goals = [goal(fist, target[0], target[1], 3)];
        let f = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &goals, pins: &[] };
        rig.solve(&f, &mut solver, &mut rotations).unwrap();
        assert!(rig.errors()[0] < 1e-3, "frame {frame}: {}", rig.errors()[0]);
        let now: Vec<f64> = rig.moved().iter().map(|&m| rotations[m]).collect();
        if let Some(before) = &last {
            for (b, n) in before.iter().zip(&now) {
                let step = (n - b + 180.0).rem_euclid(360.0) - 180.0;
                assert!(step.abs() < 20.0, "frame {frame}: a bone turned {step}°");
            }
        }
        last = Some(now);
    }
    // Out of reach (the arm is 175 long): the tip ends on the line to the goal, short of it.
    let posed = walk(&c, 0.4, &[]);
    numbers(&posed, &mut nums);
    let s = posed.origin(bone(&c, "front-upper-arm"));
    let goals = [goal(fist, s[0] + 1000.0, s[1], 3)];
    let f = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &goals, pins: &[] };
    rig.solve(&f, &mut solver, &mut rotations).unwrap();
    // Reach: shoulder to elbow to wrist (origin to origin: a child hangs on an offset, not on
    // its parent's tip) and the fist's length.
    let [upper, bracer, fist_] = ["front-upper-arm", "front-bracer", "front-fist"].map(|n| bone(&c, n));
    let reach = dist(posed.origin(bracer), posed.origin(upper))
        + dist(posed.origin(fist_), posed.origin(bracer))
        + dist(posed.tip(fist_), posed.origin(fist_));
    let err = rig.errors()[0];
    let expect = 1000.0 - reach;
    assert!((err - expect).abs() < 1e-3, "error {err}, expected {expect}");
}

#[test]
fn bad_numbers_and_goals_are_refused_naming_them() {
    let c = spineboy();
    let mut rig = rig(&c, &[]);
    let n = c.bones().len();
    let mut rotations = vec![0.0; n];
    let nums = vec![0.0; n * SPINE_BONE_NUMBERS - 1];
    let f = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &[], pins: &[] };
    let e = rig.solve(&f, &mut solver(), &mut rotations).unwrap_err().to_string();
    assert!(e.starts_with("numbers: must be"), "{e}");
    let nums = vec![0.0; n * SPINE_BONE_NUMBERS];
    let goals = [goal(n, 0.0, 0.0, 1)];
    let f = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &goals, pins: &[] };
    let e = rig.solve(&f, &mut solver(), &mut rotations).unwrap_err().to_string();
    assert_eq!(e, format!("goal: no bone {n}"));
    let goals = [goal(0, 0.0, 0.0, 2)];
    let f = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &goals, pins: &[] };
    let e = rig.solve(&f, &mut solver(), &mut rotations).unwrap_err().to_string();
    assert_eq!(e, "goal on bone 0: bones must be from 1 to 1 (up to its root), got 2");
    let bad = SpineBone { parent: Some(0), length: 1.0, inherit: Default::default(), limits_deg: None };
    let e = SpineRig::new(vec![bad]).unwrap_err().to_string();
    assert_eq!(e, "bones[0].parent: must be below 0, got 0");
}

#[test]
fn a_bone_moved_below_bones_that_do_not_move_is_carried_by_the_one_above_them() {
    // The torso turns for its goal; the fist, five bones below it (torso2, torso3, the
    // shoulder, the upper arm and the bracer do not move), turns for its own: its solved place
    // carries it with the torso, and the errors the rig reports are those of the pose made again.
    let c = spineboy();
    let posed = walk(&c, 0.4, &[]);
    let (torso, fist) = (bone(&c, "torso"), bone(&c, "front-fist"));
    let mut rig = rig(&c, &[]);
    let mut nums = Vec::new();
    numbers(&posed, &mut nums);
    let (t, f) = (posed.tip(torso), posed.tip(fist));
    let goals = [goal(torso, t[0] - 20.0, t[1], 1), goal(fist, f[0] + 30.0, f[1] + 30.0, 1)];
    let frame = SpineFrame { numbers: &nums, placement: Placement::default(), goals: &goals, pins: &[] };
    let mut rotations = vec![0.0; c.bones().len()];
    rig.solve(&frame, &mut solver(), &mut rotations).unwrap();
    assert_eq!(rig.moved(), [torso, fist]);
    let again = walk(&c, 0.4, &turns(&rig, &posed, &rotations));
    for (k, (b, g)) in [(torso, [t[0] - 20.0, t[1]]), (fist, [f[0] + 30.0, f[1] + 30.0])].into_iter().enumerate() {
        let error = dist(again.tip(b), g);
        assert!((error - rig.errors()[k]).abs() < 1e-6, "bone {b}: {error} made again, {} solved", rig.errors()[k]);
    }
    assert!(dist(again.tip(torso), posed.tip(torso)) > 5.0, "the torso turned");
    assert!(dist(again.tip(fist), f) > 5.0, "the fist moved");
}
