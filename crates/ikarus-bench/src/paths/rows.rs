//! The rows of `ikarus bench --paths`: each solver's path metrics summed up per arm, limits
//! setting and (optionally) kind, and the targets checked against them.

use ikarus_edge::stats::{median, nearest_rank};
use serde::Serialize;

use super::measure::{Answer, PathMetrics, PathSolver};
use super::set::{Kind, PathSet};

/// One row of the table.
#[derive(Debug, Clone, Serialize)]
pub struct PathRow {
    /// The arm's name.
    pub arm: &'static str,
    /// Whether the limits were enforced.
    pub limits: bool,
    /// The kind of path, or `all`.
    pub kind: &'static str,
    /// The solver's label.
    pub solver: &'static str,
    /// Paths.
    pub paths: usize,
    /// Samples over all paths.
    pub samples: usize,
    /// Samples reached (judged by forward kinematics).
    pub reached: usize,
    /// `reached` as a percentage of `samples`, truncated to a tenth.
    pub reached_percent: f64,
    /// Samples no pose reaches (farther than the reach from the base).
    pub beyond_samples: usize,
    /// Samples `follow` marked `limited`; `None` for the other solvers.
    pub limited: Option<usize>,
    /// Steps over the flip bound, over all paths.
    pub flips: usize,
    /// Paths with at least one flip.
    pub paths_with_flips: usize,
    /// FK paths (a continuous solution exists).
    pub fk_paths: usize,
    /// FK paths with at least one flip.
    pub fk_paths_with_flips: usize,
    /// Samples of FK paths not reached.
    pub fk_samples_missed: usize,
    /// The largest ratio, over FK paths, of the path's largest joint step to the generating
    /// trajectory's; `None` without FK paths.
    pub step_ratio_max: Option<f64>,
    /// The largest joint step of any path, degrees.
    pub max_step_deg: f64,
    /// Medians over paths of each path's largest joint velocity, acceleration and jerk, degrees
    /// per sample, sample² and sample³.
    pub velocity_deg_median: f64,
    pub acceleration_deg_median: f64,
    pub jerk_deg_median: f64,
    /// Median and 99th percentile (nearest rank) of the time per sample, µs.
    pub median_us: f64,
    pub p99_us: f64,
}

/// The row of `solver` on the paths of `set` whose kind is `kind` (`None`: every path).
pub fn row(
    set: &PathSet,
    kind: Option<Kind>,
    solver: PathSolver,
    answers: &[Answer],
    metrics: &[PathMetrics],
) -> Option<PathRow> {
    let picked: Vec<usize> = (0..set.paths.len()).filter(|&k| kind.is_none_or(|c| set.paths[k].kind == c)).collect();
    if picked.is_empty() {
        return None;
    }
    let paths = || picked.iter().map(|&k| (&set.paths[k], &metrics[k]));
    let samples: usize = paths().map(|(p, _)| p.path.len()).sum();
    let reached: usize = paths().map(|(_, m)| m.reached).sum();
    let fk = || paths().filter(|(p, _)| p.kind.fk());
    let sorted = |f: &dyn Fn(&PathMetrics) -> f64| {
        let mut v: Vec<f64> = paths().map(|(_, m)| f(m).to_degrees()).collect();
        v.sort_by(f64::total_cmp);
        median(&v)
    };
    let mut micros: Vec<f64> = picked.iter().flat_map(|&k| answers[k].micros.iter().copied()).collect();
    micros.sort_by(f64::total_cmp);
    Some(PathRow {
        arm: set.arm,
        limits: set.limited,
        kind: kind.map_or("all", Kind::name),
        solver: solver.label(),
        paths: picked.len(),
        samples,
        reached,
        reached_percent: (1000.0 * reached as f64 / samples as f64).floor() / 10.0,
        beyond_samples: paths().map(|(p, _)| p.beyond).sum(),
        limited: (solver == PathSolver::Follow).then(|| paths().map(|(_, m)| m.limited).sum()),
        flips: paths().map(|(_, m)| m.flips).sum(),
        paths_with_flips: paths().filter(|(_, m)| m.flips > 0).count(),
        fk_paths: fk().count(),
        fk_paths_with_flips: fk().filter(|(_, m)| m.flips > 0).count(),
        fk_samples_missed: fk().map(|(p, m)| p.path.len() - m.reached).sum(),
        step_ratio_max: fk().filter_map(|(p, m)| p.truth_step.map(|t| m.max_step / t)).reduce(f64::max),
        max_step_deg: paths().map(|(_, m)| m.max_step.to_degrees()).fold(0.0, f64::max),
        velocity_deg_median: sorted(&|m| m.max_step),
        acceleration_deg_median: sorted(&|m| m.max_acceleration),
        jerk_deg_median: sorted(&|m| m.max_jerk),
        median_us: if micros.is_empty() { f64::NAN } else { median(&micros) },
        p99_us: if micros.is_empty() { f64::NAN } else { nearest_rank(&micros, 0.99) },
    })
}

/// One target of the issue, checked.
#[derive(Debug, Clone, Serialize)]
pub struct Target {
    /// What is promised.
    pub target: String,
    /// Whether it holds.
    pub met: bool,
    /// The figure it was judged by.
    pub figure: String,
}

/// The targets, checked on the `all` rows: `plan` without flips and reaching every
/// sample on FK paths, with steps at most twice the generating trajectory's; `follow` never
/// over the bound; `follow` ≤ 1 µs per sample (median) on the seed arm and ≤ 2 µs on seven;
/// `plan` under 1 ms per sample on the seed arm.
pub fn targets(rows: &[PathRow], max_step_deg: f64) -> Vec<Target> {
    let mut out = Vec::new();
    for r in rows.iter().filter(|r| r.kind == "all") {
        let at = format!("{} limits {}", r.arm, if r.limits { "on" } else { "off" });
        let mut push = |target: String, met: bool, figure: String| out.push(Target { target, met, figure });
        match r.solver {
            "plan" => {
                push(
                    format!("{at}: plan has 0 flips and reaches every sample on FK paths"),
                    r.fk_paths_with_flips == 0 && r.fk_samples_missed == 0,
                    format!(
                        "{} of {} FK paths with flips, {} FK samples missed",
                        r.fk_paths_with_flips, r.fk_paths, r.fk_samples_missed
                    ),
                );
                if let Some(ratio) = r.step_ratio_max {
                    push(
                        format!("{at}: plan's largest step ≤ 2× the generating trajectory's"),
                        ratio <= 2.0,
                        format!("{ratio:.2}×"),
                    );
                }
                if r.arm == "seed" {
                    push(
                        format!("{at}: plan well under 1 ms per sample"),
                        r.median_us < 1000.0,
                        format!("median {:.1} µs, p99 {:.1} µs per sample", r.median_us, r.p99_us),
                    );
                }
            }
            "follow" => {
                push(
                    format!("{at}: follow never steps over {max_step_deg}°"),
                    r.flips == 0 && r.max_step_deg <= max_step_deg * (1.0 + 1e-9),
                    format!("largest step {:.3}°", r.max_step_deg),
                );
                let bound = match r.arm {
                    "seed" => Some(1.0),
                    "seven" => Some(2.0),
                    _ => None,
                };
                if let Some(b) = bound {
                    push(
                        format!("{at}: follow median ≤ {b} µs per sample"),
                        r.median_us <= b,
                        format!("median {:.2} µs", r.median_us),
                    );
                }
            }
            _ => {}
        }
    }
    out
}
