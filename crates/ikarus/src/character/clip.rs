//! A character's animation clips: timelines over the bones' local transforms and the
//! constraints' settings, keyed with linear, stepped and Bézier curves.

use super::{ConstraintTimeline, IkSettings};

/// A named animation: timelines over the bones' local transforms and the constraints'
/// settings. Times are seconds from the clip's start.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    /// Its name in the file.
    pub name: String,
    /// The latest key time of any timeline.
    pub duration: f64,
    /// The bones' timelines.
    pub bones: Vec<BoneTimeline>,
    /// The constraints' timelines.
    pub constraints: Vec<ConstraintTimeline>,
}

/// What a bone timeline keys. Rotation, translation and shear keys add to the setup values;
/// scale keys multiply the setup scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoneProperty {
    /// One channel: radians.
    Rotate,
    /// Two channels: x, y.
    Translate,
    /// One channel: x.
    TranslateX,
    /// One channel: y.
    TranslateY,
    /// Two channels: x, y.
    Scale,
    /// One channel: x.
    ScaleX,
    /// One channel: y.
    ScaleY,
    /// Two channels, radians: x, y.
    Shear,
    /// One channel, radians: x.
    ShearX,
    /// One channel, radians: y.
    ShearY,
}

impl BoneProperty {
    /// How many values a key of this property holds (1 or 2).
    pub fn channels(self) -> usize {
        match self {
            BoneProperty::Translate | BoneProperty::Scale | BoneProperty::Shear => 2,
            BoneProperty::Rotate
            | BoneProperty::TranslateX
            | BoneProperty::TranslateY
            | BoneProperty::ScaleX
            | BoneProperty::ScaleY
            | BoneProperty::ShearX
            | BoneProperty::ShearY => 1,
        }
    }
}

/// How a channel goes from a key to the next.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Interpolation {
    /// A straight line to the next key's value.
    Linear,
    /// Holds the key's value until the next key.
    Stepped,
    /// A cubic Bézier from `(time, value)` of this key to that of the next, with these two
    /// control points `[time, value]` in absolute units (Spine 4's `curve` numbers).
    Bezier {
        /// The first control point, `[time, value]`.
        c1: [f64; 2],
        /// The second control point, `[time, value]`.
        c2: [f64; 2],
    },
}

/// One key of a bone timeline: `values[..channels]` are used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoneKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The key's values (`channels()` of them).
    pub values: [f64; 2],
    /// Per channel, toward the next key (ignored on the last key).
    pub curves: [Interpolation; 2],
}

/// A bone's timeline for one property, keys in increasing time.
#[derive(Debug, Clone, PartialEq)]
pub struct BoneTimeline {
    /// The bone's index.
    pub bone: usize,
    /// What the keys hold.
    pub property: BoneProperty,
    /// The keys, in increasing time.
    pub keys: Vec<BoneKey>,
}

/// One key of an IK constraint's timeline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IkKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The settings at this key.
    pub settings: IkSettings,
    /// Toward the next key, for `mix` and `softness` (the flags are stepped).
    pub curves: [Interpolation; 2],
}
