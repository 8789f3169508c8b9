//! The output of `ikarus bench --reach`: four aligned plain-text tables (verdict time, region
//! build, agreement, unreachable answered), Markdown tables for the README, or JSON; each with
//! the targets checked and every disagreement listed.

use std::io::{self, Write};

use serde::Serialize;

pub use crate::table::Target;
use crate::table::write_targets;

use super::agree::Agreement;
use super::timing::{BuildRow, GoalKind, SpeedupRow, VerdictRow};

/// What the output says about the run as a whole.
#[derive(Debug, Clone, Serialize)]
pub struct ReachHeader {
    /// The command line, as `ikarus bench …`.
    pub command: String,
    /// The version of ikarus.
    pub ikarus_version: &'static str,
    /// `--seed`.
    pub seed: u64,
    /// Random points per arm (`--points`).
    pub points: u64,
    /// Unreachable goals per speed-up row (`--goals`).
    pub goals: usize,
    /// Tolerance of the verdict and of every solve.
    pub tolerance: f64,
    /// Every this many points, an unreachable one is searched for by every method.
    pub subset_every: u64,
    /// Threads of the agreement check (the timings run on one).
    pub threads: usize,
    /// Logical CPUs of the machine.
    pub cpus: usize,
    /// Operating system and CPU architecture, as Rust names them.
    pub os: &'static str,
    pub arch: &'static str,
    /// Whether ikarus was built without optimisations (its times then mean little).
    pub debug_build: bool,
}

/// Everything measured.
#[derive(Debug, Clone, Serialize)]
pub struct ReachReport {
    pub header: ReachHeader,
    pub verdict: Vec<VerdictRow>,
    pub build: Vec<BuildRow>,
    pub agreement: Vec<Agreement>,
    pub speedup: Vec<SpeedupRow>,
    pub targets: Vec<Target>,
}

/// The targets: 100 % agreement on every arm; a verdict median ≤ 1 µs on every arm;
/// the seed arm's region built in under 1 ms and the eight-link arm's in ≤ 10 ms (medians);
/// and an unreachable goal of the seed arm (out of reach because of its limits) answered at
/// least 50× faster with the verdict than without.
pub fn targets(
    verdict: &[VerdictRow],
    build: &[BuildRow],
    agreement: &[Agreement],
    speedup: &[SpeedupRow],
) -> Vec<Target> {
    let join = |v: Vec<String>| v.join(", ");
    let mut out = Vec::new();
    out.push(Target {
        target: "100% agreement between the verdict and solving".to_owned(),
        met: (!agreement.is_empty()).then(|| agreement.iter().all(|a| a.agree == a.points)),
        figure: join(agreement.iter().map(|a| format!("{} {}% of {}", a.arm, a.agree_percent, a.points)).collect()),
    });
    out.push(Target {
        target: "verdict ≤ 1 µs per point (median)".to_owned(),
        met: (!verdict.is_empty()).then(|| verdict.iter().all(|v| v.median_ns <= 1000.0)),
        figure: join(verdict.iter().map(|v| format!("{} {:.0} ns", v.arm, v.median_ns)).collect()),
    });
    let built = |links: usize, limit_ms: f64, strict: bool| {
        let rows: Vec<&BuildRow> = build.iter().filter(|b| b.links == links).collect();
        Target {
            target: format!(
                "region of {links} links built in {} {limit_ms} ms (median)",
                if strict { "<" } else { "≤" }
            ),
            met: (!rows.is_empty())
                .then(|| rows.iter().all(|b| if strict { b.median_ms < limit_ms } else { b.median_ms <= limit_ms })),
            figure: join(rows.iter().map(|b| format!("{} {:.3} ms", b.arm, b.median_ms)).collect()),
        }
    };
    out.push(built(3, 1.0, true));
    out.push(built(8, 10.0, false));
    let seed: Vec<&SpeedupRow> = speedup.iter().filter(|s| s.arm == "seed" && s.kind == GoalKind::LimitsOnly).collect();
    out.push(Target {
        target: "unreachable goal (seed arm, out of reach by its limits) answered ≥ 50× faster".to_owned(),
        met: (!seed.is_empty()).then(|| seed.iter().all(|s| s.ratio >= 50.0)),
        figure: join(
            seed.iter()
                .map(|s| {
                    format!("{}× ({} vs {} µs)", ratio(s.ratio), micros(s.with_median_us), micros(s.without_median_us))
                })
                .collect(),
        ),
    });
    out
}

/// What the tables mean.
const LEGEND: &str = "verdict: Region::verdict(point, 1e-6) on the arm's exact region with its limits, over the \
random points (uniform in the square of side 2·reach about the base); median and p99 of each verdict timed alone \
(the clock's own time, `clock`, included); batched: median over batches of 1024 points timed as one, per point; one thread. build: Region::of(chain, true) \
repeated for about a second; eight is the seven arm plus a link of 0.4 with a range of ±150°. agreement: every \
point the verdict calls reachable must be reached by the default solver (SolveOptions::default(), limits \
locked, restarts), and no point it calls unreachable may be reached by lm's search with restarts and \
reach_verdict off, nor, on every 100th point, by any method but analytic (each with its default limit mode and \
restarts); reached means the final angles put the tip within 1e-6 of the point with every joint inside its \
limits, by forward kinematics. answered: unreachable points the default solver answered `unreachable` with the \
tip on the nearest reachable point. unreachable answered: the default options with the verdict and with \
reach_verdict off, from the arm's start pose, each solve timed alone, one thread; limits only: random points \
inside the annulus the verdict calls unreachable; beyond reach: random points outside the annulus (already \
answered without restarts before the verdict).";

type Table = (Vec<&'static str>, Vec<bool>, Vec<Vec<String>>);

fn verdict_table(rows: &[VerdictRow]) -> Table {
    let head = vec!["arm", "links", "points", "reachable", "median ns", "p99 ns", "batched ns", "clock ns"];
    let right = vec![false, true, true, true, true, true, true, true];
    let cells = rows
        .iter()
        .map(|v| {
            vec![
                v.arm.to_owned(),
                v.links.to_string(),
                v.points.to_string(),
                format!("{:.1}%", 100.0 * v.reachable as f64 / v.points.max(1) as f64),
                format!("{:.0}", v.median_ns),
                format!("{:.0}", v.p99_ns),
                format!("{:.0}", v.batched_ns),
                format!("{:.0}", v.clock_ns),
            ]
        })
        .collect();
    (head, right, cells)
}

fn build_table(rows: &[BuildRow]) -> Table {
    let head = vec!["arm", "links", "pieces", "area", "builds", "median ms", "min ms", "max ms"];
    let right = vec![false, true, true, true, true, true, true, true];
    let cells = rows
        .iter()
        .map(|b| {
            vec![
                b.arm.to_owned(),
                b.links.to_string(),
                b.pieces.to_string(),
                format!("{:.4}", b.area),
                b.builds.to_string(),
                format!("{:.3}", b.median_ms),
                format!("{:.3}", b.min_ms),
                format!("{:.3}", b.max_ms),
            ]
        })
        .collect();
    (head, right, cells)
}

fn agreement_table(rows: &[Agreement]) -> Table {
    let head = vec![
        "arm",
        "points",
        "reachable",
        "reached",
        "unreachable",
        "not reached",
        "answered",
        "subset",
        "none reached",
        "agree",
    ];
    let right = vec![false, true, true, true, true, true, true, true, true, true];
    let cells = rows
        .iter()
        .map(|a| {
            vec![
                a.arm.to_owned(),
                a.points.to_string(),
                a.reachable.to_string(),
                a.reached.to_string(),
                a.unreachable.to_string(),
                a.unreachable_confirmed.to_string(),
                a.answered_unreachable.to_string(),
                a.subset.to_string(),
                a.subset_confirmed.to_string(),
                format!("{}% ({})", a.agree_percent, a.agree),
            ]
        })
        .collect();
    (head, right, cells)
}

fn speedup_table(rows: &[SpeedupRow]) -> Table {
    let head = vec![
        "arm",
        "goals",
        "n",
        "verdict µs",
        "search µs",
        "×",
        "unreachable",
        "search iter",
        "restarts",
        "search ended",
    ];
    let right = vec![false, false, true, true, true, true, true, true, true, false];
    let cells = rows
        .iter()
        .map(|s| {
            vec![
                s.arm.to_owned(),
                s.kind.name().to_owned(),
                s.goals.to_string(),
                micros(s.with_median_us),
                micros(s.without_median_us),
                ratio(s.ratio),
                s.with_unreachable.to_string(),
                format!("{:.1}", s.without_iterations),
                format!("{:.1}", s.without_restarts),
                s.without_statuses.iter().map(|(st, c)| format!("{st} {c}")).collect::<Vec<_>>().join(", "),
            ]
        })
        .collect();
    (head, right, cells)
}

/// The four tables with their titles.
fn tables(r: &ReachReport) -> [(String, Table); 4] {
    let points = r.header.points;
    [
        ("verdict time per point, limits on".to_owned(), verdict_table(&r.verdict)),
        ("region build time, limits on".to_owned(), build_table(&r.build)),
        (format!("verdict against solving over {points} random points per arm"), agreement_table(&r.agreement)),
        (
            "unreachable goal answered: with the verdict vs. the search (reach_verdict off)".to_owned(),
            speedup_table(&r.speedup),
        ),
    ]
}

/// The JSON document: the report as it is.
pub fn json(w: &mut dyn Write, r: &ReachReport) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *w, r)?;
    writeln!(w)
}

/// Writes the aligned plain-text tables, the disagreements, the targets and the legend.
pub fn text(w: &mut dyn Write, r: &ReachReport) -> io::Result<()> {
    writeln!(w, "ikarus bench --reach: {}", facts(&r.header))?;
    for (title, (head, right, rows)) in tables(r) {
        writeln!(w)?;
        writeln!(w, "{title}")?;
        let mut widths: Vec<usize> = head.iter().map(|h| h.chars().count()).collect();
        for row in &rows {
            for (w, c) in widths.iter_mut().zip(row) {
                *w = (*w).max(c.chars().count());
            }
        }
        let head: Vec<String> = head.iter().map(|&h| h.to_owned()).collect();
        for row in std::iter::once(&head).chain(&rows) {
            let mut s = String::from(" ");
            for ((cell, &width), &right) in row.iter().zip(&widths).zip(&right) {
                let pad = " ".repeat(width - cell.chars().count());
                s += "  ";
                if right { s += &format!("{pad}{cell}") } else { s += &format!("{cell}{pad}") }
            }
            writeln!(w, "{}", s.trim_end())?;
        }
    }
    writeln!(w)?;
    write_disagreements(w, r, "")?;
    writeln!(w)?;
    write_targets(w, &r.targets, "")?;
    writeln!(w)?;
    for l in crate::table::wrap(LEGEND, 100) {
        writeln!(w, "{l}")?;
    }
    Ok(())
}

/// Writes the Markdown tables: the command line, the facts, the tables, the disagreements, the
/// targets, the legend.
pub fn markdown(w: &mut dyn Write, r: &ReachReport) -> io::Result<()> {
    writeln!(w, "`{}`", r.header.command)?;
    writeln!(w)?;
    writeln!(w, "{}", facts(&r.header))?;
    for (title, (head, right, rows)) in tables(r) {
        writeln!(w)?;
        writeln!(w, "{title}:")?;
        writeln!(w)?;
        writeln!(w, "| {} |", head.join(" | "))?;
        writeln!(w, "|{}", right.iter().map(|&r| if r { "--:|" } else { "---|" }).collect::<String>())?;
        for row in rows {
            writeln!(w, "| {} |", row.join(" | "))?;
        }
    }
    writeln!(w)?;
    write_disagreements(w, r, "- ")?;
    writeln!(w)?;
    write_targets(w, &r.targets, "- ")?;
    writeln!(w)?;
    writeln!(w, "{LEGEND}")
}

/// How many disagreements are listed in text and Markdown (JSON has all).
const LISTED: usize = 50;

fn write_disagreements(w: &mut dyn Write, r: &ReachReport, bullet: &str) -> io::Result<()> {
    let all: Vec<_> = r.agreement.iter().flat_map(|a| a.disagreements.iter().map(move |d| (a.arm, d))).collect();
    writeln!(w, "disagreements: {}", all.len())?;
    if !all.is_empty() && !bullet.is_empty() {
        writeln!(w)?;
    }
    for (arm, d) in all.iter().take(LISTED) {
        writeln!(
            w,
            "{bullet}{arm} point {} ({}, {}): verdict {} (distance {:.3e}), {:.3e} from the boundary; {} ended {} with the tip {:.3e} away{}",
            d.index,
            d.point[0],
            d.point[1],
            if d.reachable { "reachable" } else { "unreachable" },
            d.distance,
            d.boundary_distance,
            d.solver,
            d.status,
            d.error,
            if d.inside_limits { "" } else { ", outside the limits" },
        )?;
    }
    if all.len() > LISTED {
        writeln!(w, "{bullet}… and {} more (--json lists every one)", all.len() - LISTED)?;
    }
    Ok(())
}

fn facts(h: &ReachHeader) -> String {
    let debug = if h.debug_build { " (debug build: times mean little)" } else { "" };
    format!(
        "ikarus {}{debug}, seed {}, {} points per arm, {} goals per speed-up row, tolerance {}, timings on one thread, agreement on {}, {}-{} with {} CPUs",
        h.ikarus_version, h.seed, h.points, h.goals, h.tolerance, h.threads, h.arch, h.os, h.cpus
    )
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reach::agree::Disagreement;

    fn agreement(arm: &'static str, points: u64, agree: u64) -> Agreement {
        Agreement {
            arm,
            points,
            agree,
            agree_percent: super::super::agree::percent(agree, points),
            ..Agreement::default()
        }
    }

    fn speedup(arm: &'static str, kind: GoalKind, with: f64, without: f64) -> SpeedupRow {
        SpeedupRow {
            arm,
            kind,
            goals: 10,
            with_median_us: with,
            without_median_us: without,
            ratio: without / with,
            with_unreachable: 10,
            without_iterations: 300.0,
            without_restarts: 16.0,
            without_statuses: vec![("stalled", 10)],
        }
    }

    fn build(arm: &'static str, links: usize, median_ms: f64) -> BuildRow {
        BuildRow { arm, links, builds: 11, pieces: 40, area: 1.0, median_ms, min_ms: median_ms, max_ms: median_ms }
    }

    fn verdict(arm: &'static str, median_ns: f64) -> VerdictRow {
        VerdictRow {
            arm,
            links: 3,
            points: 100,
            reachable: 40,
            median_ns,
            p99_ns: 2.0 * median_ns,
            batched_ns: median_ns,
            clock_ns: 20.0,
        }
    }

    #[test]
    fn targets_are_checked() {
        let t = targets(
            &[verdict("seed", 120.0), verdict("seven", 400.0)],
            &[build("seed", 3, 0.2), build("seven", 7, 0.8), build("eight", 8, 0.9)],
            &[agreement("seed", 1000, 1000), agreement("seven", 1000, 1000)],
            &[speedup("seed", GoalKind::LimitsOnly, 0.5, 150.0), speedup("seed", GoalKind::Beyond, 0.5, 1.0)],
        );
        assert!(t.iter().all(|t| t.met == Some(true)), "{t:?}");
        assert_eq!(t[0].figure, "seed 100% of 1000, seven 100% of 1000");
        assert_eq!(t[4].figure, "300× (0.50 vs 150.0 µs)");
        // One disagreement, a slow verdict, a slow build, a small ratio: each missed.
        let t = targets(
            &[verdict("seed", 1001.0)],
            &[build("seed", 3, 1.0), build("eight", 8, 10.5)],
            &[agreement("seed", 1_000_000, 999_999)],
            &[speedup("seed", GoalKind::LimitsOnly, 2.0, 99.0)],
        );
        assert!(t.iter().all(|t| t.met == Some(false)), "{t:?}");
        assert_eq!(t[0].figure, "seed 99.9999% of 1000000");
        // Nothing measured.
        assert!(targets(&[], &[], &[], &[]).iter().all(|t| t.met.is_none()));
    }

    #[test]
    fn disagreements_are_listed() {
        let mut a = agreement("seed", 10, 9);
        a.disagreements.push(Disagreement {
            index: 7,
            point: [1.5, -2.0],
            reachable: true,
            distance: 0.0,
            boundary_distance: 3e-7,
            solver: "default".to_owned(),
            status: "stalled",
            error: 0.01,
            inside_limits: true,
        });
        let header = ReachHeader {
            command: "ikarus bench --reach".to_owned(),
            ikarus_version: "0",
            seed: 1,
            points: 10,
            goals: 10,
            tolerance: 1e-6,
            subset_every: 100,
            threads: 2,
            cpus: 2,
            os: "linux",
            arch: "x86_64",
            debug_build: false,
        };
        let r = ReachReport {
            header,
            verdict: vec![],
            build: vec![],
            agreement: vec![a],
            speedup: vec![],
            targets: vec![],
        };
        let mut out = Vec::new();
        text(&mut out, &r).unwrap();
        let out = String::from_utf8(out).unwrap();
        assert!(out.contains("disagreements: 1\n"), "{out}");
        assert!(
            out.contains("seed point 7 (1.5, -2): verdict reachable (distance 0.000e0), 3.000e-7 from the boundary; default ended stalled with the tip 1.000e-2 away\n"),
            "{out}"
        );
        let mut md = Vec::new();
        markdown(&mut md, &r).unwrap();
        assert!(String::from_utf8(md).unwrap().contains("| seed | 10 | 0 | 0 | 0 | 0 | 0 | 0 | 0 | 90% (9) |"));
    }
}
