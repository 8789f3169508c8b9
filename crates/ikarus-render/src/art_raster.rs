//! Textured triangles into a premultiplied RGBA8 buffer: the drawing of a character's [`Art`].
//!
//! The rules, per piece in draw order and per triangle of the piece:
//!
//! - **Coverage.** The triangle's corners are mapped to pixels and snapped to 1/256 of a pixel;
//!   a pixel is drawn when its centre is inside the triangle by the exact integer edge
//!   functions, with the *top-left rule* for centres on an edge: a centre on an edge belongs to
//!   the triangle whose edge is a top edge (horizontal, interior below) or a left edge
//!   (interior to its right). Two triangles sharing an edge therefore cover every pixel along
//!   it exactly once: no seams, no pixel blended twice. Edges are not anti-aliased (neither are
//!   the triangle edges of Spine's reference pictures).
//! - **Texture coordinates** are interpolated affinely over the triangle (barycentric weights
//!   from the same edge functions), as Spine's renderers do.
//! - **Sampling** is bilinear (an atlas page's `filter: Linear`) between the four texels around
//!   `(u·width − ½, v·height − ½)`, clamped to the page's border, in premultiplied colours: a
//!   straight page's texels are multiplied by their alpha before filtering, so a straight page
//!   and its premultiplied twin give the same picture and transparent texels do not darken the
//!   edges of the art.
//! - **Tint.** With `t` the premultiplied texel, `(r, g, b, a)` the piece's straight tint:
//!   `src = (t.r·r·a, t.g·g·a, t.b·b·a, t.a·a)`. With a dark colour `D` (two-colour tinting),
//!   the light colour `L = (r, g, b)` is what white becomes and `D` what black becomes, linearly
//!   between: the straight colour `c` becomes `c·L + (1 − c)·D`, premultiplied
//!   `src.rgb = a·(t.rgb·L + (t.a − t.rgb)·D)`. No public Spine page writes the formula down;
//!   it is derived from what they say: the slot's colour "is used as the light color for two
//!   color tinting" beside the dark colour, whose alpha is not used (the runtime API
//!   reference, `Slot.getColor`, `Slot.getDarkColor`); the feature is called *tint black* (the
//!   colour black becomes) and Spine 3.6's announcement names its effects: solid colour
//!   outlines (light = dark: every texel one colour), inverted colours (light black, dark
//!   white), which this rule gives (tests below). Spine's canvas renderer, which drew the
//!   reference pictures, does not do two-colour tinting (the same announcement), so no
//!   picture checks it.
//! - **Blending** onto the buffer with the piece's [`Blend`] (its formulas are on the type), in
//!   0..1, the colour then clamped to `0..=alpha` and rounded to 8 bits.
//!
//! Work is bounded: the pixels visited are each triangle's bounding box clipped to the buffer.
//! Triangles with a non-finite corner or UV, no area, or a corner farther than 2²¹ pixels from
//! the origin are skipped.

use resvg::tiny_skia::Pixmap;

use crate::RenderError;
use crate::art::{Art, ArtPiece, Blend, Page, WorldToPixel};
use crate::raster::new_pixmap;

/// Subpixel steps per pixel of the snapped corners.
const SUB: i64 = 256;
/// Corners farther than this from the origin, in pixels, skip their triangle (keeps the exact
/// edge functions inside `i64`).
const MAX_COORD: f64 = (1u32 << 21) as f64;

/// Draws `art`'s pieces in order onto `pixmap` (premultiplied RGBA8, over what is there),
/// placing world points with `to_pixel`. See the module's rules.
///
/// ```
/// use ikarus_render::{Art, ArtPiece, Blend, Page, Pixmap, WorldToPixel, draw_art};
///
/// // A one-texel red page on a world square 0..10 × 0..10, drawn 2 px per unit on 20 × 20.
/// let page = Page { width: 1, height: 1, rgba: vec![255, 0, 0, 255], pma: false };
/// let square = ArtPiece {
///     page: 0,
///     positions: vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
///     uvs: vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
///     triangles: vec![[0, 1, 2], [0, 2, 3]],
///     color: [1.0, 1.0, 1.0, 0.5],
///     dark: None,
///     blend: Blend::Normal,
/// };
/// let art = Art { pages: &[page], pieces: vec![square] };
/// let to_pixel = WorldToPixel { xx: 2.0, xy: 0.0, yx: 0.0, yy: -2.0, tx: 0.0, ty: 20.0 };
/// let mut pixmap = Pixmap::new(20, 20).unwrap();
/// draw_art(&art, &to_pixel, &mut pixmap)?;
/// // Every pixel is drawn once, the diagonal too: premultiplied half red.
/// assert!(pixmap.data().chunks_exact(4).all(|p| p == [128, 0, 0, 128]));
/// # Ok::<(), ikarus_render::RenderError>(())
/// ```
///
/// # Errors
/// [`RenderError::Art`] or [`RenderError::NonFinite`] when [`Art::check`] fails; nothing is
/// drawn then.
pub fn draw_art(art: &Art, to_pixel: &WorldToPixel, pixmap: &mut Pixmap) -> Result<(), RenderError> {
    art.check()?;
    let mut target = Target { width: pixmap.width() as i64, height: pixmap.height() as i64, data: pixmap.data_mut() };
    for piece in &art.pieces {
        let shade = Shade::new(piece, &art.pages[piece.page]);
        for tri in &piece.triangles {
            let corner = |k: u16| {
                let [x, y] = piece.positions[usize::from(k)];
                let [u, v] = piece.uvs[usize::from(k)];
                let (px, py) = to_pixel.apply(f64::from(x), f64::from(y));
                Corner::snap(px, py, f64::from(u), f64::from(v))
            };
            if let (Some(a), Some(b), Some(c)) = (corner(tri[0]), corner(tri[1]), corner(tri[2])) {
                draw_triangle(&mut target, &shade, [a, b, c]);
            }
        }
    }
    Ok(())
}

/// A transparent `width` × `height` pixmap with `art` drawn on it: [`draw_art`] on a fresh
/// buffer.
///
/// # Errors
/// [`RenderError::Size`] when a side is outside [`MIN_SIDE`](crate::MIN_SIDE)`..=`
/// [`MAX_SIDE`](crate::MAX_SIDE), and [`draw_art`]'s.
pub fn art_pixmap(art: &Art, to_pixel: &WorldToPixel, width: u32, height: u32) -> Result<Pixmap, RenderError> {
    let mut pixmap = new_pixmap(width, height)?;
    draw_art(art, to_pixel, &mut pixmap)?;
    Ok(pixmap)
}

/// The buffer being drawn on.
struct Target<'a> {
    width: i64,
    height: i64,
    data: &'a mut [u8],
}

/// A triangle corner: snapped pixel position (1/256 px) and texture coordinates.
#[derive(Clone, Copy)]
struct Corner {
    x: i64,
    y: i64,
    u: f64,
    v: f64,
}

impl Corner {
    fn snap(px: f64, py: f64, u: f64, v: f64) -> Option<Self> {
        let near = |c: f64| c.is_finite() && c.abs() <= MAX_COORD;
        (near(px) && near(py) && u.is_finite() && v.is_finite()).then(|| Self {
            x: (px * SUB as f64).round() as i64,
            y: (py * SUB as f64).round() as i64,
            u,
            v,
        })
    }
}

/// One edge `a → b`'s function `E(p) = (b − a) × (p − a)`, positive inside a triangle whose
/// corners are in positive order, with its steps per pixel and the top-left bias.
#[derive(Clone, Copy)]
struct Edge {
    ax: i64,
    ay: i64,
    dx: i64,
    dy: i64,
    /// 0 when the edge owns the centres on it (top or left), −1 when not: inside is `E + bias ≥ 0`.
    bias: i64,
}

impl Edge {
    fn new(a: Corner, b: Corner) -> Self {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        // With y down and positive orientation, an edge going up (dy < 0) has the interior on
        // its right: a left edge; a horizontal edge going right has it below: a top edge.
        let owns = dy < 0 || (dy == 0 && dx > 0);
        Self { ax: a.x, ay: a.y, dx, dy, bias: if owns { 0 } else { -1 } }
    }

    /// `E` at the centre of pixel `(i, j)`.
    fn at(&self, i: i64, j: i64) -> i64 {
        let (px, py) = (i * SUB + SUB / 2, j * SUB + SUB / 2);
        self.dx * (py - self.ay) - self.dy * (px - self.ax)
    }

    /// How `E` changes from one pixel to the next on a row.
    fn step(&self) -> i64 {
        -self.dy * SUB
    }
}

/// The first and last pixel index whose centre `k·SUB + SUB/2` lies in `lo..=hi` (subpixels),
/// clipped to `0..n`; empty when `first > last`.
fn centres(lo: i64, hi: i64, n: i64) -> (i64, i64) {
    let first = (lo - SUB / 2 + SUB - 1).div_euclid(SUB);
    let last = (hi - SUB / 2).div_euclid(SUB);
    (first.max(0), last.min(n - 1))
}

fn draw_triangle(target: &mut Target<'_>, shade: &Shade<'_>, [a, mut b, mut c]: [Corner; 3]) {
    let mut area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if area == 0 {
        return;
    }
    if area < 0 {
        std::mem::swap(&mut b, &mut c);
        area = -area;
    }
    // Each edge's function is the weight of the corner opposite it.
    let edges = [Edge::new(b, c), Edge::new(c, a), Edge::new(a, b)];
    let (i0, i1) = centres(a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x), target.width);
    let (j0, j1) = centres(a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y), target.height);
    let inv = 1.0 / area as f64;
    for j in j0..=j1 {
        let mut w = edges.map(|e| e.at(i0, j));
        for i in i0..=i1 {
            if w.iter().zip(&edges).all(|(w, e)| w + e.bias >= 0) {
                let [la, lb, lc] = w.map(|w| w as f64 * inv);
                let u = la * a.u + lb * b.u + lc * c.u;
                let v = la * a.v + lb * b.v + lc * c.v;
                let k = 4 * (j * target.width + i) as usize;
                let dst = &mut target.data[k..k + 4];
                shade.blend(shade.colour(u, v), dst);
            }
            for (w, e) in w.iter_mut().zip(&edges) {
                *w += e.step();
            }
        }
    }
}

/// One piece's texture, tint and blend mode.
struct Shade<'a> {
    page: &'a Page,
    /// The tint's straight colour, clamped to 0..1.
    light: [f64; 3],
    alpha: f64,
    dark: Option<[f64; 3]>,
    blend: Blend,
}

impl<'a> Shade<'a> {
    fn new(piece: &ArtPiece, page: &'a Page) -> Self {
        let unit = |v: f32| f64::from(v).clamp(0.0, 1.0);
        let [r, g, b, a] = piece.color.map(unit);
        Self { page, light: [r, g, b], alpha: a, dark: piece.dark.map(|d| d.map(unit)), blend: piece.blend }
    }

    /// The premultiplied texel `(x, y)` (clamped to the page), 0..1.
    fn texel(&self, x: i64, y: i64) -> [f64; 4] {
        let page = self.page;
        let x = x.clamp(0, i64::from(page.width) - 1) as usize;
        let y = y.clamp(0, i64::from(page.height) - 1) as usize;
        let k = 4 * (y * page.width as usize + x);
        let [r, g, b, a] = [0, 1, 2, 3].map(|c| u32::from(page.rgba[k + c]));
        // Both kinds as a fraction of 255², so that a straight texel and its exact premultiplied
        // twin give the same bits.
        let scale = if page.pma { 255 } else { a };
        [r * scale, g * scale, b * scale, a * 255].map(|n| f64::from(n) / 65025.0)
    }

    /// The page sampled bilinearly at `(u, v)`, premultiplied.
    fn sample(&self, u: f64, v: f64) -> [f64; 4] {
        let (w, h) = (f64::from(self.page.width), f64::from(self.page.height));
        let x = (u * w - 0.5).clamp(-1.0, w);
        let y = (v * h - 0.5).clamp(-1.0, h);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        // As lerps, `a + f·(b − a)`, so that equal texels give their value exactly.
        let lerp = |a: [f64; 4], b: [f64; 4], f: f64| [0, 1, 2, 3].map(|c| a[c] + f * (b[c] - a[c]));
        let top = lerp(self.texel(x0, y0), self.texel(x0 + 1, y0), fx);
        let bottom = lerp(self.texel(x0, y0 + 1), self.texel(x0 + 1, y0 + 1), fx);
        lerp(top, bottom, fy)
    }

    /// The tinted, premultiplied colour at `(u, v)`.
    fn colour(&self, u: f64, v: f64) -> [f64; 4] {
        let t = self.sample(u, v);
        let a = self.alpha;
        let rgb: [f64; 3] = match self.dark {
            None => [0, 1, 2].map(|c| t[c] * self.light[c] * a),
            Some(dark) => [0, 1, 2].map(|c| a * (t[c] * self.light[c] + (t[3] - t[c]).max(0.0) * dark[c])),
        };
        [rgb[0], rgb[1], rgb[2], t[3] * a]
    }

    /// Blends the premultiplied `src` onto the premultiplied RGBA8 pixel `dst`.
    fn blend(&self, src: [f64; 4], dst: &mut [u8]) {
        let d = [0, 1, 2, 3].map(|c| f64::from(dst[c]) / 255.0);
        let out = blend(self.blend, src, d);
        let alpha = out[3].clamp(0.0, 1.0);
        for c in 0..3 {
            dst[c] = to_u8(out[c].clamp(0.0, alpha));
        }
        dst[3] = to_u8(alpha);
    }
}

/// `blend`'s formula (see [`Blend`]) for premultiplied `s` over premultiplied `d`, 0..1.
fn blend(mode: Blend, s: [f64; 4], d: [f64; 4]) -> [f64; 4] {
    let (sa, da) = (s[3], d[3]);
    let alpha = sa + da * (1.0 - sa);
    let rgb = [0, 1, 2].map(|c| {
        let (s, d) = (s[c], d[c]);
        match mode {
            Blend::Normal => s + d * (1.0 - sa),
            Blend::Additive => (s + d).min(1.0),
            Blend::Multiply => s * (1.0 - da) + d * (1.0 - sa) + s * d,
            Blend::Screen => s + d - s * d,
        }
    });
    [rgb[0], rgb[1], rgb[2], alpha]
}

fn to_u8(v: f64) -> u8 {
    (v * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_formulas_by_hand() {
        // Source: premultiplied (0.2, 0.4, 0.1) at alpha 0.5; destination (0.6, 0.3, 0.9) opaque.
        let s = [0.2, 0.4, 0.1, 0.5];
        let d = [0.6, 0.3, 0.9, 1.0];
        let near = |got: [f64; 4], want: [f64; 4]| {
            assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-12), "{got:?} vs {want:?}");
        };
        // Normal: s + d·(1 − 0.5).
        near(blend(Blend::Normal, s, d), [0.5, 0.55, 0.55, 1.0]);
        // Additive: s + d, capped at 1.
        near(blend(Blend::Additive, s, d), [0.8, 0.7, 1.0, 1.0]);
        // Multiply over opaque: s·0 + d·0.5 + s·d.
        near(blend(Blend::Multiply, s, d), [0.3 + 0.12, 0.15 + 0.12, 0.45 + 0.09, 1.0]);
        // Screen: s + d − s·d.
        near(blend(Blend::Screen, s, d), [0.68, 0.58, 0.91, 1.0]);
        // Over a transparent buffer every mode draws the source as it is.
        for mode in [Blend::Normal, Blend::Additive, Blend::Multiply, Blend::Screen] {
            near(blend(mode, s, [0.0; 4]), s);
        }
        // Multiply and screen over a half-transparent buffer: the W3C formulas, expanded.
        let d = [0.25, 0.0, 0.5, 0.5];
        near(blend(Blend::Multiply, s, d), [0.1 + 0.125 + 0.05, 0.2, 0.05 + 0.25 + 0.05, 0.75]);
        near(blend(Blend::Screen, s, d), [0.4, 0.4, 0.55, 0.75]);
    }

    /// The tinted colour of a one-texel straight page holding `texel` (RGBA8), with tint
    /// `color` and dark colour `dark`, premultiplied, 0..1.
    fn tinted(texel: [u8; 4], color: [f32; 4], dark: Option<[f32; 3]>) -> [f64; 4] {
        let page = Page { width: 1, height: 1, rgba: texel.to_vec(), pma: false };
        let piece =
            ArtPiece { page: 0, positions: vec![], uvs: vec![], triangles: vec![], color, dark, blend: Blend::Normal };
        Shade::new(&piece, &page).colour(0.5, 0.5)
    }

    #[test]
    fn two_colour_tint_maps_white_to_the_light_colour_and_black_to_the_dark_one() {
        let near = |got: [f64; 4], want: [f64; 4]| {
            assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-12), "{got:?} vs {want:?}");
        };
        let c = |v: u8| f64::from(v) / 255.0;
        // Spine 3.6's announcement of tint black names its effects: light = dark = one colour
        // draws the image as that solid colour (solid outlines), whatever its texels.
        for texel in [[0, 0, 0, 255], [255, 255, 255, 255], [10, 200, 90, 255]] {
            near(tinted(texel, [0.25, 0.5, 1.0, 1.0], Some([0.25, 0.5, 1.0])), [0.25, 0.5, 1.0, 1.0]);
        }
        // Light black and dark white invert the colours.
        near(tinted([10, 200, 90, 255], [0.0, 0.0, 0.0, 1.0], Some([1.0; 3])), [c(245), c(55), c(165), 1.0]);
        // A black dark colour is the one-colour tint: the texel times the light colour.
        near(tinted([10, 200, 90, 255], [0.5, 1.0, 0.0, 1.0], Some([0.0; 3])), [c(10) / 2.0, c(200), 0.0, 1.0]);
        // Between, linearly: c·L + (1 − c)·D per channel (straight), here c = 0.2, L = 1, D = 0.5
        // in red; then premultiplied by the texel's alpha (0.4) times the tint's alpha (0.5).
        let (cr, a) = (c(51), c(102) * 0.5);
        let straight = cr * 1.0 + (1.0 - cr) * 0.5;
        let got = tinted([51, 0, 255, 102], [1.0, 1.0, 1.0, 0.5], Some([0.5, 0.0, 0.0]));
        near(got, [a * straight, 0.0, a, a]);
        // The dark colour's part is scaled by alpha like the rest: a transparent texel stays
        // transparent, whatever the dark colour.
        near(tinted([0, 0, 0, 0], [1.0; 4], Some([1.0; 3])), [0.0; 4]);
    }

    #[test]
    fn pixel_centres_on_the_bounds() {
        // Centres are at k + ½ pixels: 0.5 px → pixel 0, 2.5 px → pixel 2.
        assert_eq!(centres(128, 640, 10), (0, 2));
        assert_eq!(centres(129, 639, 10), (1, 1));
        assert_eq!(centres(-5000, 5000, 10), (0, 9));
        assert_eq!(centres(3000, 4000, 10), (12, 9));
    }
}
