//! Issue 41: posing from given local transforms ([`Character::pose_given`]), what the add-on's
//! stand-in skeleton calls in its `updateWorldTransform`. The clip's locals and settings
//! ([`Character::sample`]) given back pose bit for bit as [`Character::pose`] (and, with
//! physics, as [`Character::play`]) does.

use ikarus::character::{Character, GivenPose, PhysicsMode, Placement, Play, PoseError, PoseRequest, Posed, Settings};

fn read(file: &str) -> Character {
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    ikarus_edge::character::load(&text, file).unwrap().character
}

/// The locals and settings `sample` leaves for `request` in `s` (with the paths' deforms).
fn sampled_into(
    c: &Character,
    request: &PoseRequest,
    s: &mut Posed,
) -> (Vec<ikarus::character::LocalTransform>, Vec<Settings>) {
    c.sample(request, s).unwrap();
    ((0..c.bones().len()).map(|i| s.local(i)).collect(), (0..c.constraints().len()).map(|k| s.settings(k)).collect())
}

/// [`sampled_into`] a new `Posed`.
fn sampled(c: &Character, request: &PoseRequest) -> (Vec<ikarus::character::LocalTransform>, Vec<Settings>) {
    sampled_into(c, request, &mut Posed::default())
}

fn given<'a>(
    c: &Character,
    local: &'a [ikarus::character::LocalTransform],
    settings: &'a [Settings],
    skin: Option<usize>,
) -> GivenPose<'a> {
    GivenPose { local, settings, placement: c.placement(), skin, physics: PhysicsMode::None, clock: 0.0 }
}

/// Every bone's world transform, as bits.
fn bits(p: &Posed) -> Vec<[u64; 6]> {
    (0..p.len())
        .map(|i| {
            let w = p.world(i);
            [w.a, w.b, w.c, w.d, w.x, w.y].map(f64::to_bits)
        })
        .collect()
}

#[test]
fn a_sample_given_back_poses_bit_for_bit_as_the_pose() {
    // Spineboy (IK, transform constraints), the raptor (IK), stretchyman (paths, a deform).
    for (file, clip, times) in [
        ("spine-spineboy-pro.json", "walk", [0.0, 0.4, 0.8]),
        ("spine-raptor-pro.json", "walk", [0.0, 0.38, 0.8867]),
        ("spine-stretchyman-pro.json", "sneak", [0.0, 0.5, 1.2]),
    ] {
        let c = read(file);
        let skin = c.default_skin();
        for time in times {
            let request =
                PoseRequest { clip: Some((c.clip_index(clip).unwrap(), time)), skin, ..PoseRequest::default() };
            let mut want = Posed::default();
            c.pose(&request, &mut want).unwrap();
            // Stretchyman's deform stays in `got` from its sample to its pose.
            let mut got = Posed::default();
            let (local, settings) = sampled_into(&c, &request, &mut got);
            c.pose_given(&given(&c, &local, &settings, skin), &mut got).unwrap();
            assert_eq!(bits(&got), bits(&want), "{file} {clip} at {time}");
        }
    }
}

#[test]
fn the_given_mix_and_placement_are_the_ones_posed() {
    let c = read("spine-spineboy-pro.json");
    let request = PoseRequest { clip: Some((c.clip_index("walk").unwrap(), 0.4)), ..PoseRequest::default() };
    let (local, mut settings) = sampled(&c, &request);
    let k = c.constraints().iter().position(|k| k.name() == "front-leg-ik").unwrap();
    let mut keyed = Posed::default();
    c.pose_given(&given(&c, &local, &settings, None), &mut keyed).unwrap();
    // Mix 0: the leg keeps the clip's rotations (the pose with that IK constraint off).
    let Settings::Ik(s) = &mut settings[k] else { panic!("not an IK constraint") };
    s.mix = 0.0;
    let mut off = Posed::default();
    c.pose_given(&given(&c, &local, &settings, None), &mut off).unwrap();
    let thigh = c.bones().iter().position(|b| b.name == "front-thigh").unwrap();
    assert_ne!(off.world(thigh), keyed.world(thigh));
    assert_eq!(off.local(thigh).rotation.to_bits(), local[thigh].rotation.to_bits());
    // A placement moves and scales every bone's world origin about the skeleton's.
    let placed = Placement { position: [10.0, -4.0], scale: [-2.0, 0.5] };
    let mut moved = Posed::default();
    c.pose_given(&GivenPose { placement: placed, ..given(&c, &local, &settings, None) }, &mut moved).unwrap();
    for i in 0..c.bones().len() {
        let ([x, y], [mx, my]) = (off.origin(i), moved.origin(i));
        assert!((mx - (10.0 - 2.0 * x)).abs() < 1e-9 && (my - (-4.0 + 0.5 * y)).abs() < 1e-9, "bone {i}");
    }
}

#[test]
fn physics_given_frame_by_frame_plays_as_the_play() {
    let c = read("spine-celestial-circus-pro.json");
    let clip = c.clip_index("swing").unwrap();
    let skin = c.default_skin();
    let mut want = Posed::default();
    let end = 0.5;
    let request = |t: f64| PoseRequest { clip: Some((clip, t)), skin, ..PoseRequest::default() };
    c.play(&request(end), &Play { world: c.physics_world(), ..Play::default() }, &mut want).unwrap();
    let mut got = Posed::default();
    let mut clock = 0.0;
    for f in 0..=30 {
        if f > 0 {
            clock += 1.0 / 60.0;
        }
        let (local, settings) = sampled(&c, &request(clock));
        let physics = if f == 0 { PhysicsMode::Reset } else { PhysicsMode::Update };
        c.pose_given(&GivenPose { physics, clock, ..given(&c, &local, &settings, skin) }, &mut got).unwrap();
    }
    assert_eq!(bits(&got), bits(&want));
}

#[test]
fn given_numbers_of_the_wrong_shape_are_refused() {
    let c = read("spine-spineboy-pro.json");
    let (local, settings) = sampled(&c, &PoseRequest::default());
    let mut out = Posed::default();
    let e = c.pose_given(&given(&c, &local[1..], &settings, None), &mut out).unwrap_err();
    assert_eq!(e, PoseError::GivenLocals { got: local.len() - 1, want: local.len() });
    assert!(e.to_string().starts_with("local: "), "{e}");
    let e = c.pose_given(&given(&c, &local, &settings[1..], None), &mut out).unwrap_err();
    assert!(e.to_string().starts_with("settings: "), "{e}");
    let mut swapped = settings.clone();
    let t = settings.iter().position(|s| !matches!(s, Settings::Ik(_))).unwrap();
    swapped.swap(0, t);
    assert!(
        c.pose_given(&given(&c, &local, &swapped, None), &mut out).unwrap_err().to_string().starts_with("settings[")
    );
    assert_eq!(c.pose_given(&given(&c, &local, &settings, Some(99)), &mut out), Err(PoseError::UnknownSkin(99)));
    let update = GivenPose { physics: PhysicsMode::Update, clock: f64::NAN, ..given(&c, &local, &settings, None) };
    assert!(matches!(c.pose_given(&update, &mut out), Err(PoseError::Time(_))));
}
