//! `POST /api/animate` and `POST /api/track` with a character file's text in `rig`: the
//! contract the page codes against (frames by default, the Spine document with `"format":
//! "spine"`), and the caps.

use ikarus::Interrupt;
use ikarus_edge::api::{Endpoint, Limits, call};
use serde_json::{Value, json};

fn spineboy() -> String {
    let path = format!("{}/../../examples/characters/spine-spineboy-pro.json", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).unwrap()
}

fn ask(endpoint: Endpoint, body: &Value) -> Result<Value, (u16, String)> {
    let bytes = serde_json::to_vec(body).unwrap();
    call(endpoint, &bytes, &Limits::default(), &Interrupt::new())
        .map(|r| {
            assert_eq!(r.content_type, "application/json");
            serde_json::from_slice(&r.body).unwrap()
        })
        .map_err(|p| (p.status, p.message))
}

#[test]
fn animate_answers_frames_or_the_spine_document() {
    let rig = spineboy();
    let mut body = json!({"rig": rig, "targets": [{"bone": "front-leg-target", "x": 10.0, "y": 20.0}],
        "duration": 1.0, "fps": 30, "ease": "sine"});
    let frames = ask(Endpoint::Animate, &body).unwrap();
    assert_eq!(frames["frames"].as_array().unwrap().len(), 31);
    assert_eq!(frames["frames"][30]["time"], 1.0);
    let target =
        frames["frames"][30]["bones"].as_array().unwrap().iter().find(|b| b["name"] == "front-leg-target").unwrap();
    assert!((target["x"].as_f64().unwrap() - 10.0).abs() < 1e-9 && (target["y"].as_f64().unwrap() - 20.0).abs() < 1e-9);
    assert_eq!(frames["unsupported"][0]["kind"], "bounding box attachment");

    body["format"] = json!("spine");
    body["animation_name"] = json!("reach");
    let doc = ask(Endpoint::Animate, &body).unwrap();
    let original: Value = serde_json::from_str(&rig).unwrap();
    assert_eq!(doc["skeleton"], original["skeleton"]);
    assert_eq!(doc["animations"]["walk"], original["animations"]["walk"]);
    // The editable form: the target keyed, the constraints left on (no IK keys at all here).
    assert!(doc["animations"]["reach"]["bones"]["front-leg-target"]["translate"].is_array());
    assert!(doc["animations"]["reach"]["ik"].is_null(), "{}", doc["animations"]["reach"]);
    // "bake": true, the frame-by-frame bake: every IK constraint at mix 0.
    body["bake"] = json!(true);
    let baked = ask(Endpoint::Animate, &body).unwrap();
    assert_eq!(baked["animations"]["reach"]["ik"]["front-leg-ik"][0]["mix"], 0.0);
    assert!(baked["animations"]["reach"]["bones"]["front-thigh"]["rotate"].as_array().unwrap().len() >= 31);
    let mut frames_body = body.clone();
    frames_body["format"] = json!("json");
    frames_body.as_object_mut().unwrap().remove("animation_name");
    let (status, message) = ask(Endpoint::Animate, &frames_body).unwrap_err();
    assert_eq!((status, message.as_str()), (422, "bake: only with format spine"));
    body.as_object_mut().unwrap().remove("bake");

    // The exported document again, with the same name: refused.
    body["rig"] = json!(serde_json::to_string(&doc).unwrap());
    let (status, message) = ask(Endpoint::Animate, &body).unwrap_err();
    assert_eq!(
        (status, message.as_str()),
        (422, "animation name \"reach\": the file already has an animation of that name")
    );
}

#[test]
fn track_follows_a_shape_with_a_bone() {
    let body = json!({"rig": spineboy(), "effector": "front-leg-target", "circle": [-40.0, 60.0, 30.0],
        "samples": 25, "format": "spine"});
    let doc = ask(Endpoint::Track, &body).unwrap();
    let keys = doc["animations"]["ikarus"]["bones"]["front-leg-target"]["translate"].as_array().unwrap();
    assert!(keys.len() >= 25, "{}", keys.len());
    // The last key at 24/30 s, written as the 32-bit float Spine reads (its shortest decimal).
    assert_eq!(keys.last().unwrap()["time"], 0.8);
    let frames = ask(
        Endpoint::Track,
        &json!({"rig": spineboy(), "effector": "front-leg-target", "line": [0, 0, 10, 10], "samples": 3}),
    )
    .unwrap();
    assert_eq!(frames["frames"].as_array().unwrap().len(), 3);
}

#[test]
fn bad_requests_are_one_line_naming_the_field() {
    let rig = spineboy();
    let refused = |endpoint, body: Value| match ask(endpoint, &body) {
        Err(e) => e,
        Ok(_) => panic!("accepted"),
    };
    let t = json!([{"bone": "front-leg-target", "x": 1.0, "y": 2.0}]);
    let cases = [
        (
            Endpoint::Animate,
            json!({"rig": rig, "targets": t, "fps": 1000, "duration": 10}),
            "duration, fps: 10001 frames",
        ),
        (Endpoint::Animate, json!({"rig": rig, "targets": t, "goals": []}), "unknown field `goals`"),
        (Endpoint::Animate, json!({"rig": rig, "targets": []}), "targets: give at least one"),
        (
            Endpoint::Animate,
            json!({"rig": rig, "targets": [{"bone": "toe", "x": 0, "y": 0}]}),
            "target \"toe\": no bone",
        ),
        (Endpoint::Animate, json!({"rig": rig, "targets": t, "fps": 0}), "fps: must be a positive number"),
        (
            Endpoint::Animate,
            json!({"rig": rig, "targets": t, "ease": "sine", "k1": 0.2}),
            "k1: only applies with ease parent",
        ),
        (
            Endpoint::Animate,
            json!({"rig": rig, "targets": t, "animation_name": "x"}),
            "animation_name: only with format spine",
        ),
        (
            Endpoint::Animate,
            json!({"rig": rig, "targets": t, "format": "spine", "animation_name": "walk"}),
            "animation name \"walk\": the file already has",
        ),
        (Endpoint::Track, json!({"rig": rig, "circle": [0, 0, 1]}), "effector: required with a character"),
        (Endpoint::Track, json!({"rig": rig, "effector": "hip"}), "path, line, circle, figure8: give exactly one"),
    ];
    for (endpoint, body, start) in cases {
        let (status, message) = refused(endpoint, body);
        assert_eq!(status, 422, "{message}");
        assert!(message.contains(start) && message.lines().count() == 1, "{message} (wanted {start})");
    }
}

#[test]
fn a_motions_physics_plays_unless_physics_is_false_on_animate_and_track() {
    let (rig, keys) = circus_keys();
    let hair = |frames: &Value, k: usize| {
        let bones = frames["frames"][k]["bones"].as_array().unwrap();
        let b = bones.iter().find(|b| b["name"] == "hair-back").unwrap();
        [b["tip"][0].as_f64().unwrap(), b["tip"][1].as_f64().unwrap()]
    };
    let swung =
        |a: &Value, b: &Value| (0..10).map(|k| hair(a, k)).zip((0..10).map(|k| hair(b, k))).any(|(p, q)| p != q);
    let mut body = json!({"rig": rig, "keys": keys, "animation": "swing"});
    let played = ask(Endpoint::Animate, &body).unwrap();
    body["physics"] = json!(true);
    assert_eq!(ask(Endpoint::Animate, &body).unwrap(), played);
    body["physics"] = json!(false);
    let off = ask(Endpoint::Animate, &body).unwrap();
    assert!(swung(&played, &off), "the hair swings the same with and without physics");

    let mut body = json!({"rig": rig, "effector": "face-control", "line": [30, -110, 40, -100], "samples": 10});
    let played = ask(Endpoint::Track, &body).unwrap();
    body["physics"] = json!(false);
    let off = ask(Endpoint::Track, &body).unwrap();
    assert!(swung(&played, &off), "the hair swings the same with and without physics on a track");
}

/// celestial-circus's text, and keys holding its face control for 0.3 s at 30 fps.
fn circus_keys() -> (String, Value) {
    let path = format!("{}/../../examples/characters/spine-celestial-circus-pro.json", env!("CARGO_MANIFEST_DIR"));
    let rig = std::fs::read_to_string(path).unwrap();
    (rig, json!({"fps": 30, "duration": 0.3, "tracks": {"face-control": [{"time": 0, "x": 30, "y": -110}]}}))
}

#[cfg(feature = "render")]
#[test]
fn a_characters_motion_picture_plays_its_physics_unless_physics_is_false() {
    let (rig, keys) = circus_keys();
    let render = |physics: Option<bool>| {
        let mut body = json!({"figure": "motion", "rig": rig, "keys": keys, "animation": "swing", "format": "svg"});
        if let Some(p) = physics {
            body["physics"] = json!(p);
        }
        call(Endpoint::Render, &serde_json::to_vec(&body).unwrap(), &Limits::default(), &Interrupt::new()).unwrap().body
    };
    assert_eq!(render(None), render(Some(true)));
    assert_ne!(render(None), render(Some(false)));
}
