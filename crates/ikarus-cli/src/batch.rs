//! What every batch of solves shares (`ikarus solve --batch`, for an arm's goals and a rig's
//! target sets): the thread pool, the progress bar, the timing of each solve, and the summary
//! (a line on stderr, and the same figures as JSON with `--summary-json`).

use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

use ikarus::Status;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;

use crate::error::CliError;
use crate::output::PendingFile;
use crate::stats::{median, nearest_rank};

/// Batches at least this large show a progress bar (when stderr is a terminal).
const PROGRESS_MIN_GOALS: usize = 20_000;

/// One solve of a batch: how it ended, how long it took, and what the caller keeps of it.
pub struct Solved<R> {
    pub status: Status,
    pub micros: f64,
    pub row: R,
}

/// The batch summary, also written by `--summary-json`.
#[derive(Debug, Serialize)]
pub struct Summary {
    pub goals: usize,
    pub reached: usize,
    pub reached_percent: f64,
    pub median_us: f64,
    pub p99_us: f64,
    pub threads: usize,
    pub method: &'static str,
}

/// A batch being run: its threads, and the summary file prepared up front (so that an
/// unwritable `--summary-json` fails before any work is done).
pub struct Batch {
    pub threads: usize,
    pool: rayon::ThreadPool,
    summary: Option<PendingFile>,
}

impl Batch {
    /// `threads` workers (all cores by default) and the `--summary-json` file, if any.
    pub fn new(threads: Option<usize>, summary_json: Option<&Path>) -> Result<Self, CliError> {
        let summary = summary_json.map(|p| PendingFile::create(p, "--summary-json")).transpose()?;
        let threads = threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| CliError::runtime(format!("cannot start {threads} threads: {e}")))?;
        Ok(Self { threads, pool, summary })
    }

    /// Solves every item in parallel, each with a per-thread state from `init` (a solver and
    /// its buffers), timing each solve; a progress bar on stderr for a large batch. The first
    /// error ends the batch as bad input.
    pub fn solve_all<I, S, R, E>(
        &self,
        items: &[I],
        init: impl Fn() -> S + Sync + Send,
        solve: impl Fn(&mut S, &I) -> Result<(Status, R), E> + Sync + Send,
    ) -> Result<Vec<Solved<R>>, CliError>
    where
        I: Sync,
        R: Send,
        E: std::fmt::Display + Send,
    {
        let progress = if std::io::stderr().is_terminal() && items.len() >= PROGRESS_MIN_GOALS {
            let bar = ProgressBar::with_draw_target(Some(items.len() as u64), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{spinner} solving {pos}/{len} goals [{bar:30}] {eta}")
                    .expect("static template")
                    .progress_chars("=> "),
            );
            Some(bar)
        } else {
            None
        };
        let rows = self
            .pool
            .install(|| {
                items
                    .par_iter()
                    .map_init(&init, |state, item| {
                        let started = Instant::now();
                        let result = solve(state, item);
                        let micros = started.elapsed().as_secs_f64() * 1e6;
                        if let Some(bar) = &progress {
                            bar.inc(1);
                        }
                        result.map(|(status, row)| Solved { status, micros, row })
                    })
                    .collect::<Result<Vec<_>, E>>()
            })
            .map_err(|e| CliError::input(e.to_string()))?;
        if let Some(bar) = progress {
            bar.finish_and_clear();
        }
        Ok(rows)
    }

    /// Reports the summary of `rows` (solved with `method`): a line on stderr, and the JSON
    /// file if one was asked for.
    pub fn finish<R>(self, rows: &[Solved<R>], method: &'static str) -> Result<(), CliError> {
        let summary = summarise(rows, self.threads, method);
        // Truncated, not rounded: 9999 of 10000 must not read as 100%.
        let percent = (summary.reached_percent * 100.0).floor() / 100.0;
        eprintln!(
            "batch: {} goals, {} reached ({percent:.2}%), median {:.2} µs, p99 {:.2} µs per solve, {} threads",
            summary.goals, summary.reached, summary.median_us, summary.p99_us, summary.threads
        );
        if let Some(file) = self.summary {
            let mut bytes = serde_json::to_vec_pretty(&summary).expect("summary serialises");
            bytes.push(b'\n');
            file.commit(&bytes)?;
        }
        Ok(())
    }
}

fn summarise<R>(rows: &[Solved<R>], threads: usize, method: &'static str) -> Summary {
    let mut micros: Vec<f64> = rows.iter().map(|r| r.micros).collect();
    micros.sort_by(f64::total_cmp);
    let reached = rows.iter().filter(|r| r.status == Status::Reached).count();
    Summary {
        goals: rows.len(),
        reached,
        reached_percent: 100.0 * reached as f64 / rows.len() as f64,
        median_us: median(&micros),
        p99_us: nearest_rank(&micros, 0.99),
        threads,
        method,
    }
}
