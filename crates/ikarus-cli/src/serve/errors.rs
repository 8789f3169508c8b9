//! The API's error: a status code and a JSON body `{"error": "…"}` of one line that names the
//! field and the value.

use axum::Json;
use axum::body::{Body, Bytes};
use axum::extract::rejection::JsonRejection;
use axum::extract::{FromRequest, Request};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::de::IgnoredAny;

use super::AppState;
pub use crate::api::Problem as ApiError;
use crate::api::status;

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let status = StatusCode::from_u16(self.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
        (status, Json(serde_json::json!({ "error": self.one_line() }))).into_response()
    }
}

/// A JSON request body, read within the server's caps: its content type checked, its size at
/// most `--max-body-bytes`, its memory reserved from the server's body memory, its arrival
/// bounded in time. [`crate::api::call`] parses it.
pub struct JsonBody {
    pub bytes: Bytes,
    /// The body's share of the server's body memory, given back when the body is dropped.
    _memory: tokio::sync::OwnedSemaphorePermit,
}

impl FromRequest<AppState> for JsonBody {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &AppState) -> Result<Self, Self::Rejection> {
        let max_body_bytes = state.limits.max_body_bytes;
        // The content type before the size, as `Json` checks them, by `Json`'s own rule: an
        // empty body under the same headers is refused for its type or for being empty.
        let mut probe = Request::new(Body::empty());
        *probe.headers_mut() = req.headers().clone();
        if let Err(rejection @ JsonRejection::MissingJsonContentType(_)) =
            Json::<IgnoredAny>::from_request(probe, state).await
        {
            return Err(rejected(&rejection, max_body_bytes));
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
            return Err(ApiError {
                status: status::SERVICE_UNAVAILABLE,
                message: format!(
                    "server busy: receiving too many request bodies at once (at most {} MB); try again later",
                    super::BODY_MEMORY >> 20
                ),
            });
        };
        // A client trickling its body holds a connection and a buffer: bounded in time.
        let timeout = state.limits.body_timeout;
        match tokio::time::timeout(timeout, Bytes::from_request(req, state)).await {
            Ok(Ok(bytes)) => Ok(Self { bytes, _memory: memory }),
            Ok(Err(rejection)) => Err(rejected(&rejection.into(), max_body_bytes)),
            Err(_) => Err(ApiError {
                status: status::REQUEST_TIMEOUT,
                message: format!("request body: not received within {} ms (--body-timeout-ms)", timeout.as_millis()),
            }),
        }
    }
}

fn rejected(rejection: &JsonRejection, max_body_bytes: usize) -> ApiError {
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
            ApiError { status: status::BAD_REQUEST, message: format!("request body: malformed JSON: {}", detail()) }
        }
        JsonRejection::MissingJsonContentType(_) => {
            ApiError { status: status::BAD_REQUEST, message: "Content-Type: expected application/json".to_owned() }
        }
        other if other.status() == StatusCode::PAYLOAD_TOO_LARGE => ApiError {
            status: status::PAYLOAD_TOO_LARGE,
            message: format!("request body: larger than the cap of {max_body_bytes} bytes (--max-body-bytes)"),
        },
        other => ApiError { status: other.status().as_u16(), message: format!("request body: {}", other.body_text()) },
    }
}
