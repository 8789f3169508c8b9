//! A skeleton's effector following a path: continuity, held pins, errors.

use nalgebra::Point2;

use super::{Follower, Path, SampleStatus, TrackError, TrackOptions, follow_rig, is_flip};
use crate::Goal;
use crate::fixtures::fork;
use crate::motion::Body;
use crate::solve::{Method, Pin, RigGoal, RigTask, SolveError, SolveOptions};

/// The right hand pinned.
fn pinned_right() -> RigTask {
    RigTask::new(vec![], vec![Pin::new(4)])
}

#[test]
fn the_left_hand_follows_a_circle_continuously_while_the_pinned_right_hand_stays() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let before = s.frame_points(&start);
    let path = Path::circle([-1.3, 1.8], 0.3, 60).unwrap();
    let options = TrackOptions::default();
    let t = follow_rig(&s, &start, 2, &pinned_right(), &path, &options).unwrap();
    assert_eq!(t.samples.len(), 60);
    assert_eq!(t.summary.reached, 60, "{:?}", t.summary);
    assert!(t.summary.flips.is_empty());
    for (k, sample) in t.samples.iter().enumerate() {
        // Continuity: after the first sample, no bone turns more than the bound per sample.
        if k > 0 {
            assert!(!is_flip(sample.step, options.max_step), "sample {k}: step {}", sample.step);
        }
        let points = s.frame_points(&sample.angles);
        let goal = path.goals()[k].target();
        assert!((points[3] - goal).norm() < 1e-5, "sample {k}: the left hand is {:?}", points[3]);
        // The pin holds where it started (not where the previous sample left it).
        assert!((points[5] - before[5]).norm() < 1e-5, "sample {k}: the right hand moved to {:?}", points[5]);
        assert!(sample.error < 1e-5, "sample {k}: the largest effector error is {}", sample.error);
        assert!(s.check_angles(&sample.angles).is_ok(), "sample {k} inside the limits");
    }
    // Same input, same track, bit for bit.
    assert_eq!(follow_rig(&s, &start, 2, &pinned_right(), &path, &options).unwrap(), t);
}

#[test]
fn a_held_goal_stays_met_and_every_step_is_bounded_after_the_first() {
    let s = fork();
    let start = s.start_angles().to_vec();
    // The right hand held at a point (not where it starts), the left hand along a line.
    let hold = RigTask::new(vec![RigGoal::new(4, Goal::position(1.5, 1.2).unwrap())], vec![]);
    let path = Path::line([-1.5, 1.0], [-0.8, 2.4], 40).unwrap();
    let options = TrackOptions { max_step: 4f64.to_radians(), ..TrackOptions::default() };
    let t = follow_rig(&s, &start, 2, &hold, &path, &options).unwrap();
    assert!(t.samples.iter().skip(1).all(|x| x.step <= options.max_step * (1.0 + 1e-9)));
    let last = s.frame_points(&t.samples[39].angles);
    assert_eq!(t.samples[39].status, SampleStatus::Reached, "{:?}", t.summary);
    assert!((last[5] - Point2::new(1.5, 1.2)).norm() < 1e-5, "{:?}", last[5]);
}

#[test]
fn a_rig_follower_reports_bad_tasks_and_chain_only_methods() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let options = TrackOptions::default();
    let ccd = TrackOptions {
        solve: SolveOptions { method: Method::CyclicCoordinateDescent, ..SolveOptions::default() },
        ..TrackOptions::default()
    };
    let e = Follower::rig(&s, &start, 2, &pinned_right(), &ccd).unwrap_err();
    assert!(matches!(e, TrackError::Solve(SolveError::ChainOnly { .. })), "{e:?}");
    let e = Follower::rig(&s, &start, 7, &pinned_right(), &options).unwrap_err();
    assert_eq!(e.to_string(), "goal: bone 7 does not exist (the rig has 5 bones)");
    let e = Follower::rig(&s, &start, 4, &pinned_right(), &options).unwrap_err();
    assert_eq!(e.to_string(), "pin \"right_lower\": the bone already has a goal; one goal or pin per bone");
    let e = Follower::rig(&s, &start[..3], 2, &pinned_right(), &options).unwrap_err();
    assert!(matches!(e, TrackError::Solve(SolveError::PoseLength { expected: 5, got: 3 })), "{e:?}");
}

#[test]
fn a_rig_follower_measures_every_effector_at_its_pose() {
    let s = fork();
    let start = s.start_angles().to_vec();
    let mut f = Follower::rig(&s, &start, 2, &pinned_right(), &TrackOptions::default()).unwrap();
    assert_eq!(f.body().bone(), 2);
    // The pin became a goal at the right hand's start place, with its direction.
    let pin = &f.body().task().goals[1];
    let here = s.frame_points(&start)[5];
    assert_eq!((pin.bone, pin.goal.target(), pin.goal.orientation().is_some()), (4, here, true));
    assert!(f.body().task().pins.is_empty());
    // A goal far out of reach: not reached, measured, and the pose within the bound of the start.
    let step = f.step(&Goal::position(-9.0, 0.0).unwrap());
    assert_ne!(step.status, SampleStatus::Reached);
    assert!(step.error > 5.0 && step.step <= TrackOptions::default().max_step * (1.0 + 1e-9), "{step:?}");
}
