//! Bend keys on a character's two-bone IK constraints (`keys.bends`, named by the lower bone):
//! each key sets the constraint's `bendPositive` from its time on. Checked two ways on a Spine
//! character (spineboy, y up) and a DragonBones one (mecha, y down in its file): the side the
//! lower bone turns from the upper one, measured on the posed bones, is the key's (`ccw`
//! counter-clockwise); and every bone of a keyed frame is where the runtime's rules put it for
//! the file with that constraint's `bendPositive` written in, bit for bit.

use ikarus::character::Posed;
use ikarus_edge::character::motion::{Motion, keyed};
use ikarus_edge::character::{Loaded, load};
use ikarus_edge::keys::KeysFile;
use ikarus_edge::pose::{PoseAsk, pose_into};
use serde_json::{Value, json};

fn text(file: &str) -> String {
    std::fs::read_to_string(format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

fn bone(loaded: &Loaded, name: &str) -> usize {
    loaded.character.bone_index(name).unwrap()
}

/// The side the lower bone turns from the upper one: 1 counter-clockwise, −1 clockwise.
fn side(p: &Posed, upper: usize, lower: usize) -> f64 {
    (p.rotation(lower) - p.rotation(upper)).sin().signum()
}

/// A limb of a character: its file, the two-bone constraint's upper and lower bones and target.
struct Limb {
    file: &'static str,
    upper: &'static str,
    lower: &'static str,
    target: &'static str,
}

const SPINEBOY: Limb =
    Limb { file: "spine-spineboy-pro.json", upper: "front-thigh", lower: "front-shin", target: "front-leg-target" };
const MECHA: Limb =
    Limb { file: "dragonbones-mecha_1406_ske.json", upper: "thigh_1_l", lower: "calf_l", target: "foot_l" };

/// The bends keyed: ccw from 0, cw from 0.5 s, ccw again from 0.9 s, at 10 fps.
const BENDS: [(f64, &str); 3] = [(0.0, "ccw"), (0.5, "cw"), (0.9, "ccw")];

/// The target a quarter of the way from where the setup pose has it toward the hip, so that
/// the limb bends clearly either way.
fn bent_target(loaded: &Loaded, limb: &Limb) -> [f64; 2] {
    let mut setup = Posed::default();
    pose_into(loaded, &PoseAsk::default(), &mut setup).unwrap();
    let (t, hip) = (setup.origin(bone(loaded, limb.target)), setup.origin(bone(loaded, limb.upper)));
    [0, 1].map(|k| t[k] + 0.25 * (hip[k] - t[k]))
}

fn keys(limb: &Limb, target: [f64; 2]) -> KeysFile {
    let bends: Vec<Value> = BENDS.iter().map(|(t, b)| json!({"time": t, "bend": b})).collect();
    let keys = json!({"fps": 10, "tracks": {limb.target: [{"time": 0, "x": target[0], "y": target[1]}]},
        "bends": {limb.lower: bends}});
    KeysFile::parse(&keys.to_string()).unwrap()
}

/// The file of `limb` with its constraint's `bendPositive` set to `positive`.
fn with_bend(limb: &Limb, positive: bool) -> String {
    let mut v: Value = serde_json::from_str(&text(limb.file)).unwrap();
    let iks = if v["armature"].is_array() { &mut v["armature"][0]["ik"] } else { &mut v["ik"] };
    let found =
        iks.as_array_mut().unwrap().iter_mut().find(|k| {
            k["bones"].as_array().is_some_and(|b| b.iter().any(|b| b == limb.lower)) || k["bone"] == limb.lower
        });
    found.expect("the limb's constraint")["bendPositive"] = json!(positive);
    v.to_string()
}

fn check(limb: &Limb, ccw_is_positive: bool) {
    let loaded = load(&text(limb.file), limb.file).unwrap();
    let target = bent_target(&loaded, limb);
    let (course, fps) = keyed(&loaded, &keys(limb, target), None, 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    let times = motion.frame_times();
    assert_eq!(times.len(), 10, "{}: the last bend key (0.9 s) ends the motion", limb.file);
    let (upper, lower) = (bone(&loaded, limb.upper), bone(&loaded, limb.lower));
    let ask = PoseAsk { targets: vec![(limb.target.to_owned(), target)], ..PoseAsk::default() };
    let mut posed = Posed::default();
    let mut written = Posed::default();
    for (k, &t) in times.iter().enumerate() {
        let ccw = !(5..9).contains(&k);
        motion.pose_at(t, &mut posed).unwrap();
        let want = if ccw { 1.0 } else { -1.0 };
        assert_eq!(side(&posed, upper, lower), want, "{} frame {k}: the side", limb.file);
        // The runtime's pose of the file with that bendPositive written in.
        let file = load(&with_bend(limb, ccw == ccw_is_positive), limb.file).unwrap();
        pose_into(&file, &ask, &mut written).unwrap();
        for i in 0..posed.len() {
            assert_eq!(posed.origin(i), written.origin(i), "{} frame {k}, bone {i}", limb.file);
            assert_eq!(posed.tip(i), written.tip(i), "{} frame {k}, bone {i}", limb.file);
        }
    }
}

#[test]
fn a_spine_characters_bend_keys_flip_the_knee_as_its_bend_positive_does() {
    check(&SPINEBOY, true);
}

#[test]
fn a_dragonbones_characters_bend_keys_flip_the_knee_as_its_bend_positive_does() {
    check(&MECHA, false);
}

#[test]
fn a_bend_on_a_bone_that_is_not_a_two_bone_limbs_lower_bone_is_refused_naming_them() {
    let loaded = load(&text(SPINEBOY.file), SPINEBOY.file).unwrap();
    let keys = json!({"fps": 10, "tracks": {"front-leg-target": [{"time": 0, "x": 0, "y": 0}]},
        "bends": {"front-thigh": [{"time": 0, "bend": "cw"}]}});
    let e = keyed(&loaded, &KeysFile::parse(&keys.to_string()).unwrap(), None, 1000, "cap").unwrap_err();
    assert_eq!(
        e,
        "keys.bends.front-thigh: \"front-thigh\" is not the lower bone of a two-bone IK constraint (the character's are: front-shin, rear-shin)"
    );
    let keys = json!({"fps": 10, "tracks": {"front-leg-target": [{"time": 0, "x": 0, "y": 0}]},
        "bends": {"toe": [{"time": 0, "bend": "cw"}]}});
    let e = keyed(&loaded, &KeysFile::parse(&keys.to_string()).unwrap(), None, 1000, "cap").unwrap_err();
    assert!(e.to_string().starts_with("keys.bends.toe: no bone named \"toe\""), "{e}");
}
