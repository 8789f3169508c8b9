use serde_json::json;

use super::*;
use crate::api::{Endpoint, Limits};

/// The estimate of `body` for `endpoint`, read as the server reads it: 0 for a body refused
/// (it is refused at once).
fn estimate(endpoint: Endpoint, body: &[u8]) -> f64 {
    endpoint.parse(body, &Limits::default()).map_or(0.0, |r| r.cost())
}

fn lane_of(endpoint: Endpoint, body: &serde_json::Value) -> Lane {
    lane(estimate(endpoint, body.to_string().as_bytes()))
}

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");

#[test]
fn the_pages_requests_are_quick() {
    let goal = json!({ "x": 2.0, "y": 3.0 });
    for (endpoint, body) in [
        (Endpoint::Solve, json!({ "goal": goal })),
        (Endpoint::Solve, json!({ "goal": goal, "options": { "limits": true, "record_every": 50 } })),
        (Endpoint::Animate, json!({ "goal": goal, "frames": 60 })),
        (Endpoint::Animate, json!({ "goal": goal, "duration": 1.25, "fps": 60 })),
        (Endpoint::Track, json!({ "circle": [0, 0, 4], "samples": 2, "mode": "follow" })),
        (Endpoint::Workspace, json!({})),
        (Endpoint::Workspace, json!({ "resolution": 256 })),
        (Endpoint::Reach, json!({ "point": [1, 2] })),
        (Endpoint::SolveBatch, json!({ "goals": [[1, 2], [2, 1]] })),
        (Endpoint::Render, json!({ "figure": "arm", "goal": goal, "width": 400, "height": 400 })),
    ] {
        assert!(estimate(endpoint, body.to_string().as_bytes()) > 0.0, "{endpoint:?} {body} is read");
        assert_eq!(lane_of(endpoint, &body), Lane::Quick, "{endpoint:?} {body}");
    }
}

#[test]
fn the_issues_heavy_requests_are_long() {
    let links64 = vec![json!({ "length": 0.1, "angle_deg": 5.0 }); 64];
    let goals: Vec<[f64; 2]> = (0..100_000).map(|i| [f64::from(i % 50) * 0.1, 1.0]).collect();
    let via: Vec<[f64; 2]> = (0..100).map(|i| [f64::from(i % 7) * 0.5, 1.0]).collect();
    for (endpoint, body) in [
        (Endpoint::SolveBatch, json!({ "goals": goals })),
        (Endpoint::Animate, json!({ "goal": { "x": 1, "y": 1 }, "via": via })),
        (Endpoint::Track, json!({ "arm": { "links": links64 }, "circle": [0, 0, 4], "samples": 5000 })),
        (Endpoint::Workspace, json!({ "arm": { "links": links64 }, "limits": true })),
        (Endpoint::Workspace, json!({ "resolution": 1024, "samples": 1_000_000 })),
        (
            Endpoint::Solve,
            json!({ "arm": { "links": links64 }, "goal": { "x": 1, "y": 1 }, "options": { "max_iterations": 100_000 } }),
        ),
        (Endpoint::Render, json!({ "figure": "motion", "goal": { "x": 1, "y": 1 }, "frames": 2000, "format": "gif" })),
    ] {
        assert_eq!(lane_of(endpoint, &body), Lane::Long, "{endpoint:?}");
    }
}

#[test]
fn the_arms_solver_table_counts_and_options_win() {
    let arm = json!({ "links": [{ "length": 1.0 }], "solver": { "max_iterations": 100_000_000 } });
    assert_eq!(lane_of(Endpoint::Solve, &json!({ "arm": arm, "goal": { "x": 1, "y": 0 } })), Lane::Long);
    let body = json!({ "arm": arm, "goal": { "x": 1, "y": 0 }, "options": { "max_iterations": 10 } });
    assert_eq!(lane_of(Endpoint::Solve, &body), Lane::Quick);
}

#[test]
fn a_body_refused_costs_nothing_and_a_rigs_bones_goals_and_pins_count() {
    // A body that is not the request is refused at once, where it is read: nothing to cost.
    let bodies: [&[u8]; 4] =
        [b"[]", b"nonsense", b"", br#"{"arm": 3, "options": [1], "goals": {"a": 1}, "frames": "x"}"#];
    for body in bodies {
        assert!(Endpoint::Solve.parse(body, &Limits::default()).is_err(), "{}", String::from_utf8_lossy(body));
    }
    // A rig's bones, goals and pins count.
    let bones: Vec<_> = (0..256).map(|i| json!({ "name": format!("b{i}"), "length": 1.0 })).collect();
    let goals: Vec<_> = (0..64).map(|_| json!({ "bone": "b0", "x": 1, "y": 1 })).collect();
    assert_eq!(lane_of(Endpoint::Solve, &json!({ "rig": { "bones": bones }, "goals": goals })), Lane::Long);
}

/// A chain of `bones` bones with `ik` one-bone constraints on its second bone.
fn chain(bones: usize, ik: usize) -> String {
    let mut b = vec![json!({"name": "b0"})];
    b.extend((1..bones).map(|i| json!({"name": format!("b{i}"), "parent": format!("b{}", i - 1), "length": 1})));
    let k: Vec<_> = (0..ik).map(|i| json!({"name": format!("k{i}"), "bones": ["b1"], "target": "b0"})).collect();
    json!({"skeleton": {"spine": "4.2"}, "bones": b, "ik": k}).to_string()
}

/// A character's jobs are costed from the character they read.
#[test]
fn character_jobs_are_costed_from_their_character() {
    let heavy = chain(256, 1024);
    let pose = json!({"rig": heavy, "ik": "ikarus"});
    assert!(estimate(Endpoint::Pose, pose.to_string().as_bytes()) > 0.0, "the character is read");
    assert_eq!(lane_of(Endpoint::Pose, &pose), Lane::Long);
    let motion = json!({"rig": heavy, "targets": [{"bone": "b255", "x": 1, "y": 1}], "duration": 26, "fps": 30});
    assert_eq!(lane_of(Endpoint::Animate, &motion), Lane::Long);
    let track = json!({"rig": heavy, "effector": "b255", "line": [0, 0, 1, 1], "samples": 2000});
    assert_eq!(lane_of(Endpoint::Track, &track), Lane::Long);
    // The page's playback of spineboy (its walk at a time, the runtime's rules) stays quick.
    let play = json!({"rig": SPINEBOY, "animation": "walk", "time": 0.4});
    assert_eq!(lane_of(Endpoint::Pose, &play), Lane::Quick);
    let e = estimate(Endpoint::Pose, play.to_string().as_bytes());
    assert!(e > SPINEBOY.len() as f64, "reading the file counts: {e}");
}

/// A file's text sent to `rig/parse` is costed by its bytes: a megabyte is long work.
#[test]
fn a_parse_is_costed_by_its_bytes() {
    assert_eq!(lane(estimate(Endpoint::RigParse, SPINEBOY.as_bytes())), Lane::Quick);
    let big = " ".repeat(1 << 20);
    assert!(estimate(Endpoint::RigParse, big.as_bytes()) > QUICK_COST);
    assert!(estimate(Endpoint::ArmParse, big.as_bytes()) > QUICK_COST);
}

/// A `.skel`'s bytes are costed as the most JSON text they may decode into: never 0, never
/// less than the same bytes as text, and any `.skel` is long work (its strings may copy a
/// mebibyte).
#[test]
fn a_skel_is_costed_as_the_text_it_may_decode_into() {
    let skel = include_bytes!("../../../../examples/characters/spine-spineboy-pro.skel");
    let as_text = file_bytes(FileBody::Text, skel);
    assert_eq!(as_text, estimate(Endpoint::RigParse, skel));
    assert!(file_bytes(FileBody::Bytes, skel) > 16.0 * as_text, "{as_text}");
    assert!(file_bytes(FileBody::Bytes, b"") > QUICK_COST);
    assert_eq!(file_lane(FileBody::Bytes, &skel[..10]), Lane::Long);
    assert_eq!(file_lane(FileBody::Text, SPINEBOY.as_bytes()), Lane::Quick);
}

fn key(time: f64) -> serde_json::Value {
    json!({"time": time, "x": 0, "y": 1})
}

#[test]
fn a_keyed_motion_costs_a_solve_of_its_tracks_and_pins_per_frame() {
    let animate = |body: serde_json::Value| estimate(Endpoint::Animate, body.to_string().as_bytes());
    let options = json!({"max_iterations": 10, "restarts": 0, "backtrack": 0});
    let rig = json!({"bones": [{"name": "a", "length": 1}, {"name": "b", "parent": "a", "length": 1}]});
    let keys = json!({"fps": 10, "tracks": {"a": [key(0.0), key(2.0)], "b": [key(0.0)]},
                      "bends": {"c": [{"time": 0, "bend": "cw"}, {"time": 1.5, "bend": "ccw"}]}, "pins": ["d"]});
    // 21 frames × (2 bones × (1 + 2 tracks + 1 pin) × 10 iterations + a pose of 2 bones).
    assert_eq!(animate(json!({"rig": rig, "keys": keys, "options": options})), 21.0 * (80.0 + 2.0));
    // A bend's key later than every track's sets the frames; 30 fps unless told.
    let keys =
        json!({"tracks": {"a": [key(0.0)]}, "bends": {"c": [{"time": 0, "bend": "cw"}, {"time": 1, "bend": "cw"}]}});
    assert_eq!(animate(json!({"rig": rig, "keys": keys, "options": options})), 31.0 * (40.0 + 2.0));
    // A duration past the last key sets them too (the tracks hold to it).
    let keys = json!({"tracks": {"a": [key(0.0), key(1.0)]}, "duration": 3});
    assert_eq!(animate(json!({"rig": rig, "keys": keys, "options": options})), 91.0 * (40.0 + 2.0));
    // Keys that are not keys are refused where they are read: nothing to cost.
    for keys in [json!({"tracks": 5}), json!({"tracks": {"a": 3}}), json!({"tracks": {"a": [1, {"time": "x"}]}})] {
        let one = json!({"rig": rig, "keys": keys, "options": options}).to_string();
        assert!(Endpoint::Animate.parse(one.as_bytes(), &Limits::default()).is_err(), "{keys}");
    }
}

#[test]
fn a_keyed_motion_figure_costs_its_motion_and_a_picture_per_frame_of_a_gif() {
    let options = json!({"max_iterations": 10, "restarts": 0, "backtrack": 0});
    let rig = json!({"bones": [{"name": "a", "length": 1}, {"name": "b", "parent": "a", "length": 1}]});
    let keys = json!({"fps": 10, "tracks": {"a": [key(0.0), key(2.0)]}});
    let render = |format: &str| {
        let body = json!({"figure": "motion", "format": format, "width": 10, "height": 20,
                          "rig": rig, "keys": keys, "options": options});
        estimate(Endpoint::Render, body.to_string().as_bytes())
    };
    // 21 frames × (2 bones × (1 + 1 track) × 10 iterations + a pose of 2 bones), the picture.
    let motion = 21.0 * (40.0 + 2.0);
    assert_eq!(render("png"), 200.0 + motion + 200.0);
    assert_eq!(render("gif"), 200.0 + motion + 21.0 * 200.0);
}

#[test]
fn a_character_s_keyed_gif_costs_a_picture_per_frame_too() {
    let keys = json!({"fps": 10, "tracks": {"front-leg-target": [key(0.0), key(2.0)]}});
    let render = |format: &str| {
        let body = json!({"figure": "motion", "format": format, "width": 10, "height": 20,
                          "rig": SPINEBOY, "keys": keys, "animation": "walk"});
        estimate(Endpoint::Render, body.to_string().as_bytes())
    };
    assert!(render("gif") >= 200.0 + 21.0 * 200.0, "{}", render("gif"));
    assert_eq!(render("gif") - render("png"), 20.0 * 200.0);
}
