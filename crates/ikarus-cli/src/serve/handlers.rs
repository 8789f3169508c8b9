//! The routes' handlers: each reads its request (a JSON body bounded in size, memory and time
//! by [`JsonBody`]), runs [`api::call`] — the same function Python and WebAssembly call — on a
//! worker of the pool for the computations, and answers its bytes.

use axum::extract::RawQuery;
use axum::http::{HeaderMap, header};
use axum::response::{IntoResponse, Response};
use ikarus::Interrupt;

use super::AppState;
use super::errors::{ApiBody, AtlasBody, JsonBody, OCTET_STREAM, Refusal, RigFileBody, TomlBody, essence};
use super::pool::Lane;
use crate::api::rigs::{Echo, FileBody};
use crate::api::{self, Endpoint, Problem, Reply};

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

/// What the first step of a request on the pool ended with.
enum Step {
    /// Its answer: it was quick.
    Answered(Reply),
    /// Its request, read, whose work is long: to run on a long worker.
    Long(api::Request),
}

/// [`api::call`] of `body` on a worker of the pool, in its lane, under the time budget.
///
/// The body is read into its typed request ([`Endpoint::parse`]) on a worker of the quick lane,
/// never on the runtime's threads: a body of a megabyte (a character file's text in `rig`) is
/// real work, and a reading that runs long moves to a long worker or is stopped as any quick
/// computation is ([`super::pool`]), so it can neither stall the runtime nor hold a quick
/// worker. A body that does not parse is refused there at once. The request read is costed
/// ([`api::Request::cost`]); a quick one runs on in the same worker, a long one is handed back
/// and runs on a long worker, under the same deadline. The request is read once: the same
/// value is costed and run.
async fn on_pool<T: Send + Sync + 'static>(
    endpoint: Endpoint,
    state: AppState,
    body: ApiBody<T>,
) -> Result<Response, Refusal> {
    let pool = state.pool.clone();
    let deadline = pool.deadline();
    let limits = std::sync::Arc::clone(&state.limits);
    let first = pool.run_by(deadline, Lane::Quick, move |interrupt| {
        let request = endpoint.parse(&body.bytes, &limits)?;
        drop(body);
        match super::cost::lane(request.cost()) {
            Lane::Quick => request.run(&limits, interrupt).map(Step::Answered),
            Lane::Long => Ok(Step::Long(request)),
        }
    });
    let reply = match first.await.map_err(Refusal)? {
        Step::Answered(reply) => reply,
        Step::Long(request) => pool
            .run_by(deadline, Lane::Long, move |interrupt| request.run(&state.limits, interrupt))
            .await
            .map_err(Refusal)?,
    };
    Ok(answer(reply))
}

/// A quick answer (`/api/meta`, `arm/default`, `rigs`, `arm/toml`, `ease`): no solve, no loop
/// a request can lengthen, answered on the spot.
pub fn at_once(endpoint: Endpoint, state: &AppState, body: &[u8]) -> Result<Response, Refusal> {
    api::call(endpoint, body, &state.limits, &Interrupt::new()).map(answer).map_err(Refusal)
}

/// `/api/arm/parse`: the body is a file's text, sent as `application/toml`.
/// Read on a worker of the pool, costed from its bytes ([`super::cost`]), under the time
/// budget: a character file of a megabyte is real work, which on the runtime's own threads
/// held `/api/health`, every other request and Ctrl-C for as long as it took.
pub async fn file_text(endpoint: Endpoint, state: AppState, body: TomlBody) -> Result<Response, Refusal> {
    on_pool(endpoint, state, body).await
}

/// `/api/atlas/parse`: a texture atlas and its page images (JSON under `--max-file-bytes`),
/// read on a worker of the pool as [`compute`] does.
pub async fn atlas_file(endpoint: Endpoint, state: AppState, body: AtlasBody) -> Result<Response, Refusal> {
    on_pool(endpoint, state, body).await
}

/// `/api/rig/parse`: the body is a rig or character file's text (`application/toml`) or bytes
/// (`application/octet-stream`: a Spine `.skel`, decoded into its JSON text), read on a worker
/// of the pool as [`file_text`]; `?text=1` adds the kept JSON text to a character's answer
/// ([`Echo::Text`]).
pub async fn rig_file(
    state: AppState,
    headers: HeaderMap,
    RawQuery(query): RawQuery,
    body: RigFileBody,
) -> Result<Response, Refusal> {
    let echo = echo(query.as_deref())?;
    let given = if essence(&headers) == OCTET_STREAM { FileBody::Bytes } else { FileBody::Text };
    let pool = state.pool.clone();
    let lane = super::cost::file_lane(given, &body.bytes);
    pool.run(lane, move |_| api::rigs::parse_file(&body.bytes, given, echo, &state.limits))
        .await
        .map(answer)
        .map_err(Refusal)
}

/// The `text` parameter of `/api/rig/parse`'s query: `1` to echo the text, `0` (or none) not to.
fn echo(query: Option<&str>) -> Result<Echo, Problem> {
    let mut echo = Echo::Without;
    for (key, value) in query.unwrap_or_default().split('&').filter_map(|pair| pair.split_once('=')) {
        if key == "text" {
            echo = match value {
                "1" => Echo::Text,
                "0" => Echo::Without,
                other => return Err(Problem::invalid(format!("query: text = {other:?}: expected 1 or 0"))),
            };
        }
    }
    Ok(echo)
}

/// `GET /api/health`.
pub async fn health() -> axum::Json<serde_json::Value> {
    axum::Json(serde_json::json!({ "status": "ok", "version": env!("CARGO_PKG_VERSION") }))
}
