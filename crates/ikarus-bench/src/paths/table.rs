//! The output of `ikarus bench --paths`: an aligned plain-text table (one block per arm and
//! limits setting), a Markdown table for the README, or JSON; each with the targets checked.

use std::io::{self, Write};

use serde::Serialize;

use super::rows::{PathRow, Target};

/// What the output says about the run as a whole.
#[derive(Debug, Clone, Serialize)]
pub struct PathsHeader {
    /// The command line, as `ikarus bench …`.
    pub command: String,
    /// The version of ikarus.
    pub ikarus_version: &'static str,
    /// The version `kdl_bench` reported; `None` without `--kdl`.
    pub kdl_version: Option<String>,
    /// `--seed`.
    pub seed: u64,
    /// Paths per arm and limits setting.
    pub paths_per_set: usize,
    /// Samples per path.
    pub samples: usize,
    /// The arms benchmarked.
    pub arms: Vec<&'static str>,
    /// Paths in all, FK-made, and of the kind `beyond`.
    pub paths: usize,
    pub fk_paths: usize,
    pub beyond_paths: usize,
    /// The flip bound, degrees.
    pub max_step_deg: f64,
    /// The generating trajectories' bound on a joint step, degrees.
    pub generator_max_step_deg: f64,
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

/// What the columns mean.
const LEGEND: &str = "follow: ikarus::track::follow (online, warm-started, steps bounded). plan: \
ikarus::track::plan (ladder search + polish). scratch: every sample solved from the start pose with the \
defaults. kdl lma warm: KDL's LMA, each sample from the previous sample's answer. reached: samples whose \
final angles put the tip within 1e-6 of the goal (and inside the ranges when limits are on), by forward \
kinematics. limited: samples follow held to the step bound. flips: steps over the bound (paths with ≥ 1). \
FK flips: FK paths (a continuous solution exists) with ≥ 1 flip, and FK samples missed. step÷gen: the \
largest, over FK paths, of the path's largest joint step over its generating trajectory's. max step: the \
largest joint step of any path, degrees. v, a, j: medians over paths of each path's largest joint \
velocity, acceleration and jerk, degrees per sample^k. median/p99: µs per sample (plan: the path's time \
divided by its samples, one value per path), one thread.";

/// The headings of the columns after arm and limits.
const HEADINGS: [&str; 13] = [
    "solver",
    "kind",
    "reached",
    "limited",
    "flips (paths)",
    "FK flips, missed",
    "step÷gen",
    "max step°",
    "v°",
    "a°",
    "j°",
    "median µs",
    "p99 µs",
];

fn cells(r: &PathRow) -> [String; 13] {
    [
        r.solver.to_owned(),
        r.kind.to_owned(),
        format!("{:.1}% ({}/{})", r.reached_percent, r.reached, r.samples),
        r.limited.map_or("—".to_owned(), |l| l.to_string()),
        format!("{} ({})", r.flips, r.paths_with_flips),
        format!("{}/{}, {}", r.fk_paths_with_flips, r.fk_paths, r.fk_samples_missed),
        r.step_ratio_max.map_or("—".to_owned(), |x| format!("{x:.2}")),
        format!("{:.1}", r.max_step_deg),
        format!("{:.2}", r.velocity_deg_median),
        format!("{:.2}", r.acceleration_deg_median),
        format!("{:.2}", r.jerk_deg_median),
        micros(r.median_us),
        micros(r.p99_us),
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

fn limits(on: bool) -> &'static str {
    if on { "limits on" } else { "limits off" }
}

/// The JSON document.
#[derive(Serialize)]
struct Json<'a> {
    header: &'a PathsHeader,
    rows: &'a [PathRow],
    targets: &'a [Target],
}

/// Writes the report as JSON: the header, every row (the `all` rows and, always, the per-kind
/// rows), the targets.
pub fn json(w: &mut dyn Write, header: &PathsHeader, rows: &[PathRow], targets: &[Target]) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *w, &Json { header, rows, targets })?;
    writeln!(w)
}

/// Writes the aligned plain-text table: one block per arm and limits setting, the targets, the
/// legend.
pub fn text(w: &mut dyn Write, header: &PathsHeader, rows: &[PathRow], targets: &[Target]) -> io::Result<()> {
    writeln!(w, "ikarus bench --paths: {}", facts(header))?;
    let all: Vec<[String; 13]> = rows.iter().map(cells).collect();
    let mut widths = HEADINGS.map(|h| h.chars().count());
    for c in &all {
        for (w, cell) in widths.iter_mut().zip(c) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let mut i = 0;
    while i < rows.len() {
        let (arm, on) = (rows[i].arm, rows[i].limits);
        let end = rows[i..].iter().position(|r| r.arm != arm || r.limits != on).map_or(rows.len(), |k| i + k);
        writeln!(w)?;
        let beyond = rows[i].beyond_samples;
        writeln!(w, "{arm} · {} · {} paths, {beyond} samples beyond the reach", limits(on), rows[i].paths)?;
        for c in std::iter::once(HEADINGS.map(str::to_owned)).chain(all[i..end].iter().cloned()) {
            let mut s = String::from(" ");
            for (k, (cell, width)) in c.iter().zip(widths).enumerate() {
                let pad = " ".repeat(width - cell.chars().count());
                s += "  ";
                if k < 2 { s += &format!("{cell}{pad}") } else { s += &format!("{pad}{cell}") }
            }
            writeln!(w, "{}", s.trim_end())?;
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
pub fn markdown(w: &mut dyn Write, header: &PathsHeader, rows: &[PathRow], targets: &[Target]) -> io::Result<()> {
    writeln!(w, "`{}`", header.command)?;
    writeln!(w)?;
    writeln!(w, "{}", facts(header))?;
    writeln!(w)?;
    writeln!(w, "| arm | limits | {} |", HEADINGS.join(" | "))?;
    writeln!(w, "|---|---|---|---|{}", "--:|".repeat(HEADINGS.len() - 2))?;
    for r in rows {
        let on = if r.limits { "on" } else { "off" };
        writeln!(w, "| {} | {on} | {} |", r.arm, cells(r).join(" | "))?;
    }
    writeln!(w)?;
    write_targets(w, targets, "- ")?;
    writeln!(w)?;
    writeln!(w, "{LEGEND}")
}

fn write_targets(w: &mut dyn Write, targets: &[Target], bullet: &str) -> io::Result<()> {
    let met = targets.iter().filter(|t| t.met).count();
    writeln!(w, "targets: {met} of {} met", targets.len())?;
    if !bullet.is_empty() {
        writeln!(w)?;
    }
    for t in targets {
        writeln!(w, "{bullet}{} {}: {}", if t.met { "met" } else { "MISSED" }, t.target, t.figure)?;
    }
    Ok(())
}

fn facts(h: &PathsHeader) -> String {
    let kdl = h.kdl_version.as_ref().map_or(String::new(), |v| format!(", KDL {v}"));
    let debug = if h.debug_build { " (debug build: times mean little)" } else { "" };
    format!(
        "ikarus {}{debug}{kdl}, seed {}, {} paths ({} per arm and limits setting; {} made by forward kinematics, \
         {} leaving the reach) of {} samples, flip bound {}°, one thread, {}-{} with {} CPUs",
        h.ikarus_version,
        h.seed,
        h.paths,
        h.paths_per_set,
        h.fk_paths,
        h.beyond_paths,
        h.samples,
        h.max_step_deg,
        h.arch,
        h.os,
        h.cpus
    )
}
