//! Where things go on the picture: margins, the plot area, the world → pixel map, tick steps.

use ikarus::{Chain, Point2};

/// How far beyond the maximum reach the default view extends (`base ± 1.12 · reach`).
pub const VIEW_PADDING: f64 = 1.12;

/// A goal farther than this many reaches from the base does not widen the view any more; it is
/// drawn as an arrow at the edge of the plot instead.
pub(crate) const MAX_GOAL_ZOOM_OUT: f64 = 3.0;

/// The room `View::fitting` leaves on each side of what it fits, as a share of its larger side.
pub const FIT_MARGIN: f64 = 0.12;

/// A rectangle in pixels: `left ≤ x ≤ right`, `top ≤ y ≤ bottom` (y points down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelRect {
    /// Smallest x.
    pub left: f64,
    /// Smallest y.
    pub top: f64,
    /// Largest x.
    pub right: f64,
    /// Largest y.
    pub bottom: f64,
}

impl PixelRect {
    /// The part of the segment `a`–`b` inside the rectangle, as the range `[t0, t1]` of its
    /// parameter (`a + t (b − a)`), or `None` when it misses (Liang–Barsky clipping).
    #[must_use]
    pub fn clip(&self, (x0, y0): (f64, f64), (x1, y1): (f64, f64)) -> Option<(f64, f64)> {
        let (dx, dy) = (x1 - x0, y1 - y0);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [(-dx, x0 - self.left), (dx, self.right - x0), (-dy, y0 - self.top), (dy, self.bottom - y0)] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// `right − left`.
    #[must_use]
    pub fn width(&self) -> f64 {
        self.right - self.left
    }

    /// `bottom − top`.
    #[must_use]
    pub fn height(&self) -> f64 {
        self.bottom - self.top
    }

    /// Whether (x, y) lies inside or on the border.
    #[must_use]
    pub fn contains(&self, x: f64, y: f64) -> bool {
        self.left <= x && x <= self.right && self.top <= y && y <= self.bottom
    }
}

/// Sizes of a picture's furniture (fonts, margins, strokes), all scaled with the picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Layout {
    pub width: f64,
    pub height: f64,
    /// 1 at 800 px on the short side; strokes and fonts are multiples of it.
    pub unit: f64,
    pub tick_font: f64,
    pub caption_font: f64,
    pub plot: PixelRect,
}

impl Layout {
    /// Margins: tick labels left and below the plot, a caption line at the bottom.
    pub(crate) fn new(width: u32, height: u32, top_extra: f64) -> Self {
        let (w, h) = (f64::from(width), f64::from(height));
        let unit = (w.min(h) / 800.0).clamp(0.5, 4.0);
        let tick_font = (12.5 * unit).max(9.0);
        let caption_font = (14.5 * unit).max(10.0);
        let left = (18.0 * unit + 3.0 * tick_font).min(0.2 * w);
        let right = (22.0 * unit).min(0.1 * w);
        let top = ((20.0 + top_extra) * unit).min(0.15 * h);
        let bottom = (tick_font + 14.0 * unit + caption_font + 20.0 * unit).min(0.25 * h);
        Self {
            width: w,
            height: h,
            unit,
            tick_font,
            caption_font,
            plot: PixelRect { left, top, right: w - right, bottom: h - bottom },
        }
    }

    /// Baseline of the caption line.
    pub(crate) fn caption_baseline(&self) -> f64 {
        self.height - (12.0 * self.unit).min(0.05 * self.height)
    }
}

/// The map from world coordinates to pixels of an arm picture.
///
/// The world is shown with equal scale on both axes, centred on the chain's base, so that
/// `base ± 1.12 · max_reach` fits the plot area in both directions (a wider picture shows more
/// of the world left and right, not a stretched arm). When a goal lies beyond that, the view
/// widens to include it, up to three reaches; a goal farther still is drawn as an arrow on the
/// plot's edge. The view depends only on the chain, the goal and the picture's size, so every
/// frame of an animation shares it.
///
/// Pixel coordinates have their origin at the top-left corner of the picture, x to the right,
/// y down; the pixel `(i, j)` covers `[i, i + 1) × [j, j + 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    layout: Layout,
    center: Point2<f64>,
    scale: f64,
}

impl View {
    /// The view of `chain` (and `goal`, if any) on a `width` × `height` picture.
    ///
    /// Sizes are not validated here; the rendering functions check them.
    #[must_use]
    pub fn new(chain: &Chain, goal: Option<Point2<f64>>, width: u32, height: u32) -> Self {
        Self::around(chain.base(), chain.max_reach(), goal, width, height)
    }

    /// The view centred on `base` that fits `base ± 1.12 · reach` and the farthest of `goals`
    /// (up to three reaches): [`View::new`]'s for a chain.
    fn around(
        base: Point2<f64>,
        reach: f64,
        goals: impl IntoIterator<Item = Point2<f64>>,
        width: u32,
        height: u32,
    ) -> Self {
        let layout = Layout::new(width, height, 0.0);
        let mut half = VIEW_PADDING * reach;
        for g in goals.into_iter().filter(|g| g.x.is_finite() && g.y.is_finite()) {
            let d = (g - base).norm();
            half = half.max((1.08 * d).min(MAX_GOAL_ZOOM_OUT * reach));
        }
        let plot = layout.plot;
        let scale = plot.width().min(plot.height()).max(1.0) / (2.0 * half);
        Self { layout, center: base, scale }
    }

    /// The view that shows the world box from `min` to `max` whole and centred, with equal scale
    /// on both axes and [`FIT_MARGIN`] of the box's larger side free on each side (a box of no
    /// size, a point, gets a margin of 1): a skeleton's view, fitted to its bones.
    pub(crate) fn fitting(min: Point2<f64>, max: Point2<f64>, width: u32, height: u32) -> Self {
        let layout = Layout::new(width, height, 0.0);
        let size = max - min;
        let larger = size.x.max(size.y);
        let margin = if larger > 0.0 { FIT_MARGIN * larger } else { 1.0 };
        let plot = layout.plot;
        let scale =
            (plot.width().max(1.0) / (size.x + 2.0 * margin)).min(plot.height().max(1.0) / (size.y + 2.0 * margin));
        Self { layout, center: Point2::new(0.5 * (min.x + max.x), 0.5 * (min.y + max.y)), scale }
    }

    /// Pixel coordinates `(x, y)` of the world point `p`.
    #[must_use]
    pub fn world_to_pixel(&self, p: Point2<f64>) -> (f64, f64) {
        let plot = self.layout.plot;
        let cx = 0.5 * (plot.left + plot.right);
        let cy = 0.5 * (plot.top + plot.bottom);
        (cx + (p.x - self.center.x) * self.scale, cy - (p.y - self.center.y) * self.scale)
    }

    /// The world point at pixel coordinates `(x, y)`.
    #[must_use]
    pub fn pixel_to_world(&self, x: f64, y: f64) -> Point2<f64> {
        let plot = self.layout.plot;
        let cx = 0.5 * (plot.left + plot.right);
        let cy = 0.5 * (plot.top + plot.bottom);
        Point2::new(self.center.x + (x - cx) / self.scale, self.center.y - (y - cy) / self.scale)
    }

    /// Pixels per world unit.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The plot area (inside the axes) in pixels.
    #[must_use]
    pub fn plot_area(&self) -> PixelRect {
        self.layout.plot
    }

    /// The world rectangle the plot area shows: `(min, max)` corners.
    #[must_use]
    pub fn world_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        let plot = self.layout.plot;
        let a = self.pixel_to_world(plot.left, plot.bottom);
        let b = self.pixel_to_world(plot.right, plot.top);
        (a, b)
    }

    pub(crate) fn layout(&self) -> &Layout {
        &self.layout
    }
}

/// The smallest step of the form 1, 2 or 5 × 10^k that is at least `raw` (> 0).
pub(crate) fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * mag >= raw * (1.0 - 1e-9) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// Multiples of `step` within `[lo, hi]`, as exact `k · step`.
pub(crate) fn ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    if last < first || last.saturating_sub(first) > 1000 {
        return Vec::new();
    }
    (first..=last).map(|k| k as f64 * step).collect()
}

/// `v` with as many decimals as `step` needs, a real minus sign, and no `-0`.
pub(crate) fn tick_label(v: f64, step: f64) -> String {
    let decimals = (-(step.log10() + 1e-9).floor()).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    let zero = s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.');
    if zero { s.trim_start_matches('-').to_string() } else { s.replace('-', "\u{2212}") }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::Link;

    #[test]
    fn nice_steps() {
        for (raw, want) in [(1.68, 2.0), (0.9, 1.0), (0.21, 0.5), (3.0, 5.0), (7.0, 10.0), (0.05, 0.05), (1.0, 1.0)] {
            assert!((nice_step(raw) - want).abs() < 1e-12, "{raw} -> {}", nice_step(raw));
        }
        assert_eq!(nice_step(f64::NAN), 1.0);
    }

    #[test]
    fn tick_values_and_labels() {
        assert_eq!(ticks(-6.7, 6.7, 2.0), vec![-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0]);
        assert_eq!(tick_label(-4.0, 2.0), "\u{2212}4");
        assert_eq!(tick_label(-0.0, 0.5), "0.0");
        assert_eq!(tick_label(0.25, 0.05), "0.25");
        assert_eq!(tick_label(1.5, 0.5), "1.5");
    }

    #[test]
    fn view_is_centred_on_the_base_with_equal_scale() {
        let chain = Chain::new([1.0, -2.0], &[Link::new(3.0, 0.0), Link::new(2.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let view = View::new(&chain, None, 800, 600);
        let plot = view.plot_area();
        let (x, y) = view.world_to_pixel(chain.base());
        assert!((x - 0.5 * (plot.left + plot.right)).abs() < 1e-9);
        assert!((y - 0.5 * (plot.top + plot.bottom)).abs() < 1e-9);
        // The reach circle fits vertically with the padding to spare.
        let (_, top) = view.world_to_pixel(Point2::new(1.0, -2.0 + 6.0 * VIEW_PADDING));
        assert!((top - plot.top).abs() < 1e-9, "{top} vs {}", plot.top);
        let p = Point2::new(2.5, 0.75);
        let (px, py) = view.world_to_pixel(p);
        let back = view.pixel_to_world(px, py);
        assert!((back - p).norm() < 1e-12);
        // A far goal widens the view, but only up to three reaches.
        let far = View::new(&chain, Some(Point2::new(1.0 + 100.0, -2.0)), 800, 600);
        assert!((far.scale() * 2.0 * 3.0 * 6.0 - plot.height()).abs() < 1e-9);
    }
}
