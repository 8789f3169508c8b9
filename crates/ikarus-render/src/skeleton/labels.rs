//! Bone names beside their bones, placed clear of the bones and of each other.

use ikarus::{Point2, Skeleton};

use super::Bones;
use crate::scene::Scene;
use crate::style;
use crate::svg::{Svg, num};
use crate::view::PixelRect;

/// A rough box for text of `chars` characters in DejaVu Sans at `font` px, centred at (x, y).
fn text_box(x: f64, y: f64, chars: usize, font: f64) -> PixelRect {
    let half_w = 0.5 * 0.62 * font * chars as f64;
    PixelRect { left: x - half_w, top: y - 0.6 * font, right: x + half_w, bottom: y + 0.6 * font }
}

fn overlaps(a: &PixelRect, b: &PixelRect) -> bool {
    a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom
}

/// Whether the segment `a`–`b` passes through `r`.
fn crosses(r: &PixelRect, a: (f64, f64), b: (f64, f64)) -> bool {
    r.clip(a, b).is_some()
}

/// Each bone's name beside it, in topological order. Places are tried along the bone (the
/// middle first, then towards either end), on either side, at two distances; a name is set at
/// the first place whose box stays in the plot and clear of the names already set, the `obstacles`
/// (legend, mount, goals, pins),
/// every bone (widened by its stroke) and every joint; if there is none, at the place clear
/// of the other names that crosses the fewest bones, else beside the bone's middle.
pub(super) fn labels(scene: &Scene, svg: &mut Svg, skeleton: &Skeleton, bones: &Bones, obstacles: &[PixelRect]) {
    let layout = *scene.view.layout();
    let u = layout.unit;
    let font = (0.85 * layout.tick_font).max(9.0);
    let plot = layout.plot;
    let px = |p: Point2<f64>| scene.view.world_to_pixel(p);
    let segments: Vec<((f64, f64), (f64, f64))> =
        (0..skeleton.len()).map(|i| (px(bones.starts[i]), px(bones.tips[i]))).collect();
    let mut placed: Vec<PixelRect> = Vec::with_capacity(skeleton.len() + 1);
    placed.extend_from_slice(obstacles);
    let mut texts = Vec::with_capacity(skeleton.len());
    let grow = |b: &PixelRect, by: f64| PixelRect {
        left: b.left - by,
        top: b.top - by,
        right: b.right + by,
        bottom: b.bottom + by,
    };
    for &i in skeleton.topological_order() {
        let name = skeleton.name(i);
        let chars = name.chars().count();
        let ((x0, y0), (x1, y1)) = segments[i];
        let len = (x1 - x0).hypot(y1 - y0).max(1e-9);
        // The unit normal to the bone, in pixels.
        let (nx, ny) = (-(y1 - y0) / len, (x1 - x0) / len);
        // Half the box's extent along the normal: far enough for the box to clear the bone.
        let half_extent = 0.5 * 0.62 * font * chars as f64 * nx.abs() + 0.6 * font * ny.abs();
        // The best place so far clear of the other names: (bones crossed, x, y, box).
        let (mut best, mut first): (Option<(usize, f64, f64, PixelRect)>, _) = (None, None);
        'search: for extra in [0.0, 1.2 * font, 2.4 * font] {
            for t in [0.5, 0.35, 0.65, 0.2, 0.8] {
                for side in [1.0, -1.0] {
                    let off = 7.0 * u + half_extent + extra;
                    let (cx, cy) = (x0 + t * (x1 - x0) + side * nx * off, y0 + t * (y1 - y0) + side * ny * off);
                    let b = text_box(cx, cy, chars, font);
                    first.get_or_insert((cx, cy, b));
                    let inside = plot.contains(b.left, b.top) && plot.contains(b.right, b.bottom);
                    if !inside || placed.iter().any(|p| overlaps(p, &b)) {
                        continue;
                    }
                    let wide = grow(&b, 5.5 * u);
                    let crossed = segments.iter().filter(|&&(a, z)| crosses(&wide, a, z)).count();
                    if best.is_none_or(|(c, ..)| crossed < c) {
                        best = Some((crossed, cx, cy, b));
                    }
                    if crossed == 0 {
                        break 'search;
                    }
                }
            }
        }
        if let Some((cx, cy, b)) = best.map(|(_, x, y, b)| (x, y, b)).or(first) {
            placed.push(b);
            texts.push((cx, cy + 0.35 * font, name));
        }
    }
    svg.comment("bone names");
    svg.group(&format!("font-size=\"{}\" text-anchor=\"middle\"", num(font)));
    let halo =
        format!("fill=\"#ffffff\" stroke=\"#ffffff\" stroke-width=\"{}\" stroke-linejoin=\"round\"", num(3.0 * u));
    for &(x, y, name) in &texts {
        svg.text(x, y, name, &halo);
        svg.text(x, y, name, &format!("fill=\"{}\"", style::TEXT));
    }
    svg.end_group();
}
