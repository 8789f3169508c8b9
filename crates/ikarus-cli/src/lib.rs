//! The `ikarus` command line and what it shares with the other edges of ikarus.
//!
//! The binary `ikarus` is [`main`] (with the default feature `server`). The other edges —
//! the Python package and the WebAssembly build — use [`edge`]: the HTTP API's endpoints
//! without HTTP, and the typed pieces a fast edge needs, so that every edge reads the same
//! settings, runs the same workflow and answers with the same bytes and the same messages.
//!
//! Features: `server` (default) adds `ikarus serve` (axum on tokio) and the command line;
//! `render` adds pictures to [`edge::call`] (`POST /api/render`). Without default features
//! the library builds for `wasm32-unknown-unknown`.

// Without the server, the command line's own modules are compiled (they share files with the
// edges' workflows) but nothing calls their commands.
#![cfg_attr(not(feature = "server"), allow(dead_code, unused_imports))]

mod animate;
mod api;
mod area;
mod arm;
mod batch;
mod bench;
#[cfg(feature = "server")]
mod cli;
mod ease_args;
pub mod edge;
mod error;
mod goals;
mod input;
mod motion;
mod options;
mod output;
mod picture;
mod reach;
mod render;
mod report;
mod rig;
mod rig_animate;
mod rig_args;
mod rig_batch;
mod rig_motion;
mod rig_report;
mod rig_solve;
mod rig_task;
mod rig_track;
#[cfg(feature = "server")]
mod serve;
mod settings;
#[cfg(feature = "server")]
mod shell;
mod solve;
mod stats;
mod track;
mod workspace;

#[cfg(feature = "server")]
pub use cli::main;
