//! A clip's slot timelines: what the art shows over time (Spine's animation `slots`,
//! `drawOrder` and the mesh `deform` timelines), and how each is sampled at a time.
//!
//! Rules (Spine's JSON export format, "Animations": slot, draw order and deform timelines):
//! - An attachment timeline is stepped: from a key on, the slot shows the key's attachment
//!   (`None`: nothing); before the first key, the setup attachment.
//! - A colour timeline sets the slot's colour (replacing the setup colour, not multiplying it):
//!   `rgba` all four channels, `rgb` red, green and blue (alpha stays), `alpha` alpha alone,
//!   `rgba2` the colour and the dark colour, `rgb2` red, green, blue and the dark colour. Each
//!   channel goes to the next key by its own curve; before the first key the setup colour,
//!   after the last key the last key's. As every timeline, times and values are `f32`.
//! - A draw order key holds the whole order it sets (`None`: the setup order), stepped; before
//!   the first key the setup order.
//! - A deform timeline adds offsets to one mesh's vertex coordinates (per weight entry of a
//!   weighted mesh), while the slot shows that mesh of that skin; sampled as a path's deform
//!   ([`super::DeformKey`]).

use super::path::deform;
use super::timeline::{f32ed, key_at, segment};
use super::{CharacterError, DeformKey, Interpolation};

/// The most channels a colour key holds (`rgba2`: four of the colour, three of the dark one).
pub const COLOR_CHANNELS: usize = 7;

/// One clip's slot timelines (indexed as the clips: [`super::Art::clips`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SlotClip {
    /// The attachment timelines.
    pub attachments: Vec<AttachmentTimeline>,
    /// The colour timelines.
    pub colors: Vec<ColorTimeline>,
    /// The draw order keys, in increasing time (none: the setup order throughout).
    pub draw_order: Vec<DrawOrderKey>,
    /// The meshes' deform timelines.
    pub deforms: Vec<MeshDeform>,
}

/// A slot's attachment timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct AttachmentTimeline {
    /// The slot's index.
    pub slot: usize,
    /// The keys, in increasing time.
    pub keys: Vec<AttachmentKey>,
}

/// One key of an attachment timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct AttachmentKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The attachment's name (`None`: the slot shows nothing).
    pub name: Option<String>,
}

/// What a colour timeline keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorProperty {
    /// Red, green, blue, alpha (Spine 3.8's `color`).
    Rgba,
    /// Red, green, blue.
    Rgb,
    /// Alpha.
    Alpha,
    /// Red, green, blue, alpha, then the dark colour's red, green, blue (3.8's `twoColor`).
    Rgba2,
    /// Red, green, blue, then the dark colour's red, green, blue.
    Rgb2,
}

impl ColorProperty {
    /// How many values a key holds.
    pub fn channels(self) -> usize {
        match self {
            ColorProperty::Rgba => 4,
            ColorProperty::Rgb => 3,
            ColorProperty::Alpha => 1,
            ColorProperty::Rgba2 => 7,
            ColorProperty::Rgb2 => 6,
        }
    }
}

/// One key of a colour timeline: `values[..channels]` are used, each 0 to 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColorKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The values, in the order [`ColorProperty`] lists them.
    pub values: [f64; COLOR_CHANNELS],
    /// Per channel, toward the next key (ignored on the last key).
    pub curves: [Interpolation; COLOR_CHANNELS],
}

/// A slot's colour timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorTimeline {
    /// The slot's index.
    pub slot: usize,
    /// What the keys hold.
    pub property: ColorProperty,
    /// The keys, in increasing time.
    pub keys: Vec<ColorKey>,
}

/// One key of the draw order timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawOrderKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The slots' indices, first drawn first (every slot once); `None`: the setup order.
    pub order: Option<Vec<usize>>,
}

/// A mesh's deform timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshDeform {
    /// The skin whose attachment it deforms (its index in [`super::Character::skins`]).
    pub skin: usize,
    /// The slot's index.
    pub slot: usize,
    /// The attachment's name in that skin and slot.
    pub attachment: String,
    /// The keys, in increasing time.
    pub keys: Vec<DeformKey>,
}

impl AttachmentTimeline {
    /// The key in force at `time` (`None` before the first key).
    pub fn key_at(&self, time: f64) -> Option<&AttachmentKey> {
        key_at(|i| self.keys[i].time, self.keys.len(), time).map(|i| &self.keys[i])
    }
}

impl ColorTimeline {
    /// The values at `time` (`values[..channels]`, `f32`-rounded), or `None` before the first
    /// key.
    pub fn at(&self, time: f64) -> Option<[f64; COLOR_CHANNELS]> {
        let i = key_at(|i| self.keys[i].time, self.keys.len(), time)?;
        let k = &self.keys[i];
        let mut values = k.values.map(f32ed);
        if let Some(n) = self.keys.get(i + 1) {
            let (t0, t1) = (f32ed(k.time), f32ed(n.time));
            for (ch, v) in values.iter_mut().enumerate().take(self.property.channels()) {
                *v = segment(k.curves[ch], (t0, *v), (t1, f32ed(n.values[ch])), time);
            }
        }
        Some(values)
    }

    /// Sets `color` (straight RGBA, as [`super::Rgba`]) and `dark` from the values at `time`;
    /// before the first key leaves them.
    pub fn apply(&self, time: f64, color: &mut [f64; 4], dark: &mut Option<[f64; 3]>) {
        let Some(v) = self.at(time) else { return };
        match self.property {
            ColorProperty::Rgba => color.copy_from_slice(&v[..4]),
            ColorProperty::Rgb => color[..3].copy_from_slice(&v[..3]),
            ColorProperty::Alpha => color[3] = v[0],
            ColorProperty::Rgba2 => {
                color.copy_from_slice(&v[..4]);
                *dark = Some([v[4], v[5], v[6]]);
            }
            ColorProperty::Rgb2 => {
                color[..3].copy_from_slice(&v[..3]);
                *dark = Some([v[3], v[4], v[5]]);
            }
        }
    }
}

/// The order in force at `time` among `keys`: `None` before the first key or at a key that
/// restores the setup order.
pub fn draw_order_at(keys: &[DrawOrderKey], time: f64) -> Option<&[usize]> {
    let i = key_at(|i| keys[i].time, keys.len(), time)?;
    keys[i].order.as_deref()
}

impl MeshDeform {
    /// The offsets at `time` into `out` (cleared first); `false` (and `out` empty) before the
    /// first key.
    pub fn at(&self, time: f64, out: &mut Vec<f64>) -> bool {
        deform::at(&self.keys, time, out)
    }
}

/// Spine's draw order key: from the setup order of `slots` slots and `(slot, offset)` pairs
/// sorted by slot, the order they give: each listed slot moves `offset` places from its setup
/// place, and the others keep their setup order in the places left. `Err` names the pair that
/// is out of order, leaves the slots, or lands where another listed slot is.
pub fn draw_order_from_offsets(slots: usize, offsets: &[(usize, i64)]) -> Result<Vec<usize>, String> {
    let mut order: Vec<Option<usize>> = vec![None; slots];
    let mut unchanged = Vec::with_capacity(slots);
    let mut next = 0;
    for (k, &(slot, offset)) in offsets.iter().enumerate() {
        if slot >= slots || slot < next {
            return Err(format!("offsets[{k}].slot = {slot}: not after the previous listed slot, or not a slot"));
        }
        unchanged.extend(next..slot);
        let place = i64::try_from(slot).ok().and_then(|s| s.checked_add(offset)).filter(|&p| p >= 0);
        let place = place.and_then(|p| usize::try_from(p).ok()).filter(|&p| p < slots);
        let Some(place) = place.filter(|&p| order[p].is_none()) else {
            return Err(format!("offsets[{k}].offset = {offset}: moves slot {slot} off the order or onto another"));
        };
        order[place] = Some(slot);
        next = slot + 1;
    }
    unchanged.extend(next..slots);
    let mut rest = unchanged.into_iter();
    Ok(order.into_iter().map(|o| o.or_else(|| rest.next()).unwrap_or(0)).collect())
}

/// Checks clips' slot timelines against `slots` slots, `skins` skins and `clips` clips: every
/// slot and skin exists, key times are finite and do not decrease, colour values are within 0
/// and 1, and every draw order holds each slot once.
pub(crate) fn check(all: &[SlotClip], slots: usize, skins: usize, clips: usize) -> Result<(), CharacterError> {
    let bad = |what: String| Err(CharacterError::Art { what });
    if all.len() > clips {
        return bad(format!("slot timelines for {} clips of {clips}", all.len()));
    }
    for (c, clip) in all.iter().enumerate() {
        let times = |at: String, t: &mut dyn Iterator<Item = f64>| -> Result<(), CharacterError> {
            let mut last = f64::NEG_INFINITY;
            for (i, time) in t.enumerate() {
                if !time.is_finite() || time < last {
                    return bad(format!("{at}.keys[{i}].time: {time} is not finite or before the previous key"));
                }
                last = time;
            }
            Ok(())
        };
        for (k, t) in clip.attachments.iter().enumerate() {
            if t.slot >= slots {
                return bad(format!("clips[{c}].attachments[{k}].slot: {} is not a slot", t.slot));
            }
            times(format!("clips[{c}].attachments[{k}]"), &mut t.keys.iter().map(|k| k.time))?;
        }
        for (k, t) in clip.colors.iter().enumerate() {
            if t.slot >= slots {
                return bad(format!("clips[{c}].colors[{k}].slot: {} is not a slot", t.slot));
            }
            times(format!("clips[{c}].colors[{k}]"), &mut t.keys.iter().map(|k| k.time))?;
            let n = t.property.channels();
            if t.keys.iter().any(|key| key.values[..n].iter().any(|v| !(0.0..=1.0).contains(v))) {
                return bad(format!("clips[{c}].colors[{k}]: a value is not within 0 and 1"));
            }
        }
        times(format!("clips[{c}].drawOrder"), &mut clip.draw_order.iter().map(|k| k.time))?;
        for (k, key) in clip.draw_order.iter().enumerate() {
            let Some(order) = &key.order else { continue };
            let mut seen = vec![false; slots];
            let whole =
                order.len() == slots && order.iter().all(|&s| s < slots && !std::mem::replace(&mut seen[s], true));
            if !whole {
                return bad(format!("clips[{c}].drawOrder[{k}]: not every slot once"));
            }
        }
        for (k, d) in clip.deforms.iter().enumerate() {
            if d.slot >= slots || d.skin >= skins {
                return bad(format!("clips[{c}].deforms[{k}]: slot {} or skin {} does not exist", d.slot, d.skin));
            }
            times(format!("clips[{c}].deforms[{k}]"), &mut d.keys.iter().map(|k| k.time))?;
            if d.keys.iter().flat_map(|k| &k.offsets).any(|v| !v.is_finite()) {
                return bad(format!("clips[{c}].deforms[{k}]: an offset is not finite"));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "slot_clip_tests.rs"]
mod tests;
