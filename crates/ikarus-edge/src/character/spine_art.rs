//! Spine's art as drawing needs it: the slots' colours and blend modes and the skins' region,
//! mesh and linked mesh attachments, into [`ikarus::character::Art`].
//!
//! Fields and defaults (Spine's JSON export format, "Slots" and "Skins"):
//! - `slots[]`: `color` (`RRGGBBAA` hex, white), `dark` (`RRGGBB`, none), `blend` (`normal`,
//!   `additive`, `multiply`, `screen`; normal), `attachment` (none).
//! - an attachment's `type` is `region` unless given. `region`: `path` (the attachment's name),
//!   `x`, `y`, `rotation` (degrees), `scaleX`, `scaleY` (1), `width`, `height` (32), `color`
//!   (white). `mesh`: `path`, `uvs`, `triangles`, `vertices` (unweighted `x, y` pairs in the slot
//!   bone's frame when there are as many numbers as UVs, else per vertex a bone count then
//!   `bone, x, y, weight` per bone), `hull` (0), `width`, `height` (32), `color`. `linkedmesh`:
//!   `path`, `color`, `width`, `height`, `parent` (a mesh of the same slot), `skin` (the
//!   parent's skin by name, or by index as a `.skel` gives it; the default skin unless given),
//!   `timelines` (3.8 `deform`; true: it is deformed by its parent's deform timelines, not by
//!   its own): it takes its parent's UVs, triangles, vertices and hull. `clipping`: `end` (a
//!   slot's name), `vertexCount`, `vertices` (as a mesh's: unweighted when there are
//!   `2·vertexCount` numbers); it clips what is drawn after it (a polygon of more than
//!   [`MAX_CLIP_VERTICES`] vertices is not used, and listed as unsupported). `path`, `point`
//!   and `boundingbox` are not drawn.
//! - an attachment with a `sequence` (`start` 1, `digits` 0, `setup` 0) shows region `path`
//!   followed by `start + setup` written with `digits` digits (its frames are not played; the
//!   sequence is listed as unsupported).

use std::collections::HashMap;

use ikarus::character::{
    Art, Attachment, BlendMode, ClippingAttachment, MAX_CLIP_VERTICES, MeshAttachment, PathVertices, RegionAttachment,
    Rgba, SkinArt, Slot, WHITE,
};
use serde_json::Value;

use super::spine_slots::{Slots, number, numbers, weighted};
use crate::error::Error;
use crate::names::Quoted;

/// A linked mesh waiting for its parent: where it is, where its parent is, and its own fields.
struct Link {
    skin: usize,
    slot: usize,
    name: String,
    parent_skin: usize,
    parent: String,
    own: MeshAttachment,
    at: String,
    inherits: bool,
}

/// A linked mesh that takes its parent's deform timelines (`timelines`, 3.8 `deform`: true
/// unless given): where it is and where its parent is.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Inherits {
    pub(super) skin: usize,
    pub(super) slot: usize,
    pub(super) name: String,
    pub(super) parent_skin: usize,
    pub(super) parent: String,
}

/// Reads the art of a Spine file (parsed), whose slots and skins `slots` has read, and the
/// linked meshes that take their parents' deform timelines.
pub(super) fn read(value: &Value, slots: &Slots, bone_count: usize) -> Result<(Art, Vec<Inherits>), Error> {
    let mut art = Art::default();
    let list = value.get("slots").and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
    for (s, (json, slot)) in list.iter().zip(&slots.slots).enumerate() {
        let at = format!("slots[{s}] ({:?})", Quoted(&slot.name));
        let blend = match json.get("blend") {
            None => BlendMode::Normal,
            Some(Value::String(b)) => BlendMode::from_name(b).ok_or_else(|| {
                Error::input(format!("{at}.blend = {b:?}: expected normal, additive, multiply or screen"))
            })?,
            Some(other) => return Err(Error::input(format!("{at}.blend = {other}: expected a string"))),
        };
        let dark = match json.get("dark") {
            None | Some(Value::Null) => None,
            Some(d) => {
                let [r, g, b, _] = color(Some(d), 6, &format!("{at}.dark"))?;
                Some([r, g, b])
            }
        };
        art.slots.push(Slot {
            name: slot.name.clone(),
            bone: slot.bone,
            color: color(json.get("color"), 8, &format!("{at}.color"))?,
            dark,
            blend,
            attachment: slot.attachment.clone(),
        });
    }
    let skins = value.get("skins").and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
    let skin_index: HashMap<&str, usize> =
        slots.skins.iter().enumerate().map(|(k, s)| (s.name.as_str(), k)).rev().collect();
    let mut links = Vec::new();
    for (k, skin) in skins.iter().enumerate() {
        let mut out = SkinArt { slots: vec![HashMap::new(); art.slots.len()] };
        let at = format!("skins[{k}] ({:?}).attachments", Quoted(&slots.skins[k].name));
        for (slot_name, attachments) in skin.get("attachments").and_then(Value::as_object).into_iter().flatten() {
            let slot = slots.index[slot_name];
            for (name, a) in attachments.as_object().into_iter().flatten() {
                let at = format!("{at}.{slot_name}.{name}");
                let kind = a.get("type").and_then(Value::as_str).unwrap_or("region");
                let attachment = match kind {
                    "region" => Attachment::Region(region(a, name, &at)?),
                    "mesh" => Attachment::Mesh(mesh(a, name, bone_count, &at)?),
                    "linkedmesh" => {
                        let parent_skin = match a.get("skin") {
                            None | Some(Value::Null) => slots.default_skin(),
                            Some(Value::String(s)) => skin_index.get(s.as_str()).copied(),
                            // A `.skel` read into JSON names the skin by its index.
                            Some(Value::Number(n)) => n.as_u64().and_then(|n| usize::try_from(n).ok()),
                            Some(other) => {
                                return Err(Error::input(format!("{at}.skin = {other}: expected a skin's name")));
                            }
                        };
                        let parent_skin = parent_skin.filter(|&p| p < skins.len()).ok_or_else(|| {
                            Error::input({
                                format!("{at}.skin = {}: no such skin", a.get("skin").unwrap_or(&Value::Null))
                            })
                        })?;
                        let Some(Value::String(parent)) = a.get("parent") else {
                            return Err(Error::input(format!(
                                "{at}.parent: expected the name of a mesh of slot {slot_name:?}"
                            )));
                        };
                        let inherits = match a.get("timelines").or_else(|| a.get("deform")) {
                            None => true,
                            Some(Value::Bool(b)) => *b,
                            Some(other) => {
                                return Err(Error::input(format!("{at}.timelines = {other}: expected true or false")));
                            }
                        };
                        let own = MeshAttachment {
                            path: path(a, name, &at)?,
                            uvs: Vec::new(),
                            triangles: Vec::new(),
                            vertices: PathVertices::Plain(Vec::new()),
                            hull: 0,
                            width: number(a.get("width"), 32.0, &format!("{at}.width"))?,
                            height: number(a.get("height"), 32.0, &format!("{at}.height"))?,
                            color: color(a.get("color"), 8, &format!("{at}.color"))?,
                        };
                        links.push(Link {
                            skin: k,
                            slot,
                            name: name.clone(),
                            parent_skin,
                            parent: parent.clone(),
                            own,
                            at,
                            inherits,
                        });
                        continue;
                    }
                    "clipping" => clipping(a, &slots.index, bone_count, &at)?,
                    "path" | "point" | "boundingbox" => Attachment::NotDrawn,
                    other => {
                        return Err(Error::input(format!(
                            "{at}.type = {other:?}: not an attachment type Spine writes"
                        )));
                    }
                };
                out.slots[slot].insert(name.clone(), attachment);
            }
        }
        art.skins.push(out);
    }
    let mut inherits = Vec::new();
    for link in links {
        if link.inherits {
            inherits.push(Inherits {
                skin: link.skin,
                slot: link.slot,
                name: link.name.clone(),
                parent_skin: link.parent_skin,
                parent: link.parent.clone(),
            });
        }
        let parent = art.skins[link.parent_skin].get(link.slot, &link.parent);
        let Some(Attachment::Mesh(p)) = parent else {
            return Err(Error::input(format!(
                "{}.parent = {:?}: not a mesh of this slot in that skin",
                link.at,
                Quoted(&link.parent)
            )));
        };
        let mesh = MeshAttachment {
            uvs: p.uvs.clone(),
            triangles: p.triangles.clone(),
            vertices: p.vertices.clone(),
            hull: p.hull,
            ..link.own
        };
        art.skins[link.skin].slots[link.slot].insert(link.name, Attachment::Mesh(mesh));
    }
    Ok((art, inherits))
}

/// A colour written as `digits` hex digits (`RRGGBBAA` or `RRGGBB`), white when absent.
pub(super) fn color(v: Option<&Value>, digits: usize, at: &str) -> Result<Rgba, Error> {
    let Some(v) = v else { return Ok(WHITE) };
    let Some(hex) = v.as_str().filter(|s| s.len() == digits && s.chars().all(|c| c.is_ascii_hexdigit())) else {
        return Err(Error::input(format!("{at} = {v}: expected {digits} hex digits ({})", &"RRGGBBAA"[..digits])));
    };
    let mut out = WHITE;
    for (i, c) in out.iter_mut().enumerate().take(digits / 2) {
        *c = f64::from(u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).unwrap_or(255)) / 255.0;
    }
    Ok(out)
}

/// The region an attachment shows: `path` (else its name), with a sequence's setup frame.
fn path(a: &Value, name: &str, at: &str) -> Result<String, Error> {
    let base = match a.get("path") {
        None | Some(Value::Null) => name.to_owned(),
        Some(Value::String(p)) => p.clone(),
        Some(other) => return Err(Error::input(format!("{at}.path = {other}: expected a string"))),
    };
    let Some(sequence) = a.get("sequence") else { return Ok(base) };
    let whole = |field: &str, default: f64| {
        let v = number(sequence.get(field), default, &format!("{at}.sequence.{field}"))?;
        if v < 0.0 || v.fract() != 0.0 || v > 1e6 {
            return Err(Error::input(format!("{at}.sequence.{field} = {v}: expected a whole number from 0")));
        }
        Ok(v as usize)
    };
    let (start, digits, setup) = (whole("start", 1.0)?, whole("digits", 0.0)?, whole("setup", 0.0)?);
    Ok(format!("{base}{:0digits$}", start + setup, digits = digits.min(16)))
}

/// A clipping attachment (not used, [`Attachment::NotDrawn`], past [`MAX_CLIP_VERTICES`]).
fn clipping(a: &Value, slots: &HashMap<String, usize>, bone_count: usize, at: &str) -> Result<Attachment, Error> {
    let end = match a.get("end") {
        Some(Value::String(name)) => *slots
            .get(name.as_str())
            .ok_or_else(|| Error::input(format!("{at}.end = {name:?}: no slot of that name")))?,
        other => {
            let got = other.map_or("nothing".to_owned(), Value::to_string);
            return Err(Error::input(format!("{at}.end = {got}: expected the name of the slot where clipping ends")));
        }
    };
    let count = number(a.get("vertexCount"), 0.0, &format!("{at}.vertexCount"))?;
    if count < 3.0 || count.fract() != 0.0 {
        return Err(Error::input(format!(
            "{at}.vertexCount = {count}: expected a whole number of vertices, at least 3"
        )));
    }
    if count > MAX_CLIP_VERTICES as f64 {
        return Ok(Attachment::NotDrawn);
    }
    let count = count as usize;
    let v = numbers(a.get("vertices"), &format!("{at}.vertices"))?;
    let vertices = if v.len() == 2 * count {
        PathVertices::Plain(v.chunks(2).map(|p| [p[0], p[1]]).collect())
    } else {
        PathVertices::Weighted(weighted(&v, count, bone_count, &format!("{at}.vertices"))?)
    };
    Ok(Attachment::Clipping(ClippingAttachment { end, vertices }))
}

/// A region attachment.
fn region(a: &Value, name: &str, at: &str) -> Result<RegionAttachment, Error> {
    let n = |field: &str, default: f64| number(a.get(field), default, &format!("{at}.{field}"));
    Ok(RegionAttachment {
        path: path(a, name, at)?,
        x: n("x", 0.0)?,
        y: n("y", 0.0)?,
        rotation: n("rotation", 0.0)?.to_radians(),
        scale_x: n("scaleX", 1.0)?,
        scale_y: n("scaleY", 1.0)?,
        width: n("width", 32.0)?,
        height: n("height", 32.0)?,
        color: color(a.get("color"), 8, &format!("{at}.color"))?,
    })
}

/// A mesh attachment.
fn mesh(a: &Value, name: &str, bone_count: usize, at: &str) -> Result<MeshAttachment, Error> {
    let uvs = numbers(a.get("uvs"), &format!("{at}.uvs"))?;
    if uvs.len() % 2 != 0 {
        return Err(Error::input(format!("{at}.uvs: {} numbers, expected u, v pairs", uvs.len())));
    }
    let count = uvs.len() / 2;
    let v = numbers(a.get("vertices"), &format!("{at}.vertices"))?;
    let vertices = if v.len() == uvs.len() {
        PathVertices::Plain(v.chunks(2).map(|p| [p[0], p[1]]).collect())
    } else {
        PathVertices::Weighted(weighted(&v, count, bone_count, &format!("{at}.vertices"))?)
    };
    let triangles = numbers(a.get("triangles"), &format!("{at}.triangles"))?;
    let mut indices = Vec::with_capacity(triangles.len());
    for (i, &t) in triangles.iter().enumerate() {
        if t < 0.0 || t.fract() != 0.0 || t >= count as f64 {
            return Err(Error::input(format!("{at}.triangles[{i}] = {t}: no vertex of that index ({count} vertices)")));
        }
        indices.push(t as u32);
    }
    if indices.len() % 3 != 0 {
        return Err(Error::input(format!("{at}.triangles: {} indices, expected three per triangle", indices.len())));
    }
    let hull = number(a.get("hull"), 0.0, &format!("{at}.hull"))?;
    if hull < 0.0 || hull.fract() != 0.0 || hull > count as f64 {
        return Err(Error::input(format!("{at}.hull = {hull}: expected a whole number of vertices, at most {count}")));
    }
    Ok(MeshAttachment {
        path: path(a, name, at)?,
        uvs: uvs.chunks(2).map(|p| [p[0], p[1]]).collect(),
        triangles: indices,
        vertices,
        hull: hull as usize,
        width: number(a.get("width"), 32.0, &format!("{at}.width"))?,
        height: number(a.get("height"), 32.0, &format!("{at}.height"))?,
        color: color(a.get("color"), 8, &format!("{at}.color"))?,
    })
}
