use super::*;
use std::f64::consts::PI;

fn local(x: f64, y: f64, r: f64, sx: f64, sy: f64) -> LocalTransform {
    LocalTransform { x, y, rotation: r, scale_x: sx, scale_y: sy, shear_x: 0.0, shear_y: 0.0 }
}

fn close(a: f64, b: f64) {
    assert!((a - b).abs() < 1e-12, "{a} vs {b}");
}

fn parent() -> Affine {
    // Rotated 0.7, scaled 2 along its x and 3 along its y, mirrored by a negative y scale.
    world_transform(&local(5.0, -1.0, 0.7, 2.0, -3.0), Inherit::Normal, None, Placement::default())
}

#[test]
fn the_memo_gives_the_bits_of_sin_cos() {
    assert_eq!(Trig::ZERO, {
        let (sin, cos) = math::sin_cos(0.0);
        Trig { arg: [0.0; 2], sin: [sin; 2], cos: [cos; 2] }
    });
    let mut memo = Trig::ZERO;
    for x in [0.3, 0.3, -0.0, 0.0, 1e22, 0.3, -2.5, -2.5, 0.3, -2.5, 0.3, 7.0, 1e22] {
        let (s, c) = math::sin_cos(x);
        let (ms, mc) = memo.sin_cos(x);
        assert_eq!((ms.to_bits(), mc.to_bits()), (s.to_bits(), c.to_bits()), "{x}");
    }
    // Every mode, with a memo warmed on other transforms: the same bits as without one.
    let p = parent();
    let mut trig = [Trig::ZERO; 3];
    for mode in Inherit::ALL {
        for t in [local(1.0, 2.0, 0.3, 1.5, 0.5), local(1.0, 2.0, 0.3, 1.5, 0.5), local(0.0, 1.0, -1.1, 1.0, 2.0)] {
            let a = world_transform_memo(&t, mode, Some(&p), Placement::default(), &mut trig);
            let b = world_transform(&t, mode, Some(&p), Placement::default());
            assert_eq!(format!("{a:?}"), format!("{b:?}"));
        }
    }
}

#[test]
fn normal_is_the_product_of_the_parent_and_the_local_matrix() {
    let p = parent();
    let t = local(1.0, 2.0, 0.3, 1.5, 0.5);
    let w = world_transform(&t, Inherit::Normal, Some(&p), Placement::default());
    let [x, y] = p.to_world(1.0, 2.0);
    close(w.x, x);
    close(w.y, y);
    close(w.det(), p.det() * 0.75);
    // The direction of the x axis is the parent's x direction turned by the local
    // rotation, as seen through the parent's matrix.
    let [u, v] = p.apply(math::cos(0.3), math::sin(0.3));
    close(w.rotation(), math::atan2(v, u));
}

#[test]
fn only_translation_keeps_the_local_rotation_and_scale() {
    let p = parent();
    let t = local(1.0, 2.0, 0.3, 1.5, 0.5);
    let w = world_transform(&t, Inherit::OnlyTranslation, Some(&p), Placement::default());
    close(w.rotation(), 0.3);
    close(math::hypot(w.a, w.c), 1.5);
    close(math::hypot(w.b, w.d), 0.5);
    close(w.x, p.to_world(1.0, 2.0)[0]);
}

#[test]
fn no_scale_keeps_unit_axes_and_the_normal_direction() {
    let p = parent();
    let t = local(1.0, 2.0, 0.3, 1.0, 1.0);
    let normal = world_transform(&t, Inherit::Normal, Some(&p), Placement::default());
    for mode in [Inherit::NoScale, Inherit::NoScaleOrReflection] {
        let w = world_transform(&t, mode, Some(&p), Placement::default());
        close(math::hypot(w.a, w.c), 1.0);
        close(math::hypot(w.b, w.d), 1.0);
        close(w.rotation(), normal.rotation());
        // The parent is mirrored: noScale keeps the reflection, noScaleOrReflection not.
        close(w.det(), if mode == Inherit::NoScale { -1.0 } else { 1.0 });
    }
}

#[test]
fn no_rotation_or_reflection_keeps_the_scale_not_the_turn() {
    let p = parent();
    let t = local(1.0, 2.0, 0.3, 1.0, 1.0);
    let w = world_transform(&t, Inherit::NoRotationOrReflection, Some(&p), Placement::default());
    // Area scale is the parent's, without the reflection.
    close(w.det(), 6.0);
    // An unscaled, unrotated parent leaves the local rotation alone.
    let q = world_transform(&local(0.0, 0.0, 0.0, 1.0, 1.0), Inherit::Normal, None, Placement::default());
    let turned = world_transform(&local(0.0, 0.0, 1.2, 1.0, 1.0), Inherit::Normal, Some(&q), Placement::default());
    let w = world_transform(&t, Inherit::NoRotationOrReflection, Some(&turned), Placement::default());
    close(w.rotation(), 0.3);
    // A uniformly scaled parent scales the bone but leaves its rotation.
    let big = world_transform(&local(0.0, 0.0, 1.2, 2.0, 2.0), Inherit::Normal, None, Placement::default());
    let w = world_transform(&t, Inherit::NoRotationOrReflection, Some(&big), Placement::default());
    close(w.rotation(), 0.3);
    close(math::hypot(w.a, w.c), 2.0);
}

#[test]
fn a_negative_skeleton_scale_mirrors_everything() {
    let mirrored = Placement { position: [3.0, 4.0], scale: [-1.0, 1.0] };
    let t = local(1.0, 2.0, 0.3, 1.0, 1.0);
    let root = world_transform(&t, Inherit::Normal, None, mirrored);
    close(root.x, 2.0);
    close(root.y, 6.0);
    close(root.rotation(), PI - 0.3);
    close(root.det(), -1.0);
    for mode in Inherit::ALL {
        let w = world_transform(&t, mode, Some(&root), mirrored);
        let plain = world_transform(
            &t,
            mode,
            Some(&world_transform(&t, Inherit::Normal, None, Placement::default())),
            Placement::default(),
        );
        // Mirroring the skeleton mirrors every bone about the skeleton's origin.
        close(w.x - 3.0, -(plain.x));
        close(w.y - 4.0, plain.y);
        close(w.a, -plain.a);
        close(w.c, plain.c);
    }
}
