//! Still pictures of an arm: a pose, earlier poses as ghosts, joint paths, goal, workspace.

use ikarus::kinematics::joint_positions;
use ikarus::{Chain, Point2};

use crate::RenderError;
use crate::error::{check_finite, check_point};
use crate::path::PathLayer;
use crate::raster::{check_size, svg_to_png};
use crate::reachable::Reachable;
use crate::scene::Scene;
use crate::svg::Svg;
use crate::view::View;
use crate::wedge::{chain_wedges, ranges};
use ikarus::motion::Animation;

/// What a still picture of an arm shows. Build one with [`ArmFigure::new`] or
/// [`ArmFigure::of_animation`] and adjust the fields:
///
/// ```
/// # use ikarus::{Chain, Link, Point2};
/// # use ikarus_render::{ArmFigure, arm_svg};
/// let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.3), Link::new(2.0, 0.3), Link::new(1.0, 0.3)])?;
/// let figure = ArmFigure {
///     goal: Some(Point2::new(2.0, 3.0)),
///     caption: Some("the seed arm".into()),
///     ..ArmFigure::new(&chain, chain.start_pose().angles())
/// };
/// let svg = arm_svg(&figure, 800, 800)?;
/// assert!(svg.starts_with("<svg"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct ArmFigure<'a> {
    /// The chain drawn.
    pub chain: &'a Chain,
    /// Joint angles of the arm drawn on top, radians, one per joint.
    pub pose: &'a [f64],
    /// Earlier poses drawn as thin lines, oldest first; older ones are fainter.
    pub ghosts: Vec<&'a [f64]>,
    /// Whether to mark every joint's position in each ghost and in the pose with a small cross,
    /// joined by a faint line: the path each joint travelled.
    pub traces: bool,
    /// The goal, drawn as a red target (an arrow on the edge if it lies beyond the view).
    pub goal: Option<Point2<f64>>,
    /// The reachable area to shade, if any: the exact region or a sampled grid.
    pub workspace: Option<Reachable<'a>>,
    /// Whether to draw the maximum-reach circle (and the minimum-reach circle when it is > 0).
    pub show_reach: bool,
    /// A line of text under the plot, e.g. `dls · reached · 7 iterations · error 1.2e-7`.
    pub caption: Option<String>,
    /// A tracked path, drawn under the arm.
    pub path: Option<&'a PathLayer>,
    /// Whether to draw each limited joint's range as a wedge at the joint (from the previous
    /// link's direction turned by the minimum to the maximum), as the playground does when the
    /// limits are on.
    pub ranges: bool,
}

/// At most this many ghosts are taken from an animation by [`ArmFigure::of_animation`].
pub const MAX_ANIMATION_GHOSTS: usize = 40;

impl<'a> ArmFigure<'a> {
    /// The arm at `pose` with its reach circle, and nothing else.
    #[must_use]
    pub fn new(chain: &'a Chain, pose: &'a [f64]) -> Self {
        Self {
            chain,
            pose,
            ghosts: Vec::new(),
            traces: false,
            goal: None,
            workspace: None,
            show_reach: true,
            caption: None,
            path: None,
            ranges: false,
        }
    }

    /// A whole motion in one picture: the arm at the last frame, earlier frames as ghosts
    /// (every k-th frame so that there are at most [`MAX_ANIMATION_GHOSTS`], always including
    /// the first), and the joint paths through those frames.
    ///
    /// Frames are taken at equal steps of frame index, not of distance, so an ease that slows
    /// in and out shows as ghosts bunched at both ends. An animation without frames gives a
    /// figure with an empty pose, which [`arm_svg`] rejects.
    #[must_use]
    pub fn of_animation(chain: &'a Chain, animation: &'a Animation) -> Self {
        let frames = &animation.frames;
        let Some(last) = frames.last() else {
            return Self::new(chain, &[]);
        };
        let earlier = frames.len() - 1;
        let every = earlier.div_ceil(MAX_ANIMATION_GHOSTS).max(1);
        let ghosts = frames[..earlier].iter().step_by(every).map(|f| f.angles.as_slice()).collect();
        Self { ghosts, traces: true, ..Self::new(chain, &last.angles) }
    }

    /// The view this figure is drawn in at `width` × `height`: use it to find where a world
    /// point lands on the picture.
    #[must_use]
    pub fn view(&self, width: u32, height: u32) -> View {
        View::new(self.chain, self.goal, width, height)
    }
}

/// Checks that `angles` is a pose of `chain` with finite angles; `field` names it in errors.
pub(crate) fn check_pose(chain: &Chain, angles: &[f64], field: &str) -> Result<(), RenderError> {
    if angles.len() != chain.len() {
        return Err(RenderError::Length { field: field.to_string(), expected: chain.len(), got: angles.len() });
    }
    check_finite(angles.iter().copied(), field)
}

/// The figure as an SVG document of `width` × `height` pixels.
///
/// Layers, bottom to top: grid with tick labels, the shaded workspace, the reach circles, the
/// ghosts (oldest faintest), the joint paths, the arm, the goal, the caption.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096; [`RenderError::Length`] or
/// [`RenderError::NonFinite`] for a pose or ghost that does not fit the chain or is not
/// finite, or a goal that is not finite.
pub fn arm_svg(figure: &ArmFigure, width: u32, height: u32) -> Result<String, RenderError> {
    check_size(width, height)?;
    check_pose(figure.chain, figure.pose, "pose")?;
    for (i, g) in figure.ghosts.iter().enumerate() {
        check_pose(figure.chain, g, &format!("ghosts[{i}]"))?;
    }
    check_point(figure.goal, "goal")?;
    if let Some(layer) = figure.path {
        layer.check("path")?;
    }

    let scene =
        Scene::of_chain(figure.chain, figure.view(width, height), figure.goal, figure.workspace, figure.show_reach);
    let mut svg = Svg::new(width, height);
    scene.background(&mut svg);

    let pose = joint_positions(figure.chain, figure.pose);
    if figure.ranges {
        ranges(&mut svg, &scene.view, &chain_wedges(figure.chain, &pose, figure.pose));
    }
    let ghosts: Vec<Vec<Point2<f64>>> = figure.ghosts.iter().map(|g| joint_positions(figure.chain, g)).collect();
    let n = ghosts.len();
    let faded: Vec<(&[Point2<f64>], f64)> =
        ghosts.iter().enumerate().map(|(i, g)| (g.as_slice(), ghost_opacity(i, n))).collect();
    scene.ghosts(&mut svg, &faded);
    if figure.traces {
        let mut frames: Vec<&[Point2<f64>]> = ghosts.iter().map(Vec::as_slice).collect();
        frames.push(&pose);
        scene.traces(&mut svg, &frames);
    }
    if let Some(layer) = figure.path {
        layer.draw(&scene, &mut svg, None);
    }
    scene.arm(&mut svg, &pose);
    scene.goal(&mut svg);
    scene.caption(&mut svg, figure.caption.as_deref(), None);
    Ok(svg.finish())
}

/// The figure as PNG bytes: [`arm_svg`] rasterised with [`svg_to_png`].
///
/// # Errors
/// As [`arm_svg`], and [`RenderError::Encode`] if encoding fails.
pub fn arm_png(figure: &ArmFigure, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    svg_to_png(&arm_svg(figure, width, height)?)
}

/// Opacity of ghost `i` of `n`, oldest (0) faintest: from 0.10 up to 0.45.
pub(crate) fn ghost_opacity(i: usize, n: usize) -> f64 {
    if n <= 1 {
        return 0.4;
    }
    0.10 + 0.35 * (i as f64 / (n - 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::reach::{WorkspaceOptions, sample};
    use ikarus::{JointLimits, Link};

    fn limited() -> Chain {
        let lim = |d: f64| JointLimits::new(-d.to_radians(), d.to_radians()).unwrap();
        Chain::new(
            [0.0, 0.0],
            &[
                Link::new(3.0, 0.0).with_limits(lim(45.0)),
                Link::new(2.0, 0.0),
                Link::new(1.0, 0.0).with_limits(lim(170.0)),
            ],
        )
        .unwrap()
    }

    #[test]
    fn ranges_are_wedges_at_the_limited_joints_only_when_asked() {
        let chain = limited();
        let pose = [0.0, 0.5, 0.0];
        let plain = arm_svg(&ArmFigure::new(&chain, &pose), 400, 400).unwrap();
        assert!(!plain.contains("joint ranges"));
        let with = arm_svg(&ArmFigure { ranges: true, ..ArmFigure::new(&chain, &pose) }, 400, 400).unwrap();
        let wedges = with.split("joint ranges").nth(1).unwrap().split("/>").next().unwrap();
        // Two limited joints, two wedges: ±45° a small arc, ±170° a large one.
        assert_eq!(wedges.matches('A').count(), 2, "{wedges}");
        assert!(wedges.contains(" 0 0 0 ") && wedges.contains(" 0 1 0 "), "{wedges}");
    }

    #[test]
    fn the_reachable_area_is_one_smooth_even_odd_path() {
        let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let ws =
            sample(&chain, &WorkspaceOptions { resolution: 64, limits: false, ..WorkspaceOptions::default() }).unwrap();
        let svg =
            arm_svg(&ArmFigure { workspace: Some((&ws).into()), ..ArmFigure::new(&chain, &[0.0, 0.0]) }, 400, 400)
                .unwrap();
        let area = svg.split("reachable workspace").nth(1).unwrap().split("/>").next().unwrap();
        assert!(area.contains("fill-rule=\"evenodd\""), "{area}");
        assert!(area.contains(crate::style::WORKSPACE));
        // The annulus: an outer edge and a hole, two subpaths; no cell rectangles.
        assert_eq!(area.matches('M').count(), 2);
        assert_eq!(area.matches('Z').count(), 2);
    }
}
