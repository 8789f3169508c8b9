use super::*;
use crate::chain::{Chain, Link};
use crate::ease::Ease;
use crate::fixtures::fork;
use crate::goal::Goal;
use crate::motion::{Body, Interpolation, MotionError, Timing};
use crate::solve::{Method, Pin, RigGoal, SolveError, SolveOptions};

fn options(frames: usize) -> MotionOptions {
    MotionOptions::new(Timing::Frames(frames), Ease::Sine)
}

fn tip(points: &[nalgebra::Point2<f64>], bone: usize) -> nalgebra::Point2<f64> {
    points[bone + 1]
}

/// The left hand reaches a point while the right hand is pinned.
fn reach_left(x: f64, y: f64) -> RigTask {
    RigTask::new(vec![RigGoal::new(2, Goal::position(x, y).unwrap())], vec![Pin::new(4)])
}

#[test]
fn a_skeleton_animates_through_keyframes_with_base_and_tips_as_points() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let mut middle = start.clone();
    middle[1] += 0.4;
    let mut end = middle.clone();
    end[1] += 0.4;
    // Two equal segments, linear ease, three frames: the middle frame is keyframe 1 exactly.
    let keys = vec![start.clone(), middle.clone(), end.clone()];
    let linear = MotionOptions::new(Timing::Frames(3), Ease::Linear).with_interpolation(Interpolation::Linear);
    let anim = animate_with(&s, &keys, None, linear).unwrap();
    assert_eq!(anim.frames.len(), 3);
    assert_eq!(anim.frames[0].angles, start);
    assert_eq!(anim.frames[1].angles, middle);
    assert_eq!(anim.frames[2].angles, end);
    for f in &anim.frames {
        assert_eq!(f.joints.len(), s.len() + 1);
        assert_eq!(f.joints[0], s.base());
        assert_eq!(f.joints, s.frame_points(&f.angles));
    }
    // A keyframe outside a bone's limits is refused, naming the bone's index.
    let mut bad = start.clone();
    bad[2] = 3.0;
    let e = animate_with(&s, &[start, bad], None, options(5)).unwrap_err();
    assert!(matches!(e, MotionError::OutsideLimits { index: 1, joint: 2, .. }), "{e:?}");
}

#[test]
fn a_skeleton_of_one_branch_moves_as_its_chain() {
    let chain = Chain::new([0.5, -0.25], &[Link::new(3.0, 0.1), Link::new(2.0, 0.2), Link::new(1.0, 0.3)]).unwrap();
    let skeleton = crate::fixtures::chain_written_as_rig(&chain);
    let keys = vec![vec![0.1, 0.2, 0.3], vec![0.9, -0.4, 1.3], vec![2.0, 0.5, -0.7]];
    let a = animate_with(&chain, &keys, None, options(17)).unwrap();
    let b = animate_with(&skeleton, &keys, None, options(17)).unwrap();
    assert_eq!(a, b, "same angles and, bit for bit, the same points");
}

#[test]
fn a_rig_motion_starts_at_the_start_pose_and_ends_at_the_solved_pose_with_the_pin_held() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let start_points = s.frame_points(&start);
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let task = reach_left(-1.2, 2.2);
    let m = through_rig_tasks(&mut solver, &s, &start, &[task], Route::Keyframes, options(30)).unwrap();
    assert_eq!(m.solves.len(), 1);
    let solved = &m.solves[0];
    assert_eq!(solved.status, Status::Reached, "{solved:?}");
    let frames = &m.animation.frames;
    assert_eq!(frames.len(), 30);
    assert_eq!(frames[0].angles, start, "the first frame is the start pose, bit for bit");
    assert_eq!(frames[29].angles, solved.angles, "the last frame is the solved pose (limited or near the start)");
    let last = &frames[29].joints;
    assert!((tip(last, 2) - nalgebra::Point2::new(-1.2, 2.2)).norm() < 1e-5, "{:?}", tip(last, 2));
    assert!((tip(last, 4) - tip(&start_points, 4)).norm() < 1e-5, "the pinned hand stays");
    for f in frames {
        assert_eq!(f.joints, s.frame_points(&f.angles));
        assert!(s.check_angles(&f.angles).is_ok(), "every frame inside the limits");
    }
}

#[test]
fn a_rig_motion_through_several_tasks_passes_through_every_solved_pose() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let tasks = [reach_left(-1.2, 2.2), reach_left(-1.6, 1.4), reach_left(-0.6, 2.6)];
    let o = options(90);
    let m = through_rig_tasks(&mut solver, &s, &start, &tasks, Route::Keyframes, o).unwrap();
    assert!(m.solves.iter().all(|r| r.status == Status::Reached), "{:?}", m.solves);
    // The frames are the motion of `animate_with` through the start and each solved pose, in
    // order: the spline runs through each of them (keyframe k at the path's arc length C_k).
    let mut keys = vec![start.clone()];
    keys.extend(m.solves.iter().map(|r| r.angles.clone()));
    assert_eq!(m.animation, animate_with(&s, &keys, None, o).unwrap());
    // Each solved pose lies on the motion: some frame's left hand is near each goal.
    for (k, task) in tasks.iter().enumerate() {
        let goal = task.goals[0].goal.target();
        let nearest = m.animation.frames.iter().map(|f| (tip(&f.joints, 2) - goal).norm()).fold(f64::MAX, f64::min);
        assert!(nearest < 0.15, "task {k}: the motion passes {nearest} from its goal");
    }
}

#[test]
fn a_chain_only_method_and_a_bad_task_are_errors() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let mut ccd =
        Solver::new(SolveOptions { method: Method::CyclicCoordinateDescent, ..SolveOptions::default() }).unwrap();
    let e = through_rig_tasks(&mut ccd, &s, &start, &[reach_left(0.0, 2.0)], Route::Keyframes, options(5));
    assert!(matches!(e, Err(GoalMotionError::Solve(SolveError::ChainOnly { .. }))), "{e:?}");
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let nobody = RigTask::new(vec![RigGoal::new(9, Goal::position(0.0, 2.0).unwrap())], vec![]);
    let e = through_rig_tasks(&mut solver, &s, &start, &[nobody], Route::Keyframes, options(5)).unwrap_err();
    assert_eq!(e.to_string(), "goal: bone 9 does not exist (the rig has 5 bones)");
}
