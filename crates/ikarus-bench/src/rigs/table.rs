//! The output of `ikarus bench --rigs`: an aligned plain-text table (one block per set), a
//! Markdown table for the README, or JSON; each with the targets checked.

use std::io::{self, Write};

use serde::Serialize;

pub use crate::table::Target;
use crate::table::write_targets;

use super::kdl::TREE_LABEL;
use super::rows::{RigRow, SEQUENTIAL_LABEL};

/// What the output says about the run as a whole.
#[derive(Debug, Clone, Serialize)]
pub struct RigsHeader {
    /// The command line, as `ikarus bench …`.
    pub command: String,
    /// The version of ikarus.
    pub ikarus_version: &'static str,
    /// The version `kdl_bench` reported; `None` without `--kdl`.
    pub kdl_version: Option<String>,
    /// Target sets per set.
    pub goals: usize,
    /// `--seed`.
    pub seed: u64,
    /// Each set: its name, rig, goal bones and pinned bones.
    pub sets: Vec<SetInfo>,
    /// Distance that counts as reached.
    pub tolerance: f64,
    /// Direction error of a pin that counts as held, radians.
    pub angle_tolerance: f64,
    /// Iteration cap of one solve.
    pub max_iterations: u32,
    /// The damping ikarus gives KDL's `TreeIkSolverVel_wdls`.
    pub kdl_lambda: f64,
    /// Untimed warm-up solves before each row.
    pub warmup_goals: usize,
    /// Threads the solves ran on (always one).
    pub threads: usize,
    /// Logical CPUs of the machine.
    pub cpus: usize,
    /// Operating system and CPU architecture, as Rust names them.
    pub os: &'static str,
    pub arch: &'static str,
    /// Whether ikarus was built without optimisations (its times then mean little).
    pub debug_build: bool,
}

/// A set as the header describes it.
#[derive(Debug, Clone, Serialize)]
pub struct SetInfo {
    pub name: &'static str,
    pub rig: &'static str,
    pub goals: Vec<String>,
    pub pins: Vec<String>,
}

/// The targets, on the `default` rows: ≥ 99.9 % reached on every set; a median of at
/// most 10 µs on the puppet's sets; at least 5× faster than KDL's tree solver with a higher
/// success on every set (only with `--kdl`); and, beside them, the sequential baseline's
/// success.
pub fn targets(rows: &[RigRow]) -> Vec<Target> {
    fn of<'r>(rows: &'r [RigRow], label: &str) -> Vec<&'r RigRow> {
        rows.iter().filter(|r| r.solver == label).collect()
    }
    let defaults = of(rows, "default");
    let list = |f: &dyn Fn(&RigRow) -> String, rs: &[&RigRow]| {
        rs.iter().map(|r| format!("{} {}", r.set, f(r))).collect::<Vec<_>>().join(", ")
    };
    let mut out = Vec::new();
    out.push(Target {
        target: "default reaches ≥ 99.9% of the target sets, limits on".to_owned(),
        met: Some(!defaults.is_empty() && defaults.iter().all(|r| r.reached * 1000 >= r.goals * 999)),
        figure: list(&|r| format!("{:.1}%", r.reached_percent), &defaults),
    });
    let puppet: Vec<&RigRow> = defaults.iter().copied().filter(|r| r.set.starts_with("puppet")).collect();
    out.push(Target {
        target: "default median ≤ 10 µs per puppet solve".to_owned(),
        met: (!puppet.is_empty()).then(|| puppet.iter().all(|r| r.median_us <= 10.0)),
        figure: list(&|r| format!("{:.2} µs", r.median_us), &puppet),
    });
    let kdl: Vec<(&RigRow, &RigRow)> = defaults
        .iter()
        .filter_map(|d| of(rows, TREE_LABEL).into_iter().find(|k| k.set == d.set).map(|k| (*d, k)))
        .collect();
    out.push(Target {
        target: "default ≥ 5× faster than KDL's tree solver, with a higher success".to_owned(),
        met: (!kdl.is_empty())
            .then(|| kdl.iter().all(|(d, k)| d.median_us * 5.0 <= k.median_us && d.reached > k.reached)),
        figure: if kdl.is_empty() {
            "not measured (run with --kdl)".to_owned()
        } else {
            kdl.iter()
                .map(|(d, k)| {
                    format!(
                        "{} {}× ({:.1}% vs {:.1}%)",
                        d.set,
                        ratio(k.median_us / d.median_us),
                        d.reached_percent,
                        k.reached_percent
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        },
    });
    let seq = of(rows, SEQUENTIAL_LABEL);
    out.push(Target {
        target: "the sequential-limb baseline's success, beside it".to_owned(),
        met: (!seq.is_empty()).then_some(true),
        figure: list(&|r| format!("{:.1}%", r.reached_percent), &seq),
    });
    out
}

/// What the columns mean.
const LEGEND: &str = "reached: share (and count) of target sets whose final angles put every effector within the \
tolerance of its target (pins: of where they start, direction too) with every bone inside its limits, judged by \
forward kinematics. default: Solver::solve_rig with the library's defaults (lm, limits locked, restarts); lm MODE: \
each limit mode, no restarts. sequential: each limb (the bones from the root to the effector) solved alone as a \
chain with the defaults, one after another, goals then pins, as Spine and Unity do. kdl tree nr_jl: Orocos KDL's \
TreeIkSolverPos_NR_JL over TreeIkSolverVel_wdls (position-only weights; pins hold their direction too). \
median/p99: time of one rig solve, µs, one thread. iter: mean iterations per solve (sequential: all limbs; — \
unknown). worst err: the largest effector error of any solve. × KDL tree: KDL's median on the same set / the \
row's median (above 1: faster than KDL).";

const HEADINGS: [&str; 8] = ["solver", "limits", "reached", "median µs", "p99 µs", "iter", "worst err", "× KDL tree"];
const RIGHT: [bool; 8] = [false, false, true, true, true, true, true, true];

fn cells(r: &RigRow) -> [String; 8] {
    [
        r.solver.clone(),
        r.limits.to_owned(),
        format!("{:.1}% ({})", r.reached_percent, r.reached),
        micros(r.median_us),
        micros(r.p99_us),
        r.mean_iterations.map_or("—".to_owned(), |i| format!("{i:.1}")),
        r.worst_error.map_or("inf".to_owned(), error),
        r.vs_kdl_tree.map_or(String::new(), ratio),
    ]
}

fn micros(v: f64) -> String {
    if v < 10.0 {
        format!("{v:.2}")
    } else if v < 1000.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.0}")
    }
}

/// A speed ratio with three significant digits (a whole number from 100 on).
fn ratio(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

fn error(v: f64) -> String {
    if v == 0.0 { "0".to_owned() } else { format!("{v:.1e}") }
}

/// The JSON document.
#[derive(Serialize)]
struct Json<'a> {
    header: &'a RigsHeader,
    rows: &'a [RigRow],
    targets: &'a [Target],
}

/// Writes the report as JSON: the header, every row, the targets.
pub fn json(w: &mut dyn Write, header: &RigsHeader, rows: &[RigRow], targets: &[Target]) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *w, &Json { header, rows, targets })?;
    writeln!(w)
}

/// A set's heading: its name, rig, goals and pins.
fn describe(header: &RigsHeader, set: &str, goals: usize) -> String {
    let info = header.sets.iter().find(|s| s.name == set);
    let what = info.map_or(String::new(), |i| {
        let pins = if i.pins.is_empty() { String::new() } else { format!(", pins {}", i.pins.join(" ")) };
        format!(" · {}: goals {}{pins}", i.rig, i.goals.join(" "))
    });
    format!("{set}{what} · {goals} target sets")
}

/// Writes the aligned plain-text table: one block per set, the targets, the legend.
pub fn text(w: &mut dyn Write, header: &RigsHeader, rows: &[RigRow], targets: &[Target]) -> io::Result<()> {
    writeln!(w, "ikarus bench --rigs: {}", facts(header))?;
    let all: Vec<[String; 8]> = rows.iter().map(cells).collect();
    let mut widths = HEADINGS.map(|h| h.chars().count());
    for c in &all {
        for (w, cell) in widths.iter_mut().zip(c) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let mut i = 0;
    while i < rows.len() {
        let set = rows[i].set;
        let end = rows[i..].iter().position(|r| r.set != set).map_or(rows.len(), |k| i + k);
        writeln!(w)?;
        writeln!(w, "{}", describe(header, set, rows[i].goals))?;
        for c in std::iter::once(HEADINGS.map(str::to_owned)).chain(all[i..end].iter().cloned()) {
            let mut s = String::from(" ");
            for ((cell, width), right) in c.iter().zip(widths).zip(RIGHT) {
                let pad = " ".repeat(width - cell.chars().count());
                s += "  ";
                if right { s += &format!("{pad}{cell}") } else { s += &format!("{cell}{pad}") }
            }
            writeln!(w, "{}", s.trim_end())?;
        }
        for r in &rows[i..end] {
            if let Some(e) = &r.solve_error {
                writeln!(w, "   note: {}: {} of {} solves returned an error: {e}", r.solver, r.solve_errors, r.goals)?;
            }
        }
        i = end;
    }
    writeln!(w)?;
    write_targets(w, targets, "")?;
    writeln!(w)?;
    for l in crate::table::wrap(LEGEND, 100) {
        writeln!(w, "{l}")?;
    }
    Ok(())
}

/// Writes the Markdown table: the command line, the facts, the table, the targets, the legend.
pub fn markdown(w: &mut dyn Write, header: &RigsHeader, rows: &[RigRow], targets: &[Target]) -> io::Result<()> {
    writeln!(w, "`{}`", header.command)?;
    writeln!(w)?;
    writeln!(w, "{}", facts(header))?;
    writeln!(w)?;
    writeln!(w, "| set | {} |", HEADINGS.join(" | "))?;
    writeln!(w, "|---|{}", RIGHT.map(|r| if r { "--:|" } else { "---|" }).concat())?;
    for r in rows {
        writeln!(w, "| {} | {} |", r.set, cells(r).join(" | "))?;
    }
    writeln!(w)?;
    for s in &header.sets {
        writeln!(w, "- {}", describe(header, s.name, header.goals))?;
    }
    writeln!(w)?;
    write_targets(w, targets, "- ")?;
    writeln!(w)?;
    writeln!(w, "{LEGEND}")
}

fn facts(h: &RigsHeader) -> String {
    let kdl = h.kdl_version.as_ref().map_or(String::new(), |v| format!(", KDL {v}"));
    let debug = if h.debug_build { " (debug build: times mean little)" } else { "" };
    format!(
        "ikarus {}{debug}{kdl}, {} target sets per set, seed {}, tolerance {}, one thread, {}-{} with {} CPUs",
        h.ikarus_version, h.goals, h.seed, h.tolerance, h.arch, h.os, h.cpus
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(set: &'static str, solver: &str, reached: usize, median_us: f64) -> RigRow {
        RigRow {
            set,
            solver: solver.to_owned(),
            limits: "lock",
            goals: 1000,
            reached,
            reached_percent: super::super::rows::percent(reached, 1000),
            outside_limits: 0,
            median_us,
            p99_us: 2.0 * median_us,
            mean_iterations: Some(7.0),
            worst_error: Some(1e-7),
            vs_kdl_tree: None,
            solve_errors: 0,
            solve_error: None,
        }
    }

    #[test]
    fn targets_are_checked_on_the_default_rows() {
        let rows = [
            row("puppet", "default", 1000, 8.0),
            row("puppet", "sequential", 400, 3.0),
            row("puppet", TREE_LABEL, 900, 48.0),
            row("hand", "default", 999, 30.0),
            row("hand", TREE_LABEL, 990, 100.0),
        ];
        let t = targets(&rows);
        assert_eq!(t.len(), 4);
        assert_eq!((t[0].met, t[0].figure.as_str()), (Some(true), "puppet 100.0%, hand 99.9%"));
        assert_eq!((t[1].met, t[1].figure.as_str()), (Some(true), "puppet 8.00 µs"));
        // The hand is only 3.3× faster than KDL.
        assert_eq!(t[2].met, Some(false));
        assert_eq!(t[2].figure, "puppet 6.00× (100.0% vs 90.0%), hand 3.33× (99.9% vs 99.0%)");
        assert_eq!((t[3].met, t[3].figure.as_str()), (Some(true), "puppet 40.0%"));
        // 998 of 1000 misses; without KDL, the KDL target is not measured.
        let t = targets(&[row("hand", "default", 998, 1.0)]);
        assert_eq!((t[0].met, t[1].met, t[2].met, t[3].met), (Some(false), None, None, None));
        assert_eq!(t[2].figure, "not measured (run with --kdl)");
    }

    #[test]
    fn cells_are_formatted() {
        let mut r = row("hand", "lm lock", 999, 12.345);
        r.vs_kdl_tree = Some(7.123);
        assert_eq!(
            cells(&r),
            ["lm lock", "lock", "99.9% (999)", "12.3", "24.7", "7.0", "1.0e-7", "7.12"].map(str::to_owned)
        );
        r.vs_kdl_tree = Some(132_732.05);
        assert_eq!(cells(&r)[7], "132732");
        r.worst_error = None;
        r.mean_iterations = None;
        assert_eq!((cells(&r)[5].as_str(), cells(&r)[6].as_str()), ("—", "inf"));
    }
}
