//! The KDL side of `ikarus bench`: writing goal files for `bench/kdl/kdl_bench` (and for
//! `--write-goals`), running it, and reading its per-solve output. Both formats are specified
//! in `bench/kdl/README.md`.

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Stdio};

use ikarus::{Chain, SolveOptions};
use ikarus_edge::error::Error;
use ikarus_edge::input::io_reason;

use super::judge::judge;
use super::run::{RowResult, Tally};
use super::sets::GoalSet;

/// Label of the rows of KDL's `ChainIkSolverPos_LMA`.
pub const LMA_LABEL: &str = "kdl lma";
/// Label of the rows of KDL's `ChainIkSolverPos_NR_JL`.
pub const NR_JL_LABEL: &str = "kdl nr_jl";

/// The goal file of `set` (format `ikarus-goals 1`). `comment` goes in a `#` line after the
/// first. Floats are written with Rust's `{}`, which reads back to the same number; limits in
/// radians, `nan nan` for a free joint, and for every joint of the sets whose limits are off.
pub fn goal_file(set: &GoalSet, comment: &str) -> String {
    let mut s = header(comment, &set.name(), &set.chain, set.set.limited(), &set.start, set.set.oriented());
    // Writing to a String cannot fail.
    let _ = writeln!(s, "goals {}", set.goals.len());
    for g in &set.goals {
        let _ = writeln!(s, "{} {} {}", g.x, g.y, g.phi);
    }
    s
}

/// The fields a goal file starts with, up to (not including) `goals`: the first line, the
/// `comment` line, the set's `name`, the chain (its limits only when `limited`), the `start`
/// pose, whether the goals carry an orientation, and the library's default tolerances and
/// iteration cap.
pub fn header(comment: &str, name: &str, chain: &Chain, limited: bool, start: &[f64], oriented: bool) -> String {
    let opts = SolveOptions::default();
    let join = |v: &mut dyn Iterator<Item = f64>| v.map(|x| x.to_string()).collect::<Vec<_>>().join(" ");
    let limits: Vec<String> = chain
        .limits()
        .iter()
        .map(|lim| match lim {
            Some(l) if limited => format!("{} {}", l.min(), l.max()),
            _ => "nan nan".to_owned(),
        })
        .collect();
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(s, "ikarus-goals 1");
    let _ = writeln!(s, "# {}", comment.replace('\n', " "));
    let _ = writeln!(s, "name {name}");
    let _ = writeln!(s, "links {}", chain.len());
    let _ = writeln!(s, "base {} {}", chain.base().x, chain.base().y);
    let _ = writeln!(s, "lengths {}", join(&mut chain.lengths().iter().copied()));
    let _ = writeln!(s, "limits {}", limits.join(" "));
    let _ = writeln!(s, "start {}", join(&mut start.iter().copied()));
    let _ = writeln!(s, "orientation {}", u8::from(oriented));
    let _ = writeln!(s, "tolerance {}", opts.tolerance);
    let _ = writeln!(s, "angle_tolerance {}", opts.angle_tolerance);
    let _ = writeln!(s, "max_iterations {}", opts.max_iterations);
    s
}

/// One solve as `kdl_bench` reported it.
#[derive(Debug, Clone, PartialEq)]
pub struct KdlSolve {
    /// Wall time of the `CartToJnt` call, nanoseconds.
    pub nanos: u64,
    /// Iterations; `None` when KDL does not report them (`-1`).
    pub iterations: Option<u64>,
    /// KDL's return code (0 = success).
    pub return_code: i64,
    /// The final joint angles, unwrapped.
    pub angles: Vec<f64>,
}

/// The output of one `kdl_bench` run.
#[derive(Debug, Clone, PartialEq)]
pub struct KdlRun {
    /// KDL's version, from the first line.
    pub version: String,
    /// The LMA solves, one per goal, in goal order.
    pub lma: Vec<KdlSolve>,
    /// The NR_JL solves, one per goal (empty for sets without limits).
    pub nr_jl: Vec<KdlSolve>,
}

impl KdlRun {
    /// Judges every solve the way the ikarus rows are judged, giving the `kdl lma` row and, for
    /// limits sets, the `kdl nr_jl` row.
    pub fn rows(&self, set: &GoalSet) -> Vec<RowResult> {
        let row = |solves: &[KdlSolve], label: &str, limits| {
            let mut tally = Tally::new(solves.len(), set.set.oriented());
            for (s, goal) in solves.iter().zip(&set.goals) {
                tally.add(s.nanos, s.iterations, judge(set, goal, &s.angles));
            }
            tally.finish(set, label.to_owned(), limits)
        };
        let mut rows = vec![row(&self.lma, LMA_LABEL, None)];
        if !self.nr_jl.is_empty() {
            // NR_JL clamps every iterate into the limits.
            rows.push(row(&self.nr_jl, NR_JL_LABEL, Some("clamp")));
        }
        rows
    }
}

/// Whether `kdl_bench` runs NR_JL on `set`: only when the goal file has a limited joint.
fn expects_nr_jl(set: &GoalSet) -> bool {
    set.set.limited() && set.chain.has_limits()
}

/// Parses `kdl_bench`'s output for `set`, strictly: the version line, then exactly one `lma`
/// line per goal in order, then (for limits sets) one `nr_jl` line per goal. The error names
/// the output line.
pub fn parse_output(text: &str, set: &GoalSet) -> Result<KdlRun, String> {
    parse_solves(text, &set.name(), set.chain.len(), set.goals.len(), expects_nr_jl(set))
}

/// Parses `kdl_bench`'s output for the set `name` of `goals` goals on `n` joints: the version
/// line, `goals` `lma` lines, then `goals` `nr_jl` lines if `nr_jl`.
pub(crate) fn parse_solves(text: &str, name: &str, n: usize, goals: usize, nr_jl: bool) -> Result<KdlRun, String> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let version = match lines.next() {
        None => return Err("no output".to_owned()),
        Some((_, l)) => match l.split_whitespace().collect::<Vec<_>>()[..] {
            ["kdl", v] => v.to_owned(),
            _ => return Err(format!("line 1: expected `kdl VERSION`, got `{}`", shorten(l))),
        },
    };
    let mut run = KdlRun { version, lma: Vec::with_capacity(goals), nr_jl: Vec::new() };
    for (k, line) in lines {
        let fail = |what: String| Err(format!("line {k}: {what}"));
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let Some(&solver) = tokens.first() else { return fail("empty line".to_owned()) };
        let list = match solver {
            "lma" if run.nr_jl.is_empty() => &mut run.lma,
            "lma" => return fail("an `lma` line after the `nr_jl` lines".to_owned()),
            "nr_jl" if !nr_jl => return fail(format!("an `nr_jl` line for set {name}, which has no limits")),
            "nr_jl" if run.lma.len() < goals => {
                return fail(format!("an `nr_jl` line after {} of {goals} `lma` lines", run.lma.len()));
            }
            "nr_jl" => &mut run.nr_jl,
            other => return fail(format!("unknown solver `{}`", shorten(other))),
        };
        if tokens.len() != 5 + n {
            return fail(format!(
                "expected {} fields (solver, goal, ns, iterations, code, {n} angles), got {}",
                5 + n,
                tokens.len()
            ));
        }
        if list.len() == goals {
            return fail(format!("more than {goals} `{solver}` lines"));
        }
        let at = |m: String| format!("line {k}: {m}");
        let index: usize = number(tokens[1], "goal index").map_err(at)?;
        if index != list.len() {
            return fail(format!("goal index {index}, expected {}", list.len()));
        }
        let field = |i: usize, what: &str| number::<i64>(tokens[i], what).map_err(at);
        let nanos = field(2, "nanoseconds")?;
        let iterations = field(3, "iterations")?;
        let return_code = field(4, "return code")?;
        if nanos < 0 {
            return fail(format!("nanoseconds: must not be negative, got {nanos}"));
        }
        if iterations < -1 {
            return fail(format!("iterations: must be -1 (unknown) or more, got {iterations}"));
        }
        let mut angles = Vec::with_capacity(n);
        for (j, t) in tokens[5..].iter().enumerate() {
            angles.push(number::<f64>(t, &format!("q_{j}")).map_err(at)?);
        }
        list.push(KdlSolve { nanos: nanos as u64, iterations: u64::try_from(iterations).ok(), return_code, angles });
    }
    if run.lma.len() != goals {
        return Err(format!("{} `lma` lines for {goals} goals", run.lma.len()));
    }
    if nr_jl && run.nr_jl.len() != goals {
        return Err(format!("{} `nr_jl` lines for {goals} goals", run.nr_jl.len()));
    }
    Ok(run)
}

/// Parses one token; the error says what was wrong.
fn number<T: std::str::FromStr>(token: &str, what: &str) -> Result<T, String> {
    token.parse().map_err(|_| format!("{what}: `{}` is not a valid number", shorten(token)))
}

/// At most 40 characters of `s`, for error messages.
fn shorten(s: &str) -> String {
    let mut out: String = s.chars().take(40).collect();
    if out.len() < s.len() {
        out.push('…');
    }
    out
}

/// Checks `--kdl PATH` before any work: a path that does not exist is bad input (exit 2).
pub fn check(path: &Path) -> Result<(), Error> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => Ok(()),
        Ok(_) => Err(Error::input(format!("--kdl {}: not a file", path.display()))),
        Err(e) => Err(Error::input(format!("--kdl {}: {}", path.display(), io_reason(&e)))),
    }
}

/// Writes the goal file of `set` into `dir`, runs `path` on it and parses its output. Any
/// failure is one line naming `--kdl` and the path (exit 1).
pub fn run(path: &Path, set: &GoalSet, dir: &Path, comment: &str) -> Result<KdlRun, Error> {
    let text = run_file(path, &dir.join(format!("{}.goals", set.name())), &goal_file(set, comment), &set.name())?;
    parse_output(&text, set)
        .map_err(|m| Error::runtime(format!("--kdl {}: set {}: output {m}", path.display(), set.name())))
}

/// Writes `contents` to `file`, runs `path` on it and returns its stdout. Any failure is one
/// line naming `--kdl`, the path and the set `name` (exit 1).
pub(crate) fn run_file(path: &Path, file: &Path, contents: &str, name: &str) -> Result<String, Error> {
    let fail = |what: String| Error::runtime(format!("--kdl {}: {what}", path.display()));
    std::fs::write(file, contents)
        .map_err(|e| fail(format!("cannot write the goal file {}: {}", file.display(), io_reason(&e))))?;
    let output = Command::new(path)
        .arg(file)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| fail(format!("cannot run: {}", io_reason(&e))))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let why = stderr.lines().find(|l| !l.trim().is_empty()).map_or(String::new(), |l| format!(": {}", l.trim()));
        return Err(fail(format!("failed on set {name} ({}){why}", output.status)));
    }
    String::from_utf8(output.stdout).map_err(|_| fail(format!("set {name}: output is not UTF-8")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sets::{ArmName, SetName, generate};

    fn set(kind: SetName, goals: usize) -> GoalSet {
        generate("seed", &ArmName::Seed.load().unwrap().chain, kind, goals, 1)
    }

    fn line(solver: &str, i: usize, angles: &[f64]) -> String {
        let a: Vec<String> = angles.iter().map(|x| format!("{x:.17e}")).collect();
        format!("{solver} {i} 1234 7 0 {}\n", a.join(" "))
    }

    #[test]
    fn goal_files_follow_the_format() {
        let s = set(SetName::LimitsOriented, 3);
        let text = goal_file(&s, "test");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "ikarus-goals 1");
        assert_eq!(lines[1], "# test");
        assert_eq!(lines[2], "name seed-limits-oriented");
        assert_eq!(lines[3], "links 3");
        assert_eq!(lines[4], "base 0 0");
        assert_eq!(lines[5], "lengths 3 2 1");
        let limits: Vec<f64> = lines[6].split(' ').skip(1).map(|t| t.parse().unwrap()).collect();
        assert_eq!(limits.len(), 6);
        assert_eq!(limits[1], 45f64.to_radians());
        assert!(lines[7].starts_with("start 0.0872"));
        assert_eq!(
            &lines[8..13],
            ["orientation 1", "tolerance 0.000001", "angle_tolerance 0.000001", "max_iterations 1000", "goals 3"]
        );
        assert_eq!(lines.len(), 16);
        for (l, g) in lines[13..].iter().zip(&s.goals) {
            let v: Vec<f64> = l.split(' ').map(|t| t.parse().unwrap()).collect();
            assert_eq!(v, [g.x, g.y, g.phi], "floats read back exactly");
        }
        let free = goal_file(&set(SetName::Unreachable, 1), "x");
        assert!(free.contains("\nlimits nan nan nan nan nan nan\n"));
        assert!(free.contains("\norientation 0\n"));
    }

    #[test]
    fn output_is_parsed_and_judged() {
        let s = set(SetName::LimitsPosition, 2);
        let mut text = "kdl 1.5.1\n".to_owned();
        text += &line("lma", 0, &s.goals[0].config);
        text += &line("lma", 1, &s.start);
        text += &line("nr_jl", 0, &s.goals[0].config);
        text += "nr_jl 1 99 -1 -5 nan -nan inf\n";
        let run = parse_output(&text, &s).unwrap();
        assert_eq!(run.version, "1.5.1");
        assert_eq!(run.lma[1], KdlSolve { nanos: 1234, iterations: Some(7), return_code: 0, angles: s.start.clone() });
        assert_eq!(run.nr_jl[1].iterations, None);
        assert_eq!(run.nr_jl[1].return_code, -5);
        let rows = run.rows(&s);
        assert_eq!(rows.len(), 2);
        assert_eq!((rows[0].label.as_str(), rows[0].reached, rows[0].mean_iterations), ("kdl lma", 1, Some(7.0)));
        assert_eq!((rows[1].label.as_str(), rows[1].limits, rows[1].reached), ("kdl nr_jl", Some("clamp"), 1));
        assert_eq!((rows[1].mean_iterations, rows[1].worst_error), (None, f64::INFINITY));
        assert_eq!(rows[0].median_us, 1.234);
    }

    #[test]
    fn bad_output_names_the_line() {
        let s = set(SetName::FreePosition, 2);
        let ok = |i| line("lma", i, &[0.0, 0.0, 0.0]);
        let cases = [
            (String::new(), "no output"),
            ("ikarus 1\n".to_owned(), "line 1: expected `kdl VERSION`"),
            (format!("kdl 1\n{}", ok(0)), "1 `lma` lines for 2 goals"),
            (format!("kdl 1\n{}{}{}", ok(0), ok(1), ok(2)), "line 4: more than 2 `lma` lines"),
            (format!("kdl 1\n{}{}", ok(1), ok(0)), "line 2: goal index 1, expected 0"),
            (format!("kdl 1\n{}lma 1 5 3 0 1 2\n", ok(0)), "line 3: expected 8 fields"),
            (format!("kdl 1\n{}lma 1 5 x 0 1 2 3\n", ok(0)), "line 3: iterations: `x` is not a valid number"),
            (format!("kdl 1\n{}lma 1 5 -2 0 1 2 3\n", ok(0)), "line 3: iterations: must be -1"),
            (format!("kdl 1\n{}lma 1 -5 1 0 1 2 3\n", ok(0)), "line 3: nanoseconds: must not be negative"),
            (format!("kdl 1\n{}lma 1 5 1 0 1 2 y\n", ok(0)), "line 3: q_2: `y` is not a valid number"),
            (
                format!("kdl 1\n{}{}nr_jl 0 1 -1 0 0 0 0\n", ok(0), ok(1)),
                "line 4: an `nr_jl` line for set seed-free-position",
            ),
            (format!("kdl 1\n{}\n{}", ok(0), ok(1)), "line 3: empty line"),
            (format!("kdl 1\n{}ik 1 1 1 1 1 1 1\n", ok(0)), "line 3: unknown solver `ik`"),
        ];
        for (text, want) in cases {
            let e = parse_output(&text, &s).unwrap_err();
            assert!(e.starts_with(want), "{text:?}: {e:?} does not start with {want:?}");
        }
        let limited = set(SetName::LimitsPosition, 1);
        let e = parse_output(&format!("kdl 1\n{}", ok(0)), &limited).unwrap_err();
        assert_eq!(e, "0 `nr_jl` lines for 1 goals");
    }
}
