//! `POST /api/atlas/parse`: a Spine texture atlas, and optionally its pages' PNG images, read once
//! and kept by id, as `/api/rig/parse` keeps characters: `/api/pose` with `"atlas": ID` answers
//! the pose's drawing (its `art`), `/api/render` with `"atlas": ID` draws the character with its
//! art (which needs the images).
//!
//! Body: `{"atlas": "<the .atlas text>", "pages": {"spineboy.png": "<base64 PNG>", …}}`;
//! `pages` is optional, and when given names every page the atlas names, and only those.
//! Answer: `{"id", "pages": [{"file", "width", "height", "pma", "image"}], "regions"}`.
//!
//! Caps (on top of the body's `--max-file-bytes`): a page image at most [`MAX_PAGE_SIDE`]
//! pixels a side and the atlas's images at most [`MAX_ATLAS_PIXELS`] pixels together, both
//! read from the PNG's header before anything is decoded (a small PNG can hold a huge image);
//! at most [`MAX_ATLASES`] atlases and [`MAX_ATLAS_BYTES`] bytes (text and decoded images)
//! kept, the least recently used let go. An id not kept is answered 404 naming `atlas`.

use std::collections::BTreeMap;
use std::sync::{Arc, OnceLock};

use base64::Engine;
use serde::{Deserialize, Serialize};

use super::wire::{Problem, Reply, parse_json, status};
use crate::character::art_draw::AtlasArt;
use crate::character::atlas;
use crate::character::store::{Store, Weigh, hashed};
use crate::error::Error;
use crate::names::Quoted;

/// Largest side of a page image, in pixels (Spine's packer goes to 4096 by default).
pub const MAX_PAGE_SIDE: u32 = 4096;

/// Most pixels of one atlas's page images together (two pages of 4096 × 4096).
pub const MAX_ATLAS_PIXELS: u64 = 2 * 4096 * 4096;

/// Most atlases kept.
pub const MAX_ATLASES: usize = 8;

/// Most bytes kept over every atlas: their text and their decoded images (4 bytes a pixel).
pub const MAX_ATLAS_BYTES: usize = 256 << 20;

/// The body of `/api/atlas/parse`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtlasReq {
    /// The `.atlas` file's text.
    pub atlas: String,
    /// Each page's PNG image by the file name the atlas gives it, base64.
    #[serde(default)]
    pub pages: Option<BTreeMap<String, String>>,
}

/// An atlas kept: read, its regions found by name, and its pages' images when they were sent.
#[derive(Debug)]
pub struct KeptAtlas {
    /// The atlas and its regions; its `pages` hold the decoded images, or nothing when none
    /// were sent.
    pub art: AtlasArt,
    /// Whether the page images were sent (and decoded into `art.pages`).
    pub images: bool,
    text_bytes: usize,
}

impl Weigh for KeptAtlas {
    fn bytes(&self) -> usize {
        self.text_bytes + self.art.pages.iter().map(|p| p.rgba.len()).sum::<usize>()
    }
}

/// The process's atlases.
pub fn kept() -> &'static Store<KeptAtlas> {
    static STORE: OnceLock<Store<KeptAtlas>> = OnceLock::new();
    STORE.get_or_init(|| Store::new(MAX_ATLASES, MAX_ATLAS_BYTES))
}

/// A page as the answer lists it.
#[derive(Debug, Serialize)]
struct PageJson<'a> {
    file: &'a str,
    width: u32,
    height: u32,
    pma: bool,
    image: bool,
}

/// The answer of `/api/atlas/parse`.
#[derive(Debug, Serialize)]
struct AtlasJson<'a> {
    id: String,
    pages: Vec<PageJson<'a>>,
    regions: usize,
}

/// `POST /api/atlas/parse` (see the module's doc).
pub fn parse(body: &[u8]) -> Result<Reply, Problem> {
    let req: AtlasReq = parse_json(body)?;
    let (id, kept_atlas) = read(&req)?;
    let a = &kept_atlas.art.atlas;
    let pages = a
        .pages
        .iter()
        .map(|p| PageJson { file: &p.file, width: p.size[0], height: p.size[1], pma: p.pma, image: kept_atlas.images })
        .collect();
    Reply::json(&AtlasJson { id, pages, regions: a.regions.len() })
}

/// The atlas of `req` read (its images decoded, within the caps), kept, with its id.
fn read(req: &AtlasReq) -> Result<(String, Arc<KeptAtlas>), Problem> {
    let text = &req.atlas;
    let read = atlas::read(text).map_err(|e| Problem::invalid(format!("atlas: {e}")))?;
    let Some(given) = &req.pages else {
        let id = hashed('a', &[text.as_bytes()]);
        let regions = read.lookup();
        let art = AtlasArt { atlas: read, regions, pages: Vec::new() };
        return Ok((id.clone(), kept().keep(id, KeptAtlas { art, images: false, text_bytes: text.len() })));
    };
    let names: Vec<&str> = read.pages.iter().map(|p| p.file.as_str()).collect();
    if let Some(stray) = given.keys().find(|k| !names.contains(&k.as_str())) {
        return Err(Problem::invalid(format!(
            "pages.{}: the atlas names no such page; it names {}",
            Quoted(stray),
            names.iter().map(|n| Quoted(n).to_string()).collect::<Vec<_>>().join(", ")
        )));
    }
    let mut bytes = BTreeMap::new();
    let mut pixels = 0u64;
    for name in &names {
        let Some(b64) = given.get(*name) else {
            return Err(Problem::invalid(format!(
                "pages: the atlas's page {} is missing: give every page's image, or none",
                Quoted(name)
            )));
        };
        let png = base64::engine::general_purpose::STANDARD
            .decode(b64)
            .map_err(|e| Problem::invalid(format!("pages.{}: not base64: {e}", Quoted(name))))?;
        let [w, h] =
            png_size(&png).ok_or_else(|| Problem::invalid(format!("pages.{}: not a PNG image", Quoted(name))))?;
        if w == 0 || h == 0 || w > MAX_PAGE_SIDE || h > MAX_PAGE_SIDE {
            return Err(Problem::invalid(format!(
                "pages.{}: {w}×{h} pixels; a page's sides must be between 1 and {MAX_PAGE_SIDE} pixels",
                Quoted(name)
            )));
        }
        pixels += u64::from(w) * u64::from(h);
        if pixels > MAX_ATLAS_PIXELS {
            return Err(Problem::invalid(format!(
                "pages: more than {MAX_ATLAS_PIXELS} pixels of page images in one atlas (at page {})",
                Quoted(name)
            )));
        }
        bytes.insert(*name, png);
    }
    let mut parts: Vec<&[u8]> = vec![text.as_bytes()];
    for (name, png) in &bytes {
        parts.push(name.as_bytes());
        parts.push(png);
    }
    let id = hashed('a', &parts);
    let mut image = |file: &str| bytes.get(file).cloned().ok_or_else(|| Error::input("not given"));
    let art = AtlasArt::read(text, "atlas", &mut image).map_err(Problem::from)?;
    Ok((id.clone(), kept().keep(id, KeptAtlas { art, images: true, text_bytes: text.len() })))
}

/// A PNG's width and height from its header (the `IHDR` chunk that must come first), or `None`
/// for bytes that are not a PNG.
fn png_size(png: &[u8]) -> Option<[u32; 2]> {
    const SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
    if png.len() < 24 || &png[..8] != SIGNATURE || &png[12..16] != b"IHDR" {
        return None;
    }
    let at = |i: usize| u32::from_be_bytes([png[i], png[i + 1], png[i + 2], png[i + 3]]);
    Some([at(16), at(20)])
}

/// The atlas `/api/atlas/parse` answered `id` for; a 404 naming `atlas` when it is not kept.
pub fn stored_atlas(id: &str) -> Result<Arc<KeptAtlas>, Problem> {
    kept().get(id).ok_or_else(|| {
        Problem::new(
            status::NOT_FOUND,
            format!(
                "atlas: no atlas {id:?} on the server (never read, or let go for newer ones): send it to /api/atlas/parse again"
            ),
        )
    })
}

/// Refuses, in one line, `art_only` without an atlas and an atlas sent without its page images
/// (a picture needs them): what a picture with a character's art asks of its `atlas`.
#[cfg(feature = "render")]
pub(super) fn drawable(atlas: Option<&KeptAtlas>, art_only: bool) -> Result<(), Problem> {
    if art_only && atlas.is_none() {
        return Err(Problem::invalid(
            "art_only: draws a character's art: give its atlas (\"atlas\": the id /api/atlas/parse answered)",
        ));
    }
    if let Some(atlas) = atlas.filter(|a| !a.images) {
        let pages: Vec<&str> = atlas.art.atlas.pages.iter().map(|p| p.file.as_str()).collect();
        return Err(Problem::invalid(format!(
            "atlas: sent without its page images ({}): send them to /api/atlas/parse as \"pages\" to draw the art",
            pages.join(", ")
        )));
    }
    Ok(())
}

#[cfg(test)]
#[path = "atlases_tests.rs"]
mod tests;
