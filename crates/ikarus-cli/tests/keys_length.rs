//! The keyed motion's length (`"duration"` in the keys): the frames, CSV and GIF run to it, not
//! to the last key. spineboy's front foot keyed to 0.9 s over `walk` with a duration of 2 s has
//! 2 × 30 + 1 frames, the last at 2 s, the foot holding its last key after 0.9 s while the clip
//! plays on; the command line and the API answer the same, the CSV and the GIF run to it; a
//! rig's keys run to it too; a duration before the last key, off a frame or not finite is
//! refused naming the field.

mod common;
#[path = "common/rigs.rs"]
mod rigs;

use common::{SPINEBOY, dist, point, same_bits, spineboy_keys, stdout};
use serde_json::{Value, json};

fn keys_file(name: &str, keys: &Value) -> String {
    common::temp_file("keys-length", &format!("{name}.json"), &keys.to_string())
}

fn with_duration(mut keys: Value, duration: Value) -> Value {
    keys["duration"] = duration;
    keys
}

/// The origin of bone `name` in a frame.
fn origin(frame: &Value, name: &str) -> [f64; 2] {
    let b = frame["bones"].as_array().unwrap().iter().find(|b| b["name"] == name).unwrap();
    [b["x"].as_f64().unwrap(), b["y"].as_f64().unwrap()]
}

#[test]
fn a_character_s_keys_run_to_their_duration_holding_the_last_key_while_the_clip_plays_on() {
    let keys = with_duration(spineboy_keys(), json!(2.0));
    let file = keys_file("spineboy-2s", &keys);
    let o = common::ikarus(&["animate", "--rig", SPINEBOY, "--keys", &file, "--animation", "walk", "--format", "json"]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let cli: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let frames = cli["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 61, "2 s × 30 fps + 1 (without a duration: 28, to the last key at 0.9 s)");
    assert_eq!(frames.last().unwrap()["time"].as_f64(), Some(2.0));
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f["time"].as_f64().unwrap(), k as f64 / 30.0, "frame {k}");
    }
    // After the last key the target holds it; the clip under it goes on (the head moves).
    let key = &spineboy_keys()["tracks"]["front-leg-target"][3];
    let last = [key["x"].as_f64().unwrap(), key["y"].as_f64().unwrap()];
    for f in &frames[27..] {
        assert!(dist(origin(f, "front-leg-target"), last) < 1e-9, "{}: {:?}", f["time"], origin(f, "front-leg-target"));
    }
    assert!(dist(origin(&frames[30], "head"), origin(&frames[50], "head")) > 1e-3, "the clip plays on after the keys");

    // The API answers the same; without the duration the motion stops at the last key.
    let s = common::server::start(&[]);
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    let a = s.post("/api/animate", &json!({"rig": text, "keys": keys, "animation": "walk", "format": "json"}));
    assert_eq!(a.status, 200, "{}", a.text());
    same_bits(&cli, &a.json(), "frames");
    let short = s.post("/api/animate", &json!({"rig": text, "keys": spineboy_keys(), "animation": "walk"}));
    assert_eq!(short.json()["frames"].as_array().unwrap().len(), 28);

    // The CSV runs to it too: a header and a row per bone per frame.
    let o = common::ikarus(&["animate", "--rig", SPINEBOY, "--keys", &file, "--animation", "walk", "--format", "csv"]);
    let csv = stdout(&o);
    let bones = frames[0]["bones"].as_array().unwrap().len();
    assert_eq!(csv.lines().count(), 1 + 61 * bones);
    assert!(csv.lines().last().unwrap().starts_with("60,2.0,"), "{:?}", csv.lines().last());
}

/// The number of frames of a GIF.
fn gif_frames(bytes: &[u8]) -> usize {
    let mut decoder = gif::DecodeOptions::new().read_info(bytes).unwrap();
    let mut n = 0;
    while decoder.next_frame_info().unwrap().is_some() {
        n += 1;
    }
    n
}

#[test]
fn a_character_s_keyed_gif_runs_to_the_duration() {
    let out = |name: &str, keys: &Value| {
        let file = keys_file(name, keys);
        let gif = common::temp_file("keys-length", &format!("{name}.gif"), "");
        let o = common::ikarus(&[
            "animate",
            "--rig",
            SPINEBOY,
            "--keys",
            &file,
            "--animation",
            "walk",
            "--width",
            "60",
            "--height",
            "60",
            "--out",
            &gif,
        ]);
        assert!(o.status.success(), "{}", common::stderr(&o));
        gif_frames(&std::fs::read(&gif).unwrap())
    };
    assert_eq!(out("gif-2s", &with_duration(spineboy_keys(), json!(2.0))), 61, "a frame per motion frame, to 2 s");
    assert_eq!(out("gif-keys", &spineboy_keys()), 28, "without a duration: to the last key, 0.9 s");
}

#[test]
fn a_rig_s_keys_run_to_their_duration_too() {
    let keys = json!({"fps": 10, "duration": 1.5,
        "tracks": {"left_foot": [{"time": 0, "x": 0.24, "y": -0.9}, {"time": 0.5, "x": 0.3, "y": -0.85}]}});
    let file = keys_file("puppet-1.5s", &keys);
    let v = common::json(&["animate", "--rig", &rigs::puppet(), "--keys", &file, "--no-limits", "--format", "json"]);
    assert_eq!(v["duration"].as_f64(), Some(1.5));
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 16);
    assert_eq!(frames.last().unwrap()["time"].as_f64(), Some(1.5));
    assert_eq!(point(&frames.last().unwrap()["targets"]["left_foot"]), [0.3, -0.85], "the track holds its last key");
}

#[test]
fn a_bad_duration_is_refused_naming_it() {
    let s = common::server::start(&["--max-frames", "100"]);
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    for (duration, message) in [
        (json!(0.5), "keys.duration = 0.5: before the last key's time 0.9; the motion runs at least to its last key"),
        (json!(1.01), "keys.duration = 1.01: not on a frame at 30 fps (nearest frame time 1)"),
        (json!(-1), "keys.duration = -1: must be a finite number of seconds >= 0"),
        (json!(1e300), "keys: 18446744073709551615 frames, more than the cap of 100 (--max-frames)"),
        (json!(4), "keys: 121 frames, more than the cap of 100 (--max-frames)"),
    ] {
        let keys = with_duration(spineboy_keys(), duration.clone());
        let a = s.post("/api/animate", &json!({"rig": text, "keys": keys}));
        assert_eq!(a.error(422), message, "{duration}");
    }
    let file = keys_file("spineboy-short", &with_duration(spineboy_keys(), json!(0.5)));
    let o = common::ikarus(&["animate", "--rig", SPINEBOY, "--keys", &file]);
    assert_eq!(o.status.code(), Some(2));
    let err = common::stderr(&o);
    assert!(err.contains("keys.duration = 0.5: before the last key's time 0.9"), "{err}");
}
