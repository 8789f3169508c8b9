//! Physics constraint rules no reference vector pins (celestial-circus has only the default
//! reference scale, no gravity, every constraint at 60 steps a second), checked on small
//! synthetic characters played by the pose job against what the documented behaviour implies.
//!
//! What Spine's public pages say (user guide "Physics constraints", the JSON export format's
//! `physics` constraint and skeleton object, the runtime API reference):
//! - the constraint offsets a bone from its unconstrained pose; each of `x`, `y`, `rotate`,
//!   `scaleX`, `shearX` says how much of the offset that property shows (0: "moves fully with
//!   the unconstrained pose"), so a property at 0 is left as posed;
//! - `strength` is a spring pulling the offset back, `damping` takes speed away, `wind` and
//!   `gravity` are forces (wind along x, gravity pulling down); with damping the bone comes to
//!   rest where the spring balances the forces, whatever the mass and the step;
//! - `referenceScale` (skeleton, default 100): "baseline scale factor for applying physics and
//!   other effects based on distance to non-scalable properties, such as angle or scale": a
//!   skeleton drawn twice as large with twice the reference scale moves the same, twice as
//!   large;
//! - `limit`: "movement greater than the limit will not have a greater affect on physics";
//! - `fps`: how many times a second the physics is computed (the step), whatever the game's
//!   frame rate.

use ikarus::character::Posed;
use ikarus_edge::pose::{PhysicsAsk, PoseAsk, pose_into};
use serde_json::{Value, json};

/// A character: bone `b` (at (10, 20) × `k`, length 50 × `k`, pointing along +x) with one
/// physics constraint (`fields`), reference scale `r`, and clips `still` (10 s of setup pose)
/// and `jump` (b's x steps by `jump` × `k` at 0.5 s).
fn character(k: f64, r: Option<f64>, jump: f64, fields: Value) -> ikarus_edge::character::Loaded {
    let mut skeleton = json!({"spine": "4.2.00"});
    if let Some(r) = r {
        skeleton["referenceScale"] = json!(r);
    }
    let mut physics = json!({"name": "c", "bone": "b", "limit": 100000 });
    physics.as_object_mut().unwrap().extend(fields.as_object().unwrap().clone());
    let file = json!({
        "skeleton": skeleton,
        "bones": [{"name": "root"}, {"name": "b", "parent": "root", "x": 10.0 * k, "y": 20.0 * k, "length": 50.0 * k}],
        "physics": [physics],
        "animations": {
            "still": {"bones": {"b": {"rotate": [{"time": 0}, {"time": 10}]}}},
            "jump": {"bones": {"b": {"translate": [{"time": 0, "curve": "stepped"}, {"time": 0.5, "x": jump * k},
                {"time": 10, "x": jump * k}]}}},
        },
    });
    ikarus_edge::character::load(&file.to_string(), "rules.json").unwrap()
}

/// `loaded` played from 0 to `time` through `clip` at `game` frames a second (`None`: physics off).
fn play(loaded: &ikarus_edge::character::Loaded, clip: &str, time: f64, game: Option<f64>) -> Posed {
    let physics = game.map_or(PhysicsAsk::Off, |fps| PhysicsAsk::Play { fps });
    let ask = PoseAsk { animation: Some(clip.into()), time: Some(time), physics, ..PoseAsk::default() };
    let mut out = Posed::default();
    pose_into(loaded, &ask, &mut out).unwrap();
    out
}

/// Bone b's world transform: `[a, b, c, d, x, y]`.
fn b(p: &Posed) -> [f64; 6] {
    let [a, bb, c, d] = p.matrix(1);
    let [x, y] = p.origin(1);
    [a, bb, c, d, x, y]
}

fn close(got: f64, want: f64, what: &str) {
    assert!((got - want).abs() < 1e-6, "{what}: {got}, expected {want}");
}

/// A damped constraint: strength 400, damping 0.8 (settled well within 8 s), mass 2.
fn damped(extra: Value) -> Value {
    let mut f = json!({"strength": 400, "damping": 0.8, "mass": 2, "inertia": 1});
    f.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
    f
}

#[test]
fn wind_and_gravity_settle_where_the_spring_balances_them() {
    // At rest the spring's pull, strength × offset, equals the force: wind 3 along +x and
    // gravity 2 down, in units of the reference scale: offset (3, −2) × 100 / 400.
    let c = character(1.0, None, 0.0, damped(json!({"x": 1, "y": 1, "wind": 3, "gravity": 2})));
    let m = b(&play(&c, "still", 8.0, Some(60.0)));
    close(m[4], 10.0 + 0.75, "x");
    close(m[5], 20.0 - 0.5, "y");
    // Each share shows its part: x 0.5 and y 0.25 of the same offsets; the mix 0.5 halves both.
    let c = character(1.0, None, 0.0, damped(json!({"x": 0.5, "y": 0.25, "wind": 3, "gravity": 2})));
    let m = b(&play(&c, "still", 8.0, Some(60.0)));
    close(m[4], 10.0 + 0.375, "x");
    close(m[5], 20.0 - 0.125, "y");
    let c = character(1.0, None, 0.0, damped(json!({"x": 1, "y": 1, "wind": 3, "gravity": 2, "mix": 0.5})));
    let m = b(&play(&c, "still", 8.0, Some(60.0)));
    close(m[4], 10.0 + 0.375, "x");
    close(m[5], 20.0 - 0.25, "y");
}

#[test]
fn the_skeleton_s_reference_scale_is_the_forces_unit_of_distance() {
    // referenceScale 50: the same forces move the bone half as far.
    let c = character(1.0, Some(50.0), 0.0, damped(json!({"x": 1, "y": 1, "wind": 3, "gravity": 2})));
    let m = b(&play(&c, "still", 8.0, Some(60.0)));
    close(m[4], 10.0 + 0.375, "x");
    close(m[5], 20.0 - 0.25, "y");
}

#[test]
fn a_reference_scale_that_is_not_positive_is_refused() {
    for r in [0.0, -100.0] {
        let file = json!({"skeleton": {"spine": "4.2.00", "referenceScale": r}, "bones": [{"name": "root"}]});
        let e = ikarus_edge::character::load(&file.to_string(), "rules.json").unwrap_err().to_string();
        println!("{e}");
        assert!(e.contains("skeleton.referenceScale") && e.contains(&format!("{r}")) && !e.contains('\n'), "{e}");
    }
}

#[test]
fn a_skeleton_twice_as_large_with_twice_the_reference_scale_moves_twice_as_far() {
    // Every property, forces and a jump: b twice as large (positions, length, the jump) and
    // the reference scale 200 in place of 100 poses b's origin twice as far from the root and
    // its axes the same, at every time.
    let fields = json!({"x": 0.5, "y": 0.7, "rotate": 0.8, "scaleX": 0.6, "shearX": 0.3, "wind": 4,
        "gravity": 6, "strength": 90, "damping": 0.9, "inertia": 0.7, "mass": 1.5});
    let one = character(1.0, Some(100.0), 30.0, fields.clone());
    let two = character(2.0, Some(200.0), 30.0, fields);
    for time in [0.3, 0.55, 0.8, 1.5] {
        let (p, q) = (b(&play(&one, "jump", time, Some(60.0))), b(&play(&two, "jump", time, Some(60.0))));
        for i in 0..4 {
            close(q[i], p[i], &format!("t {time}: matrix[{i}]"));
        }
        close(q[4], 2.0 * p[4], &format!("t {time}: x"));
        close(q[5], 2.0 * p[5], &format!("t {time}: y"));
    }
    // (It moved: the physics did something.)
    let (p, still) = (b(&play(&one, "jump", 0.8, Some(60.0))), b(&play(&one, "jump", 0.8, None)));
    assert!((p[4] - still[4]).abs() > 0.1 && (p[0] - still[0]).abs() > 1e-3, "{p:?} {still:?}");
}

/// The angle of the axis `(x, y)`, degrees.
fn deg(x: f64, y: f64) -> f64 {
    y.atan2(x).to_degrees()
}

#[test]
fn each_property_alone_changes_only_itself() {
    let forces = |which: &str| damped(json!({which: 1, "wind": 3, "gravity": 2}));
    let posed = |which: &str| b(&play(&character(1.0, None, 0.0, forces(which)), "still", 8.0, Some(60.0)));
    let setup = [1.0, 0.0, 0.0, 1.0, 10.0, 20.0];
    // x alone: only the origin's x moves (+0.75, the wind's balance).
    let m = posed("x");
    close(m[4], 10.75, "x: x");
    for i in [0, 1, 2, 3, 5] {
        close(m[i], setup[i], &format!("x: [{i}]"));
    }
    // y alone: only the origin's y (down 0.5, gravity's balance).
    let m = posed("y");
    close(m[5], 19.5, "y: y");
    for i in [0, 1, 2, 3, 4] {
        close(m[i], setup[i], &format!("y: [{i}]"));
    }
    // rotate alone: the origin and the axes' lengths and right angle stay; gravity turns the
    // bone (pointing along +x) down.
    let m = posed("rotate");
    close(m[4], 10.0, "rotate: x");
    close(m[5], 20.0, "rotate: y");
    close(m[0].hypot(m[2]), 1.0, "rotate: x axis");
    close(m[1].hypot(m[3]), 1.0, "rotate: y axis");
    close(m[0] * m[1] + m[2] * m[3], 0.0, "rotate: axes at a right angle");
    assert!(deg(m[0], m[2]) < -1e-3, "rotate: {m:?}");
    // shearX alone: only the x axis turns (down), keeping its length; the y axis stays.
    let m = posed("shearX");
    close(m[4], 10.0, "shearX: x");
    close(m[5], 20.0, "shearX: y");
    close(m[0].hypot(m[2]), 1.0, "shearX: x axis");
    close(m[1], 0.0, "shearX: y axis x");
    close(m[3], 1.0, "shearX: y axis y");
    assert!(deg(m[0], m[2]) < -1e-3, "shearX: {m:?}");
    // scaleX alone: the wind along the bone stretches it; nothing else changes.
    let m = posed("scaleX");
    for i in [1, 2, 3, 4, 5] {
        close(m[i], setup[i], &format!("scaleX: [{i}]"));
    }
    assert!(m[0] > 1.0 + 1e-3, "scaleX: {m:?}");
    // None: nothing moves.
    let m = b(&play(&character(1.0, None, 0.0, damped(json!({"wind": 3, "gravity": 2}))), "still", 8.0, Some(60.0)));
    for i in 0..6 {
        close(m[i], setup[i], &format!("none: [{i}]"));
    }
}

#[test]
fn a_move_beyond_the_limit_has_no_greater_effect() {
    // Limit 600 units a second: 10 units in a 1/60 s frame. Jumps of 100 and 200 both exceed
    // it, so they leave the same offset: b stays exactly 100 apart in the two plays.
    let fields = json!({"x": 1, "y": 1, "limit": 600, "strength": 100, "damping": 0.9});
    let (small, big) = (character(1.0, None, 100.0, fields.clone()), character(1.0, None, 200.0, fields));
    for time in [0.6, 0.75, 1.0] {
        let (p, q) = (b(&play(&small, "jump", time, Some(60.0))), b(&play(&big, "jump", time, Some(60.0))));
        close(q[4] - p[4], 100.0, &format!("t {time}: x apart"));
        close(q[5], p[5], &format!("t {time}: y"));
    }
    // Without the limit binding, the bigger jump lags more.
    let free = json!({"x": 1, "y": 1, "strength": 100, "damping": 0.9});
    let (small, big) = (character(1.0, None, 100.0, free.clone()), character(1.0, None, 200.0, free));
    let (p, q) = (b(&play(&small, "jump", 0.6, Some(60.0))), b(&play(&big, "jump", 0.6, Some(60.0))));
    assert!((q[4] - p[4] - 100.0).abs() > 1.0, "{} {}", q[4], p[4]);
    // A limit of 0: no movement affects the physics; the bone follows the clip.
    let fields = json!({"x": 1, "y": 1, "limit": 0, "strength": 100, "damping": 0.9});
    let c = character(1.0, None, 100.0, fields);
    let (p, still) = (b(&play(&c, "jump", 0.6, Some(60.0))), b(&play(&c, "jump", 0.6, None)));
    close(p[4], still[4], "limit 0: x");
}

#[test]
fn the_step_is_the_constraint_s_fps_whatever_the_game_s_frame_rate() {
    // 32 steps a second (a step of 1/32 s, exact in binary), played at 32, 64 and 128 frames a
    // second: at 1 s each has taken the same 32 steps from the same still pose: the same bits.
    let c = character(1.0, None, 0.0, json!({"x": 1, "y": 1, "wind": 3, "gravity": 2, "fps": 32, "damping": 0.9}));
    let at = |game: f64| b(&play(&c, "still", 1.0, Some(game)));
    let (p, q, r) = (at(32.0), at(64.0), at(128.0));
    assert_eq!(p.map(f64::to_bits), q.map(f64::to_bits));
    assert_eq!(p.map(f64::to_bits), r.map(f64::to_bits));
    assert!((p[4] - 10.0).abs() > 1e-3, "{p:?}");
    // Before the first step (1/64 s in), the bone has not moved.
    let early = b(&play(&c, "still", 1.0 / 64.0, Some(64.0)));
    close(early[4], 10.0, "early x");
    close(early[5], 20.0, "early y");
    // At 16 steps a second the path differs (fewer, longer steps).
    let c16 = character(1.0, None, 0.0, json!({"x": 1, "y": 1, "wind": 3, "gravity": 2, "fps": 16, "damping": 0.9}));
    let s = b(&play(&c16, "still", 1.0, Some(64.0)));
    assert!((s[4] - p[4]).abs() > 1e-6, "{s:?} {p:?}");
}
