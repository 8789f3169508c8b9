//! `ikarus bench --rigs`: whole-rig solves on seeded, jointly reachable target sets for the
//! shipped puppet and hand — the library's `Solver::solve_rig` with its defaults and each limit
//! mode, the sequential-limb baseline, and (with `--kdl`) Orocos KDL's tree solver.
//!
//! - [`set`]: the target sets and their generator;
//! - [`judge`](mod@judge): how every solve is judged;
//! - [`sequential`]: the sequential-limb baseline;
//! - [`rows`]: the rows and the timing;
//! - [`kdl`]: rig goal files and `kdl_bench`'s output;
//! - [`table`]: text, Markdown and JSON output, and the targets.

mod judge;
mod kdl;
mod rows;
mod sequential;
pub(super) mod set;
mod table;

use ikarus::SolveOptions;
use ikarus_edge::error::Error;
use ikarus_edge::input::io_reason;
use indicatif::ProgressBar;

use super::{BenchArgs, Sink};
use rows::RigRow;
use set::RigSet;
use table::{RigsHeader, SetInfo};

/// Runs `ikarus bench --rigs`.
pub fn run(args: &BenchArgs, sink: &dyn Sink) -> Result<(), Error> {
    if let Some(path) = &args.kdl {
        super::kdl::check(path)?;
    }
    let names = super::unique(&args.rig_sets);
    let goals = args.goals as usize;
    let sets = names.iter().map(|&n| set::generate(n, goals, args.seed)).collect::<Result<Vec<_>, _>>()?;
    let configs = rows::configs();
    let progress = super::progress_bar((sets.len() * goals * configs.len()) as u64);
    // KDL first: a broken --kdl is reported in seconds, not after the whole benchmark.
    let mut kdl_version = None;
    let mut kdl_rows: Vec<RigRow> = Vec::new();
    if let Some(path) = &args.kdl {
        let dir = tempfile::tempdir().map_err(|e| {
            Error::runtime(format!("--kdl {}: cannot make a temporary directory: {}", path.display(), io_reason(&e)))
        })?;
        let comment = format!(
            "written by ikarus {} bench --rigs --seed {} --goals {goals}",
            env!("CARGO_PKG_VERSION"),
            args.seed
        );
        for s in &sets {
            if let Some(bar) = &progress {
                bar.set_message(format!("kdl {}", s.name()));
            }
            let run = kdl::run(path, s, dir.path(), &comment)?;
            kdl_version.get_or_insert_with(|| run.version.clone());
            kdl_rows.push(run.row(s));
        }
    }
    let rows = measure_all(&sets, &configs, kdl_rows, progress.as_ref());
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    let targets = table::targets(&rows);
    let header = header(args, &sets, kdl_version);
    sink.stdout(&mut |w| {
        if args.json {
            table::json(w, &header, &rows, &targets)
        } else if args.markdown {
            table::markdown(w, &header, &rows, &targets)
        } else {
            table::text(w, &header, &rows, &targets)
        }
    })
}

/// Every row of every set: the ikarus rows, the baseline, then KDL's row if there is one; each
/// row's speed relative to KDL's on the same set.
fn measure_all(
    sets: &[RigSet],
    configs: &[rows::RigConfig],
    kdl_rows: Vec<RigRow>,
    progress: Option<&ProgressBar>,
) -> Vec<RigRow> {
    let mut out = Vec::new();
    for s in sets {
        let start = out.len();
        for c in configs {
            if let Some(bar) = progress {
                bar.set_message(format!("{} {}", s.name(), c.label));
            }
            out.push(rows::run_config(s, c, || {
                if let Some(bar) = progress {
                    bar.inc(1);
                }
            }));
        }
        if let Some(k) = kdl_rows.iter().find(|k| k.set == s.name()) {
            out.push(k.clone());
            let kdl = k.median_us;
            for r in &mut out[start..] {
                r.vs_kdl_tree = Some(kdl / r.median_us);
            }
        }
    }
    out
}

fn header(args: &BenchArgs, sets: &[RigSet], kdl_version: Option<String>) -> RigsHeader {
    let opts = SolveOptions::default();
    let names = |s: &RigSet, bones: &[usize]| bones.iter().map(|&b| s.skeleton.name(b).to_owned()).collect();
    RigsHeader {
        command: super::command_line(),
        ikarus_version: env!("CARGO_PKG_VERSION"),
        kdl_version,
        goals: args.goals as usize,
        seed: args.seed,
        sets: sets
            .iter()
            .map(|s| SetInfo { name: s.name(), rig: s.set.rig(), goals: names(s, &s.goals), pins: names(s, &s.pins) })
            .collect(),
        tolerance: opts.tolerance,
        angle_tolerance: opts.angle_tolerance,
        max_iterations: opts.max_iterations,
        kdl_lambda: kdl::KDL_LAMBDA,
        warmup_goals: rows::WARMUP.min(args.goals as usize),
        threads: 1,
        cpus: std::thread::available_parallelism().map_or(1, usize::from),
        os: std::env::consts::OS,
        arch: std::env::consts::ARCH,
        debug_build: cfg!(debug_assertions),
    }
}
