//! The timed rows of `ikarus bench --reach`, all on one thread: the verdict per point, the
//! region build, and an unreachable goal answered with the verdict and without it.

use std::hint::black_box;
use std::time::Instant;

use ikarus::reach::Region;
use ikarus::{Chain, Goal, Outcome, Point2, SolveOptions, Solver, Status};
use ikarus_edge::stats::{median, nearest_rank};
use serde::Serialize;

use super::set::{Points, ReachArm, beyond_annulus};

/// Region builds are repeated until this much time has passed…
const BUILD_BUDGET_SECS: f64 = 1.0;
/// …at least this many times…
const BUILD_MIN: usize = 11;
/// …and at most this many.
const BUILD_MAX: usize = 1001;

/// Points per batch of the batched verdict time.
const BATCH: usize = 1024;

/// Untimed solves before each speed-up row's timed pass.
const WARMUP: usize = 20;

/// The issue's example of a goal the seed arm cannot reach with its limits: "stalled after 326
/// iterations, 16 restarts (180 µs)" before the verdict.
pub const ISSUE_GOAL: [f64; 2] = [-3.0, -1.0];

/// Times of the verdict on one arm.
#[derive(Debug, Clone, Serialize)]
pub struct VerdictRow {
    pub arm: &'static str,
    pub links: usize,
    /// Points judged (the first `--points` random points).
    pub points: usize,
    /// Of them, judged reachable.
    pub reachable: usize,
    /// Median time of one verdict, timed alone (the clock's own time included), ns.
    pub median_ns: f64,
    /// 99th percentile (nearest rank) of the same, ns.
    pub p99_ns: f64,
    /// The median over batches of [`BATCH`] consecutive points, each batch timed as one, of the
    /// batch's time per point, ns (the clock's time spread over the batch; a batch the
    /// machine interrupted is one of many).
    pub batched_ns: f64,
    /// Median time of timing nothing (what `median_ns` includes of the clock), ns.
    pub clock_ns: f64,
}

/// Times the verdict of `region` (of `arm`) on the first `count` of `points`, within
/// `tolerance`.
pub fn verdict_row(arm: ReachArm, region: &Region, points: &Points, count: usize, tolerance: f64) -> VerdictRow {
    let ps: Vec<Point2<f64>> = (0..count as u64).map(|i| points.get(i)).collect();
    // Warm the caches.
    for &p in ps.iter().take(1000) {
        black_box(region.verdict(black_box(p), tolerance));
    }
    let mut ns = Vec::with_capacity(count);
    let mut reachable = 0;
    for &p in &ps {
        let started = Instant::now();
        let v = black_box(region.verdict(black_box(p), tolerance));
        ns.push(nanos(started));
        reachable += usize::from(v.reachable);
    }
    // Batches of consecutive points timed as one: the clock's own time spread thin.
    let mut batches: Vec<f64> = ps
        .chunks(BATCH)
        .map(|chunk| {
            let started = Instant::now();
            for &p in chunk {
                black_box(region.verdict(black_box(p), tolerance));
            }
            nanos(started) / chunk.len() as f64
        })
        .collect();
    batches.sort_by(f64::total_cmp);
    let mut clock = Vec::with_capacity(count.min(100_000));
    for _ in 0..count.min(100_000) {
        let started = Instant::now();
        clock.push(nanos(black_box(started)));
    }
    ns.sort_by(f64::total_cmp);
    clock.sort_by(f64::total_cmp);
    VerdictRow {
        arm: arm.name(),
        links: arm.links(),
        points: count,
        reachable,
        median_ns: or_zero(&ns, median),
        p99_ns: or_zero(&ns, |v| nearest_rank(v, 0.99)),
        batched_ns: or_zero(&batches, median),
        clock_ns: or_zero(&clock, median),
    }
}

/// Times of building one arm's region.
#[derive(Debug, Clone, Serialize)]
pub struct BuildRow {
    pub arm: &'static str,
    pub links: usize,
    /// Builds timed.
    pub builds: usize,
    /// Boundary pieces of the region.
    pub pieces: usize,
    /// Its area.
    pub area: f64,
    /// Median time of one build, ms.
    pub median_ms: f64,
    /// The fastest and the slowest build, ms.
    pub min_ms: f64,
    pub max_ms: f64,
}

/// Times `Region::of(chain, true)`: one untimed build, then builds until
/// [`BUILD_BUDGET_SECS`] have passed (at least [`BUILD_MIN`], at most [`BUILD_MAX`]).
pub fn build_row(arm: ReachArm, chain: &Chain) -> BuildRow {
    let region = Region::of(chain, true);
    let began = Instant::now();
    let mut ms = Vec::new();
    while ms.len() < BUILD_MIN || (ms.len() < BUILD_MAX && began.elapsed().as_secs_f64() < BUILD_BUDGET_SECS) {
        let started = Instant::now();
        black_box(Region::of(black_box(chain), true));
        ms.push(nanos(started) / 1e6);
    }
    ms.sort_by(f64::total_cmp);
    BuildRow {
        arm: arm.name(),
        links: chain.len(),
        builds: ms.len(),
        pieces: region.pieces(),
        area: region.area(),
        median_ms: median(&ms),
        min_ms: ms[0],
        max_ms: ms[ms.len() - 1],
    }
}

/// Which unreachable goals a speed-up row solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GoalKind {
    /// The issue's example, (−3, −1) on the seed arm, solved repeatedly.
    Issue,
    /// Random points inside the annulus (reachable with the limits off) that the verdict calls
    /// unreachable: out of reach because of the limits alone, where the search used to stall.
    LimitsOnly,
    /// Random points outside the annulus: out of reach even without limits, which the solver
    /// already answered without restarts.
    Beyond,
}

impl GoalKind {
    pub fn name(self) -> &'static str {
        match self {
            GoalKind::Issue => "(-3, -1)",
            GoalKind::LimitsOnly => "limits only",
            GoalKind::Beyond => "beyond reach",
        }
    }
}

/// An unreachable goal answered with the verdict and without it.
#[derive(Debug, Clone, Serialize)]
pub struct SpeedupRow {
    pub arm: &'static str,
    pub kind: GoalKind,
    /// Goals solved (by each solver).
    pub goals: usize,
    /// Median time of one solve with the verdict (the default options), µs.
    pub with_median_us: f64,
    /// Median time of one solve without it (`reach_verdict: false`), µs.
    pub without_median_us: f64,
    /// `without_median_us / with_median_us`.
    pub ratio: f64,
    /// Solves with the verdict that ended `unreachable`.
    pub with_unreachable: usize,
    /// Mean iterations and restarts of a solve without the verdict.
    pub without_iterations: f64,
    pub without_restarts: f64,
    /// How the solves without the verdict ended: `(status, count)`, most frequent first.
    pub without_statuses: Vec<(&'static str, usize)>,
}

/// The goals of a speed-up row: the issue's goal `count` times, or the first `count` random
/// points of the kind (fewer if the first million points hold fewer).
pub fn speedup_goals(kind: GoalKind, chain: &Chain, region: &Region, points: &Points, count: usize) -> Vec<Goal> {
    let tolerance = SolveOptions::default().tolerance;
    let wanted = |p: Point2<f64>| match kind {
        GoalKind::Issue => true,
        GoalKind::LimitsOnly => !beyond_annulus(chain, p) && !region.verdict(p, tolerance).reachable,
        GoalKind::Beyond => beyond_annulus(chain, p),
    };
    if kind == GoalKind::Issue {
        let g = Goal::position(ISSUE_GOAL[0], ISSUE_GOAL[1]).expect("a finite goal");
        return vec![g; count];
    }
    (0..1_000_000u64)
        .map(|i| points.get(i))
        .filter(|&p| wanted(p))
        .take(count)
        .map(|p| Goal::position(p.x, p.y).expect("a finite goal"))
        .collect()
}

/// Solves every goal from the chain's start pose (clamped into its limits) with the default
/// options, with the verdict and without it, each solve timed alone.
pub fn speedup_row(arm: ReachArm, kind: GoalKind, chain: &Chain, goals: &[Goal]) -> SpeedupRow {
    let start = super::start_pose(chain);
    let with = SolveOptions::default();
    let without = SolveOptions { reach_verdict: false, ..SolveOptions::default() };
    let (with_us, with_out) = time_solves(chain, &start, goals, with);
    let (without_us, without_out) = time_solves(chain, &start, goals, without);
    let n = goals.len().max(1) as f64;
    let mut statuses: Vec<(&'static str, usize)> = Vec::new();
    for o in &without_out {
        match statuses.iter_mut().find(|(s, _)| *s == o.0.as_str()) {
            Some((_, c)) => *c += 1,
            None => statuses.push((o.0.as_str(), 1)),
        }
    }
    statuses.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
    let with_median_us = or_zero(&with_us, median);
    let without_median_us = or_zero(&without_us, median);
    SpeedupRow {
        arm: arm.name(),
        kind,
        goals: goals.len(),
        with_median_us,
        without_median_us,
        ratio: without_median_us / with_median_us,
        with_unreachable: with_out.iter().filter(|o| o.0 == Status::Unreachable).count(),
        without_iterations: without_out.iter().map(|o| f64::from(o.1)).sum::<f64>() / n,
        without_restarts: without_out.iter().map(|o| f64::from(o.2)).sum::<f64>() / n,
        without_statuses: statuses,
    }
}

/// Each solve's time (µs, sorted) and `(status, iterations, restarts)`, after an untimed
/// warm-up that also builds the solver's region.
fn time_solves(
    chain: &Chain,
    start: &[f64],
    goals: &[Goal],
    options: SolveOptions,
) -> (Vec<f64>, Vec<(Status, u32, u32)>) {
    let mut solver = Solver::new(options).expect("the default options are valid");
    let mut out = Outcome::default();
    for g in goals.iter().take(WARMUP) {
        let _ = solver.solve_into(chain, start, g, &mut out);
    }
    let mut us = Vec::with_capacity(goals.len());
    let mut ends = Vec::with_capacity(goals.len());
    for g in goals {
        let started = Instant::now();
        let result = solver.solve_into(chain, start, g, &mut out);
        us.push(nanos(started) / 1000.0);
        match result {
            Ok(()) => ends.push((out.status, out.iterations, out.restarts)),
            // Not a goal the benchmark makes; counted as not unreachable.
            Err(_) => ends.push((Status::Interrupted, 0, 0)),
        }
    }
    us.sort_by(f64::total_cmp);
    (us, ends)
}

fn nanos(started: Instant) -> f64 {
    started.elapsed().as_nanos() as f64
}

/// `f` of sorted `v`, or 0 when `v` is empty.
fn or_zero(v: &[f64], f: impl Fn(&[f64]) -> f64) -> f64 {
    if v.is_empty() { 0.0 } else { f(v) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speedup_goals_are_of_their_kind() {
        let chain = ReachArm::Seed.chain().unwrap();
        let region = Region::of(&chain, true);
        let points = Points::new("seed", &chain, 1);
        let tol = SolveOptions::default().tolerance;
        let limits = speedup_goals(GoalKind::LimitsOnly, &chain, &region, &points, 50);
        let beyond = speedup_goals(GoalKind::Beyond, &chain, &region, &points, 50);
        assert_eq!((limits.len(), beyond.len()), (50, 50));
        for g in &limits {
            assert!(!beyond_annulus(&chain, g.target()) && !region.verdict(g.target(), tol).reachable);
        }
        for g in &beyond {
            assert!(beyond_annulus(&chain, g.target()) && !region.verdict(g.target(), tol).reachable);
        }
        let issue = speedup_goals(GoalKind::Issue, &chain, &region, &points, 3);
        assert_eq!(issue.len(), 3);
        assert!(!region.verdict(issue[0].target(), tol).reachable, "the issue's goal is out of reach");
    }

    #[test]
    fn rows_count_what_they_time() {
        let chain = ReachArm::Seed.chain().unwrap();
        let region = Region::of(&chain, true);
        let points = Points::new("seed", &chain, 1);
        let v = verdict_row(ReachArm::Seed, &region, &points, 200, 1e-6);
        assert_eq!((v.arm, v.links, v.points), ("seed", 3, 200));
        assert!(v.reachable > 0 && v.reachable < 200 && v.median_ns > 0.0 && v.p99_ns >= v.median_ns);
        let b = build_row(ReachArm::Seed, &chain);
        assert!(b.builds >= BUILD_MIN && b.min_ms <= b.median_ms && b.median_ms <= b.max_ms);
        assert_eq!((b.pieces, b.area), (region.pieces(), region.area()));
        let goals = speedup_goals(GoalKind::Issue, &chain, &region, &points, 3);
        let s = speedup_row(ReachArm::Seed, GoalKind::Issue, &chain, &goals);
        assert_eq!((s.goals, s.with_unreachable), (3, 3));
        assert!(s.without_restarts > 0.0 && s.without_iterations > 0.0, "{s:?}");
        assert_eq!(s.without_statuses.iter().map(|(_, c)| c).sum::<usize>(), 3);
    }
}
