//! SVG → pixels with resvg, using only the embedded DejaVu Sans (never the system's fonts).

use std::sync::{Arc, OnceLock};

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{self, fontdb};

use crate::RenderError;
use crate::svg::FONT_FAMILY;

/// The smallest side of a picture, in pixels.
pub const MIN_SIDE: u32 = 16;
/// The largest side of a picture, in pixels.
pub const MAX_SIDE: u32 = 4096;

/// A font database holding DejaVu Sans (regular and bold) from the `dejavu` crate and nothing
/// else, built once.
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = fontdb::Database::new();
            db.load_font_data(dejavu::sans::regular().to_vec());
            db.load_font_data(dejavu::sans::bold().to_vec());
            db.set_sans_serif_family(FONT_FAMILY);
            Arc::new(db)
        })
        .clone()
}

/// Checks a picture size against [`MIN_SIDE`]`..=`[`MAX_SIDE`].
pub(crate) fn check_size(width: u32, height: u32) -> Result<(), RenderError> {
    for (field, value) in [("width", width), ("height", height)] {
        if !(MIN_SIDE..=MAX_SIDE).contains(&value) {
            return Err(RenderError::Size { field, value: u64::from(value) });
        }
    }
    Ok(())
}

/// Parses SVG text with the embedded fonts.
pub(crate) fn parse(svg: &str) -> Result<usvg::Tree, RenderError> {
    let mut options = usvg::Options { font_family: FONT_FAMILY.to_string(), ..usvg::Options::default() };
    options.fontdb = fonts();
    usvg::Tree::from_str(svg, &options).map_err(|e| RenderError::Svg(e.to_string()))
}

/// The size of a parsed tree in whole pixels, checked.
fn tree_size(tree: &usvg::Tree) -> Result<(u32, u32), RenderError> {
    let size = tree.size();
    let mut out = [0u32; 2];
    for (slot, (field, value)) in out.iter_mut().zip([("width", size.width()), ("height", size.height())]) {
        let rounded = value.ceil();
        if !(f32::from(MIN_SIDE as u16)..=MAX_SIDE as f32).contains(&rounded) {
            return Err(RenderError::Size { field, value: rounded.max(0.0) as u64 });
        }
        *slot = rounded as u32;
    }
    Ok((out[0], out[1]))
}

/// Draws `tree` onto `pixmap` (over what is there), scaled so that its size fills the pixmap.
pub(crate) fn render_onto(tree: &usvg::Tree, pixmap: &mut Pixmap) {
    let size = tree.size();
    let sx = pixmap.width() as f32 / size.width();
    let sy = pixmap.height() as f32 / size.height();
    resvg::render(tree, Transform::from_scale(sx, sy), &mut pixmap.as_mut());
}

/// Rasterises SVG text into a new pixmap of the SVG's `width` × `height` (rounded up).
pub(crate) fn svg_to_pixmap(svg: &str) -> Result<Pixmap, RenderError> {
    let tree = parse(svg)?;
    let (w, h) = tree_size(&tree)?;
    let mut pixmap = new_pixmap(w, h)?;
    render_onto(&tree, &mut pixmap);
    Ok(pixmap)
}

/// A transparent pixmap of a checked size.
pub(crate) fn new_pixmap(width: u32, height: u32) -> Result<Pixmap, RenderError> {
    check_size(width, height)?;
    Pixmap::new(width, height)
        .ok_or(RenderError::Encode { format: "png", message: format!("cannot allocate {width}×{height} pixels") })
}

/// Rasterises SVG text to a PNG file's bytes (8-bit RGBA, the SVG's `width` × `height`).
///
/// Text is set in DejaVu Sans, embedded in this crate; system fonts are never consulted, so
/// the result is the same on every machine.
///
/// # Errors
/// [`RenderError::Svg`] if the text is not SVG, [`RenderError::Size`] if a side (rounded up)
/// lies outside [`MIN_SIDE`]`..=`[`MAX_SIDE`], [`RenderError::Encode`] if encoding fails.
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, RenderError> {
    pixmap_png(&svg_to_pixmap(svg)?)
}

/// Draws SVG text over what `pixmap` already holds (a character's art, say), scaled so that the
/// SVG's size fills the pixmap, with the embedded fonts.
///
/// # Errors
/// [`RenderError::Svg`] if the text is not SVG.
pub fn draw_svg_onto(svg: &str, pixmap: &mut Pixmap) -> Result<(), RenderError> {
    let tree = parse(svg)?;
    render_onto(&tree, pixmap);
    Ok(())
}

/// A pixmap's PNG file bytes (8-bit RGBA, straight alpha as PNG wants it).
///
/// # Errors
/// [`RenderError::Encode`] if encoding fails.
pub fn pixmap_png(pixmap: &Pixmap) -> Result<Vec<u8>, RenderError> {
    pixmap.encode_png().map_err(|e| RenderError::Encode { format: "png", message: e.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_embedded_fonts_are_known() {
        let db = fonts();
        let families: Vec<String> = db.faces().flat_map(|f| f.families.iter().map(|(name, _)| name.clone())).collect();
        assert_eq!(db.len(), 2, "{families:?}");
        assert!(families.iter().all(|f| f == FONT_FAMILY), "{families:?}");
    }

    #[test]
    fn sizes_are_checked() {
        assert!(check_size(16, 4096).is_ok());
        assert_eq!(check_size(15, 100).unwrap_err().to_string(), "width: must be between 16 and 4096 pixels, got 15");
        assert_eq!(
            check_size(100, 5000).unwrap_err().to_string(),
            "height: must be between 16 and 4096 pixels, got 5000"
        );
        let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"8\" height=\"40\"/>";
        assert!(matches!(svg_to_png(svg), Err(RenderError::Size { field: "width", value: 8 })));
        assert!(matches!(svg_to_png("not svg"), Err(RenderError::Svg(_))));
    }
}
