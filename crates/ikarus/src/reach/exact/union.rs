//! The union of regions bounded by lines and arcs.
//!
//! Every piece's boundary is cut wherever it meets another piece's; a cut part is on the
//! union's boundary exactly when the point just to its right (outside its own piece) lies in
//! no piece. That test treats shared stretches of boundary the way they must be treated: two
//! pieces on the same side of a shared stretch keep it once, pieces on opposite sides drop it.
//! The parts kept are chained end to end into closed loops (region on the left: outer
//! boundaries counter-clockwise, holes clockwise), and consecutive parts of one input piece are
//! joined again.
//!
//! Robustness: points closer than [`Tol::merge`] are one point, crossings of circles that meet
//! at a gap or depth below [`Tol::tangent`] are one touching point (where both are found
//! accurately: the foot of the two centres' line), and the side test looks a hundredth of a
//! part's length (at most `1e-8` of the scale) off its middle.

use super::seg::{Bbox, P, Seg, add, cross, dist, intersections, scale, sub};
use super::work::{Stop, Work};

/// Tolerances, each a fixed fraction of the scale of the problem (the chain's reach).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tol {
    /// Points this close are the same point.
    pub(crate) merge: f64,
    /// Circles (or a line and a circle) this close to touching touch at one point.
    pub(crate) tangent: f64,
    /// The farthest the side test looks off a part.
    pub(crate) probe: f64,
}

impl Tol {
    pub(crate) fn of_scale(s: f64) -> Tol {
        Tol { merge: 1e-9 * s, tangent: 1e-7 * s, probe: 1e-8 * s }
    }
}

/// A closed region: its boundary loops (region on the left) and their bounding box.
#[derive(Debug, Clone)]
pub(crate) struct Piece {
    pub(crate) segs: Vec<Seg>,
    pub(crate) bbox: Bbox,
}

impl Piece {
    pub(crate) fn new(segs: Vec<Seg>) -> Piece {
        let mut bbox = Bbox::EMPTY;
        for s in &segs {
            bbox.union(&s.bbox());
        }
        Piece { segs, bbox }
    }
}

/// The winding number of closed loops of pieces about `p` (not on them): the winding number
/// of the polygon of their chords, plus, for each arc, its sense if `p` lies between the arc
/// and its chord (the arc and the reversed chord bound that circular segment once, in the
/// arc's sense).
pub(crate) fn winding(segs: &[Seg], p: P) -> i32 {
    let mut wn = 0;
    for s in segs {
        let (a, b) = (s.a, s.b);
        if a[1] <= p[1] {
            if b[1] > p[1] && cross(sub(b, a), sub(p, a)) > 0.0 {
                wn += 1;
            }
        } else if b[1] <= p[1] && cross(sub(b, a), sub(p, a)) < 0.0 {
            wn -= 1;
        }
        if let Some(k) = s.arc {
            if dist(p, k.c) < k.r && between_arc_and_chord(s, p) {
                wn += if k.dt > 0.0 { 1 } else { -1 };
            }
        }
    }
    wn
}

/// A piece prepared for the winding number of many points: its chord, and for an arc the
/// circle's centre, squared radius, sense, and on which side of the chord the arc bulges.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Prepared {
    a: P,
    b: P,
    c: P,
    r2: f64,
    /// +1 or −1 for an arc's sense, 0 for a line.
    sense: i32,
    /// The sign of `(b − a) × (m − a)` for the arc's midpoint `m`; 0 for a full circle.
    bulge: f64,
}

impl Prepared {
    pub(crate) fn of(s: &Seg) -> Prepared {
        match s.arc {
            None => Prepared { a: s.a, b: s.b, c: [0.0; 2], r2: 0.0, sense: 0, bulge: 0.0 },
            Some(k) => {
                let bulge = if s.is_full_circle() {
                    0.0
                } else {
                    let (m, _) = s.mid_and_left();
                    cross(sub(s.b, s.a), sub(m, s.a)).signum()
                };
                Prepared { a: s.a, b: s.b, c: k.c, r2: k.r * k.r, sense: if k.dt > 0.0 { 1 } else { -1 }, bulge }
            }
        }
    }
}

/// [`winding`] over prepared pieces: the same rule without a square root or a sine.
pub(crate) fn winding_prepared(segs: &[Prepared], p: P) -> i32 {
    let mut wn = 0;
    for s in segs {
        let (a, b) = (s.a, s.b);
        let side = cross(sub(b, a), sub(p, a));
        if a[1] <= p[1] {
            if b[1] > p[1] && side > 0.0 {
                wn += 1;
            }
        } else if b[1] <= p[1] && side < 0.0 {
            wn -= 1;
        }
        if s.sense != 0 {
            let d = sub(p, s.c);
            if d[0] * d[0] + d[1] * d[1] < s.r2 && (s.bulge == 0.0 || side * s.bulge > 0.0) {
                wn += s.sense;
            }
        }
    }
    wn
}

/// Whether `p` (inside the arc's circle) lies on the arc's side of its chord.
fn between_arc_and_chord(s: &Seg, p: P) -> bool {
    if s.is_full_circle() {
        return true;
    }
    let d = sub(s.b, s.a);
    let (m, _) = s.mid_and_left();
    let side_m = cross(d, sub(m, s.a));
    let side_p = cross(d, sub(p, s.a));
    side_m * side_p > 0.0
}

/// The boundary of the union of `pieces`, as closed loops, and the number of chains of kept
/// parts that did not close (0 unless the side test was fooled by curves nearer than it looks);
/// `Err` when `work` runs out or is interrupted. The work is the pairs of items whose boxes
/// overlap in x (each tested for crossings), the cut points compared with each other, and for
/// each cut part the pieces its side test looks at and the segments their winding numbers walk.
pub(crate) fn union(pieces: &[Piece], tol: Tol, work: &mut Work<'_>) -> Result<(Vec<Vec<Seg>>, usize), Stop> {
    struct Item {
        piece: usize,
        seg: Seg,
        bbox: Bbox,
    }
    let items: Vec<Item> = pieces
        .iter()
        .enumerate()
        .flat_map(|(i, p)| p.segs.iter().map(move |s| Item { piece: i, seg: *s, bbox: s.bbox() }))
        .filter(|it| it.seg.length() > tol.merge)
        .collect();
    work.spend_n(items.len())?;

    // Cut points of every item, found by a sweep over the boxes' left edges.
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&i, &j| items[i].bbox.x0.total_cmp(&items[j].bbox.x0));
    let mut cuts: Vec<Vec<P>> = vec![Vec::new(); items.len()];
    let mut found = Vec::new();
    for (n, &i) in order.iter().enumerate() {
        let mut pairs = 1;
        for &j in &order[n + 1..] {
            if items[j].bbox.x0 > items[i].bbox.x1 + tol.merge {
                break;
            }
            pairs += 1;
            if items[i].piece == items[j].piece || !items[i].bbox.overlaps(&items[j].bbox, tol.merge) {
                continue;
            }
            found.clear();
            intersections(&items[i].seg, &items[j].seg, tol.merge, tol.tangent, &mut found);
            for &p in &found {
                cuts[i].push(p);
                cuts[j].push(p);
            }
        }
        work.spend(pairs)?;
    }

    // Cut parts, each kept if just right of it lies in no piece.
    struct Part {
        seg: Seg,
        source: usize,
        u0: f64,
    }
    let mut kept: Vec<Part> = Vec::new();
    for (i, item) in items.iter().enumerate() {
        let s = &item.seg;
        // Each cut point is compared with those kept before it.
        work.spend_n(cuts[i].len().saturating_mul(cuts[i].len()) / 2 + 1)?;
        let mut points: Vec<(f64, P)> = Vec::with_capacity(cuts[i].len());
        for &p in &cuts[i] {
            if dist(p, s.a) <= tol.merge || dist(p, s.b) <= tol.merge {
                continue;
            }
            if points.iter().any(|&(_, q)| dist(p, q) <= tol.merge) {
                continue;
            }
            points.push((s.param(p), p));
        }
        points.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut u0 = 0.0;
        let mut p0 = s.a;
        for (u1, p1) in points.into_iter().chain(std::iter::once((1.0, s.b))) {
            let part = s.sub(u0, u1, p0, p1);
            if (part.length() > tol.merge || part.is_full_circle()) && on_boundary(&part, pieces, tol, work)? {
                kept.push(Part { seg: part, source: i, u0 });
            }
            u0 = u1;
            p0 = p1;
        }
    }

    // The same stretch kept from two pieces on the same side: keep it once.
    let key = |p: P| [(p[0] / tol.merge).round() as i64, (p[1] / tol.merge).round() as i64];
    let mut seen = std::collections::HashSet::new();
    kept.retain(|part| {
        let (m, _) = part.seg.mid_and_left();
        seen.insert((key(part.seg.a), key(part.seg.b), key(m)))
    });

    // Chain the parts into loops through their shared end points.
    let mut vertices: Vec<P> = Vec::new();
    let mut grid: std::collections::HashMap<[i64; 2], Vec<usize>> = std::collections::HashMap::new();
    let cell = tol.merge * 4.0;
    let mut vertex_of = |p: P| -> usize {
        let k = [(p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64];
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&[k[0] + dx, k[1] + dy]) {
                    for &v in list {
                        if dist(vertices[v], p) <= tol.merge {
                            return v;
                        }
                    }
                }
            }
        }
        vertices.push(p);
        grid.entry(k).or_default().push(vertices.len() - 1);
        vertices.len() - 1
    };
    let ends: Vec<(usize, usize)> = kept.iter().map(|p| (vertex_of(p.seg.a), vertex_of(p.seg.b))).collect();
    let mut outgoing: Vec<Vec<usize>> = vec![Vec::new(); vertices.len()];
    for (e, &(va, _)) in ends.iter().enumerate() {
        outgoing[va].push(e);
    }
    let mut used = vec![false; kept.len()];
    let mut loops = Vec::new();
    let mut open = 0;
    for first in 0..kept.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut path = vec![first];
        let start = ends[first].0;
        let mut at = ends[first].1;
        let mut closed = at == start;
        while !closed {
            let Some(&next) = outgoing[at].iter().find(|&&e| !used[e]) else { break };
            used[next] = true;
            path.push(next);
            at = ends[next].1;
            closed = at == start;
        }
        open += usize::from(!closed);
        if closed {
            loops.push(join(&path, &kept.iter().map(|p| (p.seg, p.source, p.u0)).collect::<Vec<_>>()));
        }
    }
    Ok((loops, open))
}

/// Whether a cut part bounds the union: the point just right of its middle lies in no piece.
/// Spends a unit per piece looked at and per segment of the winding numbers taken.
fn on_boundary(part: &Seg, pieces: &[Piece], tol: Tol, work: &mut Work<'_>) -> Result<bool, Stop> {
    let (m, left) = part.mid_and_left();
    let d = (part.length() * 1e-2).min(tol.probe);
    let right = add(m, scale(left, -d));
    let mut units = 0;
    let inside = pieces.iter().any(|p| {
        units += 1;
        p.bbox.contains(right, 0.0) && {
            units += p.segs.len();
            winding(&p.segs, right) != 0
        }
    });
    work.spend_n(units)?;
    Ok(!inside)
}

/// A loop's parts with consecutive parts of one input piece joined (the loop starting where
/// one input piece's parts begin, so none is split across its end).
fn join(path: &[usize], parts: &[(Seg, usize, f64)]) -> Vec<Seg> {
    let n = path.len();
    let continues = |k: usize| {
        let (prev, cur) = (&parts[path[(k + n - 1) % n]], &parts[path[k]]);
        prev.1 == cur.1 && cur.2 > 0.0
    };
    let start = (0..n).find(|&k| !continues(k)).unwrap_or(0);
    let mut out: Vec<Seg> = Vec::with_capacity(n);
    for k in 0..n {
        let idx = (start + k) % n;
        let seg = parts[path[idx]].0;
        if k > 0 && continues(idx) {
            let last = out.last_mut().expect("a part before");
            if let (Some(a), Some(b)) = (last.arc.as_mut(), seg.arc) {
                a.dt += b.dt;
            }
            last.b = seg.b;
        } else {
            out.push(seg);
        }
    }
    out
}
