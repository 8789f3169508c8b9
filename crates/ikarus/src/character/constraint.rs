//! One constraint model for every kind a character file has: the constraints in one list,
//! applied in one update order across kinds (by `order`, ties as listed), each kind's
//! settings in one [`Settings`] the clips key through [`ConstraintKeys`].
//!
//! A new kind is a new file beside this one (its constraint, its settings, how it applies)
//! plus one arm in each enum here; the compiler then shows every match that must learn it.
//!
//! How posing updates the bones after a constraint ([`Updates`]): an IK constraint sets its
//! bones' local rotations (and scales) and recomputes its top bone and every bone below it
//! from them; a kind that writes world transforms directly (transform, path, physics, as
//! Spine's runtime does) sets its bones' world matrices, recomputes their applied local
//! transforms from them ([`super::world::Bones::set_world`]), and leaves to posing the bones
//! strictly below them.

use super::flat::Updates;
use super::transform::{TransformConstraint, TransformSettings, TransformSpace, check_mixes};
use super::{CharacterBone, CharacterError, DeformKey, IkBones, IkConstraint, IkKey, IkSettings, Interpolation};
use super::{PathConstraint, PathSettings, PhysicsConstraint, PhysicsProperty, PhysicsSettings};

/// A constraint of any kind.
#[derive(Debug, Clone, PartialEq)]
pub enum Constraint {
    /// Inverse kinematics: one bone aims, or two bones reach, for a target bone.
    Ik(IkConstraint),
    /// Path: bones moved along, and turned with, the path a slot shows.
    Path(PathConstraint),
    /// Physics (Spine 4.2): one bone swings, lags and settles as a damped spring.
    Physics(PhysicsConstraint),
    /// Transform: bones follow a target bone's rotation, translation, scale and shear by six
    /// mixes.
    Transform(TransformConstraint),
}

/// A constraint's settings that clips can key (its mixes and the like), of its kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Settings {
    /// An IK constraint's.
    Ik(IkSettings),
    /// A path constraint's.
    Path(PathSettings),
    /// A physics constraint's.
    Physics(PhysicsSettings),
    /// A transform constraint's mixes.
    Transform(TransformSettings),
}

impl Constraint {
    /// Its name in the file.
    pub fn name(&self) -> &str {
        match self {
            Constraint::Ik(c) => &c.name,
            Constraint::Path(c) => &c.name,
            Constraint::Physics(c) => &c.name,
            Constraint::Transform(c) => &c.name,
        }
    }

    /// Constraints apply in increasing `order`; ties in the order they are listed.
    pub fn order(&self) -> u32 {
        match self {
            Constraint::Ik(c) => c.order,
            Constraint::Path(c) => c.order,
            Constraint::Physics(c) => c.order,
            Constraint::Transform(c) => c.order,
        }
    }

    /// The kind as the file names its list: `ik`, `transform`, `path`, `physics`.
    pub fn kind(&self) -> &'static str {
        match self {
            Constraint::Ik(_) => "ik",
            Constraint::Path(_) => "path",
            Constraint::Physics(_) => "physics",
            Constraint::Transform(_) => "transform",
        }
    }

    /// The IK constraint, if it is one.
    pub fn ik(&self) -> Option<&IkConstraint> {
        match self {
            Constraint::Ik(c) => Some(c),
            Constraint::Path(_) => None,
            Constraint::Physics(_) => None,
            Constraint::Transform(_) => None,
        }
    }

    /// The path constraint, if it is one.
    pub fn path(&self) -> Option<&PathConstraint> {
        match self {
            Constraint::Path(c) => Some(c),
            Constraint::Ik(_) | Constraint::Physics(_) | Constraint::Transform(_) => None,
        }
    }

    /// The IK constraint, if it is one, to change.
    pub fn ik_mut(&mut self) -> Option<&mut IkConstraint> {
        match self {
            Constraint::Ik(c) => Some(c),
            Constraint::Path(_) => None,
            Constraint::Physics(_) => None,
            Constraint::Transform(_) => None,
        }
    }

    /// Its settings in the setup pose.
    pub fn setup(&self) -> Settings {
        match self {
            Constraint::Ik(c) => Settings::Ik(c.setup),
            Constraint::Path(c) => Settings::Path(c.setup),
            Constraint::Physics(c) => Settings::Physics(c.setup),
            Constraint::Transform(c) => Settings::Transform(c.setup),
        }
    }

    /// The bones posing recomputes after it.
    pub(crate) fn updates(&self) -> Updates<'_> {
        match self {
            Constraint::Ik(c) => Updates::Subtree(c.top()),
            Constraint::Path(c) => Updates::Below(&c.bones),
            Constraint::Physics(c) => Updates::Below(std::slice::from_ref(&c.bone)),
            // Local or world, the constraint leaves its bones' world transforms up to date.
            Constraint::Transform(c) => match c.space {
                TransformSpace::World | TransformSpace::Local => Updates::Below(&c.bones),
            },
        }
    }

    /// Checks it against the character's `bones` (constraint `k` of the list).
    pub(crate) fn check(&self, k: usize, bones: &[CharacterBone]) -> Result<(), CharacterError> {
        match self {
            Constraint::Ik(c) => c.check(k, bones),
            Constraint::Path(c) => c.check(k, bones),
            Constraint::Physics(c) => c.check(k, bones),
            Constraint::Transform(c) => c.check(k, bones.len()),
        }
    }
}

impl From<IkConstraint> for Constraint {
    fn from(c: IkConstraint) -> Self {
        Constraint::Ik(c)
    }
}

impl From<TransformConstraint> for Constraint {
    fn from(c: TransformConstraint) -> Self {
        Constraint::Transform(c)
    }
}

impl Settings {
    /// An IK constraint's settings, if these are.
    pub fn ik(&self) -> Option<&IkSettings> {
        match self {
            Settings::Ik(s) => Some(s),
            Settings::Path(_) => None,
            Settings::Physics(_) => None,
            Settings::Transform(_) => None,
        }
    }

    /// A transform constraint's mixes, if these are.
    pub fn transform(&self) -> Option<&TransformSettings> {
        match self {
            Settings::Transform(s) => Some(s),
            Settings::Ik(_) | Settings::Path(_) | Settings::Physics(_) => None,
        }
    }
}

impl IkConstraint {
    /// The constraint's top bone: its one bone, or the parent of its two.
    pub(crate) fn top(&self) -> usize {
        match self.bones {
            IkBones::One(b) | IkBones::Two { parent: b, .. } => b,
        }
    }

    fn check(&self, c: usize, bones: &[CharacterBone]) -> Result<(), CharacterError> {
        let n = bones.len();
        let missing = |bone: usize| CharacterError::MissingBone { constraint: c, bone };
        match self.bones {
            IkBones::One(b) if b >= n => return Err(missing(b)),
            IkBones::Two { parent, .. } if parent >= n => return Err(missing(parent)),
            IkBones::Two { child, .. } if child >= n => return Err(missing(child)),
            IkBones::Two { parent, child } if bones[child].parent != Some(parent) => {
                return Err(CharacterError::NotParentChild { constraint: c, parent, child });
            }
            IkBones::One(_) | IkBones::Two { .. } => {}
        }
        if self.target >= n {
            return Err(missing(self.target));
        }
        super::check_settings(c, &self.setup)
    }
}

/// The most channels a key of a constraint timeline holds (a transform constraint's six mixes).
pub const MAX_CHANNELS: usize = 6;

/// One key of a constraint timeline whose values are numbers only (mixes, positions,
/// strengths): `values[..channels]` are used, each with its curve toward the next key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChannelKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The key's values.
    pub values: [f64; MAX_CHANNELS],
    /// Per channel, toward the next key (ignored on the last key).
    pub curves: [Interpolation; MAX_CHANNELS],
}

/// A constraint timeline's keys, of the constraint's kind.
#[derive(Debug, Clone, PartialEq)]
pub enum ConstraintKeys {
    /// An IK constraint's: mix and softness (curved), the flags (stepped).
    Ik(Vec<IkKey>),
    /// A path constraint's `position` (one channel).
    PathPosition(Vec<ChannelKey>),
    /// A path constraint's `spacing` (one channel).
    PathSpacing(Vec<ChannelKey>),
    /// A path constraint's mixes: `mixRotate`, `mixX`, `mixY` (three channels).
    PathMix(Vec<ChannelKey>),
    /// The offsets a clip adds to the vertices of the path the constraint follows (a deform
    /// timeline of its slot's path attachment); its one curve goes from 0 to 1 between keys and
    /// is sampled when posing, not precomputed (no channel).
    PathDeform {
        /// Whose attachment it deforms: `Some(s)` skin `s`'s own, `None` the default skin's
        /// ([`super::PathConstraint::path_source`]); it applies only while the pose follows
        /// that attachment.
        skin: Option<usize>,
        /// The keys.
        keys: Vec<DeformKey>,
    },
    /// A physics constraint's: one setting (channel 0: its value; a mass for
    /// [`PhysicsProperty::Mass`]).
    Physics {
        /// The setting keyed.
        property: PhysicsProperty,
        /// The keys.
        keys: Vec<ChannelKey>,
    },
    /// A physics constraint's `reset` keys: the simulation restarts when a play passes one
    /// (times only, no channel).
    PhysicsReset(Vec<ChannelKey>),
    /// A transform constraint's: its six mixes in [`TransformSettings::to_array`]'s order.
    Transform(Vec<ChannelKey>),
}

impl ConstraintKeys {
    /// How many keys.
    pub fn len(&self) -> usize {
        match self {
            ConstraintKeys::Ik(keys) => keys.len(),
            ConstraintKeys::PathPosition(keys) | ConstraintKeys::PathSpacing(keys) | ConstraintKeys::PathMix(keys) => {
                keys.len()
            }
            ConstraintKeys::PathDeform { keys, .. } => keys.len(),
            ConstraintKeys::Physics { keys, .. } | ConstraintKeys::PhysicsReset(keys) => keys.len(),
            ConstraintKeys::Transform(keys) => keys.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// An IK constraint's keys, if these are.
    pub fn ik(&self) -> Option<&[IkKey]> {
        match self {
            ConstraintKeys::Ik(keys) => Some(keys),
            ConstraintKeys::PathPosition(_)
            | ConstraintKeys::PathSpacing(_)
            | ConstraintKeys::PathMix(_)
            | ConstraintKeys::PathDeform { .. }
            | ConstraintKeys::Physics { .. }
            | ConstraintKeys::PhysicsReset(_)
            | ConstraintKeys::Transform(_) => None,
        }
    }

    /// Key `i`'s time.
    pub fn time(&self, i: usize) -> f64 {
        match self {
            ConstraintKeys::Ik(keys) => keys[i].time,
            ConstraintKeys::PathPosition(keys) | ConstraintKeys::PathSpacing(keys) | ConstraintKeys::PathMix(keys) => {
                keys[i].time
            }
            ConstraintKeys::PathDeform { keys, .. } => keys[i].time,
            ConstraintKeys::Physics { keys, .. } | ConstraintKeys::PhysicsReset(keys) => keys[i].time,
            ConstraintKeys::Transform(keys) => keys[i].time,
        }
    }

    /// How many curved channels a key has.
    pub(crate) fn channels(&self) -> usize {
        match self {
            ConstraintKeys::Ik(_) => 2,
            ConstraintKeys::PathPosition(_) | ConstraintKeys::PathSpacing(_) => 1,
            ConstraintKeys::PathMix(_) => 3,
            ConstraintKeys::PathDeform { .. } => 0,
            ConstraintKeys::Physics { .. } => 1,
            ConstraintKeys::PhysicsReset(_) => 0,
            ConstraintKeys::Transform(_) => 6,
        }
    }

    /// Key `i`'s curve and value on channel `ch`.
    pub(crate) fn channel(&self, i: usize, ch: usize) -> (Interpolation, f64) {
        match self {
            ConstraintKeys::Ik(keys) => {
                let k = &keys[i];
                (k.curves[ch], if ch == 0 { k.settings.mix } else { k.settings.softness })
            }
            ConstraintKeys::PathPosition(keys) | ConstraintKeys::PathSpacing(keys) | ConstraintKeys::PathMix(keys) => {
                (keys[i].curves[ch], keys[i].values[ch])
            }
            ConstraintKeys::PathDeform { keys, .. } => (keys[i].curve, 0.0),
            ConstraintKeys::Physics { keys, .. } | ConstraintKeys::PhysicsReset(keys) => {
                (keys[i].curves[ch], keys[i].values[ch])
            }
            ConstraintKeys::Transform(keys) => (keys[i].curves[ch], keys[i].values[ch]),
        }
    }

    /// Checks every key's values (the timeline of constraint `k`, which is `of`).
    pub(crate) fn check(&self, k: usize, of: &Constraint) -> Result<(), CharacterError> {
        match (self, of) {
            (ConstraintKeys::Ik(keys), Constraint::Ik(_)) => {
                keys.iter().try_for_each(|key| super::check_settings(k, &key.settings))
            }
            (
                ConstraintKeys::PathPosition(_)
                | ConstraintKeys::PathSpacing(_)
                | ConstraintKeys::PathMix(_)
                | ConstraintKeys::PathDeform { .. },
                Constraint::Path(_),
            ) => Ok(()),
            (ConstraintKeys::Physics { property, keys }, Constraint::Physics(_)) => keys.iter().try_for_each(|key| {
                let value = key.values[0];
                let bad = !value.is_finite() || (*property == PhysicsProperty::Mass && value <= 0.0);
                if bad {
                    Err(CharacterError::PhysicsValue { constraint: k, field: property.name(), value })
                } else {
                    Ok(())
                }
            }),
            (ConstraintKeys::PhysicsReset(_), Constraint::Physics(_)) => Ok(()),
            (ConstraintKeys::Transform(keys), Constraint::Transform(_)) => {
                keys.iter().try_for_each(|key| check_mixes(k, &TransformSettings::from_values(&key.values)))
            }
            (keys, of) => Err(CharacterError::TimelineKind { constraint: k, keys: keys.kind(), kind: of.kind() }),
        }
    }

    /// The kind of constraint whose settings these keys hold (`ik`, `transform`, …).
    pub fn kind(&self) -> &'static str {
        match self {
            ConstraintKeys::Ik(_) => "ik",
            ConstraintKeys::Transform(_) => "transform",
            ConstraintKeys::PathPosition(_)
            | ConstraintKeys::PathSpacing(_)
            | ConstraintKeys::PathMix(_)
            | ConstraintKeys::PathDeform { .. } => "path",
            ConstraintKeys::Physics { .. } | ConstraintKeys::PhysicsReset(_) => "physics",
        }
    }
}

/// A constraint's timeline, keys in increasing time.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintTimeline {
    /// The constraint's index.
    pub constraint: usize,
    /// The keys, of the constraint's kind.
    pub keys: ConstraintKeys,
}
