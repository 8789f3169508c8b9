//! A Spine texture atlas (`.atlas`) given where a skeleton or a rig file is expected, told by its
//! text's shape so that the answer says what it is and what to pass, instead of a TOML parser's
//! complaint about its first line.
//!
//! An atlas is plain text: a page's image file name (`raptor.png`), then the page's settings
//! (`size:`, `format:`, `filter:`, `repeat:`, `pma:`, `scale:`), then region blocks, each a
//! region's name followed by its settings (`bounds:`, `xy:`, `size:`, `rotate:`, `offsets:`,
//! `orig:`, `offset:`, `index:`), the settings indented in older exports.

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
