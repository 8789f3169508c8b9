//! End-to-end tests of `ikarus bench`: the JSON, Markdown and text outputs, reproducible goal
//! files, KDL's output merged through a fake `kdl_bench`, and bad input. No test asserts a time.

mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;

use common::{fails, json, succeeds};

/// The labels of the rows of `set` in a JSON report.
fn labels(v: &Value, arm: &str, set: &str) -> Vec<String> {
    rows(v, arm, set).iter().map(|r| r["solver"].as_str().unwrap().to_owned()).collect()
}

fn rows<'a>(v: &'a Value, arm: &str, set: &str) -> Vec<&'a Value> {
    v["rows"].as_array().unwrap().iter().filter(|r| r["arm"] == arm && r["set"] == set).collect()
}

/// Writes an executable shell script `name` into `dir`.
fn script(dir: &Path, name: &str, body: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, format!("#!/bin/sh\n{body}")).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    path.to_str().unwrap().to_owned()
}

/// A stand-in for `kdl_bench`: it copies the goal file into `seen` (for the test to inspect)
/// and answers every goal with the start pose and code -5, 1000 + i ns and 3 iterations for
/// LMA, and the same for NR_JL (iterations unknown) when a joint is limited.
fn fake_kdl(dir: &Path, seen: &Path) -> String {
    let body = format!(
        r#"cp "$1" '{seen}/'
awk '
  $1 == "start" {{ start = ""; for (i = 2; i <= NF; i++) start = start " " $i }}
  $1 == "limits" {{ for (i = 2; i <= NF; i++) if ($i != "nan") limited = 1 }}
  $1 == "goals" {{ goals = $2 }}
  END {{
    print "kdl 0.0-fake"
    for (g = 0; g < goals; g++) print "lma", g, 1000 + g, 3, "-5" start
    if (limited) for (g = 0; g < goals; g++) print "nr_jl", g, 2000, -1, "-5" start
  }}' "$1"
"#,
        seen = seen.display()
    );
    script(dir, "kdl_bench", &body)
}

const FREE_ROWS: [&str; 8] = ["transpose", "pinv", "dls", "sdls", "lm", "ccd", "fabrik", "default"];

#[test]
fn json_has_a_header_and_the_expected_rows() {
    let v = json(&["bench", "--goals", "20", "--arms", "seed", "--json"]);
    let h = &v["header"];
    assert_eq!(h["command"], "ikarus bench --goals 20 --arms seed --json");
    assert_eq!(h["ikarus_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(h["kdl_version"], Value::Null);
    assert_eq!((h["goals"].as_u64(), h["seed"].as_u64(), h["threads"].as_u64()), (Some(20), Some(1), Some(1)));
    assert_eq!(h["arms"], serde_json::json!(["seed"]));

    assert_eq!(labels(&v, "seed", "free-position"), FREE_ROWS);
    assert_eq!(labels(&v, "seed", "unreachable"), FREE_ROWS);
    // The seed arm has 3 links: the closed form applies to orientation goals only.
    let mut oriented = FREE_ROWS.to_vec();
    oriented.insert(7, "analytic");
    assert_eq!(labels(&v, "seed", "free-oriented"), oriented);
    let limits = labels(&v, "seed", "limits-position");
    assert_eq!(limits.len(), 5 * 4 + 2 + 3 * 4 + 1);
    assert_eq!(&limits[..4], ["transpose clamp", "transpose lock", "transpose nullspace", "transpose weighted"]);
    assert_eq!(
        &limits[20..],
        [
            "ccd clamp",
            "fabrik clamp",
            "dls clamp +restarts",
            "dls lock +restarts",
            "dls nullspace +restarts",
            "dls weighted +restarts",
            "lm clamp +restarts",
            "lm lock +restarts",
            "lm nullspace +restarts",
            "lm weighted +restarts",
            "sdls clamp +restarts",
            "sdls lock +restarts",
            "sdls nullspace +restarts",
            "sdls weighted +restarts",
            "default"
        ]
    );
    let oriented = labels(&v, "seed", "limits-oriented");
    assert_eq!(&oriented[oriented.len() - 2..], ["analytic clamp", "default"]);

    for r in v["rows"].as_array().unwrap() {
        assert_eq!(r["goals"], 20);
        let reached = r["reached"].as_u64().unwrap();
        assert!(reached <= 20);
        assert!(r["median_us"].as_f64().unwrap() <= r["p99_us"].as_f64().unwrap());
        assert_eq!(r["vs_kdl_lma"], Value::Null);
        let oriented = r["set"].as_str().unwrap().ends_with("oriented");
        assert_eq!(r["worst_angle_error"].is_null(), !oriented || r["solve_errors"] != 0, "{r}");
        if r["set"].as_str().unwrap().starts_with("limits") {
            assert!(r["limits"].is_string());
        } else {
            assert!(r["limits"].is_null());
        }
    }
    // The damped least squares reach every one of the 20 reachable goals of the seed arm from
    // its start pose (an exact count: the goals are seeded), and the judge sees it.
    let dls = rows(&v, "seed", "free-position").into_iter().find(|r| r["solver"] == "dls").unwrap();
    assert_eq!(dls["reached"].as_u64(), Some(20), "{dls}");
    assert!(dls["mean_iterations"].as_f64().unwrap() > 0.0);

    // Keys in a stable order, as written.
    let text =
        succeeds(&["bench", "--goals", "2", "--arms", "seed", "--sets", "free-position", "--methods", "dls", "--json"]);
    let order = [
        "\"arm\"",
        "\"set\"",
        "\"solver\"",
        "\"limits\"",
        "\"goals\"",
        "\"reached\"",
        "\"reached_percent\"",
        "\"median_us\"",
        "\"p99_us\"",
        "\"mean_iterations\"",
        "\"worst_error\"",
        "\"worst_angle_error\"",
        "\"vs_kdl_lma\"",
        "\"solve_errors\"",
    ];
    let (header, rows) = text.split_at(text.find("\"rows\"").expect("rows"));
    assert!(header.contains("\"header\""));
    let at: Vec<usize> = order.iter().map(|k| rows.find(k).unwrap_or_else(|| panic!("{k} missing: {text}"))).collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{text}");
    let header_keys = ["\"command\"", "\"ikarus_version\"", "\"kdl_version\"", "\"goals\"", "\"seed\""];
    let at: Vec<usize> = header_keys.iter().map(|k| header.find(k).unwrap()).collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{text}");
}

#[test]
fn default_rows_carry_the_batched_measurement() {
    let v = json(&["bench", "--goals", "20", "--arms", "seed", "--methods", "dls,default", "--json"]);
    let mut batched = 0;
    for r in v["rows"].as_array().unwrap() {
        if r["solver"] != "default" {
            assert_eq!(r["batch"], Value::Null, "{r}");
            continue;
        }
        batched += 1;
        let b = &r["batch"];
        assert_eq!(b["error"], Value::Null, "{r}");
        assert_eq!(b["goals"], 20, "{r}");
        // The batch returns what the solves one by one return.
        assert_eq!(b["reached"], r["reached"], "{r}");
        assert_eq!(b["mismatches"], 0, "{r}");
        for k in ["us_1thr", "solves_per_s_1thr", "us_2thr", "solves_per_s_2thr", "speedup_2thr"] {
            assert!(b[k].as_f64().is_some_and(|x| x > 0.0 && x.is_finite()), "{k}: {r}");
        }
    }
    assert_eq!(batched, 5, "one default row per set");

    // The text and Markdown tables show them below the main table.
    let args = ["bench", "--goals", "3", "--arms", "seed", "--sets", "free-position", "--methods", "default"];
    let out = succeeds(&args);
    assert!(out.contains("batched · Solver::solve_batch"), "{out}");
    assert!(out.lines().any(|l| l.trim_start().starts_with("seed  free-position")), "{out}");
    let out = succeeds(&[&args[..], &["--markdown"]].concat());
    assert!(out.contains("| arm | set | reached | ≠ per-solve | µs/solve 1 thr | M solves/s 1 thr |"), "{out}");
    assert!(out.contains("| seed | free-position | "), "{out}");
    // Without a default row there is no batched table.
    let out = succeeds(&["bench", "--goals", "3", "--arms", "seed", "--sets", "free-position", "--methods", "dls"]);
    assert!(!out.contains("batched"), "{out}");
}

#[test]
fn markdown_starts_with_the_command_line() {
    let args = ["bench", "--goals", "3", "--arms", "seed", "--sets", "free-position,limits-oriented", "--markdown"];
    let out = succeeds(&args);
    let mut lines = out.lines();
    assert_eq!(
        lines.next(),
        Some("`ikarus bench --goals 3 --arms seed --sets free-position,limits-oriented --markdown`")
    );
    assert!(out.contains("\n| arm | set | solver | limits | reached | median µs | p99 µs |"), "{out}");
    assert!(out.contains("\n|---|---|---|---|--:|"), "{out}");
    assert!(out.contains("\n| seed | free-position | dls | — | "), "{out}");
    assert!(out.contains("\n| seed | limits-oriented | dls lock +restarts | lock | "), "{out}");
    assert!(!out.contains("| seed | free-oriented |"));
}

#[test]
fn text_is_one_block_per_arm_and_set() {
    let out =
        succeeds(&["bench", "--goals", "3", "--arms", "seed,seed", "--sets", "unreachable", "--methods", "lm,default"]);
    assert!(out.starts_with("ikarus bench: ikarus "), "{out}");
    assert_eq!(out.matches("\nseed · unreachable · 3 goals\n").count(), 1, "{out}");
    let block: Vec<&str> =
        out.lines().skip_while(|l| !l.starts_with("seed · ")).skip(1).take_while(|l| !l.is_empty()).collect();
    assert_eq!(block.len(), 3, "{out}");
    assert!(block[0].trim_start().starts_with("solver") && block[0].contains("× KDL LMA"));
    assert!(block[1].trim_start().starts_with("lm ") && block[2].trim_start().starts_with("default "));
    assert!(block[1].contains("100.0% (3)"), "the best pose counts as reached: {out}");
}

#[test]
fn goal_files_are_reproducible_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    for d in [&a, &b] {
        std::fs::create_dir(d).unwrap();
        let d = d.to_str().unwrap();
        succeeds(&["bench", "--goals", "5", "--methods", "lm", "--limit-modes", "lock", "--write-goals", d]);
    }
    let mut names: Vec<String> =
        std::fs::read_dir(&a).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names.len(), 15, "{names:?}");
    assert!(names.contains(&"tentacle-limits-oriented.goals".to_owned()));
    for n in &names {
        assert_eq!(std::fs::read(a.join(n)).unwrap(), std::fs::read(b.join(n)).unwrap(), "{n}");
    }

    // The first goal of seed/limits-position with seed 1, pinned to the bit.
    let text = std::fs::read_to_string(a.join("seed-limits-position.goals")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "ikarus-goals 1");
    for field in [
        "name seed-limits-position",
        "links 3",
        "base 0 0",
        "lengths 3 2 1",
        "orientation 0",
        "tolerance 0.000001",
        "max_iterations 1000",
        "goals 5",
    ] {
        assert!(lines.contains(&field), "{field}: {text}");
    }
    let goals = lines.iter().position(|l| *l == "goals 5").unwrap();
    assert_eq!(lines.len(), goals + 6);
    let first: Vec<u64> = lines[goals + 1].split(' ').map(|t| t.parse::<f64>().unwrap().to_bits()).collect();
    assert_eq!(first, [0x400C_AA01_F116_1F77, 0xBFFD_7DF3_82DE_E335, 0xBFFB_CAD8_FD1E_23AE], "{}", lines[goals + 1]);
    let limits = lines.iter().find(|l| l.starts_with("limits ")).unwrap();
    let limits: Vec<f64> = limits.split(' ').skip(1).map(|t| t.parse().unwrap()).collect();
    assert_eq!(limits, [-45f64, 45.0, -90.0, 90.0, -170.0, 170.0].map(f64::to_radians));

    // Sets whose limits are off carry none; another seed gives other goals.
    let free = std::fs::read_to_string(a.join("seven-unreachable.goals")).unwrap();
    assert!(free.contains("\nlimits nan nan nan nan nan nan nan nan nan nan nan nan nan nan\n"), "{free}");
    let c = dir.path().join("c");
    std::fs::create_dir(&c).unwrap();
    succeeds(&[
        "bench",
        "--goals",
        "5",
        "--arms",
        "seed",
        "--methods",
        "lm",
        "--seed",
        "2",
        "--write-goals",
        c.to_str().unwrap(),
    ]);
    let other = std::fs::read_to_string(c.join("seed-limits-position.goals")).unwrap();
    assert_ne!(other.lines().nth(goals + 1), Some(lines[goals + 1]));
}

#[test]
fn kdl_rows_are_merged_and_judged() {
    let dir = tempfile::tempdir().unwrap();
    let seen = dir.path().join("seen");
    let written = dir.path().join("written");
    std::fs::create_dir(&seen).unwrap();
    std::fs::create_dir(&written).unwrap();
    let kdl = fake_kdl(dir.path(), &seen);
    let v = json(&[
        "bench",
        "--goals",
        "10",
        "--arms",
        "seed",
        "--methods",
        "dls",
        "--kdl",
        &kdl,
        "--write-goals",
        written.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["header"]["kdl_version"], "0.0-fake");
    for set in ["free-position", "free-oriented", "limits-position", "limits-oriented", "unreachable"] {
        let rows = rows(&v, "seed", set);
        let labels: Vec<&str> = rows.iter().map(|r| r["solver"].as_str().unwrap()).collect();
        let lma = rows.iter().find(|r| r["solver"] == "kdl lma").unwrap_or_else(|| panic!("{set}: {labels:?}"));
        // The fake answers every goal with the start pose: nothing is reached.
        assert_eq!(lma["reached"], 0, "{set}");
        assert_eq!(lma["median_us"].as_f64(), Some(1.0045), "{set}: median of 1000..1009 ns");
        assert_eq!(lma["mean_iterations"].as_f64(), Some(3.0));
        assert_eq!(lma["vs_kdl_lma"].as_f64(), Some(1.0));
        assert!(lma["worst_error"].as_f64().unwrap() > 0.01);
        assert!(lma["limits"].is_null());
        let nr_jl = rows.iter().find(|r| r["solver"] == "kdl nr_jl");
        if set.starts_with("limits") {
            let nr_jl = nr_jl.unwrap_or_else(|| panic!("{set}: {labels:?}"));
            assert_eq!((nr_jl["reached"].as_u64(), nr_jl["median_us"].as_f64()), (Some(0), Some(2.0)));
            assert_eq!(nr_jl["mean_iterations"], Value::Null, "NR_JL does not count");
            assert_eq!(nr_jl["limits"], "clamp");
            assert_eq!(nr_jl["vs_kdl_lma"].as_f64(), Some(1.0045 / 2.0));
            assert_eq!(labels.last(), Some(&"kdl nr_jl"));
        } else {
            assert!(nr_jl.is_none(), "{set}: {labels:?}");
            assert_eq!(labels.last(), Some(&"kdl lma"));
        }
        for r in &rows {
            assert!(r["vs_kdl_lma"].as_f64().unwrap() > 0.0);
        }
        // KDL was given exactly the goal file that --write-goals writes.
        let name = format!("seed-{set}.goals");
        assert_eq!(std::fs::read(seen.join(&name)).unwrap(), std::fs::read(written.join(&name)).unwrap(), "{name}");
    }
    // The text table names KDL's version and fills the ratio column.
    let out = succeeds(&[
        "bench",
        "--goals",
        "2",
        "--arms",
        "seed",
        "--sets",
        "limits-position",
        "--methods",
        "lm",
        "--limit-modes",
        "lock",
        "--kdl",
        &kdl,
    ]);
    assert!(out.lines().next().unwrap().contains("KDL 0.0-fake"), "{out}");
    let lma = out.lines().find(|l| l.trim_start().starts_with("kdl lma")).unwrap();
    assert!(lma.trim_end().ends_with("1.00"), "{lma}");
    assert!(out.lines().any(|l| l.trim_start().starts_with("kdl nr_jl")), "{out}");
}

#[test]
fn a_broken_kdl_is_one_line_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base = ["bench", "--goals", "3", "--arms", "seed", "--methods", "dls"];
    let run = |kdl: &str, code: i32| {
        let mut args = base.to_vec();
        args.extend(["--kdl", kdl]);
        let err = fails(&args, code);
        assert!(err.starts_with(&format!("ikarus: --kdl {kdl}: ")), "{err}");
        err
    };

    let malformed = script(d, "malformed", "echo 'kdl 1.5.1'\necho 'lma 0 oops'\n");
    let err = run(&malformed, 1);
    assert!(err.contains("set seed-free-position: output line 2: expected 8 fields"), "{err}");
    let garbage = script(d, "garbage", "echo 'kdl 1.5.1'\necho 'lma 0 12 3 0 x 0 0'\n");
    let err = run(&garbage, 1);
    assert!(err.contains("output line 2: q_0: `x` is not a valid number"), "{err}");
    let short = script(d, "short", "echo 'kdl 1.5.1'\n");
    let err = run(&short, 1);
    assert!(err.contains("output 0 `lma` lines for 3 goals"), "{err}");
    let silent = script(d, "silent", "exit 0\n");
    assert!(run(&silent, 1).contains("output no output"));
    let failing = script(d, "failing", "echo 'kdl_bench: x:3: field links: bad' >&2\nexit 2\n");
    let err = run(&failing, 1);
    assert!(
        err.contains("failed on set seed-free-position (exit status: 2): kdl_bench: x:3: field links: bad"),
        "{err}"
    );

    let not_executable = d.join("plain");
    std::fs::write(&not_executable, "kdl 1\n").unwrap();
    let err = run(not_executable.to_str().unwrap(), 1);
    assert!(err.contains("cannot run"), "{err}");
    let err = run("/nonexistent/kdl_bench", 2);
    assert!(err.contains("No such file or directory"), "{err}");
    assert!(run(d.to_str().unwrap(), 2).contains("not a file"));
}

#[test]
fn bad_flags_exit_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("file");
    std::fs::write(&file, "").unwrap();
    let file = file.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["bench", "--goals", "0"], "'--goals <N>': 0: must be at least 1"),
        (&["bench", "--goals", "-3"], "unexpected argument '-3'"),
        (&["bench", "--goals", "many"], "'--goals <N>': 'many' is not a whole number"),
        (&["bench", "--seed", "x"], "invalid value 'x' for '--seed <S>'"),
        (
            &["bench", "--arms", "seed,octopus"],
            "invalid value 'octopus' for '--arms <ARM,…>' [possible values: seed, seven, tentacle]",
        ),
        (
            &["bench", "--sets", "easy"],
            "[possible values: free-position, free-oriented, limits-position, limits-oriented, unreachable]",
        ),
        (
            &["bench", "--methods", "newton"],
            "[possible values: transpose, pinv, dls, sdls, lm, ccd, fabrik, analytic, default]",
        ),
        (&["bench", "--limit-modes", "soft"], "[possible values: ignore, clamp, lock, nullspace, weighted]"),
        (&["bench", "--json", "--markdown"], "'--json' cannot be used with '--markdown'"),
        (&["bench", "--frobnicate"], "unexpected argument '--frobnicate'"),
        (
            &["bench", "--methods", "ccd", "--limit-modes", "lock"],
            "--methods ccd --limit-modes lock: no benchmark row matches",
        ),
        (&["bench", "--arms", "seven", "--methods", "analytic"], "--methods analytic: no benchmark row matches"),
        (&["bench", "--write-goals", "/nonexistent/dir"], "--write-goals /nonexistent/dir: No such file or directory"),
        (&["bench", "--write-goals", file], "not a directory"),
    ];
    for (args, want) in cases {
        let err = fails(args, 2);
        assert!(err.contains(want), "{args:?}: {err:?} lacks {want:?}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "nothing written");
}

#[test]
fn help_describes_the_command() {
    let out = succeeds(&["bench", "--help"]);
    for flag in ["--goals <N>", "--seed <S>", "--arms <ARM,…>", "--kdl <PATH>", "--write-goals <DIR>", "--markdown"] {
        assert!(out.contains(flag), "{flag}: {out}");
    }
    let _: PathBuf = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
}
