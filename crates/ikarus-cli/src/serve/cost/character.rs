//! What a character job costs (`/api/pose`, `/api/animate`, `/api/track`, `/api/render` with a
//! character file's text as `rig`, and `/api/rig/parse`): the file's reading, linear in its
//! bytes, and each pose's work, read from the file's counts by a lenient pass that allocates
//! nothing for what it skips.
//!
//! A pose under the runtime's rules updates every bone once and, after each constraint, the
//! bones below the constraint's (at worst all of them): `bones + constraints × bones` bone
//! updates, each about a link step. Under ikarus's rules (`"ik": "ikarus"`) it adds up to
//! [`ROUNDS`] rig solves of the moving bones (at most two a constraint or goal, and the pins)
//! toward every constraint, goal and pin, at most the iterations of the edge's
//! `character_options` each, each halving its step up to its `backtrack` times.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};

use super::{Body, Count, Nested, QUICK_COST};
use crate::api::rigs::FileBody;
use crate::serve::pool::Lane;

/// Link steps to read a byte of a character file (parse, check, index): a megabyte is about a
/// tenth of a second, [`super::QUICK_COST`] about 600 kB.
pub(super) const BYTE_STEPS: f64 = 4.0;

/// Bytes of JSON text a byte of a `.skel` may decode into at most, and the bytes any `.skel` may
/// add: the decoder lets its string references copy up to 16 times the file and a mebibyte
/// (`ikarus_edge::character::skel`), and writes a 4-byte float in at most about 17 characters.
pub const SKEL_TEXT_BYTES: (f64, f64) = (16.0 + 5.0, (1 << 20) as f64);

/// The lane of `/api/rig/parse` with a body held as `given`.
pub fn file_lane(given: FileBody, body: &[u8]) -> Lane {
    if file_estimate(given, body) <= QUICK_COST { Lane::Quick } else { Lane::Long }
}

/// The work of `/api/rig/parse` in link steps: reading its text, a `.skel`'s bytes as the most
/// text they may decode into ([`SKEL_TEXT_BYTES`]).
pub fn file_estimate(given: FileBody, body: &[u8]) -> f64 {
    let bytes = body.len() as f64;
    let text = match given {
        FileBody::Text => bytes,
        FileBody::Bytes => bytes * SKEL_TEXT_BYTES.0 + SKEL_TEXT_BYTES.1,
    };
    text * BYTE_STEPS
}

/// How many times at most a solve together is run (`ikarus::character::ROUNDS`).
const ROUNDS: f64 = ikarus::character::ROUNDS as f64;

/// A character file's size and counts.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct Character {
    bytes: f64,
    bones: f64,
    constraints: f64,
}

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

impl Character {
    /// The counts of `text` (a file that is not JSON counts its bytes only).
    pub(super) fn read(text: &str) -> Self {
        let shape = serde_json::from_str::<FileShape>(text).unwrap_or_default();
        let constraints = shape.ik.0 + shape.transform.0 + shape.path.0 + shape.physics.0;
        Character {
            bytes: text.len() as f64,
            bones: (shape.bones.0 + shape.armature.bones).max(1.0),
            constraints: constraints + shape.armature.constraints,
        }
    }

    /// The counts of the character kept under `id` ([`ikarus_edge::character::store`]): its
    /// file was read when it was kept, so reading costs nothing. An id not kept costs nothing
    /// (it is refused at once).
    pub(super) fn kept(id: &str) -> Option<Self> {
        let stored = ikarus_edge::character::store::global().get(id)?;
        let c = &stored.loaded.character;
        Some(Character {
            bytes: 0.0,
            bones: c.bones().len() as f64,
            constraints: (c.constraints().len() + c.unsupported().len()) as f64,
        })
    }

    /// Reading the file.
    pub(super) fn parse(&self) -> f64 {
        self.bytes * BYTE_STEPS
    }

    /// One pose, under the runtime's rules or, with `ikarus`, ikarus's with `goals` and `pins`
    /// besides the constraints.
    pub(super) fn pose(&self, rules: Rules) -> f64 {
        let runtime = self.bones + self.constraints * self.bones;
        match rules {
            Rules::Runtime => runtime,
            Rules::Ikarus { goals, pins } => {
                let targets = self.constraints + goals + pins;
                let moving = self.bones.min(2.0 * (self.constraints + goals) + pins).max(1.0);
                // The character solve's iteration cap and step halvings.
                let options = ikarus_edge::pose::character_options();
                let (iterations, backtrack) = (f64::from(options.max_iterations), f64::from(options.backtrack));
                runtime + ROUNDS * moving * (1.0 + targets) * iterations * (1.0 + backtrack)
            }
        }
    }
}

/// Whose rules a character job's poses follow.
#[derive(Debug, Clone, Copy)]
pub(super) enum Rules {
    /// The runtime's (the default).
    Runtime,
    /// ikarus's solver, with the request's goals and pins.
    Ikarus { goals: f64, pins: f64 },
}

/// A request's `rig`: a rig's table, or a character file's text (its counts).
#[derive(Debug, Default)]
pub(super) struct RigField {
    pub(super) body: Option<Body>,
    pub(super) character: Option<Character>,
}

impl<'de> Deserialize<'de> for RigField {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(RigValue)
    }
}

/// Reads a rig's table as its [`Body`], a character file's text as its counts, and anything
/// else as absent.
struct RigValue;

impl<'de> Visitor<'de> for RigValue {
    type Value = RigField;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<RigField, A::Error> {
        let body = Body::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(RigField { body: Some(body), character: None })
    }

    fn visit_str<E>(self, v: &str) -> Result<RigField, E> {
        let json = v.trim_start_matches('\u{feff}').trim_start().starts_with('{');
        Ok(RigField { body: None, character: json.then(|| Character::read(v)) })
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<RigField, A::Error> {
        super::AnyValue.visit_seq(seq).map(|_| RigField::default())
    }

    fn visit_bool<E>(self, _: bool) -> Result<RigField, E> {
        Ok(RigField::default())
    }

    fn visit_i64<E>(self, _: i64) -> Result<RigField, E> {
        Ok(RigField::default())
    }

    fn visit_u64<E>(self, _: u64) -> Result<RigField, E> {
        Ok(RigField::default())
    }

    fn visit_f64<E>(self, _: f64) -> Result<RigField, E> {
        Ok(RigField::default())
    }

    fn visit_unit<E>(self) -> Result<RigField, E> {
        Ok(RigField::default())
    }
}

impl<'de> Deserialize<'de> for Armatures {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ArmaturesValue)
    }
}

struct ArmaturesValue;

impl<'de> Visitor<'de> for ArmaturesValue {
    type Value = Armatures;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Armatures, A::Error> {
        let mut all = Armatures::default();
        while let Some(a) = seq.next_element::<Nested<ArmatureShape>>()? {
            if let Some(a) = a.0 {
                all.bones += a.bone.0;
                all.constraints += a.ik.0;
            }
        }
        Ok(all)
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Armatures, A::Error> {
        while map.next_entry::<serde::de::IgnoredAny, serde::de::IgnoredAny>()?.is_some() {}
        Ok(Armatures::default())
    }

    fn visit_str<E>(self, _: &str) -> Result<Armatures, E> {
        Ok(Armatures::default())
    }

    fn visit_bool<E>(self, _: bool) -> Result<Armatures, E> {
        Ok(Armatures::default())
    }

    fn visit_i64<E>(self, _: i64) -> Result<Armatures, E> {
        Ok(Armatures::default())
    }

    fn visit_u64<E>(self, _: u64) -> Result<Armatures, E> {
        Ok(Armatures::default())
    }

    fn visit_f64<E>(self, _: f64) -> Result<Armatures, E> {
        Ok(Armatures::default())
    }

    fn visit_unit<E>(self) -> Result<Armatures, E> {
        Ok(Armatures::default())
    }
}

#[cfg(test)]
mod tests {
    use super::super::{QUICK_COST, estimate, lane};
    use crate::api::Endpoint;
    use crate::serve::pool::Lane;
    use serde_json::json;

    const SPINEBOY: &str = include_str!("../../../../../examples/characters/spine-spineboy-pro.json");

    /// A chain of `bones` bones with `ik` one-bone constraints on its second bone.
    fn chain(bones: usize, ik: usize) -> String {
        let mut b = vec![json!({"name": "b0"})];
        b.extend((1..bones).map(|i| json!({"name": format!("b{i}"), "parent": format!("b{}", i - 1), "length": 1})));
        let k: Vec<_> = (0..ik).map(|i| json!({"name": format!("k{i}"), "bones": ["b1"], "target": "b0"})).collect();
        json!({"skeleton": {"spine": "4.2"}, "bones": b, "ik": k}).to_string()
    }

    /// A character's `rig` was read as absent (the seed arm's three links), so every character
    /// job was quick; it is now costed from the file.
    #[test]
    fn character_jobs_are_costed_from_their_file() {
        let heavy = chain(256, 1024);
        let pose = |rig: &str, ik: &str| json!({"rig": rig, "ik": ik}).to_string();
        assert_eq!(lane(Endpoint::Pose, pose(&heavy, "ikarus").as_bytes()), Lane::Long);
        let motion = json!({"rig": heavy, "targets": [{"bone": "b255", "x": 1, "y": 1}], "duration": 26, "fps": 30});
        assert_eq!(lane(Endpoint::Animate, motion.to_string().as_bytes()), Lane::Long);
        let track = json!({"rig": heavy, "effector": "b255", "line": [0, 0, 1, 1], "samples": 2000});
        assert_eq!(lane(Endpoint::Track, track.to_string().as_bytes()), Lane::Long);
        // The page's playback of spineboy (its walk at a time, the runtime's rules) stays quick.
        let play = json!({"rig": SPINEBOY, "animation": "walk", "time": 0.4}).to_string();
        assert_eq!(lane(Endpoint::Pose, play.as_bytes()), Lane::Quick);
        let e = estimate(Endpoint::Pose, play.as_bytes());
        assert!(e > SPINEBOY.len() as f64, "reading the file counts: {e}");
        // Every armature of a DragonBones file counts.
        let bones: Vec<_> = (0..2000).map(|i| json!({"name": format!("b{i}")})).collect();
        let ik: Vec<_> = (0..2000).map(|i| json!({"name": format!("k{i}")})).collect();
        let db = json!({"version": "5.5", "armature": [{"bone": [{"name": "a"}]}, {"bone": bones, "ik": ik}]});
        let e = estimate(Endpoint::Pose, json!({"rig": db.to_string()}).to_string().as_bytes());
        assert!(e > 2000.0 * 2000.0, "{e}");
    }

    /// A file's text sent to `rig/parse` is costed by its bytes: a megabyte is long work.
    #[test]
    fn a_parse_is_costed_by_its_bytes() {
        assert_eq!(lane(Endpoint::RigParse, SPINEBOY.as_bytes()), Lane::Quick);
        let big = " ".repeat(1 << 20);
        assert!(estimate(Endpoint::RigParse, big.as_bytes()) > QUICK_COST);
        assert_eq!(lane(Endpoint::RigParse, big.as_bytes()), Lane::Long);
    }

    /// A `.skel`'s bytes are costed as the most JSON text they may decode into: never 0, never
    /// less than the same bytes as text, and any `.skel` is long work (its strings may copy a
    /// mebibyte).
    #[test]
    fn a_skel_is_costed_as_the_text_it_may_decode_into() {
        use crate::api::rigs::FileBody;
        use crate::serve::cost::{file_estimate, file_lane};
        let skel = include_bytes!("../../../../../examples/characters/spine-spineboy-pro.skel");
        let as_text = file_estimate(FileBody::Text, skel);
        assert_eq!(as_text, estimate(Endpoint::RigParse, skel));
        assert!(file_estimate(FileBody::Bytes, skel) > 16.0 * as_text, "{as_text}");
        assert!(file_estimate(FileBody::Bytes, b"") > QUICK_COST);
        assert_eq!(file_lane(FileBody::Bytes, &skel[..10]), Lane::Long);
        assert_eq!(file_lane(FileBody::Text, SPINEBOY.as_bytes()), Lane::Quick);
    }
}
