//! Goals at the edges: one from flags or a request ([`make_goal`], degrees), and goal files
//! (CSV: a header `x,y` or `x,y,angle_deg`, then one goal per row). The batch input of
//! `ikarus solve --batch`, the path of `ikarus track --path` and the points of
//! `ikarus reach --batch` (header `x,y`) are read with one reader, so they word their errors
//! alike: the file, the line, the column, what is wrong.

use std::path::Path;

use ikarus::Goal;

use crate::error::Error;
use crate::options::parse_finite;

pub use ikarus_edge::goal::make_goal;

/// The goals of a goal file, column by column: each row's position as written (for the rows of
/// the output) and the goal it makes, in the file's order.
#[derive(Debug, Default, PartialEq)]
pub struct Goals {
    pub xy: Vec<[f64; 2]>,
    pub goals: Vec<Goal>,
}

impl Goals {
    fn push(&mut self, x: f64, y: f64, goal: Goal) {
        self.xy.push([x, y]);
        self.goals.push(goal);
    }

    fn append(&mut self, mut other: Goals) {
        self.xy.append(&mut other.xy);
        self.goals.append(&mut other.goals);
    }
}

/// The headers of a goal file.
const GOAL_HEADERS: &[&[&str]] = &[&["x", "y"], &["x", "y", "angle_deg"]];

/// Reads the goal file `file`; errors start with `label` (e.g. `batch file goals.csv`). An empty
/// file (a header and no row) is no goals: the caller says what it needs.
///
/// A plain file (UTF-8, no quotes, no carriage returns, no blank lines, every row the header's
/// width of finite numbers) is split on its newlines and each field parsed with `str::parse`,
/// trimmed as the `csv` crate trims it: exactly what the `csv` reader reads in it, at a third of
/// the cost. Any other file, a bad one included, is read by the `csv` reader, whose errors name
/// the line, the column and the value: the same messages as ever.
pub fn read(file: &Path, label: &str) -> Result<Goals, Error> {
    let text = crate::input::read(file, label)?;
    match plain::pieces(&text, false) {
        Some(pieces) => {
            let mut goals = Goals::default();
            pieces.into_iter().for_each(|p| goals.append(p));
            Ok(goals)
        }
        None => by_csv(&text, label),
    }
}

/// [`read`] for `ikarus solve --batch`: the goals in pieces, in order. A plain file's pieces
/// are parsed in parallel on the current rayon pool (the batch's threads) and kept apart, as
/// the batch solves them: joining them cost 3 ms of serial copying on 100,000 goals.
pub fn read_pieces(file: &Path, label: &str) -> Result<Vec<Goals>, Error> {
    let text = crate::input::read(file, label)?;
    match plain::pieces(&text, true) {
        Some(pieces) => Ok(pieces),
        None => Ok(vec![by_csv(&text, label)?]),
    }
}

/// The goals of `text` as the `csv` reader reads them; errors name the line and the column.
fn by_csv(text: &[u8], label: &str) -> Result<Goals, Error> {
    let (header, rows) = read_numbers(text, label, GOAL_HEADERS)?;
    let with_angle = header == 1;
    let mut goals = Goals::default();
    for (line, v) in rows {
        let (x, y) = (v[0], v[1]);
        let angle = if with_angle { Some(v[2]) } else { None };
        let goal = make_goal(x, y, angle).map_err(|m| Error::input(format!("{label}: line {line}: {m}")))?;
        goals.push(x, y, goal);
    }
    Ok(goals)
}

/// The fast reader of plain goal files ([`read`], [`read_pieces`]).
mod plain {
    use rayon::prelude::*;

    use super::{Goals, make_goal};

    /// A large file is parsed in pieces of about this many bytes (about 1,600 goals), in parallel:
    /// enough pieces for the threads to share the work evenly, few enough that each is worth a
    /// task.
    const PIECE_BYTES: usize = 1 << 16;

    /// The goals of `text` in pieces, in order, if it is a plain goal file; `None` if the `csv`
    /// reader must read it. With `parallel`, the pieces are parsed on the current rayon pool.
    pub fn pieces(text: &[u8], parallel: bool) -> Option<Vec<Goals>> {
        let newline = text.iter().position(|&b| b == b'\n')?;
        let (head, body) = (std::str::from_utf8(&text[..newline]).ok()?, &text[newline + 1..]);
        if head.starts_with('\u{feff}') || head.contains(['"', '\r']) {
            return None;
        }
        let names: Vec<&str> = head.split(',').map(str::trim).collect();
        let width = match names[..] {
            ["x", "y"] => 2,
            ["x", "y", "angle_deg"] => 3,
            _ => return None,
        };
        if body.is_empty() {
            return Some(Vec::new());
        }
        // The last row's newline ends it; a blank line anywhere is left to the csv reader.
        let body = body.strip_suffix(b"\n").unwrap_or(body);
        let pieces = split(body);
        if parallel && pieces.len() > 1 {
            pieces.par_iter().map(|p| piece(p, width)).collect()
        } else {
            pieces.iter().map(|p| piece(p, width)).collect()
        }
    }

    /// `body` cut after newlines into pieces of about [`PIECE_BYTES`] (each checked as UTF-8
    /// on its own, in parallel: a newline is never inside a character).
    fn split(mut body: &[u8]) -> Vec<&[u8]> {
        let mut pieces = Vec::with_capacity(body.len() / PIECE_BYTES + 1);
        while body.len() > PIECE_BYTES {
            match body[PIECE_BYTES..].iter().position(|&b| b == b'\n') {
                Some(i) => {
                    pieces.push(&body[..PIECE_BYTES + i]);
                    body = &body[PIECE_BYTES + i + 1..];
                }
                None => break,
            }
        }
        pieces.push(body);
        pieces
    }

    /// The rows of `piece` (whole lines, without the last one's newline), each `width` fields.
    fn piece(piece: &[u8], width: usize) -> Option<Goals> {
        // Bytes, not chars: `str::contains(['"', '\r'])` decodes every character (5 % of a
        // piece's instructions).
        if piece.iter().any(|&b| b == b'"' || b == b'\r') {
            return None;
        }
        let piece = std::str::from_utf8(piece).ok()?;
        let mut goals = Goals { xy: Vec::with_capacity(piece.len() / 32), goals: Vec::with_capacity(piece.len() / 32) };
        for line in piece.split('\n') {
            let mut fields = line.split(',');
            let mut number = || {
                // ASCII whitespace only: a field with other (Unicode) whitespace fails here and
                // goes to the csv reader, which trims it.
                let v: f64 = fields.next()?.trim_ascii().parse().ok()?;
                v.is_finite().then_some(v)
            };
            let (x, y) = (number()?, number()?);
            let angle = if width == 3 { Some(number()?) } else { None };
            if fields.next().is_some() {
                return None;
            }
            goals.push(x, y, make_goal(x, y, angle).ok()?);
        }
        Some(goals)
    }
}

/// Reads the point file `file` (header `x,y`, then one point per row: `ikarus reach --batch`);
/// errors start with `label`. A file without points is an error.
pub fn read_points(file: &Path, label: &str) -> Result<Vec<[f64; 2]>, Error> {
    let text = crate::input::read(file, label)?;
    let (_, rows) = read_numbers(&text, label, &[&["x", "y"]])?;
    if rows.is_empty() {
        return Err(Error::input(format!("{label}: no points (expected a header `x,y` and one point per row)")));
    }
    Ok(rows.into_iter().map(|(_, v)| [v[0], v[1]]).collect())
}

/// The rows of a CSV file of numbers: each row's line, and its values (one per column).
type NumberRows = Vec<(u64, Vec<f64>)>;

/// Reads a CSV file of finite numbers (its bytes, `text`) whose header is one of `headers`: which
/// one, and its rows. Errors start with `label` and name the line and the column.
fn read_numbers(text: &[u8], label: &str, headers: &[&[&str]]) -> Result<(usize, NumberRows), Error> {
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(text);
    let found = reader.headers().map_err(|e| Error::input(format!("{label}: {e}")))?.clone();
    let names: Vec<&str> = found.iter().collect();
    let Some(header) = headers.iter().position(|h| *h == names.as_slice()) else {
        let wanted: Vec<String> = headers.iter().map(|h| format!("`{}`", h.join(","))).collect();
        return Err(Error::input(format!(
            "{label}: line 1: header must be {}, got `{}`",
            wanted.join(" or "),
            names.join(",")
        )));
    };
    let columns = headers[header];
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| Error::input(format!("{label}: {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let values = columns
            .iter()
            .enumerate()
            .map(|(i, name)| {
                parse_finite(&record[i]).map_err(|m| Error::input(format!("{label}: line {line}: {name}: {m}")))
            })
            .collect::<Result<Vec<f64>, Error>>()?;
        rows.push((line, values));
    }
    Ok((header, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the `csv` reader reads in `text`.
    fn csv(text: &str) -> Goals {
        by_csv(text.as_bytes(), "f").unwrap()
    }

    /// What the fast reader reads in `text`, joined.
    fn plain(text: &str, parallel: bool) -> Option<Goals> {
        let mut goals = Goals::default();
        plain::pieces(text.as_bytes(), parallel)?.into_iter().for_each(|p| goals.append(p));
        Some(goals)
    }

    /// The fast reader reads what the `csv` reader reads, or leaves the file to it.
    #[test]
    fn plain_files_read_as_the_csv_reader_reads_them() {
        let read = [
            "x,y\n",
            "x,y\n1,2\n",
            "x,y\n1,2",
            " x , y \n 1 ,\t2 \n-3.5e-7,+4\n",
            "x,y,angle_deg\n1,2,1e20\n0.1,0.2,-180\n",
            "x,y\n.5,5.\n1E3,0\n",
        ];
        for text in read {
            assert_eq!(plain(text, false), Some(csv(text)), "{text:?}");
        }
        let left = [
            "x,y",
            "x,y\n1,2\n\n3,4\n",
            "x,y\n1,2\n\n",
            "x,y\r\n1,2\r\n",
            "\u{feff}x,y\n1,2\n",
            "x,y\n\"1\",2\n",
            "x,y\n1,2,3\n",
            "x,y\n1\n",
            "x,y\n1,abc\n",
            "x,y\n1,inf\n",
            "x,y\n1,NaN\n",
            "y,x\n1,2\n",
            "x,y,angle\n1,2,3\n",
            "\nx,y\n1,2\n",
            "x,y\n\u{a0}1,2\n",
        ];
        for text in left {
            assert_eq!(plain(text, false), None, "{text:?}");
        }
    }

    /// A file of many pieces reads the same in parallel, piece by piece, and by the csv reader.
    #[test]
    fn large_files_read_the_same_in_pieces() {
        let mut text = String::from("x,y,angle_deg\n");
        for i in 0..20_000 {
            let f = f64::from(i);
            text.push_str(&format!("{:?},{:?},{}\n", f.sin() * 3.0, f.cos() / 7.0, i % 360));
        }
        let serial = plain(&text, false).unwrap();
        assert_eq!(serial.goals.len(), 20_000);
        assert!(plain::pieces(text.as_bytes(), true).unwrap().len() > 10);
        assert_eq!(plain(&text, true), Some(csv(&text)));
        assert_eq!(serial, csv(&text));
        text.push_str("1,2\n");
        assert_eq!(plain(&text, true), None);
    }

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
