//! Path constraint rules no reference vector covers, checked on small synthetic characters
//! against answers computed here from the documented behaviour (within 1e-6).
//!
//! What Spine's public pages say (user guide "Path constraints" and "Paths", the JSON export
//! format's `path` constraint and path attachment):
//! - position mode: `fixed` places the first bone at a fixed distance along the path from its
//!   start, `percent` at that percentage of the total path length (the JSON stores 0..1);
//! - spacing mode: `length` adds `spacing` to each bone's length, `fixed` spaces the bones
//!   `spacing` apart, `percent` spaces them a percentage of the path length apart,
//!   `proportional` spaces them by a percentage of the path length shared out in proportion to
//!   the bones' lengths;
//! - rotate mode: `tangent` turns a bone to the path's tangent at its position, `chain` points
//!   each bone at the next one's position (the last bone, which has no next, at the point one
//!   more spacing on: ikarus's reading, the guide does not say),
//!   `chainScale` also scales a bone along its x axis so that its tip reaches the next bone;
//! - `rotation` (offset rotation) is added to each bone's rotation; the mixes apply the
//!   constraint partially (0 none, 1 fully) for rotation, x and y;
//! - a closed path joins the last knot to the first; an open path continues straight past its
//!   ends ("dashed lines at both ends ... useful when a path constraint position is less than 0%
//!   or greater than 100%");
//! - `constantSpeed` off: positions along the path are not arc lengths but spread over each
//!   curve's parameter, using `lengths` (the length up to the end of each curve);
//! - a weighted path's vertices follow several bones, each vertex the weighted sum of its
//!   bones' transformed points; an unweighted path's are in its slot bone's frame.
//!
//! Every path here is made of straight cubic curves whose control points are spread evenly
//! (knot, knot + 1/3, knot + 2/3, next knot), so the point at arc length `s` along a curve is
//! the knot plus `s` along the line, exactly, whichever way the arc length is measured.

use ikarus::character::{Character, PoseRequest, Posed};
use serde_json::{Value, json};

const TOL: f64 = 1e-6;

/// A character: `bones` after `root`, one slot `p` on `slot_bone` showing `path`, constraint `c`.
fn character(bones: Value, slot_bone: &str, path: Value, c: Value) -> Character {
    let mut all = vec![json!({"name": "root"})];
    all.extend(bones.as_array().unwrap().iter().cloned());
    let mut constraint = json!({"name": "c", "target": "p"});
    constraint.as_object_mut().unwrap().extend(c.as_object().unwrap().clone());
    let file = json!({
        "skeleton": {"spine": "4.2.00"},
        "bones": all,
        "slots": [{"name": "p", "bone": slot_bone, "attachment": "path"}],
        "skins": [{"name": "default", "attachments": {"p": {"path": path}}}],
        "path": [constraint],
    });
    ikarus_edge::character::load(&file.to_string(), "rules.json").unwrap().character
}

/// The setup pose (default skin).
fn pose(c: &Character) -> Posed {
    let mut p = Posed::default();
    c.pose(&PoseRequest { skin: c.default_skin(), ..PoseRequest::default() }, &mut p).unwrap();
    p
}

/// Asserts bone `name`'s world origin is `(x, y)` and its x axis points at `deg` degrees.
fn at(c: &Character, p: &Posed, name: &str, x: f64, y: f64, deg: f64) {
    let i = c.bone_index(name).unwrap();
    let [px, py] = p.origin(i);
    let turn = p.rotation(i).to_degrees() - deg;
    let turn = (turn - 360.0 * (turn / 360.0).round()).abs();
    assert!(
        (px - x).abs() < TOL && (py - y).abs() < TOL && turn < TOL,
        "{name}: at ({px}, {py}) turned {}°, expected ({x}, {y}) {deg}°",
        p.rotation(i).to_degrees()
    );
}

/// An open path through `knots`, each curve straight with evenly spread handles.
fn polyline(knots: &[[f64; 2]], closed: bool) -> Value {
    let n = knots.len();
    let lerp = |a: [f64; 2], b: [f64; 2], t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    let mut v = Vec::new();
    let mut lengths = Vec::new();
    let mut total = 0.0;
    for k in 0..n {
        let (prev, next) = (knots[(k + n - 1) % n], knots[(k + 1) % n]);
        let here = knots[k];
        // The in handle a third of the way back toward the previous knot, the out handle a
        // third of the way toward the next (at the open path's ends: mirrored, unused).
        let inh = if k == 0 && !closed { lerp(here, next, -1.0 / 3.0) } else { lerp(here, prev, 1.0 / 3.0) };
        let out = if k == n - 1 && !closed { lerp(here, prev, -1.0 / 3.0) } else { lerp(here, next, 1.0 / 3.0) };
        v.extend([inh[0], inh[1], here[0], here[1], out[0], out[1]]);
        if k + 1 < n || closed {
            total += (next[0] - here[0]).hypot(next[1] - here[1]);
            lengths.push(total);
        }
    }
    json!({"type": "path", "closed": closed, "lengths": lengths, "vertexCount": 3 * n, "vertices": v})
}

/// A straight path 100 long along the x axis of its slot bone.
fn straight() -> Value {
    polyline(&[[0.0, 0.0], [100.0, 0.0]], false)
}

/// The slot bone `frame`: at (20, 30), turned 90° (the path runs up from there), scaled `s`.
fn frame(s: f64) -> Value {
    json!({"name": "frame", "parent": "root", "x": 20, "y": 30, "rotation": 90, "scaleX": s, "scaleY": s})
}

#[test]
fn percent_position_is_that_share_of_the_path_s_world_length() {
    // The path is 100 long in its slot bone's frame, scaled 2: 200 in the world, going up from
    // (20, 30). Position 50 % is 100 along it; the bone turns to the tangent, straight up.
    let bones = json!([frame(2.0), {"name": "a", "parent": "root", "length": 10}]);
    let c = character(bones, "frame", straight(), json!({"bones": ["a"], "position": 0.5}));
    at(&c, &pose(&c), "a", 20.0, 130.0, 90.0);
}

#[test]
fn fixed_position_is_a_distance_from_the_path_s_start() {
    let bones = json!([frame(1.0), {"name": "a", "parent": "root", "length": 10}]);
    let c = character(bones, "frame", straight(), json!({"bones": ["a"], "positionMode": "fixed", "position": 25}));
    at(&c, &pose(&c), "a", 20.0, 55.0, 90.0);
}

/// Three bones (lengths 20, 30, 10, siblings under the root, setup rotation 17° to be turned
/// away) on the straight path along the world x axis from the root.
fn three(c: Value) -> (Character, Posed) {
    let bones = json!([
        {"name": "a", "parent": "root", "length": 20, "rotation": 17},
        {"name": "b", "parent": "root", "length": 30, "rotation": 17},
        {"name": "d", "parent": "root", "length": 10, "rotation": 17},
    ]);
    let mut k = json!({"bones": ["a", "b", "d"], "positionMode": "fixed", "position": 5});
    k.as_object_mut().unwrap().extend(c.as_object().unwrap().clone());
    let c = character(bones, "root", straight(), k);
    let p = pose(&c);
    (c, p)
}

#[test]
fn fixed_spacing_puts_the_bones_that_far_apart() {
    let (c, p) = three(json!({"spacingMode": "fixed", "spacing": 10}));
    for (name, x) in [("a", 5.0), ("b", 15.0), ("d", 25.0)] {
        at(&c, &p, name, x, 0.0, 0.0);
    }
}

#[test]
fn length_spacing_adds_the_spacing_to_each_bone_s_length() {
    // a at 5; b after a's 20 + 4; d after b's 30 + 4.
    let (c, p) = three(json!({"spacingMode": "length", "spacing": 4}));
    for (name, x) in [("a", 5.0), ("b", 29.0), ("d", 63.0)] {
        at(&c, &p, name, x, 0.0, 0.0);
    }
}

#[test]
fn percent_spacing_is_a_share_of_the_path_s_length() {
    let (c, p) = three(json!({"spacingMode": "percent", "spacing": 0.15}));
    for (name, x) in [("a", 5.0), ("b", 20.0), ("d", 35.0)] {
        at(&c, &p, name, x, 0.0, 0.0);
    }
}

#[test]
fn proportional_spacing_shares_the_spacing_by_the_bones_lengths() {
    // spacing 60 % of 100 = 60, shared 20 : 30 : 10 (the lengths add to 60): a's space 20,
    // b's 30.
    let (c, p) = three(json!({"spacingMode": "proportional", "spacing": 0.6}));
    for (name, x) in [("a", 5.0), ("b", 25.0), ("d", 55.0)] {
        at(&c, &p, name, x, 0.0, 0.0);
    }
    // 90 % of 100 = 90, three halves of each length.
    let (c, p) = three(json!({"spacingMode": "proportional", "spacing": 0.9}));
    for (name, x) in [("a", 5.0), ("b", 35.0), ("d", 80.0)] {
        at(&c, &p, name, x, 0.0, 0.0);
    }
}

/// The path along x from the root to (100, 0), then up to (100, 50).
fn corner() -> Value {
    polyline(&[[0.0, 0.0], [100.0, 0.0], [100.0, 50.0]], false)
}

#[test]
fn tangent_chain_and_chain_scale_turn_as_documented() {
    let bones = json!([
        {"name": "a", "parent": "root", "length": 10},
        {"name": "b", "parent": "root", "length": 10},
    ]);
    let k = |mode: &str| {
        json!({"bones": ["a", "b"], "positionMode": "fixed", "position": 90,
        "spacingMode": "fixed", "spacing": 20, "rotateMode": mode})
    };
    // a at 90 (on the first leg), b at 110 (10 up the second leg).
    let c = character(bones.clone(), "root", corner(), k("tangent"));
    let p = pose(&c);
    at(&c, &p, "a", 90.0, 0.0, 0.0);
    at(&c, &p, "b", 100.0, 10.0, 90.0);
    // chain: a points at b's origin (45°); b at the point one more spacing on, 130: (100, 30),
    // straight up.
    let c = character(bones.clone(), "root", corner(), k("chain"));
    let p = pose(&c);
    at(&c, &p, "a", 90.0, 0.0, 45.0);
    at(&c, &p, "b", 100.0, 10.0, 90.0);
    // Chain leaves the bones' scale alone.
    let [ma, _, mc, _] = p.matrix(c.bone_index("a").unwrap());
    assert!((ma.hypot(mc) - 1.0).abs() < TOL, "{ma} {mc}");
    // chainScale: as chain, and each x axis stretched so the tip reaches the next point: a's
    // 10 long bone spans √200, b's spans 20.
    let c = character(bones, "root", corner(), k("chainScale"));
    let p = pose(&c);
    at(&c, &p, "a", 90.0, 0.0, 45.0);
    at(&c, &p, "b", 100.0, 10.0, 90.0);
    for (name, want) in [("a", 200f64.sqrt() / 10.0), ("b", 2.0)] {
        let i = c.bone_index(name).unwrap();
        let [ma, mb, mc, md] = p.matrix(i);
        assert!((ma.hypot(mc) - want).abs() < TOL, "{name}: x axis {}", ma.hypot(mc));
        assert!((mb.hypot(md) - 1.0).abs() < TOL, "{name}: y axis {}", mb.hypot(md));
        let [x, y] = p.origin(i);
        let tip = p.tip(i);
        assert!((tip[0] - x - 10.0 * ma).abs() < TOL && (tip[1] - y - 10.0 * mc).abs() < TOL);
    }
    // a's tip is on b's origin.
    let tip = p.tip(c.bone_index("a").unwrap());
    assert!((tip[0] - 100.0).abs() < TOL && (tip[1] - 10.0).abs() < TOL, "{tip:?}");
}

#[test]
fn the_offset_rotation_is_added_and_the_mixes_apply_part_of_the_move() {
    // The path goes up from (20, 30); the bone starts at the root, unturned.
    let bones = json!([frame(1.0), {"name": "a", "parent": "root", "length": 10}]);
    let c = character(bones.clone(), "frame", straight(), json!({"bones": ["a"], "position": 0.5, "rotation": 30}));
    at(&c, &pose(&c), "a", 20.0, 80.0, 120.0);
    // Half the turn to 90°, a quarter of the way along x to 20, three quarters along y to 80.
    let mixes = json!({"bones": ["a"], "position": 0.5, "mixRotate": 0.5, "mixX": 0.25, "mixY": 0.75});
    let c = character(bones.clone(), "frame", straight(), mixes);
    at(&c, &pose(&c), "a", 5.0, 60.0, 45.0);
    // mixY defaults to mixX.
    let c = character(bones, "frame", straight(), json!({"bones": ["a"], "position": 0.5, "mixX": 0.25}));
    at(&c, &pose(&c), "a", 5.0, 20.0, 90.0);
}

#[test]
fn a_closed_path_wraps_around() {
    // A square 100 a side, counter-clockwise from the root: 400 around. The first bone at 390
    // is 10 before the start on the last side (going down the y axis); the second, 20 on, is
    // 10 along the first side.
    let square = polyline(&[[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]], true);
    let bones = json!([
        {"name": "a", "parent": "root", "length": 10},
        {"name": "b", "parent": "root", "length": 10},
    ]);
    let k =
        json!({"bones": ["a", "b"], "positionMode": "fixed", "position": 390, "spacingMode": "fixed", "spacing": 20});
    let c = character(bones.clone(), "root", square.clone(), k);
    let p = pose(&c);
    at(&c, &p, "a", 0.0, 10.0, -90.0);
    at(&c, &p, "b", 10.0, 0.0, 0.0);
    // Percent 0.6: 240 around, 40 along the third side (going toward −x).
    let c = character(bones, "root", square, json!({"bones": ["a"], "position": 0.6}));
    at(&c, &pose(&c), "a", 60.0, 100.0, 180.0);
}

#[test]
fn an_open_path_continues_straight_past_its_ends() {
    let bones = json!([{"name": "a", "parent": "root", "length": 10}]);
    for (position, x, y) in [(1.2, 100.0, 80.0), (-0.1, -15.0, 0.0)] {
        let c = character(bones.clone(), "root", corner(), json!({"bones": ["a"], "position": position}));
        // 150 long: 120 % is 30 past the top end, going up; −10 % is 15 before the start.
        let deg = if position > 1.0 { 90.0 } else { 0.0 };
        at(&c, &pose(&c), "a", x, y, deg);
    }
}

#[test]
fn without_constant_speed_a_position_is_a_curve_parameter_by_lengths() {
    // One straight curve from 0 to 100 with both handles near the start (10 and 20): its
    // parameter t is at x(t) = 30t(1 − t)² + 60t²(1 − t) + 100t³, not at 100t. Without
    // constant speed, fixed position 50 of `lengths` [100] is t = 0.5: x = 23.75. With it, the
    // arc length 50 (the guide: "more accurate", not exact; as the runtime measures it, see
    // `spline.rs`: the curve cut in ten chords at t = 0.1, 0.2, …, the distance found on its
    // chord and t walked proportionally along that chord): near 50.
    let bunched = |constant: bool| {
        json!({"type": "path", "constantSpeed": constant, "lengths": [100], "vertexCount": 6,
            "vertices": [-10, 0, 0, 0, 10, 0, 20, 0, 100, 0, 110, 0]})
    };
    let bones = json!([{"name": "a", "parent": "root", "length": 10}]);
    let k = json!({"bones": ["a"], "positionMode": "fixed", "position": 50});
    let c = character(bones.clone(), "root", bunched(false), k.clone());
    let t: f64 = 0.5;
    let x = 30.0 * t * (1.0 - t).powi(2) + 60.0 * t * t * (1.0 - t) + 100.0 * t.powi(3);
    at(&c, &pose(&c), "a", x, 0.0, 0.0);
    let c = character(bones.clone(), "root", bunched(true), k);
    let xt = |t: f64| 30.0 * t * (1.0 - t).powi(2) + 60.0 * t * t * (1.0 - t) + 100.0 * t.powi(3);
    // x(t) grows with t, so the chords end at x(0.1), x(0.2), …: the chord holding 50 is the
    // one whose end passes it, and t goes proportionally along it.
    let j = (1..=10).find(|&j| xt(j as f64 / 10.0) >= 50.0).unwrap() as f64;
    let (lo, hi) = (xt((j - 1.0) / 10.0), xt(j / 10.0));
    let x = xt((j - 1.0 + (50.0 - lo) / (hi - lo)) / 10.0);
    assert!((x - 50.0).abs() < 1.0 && (x - 50.0).abs() > 0.1, "{x}");
    at(&c, &pose(&c), "a", x, 0.0, 0.0);
    // The corner path with `lengths` that are not its own: [100, 150] says the second curve
    // is 50 long, so 125 is its middle (100, 25) however long it really is; percent 0.5 of
    // the last length, 75, is 3/4 of the way along the first curve.
    let mut path = polyline(&[[0.0, 0.0], [100.0, 0.0], [100.0, 80.0]], false);
    path["constantSpeed"] = json!(false);
    path["lengths"] = json!([100, 150]);
    let c = character(
        bones.clone(),
        "root",
        path.clone(),
        json!({"bones": ["a"], "positionMode": "fixed", "position": 125}),
    );
    at(&c, &pose(&c), "a", 100.0, 40.0, 90.0);
    let c = character(bones, "root", path, json!({"bones": ["a"], "position": 0.5}));
    at(&c, &pose(&c), "a", 75.0, 0.0, 0.0);
}

#[test]
fn a_weighted_path_follows_the_weighted_sum_of_its_bones() {
    // Each vertex: bone l (the origin, unturned) with the point (x, 0) weighted 1/4, bone r
    // (at (0, 20), turned 90°) with the point (0, −(x + 8)) weighted 3/4: r puts it at
    // (x + 8, 20). The path is the line y = 15 from x = 6 to 106; half way is (56, 15).
    let bones = json!([
        {"name": "l", "parent": "root"},
        {"name": "r", "parent": "root", "y": 20, "rotation": 90},
        {"name": "a", "parent": "root", "length": 10},
    ]);
    let xs = [-100.0 / 3.0, 0.0, 100.0 / 3.0, 200.0 / 3.0, 100.0, 400.0 / 3.0];
    let mut v = Vec::new();
    for x in xs {
        // Two bones: l (bone 1 of the file's list) and r (bone 2), each point and weight.
        v.extend([2.0, 1.0, x, 0.0, 0.25, 2.0, 0.0, -(x + 8.0), 0.75]);
    }
    let path = json!({"type": "path", "lengths": [100], "vertexCount": 6, "vertices": v});
    let c = character(bones, "root", path, json!({"bones": ["a"], "position": 0.5}));
    at(&c, &pose(&c), "a", 56.0, 15.0, 0.0);
}

#[test]
fn bones_in_a_chain_each_follow_the_path_and_carry_their_children() {
    // a → b → e, each 10 long, on the upward path from (20, 30) with length spacing 0: at
    // 30, 40, 50 up it, all turned 90°; f, e's child 5 along its x axis, follows e.
    let bones = json!([
        frame(1.0),
        {"name": "a", "parent": "root", "length": 10, "rotation": -40},
        {"name": "b", "parent": "a", "length": 10, "x": 10, "rotation": 25},
        {"name": "e", "parent": "b", "length": 10, "x": 10, "rotation": 5},
        {"name": "f", "parent": "e", "x": 5},
    ]);
    let k = json!({"bones": ["a", "b", "e"], "positionMode": "fixed", "position": 30, "rotateMode": "chain"});
    let c = character(bones, "frame", straight(), k);
    let p = pose(&c);
    for (name, y) in [("a", 60.0), ("b", 70.0), ("e", 80.0), ("f", 85.0)] {
        at(&c, &p, name, 20.0, y, 90.0);
    }
}
