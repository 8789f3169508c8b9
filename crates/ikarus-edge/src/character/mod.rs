//! Character files: Spine (4.0–4.2 JSON, and 3.8's) and DragonBones (5.x JSON) skeletons,
//! read into the library's [`Character`].
//!
//! The format is told from the content, not the file's name ([`detect`]): a Spine file has a
//! `skeleton` object with a `spine` version string and a `bones` array; a DragonBones file an
//! `armature` array beside its `version` or `frameRate`. Every problem is one line naming the
//! field's path and the value (`bones[3] ("foot").parent = "hip": no bone of that name`), after the label, as rig
//! files' are. `spine` and `dragonbones` read their format; `clips` reads Spine's
//! animations.
//!
//! What is read: bones (local transforms, inherit modes), IK constraints with all their
//! settings, and the animations' bone and IK timelines (Spine's by `clips`, DragonBones' by
//! `dragonbones_clips`), Spine's slots and region, mesh and linked mesh attachments
//! (`spine_art`, drawn by [`Character::draw_list`]) and texture atlases ([`atlas`]), with their
//! pages' images made into the renderer's art by [`art_draw`]. What is not: events, and the
//! slot timelines (attachment, colour, draw order, deform of meshes); what is not drawn or used
//! is listed in [`Character::unsupported`].

pub mod art_draw;
pub mod art_json;
pub mod atlas;
mod clips;
mod dragonbones;
mod dragonbones_clips;
pub mod export;
pub mod ik_file;
pub mod motion;
pub mod motion_art;
pub mod motion_files;
pub mod motion_play;
pub mod skel;
pub use skel::text_of;
mod spine;
mod spine_art;
mod spine_deform;
mod spine_path;
mod spine_path_clips;
pub mod spine_physics;
mod spine_skins;
mod spine_slot_clips;
mod spine_slots;
mod spine_transform;
mod spine_unsupported;
pub mod store;

use std::collections::HashMap;

use ikarus::character::{Character, CharacterError, CharacterParts};
use serde::de::DeserializeOwned;
use serde_json::Value;

use crate::error::Error;
use crate::names::Quoted;
use crate::rig::BoneCap;

/// The format of a character file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Spine's JSON export (4.0–4.2, or 3.8).
    Spine,
    /// DragonBones' JSON (5.x).
    DragonBones,
}

impl Format {
    /// `spine` or `dragonbones`, as the API's answers name it.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Format::Spine => "spine",
            Format::DragonBones => "dragonbones",
        }
    }

    /// `Spine` or `DragonBones`, as messages name it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Format::Spine => "Spine",
            Format::DragonBones => "DragonBones",
        }
    }
}

/// A character file, read.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The character.
    pub character: Character,
    /// The file's format.
    pub format: Format,
    /// The version the file says it was written by (Spine's `skeleton.spine`, DragonBones'
    /// `version`).
    pub version: String,
    /// Lines for the user (one each, without the label): what was left out of the file, a
    /// version ikarus was not made for.
    pub warnings: Vec<String>,
}

/// Whether `text` is JSON rather than a rig file (TOML), from its first character: a TOML
/// document never starts with `{`.
#[must_use]
pub fn is_json(text: &str) -> bool {
    text.trim_start_matches('\u{feff}').trim_start().starts_with('{')
}

/// Reads a character file's text under the command line's cap on bones; `label` starts every
/// error message (`rig file spineboy.json`).
pub fn load(text: &str, label: &str) -> Result<Loaded, Error> {
    load_within(text, label, BoneCap::cli())
}

/// Reads a character file's text of at most `cap` bones (counted before any bone is read);
/// `label` starts every error message.
pub fn load_within(text: &str, label: &str, cap: BoneCap) -> Result<Loaded, Error> {
    let fail = |msg: &dyn std::fmt::Display| Error::input(format!("{label}: {msg}"));
    let text = text.trim_start_matches('\u{feff}');
    let value: Value = serde_json::from_str(text).map_err(|e| fail(&format!("malformed JSON: {e}")))?;
    match detect(&value) {
        Some(Format::Spine) => spine::read(text, &value, cap).map_err(|e| fail(&e)),
        Some(Format::DragonBones) => dragonbones::read(text, &value, cap).map_err(|e| fail(&e)),
        None => Err(fail(
            &"not a character file: expected a Spine skeleton (a \"skeleton\" object with a \"spine\" version \
             and a \"bones\" array) or a DragonBones 5 file (an \"armature\" array beside \"version\" or \
             \"frameRate\")"
                .to_owned(),
        )),
    }
}

/// For a rig's commands (`--rig FILE`): nothing for a rig file (not JSON); a character file is
/// read (a bad one is its line) and refused saying what it is, since they take rig files.
pub fn not_a_rig(text: &str, label: &str) -> Result<(), Error> {
    if !is_json(text) {
        return Ok(());
    }
    let loaded = load(text, label)?;
    let c = &loaded.character;
    Err(Error::input(format!(
        "{label}: a {} character ({} bones, {} IK constraints), which this command does not take: it takes rig files (TOML); pose, solve, animate and track take characters",
        loaded.format.name(),
        c.bones().len(),
        c.ik_constraints().count()
    )))
}

/// The format of a parsed JSON document, from its content.
#[must_use]
pub fn detect(value: &Value) -> Option<Format> {
    let spine = value.get("skeleton").and_then(|s| s.get("spine")).is_some_and(Value::is_string)
        && value.get("bones").is_some_and(Value::is_array);
    let dragonbones = value.get("armature").is_some_and(Value::is_array)
        && (value.get("version").is_some() || value.get("frameRate").is_some());
    match (spine, dragonbones) {
        (true, _) => Some(Format::Spine),
        (false, true) => Some(Format::DragonBones),
        (false, false) => None,
    }
}

/// A boolean, or the string `"true"` or `"false"` (as some exports write `bendPositive`).
fn flag<'de, D: serde::Deserializer<'de>>(d: D) -> Result<bool, D::Error> {
    match <Value as serde::Deserialize>::deserialize(d)? {
        Value::Bool(b) => Ok(b),
        Value::String(t) if t == "true" => Ok(true),
        Value::String(t) if t == "false" => Ok(false),
        other => Err(serde::de::Error::custom(format_args!("expected true or false, got {other}"))),
    }
}

/// The default of a scale, a mix, a weight.
fn one() -> f64 {
    1.0
}

/// The default of `bendPositive` and DragonBones' inherit flags.
fn yes() -> bool {
    true
}

/// The text as a `T`, each refusal naming the field's path and the value
/// (`bones[3].rotation: invalid type: string "x", expected f64 at line 9 column 22`).
#[cfg(feature = "field-paths")]
fn typed<T: DeserializeOwned>(text: &str) -> Result<T, Error> {
    serde_path_to_error::deserialize(&mut serde_json::Deserializer::from_str(text))
        .map_err(|e| Error::input(e.to_string()))
}

/// The text as a `T`, each refusal serde_json's line (without the `field-paths` feature).
#[cfg(not(feature = "field-paths"))]
fn typed<T: DeserializeOwned>(text: &str) -> Result<T, Error> {
    serde::Deserialize::deserialize(&mut serde_json::Deserializer::from_str(text))
        .map_err(|e| Error::input(e.to_string()))
}

/// The bones' names to their indices, each parent resolved to an earlier bone: `names[i]` is
/// bone `i`'s name and parent's name, `at(i)` its path in the file (`bones[3]`). Refused: a
/// name used twice, a parent that is not a bone, a parent listed after its child.
fn parents(bones: &[(&str, Option<&str>)], at: impl Fn(usize) -> String) -> Result<Tree, Error> {
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut out = Vec::with_capacity(bones.len());
    for (i, (name, _)) in bones.iter().enumerate() {
        if let Some(first) = index.insert((*name).to_owned(), i) {
            return Err(Error::input(format!("{}.name = {:?}: also the name of {}", at(i), Quoted(name), at(first))));
        }
    }
    for (i, (_, parent)) in bones.iter().enumerate() {
        let p = match parent {
            None => None,
            Some(p) => match index.get(*p) {
                None => {
                    let (child, p) = (Quoted(bones[i].0), Quoted(p));
                    return Err(Error::input(format!("{} ({child:?}).parent = {p:?}: no bone of that name", at(i))));
                }
                Some(&j) if j >= i => {
                    let (child, p) = (Quoted(bones[i].0), Quoted(p));
                    return Err(Error::input(format!(
                        "{} ({child:?}).parent = {p:?}: listed after this bone (a parent comes first)",
                        at(i)
                    )));
                }
                Some(&j) => Some(j),
            },
        };
        out.push(p);
    }
    Ok(Tree { parents: out, index })
}

/// The bones' parents by index and their indices by name.
struct Tree {
    parents: Vec<Option<usize>>,
    index: HashMap<String, usize>,
}

/// The index of bone `name`, or `path = "name": no bone of that name`.
fn bone(index: &HashMap<String, usize>, name: &str, path: &str) -> Result<usize, Error> {
    index.get(name).copied().ok_or_else(|| Error::input(format!("{path} = {:?}: no bone of that name", Quoted(name))))
}

/// Names to the index of their first occurrence, in one pass (a lookup per timeline was a scan
/// of every constraint: quadratic in a file of many of both).
fn first_index<'a>(names: impl Iterator<Item = &'a str>) -> HashMap<&'a str, usize> {
    let mut index = HashMap::new();
    for (i, name) in names.enumerate() {
        index.entry(name).or_insert(i);
    }
    index
}

/// The bone count of a `bones` array, checked against the cap before anything is read.
fn count(bones: Option<&Value>, cap: BoneCap) -> Result<(), Error> {
    cap.check(length(bones))
}

/// How many constraints a file may have a bone (IK, transform, path and physics ones together),
/// and at least [`MIN_CONSTRAINT_CAP`] in all. Real characters have far fewer (spineboy: 7 for
/// 67 bones); each constraint is a pass over the bones below its own when the character is
/// posed, so their number bounds a pose's work with the bones' (600,000 constraints on 10,000
/// bones ran for minutes).
pub const CONSTRAINTS_PER_BONE: usize = 4;

/// The fewest constraints a file may have, however few its bones.
pub const MIN_CONSTRAINT_CAP: usize = 64;

/// The length of a JSON array (0 when it is absent or not one).
fn length(value: Option<&Value>) -> usize {
    value.and_then(Value::as_array).map_or(0, Vec::len)
}

/// `constraints` constraints for `bones` bones, refused past [`CONSTRAINTS_PER_BONE`] a bone
/// before anything is read: `fields: N constraints for B bones, more than the cap of C (4 a
/// bone, at least 64)`.
fn constraints_within(fields: &str, constraints: usize, bones: usize) -> Result<(), Error> {
    let cap = bones.saturating_mul(CONSTRAINTS_PER_BONE).max(MIN_CONSTRAINT_CAP);
    if constraints > cap {
        return Err(Error::input(format!(
            "{fields}: {constraints} constraints for {bones} bones, more than the cap of {cap} \
             ({CONSTRAINTS_PER_BONE} a bone, at least {MIN_CONSTRAINT_CAP})"
        )));
    }
    Ok(())
}

/// The character of checked parts; what the model still refuses (its messages name indices)
/// is said as it says it.
fn character(parts: CharacterParts) -> Result<Character, Error> {
    Character::new(parts).map_err(|e: CharacterError| Error::input(e.to_string()))
}

/// The latest `time` of any key anywhere under `value` (an animation): its duration as Spine's
/// runtime counts it, over every timeline, those ikarus does not read too.
fn latest_time(value: &Value) -> f64 {
    match value {
        Value::Object(map) => {
            let own = map.get("time").and_then(Value::as_f64).unwrap_or(0.0);
            map.values().map(latest_time).fold(own, f64::max)
        }
        Value::Array(items) => items.iter().map(latest_time).fold(0.0, f64::max),
        _ => 0.0,
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod art_tests;

#[cfg(test)]
mod caps_tests;

#[cfg(test)]
mod transform_tests;

#[cfg(test)]
mod skin_tests;

#[cfg(test)]
mod slot_clip_tests;

#[cfg(test)]
mod skin_mix_tests;
