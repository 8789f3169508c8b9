//! `ikarus bench --reach`: the exact reachable region of issue 13 measured and checked — the
//! verdict's time per point, the region's build time for 3, 7 and 8 links, the verdict against
//! solving over many random points, and an unreachable goal answered with the verdict against
//! the search it replaces.
//!
//! - [`set`]: the arms, the random points, the distance to a region's boundary;
//! - [`timing`]: the timed rows (one thread);
//! - [`agree`]: the verdict against solving (on a pool of threads);
//! - [`table`]: text, Markdown and JSON output, and the targets.

mod agree;
pub(super) mod set;
mod table;
mod timing;

use std::io::IsTerminal;

use ikarus::reach::Region;
use ikarus::{Chain, SolveOptions};
use ikarus_edge::error::Error;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::{BenchArgs, Sink};
use agree::{Context, SUBSET_EVERY};
use set::{Points, ReachArm};
use table::{ReachHeader, ReachReport};
use timing::GoalKind;

/// Threads of the agreement check (the machine's CPUs, at most this many).
const THREADS: usize = 2;

/// Runs `ikarus bench --reach`.
pub fn run(args: &BenchArgs, sink: &dyn Sink) -> Result<(), Error> {
    let tolerance = SolveOptions::default().tolerance;
    let points = args.points;
    let goals = args.goals as usize;
    let threads = THREADS.min(std::thread::available_parallelism().map_or(1, usize::from));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::runtime(format!("cannot start {threads} threads: {e}")))?;

    let mut arms = Vec::new();
    for arm in ReachArm::ALL {
        let chain = arm.chain()?;
        let region = Region::of(&chain, true);
        let pts = Points::new(arm.name(), &chain, args.seed);
        arms.push((arm, chain, region, pts));
    }
    let checked = || arms.iter().filter(|(arm, ..)| ReachArm::CHECKED.contains(arm));

    // The timings first, before the threads of the agreement warm the machine.
    let build: Vec<_> = arms.iter().map(|(arm, chain, ..)| timing::build_row(*arm, chain)).collect();
    let verdict: Vec<_> = checked()
        .map(|(arm, _, region, pts)| timing::verdict_row(*arm, region, pts, points as usize, tolerance))
        .collect();
    let mut speedup = Vec::new();
    for (arm, chain, region, pts) in checked() {
        let kinds: &[GoalKind] = if *arm == ReachArm::Seed {
            &[GoalKind::Issue, GoalKind::LimitsOnly, GoalKind::Beyond]
        } else {
            &[GoalKind::LimitsOnly, GoalKind::Beyond]
        };
        for &kind in kinds {
            let g = timing::speedup_goals(kind, chain, region, pts, goals);
            speedup.push(timing::speedup_row(*arm, kind, chain, &g));
        }
    }

    let progress = progress_bar(points * checked().count() as u64);
    let mut agreement = Vec::new();
    for (arm, chain, region, pts) in checked() {
        if let Some(bar) = &progress {
            bar.set_message(format!("{} agreement", arm.name()));
        }
        let cx = Context { arm: *arm, chain, region, start: start_pose(chain), tolerance };
        agreement.push(agree::agreement(&cx, pts, points, &pool, progress.as_ref()));
    }
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }

    let targets = table::targets(&verdict, &build, &agreement, &speedup);
    let header = ReachHeader {
        command: super::command_line(),
        ikarus_version: env!("CARGO_PKG_VERSION"),
        seed: args.seed,
        points,
        goals,
        tolerance,
        subset_every: SUBSET_EVERY,
        threads,
        cpus: std::thread::available_parallelism().map_or(1, usize::from),
        os: std::env::consts::OS,
        arch: std::env::consts::ARCH,
        debug_build: cfg!(debug_assertions),
    };
    let report = ReachReport { header, verdict, build, agreement, speedup, targets };
    sink.stdout(&mut |w| {
        if args.json {
            table::json(w, &report)
        } else if args.markdown {
            table::markdown(w, &report)
        } else {
            table::text(w, &report)
        }
    })
}

/// The start pose of every solve: the chain's own, clamped into its limits (as for the other
/// limits rows).
pub fn start_pose(chain: &Chain) -> Vec<f64> {
    let mut angles = chain.start_pose().angles().to_vec();
    for (a, lim) in angles.iter_mut().zip(chain.limits()) {
        if let Some(l) = lim {
            *a = l.clamp(*a);
        }
    }
    angles
}

/// A progress bar over `total` points, on stderr, only when stderr is a terminal.
fn progress_bar(total: u64) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() || total == 0 {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{spinner} [{bar:25}] {pos}/{len} points, {eta} left: {wide_msg}")
            .expect("static template")
            .progress_chars("=> "),
    );
    Some(bar)
}
