//! `ikarus pose` and `POST /api/pose` (issue 26): a character file posed as its runtime does,
//! checked against a reference output of Spine's runtime, against each other (the same bytes),
//! and for its refusals (one line naming the field and the value).

mod common;

use common::server::start;
use common::{fails, ikarus, stderr, stdout};
use serde_json::{Value, json};

const RAPTOR: &str = "../../examples/characters/spine-raptor-pro.json";
const SPINEBOY: &str = "../../examples/characters/spine-spineboy-pro.json";
const MECHA: &str = "../../examples/characters/dragonbones-mecha_1406_ske.json";

/// Runs `ikarus pose ARGS` and returns its stdout; it must succeed.
fn pose(args: &[&str]) -> (String, String) {
    let mut all = vec!["pose"];
    all.extend_from_slice(args);
    let o = ikarus(&all);
    assert!(o.status.success(), "{all:?}: {}", stderr(&o));
    (stdout(&o), stderr(&o))
}

/// The smallest difference between two angles in degrees.
fn turn(a: f64, b: f64) -> f64 {
    (a - b + 180.0).rem_euclid(360.0) - 180.0
}

#[test]
fn the_raptor_walks_as_spines_runtime_poses_it() {
    let (out, _) = pose(&["--rig", RAPTOR, "--animation", "walk", "--time", "0.4", "--format", "json"]);
    let got: Value = serde_json::from_str(&out).unwrap();
    let reference: Value = serde_json::from_str(
        &std::fs::read_to_string("../ikarus-edge/tests/reference/ref-raptor-walk-t0.4-spinecore4.2.119.json").unwrap(),
    )
    .unwrap();
    let bones = got["bones"].as_array().unwrap();
    assert_eq!(bones.len(), 76);
    let (mut far, mut turned) = (0.0f64, 0.0f64);
    for b in bones {
        let r = &reference["bones"][b["name"].as_str().unwrap()];
        let d = (b["x"].as_f64().unwrap() - r["x"].as_f64().unwrap())
            .abs()
            .max((b["y"].as_f64().unwrap() - r["y"].as_f64().unwrap()).abs());
        far = far.max(d);
        turned = turned.max(turn(b["rotation_deg"].as_f64().unwrap(), r["rot"].as_f64().unwrap()).abs());
        let tip = [r["tip"][0].as_f64().unwrap(), r["tip"][1].as_f64().unwrap()];
        let t = (b["tip"][0].as_f64().unwrap() - tip[0]).abs().max((b["tip"][1].as_f64().unwrap() - tip[1]).abs());
        assert!(t <= 1e-3, "{}: tip off by {t}", b["name"]);
    }
    assert!(far <= 1e-3 && turned <= 1e-3, "position off by {far}, rotation by {turned}°");
}

#[test]
fn text_json_and_pictures_say_the_same_pose() {
    let (json_out, _) = pose(&["--rig", MECHA, "--format", "json"]);
    let v: Value = serde_json::from_str(&json_out).unwrap();
    let (text, _) = pose(&["--rig", MECHA, "--format", "text"]);
    let rows: Vec<&str> = text.lines().skip(1).filter(|l| !l.starts_with("unsupported ")).collect();
    assert_eq!(rows.len(), v["bones"].as_array().unwrap().len());
    for (row, b) in rows.iter().zip(v["bones"].as_array().unwrap()) {
        let cells: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(cells[0], b["name"].as_str().unwrap());
        let x: f64 = cells[1].parse().unwrap();
        assert!((x - b["x"].as_f64().unwrap()).abs() <= 5e-5, "{row}");
    }
    let dir = std::env::temp_dir().join(format!("ikarus-pose-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("mecha.svg");
    let png = dir.join("mecha.png");
    let (quiet, _) = pose(&["--rig", MECHA, "--out", svg.to_str().unwrap()]);
    assert!(quiet.is_empty());
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(drawn.matches("<g class=\"bone\">").count(), rows.len());
    pose(&["--rig", MECHA, "--out", png.to_str().unwrap(), "--width", "300", "--height", "200"]);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_target_moves_a_limb_and_the_server_answers_the_same_bytes() {
    let args = ["--rig", SPINEBOY, "--animation", "walk", "--time", "0.25", "--target", "front-leg-target=60,20"];
    let (out, err) = pose(&[&args[..], &["--format", "json"]].concat());
    assert!(err.contains("left inactive"), "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    let bone = |n: &str| v["bones"].as_array().unwrap().iter().find(|b| b["name"] == n).unwrap().clone();
    assert_eq!(
        (bone("front-leg-target")["x"].as_f64(), bone("front-leg-target")["y"].as_f64()),
        (Some(60.0), Some(20.0))
    );
    assert!(!v["unsupported"].as_array().unwrap().is_empty());
    let server = start(&[]);
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    let body = json!({"rig": text, "animation": "walk", "time": 0.25, "targets": [{"bone": "front-leg-target", "x": 60, "y": 20}]});
    let answer = server.post("/api/pose", &body);
    assert_eq!(answer.status, 200, "{}", answer.text());
    assert_eq!(answer.text().trim_end(), out.trim_end());
    let e = server.post("/api/pose", &json!({"rig": text, "animation": "wlk"})).error(422);
    assert!(e.starts_with("animation \"wlk\": no such animation"), "{e}");
    let e = server.post("/api/pose", &json!({"rig": "[[bones]]\n"})).error(422);
    assert!(e.starts_with("rig: pose takes a character file"), "{e}");
}

#[test]
fn bad_requests_are_one_line() {
    let e = fails(&["pose", "--rig", RAPTOR, "--animation", "wlk"], 2);
    assert!(
        e.contains("animation \"wlk\": no such animation (the file has: gun-grab, gun-holster, jump, roar, walk)"),
        "{e}"
    );
    let e = fails(&["pose", "--rig", RAPTOR, "--target", "toe=1,2"], 2);
    assert!(e.contains("target \"toe\": no bone of that name"), "{e}");
    let e = fails(&["pose", "--rig", "../../examples/rigs/puppet.toml"], 2);
    assert!(e.contains("pose takes a character file"), "{e}");
    let e = fails(&["pose", "--rig", RAPTOR, "--target", "toe"], 2);
    assert!(e.contains("BONE=X,Y"), "{e}");
}
