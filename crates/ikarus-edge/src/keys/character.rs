//! A character's bend keys named as the keys name them: the two-bone IK constraint whose lower
//! bone a key names ([`bend_constraint`]) and the `bendPositive` a side means in the file's
//! format ([`bend_positive`]). The keyed motion ([`crate::character::motion::keyed`]) and
//! `POST /api/pose`'s `bends` (the page poses a drag with the bends in force) share them.

use ikarus::Bend;
use ikarus::character::IkBones;

use crate::character::{Format, Loaded};
use crate::error::Error;
use crate::names::{Quoted, listed};

/// The index of the two-bone IK constraint whose lower bone is `name`; else the problem after
/// `field` (naming the character's lower bones).
pub fn bend_constraint(loaded: &Loaded, field: &str, name: &str) -> Result<usize, Error> {
    let c = &loaded.character;
    let index = c
        .bone_index(name)
        .ok_or_else(|| Error::input(format!("{field}: no bone named {} in the character", Quoted(name))))?;
    let two = |k: &&ikarus::character::IkConstraint| matches!(k.bones, IkBones::Two { child, .. } if child == index);
    c.ik_constraints().find(|(_, k)| two(k)).map(|(k, _)| k).ok_or_else(|| {
        Error::input({
            let has = listed(c.ik_constraints().filter_map(|(_, k)| match k.bones {
                IkBones::Two { child, .. } => Some(c.bones()[child].name.as_str()),
                IkBones::One(_) => None,
            }));
            format!(
                "{field}: {} is not the lower bone of a two-bone IK constraint (the character's are: {has})",
                Quoted(name)
            )
        })
    })
}

/// The constraint's `bendPositive` for the side `bend` as the setup pose sees it: `ccw` is a
/// positive turn in Spine's y-up; DragonBones' `bendPositive` is one in its y-down.
pub fn bend_positive(loaded: &Loaded, bend: Bend) -> bool {
    (bend == Bend::Positive) == (loaded.format == Format::Spine)
}
