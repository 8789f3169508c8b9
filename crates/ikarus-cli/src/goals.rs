//! Goals at the edges: one from flags or a request ([`make_goal`], degrees), and goal files
//! (CSV: a header `x,y` or `x,y,angle_deg`, then one goal per row). The batch input of
//! `ikarus solve --batch`, the path of `ikarus track --path` and the points of
//! `ikarus reach --batch` (header `x,y`) are read with one reader, so they word their errors
//! alike: the file, the line, the column, what is wrong.

use std::path::Path;

use ikarus::Goal;

use crate::error::CliError;
use crate::options::parse_finite;

/// One row: the position as written, and the goal it makes.
pub struct GoalRow {
    pub x: f64,
    pub y: f64,
    pub goal: Goal,
}

/// A goal at `(x, y)`, with the last link's orientation when `angle_deg` is given (wrapped
/// into (−180°, 180°] exactly before it becomes radians: 1e20° is the direction it names).
pub fn make_goal(x: f64, y: f64, angle_deg: Option<f64>) -> Result<Goal, String> {
    match angle_deg {
        None => Goal::position(x, y),
        Some(a) if !a.is_finite() => Goal::with_orientation(x, y, a),
        Some(a) => Goal::with_orientation(x, y, ikarus::angle::radians_from_degrees(a)),
    }
    .map_err(|e| e.to_string())
}

/// Reads the goal file `file`; errors start with `label` (e.g. `batch file goals.csv`). An empty
/// file (a header and no row) is an empty list: the caller says what it needs.
pub fn read(file: &Path, label: &str) -> Result<Vec<GoalRow>, CliError> {
    let (header, rows) = read_numbers(file, label, &[&["x", "y"], &["x", "y", "angle_deg"]])?;
    let with_angle = header == 1;
    rows.into_iter()
        .map(|(line, v)| {
            let (x, y) = (v[0], v[1]);
            let angle = if with_angle { Some(v[2]) } else { None };
            let goal = make_goal(x, y, angle).map_err(|m| CliError::input(format!("{label}: line {line}: {m}")))?;
            Ok(GoalRow { x, y, goal })
        })
        .collect()
}

/// Reads the point file `file` (header `x,y`, then one point per row: `ikarus reach --batch`);
/// errors start with `label`. A file without points is an error.
pub fn read_points(file: &Path, label: &str) -> Result<Vec<[f64; 2]>, CliError> {
    let (_, rows) = read_numbers(file, label, &[&["x", "y"]])?;
    if rows.is_empty() {
        return Err(CliError::input(format!("{label}: no points (expected a header `x,y` and one point per row)")));
    }
    Ok(rows.into_iter().map(|(_, v)| [v[0], v[1]]).collect())
}

/// The rows of a CSV file of numbers: each row's line, and its values (one per column).
type NumberRows = Vec<(u64, Vec<f64>)>;

/// Reads a CSV file of finite numbers whose header is one of `headers`: which one, and its rows.
/// Errors start with `label` and name the line and the column.
fn read_numbers(file: &Path, label: &str, headers: &[&[&str]]) -> Result<(usize, NumberRows), CliError> {
    let text = crate::input::read(file, label)?;
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(text.as_slice());
    let found = reader.headers().map_err(|e| CliError::input(format!("{label}: {e}")))?.clone();
    let names: Vec<&str> = found.iter().collect();
    let Some(header) = headers.iter().position(|h| *h == names.as_slice()) else {
        let wanted: Vec<String> = headers.iter().map(|h| format!("`{}`", h.join(","))).collect();
        return Err(CliError::input(format!(
            "{label}: line 1: header must be {}, got `{}`",
            wanted.join(" or "),
            names.join(",")
        )));
    };
    let columns = headers[header];
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| CliError::input(format!("{label}: {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let values = columns
            .iter()
            .enumerate()
            .map(|(i, name)| {
                parse_finite(&record[i]).map_err(|m| CliError::input(format!("{label}: line {line}: {name}: {m}")))
            })
            .collect::<Result<Vec<f64>, CliError>>()?;
        rows.push((line, values));
    }
    Ok((header, rows))
}

#[cfg(test)]
mod tests {
    use super::make_goal;

    /// Issue 11: `--goal-angle 1e20` became 1.7e18 rad, which the solver wraps by an inexact
    /// 2π: it aimed 3.7° away from the direction asked for. Degrees are wrapped exactly first
    /// (1e20 = 360 · 277777777777777777 + 280, that is −80°).
    #[test]
    fn goal_angles_are_wrapped_exactly() {
        let phi = make_goal(1.0, 2.0, Some(1e20)).unwrap().orientation().unwrap();
        assert_eq!(phi, (-80f64).to_radians());
        assert_eq!(make_goal(1.0, 2.0, Some(-180.0)).unwrap().orientation(), Some(std::f64::consts::PI));
        let e = make_goal(1.0, 2.0, Some(f64::INFINITY)).unwrap_err();
        assert_eq!(e, "goal.angle: must be a finite number, got inf");
    }
}
