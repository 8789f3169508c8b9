//! Why a [`Skeleton`](super::Skeleton) is invalid: one variant per problem, each naming the bone
//! (by index and name), the field and the offending value.

use thiserror::Error;

use super::MAX_REACH;
use crate::limits::LimitsError;
use crate::number::Num;

/// Which number of a bone an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoneField {
    /// [`Bone::length`](super::Bone::length).
    Length,
    /// [`Bone::angle`](super::Bone::angle).
    Angle,
    /// [`Bone::limits`](super::Bone::limits).
    Limits,
    /// [`Bone::stiffness`](super::Bone::stiffness).
    Stiffness,
    /// [`Bone::rest`](super::Bone::rest).
    Rest,
    /// [`Bone::offset`](super::Bone::offset).
    Offset,
    /// A prismatic joint's slide ([`Joint::Prismatic`](super::Joint::Prismatic)).
    Slide,
    /// A prismatic joint's extension ([`Joint::Prismatic`](super::Joint::Prismatic)).
    Extension,
}

impl std::fmt::Display for BoneField {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            BoneField::Length => "length",
            BoneField::Angle => "angle",
            BoneField::Limits => "limits",
            BoneField::Stiffness => "stiffness",
            BoneField::Rest => "rest",
            BoneField::Offset => "offset",
            BoneField::Slide => "slide",
            BoneField::Extension => "extension",
        })
    }
}

/// Why a [`Skeleton`](super::Skeleton), or angles for it, are invalid. Every variant about a
/// bone names it as `bones[i] ("name")`, `i` its index in the order given.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SkeletonError {
    /// The skeleton has no bones.
    #[error("bones: a skeleton needs at least one bone, got none")]
    Empty,
    /// A base coordinate is NaN or infinite.
    #[error("base: coordinates must be finite, got ({}, {})", Num(*.x), Num(*.y))]
    NonFiniteBase {
        /// x of the base.
        x: f64,
        /// y of the base.
        y: f64,
    },
    /// A bone's name is empty.
    #[error("bones[{index}].name: must not be empty")]
    EmptyName {
        /// Index of the bone, from 0.
        index: usize,
    },
    /// Two bones have the same name.
    #[error("bones[{index}] ({name:?}).name: the name of bones[{first}] already; names must be unique")]
    DuplicateName {
        /// Index of the later bone, from 0.
        index: usize,
        /// The name both have.
        name: String,
        /// Index of the first bone of that name.
        first: usize,
    },
    /// A bone's number is NaN or infinite.
    #[error("bones[{index}] ({name:?}).{field}: must be a finite number, got {}", Num(*.value))]
    NonFinite {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// Which number.
        field: BoneField,
        /// The offending value.
        value: f64,
    },
    /// A bone's pair of numbers (its offset or slide) holds a NaN or an infinity.
    #[error("bones[{index}] ({name:?}).{field}: must be finite numbers, got [{}, {}]", Num(*.x), Num(*.y))]
    NonFinitePair {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// Which pair.
        field: BoneField,
        /// The first number.
        x: f64,
        /// The second number.
        y: f64,
    },
    /// A prismatic joint's slide is the zero vector: it has no direction.
    #[error("bones[{index}] ({name:?}).slide: must not be zero, got [{}, {}]", Num(*.x), Num(*.y))]
    ZeroSlide {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// x of the slide.
        x: f64,
        /// y of the slide.
        y: f64,
    },
    /// A prismatic joint's displacement (its extension, rest or a pose's value) lies outside
    /// its limits (length units).
    #[error(
        "bones[{index}] ({name:?}).{field}: {} lies outside the limits [{}, {}]",
        Num(*.value),
        Num(*.min),
        Num(*.max)
    )]
    ExtensionOutsideLimits {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// Which value: the extension or the rest.
        field: BoneField,
        /// The offending displacement.
        value: f64,
        /// Lower limit.
        min: f64,
        /// Upper limit.
        max: f64,
    },
    /// A bone's length is zero or negative.
    #[error("bones[{index}] ({name:?}).length: must be greater than 0, got {}", Num(*.value))]
    NonPositiveLength {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// The offending value.
        value: f64,
    },
    /// A bone's limits are malformed (for callers that build limits from raw numbers and want
    /// the error to name the bone).
    #[error("bones[{index}] ({name:?}).limits: {source}")]
    Limits {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// What is wrong with them.
        source: LimitsError,
    },
    /// A bone's parent names no bone.
    #[error("bones[{index}] ({name:?}).parent = {parent:?}: no bone of that name")]
    UnknownParent {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// The parent it names.
        parent: String,
    },
    /// Following parents from a bone comes back to it: the bones do not form a tree.
    #[error(
        "bones[{index}] ({name:?}).parent = {parent:?}: a cycle ({}); a bone cannot be its own ancestor",
        cycle.join(" → ")
    )]
    Cycle {
        /// Index of the first bone (in the order given) that lies on the cycle.
        index: usize,
        /// Its name.
        name: String,
        /// The parent it names.
        parent: String,
        /// The names around the cycle, from this bone up its parents and back to it.
        cycle: Vec<String>,
    },
    /// A bone's angle lies outside its limits.
    #[error(
        "bones[{index}] ({name:?}).angle: {} rad lies outside the limits [{}, {}] rad",
        Num(*.value),
        Num(*.min),
        Num(*.max)
    )]
    AngleOutsideLimits {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// The offending angle, radians.
        value: f64,
        /// Lower limit, radians.
        min: f64,
        /// Upper limit, radians.
        max: f64,
    },
    /// A bone's stiffness is negative.
    #[error("bones[{index}] ({name:?}).stiffness: must be 0 or more, got {}", Num(*.value))]
    NegativeStiffness {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// The offending value.
        value: f64,
    },
    /// A bone's rest angle lies outside its limits.
    #[error(
        "bones[{index}] ({name:?}).rest: {} rad lies outside the limits [{}, {}] rad",
        Num(*.value),
        Num(*.min),
        Num(*.max)
    )]
    RestOutsideLimits {
        /// Index of the bone, from 0.
        index: usize,
        /// Its name.
        name: String,
        /// The offending angle, radians.
        value: f64,
        /// Lower limit, radians.
        min: f64,
        /// Upper limit, radians.
        max: f64,
    },
    /// The skeleton's reach (its longest path from a root to a tip, plus the base's distance
    /// from the origin) is beyond [`MAX_REACH`] or not a finite number.
    #[error(
        "bones: the longest path of lengths reaches {} from the origin, beyond {}, the largest reach ikarus computes with",
        Num(*.reach),
        Num(MAX_REACH)
    )]
    ReachTooLarge {
        /// The longest root-to-tip path plus the base's distance from the origin.
        reach: f64,
    },
    /// Angles for the skeleton are not one per bone.
    #[error("angles: expected {expected} (one per bone), got {got}")]
    AnglesLength {
        /// Number of bones.
        expected: usize,
        /// Number of angles given.
        got: usize,
    },
}
