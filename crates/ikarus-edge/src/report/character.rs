//! A character file (Spine, DragonBones) as JSON (`POST /api/rig/parse`): its format, bones
//! with their setup transforms (degrees), IK constraints by name, clips with their durations,
//! and what ikarus leaves out.

use ikarus::character::{Character, IkBones};
use serde::Serialize;

use crate::character::Loaded;

/// `{"format", "version", "bones", "ik", "clips", "unsupported", "warnings"}`.
#[derive(Debug, Serialize)]
pub struct CharacterJson {
    /// `spine` or `dragonbones`.
    pub format: &'static str,
    /// The version the file names.
    pub version: String,
    pub bones: Vec<CharacterBoneJson>,
    pub ik: Vec<IkJson>,
    pub clips: Vec<ClipJson>,
    /// Every constraint of every kind, in the order they apply (IK ones are also in `ik`, with
    /// their settings).
    pub constraints: Vec<ConstraintJson>,
    /// The skins' names; a pose takes the one called `default` unless told otherwise.
    pub skins: Vec<String>,
    pub unsupported: Vec<UnsupportedJson>,
    /// The lines a command prints on stderr for this file.
    pub warnings: Vec<String>,
    /// Where the server (or the WebAssembly module) keeps the character read: requests give
    /// `"character": ID` instead of the file's text ([`crate::character::store`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
}

/// A bone's setup pose in its parent's frame, y up, angles in degrees.
#[derive(Debug, Serialize)]
pub struct CharacterBoneJson {
    pub name: String,
    pub parent: Option<String>,
    pub length: f64,
    pub x: f64,
    pub y: f64,
    pub rotation_deg: f64,
    pub scale_x: f64,
    pub scale_y: f64,
    pub shear_x_deg: f64,
    pub shear_y_deg: f64,
    /// Spine's name of the mode (`normal`, `noScale`, …).
    pub inherit: &'static str,
}

/// An IK constraint, its bones and target by name.
#[derive(Debug, Serialize)]
pub struct IkJson {
    pub name: String,
    pub order: u32,
    /// One bone, or the parent then the child.
    pub bones: Vec<String>,
    pub target: String,
    pub mix: f64,
    pub softness: f64,
    pub bend_positive: bool,
    pub compress: bool,
    pub stretch: bool,
    pub uniform: bool,
    /// Whose rules it follows: `spine` or `dragonbones`.
    pub rule: &'static str,
}

/// A constraint of any kind: `{"kind": "transform", "name": "aim", "order": 9}`.
#[derive(Debug, Serialize)]
pub struct ConstraintJson {
    /// `ik`, `transform`, `path` or `physics`.
    pub kind: &'static str,
    pub name: String,
    pub order: u32,
}

/// A clip's name and duration, seconds.
#[derive(Debug, Serialize)]
pub struct ClipJson {
    pub name: String,
    pub duration: f64,
}

/// What the file has and ikarus does not use: `{"kind": "bounding box attachment", "name": "…"}`.
#[derive(Debug, Serialize)]
pub struct UnsupportedJson {
    pub kind: String,
    pub name: String,
}

impl CharacterJson {
    /// The JSON of a loaded character file.
    #[must_use]
    pub fn new(loaded: &Loaded) -> Self {
        let c: &Character = &loaded.character;
        let name = |i: usize| c.bones()[i].name.clone();
        let bones = c
            .bones()
            .iter()
            .map(|b| CharacterBoneJson {
                name: b.name.clone(),
                parent: b.parent.map(name),
                length: b.length,
                x: b.setup.x,
                y: b.setup.y,
                rotation_deg: b.setup.rotation.to_degrees(),
                scale_x: b.setup.scale_x,
                scale_y: b.setup.scale_y,
                shear_x_deg: b.setup.shear_x.to_degrees(),
                shear_y_deg: b.setup.shear_y.to_degrees(),
                inherit: b.inherit.as_str(),
            })
            .collect();
        let ik = c
            .ik_constraints()
            .map(|(_, k)| IkJson {
                name: k.name.clone(),
                order: k.order,
                bones: match k.bones {
                    IkBones::One(b) => vec![name(b)],
                    IkBones::Two { parent, child } => vec![name(parent), name(child)],
                },
                target: name(k.target),
                mix: k.setup.mix,
                softness: k.setup.softness,
                bend_positive: k.setup.bend_positive,
                compress: k.setup.compress,
                stretch: k.setup.stretch,
                uniform: k.uniform,
                rule: match k.rule {
                    ikarus::character::IkRule::Spine => "spine",
                    ikarus::character::IkRule::DragonBones => "dragonbones",
                },
            })
            .collect();
        CharacterJson {
            format: loaded.format.as_str(),
            version: loaded.version.clone(),
            bones,
            ik,
            clips: c.clips().iter().map(|k| ClipJson { name: k.name.clone(), duration: k.duration }).collect(),
            constraints: c
                .order()
                .iter()
                .map(|&k| {
                    let k = &c.constraints()[k];
                    ConstraintJson { kind: k.kind(), name: k.name().to_owned(), order: k.order() }
                })
                .collect(),
            skins: c.skins().iter().map(|s| s.name.clone()).collect(),
            unsupported: c
                .unsupported()
                .iter()
                .map(|u| UnsupportedJson { kind: u.kind.clone(), name: u.name.clone() })
                .collect(),
            warnings: loaded.warnings.clone(),
            id: None,
        }
    }
}
