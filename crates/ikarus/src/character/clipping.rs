//! Clipping attachments at draw time: the polygon's world vertices cut into triangles, and the
//! triangles of the region and mesh attachments drawn while it clips cut to it.
//!
//! Rules (Spine's user guide, "Clipping attachments"; Spine 3.6's announcement):
//! - A clipping attachment clips every slot in the draw order from its own slot to its end slot,
//!   inclusive; an end slot that is its own slot (the editor's default), or that is not met
//!   after it, clips to the end of the draw order. Only one clipping area is active at a time: a
//!   clipping attachment shown while another clips is ignored.
//! - The polygon may be concave, without holes or self-intersection. It is cut into triangles by
//!   ear clipping (each ear: a convex corner with no other vertex inside or on it); a polygon
//!   with no ear left (self-intersecting, or all collinear) has its rest cut as a fan.
//! - A clipped triangle is its intersection with each of the polygon's triangles (Sutherland and
//!   Hodgman's clipping by the three edges), each piece cut as a fan; a new vertex's texture
//!   coordinates are interpolated along the cut edge (exact: they are affine over the
//!   triangle). An intersection is computed from the edge's end points in one order whichever
//!   triangle it belongs to, so two triangles sharing an edge share the cut points bit for bit.
//! - A polygon of no area keeps nothing of what it clips. One of fewer than 3 or more than
//!   [`MAX_CLIP_VERTICES`] vertices, or with a vertex not finite, clips nothing (the reader
//!   refuses or lists it first). The work per clipped triangle is bounded by the number of the
//!   polygon's triangles.

/// The most vertices a clipping polygon may have (ear clipping takes about `n³` steps).
pub const MAX_CLIP_VERTICES: usize = 256;

/// A point and its texture coordinates.
type Point = ([f64; 2], [f64; 2]);

/// The active clipping polygon, cut into counter-clockwise triangles, with scratch buffers
/// (reused from frame to frame).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Clipper {
    /// The end slot while a polygon clips (`Some(None)`: to the end of the draw order).
    end: Option<Option<usize>>,
    /// The polygon's world vertices.
    pub(crate) polygon: Vec<[f64; 2]>,
    /// Its triangles, counter-clockwise.
    pieces: Vec<[[f64; 2]; 3]>,
    /// Scratch: the polygon's vertex indices not yet cut off.
    left: Vec<usize>,
    /// Scratch: a piece being cut, and the next.
    work: [Vec<Point>; 2],
    /// Scratch: the clipped vertices, texture coordinates and triangles of one item.
    pub(crate) vertices: Vec<[f64; 2]>,
    pub(crate) uvs: Vec<[f64; 2]>,
    pub(crate) triangles: Vec<u32>,
}

/// Twice the signed area of triangle `a b c` (positive: counter-clockwise).
fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

impl Clipper {
    /// Whether a polygon clips.
    pub(crate) fn active(&self) -> bool {
        self.end.is_some()
    }

    /// Stops clipping.
    pub(crate) fn reset(&mut self) {
        self.end = None;
        self.pieces.clear();
    }

    /// Stops clipping if slot `slot` is the end slot.
    pub(crate) fn passed(&mut self, slot: usize) {
        if self.end == Some(Some(slot)) {
            self.reset();
        }
    }

    /// Starts clipping with the polygon in [`Clipper::polygon`] (world vertices), shown by slot
    /// `slot`, up to slot `end`.
    pub(crate) fn start(&mut self, slot: usize, end: usize) {
        self.pieces.clear();
        let n = self.polygon.len();
        if !(3..=MAX_CLIP_VERTICES).contains(&n) || self.polygon.iter().flatten().any(|v| !v.is_finite()) {
            return;
        }
        self.end = Some((end != slot).then_some(end));
        let area: f64 = (0..n).map(|i| cross([0.0, 0.0], self.polygon[i], self.polygon[(i + 1) % n])).sum();
        if area == 0.0 {
            return;
        }
        self.left.clear();
        self.left.extend(0..n);
        if area < 0.0 {
            self.left.reverse();
        }
        while self.left.len() > 3 {
            let m = self.left.len();
            let at = |k: usize| self.polygon[self.left[k % m]];
            let ear = (0..m).find(|&k| {
                let (a, b, c) = (at(k + m - 1), at(k), at(k + 1));
                cross(a, b, c) > 0.0
                    && (0..m).filter(|&j| j != k && j != (k + m - 1) % m && j != (k + 1) % m).all(|j| {
                        let p = at(j);
                        !(cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0)
                    })
            });
            match ear {
                Some(k) => {
                    self.pieces.push([at(k + m - 1), at(k), at(k + 1)]);
                    self.left.remove(k);
                }
                None => {
                    for k in 1..m - 1 {
                        self.pieces.push([at(0), at(k), at(k + 1)]);
                    }
                    self.left.clear();
                }
            }
        }
        if self.left.len() == 3 {
            self.pieces.push([0, 1, 2].map(|k| self.polygon[self.left[k]]));
        }
        // A piece of no area (collinear corners) keeps nothing; the rest turn counter-clockwise.
        self.pieces.retain(|p| cross(p[0], p[1], p[2]) != 0.0);
        for p in &mut self.pieces {
            if cross(p[0], p[1], p[2]) < 0.0 {
                p.swap(1, 2);
            }
        }
    }

    /// Cuts the triangles `triangles` (indices into `vertices` and `uvs`) to the polygon, into
    /// [`Clipper::vertices`], [`Clipper::uvs`] and [`Clipper::triangles`] (cleared first).
    pub(crate) fn clip(&mut self, vertices: &[[f64; 2]], uvs: &[[f64; 2]], triangles: &[u32]) {
        self.vertices.clear();
        self.uvs.clear();
        self.triangles.clear();
        for t in triangles.chunks_exact(3) {
            let corner = |k: u32| (vertices[k as usize], uvs[k as usize]);
            let triangle = [corner(t[0]), corner(t[1]), corner(t[2])];
            for p in 0..self.pieces.len() {
                let piece = self.pieces[p];
                let [mut from, mut to] = std::mem::take(&mut self.work);
                from.clear();
                from.extend_from_slice(&triangle);
                for e in 0..3 {
                    cut(&from, piece[e], piece[(e + 1) % 3], &mut to);
                    std::mem::swap(&mut from, &mut to);
                }
                if from.len() >= 3 {
                    let base = self.vertices.len() as u32;
                    self.vertices.extend(from.iter().map(|p| p.0));
                    self.uvs.extend(from.iter().map(|p| p.1));
                    for k in 1..from.len() as u32 - 1 {
                        self.triangles.extend_from_slice(&[base, base + k, base + k + 1]);
                    }
                }
                self.work = [from, to];
            }
        }
    }
}

/// Sutherland and Hodgman's step: the part of convex polygon `from` on the left of (or on) the
/// line `a → b`, into `to` (cleared first).
fn cut(from: &[Point], a: [f64; 2], b: [f64; 2], to: &mut Vec<Point>) {
    to.clear();
    let n = from.len();
    for i in 0..n {
        let (p, q) = (from[i], from[(i + 1) % n]);
        let (dp, dq) = (cross(a, b, p.0), cross(a, b, q.0));
        if dp >= 0.0 {
            to.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            // The same cut point whichever way round the edge is met.
            let ((s, ds), (e, de)) = if p.0 <= q.0 { ((p, dp), (q, dq)) } else { ((q, dq), (p, dp)) };
            let t = ds / (ds - de);
            let lerp = |u: [f64; 2], v: [f64; 2]| [u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1])];
            to.push((lerp(s.0, e.0), lerp(s.1, e.1)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(v: &[[f64; 2]], t: &[u32]) -> f64 {
        t.chunks_exact(3).map(|t| 0.5 * cross(v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]).abs()).sum()
    }

    fn clipper(polygon: &[[f64; 2]]) -> Clipper {
        let mut c = Clipper { polygon: polygon.to_vec(), ..Clipper::default() };
        c.start(0, 0);
        c
    }

    #[test]
    fn a_concave_polygon_is_cut_into_triangles_covering_it() {
        // An L of area 3 (three unit squares), clockwise: turned counter-clockwise first.
        let l = [[0.0, 0.0], [0.0, 2.0], [1.0, 2.0], [1.0, 1.0], [2.0, 1.0], [2.0, 0.0]];
        let c = clipper(&l);
        assert!(c.active());
        assert_eq!(c.pieces.len(), 4);
        assert!(c.pieces.iter().all(|p| cross(p[0], p[1], p[2]) > 0.0));
        let total: f64 = c.pieces.iter().map(|p| 0.5 * cross(p[0], p[1], p[2])).sum();
        assert_eq!(total, 3.0);
        // Too few vertices: no clipping. No area: clipping that keeps nothing.
        assert!(!clipper(&[[0.0, 0.0], [1.0, 1.0]]).active());
        let flat = clipper(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]);
        assert!(flat.active() && flat.pieces.is_empty());
    }

    #[test]
    fn a_triangle_is_cut_to_the_polygon_with_its_texture_coordinates() {
        // The L again; a square 0..2 × 0..2 with u = x/2, v = y/2 keeps the L: area 3, and every
        // vertex keeps u = x/2, v = y/2.
        let l = [[0.0, 0.0], [0.0, 2.0], [1.0, 2.0], [1.0, 1.0], [2.0, 1.0], [2.0, 0.0]];
        let mut c = clipper(&l);
        let square = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let uvs = square.map(|p| [p[0] / 2.0, p[1] / 2.0]);
        c.clip(&square, &uvs, &[0, 1, 2, 2, 3, 0]);
        assert!((area(&c.vertices, &c.triangles) - 3.0).abs() < 1e-12);
        assert!(c.vertices.iter().zip(&c.uvs).all(|(p, uv)| *uv == [p[0] / 2.0, p[1] / 2.0]));
        // Every kept point is in the L (x ≤ 1 or y ≤ 1, within 0..2).
        assert!(c.vertices.iter().all(|p| (p[0] <= 1.0 || p[1] <= 1.0) && p.iter().all(|v| (0.0..=2.0).contains(v))));
        // A triangle outside keeps nothing; one inside is kept whole.
        c.clip(&[[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]], &[[0.0; 2]; 3], &[0, 1, 2]);
        assert!(c.triangles.is_empty());
        c.clip(&[[0.1, 0.1], [0.9, 0.1], [0.1, 0.9]], &[[0.0; 2]; 3], &[0, 1, 2]);
        assert!((area(&c.vertices, &c.triangles) - 0.32).abs() < 1e-12);
    }

    #[test]
    fn the_end_slot_ends_clipping_and_its_own_slot_means_the_end_of_the_draw_order() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut c = Clipper { polygon: square.to_vec(), ..Clipper::default() };
        c.start(2, 5);
        c.passed(4);
        assert!(c.active());
        c.passed(5);
        assert!(!c.active());
        c.polygon = square.to_vec();
        c.start(2, 2);
        c.passed(2);
        assert!(c.active(), "its own slot as the end: to the end of the draw order");
    }
}
