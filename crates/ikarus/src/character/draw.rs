//! What a pose draws: per slot in draw order, its attachment's world vertices, page UVs,
//! triangles, colour and blend mode ([`Character::draw_list`]). No pixels here.
//!
//! Rules (Spine's JSON export format, "Slots", "Skins", "Region attachments", "Mesh
//! attachments"; its atlas format for the regions):
//! - Slots are drawn in the draw order (the setup order, or the clip's draw order key in force);
//!   a slot is skipped when its bone is inactive (the skin does not turn it on) or it shows no
//!   attachment, or its attachment is not a region or a mesh. The attachment's name is the
//!   slot's setup `attachment` or the clip's attachment key in force, looked up in the chosen
//!   skin first, then in the skin called `default`.
//! - A region: the quad `width × height` centred on `(x, y)`, scaled by `scaleX`, `scaleY`,
//!   rotated by `rotation`, in the slot bone's frame, then through the bone's world transform.
//!   With whitespace stripped (atlas `offsets`), the quad shrinks to the packed image's part of
//!   the original: `left = −width/2 + offsetX·width/originalWidth`, `bottom = −height/2 +
//!   offsetY·height/originalHeight`, spanning `packedWidth·width/originalWidth` by
//!   `packedHeight·height/originalHeight`. Corners in the order bottom-left, top-left, top-right,
//!   bottom-right; triangles `0 1 2`, `2 3 0`.
//! - A mesh: unweighted vertices go through the slot bone's world transform; a weighted vertex
//!   is `Σ weight · (bone's world transform applied to (x, y))`. Its UVs are in the original
//!   image, mapped onto the packed image and the page. A deform timeline's offsets are added to
//!   the vertex coordinates first (per weight entry of a weighted mesh).
//! - Colour: the slot's (setup, or the clip's colour keys) times the attachment's, channel by
//!   channel; the dark colour is the slot's.
//! - A clipping attachment draws nothing; its polygon (its vertices as a mesh's, deform
//!   included) cuts the triangles of the slots it clips (the `clipping` module's rules). A slot
//!   whose triangles are all cut away is not drawn.
//!
//! The slots' state at the clip's time ([`SlotPose`], the `slot_pose` module) is computed here,
//! not when the bones are posed, so a pose drawn without its art costs nothing more.

use std::ops::Range;

use super::art::{AtlasRegion, Attachment, BlendMode, MeshAttachment, RegionAttachment, Regions, Rgba};
use super::clipping::Clipper;
use super::path::spline::extend_world;
use super::slot_pose::SlotPose;
use super::{Affine, Character, PoseError, Posed};

/// One slot's drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawItem {
    /// The slot's index (in [`Character::art`]'s slots).
    pub slot: usize,
    /// The atlas region's index in the [`Regions`] given, `None` when the atlas has no region of
    /// that name (the UVs are then the attachment's own, 0 to 1 over its image).
    pub region: Option<usize>,
    /// Its vertices' range in [`DrawList::vertices`] and [`DrawList::uvs`].
    pub vertices: Range<usize>,
    /// Its triangles' range in [`DrawList::triangles`] (indices relative to its first vertex).
    pub triangles: Range<usize>,
    /// Slot colour times attachment colour, straight RGBA 0 to 1.
    pub color: Rgba,
    /// The slot's dark colour, if any.
    pub dark: Option<[f64; 3]>,
    /// How it is blended.
    pub blend: BlendMode,
}

/// The drawing of a pose, reused from frame to frame (its buffers keep their capacity).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrawList {
    /// The slots drawn, first drawn first.
    pub items: Vec<DrawItem>,
    /// World positions of every item's vertices.
    pub vertices: Vec<[f64; 2]>,
    /// Page coordinates (0 to 1, v down) of every item's vertices.
    pub uvs: Vec<[f64; 2]>,
    /// Triangle indices, three per triangle, relative to their item's first vertex.
    pub triangles: Vec<u32>,
    /// The slots' state the list was drawn with (attachments, colours, draw order, deforms).
    pub slots: SlotPose,
    /// The clipping polygon in force while drawing, and its scratch buffers.
    clipper: Clipper,
}

impl DrawList {
    /// Empties the list, keeping its buffers.
    pub fn clear(&mut self) {
        self.items.clear();
        self.vertices.clear();
        self.uvs.clear();
        self.triangles.clear();
    }
}

/// A region's two triangles over corners bottom-left, top-left, top-right, bottom-right.
const QUAD: [u32; 6] = [0, 1, 2, 2, 3, 0];

impl Character {
    /// The attachment slot `slot` shows in the setup pose with skin `skin`: looked up in that
    /// skin, then in the skin called `default`.
    pub fn setup_attachment(&self, slot: usize, skin: Option<usize>) -> Option<&Attachment> {
        let name = self.art.slots.get(slot)?.attachment.as_deref()?;
        let find = |k: usize| self.art.skins.get(k).and_then(|s| s.get(slot, name));
        skin.and_then(find).or_else(|| self.default_skin().and_then(find))
    }

    /// What pose `posed` draws with skin `skin` (the skin it was posed with) in the setup
    /// slot state, the images placed by `regions`, into `out` (cleared first). See the module's
    /// doc for the rules.
    pub fn draw_list(&self, posed: &Posed, skin: Option<usize>, regions: &Regions, out: &mut DrawList) {
        out.clear();
        self.slot_pose(None, skin, &mut out.slots);
        self.draw_slots(posed, skin, regions, out);
    }

    /// What pose `posed` draws with skin `skin`, the slots as clip `clip` sets them at its time
    /// (`(clip, seconds)`, as the pose was asked; `None`: the setup slots): the attachment,
    /// colour, draw order and deform timelines. The images are placed by `regions`; `out` is
    /// cleared first and allocates nothing once it has grown. `Err` for a clip the character
    /// does not have or a time that is not finite.
    pub fn draw_list_at(
        &self,
        posed: &Posed,
        skin: Option<usize>,
        clip: Option<(usize, f64)>,
        regions: &Regions,
        out: &mut DrawList,
    ) -> Result<(), PoseError> {
        if let Some((c, time)) = clip {
            if c >= self.clips().len() {
                return Err(PoseError::UnknownClip(c));
            }
            if !time.is_finite() {
                return Err(PoseError::Time(time));
            }
        }
        out.clear();
        self.slot_pose(clip, skin, &mut out.slots);
        self.draw_slots(posed, skin, regions, out);
        Ok(())
    }

    /// The drawing of every slot in `out.slots`' order and state.
    fn draw_slots(&self, posed: &Posed, skin: Option<usize>, regions: &Regions, out: &mut DrawList) {
        out.clipper.reset();
        for k in 0..out.slots.order().len() {
            let i = out.slots.order()[k];
            self.draw_slot(posed, skin, regions, i, out);
            out.clipper.passed(i);
        }
        out.clipper.reset();
    }

    /// The drawing of slot `i`, cut to the clipping polygon in force; a clipping attachment
    /// starts clipping.
    fn draw_slot(&self, posed: &Posed, skin: Option<usize>, regions: &Regions, i: usize, out: &mut DrawList) {
        let Some(slot) = self.art.slots.get(i) else { return };
        if slot.bone >= posed.len() || !posed.is_active(slot.bone) {
            return;
        }
        let name = self.shown_attachment(&out.slots, i);
        let Some((_, attachment)) = name.and_then(|name| self.find_attachment(i, name, skin)) else { return };
        let (path, color) = match attachment {
            Attachment::Region(r) => (&r.path, r.color),
            Attachment::Mesh(m) => (&m.path, m.color),
            Attachment::Clipping(c) => {
                if !out.clipper.active() {
                    let bone = posed.world(slot.bone);
                    let world = |b: usize| posed.world(b);
                    out.clipper.polygon.clear();
                    extend_world(&c.vertices, &bone, &world, out.slots.deform(i), &mut out.clipper.polygon);
                    out.clipper.start(i, c.end);
                }
                return;
            }
            Attachment::NotDrawn => return,
        };
        let region = regions.index(path);
        let geometry = region.and_then(|r| regions.get(r));
        let start = out.vertices.len();
        let first = out.triangles.len();
        match attachment {
            Attachment::Region(r) => {
                region_vertices(r, geometry, posed.world(slot.bone), out);
                out.triangles.extend_from_slice(&QUAD);
            }
            Attachment::Mesh(m) => {
                let bone = posed.world(slot.bone);
                let world = |b: usize| posed.world(b);
                extend_world(&m.vertices, &bone, &world, out.slots.deform(i), &mut out.vertices);
                mesh_uvs(m, geometry, out);
                out.triangles.extend_from_slice(&m.triangles);
            }
            Attachment::Clipping(_) | Attachment::NotDrawn => {}
        }
        if out.clipper.active() {
            out.clipper.clip(&out.vertices[start..], &out.uvs[start..], &out.triangles[first..]);
            out.vertices.truncate(start);
            out.uvs.truncate(start);
            out.triangles.truncate(first);
            if out.clipper.triangles.is_empty() {
                return;
            }
            out.vertices.extend_from_slice(&out.clipper.vertices);
            out.uvs.extend_from_slice(&out.clipper.uvs);
            out.triangles.extend_from_slice(&out.clipper.triangles);
        }
        let slot_color = out.slots.color(i);
        let color = std::array::from_fn(|c| slot_color[c] * color[c]);
        out.items.push(DrawItem {
            slot: i,
            region,
            vertices: start..out.vertices.len(),
            triangles: first..out.triangles.len(),
            color,
            dark: out.slots.dark(i),
            blend: slot.blend,
        });
    }
}

/// `m` applied to `p`.
fn apply(m: &Affine, p: [f64; 2]) -> [f64; 2] {
    [m.a * p[0] + m.b * p[1] + m.x, m.c * p[0] + m.d * p[1] + m.y]
}

/// A region's four corners in the world and on the page.
fn region_vertices(r: &RegionAttachment, geometry: Option<&AtlasRegion>, bone: Affine, out: &mut DrawList) {
    // The packed image's part of the original, in the attachment's units from its centre.
    let (left, bottom, right, top) = match geometry {
        Some(g) => {
            let sx = r.width / g.original[0];
            let sy = r.height / g.original[1];
            let left = -r.width / 2.0 + g.offsets[0] * sx;
            let bottom = -r.height / 2.0 + g.offsets[1] * sy;
            (left, bottom, left + g.bounds[2] * sx, bottom + g.bounds[3] * sy)
        }
        None => (-r.width / 2.0, -r.height / 2.0, r.width / 2.0, r.height / 2.0),
    };
    let (sin, cos) = crate::math::sin_cos(r.rotation);
    let local = |x: f64, y: f64| {
        let (x, y) = (x * r.scale_x, y * r.scale_y);
        [cos * x - sin * y + r.x, sin * x + cos * y + r.y]
    };
    let corners = [local(left, bottom), local(left, top), local(right, top), local(right, bottom)];
    out.vertices.extend(corners.iter().map(|&p| apply(&bone, p)));
    match geometry {
        Some(g) => {
            let [w, h] = [g.bounds[2], g.bounds[3]];
            let packed = [[0.0, h], [0.0, 0.0], [w, 0.0], [w, h]];
            out.uvs.extend(packed.iter().map(|&q| g.page_uv(q)));
        }
        None => out.uvs.extend_from_slice(&[[0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),
    }
}

/// A mesh's vertices on the page.
fn mesh_uvs(m: &MeshAttachment, geometry: Option<&AtlasRegion>, out: &mut DrawList) {
    match geometry {
        Some(g) => out.uvs.extend(m.uvs.iter().map(|&uv| g.page_uv(g.packed(uv)))),
        None => out.uvs.extend_from_slice(&m.uvs),
    }
}

#[cfg(test)]
#[path = "draw_tests.rs"]
mod tests;
