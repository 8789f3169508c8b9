//! What every endpoint of the API shares: the caps of a request ([`Limits`]), a refusal with its
//! status and one-line message ([`Problem`], [`status`]), reading a JSON body the way the server
//! reads it ([`parse_json`]), and an answer ([`Reply`]).

use std::fmt;

use serde::de::DeserializeOwned;

use crate::error::{Error, ErrorKind};

/// The caps of every request: the server's flags, and the same defaults for the edges that
/// have no flags (Python, WebAssembly).
#[derive(Debug, Clone)]
pub struct Limits {
    /// Largest request body, in bytes (413 above it).
    pub max_body_bytes: usize,
    /// Most links an arm of a request may have.
    pub max_links: usize,
    /// Most bones a rig of a request may have (`/api/rig/parse` included), counted before any
    /// bone is checked.
    pub max_bones: usize,
    /// Largest `options.max_iterations` of a request.
    pub max_iterations: u32,
    /// Most frames of a motion.
    pub max_frames: usize,
    /// Most samples of a path, or points of a reach request.
    pub max_samples: usize,
    /// Largest workspace resolution (cells per side).
    pub max_resolution: u32,
    /// Most restarts a request may ask for (each may run the full iteration cap).
    pub max_restarts: u32,
    /// Most goals of one `/api/solve_batch` request.
    pub max_goals: usize,
    /// Time a request has to send its body (the server's; unused elsewhere).
    pub body_timeout: std::time::Duration,
}

impl Default for Limits {
    /// The defaults of `ikarus serve`'s flags.
    fn default() -> Self {
        Self {
            max_body_bytes: 1 << 20,
            max_links: 64,
            max_bones: 256,
            max_iterations: crate::settings::DEFAULT_ITERATION_CAP,
            max_frames: 2000,
            max_samples: 5000,
            max_resolution: 1024,
            max_restarts: 64,
            max_goals: 100_000,
            body_timeout: std::time::Duration::from_millis(10_000),
        }
    }
}

/// A refused request: the HTTP status the server answers with, and the one-line message of
/// its `{"error": …}` body, which names the field and the value. Made from the edge's
/// [`Error`] (`From`), whose kind picks the status, or by the constructors here.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// 400 malformed JSON, 413 too large, 415 not the endpoint's content type, 422 a bad value,
    /// 500 internal, 503 interrupted or busy.
    pub status: u16,
    /// One line.
    pub message: String,
    /// What went wrong inside ikarus, for a 500: the server's log line, never the client's.
    detail: Option<String>,
}

/// Status codes the API answers with.
pub mod status {
    /// Malformed JSON, a body that is not text.
    pub const BAD_REQUEST: u16 = 400;
    /// The request's host is not accepted.
    pub const FORBIDDEN: u16 = 403;
    /// No such endpoint or file.
    pub const NOT_FOUND: u16 = 404;
    /// The body did not arrive in time.
    pub const REQUEST_TIMEOUT: u16 = 408;
    /// The body is over the cap.
    pub const PAYLOAD_TOO_LARGE: u16 = 413;
    /// The body's `Content-Type` is not the endpoint's (or is missing).
    pub const UNSUPPORTED_MEDIA_TYPE: u16 = 415;
    /// Well-formed JSON with a bad value.
    pub const UNPROCESSABLE_ENTITY: u16 = 422;
    /// A fault of ikarus.
    pub const INTERNAL_SERVER_ERROR: u16 = 500;
    /// Interrupted, over the time budget, or too busy.
    pub const SERVICE_UNAVAILABLE: u16 = 503;
}

impl Problem {
    /// A refusal with `status` and the one-line `message` the client reads.
    pub fn new(status: u16, message: impl Into<String>) -> Self {
        Self { status, message: message.into(), detail: None }
    }

    /// 422: the request is well-formed JSON but a value is invalid.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(status::UNPROCESSABLE_ENTITY, message)
    }

    /// 500: something failed inside ikarus. The client reads only that the details are in the
    /// server's log; `detail` (which may hold paths or panic text) is kept for that log
    /// ([`internal_detail`](Self::internal_detail)).
    pub fn internal(detail: impl Into<String>) -> Self {
        Self {
            status: status::INTERNAL_SERVER_ERROR,
            message: "internal error (the details are in the server's log)".to_owned(),
            detail: Some(detail.into().replace(['\n', '\r'], " ")),
        }
    }

    /// What failed inside ikarus, on one line, if this is an [`internal`](Self::internal)
    /// error: what the server writes to its log (`ikarus: internal error: {detail}`).
    #[must_use]
    pub fn internal_detail(&self) -> Option<&str> {
        self.detail.as_deref()
    }

    /// This refusal with another message for the client (the status and any internal detail
    /// kept), for an edge that names a field in its own words.
    #[must_use]
    pub fn with_message(self, message: impl Into<String>) -> Self {
        Self { message: message.into(), ..self }
    }

    /// The message on one line.
    pub fn one_line(&self) -> String {
        self.message.replace(['\n', '\r'], " ")
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.one_line())
    }
}

impl std::error::Error for Problem {}

impl From<Error> for Problem {
    /// The status of the error's kind (422 bad input, 400 malformed, 413 too large, 503 cut
    /// short, 500 at run time) and its text; a run-time error's text becomes the
    /// [`internal_detail`](Self::internal_detail).
    fn from(e: Error) -> Self {
        let status = match e.kind() {
            ErrorKind::Input => status::UNPROCESSABLE_ENTITY,
            ErrorKind::Malformed => status::BAD_REQUEST,
            ErrorKind::TooLarge => status::PAYLOAD_TOO_LARGE,
            ErrorKind::Unavailable => status::SERVICE_UNAVAILABLE,
            ErrorKind::Runtime => return Self::internal(e.to_string()),
        };
        Self::new(status, e.to_string())
    }
}

/// A JSON body as a `T`, refused as the server refuses it: malformed JSON (or anything after
/// the value) → 400, a value of the wrong type or an unknown field → 422, each message with the
/// field's path (`links[0].length: invalid type: …`; with the `field-paths` feature) and the line
/// and column, after `request body: `.
pub fn parse_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, Problem> {
    read_json(bytes).map_err(|e| Problem::from(e.from_source("request body")))
}

/// A JSON document as a `T`, without naming the document: malformed JSON (or anything after
/// the value) is [`ErrorKind::Malformed`] (`malformed JSON: …`), a value of the wrong type or an
/// unknown field [`ErrorKind::Input`] with the field's path (with the `field-paths` feature)
/// and serde_json's message with the line and column.
pub fn read_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, Error> {
    let malformed = |e: &dyn fmt::Display| Error::malformed(format!("malformed JSON: {e}"));
    let mut de = serde_json::Deserializer::from_slice(bytes);
    #[cfg(feature = "field-paths")]
    let read = serde_path_to_error::deserialize(&mut de);
    #[cfg(not(feature = "field-paths"))]
    let read: Result<T, serde_json::Error> = serde::Deserialize::deserialize(&mut de);
    match read {
        Ok(value) => de.end().map(|()| value).map_err(|e| malformed(&e)),
        #[cfg(feature = "field-paths")]
        Err(e) => match e.inner().classify() {
            serde_json::error::Category::Data => Err(Error::input(e.inner().to_string()).within(field_path(e.path()))),
            _ => Err(malformed(&e)),
        },
        #[cfg(not(feature = "field-paths"))]
        Err(e) => match e.classify() {
            serde_json::error::Category::Data => Err(Error::input(e.to_string())),
            _ => Err(malformed(&e)),
        },
    }
}

/// serde_path_to_error's path as a [`FieldPath`], written as it writes it (a path of unknown
/// steps only is written as nothing).
#[cfg(feature = "field-paths")]
fn field_path(path: &serde_path_to_error::Path) -> crate::error::FieldPath {
    use serde_path_to_error::Segment as S;
    if path.iter().all(|s| matches!(s, S::Unknown)) {
        return crate::error::FieldPath::new();
    }
    path.iter().fold(crate::error::FieldPath::new(), |p, s| match s {
        S::Seq { index } => p.index(*index),
        S::Map { key } => p.field(key.clone()),
        S::Enum { variant } => p.field(variant.clone()),
        S::Unknown => p.field("?"),
    })
}

/// An answer: its content type and bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reply {
    /// `application/json`, `image/png`, `image/svg+xml`, `image/gif` or `application/toml; charset=utf-8`.
    pub content_type: &'static str,
    /// The body.
    pub body: Vec<u8>,
}

impl Reply {
    /// `value` as JSON.
    pub fn json(value: &impl serde::Serialize) -> Result<Reply, Problem> {
        let body = serde_json::to_vec(value).map_err(|e| Problem::internal(format!("cannot write JSON: {e}")))?;
        Ok(Reply { content_type: "application/json", body })
    }
}

/// A body that is a file's text.
pub(crate) fn text(body: &[u8]) -> Result<&str, Problem> {
    std::str::from_utf8(body)
        .map_err(|e| Problem::new(status::BAD_REQUEST, format!("request body: not UTF-8 text ({e})")))
}
