//! The attachment timelines of a `.skel` animation: deform (vertex offsets) and sequence
//! keys, per skin, slot and attachment, written as JSON's `attachments` section.

use serde_json::{Map, Value};

use super::Names;
use super::keys::{curve, sequence_mode};
use super::reader::Reader;
use crate::error::Error;

/// The `attachments` section of an animation.
pub(super) fn attachments(r: &mut Reader<'_>, names: &Names) -> Result<Map<String, Value>, Error> {
    let at = r.at.clone();
    let n = r.count("count", 2)?;
    let mut out = Map::new();
    for _ in 0..n {
        r.at = at.clone();
        let k = r.index("skin", "skin", names.skins.len())?;
        let skin = names.skins[k].clone();
        let mut slots = Map::new();
        r.at = format!("{at}[{skin:?}]");
        let ns = r.count("count", 2)?;
        for _ in 0..ns {
            r.at = format!("{at}[{skin:?}]");
            let s = r.index("slot", "slot", names.slots.len())?;
            let slot = names.slots[s].clone();
            r.at = format!("{at}[{skin:?}][{slot:?}]");
            let na = r.count("count", 3)?;
            let mut by_name = Map::new();
            for _ in 0..na {
                let key = r
                    .string_ref("attachment")?
                    .ok_or_else(|| r.fail("attachment", "a timeline without an attachment name (got none)"))?;
                r.at = format!("{at}[{skin:?}][{slot:?}][{key:?}]");
                let start = r.pos();
                let kind = r.byte("type")?;
                let frames = r.count("frames", 4)?;
                let (kind_name, keys) = match kind {
                    0 => ("deform", deform(r, frames)?),
                    1 => ("sequence", sequence(r, frames)?),
                    b => {
                        return Err(r.fail_at(
                            start,
                            "type",
                            &format!("an unknown attachment timeline type (got {b})"),
                        ));
                    }
                };
                let entry = by_name.entry(key.clone()).or_insert_with(|| Value::Object(Map::new()));
                if let Value::Object(e) = entry {
                    e.insert(kind_name.into(), keys);
                }
                r.at = format!("{at}[{skin:?}][{slot:?}]");
            }
            slots.insert(slot, Value::Object(by_name));
        }
        out.insert(skin, Value::Object(slots));
    }
    Ok(out)
}

fn deform(r: &mut Reader<'_>, frames: usize) -> Result<Value, Error> {
    r.unsigned("bezierCount")?;
    let mut keys: Vec<Map<String, Value>> = Vec::with_capacity(frames);
    // Each key: its offsets (a count, 0 for none, then the first index and the floats); every
    // key but the last is followed by the next key's time and then its own curve.
    if frames == 0 {
        return Ok(Value::Array(Vec::new()));
    }
    let mut t = r.number("time")?;
    for i in 0..frames {
        let mut o = Map::new();
        o.insert("time".into(), std::mem::take(&mut t));
        let end = r.unsigned("vertices")?;
        if end > 0 {
            let start = r.unsigned("offset")?;
            o.insert("offset".into(), Value::from(start));
            o.insert("vertices".into(), Value::Array(r.floats("vertices", end)?));
        }
        if i + 1 < frames {
            t = r.number("time")?;
            curve(r, &mut o, 1)?;
        }
        keys.push(o);
    }
    Ok(Value::Array(keys.into_iter().map(Value::Object).collect()))
}

fn sequence(r: &mut Reader<'_>, frames: usize) -> Result<Value, Error> {
    let mut keys = Vec::with_capacity(frames);
    for _ in 0..frames {
        let mut o = Map::new();
        o.insert("time".into(), r.number("time")?);
        let start = r.pos();
        let mode_and_index = r.int("mode")?;
        o.insert("mode".into(), sequence_mode(r, start, (mode_and_index & 0xf) as usize)?);
        o.insert("index".into(), Value::from(mode_and_index >> 4));
        o.insert("delay".into(), r.number("delay")?);
        keys.push(Value::Object(o));
    }
    Ok(Value::Array(keys))
}
