use super::spline::{self, Point};
use super::*;
use crate::character::Interpolation;

/// An open path of one straight curve from (0, 0) to (90, 0), handles on the line at thirds,
/// unweighted, in the slot bone's frame.
fn straight(closed: bool) -> PathShape {
    let v = vec![[-30.0, 0.0], [0.0, 0.0], [30.0, 0.0], [60.0, 0.0], [90.0, 0.0], [120.0, 0.0]];
    PathShape { closed, constant_speed: true, lengths: vec![90.0, 180.0], vertices: PathVertices::Plain(v) }
}

fn constraint(bones: usize, rotate_mode: RotateMode, spacing_mode: SpacingMode) -> PathConstraint {
    PathConstraint {
        name: "p".into(),
        order: 0,
        skin: false,
        bones: (1..=bones).collect(),
        slot: 0,
        slot_bone: 0,
        path: Some(straight(false)),
        skin_paths: Vec::new(),
        position_mode: PositionMode::Percent,
        spacing_mode,
        rotate_mode,
        rotation: 0.0,
        setup: PathSettings::default(),
    }
}

fn close(a: f64, b: f64) {
    assert!((a - b).abs() < 1e-9, "{a} vs {b}");
}

/// A bone at `(x, y)` turned by `r`, scaled by `s` along x.
fn bone(x: f64, y: f64, r: f64, s: f64) -> Affine {
    let (sin, cos) = crate::math::sin_cos(r);
    Affine { a: cos * s, b: -sin, c: sin * s, d: cos, x, y }
}

#[test]
fn a_straight_path_is_measured_and_walked_at_constant_speed() {
    let path = straight(false);
    let mut v = Vec::new();
    spline::world_vertices(&path, &Affine::default(), &|_| Affine::default(), None, &mut v);
    let mut ends = Vec::new();
    close(spline::ends(&path, &v, &mut ends).unwrap(), 90.0);
    let mut out = Vec::new();
    spline::points(&path, &v, &ends, &[0.0, 45.0, 90.0, 100.0, -10.0], &mut out);
    let xs: Vec<f64> = out.iter().map(|p: &Point| p.x).collect();
    for (x, want) in xs.iter().zip([0.0, 45.0, 90.0, 100.0, -10.0]) {
        close(*x, want);
    }
    assert!(out.iter().all(|p| p.y == 0.0 && p.angle == 0.0));
}

#[test]
fn a_closed_path_wraps_distances() {
    // Three knots on a closed triangle-ish loop: a distance of the length plus d is d.
    let v = vec![
        [0.0, -5.0],
        [0.0, 0.0],
        [5.0, 0.0],
        [35.0, 0.0],
        [40.0, 0.0],
        [40.0, 5.0],
        [40.0, 35.0],
        [40.0, 40.0],
        [35.0, 40.0],
    ];
    let path = PathShape { closed: true, constant_speed: true, lengths: vec![], vertices: PathVertices::Plain(v) };
    let mut w = Vec::new();
    spline::world_vertices(&path, &Affine::default(), &|_| Affine::default(), None, &mut w);
    let mut ends = Vec::new();
    let total = spline::ends(&path, &w, &mut ends).unwrap();
    assert_eq!(ends.len(), 3);
    let mut out = Vec::new();
    spline::points(&path, &w, &ends, &[10.0, 10.0 + total, 10.0 - total], &mut out);
    close(out[0].x, out[1].x);
    close(out[0].y, out[1].y);
    close(out[0].x, out[2].x);
}

#[test]
fn chain_scale_places_each_bone_at_its_point_and_stretches_it_to_the_next() {
    // Two bones of length 10 at percent spacing 0.5: points at 0, 45, 90.
    let mut c = constraint(2, RotateMode::ChainScale, SpacingMode::Percent);
    c.setup.spacing = 0.5;
    let mut world = [bone(3.0, 4.0, 1.0, 1.0), bone(7.0, -2.0, -0.5, 2.0)];
    let mut scratch = PathScratch::default();
    solve(
        &c,
        &c.setup,
        &|_| Affine::default(),
        c.followed(None, None),
        Chain { world: &mut world, length: &[10.0, 10.0] },
        &mut scratch,
    );
    close(world[0].x, 0.0);
    close(world[1].x, 45.0);
    close(world[1].y, 0.0);
    for w in &world {
        close(w.rotation(), 0.0);
        close(crate::math::hypot(w.a, w.c), 4.5); // 45 units for a bone of length 10
    }
    // The y axes turned with the x axes, keeping their lengths.
    close(crate::math::hypot(world[0].b, world[0].d), 1.0);
}

#[test]
fn mixes_blend_the_move_and_the_turn() {
    let mut c = constraint(1, RotateMode::Tangent, SpacingMode::Length);
    c.setup = PathSettings { position: 0.5, spacing: 0.0, mix_rotate: 0.5, mix_x: 0.5, mix_y: 0.25 };
    let mut world = [bone(10.0, 8.0, 1.0, 1.0)];
    let mut scratch = PathScratch::default();
    solve(
        &c,
        &c.setup,
        &|_| Affine::default(),
        c.followed(None, None),
        Chain { world: &mut world, length: &[10.0] },
        &mut scratch,
    );
    // The point is (45, 0); the tangent is along +x.
    close(world[0].x, 10.0 + 35.0 * 0.5);
    close(world[0].y, 8.0 - 8.0 * 0.25);
    close(world[0].rotation(), 0.5);
}

#[test]
fn length_spacing_adds_the_bones_world_lengths() {
    let mut c = constraint(3, RotateMode::Chain, SpacingMode::Length);
    c.position_mode = PositionMode::Fixed;
    c.setup.position = 5.0;
    c.setup.spacing = 1.0;
    let mut world = [bone(0.0, 0.0, 0.0, 1.0), bone(0.0, 0.0, 0.0, 2.0), bone(0.0, 0.0, 0.0, 1.0)];
    let mut scratch = PathScratch::default();
    solve(
        &c,
        &c.setup,
        &|_| Affine::default(),
        c.followed(None, None),
        Chain { world: &mut world, length: &[10.0, 10.0, 10.0] },
        &mut scratch,
    );
    close(world[0].x, 5.0);
    close(world[1].x, 16.0);
    close(world[2].x, 37.0);
}

#[test]
fn weighted_vertices_and_deforms_follow_their_bones() {
    let bones = [Affine { x: 100.0, ..Affine::default() }, bone(0.0, 50.0, std::f64::consts::FRAC_PI_2, 1.0)];
    let w = |b, x, y, weight| Weight { bone: b, point: [x, y], weight };
    let path = PathShape {
        closed: false,
        constant_speed: true,
        lengths: vec![],
        vertices: PathVertices::Weighted(vec![vec![w(0, 1.0, 2.0, 0.5), w(1, 4.0, 0.0, 0.5)]]),
    };
    let mut out = Vec::new();
    spline::world_vertices(&path, &Affine::default(), &|i| bones[i], Some(&[1.0, 0.0, 0.0, 2.0]), &mut out);
    // Bone 0: (102, 2); bone 1 turned a quarter: (4, 2) → (−2, 54); halves: (50, 28).
    close(out[0][0], 50.0);
    close(out[0][1], 28.0);
}

#[test]
fn a_path_without_a_curve_leaves_the_bones() {
    let mut c = constraint(1, RotateMode::Tangent, SpacingMode::Length);
    c.path = Some(PathShape {
        closed: false,
        constant_speed: true,
        lengths: vec![],
        vertices: PathVertices::Plain(vec![[0.0; 2]; 3]),
    });
    let before = [bone(3.0, 4.0, 1.0, 1.0)];
    let mut world = before;
    solve(
        &c,
        &c.setup,
        &|_| Affine::default(),
        c.followed(None, None),
        Chain { world: &mut world, length: &[10.0] },
        &mut PathScratch::default(),
    );
    assert_eq!(world, before);
}

#[test]
fn deform_keys_interpolate_and_hold() {
    let d = PathDeform {
        slot: 0,
        keys: vec![
            DeformKey { time: 1.0, start: 1, offsets: vec![2.0], curve: Interpolation::Linear },
            DeformKey { time: 2.0, start: 0, offsets: vec![4.0, 2.0], curve: Interpolation::Stepped },
            DeformKey { time: 3.0, start: 0, offsets: vec![8.0, 8.0, 1.0], curve: Interpolation::Linear },
        ],
    };
    let mut out = Vec::new();
    assert!(!d.at(0.5, &mut out) && out.is_empty());
    assert!(d.at(1.5, &mut out));
    assert_eq!(out, vec![2.0, 2.0]);
    d.at(2.9, &mut out);
    assert_eq!(out, vec![4.0, 2.0, 0.0]);
    d.at(9.0, &mut out);
    assert_eq!(out, vec![8.0, 8.0, 1.0]);
}

/// A character of a root and two bones and one path constraint (index 0) on them.
fn character_parts() -> crate::character::CharacterParts {
    use crate::character::{CharacterBone, Inherit, LocalTransform};
    let bone = |name: &str, parent: Option<usize>| CharacterBone {
        name: name.into(),
        parent,
        length: 10.0,
        setup: LocalTransform::default(),
        inherit: Inherit::Normal,
    };
    crate::character::CharacterParts {
        bones: vec![bone("root", None), bone("a", Some(0)), bone("b", Some(1))],
        constraints: vec![crate::character::Constraint::Path(constraint(2, RotateMode::Chain, SpacingMode::Length))],
        ..Default::default()
    }
}

#[test]
fn the_model_refuses_missing_bones_bad_mixes_and_timelines_of_another_kind() {
    use crate::character::{Character, CharacterError, Clip, Constraint, ConstraintKeys, ConstraintTimeline};
    assert!(Character::new(character_parts()).is_ok());
    let with = |f: &dyn Fn(&mut PathConstraint)| {
        let mut p = character_parts();
        let Constraint::Path(c) = &mut p.constraints[0] else { unreachable!() };
        f(c);
        Character::new(p).unwrap_err()
    };
    assert_eq!(with(&|c| c.bones[1] = 7), CharacterError::PathBone { constraint: 0, bone: 7 });
    assert_eq!(with(&|c| c.slot_bone = 3), CharacterError::PathBone { constraint: 0, bone: 3 });
    assert_eq!(with(&|c| c.setup.mix_x = 1.5).to_string(), "path constraint 0.mixX: out of range, got 1.5");
    assert_eq!(with(&|c| c.setup.position = f64::NAN).to_string(), "path constraint 0.position: out of range, got NaN");
    let mut p = character_parts();
    p.clips.push(Clip {
        name: "c".into(),
        duration: 1.0,
        bones: vec![],
        constraints: vec![ConstraintTimeline { constraint: 0, keys: ConstraintKeys::Ik(vec![]) }],
    });
    assert_eq!(
        Character::new(p).unwrap_err(),
        CharacterError::TimelineKind { constraint: 0, keys: "ik", kind: "path" }
    );
}

#[test]
fn a_pose_follows_the_skins_own_path_else_the_default_skins() {
    use crate::character::{Character, CharacterParts, Constraint, PoseRequest, Posed, Skin};
    use crate::fixtures::character_bone;
    // The default skin's path runs along x; skin 1's own runs along y; skin 2 has a non-path
    // attachment of that name; skin 3 none.
    let v = vec![[0.0, -30.0], [0.0, 0.0], [0.0, 30.0], [0.0, 60.0], [0.0, 90.0], [0.0, 120.0]];
    let up = PathShape { vertices: PathVertices::Plain(v), ..straight(false) };
    let mut c = constraint(1, RotateMode::Tangent, SpacingMode::Length);
    c.setup.position = 0.5;
    c.skin_paths = vec![SkinPath { skin: 1, path: Some(up) }, SkinPath { skin: 2, path: None }];
    let skins = (0..4).map(|i| Skin { name: format!("s{i}"), ..Skin::default() }).collect();
    let parts = |c: PathConstraint, skins| CharacterParts {
        bones: vec![character_bone("root", None, 0.0, 0.0), {
            let mut a = character_bone("a", Some(0), 0.0, 0.0);
            a.setup.y = 10.0;
            a
        }],
        constraints: vec![Constraint::Path(c)],
        skins,
        ..CharacterParts::default()
    };
    let character = Character::new(parts(c.clone(), skins)).unwrap();
    let mut out = Posed::default();
    let mut at = |skin| {
        character.pose(&PoseRequest { skin, ..PoseRequest::default() }, &mut out).unwrap();
        out.origin(1)
    };
    let want = [
        (None, [45.0, 0.0]),
        (Some(0), [45.0, 0.0]),
        (Some(1), [0.0, 45.0]),
        (Some(2), [0.0, 10.0]),
        (Some(3), [45.0, 0.0]),
    ];
    for (skin, [x, y]) in want {
        let [gx, gy] = at(skin);
        close(gx, x);
        close(gy, y);
    }
    // A path for a skin the character does not have is refused.
    let e = Character::new(parts(c, Vec::new())).unwrap_err();
    assert_eq!(e.to_string(), "path constraint 0: a path for skin 1, which does not exist");
}
