//! Transform constraint rules no reference vector covers (the four reference characters use
//! only world, absolute constraints), checked on small synthetic characters against world
//! transforms computed here by hand from the documented behaviour (within 1e-6).
//!
//! What Spine's public pages say (user guide "Transform constraints", the forum answer on its
//! Relative option, the JSON export format's `transform` constraint):
//! - the constraint copies the target bone's world rotation, translation, scale and/or shear
//!   to the constrained bones; each mix applies that part from 0 (none) to 1 (all the way);
//! - Local: the constrained bones' local transform is modified to match the target bone's
//!   local transform; unchecked, their world transform is modified instead;
//! - Relative: the constrained bones' transform is modified by adding the target bone's
//!   transform, so the result is relative to the bone's transform before the constraint (the
//!   forum: a bone at (−50, 50) with a target at (0, 0) stays at (−50, 50) + (0, 0));
//!   unchecked, the bone's own transform has no effect at mix 100;
//! - the offsets (`rotation`, `x`, `y`, `scaleX`, `scaleY`, `shearY`) adjust the result; the
//!   guide's uses include "simulate a bone having a different parent", so in the world the
//!   translation offset is a point in the target's frame and the rotation offset turns with
//!   the target as a child's rotation does (mirrored when the target is).
//!
//! Scale "added" relatively is ambiguous for a bone whose own scale is not 1 (multiplied by
//! the target's, or the target's change added); the tests keep the constrained bone's own
//! scale 1 where relative scale is checked.

use ikarus::character::{Character, PoseRequest, Posed};
use serde_json::{Value, json};

const TOL: f64 = 1e-6;

/// A world transform: `[a, b, c, d, x, y]` (x axis `(a, c)`, y axis `(b, d)`).
type M = [f64; 6];

/// A bone's local matrix (the notes' formula), degrees.
fn local(x: f64, y: f64, rot: f64, sx: f64, sy: f64, shy: f64) -> M {
    let (r, ry) = (rot.to_radians(), (rot + 90.0 + shy).to_radians());
    [r.cos() * sx, ry.cos() * sy, r.sin() * sx, ry.sin() * sy, x, y]
}

/// `p × l`: a child's world transform from its parent's and its local one.
fn child(p: &M, l: &M) -> M {
    [
        p[0] * l[0] + p[1] * l[2],
        p[0] * l[1] + p[1] * l[3],
        p[2] * l[0] + p[3] * l[2],
        p[2] * l[1] + p[3] * l[3],
        p[0] * l[4] + p[1] * l[5] + p[4],
        p[2] * l[4] + p[3] * l[5] + p[5],
    ]
}

/// The bones: `p` at (−10, 5) turned 20°; `b`, p's child at (5, 0) turned 10° (scale `bs`);
/// the target `t` at (30, 40) turned 30°, scaled (1.5, `ty`), sheared 20° on y.
fn bones(bs: [f64; 2], ty: f64) -> Value {
    json!([
        {"name": "root"},
        {"name": "p", "parent": "root", "x": -10, "y": 5, "rotation": 20},
        {"name": "b", "parent": "p", "x": 5, "length": 10, "rotation": 10, "scaleX": bs[0], "scaleY": bs[1]},
        {"name": "t", "parent": "root", "x": 30, "y": 40, "rotation": 30, "scaleX": 1.5, "scaleY": ty, "shearY": 20},
        {"name": "k", "parent": "b", "x": 10},
    ])
}

/// p's world transform.
fn p_world() -> M {
    local(-10.0, 5.0, 20.0, 1.0, 1.0, 0.0)
}

/// The target's world transform.
fn t_world() -> M {
    local(30.0, 40.0, 30.0, 1.5, 1.0, 20.0)
}

/// The setup pose of `bones` with one transform constraint on `b`, targeting `t`, fields `c`.
fn pose(bones: Value, c: Value) -> (Character, Posed) {
    let mut k = json!({"name": "c", "bones": ["b"], "target": "t"});
    k.as_object_mut().unwrap().extend(c.as_object().unwrap().clone());
    let file = json!({"skeleton": {"spine": "4.2.00"}, "bones": bones, "transform": [k]});
    let c = ikarus_edge::character::load(&file.to_string(), "rules.json").unwrap().character;
    let mut p = Posed::default();
    c.pose(&PoseRequest::default(), &mut p).unwrap();
    (c, p)
}

/// Asserts bone `name`'s world transform is `want`.
fn is(c: &Character, p: &Posed, name: &str, want: &M) {
    let i = c.bone_index(name).unwrap();
    let [a, b, cc, d] = p.matrix(i);
    let [x, y] = p.origin(i);
    let got = [a, b, cc, d, x, y];
    let off = got.iter().zip(want).map(|(g, w)| (g - w).abs()).fold(0.0, f64::max);
    assert!(off < TOL, "{name}: {got:?}, expected {want:?}");
}

/// A world transform with x axis at `rot`° of length `sx`, y axis at `rot + 90 + shy`° of
/// length `sy`, origin `(x, y)`.
fn world(x: f64, y: f64, rot: f64, sx: f64, sy: f64, shy: f64) -> M {
    local(x, y, rot, sx, sy, shy)
}

#[test]
fn world_absolute_matches_the_target_plus_offsets_in_its_frame() {
    // Every mix 1: rotation 30 + 15; origin the target's frame's point (10, 4); x axis the
    // target's 1.5 + 0.5, y axis its 1 − 0.25; the y axis at 90° + the target's 20° + 5°
    // from the x axis.
    let offsets = json!({"rotation": 15, "x": 10, "y": 4, "scaleX": 0.5, "scaleY": -0.25, "shearY": 5});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), offsets);
    let o = child(&t_world(), &[1.0, 0.0, 0.0, 1.0, 10.0, 4.0]);
    let want = world(o[4], o[5], 45.0, 2.0, 0.75, 25.0);
    is(&c, &p, "b", &want);
    // A child of b follows: k is 10 along b's x axis.
    is(&c, &p, "k", &child(&want, &local(10.0, 0.0, 0.0, 1.0, 1.0, 0.0)));
}

#[test]
fn world_absolute_mixes_move_part_of_the_way() {
    // b's world before: p's 20° + 10° = 30°, origin p's point (5, 0). Rotation half way to
    // the target's 30° + 60° = 90°: 60°; origin a quarter of the way along x, 3/4 along y to
    // the target's origin; x axis half way from 1 to 1.5; y axis and shear untouched.
    let mixes = json!({"rotation": 60, "mixRotate": 0.5, "mixX": 0.25, "mixY": 0.75, "mixScaleX": 0.5,
        "mixScaleY": 0, "mixShearY": 0});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), mixes);
    let b0 = child(&p_world(), &local(5.0, 0.0, 10.0, 1.0, 1.0, 0.0));
    let (x, y) = (b0[4] + (30.0 - b0[4]) * 0.25, b0[5] + (40.0 - b0[5]) * 0.75);
    is(&c, &p, "b", &world(x, y, 60.0, 1.25, 1.0, 0.0));
}

#[test]
fn world_relative_adds_the_target_s_world_transform() {
    // Rotation: b's 30° + the target's 30° + 15°; origin: b's + the target's (offsets 0);
    // x axis scaled by the target's 1.5 (b's own scale 1), y axis by its 1; b's y axis turned
    // by the target's shear 20° + 5°.
    let offsets = json!({"relative": true, "rotation": 15, "shearY": 5});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), offsets);
    let b0 = child(&p_world(), &local(5.0, 0.0, 10.0, 1.0, 1.0, 0.0));
    is(&c, &p, "b", &world(b0[4] + 30.0, b0[5] + 40.0, 75.0, 1.5, 1.0, 25.0));
    // The forum's example: a target at the origin leaves the bone where it was.
    let mut still = bones([1.0, 1.0], 1.0);
    still[3] = json!({"name": "t", "parent": "root"});
    let (c, p) = pose(still, json!({"relative": true}));
    is(&c, &p, "b", &b0);
}

#[test]
fn local_absolute_copies_the_target_s_local_transform() {
    // b's local becomes the target's local plus the offsets: at (30 + 10, 40 + 4) in p's
    // frame, turned 30° + 15°, scaled (1.5 + 0.5, 1 − 0.25), sheared 20° + 5°.
    let offsets = json!({"local": true, "rotation": 15, "x": 10, "y": 4, "scaleX": 0.5, "scaleY": -0.25,
        "shearY": 5});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), offsets);
    let want = child(&p_world(), &local(40.0, 44.0, 45.0, 2.0, 0.75, 25.0));
    is(&c, &p, "b", &want);
    is(&c, &p, "k", &child(&want, &local(10.0, 0.0, 0.0, 1.0, 1.0, 0.0)));
    // Half mixes: half way from b's own local values.
    let half = json!({"local": true, "rotation": 15, "x": 10, "y": 4, "mixRotate": 0.5, "mixX": 0.5,
        "mixScaleX": 0.5, "mixShearY": 0.5});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), half);
    let want = child(&p_world(), &local(22.5, 22.0, 27.5, 1.25, 1.0, 10.0));
    is(&c, &p, "b", &want);
    // mixY apart from mixX (a quarter of the way to 44), mixScaleY apart from mixScaleX
    // (all the way from 1 to the target's 1 + 0.5).
    let apart = json!({"local": true, "y": 4, "scaleY": 0.5, "mixRotate": 0, "mixX": 0, "mixY": 0.25,
        "mixScaleX": 0, "mixScaleY": 1, "mixShearY": 0});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), apart);
    let want = child(&p_world(), &local(5.0, 11.0, 10.0, 1.0, 1.5, 0.0));
    is(&c, &p, "b", &want);
}

#[test]
fn local_relative_adds_the_target_s_local_transform() {
    // b's local plus the target's local plus the offsets: at (5 + 30 + 10, 0 + 40 + 4),
    // turned 10° + 30° + 15°, x scale 1 × (1.5 + 0.5), shear 20° + 5°.
    let offsets = json!({"local": true, "relative": true, "rotation": 15, "x": 10, "y": 4, "scaleX": 0.5,
        "shearY": 5});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), offsets);
    is(&c, &p, "b", &child(&p_world(), &local(45.0, 44.0, 55.0, 2.0, 1.0, 25.0)));
    // Mix 0.5: half the target's values and offsets added.
    let half = json!({"local": true, "relative": true, "rotation": 15, "x": 10, "mixRotate": 0.5,
        "mixX": 0.5, "mixY": 0.5, "mixScaleX": 0, "mixShearY": 0});
    let (c, p) = pose(bones([1.0, 1.0], 1.0), half);
    is(&c, &p, "b", &child(&p_world(), &local(25.0, 20.0, 32.5, 1.0, 1.0, 0.0)));
}

#[test]
fn a_mirrored_target_turns_the_offsets_as_a_child_s() {
    // The target scaled (1, −1), unsheared: its world x axis is still at 30°, mirrored. A child
    // of it with local rotation 15° and position (10, 4) points at 30° − 15° = 15° and sits at
    // the target's frame's (10, 4): the world absolute constraint puts b's x axis and origin
    // there. (With a target scaled unevenly or sheared a child's direction is not its
    // rotation plus 15°; the rotation offset is an angle, not a direction in its frame.)
    let mut mirrored = bones([1.0, 1.0], 1.0);
    mirrored[3] = json!({"name": "t", "parent": "root", "x": 30, "y": 40, "rotation": 30, "scaleY": -1});
    let (c, p) = pose(mirrored, json!({"rotation": 15, "x": 10, "y": 4, "mixScaleX": 0, "mixShearY": 0}));
    let o = child(&local(30.0, 40.0, 30.0, 1.0, -1.0, 0.0), &local(10.0, 4.0, 15.0, 1.0, 1.0, 0.0));
    let i = c.bone_index("b").unwrap();
    let [a, _, cc, _] = p.matrix(i);
    let [x, y] = p.origin(i);
    let o_rot = o[2].atan2(o[0]).to_degrees();
    assert!((o_rot - 15.0).abs() < TOL);
    assert!((cc.atan2(a).to_degrees() - o_rot).abs() < TOL && (x - o[4]).abs() < TOL && (y - o[5]).abs() < TOL);
}

#[test]
fn a_mirrored_bone_keeps_its_mirror_and_points_its_x_axis_at_the_target_s() {
    // b scaled (1, −1): the world absolute constraint (rotation only) turns its x axis to the
    // target's 30° and keeps it mirrored (its y axis at 30° − 90°).
    let (c, p) = pose(bones([1.0, -1.0], 1.0), json!({"mixX": 0, "mixScaleX": 0, "mixShearY": 0}));
    let b0 = child(&p_world(), &local(5.0, 0.0, 10.0, 1.0, -1.0, 0.0));
    is(&c, &p, "b", &world(b0[4], b0[5], 30.0, 1.0, -1.0, 0.0));
    // Relative: its x axis turned by the target's 30° from its own 30°: 60°, still mirrored.
    let (c, p) = pose(
        bones([1.0, -1.0], 1.0),
        json!({"relative": true, "mixX": 0, "mixScaleX": 0,
        "mixShearY": 0}),
    );
    is(&c, &p, "b", &world(b0[4], b0[5], 60.0, 1.0, -1.0, 0.0));
}
