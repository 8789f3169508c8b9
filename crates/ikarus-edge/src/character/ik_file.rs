//! IK files (TOML): how `--ik ikarus` solves a character's constraints, beside the character
//! file (Spine and DragonBones files have no joint limits, pins or longer limbs to say it).
//!
//! ```toml
//! pins = ["hip"]                 # bones whose tip stays where the runtime's pose has it
//! [limbs.front-leg-ik]           # a constraint, by name
//! bones = 3                      # bones moved for it, up from its last bone (default: its own 1 or 2)
//! weight = 2.0                   # > 0, when goals conflict (default 1)
//! secondary = false              # met only in what the others leave free (default false)
//! [bones.front-shin]             # a bone, by name
//! limits_deg = [-150.0, 0.0]     # its local rotation's range, degrees (the file's `rotation`)
//! stiffness = 1.0                # ≥ 0: how much it resists turning (default 0)
//! ```
//!
//! Every problem is one line naming the file, the field and the value.

use std::collections::BTreeMap;

use ikarus::character::{BoneRule, Character, LimbRule, Together};
use serde::Deserialize;

use crate::arm::toml_error;
use crate::error::Error;
use crate::names::{Quoted, cell, listed};

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct IkFile {
    #[serde(default)]
    pins: Vec<String>,
    #[serde(default)]
    limbs: BTreeMap<String, LimbFile>,
    #[serde(default)]
    bones: BTreeMap<String, BoneFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LimbFile {
    #[serde(default)]
    bones: Option<usize>,
    #[serde(default = "one")]
    weight: f64,
    #[serde(default)]
    secondary: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoneFile {
    #[serde(default)]
    limits_deg: Option<[f64; 2]>,
    #[serde(default)]
    stiffness: f64,
}

fn one() -> f64 {
    1.0
}

/// Reads an IK file's `text` against `character`: names resolved into indices, values checked.
/// `label` starts every message (`ik file legs.toml`).
pub fn read(text: &str, label: &str, character: &Character) -> Result<Together, Error> {
    let file: IkFile = toml::from_str(text).map_err(|e| Error::input(toml_error(label, text, &e)))?;
    let bad = |m: String| Error::input(format!("{label}: {m}"));
    let bone = |field: &str, name: &str| {
        character.bone_index(name).ok_or_else(|| bad(format!("{field} = {}: no bone of that name", Quoted(name))))
    };
    let mut rules = Together::default();
    for (i, name) in file.pins.iter().enumerate() {
        rules.pins.push(bone(&format!("pins[{i}]"), name)?);
    }
    for (name, limb) in &file.limbs {
        let constraint =
            character.ik_constraints().find(|(_, c)| &c.name == name).map(|(k, _)| k).ok_or_else(|| {
                let names = listed(character.ik_constraints().map(|(_, c)| c.name.as_str()));
                bad(format!("limbs.{}: no IK constraint of that name (the file has: {names})", cell(name)))
            })?;
        rules.limbs.push(LimbRule { constraint, bones: limb.bones, weight: limb.weight, secondary: limb.secondary });
    }
    for (name, b) in &file.bones {
        let field = format!("bones.{}", cell(name));
        let index = bone(&field, name)?;
        if let Some(limits) = b.limits_deg {
            let [lo, hi] = limits.map(crate::names::count_text);
            limits_in_degrees(limits).map_err(|m| bad(format!("{field}.limits_deg = [{lo}, {hi}]: {m}")))?;
        }
        let limits = b.limits_deg.map(|[lo, hi]| [lo.to_radians(), hi.to_radians()]);
        rules.bones.push(BoneRule { bone: index, limits, stiffness: b.stiffness });
    }
    character.check_together(&rules).map_err(|e| bad(e.to_string()))?;
    Ok(rules)
}

/// The most a limit may turn a bone from its setup's direction either way, degrees: a range
/// wider than this is no limit, and a farther one is a typing slip (1e308).
pub const MAX_LIMIT_DEG: f64 = 360.0;

/// `[lo, hi]` as an IK file gives a bone's limits, in degrees, checked in degrees (the solver's
/// own check sees radians, and would print them): finite, within ±[`MAX_LIMIT_DEG`], `lo ≤ hi`.
fn limits_in_degrees([lo, hi]: [f64; 2]) -> Result<(), Error> {
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(Error::input("the limits must be finite numbers of degrees"));
    }
    if lo.abs() > MAX_LIMIT_DEG || hi.abs() > MAX_LIMIT_DEG {
        return Err(Error::input(format!("each limit must be within -{MAX_LIMIT_DEG} and {MAX_LIMIT_DEG} degrees")));
    }
    if lo > hi {
        return Err(Error::input("the lower limit must not exceed the upper (degrees)"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boy() -> Character {
        let text = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
        crate::character::load(text, "spineboy").unwrap().character
    }

    #[test]
    fn a_file_is_read_by_name_and_every_problem_is_one_line() {
        let c = boy();
        let text = "pins = [\"hip\"]\n[limbs.front-leg-ik]\nbones = 3\nweight = 2.0\n[bones.front-shin]\nlimits_deg = [-150.0, 0.0]\nstiffness = 1.5\n";
        let rules = read(text, "ik file a.toml", &c).unwrap();
        assert_eq!(rules.pins, vec![c.bone_index("hip").unwrap()]);
        let limb = &rules.limbs[0];
        assert_eq!((limb.bones, limb.weight, limb.secondary), (Some(3), 2.0, false));
        assert_eq!(c.ik(limb.constraint).unwrap().name, "front-leg-ik");
        let shin = &rules.bones[0];
        assert_eq!(shin.bone, c.bone_index("front-shin").unwrap());
        assert!((shin.limits.unwrap()[0] - (-150f64).to_radians()).abs() < 1e-15 && shin.stiffness == 1.5);

        let err = |t: &str| read(t, "ik file a.toml", &c).unwrap_err().to_string();
        assert_eq!(err("pins = [\"tail\"]"), "ik file a.toml: pins[0] = \"tail\": no bone of that name");
        assert!(
            err("[limbs.leg]\n")
                .starts_with("ik file a.toml: limbs.leg: no IK constraint of that name (the file has: aim-ik")
        );
        assert_eq!(
            err("[limbs.front-leg-ik]\nbones = 1\n"),
            "ik file a.toml: limb \"front-leg-ik\": bones must be from 2 (its own) to 4 (up to its root), got 1"
        );
        assert_eq!(
            err("[limbs.front-leg-ik]\nweight = 0\n"),
            "ik file a.toml: limb \"front-leg-ik\": weight must be > 0, got 0"
        );
        // In degrees, as the file gives them, named by the file's own field.
        assert_eq!(
            err("[bones.front-shin]\nlimits_deg = [10.0, -10.0]\n"),
            "ik file a.toml: bones.front-shin.limits_deg = [10, -10]: the lower limit must not exceed the upper (degrees)"
        );
        assert_eq!(
            err("[bones.front-shin]\nlimits_deg = [1e308, 1e308]\n"),
            "ik file a.toml: bones.front-shin.limits_deg = [1e308, 1e308]: each limit must be within -360 and 360 degrees"
        );
        assert!(
            err("[bones.front-shin]\nlimit = 1\n")
                .starts_with("ik file a.toml: line 2, column 1: unknown field `limit`")
        );
        for e in [err("pins = [\"tail\"]"), err("[limbs.front-leg-ik]\nbones = 1\n")] {
            assert_eq!(e.lines().count(), 1);
        }
    }
}
