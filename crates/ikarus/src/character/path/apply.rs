//! A path constraint applied to the pose being made: its bones' world transforms moved by
//! [`super::solve`], each set with its applied local transform recomputed
//! ([`Bones::set_world`]), in the order listed (so that a bone's local transform is taken in
//! its parent's new world transform when the parent is one of the constraint's bones too).

use super::super::world::{Affine, Bones};
use super::{Chain, PathConstraint, PathScratch, PathSettings, solve};

/// What applying path constraints reuses from pose to pose: the clip's deform offsets per
/// constraint, the solver's buffers.
#[derive(Debug, Clone, Default)]
pub(crate) struct PathPose {
    /// Per constraint, the offsets the clip's deform timeline gives its path now.
    pub(crate) deform: Vec<Vec<f64>>,
    /// Per constraint, whether the clip deforms its path now.
    pub(crate) deformed: Vec<bool>,
    scratch: PathScratch,
    world: Vec<Affine>,
    length: Vec<f64>,
}

impl PathPose {
    /// Ready for a pose of a character of `n` constraints: no deform.
    pub(crate) fn reset(&mut self, n: usize) {
        self.deform.resize_with(n, Vec::new);
        self.deformed.clear();
        self.deformed.resize(n, false);
    }
}

/// Applies path constraint `k` (`c`, with settings `s`) to `bones`, along the path skin `skin`
/// gives it ([`PathConstraint::path_for`]).
pub(crate) fn apply(
    bones: &mut Bones,
    (k, c, skin): (usize, &PathConstraint, Option<usize>),
    s: &PathSettings,
    state: &mut PathPose,
) {
    let PathPose { deform, deformed, scratch, world, length } = state;
    world.clear();
    world.extend(c.bones.iter().map(|&b| bones.world[b]));
    length.clear();
    length.extend(c.bones.iter().map(|&b| bones.bones[b].length));
    let offsets = deformed.get(k).copied().unwrap_or(false).then(|| &deform[k][..]);
    let all = &*bones.world;
    solve(c, s, &|i| all[i], c.followed(skin, offsets), Chain { world, length }, scratch);
    for (&b, w) in c.bones.iter().zip(world.iter()) {
        bones.set_world(b, *w);
    }
}
