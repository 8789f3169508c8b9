//! The goal columns of a rig's batch file: the header names the goals, `NAME.x,NAME.y`, and
//! optionally `NAME.angle_deg`, per goal bone, in any order. A header is split at its last `.`,
//! since bone names may hold dots (`arm.l.x` is the x of bone `arm.l`).

use crate::error::Error;
use crate::goal;
use crate::rig::Rig;

/// Which coordinate of a goal a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    X,
    Y,
    Angle,
}

/// The columns of one goal: where its x, y and angle are in a row.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct GoalColumns {
    pub(super) bone: String,
    pub(super) x: usize,
    pub(super) y: usize,
    pub(super) angle: Option<usize>,
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
pub(super) fn goal_columns(rig: &Rig, cells: &[&str], label: &str) -> Result<Vec<GoalColumns>, Error> {
    let column = |i: usize| format!("{label}: line 1: column {} `{}`", i + 1, cells[i]);
    let mut found: Vec<(String, [Option<usize>; 3])> = Vec::new();
    for (i, cell) in cells.iter().enumerate() {
        let Some((name, part)) = split(cell) else {
            return Err(Error::input(format!(
                "{}: expected NAME.x, NAME.y or NAME.angle_deg (NAME a bone of the rig)",
                column(i)
            )));
        };
        goal::index(&rig.skeleton, name).map_err(|m| Error::input(format!("{}: {m}", column(i))))?;
        let k = match found.iter().position(|(n, _)| n == name) {
            Some(k) => k,
            None => {
                found.push((name.to_owned(), [None; 3]));
                found.len() - 1
            }
        };
        let slot = &mut found[k].1[part as usize];
        if let Some(first) = *slot {
            return Err(Error::input(format!("{}: the same as column {}", column(i), first + 1)));
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
                Err(Error::input(format!("{}: no `{bone}.{missing}` column", column(given))))
            }
        })
        .collect()
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
