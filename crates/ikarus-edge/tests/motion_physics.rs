//! A character's motion with its physics played as a game plays it: celestial-circus (30
//! physics constraints), keyed over its `swing` clip, its frames consecutive game frames.

use ikarus::character::Posed;
use ikarus_edge::character::motion::{Motion, Physics, Playhead, keyed};
use ikarus_edge::character::{Loaded, load};
use ikarus_edge::goal::NamedGoal;
use ikarus_edge::keys::KeysFile;
use ikarus_edge::pose::{IkChoice, PhysicsAsk, PoseAsk, add_goals, pose_into};
use serde_json::json;

const FILE: &str = "spine-celestial-circus-pro.json";

fn loaded() -> Loaded {
    let path = format!("{}/../../examples/characters/{FILE}", env!("CARGO_MANIFEST_DIR"));
    load(&std::fs::read_to_string(path).unwrap(), FILE).unwrap()
}

/// Where the face control sits in the setup pose, moved by (6, −4): the target the keys hold.
fn face_target(loaded: &Loaded) -> [f64; 2] {
    let mut setup = Posed::default();
    pose_into(loaded, &PoseAsk { physics: PhysicsAsk::Off, ..PoseAsk::default() }, &mut setup).unwrap();
    let o = setup.origin(loaded.character.bone_index("face-control").unwrap());
    [o[0] + 6.0, o[1] - 4.0]
}

/// The face control held at `target` for `duration` seconds at `fps`, over `swing`.
fn motion(loaded: &Loaded, target: [f64; 2], fps: u32, duration: f64) -> Motion<'_> {
    let keys = json!({"fps": fps, "duration": duration,
        "tracks": {"face-control": [{"time": 0, "x": target[0], "y": target[1]}]}});
    let keys = KeysFile::parse(&keys.to_string()).unwrap();
    let (course, fps) = keyed(loaded, &keys, Some("swing".into()), 1000, "cap").unwrap();
    Motion::new(loaded, course, fps).unwrap()
}

/// Every frame of `motion`, each bone's origin, tip and world matrix as bits.
fn frames(motion: &Motion<'_>) -> Vec<Vec<u64>> {
    let mut out = Vec::new();
    let mut head = Playhead::default();
    for t in motion.frame_times() {
        let p = motion.play_at(t, &mut head).unwrap();
        out.push(bits(p));
    }
    out
}

fn bits(p: &Posed) -> Vec<u64> {
    (0..p.len()).flat_map(|i| p.origin(i).into_iter().chain(p.tip(i)).chain(p.matrix(i))).map(f64::to_bits).collect()
}

/// The pose request of frame `k` at 60 fps: the clip at k/60 with the face control at `target`.
fn pose_ask(target: [f64; 2], time: f64, physics: PhysicsAsk) -> PoseAsk {
    PoseAsk {
        animation: Some("swing".into()),
        time: Some(time),
        targets: vec![("face-control".into(), target)],
        physics,
        ..PoseAsk::default()
    }
}

#[test]
fn a_motions_frames_are_the_pose_at_their_time_with_physics_to_the_bit() {
    let loaded = loaded();
    let target = face_target(&loaded);
    let motion = motion(&loaded, target, 60, 0.5);
    assert!(motion.plays_physics());
    let played = frames(&motion);
    assert_eq!(played.len(), 31);
    let mut posed = Posed::default();
    for (k, t) in motion.frame_times().into_iter().enumerate() {
        pose_into(&loaded, &pose_ask(target, t, PhysicsAsk::Play { fps: 60.0 }), &mut posed).unwrap();
        assert!(bits(&posed) == played[k], "frame {k} (t = {t}) is not `pose --time {t}` with physics");
    }
    // The physics bones swing: a hair bone's frames with physics are not those without, and it
    // moves between frames differently than the clip moves it.
    let hair = loaded.character.bone_index("hair-back").unwrap();
    let (mut with, mut without, mut head) = (Vec::new(), Vec::new(), Playhead::default());
    for t in motion.frame_times() {
        with.push(motion.play_at(t, &mut head).unwrap().tip(hair));
        motion.pose_at(t, &mut posed).unwrap();
        without.push(posed.tip(hair));
    }
    let lag = with.iter().zip(&without).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
    assert!(lag > 0.5, "the hair's tip with physics is at most {lag} from without");
}

#[test]
fn physics_off_gives_each_frame_on_its_own_as_before() {
    let loaded = loaded();
    let target = face_target(&loaded);
    let mut motion = motion(&loaded, target, 30, 0.4);
    motion.physics = Physics::Off;
    assert!(!motion.plays_physics());
    let off = frames(&motion);
    let mut posed = Posed::default();
    for (k, t) in motion.frame_times().into_iter().enumerate() {
        pose_into(&loaded, &pose_ask(target, t, PhysicsAsk::Off), &mut posed).unwrap();
        assert!(bits(&posed) == off[k], "frame {k}");
    }
    motion.physics = Physics::Played;
    assert!(frames(&motion) != off, "with physics the frames should differ");
}

#[test]
fn the_same_motion_gives_the_same_bits_and_its_json_streams_as_it_plays() {
    let loaded = loaded();
    let target = face_target(&loaded);
    let motion = motion(&loaded, target, 30, 0.5);
    let json = ikarus_edge::character::motion_files::json(&motion).unwrap();
    assert_eq!(json, ikarus_edge::character::motion_files::json(&motion).unwrap());
    assert_eq!(json, serde_json::to_vec(&motion.frames().unwrap()).unwrap());
    // The frames as the JSON has them are the played ones.
    let played = frames(&motion);
    let posed = motion.poses().unwrap();
    let mut head = Playhead::default();
    for (k, (t, report)) in posed.iter().enumerate() {
        let p = motion.play_at(*t, &mut head).unwrap();
        assert!(bits(p) == played[k]);
        assert_eq!(report.bones[7].x.to_bits(), p.origin(7)[0].to_bits(), "frame {k}");
    }
}

#[test]
fn between_frames_the_motion_is_its_frame_and_a_shorter_one_and_going_back_plays_again() {
    let loaded = loaded();
    let target = face_target(&loaded);
    let motion = motion(&loaded, target, 30, 0.5);
    let mut head = Playhead::default();
    let t = 7.5 / 30.0;
    let between = bits(motion.play_at(t, &mut head).unwrap());
    // Frame 8 (past it), then back between 7 and 8: from frame 7 kept, the same bits.
    motion.play_at(8.0 / 30.0, &mut head).unwrap();
    assert!(bits(motion.play_at(t, &mut head).unwrap()) == between);
    // Back to frame 2 (a new play from 0), then between 7 and 8 again.
    let two = bits(motion.play_at(2.0 / 30.0, &mut head).unwrap());
    assert!(two == frames(&motion)[2]);
    assert!(bits(motion.play_at(t, &mut head).unwrap()) == between);
    // Not frame 7 and not frame 8.
    let all = frames(&motion);
    assert!(between != all[7] && between != all[8]);
}

#[test]
fn under_ikaruss_solver_a_goal_is_met_on_the_pose_with_physics() {
    let loaded = loaded();
    let c = &loaded.character;
    let target = face_target(&loaded);
    let hat = c.bone_index("hat-front").unwrap();
    // Near where the clip has the hat's tip at 0: the hat and the face turn to it.
    let mut start = Posed::default();
    pose_into(&loaded, &pose_ask(target, 0.0, PhysicsAsk::Off), &mut start).unwrap();
    let tip = start.tip(hat);
    let goal = [tip[0] + 4.0, tip[1] - 3.0];
    let mut rules = ikarus::character::Together::default();
    let goals = [NamedGoal::new("hat-front", goal[0], goal[1], None)];
    add_goals(&mut rules, c, &goals, &[], &[], &|f| format!("{f:?}")).unwrap();
    // Within the two bones' reach while the clip swings the body (0.1 s).
    let mut motion = motion(&loaded, target, 30, 0.1);
    motion.ik = IkChoice::Ikarus(Box::new(rules));
    let played = motion.poses().unwrap();
    motion.physics = Physics::Off;
    let off = motion.poses().unwrap();
    let mut swung: f64 = 0.0;
    for ((t, on), (_, off)) in played.iter().zip(&off) {
        let b = &on.bones[hat];
        let miss = (b.tip[0] - goal[0]).hypot(b.tip[1] - goal[1]);
        assert!(miss < 1e-6, "t = {t}: the hat's tip is {miss} from its goal");
        let moved = on.bones.iter().zip(&off.bones).map(|(p, q)| (p.x - q.x).hypot(p.y - q.y)).fold(0.0, f64::max);
        swung = swung.max(moved);
    }
    println!("the physics moved a bone by up to {swung}");
    assert!(swung > 0.5, "the physics moved no bone more than {swung}");
}
