//! `ikarus bench`: times every solver configuration on seeded goal sets for the shipped arms,
//! judges every solve the same way, and (with `--kdl`) sets Orocos KDL's solvers beside them.
//!
//! - [`sets`]: the goal sets and their generator;
//! - [`run`](mod@run): the rows and the timing;
//! - [`batch`]: the batched measurement beside each `default` row (`Solver::solve_batch`
//!   on one thread and two);
//! - [`judge`](mod@judge): how every solve is judged;
//! - [`kdl`]: goal files and `kdl_bench`'s output;
//! - [`table`]: text, Markdown and JSON output;
//! - [`paths`]: `--paths`, the path benchmark (`follow`, `plan`, from scratch, KDL warm);
//! - [`rigs`]: `--rigs`, whole rigs (the library's rig solve, the sequential-limb baseline,
//!   KDL's tree solver);
//! - [`reach`]: `--reach`, the exact reachable region (verdict time, build time, the verdict
//!   against solving, unreachable goals answered with and without it);
//! - [`characters`]: `--characters`, every shipped character posed (setup and animated).
//!
//! The command line parses [`BenchArgs`] and calls [`run`](fn@run) with its stdout and output
//! files ([`Sink`]); this crate reads the shipped arms and rigs through `ikarus-edge`.

mod batch;
mod characters;
mod judge;
mod kdl;
mod paths;
mod reach;
mod rigs;
mod run;
mod sets;
mod table;

use std::io::{self, IsTerminal, Write};
use std::path::{Path, PathBuf};

use clap::Args;
use clap::builder::PossibleValuesParser;
use ikarus::{LimitMode, Method, SolveOptions};
use ikarus_edge::error::Error;
use ikarus_edge::input::io_reason;
use ikarus_edge::options::parse_at_least_one;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use run::{Config, Filter, RowResult};
use sets::{ArmName, GoalSet, SetName};
use table::Header;

/// Time the solvers on seeded goal sets for the shipped arms (one thread), optionally beside
/// Orocos KDL.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Goals per set
    #[arg(long, value_name = "N", default_value_t = 1000, value_parser = parse_at_least_one)]
    pub goals: u32,
    /// Benchmark path tracking instead of single goals: `follow`, `plan`, every sample from
    /// scratch, and (with --kdl) KDL's LMA warm-started, on seeded paths for each arm with the
    /// limits off and on
    #[arg(long, conflicts_with_all = ["goals", "sets", "methods", "limit_modes", "write_goals"])]
    pub paths: bool,
    /// Benchmark whole rigs instead of chains: seeded target sets made by forward kinematics of
    /// random configurations inside the limits (the puppet's hands and feet; its hands with its
    /// feet pinned; the hand's fingertips), solved by the library's rig solve, each limb in turn
    /// as a chain, and (with --kdl) KDL's tree solver; --goals target sets per set
    #[arg(long, conflicts_with_all = ["paths", "arms", "sets", "methods", "limit_modes", "write_goals"])]
    pub rigs: bool,
    /// Benchmark the exact reachable region under joint limits instead of solvers: the
    /// verdict's time per point (seed, seven), the region's build time (3, 7 and 8 links),
    /// the verdict against solving over --points random points per arm, and --goals
    /// unreachable goals answered with the verdict and without it
    #[arg(long, conflicts_with_all = ["paths", "rigs", "arms", "sets", "methods", "limit_modes", "write_goals", "kdl"])]
    pub reach: bool,
    /// Benchmark posing the shipped characters instead of solvers: each one's setup pose with
    /// its constraints and its animation (`walk`, else its first) at a time advancing 1/60 s per
    /// pose, by the runtime's rules, --poses times each, one thread
    #[arg(long, conflicts_with_all = ["paths", "rigs", "reach", "goals", "arms", "sets", "methods", "limit_modes", "write_goals", "kdl"])]
    pub characters: bool,
    /// With --characters: timed poses of each kind per character
    #[arg(long, value_name = "N", default_value_t = 10_000, requires = "characters", value_parser = parse_at_least_one)]
    pub poses: u32,
    /// With --reach: random points per arm for the verdict's time and its agreement with solving
    #[arg(long, value_name = "N", default_value_t = 1_000_000, requires = "reach", value_parser = parse_points)]
    pub points: u64,
    /// With --rigs: the rig sets to benchmark
    #[arg(long, value_enum, value_delimiter = ',', value_name = "SET,…", default_values_t = rigs::set::RigSetName::ALL, requires = "rigs")]
    pub rig_sets: Vec<rigs::set::RigSetName>,
    /// With --paths: paths per arm and limits setting
    #[arg(long, value_name = "N", default_value_t = 40, requires = "paths", value_parser = parse_at_least_one)]
    pub path_count: u32,
    /// With --paths: samples per path (at least 3)
    #[arg(long, value_name = "N", default_value_t = 100, requires = "paths", value_parser = parse_samples)]
    pub samples: u32,
    /// With --paths: also show a row per kind of path (JSON always has them)
    #[arg(long, requires = "paths")]
    pub by_kind: bool,
    /// Seed of the goal sets (each set mixes in its arm's and its own name)
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Arms to benchmark
    #[arg(long, value_enum, value_delimiter = ',', value_name = "ARM,…", default_values_t = ArmName::ALL)]
    pub arms: Vec<ArmName>,
    /// Goal sets to benchmark
    #[arg(long, value_enum, value_delimiter = ',', value_name = "SET,…", default_values_t = SetName::ALL)]
    pub sets: Vec<SetName>,
    /// Keep only the rows of these methods (`default`: the library's default options) [default: all]
    #[arg(long, value_delimiter = ',', value_name = "METHOD,…", value_parser = method_names())]
    pub methods: Option<Vec<String>>,
    /// Keep only the rows with these limit modes (the `default` rows stay) [default: all]
    #[arg(long, value_delimiter = ',', value_name = "MODE,…", value_parser = mode_names())]
    pub limit_modes: Option<Vec<String>>,
    /// Also run KDL's solvers: PATH is the `kdl_bench` program (`bash bench/kdl/build` builds
    /// target/kdl/kdl_bench)
    #[arg(long, value_name = "PATH")]
    pub kdl: Option<PathBuf>,
    /// Output JSON: a header object and an array of rows
    #[arg(long, conflicts_with = "markdown")]
    pub json: bool,
    /// Output a Markdown table, headed by the command line
    #[arg(long)]
    pub markdown: bool,
    /// Also write each set's goal file (the format of bench/kdl/README.md) into DIR, an
    /// existing directory, as ARM-SET.goals
    #[arg(long, value_name = "DIR")]
    pub write_goals: Option<PathBuf>,
}

/// `--samples`: a whole number, at least 3 (a jerk needs four samples, a step two).
fn parse_samples(s: &str) -> Result<u32, String> {
    let v: u32 = s.trim().parse().map_err(|_| format!("'{s}' is not a whole number"))?;
    if v < 3 { Err(format!("{v}: must be at least 3")) } else { Ok(v) }
}

/// `--points`: a whole number, at least 1.
fn parse_points(s: &str) -> Result<u64, String> {
    let v: u64 = s.trim().parse().map_err(|_| format!("'{s}' is not a whole number"))?;
    if v < 1 { Err(format!("{v}: must be at least 1")) } else { Ok(v) }
}

/// `--methods` accepts every method's name and `default`.
fn method_names() -> PossibleValuesParser {
    PossibleValuesParser::new(Method::ALL.iter().map(|m| m.name()).chain(["default"]))
}

/// `--limit-modes` accepts every limit mode's name.
fn mode_names() -> PossibleValuesParser {
    PossibleValuesParser::new(LimitMode::ALL.iter().map(|m| m.name()))
}

/// Where `ikarus bench` writes its results: the command line's stdout and its output files.
/// The benchmark itself prints nothing but its progress bar (on stderr, when that is a
/// terminal).
pub trait Sink {
    /// Runs `write` against stdout.
    fn stdout(&self, write: &mut dyn FnMut(&mut dyn Write) -> io::Result<()>) -> Result<(), Error>;
    /// Writes every `(path, text)` of `files`, each whole or not at all, every file created
    /// before any is written; `flag` names the option in messages.
    fn files(&self, flag: &'static str, files: &[(PathBuf, String)]) -> Result<(), Error>;
}

/// Runs `ikarus bench`, writing its results to `sink`.
pub fn run(args: &BenchArgs, sink: &dyn Sink) -> Result<(), Error> {
    if args.paths {
        return paths::run(args, sink);
    }
    if args.rigs {
        return rigs::run(args, sink);
    }
    if args.reach {
        return reach::run(args, sink);
    }
    if args.characters {
        return characters::run(args, sink);
    }
    // Everything that can be checked is checked before the (long) work starts.
    if let Some(path) = &args.kdl {
        kdl::check(path)?;
    }
    if let Some(dir) = &args.write_goals {
        check_dir(dir)?;
    }
    let arms = unique(&args.arms);
    let set_names = unique(&args.sets);
    let configs = run::configs();
    let plan = plan(args, &arms, &set_names, &configs)?;
    if let Some(dir) = &args.write_goals {
        write_goal_files(args, dir, &plan, sink)?;
    }

    let total: u64 = plan.iter().map(|(set, rows)| (set.goals.len() * rows.len()) as u64).sum();
    let progress = progress_bar(total);
    // KDL first: a broken --kdl is reported in seconds, not after the whole benchmark.
    let (kdl_version, kdl_rows) = match &args.kdl {
        Some(path) => run_kdl(args, path, &plan, progress.as_ref())?,
        None => (None, Vec::new()),
    };
    let rows = run_rows(&plan, kdl_rows, progress.as_ref());
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }

    let header = header(args, &arms, &set_names, kdl_version);
    sink.stdout(&mut |w| {
        if args.json {
            table::json(w, &header, &rows)
        } else if args.markdown {
            table::markdown(w, &header, &rows)
        } else {
            table::text(w, &header, &rows)
        }
    })
}

/// One goal set and the rows run on it.
type Planned<'c> = (GoalSet, Vec<&'c Config>);

/// Every goal set of the chosen arms and sets, each with the rows that apply to it and pass
/// the filters. Refused when no row is left and KDL is not run.
fn plan<'c>(
    args: &BenchArgs,
    arms: &[ArmName],
    set_names: &[SetName],
    configs: &'c [Config],
) -> Result<Vec<Planned<'c>>, Error> {
    let filter = Filter { methods: args.methods.clone(), modes: args.limit_modes.clone() };
    let mut plan: Vec<Planned<'c>> = Vec::new();
    for &arm in arms {
        let chain = arm.load()?.chain;
        for &set in set_names {
            let goal_set = sets::generate(arm.name(), &chain, set, args.goals as usize, args.seed);
            let rows = configs.iter().filter(|c| c.applies_to(&goal_set) && filter.keeps(c)).collect();
            plan.push((goal_set, rows));
        }
    }
    if args.kdl.is_none() && plan.iter().all(|(_, rows)| rows.is_empty()) {
        let mut flags = Vec::new();
        if let Some(m) = &args.methods {
            flags.push(format!("--methods {}", m.join(",")));
        }
        if let Some(m) = &args.limit_modes {
            flags.push(format!("--limit-modes {}", m.join(",")));
        }
        return Err(Error::input(format!("{}: no benchmark row matches on the sets chosen", flags.join(" "))));
    }
    Ok(plan)
}

/// The comment line of `set`'s goal file: what wrote it.
fn goal_file_comment(args: &BenchArgs, set: &GoalSet) -> String {
    format!(
        "written by ikarus {} bench --seed {} --goals {}: arm {}, set {}",
        env!("CARGO_PKG_VERSION"),
        args.seed,
        args.goals,
        set.arm,
        set.set.name()
    )
}

/// `--write-goals DIR`: every set's goal file, written by `sink` (every file created before
/// any is written).
fn write_goal_files(args: &BenchArgs, dir: &Path, plan: &[Planned], sink: &dyn Sink) -> Result<(), Error> {
    let files: Vec<(PathBuf, String)> = plan
        .iter()
        .map(|(set, _)| (dir.join(format!("{}.goals", set.name())), kdl::goal_file(set, &goal_file_comment(args, set))))
        .collect();
    sink.files("--write-goals", &files)
}

/// `--kdl PATH`: KDL's rows of every set, and the version `kdl_bench` reported.
fn run_kdl(
    args: &BenchArgs,
    path: &Path,
    plan: &[Planned],
    progress: Option<&ProgressBar>,
) -> Result<(Option<String>, Vec<Vec<RowResult>>), Error> {
    let dir = tempfile::tempdir().map_err(|e| {
        Error::runtime(format!("--kdl {}: cannot make a temporary directory: {}", path.display(), io_reason(&e)))
    })?;
    let mut version = None;
    let mut rows = Vec::new();
    for (set, _) in plan {
        if let Some(bar) = progress {
            bar.set_message(format!("kdl {}", set.name()));
        }
        let result = kdl::run(path, set, dir.path(), &goal_file_comment(args, set))?;
        version.get_or_insert_with(|| result.version.clone());
        rows.push(result.rows(set));
    }
    Ok((version, rows))
}

/// Times every row of the plan, set by set; KDL's rows of a set (`kdl_rows`, one entry per
/// set, or none) follow the set's ikarus rows, and every row of the set gets its speed
/// relative to KDL's LMA.
fn run_rows(plan: &[Planned], mut kdl_rows: Vec<Vec<RowResult>>, progress: Option<&ProgressBar>) -> Vec<RowResult> {
    let mut rows = Vec::new();
    for (k, (set, configs)) in plan.iter().enumerate() {
        let start = rows.len();
        for config in configs {
            if let Some(bar) = progress {
                bar.set_message(format!("{} {}", set.name(), config.label));
            }
            let mut row = run::run_config(set, config, || {
                if let Some(bar) = progress {
                    bar.inc(1);
                }
            });
            if config.method == "default" {
                if let Some(bar) = progress {
                    bar.set_message(format!("{} {} batched", set.name(), config.label));
                }
                row.batch = Some(batch::run(set, &config.options, &row.reached_each));
            }
            rows.push(row);
        }
        if let Some(extra) = kdl_rows.get_mut(k) {
            rows.append(extra);
            let lma = rows[start..].iter().find(|r| r.label == kdl::LMA_LABEL).map(|r| r.median_us);
            for r in &mut rows[start..] {
                r.vs_kdl_lma = lma.map(|m| m / r.median_us);
            }
        }
    }
    rows
}

/// What the output says about the run as a whole.
fn header(args: &BenchArgs, arms: &[ArmName], set_names: &[SetName], kdl_version: Option<String>) -> Header {
    let opts = SolveOptions::default();
    let goals = args.goals as usize;
    Header {
        command: command_line(),
        ikarus_version: env!("CARGO_PKG_VERSION"),
        kdl_version,
        goals,
        seed: args.seed,
        arms: arms.iter().map(|a| a.name()).collect(),
        sets: set_names.iter().map(|s| s.name()).collect(),
        tolerance: opts.tolerance,
        angle_tolerance: opts.angle_tolerance,
        max_iterations: opts.max_iterations,
        warmup_goals: run::WARMUP_GOALS.min(goals),
        threads: 1,
        cpus: std::thread::available_parallelism().map_or(1, usize::from),
        os: std::env::consts::OS,
        arch: std::env::consts::ARCH,
        debug_build: cfg!(debug_assertions),
    }
}

/// `--write-goals DIR` must be an existing directory (bad input, exit 2, otherwise); whether
/// files can be created in it shows when they are (exit 1, as for every output file).
fn check_dir(dir: &Path) -> Result<(), Error> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => Ok(()),
        Ok(_) => Err(Error::input(format!("--write-goals {}: not a directory", dir.display()))),
        Err(e) => Err(Error::input(format!("--write-goals {}: {}", dir.display(), io_reason(&e)))),
    }
}

/// `items` without repetitions, in their first order.
fn unique<T: Copy + PartialEq>(items: &[T]) -> Vec<T> {
    let mut out: Vec<T> = Vec::with_capacity(items.len());
    for &i in items {
        if !out.contains(&i) {
            out.push(i);
        }
    }
    out
}

/// A progress bar over `total` solves, on stderr, only when stderr is a terminal.
fn progress_bar(total: u64) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() || total == 0 {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{spinner} [{bar:25}] {pos}/{len} solves, {eta} left: {wide_msg}")
            .expect("static template")
            .progress_chars("=> "),
    );
    Some(bar)
}

/// The command line as `ikarus bench …`, each argument quoted for a POSIX shell if needed.
fn command_line() -> String {
    let mut parts = vec!["ikarus".to_owned()];
    parts.extend(std::env::args().skip(1).map(|a| shell_quote(&a)));
    parts.join(" ")
}

/// `arg`, single-quoted unless it consists only of characters a shell leaves alone.
fn shell_quote(arg: &str) -> String {
    let plain = !arg.is_empty() && arg.chars().all(|c| c.is_ascii_alphanumeric() || "-_./,=:+@%".contains(c));
    if plain { arg.to_owned() } else { format!("'{}'", arg.replace('\'', r"'\''")) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_are_quoted_for_the_shell() {
        assert_eq!(shell_quote("--goals"), "--goals");
        assert_eq!(shell_quote("seed,seven"), "seed,seven");
        assert_eq!(shell_quote("a b"), "'a b'");
        assert_eq!(shell_quote("it's"), r"'it'\''s'");
        assert_eq!(shell_quote(""), "''");
    }

    #[test]
    fn repetitions_are_dropped() {
        assert_eq!(unique(&[3, 1, 3, 2, 1]), [3, 1, 2]);
    }
}
