//! The rows of `ikarus bench` and how each is timed; every solve is judged by
//! [`judge`](super::judge).

use std::time::Instant;

use ikarus::{LimitMode, Method, Outcome, Restarts, SolveOptions, Solver};
use ikarus_edge::stats::{median, nearest_rank};

use super::batch::Batched;
use super::judge::{Verdict, judge};
use super::sets::{GoalSet, SetName};

/// Untimed warm-up solves before each row's timed pass, over the first goals of the set.
pub const WARMUP_GOALS: usize = 50;

/// Which sets a row is run on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// `free-position`, `free-oriented` and `unreachable`: limits off.
    Free,
    /// `limits-position` and `limits-oriented`: limits enforced.
    Limits,
}

impl Group {
    /// The group of `set`.
    pub fn of(set: SetName) -> Self {
        if set.limited() { Group::Limits } else { Group::Free }
    }
}

/// One row of the benchmark: a named solver configuration.
#[derive(Debug, Clone)]
pub struct Config {
    /// The row's label in the output, unique within a set (e.g. `dls lock +restarts`).
    pub label: String,
    /// The method's name as `--methods` filters it: [`Method::name`], or `default`.
    pub method: &'static str,
    /// The options every solve of the row runs with.
    pub options: SolveOptions,
    /// The sets the row is run on.
    pub group: Group,
}

impl Config {
    /// Whether the row is run on `set`: its group matches and, for `analytic`, the chain and
    /// goals have a closed form (2 links with position goals, 3 links with orientation goals).
    pub fn applies_to(&self, set: &GoalSet) -> bool {
        if self.group != Group::of(set.set) {
            return false;
        }
        if self.options.method == Method::Analytic {
            let n = set.chain.len();
            return (n == 2 && !set.set.oriented()) || (n == 3 && set.set.oriented());
        }
        true
    }

    /// What the limits column shows: the mode's name, or `None` when limits are ignored.
    pub fn limits(&self) -> Option<&'static str> {
        (self.options.limits != LimitMode::Ignore).then(|| self.options.limits.name())
    }
}

/// Every row of the benchmark, free-set rows first, in the order of the output.
///
/// Free sets: every iterative method with limits ignored, no closed form and no restarts (so
/// the iterations themselves are measured), `analytic`, and `default` (what `ikarus solve`
/// does without `--limits`). Limits sets: each Jacobian method with each enforcing mode, `ccd`
/// and `fabrik` with clamping, `dls`, `lm` and `sdls` with each mode and restarts, `analytic` (clamping into
/// the limits), and `default` (the library's defaults).
pub fn configs() -> Vec<Config> {
    let bare = |method: Method, limits: LimitMode| SolveOptions {
        method,
        limits,
        restarts: None,
        closed_form: false,
        ..SolveOptions::default()
    };
    let row = |label: String, method: &'static str, options: SolveOptions, group: Group| Config {
        label,
        method,
        options,
        group,
    };
    let iterative = || Method::ALL.into_iter().filter(|&m| m != Method::Analytic);
    let enforcing = || LimitMode::ALL.into_iter().filter(|&m| m != LimitMode::Ignore);
    let mut rows = Vec::new();

    for m in iterative() {
        rows.push(row(m.name().to_owned(), m.name(), bare(m, LimitMode::Ignore), Group::Free));
    }
    let analytic = Method::Analytic;
    rows.push(row(analytic.name().to_owned(), analytic.name(), bare(analytic, LimitMode::Ignore), Group::Free));
    let free_default = SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() };
    rows.push(row("default".to_owned(), "default", free_default, Group::Free));

    for m in iterative().filter(|m| m.uses_jacobian()) {
        for mode in enforcing() {
            rows.push(row(format!("{} {}", m.name(), mode.name()), m.name(), bare(m, mode), Group::Limits));
        }
    }
    for m in iterative().filter(|m| !m.uses_jacobian()) {
        let mode = LimitMode::Clamp;
        rows.push(row(format!("{} {}", m.name(), mode.name()), m.name(), bare(m, mode), Group::Limits));
    }
    for m in [Method::DampedLeastSquares, Method::LevenbergMarquardt, Method::SelectivelyDamped] {
        for mode in enforcing() {
            let options = SolveOptions { restarts: Some(Restarts::default()), ..bare(m, mode) };
            rows.push(row(format!("{} {} +restarts", m.name(), mode.name()), m.name(), options, Group::Limits));
        }
    }
    let mode = LimitMode::Clamp;
    rows.push(row(
        format!("{} {}", analytic.name(), mode.name()),
        analytic.name(),
        bare(analytic, mode),
        Group::Limits,
    ));
    rows.push(row("default".to_owned(), "default", SolveOptions::default(), Group::Limits));
    rows
}

/// The `--methods` and `--limit-modes` filters.
#[derive(Debug, Clone, Default)]
pub struct Filter {
    /// Method names to keep (`default` included); `None` keeps every method.
    pub methods: Option<Vec<String>>,
    /// Limit-mode names to keep; `None` keeps every mode. The `default` row is not filtered by
    /// mode.
    pub modes: Option<Vec<String>>,
}

impl Filter {
    /// Whether `config` is kept.
    pub fn keeps(&self, config: &Config) -> bool {
        let method_ok = self.methods.as_ref().is_none_or(|ms| ms.iter().any(|m| m == config.method));
        let mode_ok = config.method == "default"
            || self.modes.as_ref().is_none_or(|ms| ms.iter().any(|m| m == config.options.limits.name()));
        method_ok && mode_ok
    }
}

/// The results of one row on one set, ready for the table.
#[derive(Debug, Clone)]
pub struct RowResult {
    /// The arm's name.
    pub arm: &'static str,
    /// The set.
    pub set: SetName,
    /// The row's label.
    pub label: String,
    /// The limits column: the enforcing mode's name, `None` for limits ignored.
    pub limits: Option<&'static str>,
    /// Goals solved.
    pub goals: usize,
    /// Solves judged reached.
    pub reached: usize,
    /// Median time of one solve, microseconds.
    pub median_us: f64,
    /// 99th percentile (nearest rank) of the time of one solve, microseconds.
    pub p99_us: f64,
    /// Mean iterations per solve; `None` when the solver does not report them.
    pub mean_iterations: Option<f64>,
    /// The largest position error of any solve (see [`Verdict::error`]); infinite when a
    /// solve failed outright.
    pub worst_error: f64,
    /// The largest orientation error of any solve, for oriented sets.
    pub worst_angle_error: Option<f64>,
    /// Solves that returned an error instead of a pose (counted as not reached).
    pub solve_errors: usize,
    /// The first such error's message.
    pub first_solve_error: Option<String>,
    /// KDL LMA's median on the same set divided by this row's median; `None` without `--kdl`.
    pub vs_kdl_lma: Option<f64>,
    /// Each goal's verdict, in the set's order (a solve that returned an error: not reached).
    pub reached_each: Vec<bool>,
    /// The batched measurement (`default` rows only): its figures, or the batch's error.
    pub batch: Option<Result<Batched, String>>,
}

/// Collects the solves of a row.
#[derive(Debug)]
pub struct Tally {
    /// Time of each solve, nanoseconds.
    nanos: Vec<u64>,
    /// Solves judged reached.
    reached: usize,
    /// Sum of the iterations; `None` once a solve did not report them.
    iterations: Option<u64>,
    /// Largest position error so far.
    worst_error: f64,
    /// Largest orientation error so far, for oriented sets.
    worst_angle_error: Option<f64>,
    /// Solves that returned an error.
    solve_errors: usize,
    /// The first such error's message.
    first_solve_error: Option<String>,
    /// Each solve's verdict, in order.
    reached_each: Vec<bool>,
}

impl Tally {
    /// An empty tally for `goals` solves of a set (oriented or not).
    pub fn new(goals: usize, oriented: bool) -> Self {
        Self {
            nanos: Vec::with_capacity(goals),
            reached: 0,
            iterations: Some(0),
            worst_error: 0.0,
            worst_angle_error: oriented.then_some(0.0),
            solve_errors: 0,
            first_solve_error: None,
            reached_each: Vec::with_capacity(goals),
        }
    }

    /// Adds a solve that took `nanos`, ran `iterations` (`None`: unknown) and was judged
    /// `verdict`.
    pub fn add(&mut self, nanos: u64, iterations: Option<u64>, verdict: Verdict) {
        self.nanos.push(nanos);
        self.reached += usize::from(verdict.reached);
        self.reached_each.push(verdict.reached);
        self.iterations = self.iterations.zip(iterations).map(|(a, b)| a + b);
        self.worst_error = self.worst_error.max(verdict.error);
        if let (Some(w), Some(a)) = (&mut self.worst_angle_error, verdict.angle_error) {
            *w = w.max(if a.is_nan() { f64::INFINITY } else { a });
        }
    }

    /// Adds a solve that took `nanos` and returned an error.
    pub fn fail(&mut self, nanos: u64, message: String) {
        self.nanos.push(nanos);
        self.worst_error = f64::INFINITY;
        if let Some(w) = &mut self.worst_angle_error {
            *w = f64::INFINITY;
        }
        self.solve_errors += 1;
        self.reached_each.push(false);
        self.first_solve_error.get_or_insert(message);
    }

    /// The row's results.
    pub fn finish(mut self, set: &GoalSet, label: String, limits: Option<&'static str>) -> RowResult {
        self.nanos.sort_unstable();
        let us: Vec<f64> = self.nanos.iter().map(|&n| n as f64 / 1000.0).collect();
        let goals = us.len();
        RowResult {
            arm: set.arm,
            set: set.set,
            label,
            limits,
            goals,
            reached: self.reached,
            median_us: median(&us),
            p99_us: nearest_rank(&us, 0.99),
            mean_iterations: self.iterations.map(|i| i as f64 / goals as f64),
            worst_error: self.worst_error,
            worst_angle_error: self.worst_angle_error,
            solve_errors: self.solve_errors,
            first_solve_error: self.first_solve_error,
            vs_kdl_lma: None,
            reached_each: self.reached_each,
            batch: None,
        }
    }
}

/// Runs `config` on every goal of `set`: one solver and one outcome reused, every solve from
/// the set's start pose and timed alone, after an untimed warm-up over the first
/// [`WARMUP_GOALS`] goals. `tick` is called after each timed solve, outside the timing.
pub fn run_config(set: &GoalSet, config: &Config, mut tick: impl FnMut()) -> RowResult {
    let mut solver = Solver::new(config.options.clone()).expect("the benchmark's options are valid");
    let mut out = Outcome::default();
    let warmup = set.targets.len().min(WARMUP_GOALS);
    for target in &set.targets[..warmup] {
        // Only for the caches: a failure here is counted in the timed pass.
        let _ = solver.solve_into(&set.chain, &set.start, target, &mut out);
    }
    let mut tally = Tally::new(set.goals.len(), set.set.oriented());
    for (goal, target) in set.goals.iter().zip(&set.targets) {
        let started = Instant::now();
        let result = solver.solve_into(&set.chain, &set.start, target, &mut out);
        let nanos = u64::try_from(started.elapsed().as_nanos()).unwrap_or(u64::MAX);
        match result {
            Ok(()) => tally.add(nanos, Some(u64::from(out.iterations)), judge(set, goal, out.pose.angles())),
            Err(e) => tally.fail(nanos, e.to_string()),
        }
        tick();
    }
    tally.finish(set, config.label.clone(), config.limits())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sets::{ArmName, generate};

    fn seed_set(set: SetName) -> GoalSet {
        generate("seed", &ArmName::Seed.load().unwrap().chain, set, 20, 1)
    }

    #[test]
    fn rows_per_group() {
        let rows = configs();
        let labels = |g: Group| rows.iter().filter(|r| r.group == g).map(|r| r.label.as_str()).collect::<Vec<_>>();
        assert_eq!(
            labels(Group::Free),
            ["transpose", "pinv", "dls", "sdls", "lm", "ccd", "fabrik", "analytic", "default"]
        );
        let limits = labels(Group::Limits);
        assert_eq!(limits.len(), 5 * 4 + 2 + 3 * 4 + 2);
        assert!(
            limits.contains(&"dls lock +restarts")
                && limits.contains(&"fabrik clamp")
                && limits.contains(&"sdls nullspace")
        );
        for r in &rows {
            assert!(r.options.validate().is_ok());
            if r.method != "default" {
                assert!(!r.options.closed_form);
                assert_eq!(r.options.restarts.is_some(), r.label.ends_with("+restarts"));
            }
            assert_eq!(r.limits().is_none(), r.group == Group::Free);
        }
        // Analytic only where the closed form exists: 3 links with an orientation.
        let analytic = rows.iter().find(|r| r.label == "analytic").unwrap();
        assert!(analytic.applies_to(&seed_set(SetName::FreeOriented)));
        assert!(!analytic.applies_to(&seed_set(SetName::FreePosition)));
        assert!(!analytic.applies_to(&seed_set(SetName::LimitsOriented)));
    }

    #[test]
    fn filters() {
        let rows = configs();
        let keep = |f: &Filter| rows.iter().filter(|r| f.keeps(r)).map(|r| r.label.as_str()).collect::<Vec<_>>();
        let f = Filter { methods: Some(vec!["dls".into()]), modes: Some(vec!["lock".into()]) };
        assert_eq!(keep(&f), ["dls lock", "dls lock +restarts"]);
        let f = Filter { methods: None, modes: Some(vec!["ignore".into()]) };
        assert_eq!(keep(&f).len(), 9 + 1, "the free rows and the limits sets' default");
        let f = Filter { methods: Some(vec!["default".into()]), modes: Some(vec!["clamp".into()]) };
        assert_eq!(keep(&f), ["default", "default"]);
    }

    #[test]
    fn statistics() {
        let set = seed_set(SetName::FreeOriented);
        let mut t = Tally::new(3, true);
        t.add(3000, Some(4), Verdict { reached: true, error: 1e-7, angle_error: Some(2e-7) });
        t.add(1000, None, Verdict { reached: false, error: 0.5, angle_error: Some(0.1) });
        t.add(2000, Some(2), Verdict { reached: true, error: 0.0, angle_error: Some(0.0) });
        let r = t.finish(&set, "x".into(), None);
        assert_eq!((r.goals, r.reached, r.median_us, r.p99_us), (3, 2, 2.0, 3.0));
        assert_eq!((r.mean_iterations, r.worst_error, r.worst_angle_error), (None, 0.5, Some(0.1)));
    }
}
