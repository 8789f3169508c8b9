//! [`RigTask::bends`]: a bend on a joint whose bone has no goal (a knee while the foot's tip is
//! the goal), by the one rule of a goal's bend, and its checks.

use crate::skeleton::Skeleton;
use crate::{Bend, Bone, BoneBend, Goal, RigGoal, RigTask, SolveOptions, Solver};

/// A leg: thigh, shin and foot, the goal on the foot's tip.
fn leg() -> Skeleton {
    Skeleton::new(
        [0.0, 0.0],
        &[
            Bone::new("thigh", 1.0, -1.4),
            Bone::new("shin", 1.0, 0.2).with_parent("thigh"),
            Bone::new("foot", 0.3, 1.4).with_parent("shin"),
        ],
    )
    .unwrap()
}

#[test]
fn a_bend_on_a_bone_without_a_goal_picks_the_side_of_its_joint() {
    let leg = leg();
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    for (bend, sign) in [(Bend::Positive, 1.0), (Bend::Negative, -1.0)] {
        let goal = RigGoal::new(2, Goal::position(0.6, -1.4).unwrap());
        let task = RigTask { bends: vec![BoneBend { bone: 1, bend }], ..RigTask::new(vec![goal], vec![]) };
        let out = solver.solve_rig(&leg, leg.start_angles(), &task).unwrap();
        assert_eq!(out.status, crate::Status::Reached, "{bend:?}: {out:?}");
        assert!(sign * out.pose.angles()[1] > 0.1, "{bend:?}: the knee at {:?}", out.pose.angles());
    }
}

#[test]
fn bends_are_checked() {
    let leg = leg();
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let goal = RigGoal::new(2, Goal::position(0.6, -1.4).unwrap());
    let with = |bends: Vec<BoneBend>| RigTask { bends, ..RigTask::new(vec![goal.clone()], vec![]) };
    let b = |bone, bend| BoneBend { bone, bend };
    for (task, message) in [
        (with(vec![b(0, Bend::Positive)]), "goal \"thigh\".bend: the bone has no parent, so no two-bone limb to bend"),
        (
            with(vec![b(1, Bend::Positive), b(1, Bend::Negative)]),
            "bend \"shin\": the bone already has a bend; one goal or pin per bone",
        ),
        (with(vec![b(7, Bend::Positive)]), "bend: bone 7 does not exist (the rig has 3 bones)"),
    ] {
        assert_eq!(solver.solve_rig(&leg, leg.start_angles(), &task).unwrap_err().to_string(), message);
    }
}

/// A bend on the side the start pose does not have mirrors the joint (θ → −θ) and turns the
/// parent by twice the angle between the upper bone and the line from the hip to the ankle, so
/// the ankle stays: with the goal on the ankle where the start has it, the start already
/// reaches, and the answer is that mirrored pose (not a straightened knee).
#[test]
fn a_flipped_bend_mirrors_the_knee_about_the_hip_to_ankle_line_keeping_the_ankle() {
    let leg = leg();
    let start: [f64; 3] = [-1.4, 0.8, 1.4];
    // The ankle (the shin's tip) of the start pose; thigh and shin are 1 long.
    let (c0, s0) = (start[0].cos(), start[0].sin());
    let (c1, s1) = ((start[0] + start[1]).cos(), (start[0] + start[1]).sin());
    let ankle = (c0 + c1, s0 + s1);
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let goal = RigGoal::new(1, Goal::position(ankle.0, ankle.1).unwrap()).with_bend(Bend::Negative);
    let out = solver.solve_rig(&leg, &start, &RigTask::new(vec![goal], vec![])).unwrap();
    assert_eq!(out.status, crate::Status::Reached, "{out:?}");
    assert_eq!(out.iterations, 0, "the turned start reaches already: {out:?}");
    let a = out.pose.angles();
    // The line from the hip to the ankle is at start[0] + start[1]/2: the thigh turns by start[1].
    assert!((a[1] + 0.8).abs() < 1e-6, "the knee mirrored to -0.8, at {a:?}");
    assert!((a[0] - (-1.4 + 0.8)).abs() < 1e-6, "the thigh turned by 0.8, at {a:?}");
}
