//! What every batch of solves shares (`ikarus solve --batch`, for an arm's goals and a rig's
//! target sets): the thread pool, the progress bar, the timing of each solve, and the summary
//! (a line on stderr, and the same figures as JSON with `--summary-json`). An arm's goals go
//! in blocks to `Solver::solve_batch` ([`Batch::solve_blocks`]); a rig's target sets one by one
//! ([`Batch::solve_all`]).

use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::ops::Range;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use ikarus::Status;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;

use crate::error::Error;
use crate::output::{self, PendingFile};
use ikarus_edge::stats::{median, nearest_rank};

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
    /// Goals (an arm's) or target sets (a rig's) solved.
    pub goals: usize,
    /// How many ended `reached`.
    pub reached: usize,
    /// `reached` in percent of `goals`.
    pub reached_percent: f64,
    /// Median time of one solve, in µs. A rig's target sets are timed one by one; an arm's goals
    /// are solved in blocks of [`BLOCK_GOALS`] (`Solver::solve_batch`), so that a single goal's
    /// time is not observable: each block is timed, and its time divided by its goals is the
    /// figure of each of them. This is the median over the blocks of that figure.
    pub median_us: f64,
    /// The 99th percentile (nearest rank) of the same figures as `median_us`.
    pub p99_us: f64,
    /// Median time of one goal (an arm's) or target set (a rig's) solved alone, by itself, on one
    /// thread with the other threads idle, in µs: the latency one solve has, which the blocks'
    /// figures average away. Measured after the batch over [`Summary::goals_timed_alone`] goals
    /// evenly spaced through the file (a rig's batch on `--threads 1` is timed so already: its
    /// own times are these).
    pub goal_median_us: f64,
    /// The 99th percentile (nearest rank) of the same figures as `goal_median_us`.
    pub goal_p99_us: f64,
    /// How many goals were timed alone: all of them up to [`GOALS_TIMED_ALONE`] (a rig's batch
    /// on one thread: all of them).
    pub goals_timed_alone: usize,
    /// Seconds from the start of the first solve to the end of the last, on all threads
    /// together: the solving phase, without reading the file or writing stdout (for an arm, the
    /// rows of each block are formatted between its blocks, so that time is in it).
    pub wall_s: f64,
    /// `goals / wall_s`: the batch's throughput.
    pub solves_per_s: f64,
    /// Worker threads.
    pub threads: usize,
    /// The solver's method.
    pub method: &'static str,
}

/// What a batch's solving measured, for its [`Summary`].
pub struct Tally {
    pub goals: usize,
    pub reached: usize,
    /// Time per solve in µs: of each solve (a rig's), or of each block divided by its goals (an
    /// arm's).
    pub micros: Vec<f64>,
    pub wall_s: f64,
    /// Time of each goal solved alone on one thread, µs ([`time_alone`]).
    pub alone: Vec<f64>,
}

/// At most this many goals of a batch are timed alone ([`Summary::goal_median_us`]): 10,000
/// gives a p99 of 100 goals beyond it, and costs a tenth of a second at 10 µs a solve.
pub const GOALS_TIMED_ALONE: usize = 10_000;

/// Solves goal `i` of `n` with `solve`, each timed alone on this thread: every goal, or
/// [`GOALS_TIMED_ALONE`] of them evenly spaced; their times in µs.
pub fn time_alone<E>(n: usize, mut solve: impl FnMut(usize) -> Result<(), E>) -> Result<Vec<f64>, E> {
    let count = n.min(GOALS_TIMED_ALONE);
    let mut micros = Vec::with_capacity(count);
    for k in 0..count {
        let i = k * n / count;
        let started = Instant::now();
        solve(i)?;
        micros.push(started.elapsed().as_secs_f64() * 1e6);
    }
    Ok(micros)
}

/// An arm's goals are solved in blocks of this many, each by one call of `Solver::solve_batch`
/// (which will solve several goals at a time in SIMD lanes, so wants them in blocks). Measured
/// on 100,000 goals of the seed arm, one thread, 7 interleaved runs on a busy machine (load 6 on
/// 2 cores), median solves/s: blocks of 1 goal 0.35 M, of 16 0.41 M, 64 0.42 M, 256 0.39 M,
/// 1024 0.44 M: past one goal, the same within the noise (the library's batch is still a loop).
/// 64 is small enough that the median over the blocks still means something for a batch of a
/// few thousand goals, and a multiple of any SIMD width to come.
pub const BLOCK_GOALS: usize = 64;

/// Goals per task of [`Batch::solve_blocks`] at most: 16 blocks (1,024 goals, about 1.3 ms of
/// the seed arm's solving), so 100,000 goals make over 100 tasks, for the threads to share
/// evenly, each formatting its rows into one buffer of about 100 KB.
pub const TASK_GOALS: usize = 16 * BLOCK_GOALS;

/// What one task of [`Batch::solve_blocks`] made: its rows' bytes (until they are written)
/// and its measures.
struct Run {
    bytes: Vec<u8>,
    reached: usize,
    micros: Vec<f64>,
    first: Instant,
    last: Instant,
}

/// Where [`Batch::solve_blocks`] writes its rows: the `header` line first, then the rows, to
/// `out`.
pub struct Rows<'a> {
    /// Written first, before any row.
    pub header: &'a [u8],
    /// The rows' destination, flushed at the end.
    pub out: &'a mut dyn Write,
}

/// A batch being run: its threads, and the summary file prepared before any solve (so that an
/// unwritable `--summary-json` fails before the work is done).
pub struct Batch {
    pub threads: usize,
    pool: rayon::ThreadPool,
    summary: Option<PendingFile>,
}

impl Batch {
    /// `threads` workers (all cores by default) and the `--summary-json` file, if any.
    pub fn new(threads: Option<usize>, summary_json: Option<&Path>) -> Result<Self, Error> {
        let summary = summary_json.map(|p| PendingFile::create(p, "--summary-json")).transpose()?;
        Ok(Self { summary, ..Self::threads(threads)? })
    }

    /// `threads` workers (all cores by default), to read the goals on; the summary file comes
    /// later ([`Batch::summary_json`]), so that bad goals are reported before it.
    pub fn threads(threads: Option<usize>) -> Result<Self, Error> {
        let threads = threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Error::runtime(format!("cannot start {threads} threads: {e}")))?;
        Ok(Self { threads, pool, summary: None })
    }

    /// Prepares the `--summary-json` file, if any.
    pub fn summary_json(&mut self, path: Option<&Path>) -> Result<(), Error> {
        self.summary = path.map(|p| PendingFile::create(p, "--summary-json")).transpose()?;
        Ok(())
    }

    /// Runs `work` on the batch's threads (its parallel iterators use them).
    pub fn install<T: Send>(&self, work: impl FnOnce() -> T + Send) -> T {
        self.pool.install(work)
    }

    /// Solves every item in parallel, each with a per-thread state from `init` (a solver and
    /// its buffers), timing each solve; a progress bar on stderr for a large batch. The first
    /// error ends the batch as bad input.
    pub fn solve_all<I, S, R, E>(
        &self,
        items: &[I],
        init: impl Fn() -> S + Sync + Send,
        solve: impl Fn(&mut S, &I) -> Result<(Status, R), E> + Sync + Send,
    ) -> Result<(Vec<Solved<R>>, Tally), Error>
    where
        I: Sync,
        R: Send,
        E: std::fmt::Display + Send,
    {
        let progress = progress_bar(items.len());
        let started = Instant::now();
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
            .map_err(|e| Error::input(e.to_string()))?;
        let wall_s = started.elapsed().as_secs_f64();
        if let Some(bar) = progress {
            bar.finish_and_clear();
        }
        let tally = Tally {
            goals: rows.len(),
            reached: rows.iter().filter(|r| r.status == Status::Reached).count(),
            micros: rows.iter().map(|r| r.micros).collect(),
            wall_s,
            alone: Vec::new(),
        };
        Ok((rows, tally))
    }

    /// Solves `tasks` runs of goals (task `t` has `size(t)` goals, at most [`TASK_GOALS`]) in
    /// parallel, each in blocks of [`BLOCK_GOALS`], each thread with its state from `init` (a
    /// solver and its outcomes): `solve` solves a block (task `t`, a range of its goals) and
    /// says how many it reached, then `format` appends its rows to the task's buffer. Each
    /// block is timed.
    ///
    /// The threads take the tasks in order (the next one not taken), so they finish nearly in
    /// order, and this thread writes each task's rows to `out` as soon as the rows before them
    /// are written: writing overlaps solving instead of following it (writing 100,000 rows, 10
    /// MB, to a file took 10 to 20 ms, a tenth of a 2-thread batch). `out` gets `header` first (both in [`Rows`])
    /// and is flushed at the end. A reader that goes away is not an error (the batch still
    /// finishes, for its summary). The first error ends the batch as bad input; the caller
    /// checks what can fail (the options) before, so that no row is written when it does.
    pub fn solve_blocks<S, E>(
        &self,
        tasks: usize,
        size: impl Fn(usize) -> usize + Sync + Send,
        init: impl Fn() -> S + Sync + Send,
        solve: impl Fn(&mut S, usize, Range<usize>) -> Result<usize, E> + Sync + Send,
        format: impl Fn(&mut S, usize, Range<usize>, &mut Vec<u8>) + Sync + Send,
        rows: Rows<'_>,
    ) -> Result<Tally, Error>
    where
        E: std::fmt::Display + Send,
    {
        let Rows { header, out } = rows;
        let goals: usize = (0..tasks).map(&size).sum();
        let progress = progress_bar(goals);
        let run = |state: &mut S, t: usize| -> Result<Run, E> {
            let n = size(t);
            let mut run = Run {
                bytes: Vec::with_capacity(n * 128),
                reached: 0,
                micros: Vec::with_capacity(n.div_ceil(BLOCK_GOALS)),
                first: Instant::now(),
                last: Instant::now(),
            };
            for start in (0..n).step_by(BLOCK_GOALS) {
                let block = start..n.min(start + BLOCK_GOALS);
                let started = Instant::now();
                run.reached += solve(state, t, block.clone())?;
                run.last = Instant::now();
                if start == 0 {
                    run.first = started;
                }
                run.micros.push((run.last - started).as_secs_f64() * 1e6 / block.len() as f64);
                format(state, t, block.clone(), &mut run.bytes);
                if let Some(bar) = &progress {
                    bar.inc(block.len() as u64);
                }
            }
            Ok(run)
        };
        let next = AtomicUsize::new(0);
        let (done, finished) = mpsc::channel::<(usize, Result<Run, E>)>();
        let mut written = out.write_all(header);
        let mut runs: Vec<Run> = Vec::with_capacity(tasks);
        let mut error = None;
        std::thread::scope(|scope| {
            let (next, run, init) = (&next, &run, &init);
            scope.spawn(move || {
                self.pool.broadcast(|_| {
                    let mut state = init();
                    loop {
                        let t = next.fetch_add(1, Ordering::Relaxed);
                        if t >= tasks {
                            break;
                        }
                        let result = run(&mut state, t);
                        let failed = result.is_err();
                        if done.send((t, result)).is_err() || failed {
                            // Nothing more is wanted: the others stop at their next task.
                            next.store(tasks, Ordering::Relaxed);
                            break;
                        }
                    }
                });
                drop(done);
            });
            // Rows are written in order: a task that finished early waits for those before it.
            let mut waiting = BTreeMap::new();
            for (t, result) in finished {
                match result {
                    Ok(run) => {
                        waiting.insert(t, run);
                    }
                    Err(e) => {
                        error.get_or_insert(e);
                        continue;
                    }
                }
                while let Some(mut run) = waiting.remove(&runs.len()) {
                    if written.is_ok() && error.is_none() {
                        written = out.write_all(&run.bytes);
                    }
                    run.bytes = Vec::new();
                    runs.push(run);
                }
            }
        });
        if let Some(e) = error {
            return Err(Error::input(e.to_string()));
        }
        output::written(written.and_then(|()| out.flush()))?;
        if let Some(bar) = progress {
            bar.finish_and_clear();
        }
        let first = runs.iter().map(|r| r.first).min();
        let last = runs.iter().map(|r| r.last).max();
        Ok(Tally {
            goals,
            reached: runs.iter().map(|r| r.reached).sum(),
            micros: runs.iter().flat_map(|r| r.micros.iter().copied()).collect(),
            wall_s: match (first, last) {
                (Some(first), Some(last)) => (last - first).as_secs_f64(),
                _ => 0.0,
            },
            alone: Vec::new(),
        })
    }

    /// Reports the summary of a batch (solved with `method`): a line on stderr, and the JSON
    /// file if one was asked for.
    pub fn finish(self, tally: Tally, method: &'static str) -> Result<(), Error> {
        let summary = summarise(tally, self.threads, method);
        // Truncated, not rounded: 9999 of 10000 must not read as 100%.
        let percent = (summary.reached_percent * 100.0).floor() / 100.0;
        eprintln!(
            "batch: {} goals, {} reached ({percent:.2}%), median {:.2} µs, p99 {:.2} µs per solve, {} threads, \
             {:.2} ms wall, {:.0} solves/s; each alone: median {:.2} µs, p99 {:.2} µs ({} goals, 1 thread)",
            summary.goals,
            summary.reached,
            summary.median_us,
            summary.p99_us,
            summary.threads,
            summary.wall_s * 1e3,
            summary.solves_per_s,
            summary.goal_median_us,
            summary.goal_p99_us,
            summary.goals_timed_alone
        );
        if let Some(file) = self.summary {
            let mut bytes = serde_json::to_vec_pretty(&summary).expect("summary serialises");
            bytes.push(b'\n');
            file.commit(&bytes)?;
        }
        Ok(())
    }
}

/// A progress bar on stderr for a batch of `goals`, if it is large and stderr is a terminal.
fn progress_bar(goals: usize) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() || goals < PROGRESS_MIN_GOALS {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(goals as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{spinner} solving {pos}/{len} goals [{bar:30}] {eta}")
            .expect("static template")
            .progress_chars("=> "),
    );
    Some(bar)
}

fn summarise(tally: Tally, threads: usize, method: &'static str) -> Summary {
    let Tally { goals, reached, mut micros, wall_s, mut alone } = tally;
    micros.sort_by(f64::total_cmp);
    alone.sort_by(f64::total_cmp);
    // A wall clock too coarse to see the batch at all still gives a finite throughput.
    let wall_s = wall_s.max(1e-9);
    Summary {
        goals,
        reached,
        reached_percent: 100.0 * reached as f64 / goals as f64,
        median_us: median(&micros),
        p99_us: nearest_rank(&micros, 0.99),
        goal_median_us: median(&alone),
        goal_p99_us: nearest_rank(&alone, 0.99),
        goals_timed_alone: alone.len(),
        wall_s,
        solves_per_s: goals as f64 / wall_s,
        threads,
        method,
    }
}
