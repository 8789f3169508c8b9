//! Still pictures of a skeleton: its bones at a pose, joints, base, limit wedges, effector
//! goals, pins and bone names, drawn with the same layers as an arm.

use ikarus::{Point2, Skeleton};

use crate::RenderError;
use crate::error::{check_finite, check_point};
use crate::raster::{check_size, svg_to_png};
use crate::scene::Scene;
use crate::style;
use crate::svg::{PathData, Svg, num};
use crate::view::{MAX_GOAL_ZOOM_OUT, PixelRect, View};
use crate::wedge::{Wedge, ranges};
use labels::labels;
use sleeve::{draw_sleeves, sleeves};

mod labels;
mod sleeve;

/// A goal for the tip of one bone: a position and optionally a direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoneGoal {
    /// Index of the bone whose tip should reach the goal, in the skeleton's order.
    pub bone: usize,
    /// Where the tip should be.
    pub position: Point2<f64>,
    /// The direction the bone should point at its tip, radians from +x (counter-clockwise),
    /// if the goal has one: drawn as an arrow from the goal (when the goal is in view; one
    /// beyond it is an arrow on the plot's edge, as an arm's).
    pub angle: Option<f64>,
}

impl BoneGoal {
    /// A position goal for the tip of bone `bone`.
    #[must_use]
    pub fn at(bone: usize, position: Point2<f64>) -> Self {
        Self { bone, position, angle: None }
    }

    /// The same goal with a direction, radians from +x.
    #[must_use]
    pub fn with_angle(mut self, angle: f64) -> Self {
        self.angle = Some(angle);
        self
    }
}

/// What a still picture of a skeleton shows. Build one with [`SkeletonFigure::new`] and adjust
/// the fields:
///
/// ```
/// # use ikarus::{Bone, Point2, Skeleton};
/// # use ikarus_render::{BoneGoal, SkeletonFigure, skeleton_svg};
/// let skeleton = Skeleton::new(
///     [0.0, 0.0],
///     &[
///         Bone::new("trunk", 1.0, 1.5),
///         Bone::new("left", 0.8, 0.9).with_parent("trunk"),
///         Bone::new("right", 0.8, -0.9).with_parent("trunk"),
///     ],
/// )?;
/// let figure = SkeletonFigure {
///     goals: vec![BoneGoal::at(1, Point2::new(-0.5, 1.2))],
///     pins: vec![2],
///     labels: true,
///     caption: Some("a fork".into()),
///     ..SkeletonFigure::new(&skeleton, skeleton.start_angles())
/// };
/// let svg = skeleton_svg(&figure, 600, 600)?;
/// assert!(svg.starts_with("<svg"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct SkeletonFigure<'a> {
    /// The skeleton drawn.
    pub skeleton: &'a Skeleton,
    /// Its angles, radians, one per bone in the skeleton's order (as
    /// [`Skeleton::forward_into`] takes them).
    pub pose: &'a [f64],
    /// Goals for bone tips: red targets (an arrow shows a goal's direction, a dashed red line
    /// joins it to its bone's tip).
    pub goals: Vec<BoneGoal>,
    /// Bones whose tips are pinned (held where they are): a blue square on each tip.
    pub pins: Vec<usize>,
    /// Whether to draw each limited bone's range as a wedge at its joint (from the parent's
    /// direction — +x for a root — turned by the minimum to the maximum), as the arm figure does.
    pub ranges: bool,
    /// Whether to write each bone's name beside it.
    pub labels: bool,
    /// Whether to draw the maximum-reach circle around the base (off by default: the reach of
    /// a whole rig says little).
    pub show_reach: bool,
    /// A line of text under the plot.
    pub caption: Option<String>,
    /// The world box the view fits, `(min, max)`, instead of the one of [`pose`](Self::pose)
    /// ([`SkeletonFigure::extent`]): an animation gives every frame the box of all its poses,
    /// so that the view stays still. `None` (the default): the pose's own.
    pub fit: Option<(Point2<f64>, Point2<f64>)>,
}

impl<'a> SkeletonFigure<'a> {
    /// The skeleton at `pose` and nothing else.
    #[must_use]
    pub fn new(skeleton: &'a Skeleton, pose: &'a [f64]) -> Self {
        Self {
            skeleton,
            pose,
            goals: Vec::new(),
            pins: Vec::new(),
            ranges: false,
            labels: false,
            show_reach: false,
            caption: None,
            fit: None,
        }
    }

    /// The view this figure is drawn in at `width` × `height`: fitted to what it shows, the
    /// box of [`fit`](Self::fit) or else of [`extent`](Self::extent) at its pose (the base,
    /// the bones, the goals), centred, with [`FIT_MARGIN`](crate::FIT_MARGIN) of room
    /// around it. A rig's reach (the base's distance to its farthest tip over every pose) says
    /// little of where its bones are: a hand drawn in its reach's circle filled the top sixth
    /// of the picture.
    #[must_use]
    pub fn view(&self, width: u32, height: u32) -> View {
        let (min, max) = self.fit.unwrap_or_else(|| self.extent([self.pose]));
        View::fitting(min, max, width, height)
    }

    /// The world box `(min, max)` that holds the base, every bone at each of `poses`, and each
    /// goal (one farther than three reaches from the base counts as that far, in its direction:
    /// it is drawn as an arrow on the plot's edge). A pose that does not fit the skeleton (the
    /// wrong length, an angle not finite) is left out: drawing it fails with its own error.
    #[must_use]
    pub fn extent<'p>(&self, poses: impl IntoIterator<Item = &'p [f64]>) -> (Point2<f64>, Point2<f64>) {
        let skeleton = self.skeleton;
        let base = skeleton.base();
        let (mut min, mut max) = (base, base);
        let mut include = |p: Point2<f64>| {
            min = min.inf(&p);
            max = max.sup(&p);
        };
        let n = skeleton.len();
        let mut bones = Bones { starts: vec![base; n], tips: vec![base; n], directions: vec![0.0; n] };
        for pose in poses {
            if pose.len() != n || !pose.iter().all(|a| a.is_finite()) {
                continue;
            }
            skeleton.forward_into(pose, &mut bones.starts, &mut bones.tips, &mut bones.directions);
            bones.starts.iter().chain(&bones.tips).for_each(|&p| include(p));
        }
        let far = MAX_GOAL_ZOOM_OUT * skeleton.max_reach();
        for g in self.goals.iter().filter(|g| g.position.x.is_finite() && g.position.y.is_finite()) {
            let away = g.position - base;
            let d = away.x.hypot(away.y);
            include(if d > far { base + away * (far / d) } else { g.position });
        }
        (min, max)
    }

    fn check(&self) -> Result<(), RenderError> {
        let n = self.skeleton.len();
        if self.pose.len() != n {
            return Err(RenderError::Length { field: "pose".into(), expected: n, got: self.pose.len() });
        }
        check_finite(self.pose.iter().copied(), "pose")?;
        let bone = |field: String, index: usize| {
            if index < n { Ok(()) } else { Err(RenderError::UnknownBone { field, index, bones: n }) }
        };
        for (i, g) in self.goals.iter().enumerate() {
            bone(format!("goals[{i}].bone"), g.bone)?;
            check_point(Some(g.position), &format!("goals[{i}].position"))?;
            if let Some(a) = g.angle.filter(|a| !a.is_finite()) {
                return Err(RenderError::NonFinite { field: format!("goals[{i}].angle"), value: a });
            }
        }
        for (i, &p) in self.pins.iter().enumerate() {
            bone(format!("pins[{i}]"), p)?;
        }
        Ok(())
    }
}

/// Where every bone is at a pose: starts, tips and absolute directions, in the skeleton's order.
struct Bones {
    starts: Vec<Point2<f64>>,
    tips: Vec<Point2<f64>>,
    directions: Vec<f64>,
}

impl Bones {
    fn at(skeleton: &Skeleton, pose: &[f64]) -> Self {
        let n = skeleton.len();
        let mut b =
            Self { starts: vec![Point2::origin(); n], tips: vec![Point2::origin(); n], directions: vec![0.0; n] };
        skeleton.forward_into(pose, &mut b.starts, &mut b.tips, &mut b.directions);
        b
    }
}

/// The figure as an SVG document of `width` × `height` pixels.
///
/// Layers, bottom to top: grid with tick labels (and the reach circle if asked), the limit
/// wedges, dashed lines from each goal's bone tip to the goal, the base (the arm's mount, or a
/// socket when a root points down), the bones (in
/// the skeleton's topological order, each on a white halo, so a bone drawn later stands out
/// where it crosses one drawn earlier: each bone is one `<path id="bone{i}">`, `i` its index),
/// the joints (a white ring where a bone starts), the free tips (ink dots), the pins (blue
/// squares), the goals (red targets, an arrow for a direction), a legend for goals and pins, the
/// bone names, the caption.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096; [`RenderError::Length`] or
/// [`RenderError::NonFinite`] for a pose that does not fit the skeleton or is not finite, or a
/// goal that is not finite; [`RenderError::UnknownBone`] for a goal or pin on a bone the
/// skeleton does not have.
pub fn skeleton_svg(figure: &SkeletonFigure, width: u32, height: u32) -> Result<String, RenderError> {
    check_size(width, height)?;
    figure.check()?;
    let skeleton = figure.skeleton;
    let scene = Scene {
        base: skeleton.base(),
        max_reach: skeleton.max_reach(),
        min_reach: 0.0,
        view: figure.view(width, height),
        goal: None,
        workspace: None,
        show_reach: figure.show_reach,
    };
    let bones = Bones::at(skeleton, figure.pose);
    let mut svg = Svg::new(width, height);
    scene.background(&mut svg);
    if figure.ranges {
        ranges(&mut svg, &scene.view, &wedges(skeleton, &bones));
    }
    goal_leads(&scene, &mut svg, figure, &bones);
    draw_sleeves(&scene, &mut svg, &sleeves(skeleton, figure.pose, &bones), figure.ranges);
    draw_bones(&scene, &mut svg, skeleton, &bones);
    pins(&scene, &mut svg, figure, &bones);
    goals(&scene, &mut svg, figure);
    let key = legend(&scene, &mut svg, !figure.goals.is_empty(), !figure.pins.is_empty());
    if figure.labels {
        labels(&scene, &mut svg, skeleton, &bones, &obstacles(&scene, figure, &bones, key));
    }
    scene.caption(&mut svg, figure.caption.as_deref(), None);
    Ok(svg.finish())
}

/// The figure as PNG bytes: [`skeleton_svg`] rasterised with [`svg_to_png`].
///
/// # Errors
/// As [`skeleton_svg`], and [`RenderError::Encode`] if encoding fails.
pub fn skeleton_png(figure: &SkeletonFigure, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    svg_to_png(&skeleton_svg(figure, width, height)?)
}

/// The wedge of every limited revolute bone: at its start, from its parent's direction (+x for
/// a root). A prismatic bone's limits are lengths: its sleeve shows them ([`sleeve`]).
fn wedges(skeleton: &Skeleton, bones: &Bones) -> Vec<Wedge> {
    let mut out = Vec::new();
    for (i, limits) in skeleton.limits().iter().enumerate() {
        let revolute = match skeleton.joint(i) {
            ikarus::Joint::Revolute => true,
            ikarus::Joint::Prismatic { .. } => false,
        };
        if let Some(limits) = limits.filter(|_| revolute) {
            let heading = skeleton.parent(i).map_or(0.0, |p| bones.directions[p]);
            out.push(Wedge { at: bones.starts[i], heading, limits, length: skeleton.lengths()[i] });
        }
    }
    out
}

/// The base, each bone on its halo in topological order, the joints and the tips.
///
/// The base is the arm's mount (a trapezoid on hatched ground, below the base, under the
/// bones) when no root bone points below the horizontal; otherwise the mount would sit among
/// the bones (a puppet's legs hang from its base), and the base is a socket instead: a disc in
/// the mount's colour over the roots' starts, under the base's joint ring.
fn draw_bones(scene: &Scene, svg: &mut Svg, skeleton: &Skeleton, bones: &Bones) {
    svg.comment("skeleton");
    let mount = skeleton.roots().all(|r| bones.directions[r].sin() >= -0.05);
    if mount {
        scene.mount(svg, skeleton.base());
    }
    for &i in skeleton.topological_order() {
        let (x0, y0) = scene.view.world_to_pixel(bones.starts[i]);
        let (x1, y1) = scene.view.world_to_pixel(bones.tips[i]);
        let mut d = PathData::new();
        d.move_to(x0, y0).line_to(x1, y1);
        scene.link_halo(svg, &d);
        scene.link_ink(svg, &d, &format!("id=\"bone{i}\""));
    }
    if !mount {
        socket(scene, svg, skeleton.base());
    }
    scene.joint_ring(svg, skeleton.base());
    // A bone that starts off its parent's tip (an offset, a slide) has its own joint.
    for &i in skeleton.topological_order() {
        let own = skeleton.offsets()[i].is_some()
            || match skeleton.joint(i) {
                ikarus::Joint::Revolute => false,
                ikarus::Joint::Prismatic { .. } => true,
            };
        if own {
            scene.joint_ring(svg, bones.starts[i]);
        }
    }
    for &i in skeleton.topological_order() {
        if skeleton.children(i).len() > 0 {
            scene.joint_ring(svg, bones.tips[i]);
        } else {
            scene.tip_dot(svg, bones.tips[i]);
        }
    }
}

/// A base that is not a mount: a disc in the mount's colour over the bones' starts, under
/// the base's joint ring (a hub where the roots meet).
fn socket(scene: &Scene, svg: &mut Svg, base: Point2<f64>) {
    let u = scene.view.layout().unit;
    let (x, y) = scene.view.world_to_pixel(base);
    svg.circle(
        x,
        y,
        8.5 * u,
        &format!(
            "class=\"socket\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"",
            style::MOUNT,
            style::INK,
            num(1.6 * u)
        ),
    );
}

/// A thin dashed red line from each goal's bone tip to the goal, so that one can tell which
/// bone a goal belongs to.
fn goal_leads(scene: &Scene, svg: &mut Svg, figure: &SkeletonFigure, bones: &Bones) {
    let u = scene.view.layout().unit;
    let mut d = PathData::new();
    for g in &figure.goals {
        let (x0, y0) = scene.view.world_to_pixel(bones.tips[g.bone]);
        let (x1, y1) = scene.view.world_to_pixel(g.position);
        if (x1 - x0).hypot(y1 - y0) > 6.0 * u {
            d.move_to(x0, y0).line_to(x1, y1);
        }
    }
    if d.is_empty() {
        return;
    }
    svg.comment("goal leads");
    svg.path(
        &d,
        &format!(
            "fill=\"none\" stroke=\"{}\" stroke-opacity=\"0.7\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\"",
            style::GOAL,
            num(1.3 * u),
            num(4.0 * u),
            num(3.0 * u)
        ),
    );
}

/// The goals as the arm's goal, with an arrow from the target in the goal's direction.
fn goals(scene: &Scene, svg: &mut Svg, figure: &SkeletonFigure) {
    let u = scene.view.layout().unit;
    for g in &figure.goals {
        let inside = scene.goal_at(svg, g.position);
        let Some(angle) = g.angle.filter(|_| inside) else { continue };
        let (x, y) = scene.view.world_to_pixel(g.position);
        let (dx, dy) = (angle.cos(), -angle.sin());
        let (from, to, head, half) = (10.5 * u, 34.0 * u, 8.0 * u, 4.5 * u);
        let (ex, ey) = (x + dx * to, y + dy * to);
        let mut shaft = PathData::new();
        shaft.move_to(x + dx * from, y + dy * from).line_to(ex - dx * head, ey - dy * head);
        let mut tip = PathData::new();
        tip.move_to(ex, ey)
            .line_to(ex - dx * head - dy * half, ey - dy * head + dx * half)
            .line_to(ex - dx * head + dy * half, ey - dy * head - dx * half)
            .close();
        svg.path(
            &shaft,
            &format!(
                "stroke=\"#ffffff\" stroke-opacity=\"0.85\" stroke-width=\"{}\" stroke-linecap=\"round\"",
                num(5.0 * u)
            ),
        );
        svg.path(
            &shaft,
            &format!("stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\"", style::GOAL, num(2.4 * u)),
        );
        svg.path(
            &tip,
            &format!(
                "class=\"goal-direction\" fill=\"{}\" stroke=\"#ffffff\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
                style::GOAL,
                num(u)
            ),
        );
    }
}

/// A pin: a blue square with a white border centred at `(x, y)`, `half` its half side.
fn pin_square(svg: &mut Svg, x: f64, y: f64, half: f64, u: f64) {
    svg.rect(
        x - half,
        y - half,
        2.0 * half,
        2.0 * half,
        &format!("class=\"pin\" fill=\"{}\" stroke=\"#ffffff\" stroke-width=\"{}\"", style::PIN, num(1.6 * u)),
    );
}

/// Every pinned tip as a blue square over the tip's dot.
fn pins(scene: &Scene, svg: &mut Svg, figure: &SkeletonFigure, bones: &Bones) {
    if figure.pins.is_empty() {
        return;
    }
    let u = scene.view.layout().unit;
    svg.comment("pins");
    for &p in &figure.pins {
        let (x, y) = scene.view.world_to_pixel(bones.tips[p]);
        pin_square(svg, x, y, 6.5 * u, u);
    }
}

/// What bone names must not cover: the legend, the mount's ground (the socket lies under a
/// joint, which the names avoid anyway), the goals and the pins.
fn obstacles(scene: &Scene, figure: &SkeletonFigure, bones: &Bones, legend: Option<PixelRect>) -> Vec<PixelRect> {
    let u = scene.view.layout().unit;
    let around = |p: Point2<f64>, left: f64, top: f64, right: f64, bottom: f64| {
        let (x, y) = scene.view.world_to_pixel(p);
        PixelRect { left: x - left, top: y - top, right: x + right, bottom: y + bottom }
    };
    let mut out: Vec<PixelRect> = legend.into_iter().collect();
    out.push(around(figure.skeleton.base(), 21.0 * u, 0.0, 17.0 * u, 19.0 * u));
    out.extend(figure.goals.iter().map(|g| around(g.position, 13.0 * u, 13.0 * u, 13.0 * u, 13.0 * u)));
    out.extend(figure.pins.iter().map(|&p| around(bones.tips[p], 8.0 * u, 8.0 * u, 8.0 * u, 8.0 * u)));
    out
}

/// A small key in the plot's top left corner for the markers that appear (goal, pinned);
/// returns the box it takes, if any.
fn legend(scene: &Scene, svg: &mut Svg, goals: bool, pins: bool) -> Option<PixelRect> {
    if !goals && !pins {
        return None;
    }
    let layout = *scene.view.layout();
    let u = layout.unit;
    let font = layout.tick_font;
    let plot = layout.plot;
    let mut x = plot.left + 14.0 * u;
    let y = plot.top + 16.0 * u;
    svg.comment("legend");
    let text = format!("font-size=\"{}\" fill=\"{}\"", num(font), style::TEXT);
    if goals {
        svg.circle(
            x,
            y,
            5.5 * u,
            &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"", style::GOAL, num(1.6 * u)),
        );
        svg.circle(x, y, 2.2 * u, &format!("fill=\"{}\"", style::GOAL));
        svg.text(x + 10.0 * u, y + 0.35 * font, "goal", &text);
        x += 10.0 * u + 4.0 * 0.62 * font + 18.0 * u;
    }
    if pins {
        pin_square(svg, x, y, 5.0 * u, u);
        svg.text(x + 10.0 * u, y + 0.35 * font, "pinned", &text);
        x += 10.0 * u + 6.0 * 0.62 * font;
    }
    Some(PixelRect { left: plot.left, top: plot.top, right: x + 8.0 * u, bottom: y + 12.0 * u })
}

#[cfg(test)]
mod tests;
