//! The animations of a `.skel`, every timeline kind, written as Spine's JSON export writes them
//! (keys as objects with `time`, the values under their JSON names, curves as 4.x `curve`
//! arrays of absolute `cx1, cy1, cx2, cy2` per channel, or `"stepped"`).
//!
//! A curve timeline stores its first key's time and values, then for each further key its time
//! and values followed by the curve of the key before (a byte: 0 linear, 1 stepped, 2 Bezier,
//! then 4 floats per channel), so the last key has no curve.

use serde_json::{Map, Value};

use super::Names;
use super::keys::curve;
use super::reader::Reader;
use super::skeleton::pick;
use crate::error::Error;

const SLOT_KINDS: [&str; 6] = ["attachment", "rgba", "rgb", "rgba2", "rgb2", "alpha"];
const BONE_KINDS: [&str; 11] = [
    "rotate",
    "translate",
    "translatex",
    "translatey",
    "scale",
    "scalex",
    "scaley",
    "shear",
    "shearx",
    "sheary",
    "inherit",
];
const PATH_KINDS: [&str; 3] = ["position", "spacing", "mix"];
const PHYSICS_KINDS: [&str; 9] = ["inertia", "strength", "damping", "", "mass", "wind", "gravity", "mix", "reset"];
const INHERIT: [&str; 5] = ["normal", "onlyTranslation", "noRotationOrReflection", "noScale", "noScaleOrReflection"];

type Frame<'f> = &'f mut dyn FnMut(&mut Reader<'_>) -> Result<Map<String, Value>, Error>;

/// The animations, keyed by name.
pub(super) fn animations(r: &mut Reader<'_>, names: &Names) -> Result<Value, Error> {
    r.at = "animations".to_owned();
    let n = r.count("count", 10)?;
    let mut out = Map::new();
    for i in 0..n {
        r.at = format!("animations[{i}]");
        let name = r.name("name")?;
        r.at = format!("animations[{name:?}]");
        let a = animation(r, names)?;
        out.insert(name, a);
    }
    Ok(Value::Object(out))
}

fn animation(r: &mut Reader<'_>, names: &Names) -> Result<Value, Error> {
    let at = r.at.clone();
    let mut o = Map::new();
    // The number of timelines, which the sections below count again.
    r.unsigned("timelines")?;
    r.at = format!("{at}.slots");
    insert(&mut o, "slots", slots(r, names)?);
    r.at = format!("{at}.bones");
    insert(&mut o, "bones", bones(r, names)?);
    r.at = format!("{at}.ik");
    insert(&mut o, "ik", ik(r, names)?);
    r.at = format!("{at}.transform");
    insert(&mut o, "transform", transform(r, names)?);
    r.at = format!("{at}.path");
    insert(&mut o, "path", path(r, names)?);
    r.at = format!("{at}.physics");
    insert(&mut o, "physics", physics(r, names)?);
    r.at = format!("{at}.attachments");
    insert(&mut o, "attachments", super::deform::attachments(r, names)?);
    r.at = format!("{at}.drawOrder");
    if let Some(d) = draw_order(r, names)? {
        o.insert("drawOrder".into(), d);
    }
    r.at = format!("{at}.events");
    if let Some(e) = events(r, names)? {
        o.insert("events".into(), e);
    }
    Ok(Value::Object(o))
}

fn insert(o: &mut Map<String, Value>, key: &str, v: Map<String, Value>) {
    if !v.is_empty() {
        o.insert(key.into(), Value::Object(v));
    }
}

/// A key's time.
fn time(r: &mut Reader<'_>) -> Result<Map<String, Value>, Error> {
    let mut o = Map::new();
    o.insert("time".into(), r.number("time")?);
    Ok(o)
}

/// A curve timeline of `frames` keys read by `frame`, with `channels` Bezier channels.
pub(super) fn curved(r: &mut Reader<'_>, frames: usize, channels: usize, frame: Frame<'_>) -> Result<Value, Error> {
    let mut keys = Vec::with_capacity(frames);
    if frames == 0 {
        return Ok(Value::Array(keys));
    }
    let mut key = frame(r)?;
    for _ in 1..frames {
        let next = frame(r)?;
        curve(r, &mut key, channels)?;
        keys.push(Value::Object(key));
        key = next;
    }
    keys.push(Value::Object(key));
    Ok(Value::Array(keys))
}

/// One value per key, under `field`.
fn values(r: &mut Reader<'_>, frames: usize, fields: &[&str]) -> Result<Value, Error> {
    curved(r, frames, fields.len(), &mut |r| {
        let mut o = time(r)?;
        for f in fields {
            o.insert((*f).into(), r.number(f)?);
        }
        Ok(o)
    })
}

/// Colour channels as bytes, written as hex.
fn color_bytes(r: &mut Reader<'_>, field: &str, n: usize) -> Result<String, Error> {
    let b = r.take_bytes(n, field)?;
    Ok(b.iter().map(|b| format!("{b:02x}")).collect())
}

fn slots(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        r.at = at.clone();
        let s = r.index("slot", "slot", names.slots.len())?;
        let slot = names.slots[s].clone();
        r.at = format!("{at}[{slot:?}]");
        let k = r.count("count", 2)?;
        let mut timelines = Map::new();
        for _ in 0..k {
            let start = r.pos();
            let kind = usize::from(r.byte("type")?);
            let name = pick(r, start, "type", &SLOT_KINDS, kind)?;
            let frames = r.count("frames", 5)?;
            let keys = match kind {
                0 => Value::Array(
                    (0..frames)
                        .map(|_| {
                            let mut o = time(r)?;
                            if let Some(a) = r.string_ref("name")? {
                                o.insert("name".into(), Value::from(a));
                            } else {
                                o.insert("name".into(), Value::Null);
                            }
                            Ok(Value::Object(o))
                        })
                        .collect::<Result<_, Error>>()?,
                ),
                _ => {
                    r.unsigned("bezierCount")?;
                    let (light, dark) = [(0, 0), (4, 0), (3, 0), (4, 3), (3, 3), (1, 0)][kind];
                    curved(r, frames, light + dark, &mut |r| {
                        let mut o = time(r)?;
                        match (kind, dark) {
                            (5, _) => {
                                o.insert("value".into(), Value::from(f64::from(f32::from(r.byte("value")?) / 255.0)));
                            }
                            (_, 0) => {
                                o.insert("color".into(), Value::from(color_bytes(r, "color", light)?));
                            }
                            _ => {
                                o.insert("light".into(), Value::from(color_bytes(r, "light", light)?));
                                o.insert("dark".into(), Value::from(color_bytes(r, "dark", dark)?));
                            }
                        }
                        Ok(o)
                    })?
                }
            };
            timelines.insert(name.as_str().unwrap_or_default().to_owned(), keys);
        }
        out.insert(slot, Value::Object(timelines));
    }
    Ok(out)
}

fn bones(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        r.at = at.clone();
        let b = r.index("bone", "bone", names.bones.len())?;
        let bone = names.bones[b].clone();
        r.at = format!("{at}[{bone:?}]");
        let k = r.count("count", 2)?;
        let mut timelines = Map::new();
        for _ in 0..k {
            let start = r.pos();
            let kind = usize::from(r.byte("type")?);
            let name = pick(r, start, "type", &BONE_KINDS, kind)?;
            let frames = r.count("frames", 5)?;
            let keys = if kind == 10 {
                let mut keys = Vec::with_capacity(frames);
                for _ in 0..frames {
                    let mut o = time(r)?;
                    let start = r.pos();
                    let i = usize::from(r.byte("inherit")?);
                    o.insert("inherit".into(), pick(r, start, "inherit", &INHERIT, i)?);
                    keys.push(Value::Object(o));
                }
                Value::Array(keys)
            } else {
                r.unsigned("bezierCount")?;
                let two = matches!(kind, 1 | 4 | 7);
                values(r, frames, if two { &["x", "y"] } else { &["value"] })?
            };
            timelines.insert(name.as_str().unwrap_or_default().to_owned(), keys);
        }
        out.insert(bone, Value::Object(timelines));
    }
    Ok(out)
}

fn ik(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        r.at = at.clone();
        let c = r.index("constraint", "IK constraint", names.ik.len())?;
        let name = names.ik[c].clone();
        r.at = format!("{at}[{name:?}]");
        let frames = r.count("frames", 5)?;
        r.unsigned("bezierCount")?;
        let mut keys: Vec<Map<String, Value>> = Vec::with_capacity(frames);
        for _ in 0..frames {
            let (flags, key) = ik_key(r)?;
            if let Some(prev) = keys.last_mut() {
                if flags & 64 != 0 {
                    prev.insert("curve".into(), Value::from("stepped"));
                } else if flags & 128 != 0 {
                    prev.insert("curve".into(), Value::Array(r.floats("curve", 8)?));
                }
            }
            keys.push(key);
        }
        out.insert(name, Value::Array(keys.into_iter().map(Value::Object).collect()));
    }
    Ok(out)
}

/// An IK key: its flags byte (which values follow, the booleans, and the curve of the key
/// before: 64 stepped, 128 Bezier), time, mix and softness.
fn ik_key(r: &mut Reader<'_>) -> Result<(u8, Map<String, Value>), Error> {
    let flags = r.byte("flags")?;
    let mut o = time(r)?;
    let mix = match (flags & 1 != 0, flags & 2 != 0) {
        (false, _) => Value::from(0.0),
        (true, false) => Value::from(1.0),
        (true, true) => r.number("mix")?,
    };
    o.insert("mix".into(), mix);
    let softness = if flags & 4 != 0 { r.number("softness")? } else { Value::from(0.0) };
    o.insert("softness".into(), softness);
    o.insert("bendPositive".into(), Value::from(flags & 8 != 0));
    o.insert("compress".into(), Value::from(flags & 16 != 0));
    o.insert("stretch".into(), Value::from(flags & 32 != 0));
    Ok((flags, o))
}

/// A constraint's index among `list`, its name, and `at` moved under it.
fn constraint(r: &mut Reader<'_>, at: &str, list: &[String], what: &str) -> Result<String, Error> {
    r.at = at.to_owned();
    let c = r.index("constraint", what, list.len())?;
    r.at = format!("{at}[{:?}]", list[c]);
    Ok(list[c].clone())
}

fn transform(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        let name = constraint(r, &at, &names.transform, "transform constraint")?;
        let frames = r.count("frames", 28)?;
        r.unsigned("bezierCount")?;
        let fields = ["mixRotate", "mixX", "mixY", "mixScaleX", "mixScaleY", "mixShearY"];
        out.insert(name, values(r, frames, &fields)?);
    }
    Ok(out)
}

fn path(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        let name = constraint(r, &at, &names.path, "path constraint")?;
        let k = r.count("count", 3)?;
        let mut timelines = Map::new();
        for _ in 0..k {
            let start = r.pos();
            let kind = usize::from(r.byte("type")?);
            let kind_name = pick(r, start, "type", &PATH_KINDS, kind)?;
            let frames = r.count("frames", 8)?;
            r.unsigned("bezierCount")?;
            let fields: &[&str] = if kind == 2 { &["mixRotate", "mixX", "mixY"] } else { &["value"] };
            timelines.insert(kind_name.as_str().unwrap_or_default().to_owned(), values(r, frames, fields)?);
        }
        out.insert(name, Value::Object(timelines));
    }
    Ok(out)
}

fn physics(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        r.at = at.clone();
        let start = r.pos();
        let i = r.unsigned("constraint")?;
        // 0 keys every physics constraint (JSON's ""), else the index + 1.
        let name = match i.checked_sub(1) {
            None => String::new(),
            Some(c) => names.physics.get(c).cloned().ok_or_else(|| {
                r.fail_at(start, "constraint", &format!("physics constraint index {c} out of {}", names.physics.len()))
            })?,
        };
        r.at = format!("{at}[{name:?}]");
        let k = r.count("count", 2)?;
        let mut timelines = Map::new();
        for _ in 0..k {
            let start = r.pos();
            let kind = usize::from(r.byte("type")?);
            let kind_name = pick(r, start, "type", &PHYSICS_KINDS, kind)?;
            if kind == 3 {
                return Err(r.fail_at(start, "type", "an unknown type (got 3)"));
            }
            let frames = r.count("frames", 4)?;
            let keys = if kind == 8 {
                Value::Array((0..frames).map(|_| time(r).map(Value::Object)).collect::<Result<_, _>>()?)
            } else {
                r.unsigned("bezierCount")?;
                values(r, frames, &["value"])?
            };
            timelines.insert(kind_name.as_str().unwrap_or_default().to_owned(), keys);
        }
        out.insert(name, Value::Object(timelines));
    }
    Ok(out)
}

fn draw_order(r: &mut Reader<'_>, names: &Names) -> Result<Option<Value>, Error> {
    let n = r.count("count", 5)?;
    if n == 0 {
        return Ok(None);
    }
    let at = r.at.clone();
    let mut keys = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("{at}[{i}]");
        let mut o = time(r)?;
        let k = r.count("offsets", 2)?;
        let mut offsets = Vec::with_capacity(k);
        for _ in 0..k {
            let s = r.index("slot", "slot", names.slots.len())?;
            let offset = r.varint("offset", true)?;
            let mut e = Map::new();
            e.insert("slot".into(), Value::from(names.slots[s].clone()));
            e.insert("offset".into(), Value::from(offset));
            offsets.push(Value::Object(e));
        }
        o.insert("offsets".into(), Value::Array(offsets));
        keys.push(Value::Object(o));
    }
    Ok(Some(Value::Array(keys)))
}

fn events(r: &mut Reader<'_>, names: &Names) -> Result<Option<Value>, Error> {
    let n = r.count("count", 7)?;
    if n == 0 {
        return Ok(None);
    }
    let at = r.at.clone();
    let mut keys = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("{at}[{i}]");
        let mut o = time(r)?;
        let e = r.index("name", "event", names.events.len())?;
        let (name, audio) = &names.events[e];
        o.insert("name".into(), Value::from(name.clone()));
        o.insert("int".into(), Value::from(r.varint("int", false)?));
        o.insert("float".into(), r.number("float")?);
        if r.bool("string")? {
            if let Some(s) = r.string("string")? {
                o.insert("string".into(), Value::from(s));
            }
        }
        if *audio {
            o.insert("volume".into(), r.number("volume")?);
            o.insert("balance".into(), r.number("balance")?);
        }
        keys.push(Value::Object(o));
    }
    Ok(Some(Value::Array(keys)))
}
