//! The errors of `animate` and `animate_solve`: each names the field and the value.

use super::*;

#[test]
fn animate_solve_rejects_missing_or_foreign_frames() {
    let c = seed();
    let err = animate_solve(&c, &Frames::default(), Timing::Frames(60), Ease::Sine).unwrap_err();
    assert_eq!(err, MotionError::NoRecordedFrames);
    assert!(err.to_string().starts_with("frames: the solve recorded no frames"), "{err}");
    let two = chain(&[(1.0, None), (1.0, None)]);
    let options = SolveOptions { record_every: Some(1), ..SolveOptions::default() };
    let outcome =
        Solver::new(options).unwrap().solve(&two, two.start_pose(), &Goal::position(0.5, 1.0).unwrap()).unwrap();
    let err = animate_solve(&c, &outcome.frames, Timing::Frames(60), Ease::Sine).unwrap_err();
    assert_eq!(err.to_string(), "frames[0]: expected 3 angles (one per joint), got 2");
}

#[test]
fn keyframe_and_times_errors_name_the_field_and_value() {
    let free = seed();
    let limited = chain(&[(1.0, None), (1.0, None), (1.0, Some((-1.0, 1.0)))]);
    let huge = chain(&[(1.0, Some((-f64::MAX, f64::MAX)))]);
    let ok = vec![vec![0.0; 3], vec![0.5; 3]];
    let f = Timing::Frames(10);
    let sec = Timing::Duration { seconds: 2.0, fps: 30.0 };
    let cases: Vec<(Result<Animation, MotionError>, &str)> = vec![
        (animate(&free, &[], None, f, Ease::Sine), "keyframes: need at least one keyframe, got none"),
        (
            animate(&free, &[vec![0.0; 3], vec![0.0; 2]], None, f, Ease::Sine),
            "keyframes[1]: expected 3 angles (one per joint), got 2",
        ),
        (
            animate(&free, &[vec![0.0; 3], vec![0.0, 0.0, f64::NAN]], None, f, Ease::Sine),
            "keyframes[1][2]: must be a finite number, got NaN",
        ),
        (
            animate(&limited, &[vec![0.0; 3], vec![0.0, 0.0, 3.0]], None, f, Ease::Sine),
            "keyframes[1][2]: 3 rad lies outside the limits [-1, 1] rad",
        ),
        (
            animate(&free, &[vec![0.0, 0.0, f64::MAX], vec![0.0, 0.0, -f64::MAX]], None, f, Ease::Sine),
            "keyframes[1]: the joint-space path up to this pose is too long to represent, got inf rad",
        ),
        (
            animate(&huge, &[vec![f64::MAX], vec![-f64::MAX]], None, f, Ease::Sine),
            "keyframes[1]: the joint-space path up to this pose is too long to represent, got inf rad",
        ),
        (
            animate(&free, &ok, Some(&[0.0, 0.5, 1.0]), f, Ease::Sine),
            "times: expected 2 values (one per keyframe), got 3",
        ),
        (animate(&free, &ok, Some(&[0.0, f64::NAN]), f, Ease::Sine), "times[1]: must be a finite number, got NaN"),
        (animate(&free, &ok, Some(&[0.1, 1.0]), f, Ease::Sine), "times[0]: must be 0, got 0.1"),
        (
            animate(&free, &[vec![0.0; 3], vec![0.1; 3], vec![0.2; 3]], Some(&[0.0, 0.0, 1.0]), f, Ease::Sine),
            "times[1]: must be greater than times[0] = 0, got 0",
        ),
        (
            animate(&free, &ok, Some(&[0.0, 0.5]), f, Ease::Sine),
            "times[1]: the last time must equal the duration, 1, got 0.5",
        ),
        (
            animate(&free, &ok, Some(&[0.0, 1.0]), sec, Ease::Sine),
            "times[1]: the last time must equal the duration, 2, got 1",
        ),
        (
            animate(&free, &[vec![0.0; 3]], Some(&[0.0]), f, Ease::Sine),
            "times[0]: the last time must equal the duration, 1, got 0",
        ),
    ];
    for (i, (result, want)) in cases.into_iter().enumerate() {
        let err = result.expect_err(want).to_string();
        assert_eq!(err, want, "case {i}");
    }
}

#[test]
fn timing_errors_name_the_field_and_value() {
    let free = seed();
    let ok = vec![vec![0.0; 3], vec![0.5; 3]];
    let cases: Vec<(Result<Animation, MotionError>, &str)> = vec![
        (animate(&free, &ok, None, Timing::Frames(1), Ease::Sine), "frames: must be at least 2, got 1"),
        (
            animate(&free, &ok, None, Timing::Frames(MAX_FRAMES + 1), Ease::Sine),
            "frames: gives 100001 frames, more than the maximum of 100000",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: 0.0, fps: 30.0 }, Ease::Sine),
            "seconds: must be a finite number greater than 0, got 0",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: f64::INFINITY, fps: 30.0 }, Ease::Sine),
            "seconds: must be a finite number greater than 0, got inf",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: 1.0, fps: -5.0 }, Ease::Sine),
            "fps: must be a finite number greater than 0, got -5",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: 1.0, fps: f64::NAN }, Ease::Sine),
            "fps: must be a finite number greater than 0, got NaN",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: 0.01, fps: 24.0 }, Ease::Sine),
            "seconds: 0.01 s at 24 fps gives a single frame; seconds × fps must be at least 0.5",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: 1e6, fps: 1e3 }, Ease::Sine),
            "seconds × fps: gives 1000000001 frames, more than the maximum of 100000",
        ),
        (
            animate(&free, &ok, None, Timing::Duration { seconds: 1e300, fps: 1e300 }, Ease::Sine),
            "seconds × fps: gives inf frames, more than the maximum of 100000",
        ),
    ];
    for (i, (result, want)) in cases.into_iter().enumerate() {
        let err = result.expect_err(want).to_string();
        assert_eq!(err, want, "case {i}");
    }
}
