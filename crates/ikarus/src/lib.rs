//! Inverse kinematics for planar chains.
//!
//! A [`Chain`] is a planar serial chain of revolute joints, each followed by a rigid link.
//! Joint angles are radians, each relative to the previous link (the first relative to +x),
//! counter-clockwise positive. [`kinematics`] gives forward kinematics and the analytic
//! Jacobian; a [`Solver`] moves the chain's tip to a [`Goal`] with one of eight [`Method`]s
//! (Jacobian transpose, pseudoinverse, damped least squares, selectively damped least squares,
//! Levenberg–Marquardt, CCD, FABRIK, and the [`closed_form`]s), keeps joints within their limits
//! in one of four [`LimitMode`]s, restarts from other poses when a solve stalls ([`Restarts`]),
//! and reports what happened in an [`Outcome`].
//!
//! ```
//! use ikarus::{Chain, Goal, Link, Method, SolveOptions, Solver, Status};
//!
//! // The seed program's arm: lengths 3, 2, 1, every joint at 5°.
//! let start = 5f64.to_radians();
//! let chain = Chain::new([0.0, 0.0], &[
//!     Link::new(3.0, start),
//!     Link::new(2.0, start),
//!     Link::new(1.0, start),
//! ])?;
//!
//! let mut solver = Solver::new(SolveOptions {
//!     method: Method::DampedLeastSquares,
//!     record_every: Some(20),
//!     ..SolveOptions::default()
//! })?;
//! let outcome = solver.solve(&chain, chain.start_pose(), &Goal::position(2.0, 3.0)?)?;
//!
//! assert_eq!(outcome.status, Status::Reached);
//! assert!(outcome.error <= 1e-6);
//! let tip = ikarus::kinematics::end_effector(&chain, outcome.pose.angles()).position;
//! assert!((tip.x - 2.0).abs() <= 1e-6 && (tip.y - 3.0).abs() <= 1e-6);
//! // The first and the last frame are always recorded.
//! assert_eq!(outcome.frames.get(0).unwrap().iteration, 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Nothing here prints or reads files, and nothing starts threads unless asked to (workspace
//! sampling runs on rayon's pool when [`WorkspaceOptions::parallel`] is set; it is off by
//! default). The same input gives the same output, bit for bit, whatever the number of threads.

// The library never prints: output belongs to the edges (CLI, server). Tests may print.
#![cfg_attr(not(test), deny(clippy::print_stdout, clippy::print_stderr, clippy::dbg_macro))]

pub mod angle;
pub mod chain;
pub mod character;
pub mod closed_form;
pub mod ease;
pub mod goal;
pub mod interrupt;
pub mod kinematics;
mod lanes;
pub mod limits;
mod math;
pub mod motion;
pub mod names;
pub mod number;
pub mod reach;
pub mod rng;
pub mod skeleton;
pub mod solve;
pub mod track;

pub use chain::{Chain, ChainError, Link, LinkField, MAX_REACH, Pose};
pub use ease::{Ease, EaseError, EaseKind, ParentEase};
pub use goal::{Goal, GoalError};
pub use interrupt::Interrupt;
pub use kinematics::EndEffector;
pub use limits::{Bounds, JointLimits, LimitsError};
pub use motion::{Animation, AnimationFrame, Interpolation, KeyTrack, MotionError, MotionOptions, Timing};
pub use names::{Named, UnknownName};
pub use reach::{Annulus, ReachError, Workspace, WorkspaceOptions};
pub use skeleton::{Bone, BoneField, Effector, Joint, Skeleton, SkeletonError};
pub use solve::{
    Bend, BoneBend, EffectorOutcome, Frame, Frames, LimitMode, Method, OptionsError, Outcome, Pin, Priority, Restarts,
    RigGoal, RigTask, RigTaskError, SolveError, SolveOptions, Solver, StallDetection, Status,
};
pub use track::{Follower, Path, PathError, SampleStatus, Track, TrackError, TrackMode, TrackOptions};

/// Re-exported so that callers can name the point type without depending on nalgebra.
pub use nalgebra::Point2;

// The shared test fixtures (see the file), written against the public API.
#[cfg(test)]
extern crate self as ikarus;
#[cfg(test)]
#[path = "../tests/common/fixtures.rs"]
mod fixtures;

/// The Rust examples of the README and of the book (`docs/src`), compiled and run as doctests:
/// one item per page that has ```` ```rust ```` blocks, named after the page
/// (`crates/ikarus-cli/tests/readme.rs` fails when such a page is missing). Every item stands on
/// the first line of `book.rs`, so that rustdoc's line of a failing block is its line in the page.
#[cfg(doctest)]
#[rustfmt::skip]
mod book;
