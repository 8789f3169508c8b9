//! Paths for the tip: a [`Path`] of goals tracked without flips, online ([`follow`], and the
//! streaming [`Follower`]) or as one global search ([`plan`]).
//!
//! ## Follow (online)
//!
//! Each sample is solved from the previous pose, warm-started: the solver's closed form takes
//! the branch nearest the previous pose, the iteration converges to a solution near it, and
//! only when that fails does it restart, from at most `solve.restarts.attempts` seeded poses
//! within ±[`TrackOptions::radius`] of the previous pose (never from far away). Then no joint
//! moves more than [`TrackOptions::max_step`]: where the solution needs more, the whole joint
//! step `Δ` is scaled by `max_step / max|Δᵢ|`, so the arm moves that far toward the solution
//! along a straight line in joint space, the sample is [`SampleStatus::Limited`], and later
//! samples catch up. Where the goal is out of reach, the arm stays at the best pose nearest the
//! previous one ([`SampleStatus::Unreachable`]), still within the bound. It never teleports.
//!
//! ## Plan (offline)
//!
//! A ladder graph: at most [`TrackOptions::candidates`] solutions per sample (and never fewer
//! than the chain has joints), searched by dynamic programming for the joint path with the least
//! flip cost, `Σ (step − max_step)²` over the steps that are flips (so a path without flips
//! always wins, and where the bound must be exceeded, as on a path sampled too coarsely, many
//! steps a little over it cost less than one branch jump), and then the least joint motion,
//! `Σ_k Σ_i Δq_{k,i}²` (the start pose counts as sample −1; free joints the short way round),
//! then polished. Candidates of a sample are
//!
//! - both branches of the closed form where it applies (two links with a position goal, three
//!   with an orientation goal), or else
//! - the warm-started continuation of every candidate of the previous sample (the self-motion
//!   of a redundant chain is followed along several tracks at once), topped up with solves from
//!   seeded poses spread over the joint ranges ([`TrackOptions::seeds`] per sample; the first
//!   sample also from the start pose), and deduplicated: two candidates less than `max_step / 4`
//!   apart (largest joint difference) are one.
//!
//! Only candidates that reach the goal are kept when any does. The polish is a few Gauss–Seidel
//! passes ([`TrackOptions::polish_passes`]) that re-solve each sample but the first and the last
//! warm-started from the midpoint of its neighbours on the chosen path and keep the new pose
//! only if it reaches the goal, adds no flip and lowers the local joint motion: it smooths the
//! self-motion and never raises the path's cost. (The first sample is left as the search chose
//! it: pulling it toward the start pose would steepen the path's first steps.) Where every path
//! through the candidates has a flip (the path leaves what the arm can reach with its limits and
//! comes back elsewhere, or the arm must change branch), the plan never jumps: between the two
//! samples the arm leaves the path and moves by a straight line in joint space, in equal steps
//! within the bound (continuous, and inside the limits), the inserted poses marked
//! [`SampleStatus::OffPath`] and counted in [`TrackSummary::off_path`]. So no step of a plan
//! exceeds the bound either, and its [`TrackSummary::flips`] stay empty.
//!
//! ## Flips
//!
//! A flip is a step between consecutive samples in which some joint moves more than
//! [`TrackOptions::max_step`] ([`is_flip`]); joints without enforced limits are measured the
//! short way round.
//!
//! ```
//! use ikarus::track::{self, Path, TrackOptions};
//! use ikarus::{Chain, Link};
//!
//! let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.1), Link::new(2.0, 0.1), Link::new(1.0, 0.1)])?;
//! let path = Path::figure8([2.0, 1.0], 2.0, 100)?;
//! let options = TrackOptions::default();
//! let planned = track::plan(&chain, chain.start_pose().angles(), &path, &options)?;
//! assert!(planned.summary.flips.is_empty());
//! assert_eq!(planned.summary.reached, 100);
//!
//! // Online: one sample at a time, never a step over the bound.
//! let mut follower = track::Follower::new(&chain, chain.start_pose().angles(), &options)?;
//! for goal in path.goals() {
//!     let step = follower.step(goal);
//!     assert!(step.step <= options.max_step * (1.0 + 1e-9));
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod body;
mod bridge;
mod follow;
mod path;
mod plan;
mod result;

#[cfg(test)]
mod skeleton_tests;
#[cfg(test)]
mod tests;

use crate::listed_enum;
use crate::math;
use crate::number::Num;
use thiserror::Error;

use crate::angle::{nearest_equivalent, wrap_angle};
use crate::chain::Chain;
use crate::limits::Bounds;
use crate::solve::{LimitMode, OptionsError, SolveError, SolveOptions, Solver};

pub use body::{RigEffector, TrackBody};
pub use bridge::MAX_OFF_PATH_PER_SAMPLE;
pub use follow::{Follower, Step, follow, follow_rig};
pub use path::{Path, PathError, PointError};
pub use plan::plan;
pub use result::{SampleStatus, Track, TrackSample, TrackSummary, is_flip};

listed_enum! {
    /// How a path is tracked.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum TrackMode {
        /// [`follow`]: online, sample by sample, every step within the bound.
        Follow,
        /// [`plan`]: one global search over the whole path.
        Plan,
    }
}

impl TrackMode {
    /// `follow` or `plan`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            TrackMode::Follow => "follow",
            TrackMode::Plan => "plan",
        }
    }

    /// A short label.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            TrackMode::Follow => "Follow",
            TrackMode::Plan => "Plan",
        }
    }

    /// One line saying what the mode does.
    #[must_use]
    pub fn summary(self) -> &'static str {
        match self {
            TrackMode::Follow => "Online: each sample from the previous pose, no joint step over the bound",
            TrackMode::Plan => {
                "Offline: a global search for the joint path without flips (or the smallest ones) and least motion"
            }
        }
    }
}

crate::names::by_name!(TrackMode, "track mode");

/// Options of tracking a path. Start from [`TrackOptions::default`] and change what you need.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackOptions {
    /// The bound on a joint's change between consecutive samples, radians, > 0 (default 10°):
    /// [`follow`] never exceeds it, and a step over it is a flip.
    pub max_step: f64,
    /// The solver's options. Its [`SolveOptions::restarts`] are not run by the solver: they
    /// give the attempts and seed of [`follow`]'s restarts near the previous pose and the seed
    /// of [`plan`]'s seeded poses (`None`: no restarts, seed 0).
    pub solve: SolveOptions,
    /// [`follow`] restarts from poses within ±`radius` radians of the previous pose on every
    /// joint, ≥ 0 (default 0.5, about 29°).
    pub radius: f64,
    /// [`plan`]: at most this many candidate solutions per sample, ≥ 1 (default 8), and never
    /// fewer than the chain has joints: each joint adds a dimension of self-motion to keep track
    /// of (with 8 on a 20-link chain the search lost the continuous track of a path that has one).
    pub candidates: usize,
    /// [`plan`]: solves from seeded poses per sample, to find solutions the continuations miss
    /// (default 2; the first sample gets `candidates` of them).
    pub seeds: usize,
    /// [`plan`]: smoothing passes over the chosen path (default 2).
    pub polish_passes: u32,
    /// [`follow`]: bound the first sample too, as a step of at most `max_step` from the start
    /// pose (its `step` is then measured from the start pose). Off by default: the first sample
    /// is placed at the solution nearest the start pose, however far. On for a goal streamed one
    /// sample at a time from the arm's current pose (a followed pointer), so that it never jumps.
    pub bound_first: bool,
}

impl Default for TrackOptions {
    fn default() -> Self {
        Self {
            max_step: 10f64.to_radians(),
            solve: SolveOptions::default(),
            radius: 0.5,
            candidates: 8,
            seeds: 2,
            polish_passes: 2,
            bound_first: false,
        }
    }
}

/// Why a path could not be tracked. Every variant names the field and the value.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum TrackError {
    /// A tracking option is out of range.
    #[error("{field}: must be {expected}, got {}", Num(*.value))]
    OutOfRange {
        /// The option's name.
        field: &'static str,
        /// The allowed range, in words.
        expected: &'static str,
        /// The offending value.
        value: f64,
    },
    /// The solver's options are invalid.
    #[error(transparent)]
    Options(#[from] OptionsError),
    /// The start pose or the options do not fit the chain.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// [`plan`] would need more off-path poses to bridge the gaps of the path than
    /// [`MAX_OFF_PATH_PER_SAMPLE`] per sample: `max_step` is far smaller than the gaps.
    #[error(
        "max_step = {} rad: bridging the plan's gaps in steps this small needs {needed} off-path poses, more than the cap of {cap} ({MAX_OFF_PATH_PER_SAMPLE} per sample); raise max_step or sample the path more finely",
        Num(*.max_step)
    )]
    OffPathCap {
        /// The bound, radians.
        max_step: f64,
        /// The off-path poses the gaps need.
        needed: usize,
        /// The most allowed for this path.
        cap: usize,
    },
    /// The solver options' [`interrupt`](SolveOptions::interrupt) was set before the path was
    /// done.
    #[error("interrupted")]
    Interrupted,
}

impl TrackOptions {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), TrackError> {
        let bad = |field, expected, value| Err(TrackError::OutOfRange { field, expected, value });
        if !(self.max_step.is_finite() && self.max_step > 0.0) {
            return bad("max_step", "a finite number > 0", self.max_step);
        }
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return bad("radius", "a finite number ≥ 0", self.radius);
        }
        if self.candidates == 0 {
            return bad("candidates", "at least 1", 0.0);
        }
        self.solve.validate()?;
        Ok(())
    }

    /// A solver for one chain: these options checked against `chain` and `start`, with the
    /// solver's own restarts off (tracking runs its own).
    fn solver(&self, chain: &Chain, start: &[f64]) -> Result<Solver, TrackError> {
        self.validate()?;
        self.solve.validate_for(chain)?;
        check_start(chain.len(), start)?;
        Ok(Solver::new(SolveOptions { restarts: None, record_every: None, ..self.solve.clone() })?)
    }

    /// The seed of the restarts and seeded poses.
    fn seed(&self) -> u64 {
        self.solve.restarts.map_or(0, |r| r.seed)
    }
}

/// Checks that the start pose `start` has `joints` angles, all finite.
fn check_start(joints: usize, start: &[f64]) -> Result<(), SolveError> {
    if start.len() != joints {
        return Err(SolveError::PoseLength { expected: joints, got: start.len() });
    }
    match start.iter().enumerate().find(|(_, a)| !a.is_finite()) {
        Some((index, &value)) => Err(SolveError::NonFiniteAngle { index, value }),
        None => Ok(()),
    }
}

/// Tracks `path` with `chain` from the pose `start` (radians) in `mode`: [`follow`] or
/// [`plan`].
pub fn track(
    chain: &Chain,
    start: &[f64],
    path: &Path,
    mode: TrackMode,
    options: &TrackOptions,
) -> Result<Track, TrackError> {
    match mode {
        TrackMode::Follow => follow(chain, start, path, options),
        TrackMode::Plan => plan(chain, start, path, options),
    }
}

/// The limits a track enforces: the chain's, or none when the options ignore them.
fn bounds<'a>(chain: &'a Chain, options: &SolveOptions) -> Bounds<'a> {
    match options.limits {
        LimitMode::Ignore => Bounds::free(),
        LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => chain.bounds(),
    }
}

/// `a − b` for joint `i`: wrapped into [−π, π) (the short way round) when the joint has no
/// bound, plain otherwise (a limited joint cannot pass through its excluded range).
#[inline]
fn joint_delta(bounds: Bounds<'_>, i: usize, a: f64, b: f64) -> f64 {
    if bounds.get(i).is_some() { a - b } else { wrap_angle(a - b) }
}

/// The largest joint change from `from` to `to`, radians.
#[inline]
fn joint_step(bounds: Bounds<'_>, to: &[f64], from: &[f64]) -> f64 {
    to.iter().zip(from).enumerate().map(|(i, (&a, &b))| joint_delta(bounds, i, a, b).abs()).fold(0.0, f64::max)
}

/// The squared joint distance from `from` to `to`, radians².
#[inline]
fn joint_distance2(bounds: Bounds<'_>, to: &[f64], from: &[f64]) -> f64 {
    to.iter().zip(from).enumerate().map(|(i, (&a, &b))| math::square(joint_delta(bounds, i, a, b))).sum()
}

/// [`joint_step`] and [`joint_distance2`] of the same two poses in one pass over the joints,
/// bit for bit the same numbers (the plan's search asks for both of every pair of candidates).
#[inline]
fn joint_step_and_distance2(bounds: Bounds<'_>, to: &[f64], from: &[f64]) -> (f64, f64) {
    let (mut step, mut distance2) = (0.0f64, 0.0);
    for (i, (&a, &b)) in to.iter().zip(from).enumerate() {
        let d = joint_delta(bounds, i, a, b);
        step = step.max(d.abs());
        distance2 += math::square(d);
    }
    (step, distance2)
}

/// Moves every free joint of `angles` to its 2π-equivalent nearest `reference`, so that
/// consecutive poses differ by their short-way steps.
#[inline]
fn unwrap_free(bounds: Bounds<'_>, angles: &mut [f64], reference: &[f64]) {
    for (i, (a, &r)) in angles.iter_mut().zip(reference).enumerate() {
        if bounds.get(i).is_none() {
            let shifted = nearest_equivalent(*a, r);
            if shifted.is_finite() {
                *a = shifted;
            }
        }
    }
}
