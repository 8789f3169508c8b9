use super::*;
use crate::character::world_transform;
use crate::character::{Inherit, Placement};
use crate::math;

fn close(a: f64, b: f64) {
    assert!((a - b).abs() < 1e-12, "{a} vs {b}");
}

fn deg(d: f64) -> f64 {
    d.to_radians()
}

fn local(x: f64, y: f64, r: f64, sx: f64, sy: f64, shy: f64) -> LocalTransform {
    LocalTransform { x, y, rotation: deg(r), scale_x: sx, scale_y: sy, shear_x: 0.0, shear_y: deg(shy) }
}

fn at(t: LocalTransform) -> Affine {
    world_transform(&t, Inherit::Normal, None, Placement::default())
}

fn only(f: impl FnOnce(&mut TransformSettings)) -> TransformSettings {
    let mut m = TransformSettings {
        mix_rotate: 0.0,
        mix_x: 0.0,
        mix_y: 0.0,
        mix_scale_x: 0.0,
        mix_scale_y: 0.0,
        mix_shear_y: 0.0,
    };
    f(&mut m);
    m
}

#[test]
fn world_absolute_rotation_turns_toward_the_target_plus_the_offset_by_the_mix() {
    let bone = at(local(1.0, 2.0, 10.0, 2.0, 1.0, 0.0));
    let target = at(local(5.0, 5.0, 80.0, 1.0, 1.0, 0.0));
    let o = TransformOffsets { rotation: deg(20.0), ..TransformOffsets::default() };
    let w = world_absolute(&bone, &target, &o, &only(|m| m.mix_rotate = 0.5));
    // 10° + (80° + 20° − 10°)·0.5 = 55°, the axes' lengths and the origin kept.
    close(w.rotation(), deg(55.0));
    close(math::hypot(w.a, w.c), 2.0);
    close(w.det(), bone.det());
    assert_eq!((w.x, w.y), (bone.x, bone.y));
    // The difference is wrapped: from 170° toward −170° is +20°, not −340°.
    let bone = at(local(0.0, 0.0, 170.0, 1.0, 1.0, 0.0));
    let target = at(local(0.0, 0.0, -170.0, 1.0, 1.0, 0.0));
    let w = world_absolute(&bone, &target, &TransformOffsets::default(), &only(|m| m.mix_rotate = 0.5));
    close(w.rotation(), deg(180.0));
}

#[test]
fn world_absolute_translation_moves_toward_the_targets_point() {
    let bone = at(local(0.0, 0.0, 0.0, 1.0, 1.0, 0.0));
    // The target at (10, 0), turned 90°: its point (1, 2) is at (8, 1) in the world.
    let target = at(local(10.0, 0.0, 90.0, 1.0, 1.0, 0.0));
    let o = TransformOffsets { x: 1.0, y: 2.0, ..TransformOffsets::default() };
    let w = world_absolute(&bone, &target, &o, &only(|m| (m.mix_x, m.mix_y) = (1.0, 0.5)));
    close(w.x, 8.0);
    close(w.y, 0.5);
    // A mix of −1 moves away by as much.
    let w = world_absolute(&bone, &target, &o, &only(|m| (m.mix_x, m.mix_y) = (-1.0, -1.0)));
    close(w.x, -8.0);
    close(w.y, -1.0);
    close(w.rotation(), 0.0);
}

#[test]
fn world_absolute_scale_moves_each_axis_length_toward_the_targets_plus_the_offset() {
    let bone = at(local(0.0, 0.0, 30.0, 2.0, 4.0, 0.0));
    let target = at(local(0.0, 0.0, -60.0, 3.0, 1.0, 0.0));
    let o = TransformOffsets { scale_x: 0.5, scale_y: -0.5, ..TransformOffsets::default() };
    let w = world_absolute(&bone, &target, &o, &only(|m| (m.mix_scale_x, m.mix_scale_y) = (0.5, 1.0)));
    // x: 2 + (3 − 2 + 0.5)·0.5 = 2.75; y: 4 + (1 − 4 − 0.5)·1 = 0.5; directions kept.
    close(math::hypot(w.a, w.c), 2.75);
    close(math::hypot(w.b, w.d), 0.5);
    close(w.rotation(), deg(30.0));
    close(math::atan2(w.d, w.b), deg(120.0));
}

#[test]
fn world_absolute_shear_turns_the_y_axis_to_the_targets_skew_plus_the_offset() {
    let bone = at(local(0.0, 0.0, 20.0, 1.0, 3.0, 0.0));
    // The target's y axis is 90° + 30° from its x axis.
    let target = at(local(0.0, 0.0, 45.0, 1.0, 1.0, 30.0));
    let o = TransformOffsets { shear_y: deg(-10.0), ..TransformOffsets::default() };
    let w = world_absolute(&bone, &target, &o, &only(|m| m.mix_shear_y = 0.5));
    // The bone's y axis at 20° + 90° turns by (30° − 10°)·0.5 = 10°, its length kept.
    close(math::atan2(w.d, w.b), deg(120.0));
    close(math::hypot(w.b, w.d), 3.0);
    close(w.rotation(), deg(20.0));
}

#[test]
fn a_mirrored_target_turns_the_angle_offsets_around() {
    let bone = at(local(0.0, 0.0, 0.0, 1.0, 1.0, 0.0));
    let target = at(local(0.0, 0.0, 0.0, 1.0, -1.0, 0.0));
    let o = TransformOffsets { rotation: deg(30.0), ..TransformOffsets::default() };
    let w = world_absolute(&bone, &target, &o, &only(|m| m.mix_rotate = 1.0));
    close(w.rotation(), deg(-30.0));
}

#[test]
fn world_relative_adds_the_targets_values() {
    let bone = at(local(1.0, 1.0, 10.0, 2.0, 1.0, 0.0));
    let target = at(local(3.0, 4.0, 30.0, 1.5, 1.0, 0.0));
    let o = TransformOffsets { rotation: deg(5.0), ..TransformOffsets::default() };
    let all = TransformSettings { mix_shear_y: 0.0, ..TransformSettings::default() };
    let w = world_relative(&bone, &target, &o, &all);
    close(w.rotation(), deg(45.0));
    close(w.x, 4.0);
    close(w.y, 5.0);
    close(math::hypot(w.a, w.c), 3.0);
    close(math::hypot(w.b, w.d), 1.0);
}

#[test]
fn local_variants_move_toward_or_add_the_targets_local_values() {
    let b = local(1.0, 2.0, 10.0, 2.0, 1.0, 5.0);
    let t = local(5.0, -2.0, 50.0, 4.0, 3.0, 25.0);
    let o = TransformOffsets { rotation: deg(10.0), x: 1.0, ..TransformOffsets::default() };
    let half = TransformSettings::from_array([0.5; 6]);
    let a = local_absolute(&b, &t, &o, &half);
    close(a.rotation, deg(35.0));
    close(a.x, 3.5);
    close(a.y, 0.0);
    close(a.scale_x, 3.0);
    close(a.scale_y, 2.0);
    close(a.shear_y, deg(15.0));
    let r = local_relative(&b, &t, &o, &half);
    close(r.rotation, deg(40.0));
    close(r.x, 4.0);
    close(r.scale_x, 2.0 * 2.5);
    close(r.scale_y, 2.0);
    close(r.shear_y, deg(17.5));
    // Mixes of 0 change nothing.
    let none = TransformSettings::from_array([0.0; 6]);
    assert_eq!(local_absolute(&b, &t, &o, &none), b);
    assert_eq!(world_absolute(&at(b), &at(t), &o, &none), at(b));
}
