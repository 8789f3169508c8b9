//! A Spine animation's slot timelines, into [`ikarus::character::SlotClip`].
//!
//! Fields (Spine's JSON export format, "Animations"):
//! - `slots` = `{slot: {timeline: [key…]}}`. `attachment` keys: `time` (0), `name` (absent or
//!   `null`: none). Colour keys, `time` (0) and `curve` (as the other timelines: `"stepped"`, or
//!   4.x `[cx1, cy1, cx2, cy2]` per channel, 3.8 `curve`, `c2`, `c3`, `c4` for every channel):
//!   `rgba` (3.8 `color`) `color` = `RRGGBBAA`; `rgb` `color` = `RRGGBB`; `alpha` `value` (0 to
//!   1; 0); `rgba2` (3.8 `twoColor`) `light` = `RRGGBBAA`, `dark` = `RRGGBB`; `rgb2` `light` =
//!   `RRGGBB`, `dark` = `RRGGBB`. Other slot timelines are listed as unsupported.
//! - `drawOrder` (also `draworder`) = `[key…]`: `time` (0), `offsets` = `[{slot, offset}…]` in
//!   slot order (absent: the setup order), turned into the whole order by
//!   [`ikarus::character::draw_order_from_offsets`].
//! - the deform timelines of meshes and clipping polygons, found as the paths'
//!   ([`super::spine_deform`]): offsets per vertex coordinate, per weight entry of a weighted
//!   mesh. A linked mesh whose
//!   `timelines` is true (the default) is deformed by its parent's timelines, not its own.

use ikarus::character::{
    Art, Attachment, AttachmentKey, AttachmentTimeline, COLOR_CHANNELS, ColorKey, ColorProperty, ColorTimeline,
    DrawOrderKey, Interpolation, MeshDeform, SlotClip, draw_order_from_offsets,
};
use serde_json::Value;

use super::spine_art::{Inherits, color};
use super::spine_slots::{Slots, number};
use crate::error::Error;
use crate::names::Quoted;

/// A colour key's hex fields and their digits, in the order of the values.
type Fields = &'static [(&'static str, usize)];

/// The colour timelines: name (4.x, else 3.8), property, and per field its hex digits.
const COLORS: [(&str, ColorProperty, Fields); 7] = [
    ("rgba", ColorProperty::Rgba, &[("color", 8)]),
    ("color", ColorProperty::Rgba, &[("color", 8)]),
    ("rgb", ColorProperty::Rgb, &[("color", 6)]),
    ("alpha", ColorProperty::Alpha, &[]),
    ("rgba2", ColorProperty::Rgba2, &[("light", 8), ("dark", 6)]),
    ("twoColor", ColorProperty::Rgba2, &[("light", 8), ("dark", 6)]),
    ("rgb2", ColorProperty::Rgb2, &[("light", 6), ("dark", 6)]),
];

/// The slot timelines this reader knows (the others are listed as unsupported).
pub(super) const KNOWN: [&str; 8] = ["attachment", "rgba", "color", "rgb", "alpha", "rgba2", "twoColor", "rgb2"];

/// The slot timelines of animation `anim` (its JSON) named `name`, at `at`: slots by `slots`,
/// meshes by `art`, `inherits` the linked meshes deformed by their parents' timelines; `legacy`
/// for a 3.8 file.
pub(super) fn read(
    anim: &Value,
    (name, at): (&str, &str),
    slots: &Slots,
    (art, inherits): (&Art, &[Inherits]),
    legacy: bool,
) -> Result<SlotClip, Error> {
    let mut out = SlotClip::default();
    for (slot_name, timelines) in anim.get("slots").and_then(Value::as_object).into_iter().flatten() {
        let at = format!("{at}.slots.{:?}", Quoted(slot_name));
        let &slot = slots.index.get(slot_name).ok_or_else(|| Error::input(format!("{at}: no slot of that name")))?;
        for (kind, keys) in timelines.as_object().into_iter().flatten() {
            let at = format!("{at}.{kind}");
            let keys = keys.as_array().ok_or_else(|| Error::input(format!("{at}: expected a list of keys")))?;
            if kind == "attachment" {
                out.attachments.push(AttachmentTimeline { slot, keys: attachment_keys(keys, &at)? });
            } else if let Some(&(_, property, fields)) = COLORS.iter().find(|c| c.0 == kind) {
                let keys = color_keys(keys, (property, fields), legacy, &at)?;
                out.colors.push(ColorTimeline { slot, property, keys });
            }
        }
    }
    let order = anim.get("drawOrder").or_else(|| anim.get("draworder"));
    if let Some(keys) = order {
        let field = if anim.get("drawOrder").is_some() { "drawOrder" } else { "draworder" };
        out.draw_order = draw_order(keys, slots, &format!("{at}.{field}"))?;
    }
    for f in super::spine_deform::found(anim, name, slots) {
        // A linked mesh that takes its parent's timelines does not use its own.
        if inherits.iter().any(|l| (l.skin, l.slot, l.name.as_str()) == (f.skin, f.slot, f.attachment)) {
            continue;
        }
        let vertices = match art.skins.get(f.skin).and_then(|s| s.get(f.slot, f.attachment)) {
            Some(Attachment::Mesh(mesh)) => &mesh.vertices,
            Some(Attachment::Clipping(clipping)) => &clipping.vertices,
            _ => continue,
        };
        let keys = super::spine_deform::read_keys(f.keys, vertices.deform_len(), f.legacy, &f.at)?;
        let linked =
            inherits.iter().filter(|l| (l.parent_skin, l.slot, l.parent.as_str()) == (f.skin, f.slot, f.attachment));
        for l in linked {
            let keys = keys.clone();
            out.deforms.push(MeshDeform { skin: l.skin, slot: l.slot, attachment: l.name.clone(), keys });
        }
        out.deforms.push(MeshDeform { skin: f.skin, slot: f.slot, attachment: f.attachment.to_owned(), keys });
    }
    Ok(out)
}

/// A key's time, not before the previous key's.
fn time(k: &Value, previous: Option<f64>, at: &str) -> Result<f64, Error> {
    let time = number(k.get("time"), 0.0, &format!("{at}.time"))?;
    if previous.is_some_and(|p| p > time) {
        return Err(Error::input(format!("{at}.time = {time}: before the previous key's")));
    }
    Ok(time)
}

/// An attachment timeline's keys.
fn attachment_keys(keys: &[Value], at: &str) -> Result<Vec<AttachmentKey>, Error> {
    let mut out: Vec<AttachmentKey> = Vec::with_capacity(keys.len());
    for (i, k) in keys.iter().enumerate() {
        let at = format!("{at}[{i}]");
        let time = time(k, out.last().map(|k| k.time), &at)?;
        let name = match k.get("name") {
            None | Some(Value::Null) => None,
            Some(Value::String(s)) => Some(s.clone()),
            Some(other) => {
                return Err(Error::input(format!("{at}.name = {other}: expected an attachment's name or null")));
            }
        };
        out.push(AttachmentKey { time, name });
    }
    Ok(out)
}

/// A colour timeline's keys: `fields` name the hex colours the values come from, in order
/// (none: `alpha`'s `value`).
fn color_keys(
    keys: &[Value],
    (property, fields): (ColorProperty, &[(&str, usize)]),
    legacy: bool,
    at: &str,
) -> Result<Vec<ColorKey>, Error> {
    let n = property.channels();
    let mut out: Vec<ColorKey> = Vec::with_capacity(keys.len());
    for (i, k) in keys.iter().enumerate() {
        let at = format!("{at}[{i}]");
        let time = time(k, out.last().map(|k| k.time), &at)?;
        let mut values = Vec::with_capacity(COLOR_CHANNELS);
        for &(field, digits) in fields {
            let v = k.get(field).ok_or_else(|| Error::input(format!("{at}.{field}: expected {digits} hex digits")))?;
            values.extend_from_slice(&color(Some(v), digits, &format!("{at}.{field}"))?[..digits / 2]);
        }
        if fields.is_empty() {
            let v = number(k.get("value"), 0.0, &format!("{at}.value"))?;
            if !(0.0..=1.0).contains(&v) {
                return Err(Error::input(format!("{at}.value = {v}: expected an alpha from 0 to 1")));
            }
            values.push(v);
        }
        let mut key = ColorKey { time, values: [0.0; COLOR_CHANNELS], curves: [Interpolation::Linear; COLOR_CHANNELS] };
        key.values[..n].copy_from_slice(&values);
        out.push(key);
    }
    for i in 0..out.len().saturating_sub(1) {
        let (this, next) = (out[i], out[i + 1]);
        let from = (this.time, &this.values[..n]);
        let c = super::spine_path_clips::curves(
            &keys[i],
            from,
            (next.time, &next.values[..n]),
            legacy,
            &format!("{at}[{i}].curve"),
        )?;
        out[i].curves[..n].copy_from_slice(&c);
    }
    Ok(out)
}

/// The draw order keys.
fn draw_order(keys: &Value, slots: &Slots, at: &str) -> Result<Vec<DrawOrderKey>, Error> {
    let keys = keys.as_array().ok_or_else(|| Error::input(format!("{at}: expected a list of keys")))?;
    let mut out: Vec<DrawOrderKey> = Vec::with_capacity(keys.len());
    for (i, k) in keys.iter().enumerate() {
        let at = format!("{at}[{i}]");
        let time = time(k, out.last().map(|k| k.time), &at)?;
        let Some(offsets) = k.get("offsets") else {
            out.push(DrawOrderKey { time, order: None });
            continue;
        };
        let offsets = offsets.as_array().ok_or_else(|| Error::input(format!("{at}.offsets: expected a list")))?;
        let mut pairs = Vec::with_capacity(offsets.len());
        for (j, o) in offsets.iter().enumerate() {
            let at = format!("{at}.offsets[{j}]");
            let Some(Value::String(name)) = o.get("slot") else {
                return Err(Error::input(format!("{at}.slot: expected a slot's name")));
            };
            let &slot = slots
                .index
                .get(name)
                .ok_or_else(|| Error::input(format!("{at}.slot = {:?}: no such slot", Quoted(name))))?;
            let offset = number(o.get("offset"), 0.0, &format!("{at}.offset"))?;
            if offset.fract() != 0.0 || offset.abs() > slots.slots.len() as f64 {
                return Err(Error::input(format!("{at}.offset = {offset}: expected a whole number of places")));
            }
            pairs.push((slot, offset as i64));
        }
        let order =
            draw_order_from_offsets(slots.slots.len(), &pairs).map_err(|e| Error::input(format!("{at}.{e}")))?;
        out.push(DrawOrderKey { time, order: Some(order) });
    }
    Ok(out)
}
