//! Bones turned by hand in a character's keys (`"rotations"`, forward kinematics): a rotation
//! key poses the bone's local rotation at the key's time exactly, in place of the clip's (the
//! walk turns spineboy's head; the keys hold it), eased between keys and held after the last
//! until the motion's `duration`; the bones below follow; bad rotation keys are refused naming
//! the field, and a rig's keys refuse them.

use ikarus::character::Posed;
use ikarus_edge::character::motion::{Motion, keyed};
use ikarus_edge::character::{Loaded, load};
use ikarus_edge::keys::KeysFile;
use ikarus_edge::pose::{PoseAsk, pose_into};
use serde_json::json;

const SPINEBOY: &str = "spine-spineboy-pro.json";

fn spineboy() -> Loaded {
    let text = std::fs::read_to_string(format!("{}/../../examples/characters/{SPINEBOY}", env!("CARGO_MANIFEST_DIR")))
        .unwrap();
    load(&text, SPINEBOY).unwrap()
}

fn keys(v: serde_json::Value) -> KeysFile {
    KeysFile::parse(&v.to_string()).unwrap()
}

/// spineboy's front foot target held where walk has it at 0, its head turned by hand.
fn turned(loaded: &Loaded) -> KeysFile {
    let mut setup = Posed::default();
    pose_into(loaded, &PoseAsk::default(), &mut setup).unwrap();
    let [x, y] = setup.origin(loaded.character.bone_index("front-leg-target").unwrap());
    keys(json!({"fps": 10, "duration": 0.8,
        "tracks": {"front-leg-target": [{"time": 0, "x": x, "y": y}]},
        "rotations": {"head": [{"time": 0, "angle_deg": 10}, {"time": 0.2, "angle_deg": 30, "ease": "linear"}, {"time": 0.5, "angle_deg": -20}]}}))
}

#[test]
fn a_rotation_key_poses_the_bones_local_rotation_at_its_time_exactly_in_place_of_the_clips() {
    let loaded = spineboy();
    let c = &loaded.character;
    let head = c.bone_index("head").unwrap();
    let (course, fps) = keyed(&loaded, &turned(&loaded), Some("walk".into()), 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    let times = motion.frame_times();
    assert_eq!(times.len(), 9, "to the duration, 0.8 s");
    let mut posed = Posed::default();
    let mut clip = Posed::default();
    for (k, &t) in times.iter().enumerate() {
        motion.pose_at(t, &mut posed).unwrap();
        let angle = posed.local(head).rotation.to_degrees();
        let want = match k {
            0 => Some(10.0),
            2 => Some(30.0),
            5.. => Some(-20.0),
            _ => None,
        };
        match want {
            // On a key (and after the last): the key, bit for bit.
            Some(w) => assert_eq!(posed.local(head).rotation, f64::to_radians(w), "frame {k}: {angle}°"),
            None => assert!(angle > -20.0 && angle < 30.0, "frame {k}: {angle}° between its keys"),
        }
        // The walk alone turns the head otherwise: the key replaces the clip's rotation.
        let ask = PoseAsk { animation: Some("walk".into()), time: Some(t), ..PoseAsk::default() };
        pose_into(&loaded, &ask, &mut clip).unwrap();
        if k == 2 {
            assert!((clip.local(head).rotation - posed.local(head).rotation).abs() > 1e-3, "the walk's own head turn");
        }
    }
    // Eased between keys like a target's track: between 30° and −20° at 0.3 s.
    motion.pose_at(0.3, &mut posed).unwrap();
    let between = posed.local(head).rotation.to_degrees();
    assert!(between < 30.0 && between > -20.0, "{between}");
    // The bones below the head follow it (its world rotation is its parent's plus the turn).
    let neck = c.bones()[head].parent.unwrap();
    motion.pose_at(0.5, &mut posed).unwrap();
    let turn = posed.rotation(head) - posed.rotation(neck);
    assert!((turn.sin() - f64::to_radians(-20.0).sin()).abs() < 1e-2, "{}", turn.to_degrees());
}

#[test]
fn bad_rotation_keys_are_refused_naming_the_field() {
    let loaded = spineboy();
    let base = |rotations: serde_json::Value| {
        keys(json!({"tracks": {"front-leg-target": [{"time": 0, "x": 0, "y": 0}]}, "rotations": rotations}))
    };
    let refused = |rotations: serde_json::Value| keyed(&loaded, &base(rotations), None, 1000, "cap").unwrap_err();
    assert_eq!(
        refused(json!({"hed": [{"time": 0, "angle_deg": 1}]})),
        "keys.rotations.hed: no bone named \"hed\" in the character"
    );
    assert_eq!(
        refused(json!({"head": [{"time": 0.1, "angle_deg": 1}]})),
        "keys.rotations.head[0].time = 0.1: a track's first key is at time 0"
    );
    assert_eq!(
        refused(json!({"head": [{"time": 0, "angle_deg": 1}, {"time": 0.25, "angle_deg": 2}]})),
        "keys.rotations.head[1].time = 0.25: not on a frame at 30 fps (nearest frame time 0.23333333333333334)"
    );
    assert_eq!(refused(json!({"head": []})), "keys.rotations.head: a track needs at least one key, at time 0");
}
