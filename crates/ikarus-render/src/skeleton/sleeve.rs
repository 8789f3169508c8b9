//! Prismatic joints drawn as the playground draws them (`drawrig.js`'s `drawSleeves`): a
//! sleeve, a wider white rectangle with an ink border along the slide from the joint (where the
//! bone starts at displacement 0) to where the bone starts now (at least a short stub), and,
//! when the figure shows ranges, the joint's limits as a bar beside it along the slide, from
//! joint + lo to joint + hi, with a tick at each end.

use ikarus::{Joint, JointLimits, Point2, Skeleton};

use super::Bones;
use crate::scene::Scene;
use crate::style;
use crate::svg::{PathData, Svg, num};

/// The sleeve's width, in layout units (wider than a bone's halo).
const SLEEVE_UNITS: f64 = 14.0;

/// A prismatic bone's joint at a pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Sleeve {
    /// Where the bone starts at displacement 0 (its offset in its parent's frame).
    pub joint: Point2<f64>,
    /// The slide's direction in the world, a unit vector.
    pub slide: [f64; 2],
    /// Where the bone starts at the pose: `joint + displacement · slide`.
    pub start: Point2<f64>,
    /// The displacement's limits, in length units, if the joint has them.
    pub limits: Option<JointLimits>,
}

/// The sleeve of every prismatic bone at `pose` (whose forward kinematics `bones` is), in the
/// skeleton's order.
pub(super) fn sleeves(skeleton: &Skeleton, pose: &[f64], bones: &Bones) -> Vec<Sleeve> {
    let mut out = Vec::new();
    for (i, joint) in skeleton.joints().iter().enumerate() {
        let slide = match *joint {
            Joint::Revolute => continue,
            Joint::Prismatic { slide, .. } => slide.unwrap_or_else(|| {
                let (s, c) = skeleton.relative_angle(i, 0.0).sin_cos();
                [c, s]
            }),
        };
        let turn = skeleton.parent(i).map_or(0.0, |p| bones.directions[p]);
        let (s, c) = turn.sin_cos();
        let norm = slide[0].hypot(slide[1]);
        let u = [(c * slide[0] - s * slide[1]) / norm, (s * slide[0] + c * slide[1]) / norm];
        let start = bones.starts[i];
        let joint = Point2::new(start.x - pose[i] * u[0], start.y - pose[i] * u[1]);
        out.push(Sleeve { joint, slide: u, start, limits: skeleton.limits()[i] });
    }
    out
}

/// Draws `sleeves`, with their limit bars when `ranges`.
pub(super) fn draw_sleeves(scene: &Scene, svg: &mut Svg, sleeves: &[Sleeve], ranges: bool) {
    if sleeves.is_empty() {
        return;
    }
    let u = scene.view.layout().unit;
    let h = SLEEVE_UNITS * u / 2.0;
    svg.comment("prismatic joints");
    for sl in sleeves {
        let (jx, jy) = scene.view.world_to_pixel(sl.joint);
        // The slide on screen (y points down), and its normal.
        let (ux, uy) = (sl.slide[0], -sl.slide[1]);
        let (nx, ny) = (-uy, ux);
        if let Some(limits) = sl.limits.filter(|_| ranges) {
            // Beside the sleeve (to its right), where the bone does not hide it.
            let aside = h + 5.0 * u;
            let scale = scene.view.scale();
            let along = |d: f64| (jx + ux * d * scale - nx * aside, jy + uy * d * scale - ny * aside);
            let t = 0.4 * SLEEVE_UNITS * u;
            let mut d = PathData::new();
            let (a, b) = (along(limits.min()), along(limits.max()));
            // Only what lies in the plot: a range wider than the view runs to its edge, and
            // an end outside it has no tick.
            if let Some((t0, t1)) = scene.view.layout().plot.clip(a, b) {
                let at = |s: f64| (a.0 + (b.0 - a.0) * s, a.1 + (b.1 - a.1) * s);
                let (a, b) = (at(t0), at(t1));
                d.move_to(a.0, a.1).line_to(b.0, b.1);
                for ((x, y), end) in [(a, t0 == 0.0), (b, t1 == 1.0)] {
                    if end {
                        d.move_to(x - nx * t, y - ny * t).line_to(x + nx * t, y + ny * t);
                    }
                }
                svg.path(
                    &d,
                    &format!(
                        "class=\"slide-limits\" fill=\"none\" stroke=\"{}\" stroke-opacity=\"0.45\" stroke-width=\"{}\"",
                        style::INK,
                        num(2.0 * u)
                    ),
                );
            }
        }
        let (sx, sy) = scene.view.world_to_pixel(sl.start);
        let sign = if (sx - jx) * ux + (sy - jy) * uy < 0.0 { -1.0 } else { 1.0 };
        let len = (sx - jx).hypot(sy - jy).max(SLEEVE_UNITS * u) * sign;
        let mut d = PathData::new();
        d.move_to(jx + nx * h, jy + ny * h)
            .line_to(jx + ux * len + nx * h, jy + uy * len + ny * h)
            .line_to(jx + ux * len - nx * h, jy + uy * len - ny * h)
            .line_to(jx - nx * h, jy - ny * h)
            .close();
        svg.path(
            &d,
            &format!(
                "class=\"sleeve\" fill=\"#ffffff\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
                style::INK,
                num(2.0 * u)
            ),
        );
    }
}
