//! Pictures of a posed character with its art: the art under the bones ([`character_art_png`],
//! [`character_art_svg`]), or the art alone, fitted as Spine's own renderer fits a skeleton
//! ([`art_only_png`], [`art_only_svg`]).
//!
//! With the bones, the view is the bones picture's ([`character_svg`](crate::character_svg)),
//! fitted to the bones, the targets and every piece's vertices together: the grid, then the art,
//! then the bones, targets and caption. The art alone is drawn on a transparent background, the
//! box of its vertices filling [`ART_FILL`] of the picture (its larger side relative to the
//! picture's), centred, y up: the fit of Spine's reference pictures.
//!
//! An SVG cannot hold textured triangles: the art is rasterised at the picture's size and
//! embedded as one PNG `<image>` (a `data:` URL) under the vector bones.

use ikarus::Point2;

use crate::RenderError;
use crate::art::{Art, WorldToPixel};
use crate::art_raster::{art_pixmap, draw_art};
use crate::character::{CharacterFigure, Layers, character_layers};
use crate::raster::{check_size, draw_svg_onto, pixmap_png, svg_to_pixmap};
use crate::svg::Svg;
use crate::view::View;
use resvg::tiny_skia::Pixmap;

/// How much of the picture the art alone fills: its box's larger side (relative to the
/// picture's) is 90 % of it, as in Spine's reference pictures.
pub const ART_FILL: f64 = 0.9;

/// The view of `figure` and `art` together on a `width` × `height` picture.
fn view_of(figure: &CharacterFigure, art: &Art, width: u32, height: u32) -> View {
    let (mut min, mut max) = figure.extent();
    if figure.bones.is_empty() && figure.targets.is_empty() {
        if let Some(e) = art.extent() {
            (min, max) = e;
        }
    }
    if let Some((lo, hi)) = art.extent() {
        (min, max) = (min.inf(&lo), max.sup(&hi));
    }
    View::fitting(min, max, width, height)
}

/// The figure with its art as PNG bytes: the grid, the art, then the bones, targets and
/// caption, in the view fitted to the bones and the art together.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096; [`RenderError::NonFinite`] for a bone or
/// target not finite; [`Art::check`]'s; [`RenderError::Encode`] if encoding fails.
pub fn character_art_png(figure: &CharacterFigure, art: &Art, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    check_size(width, height)?;
    figure.check()?;
    let view = view_of(figure, art, width, height);
    let mut pixmap = svg_to_pixmap(&character_layers(figure, &[], view, (width, height), Layers::Grid))?;
    draw_art(art, &WorldToPixel::of_view(&view), &mut pixmap)?;
    draw_svg_onto(&character_layers(figure, &[], view, (width, height), Layers::Bones), &mut pixmap)?;
    pixmap_png(&pixmap)
}

/// The figure with its art as an SVG document: the grid, the art as one embedded PNG `<image>`
/// of the picture's size, then the bones (vector, each a `<g class="bone">` with its name),
/// targets and caption.
///
/// # Errors
/// As [`character_art_png`].
pub fn character_art_svg(figure: &CharacterFigure, art: &Art, width: u32, height: u32) -> Result<String, RenderError> {
    check_size(width, height)?;
    figure.check()?;
    let view = view_of(figure, art, width, height);
    let layer = art_pixmap(art, &WorldToPixel::of_view(&view), width, height)?;
    let href = png_data_url(&pixmap_png(&layer)?);
    Ok(character_layers(figure, &[], view, (width, height), Layers::WithImage(&href)))
}

/// The art alone on a transparent `width` × `height` pixmap, fitted as Spine's reference
/// pictures are (see [`ART_FILL`]); art with no finite vertex leaves it empty.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096, and [`Art::check`]'s.
pub fn art_only_pixmap(art: &Art, width: u32, height: u32) -> Result<Pixmap, RenderError> {
    let (min, max) = art.extent().unwrap_or((Point2::origin(), Point2::origin()));
    art_pixmap(art, &WorldToPixel::fitting(min, max, width, height, ART_FILL), width, height)
}

/// [`art_only_pixmap`] as PNG bytes (straight alpha).
///
/// # Errors
/// As [`art_only_pixmap`], and [`RenderError::Encode`] if encoding fails.
pub fn art_only_png(art: &Art, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    pixmap_png(&art_only_pixmap(art, width, height)?)
}

/// [`art_only_pixmap`] as an SVG document holding it as one PNG `<image>`.
///
/// # Errors
/// As [`art_only_png`].
pub fn art_only_svg(art: &Art, width: u32, height: u32) -> Result<String, RenderError> {
    let href = png_data_url(&art_only_png(art, width, height)?);
    let mut svg = Svg::new(width, height);
    svg.comment("art");
    svg.image(0.0, 0.0, f64::from(width), f64::from(height), &href);
    Ok(svg.finish())
}

/// `data:image/png;base64,…` of PNG bytes (RFC 4648 base64, padded).
pub(crate) fn png_data_url(png: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(22 + png.len().div_ceil(3) * 4);
    out.push_str("data:image/png;base64,");
    for chunk in png.chunks(3) {
        let b = [chunk[0], chunk.get(1).copied().unwrap_or(0), chunk.get(2).copied().unwrap_or(0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ArtPiece, Blend, Page, PosedBone};

    #[test]
    fn base64_by_the_rfc_examples() {
        // RFC 4648 section 10.
        for (plain, coded) in [("", ""), ("f", "Zg=="), ("fo", "Zm8="), ("foo", "Zm9v"), ("foobar", "Zm9vYmFy")] {
            assert_eq!(png_data_url(plain.as_bytes()), format!("data:image/png;base64,{coded}"));
        }
    }

    fn red() -> [Page; 1] {
        [Page { width: 1, height: 1, rgba: vec![255, 0, 0, 255], pma: false }]
    }

    fn square(pages: &[Page]) -> Art<'_> {
        let piece = ArtPiece {
            page: 0,
            positions: vec![[0.0, 0.0], [10.0, 0.0], [10.0, 20.0], [0.0, 20.0]],
            uvs: vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            color: [1.0; 4],
            dark: None,
            blend: Blend::Normal,
        };
        Art { pages, pieces: vec![piece] }
    }

    #[test]
    fn the_art_alone_fills_ninety_percent_centred() {
        // A 10 × 20 box on 100 × 100: 4.5 px a unit, 45 × 90 px from (27.5, 5) to (72.5, 95):
        // pixel centres 27.5 (on the left edge, which owns it) to 71.5 across (72.5 is on the
        // right edge, which does not), 5.5 to 94.5 down.
        let pixmap = art_only_pixmap(&square(&red()), 100, 100).unwrap();
        let opaque = |i: u32, j: u32| pixmap.pixel(i, j).unwrap().alpha() == 255;
        let clear = |i: u32, j: u32| pixmap.pixel(i, j).unwrap().alpha() == 0;
        assert!(opaque(27, 5) && opaque(71, 94) && opaque(50, 50));
        assert!(clear(26, 50) && clear(72, 50) && clear(50, 4) && clear(50, 95));
    }

    #[test]
    fn the_bones_go_over_the_art_in_one_view() {
        let bones = vec![PosedBone { name: "b", origin: Point2::new(5.0, 10.0), tip: Point2::new(5.0, 40.0) }];
        let figure = CharacterFigure { bones, targets: vec![], caption: None };
        let view = view_of(&figure, &square(&red()), 200, 200);
        for p in [Point2::new(0.0, 0.0), Point2::new(10.0, 40.0)] {
            let (x, y) = view.world_to_pixel(p);
            assert!(view.plot_area().contains(x, y), "{p:?}");
        }
        let svg = character_art_svg(&figure, &square(&red()), 200, 200).unwrap();
        let (art, bone) = (svg.find("<image").unwrap(), svg.find("<g class=\"bone\">").unwrap());
        assert!(art < bone && svg.find("<!-- grid -->").unwrap() < art);
        assert!(character_art_png(&figure, &square(&red()), 200, 200).unwrap().starts_with(b"\x89PNG"));
        assert!(art_only_svg(&square(&red()), 50, 50).unwrap().contains("href=\"data:image/png;base64,iVBOR"));
    }
}
