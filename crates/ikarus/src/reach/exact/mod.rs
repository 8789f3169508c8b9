//! The exact reachable region of a chain under its joint limits: closed loops of line segments
//! and circular arcs, computed (not sampled) link by link from the tip back to the base.
//!
//! # What it is
//!
//! The set of tip positions `base + Σ l_k e^{iφ_k}` over every pose with each joint in its
//! range (or free, with `limits` off), whatever the last link's direction. Its boundary is made
//! of circular arcs: an arc about a joint traced while that joint turns and the others hold (at
//! an end of their ranges, or where a later part of the chain reaches its farthest or nearest),
//! and copies of such arcs. [`Region::of`] builds it as described in the `sweep` module: each
//! joint's set is the next joint's, moved out along the link and turned through the joint's
//! range, as the union of the set's two end copies and the curved quadrilaterals its boundary
//! sweeps (or, for a full turn, annuli). The unions are computed on the arcs themselves (cut
//! where they meet, each part kept if the point just outside it lies in no piece), so the
//! region is exact up to rounding: points and curves closer than `1e-9` of the reach are
//! merged, and curves within `1e-7` of the reach of touching are taken to touch.
//!
//! Why our own union and not a polygon library: `cavalier_contours`, the well-kept crate for
//! polylines with arcs, offers the boolean of two simple closed polylines, without holes, at a
//! time, and its vertices carry nothing but a bulge; here tens to hundreds of pieces with holes
//! are united per joint, they share stretches of boundary by construction (every quadrilateral
//! shares two sides with the end copies), and each boundary part must remember the pose family
//! that traces it (so that the nearest reachable point comes with the pose that reaches it).
//! The union here is about 250 lines, with the intersection formulas beside it.
//!
//! # What it answers
//!
//! - [`Region::area`]: exact, from the loops (`½∮ x dy − y dx`, arcs in closed form);
//! - [`Region::classify`]: inside, outside, or on the boundary within a tolerance (a winding
//!   number over the loops: chords plus the circular segments of the arcs);
//! - [`Region::nearest`] and [`Region::distance`]: the nearest reachable point (the point
//!   itself inside) and how far it is;
//! - [`Region::pose_reaching`]: joint angles, within the limits, that put the tip on a boundary
//!   point, read off the pose family of the boundary part it lies on (no search).
//!
//! A chain with fewer than two joints that move reaches a curve or a point; its region has no
//! loops and no area, and only its curve is reachable ([`Region::curves`]).
//!
//! # What it costs
//!
//! Each joint's union cuts every boundary piece of its inputs against the others and tests a
//! point beside each cut part against every input, so a level of `m` pieces costs up to `m²`
//! steps; `m` is the number of arcs of the level below plus the quadrilaterals they sweep. For
//! the arms people draw the boundary stays small (3 to 7 pieces for the shipped arms, a few
//! hundred for 64 links of equal lengths) and a region builds in a millisecond or less; but the
//! pieces can multiply from level to level, and a chain of 64 links whose lengths spread from
//! 1e-9 to 1e9 ran for minutes. [`Region::try_of`] therefore meters the work (one unit per
//! pair of pieces tested for crossings, per piece a side test looks at, per segment a winding
//! number walks; a unit is at most a few hundred nanoseconds) and gives up past
//! [`Region::MAX_WORK`] units with [`RegionError::TooComplex`], or at once when its
//! [`Interrupt`](crate::Interrupt) is set with [`RegionError::Interrupted`]. [`Region::of`] has
//! no cap: use it for chains you trust.

mod seg;
mod sweep;
#[cfg(test)]
mod tests;
mod union;
mod work;

use std::f64::consts::TAU;

use nalgebra::Point2;

use crate::chain::Chain;
use crate::reach::sampling::Range;
use seg::{Bbox, P, Prov, Seg, add, angle_of, dist, rotate, sub, turn, unit};
use sweep::{Kind, Level};
use union::{Prepared, Tol, winding_prepared};
use work::{Stop, Work};

/// Why [`Region::try_of`] gave no region. Each message names what to change.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum RegionError {
    /// [`RegionOptions::interrupt`] was set before the region was built.
    #[error("interrupted")]
    Interrupted,
    /// The construction needed more than [`RegionOptions::max_work`] units of work.
    #[error(
        "links: the exact region of these {links} links needs more than {cap} steps of work (the cap was spent while sweeping joint {joint}, counted from 1 at the base, building from the tip); sample the region instead"
    )]
    TooComplex {
        /// The chain's number of links.
        links: usize,
        /// The joint (1-based from the base) whose sweep was running when the cap was spent.
        joint: usize,
        /// The cap, in units of work.
        cap: u64,
    },
}

/// How [`Region::try_of`] builds a region.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionOptions {
    /// Respect the chain's joint limits. Default `true`.
    pub limits: bool,
    /// The most units of work the construction may spend (see the [module docs](self)).
    /// Default [`Region::MAX_WORK`].
    pub max_work: u64,
    /// Stops the construction when set (checked after every inner loop of the sweep and the
    /// union, a few milliseconds apart at most). Default `None`.
    pub interrupt: Option<crate::Interrupt>,
}

impl Default for RegionOptions {
    fn default() -> Self {
        Self { limits: true, max_work: Region::MAX_WORK, interrupt: None }
    }
}

/// A piece of a region's boundary, in world coordinates (radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BoundarySegment {
    /// The straight segment from `from` to `to`.
    Line {
        /// Start.
        from: Point2<f64>,
        /// End.
        to: Point2<f64>,
    },
    /// The arc `center + radius·(cos t, sin t)` for `t` from `from_angle` to `to_angle`
    /// (counter-clockwise when `to_angle > from_angle`, clockwise otherwise; a full circle when
    /// they differ by 2π).
    Arc {
        /// Centre of the circle.
        center: Point2<f64>,
        /// Radius.
        radius: f64,
        /// Angle of the start, radians.
        from_angle: f64,
        /// Angle of the end, radians.
        to_angle: f64,
    },
}

/// Where a point lies with respect to a [`Region`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Membership {
    /// Inside, farther than the tolerance from the boundary.
    Inside,
    /// Within the tolerance of the boundary (or of the curve, for a region without area).
    Boundary,
    /// Outside, farther than the tolerance from the region.
    Outside,
}

/// The answer for one point: whether the tip can reach it, how far it is from the region
/// (0 inside), and the nearest reachable point (the point itself inside).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict {
    /// Inside or within the tolerance of the region.
    pub reachable: bool,
    /// Distance from the point to the region: 0 inside, else to the nearest boundary point.
    pub distance: f64,
    /// The nearest reachable point: the point itself inside, else on the boundary.
    pub nearest: Point2<f64>,
}

/// The exact reachable region of a chain; see the [module docs](self).
#[derive(Debug, Clone)]
pub struct Region {
    base: P,
    lengths: Vec<f64>,
    ranges: Vec<Range>,
    /// The limits respected (none where a joint is free or `limits` is off).
    bounds: Vec<Option<crate::chain::JointLimits>>,
    limits: bool,
    levels: Vec<Level>,
    /// Level 0's pieces moved to the base, with their boxes.
    world: Vec<Seg>,
    boxes: Vec<Bbox>,
    /// The same pieces prepared for the winding number.
    prepared: Vec<Prepared>,
    bbox: Bbox,
    area: f64,
    checked: bool,
}

impl Region {
    /// The default cap of [`Region::try_of`], in units of work: 5·10⁷, a few seconds of work
    /// in a release build on a 2-core machine (issue 24's 64-link arms spent it in 1.3 to 5.5 s
    /// on a machine shared by several builds). The seed arm needs 19 193 units, the seven-link
    /// arm 39 317; 64 equal links with ±60° ranges build in 0.2 s.
    pub const MAX_WORK: u64 = 50_000_000;

    /// The region of `chain`, respecting its joint limits if `limits` (a joint without limits,
    /// or with a range of a whole turn or more, turns freely). Its work has no cap (see
    /// [`Region::try_of`] for chains from untrusted input).
    #[must_use]
    pub fn of(chain: &Chain, limits: bool) -> Region {
        match Region::build(chain, limits, &mut Work::unbounded()) {
            Ok(region) => region,
            // Without a cap nor an interrupt the construction always ends.
            Err(_) => unreachable!("an unbounded construction stopped"),
        }
    }

    /// The region of `chain` as [`Region::of`] builds it, within the work cap of `options`
    /// and stopping when its interrupt is set.
    pub fn try_of(chain: &Chain, options: &RegionOptions) -> Result<Region, RegionError> {
        let mut work = Work::new(options.max_work, options.interrupt.as_ref());
        Region::build(chain, options.limits, &mut work).map_err(|(stop, joint)| match stop {
            Stop::Interrupted => RegionError::Interrupted,
            Stop::OverBudget => RegionError::TooComplex { links: chain.len(), joint: joint + 1, cap: options.max_work },
        })
    }

    /// The construction, spending `work`; `Err` with the joint (0-based) being swept, or 0 (the
    /// last one swept) for the self-check.
    fn build(chain: &Chain, limits: bool, work: &mut Work<'_>) -> Result<Region, (Stop, usize)> {
        // A full turn starts at the lower limit where there is one (limits a turn or more
        // apart), so that every angle the levels fix for it lies within the limits.
        let ranges: Vec<Range> = chain
            .limits()
            .iter()
            .map(|&l| match (Range::of(l, limits), l.filter(|_| limits)) {
                (r, Some(l)) if r.full => Range { lo: l.min(), ..r },
                (r, _) => r,
            })
            .collect();
        let lengths = chain.lengths().to_vec();
        let tol = Tol::of_scale(chain.max_reach());
        let (levels, closed) = sweep::levels(&lengths, &ranges, tol, work)?;
        let base = [chain.base().x, chain.base().y];
        let top = &levels[0];
        let mut world: Vec<Seg> = top.segs.iter().map(|s| s.moved(0.0, [1.0, 0.0], base, s.prov)).collect();
        if top.kind == Kind::Point {
            let p = add(top.point, base);
            world.push(Seg::line(p, p, Prov::Orbit { child: None, point: [0.0; 2], phase: 0.0 }));
        }
        let boxes: Vec<Bbox> = world.iter().map(Seg::bbox).collect();
        let mut bbox = Bbox::EMPTY;
        boxes.iter().for_each(|b| bbox.union(b));
        let area = if top.kind == Kind::Region { world.iter().map(Seg::area_term).sum::<f64>().max(0.0) } else { 0.0 };
        let bounds = chain.limits().iter().map(|&l| l.filter(|_| limits)).collect();
        let prepared = world.iter().map(Prepared::of).collect();
        let mut region = Region {
            base,
            lengths,
            ranges,
            bounds,
            limits,
            levels,
            world,
            boxes,
            prepared,
            bbox,
            area,
            checked: false,
        };
        region.checked = closed && region.holds_sampled_tips(chain, work).map_err(|stop| (stop, 0))?;
        Ok(region)
    }

    /// The self-check: 256 poses drawn uniformly within the ranges (a fixed sequence), their
    /// tips all inside or within `1e-9` of the reach of the region. Each tip spends a unit per
    /// link and two per boundary piece.
    fn holds_sampled_tips(&self, chain: &Chain, work: &mut Work<'_>) -> Result<bool, Stop> {
        let mut rng = crate::rng::SplitMix64(0x5eed);
        let mut angles = vec![0.0; chain.len()];
        let tol = 1e-9 * chain.max_reach();
        for _ in 0..256 {
            work.spend_n(chain.len() + 2 * self.world.len())?;
            for (a, r) in angles.iter_mut().zip(&self.ranges) {
                *a = r.lo + rng.unit() * if r.full { TAU } else { r.span };
            }
            let tip = crate::kinematics::end_effector(chain, &angles).position;
            if !self.contains(tip, tol) {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Whether the region passed its self-check: every union closed all its loops, and the
    /// tips of 256 poses drawn within the ranges lie in it. No region in the tests fails it
    /// (the union retries with a wider side test where a chain does not close); should one, it
    /// might miss reachable points, and the solver's verdict does not trust its `unreachable`.
    #[must_use]
    pub fn is_checked(&self) -> bool {
        self.checked
    }

    /// The region of the wrist (the tip of `chain` without its last link) when the last link
    /// must point at the absolute angle `direction`, moved by the last link: the set of tips
    /// reachable with the last link at that angle if the last joint turns freely (with limits
    /// off, or none on it), and a set containing it otherwise (the last joint's range then
    /// constrains the link before it too, which this region ignores). `None` for a one-link
    /// chain.
    #[must_use]
    pub fn wrist(chain: &Chain, limits: bool) -> Option<Region> {
        Region::wrist_chain(chain).map(|sub| Region::of(&sub, limits))
    }

    /// [`Region::wrist`] within the work cap and the interrupt of `options`: `Ok(None)` for a
    /// one-link chain.
    pub fn try_wrist(chain: &Chain, options: &RegionOptions) -> Result<Option<Region>, RegionError> {
        Region::wrist_chain(chain).map(|sub| Region::try_of(&sub, options)).transpose()
    }

    /// The chain without its last link (`None` for a one-link chain).
    fn wrist_chain(chain: &Chain) -> Option<Chain> {
        let links = chain.links();
        let (_, rest) = links.split_last()?;
        if rest.is_empty() {
            return None;
        }
        let base = [chain.base().x, chain.base().y];
        Chain::new(base, rest).ok()
    }

    /// Whether the joint limits were respected.
    #[must_use]
    pub fn limits(&self) -> bool {
        self.limits
    }

    /// The area, exactly (0 for a region that is a curve or a point).
    #[must_use]
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Whether the region has area (at least two joints move).
    #[must_use]
    pub fn has_area(&self) -> bool {
        self.levels[0].kind == Kind::Region
    }

    /// The boundary: closed loops, outer boundaries counter-clockwise and holes clockwise (the
    /// region on the left). Empty for a region without area.
    #[must_use]
    pub fn boundary(&self) -> Vec<Vec<BoundarySegment>> {
        if !self.has_area() {
            return Vec::new();
        }
        self.levels[0].loops.iter().map(|r| self.world[r.clone()].iter().map(public).collect()).collect()
    }

    /// For a region without area, the curves (arcs, or a single point as a line of no length)
    /// that the tip reaches; empty for a region with area.
    #[must_use]
    pub fn curves(&self) -> Vec<BoundarySegment> {
        if self.has_area() { Vec::new() } else { self.world.iter().map(public).collect() }
    }

    /// The number of boundary pieces (of curves, for a region without area).
    #[must_use]
    pub fn pieces(&self) -> usize {
        self.world.len()
    }

    /// The smallest box `[min, max]` holding the region.
    #[must_use]
    pub fn bounds(&self) -> (Point2<f64>, Point2<f64>) {
        (Point2::new(self.bbox.x0, self.bbox.y0), Point2::new(self.bbox.x1, self.bbox.y1))
    }

    /// Whether `p` is inside, outside, or within `tolerance` of the boundary. A non-finite
    /// point is outside.
    #[must_use]
    pub fn classify(&self, p: Point2<f64>, tolerance: f64) -> Membership {
        let q = [p.x, p.y];
        if !(q[0].is_finite() && q[1].is_finite()) {
            return Membership::Outside;
        }
        if self.bbox.distance(q) > tolerance {
            return Membership::Outside;
        }
        let near = self
            .world
            .iter()
            .zip(&self.boxes)
            .any(|(s, b)| b.distance(q) <= tolerance && dist(s.nearest(q), q) <= tolerance);
        if near {
            Membership::Boundary
        } else if self.has_area() && winding_prepared(&self.prepared, q) != 0 {
            Membership::Inside
        } else {
            Membership::Outside
        }
    }

    /// Whether `p` is inside or within `tolerance` of the region.
    #[must_use]
    pub fn contains(&self, p: Point2<f64>, tolerance: f64) -> bool {
        self.classify(p, tolerance) != Membership::Outside
    }

    /// The verdict for `p`: reachable (within `tolerance`), the distance to the region and the
    /// nearest reachable point.
    #[must_use]
    pub fn verdict(&self, p: Point2<f64>, tolerance: f64) -> Verdict {
        let q = [p.x, p.y];
        if self.has_area() && self.bbox.contains(q, 0.0) && winding_prepared(&self.prepared, q) != 0 {
            return Verdict { reachable: true, distance: 0.0, nearest: p };
        }
        let (_, nearest, distance) = self.nearest_on_boundary(q);
        Verdict { reachable: distance <= tolerance, distance, nearest: Point2::new(nearest[0], nearest[1]) }
    }

    /// The nearest reachable point to `p`: `p` itself inside, else the nearest boundary point.
    #[must_use]
    pub fn nearest(&self, p: Point2<f64>) -> Point2<f64> {
        self.verdict(p, 0.0).nearest
    }

    /// The distance from `p` to the region (0 inside).
    #[must_use]
    pub fn distance(&self, p: Point2<f64>) -> f64 {
        self.verdict(p, 0.0).distance
    }

    /// Joint angles within the ranges that put the tip on the boundary point nearest `p` (on
    /// the curve, for a region without area), with that point. Read off the pose family of the
    /// boundary piece the point lies on, so the tip lands on it up to rounding.
    #[must_use]
    pub fn pose_reaching(&self, p: Point2<f64>) -> (Vec<f64>, Point2<f64>) {
        let mut angles = Vec::with_capacity(self.lengths.len());
        let point = self.pose_reaching_into(p, &mut angles);
        (angles, point)
    }

    /// [`Region::pose_reaching`] into `angles` (cleared first; no allocation once it has room
    /// for one angle per joint); returns the boundary point.
    pub fn pose_reaching_into(&self, p: Point2<f64>, angles: &mut Vec<f64>) -> Point2<f64> {
        let (i, point, _) = self.nearest_on_boundary([p.x, p.y]);
        angles.clear();
        self.pose_on(i, sub(point, self.base), angles);
        Point2::new(point[0], point[1])
    }

    /// The boundary piece nearest `q`, the nearest point on it, and its distance.
    fn nearest_on_boundary(&self, q: P) -> (usize, P, f64) {
        let mut best = (0, self.world[0].a, f64::INFINITY);
        for (i, (s, b)) in self.world.iter().zip(&self.boxes).enumerate() {
            if b.distance(q) >= best.2 {
                continue;
            }
            let n = s.nearest(q);
            let d = dist(n, q);
            if d < best.2 {
                best = (i, n, d);
            }
        }
        best
    }

    /// The pose whose tip is at `q` (relative to the base) on level 0's piece `i`, following
    /// each piece's provenance down the levels.
    fn pose_on(&self, i: usize, q: P, angles: &mut Vec<f64>) {
        let n = self.lengths.len();
        let (mut seg, mut q) = (Some(i), q);
        for k in 0..n {
            let level = &self.levels[k];
            let Some(j) = seg.filter(|_| level.kind != Kind::Point) else {
                angles.extend_from_slice(&level.fixed);
                break;
            };
            match level.segs[j].prov {
                Prov::Copy { theta, child } => {
                    angles.push(theta);
                    q = sub(rotate(q, unit(-theta)), [self.lengths[k], 0.0]);
                    seg = Some(child as usize);
                }
                Prov::Orbit { child, point, phase } => {
                    angles.push(self.in_range(k, angle_of(q) - phase));
                    q = point;
                    seg = child.map(|c| c as usize);
                }
            }
        }
        // Only a broken provenance chain (a bug) could leave joints without an angle.
        debug_assert_eq!(angles.len(), n);
        for k in angles.len()..n {
            angles.push(self.ranges[k].lo);
        }
    }

    /// `theta` turned into joint `k`'s range (its nearer end if it falls outside by rounding).
    fn in_range(&self, k: usize, theta: f64) -> f64 {
        let r = self.ranges[k];
        if r.full {
            // A free joint, or limits a turn or more apart: the equivalent inside them.
            return match self.bounds[k] {
                Some(l) => l.nearest_equivalent(theta, 0.5 * (l.min() + l.max())).unwrap_or_else(|| l.clamp(theta)),
                None => crate::angle::wrap_angle(theta),
            };
        }
        let off = turn(theta - r.lo);
        if off <= r.span {
            r.lo + off
        } else if TAU - off < off - r.span {
            r.lo
        } else {
            r.lo + r.span
        }
    }
}

fn public(s: &Seg) -> BoundarySegment {
    let pt = |p: P| Point2::new(p[0], p[1]);
    match s.arc {
        None => BoundarySegment::Line { from: pt(s.a), to: pt(s.b) },
        Some(k) => BoundarySegment::Arc { center: pt(k.c), radius: k.r, from_angle: k.t0, to_angle: k.t0 + k.dt },
    }
}
