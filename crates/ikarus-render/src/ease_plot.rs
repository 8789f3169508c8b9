//! A plot of an ease curve: position s(t) and velocity ds/dt against normalised time t.

use ikarus::Ease;

use crate::RenderError;
use crate::raster::{check_size, svg_to_png};
use crate::style;
use crate::svg::{PathData, Svg, num};
use crate::view::{Layout, PixelRect, nice_step, tick_label, ticks};

/// Colour of the position curve.
const POSITION: &str = "#3f6fa6";
/// Colour of the velocity curve.
const VELOCITY: &str = style::TIP_HUE;

/// Samples per curve (plus the ease's breakpoints).
const SAMPLES: u32 = 600;

/// The title of the plot: the ease's name and parameters.
fn title(ease: &Ease) -> String {
    match ease {
        Ease::Parent(p) => format!("parent ease \u{b7} k1 = {} \u{b7} k2 = {}", p.k1(), p.k2()),
        other => format!("{} ease", other.name()),
    }
}

/// The plot as an SVG document of `width` × `height` pixels: s(t) and ds/dt for t in [0, 1],
/// a legend, labelled axes, and for [`Ease::Parent`] the phase boundaries k1 and k2 as dashed
/// vertical lines, with the constant-velocity middle lightly shaded.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096.
pub fn ease_svg(ease: &Ease, width: u32, height: u32) -> Result<String, RenderError> {
    check_size(width, height)?;
    let layout = Layout::new(width, height, 34.0);
    let (ts, breaks) = sample_times(ease);
    let vmax = ts.iter().map(|&t| ease.velocity(t)).fold(1.0, f64::max);
    let axes = Axes::new(&layout, vmax);
    let plot = layout.plot;

    let mut svg = Svg::new(width, height);
    svg.rect(0.0, 0.0, layout.width, layout.height, &format!("fill=\"{}\"", style::PAGE));
    svg.rect(plot.left, plot.top, plot.width(), plot.height(), &format!("fill=\"{}\"", style::PLOT));
    if let [k1, k2] = breaks[..] {
        svg.rect(axes.px(k1), plot.top, axes.px(k2) - axes.px(k1), plot.height(), "fill=\"#f4f6f9\"");
    }
    grid(&mut svg, &axes);
    let label_font = format!("font-size=\"{}\" fill=\"{}\"", num(layout.tick_font), style::MUTED_TEXT);
    if let [k1, k2] = breaks[..] {
        phase_boundaries(&mut svg, &axes, &label_font, k1, k2);
    }
    curves(&mut svg, &axes, ease, &ts);
    style::plot_frame(&mut svg, &plot, layout.unit);
    axis_labels(&mut svg, &axes, &layout, &label_font);
    legend(&mut svg, &layout);
    svg.text(
        0.5 * layout.width,
        plot.top - (22.0 * layout.unit + layout.tick_font).min(plot.top * 0.5),
        &title(ease),
        &format!(
            "font-size=\"{}\" font-weight=\"bold\" fill=\"{}\" text-anchor=\"middle\"",
            num(1.15 * layout.caption_font),
            style::TEXT
        ),
    );
    Ok(svg.finish())
}

/// The times sampled, uniform plus the ease's breakpoints (so that the joins are exact), and
/// the breakpoints (k1 and k2 of [`Ease::Parent`], none otherwise).
fn sample_times(ease: &Ease) -> (Vec<f64>, Vec<f64>) {
    let mut ts: Vec<f64> = (0..=SAMPLES).map(|i| f64::from(i) / f64::from(SAMPLES)).collect();
    let breaks = match ease {
        Ease::Parent(p) => vec![p.k1(), p.k2()],
        Ease::Linear | Ease::Sine | Ease::Smoothstep => Vec::new(),
    };
    ts.extend(&breaks);
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    (ts, breaks)
}

/// The plot's axes: normalised time across, velocity (and position) up, and their steps.
struct Axes {
    plot: PixelRect,
    /// The layout's unit of line widths and gaps.
    u: f64,
    x_step: f64,
    y_step: f64,
    /// The value at the top of the plot.
    y_top: f64,
}

impl Axes {
    /// Axes for velocities up to `vmax`, with a little headroom.
    fn new(layout: &Layout, vmax: f64) -> Self {
        let (u, plot) = (layout.unit, layout.plot);
        let y_step = nice_step(vmax.max(1.0) / 6.0);
        let y_top = ((vmax * 1.06) / y_step).ceil() * y_step;
        let x_step = if plot.width() > 420.0 * u { 0.1 } else { 0.2 };
        Self { plot, u, x_step, y_step, y_top }
    }

    /// The pixel column of time `t`.
    fn px(&self, t: f64) -> f64 {
        self.plot.left + t * self.plot.width()
    }

    /// The pixel row of value `v`.
    fn py(&self, v: f64) -> f64 {
        self.plot.bottom - v / self.y_top * self.plot.height()
    }
}

fn grid(svg: &mut Svg, axes: &Axes) {
    let plot = &axes.plot;
    svg.comment("grid");
    let mut grid = PathData::new();
    for t in ticks(0.0, 1.0, axes.x_step) {
        grid.move_to(axes.px(t), plot.top).line_to(axes.px(t), plot.bottom);
    }
    for v in ticks(0.0, axes.y_top, axes.y_step) {
        grid.move_to(plot.left, axes.py(v)).line_to(plot.right, axes.py(v));
    }
    svg.path(&grid, &format!("fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"", style::GRID, num(axes.u.max(0.6))));
}

/// k1 and k2 as dashed vertical lines, labelled above the plot.
fn phase_boundaries(svg: &mut Svg, axes: &Axes, label_font: &str, k1: f64, k2: f64) {
    let (plot, u) = (&axes.plot, axes.u);
    svg.comment("phase boundaries");
    for (name, k) in [("k1", k1), ("k2", k2)] {
        let x = axes.px(k);
        svg.line(
            x,
            plot.top,
            x,
            plot.bottom,
            &format!(
                "stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\"",
                style::MUTED_TEXT,
                num(1.2 * u),
                num(5.0 * u),
                num(4.0 * u)
            ),
        );
        svg.text(x, plot.top - 6.0 * u, &format!("{name} = {k}"), &format!("{label_font} text-anchor=\"middle\""));
    }
}

/// s(t) and ds/dt through the times `ts`, the velocity under the position.
fn curves(svg: &mut Svg, axes: &Axes, ease: &Ease, ts: &[f64]) {
    svg.comment("curves");
    let mut position = PathData::new();
    let mut velocity = PathData::new();
    for (i, &t) in ts.iter().enumerate() {
        let (s, v) = (ease.position(t), ease.velocity(t));
        if i == 0 {
            position.move_to(axes.px(t), axes.py(s));
            velocity.move_to(axes.px(t), axes.py(v));
        } else {
            position.line_to(axes.px(t), axes.py(s));
            velocity.line_to(axes.px(t), axes.py(v));
        }
    }
    let curve = format!(
        "fill=\"none\" stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"",
        num(2.6 * axes.u)
    );
    svg.path(&velocity, &format!("{curve} stroke=\"{VELOCITY}\""));
    svg.path(&position, &format!("{curve} stroke=\"{POSITION}\""));
}

/// The tick labels of both axes and the caption under the plot.
fn axis_labels(svg: &mut Svg, axes: &Axes, layout: &Layout, label_font: &str) {
    let (plot, u) = (&axes.plot, axes.u);
    svg.comment("axes");
    svg.group(label_font);
    svg.group("text-anchor=\"middle\"");
    let below = plot.bottom + layout.tick_font + 6.0 * u;
    for t in ticks(0.0, 1.0, axes.x_step) {
        svg.text(axes.px(t), below, &tick_label(t, axes.x_step), "");
    }
    svg.end_group();
    svg.group("text-anchor=\"end\"");
    for v in ticks(0.0, axes.y_top, axes.y_step) {
        svg.text(plot.left - 7.0 * u, axes.py(v) + 0.35 * layout.tick_font, &tick_label(v, axes.y_step), "");
    }
    svg.end_group();
    svg.end_group();
    svg.text(
        0.5 * (plot.left + plot.right),
        layout.caption_baseline(),
        "normalised time t",
        &format!("font-size=\"{}\" fill=\"{}\" text-anchor=\"middle\"", num(layout.caption_font), style::TEXT),
    );
}

/// The legend box in the plot's top left corner: which colour is which curve.
fn legend(svg: &mut Svg, layout: &Layout) {
    let (plot, u) = (&layout.plot, layout.unit);
    svg.comment("legend");
    let (lx, ly) = (plot.left + 16.0 * u, plot.top + 16.0 * u);
    let row = 1.6 * layout.caption_font;
    svg.rect(
        lx - 8.0 * u,
        ly - 6.0 * u,
        15.5 * layout.caption_font,
        2.0 * row + 4.0 * u,
        &format!(
            "fill=\"#ffffff\" fill-opacity=\"0.9\" stroke=\"{}\" stroke-width=\"{}\" rx=\"{}\"",
            style::FRAME,
            num(u),
            num(4.0 * u)
        ),
    );
    for (i, (colour, text)) in [(POSITION, "position s(t)"), (VELOCITY, "velocity ds/dt")].into_iter().enumerate() {
        let y = ly + row * (i as f64 + 0.5);
        svg.line(
            lx,
            y,
            lx + 26.0 * u,
            y,
            &format!("stroke=\"{colour}\" stroke-width=\"{}\" stroke-linecap=\"round\"", num(2.6 * u)),
        );
        svg.text(
            lx + 36.0 * u,
            y + 0.35 * layout.caption_font,
            text,
            &format!("font-size=\"{}\" fill=\"{}\"", num(layout.caption_font), style::TEXT),
        );
    }
}

/// The plot as PNG bytes: [`ease_svg`] rasterised with [`svg_to_png`].
///
/// # Errors
/// As [`ease_svg`], and [`RenderError::Encode`] if encoding fails.
pub fn ease_png(ease: &Ease, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    svg_to_png(&ease_svg(ease, width, height)?)
}
