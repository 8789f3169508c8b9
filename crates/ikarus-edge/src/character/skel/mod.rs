//! Spine's binary export (`.skel`, 4.2) decoded into the JSON tree Spine's JSON export of the
//! same skeleton has, so that one reader (`super::spine`) serves both formats and their
//! problems read the same.
//!
//! The tree has JSON's field names and units: degrees, names in place of indices, colours as
//! hex strings, curves as 4.x `curve` arrays; defaults are written out rather than omitted.
//! Floats are the binary's 32-bit values widened to f64 exactly (serde_json prints an f64 in
//! its shortest round-trip form, so the text of the tree reads back to the same bits). Objects
//! keyed by name (animations, timelines, attachments) come sorted by name, as serde_json keeps
//! them. Every section is decoded, since each follows the one before byte by byte: the header,
//! the strings table, bones, slots, IK, transform, path and physics constraints, the skins with
//! every attachment type, events, and animations with every timeline kind.
//!
//! What the binary stores otherwise than JSON is written as JSON has it: a physics
//! constraint's mass is stored as its inverse (`mass` = 1 / inverse, in f32); a transform
//! constraint's offsets and mixes not stored are 0; a linked mesh's skin is an index, named
//! once every skin is read; a deform key's offsets are `offset` and `vertices` as JSON's.
//!
//! The layout follows Spine's public "Binary export format" page; where a detail was read
//! from the example files instead (each decoded and compared with its JSON export in
//! `tests/skel.rs`): an animation starts with its number of timelines; an IK constraint's
//! flags byte holds skin (1), bend positive (2), compress (4), stretch (8), uniform (16), a
//! mix other than 0 (32) read as a float when 64 is set too (else 1), softness (128); a bone's
//! nonessential data is its colour, icon and a visibility flag.
//!
//! Bad input is one line naming the byte and what was being read
//! (`skel: byte 88: bones[3].parent: bone index 9 out of 4`), never a panic; every count is
//! checked against the bytes left before anything is allocated for it, so time and memory stay
//! within a small multiple of the file's size.

mod animations;
mod deform;
mod keys;
mod reader;
mod skeleton;
mod skins;

use serde_json::{Map, Value};

use crate::error::Error;

use reader::Reader;

/// The names the later sections refer to by index.
#[derive(Default)]
struct Names {
    bones: Vec<String>,
    slots: Vec<String>,
    ik: Vec<String>,
    transform: Vec<String>,
    path: Vec<String>,
    physics: Vec<String>,
    skins: Vec<String>,
    /// Each event's name, and whether it has an audio path (its keys then carry volume and
    /// balance).
    events: Vec<(String, bool)>,
}

/// Decodes a `.skel` file into the JSON tree of Spine's JSON export; a problem is one line
/// (`skel: byte N: <what>: <problem>`).
pub fn to_json(bytes: &[u8]) -> Result<Value, Error> {
    let mut r = Reader::new(bytes);
    let mut names = Names::default();
    let (header, nonessential) = skeleton::header(&mut r)?;
    skeleton::strings(&mut r)?;
    let mut o = Map::new();
    o.insert("skeleton".into(), header);
    o.insert("bones".into(), skeleton::bones(&mut r, &mut names, nonessential)?);
    o.insert("slots".into(), skeleton::slots(&mut r, &mut names, nonessential)?);
    o.insert("ik".into(), skeleton::ik(&mut r, &mut names)?);
    o.insert("transform".into(), skeleton::transform(&mut r, &mut names)?);
    o.insert("path".into(), skeleton::path(&mut r, &mut names)?);
    o.insert("physics".into(), skeleton::physics(&mut r, &mut names)?);
    let skins_at = r.pos();
    let mut skins = skins::skins(&mut r, &mut names, nonessential)?;
    name_linked_skins(&mut skins, &names.skins, skins_at)?;
    o.insert("skins".into(), skins);
    o.insert("events".into(), skins::events(&mut r, &mut names)?);
    o.insert("animations".into(), animations::animations(&mut r, &names)?);
    if r.left() > 0 {
        r.at = String::new();
        return Err(r.fail("end", &format!("bytes after the last animation (got {})", r.left())));
    }
    Ok(Value::Object(o))
}

/// A linked mesh's `skin` is an index into the skins, read before the later skins are: named
/// once all are read.
fn name_linked_skins(skins: &mut Value, names: &[String], at: usize) -> Result<(), Error> {
    let Value::Array(list) = skins else { return Ok(()) };
    for skin in list {
        let Some(Value::Object(slots)) = skin.get_mut("attachments") else { continue };
        for (slot, attachments) in slots.iter_mut() {
            let Value::Object(attachments) = attachments else { continue };
            for (key, a) in attachments.iter_mut() {
                if a.get("type").and_then(Value::as_str) != Some("linkedmesh") {
                    continue;
                }
                let i = a.get("skin").and_then(Value::as_u64).unwrap_or_default();
                let name = usize::try_from(i).ok().and_then(|i| names.get(i)).ok_or_else(|| {
                    Error::input({
                        format!(
                            "skel: byte {at}: skins: attachments[{slot:?}][{key:?}].skin: skin index {i} out of {}",
                            names.len()
                        )
                    })
                })?;
                a["skin"] = Value::from(name.clone());
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;

/// The text of a file given where a character may be (`--rig FILE`), from its bytes: a JSON
/// file (its first character, after a byte-order mark and white space, is `{`) as it is; else
/// the bytes are tried as Spine's binary export ([`to_json`]) and, when they decode,
/// given as the JSON text of the same skeleton (its floats read back to the same bits); else,
/// UTF-8 text (a rig file, an atlas) as it is, and anything else is refused with what the
/// binary reader found, after `label` (and that it is not UTF-8 either, when the binary
/// reader stopped in the header).
pub fn text_of(bytes: Vec<u8>, label: &str) -> Result<String, Error> {
    let start = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(&bytes);
    if start.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'{') {
        return String::from_utf8(bytes).map_err(|e| {
            Error::input(format!("{label}: cannot read: not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
        });
    }
    match to_json(&bytes) {
        Ok(tree) => serde_json::to_string(&tree).map_err(|e| Error::input(format!("{label}: {e}"))),
        Err(binary) => String::from_utf8(bytes).map_err(|e| {
            // A file whose header is not a 4.2 binary export's is more likely neither.
            let at = e.utf8_error().valid_up_to();
            Error::input(if binary.to_string().contains(": skeleton.") {
                format!("{label}: cannot read: not UTF-8 text (byte {at}), nor a Spine 4.2 binary export ({binary})")
            } else {
                format!("{label}: {binary}")
            })
        }),
    }
}
