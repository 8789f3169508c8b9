//! The API's error: a status code and a JSON body `{"error": "…"}` of one line that names the
//! field and the value; and the request bodies, read within the server's caps.
//!
//! A body is taken only with its endpoint's content type — `application/json` (or a
//! `application/…+json` type), `application/toml` for the arm and rig files' text, or
//! `application/octet-stream` for a character file's bytes (`/api/rig/parse`, a `.skel`) — and
//! refused 415 otherwise, a missing type included. None of these is a CORS "simple request"
//! type (`text/plain`, `application/x-www-form-urlencoded`, `multipart/form-data`), so a page
//! on another site cannot post a body without a preflight, and the server answers no
//! preflight: a browser never sends it.

use std::marker::PhantomData;

use axum::Json;
use axum::body::Bytes;
use axum::extract::rejection::JsonRejection;
use axum::extract::{FromRequest, Request};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};

use super::AppState;
pub use crate::api::Problem as ApiError;
use crate::api::status;

/// A refused request as axum answers it: the edge's [`ApiError`] (a `Problem`), its status and
/// the body `{"error": "…"}` of one line.
pub struct Refusal(pub ApiError);

impl From<ApiError> for Refusal {
    fn from(p: ApiError) -> Self {
        Self(p)
    }
}

impl IntoResponse for Refusal {
    fn into_response(self) -> Response {
        if let Some(detail) = self.0.internal_detail() {
            eprintln!("ikarus: internal error: {detail}");
        }
        let status = StatusCode::from_u16(self.0.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
        (status, Json(serde_json::json!({ "error": self.0.one_line() }))).into_response()
    }
}

/// The media type of an endpoint's body.
pub trait MediaType {
    /// What a refused request is told to send.
    const NAME: &'static str;
    /// Whether `essence` (the type without parameters, lowercase) is this type.
    fn accepts(essence: &str) -> bool;
    /// The size cap of such a body and the flag that sets it.
    fn cap(state: &AppState) -> (usize, &'static str) {
        (state.limits.max_body_bytes, "--max-body-bytes")
    }
}

/// JSON: `application/json`, or `application/…+json` (axum's `Json` rule).
pub struct JsonType;

impl MediaType for JsonType {
    const NAME: &'static str = "application/json";
    fn accepts(essence: &str) -> bool {
        essence == "application/json" || (essence.starts_with("application/") && essence.ends_with("+json"))
    }
}

/// An arm or rig file's text: `application/toml`.
pub struct TomlType;

impl MediaType for TomlType {
    const NAME: &'static str = "application/toml";
    fn accepts(essence: &str) -> bool {
        essence == "application/toml"
    }
    /// A file's text: `--max-file-bytes`.
    fn cap(state: &AppState) -> (usize, &'static str) {
        (state.max_file_bytes, "--max-file-bytes")
    }
}

/// A texture atlas with its page images for `/api/atlas/parse`: JSON, under `--max-file-bytes`
/// (the images make it a file's size, not a request's).
pub struct AtlasType;

impl MediaType for AtlasType {
    const NAME: &'static str = JsonType::NAME;
    fn accepts(essence: &str) -> bool {
        JsonType::accepts(essence)
    }
    /// A file: `--max-file-bytes`.
    fn cap(state: &AppState) -> (usize, &'static str) {
        TomlType::cap(state)
    }
}

/// A rig or character file for `/api/rig/parse`: its text (`application/toml`) or its bytes
/// (`application/octet-stream`, a Spine binary export `.skel`).
pub struct RigFileType;

/// The media type of a character file's bytes.
pub const OCTET_STREAM: &str = "application/octet-stream";

impl MediaType for RigFileType {
    const NAME: &'static str = "application/toml or application/octet-stream";
    fn accepts(essence: &str) -> bool {
        TomlType::accepts(essence) || essence == OCTET_STREAM
    }
    /// A file: `--max-file-bytes`.
    fn cap(state: &AppState) -> (usize, &'static str) {
        TomlType::cap(state)
    }
}

/// The request's content type without its parameters, lowercase ("" when missing).
pub fn essence(headers: &HeaderMap) -> String {
    let text = headers.get(header::CONTENT_TYPE).map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned());
    text.unwrap_or_default().split(';').next().unwrap_or_default().trim().to_ascii_lowercase()
}

/// 415 unless the request's `Content-Type` is `T` (parameters such as `charset` aside).
fn check_content_type<T: MediaType>(headers: &HeaderMap) -> Result<(), ApiError> {
    let refused = |what: String| {
        ApiError::new(status::UNSUPPORTED_MEDIA_TYPE, format!("Content-Type{what}: expected {}", T::NAME))
    };
    let Some(value) = headers.get(header::CONTENT_TYPE) else { return Err(refused(": missing".to_owned())) };
    let text = String::from_utf8_lossy(value.as_bytes());
    if T::accepts(&essence(headers)) { Ok(()) } else { Err(refused(format!(" = {text:?}"))) }
}

/// A request body of media type `T`, read within the server's caps: its content type checked
/// (415), its size at most `--max-body-bytes`, its memory reserved from the server's body
/// memory, its arrival bounded in time. [`crate::api::call`] parses it.
pub struct ApiBody<T> {
    pub bytes: Bytes,
    /// The body's share of the server's body memory, given back when the body is dropped.
    _memory: tokio::sync::OwnedSemaphorePermit,
    _type: PhantomData<T>,
}

/// A JSON body (every computation, `/api/arm/toml`).
pub type JsonBody = ApiBody<JsonType>;
/// An arm file's text (`/api/arm/parse`).
pub type TomlBody = ApiBody<TomlType>;
/// A rig or character file's text or bytes (`/api/rig/parse`).
pub type RigFileBody = ApiBody<RigFileType>;
/// A texture atlas and its page images (`/api/atlas/parse`).
pub type AtlasBody = ApiBody<AtlasType>;

impl<T: MediaType> FromRequest<AppState> for ApiBody<T> {
    type Rejection = Refusal;

    async fn from_request(req: Request, state: &AppState) -> Result<Self, Self::Rejection> {
        Self::read(req, state).await.map_err(Refusal)
    }
}

impl<T: MediaType> ApiBody<T> {
    /// The body, within the server's caps of size, memory and time.
    async fn read(req: Request, state: &AppState) -> Result<Self, ApiError> {
        let (max_body_bytes, flag) = T::cap(state);
        // The content type before the size and before the body is read.
        if let Err(refusal) = check_content_type::<T>(req.headers()) {
            drain_small(req, state).await;
            return Err(refusal);
        }
        // The memory the body may take (its declared length, or the cap) is reserved before
        // it is read: past the server's body memory the answer is 503 at once.
        let declared = req
            .headers()
            .get(axum::http::header::CONTENT_LENGTH)
            .and_then(|v| v.to_str().ok()?.trim().parse::<usize>().ok())
            .map_or(max_body_bytes, |n| n.min(max_body_bytes));
        let share = u32::try_from(declared.max(1)).unwrap_or(u32::MAX);
        let Ok(memory) = std::sync::Arc::clone(&state.bodies).try_acquire_many_owned(share) else {
            return Err(ApiError::new(
                status::SERVICE_UNAVAILABLE,
                format!(
                    "server busy: receiving too many request bodies at once (at most {} MB); try again later",
                    super::BODY_MEMORY >> 20
                ),
            ));
        };
        // A client trickling its body holds a connection and a buffer: bounded in time.
        let timeout = state.limits.body_timeout;
        match tokio::time::timeout(timeout, Bytes::from_request(req, state)).await {
            Ok(Ok(bytes)) => Ok(Self { bytes, _memory: memory, _type: PhantomData }),
            Ok(Err(rejection)) => Err(rejected(&rejection.into(), (max_body_bytes, flag))),
            Err(_) => Err(ApiError::new(
                status::REQUEST_TIMEOUT,
                format!("request body: not received within {} ms (--body-timeout-ms)", timeout.as_millis()),
            )),
        }
    }
}

/// Most bytes of a refused request's body read and dropped before the refusal is sent.
const DRAIN_BYTES: usize = 64 << 10;

/// Reads and drops the body of a request refused before its body was read, when it declares at
/// most [`DRAIN_BYTES`], within the body timeout. The connection is closed after a refusal; a
/// socket closed with unread bytes in its buffer is reset, and a client still sending or not yet
/// reading then loses the answer ("connection reset") instead of reading the refusal.
async fn drain_small(req: Request, state: &AppState) {
    let small = req
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok()?.trim().parse::<usize>().ok())
        .is_some_and(|n| n <= DRAIN_BYTES);
    if small {
        let body = axum::body::to_bytes(req.into_body(), DRAIN_BYTES);
        let _ = tokio::time::timeout(state.limits.body_timeout, body).await;
    }
}

fn rejected(rejection: &JsonRejection, (max_body_bytes, flag): (usize, &str)) -> ApiError {
    // axum's text is "Failed to …: <serde's message, with the path of the field>".
    let detail = || {
        let text = rejection.body_text();
        match text.split_once(": ") {
            Some((_, rest)) => rest.to_owned(),
            None => text,
        }
    };
    match rejection {
        JsonRejection::JsonDataError(_) => ApiError::invalid(format!("request body: {}", detail())),
        JsonRejection::JsonSyntaxError(_) => {
            ApiError::new(status::BAD_REQUEST, format!("request body: malformed JSON: {}", detail()))
        }
        JsonRejection::MissingJsonContentType(_) => {
            ApiError::new(status::UNSUPPORTED_MEDIA_TYPE, format!("Content-Type: expected {}", JsonType::NAME))
        }
        other if other.status() == StatusCode::PAYLOAD_TOO_LARGE => ApiError::new(
            status::PAYLOAD_TOO_LARGE,
            format!("request body: larger than the cap of {max_body_bytes} bytes ({flag})"),
        ),
        other => ApiError::new(other.status().as_u16(), format!("request body: {}", other.body_text())),
    }
}
