//! A path attachment's curves in the world: its vertices taken into the world, its length, and
//! the points at distances along it.
//!
//! A path of `n` vertices is `n / 3` knots, each an in handle, the knot and an out handle; an
//! open path's curves go from each knot to the next (`n / 3 − 1` curves; the first in handle
//! and the last out handle are unused), a closed path's also from the last knot back to the
//! first. With `constantSpeed` the distances are arc lengths measured in the world each pose:
//! a curve's length is that of the four chords between the cubic's points at the parameters
//! 0, ¼, ½, ¾, 1 (the path's length their sum); a distance picks the first curve that ends at
//! or after it, its fraction of that curve's length is taken along the ten chords at the
//! parameters 0, 0.1, …, 1, and the parameter is walked proportionally on the chord it falls
//! on. Without it, a distance picks a curve by the attachment's `lengths` and is a parameter
//! proportionally within that curve.
//!
//! Inferred from Spine's runtime (4.2.119) posing stretchyman: with ten chords for the curves'
//! lengths too, its bones land up to 2.5e-3 off the runtime's along the path (6e-3 in the middle
//! of the legs), with the exact arc length 0.44; with four chords for the lengths and ten
//! within a curve, 3e-5 (the runtime's f32 arithmetic).

use super::super::world::Affine;
use crate::math;

/// A path attachment (`type: "path"` in a skin).
#[derive(Debug, Clone, PartialEq)]
pub struct PathShape {
    /// Whether a curve joins the last knot back to the first (`closed`, default false).
    pub closed: bool,
    /// Whether distances are arc lengths measured each pose (`constantSpeed`, default true) or
    /// curve parameters spread over `lengths`.
    pub constant_speed: bool,
    /// The length of the path up to the end of each curve, setup pose, in the file's units
    /// (`lengths`).
    pub lengths: Vec<f64>,
    /// The vertices: handles and knots (`vertices`, `vertexCount` of them).
    pub vertices: PathVertices,
}

/// A path's vertices.
#[derive(Debug, Clone, PartialEq)]
pub enum PathVertices {
    /// Points in the slot bone's frame.
    Plain(Vec<[f64; 2]>),
    /// Per vertex, the bones it follows, each with a point in that bone's frame and a weight.
    Weighted(Vec<Vec<Weight>>),
}

impl PathVertices {
    /// How many vertices.
    pub fn len(&self) -> usize {
        match self {
            PathVertices::Plain(v) => v.len(),
            PathVertices::Weighted(v) => v.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// How many numbers a deform key holds for these vertices: two per point (per bone of a
    /// weighted vertex).
    pub fn deform_len(&self) -> usize {
        match self {
            PathVertices::Plain(v) => 2 * v.len(),
            PathVertices::Weighted(v) => 2 * v.iter().map(Vec::len).sum::<usize>(),
        }
    }
}

/// One bone's part of a weighted vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weight {
    /// The bone's index.
    pub bone: usize,
    /// The point in the bone's frame.
    pub point: [f64; 2],
    /// Its weight (a vertex's weights add up to 1).
    pub weight: f64,
}

/// A point on the path and the path's direction there (radians).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Point {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) angle: f64,
}

/// The path's vertices in the world, `deform` added to the file's coordinates first.
pub(crate) fn world_vertices(
    path: &PathShape,
    slot: &Affine,
    world: &dyn Fn(usize) -> Affine,
    deform: Option<&[f64]>,
    out: &mut Vec<[f64; 2]>,
) {
    out.clear();
    extend_world(&path.vertices, slot, world, deform, out);
}

/// Appends `vertices` in the world to `out`, `deform` added to the coordinates first (two per
/// point, per weight entry of a weighted vertex; coordinates past its end get none): a plain
/// vertex goes through `slot`, a weighted one is `Σ weight · world(bone)(x, y)`. A path's and a
/// mesh's vertices alike.
pub(crate) fn extend_world(
    vertices: &PathVertices,
    slot: &Affine,
    world: &dyn Fn(usize) -> Affine,
    deform: Option<&[f64]>,
    out: &mut Vec<[f64; 2]>,
) {
    let offset = |k: usize| {
        deform.map_or([0.0, 0.0], |d| [d.get(2 * k).copied().unwrap_or(0.0), d.get(2 * k + 1).copied().unwrap_or(0.0)])
    };
    match vertices {
        PathVertices::Plain(v) => {
            out.extend(v.iter().enumerate().map(|(k, p)| {
                let o = offset(k);
                slot.to_world(p[0] + o[0], p[1] + o[1])
            }));
        }
        PathVertices::Weighted(v) => {
            let mut k = 0;
            for vertex in v {
                let mut sum = [0.0, 0.0];
                for w in vertex {
                    let o = offset(k);
                    k += 1;
                    let [x, y] = world(w.bone).to_world(w.point[0] + o[0], w.point[1] + o[1]);
                    sum[0] += x * w.weight;
                    sum[1] += y * w.weight;
                }
                out.push(sum);
            }
        }
    }
}

/// How many curves the path has (0 when it has too few vertices).
fn curve_count(path: &PathShape, n: usize) -> usize {
    let knots = n / 3;
    if path.closed { knots } else { knots.saturating_sub(1) }
}

/// Curve `k`'s four control points.
fn curve(v: &[[f64; 2]], k: usize) -> [[f64; 2]; 4] {
    let n = v.len() / 3 * 3;
    [v[3 * k + 1], v[3 * k + 2], v[(3 * k + 3) % n], v[(3 * k + 4) % n]]
}

/// The cubic at parameter `t` and its direction there.
fn at(c: &[[f64; 2]; 4], t: f64) -> Point {
    let u = 1.0 - t;
    let (w0, w1, w2, w3) = (u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t);
    let x = c[0][0] * w0 + c[1][0] * w1 + c[2][0] * w2 + c[3][0] * w3;
    let y = c[0][1] * w0 + c[1][1] * w1 + c[2][1] * w2 + c[3][1] * w3;
    let (d0, d1, d2) = (u * u, 2.0 * u * t, t * t);
    let mut dx = (c[1][0] - c[0][0]) * d0 + (c[2][0] - c[1][0]) * d1 + (c[3][0] - c[2][0]) * d2;
    let mut dy = (c[1][1] - c[0][1]) * d0 + (c[2][1] - c[1][1]) * d1 + (c[3][1] - c[2][1]) * d2;
    if dx == 0.0 && dy == 0.0 {
        dx = c[3][0] - c[0][0];
        dy = c[3][1] - c[0][1];
    }
    Point { x, y, angle: math::atan2(dy, dx) }
}

/// The ten chords' cumulative lengths of a curve (sampled at t = 0.1 … 1).
fn chords<const N: usize>(c: &[[f64; 2]; 4]) -> [f64; N] {
    let mut out = [0.0; N];
    let mut prev = c[0];
    let mut sum = 0.0;
    for (j, o) in out.iter_mut().enumerate() {
        let p = at(c, (j + 1) as f64 / N as f64);
        sum += math::hypot(p.x - prev[0], p.y - prev[1]);
        prev = [p.x, p.y];
        *o = sum;
    }
    out
}

/// Where each curve ends along the path, into `ends` (measured in the world with
/// `constantSpeed`, four chords a curve; else the attachment's `lengths`), and the path's
/// length: the last. `None` when the path has no curve (or, without constant speed, too few
/// `lengths`).
pub(crate) fn ends(path: &PathShape, v: &[[f64; 2]], ends: &mut Vec<f64>) -> Option<f64> {
    ends.clear();
    let curves = curve_count(path, v.len());
    if curves == 0 {
        return None;
    }
    if path.constant_speed {
        let mut at = 0.0;
        for k in 0..curves {
            at += chords::<4>(&curve(v, k))[3];
            ends.push(at);
        }
    } else {
        ends.extend_from_slice(path.lengths.get(..curves)?);
    }
    ends.last().copied()
}

/// The points at `distances` along the path of world vertices `v` whose curves end at `ends`
/// (the last is the path's length).
pub(crate) fn points(path: &PathShape, v: &[[f64; 2]], ends: &[f64], distances: &[f64], out: &mut Vec<Point>) {
    out.clear();
    out.extend(distances.iter().map(|&d| point(path, v, ends, d)));
}

/// The point at distance `d`: on the first curve that ends at or after it (found by a binary
/// search), or on the line past an open path's ends.
fn point(path: &PathShape, v: &[[f64; 2]], ends: &[f64], d: f64) -> Point {
    let (curves, total) = (ends.len(), ends[ends.len() - 1]);
    let mut d = d;
    if path.closed {
        d = if total > 0.0 { d.rem_euclid(total) } else { 0.0 };
    } else if d < 0.0 {
        return line(v[1], [v[1], v[2]], d);
    } else if d > total {
        let last = curves * 3 + 1;
        return line(v[last], [v[last - 1], v[last]], d - total);
    }
    let k = ends.partition_point(|&e| e < d).min(curves - 1);
    let (start, end) = (if k == 0 { 0.0 } else { ends[k - 1] }, ends[k]);
    let c = curve(v, k);
    let span = end - start;
    if !path.constant_speed {
        let t = if span > 0.0 { ((d - start) / span).clamp(0.0, 1.0) } else { 0.0 };
        return at(&c, t);
    }
    // Within the curve: the distance scaled to its ten chords, walked proportionally on the
    // chord it falls on.
    let ch = chords::<10>(&c);
    let q = if span > 0.0 { (d - start) / span * ch[9] } else { 0.0 };
    let j = ch.iter().position(|&l| q <= l).unwrap_or(9);
    let before = if j == 0 { 0.0 } else { ch[j - 1] };
    let seg = ch[j] - before;
    let f = if seg > 0.0 { ((q - before) / seg).clamp(0.0, 1.0) } else { 0.0 };
    at(&c, (j as f64 + f) / 10.0)
}

/// The point at distance `d` from `p` along the direction from `dir[0]` to `dir[1]` (the
/// straight line that continues an open path past its ends), and that direction.
fn line(p: [f64; 2], dir: [[f64; 2]; 2], d: f64) -> Point {
    let (dx, dy) = (dir[1][0] - dir[0][0], dir[1][1] - dir[0][1]);
    let l = math::hypot(dx, dy);
    let (ux, uy) = if l > 0.0 { (dx / l, dy / l) } else { (1.0, 0.0) };
    Point { x: p[0] + ux * d, y: p[1] + uy * d, angle: math::atan2(uy, ux) }
}
