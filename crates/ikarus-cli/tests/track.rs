//! `ikarus track`: the JSON contract, the formats, the modes, pictures, and bad input.

mod common;

use std::path::Path;

use common::{fails, floats, ikarus, json, stderr, succeeds};

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

#[test]
fn json_contract_of_a_planned_figure8() {
    let v = json(&["track", "--figure8", "2,1,2", "--format", "json"]);
    assert_eq!(v["mode"], "plan");
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 100);
    let first = &samples[0];
    assert_eq!(floats(&first["goal"]), vec![2.0, 1.0]);
    assert!(first.get("angle_deg").is_none());
    assert_eq!(first["status"], "reached");
    assert_eq!(first["step_deg"], 0.0);
    assert_eq!(floats(&first["angles_deg"]).len(), 3);
    assert_eq!(first["joints"].as_array().unwrap().len(), 4);
    let s = &v["summary"];
    assert_eq!((s["samples"].as_u64(), s["reached"].as_u64(), s["flips"].as_u64()), (Some(100), Some(100), Some(0)));
    assert_eq!(s["flip_samples"], serde_json::json!([]));
    assert_eq!(s["step_bound_deg"], 10.0);
    let largest = samples.iter().map(|x| x["step_deg"].as_f64().unwrap()).fold(0.0, f64::max);
    assert_eq!(s["max_step_deg"].as_f64().unwrap(), largest);
    for key in [
        "limited",
        "unreachable",
        "stalled",
        "max_error",
        "max_velocity_deg_per_sample",
        "max_acceleration_deg_per_sample2",
        "max_jerk_deg_per_sample3",
    ] {
        assert!(s.get(key).is_some(), "summary.{key} missing: {s}");
    }
    // The tip is on the path: the last joint is the goal.
    for x in samples {
        let joints = x["joints"].as_array().unwrap();
        let tip = floats(joints.last().unwrap());
        let goal = floats(&x["goal"]);
        assert!((tip[0] - goal[0]).abs() < 1e-5 && (tip[1] - goal[1]).abs() < 1e-5, "{x}");
    }
    // Same input, same output.
    assert_eq!(v, json(&["track", "--figure8", "2,1,2", "--format", "json"]));
}

#[test]
fn follow_keeps_every_step_within_the_bound() {
    let v = json(&[
        "track",
        "--line",
        "5,0,-2,4",
        "--samples",
        "30",
        "--mode",
        "follow",
        "--max-step-deg",
        "5",
        "--limits",
    ]);
    assert_eq!(v["mode"], "follow");
    for x in v["samples"].as_array().unwrap() {
        assert!(x["step_deg"].as_f64().unwrap() <= 5.0 + 1e-9, "{x}");
    }
    assert_eq!(v["summary"]["flips"], 0);
}

#[test]
fn csv_files_with_orientations_and_the_csv_and_text_formats() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "p.csv", "x,y,angle_deg\n2,3,90\n2.1,3,90\n2.2,3,85\n");
    let v = json(&["track", "--path", &path, "--format", "json"]);
    assert_eq!(v["samples"][2]["angle_deg"], 85.0);
    assert_eq!(v["summary"]["reached"], 3);
    let csv = succeeds(&["track", "--path", &path, "--format", "csv"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "sample,x,y,angle_deg,status,error,step_deg,theta1_deg,theta2_deg,theta3_deg");
    assert_eq!(lines.len(), 4);
    assert!(lines[1].starts_with("0,2.0,3.0,90.0,reached,"), "{}", lines[1]);
    let text = succeeds(&["track", "--circle", "2,2,1", "--format", "text"]);
    assert!(text.contains("samples   100: 100 reached"), "{text}");
    assert!(text.contains("flips     0"), "{text}");
}

#[test]
fn pictures_of_a_track() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["t.svg", "t.png", "t.gif"] {
        let out = dir.path().join(name);
        let out = out.to_str().unwrap();
        succeeds(&["track", "--circle", "2,2,1.5", "--samples", "12", "--format", "csv", "--out", out]);
        let bytes = std::fs::read(out).unwrap();
        assert!(bytes.len() > 100, "{name}");
    }
    let svg = std::fs::read_to_string(dir.path().join("t.svg")).unwrap();
    assert!(svg.contains("<!-- path -->"), "no path layer");
    // Nothing but the pictures was left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);
}

#[test]
fn bad_input_exits_2_with_one_line_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let no_header = write(dir.path(), "a.csv", "1,2\n3,4\n");
    let empty = write(dir.path(), "e.csv", "x,y\n");
    let nan = write(dir.path(), "n.csv", "x,y\n1,2\nNaN,3\n");
    let cases: &[(&[&str], &str)] = &[
        (&["track", "--path", &no_header], "line 1: header must be `x,y` or `x,y,angle_deg`, got `1,2`"),
        (&["track", "--path", &empty], "no samples"),
        (&["track", "--path", &nan], "line 3: x: must be a finite number, got NaN"),
        (&["track", "--circle", "2,2,1", "--samples", "1"], "--samples 1: must be at least 2"),
        (&["track", "--line", "0,0,1,1", "--samples", "0"], "--samples 0: must be at least 2"),
        (&["track", "--circle", "2,2,0"], "--circle radius: must be a finite number > 0, got 0"),
        (&["track", "--figure8", "1,inf,1"], "number 2: must be a finite number, got inf"),
        (&["track", "--line", "1,2"], "expected 4 comma-separated numbers"),
        (&["track", "--circle", "1,1,1", "--max-step-deg", "-1"], "--max-step-deg"),
        (&["track", "--circle", "1,1,1", "--mode", "teleport"], "teleport"),
        (&["track", "--circle", "1,1,1", "--line", "0,0,1,1"], "cannot be used with"),
        (&["track", "--path", &empty, "--samples", "5"], "cannot be used with"),
        (&["track", "--circle", "1,1,1", "--out", "/tmp/x.bmp"], "unsupported picture format"),
        (&["track", "--circle", "1,1,1", "--bound-first"], "--bound-first: only applies with --mode follow"),
    ];
    for (args, want) in cases {
        let err = fails(args, 2);
        assert!(err.contains(want), "{args:?}: {err}");
    }
    let o = ikarus(&["track"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn the_solvers_step_cap_is_still_a_flag() {
    let v = json(&["track", "--circle", "2,2,1", "--samples", "10", "--solver-max-step-deg", "5", "--format", "json"]);
    assert_eq!(v["summary"]["reached"], 10);
}

/// The stroke: a circle of radius 4 from 0° to 216°, 200 samples, as a path file.
fn arc_216(dir: &Path) -> (String, Vec<[f64; 2]>) {
    let points: Vec<[f64; 2]> = (0..200)
        .map(|k| {
            let a = (216.0f64 * k as f64 / 199.0).to_radians();
            [4.0 * a.cos(), 4.0 * a.sin()]
        })
        .collect();
    let rows: Vec<String> = points.iter().map(|p| format!("{:?},{:?}", p[0], p[1])).collect();
    (write(dir, "arc.csv", &format!("x,y\n{}\n", rows.join("\n"))), points)
}

/// Checks a plan's answer on [`arc_216`] with the limits on: no step over the bound, the arm
/// off the path between the two reachable pieces, every path sample there in order.
fn check_off_path_plan(v: &serde_json::Value, points: &[[f64; 2]]) {
    let s = &v["summary"];
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(s["samples"], 200, "{s}");
    assert_eq!(s["flips"], 0, "{s}");
    assert!(s["max_step_deg"].as_f64().unwrap() <= 10.0 + 1e-6, "{s}");
    let off = s["off_path"].as_u64().unwrap() as usize;
    assert!(off >= 3, "the arm leaves the path to cross over: {s}");
    assert_eq!(samples.len(), 200 + off);
    let reached = s["reached"].as_u64().unwrap();
    assert!(reached > 40 && reached < 200, "{s}");
    for (k, w) in samples.windows(2).enumerate() {
        let (a, b) = (floats(&w[0]["angles_deg"]), floats(&w[1]["angles_deg"]));
        let step = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        assert!(step <= 10.0 + 1e-6, "poses {k}→{}: a joint moved {step}°", k + 1);
        assert!(b[0].abs() <= 45.0 + 1e-9, "pose {}: joint 1 at {}° outside its limits", k + 1, b[0]);
    }
    let on_path: Vec<Vec<f64>> =
        samples.iter().filter(|x| x["status"] != "off_path").map(|x| floats(&x["goal"])).collect();
    assert_eq!(on_path, points.iter().map(|p| p.to_vec()).collect::<Vec<_>>());
    // The off-path poses come in runs, each between two samples of the path.
    assert_ne!(samples[0]["status"], "off_path");
    assert_ne!(samples.last().unwrap()["status"], "off_path");
}

#[test]
fn a_plan_with_limits_crosses_between_reachable_pieces_off_the_path_within_the_bound() {
    let dir = tempfile::tempdir().unwrap();
    let (file, points) = arc_216(dir.path());
    let v = json(&["track", "--path", &file, "--limits", "--format", "json"]);
    check_off_path_plan(&v, &points);
    let text = succeeds(&["track", "--path", &file, "--limits", "--format", "text"]);
    let off = v["summary"]["off_path"].as_u64().unwrap();
    assert!(text.contains(&format!("off path  {off} poses between samples, within the bound")), "{text}");
    assert!(text.contains("flips     0\n"), "{text}");
    let csv = succeeds(&["track", "--path", &file, "--limits", "--format", "csv"]);
    assert_eq!(csv.lines().filter(|l| l.contains(",off_path,")).count() as u64, off);

    // The API answers the same.
    let s = common::server::start(&[]);
    let rows: Vec<serde_json::Value> = points.iter().map(|p| serde_json::json!(p)).collect();
    let body = serde_json::json!({ "path": rows, "mode": "plan", "options": { "limits": true } });
    let api = s.post("/api/track", &body).json();
    check_off_path_plan(&api, &points);
    assert_eq!(api["summary"], v["summary"]);
}

#[test]
fn a_bound_too_small_for_a_plans_gaps_is_one_line_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let (file, _) = arc_216(dir.path());
    let err = fails(&["track", "--path", &file, "--limits", "--max-step-deg", "0.01"], 2);
    assert!(err.starts_with("ikarus: max_step_deg = 0.01: bridging the plan's gaps"), "{err}");
    assert!(err.contains("more than the cap of 12800 (64 per sample)"), "{err}");
}
