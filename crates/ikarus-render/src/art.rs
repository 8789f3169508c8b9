//! A character's art, ready to draw: atlas pages and textured triangles in draw order.
//!
//! The reader of a character's atlas and attachments turns each visible slot into an
//! [`ArtPiece`] (world positions, UVs, triangles, tint, blend mode); [`draw_art`](crate::draw_art)
//! rasterises them. This file holds the data, its checks, its extent, the decoding of a PNG page
//! and the world → pixel map; the drawing itself is in `art_raster.rs`.

use ikarus::Point2;

use crate::RenderError;
use crate::View;

/// The largest side of an atlas page, in pixels (a 16384 × 16384 RGBA page is 1 GiB).
pub const MAX_PAGE_SIDE: u32 = 16384;

/// An atlas page: RGBA8 pixels, row 0 at the top, 4 bytes per pixel, `width · height · 4` bytes.
///
/// With `pma: false` the colours are straight (not multiplied by alpha), as a PNG stores them;
/// with `pma: true` they are already multiplied by alpha (an atlas page with `pma: true`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Page {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The pixels, row by row from the top, `[r, g, b, a]` each.
    pub rgba: Vec<u8>,
    /// Whether `rgba` holds premultiplied colours.
    pub pma: bool,
}

/// How a piece's colours combine with what is already drawn (Spine's slot blend modes).
///
/// With `s` the piece's premultiplied colour and alpha `sa` at a pixel and `d`, `da` the
/// buffer's (premultiplied, 0..1), the result is, per colour channel:
///
/// | mode | colour | alpha |
/// |---|---|---|
/// | `Normal` | `s + d·(1 − sa)` | `sa + da·(1 − sa)` |
/// | `Additive` | `min(1, s + d)` | `sa + da·(1 − sa)` |
/// | `Multiply` | `s·(1 − da) + d·(1 − sa) + s·d` | `sa + da·(1 − sa)` |
/// | `Screen` | `s + d − s·d` | `sa + da·(1 − sa)` |
///
/// Normal is Porter and Duff's *source over*. Multiply and screen are the W3C "Compositing and
/// Blending" separable modes composited source-over (the canvas's `multiply` and `screen`,
/// which Spine's canvas renderer uses): over a transparent buffer they draw the piece as normal,
/// over an opaque one multiply darkens (`s·d` where the piece is opaque) and screen lightens.
/// Additive adds the colours (the canvas's `lighter`) and keeps normal's alpha.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Blend {
    /// Source over.
    #[default]
    Normal,
    /// Colours added.
    Additive,
    /// Colours multiplied.
    Multiply,
    /// One minus the product of the complements.
    Screen,
}

/// One slot's attachment, ready to draw.
///
/// `positions` are world coordinates (y up), `uvs` the matching points of page `page`
/// (0..1, u to the right, v down), `triangles` index triples into both. `color` is the straight
/// RGBA tint, 0..1 (the slot's colour times the attachment's); `dark`, when present, is Spine's
/// dark colour for two-colour tinting ("tint black"), RGB 0..1.
#[derive(Debug, Clone, PartialEq)]
pub struct ArtPiece {
    /// Index into [`Art::pages`].
    pub page: usize,
    /// World positions of the vertices.
    pub positions: Vec<[f32; 2]>,
    /// Texture coordinates of the vertices, one per position.
    pub uvs: Vec<[f32; 2]>,
    /// Triangles as index triples into `positions` and `uvs`.
    pub triangles: Vec<[u16; 3]>,
    /// Straight RGBA tint, 0..1.
    pub color: [f32; 4],
    /// Dark tint colour (two-colour tinting), RGB 0..1.
    pub dark: Option<[f32; 3]>,
    /// How the piece combines with what is under it.
    pub blend: Blend,
}

/// A character's art: its atlas pages and its pieces in draw order (first drawn first).
///
/// The pages are borrowed: they are decoded once (an atlas's pages can be tens of megabytes)
/// and every pose drawn with them, each frame of a motion, holds only its own pieces.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Art<'a> {
    /// The atlas pages.
    pub pages: &'a [Page],
    /// The pieces, back to front.
    pub pieces: Vec<ArtPiece>,
}

impl Page {
    /// Decodes a PNG file's bytes into a page; `file` names it in errors, `pma` says whether
    /// its colours are premultiplied (the atlas page's `pma` field).
    ///
    /// Every PNG colour type and bit depth is accepted: palettes and transparency chunks are
    /// expanded, 16-bit samples cut to 8, grey replicated to RGB, a missing alpha made 255.
    ///
    /// # Errors
    /// [`RenderError::Image`] naming `file` when the bytes are not a PNG image, are cut short,
    /// or a side is 0 or larger than [`MAX_PAGE_SIDE`].
    pub fn decode_png(bytes: &[u8], file: &str, pma: bool) -> Result<Self, RenderError> {
        let fail = |message: String| RenderError::Image { file: file.to_string(), message };
        let limits = png::Limits { bytes: 4 * (MAX_PAGE_SIDE as usize) * (MAX_PAGE_SIDE as usize) };
        let mut decoder = png::Decoder::new_with_limits(std::io::Cursor::new(bytes), limits);
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().map_err(|e| fail(format!("not a PNG image: {e}")))?;
        let (width, height) = (reader.info().width, reader.info().height);
        for (side, value) in [("width", width), ("height", height)] {
            if value == 0 || value > MAX_PAGE_SIDE {
                return Err(fail(format!("{side} must be between 1 and {MAX_PAGE_SIDE} pixels, got {value}")));
            }
        }
        let size = reader.output_buffer_size().ok_or_else(|| fail(format!("{width}×{height} pixels is too large")))?;
        let mut buf = vec![0u8; size];
        let info = reader.next_frame(&mut buf).map_err(|e| fail(format!("cannot be decoded: {e}")))?;
        let rgba = to_rgba8(&buf, info.color_type, info.line_size, width, height)
            .ok_or_else(|| fail(format!("unexpected pixel layout {:?} {:?}", info.color_type, info.bit_depth)))?;
        Ok(Self { width, height, rgba, pma })
    }
}

/// 8-bit rows of any colour type (after `normalize_to_color8`) as RGBA8, or `None` for a layout
/// the transformations should have removed (indexed colour).
fn to_rgba8(buf: &[u8], color: png::ColorType, line_size: usize, width: u32, height: u32) -> Option<Vec<u8>> {
    let channels = match color {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return None,
    };
    let (w, h) = (width as usize, height as usize);
    if line_size < w * channels || buf.len() < line_size * h {
        return None;
    }
    let mut out = Vec::with_capacity(w * h * 4);
    for row in buf.chunks(line_size).take(h) {
        for px in row[..w * channels].chunks_exact(channels) {
            out.extend_from_slice(&match *px {
                [g] => [g, g, g, 255],
                [g, a] => [g, g, g, a],
                [r, g, b] => [r, g, b, 255],
                [r, g, b, a] => [r, g, b, a],
                _ => return None,
            });
        }
    }
    Some(out)
}

impl Art<'_> {
    /// The world bounding box `(min, max)` of every piece's finite positions, or `None` when
    /// there are none (no pieces, or no finite vertex).
    #[must_use]
    pub fn extent(&self) -> Option<(Point2<f64>, Point2<f64>)> {
        let mut bounds: Option<(Point2<f64>, Point2<f64>)> = None;
        let points = self.pieces.iter().flat_map(|piece| piece.positions.iter());
        for &[x, y] in points.filter(|[x, y]| x.is_finite() && y.is_finite()) {
            let p = Point2::new(f64::from(x), f64::from(y));
            bounds = Some(match bounds {
                None => (p, p),
                Some((lo, hi)) => {
                    (Point2::new(lo.x.min(p.x), lo.y.min(p.y)), Point2::new(hi.x.max(p.x), hi.y.max(p.y)))
                }
            });
        }
        bounds
    }

    /// Checks that the art can be drawn: every page has sides of 1 to [`MAX_PAGE_SIDE`] pixels
    /// and holds `width · height · 4` bytes, every
    /// piece names a page that exists, has one UV per position, triangles whose indices are
    /// positions, and a finite tint (and dark colour). Positions and UVs may be non-finite:
    /// such triangles are skipped when drawing.
    ///
    /// # Errors
    /// [`RenderError::Art`] naming the first offending field, e.g. `pieces[3].triangles[7]`.
    pub fn check(&self) -> Result<(), RenderError> {
        for (i, page) in self.pages.iter().enumerate() {
            for (side, value) in [("width", page.width), ("height", page.height)] {
                if value == 0 || value > MAX_PAGE_SIDE {
                    return Err(art_error(
                        format!("pages[{i}].{side}"),
                        format!("must be between 1 and {MAX_PAGE_SIDE} pixels, got {value}"),
                    ));
                }
            }
            let want = u64::from(page.width) * u64::from(page.height) * 4;
            if page.rgba.len() as u64 != want {
                return Err(art_error(
                    format!("pages[{i}].rgba"),
                    format!("a {}×{} page needs {want} bytes, got {}", page.width, page.height, page.rgba.len()),
                ));
            }
        }
        for (i, piece) in self.pieces.iter().enumerate() {
            if piece.page >= self.pages.len() {
                return Err(art_error(
                    format!("pieces[{i}].page"),
                    format!("no page {} in an atlas of {} pages", piece.page, self.pages.len()),
                ));
            }
            if piece.uvs.len() != piece.positions.len() {
                return Err(art_error(
                    format!("pieces[{i}].uvs"),
                    format!("expected one per position ({}), got {}", piece.positions.len(), piece.uvs.len()),
                ));
            }
            let n = piece.positions.len();
            if let Some((t, tri)) =
                piece.triangles.iter().enumerate().find(|(_, tri)| tri.iter().any(|&k| usize::from(k) >= n))
            {
                return Err(art_error(
                    format!("pieces[{i}].triangles[{t}]"),
                    format!("indices {tri:?} must be below the {n} positions"),
                ));
            }
            let tint = piece.color.iter().chain(piece.dark.iter().flatten());
            if let Some(v) = tint.copied().find(|v| !v.is_finite()) {
                return Err(RenderError::NonFinite { field: format!("pieces[{i}].color"), value: f64::from(v) });
            }
        }
        Ok(())
    }
}

fn art_error(field: String, problem: String) -> RenderError {
    RenderError::Art { field, problem }
}

/// The affine map from world coordinates (y up) to pixel coordinates (y down, origin at the
/// top-left corner of the picture, pixel `(i, j)` covering `[i, i + 1) × [j, j + 1)`):
/// `px = xx·x + xy·y + tx`, `py = yx·x + yy·y + ty`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldToPixel {
    /// ∂px/∂x.
    pub xx: f64,
    /// ∂px/∂y.
    pub xy: f64,
    /// ∂py/∂x.
    pub yx: f64,
    /// ∂py/∂y.
    pub yy: f64,
    /// px of the world origin.
    pub tx: f64,
    /// py of the world origin.
    pub ty: f64,
}

impl WorldToPixel {
    /// The map of a figure's [`View`] (equal scale, y flipped).
    #[must_use]
    pub fn of_view(view: &View) -> Self {
        let (tx, ty) = view.world_to_pixel(Point2::new(0.0, 0.0));
        let s = view.scale();
        Self { xx: s, xy: 0.0, yx: 0.0, yy: -s, tx, ty }
    }

    /// The map that shows the world box `min`–`max` centred on a `width` × `height` picture,
    /// with equal scale on both axes, its larger side (relative to the picture's) filling
    /// `fill` of the picture (Spine's reference pictures use 0.9), y flipped. A box of no size
    /// is drawn at scale 1 around its centre.
    #[must_use]
    pub fn fitting(min: Point2<f64>, max: Point2<f64>, width: u32, height: u32, fill: f64) -> Self {
        let (w, h) = (f64::from(width), f64::from(height));
        let size = max - min;
        let fits = [w / size.x, h / size.y].into_iter().filter(|s| s.is_finite() && *s > 0.0);
        let scale = fits.reduce(f64::min).map_or(1.0, |s| fill * s);
        let (cx, cy) = (0.5 * (min.x + max.x), 0.5 * (min.y + max.y));
        Self { xx: scale, xy: 0.0, yx: 0.0, yy: -scale, tx: 0.5 * w - scale * cx, ty: 0.5 * h + scale * cy }
    }

    /// Pixel coordinates of the world point `(x, y)`.
    #[must_use]
    pub fn apply(&self, x: f64, y: f64) -> (f64, f64) {
        (self.xx * x + self.xy * y + self.tx, self.yx * x + self.yy * y + self.ty)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encode(color: png::ColorType, depth: png::BitDepth, w: u32, h: u32, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        enc.write_header().unwrap().write_image_data(data).unwrap();
        out
    }

    #[test]
    fn pages_decode_from_every_colour_type() {
        let rgba = encode(png::ColorType::Rgba, png::BitDepth::Eight, 2, 1, &[1, 2, 3, 4, 5, 6, 7, 8]);
        let page = Page::decode_png(&rgba, "a.png", true).unwrap();
        assert_eq!((page.width, page.height, page.pma), (2, 1, true));
        assert_eq!(page.rgba, [1, 2, 3, 4, 5, 6, 7, 8]);
        let rgb = encode(png::ColorType::Rgb, png::BitDepth::Eight, 1, 2, &[9, 8, 7, 6, 5, 4]);
        assert_eq!(Page::decode_png(&rgb, "b.png", false).unwrap().rgba, [9, 8, 7, 255, 6, 5, 4, 255]);
        let grey_alpha = encode(png::ColorType::GrayscaleAlpha, png::BitDepth::Eight, 1, 1, &[100, 50]);
        assert_eq!(Page::decode_png(&grey_alpha, "c.png", false).unwrap().rgba, [100, 100, 100, 50]);
        // 16-bit samples keep their high byte.
        let deep = encode(png::ColorType::Rgba, png::BitDepth::Sixteen, 1, 1, &[1, 0, 2, 0, 3, 0, 255, 255]);
        assert_eq!(Page::decode_png(&deep, "d.png", false).unwrap().rgba, [1, 2, 3, 255]);
    }

    #[test]
    fn bad_pages_name_the_file() {
        let err = Page::decode_png(b"GIF89a", "art/spineboy.png", false).unwrap_err().to_string();
        assert!(err.starts_with("art/spineboy.png: not a PNG image"), "{err}");
        assert!(!err.contains('\n'), "{err}");
        let good = encode(png::ColorType::Rgba, png::BitDepth::Eight, 4, 4, &[7; 64]);
        let err = Page::decode_png(&good[..good.len() - 20], "cut.png", false).unwrap_err().to_string();
        assert!(err.starts_with("cut.png: "), "{err}");
    }

    fn piece(positions: Vec<[f32; 2]>) -> ArtPiece {
        let uvs = vec![[0.0; 2]; positions.len()];
        ArtPiece {
            page: 0,
            positions,
            uvs,
            triangles: vec![[0, 1, 2]],
            color: [1.0; 4],
            dark: None,
            blend: Blend::Normal,
        }
    }

    #[test]
    fn extent_covers_every_finite_position() {
        assert_eq!(Art::default().extent(), None);
        let art = Art {
            pages: &[],
            pieces: vec![
                piece(vec![[1.0, 2.0], [3.0, -1.0], [f32::NAN, 100.0]]),
                piece(vec![[-4.0, 0.5], [0.0, 7.0], [2.0, 2.0]]),
            ],
        };
        assert_eq!(art.extent(), Some((Point2::new(-4.0, -1.0), Point2::new(3.0, 7.0))));
    }

    #[test]
    fn checks_name_the_field() {
        let page = Page { width: 1, height: 1, rgba: vec![0; 4], pma: false };
        let mut art = Art { pages: &[page], pieces: vec![piece(vec![[0.0; 2]; 3])] };
        assert_eq!(art.check(), Ok(()));
        art.pieces[0].triangles.push([0, 3, 1]);
        assert_eq!(
            art.check().unwrap_err().to_string(),
            "pieces[0].triangles[1]: indices [0, 3, 1] must be below the 3 positions"
        );
        art.pieces[0].triangles.pop();
        art.pieces[0].page = 2;
        assert_eq!(art.check().unwrap_err().to_string(), "pieces[0].page: no page 2 in an atlas of 1 pages");
        art.pieces[0].page = 0;
        art.pieces[0].uvs.pop();
        assert_eq!(art.check().unwrap_err().to_string(), "pieces[0].uvs: expected one per position (3), got 2");
        art.pieces[0].uvs.push([0.0; 2]);
        art.pieces[0].dark = Some([0.0, f32::INFINITY, 0.0]);
        assert_eq!(art.check().unwrap_err().to_string(), "pieces[0].color: must be a finite number, got inf");
        art.pieces[0].dark = None;
        let short = [Page { width: 1, height: 1, rgba: vec![0; 3], pma: false }];
        art.pages = &short;
        assert_eq!(art.check().unwrap_err().to_string(), "pages[0].rgba: a 1×1 page needs 4 bytes, got 3");
        // A page of no pixels has no texel to sample.
        let empty = [Page { width: 0, height: 1, rgba: vec![], pma: false }];
        art.pages = &empty;
        assert_eq!(art.check().unwrap_err().to_string(), "pages[0].width: must be between 1 and 16384 pixels, got 0");
    }

    #[test]
    fn fitting_centres_the_box_at_the_fill() {
        let map = WorldToPixel::fitting(Point2::new(-1.0, 0.0), Point2::new(3.0, 2.0), 800, 800, 0.9);
        // The wider side (4) fills 720 px: scale 180; the centre (1, 1) lands at (400, 400).
        assert_eq!(map.apply(1.0, 1.0), (400.0, 400.0));
        assert_eq!(map.apply(-1.0, 0.0), (40.0, 580.0));
        assert_eq!(map.apply(3.0, 2.0), (760.0, 220.0));
    }
}
