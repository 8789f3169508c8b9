//! Running the solvers of `ikarus bench --paths` on a path set, and what is measured of each
//! path: every solver's poses are judged the same way, by forward kinematics.

use std::time::Instant;

use ikarus::kinematics::end_effector;
use ikarus::track::{self, Follower, SampleStatus, TrackOptions};
use ikarus::{LimitMode, Outcome, SolveOptions, Solver};

use super::set::{BenchPath, PathSet};
use crate::judge::within;

/// Rounding slack on the tolerance when judging, as in the goal benchmark.
const ROUNDING_SLACK: f64 = 1e-12;

/// The rows of the path benchmark, in the order of the output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathSolver {
    /// `ikarus::track::follow`, one [`Follower`] step per sample.
    Follow,
    /// `ikarus::track::plan` over the whole path.
    Plan,
    /// Every sample solved from the start pose with the library's defaults.
    Scratch,
    /// KDL's LMA, each sample warm-started from the previous sample's answer.
    KdlLma,
}

impl PathSolver {
    /// The row's label.
    pub fn label(self) -> &'static str {
        match self {
            PathSolver::Follow => "follow",
            PathSolver::Plan => "plan",
            PathSolver::Scratch => "scratch",
            PathSolver::KdlLma => "kdl lma warm",
        }
    }
}

/// One solver's answer on one path: a pose per sample, and the time.
#[derive(Debug, Clone, Default)]
pub struct Answer {
    /// One pose per sample, radians.
    pub poses: Vec<Vec<f64>>,
    /// Samples `follow` marked `limited`.
    pub limited: usize,
    /// Time per sample, µs: one per sample for the solvers timed sample by sample, one for the
    /// whole path (its time divided by its samples) for `plan`.
    pub micros: Vec<f64>,
}

/// What is measured of one solver on one path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathMetrics {
    /// Samples reached (within the tolerance, and inside the limits when enforced).
    pub reached: usize,
    /// Samples `follow` marked `limited`.
    pub limited: usize,
    /// Steps over the flip bound.
    pub flips: usize,
    /// The largest joint step, radians.
    pub max_step: f64,
    /// The largest joint acceleration and jerk, radians per sample² and sample³.
    pub max_acceleration: f64,
    pub max_jerk: f64,
}

/// The track options of a set: the library's defaults, with the limits ignored on free sets.
pub fn track_options(set: &PathSet) -> TrackOptions {
    TrackOptions { solve: solve_options(set), ..TrackOptions::default() }
}

/// The solver options of a set: the defaults, with the limits ignored on free sets.
pub fn solve_options(set: &PathSet) -> SolveOptions {
    if set.limited {
        SolveOptions::default()
    } else {
        SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() }
    }
}

/// Runs the solvers on the paths of a set (where `kdl` has answers, it is added), path by path
/// with the solvers interleaved, so that a slow stretch of the machine hits every row alike.
/// One untimed pass over the first path comes first. Returns one answer per solver and path.
pub fn run_set(set: &PathSet, mut tick: impl FnMut()) -> [Vec<Answer>; 3] {
    let options = track_options(set);
    let mut scratch = Solver::new(solve_options(set)).expect("the defaults are valid");
    let mut out = Outcome::default();
    if let Some(first) = set.paths.first() {
        let _ = follow(set, first, &options);
        let _ = plan(set, first, &options);
        let _ = from_scratch(set, first, &mut scratch, &mut out);
    }
    let mut answers: [Vec<Answer>; 3] = Default::default();
    for p in &set.paths {
        answers[0].push(follow(set, p, &options));
        answers[1].push(plan(set, p, &options));
        answers[2].push(from_scratch(set, p, &mut scratch, &mut out));
        tick();
    }
    answers
}

fn micros(started: Instant) -> f64 {
    started.elapsed().as_nanos() as f64 / 1000.0
}

/// `follow`: the first sample placed, each later one a step, each timed alone.
fn follow(set: &PathSet, p: &BenchPath, options: &TrackOptions) -> Answer {
    let mut follower = Follower::new(&set.chain, &set.start, options).expect("valid options and start");
    let mut answer = Answer { poses: Vec::with_capacity(p.path.len()), limited: 0, micros: Vec::new() };
    for (k, goal) in p.path.goals().iter().enumerate() {
        let started = Instant::now();
        let step = if k == 0 { follower.place(goal) } else { follower.step(goal) };
        answer.micros.push(micros(started));
        answer.limited += usize::from(step.status == SampleStatus::Limited);
        answer.poses.push(follower.pose().to_vec());
    }
    answer
}

/// `plan`: the whole path, timed as one.
fn plan(set: &PathSet, p: &BenchPath, options: &TrackOptions) -> Answer {
    let started = Instant::now();
    let track = track::plan(&set.chain, &set.start, &p.path, options).expect("valid options and start");
    let per_sample = micros(started) / p.path.len() as f64;
    // The path's samples: the poses plan inserts off the path between two of them are not judged.
    Answer { poses: track.on_path().map(|s| s.angles.clone()).collect(), limited: 0, micros: vec![per_sample] }
}

/// From scratch: every sample solved from the start pose, each timed alone.
fn from_scratch(set: &PathSet, p: &BenchPath, solver: &mut Solver, out: &mut Outcome) -> Answer {
    let mut answer = Answer { poses: Vec::with_capacity(p.path.len()), limited: 0, micros: Vec::new() };
    for goal in p.path.goals() {
        let started = Instant::now();
        let ok = solver.solve_into(&set.chain, &set.start, goal, out).is_ok();
        answer.micros.push(micros(started));
        answer.poses.push(if ok { out.pose.angles().to_vec() } else { set.start.clone() });
    }
    answer
}

/// Judges the poses of one answer on one path, and measures its steps and rates.
///
/// A sample is reached if the tip is within the solver tolerance (plus 1e-12 for rounding) and,
/// when the limits are enforced, every limited joint is inside its range modulo 2π. Rates are
/// finite differences per sample of the joint angles (a step as [`PathSet::delta`] measures
/// it), maxima over every joint and sample where defined.
pub fn measure(set: &PathSet, p: &BenchPath, answer: &Answer, max_step: f64) -> PathMetrics {
    let tolerance = SolveOptions::default().tolerance + ROUNDING_SLACK;
    let n = set.chain.len();
    let reached = p
        .path
        .goals()
        .iter()
        .zip(&answer.poses)
        .filter(|(g, q)| {
            let tip = end_effector(&set.chain, q).position;
            let inside = !set.limited
                || q.iter().zip(set.chain.limits()).all(|(&a, l)| l.is_none_or(|l| within(a, l.min(), l.max())));
            (tip - g.target()).norm() <= tolerance && inside
        })
        .count();
    let mut m =
        PathMetrics { reached, limited: answer.limited, flips: 0, max_step: 0.0, max_acceleration: 0.0, max_jerk: 0.0 };
    let mut velocity: Vec<Option<f64>> = vec![None; n];
    let mut acceleration: Vec<Option<f64>> = vec![None; n];
    for pair in answer.poses.windows(2) {
        let step = set.step(&pair[1], &pair[0]);
        m.max_step = m.max_step.max(step);
        m.flips += usize::from(track::is_flip(step, max_step));
        for i in 0..n {
            let v = set.delta(i, pair[1][i], pair[0][i]);
            if let Some(v0) = velocity[i] {
                let a = v - v0;
                m.max_acceleration = m.max_acceleration.max(a.abs());
                if let Some(a0) = acceleration[i] {
                    m.max_jerk = m.max_jerk.max((a - a0).abs());
                }
                acceleration[i] = Some(a);
            }
            velocity[i] = Some(v);
        }
    }
    m
}
