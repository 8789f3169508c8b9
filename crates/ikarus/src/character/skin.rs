//! Skins, as far as posing goes: which bones and constraints a skin turns on.
//!
//! A bone or constraint marked as skin-required (Spine's `"skin": true`) takes part in a pose
//! only while the chosen skin lists it. Rules (Spine's user guide on skin bones and skin
//! constraints; no reference case has an inactive bone, so the last two are inferred):
//! - a bone is active when it is not skin-required or the skin lists it or a bone below it (a
//!   listed bone turns its parents on), and its parent is active;
//! - a constraint is active when it is not skin-required or the skin lists it, and its target
//!   and bones are active;
//! - an inactive bone is not posed: its world transform is left at zeros (as the runtime leaves
//!   it), and an inactive constraint does nothing.

use super::CharacterBone;
use super::transform::Step;

/// A constraint of any kind, by its index in its kind's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SkinConstraint {
    /// An IK constraint (index in [`super::Character::constraints`]).
    Ik(usize),
    /// A transform constraint (index in [`super::Character::transforms`]).
    Transform(usize),
}

/// A skin: its name and what it turns on (its attachments are not read here).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Skin {
    /// Its name in the file (`default` is the one a pose takes unless told otherwise).
    pub name: String,
    /// The skin-required bones it turns on (Spine's `bones` of a skin).
    pub bones: Vec<usize>,
    /// The skin-required constraints it turns on (Spine's `ik`, `transform` of a skin).
    pub constraints: Vec<SkinConstraint>,
}

/// What only a skin turns on: the bones and constraints marked `"skin": true`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkinRequired {
    /// The skin-required bones.
    pub bones: Vec<usize>,
    /// The skin-required constraints.
    pub constraints: Vec<SkinConstraint>,
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
    /// Per step (the constraints in update order), as the skin goes (not yet its bones).
    pub(crate) steps: Vec<bool>,
    /// Scratch: the listed bones and their parents.
    listed: Vec<bool>,
}

/// What posing needs to tell active bones and constraints apart, made once with the character.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Activity {
    /// Whether anything is skin-required (else everything is active and nothing is computed).
    pub(crate) any: bool,
    /// Per bone, whether it is skin-required.
    bone_required: Vec<bool>,
    /// Per step (the constraints in update order), whether it is skin-required.
    step_required: Vec<bool>,
    /// Each IK constraint's place in the steps.
    ik_step: Vec<usize>,
    /// Each transform constraint's place in the steps.
    transform_step: Vec<usize>,
}

impl Activity {
    /// The activity rules of `bones` (count) and `steps` with `required` skin-required.
    pub(crate) fn new(bones: usize, steps: &[Step], required: &SkinRequired) -> Activity {
        let (mut ik_step, mut transform_step) = (Vec::new(), Vec::new());
        for (pos, s) in steps.iter().enumerate() {
            match *s {
                Step::Ik(k) => {
                    ik_step.resize(ik_step.len().max(k + 1), 0);
                    ik_step[k] = pos;
                }
                Step::Transform(k) => {
                    transform_step.resize(transform_step.len().max(k + 1), 0);
                    transform_step[k] = pos;
                }
            }
        }
        let mut out = Activity {
            any: !required.is_empty(),
            bone_required: vec![false; bones],
            step_required: vec![false; steps.len()],
            ik_step,
            transform_step,
        };
        for &b in &required.bones {
            out.bone_required[b] = true;
        }
        for &c in &required.constraints {
            let pos = out.step(c);
            out.step_required[pos] = true;
        }
        out
    }

    /// The place of `c` in the steps.
    fn step(&self, c: SkinConstraint) -> usize {
        match c {
            SkinConstraint::Ik(k) => self.ik_step[k],
            SkinConstraint::Transform(k) => self.transform_step[k],
        }
    }

    /// Which bones (`bones`) and steps are active with `skin` (`None`: no skin), into `out`: a
    /// step here only as the skin goes; posing also checks the bones it reads. See the module's
    /// doc.
    pub(crate) fn compute(&self, bones: &[CharacterBone], skin: Option<&Skin>, out: &mut Active) {
        let Active { bones: bone_on, steps: step_on, listed } = out;
        bone_on.clear();
        bone_on.resize(bones.len(), true);
        step_on.clear();
        step_on.resize(self.step_required.len(), true);
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
        for (on, &r) in step_on.iter_mut().zip(&self.step_required) {
            *on = !r;
        }
        for &c in skin.map_or(&[][..], |s| &s.constraints) {
            step_on[self.step(c)] = true;
        }
    }
}

/// Checks `skins` and `required` against a character of `bones` bones, `ik` IK constraints and
/// `transforms` transform ones: every index existing.
pub(crate) fn check(
    skins: &[Skin],
    required: &SkinRequired,
    [bones, ik, transforms]: [usize; 3],
) -> Result<(), super::CharacterError> {
    let missing =
        |skin: Option<usize>, what: &'static str, index: usize| super::CharacterError::SkinIndex { skin, what, index };
    let lists = skins.iter().enumerate().map(|(i, s)| (Some(i), &s.bones, &s.constraints));
    for (skin, b, c) in lists.chain([(None, &required.bones, &required.constraints)]) {
        if let Some(&i) = b.iter().find(|&&i| i >= bones) {
            return Err(missing(skin, "bone", i));
        }
        for &k in c {
            match k {
                SkinConstraint::Ik(i) if i >= ik => return Err(missing(skin, "IK constraint", i)),
                SkinConstraint::Transform(i) if i >= transforms => {
                    return Err(missing(skin, "transform constraint", i));
                }
                SkinConstraint::Ik(_) | SkinConstraint::Transform(_) => {}
            }
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "skin_tests.rs"]
mod tests;
