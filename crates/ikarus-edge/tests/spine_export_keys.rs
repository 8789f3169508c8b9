//! The Spine export's size: an animator's keys export as about as many keys (not one per bone
//! per frame), the constraints stay on, every key time is the 32-bit float Spine reads, and a
//! character scaled a million times is fitted as closely relative to its size, within the
//! bound on added keys.

mod export_play;

use export_play::{moved, played, text, timelines};
use ikarus::character::Posed;
use ikarus::{Ease, EaseKind};
use ikarus_edge::character::export::{self, Export, Form};
use ikarus_edge::character::load;
use ikarus_edge::character::motion::{Course, Motion, keyed};
use ikarus_edge::keys::KeysFile;
use ikarus_edge::pose::{PoseAsk, pose_into};
use serde_json::{Value, json};

const SPINEBOY: &str = "spine-spineboy-pro.json";

/// The IK keys of `animation` for constraint `name`.
fn ik_keys<'a>(animation: &'a Value, name: &str) -> &'a Vec<Value> {
    animation["ik"][name].as_array().unwrap()
}

#[test]
fn eight_keys_on_spineboy_s_feet_export_as_few_keys_with_the_constraints_on() {
    // Three keys per foot target and a two-key bend, over the walk.
    let loaded = load(&text(SPINEBOY), SPINEBOY).unwrap();
    let at = |bone: &str, t: f64, by: [f64; 2]| {
        let p = moved(&loaded, bone, by).1;
        json!({"time": t, "x": p[0], "y": p[1], "ease": "sine"})
    };
    let keys = json!({"fps": 30,
        "tracks": {
            "front-leg-target": [at("front-leg-target", 0.0, [0.0, 0.0]), at("front-leg-target", 0.3, [40.0, 60.0]), at("front-leg-target", 0.6, [80.0, 20.0])],
            "rear-leg-target": [at("rear-leg-target", 0.0, [0.0, 0.0]), at("rear-leg-target", 0.3, [-30.0, 40.0]), at("rear-leg-target", 0.6, [-60.0, 10.0])]},
        "bends": {"front-shin": [{"time": 0, "bend": "cw"}, {"time": 0.4, "bend": "ccw"}]}});
    let keys: KeysFile = serde_json::from_value(keys).unwrap();
    let (course, fps) = keyed(&loaded, &keys, Some("walk".into()), 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    let editable = played(SPINEBOY, &motion, Form::Editable);
    let bake = played(SPINEBOY, &motion, Form::Bake);
    let written: Vec<_> = timelines(&editable.animation)
        .into_iter()
        .filter(|(bone, kind, _)| bone.ends_with("-leg-target") && kind == "translate")
        .collect();
    let targets: usize = written.iter().map(|(_, _, k)| k.len()).sum();
    // No two of a target's keys at the same 32-bit time: each a float step or more apart.
    for (bone, _, keys) in &written {
        for w in keys.windows(2) {
            let (a, b) = (w[0]["time"].as_f64().unwrap_or(0.0) as f32, w[1]["time"].as_f64().unwrap() as f32);
            assert!(a < b, "{bone}: keys at {a} and {b}");
        }
    }
    let walk: usize = timelines(&load_walk()).iter().map(|(_, _, k)| k.len()).sum();
    println!(
        "spineboy's 8 keys over walk: editable {} bone keys ({} the targets' translate keys, {} the walk's own), {} times, {} bytes (from {}), frames off by {:.2e}; bake {} keys at {} times, {} bytes, frames off by {:.2e}",
        editable.keys,
        targets,
        walk,
        editable.times,
        editable.bytes.0,
        editable.bytes.1,
        editable.frames,
        bake.keys,
        bake.times,
        bake.bytes.0,
        bake.frames
    );
    assert!(editable.frames < 1e-2 && editable.worst < 1e-2, "{} {}", editable.frames, editable.worst);
    assert!(bake.frames < 1e-2, "{}", bake.frames);
    // The targets' keys: the six keys, and under a parent the walk moves (the foot targets),
    // a key wherever the walk's curve of the parent bends (Spine plays a curve as ten straight
    // pieces) and the fit's few; never one per frame per bone. The rest is the walk carried as
    // it was keyed.
    assert!(targets <= 250, "{targets} target keys");
    assert!(editable.keys <= walk + targets, "{} keys", editable.keys);
    assert!(editable.keys * 10 < bake.keys, "{} editable, {} baked", editable.keys, bake.keys);
    // The constraints stay on: no key at mix 0; the bend is the knee's IK keys' bendPositive.
    let ik = &editable.animation["ik"];
    for (name, keys) in ik.as_object().unwrap() {
        for k in keys.as_array().unwrap() {
            assert_ne!(k.get("mix").and_then(Value::as_f64), Some(0.0), "{name}: {k}");
        }
    }
    let knee = ik_keys(&editable.animation, "front-leg-ik");
    let side = |t: f64| {
        knee.iter().rev().find(|k| k.get("time").and_then(Value::as_f64).unwrap_or(0.0) <= t).unwrap()["bendPositive"]
            .clone()
    };
    assert_eq!(side(0.2), json!(false));
    assert_eq!(side(0.5), json!(true));
    assert!(knee.iter().any(|k| k["time"] == json!(0.4)), "a key at the bend's time: {knee:?}");
    // The bake is the frame-by-frame form: every IK constraint at mix 0.
    assert!(ik_keys(&bake.animation, "front-leg-ik")[0]["mix"] == json!(0.0));
}

/// spineboy's walk as the file has it.
fn load_walk() -> Value {
    let v: Value = serde_json::from_str(&text(SPINEBOY)).unwrap();
    v["animations"]["walk"].clone()
}

#[test]
fn a_key_at_14_30_s_is_written_and_played_at_its_32_bit_time() {
    // A bend flipping at frame 14 of 30 fps: written as 0.46666667, the float Spine reads, and
    // at that frame time (as a float) the export is the flipped pose ikarus showed.
    let loaded = load(&text(SPINEBOY), SPINEBOY).unwrap();
    let (_, start) = moved(&loaded, "front-leg-target", [0.0, 0.0]);
    let (_, end) = moved(&loaded, "front-leg-target", [10.0, 60.0]);
    let keys = json!({"fps": 30,
        "tracks": {"front-leg-target": [{"time": 0, "x": start[0], "y": start[1]}, {"time": 0.8, "x": end[0], "y": end[1]}]},
        "bends": {"front-shin": [{"time": 0, "bend": "cw"}, {"time": 14.0 / 30.0, "bend": "ccw"}]}});
    let keys: KeysFile = serde_json::from_value(keys).unwrap();
    let (course, fps) = keyed(&loaded, &keys, None, 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    for form in [Form::Editable, Form::Bake] {
        let original = text(SPINEBOY);
        let out = export::spine(&motion, &original, &Export { name: "ikarus", form }).unwrap();
        if form == Form::Editable {
            assert!(out.contains("\"time\":0.46666667,"), "the bend key's time as the f32's shortest decimal");
            assert!(!out.contains("0.4666666666666667"));
        }
        let back = load(&out, "exported").unwrap();
        let (mut a, mut b) = (Posed::default(), Posed::default());
        for k in [13, 14, 15] {
            let t = k as f64 / 30.0;
            let ask =
                PoseAsk { animation: Some("ikarus".into()), time: Some(f64::from(t as f32)), ..PoseAsk::default() };
            pose_into(&back, &ask, &mut a).unwrap();
            motion.pose_at(t, &mut b).unwrap();
            let off = export_play::distance(&a, &b);
            assert!(off < 1e-2, "{form:?}: frame {k} off by {off}");
        }
    }
}

/// A Spine file of `limbs` two-bone limbs (upper, lower, and a target per limb, under the
/// root), every length and place scaled by `scale`.
fn limbs(limbs: usize, scale: f64) -> String {
    let mut bones = vec![json!({"name": "root"})];
    let mut ik = Vec::new();
    for k in 0..limbs {
        let x = k as f64 * 100.0 * scale;
        bones.push(
            json!({"name": format!("upper{k}"), "parent": "root", "x": x, "length": 50.0 * scale, "rotation": -90}),
        );
        bones.push(json!({"name": format!("lower{k}"), "parent": format!("upper{k}"), "x": 50.0 * scale, "length": 50.0 * scale}));
        bones.push(json!({"name": format!("target{k}"), "parent": "root", "x": x + 30.0 * scale, "y": -70.0 * scale}));
        ik.push(json!({"name": format!("ik{k}"), "bones": [format!("upper{k}"), format!("lower{k}")], "target": format!("target{k}")}));
    }
    json!({"skeleton": {"spine": "4.2.22"}, "bones": bones, "ik": ik, "animations": {}}).to_string()
}

#[test]
fn a_character_scaled_a_million_times_is_fitted_to_its_size_within_the_bound() {
    // 127 two-bone limbs scaled by 10⁶, every target moved over 4 s at 30 fps (121 frames):
    // an absolute 5e-3 tolerance refined every interval (257 keys between two frames, the
    // memory frames × 257 × bones); relative to the size (5e-6 of 1.27·10¹⁰ units) the keys
    // stay near the frames, and no export adds more keys than its bound.
    let scale = 1e6;
    let text = limbs(127, scale);
    let loaded = load(&text, "limbs").unwrap();
    let targets: Vec<(String, [f64; 2])> =
        (0..127).map(|k| (format!("target{k}"), [(k as f64 * 100.0 + 60.0) * scale, -40.0 * scale])).collect();
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 4.0 };
    let motion = Motion::new(&loaded, course, 30.0).unwrap();
    let frames = motion.frame_count();
    assert_eq!(frames, 121);
    let tolerance = export::tolerance(&motion).unwrap();
    assert!(tolerance > 1e4, "{tolerance}");
    for form in [Form::Bake, Form::Editable] {
        let out = export::spine(&motion, &text, &Export { name: "ikarus", form }).unwrap();
        let doc: Value = serde_json::from_str(&out).unwrap();
        let animation = &doc["animations"]["ikarus"];
        let all = timelines(animation);
        let keys: usize = all.iter().map(|(_, _, k)| k.len()).sum();
        let mut times: Vec<f64> =
            all.iter().flat_map(|(_, _, k)| k.iter().map(|k| k["time"].as_f64().unwrap_or(0.0))).collect();
        times.sort_by(f64::total_cmp);
        times.dedup();
        println!(
            "127 limbs × 10⁶, {form:?}: {} timelines, {keys} keys at {} times, {} bytes",
            all.len(),
            times.len(),
            out.len()
        );
        // At most the frames and a few added per frame; here hardly any.
        assert!(times.len() <= 2 * frames, "{form:?}: {} key times for {frames} frames", times.len());
        let back = load(&out, "exported").unwrap();
        let (mut a, mut b) = (Posed::default(), Posed::default());
        let mut worst: f64 = 0.0;
        for t in motion.frame_times() {
            let ask =
                PoseAsk { animation: Some("ikarus".into()), time: Some(f64::from(t as f32)), ..PoseAsk::default() };
            pose_into(&back, &ask, &mut a).unwrap();
            motion.pose_at(t, &mut b).unwrap();
            worst = worst.max(export_play::distance(&a, &b));
        }
        println!("  frames off by {worst:.3e} ({:.2e} of the size)", worst / (tolerance / 5e-6));
        assert!(worst < 2.0 * tolerance, "{form:?}: {worst}");
    }
    let _ = Ease::Linear;
}

#[test]
fn a_spine_3_8_file_gets_straight_keys_that_play_back() {
    // Spine 3.8's curve is one for all of a key's channels: the editable form writes straight
    // lines, split where they stray, and plays back within the promise.
    let text = limbs(3, 1.0).replace("4.2.22", "3.8.99");
    let loaded = load(&text, "limbs").unwrap();
    let targets = vec![("target1".to_owned(), [160.0, -30.0])];
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 1.0 };
    let motion = Motion::new(&loaded, course, 30.0).unwrap();
    let out = export::spine(&motion, &text, &Export { name: "ikarus", form: Form::Editable }).unwrap();
    let doc: Value = serde_json::from_str(&out).unwrap();
    let keys = doc["animations"]["ikarus"]["bones"]["target1"]["translate"].as_array().unwrap();
    assert!(keys.iter().all(|k| k.get("curve").is_none()), "{keys:?}");
    // Straight lines follow a 50-unit sine ease closely only about every 1/100 s: a key at
    // every frame and more between, within the bound of 4 added a frame (31 frames).
    println!("3.8: {} straight keys for 31 frames", keys.len());
    assert!(keys.len() > 2 && keys.len() <= 31 + 31 * 4, "{}", keys.len());
    let back = load(&out, "exported").unwrap();
    let (mut a, mut b) = (Posed::default(), Posed::default());
    for t in motion.frame_times() {
        let ask = PoseAsk { animation: Some("ikarus".into()), time: Some(f64::from(t as f32)), ..PoseAsk::default() };
        pose_into(&back, &ask, &mut a).unwrap();
        motion.pose_at(t, &mut b).unwrap();
        let off = export_play::distance(&a, &b);
        assert!(off < 1e-2, "at {t}: {off}");
    }
}

/// Bones turned by hand (rotation keys, in place of the clip's rotation) export as a `rotate`
/// timeline of their own, fitted between their keys in place of the clip's (the walk's head keys
/// are not carried for the head), and the export runs to the keys' Length (`duration`, past the
/// last key) and plays back within 1e-2 at every frame with the constraints on.
#[test]
fn bones_turned_by_hand_export_as_their_own_rotate_keys_to_the_keys_length() {
    let loaded = load(&text(SPINEBOY), SPINEBOY).unwrap();
    let p = moved(&loaded, "front-leg-target", [40.0, 30.0]).1;
    let keys = json!({"fps": 30, "duration": 1.0,
        "tracks": {"front-leg-target": [{"time": 0.0, "x": p[0] - 40.0, "y": p[1] - 30.0}, {"time": 0.4, "x": p[0], "y": p[1]}]},
        "rotations": {"head": [{"time": 0.0, "angle_deg": 80.0}, {"time": 0.3, "angle_deg": 120.0, "ease": "sine"}, {"time": 0.6, "angle_deg": 95.0}]}});
    let keys: KeysFile = serde_json::from_value(keys).unwrap();
    let (course, fps) = keyed(&loaded, &keys, Some("walk".into()), 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    assert_eq!(motion.duration, 1.0);
    let editable = played(SPINEBOY, &motion, Form::Editable);
    assert!(editable.frames <= 1e-2, "frames off by {}", editable.frames);
    let head: Vec<_> = timelines(&editable.animation)
        .into_iter()
        .filter(|(bone, kind, _)| bone == "head" && kind == "rotate")
        .flat_map(|(_, _, k)| k)
        .collect();
    let setup = loaded.character.bones()[loaded.character.bone_index("head").unwrap()].setup.rotation.to_degrees();
    // Its keys are the turn's (relative to the setup), not the walk's: the first is 80° at 0.
    let first = &head[0];
    assert!((first["value"].as_f64().unwrap() - (80.0 - setup)).abs() < 1e-9, "{first}");
    // Keys where the turn moves, none where it holds (after its last key at 0.6 s).
    let times: Vec<f64> = head.iter().map(|k| k["time"].as_f64().unwrap_or(0.0)).collect();
    println!("the head's turn: {} keys at {times:?}", head.len());
    assert!(times.iter().filter(|t| **t > 0.6 + 1e-6).count() <= 1, "keys where the turn holds: {times:?}");
    let last = head.last().unwrap();
    assert!((last["value"].as_f64().unwrap() - (95.0 - setup)).abs() < 1e-9, "{last}");
    // The last key of the export is at the Length, not at the last key.
    let end = timelines(&editable.animation)
        .iter()
        .flat_map(|(_, _, k)| k.iter().map(|k| k["time"].as_f64().unwrap_or(0.0)))
        .fold(0.0, f64::max);
    assert!((end - 1.0).abs() < 1e-6, "the export ends at {end}");
    let ik = editable.animation["ik"].as_object().into_iter().flatten();
    let off = ik.flat_map(|(_, keys)| keys.as_array().unwrap()).filter(|k| k["mix"] == json!(0.0)).count();
    assert_eq!(off, 0, "the constraints stay on");
}

/// Keys whose Length runs the walk more than twice export its timelines looped: where a timeline
/// jumps at the loop (its last key at the clip's end differs from its first), the last key of a
/// cycle stands one 32-bit step before the next cycle's first, never at the same time (the file
/// must read back), and the motion plays back within 1e-2 at every frame.
#[test]
fn a_length_past_the_clip_loops_it_in_the_export_and_reads_back() {
    let loaded = load(&text(SPINEBOY), SPINEBOY).unwrap();
    let walk = loaded.character.clips()[loaded.character.clip_index("walk").unwrap()].duration;
    let p = moved(&loaded, "front-leg-target", [40.0, 30.0]).1;
    let keys = json!({"fps": 30, "duration": 2.5,
        "tracks": {"front-leg-target": [{"time": 0.0, "x": p[0] - 40.0, "y": p[1] - 30.0}, {"time": 0.6, "x": p[0], "y": p[1]}]}});
    let keys: KeysFile = serde_json::from_value(keys).unwrap();
    let (course, fps) = keyed(&loaded, &keys, Some("walk".into()), 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    assert!(motion.duration > 2.0 * walk, "walk is {walk} s");
    let editable = played(SPINEBOY, &motion, Form::Editable);
    assert!(editable.frames <= 1e-2, "frames off by {}", editable.frames);
    for (bone, kind, keys) in timelines(&editable.animation) {
        for w in keys.windows(2) {
            let (a, b) = (w[0]["time"].as_f64().unwrap_or(0.0) as f32, w[1]["time"].as_f64().unwrap() as f32);
            assert!(a < b, "{bone}.{kind}: keys at {a} and {b}");
        }
    }
}
