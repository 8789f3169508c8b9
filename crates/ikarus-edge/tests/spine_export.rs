//! The Spine export, checked by playing it: the exported file is read back by our own loader
//! (whose posing matches Spine's runtime within 7.5e-5, `character_reference.rs`), its new
//! animation posed at every key and at hundreds of times between (most off the frame grid),
//! and every bone's world origin and tip compared with the motion posed directly at that time.

use ikarus::character::Posed;
use ikarus::{Ease, EaseKind};
use ikarus_edge::character::export::{self, TOLERANCE};
use ikarus_edge::character::motion::{Course, Motion};
use ikarus_edge::character::{Loaded, load};
use ikarus_edge::keys::KeysFile;
use ikarus_edge::pose::{IkChoice, PoseAsk, pose, pose_into};
use serde_json::Value;

fn text(file: &str) -> String {
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).unwrap()
}

/// The setup origin of `bone` moved by `by`.
fn moved(loaded: &Loaded, bone: &str, by: [f64; 2]) -> (String, [f64; 2]) {
    let setup = pose(loaded, &PoseAsk::default()).unwrap();
    let b = setup.bones.iter().find(|b| b.name == bone).unwrap();
    (bone.to_owned(), [b.x + by[0], b.y + by[1]])
}

/// The largest distance between any bone's origin or tip in `a` and in `b`.
fn distance(a: &Posed, b: &Posed) -> f64 {
    (0..a.len())
        .flat_map(|i| [(a.origin(i), b.origin(i)), (a.tip(i), b.tip(i))])
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

/// Exports `course` of `file`, plays it back, and returns the largest error found between the
/// keys and the error at the last key against `ikarus pose --target …` at the end points.
fn played(file: &str, course: Course, fps: f64, ik: &IkChoice) -> (f64, f64, usize) {
    let original = text(file);
    let loaded = load(&original, file).unwrap();
    let mut motion = Motion::new(&loaded, course, fps).unwrap();
    motion.ik = ik.clone();
    let exported = export::spine(&motion, &original, "ikarus").unwrap();

    // Valid JSON that keeps every original top-level field and animation as it was.
    let before: Value = serde_json::from_str(&original).unwrap();
    let after: Value = serde_json::from_str(&exported).unwrap();
    for (k, v) in before.as_object().unwrap() {
        if k != "animations" {
            assert_eq!(&after[k], v, "{file}: field {k} changed");
        }
    }
    for (name, a) in before["animations"].as_object().unwrap() {
        assert_eq!(&after["animations"][name], a, "{file}: animation {name} changed");
    }
    assert_eq!(after["animations"].as_object().unwrap().len(), before["animations"].as_object().unwrap().len() + 1);
    // A second export of the same name into the exported file is refused in one line.
    let back = load(&exported, "exported").unwrap();
    let again = Motion::new(&back, motion_course(&motion), fps).unwrap();
    let e = export::spine(&again, &exported, "ikarus").unwrap_err();
    assert_eq!(e, "animation name \"ikarus\": the file already has an animation of that name");

    // Played back: at every key and at 600 times between, most off the frame grid.
    // Every key time of every timeline.
    let mut keys: Vec<f64> = after["animations"]["ikarus"]["bones"]
        .as_object()
        .unwrap()
        .values()
        .flat_map(|timelines| timelines.as_object().unwrap().values())
        .flat_map(|keys| keys.as_array().unwrap().iter().map(|k| k["time"].as_f64().unwrap()))
        .collect();
    keys.sort_by(f64::total_cmp);
    keys.dedup();
    let d = motion.duration;
    let mut times = keys.clone();
    // Halfway between every two keys (where a line strays most), and 600 times spread over all.
    // Keys closer than 1 µs bracket a jump of the motion itself, which no keyed line can follow
    // between them: the bisection narrowed it to 1/(fps · 2¹⁶) s. Check that each run of such
    // keys is one (the motion's pose at its two ends differs by more than the tolerance).
    let (mut a, mut b) = (Posed::default(), Posed::default());
    let mut jumps = 0;
    let mut run: Option<f64> = None;
    for w in keys.windows(2) {
        if w[1] - w[0] < 1e-6 {
            run.get_or_insert(w[0]);
            continue;
        }
        if let Some(first) = run.take() {
            motion.pose_at(first, &mut a).unwrap();
            motion.pose_at(w[0], &mut b).unwrap();
            assert!(distance(&a, &b) > TOLERANCE, "{file}: keys close from {first} to {} but no jump", w[0]);
            jumps += 1;
        }
        times.push((w[0] + w[1]) / 2.0);
    }
    times.extend((0..600).map(|k| d * ((k as f64 * 0.618_033_988_75) % 1.0)));
    println!("{file}: {jumps} jump(s) of the motion bracketed by keys");
    let (mut exported_pose, mut direct) = (Posed::default(), Posed::default());
    let mut worst: f64 = 0.0;
    // Each time as a 32-bit float, as the file's key times are read and as Spine's runtime keeps
    // its time: at a jump of the motion on a frame (a bend key's flip), the file can put the
    // jump only between two such times, and an f64 time between them is mid-jump.
    for t in times.iter().map(|&t| f64::from(t as f32)) {
        let ask = PoseAsk { animation: Some("ikarus".into()), time: Some(t), ..PoseAsk::default() };
        pose_into(&back, &ask, &mut exported_pose).unwrap();
        motion.pose_at(t, &mut direct).unwrap();
        worst = worst.max(distance(&exported_pose, &direct));
    }
    // At the last key: `ikarus pose --target …` at the end points.
    let ask = PoseAsk { animation: Some("ikarus".into()), time: Some(d), ..PoseAsk::default() };
    pose_into(&back, &ask, &mut exported_pose).unwrap();
    // (`ikarus pose --animation A --time T --target …` for a keyed course over a clip.)
    let end = motion.ask_at(d);
    pose_into(&loaded, &end, &mut direct).unwrap();
    let last = distance(&exported_pose, &direct);
    motion.pose_at(d, &mut exported_pose).unwrap();
    assert_eq!(distance(&exported_pose, &direct), 0.0, "the motion ends where pose puts the targets");
    (worst, last, keys.len())
}

/// The same course (for the second export).
fn motion_course(m: &Motion<'_>) -> Course {
    Course::Eased { targets: m.targets_at(m.duration), ease: Ease::Linear, duration: m.duration }
}

fn check(file: &str, course: Course, fps: f64) {
    check_with(file, course, fps, &IkChoice::Runtime);
}

fn check_with(file: &str, course: Course, fps: f64, ik: &IkChoice) {
    let (worst, last, keys) = played(file, course, fps, ik);
    println!("{file}: {keys} keys, largest error between keys {worst:.3e}, at the last key {last:.3e}");
    assert!(worst < 1e-2, "{file}: {worst}");
    assert!(worst <= TOLERANCE * 1.01, "{file}: {worst} beyond the bisection's own tolerance");
    // Keys are 32-bit floats in the runtime (and in our reader): the last key is the end pose
    // within their rounding (a value near 250 is held to about 1.5e-5), not to 1e-6.
    assert!(last < 5e-5, "{file}: {last}");
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
    check_with(file, course, 30.0, &ik);
    // The README's tour: carried to (460, 80), beyond the leg constraint's reach, the limb passes
    // full reach near 0.84 s and swings there like the square root of the time left (3 units in
    // 1/3000 s), then jumps; the keys follow the swing by halving down to 1/(30 · 2¹²) s there.
    let targets = vec![("front-foot-target".to_owned(), [460.0, 80.0])];
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 1.0 };
    let (worst, last, keys) = played(file, course, 30.0, &ik);
    println!("the tour: {keys} keys, largest error between keys {worst:.3e}, at the last key {last:.3e}");
    assert!(worst <= TOLERANCE * 1.01, "the tour's motion strays {worst} between its keys");
    assert!(last <= 1e-2, "{last}");
    assert!(keys > 31, "keys were added near full reach: {keys}");
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
    // Played back within the export's promise, 1e-2. (Over the walk's own curves the largest
    // error, at one of the 600 times between keys, is 5.07e-3: 1.4 % over the bisection's
    // tolerance, which it checks halfway between keys, not everywhere.)
    let (worst, last, count) = played(file, course().0, 30.0, &IkChoice::Runtime);
    println!(
        "{file} keyed over walk: {count} keys, largest error between keys {worst:.3e}, at the last key {last:.3e}"
    );
    assert!(worst < 1e-2, "{file}: {worst}");
    assert!(last < 5e-5, "{file}: {last}");
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
    let e = export::spine(&motion, &original, "ikarus").unwrap_err();
    assert_eq!(e, "format spine: the Spine export takes a Spine file, and this is a DragonBones file");
}
