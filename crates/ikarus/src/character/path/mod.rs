//! Path constraints (Spine's `path`): bones moved along a path attachment, a chain of cubic
//! Bézier curves held by a slot, and turned along it.
//!
//! Each pose, the path's vertices are taken into the world (from the slot bone's world
//! transform, or weighted over several bones' — [`spline::world_vertices`]); the distances
//! along the path where the bones go are given by the position and spacing modes; the points
//! at those distances are found on the curves ([`spline::points`]); then each bone, in the
//! order listed, is moved toward its point by `mixX`, `mixY`, turned toward the next point
//! (`chain`, `chainScale`) or along the path's tangent (`tangent`) by `mixRotate`, and with
//! `chainScale` scaled along its x axis so that its tip reaches the next point.
//!
//! The rules, from the user guide's description of the modes; those stretchyman uses (percent
//! position and spacing, chain scale, weighted open constant-speed paths, deform keys, all
//! mixes 1) are checked against Spine's runtime (4.2.119) posing it, within 3.2e-5 units and
//! 3e-5°; the others (`fixed` and `length` and `proportional` spacing, `tangent`, `chain`,
//! closed paths, paths without constant speed, mixes below 1, the `rotation` offset, points
//! past an open path's ends) follow the guide's words and are not checked against the runtime:
//!
//! - distances: `percent` position = `position` × the path's length, `fixed` = `position`;
//!   bone `i`'s point is at the position plus the spaces before it: `fixed` spacing `spacing`,
//!   `percent` `spacing` × the path's length, `length` the bone's world length plus `spacing`,
//!   `proportional` the bone's world length scaled so that the lengths add to `spacing` × the
//!   path's length. `chain` and `chainScale` add one more point, the last bone's tip;
//! - a point past an open path's ends is on the straight line that continues the path's end;
//!   on a closed path distances wrap around;
//! - chain modes turn bone `i`'s x axis toward point `i + 1` from point `i`; `chainScale`
//!   multiplies the bone's x axis by `(d / l − 1)·mixRotate + 1`, `d` the distance between the
//!   two points and `l` the bone's world length (its length times its x axis's length);
//! - the turn is the angle to the goal direction plus the `rotation` offset, wrapped to
//!   `[−π, π]`, times `mixRotate`; it turns the whole world matrix (both axes).

pub(crate) mod apply;
pub(crate) mod deform;
pub(crate) mod spline;

pub use deform::{DeformKey, PathDeform};
pub use spline::{PathShape, PathVertices, Weight};

use super::world::Affine;
use super::{CharacterBone, CharacterError};
use crate::math;
use std::f64::consts::PI;

/// Where the first bone goes: Spine's `positionMode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PositionMode {
    /// `position` is a distance along the path, in world units (`fixed`).
    Fixed,
    /// `position` is a fraction of the path's length (`percent`, the default).
    #[default]
    Percent,
}

/// How far apart the bones go: Spine's `spacingMode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpacingMode {
    /// A bone's world length plus `spacing` (`length`, the default).
    #[default]
    Length,
    /// `spacing` world units (`fixed`).
    Fixed,
    /// `spacing` × the path's length (`percent`).
    Percent,
    /// The bones' world lengths scaled so that they add up to `spacing` × the path's length
    /// (`proportional`).
    Proportional,
}

/// How the bones turn: Spine's `rotateMode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RotateMode {
    /// Along the path's tangent at the bone's point (`tangent`, the default).
    #[default]
    Tangent,
    /// Toward the next bone's point (`chain`).
    Chain,
    /// Toward the next bone's point, and scaled along x to reach it (`chainScale`).
    ChainScale,
}

impl RotateMode {
    /// Whether the bones aim at the next point (one point more than bones).
    fn chain(self) -> bool {
        !matches!(self, RotateMode::Tangent)
    }
}

/// A path constraint's settings that clips can key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSettings {
    /// Where the first bone goes along the path (`position`, default 0): a fraction of its
    /// length or a distance, by [`PositionMode`].
    pub position: f64,
    /// How far apart the bones go (`spacing`, default 0), by [`SpacingMode`].
    pub spacing: f64,
    /// How much of the turn (and of the chain scale) applies, 0 to 1 (`mixRotate`, 3.8's
    /// `rotateMix`; default 1).
    pub mix_rotate: f64,
    /// How much of the move along world x applies (`mixX`, 3.8's `translateMix`; default 1).
    pub mix_x: f64,
    /// How much of the move along world y applies (`mixY`, default `mixX`'s value).
    pub mix_y: f64,
}

impl Default for PathSettings {
    fn default() -> Self {
        PathSettings { position: 0.0, spacing: 0.0, mix_rotate: 1.0, mix_x: 1.0, mix_y: 1.0 }
    }
}

/// A path constraint: its bones follow the path its slot holds.
#[derive(Debug, Clone, PartialEq)]
pub struct PathConstraint {
    /// Its name in the file.
    pub name: String,
    /// Constraints apply in increasing `order` (`order`, default 0; ties as listed).
    pub order: u32,
    /// Whether it takes part only while a skin that lists it is set (`skin`, default false).
    pub skin: bool,
    /// The bones it moves, in order along the path (`bones`).
    pub bones: Vec<usize>,
    /// The index of the slot that holds the path (the `target` slot) in the file's `slots`,
    /// whose deform timelines change the path.
    pub slot: usize,
    /// The bone of the slot that holds the path (the `target` slot's `bone`): an unweighted
    /// path's vertices are in its frame.
    pub slot_bone: usize,
    /// The path the target slot shows with the default skin (or with no skin): the default
    /// skin's attachment of the slot's setup attachment name; `None` when that is not a path
    /// (or there is none): then the constraint does nothing.
    pub path: Option<PathShape>,
    /// The skins that have their own attachment of that name on the slot, and what it is: a
    /// pose with one of these skins follows its path, a pose with any other skin the default
    /// skin's ([`PathConstraint::path_for`]). Spine looks an attachment up in the chosen skin
    /// first, then in the default skin.
    pub skin_paths: Vec<SkinPath>,
    /// [`PositionMode`] (`positionMode`, default `percent`).
    pub position_mode: PositionMode,
    /// [`SpacingMode`] (`spacingMode`, default `length`).
    pub spacing_mode: SpacingMode,
    /// [`RotateMode`] (`rotateMode`, default `tangent`).
    pub rotate_mode: RotateMode,
    /// Added to each bone's turn, radians (`rotation`, degrees in the file; default 0).
    pub rotation: f64,
    /// The settings of the setup pose (clips key them).
    pub setup: PathSettings,
}

impl PathConstraint {
    /// Checks its bones (and its path's) against the character's `bones`, and its settings
    /// (constraint `k` of the list).
    pub(crate) fn check(&self, k: usize, bones: &[CharacterBone]) -> Result<(), CharacterError> {
        let n = bones.len();
        let shapes = self.path.iter().chain(self.skin_paths.iter().filter_map(|p| p.path.as_ref()));
        let weighted: Vec<usize> = shapes
            .filter_map(|p| match &p.vertices {
                PathVertices::Weighted(v) => Some(v.iter().flatten().map(|w| w.bone)),
                PathVertices::Plain(_) => None,
            })
            .flatten()
            .collect();
        if let Some(&bone) = self.bones.iter().chain([&self.slot_bone]).chain(&weighted).find(|&&b| b >= n) {
            return Err(CharacterError::PathBone { constraint: k, bone });
        }
        let s = &self.setup;
        for (field, value, max) in [
            ("mixRotate", s.mix_rotate, 1.0),
            ("mixX", s.mix_x, 1.0),
            ("mixY", s.mix_y, 1.0),
            ("position", s.position, f64::MAX),
            ("spacing", s.spacing, f64::MAX),
            ("rotation", self.rotation, f64::MAX),
        ] {
            if !(value.is_finite() && value.abs() <= max) {
                return Err(CharacterError::PathSetting { constraint: k, field, value });
            }
        }
        Ok(())
    }
}

/// A skin's own attachment under the name of a path constraint's slot's setup attachment.
#[derive(Debug, Clone, PartialEq)]
pub struct SkinPath {
    /// The skin's index in [`super::Character::skins`].
    pub skin: usize,
    /// The attachment, `None` when it is not a path (the constraint then does nothing with
    /// this skin).
    pub path: Option<PathShape>,
}

/// The path a pose follows: the shape the skin gives the slot, and the offsets a clip's deform
/// timeline adds to its vertex coordinates, if any.
#[derive(Debug, Clone, Copy)]
pub struct Followed<'a> {
    /// The shape, `None` when the slot shows no path (the constraint does nothing).
    pub shape: Option<&'a PathShape>,
    /// The deform offsets.
    pub deform: Option<&'a [f64]>,
}

impl PathConstraint {
    /// Whose attachment a pose with skin `skin` follows: `Some(s)` skin `s`'s own, `None` the
    /// default skin's. A deform timeline changes only the attachment of its own skin.
    pub fn path_source(&self, skin: Option<usize>) -> Option<usize> {
        skin.filter(|&s| self.skin_paths.iter().any(|p| p.skin == s))
    }

    /// The path a pose with skin `skin` follows: the skin's own attachment if it has one, else
    /// the default skin's. No allocation, no string compared.
    pub fn path_for(&self, skin: Option<usize>) -> Option<&PathShape> {
        match skin.and_then(|s| self.skin_paths.iter().find(|p| p.skin == s)) {
            Some(own) => own.path.as_ref(),
            None => self.path.as_ref(),
        }
    }

    /// [`Followed`] for a pose with skin `skin`, with `deform`.
    pub fn followed<'a>(&'a self, skin: Option<usize>, deform: Option<&'a [f64]>) -> Followed<'a> {
        Followed { shape: self.path_for(skin), deform }
    }
}

/// What solving a path constraint reuses from pose to pose.
#[derive(Debug, Clone, Default)]
pub struct PathScratch {
    vertices: Vec<[f64; 2]>,
    distances: Vec<f64>,
    points: Vec<spline::Point>,
    lengths: Vec<f64>,
    ends: Vec<f64>,
}

/// The constraint's bones being moved: `world[i]` is bone `bones[i]`'s world transform as
/// updated so far (changed in place), `length[i]` its length (the file's, before scale).
#[derive(Debug)]
pub struct Chain<'a> {
    /// The bones' world transforms.
    pub world: &'a mut [Affine],
    /// The bones' lengths.
    pub length: &'a [f64],
}

/// Moves the constraint's bones (`chain`) along `followed`. `bones_world` gives the world
/// transform of any bone (for the path's vertices).
pub fn solve(
    c: &PathConstraint,
    s: &PathSettings,
    bones_world: &dyn Fn(usize) -> Affine,
    followed: Followed<'_>,
    chain_bones: Chain<'_>,
    scratch: &mut PathScratch,
) {
    let Chain { world, length } = chain_bones;
    let Followed { shape: Some(path), deform } = followed else { return };
    if (s.mix_rotate == 0.0 && s.mix_x == 0.0 && s.mix_y == 0.0) || world.is_empty() {
        return;
    }
    let chain = c.rotate_mode.chain();
    spline::world_vertices(path, &bones_world(c.slot_bone), bones_world, deform, &mut scratch.vertices);
    let Some(total) = spline::ends(path, &scratch.vertices, &mut scratch.ends) else { return };
    // Each bone's world length (its length along its world x axis).
    scratch.lengths.clear();
    scratch.lengths.extend(world.iter().zip(length).map(|(w, l)| l * math::hypot(w.a, w.c)));
    distances(c, s, total, &scratch.lengths, chain, &mut scratch.distances);
    spline::points(path, &scratch.vertices, &scratch.ends, &scratch.distances, &mut scratch.points);
    let p = &scratch.points;
    for (i, w) in world.iter_mut().enumerate() {
        let here = p[i];
        w.x += (here.x - w.x) * s.mix_x;
        w.y += (here.y - w.y) * s.mix_y;
        let goal = if chain {
            let next = p[i + 1];
            let (dx, dy) = (next.x - here.x, next.y - here.y);
            if c.rotate_mode == RotateMode::ChainScale && scratch.lengths[i] != 0.0 {
                let k = (math::hypot(dx, dy) / scratch.lengths[i] - 1.0) * s.mix_rotate + 1.0;
                w.a *= k;
                w.c *= k;
            }
            math::atan2(dy, dx)
        } else {
            here.angle
        };
        if s.mix_rotate == 0.0 {
            continue;
        }
        let r = wrap(goal - math::atan2(w.c, w.a) + c.rotation) * s.mix_rotate;
        w.turn(r);
    }
}

/// An angle wrapped to `[−π, π]`.
fn wrap(r: f64) -> f64 {
    if r > PI {
        r - 2.0 * PI
    } else if r < -PI {
        r + 2.0 * PI
    } else {
        r
    }
}

/// The distances along the path of the bones' points (one more, the last tip, in chain modes).
fn distances(c: &PathConstraint, s: &PathSettings, total: f64, lengths: &[f64], chain: bool, out: &mut Vec<f64>) {
    out.clear();
    let mut at = match c.position_mode {
        PositionMode::Fixed => s.position,
        PositionMode::Percent => s.position * total,
    };
    let sum: f64 = lengths.iter().sum();
    let n = lengths.len() + usize::from(chain);
    for i in 0..n {
        out.push(at);
        let Some(&l) = lengths.get(i) else { break };
        at += match c.spacing_mode {
            SpacingMode::Fixed => s.spacing,
            SpacingMode::Percent => s.spacing * total,
            SpacingMode::Length => l + s.spacing,
            SpacingMode::Proportional if sum > 0.0 => l / sum * s.spacing * total,
            SpacingMode::Proportional => 0.0,
        };
    }
}

#[cfg(test)]
#[path = "path_tests.rs"]
mod tests;
