//! `ikarus serve`: the playground page and the JSON API over HTTP, with axum on tokio.
//!
//! Every CPU-heavy request runs in a bounded pool under a time budget ([`pool`]), in a quick or
//! a long lane by the worst case its request allows ([`cost`]), so that quick requests never
//! wait behind long ones; a panic there answers 500 and the server keeps serving. Caps (flags) bound every loop a request can start,
//! [`conn`] bounds connections, [`guard`] checks the Host and the declared body size.

mod conn;
mod cost;
mod errors;
mod guard;
mod handlers;
mod pool;

use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use axum::extract::{DefaultBodyLimit, Path, State};
use axum::http::{Method, Uri, header};
use axum::response::{Html, IntoResponse};
use axum::routing::{MethodRouter, get, post};
use clap::Args;

pub use crate::api::Limits;
use crate::api::{Endpoint, Intake, status};
use crate::error::Error;
use errors::{ApiError, JsonBody, Refusal};
use handlers::{at_once, atlas_file, compute, file_text, rig_file};

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
    ("artfiles.js", JS, include_str!("assets/artfiles.js")),
    ("artgl.js", JS, include_str!("assets/artgl.js")),
    ("artload.js", JS, include_str!("assets/artload.js")),
    ("artview.js", JS, include_str!("assets/artview.js")),
    ("bendhandles.js", JS, include_str!("assets/bendhandles.js")),
    ("body.js", JS, include_str!("assets/body.js")),
    ("camera.js", JS, include_str!("assets/camera.js")),
    ("character.js", JS, include_str!("assets/character.js")),
    ("characters.js", JS, include_str!("assets/characters.js")),
    ("chip.js", JS, include_str!("assets/chip.js")),
    ("controls.js", JS, include_str!("assets/controls.js")),
    ("draw.js", JS, include_str!("assets/draw.js")),
    ("drawchar.js", JS, include_str!("assets/drawchar.js")),
    ("charoptions.js", JS, include_str!("assets/charoptions.js")),
    ("drawkeys.js", JS, include_str!("assets/drawkeys.js")),
    ("drawrig.js", JS, include_str!("assets/drawrig.js")),
    ("export.js", JS, include_str!("assets/export.js")),
    ("files.js", JS, include_str!("assets/files.js")),
    ("history.js", JS, include_str!("assets/history.js")),
    ("input.js", JS, include_str!("assets/input.js")),
    ("keyed.js", JS, include_str!("assets/keyed.js")),
    ("keybends.js", JS, include_str!("assets/keybends.js")),
    ("keyexports.js", JS, include_str!("assets/keyexports.js")),
    ("keys.js", JS, include_str!("assets/keys.js")),
    ("links.js", JS, include_str!("assets/links.js")),
    ("onion.js", JS, include_str!("assets/onion.js")),
    ("paths.js", JS, include_str!("assets/paths.js")),
    ("project.js", JS, include_str!("assets/project.js")),
    ("projects.js", JS, include_str!("assets/projects.js")),
    ("region.js", JS, include_str!("assets/region.js")),
    ("rig.js", JS, include_str!("assets/rig.js")),
    ("rigs.js", JS, include_str!("assets/rigs.js")),
    ("timeline.js", JS, include_str!("assets/timeline.js")),
    ("track.js", JS, include_str!("assets/track.js")),
    ("view.js", JS, include_str!("assets/view.js")),
    ("viewctl.js", JS, include_str!("assets/viewctl.js")),
    ("bodyctl.js", JS, include_str!("assets/bodyctl.js")),
    ("keybody.js", JS, include_str!("assets/keybody.js")),
    ("keyplay.js", JS, include_str!("assets/keyplay.js")),
    ("keymotion.js", JS, include_str!("assets/keymotion.js")),
    ("keybar.js", JS, include_str!("assets/keybar.js")),
    ("state.js", JS, include_str!("assets/state.js")),
    ("armmotion.js", JS, include_str!("assets/armmotion.js")),
    ("workspace.js", JS, include_str!("assets/workspace.js")),
    ("paint.js", JS, include_str!("assets/paint.js")),
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
    /// Largest file text sent to /api/rig/parse or /api/arm/parse, in bytes (413 above it): a
    /// character read there is kept and later requests refer to it by id
    #[arg(long, default_value_t = 16 << 20, value_name = "BYTES", value_parser = clap::value_parser!(u64).range(1..=1 << 30))]
    pub max_file_bytes: u64,
    /// Most links an arm of a request may have
    #[arg(long, default_value_t = 64, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub max_links: u64,
    /// Most bones a rig of a request may have (/api/rig/parse included; a rig has at most 64 goals and pins)
    #[arg(long, default_value_t = 256, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub max_bones: u64,
    /// Largest options.max_iterations of a request
    #[arg(long, default_value_t = crate::settings::DEFAULT_ITERATION_CAP, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
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
    /// Computations (solve, animate, track, workspace, reach, render) run at once, long ones on at most --long-workers of them [default: the number of CPUs]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1024))]
    pub workers: Option<u64>,
    /// Workers for long computations (a request whose worst case is long, or a quick one still running after half a second); the others are kept for quick requests [default: half the workers, at least 1]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1024))]
    pub long_workers: Option<u64>,
    /// Computations that may wait for a worker; beyond that a request is answered 503 at once
    #[arg(long, default_value_t = 256, value_name = "N", value_parser = clap::value_parser!(u64).range(0..=100_000))]
    pub max_queued: u64,
    /// Time budget of each computation, waiting included; past it the work stops and the answer is 503
    #[arg(long, default_value_t = 10_000, value_name = "MS", value_parser = clap::value_parser!(u64).range(1..=86_400_000))]
    pub request_budget_ms: u64,
    /// Open connections at most; one more gets 503 and is closed
    #[arg(long, default_value_t = 512, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub max_connections: u64,
    /// Time a connection has to send a request's headers, idle keep-alive time included
    #[arg(long, default_value_t = 5_000, value_name = "MS", value_parser = clap::value_parser!(u64).range(1..=3_600_000))]
    pub header_timeout_ms: u64,
    /// Time a request has to send its body (408 after it)
    #[arg(long, default_value_t = 10_000, value_name = "MS", value_parser = clap::value_parser!(u64).range(1..=3_600_000))]
    pub body_timeout_ms: u64,
    /// Host name accepted besides localhost, 127.0.0.1 and [::1] while listening on loopback (repeatable)
    #[arg(long, value_name = "NAME")]
    pub allow_host: Vec<String>,
}

/// What every handler shares.
#[derive(Debug, Clone)]
pub struct AppState {
    pub limits: Arc<Limits>,
    pub pool: pool::Pool,
    /// Bytes of request bodies being received or held, at most [`BODY_MEMORY`] (or one body
    /// at the cap, if larger): so that many slow clients cannot fill the memory with bodies.
    pub bodies: Arc<tokio::sync::Semaphore>,
    /// The cap of a file's text (`--max-file-bytes`).
    pub max_file_bytes: usize,
}

/// Whether `path` takes a file (`/api/arm/parse`, `/api/rig/parse`, `/api/atlas/parse`: their
/// [`Intake`]), under `--max-file-bytes` rather than `--max-body-bytes`.
pub fn is_file_path(path: &str) -> bool {
    Endpoint::at(path).is_some_and(|e| e.intake().takes_file())
}

/// Bytes all the request bodies being received may hold at once.
pub const BODY_MEMORY: usize = 64 << 20;

pub fn run(args: &ServeArgs) -> Result<(), Error> {
    let limits = Limits {
        max_body_bytes: usize::try_from(args.max_body_bytes).unwrap_or(usize::MAX),
        max_links: usize::try_from(args.max_links).unwrap_or(usize::MAX),
        max_bones: usize::try_from(args.max_bones).unwrap_or(usize::MAX),
        max_iterations: args.max_iterations,
        max_frames: usize::try_from(args.max_frames).unwrap_or(usize::MAX),
        max_samples: usize::try_from(args.max_samples).unwrap_or(usize::MAX),
        max_resolution: args.max_resolution,
        max_restarts: Limits::default().max_restarts,
        max_goals: Limits::default().max_goals,
        body_timeout: Duration::from_millis(args.body_timeout_ms),
    };
    let parallelism = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let workers = args.workers.map_or(parallelism, |w| usize::try_from(w).unwrap_or(usize::MAX));
    let settings = Settings {
        pool: pool::PoolConfig {
            workers,
            long_workers: args
                .long_workers
                .map_or((workers / 2).max(1), |w| usize::try_from(w).unwrap_or(usize::MAX).min(workers)),
            max_queued: usize::try_from(args.max_queued).unwrap_or(usize::MAX),
            budget: Duration::from_millis(args.request_budget_ms),
        },
        conn: conn::ConnConfig {
            max_connections: usize::try_from(args.max_connections).unwrap_or(usize::MAX),
            header_timeout: Duration::from_millis(args.header_timeout_ms),
        },
        allowed_hosts: args.allow_host.iter().map(|h| h.to_ascii_lowercase()).collect(),
        max_file_bytes: usize::try_from(args.max_file_bytes).unwrap_or(usize::MAX),
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| Error::runtime(format!("cannot start the server's runtime: {e}")))?;
    let result = runtime.block_on(serve(SocketAddr::new(args.host, args.port), limits, settings));
    // Computations still running were interrupted and answered; do not wait for them (a
    // blocking task is not cancellable), the process ends here.
    runtime.shutdown_background();
    result
}

/// The server's settings besides the request caps.
struct Settings {
    pool: pool::PoolConfig,
    conn: conn::ConnConfig,
    allowed_hosts: Vec<String>,
    max_file_bytes: usize,
}

async fn serve(addr: SocketAddr, limits: Limits, settings: Settings) -> Result<(), Error> {
    // `::ffff:127.0.0.1` is loopback too.
    let loopback = addr.ip().to_canonical().is_loopback();
    if !loopback {
        eprintln!(
            "ikarus serve: warning: listening on {}, beyond this machine: anyone who can reach it can use the server",
            addr.ip()
        );
    }
    let listener = tokio::net::TcpListener::bind(addr).await.map_err(|e| {
        Error::runtime(format!("--port {}: cannot listen on {addr}: {}", addr.port(), crate::input::io_reason(&e)))
    })?;
    let bound = listener.local_addr().map_err(|e| Error::runtime(format!("cannot read the bound address: {e}")))?;
    // The Ctrl-C handler is installed before the address is printed, so that a Ctrl-C sent
    // as soon as the server says it listens stops it cleanly.
    let mut signals = Signals::install()?;
    let (stop_tx, stop_rx) = tokio::sync::watch::channel(false);
    let guard = guard::Guard {
        any_host: !loopback,
        allowed_hosts: settings.allowed_hosts,
        max_body_bytes: limits.max_body_bytes,
        max_file_bytes: settings.max_file_bytes,
    };
    let pool = pool::Pool::new(settings.pool, stop_rx.clone());
    println!("ikarus serve: listening on http://{bound}");
    let server = tokio::spawn(conn::serve(
        listener,
        router(limits, pool, guard, settings.max_file_bytes),
        settings.conn,
        stop_rx,
    ));
    signals.next().await;
    eprintln!("ikarus serve: stopping (Ctrl-C again to quit at once)");
    // A second signal ends the process whatever is still running.
    tokio::spawn(async move {
        signals.next().await;
        eprintln!("ikarus serve: stopped at once");
        std::process::exit(130);
    });
    // Stops accepting, interrupts every computation, closes the connections.
    let _ = stop_tx.send(true);
    let _ = server.await;
    eprintln!("ikarus serve: stopped");
    Ok(())
}

/// Ctrl-C (SIGINT), or SIGTERM on Unix; the handlers are installed by [`Signals::install`].
struct Signals {
    #[cfg(unix)]
    interrupt: tokio::signal::unix::Signal,
    #[cfg(unix)]
    terminate: tokio::signal::unix::Signal,
}

impl Signals {
    fn install() -> Result<Self, Error> {
        #[cfg(unix)]
        {
            use tokio::signal::unix::{SignalKind, signal};
            let failed = |e: std::io::Error| Error::runtime(format!("cannot install the Ctrl-C handler: {e}"));
            Ok(Self {
                interrupt: signal(SignalKind::interrupt()).map_err(failed)?,
                terminate: signal(SignalKind::terminate()).map_err(failed)?,
            })
        }
        #[cfg(not(unix))]
        Ok(Self {})
    }

    /// The next signal.
    async fn next(&mut self) {
        #[cfg(unix)]
        tokio::select! {
            _ = self.interrupt.recv() => {}
            _ = self.terminate.recv() => {}
        }
        #[cfg(not(unix))]
        if tokio::signal::ctrl_c().await.is_err() {
            std::future::pending::<()>().await;
        }
    }
}

/// The routes, with the body cap and the request checks.
fn router(limits: Limits, pool: pool::Pool, guard: guard::Guard, max_file_bytes: usize) -> Router {
    let body_cap = limits.max_body_bytes;
    let bodies = Arc::new(tokio::sync::Semaphore::new(BODY_MEMORY.max(body_cap).max(max_file_bytes)));
    let state = AppState { limits: Arc::new(limits), pool, bodies, max_file_bytes };
    let file_cap = DefaultBodyLimit::max(max_file_bytes);
    let mut routes = Router::new()
        .route("/", get(|| async { Html(INDEX_HTML) }))
        .route("/{asset}", get(asset))
        .route("/api/health", get(handlers::health));
    for &endpoint in Endpoint::ALL {
        routes = routes.route(endpoint.path(), route(endpoint, file_cap));
    }
    routes
        .fallback(not_found)
        .layer(DefaultBodyLimit::max(body_cap))
        .layer(axum::middleware::from_fn_with_state(Arc::new(guard), guard::check))
        .with_state(state)
}

/// The route of `endpoint`, as its [`Intake`] says: `GET` answered at once, or `POST` with its
/// body's content type and cap, answered at once or on the pool.
fn route(endpoint: Endpoint, file_cap: DefaultBodyLimit) -> MethodRouter<AppState> {
    match endpoint.intake() {
        Intake::Nothing => get(move |State(s): State<AppState>| async move { at_once(endpoint, &s, b"") }),
        Intake::Json => {
            post(move |State(s): State<AppState>, b: JsonBody| async move { at_once(endpoint, &s, &b.bytes) })
        }
        Intake::Computation => post(move |State(s), b| compute(endpoint, s, b)),
        Intake::FileText => post(move |State(s), b| file_text(endpoint, s, b)).layer(file_cap),
        Intake::JsonFile => post(move |State(s), b| atlas_file(endpoint, s, b)).layer(file_cap),
        Intake::FileTextOrBytes => post(|State(s), h, q, b| rig_file(s, h, q, b)).layer(file_cap),
    }
}

/// One of the page's `ASSETS`, by name.
async fn asset(Path(name): Path<String>, method: Method, uri: Uri) -> Result<impl IntoResponse, Refusal> {
    match ASSETS.iter().find(|(n, ..)| *n == name) {
        Some(&(_, kind, text)) => Ok(([(header::CONTENT_TYPE, kind)], text)),
        None => Err(not_found(method, uri).await),
    }
}

async fn not_found(method: Method, uri: Uri) -> Refusal {
    Refusal(ApiError::new(status::NOT_FOUND, format!("{method} {}: no such endpoint", uri.path())))
}
