//! Building the region link by link, from the tip back to the base.
//!
//! Level `k` is the set the tip reaches relative to joint `k`, in the frame in which joint
//! `k`'s angle is measured; past the last joint it is the single point at the origin. Level `k`
//! is level `k + 1` moved out along link `k` (by `(l_k, 0)`) and turned through joint `k`'s
//! range `[lo, lo + span]`: the *sweep* of that set `T`. Three cases:
//!
//! - **a single angle** (`span = 0`): the set turned by `lo`;
//! - **a full turn**: the union of the circles about the joint through `T`'s points, that is
//!   annuli: each boundary part of `T` (cut where its distance from the joint turns) covers
//!   the radii between its ends, and a gap between those radii is covered too when its middle
//!   circle lies inside `T`;
//! - **a range**: `rot(lo)·T ∪ rot(lo + span)·T ∪` the sweep of `T`'s boundary. (A point
//!   reached at some angle in the range is reached at the range's start, or is on `T`'s
//!   boundary at the first angle that reaches it.) Each boundary part moving steadily outward
//!   from `A` to `B` sweeps a curved quadrilateral: the part turned by `lo`, the arc of `B` about
//!   the joint, the part turned by `lo + span` run backwards, the arc of `A` back; its cross-
//!   section at each radius is one arc of the range's width, so it is a simple region. The
//!   union of the two copies and every quadrilateral is the level.
//!
//! A point sweeps an arc (a curve), a curve sweeps a region; a set with no area is kept as its
//! curves. Every piece records the pose family that traces it ([`Prov`]), which is how
//! [`Region::pose_at`](super::Region) turns a boundary point back into joint angles.

use std::f64::consts::TAU;

use super::seg::{Bbox, P, Prov, Seg, add, angle_of, norm, rotate, sub, unit};
use super::union::{Piece, Tol, union, winding};
use super::work::{Stop, Work};
use crate::reach::sampling::Range;

/// What kind of set a level is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// One point: every joint from this one on has a single angle.
    Point,
    /// Curves with no area (open arcs and circles).
    Curve,
    /// A region with area, bounded by closed loops.
    Region,
}

/// One level: the set, its pieces (for a region, loop after loop), and for a point the joint
/// angles that put the tip there.
#[derive(Debug, Clone)]
pub(crate) struct Level {
    pub(crate) kind: Kind,
    pub(crate) segs: Vec<Seg>,
    /// For a region, each loop's range of `segs`.
    pub(crate) loops: Vec<std::ops::Range<usize>>,
    /// For a point: where it is, and the angles of this joint and every one after it.
    pub(crate) point: P,
    pub(crate) fixed: Vec<f64>,
}

impl Level {
    fn point(point: P, fixed: Vec<f64>) -> Level {
        Level { kind: Kind::Point, segs: Vec::new(), loops: Vec::new(), point, fixed }
    }

    fn curve(segs: Vec<Seg>) -> Level {
        Level { kind: Kind::Curve, segs, loops: Vec::new(), point: [0.0; 2], fixed: Vec::new() }
    }

    fn region(loops: Vec<Vec<Seg>>) -> Level {
        let mut segs = Vec::new();
        let mut ranges = Vec::new();
        for l in loops {
            let start = segs.len();
            segs.extend(l);
            ranges.push(start..segs.len());
        }
        if segs.is_empty() {
            return Level::curve(segs);
        }
        Level { kind: Kind::Region, segs, loops: ranges, point: [0.0; 2], fixed: Vec::new() }
    }
}

/// Every level of a chain given its link lengths and joint ranges: `levels[k]` for joint `k`,
/// and `levels[n]`, the point past the tip; and whether every union closed all its chains.
/// `Err` with the joint being swept when `work` runs out or is interrupted.
pub(crate) fn levels(
    lengths: &[f64],
    ranges: &[Range],
    tol: Tol,
    work: &mut Work<'_>,
) -> Result<(Vec<Level>, bool), (Stop, usize)> {
    let n = lengths.len();
    let mut levels: Vec<Level> = Vec::with_capacity(n + 1);
    levels.push(Level::point([0.0; 2], Vec::new()));
    let mut closed = true;
    for k in (0..n).rev() {
        let child = levels.last().expect("the level past the tip");
        let (level, ok) = sweep(child, [lengths[k], 0.0], ranges[k], tol, work).map_err(|stop| (stop, k))?;
        closed &= ok;
        levels.push(level);
    }
    levels.reverse();
    Ok((levels, closed))
}

/// Level `k` from level `k + 1` (`child`), link `k` as `shift` and joint `k`'s range.
///
/// Where rounding leaves nothing with area (a link far shorter than the rounding of the next,
/// as with lengths 1 and 5e-324, or 1e150 and 1e-150: the curves it draws are constant in their
/// distance from the joint to the last bit, and a turn moves them along themselves), the level
/// is a curve: the child's two end copies and the arc each child piece's start traces about
/// the joint through the range, so that no level is ever empty and every tip stays on it.
///
/// A child no wider than half the merge tolerance is one point to the union (every piece of it
/// lies within that of its first piece): only its first piece is swept. Without that, links
/// shorter than the rounding of the reach (the tip half of 64 links from 1e9 down to 1e-9)
/// doubled the pieces at every level, 2⁶⁰ of them in the end.
fn sweep(child: &Level, shift: P, range: Range, tol: Tol, work: &mut Work<'_>) -> Result<(Level, bool), Stop> {
    // Moving and copying the child's pieces.
    work.spend_n(child.segs.len())?;
    let first;
    let child = if child.segs.len() > 1 && extent(&child.segs) <= 0.5 * tol.merge {
        first = Level::curve(child.segs[..1].to_vec());
        &first
    } else {
        child
    };
    let (level, closed) = sweep_exactly(child, shift, range, tol, work)?;
    if level.segs.is_empty() && child.kind != Kind::Point {
        // The child's two end copies, and for a curve the arc each piece's start traces
        // between them: a piece at a constant distance from the joint (an arc about it, to the
        // last bit) covers, over the range, its own angles and that orbit. (A region whose
        // union kept nothing, which its self-check then fails, stays its two copies.)
        work.spend_n(3 * child.segs.len())?;
        let span = if range.full { TAU } else { range.span };
        let mut curve = copy(child, shift, range.lo);
        curve.extend(copy(child, shift, range.lo + span));
        let curves = if child.kind == Kind::Curve { child.segs.as_slice() } else { &[] };
        for (j, s) in curves.iter().enumerate() {
            let a = add(s.a, shift);
            let r = norm(a);
            if r > 0.0 {
                let from = rotate(a, unit(range.lo));
                let to = if range.full { from } else { rotate(a, unit(range.lo + span)) };
                curve.push(Seg::arc([0.0; 2], r, angle_of(a) + range.lo, span, from, to, orbit(j, a, shift)));
            }
        }
        return Ok((Level::curve(curve), closed));
    }
    Ok((level, closed))
}

/// The diagonal of the box holding `segs`.
fn extent(segs: &[Seg]) -> f64 {
    let mut b = Bbox::EMPTY;
    segs.iter().for_each(|s| b.union(&s.bbox()));
    norm([b.x1 - b.x0, b.y1 - b.y0])
}

fn sweep_exactly(child: &Level, shift: P, range: Range, tol: Tol, work: &mut Work<'_>) -> Result<(Level, bool), Stop> {
    let lo = range.lo;
    let span = if range.full { TAU } else { range.span };
    if child.kind == Kind::Point {
        let p = add(child.point, shift);
        let r = norm(p);
        let fixed = |angle: f64| std::iter::once(angle).chain(child.fixed.iter().copied()).collect();
        if span == 0.0 || r == 0.0 {
            return Ok((Level::point(rotate(p, unit(lo)), fixed(lo)), true));
        }
        let phase = angle_of(p);
        let prov = Prov::Orbit { child: None, point: child.point, phase };
        let arc = if range.full {
            Seg::arc([0.0; 2], r, phase, TAU, p, p, prov)
        } else {
            let (a, b) = (rotate(p, unit(lo)), rotate(p, unit(lo + span)));
            Seg::arc([0.0; 2], r, phase + lo, span, a, b, prov)
        };
        return Ok((Level::curve(vec![arc]), true));
    }
    if span == 0.0 {
        let copy = copy(child, shift, lo);
        return Ok(match child.kind {
            Kind::Region => {
                let mut level = child.clone();
                level.segs = copy;
                (level, true)
            }
            Kind::Point | Kind::Curve => (Level::curve(copy), true),
        });
    }
    // The child moved out along the link; each piece's radial parts remember the piece.
    let moved: Vec<Seg> = child.segs.iter().map(|s| s.moved(0.0, [1.0, 0.0], shift, s.prov)).collect();
    let mut parts: Vec<(usize, Seg)> = Vec::new();
    let mut buf = Vec::new();
    for (j, s) in moved.iter().enumerate() {
        buf.clear();
        s.radial_parts(&mut buf, range.full);
        parts.extend(buf.iter().map(|p| (j, *p)));
    }
    work.spend_n(parts.len())?;
    if range.full {
        // A gap's middle circle is tested against every moved piece.
        let inside = |q: P, work: &mut Work<'_>| -> Result<bool, Stop> {
            if child.kind != Kind::Region {
                return Ok(false);
            }
            work.spend_n(moved.len())?;
            Ok(winding(&moved, q) != 0)
        };
        return Ok((Level::region(annuli(&parts, shift, inside, tol, work)?), true));
    }
    let pieces = pieces(child, &parts, shift, lo, span);
    // The side test looks 1e-8 of the reach off each part; where curves run closer than that
    // without meeting (they touch, or cross at a glancing angle) it can misjudge a part, and a
    // chain of kept parts then fails to close. Looking farther off settles those; the first
    // look that closes every chain is taken.
    let mut best: Option<(Vec<Vec<Seg>>, usize)> = None;
    for widen in [1.0, 100.0, 1e4] {
        let (loops, open) = union(&pieces, Tol { probe: tol.probe * widen, ..tol }, work)?;
        if open == 0 {
            return Ok((Level::region(loops), true));
        }
        if best.as_ref().is_none_or(|b| open < b.1) {
            best = Some((loops, open));
        }
    }
    Ok((Level::region(best.map(|b| b.0).unwrap_or_default()), false))
}

/// The pieces whose union is a limited joint's level: the child's two end copies (if it has
/// area) and the quadrilateral of each outward part.
pub(crate) fn pieces(child: &Level, parts: &[(usize, Seg)], shift: P, lo: f64, span: f64) -> Vec<Piece> {
    let mut pieces: Vec<Piece> = Vec::with_capacity(parts.len() + 2);
    if child.kind == Kind::Region {
        for theta in [lo, lo + span] {
            pieces.push(Piece::new(copy(child, shift, theta)));
        }
    }
    for &(j, s) in parts {
        if norm(s.a) < norm(s.b) {
            pieces.push(Piece::new(quad(&s, j, shift, lo, span)));
        }
    }
    pieces
}

/// The child moved out along the link and turned by `theta`.
fn copy(child: &Level, shift: P, theta: f64) -> Vec<Seg> {
    let cs = unit(theta);
    let shift = rotate(shift, cs);
    child
        .segs
        .iter()
        .enumerate()
        .map(|(j, s)| s.moved(theta, cs, shift, Prov::Copy { theta, child: j as u32 }))
        .collect()
}

/// The orbit of a moved child point `p` (on the child's piece `j`): its provenance.
fn orbit(j: usize, p: P, shift: P) -> Prov {
    Prov::Orbit { child: Some(j as u32), point: sub(p, shift), phase: angle_of(p) }
}

/// The curved quadrilateral swept by the outward part `s` (of the moved child's piece `j`)
/// turned through `[lo, lo + span]`, counter-clockwise.
fn quad(s: &Seg, j: usize, shift: P, lo: f64, span: f64) -> Vec<Seg> {
    let hi = lo + span;
    let (cl, ch) = (unit(lo), unit(hi));
    let first = s.moved(lo, cl, [0.0; 2], Prov::Copy { theta: lo, child: j as u32 });
    let last = s.moved(hi, ch, [0.0; 2], Prov::Copy { theta: hi, child: j as u32 }).reversed();
    let (ra, rb) = (norm(s.a), norm(s.b));
    let (ta, tb) = (angle_of(s.a), angle_of(s.b));
    let outer = Seg::arc([0.0; 2], rb, tb + lo, span, first.b, last.a, orbit(j, s.b, shift));
    let mut out = vec![first, outer, last];
    if ra > 0.0 {
        out.push(Seg::arc([0.0; 2], ra, ta + hi, -span, last.b, first.a, orbit(j, s.a, shift)));
    }
    out
}

/// The annuli swept by a full turn: the radii each part covers, merged, with the gaps whose
/// middle circle lies inside the child also covered; each annulus as its outer circle
/// (counter-clockwise) and, unless it reaches the joint, its inner circle (clockwise).
fn annuli(
    parts: &[(usize, Seg)],
    shift: P,
    inside: impl Fn(P, &mut Work<'_>) -> Result<bool, Stop>,
    tol: Tol,
    work: &mut Work<'_>,
) -> Result<Vec<Vec<Seg>>, Stop> {
    // (radius, point, piece) at each end of each part's interval.
    type End = (f64, P, usize);
    let mut spans: Vec<(End, End)> = parts.iter().map(|&(j, s)| ((norm(s.a), s.a, j), (norm(s.b), s.b, j))).collect();
    spans.sort_by(|x, y| x.0.0.total_cmp(&y.0.0));
    let mut merged: Vec<(End, End)> = Vec::new();
    let covered = |r0: f64, r1: f64, work: &mut Work<'_>| inside([0.5 * (r0 + r1), 0.0], work);
    for s in spans {
        match merged.last_mut() {
            Some(m) if s.0.0 <= m.1.0 + tol.merge || covered(m.1.0, s.0.0, work)? => {
                if s.1.0 > m.1.0 {
                    m.1 = s.1;
                }
            }
            _ => merged.push(s),
        }
    }
    let mut loops = Vec::new();
    for (k, (inner, outer)) in merged.iter().enumerate() {
        let reaches_joint = k == 0 && covered(0.0, inner.0, work)?;
        let circle =
            |(r, p, j): End, sense: f64| Seg::arc([0.0; 2], r, angle_of(p), sense * TAU, p, p, orbit(j, p, shift));
        let mut l = vec![circle(*outer, 1.0)];
        if !reaches_joint && inner.0 > tol.merge {
            l.push(circle(*inner, -1.0));
        }
        // Two loops, so that each is a closed loop on its own.
        let hole = l.split_off(1);
        loops.push(l);
        if !hole.is_empty() {
            loops.push(hole);
        }
    }
    Ok(loops)
}
