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
//! [`edge`] gathers what Python and WebAssembly call (the API without HTTP, the arm and rig
//! files, the errors); the other modules, each documented, are the pieces the command line
//! uses beside it: the files and their checks ([`arm`], [`rig`], [`keys`], [`character`]), the
//! settings ([`settings`], [`options`], [`goal`]), the jobs ([`motion`], [`track`], [`area`],
//! [`reach`], [`pose`]), the answers ([`report`], [`pose_report`]) and the one error type
//! ([`error`]).

pub mod edge;

pub mod api;
pub mod area;
pub mod arm;
pub mod body;
pub mod character;
pub mod ease_args;
pub mod error;

pub use error::{Error, ErrorKind};
pub mod goal;
pub mod input;
pub mod keys;
pub mod motion;
pub mod names;
pub mod options;
pub mod picture;
pub mod pose;
pub mod pose_finite;
pub mod pose_report;
pub mod reach;
pub mod report;
pub mod rig;
pub mod settings;
pub mod stats;
pub mod track;
