//! IK constraints solved as the character's runtime solves them: Spine's rules (one bone, two
//! bones by the law of cosines in the parent's parent's frame, with softness, stretch,
//! compress and uniform) and DragonBones' (one bone aims, two bones by a circle–circle
//! intersection in world space). Each rule changes the bones' local transforms only; the
//! caller updates the world transforms below the constrained bones afterwards.

use super::world::{Affine, Bones, aim_frame};
use super::{IkSettings, Inherit};
use crate::math;
use std::f64::consts::PI;

/// `angle` wrapped into `(−π, π]`.
fn wrap(angle: f64) -> f64 {
    let a = angle % (2.0 * PI);
    if a > PI {
        a - 2.0 * PI
    } else if a <= -PI {
        a + 2.0 * PI
    } else {
        a
    }
}

/// One bone, Spine's rule. The target is brought into the frame the bone's rotation is
/// measured in (its parent's frame, see [`aim_frame`]) relative to the bone's origin, giving
/// `(tx, ty)`; the rotation moves by `mix · wrap(atan2(ty, tx) − shearX − rotation)` (plus π
/// when scaleX < 0). With `compress` and the target nearer than `length·scaleX`, or `stretch`
/// and farther, scaleX is multiplied by `(|t| / (length·scaleX) − 1)·mix + 1`, and scaleY too
/// when `uniform`.
pub(crate) fn spine_one(v: &mut Bones, bone: usize, target: [f64; 2], s: &IkSettings, uniform: bool) {
    if s.mix == 0.0 {
        return;
    }
    let (frame, theta) = aim_frame(v.bones[bone].inherit, &v.parent_world(bone), v.placement);
    let origin = v.world[bone];
    let Some([tx, ty]) = Affine { x: origin.x, y: origin.y, ..frame }.to_local(target[0], target[1]) else {
        return;
    };
    let l = &mut v.local[bone];
    let mut turn = math::atan2(ty, tx) + theta - l.shear_x - l.rotation;
    if l.scale_x < 0.0 {
        turn += PI;
    }
    l.rotation += wrap(turn) * s.mix;
    if s.compress || s.stretch {
        let b = v.bones[bone].length * l.scale_x;
        let dd = math::hypot(tx, ty);
        if b > 1e-4 && ((s.compress && dd < b) || (s.stretch && dd > b)) {
            let k = (dd / b - 1.0) * s.mix + 1.0;
            l.scale_x *= k;
            if uniform {
                l.scale_y *= k;
            }
        }
    }
}

/// Where the child's tip goes in the two-bone solve: the parent's angle `a1` and the child's
/// angle `a2` relative to the line from the parent's origin to the child's origin, both in the
/// parent's parent's frame.
struct Angles {
    a1: f64,
    a2: f64,
}

/// The two-bone lengths and target in the parent's parent's frame, relative to the parent's
/// origin.
struct Limb {
    l1: f64,
    l2: f64,
    t: [f64; 2],
    bend: f64,
}

/// Two bones, Spine's rule (nothing unless both bones inherit normally). See the module's doc
/// and NOTES: negative scales become π offsets and sign flips; the child's local y is kept only
/// with a uniform parent scale and stretch off; `l1` is the distance from the parent's origin
/// to the child's, `l2` the child's length times its scaleX; softness eases the target toward
/// the root over a band `2s′` wide (`s′ = s·psx·(csx + 1)/2`): with `sd = |t| − l1 − l2·psx + s′
/// > 0` the target comes nearer by `sd²/(4s′)` while `sd < 2s′`, and by `sd − s′` beyond, so
/// the distance `L − s′ + sd − sd²/(4s′)` meets the full reach `L` with a zero slope.
pub(crate) fn spine_two(
    v: &mut Bones,
    (parent, child): (usize, usize),
    target: [f64; 2],
    s: &IkSettings,
    uniform: bool,
) {
    if s.mix == 0.0 || v.bones[parent].inherit != Inherit::Normal || v.bones[child].inherit != Inherit::Normal {
        return;
    }
    let (pl, cl) = (v.local[parent], v.local[child]);
    let (mut psx, mut psy, mut sx, mut sy) = (pl.scale_x, pl.scale_y, pl.scale_x, pl.scale_y);
    let (os1, mut s2) = if psx < 0.0 {
        psx = -psx;
        (PI, -1.0)
    } else {
        (0.0, 1.0)
    };
    if psy < 0.0 {
        psy = -psy;
        s2 = -s2;
    }
    let (csx, os2) = if cl.scale_x < 0.0 { (-cl.scale_x, PI) } else { (cl.scale_x, 0.0) };
    let u = (psx - psy).abs() <= 1e-4;
    let (cx, cy) = (cl.x, if !u || s.stretch { 0.0 } else { cl.y });
    let [wx, wy] = v.world[parent].to_world(cx, cy);
    let pp = v.parent_world(parent);
    let (Some(c), Some(t)) = (pp.to_local(wx, wy), pp.to_local(target[0], target[1])) else { return };
    let l1 = math::hypot(c[0] - pl.x, c[1] - pl.y);
    if l1 < 1e-4 {
        spine_one(v, parent, target, &IkSettings { compress: false, ..*s }, false);
        v.local[child].y = cy;
        return;
    }
    let mut limb = Limb {
        l1,
        l2: v.bones[child].length * csx,
        t: [t[0] - pl.x, t[1] - pl.y],
        bend: if s.bend_positive { 1.0 } else { -1.0 },
    };
    if s.softness != 0.0 {
        let soft = s.softness * psx * (csx + 1.0) / 2.0;
        let td = math::hypot(limb.t[0], limb.t[1]);
        let sd = td - l1 - limb.l2 * psx + soft;
        if sd > 0.0 {
            let q = (sd / (2.0 * soft)).min(1.0) - 1.0;
            let p = (sd - soft * (1.0 - q * q)) / td;
            limb.t = [limb.t[0] * (1.0 - p), limb.t[1] * (1.0 - p)];
        }
    }
    let angles = if u {
        limb.l2 *= psx;
        let (angles, straight) = law_of_cosines(&limb);
        if straight && s.stretch {
            let dd = limb.t[0] * limb.t[0] + limb.t[1] * limb.t[1];
            let k = (dd.sqrt() / (limb.l1 + limb.l2) - 1.0) * s.mix + 1.0;
            sx *= k;
            if uniform {
                sy *= k;
            }
        }
        angles
    } else {
        ellipse(&limb, psx, psy)
    };
    let os = math::atan2(cy, cx) * s2;
    let p = &mut v.local[parent];
    p.rotation += wrap(angles.a1 - os + os1 - p.rotation) * s.mix;
    p.scale_x = sx;
    p.scale_y = sy;
    p.shear_x = 0.0;
    p.shear_y = 0.0;
    let c = &mut v.local[child];
    c.y = cy;
    c.rotation += wrap(s2 * (angles.a2 + os) - c.shear_x + os2 - c.rotation) * s.mix;
}

/// Uniform parent scale: `cos a2 = (|t|² − l1² − l2²)/(2·l1·l2)`; below −1 the elbow is folded
/// (`a2 = π·bend`), above 1 straight (`a2 = 0`; the flag says so, for the stretch), else
/// `a2 = bend·acos`; `a1 = atan2(ty·A − tx·B, tx·A + ty·B)` with `A = l1 + l2·cos a2`,
/// `B = l2·sin a2`.
fn law_of_cosines(limb: &Limb) -> (Angles, bool) {
    let [tx, ty] = limb.t;
    let (l1, l2) = (limb.l1, limb.l2);
    let cos = (tx * tx + ty * ty - l1 * l1 - l2 * l2) / (2.0 * l1 * l2);
    let straight = cos > 1.0 || cos.is_nan();
    let a2 = if cos < -1.0 {
        PI * limb.bend
    } else if straight {
        0.0
    } else {
        math::acos(cos) * limb.bend
    };
    let (sin2, cos2) = math::sin_cos(a2);
    let (a, b) = (l1 + l2 * cos2, l2 * sin2);
    (Angles { a1: math::atan2(ty * a - tx * b, tx * a + ty * b), a2 }, straight)
}

/// Non-uniform parent scale: the child's tip lies on the ellipse `(l1 + A·cos φ, B·sin φ)`,
/// `A = psx·l2`, `B = psy·l2`, in the frame of the line from the parent's origin to the
/// child's. A point at distance `d = |t|` has `x` solving `(A² − B²)x² + 2B²l1·x + A²B² −
/// B²l1² − A²d² = 0`; the root of least `|x|` with `x² ≤ d²` is taken. Without one, the
/// ellipse's nearest or farthest point (φ = π, 0 or `cos φ = −A·l1/(A² − B²)`, where the
/// distance's derivative `2 sin φ ((B² − A²) cos φ − A·l1)` vanishes), whichever `d` is nearer.
fn ellipse(limb: &Limb, psx: f64, psy: f64) -> Angles {
    let [tx, ty] = limb.t;
    let (l1, bend) = (limb.l1, limb.bend);
    let (a, b) = (psx * limb.l2, psy * limb.l2);
    let (aa, bb, dd) = (a * a, b * b, tx * tx + ty * ty);
    let ta = math::atan2(ty, tx);
    let c2 = aa - bb;
    let c1 = 2.0 * bb * l1;
    let c0 = aa * bb - bb * l1 * l1 - aa * dd;
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc >= 0.0 && c2 != 0.0 {
        let q = -(c1 + disc.sqrt().copysign(c1)) / 2.0;
        let (r0, r1) = (q / c2, if q != 0.0 { c0 / q } else { f64::INFINITY });
        let r = if r0.abs() < r1.abs() { r0 } else { r1 };
        if r * r <= dd {
            let y = (dd - r * r).sqrt() * bend;
            return Angles { a1: ta - math::atan2(y, r), a2: math::atan2(y / psy, (r - l1) / psx) };
        }
    }
    let (mut near, mut far) = (([l1 - a, 0.0], PI), ([l1 + a, 0.0], 0.0));
    let dist = |p: [f64; 2]| p[0] * p[0] + p[1] * p[1];
    let cos = if c2 != 0.0 { -a * l1 / c2 } else { f64::NAN };
    if (-1.0..=1.0).contains(&cos) {
        let phi = math::acos(cos);
        let (sin, cos) = math::sin_cos(phi);
        let p = [a * cos + l1, b * sin];
        if dist(p) < dist(near.0) {
            near = (p, phi);
        }
        if dist(p) > dist(far.0) {
            far = (p, phi);
        }
    }
    let (p, phi) = if dd <= (dist(near.0) + dist(far.0)) / 2.0 { near } else { far };
    Angles { a1: ta - math::atan2(p[1] * bend, p[0]), a2: phi * bend }
}

/// The sign a world turn takes in the local rotation of a bone under `frame`: −1 when the
/// frame mirrors.
fn handedness(frame: &Affine) -> f64 {
    if frame.det() < 0.0 { -1.0 } else { 1.0 }
}

/// Two bones, DragonBones' rule, in world space: with the root `o` (the parent's origin), the
/// elbow's distance `l1` from it, the child's world length `l2` and the target at distance `d`,
/// a reachable target (`|l1 − l2| < d < l1 + l2`) puts the elbow at `o + a·û ± h·û⊥`,
/// `a = (l1² − l2² + d²)/(2d)`, `h = √(l1² − a²)`, on the counter-clockwise side (in y-up
/// terms) when `bendPositive` XOR the parent's parent's frame mirrors, else on the clockwise
/// side; out of reach the parent points the elbow straight at the target. The child then aims
/// at the target. Each turn is blended by the weight (`mix`). `below` is the parent and every
/// bone below it, in update order (recomputed between the two turns).
pub(crate) fn dragonbones_two(
    v: &mut Bones,
    (parent, child): (usize, usize),
    below: super::flat::Subtree<'_>,
    target: [f64; 2],
    s: &IkSettings,
) {
    if s.mix == 0.0 {
        return;
    }
    let pp = v.parent_world(parent);
    let (o, e) = (v.world[parent], v.world[child]);
    let (ex, ey) = (e.x - o.x, e.y - o.y);
    let (tx, ty) = (target[0] - o.x, target[1] - o.y);
    let l1 = math::hypot(ex, ey);
    let l2 = math::hypot(e.a, e.c) * v.bones[child].length;
    let d = math::hypot(tx, ty);
    let elbow = if d > 0.0 && d < l1 + l2 && d > (l1 - l2).abs() {
        let a = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d);
        let h = (l1 * l1 - a * a).max(0.0).sqrt();
        let side = if s.bend_positive != (pp.det() < 0.0) { 1.0 } else { -1.0 };
        let (ux, uy) = (tx / d, ty / d);
        [a * ux - side * h * uy, a * uy + side * h * ux]
    } else {
        [tx, ty]
    };
    let turn = wrap(math::atan2(elbow[1], elbow[0]) - math::atan2(ey, ex));
    v.local[parent].rotation += turn * handedness(&pp) * s.mix;
    v.update_subtree(below);
    let e = v.world[child];
    let turn = wrap(math::atan2(target[1] - e.y, target[0] - e.x) - e.rotation());
    v.local[child].rotation += turn * handedness(&v.world[parent]) * s.mix;
}

#[cfg(test)]
#[path = "ik_tests.rs"]
mod tests;
