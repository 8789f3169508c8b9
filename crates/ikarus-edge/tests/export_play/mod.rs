//! Playing a Spine export back: the exported file read by our own loader (whose posing matches
//! Spine's runtime within 7.5e-5, `character_reference.rs`), its new animation posed at every
//! frame time, every key and hundreds of times between, each as the 32-bit float Spine's
//! runtime keeps a time in, and every bone's world origin and tip compared with the motion;
//! both played as a game plays them when the motion plays physics.

#![allow(dead_code)]

use ikarus::Ease;
use ikarus::character::{PhysicsWorld, PlayFrame, PoseRequest, Posed};
use ikarus_edge::character::export::{self, Export, Form};
use ikarus_edge::character::motion::{Course, Motion, Playhead};
use ikarus_edge::character::{Loaded, load};
use ikarus_edge::pose::{IkChoice, PhysicsAsk, PoseAsk, pose, pose_into};
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
    // In increasing order: the motion is played as a game plays it, one frame after another.
    times.sort_by(f64::total_cmp);
    // Both are played as a game plays them, the physics stepping frame by frame at the
    // motion's fps and clock: the motion with its physics (unless asked off), the export's
    // animation at the same clock ([`Game`]). The bake holds what the physics did, its physics
    // at mix 0; the editable form under the runtime's rules keeps them on, to play on top of
    // the keys as they do on the motion. Under ikarus's solver the editable form switches
    // every constraint off and is fitted to the motion without physics, so it is compared with
    // that.
    let game = motion.plays_physics() && !(form == Form::Editable && motion.ik != IkChoice::Runtime);
    let exported_game = game.then(|| Game::new(&back, motion));
    let exported_at = |t: f64, out: &mut Posed| match &exported_game {
        Some(g) => g.at(&back, t, out),
        None => {
            let ask = PoseAsk {
                animation: Some("ikarus".into()),
                time: Some(t),
                physics: PhysicsAsk::Off,
                ..PoseAsk::default()
            };
            pose_into(&back, &ask, out).unwrap();
        }
    };
    let (mut exported_pose, mut direct, mut head) = (Posed::default(), Posed::default(), Playhead::default());
    let mut motion_at = |t: f64, direct: &mut Posed| {
        if game {
            *direct = motion.play_at(t, &mut head).unwrap().clone();
        } else {
            motion.pose_at(t, direct).unwrap();
        }
    };
    let mut worst: f64 = 0.0;
    for t in times.iter().map(|&t| f64::from(t as f32)).filter(|t| *t <= d) {
        exported_at(t, &mut exported_pose);
        motion_at(t, &mut direct);
        worst = worst.max(distance(&exported_pose, &direct));
    }
    // At every frame: what ikarus showed at the frame's time, what Spine plays at that time
    // read as a 32-bit float.
    let mut frames: f64 = 0.0;
    for t in motion.frame_times() {
        // A game plays the export at its own clock, the motion's (the keys' times 32-bit
        // floats as written): a frame read a hair earlier would step the physics once less.
        exported_at(if game { t } else { f64::from(t as f32) }, &mut exported_pose);
        motion_at(t, &mut direct);
        frames = frames.max(distance(&exported_pose, &direct));
    }
    // At the last key: `ikarus pose --target …` at the end points (with physics played, the
    // motion's last frame: its physics has a history that a pose at a time has not).
    exported_at(d, &mut exported_pose);
    if game {
        motion_at(d, &mut direct);
    } else {
        pose_into(loaded, &motion.ask_at(d), &mut direct).unwrap();
    }
    let last = distance(&exported_pose, &direct);
    Played { frames, worst, last, keys: count, times: keys.len(), bytes: (exported.len(), original.len()), animation }
}

/// The export's animation `ikarus` played as a game plays it at the motion's frames: the clock
/// at 0 on the first frame (the physics restarting), `1 / fps` more a frame (added up), the
/// last at the motion's end unless that is a whole number of frames; the clip at the clock.
pub struct Game {
    clip: usize,
    /// Each frame's time, clock and pose.
    frames: Vec<(f64, f64, Posed)>,
}

impl Game {
    pub fn new(back: &Loaded, motion: &Motion<'_>) -> Self {
        let c = &back.character;
        let clip = c.clip_index("ikarus").unwrap();
        let times = motion.frame_times();
        let whole = (motion.duration * motion.fps - (motion.duration * motion.fps).round()).abs() < 1e-9;
        let mut frames: Vec<(f64, f64, Posed)> = Vec::new();
        let mut posed = Posed::default();
        for (k, &t) in times.iter().enumerate() {
            let before = frames.last().map(|f| f.1);
            let clock = match before {
                None => 0.0,
                Some(b) if k + 1 < times.len() || whole => b + 1.0 / motion.fps,
                Some(_) => motion.duration,
            };
            let request = PoseRequest { clip: Some((clip, clock)), skin: c.default_skin(), ..PoseRequest::default() };
            let frame = PlayFrame { clock, before, world: PhysicsWorld::default() };
            c.play_frame(&request, &frame, &mut posed).unwrap();
            frames.push((t, clock, posed.clone()));
        }
        Game { clip, frames }
    }

    /// The animation at `t`: the frame at or before it, and one shorter frame to it.
    pub fn at(&self, back: &Loaded, t: f64, out: &mut Posed) {
        let k = self.frames.iter().rposition(|f| f.0 <= t).unwrap_or(0);
        let (at, clock, posed) = &self.frames[k];
        *out = posed.clone();
        if t > *at {
            let now = clock + (t - at);
            let request = PoseRequest {
                clip: Some((self.clip, now)),
                skin: back.character.default_skin(),
                ..PoseRequest::default()
            };
            let frame = PlayFrame { clock: now, before: Some(*clock), world: PhysicsWorld::default() };
            back.character.play_frame(&request, &frame, out).unwrap();
        }
    }
}
