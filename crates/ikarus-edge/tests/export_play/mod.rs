//! Playing a Spine export back: the exported file read by our own loader (whose posing matches
//! Spine's runtime within 7.5e-5, `character_reference.rs`), its new animation posed at every
//! frame time, every key and hundreds of times between, each as the 32-bit float Spine's
//! runtime keeps a time in, and every bone's world origin and tip compared with the motion.

#![allow(dead_code)]

use ikarus::Ease;
use ikarus::character::Posed;
use ikarus_edge::character::export::{self, Export, Form};
use ikarus_edge::character::motion::{Course, Motion};
use ikarus_edge::character::{Loaded, load};
use ikarus_edge::pose::{PhysicsAsk, PoseAsk, pose, pose_into};
use serde_json::Value;

pub fn text(file: &str) -> String {
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).unwrap()
}

/// The setup origin of `bone` moved by `by`.
pub fn moved(loaded: &Loaded, bone: &str, by: [f64; 2]) -> (String, [f64; 2]) {
    let setup = pose(loaded, &PoseAsk::default()).unwrap();
    let b = setup.bones.iter().find(|b| b.name == bone).unwrap();
    (bone.to_owned(), [b.x + by[0], b.y + by[1]])
}

/// The largest distance between any bone's origin or tip in `a` and in `b`.
pub fn distance(a: &Posed, b: &Posed) -> f64 {
    (0..a.len())
        .flat_map(|i| [(a.origin(i), b.origin(i)), (a.tip(i), b.tip(i))])
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

/// What a playback found.
#[derive(Debug)]
pub struct Played {
    /// The largest error at a frame time (export at the f32 time, the motion at the frame's).
    pub frames: f64,
    /// The largest error at any time checked (both at the f32 time).
    pub worst: f64,
    /// The error at the last key against `pose --target …` at the end points.
    pub last: f64,
    /// Bone keys in the new animation.
    pub keys: usize,
    /// Distinct key times of its bone timelines.
    pub times: usize,
    /// The exported text's length and the original's.
    pub bytes: (usize, usize),
    /// The new animation.
    pub animation: Value,
}

/// Every key of every bone timeline of `animation`: (bone, timeline, keys).
pub fn timelines(animation: &Value) -> Vec<(String, String, Vec<Value>)> {
    let mut out = Vec::new();
    for (bone, t) in animation["bones"].as_object().unwrap() {
        for (kind, keys) in t.as_object().unwrap() {
            out.push((bone.clone(), kind.clone(), keys.as_array().unwrap().clone()));
        }
    }
    out
}

/// Exports `motion` of `file` in `form`, checks the file keeps what it had, plays it back.
pub fn played(file: &str, motion: &Motion<'_>, form: Form) -> Played {
    let original = text(file);
    let loaded = motion.loaded;
    let exported = export::spine(motion, &original, &Export { name: "ikarus", form }).unwrap();

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
    let course =
        Course::Eased { targets: motion.targets_at(motion.duration), ease: Ease::Linear, duration: motion.duration };
    let again = Motion::new(&back, course, motion.fps).unwrap();
    let e = export::spine(&again, &exported, &Export { name: "ikarus", form }).unwrap_err();
    assert_eq!(e, "animation name \"ikarus\": the file already has an animation of that name");

    let animation = after["animations"]["ikarus"].clone();
    let mut keys: Vec<f64> = Vec::new();
    let mut count = 0;
    for (bone, kind, tl) in timelines(&animation) {
        count += tl.len();
        let times: Vec<f64> = tl.iter().map(|k| k["time"].as_f64().unwrap_or(0.0)).collect();
        for w in times.windows(2) {
            // Every key time a 32-bit float written as its shortest decimal, increasing.
            assert!((w[0] as f32) <= (w[1] as f32), "{file}: {bone}.{kind}: keys out of order at {w:?}");
        }
        for t in &times {
            assert_eq!(format!("{}", *t as f32).parse::<f64>().unwrap(), *t, "{file}: {bone}.{kind}: time {t}");
        }
        keys.extend(times);
    }
    keys.sort_by(f64::total_cmp);
    keys.dedup();
    let d = motion.duration;
    let mut times = keys.clone();
    // Halfway between every two keys, but for keys closer than 1 µs: those bracket a jump of
    // the motion itself (a bend flipping, a limb past full reach), which no key follows
    // between them.
    for w in keys.windows(2) {
        if w[1] - w[0] >= 1e-6 {
            times.push((w[0] + w[1]) / 2.0);
        }
    }
    times.extend((0..600).map(|k| d * ((k as f64 * 0.618_033_988_75) % 1.0)));
    // The motion is sampled with physics left out (Spine's `Physics.none`), and so is the
    // exported file: physics constraints the editable form leaves on would play on top in a game.
    let (mut exported_pose, mut direct) = (Posed::default(), Posed::default());
    let mut worst: f64 = 0.0;
    for t in times.iter().map(|&t| f64::from(t as f32)).filter(|t| *t <= d) {
        let ask =
            PoseAsk { animation: Some("ikarus".into()), time: Some(t), physics: PhysicsAsk::Off, ..PoseAsk::default() };
        pose_into(&back, &ask, &mut exported_pose).unwrap();
        motion.pose_at(t, &mut direct).unwrap();
        worst = worst.max(distance(&exported_pose, &direct));
    }
    // At every frame: what ikarus showed at the frame's time, what Spine plays at that time
    // read as a 32-bit float.
    let mut frames: f64 = 0.0;
    for t in motion.frame_times() {
        let ask = PoseAsk {
            animation: Some("ikarus".into()),
            time: Some(f64::from(t as f32)),
            physics: PhysicsAsk::Off,
            ..PoseAsk::default()
        };
        pose_into(&back, &ask, &mut exported_pose).unwrap();
        motion.pose_at(t, &mut direct).unwrap();
        frames = frames.max(distance(&exported_pose, &direct));
    }
    // At the last key: `ikarus pose --target …` at the end points.
    let ask =
        PoseAsk { animation: Some("ikarus".into()), time: Some(d), physics: PhysicsAsk::Off, ..PoseAsk::default() };
    pose_into(&back, &ask, &mut exported_pose).unwrap();
    let end = motion.ask_at(d);
    pose_into(loaded, &end, &mut direct).unwrap();
    let last = distance(&exported_pose, &direct);
    Played { frames, worst, last, keys: count, times: keys.len(), bytes: (exported.len(), original.len()), animation }
}
