//! Spine's deform timelines (of path attachments here): in an animation, `attachments` = `{skin:
//! {slot: {attachment: {deform: [key…]}}}}` (4.x; 3.8 calls it `deform` = `{skin: {slot:
//! {attachment: [key…]}}}`). A key: `time` (0), `offset` (0, where `vertices` start among the
//! offsets), `vertices` (absent: all zeros), `curve` (absent: linear; `"stepped"`; 4.x
//! `[cx1, cy1, cx2, cy2]` with values from 0 to 1; 3.8 `curve`, `c2`, `c3`, `c4` normalised).
//! Meshes' deform timelines are read the same way by [`super::spine_slot_clips`].

use ikarus::character::{DeformKey, Interpolation, PathDeform};
use serde_json::Value;

use super::spine_slots::{Slots, number};
use crate::error::Error;

/// A path's deform timeline and the skin it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SkinDeform {
    /// The skin's name.
    pub(super) skin: String,
    /// Whose attachment it deforms: `None` the default skin's, `Some(s)` skin `s`'s own (as
    /// [`ikarus::character::PathConstraint::path_source`] tells them apart).
    pub(super) source: Option<usize>,
    /// The attachment's name.
    pub(super) attachment: String,
    /// The timeline.
    pub(super) deform: PathDeform,
}

/// One deform timeline of an animation, found in the file: its skin's index, slot's index,
/// attachment's name, keys (JSON) and where they are.
pub(super) struct Found<'a> {
    pub(super) skin: usize,
    pub(super) slot: usize,
    pub(super) attachment: &'a str,
    pub(super) keys: &'a [Value],
    pub(super) at: String,
    /// Whether 3.8's curve form is read.
    pub(super) legacy: bool,
}

/// Every deform timeline of animation `anim` (its JSON) named `name` whose skin and slot exist.
pub(super) fn found<'a>(anim: &'a Value, name: &str, slots: &Slots) -> Vec<Found<'a>> {
    let (field, legacy) = if anim.get("attachments").is_some() { ("attachments", false) } else { ("deform", true) };
    let mut out = Vec::new();
    let Some(skins) = anim.get(field).and_then(Value::as_object) else { return out };
    for (skin_name, by_slot) in skins {
        let Some(skin) = slots.skins.iter().position(|s| &s.name == skin_name) else { continue };
        let Some(by_slot) = by_slot.as_object() else { continue };
        for (slot_name, by_attachment) in by_slot {
            let Some(&slot) = slots.index.get(slot_name) else { continue };
            let Some(by_attachment) = by_attachment.as_object() else { continue };
            for (attachment, timelines) in by_attachment {
                let keys = if legacy { Some(timelines) } else { timelines.get("deform") };
                let Some(keys) = keys.and_then(Value::as_array) else { continue };
                let at = format!("animations.{name}.{field}.{skin_name}.{slot_name}.{attachment}");
                let at = if legacy { at } else { format!("{at}.deform") };
                out.push(Found { skin, slot, attachment, keys, at, legacy });
            }
        }
    }
    out
}

/// The path deform timelines of animation `anim` (its JSON) named `name`.
pub(super) fn read(anim: &Value, name: &str, slots: &Slots) -> Result<Vec<SkinDeform>, Error> {
    let default = slots.default_skin();
    let mut out = Vec::new();
    for f in found(anim, name, slots) {
        let skin = &slots.skins[f.skin];
        let Some(Some(path)) = skin.attachments.get(&(f.slot, f.attachment.to_owned())) else { continue };
        let keys = read_keys(f.keys, path.vertices.deform_len(), f.legacy, &f.at)?;
        out.push(SkinDeform {
            skin: skin.name.clone(),
            source: (Some(f.skin) != default).then_some(f.skin),
            attachment: f.attachment.to_owned(),
            deform: PathDeform { slot: f.slot, keys },
        });
    }
    Ok(out)
}

/// The keys of one deform timeline, `len` offsets each.
pub(super) fn read_keys(keys: &[Value], len: usize, legacy: bool, at: &str) -> Result<Vec<DeformKey>, Error> {
    let mut out: Vec<DeformKey> = Vec::with_capacity(keys.len());
    for (i, k) in keys.iter().enumerate() {
        let at = format!("{at}[{i}]");
        let time = number(k.get("time"), 0.0, &format!("{at}.time"))?;
        if out.last().is_some_and(|p| p.time > time) {
            return Err(Error::input(format!("{at}.time = {time}: before the previous key's")));
        }
        let offset = number(k.get("offset"), 0.0, &format!("{at}.offset"))?;
        let mut offsets = Vec::new();
        if let Some(v) = k.get("vertices") {
            let Some(v) = v.as_array() else {
                return Err(Error::input(format!("{at}.vertices: expected a list of numbers")));
            };
            if offset < 0.0 || offset.fract() != 0.0 || offset + v.len() as f64 > len as f64 {
                return Err(Error::input(format!(
                    "{at}.offset = {offset}: with {} vertices past the path's {len} coordinates",
                    v.len()
                )));
            }
            for (j, x) in v.iter().enumerate() {
                offsets.push(number(Some(x), 0.0, &format!("{at}.vertices[{j}]"))?);
            }
        }
        let start = if offsets.is_empty() { 0 } else { offset as usize };
        out.push(DeformKey { time, start, offsets, curve: Interpolation::Linear });
    }
    // Curves need the next key's time.
    for i in 0..out.len() {
        let next = out.get(i + 1).map_or(out[i].time, |n| n.time);
        out[i].curve = curve(&keys[i], [out[i].time, next], legacy, &format!("{at}[{i}].curve"))?;
    }
    Ok(out)
}

/// A key's curve from 0 at `times[0]` to 1 at `times[1]`.
fn curve(k: &Value, times: [f64; 2], legacy: bool, at: &str) -> Result<Interpolation, Error> {
    match k.get("curve") {
        None => Ok(Interpolation::Linear),
        Some(Value::String(s)) if s == "stepped" => Ok(Interpolation::Stepped),
        Some(Value::Array(p)) if !legacy && p.len() == 4 => {
            let n = p
                .iter()
                .enumerate()
                .map(|(j, x)| number(Some(x), 0.0, &format!("{at}[{j}]")))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Interpolation::Bezier { c1: [n[0], n[1]], c2: [n[2], n[3]] })
        }
        Some(c @ Value::Number(_)) if legacy => {
            let cx1 = number(Some(c), 0.0, at)?;
            let cy1 = number(k.get("c2"), 0.0, &format!("{at}.c2"))?;
            let cx2 = number(k.get("c3"), 1.0, &format!("{at}.c3"))?;
            let cy2 = number(k.get("c4"), 1.0, &format!("{at}.c4"))?;
            Ok(super::clips::unit_bezier([times[0], 0.0], [times[1], 1.0], [cx1, cy1, cx2, cy2]))
        }
        Some(other) => Err(Error::input(format!("{at} = {other}: expected \"stepped\" or [cx1, cy1, cx2, cy2]"))),
    }
}
