//! Spine's transform constraints (the `transform` list), read into the library's
//! [`TransformConstraint`]s.
//!
//! Fields and defaults as the JSON export format has them: `name`, `order` (0), `skin` (false;
//! see [`super::spine_skins`]), `bones` (names, at least one), `target` (a bone), the offsets `rotation`, `x`, `y`, `scaleX`,
//! `scaleY`, `shearY` (0; degrees for the angles), `local` and `relative` (false), and the mixes
//! `mixRotate` (1), `mixX` (1), `mixY` (`mixX`'s value), `mixScaleX` (1), `mixScaleY`
//! (`mixScaleX`'s value), `mixShearY` (1). Spine 3.8 names the mixes `rotateMix`,
//! `translateMix` (x and y), `scaleMix` (x and y) and `shearMix` (each 1 by default). A mix must
//! be within −1 and 1 (a negative one moves away from the target); a bone may not be its own
//! constraint's target.

use std::collections::HashMap;

use ikarus::character::{TransformConstraint, TransformMode, TransformOffsets, TransformSettings, TransformSpace};
use serde::Deserialize;

use crate::error::Error;
use crate::names::Quoted;

/// One entry of the `transform` list as written.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct TransformJson {
    pub(super) name: String,
    #[serde(default)]
    order: u32,
    /// Whether only a skin that lists it turns it on (Spine's `skin`).
    #[serde(default)]
    pub(super) skin: bool,
    bones: Vec<String>,
    target: String,
    #[serde(default)]
    rotation: f64,
    #[serde(default)]
    x: f64,
    #[serde(default)]
    y: f64,
    #[serde(default)]
    scale_x: f64,
    #[serde(default)]
    scale_y: f64,
    #[serde(default)]
    shear_y: f64,
    #[serde(default)]
    local: bool,
    #[serde(default)]
    relative: bool,
    #[serde(flatten)]
    mixes: MixesJson,
}

/// The six mixes, 4.x names first, 3.8 names beside them; each absent one is `None`.
#[derive(Deserialize, Default)]
#[serde(rename_all = "camelCase")]
pub(super) struct MixesJson {
    mix_rotate: Option<f64>,
    mix_x: Option<f64>,
    mix_y: Option<f64>,
    mix_scale_x: Option<f64>,
    mix_scale_y: Option<f64>,
    mix_shear_y: Option<f64>,
    rotate_mix: Option<f64>,
    translate_mix: Option<f64>,
    scale_mix: Option<f64>,
    shear_mix: Option<f64>,
}

/// The mixes' names in the file, in [`TransformSettings::to_array`]'s order.
pub(super) const MIX_NAMES: [&str; 6] = ["mixRotate", "mixX", "mixY", "mixScaleX", "mixScaleY", "mixShearY"];

impl MixesJson {
    /// The mixes with their defaults: 1, `mixY` as `mixX`, `mixScaleY` as `mixScaleX`, the 3.8
    /// names where the 4.x ones are absent. Each must be within −1 and 1 (`at.mixX = 3: …`).
    pub(super) fn settings(&self, at: &str) -> Result<TransformSettings, Error> {
        let rotate = self.mix_rotate.or(self.rotate_mix).unwrap_or(1.0);
        let x = self.mix_x.or(self.translate_mix).unwrap_or(1.0);
        let y = self.mix_y.or(self.translate_mix).unwrap_or(x);
        let scale_x = self.mix_scale_x.or(self.scale_mix).unwrap_or(1.0);
        let scale_y = self.mix_scale_y.or(self.scale_mix).unwrap_or(scale_x);
        let shear_y = self.mix_shear_y.or(self.shear_mix).unwrap_or(1.0);
        let mixes = [rotate, x, y, scale_x, scale_y, shear_y];
        if let Some((name, v)) = MIX_NAMES.iter().zip(mixes).find(|(_, v)| !(-1.0..=1.0).contains(v)) {
            return Err(Error::input(format!("{at}.{name} = {v}: must be within -1 and 1")));
        }
        Ok(TransformSettings::from_array(mixes))
    }
}

/// Reads `list` (the file's `transform`), with `index` the bones' indices by name.
pub(super) fn read(list: &[TransformJson], index: &HashMap<String, usize>) -> Result<Vec<TransformConstraint>, Error> {
    list.iter()
        .enumerate()
        .map(|(i, k)| constraint(k, index, &format!("transform[{i}] ({:?})", Quoted(&k.name))))
        .collect()
}

fn constraint(k: &TransformJson, index: &HashMap<String, usize>, at: &str) -> Result<TransformConstraint, Error> {
    if k.bones.is_empty() {
        return Err(Error::input(format!("{at}.bones: expected at least one bone, got none")));
    }
    let bones = k
        .bones
        .iter()
        .enumerate()
        .map(|(j, name)| super::bone(index, name, &format!("{at}.bones[{j}]")))
        .collect::<Result<Vec<_>, _>>()?;
    let target = super::bone(index, &k.target, &format!("{at}.target"))?;
    if let Some(j) = bones.iter().position(|&b| b == target) {
        return Err(Error::input(format!("{at}.bones[{j}] = {:?}: the constraint's target too", Quoted(&k.target))));
    }
    Ok(TransformConstraint {
        name: k.name.clone(),
        order: k.order,
        bones,
        target,
        offsets: TransformOffsets {
            rotation: k.rotation.to_radians(),
            x: k.x,
            y: k.y,
            scale_x: k.scale_x,
            scale_y: k.scale_y,
            shear_y: k.shear_y.to_radians(),
        },
        space: if k.local { TransformSpace::Local } else { TransformSpace::World },
        mode: if k.relative { TransformMode::Relative } else { TransformMode::Absolute },
        setup: k.mixes.settings(at)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> HashMap<String, usize> {
        ["root", "arm", "aim"].iter().enumerate().map(|(i, n)| ((*n).to_owned(), i)).collect()
    }

    fn one(json: &str) -> Result<TransformConstraint, Error> {
        let list: Vec<TransformJson> = serde_json::from_str(&format!("[{json}]")).unwrap();
        read(&list, &names()).map(|mut v| v.remove(0))
    }

    #[test]
    fn defaults_and_offsets_are_read_as_the_format_has_them() {
        let c = one(r#"{"name": "t", "bones": ["arm"], "target": "aim"}"#).unwrap();
        assert_eq!((c.order, c.bones.as_slice(), c.target), (0, &[1][..], 2));
        assert_eq!(c.setup, TransformSettings::default());
        assert_eq!(c.offsets, TransformOffsets::default());
        assert_eq!((c.space, c.mode), (TransformSpace::World, TransformMode::Absolute));
        let c = one(r#"{"name": "t", "order": 3, "bones": ["arm", "root"], "target": "aim", "rotation": 90, "x": 2,
                "y": -1, "scaleX": 0.5, "scaleY": 0.25, "shearY": -45, "local": true, "relative": true,
                "mixRotate": 0.5, "mixX": -1, "mixScaleX": 0.25, "mixShearY": 0}"#)
        .unwrap();
        assert_eq!(c.bones, vec![1, 0]);
        assert_eq!((c.space, c.mode), (TransformSpace::Local, TransformMode::Relative));
        assert_eq!(c.offsets.rotation, 90f64.to_radians());
        assert_eq!(c.offsets.shear_y, (-45f64).to_radians());
        assert_eq!([c.offsets.x, c.offsets.y, c.offsets.scale_x, c.offsets.scale_y], [2.0, -1.0, 0.5, 0.25]);
        // mixY follows mixX, mixScaleY mixScaleX.
        assert_eq!(c.setup.to_array(), [0.5, -1.0, -1.0, 0.25, 0.25, 0.0]);
    }

    #[test]
    fn spine_3_8_names_are_read() {
        let c = one(r#"{"name": "t", "bones": ["arm"], "target": "aim", "rotateMix": 0.5, "translateMix": 0.25,
                "scaleMix": 0.75, "shearMix": 0}"#)
        .unwrap();
        assert_eq!(c.setup.to_array(), [0.5, 0.25, 0.25, 0.75, 0.75, 0.0]);
    }

    #[test]
    fn bad_constraints_are_one_line_naming_the_field_and_value() {
        let e = |json: &str| one(json).unwrap_err();
        assert_eq!(
            e(r#"{"name": "aim", "bones": ["arm"], "target": "aim", "mixRotate": 3}"#),
            r#"transform[0] ("aim").mixRotate = 3: must be within -1 and 1"#
        );
        assert_eq!(
            e(r#"{"name": "t", "bones": ["arm", "leg"], "target": "aim"}"#),
            r#"transform[0] ("t").bones[1] = "leg": no bone of that name"#
        );
        assert_eq!(
            e(r#"{"name": "t", "bones": ["arm"], "target": "nose"}"#),
            r#"transform[0] ("t").target = "nose": no bone of that name"#
        );
        assert_eq!(
            e(r#"{"name": "t", "bones": [], "target": "aim"}"#),
            r#"transform[0] ("t").bones: expected at least one bone, got none"#
        );
        assert_eq!(
            e(r#"{"name": "t", "bones": ["aim"], "target": "aim"}"#),
            r#"transform[0] ("t").bones[0] = "aim": the constraint's target too"#
        );
    }
}
