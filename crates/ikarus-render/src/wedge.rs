//! Joint ranges as wedges at the joints, for arms and skeletons alike.

use ikarus::{Chain, JointLimits, Point2};

use crate::style;
use crate::svg::{PathData, Svg, num};
use crate::view::View;

/// One joint's range drawn as a wedge: at `at`, from `heading + limits.min()` to
/// `heading + limits.max()` (world angles), its radius scaled from `length`, the joint's link.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Wedge {
    pub at: Point2<f64>,
    pub heading: f64,
    pub limits: JointLimits,
    pub length: f64,
}

/// The wedges of a chain's limited joints at a pose: `joints` are the pose's joint positions
/// (base first), `pose` its angles; joint i's heading is the sum of the angles before it.
pub(crate) fn chain_wedges(chain: &Chain, joints: &[Point2<f64>], pose: &[f64]) -> Vec<Wedge> {
    let lengths = chain.lengths();
    let mut heading = 0.0;
    let mut out = Vec::new();
    for (i, limits) in chain.limits().iter().enumerate() {
        if let (Some(l), Some(&at)) = (limits, joints.get(i)) {
            out.push(Wedge { at, heading, limits: *l, length: lengths.get(i).copied().unwrap_or(0.0) });
        }
        heading += pose.get(i).copied().unwrap_or(0.0);
    }
    out
}

/// Each limited joint's range as a wedge at the joint in `view`, from the direction of the link
/// before it turned by the minimum to the maximum ([`chain_wedges`] for an arm).
pub(crate) fn ranges(svg: &mut Svg, view: &View, wedges: &[Wedge]) {
    let u = view.layout().unit;
    let scale = view.scale();
    let mut d = PathData::new();
    for w in wedges {
        let r = (w.length * scale * 0.4).clamp(14.0 * u, 46.0 * u);
        let (cx, cy) = view.world_to_pixel(w.at);
        let (lo, hi) = (w.heading + w.limits.min(), w.heading + w.limits.max());
        // World angles turn counter-clockwise; pixels have y down.
        let at = |a: f64| (cx + r * a.cos(), cy - r * a.sin());
        let ((x0, y0), (x1, y1)) = (at(lo), at(hi));
        d.move_to(cx, cy).line_to(x0, y0);
        d.arc_to(r, hi - lo > std::f64::consts::PI, false, x1, y1).close();
    }
    if d.is_empty() {
        return;
    }
    svg.comment("joint ranges");
    svg.path(
        &d,
        &format!(
            "fill=\"{}\" fill-opacity=\"0.1\" stroke=\"{}\" stroke-opacity=\"0.45\" stroke-width=\"{}\"",
            style::INK,
            style::INK,
            num(u)
        ),
    );
}
