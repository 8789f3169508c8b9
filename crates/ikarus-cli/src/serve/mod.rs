//! `ikarus serve`: the playground page and the JSON API over HTTP, with axum on tokio.
//!
//! Every CPU-heavy request runs on tokio's blocking pool; a panic there answers 500 and the
//! server keeps serving. Caps (flags) bound every loop a request can start.

mod api;
mod arm_files;
mod errors;
mod meta;
mod requests;

use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;

use axum::Router;
use axum::extract::{DefaultBodyLimit, Path};
use axum::http::{Method, StatusCode, Uri, header};
use axum::response::{Html, IntoResponse};
use axum::routing::{get, post};
use clap::Args;

use crate::error::CliError;
use errors::ApiError;

/// The playground page and its assets, embedded at compile time (no build step, nothing fetched).
const INDEX_HTML: &str = include_str!("assets/index.html");
const CSS: &str = "text/css; charset=utf-8";
const JS: &str = "text/javascript; charset=utf-8";
/// The files the page loads, served at `/{name}`: name, content type, text. The scripts are ES
/// modules; `main.js` imports the others.
const ASSETS: &[(&str, &str, &str)] = &[
    ("app.css", CSS, include_str!("assets/app.css")),
    ("main.js", JS, include_str!("assets/main.js")),
    ("api.js", JS, include_str!("assets/api.js")),
    ("armfile.js", JS, include_str!("assets/armfile.js")),
    ("controls.js", JS, include_str!("assets/controls.js")),
    ("draw.js", JS, include_str!("assets/draw.js")),
    ("export.js", JS, include_str!("assets/export.js")),
    ("files.js", JS, include_str!("assets/files.js")),
    ("input.js", JS, include_str!("assets/input.js")),
    ("links.js", JS, include_str!("assets/links.js")),
    ("paths.js", JS, include_str!("assets/paths.js")),
    ("timeline.js", JS, include_str!("assets/timeline.js")),
    ("track.js", JS, include_str!("assets/track.js")),
    ("view.js", JS, include_str!("assets/view.js")),
];

/// Serve the JSON API on HTTP (loopback only unless --host says otherwise)
#[derive(Debug, Clone, Args)]
pub struct ServeArgs {
    /// Address to listen on; anything but a loopback address exposes the server to the network
    #[arg(long, default_value = "127.0.0.1", value_name = "IP")]
    pub host: IpAddr,
    /// Port to listen on; 0 picks a free one (the address printed says which)
    #[arg(long, default_value_t = 7878)]
    pub port: u16,
    /// Largest request body, in bytes (413 above it)
    #[arg(long, default_value_t = 1 << 20, value_name = "BYTES", value_parser = clap::value_parser!(u64).range(1..=1 << 30))]
    pub max_body_bytes: u64,
    /// Most links an arm of a request may have
    #[arg(long, default_value_t = 64, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub max_links: u64,
    /// Largest options.max_iterations of a request
    #[arg(long, default_value_t = 100_000, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub max_iterations: u32,
    /// Most frames of a motion
    #[arg(long, default_value_t = 2000, value_name = "N", value_parser = clap::value_parser!(u64).range(2..=1_000_000))]
    pub max_frames: u64,
    /// Most samples of a path (POST /api/track)
    #[arg(long, default_value_t = 5000, value_name = "N", value_parser = clap::value_parser!(u64).range(2..=1_000_000))]
    pub max_samples: u64,
    /// Largest workspace resolution (cells per side, at most 4096)
    #[arg(long, default_value_t = 1024, value_name = "N", value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub max_resolution: u32,
}

/// The caps of every request, from the flags.
#[derive(Debug, Clone)]
pub struct Limits {
    pub max_body_bytes: usize,
    pub max_links: usize,
    pub max_iterations: u32,
    pub max_frames: usize,
    pub max_samples: usize,
    pub max_resolution: u32,
}

/// What every handler shares.
#[derive(Debug, Clone)]
pub struct AppState {
    pub limits: Arc<Limits>,
}

pub fn run(args: &ServeArgs) -> Result<(), CliError> {
    let limits = Limits {
        max_body_bytes: usize::try_from(args.max_body_bytes).unwrap_or(usize::MAX),
        max_links: usize::try_from(args.max_links).unwrap_or(usize::MAX),
        max_iterations: args.max_iterations,
        max_frames: usize::try_from(args.max_frames).unwrap_or(usize::MAX),
        max_samples: usize::try_from(args.max_samples).unwrap_or(usize::MAX),
        max_resolution: args.max_resolution,
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| CliError::runtime(format!("cannot start the server's runtime: {e}")))?;
    runtime.block_on(serve(SocketAddr::new(args.host, args.port), limits))
}

async fn serve(addr: SocketAddr, limits: Limits) -> Result<(), CliError> {
    if !addr.ip().is_loopback() {
        eprintln!(
            "ikarus serve: warning: listening on {}, beyond this machine: anyone who can reach it can use the server",
            addr.ip()
        );
    }
    let listener = tokio::net::TcpListener::bind(addr).await.map_err(|e| {
        CliError::runtime(format!("--port {}: cannot listen on {addr}: {}", addr.port(), crate::arm::io_reason(&e)))
    })?;
    let bound = listener.local_addr().map_err(|e| CliError::runtime(format!("cannot read the bound address: {e}")))?;
    // The Ctrl-C handler is installed before the address is printed, so that a Ctrl-C sent
    // as soon as the server says it listens stops it cleanly.
    let stop = shutdown_signal()?;
    println!("ikarus serve: listening on http://{bound}");
    axum::serve(listener, router(limits))
        .with_graceful_shutdown(stop)
        .await
        .map_err(|e| CliError::runtime(format!("server failed: {e}")))?;
    eprintln!("ikarus serve: stopped");
    Ok(())
}

/// A future that completes on Ctrl-C (SIGINT), or SIGTERM on Unix; the handlers are
/// installed when this returns.
fn shutdown_signal() -> Result<impl std::future::Future<Output = ()>, CliError> {
    let failed = |e: std::io::Error| CliError::runtime(format!("cannot install the Ctrl-C handler: {e}"));
    #[cfg(unix)]
    {
        use tokio::signal::unix::{SignalKind, signal};
        let mut interrupt = signal(SignalKind::interrupt()).map_err(failed)?;
        let mut terminate = signal(SignalKind::terminate()).map_err(failed)?;
        Ok(async move {
            tokio::select! {
                _ = interrupt.recv() => {}
                _ = terminate.recv() => {}
            }
        })
    }
    #[cfg(not(unix))]
    {
        let _ = failed;
        Ok(async {
            if tokio::signal::ctrl_c().await.is_err() {
                std::future::pending::<()>().await;
            }
        })
    }
}

/// The routes, with the body cap.
pub fn router(limits: Limits) -> Router {
    let body_cap = limits.max_body_bytes;
    let state = AppState { limits: Arc::new(limits) };
    Router::new()
        .route("/", get(|| async { Html(INDEX_HTML) }))
        .route("/{asset}", get(asset))
        .route("/api/health", get(api::health))
        .route("/api/meta", get(meta::handler))
        .route("/api/arm/default", get(api::default_arm))
        .route("/api/arm/parse", post(arm_files::parse_handler))
        .route("/api/arm/toml", post(arm_files::toml_handler))
        .route("/api/solve", post(api::solve))
        .route("/api/animate", post(api::animate))
        .route("/api/track", post(api::track))
        .route("/api/workspace", post(api::workspace))
        .route("/api/render", post(api::render))
        .fallback(not_found)
        .layer(DefaultBodyLimit::max(body_cap))
        .with_state(state)
}

/// One of the page's `ASSETS`, by name.
async fn asset(Path(name): Path<String>, method: Method, uri: Uri) -> Result<impl IntoResponse, ApiError> {
    match ASSETS.iter().find(|(n, ..)| *n == name) {
        Some(&(_, kind, text)) => Ok(([(header::CONTENT_TYPE, kind)], text)),
        None => Err(not_found(method, uri).await),
    }
}

async fn not_found(method: Method, uri: Uri) -> ApiError {
    ApiError { status: StatusCode::NOT_FOUND, message: format!("{method} {}: no such endpoint", uri.path()) }
}

/// Runs `work` on the blocking pool; a panic becomes a 500 and the server keeps serving.
pub async fn blocking<T: Send + 'static>(
    work: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    match tokio::task::spawn_blocking(work).await {
        Ok(result) => result,
        Err(e) if e.is_panic() => {
            let payload = e.into_panic();
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a request handler panicked".to_owned());
            Err(ApiError::internal(what))
        }
        Err(e) => Err(ApiError::internal(e.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn a_panic_in_a_handler_becomes_a_500() {
        let e = blocking::<()>(|| panic!("boom")).await.unwrap_err();
        assert_eq!(e.status, StatusCode::INTERNAL_SERVER_ERROR);
        assert_eq!(e.message, "internal error: boom");
        // The pool still works afterwards.
        assert_eq!(blocking(|| Ok(7)).await.unwrap(), 7);
    }
}
