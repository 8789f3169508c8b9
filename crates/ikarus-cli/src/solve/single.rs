//! The single solve of `ikarus solve`, one workflow over the body: what differs between an arm
//! and a rig (the goal or the task, the solver's entry point, the answers, the picture) is a
//! [`Single`], chosen once.

use std::io::Write;
use std::time::Instant;

use ikarus::{Goal, LimitMode, Outcome, RigTask, SolveOptions, Solver};

use super::write::{ChainReport, rig_csv, rig_text};
use super::{Format, SolveArgs};
use crate::arm::Arm;
use crate::body::Body;
use crate::error::Error;
use crate::goal_args::{GoalArg, Target};
use crate::goals::make_goal;
use crate::output;
use crate::picture::{Drawing, PictureOut, arm_drawing, draw, report_format, rig_figure};
use crate::report::RigSolveReport;
use crate::rig::Rig;
use crate::settings::{DEFAULT_RECORD_EVERY, solver};

/// What a single solve asks of its body.
enum Single<'a> {
    /// An arm's one goal (`--goal X,Y`, `--goal-angle`).
    Chain { arm: &'a Arm, goal: Goal },
    /// A rig's goals on named bones and pins, solved together from its start pose.
    Rig { rig: &'a Rig, task: RigTask },
}

/// Solves the goal(s) of the flags on `body` and writes the answer (and the picture of
/// `--out`). The checks come in each body's order: an arm's goal, the picture, the options; a
/// rig's goals, the options, the picture.
pub(super) fn run(args: &SolveArgs, body: &Body) -> Result<(), Error> {
    let (job, mut solver, picture) = match body {
        Body::Chain(arm) => {
            let goal = arm_goal(args)?;
            let picture = args.picture.prepare()?;
            let every = args.record_every.or(arm.solver.record_every).unwrap_or(DEFAULT_RECORD_EVERY);
            let solver = solver(arm.options(&args.body.solver.settings(), Some(every))?)?;
            (Single::Chain { arm, goal }, solver, picture)
        }
        Body::Rig(rig) => {
            let mut targets = args.goal.iter().map(|g| Target::of(g, rig)).collect::<Result<Vec<_>, _>>()?;
            // `--goal-angle` (an arm file's rig: a rig file's is refused by the flags) is the tip's.
            for t in targets.iter_mut().filter(|_| args.goal_angle.is_some()) {
                t.angle_deg = args.goal_angle;
            }
            let task = args.body.rig_task.task(&rig.skeleton, &targets)?;
            // No frames unless asked for: a rig's frames are one point per bone each.
            let every = args.record_every.or(rig.solver.record_every);
            let solver = solver(rig.options(&args.body.solver.settings(), every)?)?;
            (Single::Rig { rig, task }, solver, args.picture.prepare()?)
        }
    };
    let started = Instant::now();
    let outcome = job.solve(&mut solver)?;
    let micros = started.elapsed().as_secs_f64() * 1e6;
    let options = solver.options();
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    if let Some(format) = report_format(args.format, picture.is_some(), Format::Text, Format::Json) {
        output::stdout(|w| job.write(w, format, options, &outcome, micros))?;
    }
    if let Some(out) = picture {
        draw_picture(&job.drawing(options, &outcome), out, args)?;
    }
    Ok(())
}

/// Draws `drawing` into the prepared `--out` file.
fn draw_picture(drawing: &Drawing, out: PictureOut, args: &SolveArgs) -> Result<(), Error> {
    let bytes = draw(drawing, out.format, args.picture.size.width, args.picture.size.height, &|_, _| {})?;
    out.commit(&bytes)
}

impl Single<'_> {
    /// The solve from the body's start pose; a refusal of the solver as its one line.
    fn solve(&self, solver: &mut Solver) -> Result<Outcome, Error> {
        let solved = match self {
            Single::Chain { arm, goal } => solver.solve(&arm.chain, arm.chain.start_pose(), goal),
            Single::Rig { rig, task } => solver.solve_rig(&rig.skeleton, rig.skeleton.start_angles(), task),
        };
        solved.map_err(|e| Error::input(e.to_string()))
    }

    /// The answer in `format`: pretty JSON, the CSV of the frames (a rig's: its pose), or the
    /// text for people.
    fn write(
        &self,
        w: &mut dyn Write,
        format: Format,
        options: &SolveOptions,
        outcome: &Outcome,
        micros: f64,
    ) -> std::io::Result<()> {
        match (self, format) {
            (Single::Chain { arm, goal }, _) => {
                let report = ChainReport { arm, options, goal, outcome, micros };
                match format {
                    Format::Json => pretty(w, &report.json()),
                    Format::Csv => report.csv(w),
                    Format::Text => report.text(w),
                }
            }
            (Single::Rig { rig, .. }, Format::Json) => {
                pretty(w, &RigSolveReport { body: rig, options, outcome, micros }.json())
            }
            (Single::Rig { rig, .. }, Format::Csv) => rig_csv(w, rig, outcome),
            (Single::Rig { rig, task }, Format::Text) => rig_text(w, rig, task, options, outcome, micros),
        }
    }

    /// The picture of `--out`: the body in the solved pose, its goal(s) marked.
    fn drawing<'o>(&'o self, options: &SolveOptions, outcome: &'o Outcome) -> Drawing<'o> {
        match self {
            Single::Chain { arm, goal } => arm_drawing(arm, outcome.pose.angles(), Some(goal.target()), None),
            Single::Rig { rig, task } => {
                let caption = format!("{} · {} after {} iterations", rig.name, outcome.status, outcome.iterations);
                let ranges = options.limits != LimitMode::Ignore;
                Drawing::Skeleton(rig_figure(rig, outcome.pose.angles(), task, ranges, Some(caption)))
            }
        }
    }
}

/// `value` as pretty JSON and a newline.
fn pretty(w: &mut dyn Write, value: &impl serde::Serialize) -> std::io::Result<()> {
    serde_json::to_writer_pretty(&mut *w, value)?;
    writeln!(w)
}

/// The one goal of an arm: `--goal X,Y` given once.
fn arm_goal(args: &SolveArgs) -> Result<Goal, Error> {
    match &args.goal[..] {
        [GoalArg::Point([x, y])] => make_goal(*x, *y, args.goal_angle),
        [named @ GoalArg::Named { .. }] => {
            Err(Error::input(format!("{}: a goal on a named bone needs --rig FILE", named.text())))
        }
        goals => Err(Error::input(format!(
            "--goal: an arm has one tip, so one --goal X,Y, got {} (several goals need --rig FILE)",
            goals.len()
        ))),
    }
}
