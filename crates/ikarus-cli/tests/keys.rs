//! Keyframes per effector: `ikarus animate --rig FILE --keys KEYS.json` through the binary and
//! `POST /api/animate` with `keys` over real HTTP. The puppet's walk-like keys reach every key
//! at its time with limits on, the frames are at k/fps, the pins hold where the start pose has
//! them, a bend key flips the knee, the command line and the API answer the same bits, twice
//! the same bytes, and every bad field is refused naming it. The tests that check `reached`
//! need the real rig solver.

mod common;
#[path = "common/rigs.rs"]
mod rigs;

use common::{SPINEBOY, dist, fails, ikarus, json, point, same_bits, spineboy_keys, stdout, succeeds};
use rigs::{puppet, puppet_start_tip as start_tip};
use serde_json::{Value, json};

const WALK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/keys/puppet-walk.json");

fn walk() -> Value {
    serde_json::from_str(&std::fs::read_to_string(WALK).unwrap()).unwrap()
}

/// Writes `keys` to a file of the test's own and gives its path.
fn keys_file(name: &str, keys: &Value) -> String {
    common::temp_file("keys", &format!("{name}.json"), &keys.to_string())
}

#[test]
fn the_puppet_s_walk_reaches_every_key_at_its_time_with_limits_on() {
    let v = json(&["animate", "--rig", &puppet(), "--keys", WALK, "--limits", "--format", "json"]);
    assert_eq!((v["rig"].as_str(), v["fps"].as_f64(), v["duration"].as_f64()), (Some("puppet"), Some(30.0), Some(0.9)));
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 28);
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f["time"].as_f64().unwrap().to_bits(), (k as f64 / 30.0).to_bits(), "frame {k}");
        assert_eq!(f["status"], "reached", "frame {k}: {}", f["error"]);
    }
    let keys = walk();
    let rig = rigs::json("puppet");
    let names = rigs::names(&rig);
    for (bone, track) in keys["tracks"].as_object().unwrap() {
        assert_eq!(track.as_array().unwrap().len(), 4, "{bone}");
        for key in track.as_array().unwrap() {
            let k = (key["time"].as_f64().unwrap() * 30.0).round() as usize;
            let target = [key["x"].as_f64().unwrap(), key["y"].as_f64().unwrap()];
            let f = &frames[k];
            assert_eq!(point(&f["targets"][bone]).map(f64::to_bits), target.map(f64::to_bits), "{bone} at {k}");
            assert!(dist(point(&f["joints"][bone]), target) <= 1e-6, "{bone} at frame {k}: {}", f["joints"][bone]);
        }
    }
    // Limits on: every angle within its bone's range.
    for f in frames {
        for (i, bone) in rig["bones"].as_array().unwrap().iter().enumerate() {
            let [lo, hi] = [0, 1].map(|j| bone["limits_deg"][j].as_f64().unwrap());
            let a = f["angles_deg"][&names[i]].as_f64().unwrap();
            assert!(a >= lo - 1e-9 && a <= hi + 1e-9, "{}: {a} outside [{lo}, {hi}]", names[i]);
        }
    }
}

#[test]
fn pins_hold_where_the_start_pose_has_them_over_the_whole_motion() {
    // The left foot keyed while its knee (the left thigh's tip) is pinned: unpinned, the thigh
    // swings (its tip moves 0.06); pinned, the tip and the thigh's direction hold all along,
    // not merely where each frame's solve starts.
    let key = |t: f64, x: f64, y: f64| json!({"time": t, "x": x, "y": y});
    let mut keys = json!({"fps": 30, "tracks": {
        "left_foot": [key(0.0, 0.24, -0.9), key(0.3, 0.2, -0.85), key(0.6, 0.15, -0.82), key(0.9, 0.24, -0.9)],
        "right_hand": walk()["tracks"]["right_hand"].clone()},
        "pins": ["left_thigh", "right_foot"]});
    let run = |keys: &Value, name: &str| {
        let file = keys_file(name, keys);
        json(&["animate", "--rig", &puppet(), "--keys", &file, "--format", "json"])
    };
    let v = run(&keys, "pins");
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 28);
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f["status"], "reached", "frame {k}");
        for pin in ["left_thigh", "right_foot"] {
            assert!(dist(point(&f["joints"][pin]), start_tip(pin)) <= 1e-6, "{pin} at frame {k}");
        }
        let thigh = f["angles_deg"]["left_thigh"].as_f64().unwrap();
        assert!((thigh + 85.0).abs() < 1e-4, "frame {k}: the thigh turned to {thigh}");
        assert_eq!(f["targets"].as_object().unwrap().len(), 2, "the pins are not tracks");
    }
    keys["pins"] = json!([]);
    let free = run(&keys, "unpinned");
    let moved = free["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| dist(point(&f["joints"]["left_thigh"]), start_tip("left_thigh")));
    assert!(moved.fold(0.0, f64::max) > 0.01, "unpinned, the knee moves");
}

/// The frames of the puppet's left foot keyed from `from` to `to` over 1 s at 10 fps, its knee
/// keyed ccw at 0 and cw from 0.5 s (`name` names the keys file).
fn knee_flipped(name: &str, from: [f64; 2], to: [f64; 2]) -> Vec<Value> {
    let keys = json!({"fps": 10,
        "tracks": {"left_foot": [{"time": 0, "x": from[0], "y": from[1]}, {"time": 1.0, "x": to[0], "y": to[1]}]},
        "bends": {"left_shin": [{"time": 0, "bend": "ccw"}, {"time": 0.5, "bend": "cw"}]}});
    let file = keys_file(name, &keys);
    let v = json(&["animate", "--rig", &puppet(), "--keys", &file, "--format", "json"]);
    v["frames"].as_array().unwrap().clone()
}

#[test]
fn a_bend_key_flips_the_knee_and_the_foot_still_reaches() {
    let frames = knee_flipped("bend", [0.3, -0.75], [0.2, -0.8]);
    assert_eq!(frames.len(), 11);
    for (k, f) in frames.iter().enumerate() {
        let knee = f["angles_deg"]["left_shin"].as_f64().unwrap();
        if k < 5 {
            assert!(knee > 1.0, "frame {k}: ccw, the knee at {knee}");
        } else {
            assert!(knee <= 0.0, "frame {k}: cw, the knee at {knee}");
        }
        assert_eq!(f["status"], "reached", "frame {k}");
    }
}

/// A bend key on the wrong side mirrors the knee (θ → −θ, the thigh turned so that the ankle
/// stays), as Spine and Godot flip a bend: the next frame's knee is the mirrored angle, not a
/// straight leg the solver barely leaves.
#[test]
fn a_bend_flip_mirrors_the_knee_rather_than_straightening_it() {
    let frames = knee_flipped("flip", [0.3, -0.6], [0.25, -0.62]);
    let knee = |k: usize| frames[k]["angles_deg"]["left_shin"].as_f64().unwrap();
    let before = knee(4);
    assert!((35.0..60.0).contains(&before), "before the flip, the knee at {before}");
    for (k, frame) in frames.iter().enumerate().skip(5) {
        let after = frame["angles_deg"]["left_shin"].as_f64().unwrap();
        assert!(after < -20.0, "frame {k}: the flipped knee at {after}, not mirrored from {before}");
        assert!((after + before).abs() < 15.0, "frame {k}: the knee at {after}, the mirror of {before}");
        assert_eq!(frame["status"], "reached", "frame {k}");
    }
}

#[test]
fn a_track_with_directions_turns_the_bone_to_them() {
    // The foot's tip and its absolute direction keyed: level at 0, 20° up at 0.5 s, eased.
    let keys = json!({"fps": 10, "tracks": {"left_foot": [
        {"time": 0, "x": 0.24, "y": -0.86, "angle_deg": 0}, {"time": 0.5, "x": 0.3, "y": -0.8, "angle_deg": 20}]}});
    let file = keys_file("angle", &keys);
    let v = json(&["animate", "--rig", &puppet(), "--keys", &file, "--format", "json"]);
    let frames = v["frames"].as_array().unwrap();
    let direction = |f: &Value| {
        ["left_thigh", "left_shin", "left_foot"].iter().map(|b| f["angles_deg"][b].as_f64().unwrap()).sum::<f64>()
    };
    for (k, want) in [(0, 0.0), (5, 20.0)] {
        assert_eq!(frames[k]["status"], "reached", "frame {k}");
        assert!((direction(&frames[k]) - want).abs() < 1e-3, "frame {k}: {}", direction(&frames[k]));
    }
    // Between, the direction follows the sine ease from 0° to 20°.
    let mid = direction(&frames[2]);
    let eased = 20.0 * (1.0 - (std::f64::consts::PI * 0.4).cos()) / 2.0;
    assert!((mid - eased).abs() < 1e-3, "{mid} vs {eased}");
}

#[test]
fn the_command_line_and_the_api_answer_the_same_bits_and_twice_the_same_bytes() {
    let args = ["animate", "--rig", &puppet(), "--keys", WALK, "--limits", "--format", "json"];
    let (a, b) = (succeeds(&args), succeeds(&args));
    assert_eq!(a, b, "the command line twice");
    let s = common::server::start(&[]);
    let body = json!({"rig": rigs::json("puppet"), "keys": walk(), "options": {"limits": true}});
    let (x, y) = (s.post("/api/animate", &body), s.post("/api/animate", &body));
    assert_eq!(x.status, 200, "{}", x.text());
    assert_eq!(x.body, y.body, "the API twice");
    same_bits(&serde_json::from_str(&a).unwrap(), &x.json(), "answer");
}

#[test]
fn csv_has_a_row_per_frame_in_seconds_and_text_a_summary() {
    let csv = succeeds(&["animate", "--rig", &puppet(), "--keys", WALK, "--format", "csv"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 29);
    assert!(lines[0].starts_with("time,pelvis_deg,"), "{}", lines[0]);
    assert!(lines[0].ends_with("right_foot.x,right_foot.y"), "{}", lines[0]);
    assert!(lines[10].starts_with(&format!("{:?},", 9.0 / 30.0)), "{}", lines[10]);
    let text = succeeds(&["animate", "--rig", &puppet(), "--keys", WALK, "--format", "text"]);
    assert!(text.contains("motion    28 frames over 0.9 s at 30 fps"), "{text}");
    assert!(text.contains("solves    28 of 28 reached"), "{text}");
}

/// One key track `{"left_foot": keys}` with `extra` fields merged into the keys.
fn keyed(track: Value, extra: Value) -> Value {
    let mut keys = json!({"tracks": {"left_foot": track}});
    for (k, v) in extra.as_object().unwrap() {
        keys[k] = v.clone();
    }
    keys
}

fn two_keys() -> Value {
    json!([{"time": 0, "x": 0.24, "y": -0.9}, {"time": 0.5, "x": 0.3, "y": -0.85}])
}

#[test]
fn every_bad_field_is_refused_naming_it() {
    let s = common::server::start(&["--max-frames", "20"]);
    let refused = |keys: Value| {
        let a = s.post("/api/animate", &json!({"rig": rigs::json("puppet"), "keys": keys}));
        a.error(422)
    };
    let bones = "no bone named \"left_fot\" in the rig (its bones: pelvis, spine, neck, head, left_upper_arm, left_forearm, left_hand, right_upper_arm, right_forearm, right_hand, left_thigh, left_shin, left_foot, right_thigh, right_shin, right_foot)";
    let k = |time: f64| json!({"time": time, "x": 0.2, "y": -0.85});
    for (keys, message) in [
        (keyed(two_keys(), json!({"fps": 0})), "keys.fps = 0: must be greater than 0 and at most 240".to_owned()),
        (keyed(two_keys(), json!({"fps": 241})), "keys.fps = 241: must be greater than 0 and at most 240".into()),
        (
            json!({"tracks": {}}),
            "keys.tracks: at least one track, bone name → keys [{\"time\": 0, \"x\": …, \"y\": …}, …]".into(),
        ),
        (json!({"tracks": {"left_fot": two_keys()}}), format!("keys.tracks.left_fot: {bones}")),
        (keyed(json!([]), json!({})), "keys.tracks.left_foot: a track needs at least one key, at time 0".into()),
        (
            keyed(json!([k(0.1)]), json!({})),
            "keys.tracks.left_foot[0].time = 0.1: a track's first key is at time 0".into(),
        ),
        (
            keyed(json!([k(0.0), k(0.01)]), json!({})),
            "keys.tracks.left_foot[1].time = 0.01: not on a frame at 30 fps (nearest frame time 0)".into(),
        ),
        (
            keyed(json!([k(0.0), k(0.3), k(0.2)]), json!({})),
            "keys.tracks.left_foot[2].time = 0.2: must be after the previous key's time 0.3".into(),
        ),
        (
            keyed(json!([k(0.0), k(-1.0)]), json!({})),
            "keys.tracks.left_foot[1].time = -1: must be a finite number of seconds >= 0".into(),
        ),
        (keyed(json!([k(0.0), k(1.0)]), json!({})), "keys: 31 frames, more than the cap of 20 (--max-frames)".into()),
        (
            keyed(json!([{"time": 0, "x": 0.2, "y": -0.8, "ease": "sine", "k1": 0.2}]), json!({})),
            "keys.tracks.left_foot[0].k1: only applies with \"ease\": \"parent\"".into(),
        ),
        (
            keyed(json!([{"time": 0, "x": 0.2, "y": -0.8, "ease": "parent", "k1": 0.9, "k2": 0.2}]), json!({})),
            "keys.tracks.left_foot[0].k1: must not exceed k2, got k1 = 0.9, k2 = 0.2".into(),
        ),
        (
            keyed(json!([{"time": 0, "x": 0.2, "y": -0.8, "angle_deg": 0}, k(0.5)]), json!({})),
            "keys.tracks.left_foot[1].angle_deg: give it on every key of a track or on none (key 0 has one)".into(),
        ),
        (keyed(two_keys(), json!({"pins": ["left_fot"]})), format!("keys.pins[0]: {bones}")),
        (
            keyed(two_keys(), json!({"pins": ["left_foot"]})),
            "keys.pins[0] = left_foot: the bone is also keyed in keys.tracks; a pinned tip holds still".into(),
        ),
        (
            keyed(two_keys(), json!({"pins": ["right_foot", "right_foot"]})),
            "keys.pins[1] = right_foot: pinned twice".into(),
        ),
        (
            keyed(two_keys(), json!({"bends": {"pelvis": [{"time": 0, "bend": "cw"}]}})),
            "keys.bends.pelvis: the bone has no parent, so no joint to bend".into(),
        ),
        (
            keyed(two_keys(), json!({"bends": {"left_shin": [{"time": 0.05, "bend": "cw"}]}})),
            "keys.bends.left_shin[0].time = 0.05: a track's first key is at time 0".into(),
        ),
    ] {
        assert_eq!(refused(keys.clone()), message, "{keys}");
    }
    // The caps: tracks and pins together, keys per track.
    let many: serde_json::Map<String, Value> = (0..60).map(|i| (format!("b{i}"), two_keys())).collect();
    let pins: Vec<String> = (0..5).map(|i| format!("p{i}")).collect();
    assert_eq!(
        refused(json!({"tracks": many, "pins": pins})),
        "keys.tracks, keys.pins: 65 tracks and pins, more than the cap of 64"
    );
    let long: Vec<Value> = (0..1001).map(|k| json!({"time": k as f64 / 240.0, "x": 0.2, "y": -0.85})).collect();
    assert_eq!(
        refused(json!({"fps": 240, "tracks": {"left_foot": long}})),
        "keys.tracks.left_foot: 1001 keys, more than the cap of 1000"
    );
    // What serde reads names its field too.
    let wrong = refused(keyed(json!([{"time": 0, "x": "a", "y": 0}]), json!({})));
    assert!(wrong.starts_with("request body: keys.tracks.left_foot[0].x: invalid type: string \"a\""), "{wrong}");
    let wrong = refused(keyed(two_keys(), json!({"bends": {"left_shin": [{"time": 0, "bend": "up"}]}})));
    assert!(wrong.starts_with("request body: keys.bends.left_shin[0].bend: unknown variant `up`"), "{wrong}");
    // The fields keys replace, and an arm.
    let a = s.post(
        "/api/animate",
        &json!({"rig": rigs::json("puppet"), "keys": keyed(two_keys(), json!({})), "frames": 10}),
    );
    assert_eq!(
        a.error(422),
        "frames: not with keys (the keys give the targets, pins, bends and fps; the motion starts at the rig's start pose)"
    );
    // The built-in arm is keyed as its one-branch rig, bones link0, link1, link2.
    let a = s.post("/api/animate", &json!({"keys": keyed(two_keys(), json!({}))}));
    let e = a.error(422);
    assert!(e.starts_with("keys.tracks.left_foot: no bone named") && e.contains("link2"), "{e}");
    s.assert_healthy();
}

#[test]
fn the_command_line_refuses_what_keys_replace_and_bad_keys_files() {
    let file = keys_file("two", &keyed(two_keys(), json!({})));
    let err = fails(&["animate", "--rig", &puppet(), "--keys", &file, "--goal", "left_hand=0,0"], 2);
    assert!(err.contains("'--keys <KEYS.json>' cannot be used with '--goal"), "{err}");
    let err = fails(&["animate", "--rig", &puppet(), "--keys", &file, "--pin", "right_foot"], 2);
    assert!(err.contains("cannot be used with '--pin"), "{err}");
    let err = fails(&["animate", "--keys", &file], 2);
    assert!(
        err.starts_with(&format!("ikarus: --keys {file}: keys.tracks.left_foot: no bone named"))
            && err.contains("link2"),
        "{err}"
    );
    let bad = keys_file("bad", &keyed(two_keys(), json!({"fps": 0})));
    let err = fails(&["animate", "--rig", &puppet(), "--keys", &bad], 2);
    assert_eq!(err, format!("ikarus: --keys {bad}: keys.fps = 0: must be greater than 0 and at most 240\n"));
    let o = ikarus(&["animate", "--rig", &puppet(), "--keys", "/nonexistent/keys.json"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stdout(&o).is_empty());
}

/// The stdout of a command that succeeds (spineboy's constraints ikarus leaves inactive are
/// named on stderr).
fn stdout_of(args: &[&str]) -> String {
    let o = ikarus(args);
    assert!(o.status.success(), "{args:?}: {}", common::stderr(&o));
    stdout(&o)
}

#[test]
fn a_character_s_keys_over_a_clip_answer_the_same_through_the_command_line_and_the_api() {
    let file = keys_file("spineboy", &spineboy_keys());
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    let s = common::server::start(&[]);
    for format in ["json", "spine"] {
        let cli =
            stdout_of(&["animate", "--rig", SPINEBOY, "--keys", &file, "--animation", "walk", "--format", format]);
        let body = json!({"rig": text, "keys": spineboy_keys(), "animation": "walk", "format": format});
        let a = s.post("/api/animate", &body);
        assert_eq!(a.status, 200, "{}", a.text());
        same_bits(&serde_json::from_str(&cli).unwrap(), &a.json(), format);
        if format == "json" {
            let frames = a.json()["frames"].as_array().unwrap().len();
            assert_eq!(frames, 28);
        }
    }
    // Bend keys on the front knee (its constraint's bendPositive from each key's time on): the
    // same bits again, and the knee's frames differ from the unbent motion's.
    let mut bent = spineboy_keys();
    bent["bends"] = json!({"front-shin": [{"time": 0, "bend": "cw"}, {"time": 0.5, "bend": "ccw"}]});
    let bent_file = keys_file("spineboy-bent", &bent);
    let cli =
        stdout_of(&["animate", "--rig", SPINEBOY, "--keys", &bent_file, "--animation", "walk", "--format", "json"]);
    let a = s.post("/api/animate", &json!({"rig": text, "keys": bent, "animation": "walk"}));
    assert_eq!(a.status, 200, "{}", a.text());
    let cli: Value = serde_json::from_str(&cli).unwrap();
    same_bits(&cli, &a.json(), "bent");
    let plain: Value = serde_json::from_str(&stdout_of(&[
        "animate",
        "--rig",
        SPINEBOY,
        "--keys",
        &file,
        "--animation",
        "walk",
        "--format",
        "json",
    ]))
    .unwrap();
    let shin = |v: &Value, k: usize| {
        v["frames"][k]["bones"].as_array().unwrap().iter().find(|b| b["name"] == "front-shin").unwrap()["rotation_deg"]
            .as_f64()
            .unwrap()
    };
    assert_eq!(shin(&cli, 3), shin(&plain, 3), "before 0.5 s the file's own bend (cw: its bendPositive false)");
    assert!((shin(&cli, 20) - shin(&plain, 20)).abs() > 1.0, "from 0.5 s on the knee bends the other way");
    // Refusals: what a character does not take, an unknown clip, the eased course's fields.
    let refused = |extra: Value| {
        let mut body = json!({"rig": text, "keys": spineboy_keys()});
        for (k, v) in extra.as_object().unwrap() {
            body[k] = v.clone();
        }
        s.post("/api/animate", &body).error(422)
    };
    let mut pinned = spineboy_keys();
    pinned["pins"] = json!(["front-foot"]);
    assert_eq!(
        refused(json!({"keys": pinned})),
        "keys.pins: not for a character (pins hold a rig's tips; a character's target bones are keyed)"
    );
    let mut bent = spineboy_keys();
    bent["bends"] = json!({"front-thigh": [{"time": 0, "bend": "cw"}]});
    assert_eq!(
        refused(json!({"keys": bent})),
        "keys.bends.front-thigh: \"front-thigh\" is not the lower bone of a two-bone IK constraint (the character's are: front-shin, rear-shin)"
    );
    let e = refused(json!({"animation": "wlk"}));
    assert!(e.starts_with("animation \"wlk\": no such animation (the file has: ") && e.contains("walk"), "{e}");
    assert_eq!(
        refused(json!({"duration": 1.0})),
        "duration: not with keys (the keys give the targets, their eases and the fps)"
    );
    let unknown = refused(json!({"keys": {"tracks": {"toe": [{"time": 0, "x": 0, "y": 0}]}}}));
    assert_eq!(unknown, "keys.tracks.toe: no bone named \"toe\" in the character");
    let a = s.post(
        "/api/animate",
        &json!({"rig": text, "targets": [{"bone": "front-leg-target", "x": 0, "y": 0}], "animation": "walk"}),
    );
    assert_eq!(a.error(422), "animation: only with keys (the clip under the keyed targets)");
}
