//! `ikarus solve`: one goal (JSON, CSV or text), or a batch of goals from a CSV file; with
//! `--rig FILE`, goals on the tips of a rig's bones and pins, solved together from the rig's
//! start pose, or a batch of target sets. One command, one reader of the body ([`Body`]).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Args, ValueEnum};
use ikarus::{Goal, LimitMode, Outcome, RigTask, SolveOptions, Status};

use crate::arm::Arm;
use crate::batch::{BLOCK_GOALS, Batch, Rows, TASK_GOALS};
use crate::body::Body;
use crate::error::CliError;
use crate::goal;
use crate::goal_args::{GoalArg, RigTaskArgs, Target, parse_goal};
use crate::goals::{self, Goals, make_goal};
use crate::options::{parse_angle, parse_at_least_one, parse_finite};
use crate::output;
use crate::picture::{Drawing, StillArgs, arm_drawing, draw, report_format, rig_figure};
use crate::report::RigSolveReport;
use crate::report::{SolveJson, SolveReport, deg_text};
use crate::rig::Rig;
use crate::settings::{DEFAULT_RECORD_EVERY, SolverFlags, solver};

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
    match (Body::load(args.arm.as_deref(), args.rig.as_deref())?, &args.batch) {
        (Body::Chain(arm), Some(path)) => run_batch(args, &arm, path),
        (Body::Chain(arm), None) => run_single(args, &arm),
        (Body::Rig(rig), Some(path)) => run_rig_batch(args, &rig, path),
        (Body::Rig(rig), None) => run_rig_single(args, &rig),
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

// A rig: goals on the tips of its bones and pins, solved together (`--rig FILE`).

/// A rig's goals (`--goal NAME=X,Y`) and pins, solved together from its start pose.
fn run_rig_single(args: &SolveArgs, rig: &Rig) -> Result<(), CliError> {
    let mut targets = args.goal.iter().map(|g| Target::of(g, rig)).collect::<Result<Vec<_>, _>>()?;
    // `--goal-angle` (an arm file's rig: a rig file's is refused by the flags) is the tip's.
    for t in targets.iter_mut().filter(|_| args.goal_angle.is_some()) {
        t.angle_deg = args.goal_angle;
    }
    let task = args.rig_task.task(&rig.skeleton, &targets)?;
    // No frames unless asked for: a rig's frames are one point per bone each.
    let every = args.record_every.or(rig.solver.record_every);
    let mut solver = solver(rig.options(&args.solver.settings(), every)?)?;
    let picture = args.picture.prepare()?;
    let started = Instant::now();
    let outcome = solver
        .solve_rig(&rig.skeleton, rig.skeleton.start_angles(), &task)
        .map_err(|e| CliError::input(e.to_string()))?;
    let micros = started.elapsed().as_secs_f64() * 1e6;
    let options = solver.options();
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    if let Some(format) = report_format(args.format, picture.is_some(), Format::Text, Format::Json) {
        output::stdout(|w| match format {
            Format::Json => {
                let report = RigSolveReport { rig, options, outcome: &outcome, micros };
                serde_json::to_writer_pretty(&mut *w, &report.json())?;
                writeln!(w)
            }
            Format::Csv => rig_csv(w, rig, &outcome),
            Format::Text => rig_text(w, rig, &task, options, &outcome, micros),
        })?;
    }
    if let Some(out) = picture {
        let caption = format!("{} · {} after {} iterations", rig.name, outcome.status, outcome.iterations);
        let figure = rig_figure(rig, outcome.pose.angles(), &task, options.limits != LimitMode::Ignore, Some(caption));
        let bytes = draw(&Drawing::Skeleton(figure), out.format, args.picture.width, args.picture.height, &|_, _| {})?;
        out.commit(&bytes)?;
    }
    Ok(())
}

/// The CSV header of a rig's pose: `NAME_deg` per bone, then `NAME_ext` per prismatic bone,
/// in the rig's order ([`crate::report::pose_columns`]).
pub fn angle_columns(rig: &Rig) -> String {
    crate::report::pose_columns(&rig.skeleton).join(",")
}

/// `,value` for every column of [`angle_columns`] at joint values `q`.
pub fn write_pose(w: &mut dyn Write, rig: &Rig, q: &[f64]) -> std::io::Result<()> {
    for v in crate::report::pose_values(&rig.skeleton, q) {
        write!(w, ",{v:?}")?;
    }
    Ok(())
}

/// One row: `status,iterations,error` and every bone's angle (then every prismatic bone's
/// displacement).
fn rig_csv(w: &mut dyn Write, rig: &Rig, o: &Outcome) -> std::io::Result<()> {
    writeln!(w, "status,iterations,error,{}", angle_columns(rig))?;
    write!(w, "{},{},{:?}", o.status, o.iterations, o.error)?;
    write_pose(w, rig, o.pose.angles())?;
    writeln!(w)
}

/// A report for people: the rig, the solve, one line per effector, the angles.
fn rig_text(
    w: &mut dyn Write,
    rig: &Rig,
    task: &RigTask,
    opts: &SolveOptions,
    o: &Outcome,
    micros: f64,
) -> std::io::Result<()> {
    let s = &rig.skeleton;
    let limits = match (opts.limits, s.has_limits()) {
        (LimitMode::Ignore, true) => "off (the rig has ranges: --limits enforces them)".to_owned(),
        (LimitMode::Ignore, false) => "off".to_owned(),
        (mode, _) => format!("on ({})", mode.name()),
    };
    writeln!(w, "rig       {} ({} bones)", rig.name, s.len())?;
    writeln!(w, "method    {}   limits {limits}", opts.method.name())?;
    if task.mix < 1.0 {
        writeln!(w, "mix       {} of the way from the start pose to the solution", task.mix)?;
    }
    let restarts = match o.restarts {
        0 => String::new(),
        1 => ", 1 restart".to_owned(),
        k => format!(", {k} restarts"),
    };
    writeln!(w, "status    {} after {} iterations{restarts} ({micros:.1} µs)", o.status, o.iterations)?;
    writeln!(w, "error     {:.3e} (the largest; tolerance {:e})", o.error, opts.tolerance)?;
    let width = o.effectors.iter().map(|e| s.name(e.bone).chars().count()).max().unwrap_or(0);
    for (k, e) in o.effectors.iter().enumerate() {
        let what = if e.pinned {
            "pinned".to_owned()
        } else {
            let g = &task.goals[k].goal;
            let t = g.target();
            let angle = g.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
            format!("goal ({}, {}){angle}", t.x, t.y)
        };
        let mut line = format!(
            "  {:width$}  {what}: {} · error {:.3e} · tip ({:.6}, {:.6})",
            s.name(e.bone),
            e.status,
            e.error,
            e.tip.x,
            e.tip.y
        );
        if e.pinned || task.goals[k].goal.orientation().is_some() {
            line.push_str(&format!(" pointing {}", deg_text(e.orientation, 3)));
        }
        writeln!(w, "{}", line.trim_end())?;
    }
    let angles: Vec<String> =
        s.names().iter().zip(o.pose.angles()).map(|(n, &a)| format!("{n} {}", deg_text(a, 3))).collect();
    writeln!(w, "angles    {}", angles.join(", "))?;
    if let Some(k) = opts.record_every {
        writeln!(w, "frames    {} recorded (every {k} iterations; --format json lists them)", o.frames.len())?;
    }
    Ok(())
}

// A rig's batch (`--rig FILE --batch GOALS.csv`): one target set per row, each solved from the
// rig's start pose (the `--pin`s and the per-goal flags apply to every row); one CSV row per set
// on stdout, the batch summary on stderr (shared with an arm's batch, [`crate::batch`]).
//
// The header names the goals: `NAME.x,NAME.y`, and optionally `NAME.angle_deg`, per goal bone,
// in any order. A header is split at its last `.`, since bone names may hold dots (`arm.l.x` is
// the x of bone `arm.l`).

/// Which coordinate of a goal a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    X,
    Y,
    Angle,
}

/// The columns of one goal: where its x, y and angle are in a row.
#[derive(Debug, Clone, PartialEq)]
struct GoalColumns {
    bone: String,
    x: usize,
    y: usize,
    angle: Option<usize>,
}

/// A header cell `NAME.x`, `NAME.y` or `NAME.angle_deg`, split at the last `.`.
fn split(cell: &str) -> Option<(&str, Part)> {
    let (name, part) = cell.rsplit_once('.')?;
    let part = match part {
        "x" => Part::X,
        "y" => Part::Y,
        "angle_deg" => Part::Angle,
        _ => return None,
    };
    (!name.is_empty()).then_some((name, part))
}

/// The goals a header names, in the order of their first column; problems name the column.
fn goal_columns(rig: &Rig, cells: &[&str], label: &str) -> Result<Vec<GoalColumns>, CliError> {
    let column = |i: usize| format!("{label}: line 1: column {} `{}`", i + 1, cells[i]);
    let mut found: Vec<(String, [Option<usize>; 3])> = Vec::new();
    for (i, cell) in cells.iter().enumerate() {
        let Some((name, part)) = split(cell) else {
            return Err(CliError::input(format!(
                "{}: expected NAME.x, NAME.y or NAME.angle_deg (NAME a bone of the rig)",
                column(i)
            )));
        };
        goal::index(&rig.skeleton, name).map_err(|m| CliError::input(format!("{}: {m}", column(i))))?;
        let k = match found.iter().position(|(n, _)| n == name) {
            Some(k) => k,
            None => {
                found.push((name.to_owned(), [None; 3]));
                found.len() - 1
            }
        };
        let slot = &mut found[k].1[part as usize];
        if let Some(first) = *slot {
            return Err(CliError::input(format!("{}: the same as column {}", column(i), first + 1)));
        }
        *slot = Some(i);
    }
    found
        .into_iter()
        .map(|(bone, [x, y, angle])| match (x, y) {
            (Some(x), Some(y)) => Ok(GoalColumns { bone, x, y, angle }),
            _ => {
                let given = [x, y, angle].into_iter().flatten().min().expect("a goal is found by one of its columns");
                let missing = if x.is_none() { "x" } else { "y" };
                Err(CliError::input(format!("{}: no `{bone}.{missing}` column", column(given))))
            }
        })
        .collect()
}

fn run_rig_batch(args: &SolveArgs, rig: &Rig, path: &Path) -> Result<(), CliError> {
    let label = format!("batch file {}", path.display());
    let bytes = crate::input::read(path, &label)?;
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(bytes.as_slice());
    let header = reader.headers().map_err(|e| CliError::input(format!("{label}: {e}")))?.clone();
    let cells: Vec<&str> = header.iter().collect();
    let columns = goal_columns(rig, &cells, &label)?;
    if columns.is_empty() {
        return Err(CliError::input(format!(
            "{label}: line 1: no goal columns (expected NAME.x,NAME.y for each goal bone)"
        )));
    }
    // The task's shape (bones, pins, controls) is checked once, with the columns as sources;
    // each row then only replaces the targets.
    let targets: Vec<Target> = columns
        .iter()
        .map(|c| Target {
            bone: c.bone.clone(),
            x: 0.0,
            y: 0.0,
            angle_deg: c.angle.map(|_| 0.0),
            source: format!("{label}: column {} `{}`", c.x + 1, cells[c.x]),
        })
        .collect();
    let template = args.rig_task.task(&rig.skeleton, &targets)?;

    // Each row's values, checked as targets here (so that a bad one is named by its line); each
    // worker fills its own copy of the task with a row's targets.
    let targets = |task: &mut RigTask, values: &[f64]| -> Result<(), (String, String)> {
        for (goal, c) in task.goals.iter_mut().zip(&columns) {
            goal.goal =
                make_goal(values[c.x], values[c.y], c.angle.map(|a| values[a])).map_err(|m| (c.bone.clone(), m))?;
        }
        Ok(())
    };
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut check = template.clone();
    for record in reader.records() {
        let record = record.map_err(|e| CliError::input(format!("{label}: {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let values = (0..cells.len())
            .map(|i| {
                parse_finite(&record[i])
                    .map_err(|m| CliError::input(format!("{label}: line {line}: {}: {m}", cells[i])))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        targets(&mut check, &values)
            .map_err(|(bone, m)| CliError::input(format!("{label}: line {line}: {bone}: {m}")))?;
        rows.push(values);
    }
    if rows.is_empty() {
        return Err(CliError::input(format!("{label}: no target sets (expected a header and one target set per row)")));
    }

    let solver = solver(rig.options(&args.solver.settings(), None)?)?;
    let batch = Batch::new(args.threads, args.summary_json.as_deref())?;
    let skeleton = &rig.skeleton;
    let (solved, tally) = batch.solve_all(
        &rows,
        || (solver.clone(), Outcome::default(), template.clone()),
        |(solver, out, task), values| {
            targets(task, values).map_err(|(bone, m)| format!("{bone}: {m}"))?;
            solver.solve_rig_into(skeleton, skeleton.start_angles(), task, out).map_err(|e| e.to_string())?;
            Ok::<_, String>((out.status, (out.error, out.iterations, out.pose.angles().to_vec())))
        },
    )?;
    output::stdout(|w| {
        writeln!(w, "{},status,error,iterations,{}", cells.join(","), angle_columns(rig))?;
        for (values, r) in rows.iter().zip(&solved) {
            let (error, iterations, angles) = &r.row;
            let values: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
            write!(w, "{},{},{:?},{}", values.join(","), r.status, error, iterations)?;
            write_pose(w, rig, angles)?;
            writeln!(w)?;
        }
        Ok(())
    })?;
    batch.finish(tally, solver.options().method.name())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rig() -> Rig {
        Rig::parse(
            "[[bones]]\nname = \"trunk\"\nlength = 1\nangle_deg = 90\n\
             [[bones]]\nname = \"arm.l\"\nparent = \"trunk\"\nlength = 1\n\
             [[bones]]\nname = \"arm.r\"\nparent = \"trunk\"\nlength = 1\n",
            "r",
        )
        .unwrap()
    }

    #[test]
    fn headers_split_at_the_last_dot() {
        assert_eq!(split("arm.l.x"), Some(("arm.l", Part::X)));
        assert_eq!(split("arm.l.angle_deg"), Some(("arm.l", Part::Angle)));
        assert_eq!(split("arm.l"), None);
        assert_eq!(split(".x"), None);
        let cols = goal_columns(&rig(), &["arm.l.y", "arm.r.x", "arm.l.x", "arm.r.y", "arm.l.angle_deg"], "b").unwrap();
        assert_eq!(
            cols,
            vec![
                GoalColumns { bone: "arm.l".into(), x: 2, y: 0, angle: Some(4) },
                GoalColumns { bone: "arm.r".into(), x: 1, y: 3, angle: None },
            ]
        );
    }

    #[test]
    fn header_problems_name_the_column() {
        let cases: [(&[&str], &str); 5] = [
            (&["arm.l.x", "arm.l.z"], "b: line 1: column 2 `arm.l.z`: expected NAME.x, NAME.y or NAME.angle_deg"),
            (&["arm.x", "arm.y"], "b: line 1: column 1 `arm.x`: no bone named \"arm\" in the rig"),
            (&["arm.l.x", "arm.l.y", "arm.l.x"], "b: line 1: column 3 `arm.l.x`: the same as column 1"),
            (&["arm.l.x", "arm.r.y", "arm.r.x"], "b: line 1: column 1 `arm.l.x`: no `arm.l.y` column"),
            (&["arm.l.angle_deg", "arm.l.y"], "b: line 1: column 1 `arm.l.angle_deg`: no `arm.l.x` column"),
        ];
        for (cells, want) in cases {
            let e = goal_columns(&rig(), cells, "b").unwrap_err().to_string();
            assert!(e.starts_with(want), "{cells:?}: got {e:?}, want {want:?}");
        }
    }
}
