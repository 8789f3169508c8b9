//! The shaded reachable area under an arm: the exact region (loops of lines and true arcs), or
//! a sampled occupancy grid (its smoothed edge).

use ikarus::Point2;
use ikarus::reach::{BoundarySegment, Region, Workspace};

use crate::style;
use crate::svg::{PathData, Svg, num};
use crate::view::View;

/// The reachable area a picture shades.
#[derive(Debug, Clone, Copy)]
pub enum Reachable<'a> {
    /// The exact region ([`Region::of`]): its boundary drawn with SVG arcs, or, for a region
    /// without area (fewer than two joints move), its curve stroked.
    Exact(&'a Region),
    /// A sampled occupancy grid: the smoothed edge of its cells ([`Workspace::outline`]).
    Grid(&'a Workspace),
}

impl Reachable<'_> {
    /// Whether the area was computed within the joint ranges (the picture then shows them).
    #[must_use]
    pub fn limits(&self) -> bool {
        match self {
            Reachable::Exact(r) => r.limits(),
            Reachable::Grid(w) => w.limits(),
        }
    }
}

impl<'a> From<&'a Region> for Reachable<'a> {
    fn from(region: &'a Region) -> Self {
        Reachable::Exact(region)
    }
}

impl<'a> From<&'a Workspace> for Reachable<'a> {
    fn from(workspace: &'a Workspace) -> Self {
        Reachable::Grid(workspace)
    }
}

impl Reachable<'_> {
    /// The reachable area in `view`, shaded in the workspace colour and traced thinly in the
    /// reach colour.
    pub(crate) fn draw(self, svg: &mut Svg, view: &View) {
        match self {
            Reachable::Exact(region) if region.has_area() => region_loops(svg, view, region),
            Reachable::Exact(region) => region_curves(svg, view, region),
            Reachable::Grid(ws) => grid_outline(svg, view, ws),
        }
    }
}

/// The exact region as one path of its boundary loops (outer counter-clockwise, holes
/// clockwise), with arcs as SVG arcs, filled with the even-odd rule so that holes stay empty.
fn region_loops(svg: &mut Svg, view: &View, region: &Region) {
    let mut d = PathData::new();
    for ring in region.boundary() {
        let Some(first) = ring.first() else { continue };
        let (x, y) = view.world_to_pixel(start(first));
        d.move_to(x, y);
        for seg in &ring {
            segment(&mut d, view, seg);
        }
        d.close();
    }
    fill(svg, view, &d);
}

/// A region without area: its curves (or its single point) stroked in the reach colour.
fn region_curves(svg: &mut Svg, view: &View, region: &Region) {
    let u = view.layout().unit;
    let mut d = PathData::new();
    for seg in region.curves() {
        let (x, y) = view.world_to_pixel(start(&seg));
        d.move_to(x, y);
        match seg {
            BoundarySegment::Line { from, to } if from == to => {
                // A point: a dot, drawn as a stroke of no length with round caps.
                d.line_to(x, y);
            }
            BoundarySegment::Line { .. } | BoundarySegment::Arc { .. } => segment(&mut d, view, &seg),
        }
    }
    if d.is_empty() {
        return;
    }
    svg.comment("reachable workspace (a curve: fewer than two joints move)");
    svg.path(
        &d,
        &format!(
            "fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\"",
            style::REACH,
            num(4.0 * u)
        ),
    );
}

/// One segment from its start (the current point) to its end. An arc of more than half a
/// turn is drawn as two halves, so that a full circle (same start and end) is drawn too.
fn segment(d: &mut PathData, view: &View, seg: &BoundarySegment) {
    match *seg {
        BoundarySegment::Line { to, .. } => {
            let (x, y) = view.world_to_pixel(to);
            d.line_to(x, y);
        }
        BoundarySegment::Arc { center, radius, from_angle, to_angle } => {
            let r = radius * view.scale();
            let sweep = to_angle - from_angle;
            let pieces = if sweep.abs() > std::f64::consts::PI { 2 } else { 1 };
            for k in 1..=pieces {
                let t = from_angle + sweep * f64::from(k) / f64::from(pieces);
                let end = Point2::new(center.x + radius * t.cos(), center.y + radius * t.sin());
                let (x, y) = view.world_to_pixel(end);
                // World counter-clockwise stays counter-clockwise on the screen (y flips
                // with the picture): SVG's sweep flag 0.
                d.arc_to(r, false, sweep < 0.0, x, y);
            }
        }
    }
}

/// The reachable area as one path: the smooth edge of the occupied cells
/// ([`Workspace::outline`], the playground's edge too).
fn grid_outline(svg: &mut Svg, view: &View, ws: &Workspace) {
    let mut d = PathData::new();
    for ring in ws.outline(ikarus::reach::OUTLINE_SMOOTHING) {
        for (k, p) in ring.iter().enumerate() {
            let (x, y) = view.world_to_pixel(*p);
            if k == 0 {
                d.move_to(x, y);
            } else {
                d.line_to(x, y);
            }
        }
        d.close();
    }
    fill(svg, view, &d);
}

/// `d` filled with the even-odd rule (holes stay empty) and traced thinly.
fn fill(svg: &mut Svg, view: &View, d: &PathData) {
    if d.is_empty() {
        return;
    }
    svg.comment("reachable workspace");
    svg.path(
        d,
        &format!(
            "fill=\"{}\" fill-rule=\"evenodd\" stroke=\"{}\" stroke-opacity=\"0.6\" stroke-width=\"{}\"",
            style::WORKSPACE,
            style::REACH,
            num(0.8 * view.layout().unit)
        ),
    );
}

/// Where a segment starts.
fn start(seg: &BoundarySegment) -> Point2<f64> {
    match *seg {
        BoundarySegment::Line { from, .. } => from,
        BoundarySegment::Arc { center, radius, from_angle, .. } => {
            Point2::new(center.x + radius * from_angle.cos(), center.y + radius * from_angle.sin())
        }
    }
}

#[cfg(test)]
mod tests {
    use ikarus::reach::Region;
    use ikarus::{Chain, JointLimits, Link};

    use crate::{ArmFigure, arm_svg};

    fn area_path(svg: &str) -> &str {
        svg.split("reachable workspace").nth(1).unwrap().split("/>").next().unwrap()
    }

    #[test]
    fn the_exact_region_is_drawn_with_arcs() {
        let lim = |d: f64| JointLimits::new(-d.to_radians(), d.to_radians()).unwrap();
        let chain = Chain::new(
            [0.0, 0.0],
            &[
                Link::new(3.0, 0.0).with_limits(lim(45.0)),
                Link::new(2.0, 0.0).with_limits(lim(90.0)),
                Link::new(1.0, 0.0).with_limits(lim(170.0)),
            ],
        )
        .unwrap();
        let region = Region::of(&chain, true);
        let pose = [0.0; 3];
        let svg = arm_svg(&ArmFigure { workspace: Some((&region).into()), ..ArmFigure::new(&chain, &pose) }, 400, 400)
            .unwrap();
        let area = area_path(&svg);
        let loops = region.boundary();
        assert_eq!(area.matches('M').count(), loops.len(), "{area}");
        assert_eq!(area.matches('Z').count(), loops.len());
        let arcs: usize =
            loops.iter().flatten().filter(|s| matches!(s, ikarus::reach::BoundarySegment::Arc { .. })).count();
        assert!(area.matches('A').count() >= arcs && arcs > 0, "{area}");
        assert!(area.contains("fill-rule=\"evenodd\""));
    }

    #[test]
    fn the_free_annulus_is_two_full_circles() {
        let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let region = Region::of(&chain, false);
        let svg =
            arm_svg(&ArmFigure { workspace: Some((&region).into()), ..ArmFigure::new(&chain, &[0.0, 0.0]) }, 400, 400)
                .unwrap();
        let area = area_path(&svg);
        assert_eq!(area.matches('M').count(), 2, "{area}");
        // Each full circle as two half arcs, no straight pieces.
        assert_eq!(area.matches('A').count(), 4, "{area}");
        assert_eq!(area.matches('L').count(), 0, "{area}");
    }

    #[test]
    fn a_region_without_area_draws_its_curve() {
        let chain = Chain::new([1.0, 0.0], &[Link::new(2.0, 0.0)]).unwrap();
        let region = Region::of(&chain, false);
        let svg = arm_svg(&ArmFigure { workspace: Some((&region).into()), ..ArmFigure::new(&chain, &[0.0]) }, 300, 300)
            .unwrap();
        let curve = svg.split("reachable workspace (a curve").nth(1).unwrap().split("/>").next().unwrap();
        assert!(curve.contains("fill=\"none\"") && curve.contains('A'), "{curve}");
    }
}
