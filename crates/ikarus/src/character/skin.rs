//! Skins, as far as posing goes: which bones and constraints a skin turns on.
//!
//! A bone or constraint marked as skin-required (Spine's `"skin": true`) takes part in a pose
//! only while the chosen skin lists it. Rules (Spine's user guide, "Skins": "skins are made up
//! of attachments, bones, and constraints that are only active when the skin is visible"; the
//! rest is not spelled out there, no reference case has an inactive bone, so the last three are
//! inferred from what an inactive bone is — one the runtime does not update):
//! - a bone is active when it is not skin-required or the skin lists it or a bone below it (a
//!   listed bone turns its parents on), and its parent is active (a plain bone below an inactive
//!   one is inactive too);
//! - a constraint is active when it is not skin-required or the skin lists it, and its target
//!   and bones (a path constraint's: its slot's bone) are active;
//! - an inactive bone is not posed: its world transform is left at zeros (as the runtime leaves
//!   it; the reference files list such bones with `active: false`), and an inactive constraint
//!   does nothing;
//! - a target on an inactive bone is refused ([`super::PoseError::InactiveTarget`]): the bone is
//!   not posed, so it cannot be put anywhere.

use super::{CharacterBone, CharacterError};

/// A skin: its name and what it turns on (its attachments are not read here).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Skin {
    /// Its name in the file (`default` is the one a pose takes unless told otherwise).
    pub name: String,
    /// The skin-required bones it turns on (Spine's `bones` of a skin).
    pub bones: Vec<usize>,
    /// The skin-required constraints it turns on (Spine's `ik`, `transform`, … of a skin), by
    /// index in [`super::Character::constraints`].
    pub constraints: Vec<usize>,
}

/// What only a skin turns on: the bones and constraints marked `"skin": true`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkinRequired {
    /// The skin-required bones.
    pub bones: Vec<usize>,
    /// The skin-required constraints, by index in [`super::Character::constraints`].
    pub constraints: Vec<usize>,
}

impl SkinRequired {
    /// Whether nothing is skin-required (every bone and constraint is always active).
    pub fn is_empty(&self) -> bool {
        self.bones.is_empty() && self.constraints.is_empty()
    }
}

/// Which bones and constraints a pose found active.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Active {
    /// Per bone.
    pub(crate) bones: Vec<bool>,
    /// Per constraint, as the skin goes (not yet its bones).
    pub(crate) constraints: Vec<bool>,
    /// Scratch: the listed bones and their parents.
    listed: Vec<bool>,
    /// Whether `bones` and `constraints` are all on, for a character of their sizes (a pose of
    /// a character without skin-required parts then leaves them as they are).
    all_on: bool,
}

/// What posing needs to tell active bones and constraints apart, made once with the character.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Activity {
    /// Whether anything is skin-required (else everything is active and nothing is computed).
    pub(crate) any: bool,
    /// Per bone, whether it is skin-required.
    bone_required: Vec<bool>,
    /// Per constraint, whether it is skin-required.
    constraint_required: Vec<bool>,
}

impl Activity {
    /// The activity rules of `bones` bones and `constraints` constraints with `required`
    /// skin-required (indices checked by [`check`]).
    pub(crate) fn new(bones: usize, constraints: usize, required: &SkinRequired) -> Activity {
        let mut out = Activity {
            any: !required.is_empty(),
            bone_required: vec![false; bones],
            constraint_required: vec![false; constraints],
        };
        for &b in &required.bones {
            out.bone_required[b] = true;
        }
        for &c in &required.constraints {
            out.constraint_required[c] = true;
        }
        out
    }

    /// Which bones (`bones`) and constraints are active with `skin` (`None`: no skin), into
    /// `out`: a constraint here only as the skin goes; posing also checks the bones it reads. See
    /// the module's doc.
    #[inline]
    pub(crate) fn compute(&self, bones: &[CharacterBone], skin: Option<&Skin>, out: &mut Active) {
        let sized = out.bones.len() == bones.len() && out.constraints.len() == self.constraint_required.len();
        if !self.any && out.all_on && sized {
            return;
        }
        self.compute_all(bones, skin, out);
    }

    /// [`Activity::compute`] past its shortcut.
    fn compute_all(&self, bones: &[CharacterBone], skin: Option<&Skin>, out: &mut Active) {
        let Active { bones: bone_on, constraints: step_on, listed, all_on } = out;
        bone_on.clear();
        bone_on.resize(bones.len(), true);
        step_on.clear();
        step_on.resize(self.constraint_required.len(), true);
        *all_on = !self.any;
        if !self.any {
            return;
        }
        for (on, &r) in bone_on.iter_mut().zip(&self.bone_required) {
            *on = !r;
        }
        // The listed bones and their parents, children first (a linear pass).
        listed.clear();
        listed.resize(bones.len(), false);
        for &b in skin.map_or(&[][..], |s| &s.bones) {
            listed[b] = true;
        }
        for i in (0..bones.len()).rev() {
            if listed[i] {
                bone_on[i] = true;
                if let Some(p) = bones[i].parent {
                    listed[p] = true;
                }
            }
        }
        for i in 0..bones.len() {
            if let Some(p) = bones[i].parent {
                bone_on[i] &= bone_on[p];
            }
        }
        for (on, &r) in step_on.iter_mut().zip(&self.constraint_required) {
            *on = !r;
        }
        for &c in skin.map_or(&[][..], |s| &s.constraints) {
            step_on[c] = true;
        }
    }
}

/// Checks `skins` and `required` against a character of `bones` bones and `constraints`
/// constraints: every index existing.
pub(crate) fn check(
    skins: &[Skin],
    required: &SkinRequired,
    [bones, constraints]: [usize; 2],
) -> Result<(), CharacterError> {
    let lists = skins.iter().enumerate().map(|(i, s)| (Some(i), &s.bones, &s.constraints));
    for (skin, b, c) in lists.chain([(None, &required.bones, &required.constraints)]) {
        if let Some(&index) = b.iter().find(|&&i| i >= bones) {
            return Err(CharacterError::SkinIndex { skin, what: "bone", index });
        }
        if let Some(&index) = c.iter().find(|&&i| i >= constraints) {
            return Err(CharacterError::SkinIndex { skin, what: "constraint", index });
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "skin_tests.rs"]
mod tests;
