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
use super::{CharacterError, LocalTransform};
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

    /// The mixes from the first six of `values` ([`TransformSettings::to_array`]'s order, a
    /// transform timeline's [`super::ChannelKey::values`]).
    pub fn from_values(values: &[f64; super::MAX_CHANNELS]) -> Self {
        let mut six = [0.0; 6];
        six.copy_from_slice(&values[..6]);
        TransformSettings::from_array(six)
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
        b.turn(r);
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
        b.turn(wrap(t.rotation() + off_rotation) * m.mix_rotate);
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

/// Applies constraint `c` with mixes `m` to the bones being posed: each bone's transform changed
/// (see the module's doc); in the world variants its world transform set and its applied local
/// transform recomputed from it ([`Bones::set_world`]), in the local variants its local
/// transform set and its world transform (and those below it) recomputed. The caller updates
/// the bones strictly below them afterwards. With every mix 0 it does nothing, as an IK
/// constraint at mix 0 does: the bones keep their local transforms bit for bit (a world one set
/// to itself would recompute them with a rounding).
pub(crate) fn apply(v: &mut Bones, c: &TransformConstraint, m: &TransformSettings) {
    // With every mix 0 the constraint does nothing: its bones keep their local transforms to
    // the bit (a world transform set and read back would round them).
    if [m.mix_rotate, m.mix_x, m.mix_y, m.mix_scale_x, m.mix_scale_y, m.mix_shear_y] == [0.0; 6] {
        return;
    }
    let o = &c.offsets;
    match c.space {
        TransformSpace::World => {
            let t = v.world[c.target];
            for &b in &c.bones {
                let w = match c.mode {
                    TransformMode::Absolute => world_absolute(&v.world[b], &t, o, m),
                    TransformMode::Relative => world_relative(&v.world[b], &t, o, m),
                };
                v.set_world(b, w);
            }
        }
        TransformSpace::Local => {
            let t = v.local[c.target];
            for &b in &c.bones {
                v.local[b] = match c.mode {
                    TransformMode::Absolute => local_absolute(&v.local[b], &t, o, m),
                    TransformMode::Relative => local_relative(&v.local[b], &t, o, m),
                };
                v.update_below(b);
            }
        }
    }
}

impl TransformConstraint {
    /// Checks it against a character of `bones` bones (constraint `k` of the list): its bones
    /// and target existing, every offset and mix finite.
    pub(crate) fn check(&self, k: usize, bones: usize) -> Result<(), CharacterError> {
        if let Some(&bone) = self.bones.iter().chain([&self.target]).find(|&&b| b >= bones) {
            return Err(CharacterError::TransformBone { constraint: k, bone });
        }
        let o = &self.offsets;
        let offsets = [
            ("rotation", o.rotation),
            ("x", o.x),
            ("y", o.y),
            ("scaleX", o.scale_x),
            ("scaleY", o.scale_y),
            ("shearY", o.shear_y),
        ];
        if let Some(&(field, value)) = offsets.iter().find(|(_, v)| !v.is_finite()) {
            return Err(CharacterError::NotFiniteSetting { constraint: k, field, value });
        }
        check_mixes(k, &self.setup)
    }
}

/// The mixes' names in Spine's terms, in [`TransformSettings::to_array`]'s order.
pub const MIX_NAMES: [&str; 6] = ["mixRotate", "mixX", "mixY", "mixScaleX", "mixScaleY", "mixShearY"];

/// Checks that the mixes of constraint `k` are finite.
pub(crate) fn check_mixes(k: usize, s: &TransformSettings) -> Result<(), CharacterError> {
    match MIX_NAMES.iter().zip(s.to_array()).find(|(_, v)| !v.is_finite()) {
        Some((&field, value)) => Err(CharacterError::NotFiniteSetting { constraint: k, field, value }),
        None => Ok(()),
    }
}

#[cfg(test)]
#[path = "transform_tests.rs"]
mod tests;
