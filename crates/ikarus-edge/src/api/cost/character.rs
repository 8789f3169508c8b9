//! What a character job costs (`/api/pose`, `/api/animate`, `/api/track`, `/api/render` with a
//! character, and `/api/rig/parse`): the file's reading, linear in its bytes, and each pose's
//! work, from the character's bones and constraints.
//!
//! A pose under the runtime's rules updates every bone once and, after each constraint, the
//! bones below the constraint's (at worst all of them): `bones + constraints × bones` bone
//! updates, each about a link step. Under ikarus's rules (`"ik": "ikarus"`) it adds up to
//! `ikarus::character::ROUNDS` rig solves of the moving bones (at most two a constraint or
//! goal, and the pins) toward every constraint, goal and pin, at most the iterations of the
//! edge's `character_options` each, each halving its step up to its `backtrack` times.
//!
//! A job that reads its character before it runs ([`Character::of_loaded`]) costs from what it
//! read; a figure of `/api/render`, which reads it as it draws, costs from the file's counts
//! ([`Character::of_request`]: a lenient pass that allocates nothing for what it skips).

use std::fmt;

use serde::Deserialize;
use serde::de::{Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::super::rigs::FileBody;
use crate::character::{Loaded, is_json, store};

/// Link steps to read a byte of a character file (parse, check, index): a megabyte is about a
/// tenth of a second.
pub const BYTE_STEPS: f64 = 4.0;

/// Bytes of JSON text a byte of a `.skel` may decode into at most, and the bytes any `.skel` may
/// add: the decoder lets its string references copy up to 16 times the file and a mebibyte
/// (`crate::character::skel`), and writes a 4-byte float in at most about 17 characters.
pub const SKEL_TEXT_BYTES: (f64, f64) = (16.0 + 5.0, (1 << 20) as f64);

/// The work of `/api/rig/parse` (and `/api/arm/parse`) in link steps: reading its text, a
/// `.skel`'s bytes as the most text they may decode into ([`SKEL_TEXT_BYTES`]).
#[must_use]
pub fn file_bytes(given: FileBody, body: &[u8]) -> f64 {
    let bytes = body.len() as f64;
    let text = match given {
        FileBody::Text => bytes,
        FileBody::Bytes => bytes * SKEL_TEXT_BYTES.0 + SKEL_TEXT_BYTES.1,
    };
    text * BYTE_STEPS
}

/// A character's size and counts.
#[derive(Debug, Default, Clone, Copy)]
pub struct Character {
    bytes: f64,
    bones: f64,
    constraints: f64,
}

impl Character {
    /// A character read for this request: its file's `text` when it came with the request
    /// (reading it counts), none when it was kept ([`store`]: read when it was kept).
    #[must_use]
    pub fn of_loaded(loaded: &Loaded, text: Option<&str>) -> Self {
        let c = &loaded.character;
        Character {
            bytes: text.map_or(0.0, |t| t.len() as f64),
            bones: c.bones().len() as f64,
            constraints: (c.constraints().len() + c.unsupported().len()) as f64,
        }
    }

    /// The character a request names, not yet read: its file's text `rig` (counted), or the
    /// kept one `id` names. None when neither is given or the id is not kept (refused at once).
    #[must_use]
    pub fn of_request(rig: Option<&str>, id: Option<&str>) -> Option<Self> {
        match rig {
            Some(text) => is_json(text).then(|| Character::read(text)),
            None => store::global().get(id?).map(|stored| Character::of_loaded(&stored.loaded, None)),
        }
    }

    /// The counts of `text` (a file that is not JSON counts its bytes only).
    fn read(text: &str) -> Self {
        let shape = serde_json::from_str::<FileShape>(text).unwrap_or_default();
        let constraints = shape.ik.0 + shape.transform.0 + shape.path.0 + shape.physics.0;
        Character {
            bytes: text.len() as f64,
            bones: (shape.bones.0 + shape.armature.bones).max(1.0),
            constraints: constraints + shape.armature.constraints,
        }
    }

    /// Reading the file.
    #[must_use]
    pub fn parse(&self) -> f64 {
        self.bytes * BYTE_STEPS
    }

    /// One pose, under the runtime's rules or ikarus's with goals and pins besides the
    /// constraints.
    #[must_use]
    pub fn pose(&self, rules: Rules) -> f64 {
        let runtime = self.bones + self.constraints * self.bones;
        match rules {
            Rules::Runtime => runtime,
            Rules::Ikarus { goals, pins } => {
                let targets = self.constraints + goals + pins;
                let moving = self.bones.min(2.0 * (self.constraints + goals) + pins).max(1.0);
                let rounds = ikarus::character::ROUNDS as f64;
                // The character solve's iteration cap and step halvings.
                let options = crate::pose::character_options();
                let (iterations, backtrack) = (f64::from(options.max_iterations), f64::from(options.backtrack));
                runtime + rounds * moving * (1.0 + targets) * iterations * (1.0 + backtrack)
            }
        }
    }
}

/// Whose rules a character job's poses follow.
#[derive(Debug, Clone, Copy)]
pub enum Rules {
    /// The runtime's (the default).
    Runtime,
    /// ikarus's solver, with the request's goals and pins.
    Ikarus {
        /// How many goals the request has.
        goals: f64,
        /// How many pins the request has.
        pins: f64,
    },
}

impl Rules {
    /// The rules a request's `ik` asks for, with its goals and pins.
    #[must_use]
    pub fn of(ik: Option<&str>, goals: f64, pins: f64) -> Self {
        if ik == Some("ikarus") { Rules::Ikarus { goals, pins } } else { Rules::Runtime }
    }
}

/// An array's length, or 0 (any other value).
#[derive(Debug, Default)]
struct Count(f64);

/// The counts of a Spine or DragonBones file: every armature's bones and IK constraints.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct FileShape {
    bones: Count,
    ik: Count,
    transform: Count,
    path: Count,
    physics: Count,
    armature: Armatures,
}

/// A DragonBones armature's counts.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct ArmatureShape {
    bone: Count,
    ik: Count,
}

/// Every armature's bones and constraints, summed.
#[derive(Debug, Default)]
struct Armatures {
    bones: f64,
    constraints: f64,
}

/// An armature, or nothing (any other value).
#[derive(Debug, Default)]
struct MaybeArmature(Option<ArmatureShape>);

/// Anything but the shape expected is absent: a visitor's every other method says so.
macro_rules! absent_otherwise {
    ($value:ty) => {
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("any JSON value")
        }
        fn visit_bool<E>(self, _: bool) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_i64<E>(self, _: i64) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_u64<E>(self, _: u64) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_f64<E>(self, _: f64) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_str<E>(self, _: &str) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_unit<E>(self) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_none<E>(self) -> Result<$value, E> {
            Ok(<$value>::default())
        }
    };
}

/// Skips the entries of a map it does not keep.
fn skip_map<'de, A: MapAccess<'de>>(mut map: A) -> Result<(), A::Error> {
    while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
    Ok(())
}

struct CountValue;

impl<'de> Visitor<'de> for CountValue {
    type Value = Count;

    absent_otherwise!(Count);

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Count, A::Error> {
        let mut n = 0.0;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            n += 1.0;
        }
        Ok(Count(n))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Count, A::Error> {
        skip_map(map).map(|()| Count(0.0))
    }
}

impl<'de> Deserialize<'de> for Count {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(CountValue)
    }
}

struct ArmatureValue;

impl<'de> Visitor<'de> for ArmatureValue {
    type Value = MaybeArmature;

    absent_otherwise!(MaybeArmature);

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<MaybeArmature, A::Error> {
        ArmatureShape::deserialize(serde::de::value::MapAccessDeserializer::new(map)).map(|a| MaybeArmature(Some(a)))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<MaybeArmature, A::Error> {
        CountValue.visit_seq(seq).map(|_| MaybeArmature(None))
    }
}

impl<'de> Deserialize<'de> for MaybeArmature {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ArmatureValue)
    }
}

struct ArmaturesValue;

impl<'de> Visitor<'de> for ArmaturesValue {
    type Value = Armatures;

    absent_otherwise!(Armatures);

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Armatures, A::Error> {
        let mut all = Armatures::default();
        while let Some(a) = seq.next_element::<MaybeArmature>()? {
            if let Some(a) = a.0 {
                all.bones += a.bone.0;
                all.constraints += a.ik.0;
            }
        }
        Ok(all)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Armatures, A::Error> {
        skip_map(map).map(|()| Armatures::default())
    }
}

impl<'de> Deserialize<'de> for Armatures {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ArmaturesValue)
    }
}
