//! The Spine export, checked by playing it back ([`export_play`]) in both forms: the editable
//! one (the default: the animator's keys with fitted curves, the constraints on) and the bake.

mod export_play;

use export_play::{distance, moved, played, text};
use ikarus::character::Posed;
use ikarus::{Ease, EaseKind};
use ikarus_edge::character::export::{self, Export, Form};
use ikarus_edge::character::load;
use ikarus_edge::character::motion::{Course, Motion};
use ikarus_edge::keys::KeysFile;
use ikarus_edge::pose::{IkChoice, PoseAsk, pose_into};
use serde_json::Value;

/// Both forms of `course` played back within the promise; the bake within its bisection's
/// tolerance. The editable form's playback error and key count, for the tests' own checks.
fn check_with(file: &str, course: Course, fps: f64, ik: &IkChoice) -> [export_play::Played; 2] {
    let loaded = load(&text(file), file).unwrap();
    let mut motion = Motion::new(&loaded, course, fps).unwrap();
    motion.ik = ik.clone();
    let editable = played(file, &motion, Form::Editable);
    let bake = played(file, &motion, Form::Bake);
    for (form, p) in [("editable", &editable), ("bake", &bake)] {
        println!(
            "{file} {form}: {} keys at {} times, {} bytes from {}, error at frames {:.3e}, between {:.3e}, at the last key {:.3e}",
            p.keys, p.times, p.bytes.0, p.bytes.1, p.frames, p.worst, p.last
        );
        assert!(p.frames < 1e-2, "{file} {form}: {} at a frame", p.frames);
        if form == "editable" && *ik == IkChoice::Runtime {
            assert!(p.worst < 1e-2, "{file} {form}: {}", p.worst);
        }
        // Keys are 32-bit floats in the runtime (and in our reader): the last key is the end
        // pose within their rounding (a value near 250 is held to about 1.5e-5).
        assert!(p.last < 5e-5, "{file} {form}: {}", p.last);
    }
    [editable, bake]
}

fn check(file: &str, course: Course, fps: f64) -> [export_play::Played; 2] {
    check_with(file, course, fps, &IkChoice::Runtime)
}

/// Whether any IK key of `animation` has mix 0.
fn mix_zero(animation: &Value) -> bool {
    animation["ik"]
        .as_object()
        .into_iter()
        .flatten()
        .flat_map(|(_, keys)| keys.as_array().unwrap())
        .any(|k| k["mix"] == 0.0)
}

#[test]
fn spineboy_legs_moved_and_played_back() {
    let file = "spine-spineboy-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let targets =
        vec![moved(&loaded, "front-leg-target", [60.0, 80.0]), moved(&loaded, "rear-leg-target", [-40.0, 50.0])];
    check(file, Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 1.0 }, 30.0);
}

#[test]
fn raptor_legs_moved_and_played_back() {
    let file = "spine-raptor-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let targets =
        vec![moved(&loaded, "front-leg-target", [80.0, 120.0]), moved(&loaded, "back-leg-target", [-60.0, 90.0])];
    check(file, Course::Eased { targets, ease: EaseKind::Smoothstep.ease(None, None).unwrap(), duration: 0.8 }, 24.0);
}

#[test]
fn a_motion_solved_by_ikarus_plays_back_too() {
    // The raptor's front leg as one four-bone limb (its leg constraint secondary): keyed
    // rotations of a solve the file's constraints do not make, played back by them at mix 0.
    let file = "spine-raptor-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let rules = ikarus_edge::character::ik_file::read(
        "[limbs.front-foot-ik]\nbones = 4\n[limbs.front-leg-ik]\nsecondary = true\n",
        "ik file",
        &loaded.character,
    )
    .unwrap();
    let ik = IkChoice::Ikarus(Box::new(rules));
    let targets = vec![moved(&loaded, "front-foot-target", [420.0, 90.0])];
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 0.5 };
    let [editable, bake] = check_with(file, course, 30.0, &ik);
    // ikarus's solve keyed at the course's two key times (and where a fit strays), the
    // constraints it replaces at mix 0; the bake keys every frame.
    assert!(mix_zero(&editable.animation) && mix_zero(&bake.animation));
    assert!(editable.keys * 3 < bake.keys, "{} editable keys, {} baked", editable.keys, bake.keys);
    // The book's Spine tour (docs/src/guide/characters.md): carried to (460, 80), beyond the leg constraint's reach, the limb passes
    // full reach near 0.84 s and swings there like the square root of the time left (3 units in
    // 1/3000 s), then jumps; the bake follows the swing by halving down to 1/(30 · 2¹²) s there.
    let targets = vec![("front-foot-target".to_owned(), [460.0, 80.0])];
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 1.0 };
    let mut motion = Motion::new(&loaded, course, 30.0).unwrap();
    motion.ik = ik;
    for form in [Form::Editable, Form::Bake] {
        let p = played(file, &motion, form);
        println!(
            "the tour {form:?}: {} keys at {} times, error at frames {:.3e}, between keys {:.3e}, at the last key {:.3e}",
            p.keys, p.times, p.frames, p.worst, p.last
        );
        assert!(p.frames < 1e-2, "{form:?}: the tour's frames stray {}", p.frames);
        assert!(p.last <= 1e-2, "{}", p.last);
        if form == Form::Bake {
            assert!(p.times > 31, "keys were added near full reach: {}", p.times);
        }
    }
}

#[test]
fn a_keyed_foot_target_over_the_walk_played_back() {
    // spineboy's front foot target keyed over `walk`, four keys: at each key time the posed
    // target bone's origin is on the key; the exported animation plays the motion back.
    let file = "spine-spineboy-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let keys: Vec<(f64, [f64; 2])> = [(0.0, [0.0, 0.0]), (0.3, [40.0, 60.0]), (0.6, [80.0, 20.0]), (0.9, [20.0, 0.0])]
        .into_iter()
        .map(|(t, by)| (t, moved(&loaded, "front-leg-target", by).1))
        .collect();
    let track: Vec<Value> = keys
        .iter()
        .enumerate()
        .map(|(i, (t, [x, y]))| {
            let ease = ["sine", "linear", "smoothstep", "sine"][i];
            serde_json::json!({"time": t, "x": x, "y": y, "ease": ease})
        })
        .collect();
    let keys_json = serde_json::json!({"fps": 30, "tracks": {"front-leg-target": track}});
    let file_keys: KeysFile = serde_json::from_value(keys_json).unwrap();
    let course =
        || ikarus_edge::character::motion::keyed(&loaded, &file_keys, Some("walk".into()), 1000, "cap").unwrap();
    let (c, fps) = course();
    assert_eq!(fps, 30.0);
    let motion = Motion::new(&loaded, c, fps).unwrap();
    assert_eq!(motion.frame_count(), 28);
    let bone = loaded.character.bone_index("front-leg-target").unwrap();
    let mut posed = Posed::default();
    for (t, key) in &keys {
        motion.pose_at(*t, &mut posed).unwrap();
        let o = posed.origin(bone);
        assert!((o[0] - key[0]).hypot(o[1] - key[1]) < 1e-9, "at {t}: {o:?} vs {key:?}");
        assert_eq!(motion.targets_at(*t)[0].1.map(f64::to_bits), key.map(f64::to_bits), "at {t}");
    }
    // Over the clip: at a key the pose is `pose --animation walk --time t --target …`'s.
    let ask = PoseAsk {
        animation: Some("walk".into()),
        time: Some(0.6),
        targets: vec![("front-leg-target".into(), keys[2].1)],
        ..PoseAsk::default()
    };
    let mut direct = Posed::default();
    pose_into(&loaded, &ask, &mut direct).unwrap();
    motion.pose_at(0.6, &mut posed).unwrap();
    assert_eq!(distance(&posed, &direct), 0.0);
    // Played back within the export's promise, 1e-2, in both forms. (The bake, over the
    // walk's own curves: its largest error, at one of the 600 times between keys, is 5.07e-3,
    // 1.4 % over the bisection's tolerance, which it checks halfway between keys.)
    for form in [Form::Editable, Form::Bake] {
        let p = played(file, &motion, form);
        println!(
            "{file} keyed over walk, {form:?}: {} keys at {} times, {} bytes from {}, error at frames {:.3e}, between {:.3e}, at the last key {:.3e}",
            p.keys, p.times, p.bytes.0, p.bytes.1, p.frames, p.worst, p.last
        );
        assert!(p.frames < 1e-2, "{file} {form:?}: {} at a frame", p.frames);
        if form == Form::Editable {
            assert!(p.worst < 1e-2, "{file} {form:?}: {} between frames", p.worst);
        }
        assert!(p.last < 5e-5, "{file}: {}", p.last);
    }
}

#[test]
fn a_knee_bent_the_other_way_by_a_key_played_back() {
    // spineboy's front knee keyed to bend ccw from 0.4 s (its file says cw), the foot target
    // raised on two keys: the flip is a jump of the motion, bracketed by keys, and the rest
    // plays back as any keyed course does.
    let file = "spine-spineboy-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let (_, start) = moved(&loaded, "front-leg-target", [0.0, 0.0]);
    let (_, end) = moved(&loaded, "front-leg-target", [10.0, 60.0]);
    let keys = serde_json::json!({"fps": 30,
        "tracks": {"front-leg-target": [{"time": 0, "x": start[0], "y": start[1]}, {"time": 0.8, "x": end[0], "y": end[1]}]},
        "bends": {"front-shin": [{"time": 0, "bend": "cw"}, {"time": 0.4, "bend": "ccw"}]}});
    let keys: KeysFile = serde_json::from_value(keys).unwrap();
    let (course, fps) = ikarus_edge::character::motion::keyed(&loaded, &keys, None, 1000, "cap").unwrap();
    check(file, course, fps);
}

#[test]
fn a_traced_circle_played_back() {
    let file = "spine-spineboy-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let (_, [cx, cy]) = moved(&loaded, "front-leg-target", [0.0, 40.0]);
    let points: Vec<[f64; 2]> = (0..=40)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 40.0;
            [cx + 40.0 * a.cos(), cy + 40.0 * a.sin()]
        })
        .collect();
    check(file, Course::Path { bone: "front-leg-target".into(), points }, 30.0);
}

#[test]
fn a_dragonbones_file_is_not_exported() {
    let file = "dragonbones-mecha_1406_ske.json";
    let original = text(file);
    let loaded = load(&original, file).unwrap();
    let bone = loaded.character.bones()[1].name.clone();
    let motion = Motion::new(
        &loaded,
        Course::Eased { targets: vec![(bone, [1.0, 2.0])], ease: Ease::Linear, duration: 1.0 },
        30.0,
    )
    .unwrap();
    let e = export::spine(&motion, &original, &Export { name: "ikarus", form: Form::Editable }).unwrap_err();
    assert_eq!(e, "format spine: the Spine export takes a Spine file, and this is a DragonBones file");
}
