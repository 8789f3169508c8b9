//! World transforms of a character's bones, as Spine's runtime computes them.
//!
//! A bone's local matrix is `L = [[cos(r + shx)·sx, cos(r + π/2 + shy)·sy], [sin(r + shx)·sx,
//! sin(r + π/2 + shy)·sy]]` and its origin `(x, y)` in the parent's frame. With the parent's
//! world matrix `P` and origin `o`, and the skeleton's scale `S = diag(Sx, Sy)`:
//!
//! - the origin is always `P·(x, y) + o` (every mode inherits translation);
//! - `normal`: `W = P·L`;
//! - `onlyTranslation`: `W = S·L` (only the skeleton's own scale, which may mirror);
//! - `noRotationOrReflection`: with `Q = S⁻¹·P` (the parent's matrix without the skeleton's
//!   scale), `θ` the direction of `Q`'s x axis, `sx = |Q's x axis|` and `sy = |det Q| / sx`,
//!   `W = S·R(θ)·diag(sx, sy)·R(−θ)·L`: the parent's scale along its own axes, without its
//!   rotation nor its reflection;
//! - `noScale` and `noScaleOrReflection`: the bone's x axis points where `Q·(cos r, sin r)`
//!   points (where it would point under `normal`), in a frame of unit axes `Z` (x axis that
//!   direction, y axis perpendicular counter-clockwise, turned over when `det Q < 0` for
//!   `noScale` only), and `W = S·Z·K` with `K` the local matrix without rotation (shear and
//!   scale only).
//!
//! A root bone's parent is the skeleton itself: `P = S`, `o` = the skeleton's position.

use super::flat::{Link, ROOT};
use super::{CharacterBone, Constraint, IkBones, Inherit, LocalTransform, Placement};
use crate::math;
use std::f64::consts::FRAC_PI_2;

/// A 2D affine transform: the matrix `[[a, b], [c, d]]` and the origin `(x, y)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Row 1, column 1: x of the x axis.
    pub a: f64,
    /// Row 1, column 2: x of the y axis.
    pub b: f64,
    /// Row 2, column 1: y of the x axis.
    pub c: f64,
    /// Row 2, column 2: y of the y axis.
    pub d: f64,
    /// The origin's x.
    pub x: f64,
    /// The origin's y.
    pub y: f64,
}

impl Default for Affine {
    fn default() -> Self {
        Affine { a: 1.0, b: 0.0, c: 0.0, d: 1.0, x: 0.0, y: 0.0 }
    }
}

impl Affine {
    /// The skeleton's own frame: its scale and position.
    pub fn of_placement(p: Placement) -> Affine {
        Affine { a: p.scale[0], b: 0.0, c: 0.0, d: p.scale[1], x: p.position[0], y: p.position[1] }
    }

    /// `ad − bc`.
    pub fn det(&self) -> f64 {
        self.a * self.d - self.b * self.c
    }

    /// The matrix applied to the vector `(x, y)` (no translation).
    pub fn apply(&self, x: f64, y: f64) -> [f64; 2] {
        [self.a * x + self.b * y, self.c * x + self.d * y]
    }

    /// The point `(x, y)` of this frame in the world.
    pub fn to_world(&self, x: f64, y: f64) -> [f64; 2] {
        let [u, v] = self.apply(x, y);
        [u + self.x, v + self.y]
    }

    /// The world point `(x, y)` in this frame (`None` when the matrix is singular).
    pub fn to_local(&self, x: f64, y: f64) -> Option<[f64; 2]> {
        let det = self.det();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let (u, v) = (x - self.x, y - self.y);
        Some([(u * self.d - v * self.b) / det, (v * self.a - u * self.c) / det])
    }

    /// The product of the matrices `self · other`, with `other`'s origin taken into this frame.
    pub fn times(&self, o: &Affine) -> Affine {
        let [x, y] = self.to_world(o.x, o.y);
        Affine {
            a: self.a * o.a + self.b * o.c,
            b: self.a * o.b + self.b * o.d,
            c: self.c * o.a + self.d * o.c,
            d: self.c * o.b + self.d * o.d,
            x,
            y,
        }
    }

    /// The origin `[x, y]`.
    #[inline]
    pub(crate) fn origin(&self) -> [f64; 2] {
        [self.x, self.y]
    }

    /// The matrix turned by `r` radians (both axes; the origin stays).
    pub(crate) fn turn(&mut self, r: f64) {
        let (sin, cos) = math::sin_cos(r);
        let (a, b, c, d) = (self.a, self.b, self.c, self.d);
        self.a = cos * a - sin * c;
        self.b = cos * b - sin * d;
        self.c = sin * a + cos * c;
        self.d = sin * b + cos * d;
    }

    /// The direction of the x axis, radians: `atan2(c, a)`.
    pub fn rotation(&self) -> f64 {
        math::atan2(self.c, self.a)
    }

    /// The matrix with the skeleton's scale divided out of its rows (`S⁻¹·M`).
    fn unscaled(&self, s: [f64; 2]) -> Affine {
        Affine { a: self.a / s[0], b: self.b / s[0], c: self.c / s[1], d: self.d / s[1], ..*self }
    }

    /// The matrix with the skeleton's scale applied to its rows (`S·M`).
    fn scaled(&self, s: [f64; 2]) -> Affine {
        Affine { a: self.a * s[0], b: self.b * s[0], c: self.c * s[1], d: self.d * s[1], ..*self }
    }
}

/// The sines and cosines a bone's world transform needed last and the time before, by
/// argument: a memo, so that a bone whose rotation and shear did not change since (in this pose
/// or the previous one) costs no sine nor cosine, and a bone a constraint turns (its rotation
/// before the constraint, then after, pose after pose) neither. The answer is the same bits
/// either way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Trig {
    arg: [f64; 2],
    sin: [f64; 2],
    cos: [f64; 2],
}

impl Trig {
    /// The memo of `sin_cos(0)`, exact: `(0, 1)`.
    pub(crate) const ZERO: Trig = Trig { arg: [0.0; 2], sin: [0.0; 2], cos: [1.0; 2] };

    /// `math::sin_cos(x)`, from the memo when one of its arguments has the same bits (the
    /// latest first); else computed, and the older argument forgotten.
    #[inline]
    fn sin_cos(&mut self, x: f64) -> (f64, f64) {
        let bits = x.to_bits();
        if self.arg[0].to_bits() == bits {
            return (self.sin[0], self.cos[0]);
        }
        if self.arg[1].to_bits() != bits {
            let (sin, cos) = math::sin_cos(x);
            self.arg[1] = x;
            self.sin[1] = sin;
            self.cos[1] = cos;
        }
        self.arg.swap(0, 1);
        self.sin.swap(0, 1);
        self.cos.swap(0, 1);
        (self.sin[0], self.cos[0])
    }
}

/// A bone's memos: its local x axis's angle, its y axis's, and its rotation alone (the `noScale`
/// modes).
pub(crate) type BoneTrig = [Trig; 3];

/// The local matrix of `t` turned by `rotation` (its own rotation, or 0 for the rotation-free
/// part), origin 0.
fn local_matrix(t: &LocalTransform, rotation: f64, trig: &mut BoneTrig) -> Affine {
    let (sx, cx) = trig[0].sin_cos(rotation + t.shear_x);
    let (sy, cy) = trig[1].sin_cos(rotation + FRAC_PI_2 + t.shear_y);
    Affine { a: cx * t.scale_x, b: cy * t.scale_y, c: sx * t.scale_x, d: sy * t.scale_y, x: 0.0, y: 0.0 }
}

/// The frame a bone's local rotation is measured in, for aiming it (one-bone IK): the matrix
/// `F` and the angle `θ` such that the bone's world x axis points along `F·(cos(r + shx − θ),
/// sin(r + shx − θ))` — exactly for `normal`, `onlyTranslation` and
/// `noRotationOrReflection`, and the parent's own matrix for the `noScale` modes (as the
/// runtime does). Its origin is the parent's.
pub(crate) fn aim_frame(inherit: Inherit, parent: &Affine, placement: Placement) -> (Affine, f64) {
    let s = placement.scale;
    match inherit {
        Inherit::Normal | Inherit::NoScale | Inherit::NoScaleOrReflection => (*parent, 0.0),
        Inherit::OnlyTranslation => (Affine { x: parent.x, y: parent.y, ..Affine::of_placement(placement) }, 0.0),
        Inherit::NoRotationOrReflection => {
            let (frame, theta) = unrotated(&parent.unscaled(s));
            (Affine { x: parent.x, y: parent.y, ..frame.scaled(s) }, theta)
        }
    }
}

/// `R(θ)·diag(sx, sy)` for `q`, with `θ`: see the module's doc.
fn unrotated(q: &Affine) -> (Affine, f64) {
    let sx2 = q.a * q.a + q.c * q.c;
    if sx2 > 1e-8 {
        let s = q.det().abs() / sx2;
        (Affine { a: q.a, b: -q.c * s, c: q.c, d: q.a * s, x: 0.0, y: 0.0 }, math::atan2(q.c, q.a))
    } else {
        // No x axis left: keep the y axis's length, along +y.
        let sy = math::hypot(q.b, q.d);
        (Affine { a: 0.0, b: 0.0, c: 0.0, d: sy, x: 0.0, y: 0.0 }, 0.0)
    }
}

/// The world transform of a bone with local transform `t` and inherit mode `inherit`, below
/// `parent`'s world transform (`None` for a root). The math is in the module's doc.
pub fn world_transform(t: &LocalTransform, inherit: Inherit, parent: Option<&Affine>, placement: Placement) -> Affine {
    world_transform_memo(t, inherit, parent, placement, &mut [Trig::ZERO; 3])
}

/// [`world_transform`] with the bone's memo of sines and cosines.
fn world_transform_memo(
    t: &LocalTransform,
    inherit: Inherit,
    parent: Option<&Affine>,
    placement: Placement,
    trig: &mut BoneTrig,
) -> Affine {
    let s = placement.scale;
    let Some(p) = parent else {
        return Affine::of_placement(placement).times(&Affine { x: t.x, y: t.y, ..local_matrix(t, t.rotation, trig) });
    };
    let [x, y] = p.to_world(t.x, t.y);
    let m = match inherit {
        Inherit::Normal => p.times(&local_matrix(t, t.rotation, trig)),
        Inherit::OnlyTranslation => local_matrix(t, t.rotation, trig).scaled(s),
        Inherit::NoRotationOrReflection => {
            let (frame, theta) = unrotated(&p.unscaled(s));
            frame.times(&local_matrix(t, t.rotation - theta, trig)).scaled(s)
        }
        Inherit::NoScale | Inherit::NoScaleOrReflection => {
            let q = p.unscaled(s);
            let (sin, cos) = trig[2].sin_cos(t.rotation);
            let [zx, zy] = q.apply(cos, sin);
            let len = math::hypot(zx, zy);
            let (za, zc) = if len > 1e-12 { (zx / len, zy / len) } else { (1.0, 0.0) };
            let flip = if inherit == Inherit::NoScale && q.det() < 0.0 { -1.0 } else { 1.0 };
            let z = Affine { a: za, b: -zc * flip, c: zc, d: za * flip, x: 0.0, y: 0.0 };
            z.times(&local_matrix(t, 0.0, trig)).scaled(s)
        }
    };
    Affine { x, y, ..m }
}

/// A character's bones being posed: their local transforms (which posing changes) and their
/// world transforms (kept up to date by [`Bones::update_below`]).
pub(crate) struct Bones<'a> {
    pub(crate) bones: &'a [CharacterBone],
    /// Each bone's parent and inherit mode, side by side.
    pub(crate) links: &'a [Link],
    pub(crate) placement: Placement,
    pub(crate) local: &'a mut [LocalTransform],
    pub(crate) world: &'a mut [Affine],
    /// Scratch: which bones are below the one being updated.
    pub(crate) below: &'a mut [bool],
    /// Per bone, the sines and cosines its world transform last needed.
    pub(crate) trig: &'a mut [BoneTrig],
}

impl Bones<'_> {
    /// The world transform of bone `i`'s parent (the skeleton's frame for a root).
    pub(crate) fn parent_world(&self, i: usize) -> Affine {
        match self.links[i].parent {
            ROOT => Affine::of_placement(self.placement),
            p => self.world[p as usize],
        }
    }

    /// Recomputes bone `i`'s world transform from its local one and its parent's world one:
    /// [`world_transform_memo`], with the parent read in place and the common case (a child
    /// inheriting normally) spelled out, the same operations in the same order.
    #[inline]
    fn update(&mut self, i: usize) {
        let Link { parent, inherit } = self.links[i];
        let t = &self.local[i];
        let trig = &mut self.trig[i];
        let w = if parent == ROOT {
            world_transform_memo(t, inherit, None, self.placement, trig)
        } else {
            let p = &self.world[parent as usize];
            if inherit == Inherit::Normal {
                let [x, y] = p.to_world(t.x, t.y);
                Affine { x, y, ..p.times(&local_matrix(t, t.rotation, trig)) }
            } else {
                world_transform_memo(t, inherit, Some(p), self.placement, trig)
            }
        };
        self.world[i] = w;
    }

    /// Recomputes every bone's world transform, parent first.
    pub(crate) fn update_all(&mut self) {
        for i in 0..self.links.len() {
            self.update(i);
        }
    }

    /// Recomputes every bone's world transform but the `deferred` ones (see [`deferred`]),
    /// which the constraints' updates compute before anything reads them.
    pub(crate) fn update_all_but(&mut self, deferred: &[bool]) {
        for (i, &d) in deferred.iter().enumerate() {
            if !d {
                self.update(i);
            }
        }
    }

    /// Recomputes the world transforms of `bones`, in this order: a bone and every bone below
    /// it, parents first (a constraint's subtree, [`super::flat::Flat::below`]).
    pub(crate) fn update_listed(&mut self, bones: &[u32]) {
        for &j in bones {
            self.update(j as usize);
        }
    }

    /// Recomputes a constraint's subtree: `top` and every bone below it, from its list when the
    /// character keeps one ([`super::flat::Subtree`]), else by [`Bones::update_below`]'s scan
    /// (the same bones in the same order).
    #[inline]
    pub(crate) fn update_subtree(&mut self, subtree: super::flat::Subtree<'_>) {
        match subtree {
            super::flat::Subtree::Listed(bones) => self.update_listed(bones),
            super::flat::Subtree::Below(top) => self.update_below(top),
            super::flat::Subtree::Under(tops) => self.update_under(tops),
        }
    }

    /// Recomputes the world transforms of every bone strictly below one of `tops` (not `tops`
    /// themselves, unless one is below another): [`super::flat::strictly_below`] by a scan.
    fn update_under(&mut self, tops: &[u32]) {
        let Some(&first) = tops.iter().min() else { return };
        let first = first as usize;
        self.below[first..].fill(false);
        for &t in tops {
            self.below[t as usize] = true;
        }
        for j in first + 1..self.links.len() {
            let p = self.links[j].parent;
            if p != ROOT && p as usize >= first && self.below[p as usize] {
                self.below[j] = true;
                self.update(j);
            }
        }
    }

    /// Recomputes bone `i`'s world transform and those of every bone below it (bones are
    /// listed parent first, so one pass from `i` on suffices).
    pub(crate) fn update_below(&mut self, i: usize) {
        self.below[i..].fill(false);
        self.below[i] = true;
        self.update(i);
        for j in i + 1..self.links.len() {
            let p = self.links[j].parent;
            if p != ROOT && p as usize >= i && self.below[p as usize] {
                self.below[j] = true;
                self.update(j);
            }
        }
    }
}

/// The bones whose world transform the first pass of a pose without targets may skip: each is
/// below (or is) the bones of a constraint, so that constraint's update below them recomputes
/// it, and nothing reads it before — no constraint applied up to then reads it (its target, its
/// bones, the parent of its first bone) and no bone the first pass computes is its child. The
/// pose's every number is then the same, bit for bit, with one update fewer per such bone.
/// `order` is the constraints' indices in the order they apply.
pub(crate) fn deferred(bones: &[CharacterBone], constraints: &[Constraint], order: &[usize]) -> Vec<bool> {
    let n = bones.len();
    // The first constraint (its place in `order`) whose update recomputes the bone, and the
    // first that reads it.
    // Linear in the bones and constraints: the first constraint topped at each bone, then, parents
    // first, the earliest of a bone's own and its parent's (a constraint's update recomputes its
    // top and every bone below it).
    let (mut fresh, mut read) = (vec![usize::MAX; n], vec![usize::MAX; n]);
    let mut other = usize::MAX;
    for (pos, &k) in order.iter().enumerate() {
        let Some(c) = constraints[k].ik() else {
            // Another kind may read any bone: nothing is skipped past the first one.
            other = other.min(pos);
            continue;
        };
        let (top, child) = match c.bones {
            IkBones::One(b) => (b, None),
            IkBones::Two { parent, child } => (parent, Some(child)),
        };
        for r in [Some(c.target), Some(top), child, bones[top].parent].into_iter().flatten() {
            read[r] = read[r].min(pos);
        }
        fresh[top] = fresh[top].min(pos);
    }
    for j in 0..n {
        if let Some(p) = bones[j].parent {
            fresh[j] = fresh[j].min(fresh[p]);
        }
        read[j] = read[j].min(other);
    }
    let mut deferred: Vec<bool> = (0..n).map(|j| fresh[j] != usize::MAX && read[j] > fresh[j]).collect();
    // A bone the first pass computes reads its parent: that one is computed too.
    for j in (0..n).rev() {
        if let (false, Some(p)) = (deferred[j], bones[j].parent) {
            deferred[p] = false;
        }
    }
    deferred
}

#[cfg(test)]
#[path = "world_tests.rs"]
mod tests;
