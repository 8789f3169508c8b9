//! `ikarus solve --rig FILE --batch GOALS.csv`: one target set per row, each solved from the
//! rig's start pose (the `--pin`s and the per-goal flags apply to every row); one CSV row per
//! set on stdout, the batch summary on stderr (shared with an arm's batch, [`crate::batch`]).
//!
//! The header names the goals: `NAME.x,NAME.y`, and optionally `NAME.angle_deg`, per goal
//! bone, in any order. A header is split at its last `.`, since bone names may hold dots
//! (`arm.l.x` is the x of bone `arm.l`).

use std::path::Path;

use ikarus::{Outcome, RigTask};

use crate::batch::Batch;
use crate::error::CliError;
use crate::goals::make_goal;
use crate::options::parse_finite;
use crate::output;
use crate::rig::Rig;
use crate::rig_args::Target;
use crate::rig_solve::angle_columns;
use crate::rig_task;
use crate::settings::solver;
use crate::solve::SolveArgs;

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
        rig_task::index(&rig.skeleton, name).map_err(|m| CliError::input(format!("{}: {m}", column(i))))?;
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

pub fn run(args: &SolveArgs, rig: &Rig, path: &Path) -> Result<(), CliError> {
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
            for a in angles {
                write!(w, ",{:?}", a.to_degrees())?;
            }
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
