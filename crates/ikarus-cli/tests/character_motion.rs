//! `ikarus animate --rig FILE.json` and `ikarus track --rig FILE.json` (issue 26): a character's
//! motion as frames or as the file with a Spine animation added, and the refusals (one line
//! naming the flag). The export's accuracy is checked in `ikarus-edge/tests/spine_export.rs`.

mod common;

use common::{fails, ikarus, json, stderr};
use serde_json::Value;

const RAPTOR: &str = "../../examples/characters/spine-raptor-pro.json";
const MECHA: &str = "../../examples/characters/dragonbones-mecha_1406_ske.json";
const PUPPET: &str = "../../examples/rigs/puppet.toml";

fn bone<'a>(frame: &'a Value, name: &str) -> &'a Value {
    frame["bones"].as_array().unwrap().iter().find(|b| b["name"] == name).unwrap()
}

#[test]
fn animate_moves_a_target_over_the_frames() {
    let setup = json(&["pose", "--rig", RAPTOR, "--format", "json"]);
    let got = json(&["animate", "--rig", RAPTOR, "--target", "front-leg-target=250,60", "--format", "json"]);
    let frames = got["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 31, "1 s at 30 fps by default");
    assert_eq!(frames[30]["time"], 1.0);
    let start = bone(&frames[0], "front-leg-target");
    let was = bone(&setup, "front-leg-target");
    assert!((start["x"].as_f64().unwrap() - was["x"].as_f64().unwrap()).abs() < 1e-9);
    // The end is what `ikarus pose --target …` gives.
    let end = json(&["pose", "--rig", RAPTOR, "--target", "front-leg-target=250,60", "--format", "json"]);
    for (a, b) in frames[30]["bones"].as_array().unwrap().iter().zip(end["bones"].as_array().unwrap()) {
        assert_eq!(a["name"], b["name"]);
        for k in ["x", "y"] {
            assert!((a[k].as_f64().unwrap() - b[k].as_f64().unwrap()).abs() < 1e-9, "{a} {b}");
        }
    }
    let half = json(&[
        "animate",
        "--rig",
        RAPTOR,
        "--target",
        "front-leg-target=250,60",
        "--duration",
        "0.5",
        "--fps",
        "10",
        "--format",
        "json",
    ]);
    assert_eq!(half["frames"].as_array().unwrap().len(), 6);
}

#[test]
fn the_spine_export_is_written_whole_and_refused_twice() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("raptor-reach.json");
    let out = out.to_str().unwrap();
    let o = ikarus(&[
        "animate",
        "--rig",
        RAPTOR,
        "--target",
        "front-leg-target=250,60",
        "--format",
        "spine",
        "--animation-name",
        "reach",
        "--out",
        out,
    ]);
    assert!(o.status.success() && o.stdout.is_empty(), "{}", stderr(&o));
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
    let original: Value = serde_json::from_str(&std::fs::read_to_string(RAPTOR).unwrap()).unwrap();
    for (k, v) in original.as_object().unwrap() {
        if k != "animations" {
            assert_eq!(&doc[k], v);
        }
    }
    assert_eq!(doc["animations"]["walk"], original["animations"]["walk"]);
    // The editable form: the target keyed at the motion's two key times and where a fit
    // strays (Spine plays a curve as ten straight pieces, so a sine ease over 390 units
    // carried by the leg near its full reach needs a key every frame or so: at most two a
    // frame), the leg left to its constraint, which stays on (no mix 0 key).
    let reach = &doc["animations"]["reach"];
    let keys = reach["bones"]["front-leg-target"]["translate"].as_array().unwrap();
    println!("the raptor's eased reach: {} target keys", keys.len());
    assert!((2..=62).contains(&keys.len()), "{} keys", keys.len());
    assert!(reach["bones"]["front-leg1"].is_null() && reach["ik"].is_null(), "{reach}");
    // --bake: every bone the constraints moved keyed frame by frame, the constraints at mix 0.
    let baked =
        json(&["animate", "--rig", RAPTOR, "--target", "front-leg-target=250,60", "--format", "spine", "--bake"]);
    let baked = &baked["animations"]["ikarus"];
    assert!(baked["bones"]["front-leg1"]["rotate"].as_array().unwrap().len() >= 31, "{baked}");
    assert_eq!(baked["ik"]["front-leg-ik"][0]["mix"], 0.0);
    let e = fails(&["animate", "--rig", RAPTOR, "--target", "front-leg-target=250,60", "--bake"], 2);
    assert!(e.contains("--bake: only with --format spine"), "{e}");
    let again = dir.path().join("again.json");
    let e = fails(
        &[
            "animate",
            "--rig",
            out,
            "--target",
            "front-leg-target=0,0",
            "--format",
            "spine",
            "--animation-name",
            "reach",
            "--out",
            again.to_str().unwrap(),
        ],
        2,
    );
    assert!(e.ends_with("animation name \"reach\": the file already has an animation of that name\n"), "{e}");
    assert!(!again.exists(), "nothing written");
}

#[test]
fn track_moves_a_bone_along_a_path() {
    let got = json(&[
        "track",
        "--rig",
        RAPTOR,
        "--effector",
        "front-leg-target",
        "--line",
        "100,50,250,60",
        "--samples",
        "11",
        "--format",
        "json",
    ]);
    let frames = got["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 11);
    let last = bone(&frames[10], "front-leg-target");
    assert!((last["x"].as_f64().unwrap() - 250.0).abs() < 1e-9 && (last["y"].as_f64().unwrap() - 60.0).abs() < 1e-9);
    assert!((frames[10]["time"].as_f64().unwrap() - 10.0 / 30.0).abs() < 1e-12);
    let spine = json(&[
        "track",
        "--rig",
        RAPTOR,
        "--effector",
        "front-leg-target",
        "--circle",
        "150,60,40",
        "--samples",
        "9",
        "--fps",
        "8",
        "--format",
        "spine",
    ]);
    let keys = spine["animations"]["ikarus"]["bones"]["front-leg-target"]["translate"].as_array().unwrap();
    assert_eq!(keys.last().unwrap()["time"], 1.0);
}

#[test]
fn flags_that_do_not_apply_are_refused_naming_the_flag() {
    let t = "front-leg-target=250,60";
    for (args, flag) in [
        (vec!["animate", "--rig", RAPTOR, "--target", t, "--goal", "hip=1,2"], "--goal"),
        (vec!["animate", "--rig", RAPTOR, "--target", t, "--method", "ccd"], "--method"),
        (vec!["animate", "--rig", RAPTOR, "--target", t, "--pin", "hip"], "--pin"),
        (vec!["animate", "--rig", RAPTOR, "--target", t, "--frames", "5"], "--frames"),
        (vec!["track", "--rig", RAPTOR, "--effector", "hip", "--line", "0,0,1,1", "--mode", "follow"], "--mode"),
    ] {
        let e = fails(&args, 2);
        assert!(e.starts_with(&format!("ikarus: {flag}: not with a character file")), "{e}");
    }
    let e = fails(&["animate", "--rig", RAPTOR, "--target", t, "--format", "text"], 2);
    assert!(e.contains("--format text: a character's motion is written as json"), "{e}");
    let e = fails(&["animate", "--rig", RAPTOR, "--target", t, "--animation-name", "x"], 2);
    assert!(e.contains("--animation-name: only with --format spine"), "{e}");
    let e = fails(&["animate", "--rig", RAPTOR], 2);
    assert!(e.contains("--target: give at least one"), "{e}");
    let e = fails(&["animate", "--rig", RAPTOR, "--target", "toe=1,2"], 2);
    assert!(e.ends_with("target \"toe\": no bone of that name\n"), "{e}");
    let e = fails(&["track", "--rig", RAPTOR, "--line", "0,0,1,1"], 2);
    assert!(e.contains("--effector: required with a character file"), "{e}");
    // A rig file takes none of the character's flags.
    let e = fails(&["animate", "--rig", PUPPET, "--goal", "head=1,2", "--target", "head=1,2"], 2);
    assert!(e.contains("--target: only with a character file"), "{e}");
    let e = fails(&["track", "--line", "0,0,1,1", "--format", "spine"], 2);
    assert!(e.contains("--format spine: only with a character file"), "{e}");
    // A DragonBones file is posed but not exported as Spine.
    let o = ikarus(&["animate", "--rig", MECHA, "--target", "root=1,2", "--format", "spine"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).trim_end().ends_with("the Spine export takes a Spine file, and this is a DragonBones file"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_characters_motion_plays_its_physics_unless_physics_is_off() {
    const CIRCUS: &str = "../../examples/characters/spine-celestial-circus-pro.json";
    let args = ["--rig", CIRCUS, "--target", "face-control=30,-110", "--duration", "0.2", "--format", "json"];
    let animate = |physics: &[&str]| json(&[&["animate"][..], &args, physics].concat());
    let (played, on, off) = (animate(&[]), animate(&["--physics", "on"]), animate(&["--physics", "off"]));
    assert_eq!(played, on);
    let hair = |v: &Value, k: usize| bone(&v["frames"][k], "hair-back")["tip"].clone();
    assert!((0..7).any(|k| hair(&played, k) != hair(&off, k)), "the hair swings the same with physics off");
    // Frame 0 restarts the physics: nothing has swung yet.
    assert_eq!(hair(&played, 0), hair(&off, 0));
    let track = |physics: &[&str]| {
        let shape = ["track", "--rig", CIRCUS, "--effector", "face-control", "--line", "30,-110,40,-100"];
        json(&[&shape[..], &["--samples", "8", "--format", "json"], physics].concat())
    };
    let (played, off) = (track(&[]), track(&["--physics", "off"]));
    assert!((0..8).any(|k| hair(&played, k) != hair(&off, k)), "the hair swings the same on a track");
    let e = fails(&["animate", "--rig", PUPPET, "--goal", "head=1,2", "--physics", "off"], 2);
    assert!(e.contains("--physics: only with a character file"), "{e}");
}
