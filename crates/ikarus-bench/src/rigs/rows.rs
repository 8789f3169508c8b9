//! The rows of `ikarus bench --rigs`, how each is timed, and what is reported of it.

use std::time::Instant;

use ikarus::{LimitMode, Outcome, SolveOptions, Solver};
use ikarus_edge::stats::{median, nearest_rank};
use serde::Serialize;

use super::judge::{Judge, RigVerdict};
use super::sequential::Sequential;
use super::set::RigSet;

/// Untimed warm-up solves before each row's timed pass, over the first target sets.
pub const WARMUP: usize = 50;

/// Label of the sequential-limb baseline's row.
pub const SEQUENTIAL_LABEL: &str = "sequential";

/// Who solves a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The library's `Solver::solve_rig`: every effector together.
    Ikarus,
    /// Each limb as a chain, one after another.
    Sequential,
}

/// One row: a named solver configuration.
#[derive(Debug, Clone)]
pub struct RigConfig {
    /// The row's label.
    pub label: String,
    /// Who solves it.
    pub kind: Kind,
    /// The options of every solve (of every limb's, for the sequential baseline).
    pub options: SolveOptions,
}

/// Every ikarus row, in the order of the output: `default` (the library's defaults: lm, limits
/// locked, restarts), then lm with each enforcing limit mode and no restarts (so that the
/// iterations themselves are measured, as the chain rows do), then the sequential baseline
/// with the defaults for every limb.
pub fn configs() -> Vec<RigConfig> {
    let mut rows =
        vec![RigConfig { label: "default".to_owned(), kind: Kind::Ikarus, options: SolveOptions::default() }];
    let method = SolveOptions::default().method;
    for mode in LimitMode::ALL.into_iter().filter(|&m| m != LimitMode::Ignore) {
        rows.push(RigConfig {
            label: format!("{} {}", method.name(), mode.name()),
            kind: Kind::Ikarus,
            options: SolveOptions { limits: mode, restarts: None, ..SolveOptions::default() },
        });
    }
    rows.push(RigConfig {
        label: SEQUENTIAL_LABEL.to_owned(),
        kind: Kind::Sequential,
        options: SolveOptions::default(),
    });
    rows
}

/// The results of one row on one set.
#[derive(Debug, Clone, Serialize)]
pub struct RigRow {
    /// The set's name.
    pub set: &'static str,
    /// The row's label.
    pub solver: String,
    /// How the limits are enforced: the limit mode's name (KDL's NR_JL: `clamp`).
    pub limits: &'static str,
    /// Target sets solved.
    pub goals: usize,
    /// Solves judged reached.
    pub reached: usize,
    /// `reached` as a percentage of `goals`, truncated to a tenth.
    pub reached_percent: f64,
    /// Solves whose angles broke a limit.
    pub outside_limits: usize,
    /// Median time of one rig solve, µs.
    pub median_us: f64,
    /// 99th percentile (nearest rank) of the time of one rig solve, µs.
    pub p99_us: f64,
    /// Mean iterations per solve (the sequential baseline: all limbs' together); `None` when
    /// unknown.
    pub mean_iterations: Option<f64>,
    /// The largest effector error of any solve; `None` when infinite (not a pose, or an error).
    pub worst_error: Option<f64>,
    /// KDL's tree solver's median on the same set divided by this row's; `None` without
    /// `--kdl`.
    pub vs_kdl_tree: Option<f64>,
    /// Solves that returned an error (counted as not reached).
    pub solve_errors: usize,
    /// The first such error's message.
    pub solve_error: Option<String>,
}

/// Collects the solves of a row.
#[derive(Debug)]
pub struct RigTally {
    nanos: Vec<u64>,
    reached: usize,
    outside_limits: usize,
    iterations: Option<u64>,
    worst_error: f64,
    solve_errors: usize,
    first_solve_error: Option<String>,
}

impl RigTally {
    /// An empty tally for `goals` solves.
    pub fn new(goals: usize) -> Self {
        Self {
            nanos: Vec::with_capacity(goals),
            reached: 0,
            outside_limits: 0,
            iterations: Some(0),
            worst_error: 0.0,
            solve_errors: 0,
            first_solve_error: None,
        }
    }

    /// Adds a solve that took `nanos`, ran `iterations` (`None`: unknown) and was judged
    /// `verdict`.
    pub fn add(&mut self, nanos: u64, iterations: Option<u64>, verdict: RigVerdict) {
        self.nanos.push(nanos);
        self.reached += usize::from(verdict.reached);
        self.outside_limits += usize::from(!verdict.inside_limits);
        self.iterations = self.iterations.zip(iterations).map(|(a, b)| a + b);
        self.worst_error = self.worst_error.max(if verdict.error.is_nan() { f64::INFINITY } else { verdict.error });
    }

    /// Adds a solve that took `nanos` and returned an error.
    pub fn fail(&mut self, nanos: u64, message: String) {
        self.nanos.push(nanos);
        self.worst_error = f64::INFINITY;
        self.solve_errors += 1;
        self.first_solve_error.get_or_insert(message);
    }

    /// The row's results.
    pub fn finish(mut self, set: &RigSet, solver: String, limits: &'static str) -> RigRow {
        self.nanos.sort_unstable();
        let us: Vec<f64> = self.nanos.iter().map(|&n| n as f64 / 1000.0).collect();
        let goals = us.len();
        let (median_us, p99_us) = if us.is_empty() { (0.0, 0.0) } else { (median(&us), nearest_rank(&us, 0.99)) };
        RigRow {
            set: set.name(),
            solver,
            limits,
            goals,
            reached: self.reached,
            reached_percent: percent(self.reached, goals),
            outside_limits: self.outside_limits,
            median_us,
            p99_us,
            mean_iterations: self.iterations.filter(|_| goals > 0).map(|i| i as f64 / goals as f64),
            worst_error: Some(self.worst_error).filter(|e| e.is_finite()),
            vs_kdl_tree: None,
            solve_errors: self.solve_errors,
            solve_error: self.first_solve_error,
        }
    }
}

/// `reached` of `goals` as a percentage truncated to a tenth: 999 of 1000 must not read as
/// 100%.
pub fn percent(reached: usize, goals: usize) -> f64 {
    if goals == 0 { 0.0 } else { (1000.0 * reached as f64 / goals as f64).floor() / 10.0 }
}

/// Runs `config` on every target set of `set`: one solver and one outcome reused, every solve
/// from the set's start pose and timed alone, after an untimed warm-up over the first
/// [`WARMUP`] target sets. `tick` is called after each timed solve, outside the timing.
pub fn run_config(set: &RigSet, config: &RigConfig, mut tick: impl FnMut()) -> RigRow {
    let mut judge = Judge::default();
    let mut tally = RigTally::new(set.cases.len());
    let warmup = set.cases.len().min(WARMUP);
    match config.kind {
        Kind::Ikarus => {
            let mut solver = Solver::new(config.options.clone()).expect("the benchmark's options are valid");
            let mut out = Outcome::default();
            for case in &set.cases[..warmup] {
                // Only for the caches: a failure here is counted in the timed pass.
                let _ = solver.solve_rig_into(&set.skeleton, &set.start, &case.task, &mut out);
            }
            for case in &set.cases {
                let started = Instant::now();
                let result = solver.solve_rig_into(&set.skeleton, &set.start, &case.task, &mut out);
                let nanos = elapsed(started);
                match result {
                    Ok(()) => {
                        tally.add(nanos, Some(u64::from(out.iterations)), judge.judge(set, case, out.pose.angles()))
                    }
                    Err(e) => tally.fail(nanos, e.to_string()),
                }
                tick();
            }
        }
        Kind::Sequential => {
            let mut seq = Sequential::new(set, config.options.clone());
            for case in &set.cases[..warmup] {
                let _ = seq.solve(&set.start, case);
            }
            for case in &set.cases {
                let started = Instant::now();
                let result = seq.solve(&set.start, case);
                let nanos = elapsed(started);
                match result {
                    Ok((angles, iterations)) => tally.add(nanos, Some(iterations), judge.judge(set, case, angles)),
                    Err(e) => tally.fail(nanos, e.to_string()),
                }
                tick();
            }
        }
    }
    tally.finish(set, config.label.clone(), config.options.limits.name())
}

fn elapsed(started: Instant) -> u64 {
    u64::try_from(started.elapsed().as_nanos()).unwrap_or(u64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigs::set::{RigSetName, generate};

    #[test]
    fn rows_are_the_default_each_mode_and_the_baseline() {
        let labels: Vec<String> = configs().into_iter().map(|c| c.label).collect();
        assert_eq!(labels, ["default", "lm clamp", "lm lock", "lm nullspace", "lm weighted", "sequential"]);
        for c in configs() {
            assert!(c.options.validate().is_ok());
            assert_ne!(c.options.limits, LimitMode::Ignore, "{}: limits are always on", c.label);
        }
    }

    #[test]
    fn statistics() {
        let set = generate(RigSetName::Hand, 3, 1).unwrap();
        let mut t = RigTally::new(3);
        let ok = RigVerdict { reached: true, error: 1e-7, angle_error: 0.0, inside_limits: true };
        t.add(3000, Some(4), ok);
        t.add(1000, Some(2), RigVerdict { reached: false, error: 0.5, angle_error: 0.0, inside_limits: false });
        t.fail(2000, "boom".to_owned());
        let r = t.finish(&set, "x".into(), "lock");
        assert_eq!((r.goals, r.reached, r.outside_limits, r.median_us, r.p99_us), (3, 1, 1, 2.0, 3.0));
        assert_eq!((r.worst_error, r.solve_errors, r.solve_error.as_deref()), (None, 1, Some("boom")));
        assert_eq!(r.mean_iterations, Some(2.0));
        assert_eq!(percent(999, 1000), 99.9);
        assert_eq!(percent(1, 3), 33.3);
    }

    #[test]
    fn every_row_runs_and_is_judged() {
        let set = generate(RigSetName::PuppetPins, 4, 1).unwrap();
        for c in configs() {
            let mut ticks = 0;
            let r = run_config(&set, &c, || ticks += 1);
            assert_eq!((r.goals, ticks, r.solve_errors), (4, 4, 0), "{}", c.label);
            assert!(r.reached <= 4 && r.worst_error.is_some());
        }
    }
}
