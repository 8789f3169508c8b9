//! Spine's slots and the skins' attachments that posing needs: today the path attachments
//! (path constraints follow them). Every skin's are kept, by skin, so that choosing a skin can
//! select its paths: Spine looks a slot's attachment up by name in the chosen skin first, then
//! in the default skin, so every skin's attachment names are kept too (one of another type
//! hides the default skin's path of that name).
//!
//! `slots[]`: `name`, `bone`, `attachment` (the setup pose's, none when absent). `skins[]`
//! (4.x; 3.8 too): `name`, `attachments` = `{slot: {attachment name: attachment}}`; an
//! attachment of `type: "path"` has `closed` (false), `constantSpeed` (true), `lengths`,
//! `vertexCount` and `vertices`: unweighted, `x, y` pairs in the slot bone's frame; weighted
//! (more numbers than `2·vertexCount`), per vertex a bone count then `(bone index, x, y,
//! weight)` per bone.

use std::collections::HashMap;

use ikarus::character::{PathShape, PathVertices, Weight};
use serde_json::Value;

use crate::error::Error;
use crate::names::Quoted;

/// A slot: its bone and the attachment it shows in the setup pose.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Slot {
    /// Its name in the file.
    pub(super) name: String,
    /// Its bone's index.
    pub(super) bone: usize,
    /// The setup pose's attachment's name (`attachment`), if any.
    pub(super) attachment: Option<String>,
}

/// A skin's attachments, by slot index and attachment name: the paths read, the others `None`.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Skin {
    /// Its name in the file.
    pub(super) name: String,
    /// `(slot, attachment name)` → the path, `None` for an attachment of another type.
    pub(super) attachments: HashMap<(usize, String), Option<PathShape>>,
}

/// The slots, their indices by name, and the skins.
#[derive(Debug, Clone, Default)]
pub(super) struct Slots {
    pub(super) slots: Vec<Slot>,
    pub(super) index: HashMap<String, usize>,
    pub(super) skins: Vec<Skin>,
}

impl Slots {
    /// The index of the skin called `default` (the one a slot's attachment falls back to).
    pub(super) fn default_skin(&self) -> Option<usize> {
        self.skins.iter().position(|s| s.name == "default")
    }

    /// Skin `skin`'s own attachment under the name slot `slot` shows in the setup pose: absent
    /// when the skin has none of that name, `Some(None)` when it is not a path.
    pub(super) fn setup_attachment(&self, skin: usize, slot: usize) -> Option<&Option<PathShape>> {
        let name = self.slots[slot].attachment.as_ref()?;
        self.skins[skin].attachments.get(&(slot, name.clone()))
    }
}

/// Reads `slots` and `skins` of a Spine file (parsed), bones resolved by `bones`.
pub(super) fn read(value: &Value, bones: &HashMap<String, usize>) -> Result<Slots, Error> {
    let mut out = Slots::default();
    for (i, s) in value.get("slots").and_then(Value::as_array).map_or(&[][..], Vec::as_slice).iter().enumerate() {
        let at = format!("slots[{i}]");
        let name = text(s.get("name"), &format!("{at}.name"))?;
        let at = format!("{at} ({:?})", Quoted(&name));
        let bone_name = text(s.get("bone"), &format!("{at}.bone"))?;
        let bone = super::bone(bones, &bone_name, &format!("{at}.bone"))?;
        let attachment = match s.get("attachment") {
            None | Some(Value::Null) => None,
            Some(a) => Some(text(Some(a), &format!("{at}.attachment"))?),
        };
        if let Some(first) = out.index.insert(name.clone(), i) {
            return Err(Error::input(format!("{at}.name = {:?}: also the name of slots[{first}]", Quoted(&name))));
        }
        out.slots.push(Slot { name, bone, attachment });
    }
    let skins = value.get("skins").and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
    for (k, skin) in skins.iter().enumerate() {
        let name = text(skin.get("name"), &format!("skins[{k}].name"))?;
        let at = format!("skins[{k}] ({:?}).attachments", Quoted(&name));
        let mut kept = HashMap::new();
        if let Some(slots) = skin.get("attachments").and_then(Value::as_object) {
            for (slot_name, attachments) in slots {
                let Some(&slot) = out.index.get(slot_name) else {
                    return Err(Error::input(format!("{at}: {:?} is not a slot", Quoted(slot_name))));
                };
                let Some(attachments) = attachments.as_object() else { continue };
                for (a_name, a) in attachments {
                    let shape = if a.get("type").and_then(Value::as_str) == Some("path") {
                        Some(path(a, bones.len(), &format!("{at}.{slot_name}.{a_name}"))?)
                    } else {
                        None
                    };
                    kept.insert((slot, a_name.clone()), shape);
                }
            }
        }
        out.skins.push(Skin { name, attachments: kept });
    }
    Ok(out)
}

/// A string field.
fn text(v: Option<&Value>, at: &str) -> Result<String, Error> {
    match v {
        Some(Value::String(s)) => Ok(s.clone()),
        Some(other) => Err(Error::input(format!("{at} = {other}: expected a string"))),
        None => Err(Error::input(format!("{at}: missing"))),
    }
}

/// A finite number, or `default` when absent.
pub(super) fn number(v: Option<&Value>, default: f64, at: &str) -> Result<f64, Error> {
    match v {
        None => Ok(default),
        Some(x) => x
            .as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| Error::input(format!("{at} = {x}: expected a finite number"))),
    }
}

/// A boolean, or `default` when absent.
fn boolean(v: Option<&Value>, default: bool, at: &str) -> Result<bool, Error> {
    match v {
        None => Ok(default),
        Some(Value::Bool(b)) => Ok(*b),
        Some(other) => Err(Error::input(format!("{at} = {other}: expected true or false"))),
    }
}

/// A list of finite numbers.
pub(super) fn numbers(v: Option<&Value>, at: &str) -> Result<Vec<f64>, Error> {
    let Some(list) = v.and_then(Value::as_array) else {
        return Err(Error::input(format!("{at}: expected a list of numbers")));
    };
    list.iter().enumerate().map(|(i, x)| number(Some(x), 0.0, &format!("{at}[{i}]"))).collect()
}

/// A path attachment.
fn path(a: &Value, bone_count: usize, at: &str) -> Result<PathShape, Error> {
    let closed = boolean(a.get("closed"), false, &format!("{at}.closed"))?;
    let constant_speed = boolean(a.get("constantSpeed"), true, &format!("{at}.constantSpeed"))?;
    let lengths = numbers(a.get("lengths"), &format!("{at}.lengths"))?;
    let count = number(a.get("vertexCount"), 0.0, &format!("{at}.vertexCount"))?;
    let v = numbers(a.get("vertices"), &format!("{at}.vertices"))?;
    if count < 0.0 || count.fract() != 0.0 || count > v.len() as f64 {
        return Err(Error::input(format!(
            "{at}.vertexCount = {count}: expected a whole number of vertices, at most {}",
            v.len()
        )));
    }
    let count = count as usize;
    let vertices = if v.len() == 2 * count {
        PathVertices::Plain(v.chunks(2).map(|p| [p[0], p[1]]).collect())
    } else {
        PathVertices::Weighted(weighted(&v, count, bone_count, &format!("{at}.vertices"))?)
    };
    Ok(PathShape { closed, constant_speed, lengths, vertices })
}

/// Weighted vertices: per vertex a bone count, then `(bone, x, y, weight)` per bone.
pub(super) fn weighted(v: &[f64], count: usize, bone_count: usize, at: &str) -> Result<Vec<Vec<Weight>>, Error> {
    let mut out = Vec::with_capacity(count);
    let mut i = 0;
    for _ in 0..count {
        let n = *v
            .get(i)
            .ok_or_else(|| Error::input(format!("{at}: ends at {i}, before vertex {} of {count}", out.len())))?;
        if n < 1.0 || n.fract() != 0.0 || (i + 1) as f64 + 4.0 * n > v.len() as f64 {
            return Err(Error::input(format!("{at}[{i}] = {n}: expected a bone count that the numbers after it hold")));
        }
        let mut vertex = Vec::with_capacity(n as usize);
        for k in 0..n as usize {
            let j = i + 1 + 4 * k;
            let b = v[j];
            if b < 0.0 || b.fract() != 0.0 || b >= bone_count as f64 {
                return Err(Error::input(format!("{at}[{j}] = {b}: no bone of that index ({bone_count} bones)")));
            }
            vertex.push(Weight { bone: b as usize, point: [v[j + 1], v[j + 2]], weight: v[j + 3] });
        }
        i += 1 + 4 * n as usize;
        out.push(vertex);
    }
    if i != v.len() {
        return Err(Error::input(format!("{at}: {} numbers, {count} weighted vertices end at {i}", v.len())));
    }
    Ok(out)
}
