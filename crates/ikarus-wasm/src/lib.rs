//! ikarus in the browser: the JSON API of `ikarus serve` compiled to WebAssembly.
//!
//! The general entry point, [`call`], is the server's: it hands the endpoint and the
//! request body to [`ikarus_edge::edge::call`], the function behind `ikarus serve`'s handlers, so
//! every answer is the server's bytes for the same request (the same shapes, the same numbers,
//! the same one-line message and status for a bad request). Nothing here parses requests or
//! shapes answers. `web/build` compiles this crate for `wasm32-unknown-unknown` and runs
//! `wasm-bindgen --target web`; `web/ikarus.js` is the small JavaScript API over it.
//!
//! Beside it, typed handles for the hot paths, without JSON: a [`Chain`] (an arm read once, then
//! `solve(x, y, out)` and `solveBatch(goals, out)`) and a [`Character`] (a character file read
//! once, then `pose(time, targets, out)`), each writing numbers into a `Float64Array` the caller
//! owns, bit for bit those of [`call`]'s JSON for the same request.
//!
//! Natively the crate is an ordinary library (so that `cargo test --workspace` checks it on a
//! machine without the wasm target); its tests call [`answer`], which [`call`] wraps.

use std::sync::Mutex;

mod chain;
mod character;

pub use chain::{Chain, follow_status_name, status_name};
pub use character::Character;

use ikarus::Interrupt;
use ikarus_edge::edge::{self, Endpoint, Limits};
use wasm_bindgen::prelude::*;

/// A refused request, as thrown to JavaScript: the HTTP status `ikarus serve` answers for it
/// (400 malformed JSON, 404 no such endpoint, 422 a bad value, 500 internal) and its one-line
/// message, the text of the server's `{"error": …}`.
#[wasm_bindgen]
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    status: u16,
    message: String,
}

#[wasm_bindgen]
impl Problem {
    /// The HTTP status the server answers for this request.
    #[wasm_bindgen(getter)]
    pub fn status(&self) -> u16 {
        self.status
    }

    /// The one-line message (the server's `{"error": …}`).
    #[wasm_bindgen(getter)]
    pub fn message(&self) -> String {
        self.message.clone()
    }
}

/// The answer of `path` (`"solve"`, `"/api/solve"`, `"arm/default"`, …) to `body` (the request's
/// JSON, or an arm or rig file's TOML text for `arm/parse` and `rig/parse`; ignored by the GET
/// endpoints), under the server's default limits: the answer's text (JSON; the arm file's TOML
/// for `arm/toml`), or the [`Problem`] the server would answer.
///
/// The limits are `Limits::default()`, the defaults of `ikarus serve`'s flags, every cap the
/// edge has included (frames, samples, bones, iterations, restarts, and what bounds an export's
/// keys), so one request cannot ask the module for more than the server would do: wasm32 has
/// 4 GB, and an allocation past them aborts the instance (`web/ikarus.js` restarts it).
pub fn answer(path: &str, body: &str) -> Result<String, Problem> {
    let endpoint =
        Endpoint::from_path(path).ok_or_else(|| Problem { status: 404, message: format!("no endpoint {path:?}") })?;
    let reply = edge::call(endpoint, body.as_bytes(), &Limits::default(), &Interrupt::new())
        .map_err(|p| Problem { status: p.status, message: p.message })?;
    String::from_utf8(reply.body)
        .map_err(|e| Problem { status: 500, message: format!("{}: the answer is not text: {e}", endpoint.path()) })
}

/// [`answer`] for JavaScript: returns the answer's text, throws a [`Problem`].
#[cfg(feature = "json")]
#[wasm_bindgen]
pub fn call(path: &str, body: &str) -> Result<String, Problem> {
    answer(path, body)
}

/// A character file's bytes as the JSON text [`call`] and [`Character`] read: a JSON file's text
/// as is, a Spine 4.2 binary export's (`.skel`) decoded into the JSON tree Spine's JSON export
/// of it has, by the function `ikarus pose --rig FILE.skel` reads it with; bytes that are
/// neither are a 422 [`Problem`] with the command line's one line (`rig file: skel: byte …`).
pub fn text_of(bytes: &[u8]) -> Result<String, Problem> {
    ikarus_edge::character::text_of(bytes.to_vec(), "rig file")
        .map_err(|e| Problem { status: 422, message: e.to_string() })
}

/// [`text_of`] for JavaScript (`characterText(bytes)` in `web/ikarus.js`): returns the JSON
/// text, throws a [`Problem`].
#[cfg(feature = "json")]
#[wasm_bindgen(js_name = characterText)]
pub fn character_text(bytes: &[u8]) -> Result<String, Problem> {
    text_of(bytes)
}

/// What `ikarus serve` answers `POST /api/rig/parse?text=1` with these bytes as
/// `application/octet-stream` (a `.skel`, or any character or rig file): `{"character": …,
/// "text": "<its JSON text>"}` (the character kept under its id), `{"rig": …}`, or the
/// [`Problem`] (422 for a file that cannot be read).
pub fn parse_bytes(bytes: &[u8]) -> Result<String, Problem> {
    use ikarus_edge::api::rigs::{Echo, FileBody, parse_file};
    let reply = parse_file(bytes, FileBody::Bytes, Echo::Text, &Limits::default())
        .map_err(|p| Problem { status: p.status, message: p.message })?;
    String::from_utf8(reply.body)
        .map_err(|e| Problem { status: 500, message: format!("/api/rig/parse: the answer is not text: {e}") })
}

/// [`parse_bytes`] for JavaScript (`parseRigBytes(bytes)` in `web/ikarus.js`).
#[cfg(feature = "json")]
#[wasm_bindgen(js_name = parseRigBytes)]
pub fn parse_rig_bytes(bytes: &[u8]) -> Result<String, Problem> {
    parse_bytes(bytes)
}

/// The version of ikarus this module was built from (the crate version, as `/api/health` says).
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_owned()
}

/// The message of the last panic, kept by the hook that [`start`] installs: on wasm32 a panic
/// aborts (the JavaScript side sees only `RuntimeError: unreachable`), so `web/ikarus.js` asks
/// for it to say what went wrong.
static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

/// Run once when the module is initialised: keep each panic's message for [`last_panic`].
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = Some(info.to_string());
        }
    }));
}

/// The message of the last panic (with its place in the source), if there was one.
#[wasm_bindgen]
pub fn last_panic() -> Option<String> {
    LAST_PANIC.lock().ok().and_then(|last| last.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_are_the_servers_and_refusals_keep_status_and_message() {
        let solved: serde_json::Value =
            serde_json::from_str(&answer("solve", r#"{"goal":{"x":2,"y":3}}"#).unwrap()).unwrap();
        assert_eq!(solved["status"], "reached");
        assert_eq!(answer("/api/arm/default", "").unwrap(), answer("arm/default", "ignored").unwrap());

        let malformed = answer("solve", "{").unwrap_err();
        assert_eq!(malformed.status, 400, "{malformed:?}");
        let bad = answer("solve", r#"{"goal":{"x":2,"y":3},"options":{"tolerance":0}}"#).unwrap_err();
        assert_eq!(bad.status, 422);
        assert_eq!(bad.message, "options.tolerance = 0: must be a finite number greater than 0");

        let nowhere = answer("nowhere", "{}").unwrap_err();
        assert_eq!((nowhere.status, nowhere.message.as_str()), (404, r#"no endpoint "nowhere""#));
    }

    /// A `.skel`'s bytes: its JSON text, which `rig/parse` reads as the answer for the bytes
    /// says; bytes that are not a character are a 422 with the command line's line.
    #[test]
    fn a_skels_bytes_read_as_its_json_text() {
        let skel = include_bytes!("../../../examples/characters/spine-spineboy-pro.skel");
        let text = text_of(skel).unwrap();
        let parsed: serde_json::Value = serde_json::from_str(&answer("rig/parse", &text).unwrap()).unwrap();
        let from_bytes: serde_json::Value = serde_json::from_str(&parse_bytes(skel).unwrap()).unwrap();
        assert_eq!(from_bytes["text"].as_str(), Some(text.as_str()));
        assert_eq!(from_bytes["character"]["bones"], parsed["character"]["bones"]);
        assert_eq!(parsed["character"]["bones"].as_array().unwrap().len(), 67);
        let cut = text_of(&skel[..100]).unwrap_err();
        assert_eq!(cut.status, 422);
        assert!(cut.message.starts_with("rig file: skel: byte "), "{cut:?}");
        assert_eq!(parse_bytes(&skel[..100]).unwrap_err(), cut);
    }

    /// The module answers under `ikarus serve`'s default caps: a request over one is refused as
    /// the server refuses it, before any work (wasm32 has 4 GB: work grown past it traps).
    #[test]
    fn requests_are_held_to_the_servers_default_caps() {
        let caps = Limits::default();
        let over = format!(r#"{{"goal":{{"x":2,"y":3}},"frames":{}}}"#, caps.max_frames + 1);
        let refused = answer("animate", &over).unwrap_err();
        assert_eq!(refused.status, 422, "{refused:?}");
        assert!(refused.message.contains(&caps.max_frames.to_string()), "{refused:?}");
        let at = format!(r#"{{"goal":{{"x":2,"y":3}},"frames":{}}}"#, caps.max_frames);
        assert!(answer("animate", &at).is_ok());
        let restarts = format!(r#"{{"goal":{{"x":2,"y":3}},"options":{{"restarts":{}}}}}"#, caps.max_restarts + 1);
        assert_eq!(answer("solve", &restarts).unwrap_err().status, 422);
    }
}
