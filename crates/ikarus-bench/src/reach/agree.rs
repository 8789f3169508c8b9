//! The verdict against solving, over many random points: every point the verdict calls
//! reachable must be reached by the default solver, and no point it calls unreachable may be
//! reached by a search with restarts (the default method on every such point, every method on
//! a deterministic subset). Solves are judged by forward kinematics, not by their status.

use ikarus::kinematics::end_effector;
use ikarus::reach::Region;
use ikarus::{Chain, Goal, Method, Outcome, Point2, Restarts, SolveOptions, Solver, Status};
use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::Serialize;

use super::set::{Points, ReachArm, boundary_distance};
use crate::judge::within;

/// Every this many points (by index), a point the verdict calls unreachable is also searched
/// for by every method.
pub const SUBSET_EVERY: u64 = 100;

/// Rounding slack added to the tolerance when judging a solve, as for the other rows.
const ROUNDING_SLACK: f64 = 1e-12;

/// How far the tip of the verdict's answer may lie from the nearest reachable point.
const ANSWER_SLACK: f64 = 1e-9;

/// Points between two ticks of the progress bar.
const TICK: u64 = 256;

/// The methods that search on the subset: every method but `analytic` (a closed form for two
/// links, or three with an orientation; elsewhere it falls back on `dls`, which is searched
/// already), each with its default limit mode and restarts.
pub fn subset_methods() -> Vec<Method> {
    Method::ALL.into_iter().filter(|&m| m != Method::Analytic).collect()
}

/// A point where the verdict and solving disagree.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Disagreement {
    /// The point's index among the arm's random points.
    pub index: u64,
    pub point: [f64; 2],
    /// The verdict: reachable or not, and its distance to the region (0 inside).
    pub reachable: bool,
    pub distance: f64,
    /// The point's distance to the region's boundary (inside: how deep it lies).
    pub boundary_distance: f64,
    /// The solve that disagreed: its label, status, and its tip's distance from the point.
    pub solver: String,
    pub status: &'static str,
    pub error: f64,
    /// Whether its angles were inside the limits.
    pub inside_limits: bool,
}

/// What the check found on one arm.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Agreement {
    pub arm: &'static str,
    pub points: u64,
    /// Points the verdict calls reachable, and of them those the default solver reached.
    pub reachable: u64,
    pub reached: u64,
    /// Points the verdict calls unreachable, and of them those the default method's search
    /// (`reach_verdict: false`, restarts) did not reach.
    pub unreachable: u64,
    pub unreachable_confirmed: u64,
    /// Of the unreachable points, those the default solver (verdict on) answered
    /// `unreachable` with its tip on the nearest reachable point.
    pub answered_unreachable: u64,
    /// Unreachable points searched for by every method, and of them those no method reached.
    pub subset: u64,
    pub subset_confirmed: u64,
    /// The methods of the subset.
    pub subset_methods: Vec<&'static str>,
    /// Points where verdict and solving agree, as a share of all, truncated to 1e-4 %.
    pub agree: u64,
    pub agree_percent: f64,
    /// Every disagreement, by index.
    pub disagreements: Vec<Disagreement>,
}

impl Agreement {
    fn merge(mut self, other: Agreement) -> Agreement {
        self.arm = if self.arm.is_empty() { other.arm } else { self.arm };
        self.points += other.points;
        self.reachable += other.reachable;
        self.reached += other.reached;
        self.unreachable += other.unreachable;
        self.unreachable_confirmed += other.unreachable_confirmed;
        self.answered_unreachable += other.answered_unreachable;
        self.subset += other.subset;
        self.subset_confirmed += other.subset_confirmed;
        self.disagreements.extend(other.disagreements);
        self
    }

    fn finish(mut self, arm: ReachArm) -> Agreement {
        self.arm = arm.name();
        self.subset_methods = subset_methods().into_iter().map(Method::name).collect();
        self.disagreements.sort_by_key(|d| d.index);
        let mut wrong: Vec<u64> = self.disagreements.iter().map(|d| d.index).collect();
        wrong.dedup();
        self.agree = self.points - wrong.len() as u64;
        self.agree_percent = percent(self.agree, self.points);
        self
    }
}

/// `part` of `whole` as a percentage truncated to 1e-4 %: one miss in a million must not read
/// as 100 %.
pub fn percent(part: u64, whole: u64) -> f64 {
    if whole == 0 { 0.0 } else { (1e6 * part as f64 / whole as f64).floor() / 1e4 }
}

/// What a point is judged against: the arm's chain, the region giving the verdict, the start
/// pose of every solve and the tolerance.
pub struct Context<'a> {
    pub arm: ReachArm,
    pub chain: &'a Chain,
    pub region: &'a Region,
    pub start: Vec<f64>,
    pub tolerance: f64,
}

/// One thread's solvers and outcome, reused from point to point.
struct Solvers {
    default: Solver,
    search: Solver,
    methods: Vec<(Method, Solver)>,
    out: Outcome,
}

impl Solvers {
    fn new() -> Self {
        let search = |method: Method| {
            Solver::new(SolveOptions {
                method,
                limits: method.default_limit_mode(),
                restarts: Some(Restarts::default()),
                reach_verdict: false,
                ..SolveOptions::default()
            })
            .expect("valid options")
        };
        let default_method = SolveOptions::default().method;
        Self {
            default: Solver::new(SolveOptions::default()).expect("the default options are valid"),
            search: search(default_method),
            methods: subset_methods().into_iter().map(|m| (m, search(m))).collect(),
            out: Outcome::default(),
        }
    }
}

/// A solve's result, judged by forward kinematics: whether the tip is within the tolerance of
/// the goal with every joint inside its limits, and the parts of that judgement.
#[derive(Debug, Clone, Copy)]
struct Judged {
    reached: bool,
    status: &'static str,
    error: f64,
    inside_limits: bool,
}

fn solve(cx: &Context, solver: &mut Solver, out: &mut Outcome, goal: &Goal) -> Judged {
    if let Err(e) = solver.solve_into(cx.chain, &cx.start, goal, out) {
        // The goals are finite and the options valid: a bug, reported as a disagreement.
        let _ = e;
        return Judged { reached: false, status: "error", error: f64::INFINITY, inside_limits: false };
    }
    let angles = out.pose.angles();
    let tip = end_effector(cx.chain, angles).position;
    let error = (tip - goal.target()).norm();
    let inside_limits =
        angles.iter().zip(cx.chain.limits()).all(|(&a, l)| l.is_none_or(|l| within(a, l.min(), l.max())));
    Judged {
        reached: error <= cx.tolerance + ROUNDING_SLACK && inside_limits,
        status: out.status.as_str(),
        error,
        inside_limits,
    }
}

/// Judges point `index` (at `p`) into `tally`.
fn check(cx: &Context, s: &mut Solvers, index: u64, p: Point2<f64>, tally: &mut Agreement) {
    let goal = Goal::position(p.x, p.y).expect("random points are finite");
    let v = cx.region.verdict(p, cx.tolerance);
    tally.points += 1;
    let disagree = |label: &str, j: Judged, tally: &mut Agreement| {
        tally.disagreements.push(Disagreement {
            index,
            point: [p.x, p.y],
            reachable: v.reachable,
            distance: v.distance,
            boundary_distance: boundary_distance(cx.region, p),
            solver: label.to_owned(),
            status: j.status,
            error: j.error,
            inside_limits: j.inside_limits,
        });
    };
    if v.reachable {
        tally.reachable += 1;
        let j = solve(cx, &mut s.default, &mut s.out, &goal);
        if j.reached {
            tally.reached += 1;
        } else {
            disagree("default", j, tally);
        }
        return;
    }
    tally.unreachable += 1;
    let answer = solve(cx, &mut s.default, &mut s.out, &goal);
    if s.out.status == Status::Unreachable && (answer.error - v.distance).abs() <= ANSWER_SLACK * (1.0 + v.distance) {
        tally.answered_unreachable += 1;
    }
    let j = solve(cx, &mut s.search, &mut s.out, &goal);
    if j.reached {
        disagree(&format!("{} search", SolveOptions::default().method.name()), j, tally);
    } else {
        tally.unreachable_confirmed += 1;
    }
    if index % SUBSET_EVERY == 0 {
        tally.subset += 1;
        let mut confirmed = true;
        for (m, solver) in &mut s.methods {
            let j = solve(cx, solver, &mut s.out, &goal);
            if j.reached {
                confirmed = false;
                disagree(&format!("{} search", m.name()), j, tally);
            }
        }
        tally.subset_confirmed += u64::from(confirmed);
    }
}

/// Checks the first `count` of `points` on `pool`'s threads, ticking `progress` as it goes.
pub fn agreement(
    cx: &Context,
    points: &Points,
    count: u64,
    pool: &rayon::ThreadPool,
    progress: Option<&ProgressBar>,
) -> Agreement {
    let tally = pool.install(|| {
        (0..count as usize)
            .into_par_iter()
            .with_min_len(TICK as usize)
            .fold(
                || (Solvers::new(), Agreement::default()),
                |(mut s, mut t), i| {
                    let i = i as u64;
                    check(cx, &mut s, i, points.get(i), &mut t);
                    if let Some(bar) = progress {
                        if (i + 1) % TICK == 0 {
                            bar.inc(TICK);
                        }
                    }
                    (s, t)
                },
            )
            .map(|(_, t)| t)
            .reduce(Agreement::default, Agreement::merge)
    });
    if let Some(bar) = progress {
        bar.inc(count % TICK);
    }
    tally.finish(cx.arm)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool() -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap()
    }

    #[test]
    fn the_seed_arm_agrees_on_a_few_hundred_points() {
        let chain = ReachArm::Seed.chain().unwrap();
        let region = Region::of(&chain, true);
        let cx = Context {
            arm: ReachArm::Seed,
            chain: &chain,
            region: &region,
            start: super::super::start_pose(&chain),
            tolerance: 1e-6,
        };
        let points = Points::new("seed", &chain, 1);
        let a = agreement(&cx, &points, 300, &pool(), None);
        assert_eq!(a.points, 300);
        assert_eq!(a.reachable + a.unreachable, 300);
        assert!(a.reachable > 30 && a.unreachable > 30, "{a:?}");
        assert_eq!(a.disagreements, []);
        assert_eq!((a.agree, a.agree_percent), (300, 100.0));
        assert_eq!((a.reached, a.unreachable_confirmed), (a.reachable, a.unreachable));
        assert_eq!(a.answered_unreachable, a.unreachable);
        assert_eq!(
            a.subset,
            (0..300).step_by(SUBSET_EVERY as usize).filter(|&i| !region.verdict(points.get(i), 1e-6).reachable).count()
                as u64
        );
        assert_eq!(a.subset_confirmed, a.subset);
        // The same on one thread: the tally does not depend on how the points were shared out.
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let b = agreement(&cx, &points, 300, &one, None);
        assert_eq!((b.reachable, b.subset, b.answered_unreachable), (a.reachable, a.subset, a.answered_unreachable));
    }

    #[test]
    fn a_verdict_too_generous_is_flagged() {
        // The region without limits calls the whole annulus reachable: the points in it that
        // the limits keep out of reach are not reached by the default solver.
        let chain = ReachArm::Seed.chain().unwrap();
        let free = Region::of(&chain, false);
        let limited = Region::of(&chain, true);
        let cx = Context {
            arm: ReachArm::Seed,
            chain: &chain,
            region: &free,
            start: super::super::start_pose(&chain),
            tolerance: 1e-6,
        };
        let points = Points::new("seed", &chain, 1);
        let a = agreement(&cx, &points, 200, &pool(), None);
        let wrong: Vec<u64> = (0..200)
            .filter(|&i| free.verdict(points.get(i), 1e-6).reachable && !limited.verdict(points.get(i), 1e-6).reachable)
            .collect();
        assert!(!wrong.is_empty());
        assert_eq!(a.disagreements.iter().map(|d| d.index).collect::<Vec<_>>(), wrong);
        for d in &a.disagreements {
            assert!(d.reachable && d.solver == "default" && d.status == "unreachable" && d.error > 1e-6, "{d:?}");
        }
        assert_eq!(a.agree, 200 - wrong.len() as u64);
        assert!(a.agree_percent < 100.0);
    }

    #[test]
    fn a_verdict_too_strict_is_flagged() {
        // The region of the seed arm with every range halved calls points unreachable that the
        // arm with its own ranges reaches: the searches reach them.
        let chain = ReachArm::Seed.chain().unwrap();
        let links: Vec<ikarus::Link> = chain
            .links()
            .into_iter()
            .zip(chain.limits())
            .map(|(l, lim)| {
                let lim = lim.unwrap();
                l.with_limits(ikarus::JointLimits::new(lim.min() / 2.0, lim.max() / 2.0).unwrap())
            })
            .collect();
        let narrow = Region::of(&Chain::new([0.0, 0.0], &links).unwrap(), true);
        let cx = Context {
            arm: ReachArm::Seed,
            chain: &chain,
            region: &narrow,
            start: super::super::start_pose(&chain),
            tolerance: 1e-6,
        };
        let points = Points::new("seed", &chain, 4);
        let a = agreement(&cx, &points, 201, &pool(), None);
        assert!(a.unreachable_confirmed < a.unreachable, "{a:?}");
        let lm: Vec<&Disagreement> = a.disagreements.iter().filter(|d| d.solver == "lm search").collect();
        assert!(!lm.is_empty());
        for d in &lm {
            assert!(
                !d.reachable && d.distance > 1e-6 && d.status == "reached" && d.error <= 1e-6 && d.inside_limits,
                "{d:?}"
            );
        }
        assert!(a.agree < 201);
    }

    #[test]
    fn percentages_are_truncated() {
        assert_eq!(percent(999_999, 1_000_000), 99.9999);
        assert_eq!(percent(1_000_000, 1_000_000), 100.0);
        assert_eq!(percent(2, 3), 66.6666);
        assert_eq!(percent(0, 0), 0.0);
    }
}
