//! What tracking a path returns: one [`TrackSample`] per sample and a [`TrackSummary`] of
//! flips, errors and the joint-space velocity, acceleration and jerk.

use crate::goal::Goal;
use crate::limits::Bounds;
use crate::solve::Status;

crate::listed_enum! {
    /// How one sample of a path ended.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum SampleStatus {
        /// The tip is within tolerance of the sample's goal.
        Reached,
        /// [`follow`](super::follow) only: the goal needed a larger joint step than
        /// [`TrackOptions::max_step`](super::TrackOptions::max_step), so the arm moved that far
        /// toward it and catches up on later samples.
        Limited,
        /// The goal is out of reach even with the limits ignored; the pose is the best found
        /// nearest the previous one.
        Unreachable,
        /// No solution was found near the previous pose (a local minimum, or joints held at their
        /// limits); the pose is the best found.
        Stalled,
        /// The solver's iteration cap was hit while the pose was still moving.
        IterationLimit,
        /// The solve was interrupted ([`SolveOptions::interrupt`](crate::SolveOptions::interrupt)).
        Interrupted,
        /// [`plan`](super::plan) only: not one of the path's samples but a pose it inserted on the
        /// way to the next one, where the chosen poses of two consecutive samples lie further apart
        /// than [`TrackOptions::max_step`](super::TrackOptions::max_step) (where the path leaves
        /// what the arm can follow, or the arm must change branch): the arm leaves the path there
        /// and moves by a straight line in joint space, in steps within the bound. Its goal is the
        /// next sample's.
        OffPath,
    }
}

impl SampleStatus {
    /// `reached`, `limited`, `unreachable`, `stalled`, `iteration_limit`, `interrupted` or
    /// `off_path`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            SampleStatus::Reached => "reached",
            SampleStatus::Limited => "limited",
            SampleStatus::Unreachable => "unreachable",
            SampleStatus::Stalled => "stalled",
            SampleStatus::IterationLimit => "iteration_limit",
            SampleStatus::Interrupted => "interrupted",
            SampleStatus::OffPath => "off_path",
        }
    }

    /// The sample status of a solve that ended with `status`.
    #[must_use]
    pub fn from_solve(status: Status) -> Self {
        match status {
            Status::Reached => SampleStatus::Reached,
            Status::Unreachable => SampleStatus::Unreachable,
            Status::Stalled => SampleStatus::Stalled,
            Status::IterationLimit => SampleStatus::IterationLimit,
            Status::Interrupted => SampleStatus::Interrupted,
        }
    }
}

impl std::fmt::Display for SampleStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One sample of a tracked path, or a pose [`plan`](super::plan) inserted between two
/// ([`SampleStatus::OffPath`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSample {
    /// The sample's goal.
    pub goal: Goal,
    /// How it ended.
    pub status: SampleStatus,
    /// Distance from the tip to the goal's position.
    pub error: f64,
    /// Absolute orientation error, radians in [0, π]; 0 without an orientation goal.
    pub angle_error: f64,
    /// The pose, radians, one angle per joint. Free joints are unwrapped along the path (each
    /// the equivalent nearest its previous value), so consecutive poses differ by their steps.
    pub angles: Vec<f64>,
    /// The largest joint change from the previous sample, radians (free joints the short way
    /// round); 0 for the first sample.
    pub step: f64,
}

/// A summary of a tracked path. Joint-space rates are finite differences per sample, radians:
/// velocity `v_k = q_k − q_{k−1}` (the step), acceleration `v_k − v_{k−1}`, jerk the difference
/// of accelerations; each maximum is over every joint and sample where it is defined.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSummary {
    /// Samples in the path (the off-path poses not counted).
    pub samples: usize,
    /// Samples [`SampleStatus::Reached`].
    pub reached: usize,
    /// Samples [`SampleStatus::Limited`].
    pub limited: usize,
    /// Samples [`SampleStatus::Unreachable`].
    pub unreachable: usize,
    /// Samples [`SampleStatus::Stalled`] or [`SampleStatus::IterationLimit`].
    pub stalled: usize,
    /// Poses [`SampleStatus::OffPath`]: inserted by [`plan`](super::plan) where the arm leaves
    /// the path to move between two samples within the bound.
    pub off_path: usize,
    /// The samples whose step is a flip: some joint moved more than the bound
    /// ([`is_flip`]) since the previous sample.
    pub flips: Vec<usize>,
    /// The largest step, radians.
    pub max_step: f64,
    /// The largest position error of the path's samples (the off-path poses not counted).
    pub max_error: f64,
    /// The largest joint velocity, radians per sample.
    pub max_velocity: f64,
    /// The largest joint acceleration, radians per sample².
    pub max_acceleration: f64,
    /// The largest joint jerk, radians per sample³.
    pub max_jerk: f64,
}

/// A tracked path: every sample (and the poses [`plan`](super::plan) inserted between them), and
/// their summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// One per sample of the path, in order, and [`SampleStatus::OffPath`] poses between two
    /// samples where [`plan`](super::plan) left the path to stay within the bound (see
    /// [`Track::on_path`] for the path's samples alone).
    pub samples: Vec<TrackSample>,
    /// Flips, errors and rates.
    pub summary: TrackSummary,
}

/// Whether a step of `step` radians is a flip under the bound `max_step`: larger by more than
/// rounding (a relative 1e-9), so that a step scaled to exactly the bound is not one.
#[must_use]
pub fn is_flip(step: f64, max_step: f64) -> bool {
    step > max_step * (1.0 + 1e-9)
}

impl Track {
    /// The track of `samples` (their `step` already set), summarised with the flip bound
    /// `max_step`; `bounds` says which joints are free (their changes measured the short way).
    pub(super) fn new(samples: Vec<TrackSample>, bounds: Bounds<'_>, max_step: f64) -> Self {
        let summary = summarise(&samples, bounds, max_step);
        Self { samples, summary }
    }

    /// The path's samples, one per goal in order: [`Track::samples`] without the off-path
    /// poses.
    pub fn on_path(&self) -> impl Iterator<Item = &TrackSample> {
        self.samples.iter().filter(|s| s.status != SampleStatus::OffPath)
    }
}

fn summarise(samples: &[TrackSample], bounds: Bounds<'_>, max_step: f64) -> TrackSummary {
    let count = |s: &[SampleStatus]| samples.iter().filter(|x| s.contains(&x.status)).count();
    let n = samples.first().map_or(0, |s| s.angles.len());
    let (mut max_velocity, mut max_acceleration, mut max_jerk) = (0.0f64, 0.0f64, 0.0f64);
    // Per joint: the last velocity and acceleration, once defined.
    let mut velocity: Vec<Option<f64>> = vec![None; n];
    let mut acceleration: Vec<Option<f64>> = vec![None; n];
    for pair in samples.windows(2) {
        for i in 0..n {
            let v = super::joint_delta(bounds, i, pair[1].angles[i], pair[0].angles[i]);
            max_velocity = max_velocity.max(v.abs());
            if let Some(v0) = velocity[i] {
                let a = v - v0;
                max_acceleration = max_acceleration.max(a.abs());
                if let Some(a0) = acceleration[i] {
                    max_jerk = max_jerk.max((a - a0).abs());
                }
                acceleration[i] = Some(a);
            }
            velocity[i] = Some(v);
        }
    }
    let off_path = count(&[SampleStatus::OffPath]);
    TrackSummary {
        samples: samples.len() - off_path,
        reached: count(&[SampleStatus::Reached]),
        limited: count(&[SampleStatus::Limited]),
        unreachable: count(&[SampleStatus::Unreachable]),
        stalled: count(&[SampleStatus::Stalled, SampleStatus::IterationLimit]),
        off_path,
        flips: samples.iter().enumerate().filter(|(_, s)| is_flip(s.step, max_step)).map(|(k, _)| k).collect(),
        max_step: samples.iter().map(|s| s.step).fold(0.0, f64::max),
        max_error: samples.iter().filter(|s| s.status != SampleStatus::OffPath).map(|s| s.error).fold(0.0, f64::max),
        max_velocity,
        max_acceleration,
        max_jerk,
    }
}
