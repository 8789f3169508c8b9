//! Goals at the edges: one from flags or a request ([`make_goal`], degrees), and goal files
//! (CSV: a header `x,y` or `x,y,angle_deg`, then one goal per row). The batch input of
//! `ikarus solve --batch` and the path of `ikarus track --path` read them with one reader, so
//! both word their errors alike: the file, the line, the column, what is wrong.

use std::path::Path;

use ikarus::Goal;

use crate::arm::io_reason;
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
    let text = std::fs::read(file).map_err(|e| CliError::input(format!("{label}: cannot read: {}", io_reason(&e))))?;
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(text.as_slice());
    let headers = reader.headers().map_err(|e| CliError::input(format!("{label}: {e}")))?.clone();
    let names: Vec<&str> = headers.iter().collect();
    let with_angle = match names[..] {
        ["x", "y"] => false,
        ["x", "y", "angle_deg"] => true,
        _ => {
            return Err(CliError::input(format!(
                "{label}: line 1: header must be `x,y` or `x,y,angle_deg`, got `{}`",
                names.join(",")
            )));
        }
    };
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| CliError::input(format!("{label}: {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let field = |i: usize, name: &str| {
            parse_finite(&record[i]).map_err(|m| CliError::input(format!("{label}: line {line}: {name}: {m}")))
        };
        let (x, y) = (field(0, "x")?, field(1, "y")?);
        let angle = if with_angle { Some(field(2, "angle_deg")?) } else { None };
        let goal = make_goal(x, y, angle).map_err(|m| CliError::input(format!("{label}: line {line}: {m}")))?;
        rows.push(GoalRow { x, y, goal });
    }
    Ok(rows)
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
