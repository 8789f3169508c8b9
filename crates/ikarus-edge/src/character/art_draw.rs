//! A character's art made ready for the renderer: an atlas read with its page images decoded
//! ([`AtlasArt`]), and a pose's [`DrawList`] turned into [`ikarus_render::Art`] pieces
//! ([`AtlasArt::art`]). One place for every edge: the command line reads the pages beside the
//! atlas file ([`AtlasArt::read_file`]); the server, Python and WebAssembly hand the bytes in
//! ([`AtlasArt::read`]).
//!
//! Rules:
//! - A page's image is the file the atlas names for it (its first line), in the atlas file's
//!   folder; its colours are premultiplied when the page says `pma: true`.
//! - An attachment the pose draws whose region (its `path`, else its name) is not in the atlas is
//!   refused, as Spine's runtimes refuse a skeleton whose atlas lacks a region it names; the
//!   refusal names the region and the slot.
//! - Each drawn slot is one piece: its vertices and UVs as the library computed them (as
//!   `f32`), its triangles, its tint (slot colour × attachment colour), dark colour and blend.

use std::path::Path;

use ikarus::character::{BlendMode, Character, DrawList, Posed, Regions};
use ikarus_render::{Art, ArtPiece, Blend, Page};

use super::atlas::{self, Atlas};
use crate::error::Error;
use crate::names::Quoted;

/// An atlas with its pages' images decoded: what drawing a character's art takes.
#[derive(Debug, Clone)]
pub struct AtlasArt {
    /// The atlas as read.
    pub atlas: Atlas,
    /// Its regions, found by name.
    pub regions: Regions,
    /// Its pages' images, as the atlas lists the pages.
    pub pages: Vec<Page>,
}

impl AtlasArt {
    /// Reads the atlas `text` (errors start with `label`) and decodes each page's image, whose
    /// bytes `image` gives for the file name the atlas names (`Err` says why there are none:
    /// it is put after the page's name).
    ///
    /// # Errors
    /// One line: a bad atlas line, a page whose image cannot be had or is not a PNG image.
    pub fn read(text: &str, label: &str, image: &mut dyn FnMut(&str) -> Result<Vec<u8>, Error>) -> Result<Self, Error> {
        let atlas = atlas::read(text).map_err(|e| Error::input(format!("{label}: {e}")))?;
        let mut pages = Vec::with_capacity(atlas.pages.len());
        for (i, page) in atlas.pages.iter().enumerate() {
            let bytes = image(&page.file)
                .map_err(|e| Error::input(format!("{label}: page {i} {}: {e}", Quoted(&page.file))))?;
            let decoded = Page::decode_png(&bytes, &page.file, page.pma)
                .map_err(|e| Error::input(format!("{label}: page {i} {e}")))?;
            pages.push(decoded);
        }
        let regions = atlas.lookup();
        Ok(Self { atlas, regions, pages })
    }

    /// [`AtlasArt::read`] of the atlas file at `path`, the pages' images read from its folder.
    ///
    /// # Errors
    /// An input error in one line: the atlas cannot be read (`atlas file x.atlas: cannot read:
    /// No such file or directory`), a page's image is not in the folder (naming the page and
    /// the folder), or [`AtlasArt::read`]'s.
    pub fn read_file(path: &Path) -> Result<Self, Error> {
        let label = format!("atlas file {}", path.display());
        let text = crate::input::read_text(path, &label)?;
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let mut image = |file: &str| {
            let at = folder.join(file);
            if !at.is_file() {
                return Err(Error::input(format!("no such image in {}", folder.display())));
            }
            crate::input::read(&at, &at.display().to_string()).map_err(|e| Error::input(e.to_string()))
        };
        Self::read(&text, &label, &mut image)
    }

    /// The art pose `posed` of `c` draws with skin `skin` (the skin it was posed with) and the
    /// slots as clip `clip` keys them at its time (the clip it was posed with: its attachment,
    /// colour, draw-order and deform keys), its vertices computed into `list` (reused): the
    /// pages (borrowed, never copied) and one piece per drawn slot.
    ///
    /// # Errors
    /// One line naming the region and the slot when the atlas lacks a region the pose draws, or
    /// an attachment has more vertices than a piece holds (65 536); a clip the character does
    /// not have or a time that is not finite.
    pub fn art(
        &self,
        c: &Character,
        posed: &Posed,
        (skin, clip): (Option<usize>, Option<(usize, f64)>),
        list: &mut DrawList,
    ) -> Result<Art<'_>, Error> {
        c.draw_list_at(posed, skin, clip, &self.regions, list).map_err(|e| Error::input(e.to_string()))?;
        let mut pieces = Vec::with_capacity(list.items.len());
        for item in &list.items {
            let slot = &c.art().slots[item.slot];
            let Some(region) = item.region.and_then(|r| self.regions.get(r)) else {
                let name = c.setup_attachment(item.slot, skin).map_or("?", attachment_path);
                return Err(Error::input(format!(
                    "the atlas has no region {} (slot {}'s attachment): give the atlas exported with this skeleton",
                    Quoted(name),
                    Quoted(&slot.name)
                )));
            };
            let vertices = &list.vertices[item.vertices.clone()];
            if vertices.len() > usize::from(u16::MAX) + 1 {
                return Err(Error::input(format!(
                    "slot {}: {} vertices, more than a piece holds (65536)",
                    Quoted(&slot.name),
                    vertices.len()
                )));
            }
            let to32 = |p: &[f64; 2]| [p[0] as f32, p[1] as f32];
            let triangles = list.triangles[item.triangles.clone()]
                .chunks_exact(3)
                .map(|t| [t[0] as u16, t[1] as u16, t[2] as u16])
                .collect();
            pieces.push(ArtPiece {
                page: region.page,
                positions: vertices.iter().map(to32).collect(),
                uvs: list.uvs[item.vertices.clone()].iter().map(to32).collect(),
                triangles,
                color: item.color.map(|v| v as f32),
                dark: item.dark.map(|d| d.map(|v| v as f32)),
                blend: blend(item.blend),
            });
        }
        Ok(Art { pages: &self.pages, pieces })
    }
}

/// The renderer's blend of a slot's blend mode.
fn blend(mode: BlendMode) -> Blend {
    match mode {
        BlendMode::Normal => Blend::Normal,
        BlendMode::Additive => Blend::Additive,
        BlendMode::Multiply => Blend::Multiply,
        BlendMode::Screen => Blend::Screen,
    }
}

/// The region name an attachment draws (`?` for one not drawn).
fn attachment_path(a: &ikarus::character::Attachment) -> &str {
    match a {
        ikarus::character::Attachment::Region(r) => &r.path,
        ikarus::character::Attachment::Mesh(m) => &m.path,
        ikarus::character::Attachment::Clipping(_) | ikarus::character::Attachment::NotDrawn => "?",
    }
}
