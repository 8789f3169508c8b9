//! Spine's texture atlas (`.atlas`): read ([`read`]) into its pages and regions, and told by its
//! text's shape ([`is_atlas`]) when it is given where a skeleton or a rig file is expected, so
//! that the answer says what it is and what to pass.
//!
//! An atlas is plain text: a page's image file name (`raptor.png`), then the page's settings
//! (`size:`, `format:`, `filter:`, `repeat:`, `pma:`, `scale:`), then region blocks, each a
//! region's name followed by its settings (`bounds:`, `xy:`, `size:`, `rotate:`, `offsets:`,
//! `orig:`, `offset:`, `index:`), the settings indented in older exports.
//!
//! Reading (Spine's "Atlas export format" page, 4.x, and the libgdx format of 3.x exports): a
//! blank line ends a page; the next name line starts a page, any other name line a region of the
//! current page. Page fields: `size: w, h` (required here: UVs are fractions of it), `pma`
//! (false), `scale` (1; one or two numbers), `format`, `filter`, `repeat` (kept out: a loader's
//! business). Region fields: `bounds: x, y, w, h` (3.x: `xy: x, y` and `size: w, h`), `offsets:
//! left, bottom, originalW, originalH` (3.x: `offset: left, bottom` and `orig: w, h`; default no
//! whitespace), `rotate: true | false | degrees` (`true` is 90; 0, 90, 180 or 270), `index`
//! (−1). `w, h` are the image's own, before its rotation on the page. Other region fields
//! (`split`, `pad`, custom values) are skipped.

/// The image files an atlas page names.
const PAGE_IMAGES: [&str; 5] = [".png", ".jpg", ".jpeg", ".webp", ".pma.png"];

/// The keys of a page's or a region's settings lines.
const KEYS: [&str; 13] = [
    "size", "format", "filter", "repeat", "pma", "scale", "bounds", "xy", "rotate", "offsets", "orig", "offset",
    "index",
];

/// Whether `text` looks like a Spine texture atlas: its first line that is not blank names an
/// image file, and the next one is a page's or a region's setting (`key: value`).
#[must_use]
pub fn is_atlas(text: &str) -> bool {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty()).take(2);
    let (Some(page), Some(setting)) = (lines.next(), lines.next()) else { return false };
    let lower = page.to_ascii_lowercase();
    let image = PAGE_IMAGES.iter().any(|ext| lower.ends_with(ext)) && !page.contains(['=', '[', '"']);
    let key = setting.split_once(':').map(|(k, _)| k.trim());
    image && key.is_some_and(|k| KEYS.contains(&k))
}

/// The one-line refusal of an atlas given as a skeleton (without a label).
pub const ATLAS: &str =
    "this is a Spine texture atlas (.atlas), not a skeleton: pass the skeleton's .json (or .skel) exported beside it";

use crate::error::Error;
use ikarus::character::{AtlasRegion, Regions};

/// An atlas page: its image and how it is stored.
#[derive(Debug, Clone, PartialEq)]
pub struct AtlasPage {
    /// The image's file name, relative to the atlas file's folder.
    pub file: String,
    /// The image's width and height in pixels.
    pub size: [u32; 2],
    /// Whether the image's colours are premultiplied by alpha.
    pub pma: bool,
    /// The scale the images were packed at (`scale`, x and y; 1 unless given).
    pub scale: [f64; 2],
}

/// A texture atlas: its pages and their regions.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Atlas {
    /// The pages, as listed.
    pub pages: Vec<AtlasPage>,
    /// The regions of every page, as listed (each names its page by index).
    pub regions: Vec<AtlasRegion>,
    /// Per region, its `index` (−1 unless given; a sequence's frames share a name).
    pub indices: Vec<i32>,
}

impl Atlas {
    /// The regions, found by name, as drawing takes them.
    #[must_use]
    pub fn lookup(&self) -> Regions {
        Regions::new(self.regions.clone())
    }
}

/// A region being read: its fields as they come, in either spelling.
#[derive(Default)]
struct Pending {
    name: String,
    line: usize,
    xy: Option<[f64; 2]>,
    size: Option<[f64; 2]>,
    offset: Option<[f64; 2]>,
    orig: Option<[f64; 2]>,
    degrees: u16,
    index: i32,
}

/// Reads an atlas's text. A bad line is refused naming its number (from 1), field and value.
pub fn read(text: &str) -> Result<Atlas, Error> {
    let mut atlas = Atlas::default();
    let mut new_page = true;
    let mut region: Option<Pending> = None;
    for (n, raw) in text.lines().enumerate() {
        let n = n + 1;
        let line = raw.trim();
        if line.is_empty() {
            finish(&mut atlas, region.take())?;
            new_page = true;
            continue;
        }
        let Some((key, value)) = line.split_once(':') else {
            finish(&mut atlas, region.take())?;
            if new_page {
                atlas.pages.push(AtlasPage { file: line.to_owned(), size: [0, 0], pma: false, scale: [1.0, 1.0] });
                new_page = false;
            } else {
                region = Some(Pending { name: line.to_owned(), line: n, index: -1, ..Pending::default() });
            }
            continue;
        };
        let (key, value) = (key.trim(), value.trim());
        let at = |what: &str| Error::input(format!("atlas line {n}: {key}: {value:?}: {what}"));
        let Some(page) = atlas.pages.last_mut() else { return Err(at("a setting before any page's image name")) };
        match region.as_mut() {
            None => match key {
                "size" => {
                    let [w, h] = numbers::<2>(value).map_err(|e| at(e.message()))?;
                    if w < 1.0 || h < 1.0 || w.fract() != 0.0 || h.fract() != 0.0 || w > 65536.0 || h > 65536.0 {
                        return Err(at("expected two whole numbers of pixels, 1 to 65536"));
                    }
                    page.size = [w as u32, h as u32];
                }
                "pma" => page.pma = flag(value).map_err(|e| at(e.message()))?,
                "scale" => {
                    let list = list(value).map_err(|e| at(e.message()))?;
                    page.scale = match list[..] {
                        [s] if s > 0.0 => [s, s],
                        [x, y] if x > 0.0 && y > 0.0 => [x, y],
                        _ => return Err(at("expected one or two positive numbers")),
                    };
                }
                "format" | "filter" | "repeat" => {}
                _ => return Err(at("not a page setting (size, format, filter, repeat, pma, scale)")),
            },
            Some(r) => match key {
                "bounds" => {
                    let [x, y, w, h] = numbers::<4>(value).map_err(|e| at(e.message()))?;
                    (r.xy, r.size) = (Some([x, y]), Some([w, h]));
                }
                "xy" => r.xy = Some(numbers::<2>(value).map_err(|e| at(e.message()))?),
                "size" => r.size = Some(numbers::<2>(value).map_err(|e| at(e.message()))?),
                "offsets" => {
                    let [x, y, w, h] = numbers::<4>(value).map_err(|e| at(e.message()))?;
                    (r.offset, r.orig) = (Some([x, y]), Some([w, h]));
                }
                "offset" => r.offset = Some(numbers::<2>(value).map_err(|e| at(e.message()))?),
                "orig" => r.orig = Some(numbers::<2>(value).map_err(|e| at(e.message()))?),
                "rotate" => {
                    r.degrees = match value {
                        "true" => 90,
                        "false" => 0,
                        _ => match value.parse::<i32>() {
                            Ok(d) if d.rem_euclid(90) == 0 => d.rem_euclid(360) as u16,
                            _ => return Err(at("expected true, false or a multiple of 90 degrees")),
                        },
                    };
                }
                "index" => r.index = value.parse().map_err(|_| at("expected a whole number"))?,
                _ => {}
            },
        }
    }
    finish(&mut atlas, region.take())?;
    Ok(atlas)
}

/// Adds a region read to its page, once its fields are checked.
fn finish(atlas: &mut Atlas, region: Option<Pending>) -> Result<(), Error> {
    let Some(r) = region else { return Ok(()) };
    let at = |what: &str| Error::input(format!("atlas line {} (region {:?}): {what}", r.line, r.name));
    let page = atlas.pages.len() - 1;
    let p = &atlas.pages[page];
    if p.size[0] == 0 {
        return Err(at(&format!("page {:?} has no size: (needed to place its regions)", p.file)));
    }
    let (Some([x, y]), Some([w, h])) = (r.xy, r.size) else { return Err(at("bounds: missing")) };
    let on_page = if r.degrees % 180 == 90 { [h, w] } else { [w, h] };
    if [x, y, w, h].iter().any(|v| *v < 0.0)
        || x + on_page[0] > f64::from(p.size[0])
        || y + on_page[1] > f64::from(p.size[1])
    {
        return Err(at(&format!("bounds: {x}, {y}, {w}, {h}: not within the page ({} × {})", p.size[0], p.size[1])));
    }
    let offsets = r.offset.unwrap_or([0.0, 0.0]);
    let original = r.orig.unwrap_or([w, h]);
    if original[0] <= 0.0 || original[1] <= 0.0 || offsets[0] + w > original[0] || offsets[1] + h > original[1] {
        return Err(at(&format!(
            "offsets: {}, {}, {}, {}: the packed image ({w} × {h}) must fit in the original size",
            offsets[0], offsets[1], original[0], original[1]
        )));
    }
    atlas.regions.push(AtlasRegion {
        name: r.name,
        page,
        page_size: [f64::from(p.size[0]), f64::from(p.size[1])],
        bounds: [x, y, w, h],
        offsets,
        original,
        degrees: r.degrees,
        pma: p.pma,
    });
    atlas.indices.push(r.index);
    Ok(())
}

/// Comma-separated finite numbers.
fn list(value: &str) -> Result<Vec<f64>, Error> {
    value
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| Error::input(format!("{:?} is not a number", v.trim())))
        })
        .collect()
}

/// Exactly `N` comma-separated numbers.
fn numbers<const N: usize>(value: &str) -> Result<[f64; N], Error> {
    let list = list(value)?;
    list.try_into().map_err(|l: Vec<f64>| Error::input(format!("expected {N} numbers, got {}", l.len())))
}

/// `true` or `false`.
fn flag(value: &str) -> Result<bool, Error> {
    match value {
        "true" => Ok(true),
        "false" => Ok(false),
        _ => Err(Error::input("expected true or false")),
    }
}

#[cfg(test)]
#[path = "atlas_tests.rs"]
mod read_tests;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atlases_old_and_new_are_told_and_rigs_are_not() {
        assert!(is_atlas("raptor.png\n\tsize: 1024, 512\n\tfilter: Linear, Linear\nback-arm\n\tbounds: 1, 2, 3, 4\n"));
        assert!(is_atlas("\nspineboy.png\nsize: 1024,256\nformat: RGBA8888\nfilter: Linear,Linear\nrepeat: none\n"));
        assert!(is_atlas("a.PNG\r\nbounds: 0,0,1,1\r\n"));
        assert!(!is_atlas("name = \"puppet\"\n[[bones]]\nname = \"a.png\"\n"));
        assert!(!is_atlas("x.png\n"));
        assert!(!is_atlas("# a.png\nsize = 3\n"));
        assert!(!is_atlas(""));
    }
}
