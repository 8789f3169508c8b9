//! The output of `ikarus bench`: an aligned plain-text table (one block per arm and set), a
//! Markdown table for the README, or JSON.

use std::io::{self, Write};

use serde::Serialize;

use super::batch::{self, Batched};
use super::run::RowResult;

/// What the output says about the run as a whole.
#[derive(Debug, Clone, Serialize)]
pub struct Header {
    /// The command line, as `ikarus bench …`.
    pub command: String,
    /// The version of ikarus.
    pub ikarus_version: &'static str,
    /// The version `kdl_bench` reported; `None` without `--kdl`.
    pub kdl_version: Option<String>,
    /// Goals per set.
    pub goals: usize,
    /// `--seed`.
    pub seed: u64,
    /// The arms benchmarked.
    pub arms: Vec<&'static str>,
    /// The sets benchmarked.
    pub sets: Vec<&'static str>,
    /// Distance that counts as reached.
    pub tolerance: f64,
    /// Orientation error that counts as reached, radians.
    pub angle_tolerance: f64,
    /// Iteration cap of one solve.
    pub max_iterations: u32,
    /// Untimed warm-up solves before each row.
    pub warmup_goals: usize,
    /// Threads the per-solve rows ran on (always one; the batched measurement runs on one and two).
    pub threads: usize,
    /// Logical CPUs of the machine.
    pub cpus: usize,
    /// Operating system, as Rust names it.
    pub os: &'static str,
    /// CPU architecture, as Rust names it.
    pub arch: &'static str,
    /// Whether ikarus was built without optimisations (its times then mean little).
    pub debug_build: bool,
}

/// A row as the JSON output writes it (see [`RowResult`] for the meaning of each field).
#[derive(Debug, Serialize)]
struct RowJson<'a> {
    /// The arm's name.
    arm: &'a str,
    /// The set's name.
    set: &'a str,
    /// The row's label.
    solver: &'a str,
    /// The enforcing limit mode; `None` when limits are ignored.
    limits: Option<&'a str>,
    /// Goals solved.
    goals: usize,
    /// Solves judged reached.
    reached: usize,
    /// `reached` as a percentage of `goals`, truncated to a tenth.
    reached_percent: f64,
    /// Median time of one solve, µs.
    median_us: f64,
    /// 99th percentile (nearest rank) of the time of one solve, µs.
    p99_us: f64,
    /// Mean iterations per solve; `None` when unknown.
    mean_iterations: Option<f64>,
    /// Worst position error; `None` when infinite (a solve failed outright).
    worst_error: Option<f64>,
    /// Worst orientation error, radians, for oriented sets; `None` otherwise or when infinite.
    worst_angle_error: Option<f64>,
    /// KDL LMA's median / this row's median; `None` without `--kdl`.
    vs_kdl_lma: Option<f64>,
    /// Solves that returned an error.
    solve_errors: usize,
    /// The first such error's message.
    solve_error: Option<&'a str>,
    /// The batched measurement (`default` rows); `None` on the other rows.
    batch: Option<BatchJson<'a>>,
}

/// A `default` row's batched measurement as the JSON output writes it.
#[derive(Debug, Serialize)]
struct BatchJson<'a> {
    /// The figures, when the batch ran.
    #[serde(flatten)]
    figures: Option<&'a Batched>,
    /// The batch's error, when it returned one.
    error: Option<&'a str>,
}

/// The JSON document: the header, then the rows.
#[derive(Debug, Serialize)]
struct Json<'a> {
    /// Facts about the run.
    header: &'a Header,
    /// One object per row, in the order of the text table.
    rows: Vec<RowJson<'a>>,
}

/// What the columns mean, printed under the text and Markdown tables.
const LEGEND: &str = "reached: share (and count) of goals judged reached from the final angles by forward \
kinematics (position within the tolerance; orientation too for oriented sets; limited joints within their \
limits modulo 2π for limits sets; unreachable set: as close as the arm can get). median/p99: time of one \
solve, µs, one thread. iter: mean iterations per solve (— unknown; KDL LMA counts from 0). pos err, ang err: \
worst final position error and orientation error (rad) over all goals (unreachable set: distance beyond the \
closest reachable point). × KDL LMA: KDL LMA's median on the same set / the row's median (above 1: faster \
than KDL LMA).";

/// What the batched table's columns mean.
const BATCH_LEGEND: &str = "batched: the goals of each `default` row solved again with Solver::solve_batch (the \
same options, from the start pose). µs/solve: wall time of a pass over all the goals / goals (a mean: slow goals count \
in full, unlike in the per-solve median), median of at least 5 samples of about 0.04 s, 0.2 s in all; M solves/s: millions of solves per second; 2 thr: the goals split in two halves, one \
thread each; × 2 thr: 2 threads' throughput / 1 thread's. reached: the batched outcomes judged as above; \
≠ per-solve: goals judged otherwise than in the per-solve row, or whose 2-thread outcome differs from the \
1-thread one (0 when the batch returns what solve_into does).";

/// The headings of the batched table, after arm and set.
const BATCH_HEADINGS: [&str; 7] =
    ["reached", "≠ per-solve", "µs/solve 1 thr", "M solves/s 1 thr", "µs/solve 2 thr", "M solves/s 2 thr", "× 2 thr"];

/// The batched table's rows: arm, set, then the cells under [`BATCH_HEADINGS`].
fn batch_rows(rows: &[RowResult]) -> Vec<Vec<String>> {
    rows.iter()
        .filter_map(|r| {
            let mut c = vec![r.arm.to_owned(), r.set.name().to_owned()];
            match r.batch.as_ref()? {
                Ok(b) => c.extend([
                    format!(
                        "{:.1}% ({})",
                        (1000.0 * b.reached as f64 / b.goals.max(1) as f64).floor() / 10.0,
                        b.reached
                    ),
                    b.mismatches.to_string(),
                    micros(b.us_1thr),
                    significant_any(b.solves_per_s_1thr / 1e6),
                    micros(b.us_2thr),
                    significant_any(b.solves_per_s_2thr / 1e6),
                    ratio(b.speedup_2thr),
                ]),
                Err(_) => {
                    c.push("error".to_owned());
                    c.extend(std::iter::repeat_n("—".to_owned(), 6));
                }
            }
            Some(c)
        })
        .collect()
}

/// Notes on batches that returned an error.
fn batch_notes(rows: &[RowResult]) -> Vec<String> {
    rows.iter()
        .filter_map(|r| match r.batch.as_ref()? {
            Err(e) => Some(format!("{} {}: the batch returned an error: {e}", r.arm, r.set.name())),
            Ok(_) => None,
        })
        .collect()
}

/// Writes the batched table as aligned text (nothing when no row was batched).
fn batch_text(w: &mut dyn Write, rows: &[RowResult]) -> io::Result<()> {
    {
        let body = batch_rows(rows);
        if body.is_empty() {
            return Ok(());
        }
        writeln!(w)?;
        writeln!(
            w,
            "batched · Solver::solve_batch, default options, 1 and 2 threads (median of at least {} samples, {} s in all)",
            batch::SAMPLES,
            batch::MIN_SECONDS
        )?;
        let mut head = vec!["arm".to_owned(), "set".to_owned()];
        head.extend(BATCH_HEADINGS.map(str::to_owned));
        let mut widths: Vec<usize> = head.iter().map(|h| h.chars().count()).collect();
        for c in &body {
            for (w, cell) in widths.iter_mut().zip(c) {
                *w = (*w).max(cell.chars().count());
            }
        }
        for cells in std::iter::once(&head).chain(&body) {
            let mut s = String::from(" ");
            for (k, (cell, width)) in cells.iter().zip(&widths).enumerate() {
                let pad = " ".repeat(width - cell.chars().count());
                s.push_str("  ");
                if k < 2 {
                    s.push_str(cell);
                    s.push_str(&pad);
                } else {
                    s.push_str(&pad);
                    s.push_str(cell);
                }
            }
            writeln!(w, "{}", s.trim_end())?;
        }
        for n in batch_notes(rows) {
            writeln!(w, "   note: {n}")?;
        }
        Ok(())
    }
}

/// Writes the batched table in Markdown (nothing when no row was batched).
fn batch_markdown(w: &mut dyn Write, rows: &[RowResult]) -> io::Result<()> {
    let body = batch_rows(rows);
    if body.is_empty() {
        return Ok(());
    }
    writeln!(w)?;
    let mut head = vec!["arm", "set"];
    head.extend(BATCH_HEADINGS);
    writeln!(w, "| {} |", head.join(" | "))?;
    let rule: Vec<&str> = (0..head.len()).map(|k| if k < 2 { "---" } else { "--:" }).collect();
    writeln!(w, "|{}|", rule.join("|"))?;
    for c in body {
        writeln!(w, "| {} |", c.join(" | "))?;
    }
    let notes = batch_notes(rows);
    if !notes.is_empty() {
        writeln!(w)?;
        for n in notes {
            writeln!(w, "- {n}")?;
        }
    }
    Ok(())
}

/// Writes the report as JSON.
pub fn json(w: &mut dyn Write, header: &Header, rows: &[RowResult]) -> io::Result<()> {
    let rows = rows
        .iter()
        .map(|r| RowJson {
            arm: r.arm,
            set: r.set.name(),
            solver: &r.label,
            limits: r.limits,
            goals: r.goals,
            reached: r.reached,
            reached_percent: percent(r),
            median_us: r.median_us,
            p99_us: r.p99_us,
            mean_iterations: r.mean_iterations,
            worst_error: Some(r.worst_error).filter(|e| e.is_finite()),
            worst_angle_error: r.worst_angle_error.filter(|e| e.is_finite()),
            vs_kdl_lma: r.vs_kdl_lma,
            solve_errors: r.solve_errors,
            solve_error: r.first_solve_error.as_deref(),
            batch: r
                .batch
                .as_ref()
                .map(|b| BatchJson { figures: b.as_ref().ok(), error: b.as_ref().err().map(String::as_str) }),
        })
        .collect();
    serde_json::to_writer_pretty(&mut *w, &Json { header, rows })?;
    writeln!(w)
}

/// The headings of the table columns after arm and set.
const HEADINGS: [&str; 9] =
    ["solver", "limits", "reached", "median µs", "p99 µs", "iter", "pos err", "ang err", "× KDL LMA"];

/// Whether each column of [`HEADINGS`] is right-aligned.
const RIGHT: [bool; 9] = [false, false, true, true, true, true, true, true, true];

/// The cells of a row under [`HEADINGS`].
fn cells(r: &RowResult) -> [String; 9] {
    [
        r.label.clone(),
        r.limits.unwrap_or("—").to_owned(),
        format!("{:.1}% ({})", percent(r), r.reached),
        micros(r.median_us),
        micros(r.p99_us),
        r.mean_iterations.map_or("—".to_owned(), |i| format!("{i:.1}")),
        error(r.worst_error),
        r.worst_angle_error.map_or(String::new(), error),
        r.vs_kdl_lma.map_or(String::new(), ratio),
    ]
}

/// Writes the aligned plain-text table: a heading, one block per arm and set, the legend.
pub fn text(w: &mut dyn Write, header: &Header, rows: &[RowResult]) -> io::Result<()> {
    writeln!(w, "ikarus bench: {}", facts(header))?;
    let all: Vec<[String; 9]> = rows.iter().map(cells).collect();
    let mut widths = HEADINGS.map(|h| h.chars().count());
    for c in &all {
        for (w, cell) in widths.iter_mut().zip(c) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |w: &mut dyn Write, cells: &[String; 9]| -> io::Result<()> {
        let mut s = String::from(" ");
        for ((cell, width), right) in cells.iter().zip(widths).zip(RIGHT) {
            let pad = " ".repeat(width - cell.chars().count());
            s.push_str("  ");
            if right {
                s.push_str(&pad);
                s.push_str(cell);
            } else {
                s.push_str(cell);
                s.push_str(&pad);
            }
        }
        writeln!(w, "{}", s.trim_end())
    };
    let mut i = 0;
    while i < rows.len() {
        let (arm, set) = (rows[i].arm, rows[i].set);
        let end = rows[i..].iter().position(|r| r.arm != arm || r.set != set).map_or(rows.len(), |k| i + k);
        writeln!(w)?;
        writeln!(w, "{arm} · {} · {} goals", set.name(), rows[i].goals)?;
        line(w, &HEADINGS.map(str::to_owned))?;
        for c in &all[i..end] {
            line(w, c)?;
        }
        for r in &rows[i..end] {
            if let Some(note) = note(r) {
                writeln!(w, "   note: {note}")?;
            }
        }
        i = end;
    }
    batch_text(w, rows)?;
    writeln!(w)?;
    for l in wrap(LEGEND, 100) {
        writeln!(w, "{l}")?;
    }
    if rows.iter().any(|r| r.batch.is_some()) {
        for l in wrap(BATCH_LEGEND, 100) {
            writeln!(w, "{l}")?;
        }
    }
    Ok(())
}

/// `text` broken into lines of at most `width` characters, at spaces.
pub(super) fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split(' ') {
        let last = lines.last_mut().expect("never empty");
        if !last.is_empty() && last.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_owned());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    lines
}

/// Writes the Markdown table: the command line first, then the facts, the table, the notes
/// and the legend.
pub fn markdown(w: &mut dyn Write, header: &Header, rows: &[RowResult]) -> io::Result<()> {
    writeln!(w, "`{}`", header.command)?;
    writeln!(w)?;
    writeln!(w, "{}", facts(header))?;
    writeln!(w)?;
    let mut head = vec!["arm", "set"];
    head.extend(HEADINGS);
    writeln!(w, "| {} |", head.join(" | "))?;
    let rule: Vec<&str> = [false, false].iter().chain(&RIGHT).map(|&r| if r { "--:" } else { "---" }).collect();
    writeln!(w, "|{}|", rule.join("|"))?;
    for r in rows {
        let c = cells(r);
        writeln!(w, "| {} | {} | {} |", r.arm, r.set.name(), c.join(" | "))?;
    }
    let notes: Vec<String> =
        rows.iter().filter_map(|r| note(r).map(|n| format!("{} {}: {n}", r.arm, r.set.name()))).collect();
    if !notes.is_empty() {
        writeln!(w)?;
        for n in notes {
            writeln!(w, "- {n}")?;
        }
    }
    batch_markdown(w, rows)?;
    writeln!(w)?;
    writeln!(w, "{LEGEND}")?;
    if rows.iter().any(|r| r.batch.is_some()) {
        writeln!(w)?;
        writeln!(w, "{BATCH_LEGEND}")?;
    }
    Ok(())
}

/// The heading line: versions, goals, seed, machine.
fn facts(h: &Header) -> String {
    let kdl = h.kdl_version.as_ref().map_or(String::new(), |v| format!(", KDL {v}"));
    let debug = if h.debug_build { " (debug build: times mean little)" } else { "" };
    format!(
        "ikarus {}{debug}{kdl}, {} goals per set, seed {}, one thread, {}-{} with {} CPUs",
        h.ikarus_version, h.goals, h.seed, h.arch, h.os, h.cpus
    )
}

/// A note on a row whose solves returned errors.
fn note(r: &RowResult) -> Option<String> {
    let e = r.first_solve_error.as_deref()?;
    Some(format!(
        "{}: {} of {} solves returned an error (counted as not reached): {e}",
        r.label, r.solve_errors, r.goals
    ))
}

/// The share of goals reached, percent, truncated to a tenth: 999 of 1000 must not read as
/// 100%.
fn percent(r: &RowResult) -> f64 {
    (1000.0 * r.reached as f64 / r.goals as f64).floor() / 10.0
}

/// Microseconds with three or four significant digits.
fn micros(v: f64) -> String {
    if v < 10.0 {
        format!("{v:.2}")
    } else if v < 1000.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.0}")
    }
}

/// An error with two or three significant digits: plain between 0.001 and 10000, else in
/// scientific notation; `0` and `inf` as such.
fn error(v: f64) -> String {
    if v == 0.0 {
        "0".to_owned()
    } else if v.is_infinite() {
        "inf".to_owned()
    } else if (1e-3..1e4).contains(&v.abs()) {
        significant(v)
    } else {
        format!("{v:.1e}")
    }
}

/// A speed ratio with two or three significant digits.
fn ratio(v: f64) -> String {
    if v >= 1e-3 { significant(v) } else { format!("{v:.1e}") }
}

/// A positive figure with three significant digits (scientific notation outside 0.001..10000).
fn significant_any(v: f64) -> String {
    if (1e-3..1e4).contains(&v) { significant(v) } else { format!("{v:.2e}") }
}

/// `v` (between 0.001 and 10000) with three significant digits, or a whole number.
fn significant(v: f64) -> String {
    let decimals = (2 - v.abs().log10().floor() as i32).clamp(0, 5) as usize;
    format!("{v:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sets::SetName;

    fn row(label: &str, set: SetName, reached: usize) -> RowResult {
        RowResult {
            arm: "seed",
            set,
            label: label.to_owned(),
            limits: None,
            goals: 1000,
            reached,
            median_us: 12.345,
            p99_us: 1234.4,
            mean_iterations: Some(3.24),
            worst_error: 9.87e-7,
            worst_angle_error: set.oriented().then_some(0.0),
            solve_errors: 0,
            first_solve_error: None,
            vs_kdl_lma: Some(2.5),
            reached_each: Vec::new(),
            batch: None,
        }
    }

    fn header() -> Header {
        Header {
            command: "ikarus bench --goals 1000".to_owned(),
            ikarus_version: "0.1.0",
            kdl_version: Some("1.5.1".to_owned()),
            goals: 1000,
            seed: 1,
            arms: vec!["seed"],
            sets: vec!["free-position"],
            tolerance: 1e-6,
            angle_tolerance: 1e-6,
            max_iterations: 1000,
            warmup_goals: 50,
            threads: 1,
            cpus: 8,
            os: "linux",
            arch: "x86_64",
            debug_build: false,
        }
    }

    #[test]
    fn cells_are_formatted() {
        let c = cells(&row("dls", SetName::FreeOriented, 999));
        assert_eq!(c, ["dls", "—", "99.9% (999)", "12.3", "1234", "3.2", "9.9e-7", "0", "2.50"].map(str::to_owned));
        assert_eq!(cells(&row("dls", SetName::FreePosition, 1000))[7], "");
        assert_eq!(
            [error(5.834), error(0.0374), error(12345.0), error(f64::INFINITY)],
            ["5.83", "0.0374", "1.2e4", "inf"]
        );
        assert_eq!([ratio(0.0123), ratio(1.0), ratio(123.4), ratio(1e-4)], ["0.0123", "1.00", "123", "1.0e-4"]);
    }

    #[test]
    fn text_blocks_are_aligned() {
        let rows = [
            row("dls", SetName::FreePosition, 1000),
            row("kdl lma", SetName::FreePosition, 3),
            row("x", SetName::Unreachable, 0),
        ];
        let mut out = Vec::new();
        text(&mut out, &header(), &rows).unwrap();
        let out = String::from_utf8(out).unwrap();
        assert!(out.starts_with("ikarus bench: ikarus 0.1.0, KDL 1.5.1, 1000 goals per set"), "{out}");
        assert!(out.contains("\nseed · free-position · 1000 goals\n"));
        assert!(out.contains("\nseed · unreachable · 1000 goals\n"));
        let lines: Vec<&str> = out.lines().filter(|l| l.contains("12.3")).collect();
        assert_eq!(lines.len(), 3);
        let at = |l: &str| l.find("12.3").unwrap();
        assert!(lines.iter().all(|l| at(l) == at(lines[0])), "{out}");
    }

    #[test]
    fn the_legend_is_wrapped() {
        let lines = wrap(LEGEND, 100);
        assert!(lines.len() > 3 && lines.iter().all(|l| l.chars().count() <= 100));
        assert_eq!(lines.join(" "), LEGEND);
    }

    #[test]
    fn batched_rows_get_a_table_of_their_own() {
        let mut d = row("default", SetName::FreePosition, 1000);
        d.batch = Some(Ok(Batched {
            goals: 1000,
            reached: 999,
            mismatches: 0,
            us_1thr: 2.0,
            solves_per_s_1thr: 5e5,
            us_2thr: 1.25,
            solves_per_s_2thr: 8e5,
            speedup_2thr: 1.6,
        }));
        let mut e = row("default", SetName::LimitsPosition, 1000);
        e.batch = Some(Err("bad start".to_owned()));
        let rows = [row("dls", SetName::FreePosition, 10), d, e];
        let mut out = Vec::new();
        markdown(&mut out, &header(), &rows).unwrap();
        let out = String::from_utf8(out).unwrap();
        assert!(out.contains("| arm | set | reached | ≠ per-solve | µs/solve 1 thr |"), "{out}");
        assert!(
            out.contains("| seed | free-position | 99.9% (999) | 0 | 2.00 | 0.500 | 1.25 | 0.800 | 1.60 |"),
            "{out}"
        );
        assert!(out.contains("| seed | limits-position | error | — |"), "{out}");
        assert!(out.contains("- seed limits-position: the batch returned an error: bad start"), "{out}");
        let mut out = Vec::new();
        text(&mut out, &header(), &rows).unwrap();
        let out = String::from_utf8(out).unwrap();
        assert!(out.contains("\nbatched · Solver::solve_batch"), "{out}");
        assert!(out.contains("M solves/s 2 thr"), "{out}");
        // No batched row, no batched table.
        let mut out = Vec::new();
        text(&mut out, &header(), &rows[..1]).unwrap();
        assert!(!String::from_utf8(out).unwrap().contains("batched"));
    }

    #[test]
    fn markdown_starts_with_the_command() {
        let mut out = Vec::new();
        markdown(&mut out, &header(), &[row("dls", SetName::FreePosition, 10)]).unwrap();
        let out = String::from_utf8(out).unwrap();
        assert!(out.starts_with("`ikarus bench --goals 1000`\n\n"));
        assert!(out.contains("| arm | set | solver |"));
        assert!(out.contains("| seed | free-position | dls | — | 1.0% (10) |"));
    }
}

/// One of an issue's targets, checked on a mode's rows (`--rigs`, `--reach`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Target {
    /// What is promised.
    pub target: String,
    /// Whether it holds; `None` when it was not measured.
    pub met: Option<bool>,
    /// The figures it was judged by.
    pub figure: String,
}

/// `targets: M of N measured met`, then one line per target (`bullet` before each, a blank
/// line first when there is a bullet).
pub(crate) fn write_targets(w: &mut dyn std::io::Write, targets: &[Target], bullet: &str) -> std::io::Result<()> {
    let met = targets.iter().filter(|t| t.met == Some(true)).count();
    let measured = targets.iter().filter(|t| t.met.is_some()).count();
    writeln!(w, "targets: {met} of {measured} measured met")?;
    if !bullet.is_empty() {
        writeln!(w)?;
    }
    for t in targets {
        let mark = match t.met {
            Some(true) => "met",
            Some(false) => "MISSED",
            None => "not measured",
        };
        writeln!(w, "{bullet}{mark} {}: {}", t.target, t.figure)?;
    }
    Ok(())
}
