//! What [`super::Character::new`] refuses: a character that breaks the model's rules, named by
//! index (the edge names fields and values in its own messages).

use thiserror::Error;

/// A character that breaks the model's rules. The edge reads files by name and words its own
/// errors; these name indices.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CharacterError {
    /// The slots or attachments break a rule of [`super::Art`].
    #[error("art: {what}")]
    Art {
        /// What is wrong, with where.
        what: String,
    },
    /// The character has no bones.
    #[error("bones: a character needs at least one bone, got none")]
    NoBones,
    /// A bone's parent is not listed before it.
    #[error("bones[{bone}].parent: {parent} is not an earlier bone")]
    ParentOrder {
        /// The bone's index.
        bone: usize,
        /// Its parent's index.
        parent: usize,
    },
    /// A bone's number is NaN or infinite.
    #[error("bones[{bone}].{field}: must be finite, got {value}")]
    NotFinite {
        /// The bone's index.
        bone: usize,
        /// The field's name in Spine's terms.
        field: &'static str,
        /// The value found.
        value: f64,
    },
    /// The skeleton's reference scale is not a positive finite number.
    #[error("skeleton.referenceScale: must be positive and finite, got {value}")]
    ReferenceScale {
        /// The value found.
        value: f64,
    },
    /// A bone's length is negative.
    #[error("bones[{bone}].length: must not be negative, got {value}")]
    NegativeLength {
        /// The bone's index.
        bone: usize,
        /// The value found.
        value: f64,
    },
    /// A constraint names a bone that does not exist.
    #[error("ik[{constraint}]: bone {bone} does not exist")]
    MissingBone {
        /// The constraint's index.
        constraint: usize,
        /// The bone index named.
        bone: usize,
    },
    /// A two-bone constraint's second bone is not the first one's child.
    #[error("ik[{constraint}].bones: bone {child} is not a child of bone {parent}")]
    NotParentChild {
        /// The constraint's index.
        constraint: usize,
        /// The first bone's index.
        parent: usize,
        /// The second bone's index.
        child: usize,
    },
    /// A constraint's mix is outside [0, 1] or its softness negative or not finite.
    #[error("ik[{constraint}].{field}: out of range, got {value}")]
    Setting {
        /// The constraint's index.
        constraint: usize,
        /// `mix` or `softness`.
        field: &'static str,
        /// The value found.
        value: f64,
    },
    /// A path constraint names a bone that does not exist.
    #[error("path constraint {constraint}: bone {bone} does not exist")]
    PathBone {
        /// The constraint's index.
        constraint: usize,
        /// The bone's index.
        bone: usize,
    },
    /// A path constraint's setting is out of range (a mix outside −1 … 1, a value not finite).
    #[error("path constraint {constraint}.{field}: out of range, got {value}")]
    PathSetting {
        /// The constraint's index.
        constraint: usize,
        /// The field: `mixRotate`, `position`, …
        field: &'static str,
        /// The value found.
        value: f64,
    },
    /// A path constraint has a path for a skin that does not exist.
    #[error("path constraint {constraint}: a path for skin {skin}, which does not exist")]
    PathSkin {
        /// The constraint's index.
        constraint: usize,
        /// The skin's index.
        skin: usize,
    },
    /// A timeline names a bone or constraint that does not exist.
    #[error("clips[{clip}]: a timeline names {what} {index}, which does not exist")]
    MissingTarget {
        /// The clip's index.
        clip: usize,
        /// `bone` or `constraint`.
        what: &'static str,
        /// The index named.
        index: usize,
    },
    /// A key's time is not finite, negative, or not after the previous key's.
    #[error("clips[{clip}]: a key's time must be finite, at least 0 and after the previous key's, got {time}")]
    KeyTime {
        /// The clip's index.
        clip: usize,
        /// The time found.
        time: f64,
    },
    /// A transform constraint names a bone that does not exist.
    #[error("transform[{constraint}]: bone {bone} does not exist")]
    TransformBone {
        /// The constraint's index.
        constraint: usize,
        /// The bone index named.
        bone: usize,
    },
    /// A constraint's offset or mix (of a kind that takes any number) is NaN or infinite.
    #[error("constraints[{constraint}].{field}: must be finite, got {value}")]
    NotFiniteSetting {
        /// The constraint's index.
        constraint: usize,
        /// The field's name in Spine's terms.
        field: &'static str,
        /// The value found.
        value: f64,
    },
    /// A constraint timeline's keys are of another kind than its constraint.
    #[error("a timeline of constraint {constraint} keys {keys} settings, but it is a {kind} constraint")]
    TimelineKind {
        /// The constraint's index.
        constraint: usize,
        /// The keys' kind.
        keys: &'static str,
        /// The constraint's kind.
        kind: &'static str,
    },
    /// A skin (or the list of what only a skin turns on) names a bone or constraint that does
    /// not exist.
    #[error("{}: {what} {index} does not exist", skin.map_or("skin-required".to_owned(), |s| format!("skins[{s}]")))]
    SkinIndex {
        /// The skin's index (`None`: the skin-required list).
        skin: Option<usize>,
        /// `bone` or `constraint`.
        what: &'static str,
        /// The index named.
        index: usize,
    },
    /// A key's value is NaN or infinite.
    #[error("clips[{clip}]: a key's value must be finite, got {value}")]
    KeyValue {
        /// The clip's index.
        clip: usize,
        /// The value found.
        value: f64,
    },
    /// A physics constraint's bone does not exist.
    #[error("physics constraints[{constraint}]: bone {bone} does not exist")]
    PhysicsBone {
        /// The constraint's index.
        constraint: usize,
        /// The bone named.
        bone: usize,
    },
    /// A physics constraint's value (or a key of it) is out of range.
    #[error("physics constraints[{constraint}].{field}: out of range, got {value}")]
    PhysicsValue {
        /// The constraint's index.
        constraint: usize,
        /// The field: `fps`, `mass`, `limit`, `strength`, …
        field: &'static str,
        /// The value found.
        value: f64,
    },
}
