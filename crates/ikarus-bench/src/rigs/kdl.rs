//! The KDL side of `ikarus bench --rigs`: a rig goal file (format `ikarus-rig-goals 1`, see
//! `bench/kdl/README.md`) for `bench/kdl/kdl_bench`, which solves it with KDL's tree solver
//! (`TreeIkSolverPos_NR_JL` over `TreeIkSolverVel_wdls`), and its per-solve output.

use std::fmt::Write as _;
use std::path::Path;

use ikarus::SolveOptions;
use ikarus_edge::error::Error;

use super::judge::Judge;
use super::rows::{RigRow, RigTally};
use super::set::RigSet;
use crate::kdl::{KdlSolve, run_file};

/// Label of the rows of KDL's tree solver.
pub const TREE_LABEL: &str = "kdl tree nr_jl";

/// The damping of KDL's `TreeIkSolverVel_wdls` that ikarus writes into rig goal files. KDL's
/// default is 0, which divides 0 by 0 on the planar rigs' zero singular values (a bone moves
/// its tips only in the plane): the steps turn NaN and a solve runs its 1000 iterations for
/// over a second. On 60 target sets of each set, KDL reached as many with 1e-5, 1e-4 and 1e-3
/// and fewer with 1e-2 and 0.1; its time varied within noise.
pub const KDL_LAMBDA: f64 = 1e-3;

/// The rig goal file of `set`. `comment` goes in a `#` line after the first. Floats are written
/// with Rust's `{}`, which reads back to the same number; angles and limits in radians.
pub fn rig_file(set: &RigSet, comment: &str) -> String {
    let s = &set.skeleton;
    let opts = SolveOptions::default();
    let join = |v: Vec<String>| v.join(" ");
    let floats = |v: &[f64]| join(v.iter().map(f64::to_string).collect());
    let mut f = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(f, "ikarus-rig-goals 1");
    let _ = writeln!(f, "# {}", comment.replace('\n', " "));
    let _ = writeln!(f, "name {}", set.name());
    let _ = writeln!(f, "bones {}", s.len());
    let _ = writeln!(f, "base {} {}", s.base().x, s.base().y);
    let _ = writeln!(
        f,
        "parents {}",
        join(s.parents().iter().map(|p| p.map_or("-1".to_owned(), |p| p.to_string())).collect())
    );
    let _ = writeln!(f, "lengths {}", floats(s.lengths()));
    let limits =
        s.limits().iter().map(|l| l.map_or("nan nan".to_owned(), |l| format!("{} {}", l.min(), l.max()))).collect();
    let _ = writeln!(f, "limits {}", join(limits));
    let _ = writeln!(f, "start {}", floats(&set.start));
    let _ = writeln!(f, "effectors {}", join(set.effectors().map(|e| e.to_string()).collect()));
    let pinned = set.goals.iter().map(|_| "0").chain(set.pins.iter().map(|_| "1")).map(str::to_owned).collect();
    let _ = writeln!(f, "pinned {}", join(pinned));
    let _ = writeln!(f, "tolerance {}", opts.tolerance);
    let _ = writeln!(f, "max_iterations {}", opts.max_iterations);
    let _ = writeln!(f, "lambda {KDL_LAMBDA}");
    let _ = writeln!(f, "goals {}", set.cases.len());
    for c in &set.cases {
        let mut line: Vec<String> = Vec::with_capacity(3 * (set.goals.len() + set.pins.len()));
        for (t, phi) in c.targets.iter().zip(&c.directions) {
            line.extend([t.x.to_string(), t.y.to_string(), phi.to_string()]);
        }
        for (tip, phi) in &set.pin_targets {
            line.extend([tip.x.to_string(), tip.y.to_string(), phi.to_string()]);
        }
        let _ = writeln!(f, "{}", line.join(" "));
    }
    f
}

/// The output of one `kdl_bench` run on a rig goal file.
#[derive(Debug, Clone, PartialEq)]
pub struct KdlRigRun {
    /// KDL's version, from the first line.
    pub version: String,
    /// One solve per target set, in order; the angles in the skeleton's order.
    pub solves: Vec<KdlSolve>,
}

impl KdlRigRun {
    /// Judges every solve the way the ikarus rows are judged.
    pub fn row(&self, set: &RigSet) -> RigRow {
        let mut judge = Judge::default();
        let mut tally = RigTally::new(self.solves.len());
        for (s, case) in self.solves.iter().zip(&set.cases) {
            tally.add(s.nanos, s.iterations, judge.judge(set, case, &s.angles));
        }
        // NR_JL clamps every iterate into the limits.
        tally.finish(set, TREE_LABEL.to_owned(), "clamp")
    }
}

/// Parses `kdl_bench`'s output for `set`, strictly: the version line, then exactly one `tree`
/// line per target set in order, each with one angle per bone. The error names the line.
pub fn parse_output(text: &str, set: &RigSet) -> Result<KdlRigRun, String> {
    let (n, goals) = (set.skeleton.len(), set.cases.len());
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let version = match lines.next().map(|(_, l)| (l, l.split_whitespace().collect::<Vec<_>>())) {
        None => return Err("no output".to_owned()),
        Some((_, t)) if t.len() == 2 && t[0] == "kdl" => t[1].to_owned(),
        Some((l, _)) => return Err(format!("line 1: expected `kdl VERSION`, got `{}`", shorten(l))),
    };
    let mut solves = Vec::with_capacity(goals);
    for (k, line) in lines {
        let at = |m: String| format!("line {k}: {m}");
        let t: Vec<&str> = line.split_whitespace().collect();
        match t.first() {
            None => return Err(at("empty line".to_owned())),
            Some(&"tree") => {}
            Some(other) => return Err(at(format!("unknown solver `{}`", shorten(other)))),
        }
        if t.len() != 5 + n {
            return Err(at(format!(
                "expected {} fields (tree, goal, ns, iterations, code, {n} angles), got {}",
                5 + n,
                t.len()
            )));
        }
        if solves.len() == goals {
            return Err(at(format!("more than {goals} `tree` lines")));
        }
        let index: usize = number(t[1], "goal index").map_err(at)?;
        if index != solves.len() {
            return Err(at(format!("goal index {index}, expected {}", solves.len())));
        }
        let nanos: i64 = number(t[2], "nanoseconds").map_err(at)?;
        let iterations: i64 = number(t[3], "iterations").map_err(at)?;
        let return_code: i64 = number(t[4], "return code").map_err(at)?;
        if nanos < 0 {
            return Err(at(format!("nanoseconds: must not be negative, got {nanos}")));
        }
        if iterations < -1 {
            return Err(at(format!("iterations: must be -1 (unknown) or more, got {iterations}")));
        }
        let angles = t[5..]
            .iter()
            .enumerate()
            .map(|(j, a)| number::<f64>(a, &format!("q_{j}")).map_err(at))
            .collect::<Result<Vec<f64>, String>>()?;
        solves.push(KdlSolve { nanos: nanos as u64, iterations: u64::try_from(iterations).ok(), return_code, angles });
    }
    if solves.len() != goals {
        return Err(format!("{} `tree` lines for {goals} target sets", solves.len()));
    }
    Ok(KdlRigRun { version, solves })
}

fn number<T: std::str::FromStr>(token: &str, what: &str) -> Result<T, String> {
    token.parse().map_err(|_| format!("{what}: `{}` is not a valid number", shorten(token)))
}

fn shorten(s: &str) -> String {
    let mut out: String = s.chars().take(40).collect();
    if out.len() < s.len() {
        out.push('…');
    }
    out
}

/// Writes the rig goal file of `set` into `dir`, runs `kdl_bench` on it and parses its output.
/// Any failure is one line naming `--kdl` and the path (exit 1).
pub fn run(path: &Path, set: &RigSet, dir: &Path, comment: &str) -> Result<KdlRigRun, Error> {
    let file = dir.join(format!("{}.rig-goals", set.name()));
    let text = run_file(path, &file, &rig_file(set, comment), set.name())?;
    parse_output(&text, set)
        .map_err(|m| Error::runtime(format!("--kdl {}: set {}: output {m}", path.display(), set.name())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigs::set::{RigSetName, generate};

    fn line(i: usize, angles: &[f64]) -> String {
        let a: Vec<String> = angles.iter().map(|x| format!("{x:.17e}")).collect();
        format!("tree {i} 2500 -1 0 {}\n", a.join(" "))
    }

    #[test]
    fn rig_files_follow_the_format_and_read_back_exactly() {
        let s = generate(RigSetName::PuppetPins, 3, 1).unwrap();
        let text = rig_file(&s, "test\nmore");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(&lines[..5], ["ikarus-rig-goals 1", "# test more", "name puppet-pins", "bones 16", "base 0 0"]);
        let values = |key: &str| -> Vec<f64> {
            let l = lines.iter().find(|l| l.split(' ').next() == Some(key)).unwrap();
            l.split(' ').skip(1).map(|t| t.parse().unwrap()).collect()
        };
        let parents: Vec<Option<usize>> =
            values("parents").iter().map(|&p| if p < 0.0 { None } else { Some(p as usize) }).collect();
        assert_eq!(parents, s.skeleton.parents());
        assert_eq!(values("lengths"), s.skeleton.lengths());
        let limits = values("limits");
        for (i, l) in s.skeleton.limits().iter().enumerate() {
            assert_eq!([limits[2 * i], limits[2 * i + 1]], [l.unwrap().min(), l.unwrap().max()]);
        }
        assert_eq!(values("start"), s.start);
        let effectors: Vec<usize> = values("effectors").iter().map(|&e| e as usize).collect();
        assert_eq!(effectors, s.effectors().collect::<Vec<_>>());
        assert_eq!(values("pinned"), [0.0, 0.0, 1.0, 1.0]);
        assert_eq!(values("lambda"), [KDL_LAMBDA]);
        assert_eq!(values("goals"), [3.0]);
        let first = lines.iter().position(|l| l.starts_with("goals ")).unwrap() + 1;
        assert_eq!(lines.len(), first + 3);
        for (l, c) in lines[first..].iter().zip(&s.cases) {
            let v: Vec<f64> = l.split(' ').map(|t| t.parse().unwrap()).collect();
            assert_eq!(v.len(), 12);
            assert_eq!([v[0], v[1], v[3], v[4]], [c.targets[0].x, c.targets[0].y, c.targets[1].x, c.targets[1].y]);
            assert_eq!([v[6], v[7], v[8]], [s.pin_targets[0].0.x, s.pin_targets[0].0.y, s.pin_targets[0].1]);
        }
    }

    #[test]
    fn output_round_trips_and_is_judged() {
        let s = generate(RigSetName::Hand, 2, 1).unwrap();
        let text = format!("kdl 1.5.1\n{}{}", line(0, &s.cases[0].config), line(1, &s.start));
        let run = parse_output(&text, &s).unwrap();
        assert_eq!(run.version, "1.5.1");
        assert_eq!(run.solves[0].angles, s.cases[0].config, "angles read back bit for bit");
        assert_eq!((run.solves[1].iterations, run.solves[1].nanos), (None, 2500));
        let row = run.row(&s);
        assert_eq!((row.solver.as_str(), row.goals, row.reached), (TREE_LABEL, 2, 1));
        assert_eq!(row.median_us, 2.5);
    }

    #[test]
    fn bad_output_names_the_line() {
        let s = generate(RigSetName::Hand, 2, 1).unwrap();
        let ok = |i| line(i, &s.start);
        let cases = [
            (String::new(), "no output"),
            ("kdl\n".to_owned(), "line 1: expected `kdl VERSION`"),
            (format!("kdl 1\n{}", ok(0)), "1 `tree` lines for 2 target sets"),
            (format!("kdl 1\n{}{}{}", ok(0), ok(1), ok(2)), "line 4: more than 2 `tree` lines"),
            (format!("kdl 1\n{}{}", ok(1), ok(0)), "line 2: goal index 1, expected 0"),
            (format!("kdl 1\n{}tree 1 5 -1 0 1 2\n", ok(0)), "line 3: expected 22 fields"),
            (format!("kdl 1\n{}lma 1 5 -1 0 1 2\n", ok(0)), "line 3: unknown solver `lma`"),
            (format!("kdl 1\n{}\n{}", ok(0), ok(1)), "line 3: empty line"),
            (
                format!("kdl 1\n{}", line(0, &s.start).replace("2500", "-1")),
                "line 2: nanoseconds: must not be negative",
            ),
        ];
        for (text, want) in cases {
            let e = parse_output(&text, &s).unwrap_err();
            assert!(e.starts_with(want), "{text:?}: {e:?} does not start with {want:?}");
        }
        let mut bad = ok(0);
        bad = bad.replacen(" 0 ", " 0 x", 1);
        let e = parse_output(&format!("kdl 1\n{bad}{}", ok(1)), &s).unwrap_err();
        assert!(e.starts_with("line 2:"), "{e}");
    }
}
