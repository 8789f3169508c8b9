//! A bone's applied local transform recomputed from a world transform a constraint set
//! directly (transform, path and physics constraints work in world space, as Spine's runtime
//! does): the local transform that, below the bone's parent and with its inherit mode, gives
//! that world transform again, so that the bones below it and any later constraint that reads
//! local values see the constrained bone.
//!
//! The world matrix is `F·L` (times the skeleton's scale for the modes that drop the parent's)
//! where `F` is the frame the bone's local matrix `L` is multiplied into: the parent's matrix
//! (`normal`), the skeleton's scale (`onlyTranslation`), the parent's matrix without its
//! rotation (`noRotationOrReflection`, with that rotation added back to the angle), or the
//! parent's rotation along the bone's current local rotation (`noScale`,
//! `noScaleOrReflection`: exact while the constraint leaves the direction the frame is built
//! from, an approximation otherwise). `L` is decomposed keeping the bone's shear along x:
//! rotation `atan2(c, a) − shearX`, scale x `hypot(a, c)`, scale y `±hypot(b, d)` (the sign of
//! the determinant) and the shear along y that turns the y axis where it is.

use super::flat::ROOT;
use super::world::{Affine, Bones, aim_frame, world_transform};
use super::{Inherit, LocalTransform, Placement};
use crate::math;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The local transform giving world transform `w` below `parent` (`None`: a root) with
/// `inherit`; `current` is the bone's local transform before (its rotation builds the frame of
/// the `noScale` modes).
pub(crate) fn local_from_world(
    w: &Affine,
    current: &LocalTransform,
    inherit: Inherit,
    parent: Option<&Affine>,
    placement: Placement,
) -> LocalTransform {
    let root = Affine::of_placement(placement);
    let p = parent.unwrap_or(&root);
    let [x, y] = p.to_local(w.x, w.y).unwrap_or([current.x, current.y]);
    let (frame, theta) = match (parent, inherit) {
        (None, _) | (Some(_), Inherit::Normal) => (*p, 0.0),
        (Some(_), Inherit::OnlyTranslation) => (root, 0.0),
        (Some(q), Inherit::NoRotationOrReflection) => aim_frame(inherit, q, placement),
        (Some(q), Inherit::NoScale | Inherit::NoScaleOrReflection) => {
            // The frame of the current rotation: the world transform of the bone turned to
            // its current rotation with unit scale and no shear, less that rotation.
            let unit =
                LocalTransform { x: 0.0, y: 0.0, scale_x: 1.0, scale_y: 1.0, shear_x: 0.0, shear_y: 0.0, ..*current };
            let z = world_transform(&unit, inherit, Some(q), placement);
            let (s, c) = math::sin_cos(current.rotation);
            let undo = Affine { a: c, b: s, c: -s, d: c, x: 0.0, y: 0.0 };
            (z.times(&undo), 0.0)
        }
    };
    let Some(m) = inverse_linear(&frame).map(|f| f.times(&Affine { x: 0.0, y: 0.0, ..*w })) else {
        return LocalTransform { x, y, ..*current };
    };
    // The x axis's angle is the rotation plus the shear along x, which is kept.
    let rotation = math::atan2(m.c, m.a) - current.shear_x;
    let scale_x = math::hypot(m.a, m.c);
    let det = m.det();
    let sign = if det < 0.0 { -1.0 } else { 1.0 };
    let scale_y = sign * math::hypot(m.b, m.d);
    let shear_y = wrap(math::atan2(sign * m.d, sign * m.b) - rotation - FRAC_PI_2);
    LocalTransform { x, y, rotation: rotation + theta, scale_x, scale_y, shear_x: current.shear_x, shear_y }
}

/// The inverse of `f`'s matrix (no translation), `None` when singular.
fn inverse_linear(f: &Affine) -> Option<Affine> {
    let det = f.det();
    (det != 0.0 && det.is_finite()).then(|| Affine {
        a: f.d / det,
        b: -f.b / det,
        c: -f.c / det,
        d: f.a / det,
        x: 0.0,
        y: 0.0,
    })
}

/// An angle wrapped into `(−π, π]`.
fn wrap(a: f64) -> f64 {
    let r = a - TAU * ((a + PI) / TAU).floor();
    if r == -PI { PI } else { r }
}

impl Bones<'_> {
    /// Sets bone `i`'s world transform to `w` and its local transform to the applied one that
    /// gives it ([`local_from_world`]). The bones below are not updated.
    pub(crate) fn set_world(&mut self, i: usize, w: Affine) {
        let link = self.links[i];
        let parent = (link.parent != ROOT).then(|| self.world[link.parent as usize]);
        self.local[i] = local_from_world(&w, &self.local[i], link.inherit, parent.as_ref(), self.placement);
        self.world[i] = w;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    fn random_local(rng: &mut SplitMix64) -> LocalTransform {
        LocalTransform {
            x: rng.range(-5.0, 5.0),
            y: rng.range(-5.0, 5.0),
            rotation: rng.range(-3.0, 3.0),
            scale_x: rng.range(0.3, 2.0) * if rng.chance(0.2) { -1.0 } else { 1.0 },
            scale_y: rng.range(0.3, 2.0) * if rng.chance(0.2) { -1.0 } else { 1.0 },
            shear_x: if rng.chance(0.5) { 0.0 } else { rng.range(-0.5, 0.5) },
            shear_y: if rng.chance(0.5) { 0.0 } else { rng.range(-0.5, 0.5) },
        }
    }

    fn close(a: &Affine, b: &Affine, tol: f64) -> bool {
        [a.a - b.a, a.b - b.b, a.c - b.c, a.d - b.d, a.x - b.x, a.y - b.y].iter().all(|d| d.abs() < tol)
    }

    #[test]
    fn the_applied_transform_gives_the_world_transform_back() {
        // Random parents, local transforms and placements: the world transform of the local
        // transform recomputed from a world transform is that world transform, for every mode
        // whose frame does not depend on the rotation, and for the noScale modes where the
        // world matrix came from a local one (the frame is then the one it was made in).
        let mut rng = SplitMix64(39);
        for round in 0..2000 {
            let placement = if round % 4 == 0 {
                Placement { position: [2.0, -1.0], scale: [-1.5, 0.75] }
            } else {
                Placement::default()
            };
            let parent = world_transform(&random_local(&mut rng), Inherit::Normal, None, placement);
            let inherit = Inherit::ALL[round % 5];
            let local = random_local(&mut rng);
            let w = world_transform(&local, inherit, Some(&parent), placement);
            let back = local_from_world(&w, &local, inherit, Some(&parent), placement);
            let again = world_transform(&back, inherit, Some(&parent), placement);
            assert!(close(&again, &w, 1e-9), "{inherit:?}: {w:?} → {back:?} → {again:?}");
            let root = local_from_world(&w, &local, inherit, None, placement);
            assert!(close(&world_transform(&root, inherit, None, placement), &w, 1e-9), "root {w:?}");
        }
    }

    #[test]
    fn a_world_turn_is_a_local_turn_under_a_normal_parent() {
        let parent = world_transform(
            &LocalTransform { rotation: 0.7, scale_x: 2.0, ..LocalTransform::default() },
            Inherit::Normal,
            None,
            Placement::default(),
        );
        let local = LocalTransform { x: 1.0, y: 2.0, rotation: 0.2, ..LocalTransform::default() };
        let w = world_transform(&local, Inherit::Normal, Some(&parent), Placement::default());
        let (s, c) = math::sin_cos(0.3);
        let turned = Affine { x: w.x, y: w.y, ..Affine { a: c, b: -s, c: s, d: c, x: 0.0, y: 0.0 }.times(&w) };
        let back = local_from_world(&turned, &local, Inherit::Normal, Some(&parent), Placement::default());
        assert!((back.x - 1.0).abs() < 1e-12 && (back.y - 2.0).abs() < 1e-12, "{back:?}");
        let again = world_transform(&back, Inherit::Normal, Some(&parent), Placement::default());
        assert!(close(&again, &turned, 1e-12));
    }
}
