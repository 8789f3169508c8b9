//! The batched measurement beside each `default` row: the set's goals solved with
//! [`Solver::solve_batch`] (the row's options, from the set's start pose) on one thread and on
//! two (the goals split in two halves, one per thread), timed as throughput; every batched
//! outcome judged again and compared with the per-solve row.

use std::time::Instant;

use ikarus::{Outcome, SolveOptions, Solver};
use ikarus_edge::stats::median;
use serde::Serialize;

use super::judge::judge;
use super::sets::GoalSet;

/// Timed samples per thread count; the reported time is their median.
pub const SAMPLES: usize = 5;

/// The least wall time of all the samples of one thread count together, seconds.
pub const MIN_SECONDS: f64 = 0.2;

/// The batched measurement of a `default` row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Batched {
    /// Goals of the batch.
    pub goals: usize,
    /// Batched outcomes judged reached (by the same judge as every row).
    pub reached: usize,
    /// Goals whose batched outcome was judged otherwise than the per-solve row's, or whose
    /// two-thread outcome differs from the one-thread outcome (status or angles, bit for bit);
    /// 0 when the batch returns what `solve_into` returns.
    pub mismatches: usize,
    /// Median wall time of one batched pass on one thread, per solve, µs.
    pub us_1thr: f64,
    /// Solves per second on one thread.
    pub solves_per_s_1thr: f64,
    /// Median wall time of one pass with the goals split over two threads, per solve, µs.
    pub us_2thr: f64,
    /// Solves per second on two threads.
    pub solves_per_s_2thr: f64,
    /// Two threads' throughput over one thread's.
    pub speedup_2thr: f64,
}

/// Runs the batched measurement of a `default` row's `options` on `set`; `reached_each` is the
/// per-solve row's verdict on each goal. A batch that returns an error gives its message.
pub fn run(set: &GoalSet, options: &SolveOptions, reached_each: &[bool]) -> Result<Batched, String> {
    let new_solver = || Solver::new(options.clone()).expect("the benchmark's options are valid");
    let (chain, start, goals) = (&set.chain, set.start.as_slice(), set.targets.as_slice());

    // One thread: also the untimed first pass, whose error (if any) is reported.
    let mut solver = new_solver();
    let mut one: Vec<Outcome> = Vec::new();
    solver.solve_batch(chain, start, goals, &mut one).map_err(|e| e.to_string())?;
    let per_pass_1 = time(|reps| {
        for _ in 0..reps {
            // The first pass succeeded; the same goals give the same answer.
            let _ = solver.solve_batch(chain, start, goals, &mut one);
        }
    });

    // Two threads, each with its own solver and outcomes (boxed apart: no false sharing), on
    // its half of the goals.
    let (a, b) = goals.split_at(goals.len().div_ceil(2));
    let mut halves = [Box::new((new_solver(), Vec::new(), a)), Box::new((new_solver(), Vec::new(), b))];
    let per_pass_2 = time(|reps| {
        std::thread::scope(|s| {
            for half in &mut halves {
                let (solver, out, goals) = &mut **half;
                s.spawn(move || {
                    for _ in 0..reps {
                        let _ = solver.solve_batch(chain, start, goals, &mut *out);
                    }
                });
            }
        });
    });
    let two: Vec<&Outcome> = halves.iter().flat_map(|half| &half.1).collect();

    let mut reached = 0;
    let mut mismatches = 0;
    for (i, o) in one.iter().enumerate() {
        let verdict = judge(set, &set.goals[i], o.pose.angles());
        reached += usize::from(verdict.reached);
        let same_verdict = reached_each.get(i) == Some(&verdict.reached);
        if !same_verdict || two.get(i).is_none_or(|t| !same_outcome(o, t)) {
            mismatches += 1;
        }
    }
    let n = goals.len().max(1) as f64;
    let (us_1thr, us_2thr) = (per_pass_1 * 1e6 / n, per_pass_2 * 1e6 / n);
    Ok(Batched {
        goals: goals.len(),
        reached,
        mismatches,
        us_1thr,
        solves_per_s_1thr: 1e6 / us_1thr,
        us_2thr,
        solves_per_s_2thr: 1e6 / us_2thr,
        speedup_2thr: us_1thr / us_2thr,
    })
}

/// Whether two outcomes have the same status and the same angles, bit for bit.
fn same_outcome(a: &Outcome, b: &Outcome) -> bool {
    a.status == b.status
        && a.iterations == b.iterations
        && a.pose.angles().len() == b.pose.angles().len()
        && a.pose.angles().iter().zip(b.pose.angles()).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// The median wall time of one pass, seconds: `sample(reps)` runs `reps` passes; `reps` is
/// chosen so that one sample takes about `MIN_SECONDS / SAMPLES`, then samples are timed until
/// there are at least [`SAMPLES`] of them and they took at least [`MIN_SECONDS`] together.
fn time(mut sample: impl FnMut(usize)) -> f64 {
    let target = MIN_SECONDS / SAMPLES as f64;
    // Calibration (also a warm-up): double the passes until a sample takes a tenth of the
    // target, then scale up.
    let mut reps = 1usize;
    let reps = loop {
        let t = Instant::now();
        sample(reps);
        let s = t.elapsed().as_secs_f64();
        if s >= target / 10.0 {
            break ((reps as f64 * target / s).ceil() as usize).max(1);
        }
        reps *= 2;
    };
    let mut per_pass = Vec::new();
    let mut total = 0.0;
    while per_pass.len() < SAMPLES || total < MIN_SECONDS {
        let t = Instant::now();
        sample(reps);
        let s = t.elapsed().as_secs_f64();
        total += s;
        per_pass.push(s / reps as f64);
    }
    per_pass.sort_by(f64::total_cmp);
    median(&per_pass)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::{configs, run_config};
    use crate::sets::{ArmName, SetName, generate};

    #[test]
    fn the_batch_agrees_with_the_per_solve_row() {
        let set = generate("seed", &ArmName::Seed.load().unwrap().chain, SetName::FreeOriented, 9, 1);
        let config = configs().into_iter().find(|c| c.method == "default" && c.applies_to(&set)).unwrap();
        let row = run_config(&set, &config, || {});
        let b = run(&set, &config.options, &row.reached_each).unwrap();
        assert_eq!((b.goals, b.reached, b.mismatches), (9, row.reached, 0));
        assert!(b.us_1thr > 0.0 && b.us_2thr > 0.0 && b.speedup_2thr > 0.0);
        assert!((b.solves_per_s_1thr * b.us_1thr - 1e6).abs() < 1e-3);
        // A per-solve verdict that differs is counted.
        let mut other = row.reached_each.clone();
        other[0] = !other[0];
        assert_eq!(run(&set, &config.options, &other).unwrap().mismatches, 1);
    }
}
