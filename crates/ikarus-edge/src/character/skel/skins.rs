//! The skins of a `.skel` (the default skin, then the named ones) with every attachment type
//! (region, boundingbox, mesh, linkedmesh, path, point, clipping, and their sequences), and the
//! events, written as Spine's JSON export writes them.

use serde_json::{Map, Value};

use super::Names;
use super::reader::Reader;
use crate::error::Error;

/// Attachment types, by their number in the file.
const TYPES: [&str; 7] = ["region", "boundingbox", "mesh", "linkedmesh", "path", "point", "clipping"];

/// The skins: the default skin first (when the file has one), then the named ones.
pub(super) fn skins(r: &mut Reader<'_>, names: &mut Names, nonessential: bool) -> Result<Value, Error> {
    let mut out = Vec::new();
    r.at = "skins[\"default\"]".to_owned();
    let slots = r.count("slots", 2)?;
    if slots > 0 {
        let mut o = Map::new();
        o.insert("name".into(), Value::from("default"));
        o.insert("attachments".into(), attachments(r, names, slots, nonessential)?);
        names.skins.push("default".to_owned());
        out.push(Value::Object(o));
    }
    r.at = "skins".to_owned();
    let n = r.count("count", 7)?;
    for _ in 0..n {
        r.at = format!("skins[{}]", out.len());
        let mut o = Map::new();
        let name = r.name("name")?;
        r.at = format!("skins[{}] ({name:?})", out.len());
        o.insert("name".into(), Value::from(name.clone()));
        if nonessential {
            o.insert("color".into(), Value::from(r.rgba("color")?));
        }
        let lists: [(&str, &[String], &str); 5] = [
            ("bones", &names.bones, "bone"),
            ("ik", &names.ik, "IK constraint"),
            ("transform", &names.transform, "transform constraint"),
            ("path", &names.path, "path constraint"),
            ("physics", &names.physics, "physics constraint"),
        ];
        for (field, list, what) in lists {
            let k = r.count(field, 1)?;
            let mut items = Vec::with_capacity(k);
            for _ in 0..k {
                items.push(Value::from(list[r.index(field, what, list.len())?].clone()));
            }
            if !items.is_empty() {
                o.insert(field.into(), Value::Array(items));
            }
        }
        let slots = r.count("slots", 2)?;
        o.insert("attachments".into(), attachments(r, names, slots, nonessential)?);
        names.skins.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}

/// A skin's attachments: per slot, per placeholder name.
fn attachments(r: &mut Reader<'_>, names: &Names, slots: usize, nonessential: bool) -> Result<Value, Error> {
    let skin = r.at.clone();
    let mut by_slot = Map::new();
    for _ in 0..slots {
        r.at = skin.clone();
        let s = r.index("slot", "slot", names.slots.len())?;
        let slot = names.slots[s].clone();
        r.at = format!("{skin}.attachments[{slot:?}]");
        let n = r.count("count", 2)?;
        let mut by_name = Map::new();
        for _ in 0..n {
            let key = r.string_ref("name")?.ok_or_else(|| r.fail("name", "an attachment without a name (got none)"))?;
            r.at = format!("{skin}.attachments[{slot:?}][{key:?}]");
            let a = attachment(r, names, &key, nonessential)?;
            by_name.insert(key, a);
            r.at = format!("{skin}.attachments[{slot:?}]");
        }
        by_slot.insert(slot, Value::Object(by_name));
    }
    Ok(Value::Object(by_slot))
}

/// One attachment, from its flags byte on.
fn attachment(r: &mut Reader<'_>, names: &Names, key: &str, nonessential: bool) -> Result<Value, Error> {
    let start = r.pos();
    let flags = r.byte("type")?;
    let kind = usize::from(flags & 7);
    let mut o = Map::new();
    o.insert("type".into(), super::skeleton::pick(r, start, "type", &TYPES, kind)?);
    let name = if flags & 8 != 0 { r.string_ref("name")? } else { None }.unwrap_or_else(|| key.to_owned());
    o.insert("name".into(), Value::from(name.clone()));
    let textured = |r: &mut Reader<'_>, o: &mut Map<String, Value>| -> Result<(), Error> {
        let path = if flags & 16 != 0 { r.string_ref("path")? } else { None }.unwrap_or_else(|| name.clone());
        o.insert("path".into(), Value::from(path));
        if flags & 32 != 0 {
            o.insert("color".into(), Value::from(r.rgba("color")?));
        }
        if flags & 64 != 0 {
            o.insert("sequence".into(), sequence(r)?);
        }
        Ok(())
    };
    match kind {
        0 => {
            textured(r, &mut o)?;
            let rotation = if flags & 128 != 0 { r.number("rotation")? } else { Value::from(0.0) };
            o.insert("rotation".into(), rotation);
            for f in ["x", "y", "scaleX", "scaleY", "width", "height"] {
                o.insert(f.into(), r.number(f)?);
            }
        }
        1 => {
            vertices(r, &mut o, flags & 16 != 0)?;
            color(r, &mut o, nonessential)?;
        }
        2 => {
            textured(r, &mut o)?;
            let hull = r.unsigned("hull")?;
            o.insert("hull".into(), Value::from(hull));
            let count = vertices(r, &mut o, flags & 128 != 0)?;
            o.insert("uvs".into(), Value::Array(r.floats("uvs", count * 2)?));
            let triangles = (count * 2).checked_sub(hull + 2).map(|t| t * 3);
            let triangles = triangles.ok_or_else(|| {
                r.fail("hull", &format!("a hull of more vertices than the mesh's {count} (got {hull})"))
            })?;
            o.insert("triangles".into(), shorts(r, "triangles", triangles)?);
            if nonessential {
                let n = r.count("edges", 1)?;
                o.insert("edges".into(), shorts(r, "edges", n)?);
                o.insert("width".into(), r.number("width")?);
                o.insert("height".into(), r.number("height")?);
            }
        }
        3 => {
            textured(r, &mut o)?;
            o.insert("timelines".into(), Value::from(flags & 128 != 0));
            let skin = r.unsigned("skin")?;
            o.insert("skin".into(), Value::from(skin));
            let parent =
                r.string_ref("parent")?.ok_or_else(|| r.fail("parent", "a linked mesh without a parent (got none)"))?;
            o.insert("parent".into(), Value::from(parent));
            if nonessential {
                o.insert("width".into(), r.number("width")?);
                o.insert("height".into(), r.number("height")?);
            }
        }
        4 => {
            o.insert("closed".into(), Value::from(flags & 16 != 0));
            o.insert("constantSpeed".into(), Value::from(flags & 32 != 0));
            let count = vertices(r, &mut o, flags & 64 != 0)?;
            o.insert("lengths".into(), Value::Array(r.floats("lengths", count / 3)?));
            color(r, &mut o, nonessential)?;
        }
        5 => {
            for f in ["rotation", "x", "y"] {
                o.insert(f.into(), r.number(f)?);
            }
            color(r, &mut o, nonessential)?;
        }
        _ => {
            let end = r.index("end", "slot", names.slots.len())?;
            o.insert("end".into(), Value::from(names.slots[end].clone()));
            vertices(r, &mut o, flags & 16 != 0)?;
            color(r, &mut o, nonessential)?;
        }
    }
    Ok(Value::Object(o))
}

fn color(r: &mut Reader<'_>, o: &mut Map<String, Value>, nonessential: bool) -> Result<(), Error> {
    if nonessential {
        o.insert("color".into(), Value::from(r.rgba("color")?));
    }
    Ok(())
}

/// A sequence: count, start, digits, setup index.
fn sequence(r: &mut Reader<'_>) -> Result<Value, Error> {
    let mut o = Map::new();
    for f in ["count", "start", "digits", "setup"] {
        o.insert(f.into(), Value::from(r.unsigned(f)?));
    }
    Ok(Value::Object(o))
}

/// `n` varint+ indices.
fn shorts(r: &mut Reader<'_>, field: &str, n: usize) -> Result<Value, Error> {
    if n > r.left() {
        return Err(r.fail(field, &format!("a count beyond the {} bytes left (got {n})", r.left())));
    }
    (0..n).map(|_| r.unsigned(field).map(Value::from)).collect::<Result<Vec<_>, _>>().map(Value::Array)
}

/// Vertices: their count, then (x, y) pairs, or per vertex its bones (count, then index, x, y,
/// weight each) when `weighted`; writes `vertexCount` and `vertices` as JSON does and returns
/// the count.
fn vertices(r: &mut Reader<'_>, o: &mut Map<String, Value>, weighted: bool) -> Result<usize, Error> {
    let count = r.count("vertexCount", if weighted { 1 } else { 8 })?;
    o.insert("vertexCount".into(), Value::from(count));
    let values = if weighted {
        let mut v = Vec::new();
        for _ in 0..count {
            let bones = r.count("vertices", 13)?;
            v.push(Value::from(bones));
            for _ in 0..bones {
                v.push(Value::from(r.unsigned("vertices")?));
                v.extend(r.floats("vertices", 3)?);
            }
        }
        v
    } else {
        r.floats("vertices", count * 2)?
    };
    o.insert("vertices".into(), Value::Array(values));
    Ok(count)
}

/// The events: name, int, float, string and audio path (with volume and balance when there is
/// one), keyed by name.
pub(super) fn events(r: &mut Reader<'_>, names: &mut Names) -> Result<Value, Error> {
    r.at = "events".to_owned();
    let n = r.count("count", 8)?;
    let mut out = Map::new();
    for i in 0..n {
        r.at = format!("events[{i}]");
        let name = r.name("name")?;
        let mut o = Map::new();
        o.insert("int".into(), Value::from(r.varint("int", false)?));
        o.insert("float".into(), r.number("float")?);
        if let Some(s) = r.string("string")? {
            o.insert("string".into(), Value::from(s));
        }
        if let Some(audio) = r.string("audio")? {
            o.insert("audio".into(), Value::from(audio));
            o.insert("volume".into(), r.number("volume")?);
            o.insert("balance".into(), r.number("balance")?);
        }
        names.events.push((name.clone(), o.contains_key("audio")));
        out.insert(name, Value::Object(o));
    }
    Ok(Value::Object(out))
}
