//! A pose's drawing as JSON (`/api/pose`'s `"art"`, with `"atlas": ID`): what a page that holds
//! the atlas's images needs to draw the character itself, slot by slot in draw order. The
//! numbers are the library's ([`Character::draw_list_at`]): world vertices (y up, as the bones'),
//! page UVs (0 to 1, v down), triangles, the tint (slot colour × attachment colour, straight),
//! the dark colour of two-colour tinting, the blend mode.

use ikarus::character::{AtlasRegion, BlendMode, Character, DrawItem, DrawList, Regions};
use serde::Serialize;

use super::atlas::Atlas;
use crate::error::Error;
use crate::names::Quoted;

/// The pose's drawing.
#[derive(Debug, Clone, Serialize)]
pub struct ArtJson {
    /// The atlas's page image files, as `page` numbers them.
    pub pages: Vec<String>,
    /// The slots drawn, first drawn first.
    pub slots: Vec<SlotArtJson>,
}

/// One drawn slot.
#[derive(Debug, Clone, Serialize)]
pub struct SlotArtJson {
    /// The slot's name.
    pub slot: String,
    /// The attachment it shows.
    pub attachment: String,
    /// Its region's page (index into [`ArtJson::pages`]).
    pub page: usize,
    /// `normal`, `additive`, `multiply` or `screen`.
    pub blend: &'static str,
    /// Slot colour × attachment colour, straight RGBA 0 to 1.
    pub color: [f64; 4],
    /// The dark colour of two-colour tinting, if the slot has one.
    pub dark: Option<[f64; 3]>,
    /// World positions, `x0, y0, x1, y1, …`.
    pub vertices: Vec<f64>,
    /// Page coordinates, `u0, v0, …` (0 to 1, v down).
    pub uvs: Vec<f64>,
    /// Triangles, three indices each into this slot's vertices.
    pub triangles: Vec<u32>,
}

/// The name of a blend mode in the JSON (and in Spine's).
#[must_use]
pub fn blend_name(mode: BlendMode) -> &'static str {
    match mode {
        BlendMode::Normal => "normal",
        BlendMode::Additive => "additive",
        BlendMode::Multiply => "multiply",
        BlendMode::Screen => "screen",
    }
}

/// The atlas region `item` draws, or the refusal naming the region and the slot when the atlas
/// lacks it (as Spine's runtimes refuse a skeleton whose atlas lacks a region it names).
///
/// # Errors
/// `the atlas has no region "x" (slot "y"'s attachment): …`.
pub fn region_of<'r>(
    c: &Character,
    list: &DrawList,
    item: &DrawItem,
    regions: &'r Regions,
) -> Result<&'r AtlasRegion, Error> {
    item.region.and_then(|r| regions.get(r)).ok_or_else(|| {
        Error::input({
            let slot = &c.art().slots[item.slot].name;
            let name = c.shown_attachment(&list.slots, item.slot).unwrap_or("?");
            format!(
                "the atlas has no region {} (slot {}'s attachment): give the atlas exported with this skeleton",
                Quoted(name),
                Quoted(slot)
            )
        })
    })
}

impl ArtJson {
    /// The drawing `list` (drawn from `c` with `atlas`'s regions `regions`) as JSON.
    ///
    /// # Errors
    /// [`region_of`]'s, for the first slot whose region the atlas lacks.
    pub fn of(c: &Character, list: &DrawList, atlas: &Atlas, regions: &Regions) -> Result<Self, Error> {
        let flat = |points: &[[f64; 2]]| points.iter().flatten().copied().collect::<Vec<f64>>();
        let slots = list
            .items
            .iter()
            .map(|item| {
                let region = region_of(c, list, item, regions)?;
                Ok(SlotArtJson {
                    slot: c.art().slots[item.slot].name.clone(),
                    attachment: c.shown_attachment(&list.slots, item.slot).unwrap_or_default().to_owned(),
                    page: region.page,
                    blend: blend_name(item.blend),
                    color: item.color,
                    dark: item.dark,
                    vertices: flat(&list.vertices[item.vertices.clone()]),
                    uvs: flat(&list.uvs[item.vertices.clone()]),
                    triangles: list.triangles[item.triangles.clone()].to_vec(),
                })
            })
            .collect::<Result<Vec<_>, Error>>()?;
        Ok(Self { pages: atlas.pages.iter().map(|p| p.file.clone()).collect(), slots })
    }
}
