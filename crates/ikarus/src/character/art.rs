//! What a character draws: its slots (the draw order), the skins' region and mesh attachments,
//! and the atlas regions their images come from. The world vertices, UVs and colours of a pose
//! are computed by [`super::Character::draw_list`] (the `draw` module); pixels are the
//! renderer's business.
//!
//! Terms and fields follow Spine's JSON export format (its "Slots" and "Skins" sections) and its
//! texture atlas format. Colours are straight (not premultiplied) RGBA, each channel 0 to 1.

use std::collections::HashMap;

use super::{CharacterError, PathVertices};
use crate::listed_enum;

/// A straight RGBA colour, each channel 0 to 1.
pub type Rgba = [f64; 4];

/// Opaque white, the colour of a slot or an attachment that names none.
pub const WHITE: Rgba = [1.0, 1.0, 1.0, 1.0];

listed_enum! {
    /// How a slot's attachment is blended onto what is drawn below it (Spine's `blend`).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
    pub enum BlendMode {
        /// Source over (the default).
        #[default]
        Normal,
        /// Added to what is below.
        Additive,
        /// Multiplied with what is below.
        Multiply,
        /// One minus the product of the inverses.
        Screen,
    }
}

impl BlendMode {
    /// Spine's name of the mode (`normal`, `additive`, `multiply`, `screen`).
    pub fn as_str(self) -> &'static str {
        match self {
            BlendMode::Normal => "normal",
            BlendMode::Additive => "additive",
            BlendMode::Multiply => "multiply",
            BlendMode::Screen => "screen",
        }
    }

    /// The mode Spine calls `name`.
    pub fn from_name(name: &str) -> Option<BlendMode> {
        BlendMode::ALL.into_iter().find(|m| m.as_str() == name)
    }
}

/// A slot: a place in the draw order on a bone, showing at most one attachment at a time.
#[derive(Debug, Clone, PartialEq)]
pub struct Slot {
    /// Its name in the file.
    pub name: String,
    /// Its bone's index.
    pub bone: usize,
    /// Its colour (`color`, white unless given); the attachment's is multiplied by it.
    pub color: Rgba,
    /// Its dark colour for two-colour tinting (`dark`, RGB), if any.
    pub dark: Option<[f64; 3]>,
    /// How it is blended.
    pub blend: BlendMode,
    /// The setup pose's attachment's name, if any.
    pub attachment: Option<String>,
}

/// A region attachment: one image, a quad placed on the slot's bone.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionAttachment {
    /// The atlas region's name (`path`, else the attachment's name).
    pub path: String,
    /// The quad's centre in the bone's frame.
    pub x: f64,
    /// The quad's centre in the bone's frame.
    pub y: f64,
    /// Its rotation in the bone's frame, radians counter-clockwise.
    pub rotation: f64,
    /// Its scale along its own x axis.
    pub scale_x: f64,
    /// Its scale along its own y axis.
    pub scale_y: f64,
    /// The image's width in the skeleton's units (before scaling).
    pub width: f64,
    /// The image's height in the skeleton's units (before scaling).
    pub height: f64,
    /// Its colour (white unless given).
    pub color: Rgba,
}

/// A mesh attachment: an image drawn as triangles whose vertices follow one bone or several.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshAttachment {
    /// The atlas region's name (`path`, else the attachment's name).
    pub path: String,
    /// Per vertex, its texture coordinates in the original image, 0 to 1, v downward.
    pub uvs: Vec<[f64; 2]>,
    /// Vertex indices, three per triangle.
    pub triangles: Vec<u32>,
    /// The vertices: in the slot bone's frame, or weighted over several bones.
    pub vertices: PathVertices,
    /// How many vertices (the first ones) make the hull.
    pub hull: usize,
    /// The image's width in the skeleton's units (the editor's; drawing does not use it).
    pub width: f64,
    /// The image's height in the skeleton's units (the editor's; drawing does not use it).
    pub height: f64,
    /// Its colour (white unless given).
    pub color: Rgba,
}

/// A clipping attachment: a polygon that clips the region and mesh attachments of the slots
/// from its own to its end slot in the draw order (see the `clipping` module's rules).
#[derive(Debug, Clone, PartialEq)]
pub struct ClippingAttachment {
    /// The slot at which clipping ends, inclusive (its own slot: the end of the draw order).
    pub end: usize,
    /// The polygon's vertices: in the slot bone's frame, or weighted over several bones.
    pub vertices: PathVertices,
}

/// An attachment as drawing sees it.
#[derive(Debug, Clone, PartialEq)]
pub enum Attachment {
    /// A region (a quad).
    Region(RegionAttachment),
    /// A mesh (a linked mesh is read as a mesh with its parent's geometry).
    Mesh(MeshAttachment),
    /// A clipping polygon: not drawn, it clips what is drawn after it.
    Clipping(ClippingAttachment),
    /// An attachment that is not drawn (path, point, bounding box): it still hides a default
    /// skin's attachment of the same name.
    NotDrawn,
}

/// One skin's attachments: per slot, by attachment name.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkinArt {
    /// Indexed by slot; each map from attachment name to attachment.
    pub slots: Vec<HashMap<String, Attachment>>,
}

impl SkinArt {
    /// Slot `slot`'s attachment called `name`, if this skin has it.
    pub fn get(&self, slot: usize, name: &str) -> Option<&Attachment> {
        self.slots.get(slot).and_then(|m| m.get(name))
    }
}

/// A character's art: its slots in the setup draw order and each skin's attachments (indexed as
/// [`super::Character::skins`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Art {
    /// The slots, in the setup pose's draw order (first drawn first).
    pub slots: Vec<Slot>,
    /// Per skin (as [`super::Character::skins`] lists them), its attachments.
    pub skins: Vec<SkinArt>,
    /// Per clip (as [`super::Character::clips`] lists them; fewer: the rest have none), its
    /// slot timelines.
    pub clips: Vec<super::SlotClip>,
}

impl Art {
    /// Checks the art against a character of `bones` bones and `skins` skins: every slot's bone
    /// and every weight's bone exists, each skin's attachments are indexed by existing slots,
    /// numbers are finite, a mesh has one UV per vertex and whole triangles of existing
    /// vertices, and its hull is not larger than it; a clipping polygon has 3 to
    /// [`super::MAX_CLIP_VERTICES`] vertices and ends at an existing slot; the slot timelines
    /// of at most `clips` clips follow [`super::slot_clip`]'s rules.
    pub(crate) fn check(&self, bones: usize, skins: usize, clips: usize) -> Result<(), CharacterError> {
        let bad = |what: String| Err(CharacterError::Art { what });
        if self.skins.len() > skins {
            return bad(format!("{} skins of attachments for {skins} skins", self.skins.len()));
        }
        for (i, s) in self.slots.iter().enumerate() {
            if s.bone >= bones {
                return bad(format!("slots[{i}].bone: {} is not a bone", s.bone));
            }
            if s.color.iter().chain(s.dark.iter().flatten()).any(|c| !(0.0..=1.0).contains(c)) {
                return bad(format!("slots[{i}].color: channels must be within 0 to 1"));
            }
        }
        for (k, skin) in self.skins.iter().enumerate() {
            if skin.slots.len() > self.slots.len() {
                return bad(format!("skins[{k}]: attachments for {} slots of {}", skin.slots.len(), self.slots.len()));
            }
            for (slot, map) in skin.slots.iter().enumerate() {
                for (name, a) in map {
                    check_attachment(a, bones, self.slots.len()).map_err(|e| CharacterError::Art {
                        what: format!("skins[{k}], slot {slot}, attachment {name:?}: {e}"),
                    })?;
                }
            }
        }
        super::slot_clip::check(&self.clips, self.slots.len(), skins, clips)
    }
}

/// Whether every vertex is finite and every weight's bone exists.
fn finite(vertices: &PathVertices, bones: usize) -> bool {
    match vertices {
        PathVertices::Plain(v) => v.iter().flatten().all(|x| x.is_finite()),
        PathVertices::Weighted(v) => {
            v.iter().flatten().all(|w| w.bone < bones && w.point.iter().all(|x| x.is_finite()) && w.weight.is_finite())
        }
    }
}

/// One attachment's rules (see [`Art::check`]).
fn check_attachment(a: &Attachment, bones: usize, slots: usize) -> Result<(), String> {
    match a {
        Attachment::NotDrawn => Ok(()),
        Attachment::Clipping(c) => {
            let n = c.vertices.len();
            if !(3..=super::MAX_CLIP_VERTICES).contains(&n) {
                return Err(format!("a clipping polygon of {n} vertices (3 to {})", super::MAX_CLIP_VERTICES));
            }
            if c.end >= slots {
                return Err(format!("end slot {}: only {slots} slots", c.end));
            }
            if !finite(&c.vertices, bones) {
                return Err("a vertex is not finite, or a weight's bone does not exist".into());
            }
            Ok(())
        }
        Attachment::Region(r) => {
            let numbers = [r.x, r.y, r.rotation, r.scale_x, r.scale_y, r.width, r.height];
            if numbers.iter().any(|v| !v.is_finite()) {
                return Err("a number is not finite".into());
            }
            Ok(())
        }
        Attachment::Mesh(m) => {
            let n = m.vertices.len();
            if m.uvs.len() != n {
                return Err(format!("{} uvs for {n} vertices", m.uvs.len()));
            }
            if m.triangles.len() % 3 != 0 {
                return Err(format!("{} triangle indices: not a multiple of 3", m.triangles.len()));
            }
            if let Some(t) = m.triangles.iter().find(|&&t| t as usize >= n) {
                return Err(format!("triangle index {t}: only {n} vertices"));
            }
            if m.hull > n {
                return Err(format!("hull {}: only {n} vertices", m.hull));
            }
            if !finite(&m.vertices, bones) || m.uvs.iter().flatten().any(|x| !x.is_finite()) {
                return Err("a vertex or uv is not finite, or a weight's bone does not exist".into());
            }
            Ok(())
        }
    }
}

/// Where an atlas region's image lies on its page, as Spine's atlas format gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct AtlasRegion {
    /// Its name (an attachment's `path`).
    pub name: String,
    /// Its page's index in the atlas.
    pub page: usize,
    /// The page's size in pixels.
    pub page_size: [f64; 2],
    /// `x, y, width, height` in pixels, y down from the page's top-left: the packed image's
    /// place, its width and height as the image stands (before the rotation on the page).
    pub bounds: [f64; 4],
    /// Pixels of whitespace stripped from the original image's left and bottom edges.
    pub offsets: [f64; 2],
    /// The original image's width and height in pixels, whitespace included.
    pub original: [f64; 2],
    /// How far the image is rotated on the page, counter-clockwise: 0, 90, 180 or 270.
    pub degrees: u16,
    /// Whether its page's colours are premultiplied by alpha.
    pub pma: bool,
}

impl AtlasRegion {
    /// Page coordinates (0 to 1, v down) of point `q` of the packed image, in pixels from its
    /// top-left corner, y down, as the image stands. Rotated images: at 90° the image's top
    /// edge runs up the left side of its place on the page (found on the shipped atlases: every
    /// mesh's triangles then fall on opaque pixels); 180° and 270° continue the same turn.
    pub fn page_uv(&self, q: [f64; 2]) -> [f64; 2] {
        let [x, y, w, h] = self.bounds;
        let [qx, qy] = q;
        let (px, py) = match self.degrees {
            90 => (x + qy, y + w - qx),
            180 => (x + w - qx, y + h - qy),
            270 => (x + h - qy, y + qx),
            _ => (x + qx, y + qy),
        };
        [px / self.page_size[0], py / self.page_size[1]]
    }

    /// The packed image's pixel (from its top-left, y down) of a point of the original image
    /// given as 0-to-1 coordinates, v down (a mesh's UV).
    pub fn packed(&self, uv: [f64; 2]) -> [f64; 2] {
        let [ow, oh] = self.original;
        let top = oh - self.offsets[1] - self.bounds[3];
        [uv[0] * ow - self.offsets[0], uv[1] * oh - top]
    }
}

/// An atlas's regions, found by name: what [`super::Character::draw_list`] takes the images'
/// places from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Regions {
    regions: Vec<AtlasRegion>,
    by_name: HashMap<String, usize>,
}

impl Regions {
    /// The regions, found by name (a name listed twice, as a sequence's frames are, finds the
    /// first).
    pub fn new(regions: Vec<AtlasRegion>) -> Regions {
        let mut by_name = HashMap::new();
        for (i, r) in regions.iter().enumerate() {
            by_name.entry(r.name.clone()).or_insert(i);
        }
        Regions { regions, by_name }
    }

    /// Every region, as listed.
    pub fn all(&self) -> &[AtlasRegion] {
        &self.regions
    }

    /// The index of the region called `name`.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.by_name.get(name).copied()
    }

    /// Region `i`.
    pub fn get(&self, i: usize) -> Option<&AtlasRegion> {
        self.regions.get(i)
    }
}
