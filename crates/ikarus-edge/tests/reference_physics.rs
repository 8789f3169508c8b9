//! Celestial-circus's physics constraints as Spine's runtime plays them
//! (`tests/reference/spine-celestial-circus-pro-full.json`, spine-core 4.2.119): the pose job
//! plays the clip from 0 with physics unless told not to, and a play gives the same bits every
//! time. Every bone of every case, physics on and off, is compared by `reference_full.rs`.

use ikarus::character::{Play, PoseRequest, Posed};
use serde_json::Value;

const FILE: &str = "spine-celestial-circus-pro.json";

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn the_same_play_gives_the_same_bits() {
    let path = format!("{}/../../examples/characters/{FILE}", env!("CARGO_MANIFEST_DIR"));
    let c = ikarus_edge::character::load(&std::fs::read_to_string(path).unwrap(), FILE).unwrap().character;
    assert_eq!(c.constraints().iter().filter(|k| k.kind() == "physics").count(), 30);
    let request = PoseRequest { clip: Some((c.clip_index("wind-idle").unwrap(), 1.0)), ..PoseRequest::default() };
    let bits = |posed: &Posed| -> Vec<u64> {
        (0..posed.len()).flat_map(|i| posed.matrix(i).into_iter().chain(posed.origin(i))).map(f64::to_bits).collect()
    };
    let (mut a, mut b) = (Posed::default(), Posed::default());
    c.play(&request, &Play::default(), &mut a).unwrap();
    c.play(&request, &Play::default(), &mut b).unwrap();
    assert_eq!(bits(&a), bits(&b));
    // Played again into the same `Posed` (its physics state restarts at 0): the same bits.
    c.play(&request, &Play::default(), &mut a).unwrap();
    assert_eq!(bits(&a), bits(&b));
}

#[test]
fn the_pose_job_plays_physics_unless_it_is_off() {
    use ikarus_edge::pose::{PhysicsAsk, PoseAsk, pose};
    let path = format!("{}/../../examples/characters/{FILE}", env!("CARGO_MANIFEST_DIR"));
    let loaded = ikarus_edge::character::load(&std::fs::read_to_string(path).unwrap(), FILE).unwrap();
    let ask = |physics| PoseAsk { animation: Some("swing".into()), time: Some(1.0), physics, ..PoseAsk::default() };
    let played = pose(&loaded, &ask(PhysicsAsk::default())).unwrap();
    let still = pose(&loaded, &ask(PhysicsAsk::Off)).unwrap();
    let path = format!("{}/tests/reference/spine-celestial-circus-pro-full.json", env!("CARGO_MANIFEST_DIR"));
    let reference: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let case = reference["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["case"]["animation"] == "swing" && c["case"]["time"] == 1.0 && c["case"]["physics"] == true)
        .unwrap();
    let bench = |report: &ikarus_edge::pose::PoseReport| {
        let b = report.bones.iter().find(|b| b.name == "bench-back").unwrap();
        (b.x - num(&case["bones"]["bench-back"]["x"])).hypot(b.y - num(&case["bones"]["bench-back"]["y"]))
    };
    assert!(bench(&played) < 1e-3, "{}", bench(&played));
    assert!(bench(&still) > 1.0, "{}", bench(&still));
    assert!(loaded.warnings.iter().all(|w| !w.contains("physics")), "{:?}", loaded.warnings);
}
