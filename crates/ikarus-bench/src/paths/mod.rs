//! `ikarus bench --paths`: `follow`, `plan`, solving every sample from scratch, and (with
//! `--kdl`) KDL's LMA warm-started from the previous sample, on seeded path sets for the
//! shipped arms with the limits on and off.
//!
//! - [`set`]: the paths and their generator;
//! - [`measure`]: running the solvers and judging their poses;
//! - [`rows`]: the rows and the targets;
//! - [`kdl`]: path files and `kdl_bench`'s answers;
//! - [`table`]: text, Markdown and JSON output.

mod kdl;
mod measure;
mod rows;
pub(super) mod set;
mod table;

use ikarus::track::TrackOptions;
use ikarus_edge::error::Error;
use ikarus_edge::input::io_reason;
use indicatif::ProgressBar;

use super::{BenchArgs, Sink};
use measure::{Answer, PathSolver};
use rows::PathRow;
use set::{Kind, PathSet};
use table::PathsHeader;

/// Runs `ikarus bench --paths`.
pub fn run(args: &BenchArgs, sink: &dyn Sink) -> Result<(), Error> {
    if let Some(path) = &args.kdl {
        super::kdl::check(path)?;
    }
    let arms = super::unique(&args.arms);
    let (count, samples) = (args.path_count as usize, args.samples as usize);
    let mut sets = Vec::new();
    for &arm in &arms {
        let chain = arm.load()?.chain;
        for limited in [false, true] {
            sets.push(set::generate(arm.name(), &chain, limited, count, samples, args.seed));
        }
    }
    let comment = format!(
        "written by ikarus {} bench --paths --seed {} --path-count {count} --samples {samples}",
        env!("CARGO_PKG_VERSION"),
        args.seed
    );
    let progress = super::progress_bar((sets.len() * count) as u64);
    // KDL first: a broken --kdl is reported in seconds, not after the whole benchmark.
    let mut kdl_version = None;
    let mut kdl_answers: Vec<Vec<Answer>> = Vec::new();
    if let Some(path) = &args.kdl {
        let dir = tempfile::tempdir().map_err(|e| {
            Error::runtime(format!("--kdl {}: cannot make a temporary directory: {}", path.display(), io_reason(&e)))
        })?;
        for s in &sets {
            if let Some(bar) = &progress {
                bar.set_message(format!("kdl {}", s.name()));
            }
            let (version, answers) = kdl::run(path, s, dir.path(), &comment)?;
            kdl_version.get_or_insert(version);
            kdl_answers.push(answers);
        }
    }
    let rows = measure_all(&sets, &mut kdl_answers, progress.as_ref());
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    let max_step_deg = TrackOptions::default().max_step.to_degrees();
    let shown: Vec<PathRow> = rows.iter().filter(|r| args.by_kind || r.kind == "all").cloned().collect();
    let targets = rows::targets(&rows, max_step_deg);
    let header = header(args, &arms, &sets, kdl_version, max_step_deg);
    sink.stdout(&mut |w| {
        if args.json {
            table::json(w, &header, &rows, &targets)
        } else if args.markdown {
            table::markdown(w, &header, &shown, &targets)
        } else {
            table::text(w, &header, &shown, &targets)
        }
    })
}

/// Runs every set and returns its rows: per set, each solver's `all` row, then each solver's
/// row per kind.
fn measure_all(sets: &[PathSet], kdl_answers: &mut [Vec<Answer>], progress: Option<&ProgressBar>) -> Vec<PathRow> {
    let max_step = TrackOptions::default().max_step;
    let mut rows = Vec::new();
    for (k, s) in sets.iter().enumerate() {
        if let Some(bar) = progress {
            bar.set_message(s.name());
        }
        let [follow, plan, scratch] = measure::run_set(s, || {
            if let Some(bar) = progress {
                bar.inc(1);
            }
        });
        let mut solvers = vec![(PathSolver::Follow, follow), (PathSolver::Plan, plan), (PathSolver::Scratch, scratch)];
        if let Some(kdl) = kdl_answers.get_mut(k) {
            solvers.push((PathSolver::KdlLma, std::mem::take(kdl)));
        }
        let judged: Vec<_> = solvers
            .iter()
            .map(|(solver, answers)| {
                let metrics: Vec<_> =
                    s.paths.iter().zip(answers).map(|(p, a)| measure::measure(s, p, a, max_step)).collect();
                (*solver, answers, metrics)
            })
            .collect();
        for kind in std::iter::once(None).chain(Kind::ALL.map(Some)) {
            for (solver, answers, metrics) in &judged {
                rows.extend(rows::row(s, kind, *solver, answers, metrics));
            }
        }
    }
    rows
}

fn header(
    args: &BenchArgs,
    arms: &[super::sets::ArmName],
    sets: &[PathSet],
    kdl_version: Option<String>,
    max_step_deg: f64,
) -> PathsHeader {
    let paths = || sets.iter().flat_map(|s| &s.paths);
    PathsHeader {
        command: super::command_line(),
        ikarus_version: env!("CARGO_PKG_VERSION"),
        kdl_version,
        seed: args.seed,
        paths_per_set: args.path_count as usize,
        samples: args.samples as usize,
        arms: arms.iter().map(|a| a.name()).collect(),
        paths: paths().count(),
        fk_paths: paths().filter(|p| p.kind.fk()).count(),
        beyond_paths: paths().filter(|p| p.kind == Kind::Beyond).count(),
        max_step_deg,
        generator_max_step_deg: set::GEN_MAX_STEP_DEG,
        threads: 1,
        cpus: std::thread::available_parallelism().map_or(1, usize::from),
        os: std::env::consts::OS,
        arch: std::env::consts::ARCH,
        debug_build: cfg!(debug_assertions),
    }
}
