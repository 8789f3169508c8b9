//! Finite inputs whose pose overflows are refused in one line naming the field (exit 2, HTTP
//! 422), never answered as a pose with `null` in its JSON or `NaN` in its table. Before, each of
//! these four files was posed with exit 0 / HTTP 200.

mod common;

use common::{fails, temp_file};
use serde_json::json;

/// Each file, what to ask of it, and the one line it is refused with (after the file's label).
const CASES: [(&str, &str, &[&str], &str); 4] = [
    (
        "scale.json",
        r#"{"skeleton":{"spine":"4.2.0"},"bones":[{"name":"root"},
            {"name":"a","parent":"root","scaleX":1e200,"length":10},
            {"name":"hip","parent":"a","scaleX":1e200,"length":10}]}"#,
        &[],
        "bones[2] (\"hip\").scaleX = 1e200: the pose overflows (bone \"hip\"'s rotation and scale are not finite: \
         scaleX 1e200 under bone \"a\"'s world scale 1e200)",
    ),
    (
        "length.json",
        r#"{"skeleton":{"spine":"4.2.0"},"bones":[{"name":"root"},{"name":"a","parent":"root","x":1e308,"length":1e308}]}"#,
        &[],
        "bones[1] (\"a\").length = 1e308: the pose overflows (bone \"a\"'s tip is not finite: origin (1e308, 0) plus \
         length 1e308 along a world scale of 1)",
    ),
    (
        "softness.json",
        r#"{"skeleton":{"spine":"4.2.0"},"bones":[{"name":"root"},
            {"name":"up","parent":"root","length":10,"rotation":-90},
            {"name":"low","parent":"up","x":10,"length":10},{"name":"t","parent":"root","x":5,"y":-15}],
            "ik":[{"name":"leg","bones":["up","low"],"target":"t","softness":1e308}]}"#,
        &[],
        "ik[0] (\"leg\").softness = 1e308: the pose overflows (bone \"up\"'s rotation and scale are not finite)",
    ),
    (
        "key.json",
        r#"{"skeleton":{"spine":"4.2.0"},"bones":[{"name":"root"},{"name":"a","parent":"root","length":10}],
            "animations":{"go":{"bones":{"a":{"translate":[{"time":0,"x":1e300,"y":0}]}}}}}"#,
        &["--animation", "go", "--time", "0"],
        "animation \"go\" at 0 s: bone \"a\"'s x is keyed to inf (a key beyond a 32-bit float, as the runtime keeps \
         it, or a sum of keys past the largest number): the pose overflows",
    ),
];

#[test]
fn a_pose_that_overflows_is_refused_naming_the_field() {
    for (name, text, extra, message) in CASES {
        let path = temp_file("finite", name, text);
        let mut args = vec!["pose", "--rig", &path];
        args.extend(extra);
        let e = fails(&args, 2);
        assert_eq!(e, format!("ikarus: rig file {path}: {message}\n"));
        // The text table and a picture refuse it the same way (a picture was exit 1).
        let e = fails(&[&args[..], &["--format", "text"]].concat(), 2);
        assert_eq!(e, format!("ikarus: rig file {path}: {message}\n"));
        let png = temp_file("finite", "pose.png", "");
        std::fs::remove_file(&png).unwrap();
        let e = fails(&[&args[..], &["--out", &png]].concat(), 2);
        assert_eq!(e, format!("ikarus: rig file {path}: {message}\n"));
        assert!(!std::path::Path::new(&png).exists());
    }
}

#[test]
fn a_motion_whose_frames_overflow_is_refused() {
    let (name, text, _, message) = CASES[2];
    let path = temp_file("finite-motion", name, text);
    let e = fails(&["animate", "--rig", &path, "--target", "t=1,1", "--format", "csv"], 2);
    assert_eq!(e, format!("ikarus: rig file {path}: {message}\n"));
}

#[test]
fn the_api_refuses_a_pose_that_overflows() {
    let s = common::server::start(&[]);
    for (_, text, extra, message) in CASES {
        let body = if extra.is_empty() {
            json!({"rig": text})
        } else {
            json!({"rig": text, "animation": extra[1], "time": 0.0})
        };
        assert_eq!(s.post("/api/pose", &body).error(422), message);
    }
    s.assert_healthy();
}

#[test]
fn a_finite_pose_at_the_ends_of_the_range_is_drawn() {
    // Bones at ±1e308 are finite and posed; drawing them overflowed the axis ticks' count
    // (a panic, exit 101).
    let text = r#"{"skeleton":{"spine":"4.2.0"},"bones":[{"name":"root"},
        {"name":"a","parent":"root","x":1e308},{"name":"b","parent":"root","x":-1e308}]}"#;
    let path = temp_file("finite-far", "far.json", text);
    for ext in ["png", "svg"] {
        let out = temp_file("finite-far", &format!("far.{ext}"), "");
        let o = common::ikarus(&["pose", "--rig", &path, "--out", &out]);
        assert!(o.status.success(), "{ext}: {}", common::stderr(&o));
        assert!(std::fs::metadata(&out).unwrap().len() > 0);
    }
}
