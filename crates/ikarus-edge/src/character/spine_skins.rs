//! Spine's skins as far as posing goes: each skin's name and the skin-required bones and
//! constraints it turns on.
//!
//! 4.x (and 3.8) write `skins` as a list of `{name, bones, ik, transform, path, physics,
//! attachments}` (each list of names optional); older exports write an object of skins by name,
//! read here as names only. A bone or a constraint of any kind with `"skin": true` takes part
//! only while a chosen skin lists it ([`ikarus::character::SkinRequired`]); attachments are not
//! read here.

use std::collections::HashMap;

use ikarus::character::Skin;
use serde::Deserialize;
use serde::de::IgnoredAny;

use super::clips::Ordered;
use crate::error::Error;
use crate::names::Quoted;

/// The file's `skins`: a list (4.x, 3.8) or an object by name (older).
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum SkinsJson {
    /// `[{name, bones, ik, transform, …}]`.
    List(Vec<SkinJson>),
    /// `{name: {slot: {attachment: …}}}`.
    Object(Ordered<IgnoredAny>),
}

impl Default for SkinsJson {
    fn default() -> Self {
        SkinsJson::List(Vec::new())
    }
}

/// One skin of the list.
#[derive(Deserialize)]
pub(super) struct SkinJson {
    name: String,
    #[serde(default)]
    bones: Vec<String>,
    #[serde(default)]
    ik: Vec<String>,
    #[serde(default)]
    transform: Vec<String>,
    #[serde(default)]
    path: Vec<String>,
    #[serde(default)]
    physics: Vec<String>,
}

/// What a skin's names resolve to: the bones' indices, and the constraints' indices in the
/// character's one list of constraints, by kind.
pub(super) struct SkinNames<'a> {
    pub(super) bones: &'a HashMap<String, usize>,
    pub(super) ik: &'a HashMap<&'a str, usize>,
    pub(super) transform: &'a HashMap<&'a str, usize>,
    pub(super) path: &'a HashMap<&'a str, usize>,
    pub(super) physics: &'a HashMap<&'a str, usize>,
}

/// The skins of `skins`, names resolved: `skins[1] ("hero").bones[0] = "cape": no bone of that
/// name`, and the like for `ik` and `transform`.
pub(super) fn read(skins: &SkinsJson, names: &SkinNames<'_>) -> Result<Vec<Skin>, Error> {
    let list = match skins {
        SkinsJson::Object(by_name) => {
            return Ok(by_name.0.iter().map(|(name, _)| Skin { name: name.clone(), ..Skin::default() }).collect());
        }
        SkinsJson::List(list) => list,
    };
    list.iter()
        .enumerate()
        .map(|(i, s)| {
            let at = format!("skins[{i}] ({:?})", Quoted(&s.name));
            let bones = s
                .bones
                .iter()
                .enumerate()
                .map(|(j, b)| super::bone(names.bones, b, &format!("{at}.bones[{j}]")))
                .collect::<Result<Vec<_>, _>>()?;
            let mut constraints = Vec::new();
            for (field, list, index, kind) in [
                ("ik", &s.ik, names.ik, "IK constraint"),
                ("transform", &s.transform, names.transform, "transform constraint"),
                ("path", &s.path, names.path, "path constraint"),
                ("physics", &s.physics, names.physics, "physics constraint"),
            ] {
                for (j, name) in list.iter().enumerate() {
                    let k = index.get(name.as_str()).ok_or_else(|| {
                        Error::input(format!("{at}.{field}[{j}] = {:?}: no {kind} of that name", Quoted(name)))
                    })?;
                    constraints.push(*k);
                }
            }
            Ok(Skin { name: s.name.clone(), bones, constraints })
        })
        .collect()
}
