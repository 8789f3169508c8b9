//! Transform constraints as Spine's runtime applies them: each constrained bone's rotation,
//! translation, scale and shear move toward (or, relative, by) its target bone's, by six mixes.
//!
//! Four variants, from the file's `local` and `relative` flags ([`TransformSpace`],
//! [`TransformMode`]). In the world variants the bones' world matrices are changed in place and
//! their local (applied) transforms recomputed from them; in the local variants the local
//! transforms are changed and the world ones recomputed. Angles are radians, wrapped into
//! `(−π, π]` where noted; `T` is the target's world matrix `[[ta, tb], [tc, td]]`, `B` a bone's.
//!
//! World, absolute (the default):
//! - rotation: both axes of `B` turn by `mixRotate · wrap(atan2(tc, ta) + rotation −
//!   atan2(c, a))`;
//! - translation: the origin moves toward the target's point `T·(x, y) + target origin` by
//!   `mixX` along x and `mixY` along y;
//! - scale: each axis's length `s` becomes `s + (|T's axis| − s + scaleX) · mixScaleX` (the same
//!   along y with `scaleY`, `mixScaleY`); an axis of length 0 stays so;
//! - shear: the y axis turns, keeping its length, to `by + wrap(tφ − bφ + shearY) · mixShearY`, with
//!   `by` its direction, `tφ`, `bφ` the angles from the target's and the bone's x axis to
//!   their y axis;
//! - a target whose matrix mirrors (`det T < 0`) turns the `rotation` and `shearY` offsets
//!   around (inferred from the user guide's reflection rules; no reference case has one).
//!
//! World, relative: the rotation turns by `mixRotate · wrap(atan2(tc, ta) + rotation)`, the
//! origin moves by `(mixX, mixY) ×` the target's point `T·(x, y) + target origin`, each axis
//! is scaled by `(|T's axis| − 1 + offset) · mix + 1`, and the y axis turns by `(tφ − π/2 +
//! shearY) · mixShearY`.
//!
//! Local, absolute: each of the bone's local rotation, x, y, scaleX, scaleY and shearY moves
//! toward the target's local one plus the offset by its mix (the angles by the wrapped
//! difference). Local, relative: the target's local value plus the offset, times the mix, is
//! added to the bone's (scales: the bone's scale is multiplied by `(target − 1 + offset) · mix +
//! 1`).

use super::world::{Affine, Bones};
use super::{CharacterError, Clip, IkConstraint, Inherit, LocalTransform, Placement};
use crate::math;
use std::f64::consts::{FRAC_PI_2, PI};

/// The six mixes of a transform constraint (what clips key), each 0 (no effect) to 1 (all the
/// way); Spine also takes values outside, e.g. −1 to move away from the target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransformSettings {
    /// Rotation mix (Spine's `mixRotate`, 3.8 `rotateMix`; default 1).
    pub mix_rotate: f64,
    /// Translation mix along x (`mixX`, 3.8 `translateMix`; default 1).
    pub mix_x: f64,
    /// Translation mix along y (`mixY`; default `mixX`'s value).
    pub mix_y: f64,
    /// Scale mix along x (`mixScaleX`, 3.8 `scaleMix`; default 1).
    pub mix_scale_x: f64,
    /// Scale mix along y (`mixScaleY`; default `mixScaleX`'s value).
    pub mix_scale_y: f64,
    /// Shear mix of the y axis (`mixShearY`, 3.8 `shearMix`; default 1).
    pub mix_shear_y: f64,
}

impl Default for TransformSettings {
    fn default() -> Self {
        TransformSettings {
            mix_rotate: 1.0,
            mix_x: 1.0,
            mix_y: 1.0,
            mix_scale_x: 1.0,
            mix_scale_y: 1.0,
            mix_shear_y: 1.0,
        }
    }
}

impl TransformSettings {
    /// The mixes in the order clips key them: rotate, x, y, scaleX, scaleY, shearY.
    pub fn to_array(self) -> [f64; 6] {
        [self.mix_rotate, self.mix_x, self.mix_y, self.mix_scale_x, self.mix_scale_y, self.mix_shear_y]
    }

    /// The mixes from [`TransformSettings::to_array`]'s order.
    pub fn from_array([mix_rotate, mix_x, mix_y, mix_scale_x, mix_scale_y, mix_shear_y]: [f64; 6]) -> Self {
        TransformSettings { mix_rotate, mix_x, mix_y, mix_scale_x, mix_scale_y, mix_shear_y }
    }
}

/// What a transform constraint adds to its target's values (all 0 by default).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TransformOffsets {
    /// Radians added to the target's rotation (Spine's `rotation`, degrees in the file).
    pub rotation: f64,
    /// The target's point: x in the target's frame (world), or added to its local x (`x`).
    pub x: f64,
    /// The target's point: y in the target's frame (world), or added to its local y (`y`).
    pub y: f64,
    /// Added to the target's scale along x (`scaleX`).
    pub scale_x: f64,
    /// Added to the target's scale along y (`scaleY`).
    pub scale_y: f64,
    /// Radians added to the target's shear of its y axis (`shearY`, degrees in the file).
    pub shear_y: f64,
}

/// Where a transform constraint works (Spine's `local`, default false: the world).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TransformSpace {
    /// On the world matrices.
    #[default]
    World,
    /// On the local transforms, each in its parent's frame.
    Local,
}

/// Whether a transform constraint replaces the bones' values or adds to them (Spine's
/// `relative`, default false: absolute).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TransformMode {
    /// Move toward the target's values plus the offsets.
    #[default]
    Absolute,
    /// Add the target's values plus the offsets.
    Relative,
}

/// A transform constraint: its bones' transforms follow its target's.
#[derive(Debug, Clone, PartialEq)]
pub struct TransformConstraint {
    /// Its name in the file.
    pub name: String,
    /// Constraints are applied in increasing `order` (ties: the order they are listed in).
    pub order: u32,
    /// The bones it moves (Spine's `bones`), at least one.
    pub bones: Vec<usize>,
    /// The bone whose transform they follow.
    pub target: usize,
    /// What is added to the target's values.
    pub offsets: TransformOffsets,
    /// World or local.
    pub space: TransformSpace,
    /// Absolute or relative.
    pub mode: TransformMode,
    /// The mixes of the setup pose (clips key them).
    pub setup: TransformSettings,
}

/// `angle` wrapped into `[−π, π]`, as the runtime wraps: `r − ceil(r / 2π − 1/2)·2π`.
fn wrap(r: f64) -> f64 {
    r - (r / (2.0 * PI) - 0.5).ceil() * (2.0 * PI)
}

/// `b`'s axes turned by `r`.
fn turn(b: &mut Affine, r: f64) {
    let (sin, cos) = math::sin_cos(r);
    let (a, bb, c, d) = (b.a, b.b, b.c, b.d);
    b.a = cos * a - sin * c;
    b.b = cos * bb - sin * d;
    b.c = sin * a + cos * c;
    b.d = sin * bb + cos * d;
}

/// `b`'s y axis set to direction `r`, its length kept.
fn aim_y(b: &mut Affine, r: f64) {
    let s = math::hypot(b.b, b.d);
    let (sin, cos) = math::sin_cos(r);
    b.b = cos * s;
    b.d = sin * s;
}

/// The angle from `m`'s x axis to its y axis.
fn skew(m: &Affine) -> f64 {
    math::atan2(m.d, m.b) - math::atan2(m.c, m.a)
}

/// A bone's world transform `b` after the constraint, world absolute (see the module's doc).
pub fn world_absolute(b: &Affine, t: &Affine, o: &TransformOffsets, m: &TransformSettings) -> Affine {
    let mut b = *b;
    let reflect = if t.det() > 0.0 { 1.0 } else { -1.0 };
    let (off_rotation, off_shear) = (o.rotation * reflect, o.shear_y * reflect);
    if m.mix_rotate != 0.0 {
        let r = wrap(t.rotation() - b.rotation() + off_rotation) * m.mix_rotate;
        turn(&mut b, r);
    }
    if m.mix_x != 0.0 || m.mix_y != 0.0 {
        let [px, py] = t.to_world(o.x, o.y);
        b.x += (px - b.x) * m.mix_x;
        b.y += (py - b.y) * m.mix_y;
    }
    if m.mix_scale_x != 0.0 {
        let s = math::hypot(b.a, b.c);
        if s != 0.0 {
            let k = (s + (math::hypot(t.a, t.c) - s + o.scale_x) * m.mix_scale_x) / s;
            b.a *= k;
            b.c *= k;
        }
    }
    if m.mix_scale_y != 0.0 {
        let s = math::hypot(b.b, b.d);
        if s != 0.0 {
            let k = (s + (math::hypot(t.b, t.d) - s + o.scale_y) * m.mix_scale_y) / s;
            b.b *= k;
            b.d *= k;
        }
    }
    if m.mix_shear_y != 0.0 {
        let by = math::atan2(b.d, b.b);
        let r = wrap(skew(t) - skew(&b));
        aim_y(&mut b, by + (r + off_shear) * m.mix_shear_y);
    }
    b
}

/// A bone's world transform `b` after the constraint, world relative (see the module's doc).
pub fn world_relative(b: &Affine, t: &Affine, o: &TransformOffsets, m: &TransformSettings) -> Affine {
    let mut b = *b;
    let reflect = if t.det() > 0.0 { 1.0 } else { -1.0 };
    let (off_rotation, off_shear) = (o.rotation * reflect, o.shear_y * reflect);
    if m.mix_rotate != 0.0 {
        turn(&mut b, wrap(t.rotation() + off_rotation) * m.mix_rotate);
    }
    if m.mix_x != 0.0 || m.mix_y != 0.0 {
        let [px, py] = t.to_world(o.x, o.y);
        b.x += px * m.mix_x;
        b.y += py * m.mix_y;
    }
    if m.mix_scale_x != 0.0 {
        let k = (math::hypot(t.a, t.c) - 1.0 + o.scale_x) * m.mix_scale_x + 1.0;
        b.a *= k;
        b.c *= k;
    }
    if m.mix_scale_y != 0.0 {
        let k = (math::hypot(t.b, t.d) - 1.0 + o.scale_y) * m.mix_scale_y + 1.0;
        b.b *= k;
        b.d *= k;
    }
    if m.mix_shear_y != 0.0 {
        let r = wrap(skew(t));
        let by = math::atan2(b.d, b.b);
        aim_y(&mut b, by + (r - FRAC_PI_2 + off_shear) * m.mix_shear_y);
    }
    b
}

/// A bone's local transform `b` after the constraint, local absolute (see the module's doc).
pub fn local_absolute(
    b: &LocalTransform,
    t: &LocalTransform,
    o: &TransformOffsets,
    m: &TransformSettings,
) -> LocalTransform {
    let mut b = *b;
    if m.mix_rotate != 0.0 {
        b.rotation += wrap(t.rotation - b.rotation + o.rotation) * m.mix_rotate;
    }
    b.x += (t.x - b.x + o.x) * m.mix_x;
    b.y += (t.y - b.y + o.y) * m.mix_y;
    b.scale_x += (t.scale_x - b.scale_x + o.scale_x) * m.mix_scale_x;
    b.scale_y += (t.scale_y - b.scale_y + o.scale_y) * m.mix_scale_y;
    if m.mix_shear_y != 0.0 {
        b.shear_y += wrap(t.shear_y - b.shear_y + o.shear_y) * m.mix_shear_y;
    }
    b
}

/// A bone's local transform `b` after the constraint, local relative (see the module's doc).
pub fn local_relative(
    b: &LocalTransform,
    t: &LocalTransform,
    o: &TransformOffsets,
    m: &TransformSettings,
) -> LocalTransform {
    let mut b = *b;
    b.rotation += (t.rotation + o.rotation) * m.mix_rotate;
    b.x += (t.x + o.x) * m.mix_x;
    b.y += (t.y + o.y) * m.mix_y;
    b.scale_x *= (t.scale_x - 1.0 + o.scale_x) * m.mix_scale_x + 1.0;
    b.scale_y *= (t.scale_y - 1.0 + o.scale_y) * m.mix_scale_y + 1.0;
    b.shear_y += (t.shear_y + o.shear_y) * m.mix_shear_y;
    b
}

/// The local transform (shearX 0) whose world transform under `parent` (`None`: a root) with
/// `inherit` is `w`: the inverse of [`super::world_transform`], exact up to rounding while the
/// matrices are not singular (a singular one leaves `keep`, the bone's local transform before).
pub fn local_from_world(
    w: &Affine,
    inherit: Inherit,
    parent: Option<&Affine>,
    placement: Placement,
    keep: &LocalTransform,
) -> LocalTransform {
    let s = Affine::of_placement(placement);
    let p = parent.copied().unwrap_or(s);
    let Some([x, y]) = p.to_local(w.x, w.y) else { return *keep };
    let m = Affine { x: 0.0, y: 0.0, ..*w };
    let Some(inverse) = invert(&p) else { return *keep };
    let s_inverse = invert(&Affine { x: 0.0, y: 0.0, ..s });
    let unscaled = s_inverse.map(|si| si.times(&m));
    let local = match (inherit, parent) {
        (_, None) | (Inherit::Normal, _) => Some((inverse.times(&m), 0.0)),
        (Inherit::OnlyTranslation, _) => unscaled.map(|l| (l, 0.0)),
        (Inherit::NoRotationOrReflection, Some(p)) => {
            let q = s_inverse.map(|si| si.times(p));
            match (q, unscaled) {
                (Some(q), Some(u)) => {
                    let sx2 = q.a * q.a + q.c * q.c;
                    let (frame, theta) = if sx2 > 1e-8 {
                        let k = q.det().abs() / sx2;
                        (Affine { a: q.a, b: -q.c * k, c: q.c, d: q.a * k, x: 0.0, y: 0.0 }, math::atan2(q.c, q.a))
                    } else {
                        (Affine { a: 0.0, b: 0.0, c: 0.0, d: math::hypot(q.b, q.d), x: 0.0, y: 0.0 }, 0.0)
                    };
                    invert(&frame).map(|f| (f.times(&u), theta))
                }
                _ => None,
            }
        }
        (Inherit::NoScale | Inherit::NoScaleOrReflection, Some(p)) => {
            // The world x axis's direction is Q·(cos r, sin r)'s: r from Q⁻¹ applied to it.
            let q = s_inverse.map(|si| si.times(p));
            match (q.and_then(|q| invert(&q).map(|qi| (q, qi))), unscaled) {
                (Some((q, qi)), Some(u)) => {
                    let [rx, ry] = qi.apply(u.a, u.c);
                    let r = math::atan2(ry, rx);
                    let (sin, cos) = math::sin_cos(r);
                    let [zx, zy] = q.apply(cos, sin);
                    let len = math::hypot(zx, zy);
                    let (za, zc) = if len > 1e-12 { (zx / len, zy / len) } else { (1.0, 0.0) };
                    let flip = if inherit == Inherit::NoScale && q.det() < 0.0 { -1.0 } else { 1.0 };
                    let z = Affine { a: za, b: -zc * flip, c: zc, d: za * flip, x: 0.0, y: 0.0 };
                    invert(&z).map(|zi| (zi.times(&u), r))
                }
                _ => None,
            }
        }
    };
    let Some((l, extra)) = local else { return *keep };
    let mut out = decompose(&l);
    out.rotation += extra;
    LocalTransform { x, y, ..out }
}

/// The inverse of `m`'s matrix (origin 0), `None` when singular.
fn invert(m: &Affine) -> Option<Affine> {
    let det = m.det();
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some(Affine { a: m.d / det, b: -m.b / det, c: -m.c / det, d: m.a / det, x: 0.0, y: 0.0 })
}

/// Rotation, scales and y shear (shearX 0) of a local matrix `l`: the x axis gives the
/// rotation and scaleX, the y axis's length scaleY (negative when `l` mirrors) and its angle
/// from the x axis, less π/2, shearY. An x axis shorter than 1e-4 is taken as none: scaleX
/// 0, the rotation from the y axis.
fn decompose(l: &Affine) -> LocalTransform {
    let sx = math::hypot(l.a, l.c);
    let det = l.det();
    if sx <= 1e-4 {
        let sy = math::hypot(l.b, l.d);
        return LocalTransform {
            rotation: math::atan2(l.d, l.b) - FRAC_PI_2,
            scale_x: 0.0,
            scale_y: sy,
            ..LocalTransform::default()
        };
    }
    let rotation = math::atan2(l.c, l.a);
    let sy = math::hypot(l.b, l.d) * if det < 0.0 { -1.0 } else { 1.0 };
    let shear_y = if sy == 0.0 { 0.0 } else { wrap(math::atan2(l.d / sy, l.b / sy) - rotation - FRAC_PI_2) };
    LocalTransform { x: 0.0, y: 0.0, rotation, scale_x: sx, scale_y: sy, shear_x: 0.0, shear_y }
}

/// Applies constraint `c` with mixes `m` to the bones being posed: each bone's transform changed
/// (see the module's doc) and, in the world variants, its local transform recomputed from its
/// new world one. The caller updates the world transforms below the bones afterwards (in the
/// local variants, the bones' own too).
pub(crate) fn apply(v: &mut Bones, c: &TransformConstraint, m: &TransformSettings) {
    let o = &c.offsets;
    match c.space {
        TransformSpace::World => {
            let t = v.world[c.target];
            for &b in &c.bones {
                let w = match c.mode {
                    TransformMode::Absolute => world_absolute(&v.world[b], &t, o, m),
                    TransformMode::Relative => world_relative(&v.world[b], &t, o, m),
                };
                v.world[b] = w;
                let parent = v.bones[b].parent.map(|p| v.world[p]);
                v.local[b] = local_from_world(&w, v.bones[b].inherit, parent.as_ref(), v.placement, &v.local[b]);
            }
        }
        TransformSpace::Local => {
            let t = v.local[c.target];
            for &b in &c.bones {
                v.local[b] = match c.mode {
                    TransformMode::Absolute => local_absolute(&v.local[b], &t, o, m),
                    TransformMode::Relative => local_relative(&v.local[b], &t, o, m),
                };
            }
        }
    }
}

/// One constraint of any kind, by its index in its kind's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Step {
    /// An IK constraint.
    Ik(usize),
    /// A transform constraint.
    Transform(usize),
}

/// Every constraint in the order they apply: by `order`, and for equal orders IK constraints
/// first, then transform ones, each kind as listed (Spine's update order looks for the
/// constraint of each order among its IK constraints first, then its transform ones).
pub(crate) fn steps(ik: &[IkConstraint], transforms: &[TransformConstraint]) -> Vec<Step> {
    let mut out: Vec<(u32, u8, usize, Step)> =
        ik.iter().enumerate().map(|(i, c)| (c.order, 0, i, Step::Ik(i))).collect();
    out.extend(transforms.iter().enumerate().map(|(i, c)| (c.order, 1, i, Step::Transform(i))));
    out.sort_by_key(|&(order, kind, i, _)| (order, kind, i));
    out.into_iter().map(|(.., s)| s).collect()
}

/// Checks the transform constraints of a character of `bones` bones and their timelines in
/// `clips`: every bone and target existing, every offset and mix finite, keys in increasing
/// finite time.
pub(crate) fn check(transforms: &[TransformConstraint], bones: usize, clips: &[Clip]) -> Result<(), CharacterError> {
    let finite = |constraint: usize, s: &TransformSettings| {
        let names = ["mixRotate", "mixX", "mixY", "mixScaleX", "mixScaleY", "mixShearY"];
        match names.iter().zip(s.to_array()).find(|(_, v)| !v.is_finite()) {
            Some((field, value)) => Err(CharacterError::TransformSetting { constraint, field, value }),
            None => Ok(()),
        }
    };
    for (k, c) in transforms.iter().enumerate() {
        if let Some(&bone) = c.bones.iter().chain([&c.target]).find(|&&b| b >= bones) {
            return Err(CharacterError::TransformBone { constraint: k, bone });
        }
        let o = &c.offsets;
        let offsets = [
            ("rotation", o.rotation),
            ("x", o.x),
            ("y", o.y),
            ("scaleX", o.scale_x),
            ("scaleY", o.scale_y),
            ("shearY", o.shear_y),
        ];
        if let Some(&(field, value)) = offsets.iter().find(|(_, v)| !v.is_finite()) {
            return Err(CharacterError::TransformSetting { constraint: k, field, value });
        }
        finite(k, &c.setup)?;
    }
    for (ci, clip) in clips.iter().enumerate() {
        for t in &clip.transforms {
            if t.constraint >= transforms.len() {
                return Err(CharacterError::MissingTarget {
                    clip: ci,
                    what: "transform constraint",
                    index: t.constraint,
                });
            }
            super::check_times(ci, t.keys.iter().map(|k| k.time))?;
            for k in &t.keys {
                if let Some(value) = k.settings.to_array().into_iter().find(|v| !v.is_finite()) {
                    return Err(CharacterError::KeyValue { clip: ci, value });
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "transform_tests.rs"]
mod tests;
