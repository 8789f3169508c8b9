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
    /// Every bone's setup pose, parents before children.
    pub bones: Vec<CharacterBoneJson>,
    /// The IK constraints, with their bones, target and settings.
    pub ik: Vec<IkJson>,
    /// The animation clips.
    pub clips: Vec<ClipJson>,
    /// Every constraint of every kind, in the order they apply (IK ones are also in `ik`, with
    /// their settings).
    pub constraints: Vec<ConstraintJson>,
    /// The skins' names; a pose takes the one called `default` unless told otherwise.
    pub skins: Vec<String>,
    /// What the file has that ikarus does not use.
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
    /// The bone's name.
    pub name: String,
    /// Its parent's name; `null` for a root.
    pub parent: Option<String>,
    /// Its length.
    pub length: f64,
    /// Its x in its parent's frame.
    pub x: f64,
    /// Its y in its parent's frame, y up.
    pub y: f64,
    /// Its rotation from its parent's direction, degrees.
    pub rotation_deg: f64,
    /// Its scale along its own x.
    pub scale_x: f64,
    /// Its scale along its own y.
    pub scale_y: f64,
    /// Its shear of x, degrees.
    pub shear_x_deg: f64,
    /// Its shear of y, degrees.
    pub shear_y_deg: f64,
    /// Spine's name of the mode (`normal`, `noScale`, …).
    pub inherit: &'static str,
}

/// An IK constraint, its bones and target by name.
#[derive(Debug, Serialize)]
pub struct IkJson {
    /// The constraint's name.
    pub name: String,
    /// Where it applies among all the constraints (lower first).
    pub order: u32,
    /// One bone, or the parent then the child.
    pub bones: Vec<String>,
    /// The bone its chain reaches for.
    pub target: String,
    /// How much of the solved rotation it applies: 0 none, 1 all.
    pub mix: f64,
    /// The distance from the target at which the two bones start to straighten softly; 0 off.
    pub softness: f64,
    /// Which way a two-bone chain bends: `true` for the positive bend direction.
    pub bend_positive: bool,
    /// Whether a bone shrinks when the target is nearer than it reaches.
    pub compress: bool,
    /// Whether a bone stretches when the target is further than it reaches.
    pub stretch: bool,
    /// Whether a stretching or compressing bone scales in y too.
    pub uniform: bool,
    /// Whose rules it follows: `spine` or `dragonbones`.
    pub rule: &'static str,
}

/// A constraint of any kind: `{"kind": "transform", "name": "aim", "order": 9}`.
#[derive(Debug, Serialize)]
pub struct ConstraintJson {
    /// `ik`, `transform`, `path` or `physics`.
    pub kind: &'static str,
    /// The constraint's name.
    pub name: String,
    /// Where it applies among all the constraints (lower first).
    pub order: u32,
}

/// A clip's name and duration, seconds.
#[derive(Debug, Serialize)]
pub struct ClipJson {
    /// The clip's name.
    pub name: String,
    /// Its duration, seconds.
    pub duration: f64,
}

/// What the file has and ikarus does not use: `{"kind": "bounding box attachment", "name": "…"}`.
#[derive(Debug, Serialize)]
pub struct UnsupportedJson {
    /// What kind of thing it is (`bounding box attachment`, …).
    pub kind: String,
    /// Its name in the file.
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
