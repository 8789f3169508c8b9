//! Issue 11's findings at the extremes, through the binary: a solve's report describes its own
//! pose (the tip is the forward kinematics of the returned angles and the status agrees with
//! the error) on an arm of lengths from 1e-9 to 1e9; no number is ever NaN (`null` in JSON);
//! huge lengths, start angles and goal orientations solve; numbers in error lines are short.

mod common;

use std::path::Path;

use serde_json::Value;

use common::{fails, json};

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

/// An arm file of `lengths`, every joint at `angle_deg`.
fn arm_file(lengths: &[f64], angle_deg: f64, limits_deg: Option<[f64; 2]>) -> String {
    let mut s = String::new();
    for l in lengths {
        s += &format!("[[links]]\nlength = {l:e}\nangle_deg = {angle_deg:e}\n");
        if let Some([lo, hi]) = limits_deg {
            s += &format!("limits_deg = [{lo}, {hi}]\n");
        }
    }
    s
}

/// No `null` where a number belongs: only an absent goal orientation, and the region's distance
/// of a solve made without limits (no verdict), may be `null`.
fn assert_no_null(v: &Value, key: &str) {
    match v {
        Value::Null => assert!(key == "angle_deg" || key == "reach_distance", "null at {key}"),
        Value::Object(m) if m.get("limits") == Some(&Value::Bool(true)) && m.contains_key("reach_distance") => {
            assert!(m["reach_distance"].is_number(), "a solve with limits has a number at reach_distance: {v}");
            m.iter().for_each(|(k, x)| assert_no_null(x, k));
        }
        Value::Array(a) => a.iter().for_each(|x| assert_no_null(x, key)),
        Value::Object(m) => m.iter().for_each(|(k, x)| assert_no_null(x, k)),
        _ => {}
    }
}

/// CCD reported `reached` with an error of 7.9e-7 where its pose was 3.9e-6 away, on an arm of
/// lengths mixed between 1e-9 and 1e9: its tip was tracked by rotating points, not by the
/// forward kinematics of its angles. Now the reported tip is the last joint (computed by forward
/// kinematics from the reported angles), digit for digit, for every method.
#[test]
fn reports_describe_their_own_pose_at_mixed_magnitudes() {
    let dir = tempfile::tempdir().unwrap();
    let lengths = [3e-9, 2e8, 5e-4, 7e5, 1e-2, 4e8, 9e-7, 3e3, 6e-5, 1e9, 2e-1, 8e6];
    let arm = write(dir.path(), "mixed.toml", &arm_file(&lengths, 17.0, None));
    let chain = ikarus::Chain::new([0.0, 0.0], &lengths.iter().map(|&l| ikarus::Link::new(l, 0.0)).collect::<Vec<_>>())
        .unwrap();
    let mut reached = 0;
    for k in 0..6 {
        // Goals some pose reaches: the tip of the angles k·0.7 rad, alternating in sign.
        let pose: Vec<f64> = (0..lengths.len()).map(|i| if i % 2 == 0 { 0.7 * f64::from(k) } else { -0.4 }).collect();
        let tip = ikarus::kinematics::end_effector(&chain, &pose).position;
        let goal = format!("{},{}", tip.x, tip.y);
        for method in ["ccd", "fabrik", "lm", "transpose"] {
            let v = json(&["solve", "--arm", &arm, "--goal", &goal, "--method", method, "--max-iterations", "300"]);
            assert_no_null(&v, "");
            let joints = v["joints"].as_array().unwrap();
            let last = &joints[joints.len() - 1];
            assert_eq!((&v["end_effector"]["x"], &v["end_effector"]["y"]), (&last[0], &last[1]), "{method}, {goal}");
            let (x, y) = (last[0].as_f64().unwrap(), last[1].as_f64().unwrap());
            let error = v["error"].as_f64().unwrap();
            // JSON numbers read back within an ulp or so: allow 4 ulps of the coordinates.
            let d = (x - tip.x).hypot(y - tip.y);
            let ulps = 4.0 * f64::EPSILON * x.abs().max(y.abs());
            assert!((error - d).abs() <= ulps, "{method}: error {error} vs {d}");
            let tolerance = v["tolerance"].as_f64().unwrap();
            assert_eq!(v["status"] == "reached", error <= tolerance, "{method}: {} with error {error}", v["status"]);
            reached += usize::from(v["status"] == "reached");
        }
    }
    assert!(reached > 0);
}

/// Transpose without line search on a 100-link limited arm, goal (1e99, 1e99): the angles,
/// error and tip were NaN (`null`) while the limits claimed to hold. Lengths of 1e52: the
/// transpose step overflowed and stalled after 0 iterations on a reachable goal.
#[test]
fn huge_goals_and_lengths_give_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let limited = write(dir.path(), "limited.toml", &arm_file(&[1.0; 100], 5.0, Some([-60.0, 60.0])));
    let v = json(&[
        "solve",
        "--arm",
        &limited,
        "--goal",
        "1e99,1e99",
        "--method",
        "transpose",
        "--backtrack",
        "0",
        "--limits",
    ]);
    assert_no_null(&v, "");
    assert_eq!(v["status"], "unreachable");
    for a in v["angles_deg"].as_array().unwrap() {
        let a = a.as_f64().unwrap();
        assert!((-60.0..=60.0).contains(&a), "{a}");
    }
    let huge = write(dir.path(), "huge.toml", &arm_file(&[1e52; 3], 5.0, None));
    let v = json(&["solve", "--arm", &huge, "--goal", "1e52,2e52", "--method", "transpose", "--tolerance", "1e40"]);
    assert_eq!(v["status"], "reached", "{v}");
}

/// `angle_deg = 1e300` was 1.7e298 rad, which no step changes (stalled after 0 iterations);
/// `--goal-angle 1e20` aimed 3.7° off. Both are normalised exactly at the edge.
#[test]
fn huge_angles_are_normalised() {
    let dir = tempfile::tempdir().unwrap();
    let arm = write(dir.path(), "spun.toml", &arm_file(&[3.0, 2.0, 1.0], 1e300, None));
    let v = json(&["solve", "--arm", &arm, "--goal", "2,3"]);
    assert_eq!(v["status"], "reached", "{v}");
    let v = json(&["solve", "--goal", "2,3", "--goal-angle", "1e20", "--no-closed-form"]);
    assert_eq!(v["status"], "reached", "{v}");
    // 1e20 = 360 · 277777777777777777 + 280: the goal is −80°, and so is the tip.
    assert_eq!(v["goal"]["angle_deg"], -80.0);
    let phi = v["end_effector"]["angle_deg"].as_f64().unwrap();
    assert!(ikarus::angle::wrap_degrees(phi + 80.0).abs() < 1e-4, "{phi}");
}

/// Error lines printed 1e300 with all its 301 digits.
#[test]
fn numbers_in_error_lines_are_short() {
    let dir = tempfile::tempdir().unwrap();
    let arm = write(dir.path(), "bad.toml", "[[links]]\nlength = -1e300\n");
    let e = fails(&["solve", "--arm", &arm, "--goal", "1,1"], 2);
    assert!(e.ends_with("links[0].length = -1e300: must be greater than 0\n"), "{e}");
    let e = fails(&["solve", "--goal", "1,1", "--lambda=-1e300"], 2);
    assert!(e.contains("-1e300: must be a finite number ≥ 0") && e.len() < 200, "{e}");
}

/// Issue 24: `ikarus workspace --limits` on 64 links whose lengths spread from 1e-9 to 1e9 ran
/// for over two minutes. The exact region now has a work cap: the command ends with one line
/// naming the links and the way out (`--grid`), exit 2, in bounded time (about 2 s in release).
#[test]
fn an_exact_region_over_its_work_cap_is_refused_with_the_way_out() {
    let dir = tempfile::tempdir().unwrap();
    let lengths: Vec<f64> = (0..64).map(|k| 10f64.powf(-9.0 + 18.0 * f64::from(k) / 63.0)).collect();
    let arm = write(dir.path(), "spread.toml", &arm_file(&lengths, 0.0, Some([-90.0, 90.0])));
    for command in ["workspace", "reach"] {
        let mut args = vec![command, "--arm", &arm, "--limits"];
        if command == "reach" {
            args.extend(["--point", "0,0"]);
        }
        let err = fails(&args, 2);
        assert!(err.contains("spread.toml: links: the exact region of these 64 links needs more than"), "{err}");
        assert!(err.contains("--grid"), "{err}");
    }
}

/// Issue 24: a link of 5e-324 (subnormal) made the exact region fail (`/api/workspace`
/// answered 500, the CLI exited 1 calling it a bug). Links far shorter than the rounding of the
/// reach (5e-324 or 1e-310 beside 1, 1e-150 beside 1e150) sweep no area a float can hold: the
/// region is the other joint's arc, answered without area (a curve, or with limits off the
/// annulus of width 0).
#[test]
fn subnormal_and_extreme_lengths_give_a_region() {
    let dir = tempfile::tempdir().unwrap();
    for lengths in [[1.0, 5e-324], [5e-324, 1.0], [1.0, 1e-310], [1e150, 1e-150], [1e-150, 1e150]] {
        let arm = write(dir.path(), "tiny.toml", &arm_file(&lengths, 0.0, Some([-60.0, 60.0])));
        for limits in ["--limits", "--no-limits"] {
            let v = json(&["workspace", "--arm", &arm, limits, "--format", "json"]);
            assert_eq!((v["exact"].as_bool(), v["area"].as_f64()), (Some(true), Some(0.0)), "{lengths:?}: {v}");
            // A curve, or (limits off: the annulus) circles of width 0.
            let pieces = v["curves"].as_array().unwrap().len() + v["boundary"].as_array().unwrap().len();
            assert!(pieces > 0, "{lengths:?}: {v}");
            let v = json(&["reach", "--arm", &arm, limits, "--point", "0,0", "--format", "json"]);
            assert!(v["distance"].as_f64().is_some_and(f64::is_finite), "{lengths:?}: {v}");
        }
    }
}

/// Issue 24: `ikarus track --circle 0,0,1e308` answered `"error": null` on every sample and the
/// arm did not stretch toward the goals. Every command now gives a finite goal a finite error
/// and points the arm at it: track (both modes), solve (with and without limits), animate.
#[test]
fn goals_near_the_largest_float_give_finite_errors_and_point_the_arm() {
    let finite_error = |v: &Value, what: &str| {
        let e = v["error"].as_f64().unwrap_or_else(|| panic!("{what}: error {}", v["error"]));
        assert!(e.is_finite() && e > 1e307, "{what}: {e}");
    };
    for mode in ["plan", "follow"] {
        let v = json(&["track", "--circle", "0,0,1e308", "--samples", "12", "--mode", mode, "--max-step-deg", "40"]);
        assert_no_null(&v, "");
        for s in v["samples"].as_array().unwrap() {
            finite_error(s, mode);
            let joints = s["joints"].as_array().unwrap();
            let tip = joints.last().unwrap();
            let (x, y) = (tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap());
            let (gx, gy) = (s["goal"][0].as_f64().unwrap(), s["goal"][1].as_f64().unwrap());
            assert!((x.hypot(y) - 6.0).abs() < 1e-3, "{mode}: the arm stretched out: {tip:?}");
            let turn = ikarus::angle::wrap_angle(y.atan2(x) - gy.atan2(gx));
            assert!(turn.abs() < 1e-3, "{mode}: the arm points at the goal: {tip:?} vs ({gx}, {gy})");
        }
    }
    for limits in [&[][..], &["--limits"]] {
        let v = json(&[&["solve", "--goal=-1e308,1e308"][..], limits].concat());
        assert_no_null(&v, "");
        finite_error(&v, "solve");
        let tip = &v["end_effector"];
        // Toward the goal (up and left; the seed's ranges keep it from going further left).
        assert!(tip["x"].as_f64().unwrap() < 1e-9 && tip["y"].as_f64().unwrap() > 4.0, "{limits:?}: {tip}");
    }
    let o = common::ikarus(&["animate", "--goal", "0,1e308", "--frames", "3", "--format", "json"]);
    assert!(o.status.success());
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_no_null(&v, "");
    finite_error(&v["solves"][0], "animate");
    // The line on stderr writes the goal short.
    assert_eq!(
        common::stderr(&o),
        "ikarus: goal (0, 1e308) not reached: unreachable, error 1.000e308; the motion ends at the best pose found\n"
    );
}
