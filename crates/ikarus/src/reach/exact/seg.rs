//! The two kinds of boundary piece, line segments and circular arcs, with what the sweep, the
//! union and the queries ask of them: points along them, sub-pieces, rotation and translation,
//! bounding boxes, intersections, the area under them, and the nearest point.
//!
//! An arc is stored with its end points as given (so that pieces that share a vertex share it
//! bit for bit) and with its start angle and signed sweep (counter-clockwise positive), from
//! which everything between the ends is computed. A full circle has equal ends and a sweep of
//! ±2π.

use std::f64::consts::{PI, TAU};

use crate::math;

/// A point or vector.
pub(crate) type P = [f64; 2];

#[inline]
pub(crate) fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1]]
}
#[inline]
pub(crate) fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}
#[inline]
pub(crate) fn scale(a: P, s: f64) -> P {
    [a[0] * s, a[1] * s]
}
#[inline]
pub(crate) fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
#[inline]
pub(crate) fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
#[inline]
pub(crate) fn norm(a: P) -> f64 {
    math::hypot(a[0], a[1])
}
#[inline]
pub(crate) fn dist(a: P, b: P) -> f64 {
    norm(sub(a, b))
}
#[inline]
pub(crate) fn unit(t: f64) -> P {
    let (s, c) = math::sin_cos(t);
    [c, s]
}
/// `a` turned by the angle whose cosine and sine are `cs`.
#[inline]
pub(crate) fn rotate(a: P, cs: P) -> P {
    [cs[0] * a[0] - cs[1] * a[1], cs[1] * a[0] + cs[0] * a[1]]
}
#[inline]
pub(crate) fn angle_of(a: P) -> f64 {
    math::atan2(a[1], a[0])
}

/// Where a boundary piece came from: the pose family whose tip traces it, one level down.
///
/// Level `k`'s set is the tip's reach relative to joint `k`, in the frame in which joint `k`'s
/// angle is measured; level `k + 1`'s set moved out along link `k` is the set that joint `k`
/// turns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Prov {
    /// Joint `k` held at `theta` (an end of its range): the piece is level `k + 1`'s piece
    /// `child`, moved out along link `k` and turned by `theta`.
    Copy { theta: f64, child: u32 },
    /// Joint `k` turning: the piece is an arc about joint `k` traced by the point `point` of
    /// level `k + 1` (on its piece `child`, or the level's single point if `None`), which sits
    /// at the angle `phase` once moved out along link `k`.
    Orbit { child: Option<u32>, point: P, phase: f64 },
}

/// A line segment or a circular arc from `a` to `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Seg {
    pub(crate) a: P,
    pub(crate) b: P,
    pub(crate) arc: Option<Arc>,
    pub(crate) prov: Prov,
}

/// The circle and angles of an arc: `c + r·e^{i(t0 + u·dt)}` for `u` in `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Arc {
    pub(crate) c: P,
    pub(crate) r: f64,
    pub(crate) t0: f64,
    pub(crate) dt: f64,
}

/// An axis-aligned box `[x0, x1] × [y0, y1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Bbox {
    pub(crate) x0: f64,
    pub(crate) y0: f64,
    pub(crate) x1: f64,
    pub(crate) y1: f64,
}

impl Bbox {
    pub(crate) const EMPTY: Bbox =
        Bbox { x0: f64::INFINITY, y0: f64::INFINITY, x1: f64::NEG_INFINITY, y1: f64::NEG_INFINITY };

    pub(crate) fn add(&mut self, p: P) {
        self.x0 = self.x0.min(p[0]);
        self.y0 = self.y0.min(p[1]);
        self.x1 = self.x1.max(p[0]);
        self.y1 = self.y1.max(p[1]);
    }

    pub(crate) fn union(&mut self, o: &Bbox) {
        self.x0 = self.x0.min(o.x0);
        self.y0 = self.y0.min(o.y0);
        self.x1 = self.x1.max(o.x1);
        self.y1 = self.y1.max(o.y1);
    }

    pub(crate) fn overlaps(&self, o: &Bbox, slack: f64) -> bool {
        self.x0 <= o.x1 + slack && o.x0 <= self.x1 + slack && self.y0 <= o.y1 + slack && o.y0 <= self.y1 + slack
    }

    pub(crate) fn contains(&self, p: P, slack: f64) -> bool {
        self.x0 - slack <= p[0] && p[0] <= self.x1 + slack && self.y0 - slack <= p[1] && p[1] <= self.y1 + slack
    }

    /// Distance from `p` to the box (0 inside).
    pub(crate) fn distance(&self, p: P) -> f64 {
        let dx = (self.x0 - p[0]).max(p[0] - self.x1).max(0.0);
        let dy = (self.y0 - p[1]).max(p[1] - self.y1).max(0.0);
        math::hypot(dx, dy)
    }
}

/// `t` moved by whole turns into `[0, 2π)`.
#[inline]
pub(crate) fn turn(t: f64) -> f64 {
    let w = t.rem_euclid(TAU);
    if w >= TAU { 0.0 } else { w }
}

impl Seg {
    pub(crate) fn line(a: P, b: P, prov: Prov) -> Seg {
        Seg { a, b, arc: None, prov }
    }

    /// The arc about `c` of radius `r` from angle `t0` through the signed sweep `dt`, its ends
    /// `a` and `b` given by the caller (on the circle at those angles).
    pub(crate) fn arc(c: P, r: f64, t0: f64, dt: f64, a: P, b: P, prov: Prov) -> Seg {
        Seg { a, b, arc: Some(Arc { c, r, t0, dt }), prov }
    }

    pub(crate) fn is_full_circle(&self) -> bool {
        self.arc.is_some_and(|a| a.dt.abs() >= TAU)
    }

    /// The point at parameter `u` in `[0, 1]` (the stored ends at 0 and 1).
    pub(crate) fn at(&self, u: f64) -> P {
        if u == 0.0 {
            return self.a;
        }
        if u == 1.0 {
            return self.b;
        }
        match self.arc {
            None => add(self.a, scale(sub(self.b, self.a), u)),
            Some(k) => add(k.c, scale(unit(k.t0 + u * k.dt), k.r)),
        }
    }

    /// Length of the piece.
    pub(crate) fn length(&self) -> f64 {
        match self.arc {
            None => dist(self.a, self.b),
            Some(k) => k.r * k.dt.abs(),
        }
    }

    /// The parameter of a point `p` on (or next to) the piece: the projection for a line, the
    /// angle from the start along the sweep for an arc (in `[0, 2π)` turned into the sweep's
    /// sense, so a point before the start reads as near the end of a full turn).
    pub(crate) fn param(&self, p: P) -> f64 {
        match self.arc {
            None => {
                let d = sub(self.b, self.a);
                let l2 = dot(d, d);
                if l2 == 0.0 { 0.0 } else { dot(sub(p, self.a), d) / l2 }
            }
            Some(k) => {
                let t = angle_of(sub(p, k.c));
                let off = if k.dt >= 0.0 { turn(t - k.t0) } else { turn(k.t0 - t) };
                off / k.dt.abs()
            }
        }
    }

    /// The piece from parameter `u0` to `u1`, with the ends `pa` and `pb` as given.
    pub(crate) fn sub(&self, u0: f64, u1: f64, pa: P, pb: P) -> Seg {
        match self.arc {
            None => Seg::line(pa, pb, self.prov),
            Some(k) => Seg::arc(k.c, k.r, k.t0 + u0 * k.dt, (u1 - u0) * k.dt, pa, pb, self.prov),
        }
    }

    /// The piece run backwards.
    pub(crate) fn reversed(&self) -> Seg {
        match self.arc {
            None => Seg::line(self.b, self.a, self.prov),
            Some(k) => Seg::arc(k.c, k.r, k.t0 + k.dt, -k.dt, self.b, self.a, self.prov),
        }
    }

    /// The piece turned about the origin by `theta` (with `cs = (cos θ, sin θ)`), then moved by
    /// `shift`.
    pub(crate) fn moved(&self, theta: f64, cs: P, shift: P, prov: Prov) -> Seg {
        let m = |p: P| add(rotate(p, cs), shift);
        match self.arc {
            None => Seg::line(m(self.a), m(self.b), prov),
            Some(k) => Seg::arc(m(k.c), k.r, k.t0 + theta, k.dt, m(self.a), m(self.b), prov),
        }
    }

    /// The midpoint and the unit normal pointing to the piece's left.
    pub(crate) fn mid_and_left(&self) -> (P, P) {
        match self.arc {
            None => {
                let d = sub(self.b, self.a);
                let l = norm(d);
                (scale(add(self.a, self.b), 0.5), [-d[1] / l, d[0] / l])
            }
            Some(k) => {
                let e = unit(k.t0 + 0.5 * k.dt);
                let n = if k.dt > 0.0 { [-e[0], -e[1]] } else { e };
                (add(k.c, scale(e, k.r)), n)
            }
        }
    }

    pub(crate) fn bbox(&self) -> Bbox {
        let mut b = Bbox::EMPTY;
        b.add(self.a);
        b.add(self.b);
        if let Some(k) = self.arc {
            // The axis extremes the arc passes: angles 0, π/2, π, 3π/2.
            let (lo, span) = if k.dt >= 0.0 { (k.t0, k.dt) } else { (k.t0 + k.dt, -k.dt) };
            for q in 0..4 {
                let t = f64::from(q) * PI / 2.0;
                if turn(t - lo) <= span {
                    b.add(add(k.c, scale(unit(t), k.r)));
                }
            }
        }
        b
    }

    /// `½ ∫ (x dy − y dx)` along the piece: summed over a closed loop, its signed area.
    /// For an arc `p(t) = c + r e^{it}` it is `½ (c × (b − a) + r² Δt)`.
    pub(crate) fn area_term(&self) -> f64 {
        match self.arc {
            None => 0.5 * cross(self.a, self.b),
            Some(k) => 0.5 * (cross(k.c, sub(self.b, self.a)) + k.r * k.r * k.dt),
        }
    }

    /// The point of the piece nearest `p`.
    pub(crate) fn nearest(&self, p: P) -> P {
        match self.arc {
            None => {
                let u = self.param(p).clamp(0.0, 1.0);
                self.at(u)
            }
            Some(k) => {
                let v = sub(p, k.c);
                let d = norm(v);
                if d > 0.0 && self.spans(angle_of(v)) {
                    add(k.c, scale(v, k.r / d))
                } else if dist(p, self.a) <= dist(p, self.b) {
                    self.a
                } else {
                    self.b
                }
            }
        }
    }

    /// Whether the arc passes the direction `t` from its centre (always for a line).
    pub(crate) fn spans(&self, t: f64) -> bool {
        match self.arc {
            None => true,
            Some(k) => {
                let off = if k.dt >= 0.0 { turn(t - k.t0) } else { turn(k.t0 - t) };
                off <= k.dt.abs()
            }
        }
    }

    /// The piece cut where its distance from the origin turns (so each part moves steadily
    /// outward or inward), each part run outward; parts of no length are left out, and so are
    /// arcs about the origin (of constant distance) unless `keep_level`.
    pub(crate) fn radial_parts(&self, out: &mut Vec<Seg>, keep_level: bool) {
        let mut cuts: [f64; 2] = [f64::NAN; 2];
        match self.arc {
            None => {
                let d = sub(self.b, self.a);
                let l2 = dot(d, d);
                if l2 == 0.0 {
                    return;
                }
                cuts[0] = -dot(self.a, d) / l2;
            }
            Some(k) => {
                if norm(k.c) == 0.0 {
                    if keep_level {
                        out.push(*self);
                    }
                    return;
                }
                // Farthest from the origin towards the centre's direction, nearest opposite.
                let t = angle_of(k.c);
                for (i, t) in [t, t + PI].into_iter().enumerate() {
                    let off = if k.dt >= 0.0 { turn(t - k.t0) } else { turn(k.t0 - t) };
                    cuts[i] = off / k.dt.abs();
                }
            }
        }
        let mut us: Vec<f64> = cuts.into_iter().filter(|u| *u > 0.0 && *u < 1.0).collect();
        us.sort_by(f64::total_cmp);
        let mut u0 = 0.0;
        let mut p0 = self.a;
        for u in us.into_iter().chain(std::iter::once(1.0)) {
            let p1 = self.at(u);
            if p1 != p0 {
                let part = self.sub(u0, u, p0, p1);
                out.push(if norm(p1) >= norm(p0) { part } else { part.reversed() });
            }
            u0 = u;
            p0 = p1;
        }
    }
}

/// Where two pieces meet: the points common to both (a crossing, a touching point, or the ends
/// of a stretch they share), each within `tol` of both.
///
/// Ends of either piece within `merge` of the other come first (shared stretches,
/// T-junctions, touching ends), then crossings; curves closer than `tangent` to touching give
/// one point, the foot of the line through the two centres (or of the perpendicular), which is
/// found accurately where the crossings are not.
pub(crate) fn intersections(s: &Seg, t: &Seg, merge: f64, tangent: f64, out: &mut Vec<P>) {
    for (x, y) in [(s, t), (t, s)] {
        for p in [x.a, x.b] {
            if dist(y.nearest(p), p) <= merge {
                out.push(p);
            }
        }
    }
    let ends = out.len();
    match (s.arc, t.arc) {
        (None, None) => line_line(s, t, out),
        (None, Some(k)) => line_circle(s, k.c, k.r, tangent, out),
        (Some(k), None) => line_circle(t, k.c, k.r, tangent, out),
        (Some(k1), Some(k2)) => circle_circle(k1.c, k1.r, k2.c, k2.r, merge, tangent, out),
    }
    let mut k = ends;
    while k < out.len() {
        let p = out[k];
        let on_both = dist(s.nearest(p), p) <= tangent && dist(t.nearest(p), p) <= tangent;
        if on_both && !out[..k].iter().any(|&q| dist(p, q) <= merge) {
            k += 1;
        } else {
            out.remove(k);
        }
    }
}

fn line_line(s: &Seg, t: &Seg, out: &mut Vec<P>) {
    let d1 = sub(s.b, s.a);
    let d2 = sub(t.b, t.a);
    let den = cross(d1, d2);
    let scale_ = norm(d1) * norm(d2);
    if den.abs() <= 1e-14 * scale_ {
        return; // parallel: shared stretches come from the end points
    }
    let w = sub(t.a, s.a);
    let u = cross(w, d2) / den;
    out.push(add(s.a, scale(d1, u)));
}

fn line_circle(s: &Seg, c: P, r: f64, tol: f64, out: &mut Vec<P>) {
    let d = sub(s.b, s.a);
    let l = norm(d);
    if l == 0.0 {
        return;
    }
    let e = scale(d, 1.0 / l);
    let w = sub(c, s.a);
    let along = dot(w, e);
    let off = cross(e, w); // signed distance of the centre from the line
    let h2 = r * r - off * off;
    let foot = add(s.a, scale(e, along));
    if h2 < 0.0 {
        if r - off.abs() >= -tol {
            out.push(foot); // touching, up to rounding
        }
        return;
    }
    let h = h2.sqrt();
    if h <= tol {
        out.push(foot);
    } else {
        out.push(add(foot, scale(e, h)));
        out.push(sub(foot, scale(e, h)));
    }
}

fn circle_circle(c1: P, r1: f64, c2: P, r2: f64, merge: f64, tol: f64, out: &mut Vec<P>) {
    let v = sub(c2, c1);
    let d = norm(v);
    if d <= merge {
        return; // concentric: a shared stretch comes from the end points
    }
    let a = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    let h2 = r1 * r1 - a * a;
    let e = scale(v, 1.0 / d);
    let foot = add(c1, scale(e, a));
    if h2 < 0.0 {
        // Apart or nested: a touching point only if the gap is within the tolerance.
        let gap = (d - (r1 + r2)).abs().min((d - (r1 - r2).abs()).abs());
        if gap <= tol {
            out.push(foot);
        }
        return;
    }
    let h = h2.sqrt();
    if h <= tol {
        out.push(foot);
    } else {
        let n = [-e[1], e[0]];
        out.push(add(foot, scale(n, h)));
        out.push(sub(foot, scale(n, h)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ORIGIN: Prov = Prov::Orbit { child: None, point: [0.0, 0.0], phase: 0.0 };

    #[test]
    fn an_arcs_area_term_sums_to_a_circles_area() {
        let c = [0.3, -0.2];
        let r = 1.7;
        let quarter = |q: f64| {
            let t0 = q * PI / 2.0;
            let t1 = t0 + PI / 2.0;
            Seg::arc(c, r, t0, PI / 2.0, add(c, scale(unit(t0), r)), add(c, scale(unit(t1), r)), ORIGIN)
        };
        let area: f64 = (0..4).map(|q| quarter(f64::from(q)).area_term()).sum();
        assert!((area - PI * r * r).abs() < 1e-12, "{area}");
    }

    #[test]
    fn radial_parts_move_steadily_outward() {
        let c = [2.0, 0.0];
        let s = Seg::arc(c, 1.0, -PI, TAU, [1.0, 0.0], [1.0, 0.0], ORIGIN);
        let mut parts = Vec::new();
        s.radial_parts(&mut parts, false);
        assert_eq!(parts.len(), 2);
        for p in &parts {
            let n = 64;
            let r: Vec<f64> = (0..=n).map(|i| norm(p.at(f64::from(i) / f64::from(n)))).collect();
            assert!(r.windows(2).all(|w| w[1] >= w[0] - 1e-12), "{r:?}");
            assert!((r[0] - 1.0).abs() < 1e-12 && (r[n as usize] - 3.0).abs() < 1e-12);
        }
    }

    #[test]
    fn circles_cross_where_both_equations_hold() {
        let s = Seg::arc([0.0, 0.0], 1.0, 0.0, TAU, [1.0, 0.0], [1.0, 0.0], ORIGIN);
        let t = Seg::arc([1.0, 0.5], 0.8, 0.0, TAU, [1.8, 0.5], [1.8, 0.5], ORIGIN);
        let mut out = Vec::new();
        intersections(&s, &t, 1e-12, 1e-10, &mut out);
        assert_eq!(out.len(), 2);
        for p in out {
            assert!((norm(p) - 1.0).abs() < 1e-12);
            assert!((dist(p, [1.0, 0.5]) - 0.8).abs() < 1e-12);
        }
    }
}
