//! `ikarus solve`: one goal (JSON, CSV or text), or a batch of goals from a CSV file; with
//! `--rig`, goals on a rig's bones ([`crate::rig_solve`]).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Args, ValueEnum};
use ikarus::{Goal, Outcome, SolveOptions, Status};

use crate::arm::Arm;
use crate::batch::{BLOCK_GOALS, Batch, Rows, TASK_GOALS};
use crate::error::CliError;
use crate::goals::{self, Goals, make_goal};
use crate::options::{parse_angle, parse_at_least_one};
use crate::output;
use crate::picture::{StillArgs, arm_drawing, draw, report_format};
use crate::report::{SolveJson, SolveReport, deg_text};
use crate::rig_args::{GoalArg, RigTaskArgs, parse_goal};
use crate::settings::{SolverFlags, solver};

/// Frames recorded by default: every 20 iterations, as the seed program did.
const DEFAULT_RECORD_EVERY: u32 = 20;

// Floats in CSV are written with `{:?}`: the shortest text that reads back to the same
// number, in scientific notation where that is shorter (1.2e-7, not 0.00000012).

/// Output format of a single solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One JSON object (the default when stdout is not a terminal).
    Json,
    /// The recorded frames, one row each.
    Csv,
    /// A short report for people (the default on a terminal).
    Text,
}

/// Move the arm's tip to a goal and report the pose, or solve a batch of goals; with `--rig`,
/// the same for goals on the tips of a rig's bones, solved together.
#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Goal position of the tip; with --rig, NAME=X,Y[,DEG]: the tip of bone NAME at X,Y (and
    /// pointing DEG degrees from +x), repeatable
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_goal,
          required_unless_present_any = ["batch", "rig"])]
    pub goal: Vec<GoalArg>,
    /// Goal orientation of the last link, degrees from +x (counter-clockwise)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = parse_angle,
          conflicts_with_all = ["batch", "rig"])]
    pub goal_angle: Option<f64>,
    /// Arm file (TOML) [default: the built-in seed arm, lengths 3, 2, 1]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    /// Rig file (TOML): a tree of named bones; its goals (--goal NAME=X,Y) and pins (--pin
    /// NAME) are solved together
    #[arg(long, value_name = "FILE", conflicts_with = "arm")]
    pub rig: Option<PathBuf>,
    #[command(flatten)]
    pub rig_task: RigTaskArgs,
    #[command(flatten)]
    pub solver: SolverFlags,
    /// Record a frame every K iterations, plus the first and the last [default: 20; with
    /// --rig, none]
    #[arg(long, value_name = "K", value_parser = parse_at_least_one)]
    pub record_every: Option<u32>,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out]
    #[arg(long, value_enum, conflicts_with = "batch")]
    pub format: Option<Format>,
    /// Solve every goal of a CSV file (header `x,y` or `x,y,angle_deg`; with --rig, `NAME.x,NAME.y`
    /// and optionally `NAME.angle_deg` per goal) from the start pose; one CSV row per goal (or
    /// target set) on stdout, a summary on stderr
    #[arg(long, value_name = "GOALS.csv", conflicts_with = "goal")]
    pub batch: Option<PathBuf>,
    /// Threads for --batch [default: all cores]
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Also write the batch summary as JSON to PATH
    #[arg(long, value_name = "PATH")]
    pub summary_json: Option<PathBuf>,
    #[command(flatten)]
    pub picture: StillArgs,
}

fn parse_threads(s: &str) -> Result<usize, String> {
    let n = parse_at_least_one(s)? as usize;
    if n > 1024 { Err(format!("{n}: must be at most 1024")) } else { Ok(n) }
}

pub fn run(args: &SolveArgs) -> Result<(), CliError> {
    if args.batch.is_none() {
        if let Some(n) = args.threads {
            return Err(CliError::input(format!("--threads {n}: only applies with --batch")));
        }
        if let Some(p) = &args.summary_json {
            return Err(CliError::input(format!("--summary-json {}: only applies with --batch", p.display())));
        }
    } else if let Some(p) = &args.picture.out {
        return Err(CliError::input(format!("--out {}: only applies to a single solve, not --batch", p.display())));
    }
    if let Some(path) = &args.rig {
        return crate::rig_solve::run(args, path);
    }
    let arm = Arm::load(args.arm.as_deref())?;
    match &args.batch {
        Some(path) => run_batch(args, &arm, path),
        None => run_single(args, &arm),
    }
}

/// The one goal of an arm: `--goal X,Y` given once.
fn arm_goal(args: &SolveArgs) -> Result<Goal, CliError> {
    match &args.goal[..] {
        [GoalArg::Point([x, y])] => make_goal(*x, *y, args.goal_angle).map_err(CliError::input),
        [named @ GoalArg::Named { .. }] => {
            Err(CliError::input(format!("{}: a goal on a named bone needs --rig FILE", named.text())))
        }
        goals => Err(CliError::input(format!(
            "--goal: an arm has one tip, so one --goal X,Y, got {} (several goals need --rig FILE)",
            goals.len()
        ))),
    }
}

fn run_single(args: &SolveArgs, arm: &Arm) -> Result<(), CliError> {
    let goal = arm_goal(args)?;
    let picture = args.picture.prepare()?;
    let every = args.record_every.or(arm.solver.record_every).unwrap_or(DEFAULT_RECORD_EVERY);
    let mut solver = solver(arm.options(&args.solver.settings(), Some(every))?)?;
    let started = Instant::now();
    let outcome =
        solver.solve(&arm.chain, arm.chain.start_pose(), &goal).map_err(|e| CliError::input(e.to_string()))?;
    let micros = started.elapsed().as_secs_f64() * 1e6;
    let report = Report { arm, options: solver.options(), goal: &goal, outcome: &outcome, micros };
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    if let Some(format) = report_format(args.format, picture.is_some(), Format::Text, Format::Json) {
        output::stdout(|w| match format {
            Format::Json => {
                serde_json::to_writer_pretty(&mut *w, &report.json())?;
                writeln!(w)
            }
            Format::Csv => report.csv(w),
            Format::Text => report.text(w),
        })?;
    }
    if let Some(out) = picture {
        let drawing = arm_drawing(arm, outcome.pose.angles(), Some(goal.target()), None);
        let bytes = draw(&drawing, out.format, args.picture.width, args.picture.height, &|_, _| {})?;
        out.commit(&bytes)?;
    }
    Ok(())
}

/// A finished single solve and what it needs to be described.
struct Report<'a> {
    arm: &'a Arm,
    options: &'a SolveOptions,
    goal: &'a Goal,
    outcome: &'a Outcome,
    micros: f64,
}

impl Report<'_> {
    fn json(&self) -> SolveJson<'_> {
        SolveReport {
            arm: self.arm,
            options: self.options,
            goal: self.goal,
            outcome: self.outcome,
            micros: self.micros,
        }
        .json()
    }

    fn csv(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let n = self.arm.chain.len();
        let mut header = vec!["iteration".to_owned()];
        header.extend((1..=n).map(|i| format!("theta{i}_deg")));
        for k in 0..=n {
            header.push(format!("x{k}"));
            header.push(format!("y{k}"));
        }
        writeln!(w, "{}", header.join(","))?;
        for f in self.outcome.frames.iter() {
            write!(w, "{}", f.iteration)?;
            for a in f.angles {
                write!(w, ",{:?}", a.to_degrees())?;
            }
            for p in f.joints {
                write!(w, ",{:?},{:?}", p.x, p.y)?;
            }
            writeln!(w)?;
        }
        Ok(())
    }

    fn text(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let o = self.outcome;
        let opts = self.options;
        let target = self.goal.target();
        let goal_angle = self.goal.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
        let limits = match (opts.limits, self.arm.chain.has_limits()) {
            (ikarus::LimitMode::Ignore, true) => "off (the arm has ranges: --limits enforces them)".to_owned(),
            (ikarus::LimitMode::Ignore, false) => "off".to_owned(),
            (mode, _) => format!("on ({})", mode.name()),
        };
        writeln!(
            w,
            "arm       {} ({} links, reach {})",
            self.arm.name,
            self.arm.chain.len(),
            self.arm.chain.max_reach()
        )?;
        writeln!(w, "goal      ({}, {}){goal_angle}", target.x, target.y)?;
        writeln!(w, "method    {}   limits {limits}", opts.method.name())?;
        let restarts = match o.restarts {
            0 => String::new(),
            1 => ", 1 restart".to_owned(),
            k => format!(", {k} restarts"),
        };
        match o.reach_distance {
            Some(d) if o.status == ikarus::Status::Unreachable && d > 0.0 => writeln!(
                w,
                "status    unreachable: {d:.6} outside the reachable region, the tip at its nearest point ({:.1} µs)",
                self.micros
            )?,
            _ => writeln!(
                w,
                "status    {} after {} iterations{restarts} ({:.1} µs)",
                o.status, o.iterations, self.micros
            )?,
        }
        write!(w, "error     {:.3e} (tolerance {:e})", o.error, opts.tolerance)?;
        if self.goal.orientation().is_some() {
            write!(w, ", orientation {:.3e}°", o.angle_error.to_degrees())?;
        }
        writeln!(w)?;
        let tip = o.end_effector;
        writeln!(
            w,
            "tip       ({:.6}, {:.6}) pointing {}",
            tip.position.x,
            tip.position.y,
            deg_text(tip.orientation, 3)
        )?;
        let angles: Vec<String> = o.pose.angles().iter().map(|&a| deg_text(a, 3)).collect();
        writeln!(w, "angles    {}", angles.join(", "))?;
        let joints = ikarus::kinematics::joint_positions(&self.arm.chain, o.pose.angles());
        let joints: Vec<String> = joints.iter().map(|p| format!("({:.3}, {:.3})", p.x, p.y)).collect();
        writeln!(w, "joints    {}", joints.join(" → "))?;
        if let Some(k) = opts.record_every {
            writeln!(
                w,
                "frames    {} recorded (every {k} iterations; --format json or csv lists them)",
                o.frames.len()
            )?;
        }
        Ok(())
    }
}

fn run_batch(args: &SolveArgs, arm: &Arm, path: &Path) -> Result<(), CliError> {
    // The threads first, to parse the goals on; then the errors in the order of the work: the
    // goals, the options, the summary file.
    let mut batch = Batch::threads(args.threads)?;
    let label = format!("batch file {}", path.display());
    let pieces = batch.install(|| goals::read_pieces(path, &label))?;
    if pieces.iter().all(|p| p.goals.is_empty()) {
        return Err(CliError::input(format!("{label}: no goals (expected a header and one goal per row)")));
    }
    let solver = solver(arm.options(&args.solver.settings(), None)?)?;
    batch.summary_json(args.summary_json.as_deref())?;
    let chain = &arm.chain;
    let start = chain.start_pose().angles();
    // What can fail in a solve (the start pose, the options) fails here, before any row.
    solver.clone().solve_batch(chain, start, &[], &mut Vec::new()).map_err(|e| CliError::input(e.to_string()))?;
    let thetas: Vec<String> = (1..=chain.len()).map(|i| format!("theta{i}_deg")).collect();
    let header = format!("x,y,status,error,iterations,{}\n", thetas.join(","));
    let stdout = std::io::stdout();
    // Tasks of at most TASK_GOALS goals, each within one piece of the file.
    let tasks: Vec<(&[[f64; 2]], &[Goal])> =
        pieces.iter().flat_map(|p: &Goals| p.xy.chunks(TASK_GOALS).zip(p.goals.chunks(TASK_GOALS))).collect();
    let tally = batch.solve_blocks(
        tasks.len(),
        |t| tasks[t].1.len(),
        || (solver.clone(), Vec::<Outcome>::with_capacity(BLOCK_GOALS)),
        |(solver, out), t, block| {
            solver.solve_batch(chain, start, &tasks[t].1[block], out)?;
            Ok::<_, ikarus::SolveError>(out.iter().filter(|o| o.status == Status::Reached).count())
        },
        |(_, out), t, block, buf| {
            for ([x, y], o) in tasks[t].0[block].iter().zip(out.iter()) {
                row(buf, *x, *y, o);
            }
        },
        Rows { header: header.as_bytes(), out: &mut std::io::BufWriter::new(stdout.lock()) },
    )?;
    batch.finish(tally, solver.options().method.name())
}

/// Appends the CSV row of the goal at `(x, y)` solved as `o`:
/// `x,y,status,error,iterations,theta1_deg…`, floats as `{:?}` writes them.
fn row(buf: &mut Vec<u8>, x: f64, y: f64, o: &Outcome) {
    output::push_f64(buf, x);
    buf.push(b',');
    output::push_f64(buf, y);
    buf.push(b',');
    buf.extend_from_slice(o.status.as_str().as_bytes());
    buf.push(b',');
    output::push_f64(buf, o.error);
    buf.push(b',');
    let _ = write!(buf, "{}", o.iterations);
    for a in o.pose.angles() {
        buf.push(b',');
        output::push_f64(buf, a.to_degrees());
    }
    buf.push(b'\n');
}
