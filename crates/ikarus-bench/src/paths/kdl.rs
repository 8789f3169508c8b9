//! The KDL side of `ikarus bench --paths`: a path file for `bench/kdl/kdl_bench` (a goal file
//! with a `paths` field, see `bench/kdl/README.md`), and its warm-started LMA answers.

use std::fmt::Write as _;
use std::path::Path;

use ikarus_edge::error::Error;

use super::measure::Answer;
use super::set::{PathSet, points};
use crate::kdl::{header, parse_solves, run_file};

/// The path file of `set`: format `ikarus-goals 1` with `orientation 0`, every sample of every
/// path as a goal line `x y 0`, and `paths L₀ L₁ …`, each path's sample count in order.
/// `comment` goes in a `#` line after the first.
pub fn path_file(set: &PathSet, comment: &str) -> String {
    let mut s = header(comment, &set.name(), &set.chain, set.limited, &set.start, false);
    let lengths: Vec<String> = set.paths.iter().map(|p| p.path.len().to_string()).collect();
    let total: usize = set.paths.iter().map(|p| p.path.len()).sum();
    // Writing to a String cannot fail.
    let _ = writeln!(s, "paths {}", lengths.join(" "));
    let _ = writeln!(s, "goals {total}");
    for p in &set.paths {
        for (x, y) in points(&p.path) {
            let _ = writeln!(s, "{x} {y} 0");
        }
    }
    s
}

/// Parses `kdl_bench`'s output on the path file of `set` into one answer per path, and the
/// version it reported.
pub fn parse(text: &str, set: &PathSet) -> Result<(String, Vec<Answer>), String> {
    let total: usize = set.paths.iter().map(|p| p.path.len()).sum();
    let run = parse_solves(text, &set.name(), set.chain.len(), total, false)?;
    let mut solves = run.lma.into_iter();
    let answers = set
        .paths
        .iter()
        .map(|p| {
            let mut a = Answer { poses: Vec::with_capacity(p.path.len()), limited: 0, micros: Vec::new() };
            for s in solves.by_ref().take(p.path.len()) {
                a.micros.push(s.nanos as f64 / 1000.0);
                a.poses.push(s.angles);
            }
            a
        })
        .collect();
    Ok((run.version, answers))
}

/// Writes the path file of `set` into `dir`, runs `kdl_bench` on it and reads its answers.
pub fn run(path: &Path, set: &PathSet, dir: &Path, comment: &str) -> Result<(String, Vec<Answer>), Error> {
    let file = dir.join(format!("{}.paths", set.name()));
    let text = run_file(path, &file, &path_file(set, comment), &set.name())?;
    parse(&text, set).map_err(|m| Error::runtime(format!("--kdl {}: set {}: output {m}", path.display(), set.name())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paths::set::generate;
    use crate::sets::ArmName;

    #[test]
    fn path_files_list_every_sample_and_answers_split_by_path() {
        let set = generate("seed", &ArmName::Seed.load().unwrap().chain, true, 3, 4, 1);
        let text = path_file(&set, "test");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(&lines[..3], ["ikarus-goals 1", "# test", "name seed-limits"]);
        assert!(text.contains("\norientation 0\n") && text.contains("\npaths 4 4 4\ngoals 12\n"), "{text}");
        assert_eq!(lines.len(), 14 + 12);
        let mut out = "kdl 1.5.1\n".to_owned();
        for g in 0..12 {
            out += &format!("lma {g} {} 5 0 0.1 0.2 {g}\n", 1000 * (g + 1));
        }
        let (version, answers) = parse(&out, &set).unwrap();
        assert_eq!(version, "1.5.1");
        assert_eq!(answers.len(), 3);
        assert_eq!(answers[1].poses[0], [0.1, 0.2, 4.0]);
        assert_eq!(answers[2].micros, [9.0, 10.0, 11.0, 12.0]);
        assert!(parse("kdl 1\n", &set).unwrap_err().contains("0 `lma` lines for 12 goals"));
    }
}
