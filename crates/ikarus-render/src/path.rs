//! A path for the tip, drawn over an arm picture: the wanted path as a dashed line, the tip's
//! trace as a solid line, and flips as red rings.

use ikarus::Point2;

use crate::RenderError;
use crate::error::check_finite;
use crate::scene::Scene;
use crate::style;
use crate::svg::{PathData, Svg, num};

/// A tracked path drawn with an arm ([`ArmFigure::path`](crate::ArmFigure::path),
/// [`Overlay::path`](crate::Overlay::path)).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PathLayer {
    /// The path the tip should follow, in order: a dashed blue line.
    pub goals: Vec<Point2<f64>>,
    /// Where the tip went, one point per sample: a solid orange line. In a GIF with one frame
    /// per sample, frame `i` shows the trace up to sample `i`.
    pub trace: Vec<Point2<f64>>,
    /// Where the tip was after a flip (a joint jumped more than the bound): red rings.
    pub flips: Vec<Point2<f64>>,
}

impl PathLayer {
    /// Checks that every point is finite; `field` names the layer in errors.
    pub(crate) fn check(&self, field: &str) -> Result<(), RenderError> {
        for (name, points) in [("goals", &self.goals), ("trace", &self.trace), ("flips", &self.flips)] {
            check_finite(points.iter().flat_map(|p| [p.x, p.y]), &format!("{field}.{name}"))?;
        }
        Ok(())
    }

    /// Draws the layer with the trace cut after `upto` points (all of it when `None`).
    pub(crate) fn draw(&self, scene: &Scene, svg: &mut Svg, upto: Option<usize>) {
        let u = scene.view.layout().unit;
        svg.comment("path");
        let line = |points: &[Point2<f64>]| {
            let mut d = PathData::new();
            for (i, &p) in points.iter().enumerate() {
                let (x, y) = scene.view.world_to_pixel(p);
                if i == 0 {
                    d.move_to(x, y);
                } else {
                    d.line_to(x, y);
                }
            }
            d
        };
        let round = "fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
        svg.path(
            &line(&self.goals),
            &format!(
                "{round} stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\"",
                style::JOINT_HUES[0],
                num(1.6 * u),
                num(5.0 * u),
                num(4.0 * u)
            ),
        );
        let end = upto.map_or(self.trace.len(), |k| (k + 1).min(self.trace.len()));
        svg.path(
            &line(&self.trace[..end]),
            &format!("{round} stroke=\"{}\" stroke-width=\"{}\" stroke-opacity=\"0.9\"", style::TIP_HUE, num(2.2 * u)),
        );
        for &p in &self.flips {
            let (x, y) = scene.view.world_to_pixel(p);
            svg.circle(
                x,
                y,
                7.0 * u,
                &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"", style::GOAL, num(2.2 * u)),
            );
        }
    }
}
