//! The layers of an arm picture, shared by still figures and animation frames: background
//! (grid, workspace, reach circles, ticks), ghosts, joint paths, the arm, the goal, the caption.

use ikarus::{Chain, Point2};

use crate::reachable::Reachable;
use crate::style;
use crate::svg::{PathData, Svg, num};
use crate::view::{View, nice_step, tick_label, ticks};

/// How the joints' paths of an animation are drawn.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum TrailStyle {
    /// A faint line through the positions and a small cross at each (as the still figures).
    #[default]
    Marks,
    /// Lines only, as the playground's screen: the joints' paths in their hues at 0.7 opacity,
    /// the tip's opaque and wider in the path colour.
    Lines,
}

/// What every picture of one arm or skeleton shares.
pub(crate) struct Scene<'a> {
    /// Where the arm's or skeleton's roots start.
    pub base: Point2<f64>,
    /// The farthest any tip can be from the base.
    pub max_reach: f64,
    /// The nearest the tip can come to the base (0 for a skeleton: no inner circle).
    pub min_reach: f64,
    pub view: View,
    pub goal: Option<Point2<f64>>,
    pub workspace: Option<Reachable<'a>>,
    pub show_reach: bool,
}

impl Scene<'_> {
    /// The layers shared by every picture of `chain`, in `view`.
    pub(crate) fn of_chain<'w>(
        chain: &Chain,
        view: View,
        goal: Option<Point2<f64>>,
        workspace: Option<Reachable<'w>>,
        show_reach: bool,
    ) -> Scene<'w> {
        Scene {
            base: chain.base(),
            max_reach: chain.max_reach(),
            min_reach: chain.min_reach(),
            view,
            goal,
            workspace,
            show_reach,
        }
    }

    fn px(&self, p: Point2<f64>) -> (f64, f64) {
        self.view.world_to_pixel(p)
    }

    fn u(&self) -> f64 {
        self.view.layout().unit
    }

    /// Page, plot area, grid, workspace, reach circles, axes and tick labels.
    pub(crate) fn background(&self, svg: &mut Svg) {
        let layout = *self.view.layout();
        let plot = layout.plot;
        let u = self.u();
        svg.rect(0.0, 0.0, layout.width, layout.height, &format!("fill=\"{}\"", style::PAGE));
        svg.rect(plot.left, plot.top, plot.width(), plot.height(), &format!("fill=\"{}\"", style::PLOT));

        // Tick step: about one grid line per 90 px, from 1, 2, 5 × 10^k.
        let (lo, hi) = self.view.world_bounds();
        let step = nice_step(90.0 * u / self.view.scale());
        let xs = ticks(lo.x, hi.x, step);
        let ys = ticks(lo.y, hi.y, step);

        svg.comment("grid");
        let mut minor = PathData::new();
        let mut major = PathData::new();
        for x in ticks(lo.x, hi.x, step / 2.0) {
            let (px, _) = self.px(Point2::new(x, 0.0));
            let d = if xs.iter().any(|&t| (t - x).abs() < 1e-9 * step) { &mut major } else { &mut minor };
            d.move_to(px, plot.top).line_to(px, plot.bottom);
        }
        for y in ticks(lo.y, hi.y, step / 2.0) {
            let (_, py) = self.px(Point2::new(0.0, y));
            let d = if ys.iter().any(|&t| (t - y).abs() < 1e-9 * step) { &mut major } else { &mut minor };
            d.move_to(plot.left, py).line_to(plot.right, py);
        }
        let w = num(u.max(0.6));
        svg.path(&minor, &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{w}\"", style::GRID_MINOR));
        svg.path(&major, &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{w}\"", style::GRID));

        if let Some(area) = self.workspace {
            area.draw(svg, &self.view);
        }

        // The axes through the origin, when in view, with their names at the positive ends.
        let (ox, oy) = self.px(Point2::origin());
        let axis = format!("stroke=\"{}\" stroke-width=\"{}\"", style::AXIS, num(1.2 * u));
        let name = format!("font-size=\"{}\" fill=\"{}\"", num(layout.tick_font), style::MUTED_TEXT);
        if plot.left <= ox && ox <= plot.right {
            svg.line(ox, plot.top, ox, plot.bottom, &axis);
            svg.text(ox + 6.0 * u, plot.top + layout.tick_font + 2.0 * u, "y", &name);
        }
        if plot.top <= oy && oy <= plot.bottom {
            svg.line(plot.left, oy, plot.right, oy, &axis);
            svg.text(plot.right - 6.0 * u, oy - 6.0 * u, "x", &format!("{name} text-anchor=\"end\""));
        }

        if self.show_reach {
            self.reach_circles(svg);
        }

        style::plot_frame(svg, &plot, u);

        svg.comment("tick labels");
        svg.group(&format!("font-size=\"{}\" fill=\"{}\"", num(layout.tick_font), style::MUTED_TEXT));
        let below = plot.bottom + layout.tick_font + 6.0 * u;
        svg.group("text-anchor=\"middle\"");
        for &x in &xs {
            let (px, _) = self.px(Point2::new(x, 0.0));
            svg.text(px, below, &tick_label(x, step), "");
        }
        svg.end_group();
        svg.group("text-anchor=\"end\"");
        for &y in &ys {
            let (_, py) = self.px(Point2::new(0.0, y));
            svg.text(plot.left - 7.0 * u, py + 0.35 * layout.tick_font, &tick_label(y, step), "");
        }
        svg.end_group();
        svg.end_group();
    }

    fn reach_circles(&self, svg: &mut Svg) {
        let u = self.u();
        let (cx, cy) = self.px(self.base);
        let s = self.view.scale();
        svg.comment("reach");
        svg.circle(
            cx,
            cy,
            self.max_reach * s,
            &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"", style::REACH, num(1.6 * u)),
        );
        let inner = self.min_reach;
        if inner > 0.0 {
            svg.circle(
                cx,
                cy,
                inner * s,
                &format!(
                    "fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\"",
                    style::REACH,
                    num(1.4 * u),
                    num(6.0 * u),
                    num(4.0 * u)
                ),
            );
        }
    }

    /// Earlier poses, oldest first, as thin lines fading with age (`opacity[i]` each).
    pub(crate) fn ghosts(&self, svg: &mut Svg, ghosts: &[(&[Point2<f64>], f64)]) {
        if ghosts.is_empty() {
            return;
        }
        let u = self.u();
        svg.comment("ghosts");
        svg.group(&format!(
            "fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"",
            style::INK,
            num(2.2 * u)
        ));
        for (joints, opacity) in ghosts {
            svg.path(&polyline(self, joints), &format!("stroke-opacity=\"{}\"", opacity_str(*opacity)));
        }
        svg.end_group();
    }

    /// The path of every moving joint over `frames` (each base first, tip last): a faint line
    /// through the positions and a small cross at each.
    pub(crate) fn traces(&self, svg: &mut Svg, frames: &[&[Point2<f64>]]) {
        let Some(first) = frames.first() else { return };
        let n = first.len().saturating_sub(1);
        let u = self.u();
        let arm = 3.0 * u;
        svg.comment("joint paths");
        svg.group(&format!("fill=\"none\" stroke-linecap=\"round\" stroke-width=\"{}\"", num(1.1 * u)));
        for k in 1..=n {
            let hue = style::joint_hue(k, n);
            let mut line = PathData::new();
            let mut crosses = PathData::new();
            for (i, joints) in frames.iter().enumerate() {
                let (x, y) = self.px(joints[k]);
                if i == 0 {
                    line.move_to(x, y);
                } else {
                    line.line_to(x, y);
                }
                crosses.move_to(x - arm, y - arm).line_to(x + arm, y + arm);
                crosses.move_to(x - arm, y + arm).line_to(x + arm, y - arm);
            }
            svg.path(&line, &format!("stroke=\"{hue}\" stroke-opacity=\"0.35\" stroke-linejoin=\"round\""));
            svg.path(&crosses, &format!("stroke=\"{hue}\" stroke-opacity=\"0.9\""));
        }
        svg.end_group();
    }

    /// One step of the joint paths, to draw over the steps before it: every joint's line from
    /// `from` to `to` (none for the first frame) and its cross at `to`. The steps together
    /// draw what [`Scene::traces`] draws at once, in time linear in the frames (an animation
    /// redrawing the whole trail every frame is quadratic); the pieces are butt-capped so the
    /// translucent line does not darken where they meet.
    ///
    /// With [`TrailStyle::Lines`] (the playground's screen) there are no crosses, the lines are
    /// the joints' hues at 0.7 opacity, 1.5 units wide, and the tip's is opaque and 2.5 wide.
    pub(crate) fn trace_step(
        &self,
        svg: &mut Svg,
        from: Option<&[Point2<f64>]>,
        to: &[Point2<f64>],
        trail: TrailStyle,
    ) {
        let n = to.len().saturating_sub(1);
        let u = self.u();
        let arm = 3.0 * u;
        svg.group(&format!("fill=\"none\" stroke-width=\"{}\"", num(1.1 * u)));
        for k in 1..=n {
            let hue = style::joint_hue(k, n);
            let (x, y) = self.px(to[k]);
            let line_attrs = match (trail, k == n) {
                (TrailStyle::Marks, _) => format!("stroke=\"{hue}\" stroke-opacity=\"0.35\" stroke-linecap=\"butt\""),
                (TrailStyle::Lines, false) => format!(
                    "stroke=\"{hue}\" stroke-opacity=\"0.7\" stroke-linecap=\"butt\" stroke-width=\"{}\"",
                    num(1.5 * u)
                ),
                (TrailStyle::Lines, true) => {
                    format!("stroke=\"{hue}\" stroke-linecap=\"round\" stroke-width=\"{}\"", num(2.5 * u))
                }
            };
            if let Some(from) = from {
                let (x0, y0) = self.px(from[k]);
                let mut line = PathData::new();
                line.move_to(x0, y0).line_to(x, y);
                svg.path(&line, &line_attrs);
            }
            if trail == TrailStyle::Lines {
                continue;
            }
            let mut cross = PathData::new();
            cross.move_to(x - arm, y - arm).line_to(x + arm, y + arm);
            cross.move_to(x - arm, y + arm).line_to(x + arm, y - arm);
            svg.path(&cross, &format!("stroke=\"{hue}\" stroke-opacity=\"0.9\" stroke-linecap=\"round\""));
        }
        svg.end_group();
    }

    /// The arm: mount, links as thick round-capped strokes on a white halo, joints as rings,
    /// the tip as a filled dot.
    pub(crate) fn arm(&self, svg: &mut Svg, joints: &[Point2<f64>]) {
        svg.comment("arm");
        self.mount(svg, joints[0]);
        let links = polyline(self, joints);
        self.link_halo(svg, &links);
        self.link_ink(svg, &links, "");
        let last = joints.len() - 1;
        for (i, &p) in joints.iter().enumerate() {
            if i == last {
                self.tip_dot(svg, p);
            } else {
                self.joint_ring(svg, p);
            }
        }
    }

    /// The mount at `base`: a small trapezoid standing on a hatched ground line.
    pub(crate) fn mount(&self, svg: &mut Svg, base: Point2<f64>) {
        let u = self.u();
        let (bx, by) = self.px(base);
        let (hw, h) = (11.0 * u, 13.0 * u);
        let mut mount = PathData::new();
        mount
            .move_to(bx - 0.35 * hw, by)
            .line_to(bx + 0.35 * hw, by)
            .line_to(bx + hw, by + h)
            .line_to(bx - hw, by + h)
            .close();
        svg.path(
            &mount,
            &format!(
                "fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
                style::MOUNT,
                style::INK,
                num(1.4 * u)
            ),
        );
        let g = 1.45 * hw;
        let mut ground = PathData::new();
        ground.move_to(bx - g, by + h).line_to(bx + g, by + h);
        let mut hatch = PathData::new();
        let step = 4.5 * u;
        let mut x = bx - g + step;
        while x <= bx + g + 1e-9 {
            hatch.move_to(x, by + h).line_to(x - step, by + h + step);
            x += step;
        }
        svg.path(
            &ground,
            &format!("stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\"", style::INK, num(1.6 * u)),
        );
        svg.path(
            &hatch,
            &format!("stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"round\"", style::INK, num(0.9 * u)),
        );
    }

    /// The white halo under links (`d`, in pixels), so that crossing links stay apart.
    pub(crate) fn link_halo(&self, svg: &mut Svg, d: &PathData) {
        svg.path(d, &format!("{ROUND} stroke=\"#ffffff\" stroke-width=\"{}\"", num(11.0 * self.u())));
    }

    /// Links (`d`, in pixels) as thick ink strokes; `extra` adds attributes (an id).
    pub(crate) fn link_ink(&self, svg: &mut Svg, d: &PathData, extra: &str) {
        let sep = if extra.is_empty() { "" } else { " " };
        svg.path(d, &format!("{ROUND} stroke=\"{}\" stroke-width=\"{}\"{sep}{extra}", style::INK, num(6.5 * self.u())));
    }

    /// A joint: a white ring with an ink border.
    pub(crate) fn joint_ring(&self, svg: &mut Svg, p: Point2<f64>) {
        let u = self.u();
        let (x, y) = self.px(p);
        svg.circle(
            x,
            y,
            4.6 * u,
            &format!("fill=\"#ffffff\" stroke=\"{}\" stroke-width=\"{}\"", style::INK, num(2.2 * u)),
        );
    }

    /// A tip: a filled ink dot with a white border.
    pub(crate) fn tip_dot(&self, svg: &mut Svg, p: Point2<f64>) {
        let u = self.u();
        let (x, y) = self.px(p);
        svg.circle(
            x,
            y,
            4.6 * u,
            &format!("fill=\"{}\" stroke=\"#ffffff\" stroke-width=\"{}\"", style::INK, num(1.6 * u)),
        );
    }

    /// The goal, if any: see [`Scene::goal_at`].
    pub(crate) fn goal(&self, svg: &mut Svg) {
        if let Some(goal) = self.goal {
            self.goal_at(svg, goal);
        }
    }

    /// A goal at `goal`: a red ring with a red centre on a white halo; an arrow on the plot's
    /// edge if it lies outside the view. Returns whether it was drawn inside the plot.
    pub(crate) fn goal_at(&self, svg: &mut Svg, goal: Point2<f64>) -> bool {
        let u = self.u();
        let plot = self.view.plot_area();
        let (x, y) = self.px(goal);
        svg.comment("goal");
        if plot.contains(x, y) {
            svg.circle(
                x,
                y,
                10.5 * u,
                &format!("fill=\"none\" stroke=\"#ffffff\" stroke-width=\"{}\" stroke-opacity=\"0.85\"", num(5.0 * u)),
            );
            svg.circle(
                x,
                y,
                10.5 * u,
                &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"", style::GOAL, num(2.4 * u)),
            );
            svg.circle(x, y, 4.2 * u, &format!("fill=\"{}\"", style::GOAL));
            return true;
        }
        // Outside: walk from the plot's centre towards the goal until 16 px inside the edge.
        let (cx, cy) = (0.5 * (plot.left + plot.right), 0.5 * (plot.top + plot.bottom));
        let (dx, dy) = (x - cx, y - cy);
        let inset = 16.0 * u;
        let tx = if dx.abs() > 1e-12 { (0.5 * plot.width() - inset) / dx.abs() } else { f64::INFINITY };
        let ty = if dy.abs() > 1e-12 { (0.5 * plot.height() - inset) / dy.abs() } else { f64::INFINITY };
        let t = tx.min(ty);
        let (ax, ay) = (cx + dx * t, cy + dy * t);
        let len = dx.hypot(dy);
        let (ux, uy) = (dx / len, dy / len);
        let (s, w) = (13.0 * u, 7.0 * u);
        let mut arrow = PathData::new();
        arrow
            .move_to(ax + ux * s * 0.5, ay + uy * s * 0.5)
            .line_to(ax - ux * s * 0.5 - uy * w, ay - uy * s * 0.5 + ux * w)
            .line_to(ax - ux * s * 0.5 + uy * w, ay - uy * s * 0.5 - ux * w)
            .close();
        svg.path(&arrow, &format!("fill=\"{}\"", style::GOAL));
        let label = format!("goal ({}, {})", short(goal.x), short(goal.y));
        let anchor = if ux > 0.3 {
            "end"
        } else if ux < -0.3 {
            "start"
        } else {
            "middle"
        };
        let ly = ay - uy * 16.0 * u + 0.35 * self.view.layout().tick_font;
        svg.text(
            ax - ux * 16.0 * u,
            ly,
            &label,
            &format!(
                "font-size=\"{}\" fill=\"{}\" text-anchor=\"{anchor}\"",
                num(self.view.layout().tick_font),
                style::GOAL
            ),
        );
        false
    }

    /// The caption centred below the plot, and an optional note (a clock) in the plot's top
    /// right corner, where it cannot collide with a long caption.
    pub(crate) fn caption(&self, svg: &mut Svg, caption: Option<&str>, right: Option<&str>) {
        let layout = self.view.layout();
        let y = layout.caption_baseline();
        let font = format!("font-size=\"{}\" fill=\"{}\"", num(layout.caption_font), style::TEXT);
        if let Some(c) = caption.filter(|c| !c.is_empty()) {
            svg.text(0.5 * layout.width, y, c, &format!("{font} text-anchor=\"middle\""));
        }
        if let Some(r) = right {
            svg.text(
                layout.plot.right - 0.8 * layout.tick_font,
                layout.plot.top + 1.6 * layout.tick_font,
                r,
                &format!("font-size=\"{}\" fill=\"{}\" text-anchor=\"end\"", num(layout.tick_font), style::MUTED_TEXT),
            );
        }
    }
}

/// The stroke attributes of links and bones.
const ROUND: &str = "fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";

/// The joints as one open polyline in pixels.
fn polyline(scene: &Scene, joints: &[Point2<f64>]) -> PathData {
    let mut d = PathData::new();
    for (i, &p) in joints.iter().enumerate() {
        let (x, y) = scene.px(p);
        if i == 0 {
            d.move_to(x, y);
        } else {
            d.line_to(x, y);
        }
    }
    d
}

fn opacity_str(o: f64) -> String {
    format!("{:.3}", o.clamp(0.0, 1.0))
}

/// A coordinate for a label: up to 3 significant decimals.
fn short(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.replace('-', "\u{2212}")
}
