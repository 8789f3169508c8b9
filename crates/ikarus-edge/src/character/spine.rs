//! Spine's JSON export (4.0–4.2; 3.8 names a bone's inherit mode `transform` and writes its
//! curves normalised): bones, IK constraints, transform constraints
//! ([`super::spine_transform`]), the path and physics constraints' names (left inactive), the
//! skins and what only a skin turns on (`"skin": true` on a bone or constraint,
//! [`super::spine_skins`]), and the animations ([`super::clips`]).
//!
//! Defaults as the format has them: a bone's `length`, `x`, `y`, `rotation`, `shearX`,
//! `shearY` 0, `scaleX`, `scaleY` 1, `inherit` `normal`; an IK constraint's `order` 0, `mix` 1,
//! `softness` 0, `bendPositive` true, `compress`, `stretch`, `uniform`, `skin` false. Degrees become
//! radians. The `skeleton` object's `x`, `y`, `width` and `height` are the bounds of the setup
//! pose's attachments, not a placement: the character is placed at the origin, unscaled; its
//! `referenceScale` (default 100) is the distance physics forces are given in.

use std::collections::HashMap;

use ikarus::character::{
    CharacterBone, CharacterParts, Constraint, IkBones, IkConstraint, IkRule, IkSettings, Inherit, LocalTransform,
    SkinRequired, Unsupported,
};
use serde::Deserialize;
use serde_json::Value;

use super::clips::{self, Ordered};
use super::{Format, Loaded};
use crate::error::Error;
use crate::names::Quoted;
use crate::rig::BoneCap;

#[derive(Deserialize)]
struct SpineFile {
    skeleton: Skeleton,
    bones: Vec<BoneJson>,
    #[serde(default)]
    ik: Vec<IkJson>,
    #[serde(default)]
    transform: Vec<super::spine_transform::TransformJson>,
    #[serde(default)]
    path: Vec<super::spine_path::PathJson>,
    #[serde(default)]
    animations: Ordered<clips::Animation>,
    #[serde(default)]
    skins: super::spine_skins::SkinsJson,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Skeleton {
    spine: String,
    /// The distance physics forces are given in (absent: the runtime's 100).
    #[serde(default)]
    reference_scale: Option<f64>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct BoneJson {
    name: String,
    #[serde(default)]
    parent: Option<String>,
    #[serde(default)]
    length: f64,
    #[serde(default)]
    x: f64,
    #[serde(default)]
    y: f64,
    #[serde(default)]
    rotation: f64,
    #[serde(default = "super::one")]
    scale_x: f64,
    #[serde(default = "super::one")]
    scale_y: f64,
    #[serde(default)]
    shear_x: f64,
    #[serde(default)]
    shear_y: f64,
    #[serde(default)]
    inherit: Option<InheritJson>,
    /// 3.8's name of `inherit`.
    #[serde(default)]
    transform: Option<InheritJson>,
    /// Whether only a skin that lists it turns it on.
    #[serde(default)]
    skin: bool,
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "camelCase")]
enum InheritJson {
    Normal,
    OnlyTranslation,
    NoRotationOrReflection,
    NoScale,
    NoScaleOrReflection,
}

impl From<InheritJson> for Inherit {
    fn from(i: InheritJson) -> Self {
        match i {
            InheritJson::Normal => Inherit::Normal,
            InheritJson::OnlyTranslation => Inherit::OnlyTranslation,
            InheritJson::NoRotationOrReflection => Inherit::NoRotationOrReflection,
            InheritJson::NoScale => Inherit::NoScale,
            InheritJson::NoScaleOrReflection => Inherit::NoScaleOrReflection,
        }
    }
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct IkJson {
    name: String,
    #[serde(default)]
    order: u32,
    bones: Vec<String>,
    target: String,
    #[serde(default = "super::one")]
    mix: f64,
    #[serde(default)]
    softness: f64,
    #[serde(default = "super::yes")]
    bend_positive: bool,
    #[serde(default)]
    compress: bool,
    #[serde(default)]
    stretch: bool,
    #[serde(default)]
    uniform: bool,
    /// Whether only a skin that lists it turns it on.
    #[serde(default)]
    skin: bool,
}

/// Reads a Spine file (`value` is its text parsed, for the cap and the clips' durations).
pub(super) fn read(text: &str, value: &Value, cap: BoneCap) -> Result<Loaded, Error> {
    super::count(value.get("bones"), cap)?;
    let constraints = ["ik", "transform", "path", "physics"].map(|k| super::length(value.get(k))).iter().sum();
    super::constraints_within("ik, transform, path, physics", constraints, super::length(value.get("bones")))?;
    let file: SpineFile = super::typed(text)?;
    let version = file.skeleton.spine.clone();
    let legacy = version.starts_with("3.");
    let mut warnings = Vec::new();
    if !(version.starts_with("3.8") || ["4.0", "4.1", "4.2"].iter().any(|v| version.starts_with(v))) {
        warnings.push(format!(
            "skeleton.spine: {:?} is not a version ikarus was made for (3.8, 4.0 to 4.2); read as {}",
            Quoted(&version),
            if legacy { "3.8" } else { "4.2" }
        ));
    }
    let named: Vec<(&str, Option<&str>)> = file.bones.iter().map(|b| (b.name.as_str(), b.parent.as_deref())).collect();
    let super::Tree { parents: parent_of, index } = super::parents(&named, |i| format!("bones[{i}]"))?;
    if let Some((i, b)) = file.bones.iter().enumerate().find(|(_, b)| b.length < 0.0) {
        return Err(Error::input(format!(
            "bones[{i}] ({:?}).length = {}: must not be negative",
            Quoted(&b.name),
            b.length
        )));
    }
    let bones = file.bones.iter().zip(parent_of.iter().copied()).map(|(b, parent)| bone(b, parent)).collect();
    let constraints = file
        .ik
        .iter()
        .enumerate()
        .map(|(i, k)| {
            constraint(k, &index, &format!("ik[{i}] ({:?})", Quoted(&k.name)), &parent_of).map(Constraint::Ik)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut constraints = constraints;
    // The other kinds after the IK ones (whose indices the page and the API use), in the order
    // the file lists its kinds (ties of `order` apply as listed).
    let first_transform = constraints.len();
    constraints.extend(super::spine_transform::read(&file.transform, &index)?.into_iter().map(Constraint::Transform));
    let slots = super::spine_slots::read(value, &index)?;
    let first_path = constraints.len();
    for (i, k) in file.path.iter().enumerate() {
        constraints.push(Constraint::Path(super::spine_path::constraint(i, k, &index, &slots)?));
    }
    let path_names: HashMap<&str, usize> =
        super::first_index(file.path.iter().map(|k| k.name())).into_iter().map(|(n, i)| (n, first_path + i)).collect();
    let targets: Vec<(usize, usize, Option<&str>)> = constraints[first_path..]
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match c {
            Constraint::Path(p) => Some((first_path + i, p.slot, slots.slots[p.slot].attachment.as_deref())),
            Constraint::Ik(_) | Constraint::Physics(_) | Constraint::Transform(_) => None,
        })
        .collect();
    let physics = super::spine_physics::read(value, &index)?;
    let first_physics = constraints.len();
    constraints.extend(physics.iter().cloned().map(Constraint::Physics));
    let physics_names: HashMap<&str, usize> = super::first_index(physics.iter().map(|k| k.name.as_str()))
        .into_iter()
        .map(|(name, i)| (name, first_physics + i))
        .collect();
    let unsupported = super::spine_unsupported::features(value);
    let (mut art, inherits) = super::spine_art::read(value, &slots, index.len())?;
    let ik_names = super::first_index(file.ik.iter().map(|k| k.name.as_str()));
    let transform_names: HashMap<&str, usize> = super::first_index(file.transform.iter().map(|k| k.name.as_str()))
        .into_iter()
        .map(|(name, i)| (name, first_transform + i))
        .collect();
    let names = clips::Names { bones: &index, constraints: &ik_names, transforms: &transform_names };
    let skin_names = super::spine_skins::SkinNames {
        bones: &index,
        ik: &ik_names,
        transform: &transform_names,
        path: &path_names,
        physics: &physics_names,
    };
    let skins = super::spine_skins::read(&file.skins, &skin_names)?;
    let skin_required = SkinRequired {
        bones: file.bones.iter().enumerate().filter(|(_, b)| b.skin).map(|(i, _)| i).collect(),
        constraints: (file.ik.iter().map(|k| k.skin))
            .chain(file.transform.iter().map(|k| k.skin))
            .chain(file.path.iter().map(|k| k.skin()))
            .chain(physics.iter().map(|k| k.skin))
            .enumerate()
            .filter(|(_, skin)| *skin)
            .map(|(k, _)| k)
            .collect(),
    };
    let clips = file
        .animations
        .0
        .iter()
        .map(|(name, animation)| {
            let json = &value["animations"][name];
            let duration = super::latest_time(json);
            let mut clip = clips::clip(name, animation, duration, &names, legacy)?;
            let deforms = super::spine_deform::read(json, name, &slots)?;
            let at = format!("animations.{:?}", Quoted(name));
            let paths = super::spine_path_clips::read(json, &at, &path_names, &targets, &deforms, legacy)?;
            clip.constraints.extend(paths);
            let keys = super::spine_physics::clip_timelines(json, &physics, first_physics, &at)?;
            clip.constraints.extend(keys);
            let slot_clip = super::spine_slot_clips::read(json, (name, &at), &slots, (&art, &inherits), legacy)?;
            Ok::<_, Error>((clip, slot_clip))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let (clips, slot_clips): (Vec<_>, Vec<_>) = clips.into_iter().unzip();
    art.clips = slot_clips;
    if !unsupported.is_empty() {
        warnings.push(inactive(&unsupported));
    }
    let parts = CharacterParts {
        bones,
        constraints,
        clips,
        unsupported,
        skins,
        skin_required,
        art,
        ..CharacterParts::default()
    };
    let mut character = super::character(parts)?;
    if let Some(r) = file.skeleton.reference_scale {
        character = character.with_reference_scale(r).map_err(|e| Error::input(e.to_string()))?;
    }
    Ok(Loaded { character, format: Format::Spine, version, warnings })
}

/// `not used by ikarus (left out): bounding box attachment "bb (skin default, slot hand)", …`.
pub(super) fn inactive(unsupported: &[Unsupported]) -> String {
    let list: Vec<String> = unsupported.iter().map(|u| format!("{} {:?}", u.kind, Quoted(&u.name))).collect();
    format!("not used by ikarus (left out): {}", list.join(", "))
}

fn bone(b: &BoneJson, parent: Option<usize>) -> CharacterBone {
    CharacterBone {
        name: b.name.clone(),
        parent,
        length: b.length,
        setup: LocalTransform {
            x: b.x,
            y: b.y,
            rotation: b.rotation.to_radians(),
            scale_x: b.scale_x,
            scale_y: b.scale_y,
            shear_x: b.shear_x.to_radians(),
            shear_y: b.shear_y.to_radians(),
        },
        inherit: b.inherit.or(b.transform).map_or(Inherit::Normal, Inherit::from),
    }
}

fn constraint(
    k: &IkJson,
    index: &HashMap<String, usize>,
    at: &str,
    parent_of: &[Option<usize>],
) -> Result<IkConstraint, Error> {
    let bones = match k.bones.as_slice() {
        [one] => IkBones::One(super::bone(index, one, &format!("{at}.bones[0]"))?),
        [first, second] => {
            let parent = super::bone(index, first, &format!("{at}.bones[0]"))?;
            let child = super::bone(index, second, &format!("{at}.bones[1]"))?;
            if parent_of[child] != Some(parent) {
                return Err(Error::input(format!(
                    "{at}.bones[1] = {:?}: not a child of {:?}",
                    Quoted(second),
                    Quoted(first)
                )));
            }
            IkBones::Two { parent, child }
        }
        other => return Err(Error::input(format!("{at}.bones: expected one or two bones, got {}", other.len()))),
    };
    let target = super::bone(index, &k.target, &format!("{at}.target"))?;
    if !(0.0..=1.0).contains(&k.mix) {
        return Err(Error::input(format!("{at}.mix = {}: must be within 0 and 1", k.mix)));
    }
    if k.softness < 0.0 {
        return Err(Error::input(format!("{at}.softness = {}: must not be negative", k.softness)));
    }
    Ok(IkConstraint {
        name: k.name.clone(),
        order: k.order,
        bones,
        target,
        setup: IkSettings {
            mix: k.mix,
            softness: k.softness,
            bend_positive: k.bend_positive,
            compress: k.compress,
            stretch: k.stretch,
        },
        uniform: k.uniform,
        rule: IkRule::Spine,
    })
}
