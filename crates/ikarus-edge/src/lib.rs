//! What the edges of ikarus share: arm and rig files, solver settings and their checks, the
//! HTTP API's endpoints without HTTP ([`edge::call`]), one workflow per job, the JSON answers
//! and the messages. The command line and `ikarus serve` (`ikarus-cli`), the Python package
//! (`ikarus-py`) and the WebAssembly build (`ikarus-wasm`) wrap it, so that every edge reads the
//! same settings, runs the same workflow and answers with the same bytes and the same messages.
//!
//! No command line, no HTTP, no terminal: this crate parses no flags, prints nothing and
//! draws no progress bars. Feature `render` adds pictures to [`edge::call`]
//! (`POST /api/render`). It builds for `wasm32-unknown-unknown`.
//!
//! [`edge`] is the stable face for Python and WebAssembly; the other modules are the pieces
//! the command line shares with it (hidden from the docs).

pub mod edge;

#[doc(hidden)]
pub mod api;
#[doc(hidden)]
pub mod area;
#[doc(hidden)]
pub mod arm;
#[doc(hidden)]
pub mod body;
#[doc(hidden)]
pub mod character;
#[doc(hidden)]
pub mod ease_args;
#[doc(hidden)]
pub mod error;

pub use error::{Error, ErrorKind};
#[doc(hidden)]
pub mod goal;
#[doc(hidden)]
pub mod input;
#[doc(hidden)]
pub mod keys;
#[doc(hidden)]
pub mod motion;
#[doc(hidden)]
pub mod names;
#[doc(hidden)]
pub mod options;
#[doc(hidden)]
pub mod picture;
#[doc(hidden)]
pub mod pose;
#[doc(hidden)]
pub mod pose_finite;
pub mod pose_report;
#[doc(hidden)]
pub mod reach;
#[doc(hidden)]
pub mod report;
#[doc(hidden)]
pub mod rig;
#[doc(hidden)]
pub mod settings;
#[doc(hidden)]
pub mod stats;
#[doc(hidden)]
pub mod track;
