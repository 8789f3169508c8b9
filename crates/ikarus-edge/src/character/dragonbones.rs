//! DragonBones 5.x JSON: the first armature's bones and IK constraints.
//!
//! DragonBones' y points down; the model's up. A bone's `transform {x, y, skX, skY, scX, scY}`
//! (degrees; scales default 1) has the local matrix `[[cos skY·scX, −sin skX·scY], [sin skY·scX,
//! cos skX·scY]]` in y-down terms. Flipped (`F·M·F` with `F = diag(1, −1)`), its x axis is
//! `(cos −skY, sin −skY)·scX` and its y axis `(−sin(−skX), cos(−skX))·scY`: rotation `−skY`, shear
//! x 0, shear y `−(skX − skY)`, origin `(x, −y)`. Products of flipped matrices are the flipped
//! products, so world transforms flip the same way.
//!
//! `inheritTranslation`, `inheritRotation`, `inheritScale`, `inheritReflection` (all true by
//! default) become the inherit mode that matches them; a combination no mode matches gets the
//! nearest, listed in [`Character::unsupported`](ikarus::character::Character::unsupported) as
//! kind `inherit`. IK `{name, bone, target, chain, bendPositive, weight}`: `bone` is the END
//! bone, `chain` 0 one bone, 1 it and its parent; `bendPositive` is true by default, a boolean
//! or the string `"true"`/`"false"`, kept as the file has it (in DragonBones' y-down frame); the
//! constraints apply in the order listed. Animations are read by [`super::dragonbones_clips`].

use ikarus::character::{
    CharacterBone, CharacterParts, Constraint, IkBones, IkConstraint, IkRule, IkSettings, Inherit, LocalTransform,
    Unsupported,
};
use serde::Deserialize;
use serde_json::Value;

use super::dragonbones_clips::{self, AnimationJson, Context, Notes};
use super::{Format, Loaded};
use crate::error::Error;
use crate::names::Quoted;
use crate::rig::BoneCap;

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct DragonBonesFile {
    #[serde(default)]
    version: Option<String>,
    #[serde(default)]
    frame_rate: Option<f64>,
    armature: Vec<Armature>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Armature {
    #[serde(default)]
    frame_rate: Option<f64>,
    #[serde(default)]
    bone: Vec<BoneJson>,
    #[serde(default)]
    ik: Vec<IkJson>,
    #[serde(default)]
    animation: Vec<AnimationJson>,
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
    transform: TransformJson,
    #[serde(default = "super::yes")]
    inherit_translation: bool,
    #[serde(default = "super::yes")]
    inherit_rotation: bool,
    #[serde(default = "super::yes")]
    inherit_scale: bool,
    #[serde(default = "super::yes")]
    inherit_reflection: bool,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct TransformJson {
    #[serde(default)]
    x: f64,
    #[serde(default)]
    y: f64,
    #[serde(default)]
    sk_x: f64,
    #[serde(default)]
    sk_y: f64,
    #[serde(default = "super::one")]
    sc_x: f64,
    #[serde(default = "super::one")]
    sc_y: f64,
}

impl Default for TransformJson {
    fn default() -> Self {
        TransformJson { x: 0.0, y: 0.0, sk_x: 0.0, sk_y: 0.0, sc_x: 1.0, sc_y: 1.0 }
    }
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct IkJson {
    name: String,
    bone: String,
    target: String,
    #[serde(default)]
    chain: u32,
    #[serde(default = "super::yes", deserialize_with = "super::flag")]
    bend_positive: bool,
    #[serde(default = "super::one")]
    weight: f64,
}

/// Reads a DragonBones file's first armature (`value` is its text parsed, for the caps: the
/// bones and constraints of every armature count, since every armature is parsed).
pub(super) fn read(text: &str, value: &Value, cap: BoneCap) -> Result<Loaded, Error> {
    let armatures = value.get("armature").and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
    let bones = armatures.iter().map(|a| super::length(a.get("bone"))).sum();
    cap.check(bones)?;
    let constraints = armatures.iter().map(|a| super::length(a.get("ik"))).sum();
    super::constraints_within("armature[].ik", constraints, bones)?;
    let file: DragonBonesFile = super::typed(text)?;
    let version = file.version.unwrap_or_default();
    let mut warnings = Vec::new();
    if !version.starts_with('5') {
        warnings
            .push(format!("version: {:?} is not a version ikarus was made for (5.x); read as 5.5", Quoted(&version)));
    }
    let Some(armature) = file.armature.into_iter().next() else {
        return Err(Error::input("armature: expected at least one armature, got none"));
    };
    let named: Vec<(&str, Option<&str>)> =
        armature.bone.iter().map(|b| (b.name.as_str(), b.parent.as_deref())).collect();
    let at = |i: usize| format!("armature[0].bone[{i}]");
    let super::Tree { parents: parent_of, index } = super::parents(&named, at)?;
    if let Some((i, b)) = armature.bone.iter().enumerate().find(|(_, b)| b.length < 0.0) {
        return Err(Error::input(format!(
            "{} ({:?}).length = {}: must not be negative",
            at(i),
            Quoted(&b.name),
            b.length
        )));
    }
    let mut unsupported = Vec::new();
    let mut bones = Vec::with_capacity(armature.bone.len());
    for (b, parent) in armature.bone.iter().zip(parent_of.iter().copied()) {
        let (inherit, exact) = inherit(b);
        if !exact {
            unsupported.push(Unsupported { kind: "inherit mode".to_owned(), name: b.name.clone() });
        }
        let t = &b.transform;
        let setup = LocalTransform {
            x: t.x,
            y: -t.y,
            rotation: (-t.sk_y).to_radians(),
            scale_x: t.sc_x,
            scale_y: t.sc_y,
            shear_x: 0.0,
            shear_y: (t.sk_y - t.sk_x).to_radians(),
        };
        bones.push(CharacterBone { name: b.name.clone(), parent, length: b.length, setup, inherit });
    }
    let mut constraints = Vec::with_capacity(armature.ik.len());
    for (i, k) in armature.ik.iter().enumerate() {
        let at = format!("armature[0].ik[{i}] ({:?})", Quoted(&k.name));
        let end = super::bone(&index, &k.bone, &format!("{at}.bone"))?;
        let bones = match (k.chain, parent_of[end]) {
            (0, _) => IkBones::One(end),
            (1, Some(parent)) => IkBones::Two { parent, child: end },
            (1, None) => return Err(Error::input(format!("{at}.chain = 1: bone {:?} has no parent", Quoted(&k.bone)))),
            (n, _) => return Err(Error::input(format!("{at}.chain = {n}: expected 0 (one bone) or 1 (two bones)"))),
        };
        let target = super::bone(&index, &k.target, &format!("{at}.target"))?;
        if !(0.0..=1.0).contains(&k.weight) {
            return Err(Error::input(format!("{at}.weight = {}: must be within 0 and 1", k.weight)));
        }
        let setup = IkSettings { mix: k.weight, bend_positive: k.bend_positive, ..IkSettings::default() };
        let order = u32::try_from(i).unwrap_or(u32::MAX);
        constraints.push(Constraint::Ik(IkConstraint {
            name: k.name.clone(),
            order,
            bones,
            target,
            setup,
            uniform: false,
            rule: IkRule::DragonBones,
        }));
    }
    let frame_rate = armature.frame_rate.or(file.frame_rate).unwrap_or(24.0);
    if !(frame_rate > 0.0 && frame_rate.is_finite()) {
        return Err(Error::input(format!(
            "armature[0].frameRate = {frame_rate}: must be a number of frames per second above 0"
        )));
    }
    let names = super::first_index(armature.ik.iter().map(|k| k.name.as_str()));
    let cx = Context { bones: &index, constraints: &names, frame_rate };
    let mut notes = Notes::default();
    let clips = armature
        .animation
        .iter()
        .enumerate()
        .map(|(i, a)| dragonbones_clips::clip(i, a, &cx, &mut notes))
        .collect::<Result<Vec<_>, _>>()?;
    if notes.approximated > 0 {
        warnings.push(format!(
            "animations: {} frames ease by a tweenEasing other than 0 or by a curve, read as Bezier curves sampled as Spine's runtime samples them (within about 1 % of each change of DragonBones' own easing)",
            notes.approximated
        ));
    }
    if notes.instant > 0 {
        warnings.push(format!(
            "animations: {} frames of duration 0 before a timeline's last are instant changes, read as the next frame's value",
            notes.instant
        ));
    }
    if !unsupported.is_empty() {
        warnings.push(super::spine::inactive(&unsupported));
    }
    let parts = CharacterParts { bones, constraints, clips, unsupported, ..CharacterParts::default() };
    Ok(Loaded { character: super::character(parts)?, format: Format::DragonBones, version, warnings })
}

/// The inherit mode of a bone's four flags, and whether it matches them exactly (otherwise it
/// is the nearest: Spine's modes always inherit translation, inherit reflection with rotation
/// and scale or with rotation alone, and never without rotation).
fn inherit(b: &BoneJson) -> (Inherit, bool) {
    let (rotation, scale, reflection) = (b.inherit_rotation, b.inherit_scale, b.inherit_reflection);
    let mode = match (rotation, scale, reflection) {
        (true, true, _) => Inherit::Normal,
        (true, false, true) => Inherit::NoScale,
        (true, false, false) => Inherit::NoScaleOrReflection,
        (false, true, _) => Inherit::NoRotationOrReflection,
        (false, false, _) => Inherit::OnlyTranslation,
    };
    // Spine's modes without rotation drop the parent's reflection too.
    let exact = b.inherit_translation && (rotation == reflection || (rotation && !scale));
    (mode, exact)
}
