use super::*;

fn constraint(shares: PhysicsShares) -> PhysicsConstraint {
    PhysicsConstraint {
        name: "p".into(),
        order: 0,
        skin: false,
        bone: 0,
        shares,
        limit: 5000.0,
        fps: 60.0,
        setup: PhysicsSettings::default(),
        global: PhysicsGlobal::default(),
    }
}

fn input(c: &PhysicsConstraint, settings: PhysicsSettings, time: f64) -> PhysicsInput<'_> {
    PhysicsInput { constraint: c, settings, world: PhysicsWorld::default(), time, length: 10.0 }
}

const XY: PhysicsShares = PhysicsShares { x: 1.0, y: 1.0, rotate: 0.0, scale_x: 0.0, shear_x: 0.0 };
const TURN: PhysicsShares = PhysicsShares { x: 0.0, y: 0.0, rotate: 1.0, scale_x: 1.0, shear_x: 0.0 };

#[test]
fn a_bone_at_rest_stays_put() {
    for shares in [XY, TURN] {
        let c = constraint(shares);
        let mut state = PhysicsState::default();
        let posed = Affine { a: 0.8, b: -0.6, c: 0.6, d: 0.8, x: 3.0, y: -4.0 };
        let mut bone = posed;
        state.apply(&input(&c, c.setup, 0.0), PhysicsMode::Reset, &mut bone);
        let mut time = 0.0;
        for _ in 0..120 {
            time += 1.0 / 60.0;
            let mut bone = posed;
            state.apply(&input(&c, c.setup, time), PhysicsMode::Update, &mut bone);
            // Only the rounding of measuring the bone's own direction back moves it.
            for (p, q) in [(bone.a, posed.a), (bone.b, posed.b), (bone.c, posed.c), (bone.d, posed.d)] {
                assert!((p - q).abs() < 1e-12, "{bone:?}");
            }
            assert_eq!([bone.x, bone.y], [posed.x, posed.y]);
        }
    }
}

#[test]
fn a_move_is_left_behind_by_the_inertia_then_one_spring_step() {
    // Moved by (2, 0) with inertia 0.5: the offset is −1; one step of 1/60 with strength 100,
    // mass 1: v = 100/60, o = −1 + v/60; damping 0.9 acts on v after.
    let c = constraint(XY);
    let s = PhysicsSettings { inertia: 0.5, damping: 0.9, ..PhysicsSettings::default() };
    let mut state = PhysicsState::default();
    let mut bone = Affine::default();
    state.apply(&input(&c, s, 0.0), PhysicsMode::Reset, &mut bone);
    let mut bone = Affine { x: 2.0, ..Affine::default() };
    let step = 1.0 / 60.0;
    state.apply(&input(&c, s, step), PhysicsMode::Update, &mut bone);
    let v = 100.0 * step;
    let o = -1.0 + v * step;
    assert!((bone.x - (2.0 + o)).abs() < 1e-12, "{}", bone.x);
    assert_eq!(bone.y, 0.0);
    // Next pose, unmoved: v·0.9 then the spring again.
    let mut bone = Affine { x: 2.0, ..Affine::default() };
    state.apply(&input(&c, s, 2.0 * step), PhysicsMode::Update, &mut bone);
    let v2 = v * 0.9 - o * 100.0 * step;
    assert!((bone.x - (2.0 + o + v2 * step)).abs() < 1e-12, "{}", bone.x);
}

#[test]
fn none_leaves_the_bone_and_the_state() {
    let c = constraint(XY);
    let mut state = PhysicsState::default();
    let mut bone = Affine { x: 5.0, ..Affine::default() };
    state.apply(&input(&c, c.setup, 1.0), PhysicsMode::None, &mut bone);
    assert_eq!(bone, Affine { x: 5.0, ..Affine::default() });
    assert_eq!(state, PhysicsState::default());
}

#[test]
fn wind_pushes_along_x_scaled_by_the_reference_scale() {
    let c = constraint(XY);
    let s = PhysicsSettings { wind: 2.0, ..PhysicsSettings::default() };
    let mut state = PhysicsState::default();
    let mut bone = Affine::default();
    state.apply(&input(&c, s, 0.0), PhysicsMode::Reset, &mut bone);
    let step = 1.0 / 60.0;
    state.apply(&input(&c, s, step), PhysicsMode::Update, &mut bone);
    assert!((bone.x - 200.0 * step * step).abs() < 1e-12, "{}", bone.x);
    assert_eq!(bone.y, 0.0);
}

#[test]
fn the_remainder_is_carried_so_30_fps_steps_every_other_60th() {
    let mut c = constraint(XY);
    c.fps = 30.0;
    let mut state = PhysicsState::default();
    let mut bone = Affine::default();
    state.apply(&input(&c, c.setup, 0.0), PhysicsMode::Reset, &mut bone);
    let mut xs = Vec::new();
    for k in 1..=4 {
        let mut bone = Affine { x: 1.0, ..Affine::default() };
        state.apply(&input(&c, c.setup, k as f64 / 60.0), PhysicsMode::Update, &mut bone);
        xs.push(bone.x);
    }
    // Inertia 1: the first pose leaves the bone at 0 (offset −1) without a step; the second
    // steps once and so moves; the third does not step.
    assert_eq!(xs[0], 0.0);
    assert!(xs[1] > 0.0);
    assert_eq!(xs[1], xs[2]);
    assert!(xs[3] != xs[2]);
}

#[test]
fn a_turn_of_the_parent_swings_the_tip_back() {
    // The bone turns by 0.1 rad about its origin: with inertia 1 its tip stays behind, so the
    // rotation offset is −0.1 before the step.
    let c = constraint(PhysicsShares { rotate: 1.0, ..PhysicsShares::default() });
    let s = PhysicsSettings { strength: 0.0, ..PhysicsSettings::default() };
    let mut state = PhysicsState::default();
    let mut bone = Affine::default();
    state.apply(&input(&c, s, 0.0), PhysicsMode::Reset, &mut bone);
    let (sin, cos) = crate::math::sin_cos(0.1);
    let mut bone = Affine { a: cos, b: -sin, c: sin, d: cos, x: 0.0, y: 0.0 };
    state.apply(&input(&c, s, 1.0 / 60.0), PhysicsMode::Update, &mut bone);
    assert!(bone.rotation().abs() < 1e-12, "{}", bone.rotation());
}

#[test]
fn a_clock_far_ahead_takes_a_bounded_number_of_steps() {
    let c = constraint(XY);
    let mut state = PhysicsState::default();
    let mut bone = Affine::default();
    state.apply(&input(&c, c.setup, 0.0), PhysicsMode::Reset, &mut bone);
    let mut bone = Affine { x: 1.0, ..Affine::default() };
    state.apply(&input(&c, c.setup, 1e12), PhysicsMode::Update, &mut bone);
    assert!(bone.x.is_finite());
}
