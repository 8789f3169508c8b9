//! Rig files for the page: `GET /api/rigs` (the shipped rig files, embedded in the binary) and
//! `POST /api/rig/parse` (rig-file text → `{"rig": …}`, a Spine or DragonBones file's JSON →
//! `{"character": …}`, or `{"problem": "…"}`, as `/api/arm/parse`), in the shapes of
//! `crate::report`. A Spine binary export (`.skel`) is sent as its bytes ([`FileBody::Bytes`]):
//! decoded into its JSON text by [`crate::character::text_of`], the function the command line
//! reads a file with, then read and kept as that text; a file that cannot be read is then a
//! 422 with its one line. Asked with [`Echo::Text`] (`?text=1`), a character's answer carries
//! the JSON text that was kept (`"text"`), which is how the page gets a `.skel`'s JSON.

use serde::Serialize;

use super::fields::json_response;
use super::wire::{Limits, Problem, Reply, text};
use crate::report::RigJson;
use crate::report::character::CharacterJson;
use crate::rig::BoneCap;

/// The shipped rigs (`examples/rigs/`), by name, as rig-file text.
pub const SHIPPED: &[(&str, &str)] = &[
    ("puppet", include_str!("../../../../examples/rigs/puppet.toml")),
    ("hand", include_str!("../../../../examples/rigs/hand.toml")),
];

/// One shipped rig.
#[derive(Serialize)]
pub struct Shipped {
    name: &'static str,
    rig: RigJson,
}

#[derive(Serialize)]
struct Rigs {
    rigs: Vec<Shipped>,
}

/// `GET /api/rigs`: `{"rigs": [{"name", "rig"}, …]}`.
pub fn list() -> Result<Reply, Problem> {
    let rigs = SHIPPED
        .iter()
        .map(|(name, text)| {
            let rig = RigJson::parse(text, &format!("examples/rigs/{name}.toml"))
                .map_err(|e| Problem::internal(e.to_string()))?;
            Ok(Shipped { name, rig })
        })
        .collect::<Result<Vec<_>, Problem>>()?;
    json_response(&Rigs { rigs })
}

/// The answer of `POST /api/rig/parse`: the rig, or why the text is not a rig file (a 200
/// either way, as `/api/arm/parse`).
#[derive(Debug, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Parsed {
    /// `{"rig": …}`: a rig file's rig.
    Rig(RigJson),
    /// `{"character": …}`: a character file's skeleton, with the `id` it is kept under.
    Character(Box<CharacterJson>),
    /// `{"problem": "…"}`: why the text is neither.
    Problem(String),
}

/// `POST /api/rig/parse`: the body is the file's text, of at most `--max-bones` bones (a
/// bigger one is a problem, found before any bone is checked): a rig file (TOML), or a
/// character file (JSON, told by its first character; [`crate::character`]).
pub fn parsed(text: &str, limits: &Limits) -> Parsed {
    let cap = BoneCap::flag(limits.max_bones);
    if crate::character::is_json(text) {
        return match crate::character::load_within(text, "rig file", cap) {
            Ok(loaded) => {
                let mut json = CharacterJson::new(&loaded);
                let (id, _) = crate::character::store::global().put(text.to_owned(), loaded);
                json.id = Some(id);
                Parsed::Character(Box::new(json))
            }
            Err(problem) => Parsed::Problem(problem.to_string()),
        };
    }
    match RigJson::parse_within(text, "rig file", cap) {
        Ok(rig) => Parsed::Rig(rig),
        Err(problem) => Parsed::Problem(problem.to_string()),
    }
}

/// How the body of `POST /api/rig/parse` holds the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileBody {
    /// The file's text, UTF-8 (`application/toml`): a rig file (TOML) or a character's JSON.
    Text,
    /// The file's bytes (`application/octet-stream`): a Spine binary export (`.skel`), or any
    /// file [`FileBody::Text`] takes; a file that cannot be read is a 422, not a `problem`.
    Bytes,
}

/// Whether a character's answer carries the JSON text the server keeps for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Echo {
    /// `{"character": …}` alone (the default).
    Without,
    /// `{"character": …, "text": "…"}` (`?text=1`): the character file's JSON text, a `.skel`'s
    /// decoded; a rig or a problem has no `text`.
    Text,
}

/// The answer of `POST /api/rig/parse` with its echo of the text.
#[derive(Serialize)]
struct Answer<'a> {
    #[serde(flatten)]
    parsed: &'a Parsed,
    #[serde(skip_serializing_if = "Option::is_none")]
    text: Option<&'a str>,
}

/// `POST /api/rig/parse` of `body` held as `given`: [`parsed`] of the file's text (a `.skel`'s
/// bytes decoded first), its `text` added when `echo` asks and the file is a character's.
pub fn parse_file(body: &[u8], given: FileBody, echo: Echo, limits: &Limits) -> Result<Reply, Problem> {
    let owned;
    let file = match given {
        FileBody::Text => text(body)?,
        FileBody::Bytes => {
            owned =
                crate::character::text_of(body.to_vec(), "rig file").map_err(|e| Problem::invalid(e.to_string()))?;
            owned.as_str()
        }
    };
    let parsed = parsed(file, limits);
    if let (FileBody::Bytes, Parsed::Problem(problem)) = (given, &parsed) {
        return Err(Problem::invalid(problem.clone()));
    }
    let text = match (&parsed, echo) {
        (Parsed::Character(_), Echo::Text) => Some(file),
        _ => None,
    };
    json_response(&Answer { parsed: &parsed, text })
}

#[cfg(test)]
#[path = "rigs_tests.rs"]
mod tests;
