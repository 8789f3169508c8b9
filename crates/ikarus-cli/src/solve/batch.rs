//! The batches of `ikarus solve --batch GOALS.csv`: an arm's goals, solved in blocks by the
//! batch solver (SIMD lanes), one CSV row per goal; a rig's target sets (columns named by
//! [`super::columns`]), one CSV row per set. Both on stdout, the summary on stderr
//! ([`crate::batch`]).

use std::io::Write;
use std::path::Path;

use ikarus::{Goal, Outcome, RigTask, Status};

use super::SolveArgs;
use super::columns::goal_columns;
use super::write::{angle_columns, write_pose};
use crate::arm::Arm;
use crate::batch::{BLOCK_GOALS, Batch, Rows, TASK_GOALS, Tally, time_alone};
use crate::error::Error;
use crate::goal_args::Target;
use crate::goals::{self, Goals, make_goal};
use crate::options::parse_finite;
use crate::output;
use crate::rig::Rig;
use crate::settings::solver;

pub(super) fn run_batch(args: &SolveArgs, arm: &Arm, path: &Path) -> Result<(), Error> {
    // The threads first, to parse the goals on; then the errors in the order of the work: the
    // goals, the options, the summary file.
    let mut batch = Batch::threads(args.threads)?;
    let label = format!("batch file {}", path.display());
    let pieces = batch.install(|| goals::read_pieces(path, &label))?;
    if pieces.iter().all(|p| p.goals.is_empty()) {
        return Err(Error::input(format!("{label}: no goals (expected a header and one goal per row)")));
    }
    let solver = solver(arm.options(&args.body.solver.settings(), None)?)?;
    batch.summary_json(args.summary_json.as_deref())?;
    let chain = &arm.chain;
    let start = chain.start_pose().angles();
    // What can fail in a solve (the start pose, the options) fails here, before any row.
    solver.clone().solve_batch(chain, start, &[], &mut Vec::new()).map_err(|e| Error::input(e.to_string()))?;
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
    // Each goal alone, on this thread (the pool is idle now).
    let goals: Vec<&Goal> = pieces.iter().flat_map(|p| &p.goals).collect();
    let (mut alone, mut outcome) = (solver.clone(), Outcome::default());
    let timed = time_alone(goals.len(), |i| alone.solve_into(chain, start, goals[i], &mut outcome));
    let tally = Tally { alone: timed.map_err(|e| Error::input(e.to_string()))?, ..tally };
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

// A rig's batch (`--rig FILE --batch GOALS.csv`): one target set per row, each solved from the
// rig's start pose (the `--pin`s and the per-goal flags apply to every row); one CSV row per set
// on stdout, the batch summary on stderr (shared with an arm's batch, [`crate::batch`]).
pub(super) fn run_rig_batch(args: &SolveArgs, rig: &Rig, path: &Path) -> Result<(), Error> {
    let label = format!("batch file {}", path.display());
    let bytes = crate::input::read(path, &label)?;
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(bytes.as_slice());
    let header = reader.headers().map_err(|e| Error::input(format!("{label}: {e}")))?.clone();
    let cells: Vec<&str> = header.iter().collect();
    let columns = goal_columns(rig, &cells, &label)?;
    if columns.is_empty() {
        return Err(Error::input(format!(
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
    let template = args.body.rig_task.task(&rig.skeleton, &targets)?;

    // Each row's values, checked as targets here (so that a bad one is named by its line); each
    // worker fills its own copy of the task with a row's targets.
    let targets = |task: &mut RigTask, values: &[f64]| -> Result<(), (String, Error)> {
        for (goal, c) in task.goals.iter_mut().zip(&columns) {
            goal.goal =
                make_goal(values[c.x], values[c.y], c.angle.map(|a| values[a])).map_err(|m| (c.bone.clone(), m))?;
        }
        Ok(())
    };
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut check = template.clone();
    for record in reader.records() {
        let record = record.map_err(|e| Error::input(format!("{label}: {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let values = (0..cells.len())
            .map(|i| {
                parse_finite(&record[i]).map_err(|m| Error::input(format!("{label}: line {line}: {}: {m}", cells[i])))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        targets(&mut check, &values).map_err(|(bone, m)| Error::input(format!("{label}: line {line}: {bone}: {m}")))?;
        rows.push(values);
    }
    if rows.is_empty() {
        return Err(Error::input(format!("{label}: no target sets (expected a header and one target set per row)")));
    }

    let solver = solver(rig.options(&args.body.solver.settings(), None)?)?;
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
    // Each target set alone on one thread: a batch on one thread has timed them so already.
    let alone = if batch.threads == 1 {
        tally.micros.clone()
    } else {
        let (mut alone, mut out, mut task) = (solver.clone(), Outcome::default(), template.clone());
        time_alone(rows.len(), |i| {
            targets(&mut task, &rows[i]).map_err(|(bone, m)| format!("{bone}: {m}"))?;
            alone.solve_rig_into(skeleton, skeleton.start_angles(), &task, &mut out).map_err(|e| e.to_string())
        })
        .map_err(Error::input)?
    };
    let tally = Tally { alone, ..tally };
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
