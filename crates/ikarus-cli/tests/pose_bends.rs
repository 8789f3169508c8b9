//! `POST /api/pose` with `bends`: the side of a two-bone IK constraint named by its lower bone, as
//! a keys file's bend key sets it (the page poses a drag in Key mode with the bends in force).
//! spineboy's front knee bends the other way with `{"front-shin": …}` flipped, and a name that is
//! not a two-bone constraint's lower bone is refused naming the field.

mod common;

use common::SPINEBOY;
use serde_json::{Value, json};

/// The side the front shin turns from the front thigh: the sine of the turn's sign.
fn knee(answer: &Value) -> f64 {
    let at = |n: &str| {
        answer["bones"].as_array().unwrap().iter().find(|b| b["name"] == n).unwrap()["rotation_deg"].as_f64().unwrap()
    };
    (at("front-shin") - at("front-thigh")).to_radians().sin().signum()
}

#[test]
fn a_pose_takes_the_bends_the_keys_name() {
    let s = common::server::start(&[]);
    let rig = std::fs::read_to_string(SPINEBOY).unwrap();
    let setup = s.post("/api/pose", &json!({"rig": rig})).json();
    let origin = |n: &str| {
        let b = setup["bones"].as_array().unwrap().iter().find(|b| b["name"] == n).unwrap();
        [b["x"].as_f64().unwrap(), b["y"].as_f64().unwrap()]
    };
    // The foot a third of the way up to the hip: the knee bends clearly either way.
    let (foot, hip) = (origin("front-leg-target"), origin("front-thigh"));
    let target = json!([{"bone": "front-leg-target", "x": foot[0] + (hip[0] - foot[0]) / 3.0, "y": foot[1] + (hip[1] - foot[1]) / 3.0}]);
    let pose = |bends: Value| s.post("/api/pose", &json!({"rig": rig, "targets": target, "bends": bends}));
    let plain = pose(json!({}));
    assert_eq!(plain.status, 200, "{}", plain.text());
    let side = knee(&plain.json());
    let same = if side > 0.0 { "ccw" } else { "cw" };
    let other = if side > 0.0 { "cw" } else { "ccw" };
    assert_eq!(knee(&pose(json!({"front-shin": same})).json()), side);
    assert_eq!(knee(&pose(json!({"front-shin": other})).json()), -side, "the knee flips");
    assert_eq!(
        pose(json!({"head": "cw"})).error(422),
        "bends.head: \"head\" is not the lower bone of a two-bone IK constraint (the character's are: front-shin, rear-shin)"
    );
    assert!(
        pose(json!({"front-shin": "left"})).error(422).contains("bends.front-shin"),
        "a side that is not ccw or cw"
    );
}
