//! Spine's path constraints (`path[]`): `name`, `order` (0), `skin` (false), `bones`, `target`
//! (a slot whose attachment in the skin is a path), `positionMode` (`percent`; `fixed`),
//! `spacingMode` (`length`; `fixed`, `percent`, `proportional`), `rotateMode` (`tangent`;
//! `chain`, `chainScale`), `rotation` (0, degrees), `position` (0), `spacing` (0), `mixRotate`
//! (1; 3.8 `rotateMix`), `mixX` (1; 3.8 `translateMix`), `mixY` (`mixX`'s value). Mixes are
//! refused outside −1 … 1 (the runtime blends with them; the editor keeps them within 0 … 1,
//! files have negative ones for other kinds).
//!
//! The path is the target slot's setup attachment as the chosen skin shows it: Spine looks it
//! up by name in the chosen skin first, then in the default skin (the runtime guide's "Runtime
//! Skins"; `Skeleton.getAttachment`). So the constraint carries the default skin's path and each
//! other skin's own attachment of that name ([`ikarus::character::SkinPath`]), and a pose picks
//! by the skin's index. Whether a constraint marked `skin: true` takes part is the skin's
//! business ([`super::spine_skins`]), not its path's.

use std::collections::HashMap;

use ikarus::character::{PathConstraint, PathSettings, PositionMode, RotateMode, SkinPath, SpacingMode};
use serde::Deserialize;

use super::spine_slots::Slots;
use crate::error::Error;
use crate::names::Quoted;

/// One entry of `path`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct PathJson {
    name: String,
    #[serde(default)]
    order: u32,
    #[serde(default)]
    skin: bool,
    #[serde(default)]
    bones: Vec<String>,
    target: String,
    #[serde(default)]
    position_mode: Option<String>,
    #[serde(default)]
    spacing_mode: Option<String>,
    #[serde(default)]
    rotate_mode: Option<String>,
    #[serde(default)]
    rotation: f64,
    #[serde(default)]
    position: f64,
    #[serde(default)]
    spacing: f64,
    #[serde(default)]
    mix_rotate: Option<f64>,
    #[serde(default)]
    rotate_mix: Option<f64>,
    #[serde(default)]
    mix_x: Option<f64>,
    #[serde(default)]
    translate_mix: Option<f64>,
    #[serde(default)]
    mix_y: Option<f64>,
}

impl PathJson {
    /// Its name.
    pub(super) fn name(&self) -> &str {
        &self.name
    }

    /// Whether it takes part only while a chosen skin lists it (`skin`).
    pub(super) fn skin(&self) -> bool {
        self.skin
    }
}

/// Reads path constraint `i`, its path the target slot's setup attachment in the default skin
/// and in each skin that has its own.
pub(super) fn constraint(
    i: usize,
    k: &PathJson,
    bones: &HashMap<String, usize>,
    slots: &Slots,
) -> Result<PathConstraint, Error> {
    let at = format!("path[{i}] ({:?})", Quoted(&k.name));
    if k.bones.is_empty() {
        return Err(Error::input(format!("{at}.bones: expected at least one bone, got none")));
    }
    let list = k
        .bones
        .iter()
        .enumerate()
        .map(|(j, b)| super::bone(bones, b, &format!("{at}.bones[{j}]")))
        .collect::<Result<Vec<_>, _>>()?;
    let slot = *slots
        .index
        .get(&k.target)
        .ok_or_else(|| Error::input(format!("{at}.target = {:?}: no slot of that name", Quoted(&k.target))))?;
    let position_mode = mode(
        &k.position_mode,
        &at,
        "positionMode",
        &[("fixed", PositionMode::Fixed), ("percent", PositionMode::Percent)],
    )?;
    let spacing_mode = mode(
        &k.spacing_mode,
        &at,
        "spacingMode",
        &[
            ("length", SpacingMode::Length),
            ("fixed", SpacingMode::Fixed),
            ("percent", SpacingMode::Percent),
            ("proportional", SpacingMode::Proportional),
        ],
    )?;
    let rotate_mode = mode(
        &k.rotate_mode,
        &at,
        "rotateMode",
        &[("tangent", RotateMode::Tangent), ("chain", RotateMode::Chain), ("chainScale", RotateMode::ChainScale)],
    )?;
    let mix_rotate = k.mix_rotate.or(k.rotate_mix).unwrap_or(1.0);
    let mix_x = k.mix_x.or(k.translate_mix).unwrap_or(1.0);
    let mix_y = k.mix_y.or(k.translate_mix).unwrap_or(mix_x);
    for (field, v) in [("mixRotate", mix_rotate), ("mixX", mix_x), ("mixY", mix_y)] {
        if !(-1.0..=1.0).contains(&v) {
            return Err(Error::input(format!("{at}.{field} = {v}: must be within −1 and 1")));
        }
    }
    for (field, v) in [("rotation", k.rotation), ("position", k.position), ("spacing", k.spacing)] {
        if !v.is_finite() {
            return Err(Error::input(format!("{at}.{field} = {v}: must be finite")));
        }
    }
    let default = slots.default_skin();
    let path = default.and_then(|d| slots.setup_attachment(d, slot)).cloned().flatten();
    let skin_paths = (0..slots.skins.len())
        .filter(|&s| Some(s) != default)
        .filter_map(|s| slots.setup_attachment(s, slot).map(|p| SkinPath { skin: s, path: p.clone() }))
        .collect();
    Ok(PathConstraint {
        name: k.name.clone(),
        order: k.order,
        skin: k.skin,
        bones: list,
        slot,
        slot_bone: slots.slots[slot].bone,
        path,
        skin_paths,
        position_mode,
        spacing_mode,
        rotate_mode,
        rotation: k.rotation.to_radians(),
        setup: PathSettings { position: k.position, spacing: k.spacing, mix_rotate, mix_x, mix_y },
    })
}

/// A mode by its Spine name (the default when absent).
fn mode<T: Copy + Default>(v: &Option<String>, at: &str, field: &str, modes: &[(&str, T)]) -> Result<T, Error> {
    let Some(name) = v else { return Ok(T::default()) };
    modes.iter().find(|(n, _)| n == name).map(|(_, m)| *m).ok_or_else(|| {
        Error::input({
            let names: Vec<&str> = modes.iter().map(|(n, _)| *n).collect();
            format!("{at}.{field} = {:?}: expected one of {}", Quoted(name), names.join(", "))
        })
    })
}

#[cfg(test)]
#[path = "spine_path_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "spine_path_skin_tests.rs"]
mod skin_tests;
