//! The routes' handlers: each reads its request (a JSON body bounded in size, memory and time
//! by [`JsonBody`]), runs [`api::call`] — the same function Python and WebAssembly call — on a
//! worker of the pool for the computations, and answers its bytes.

use axum::http::header;
use axum::response::{IntoResponse, Response};
use ikarus::Interrupt;

use super::AppState;
use super::errors::{ApiBody, JsonBody, Refusal, TomlBody};
use crate::api::{self, Endpoint, Reply};

/// An answer's bytes under its content type.
fn answer(reply: Reply) -> Response {
    ([(header::CONTENT_TYPE, reply.content_type)], reply.body).into_response()
}

/// A computation (`/api/solve`, `solve_batch`, `animate`, `track`, `workspace`, `reach`, `render`): its JSON
/// body answered by [`api::call`] on a worker of the pool, in the lane its cost estimate says,
/// under the time budget.
pub async fn compute(endpoint: Endpoint, state: AppState, body: JsonBody) -> Result<Response, Refusal> {
    on_pool(endpoint, state, body).await
}

/// [`api::call`] of `body` on a worker of the pool, in its lane, under the time budget.
async fn on_pool<T: Send + Sync + 'static>(
    endpoint: Endpoint,
    state: AppState,
    body: ApiBody<T>,
) -> Result<Response, Refusal> {
    let pool = state.pool.clone();
    let lane = super::cost::lane(endpoint, &body.bytes);
    pool.run(lane, move |interrupt| api::call(endpoint, &body.bytes, &state.limits, interrupt))
        .await
        .map(answer)
        .map_err(Refusal)
}

/// A quick answer (`/api/meta`, `arm/default`, `rigs`, `arm/toml`, `ease`): no solve, no loop
/// a request can lengthen, answered on the spot.
pub fn at_once(endpoint: Endpoint, state: &AppState, body: &[u8]) -> Result<Response, Refusal> {
    api::call(endpoint, body, &state.limits, &Interrupt::new()).map(answer).map_err(Refusal)
}

/// `/api/arm/parse` and `/api/rig/parse`: the body is a file's text, sent as `application/toml`.
/// Read on a worker of the pool, costed from its bytes ([`super::cost`]), under the time
/// budget: a character file of a megabyte is real work, which on the runtime's own threads
/// held `/api/health`, every other request and Ctrl-C for as long as it took.
pub async fn file_text(endpoint: Endpoint, state: AppState, body: TomlBody) -> Result<Response, Refusal> {
    on_pool(endpoint, state, body).await
}

/// `GET /api/health`.
pub async fn health() -> axum::Json<serde_json::Value> {
    axum::Json(serde_json::json!({ "status": "ok", "version": env!("CARGO_PKG_VERSION") }))
}
