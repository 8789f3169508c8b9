//! The `ikarus` command line and `ikarus serve`: clap flags, files and the terminal on stdin,
//! stdout and stderr, HTTP, and `ikarus bench` (the crate `ikarus-bench`, given the command
//! line's stdout and files), around what the edges share (the crate `ikarus-edge`: arm and rig
//! files, settings, the API's endpoints, one workflow per job).
//!
//! The binary `ikarus` is [`main`] (with the default feature `server`).

// The edge's modules under their old names, so that the commands' paths (`crate::arm::Arm`)
// stay as they were; the modules below that share a name with an edge module re-export it and
// add the command line's part (its flags, its terminal output).
use ikarus_edge::{api, area, arm, body, error, goal, input, motion, report, rig};
// `ikarus bench`, its own crate (`crates/ikarus-bench`).
use ikarus_bench as bench;

mod animate;
mod batch;
mod body_args;
mod character_motion;
#[cfg(feature = "server")]
mod cli;
mod columns;
mod ease_args;
mod goal_args;
mod goals;
mod motion_art;
mod options;
mod output;
mod picture;
mod pose;
mod pose_art;
mod reach;
mod render;
#[cfg(feature = "server")]
mod serve;
mod settings;
#[cfg(feature = "server")]
mod shell;
mod solve;
mod track;
mod workspace;

#[cfg(feature = "server")]
pub use cli::main;
