//! End-to-end tests of `ikarus bench --paths`: the rows and columns of its JSON, determinism,
//! `plan` without flips on paths made by forward kinematics, KDL's answers through a fake
//! `kdl_bench`, and bad flags. No test asserts a time.

mod common;

use std::path::Path;

use serde_json::Value;

use common::{fails, json, succeeds};

const SOLVERS: [&str; 3] = ["follow", "plan", "scratch"];

fn small(extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> =
        ["bench", "--paths", "--path-count", "10", "--samples", "12", "--json"].map(str::to_owned).to_vec();
    args.extend(extra.iter().map(|s| (*s).to_owned()));
    args
}

fn run(args: &[String]) -> Value {
    json(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

/// The rows with kind `all`.
fn all_rows(v: &Value) -> Vec<&Value> {
    v["rows"].as_array().unwrap().iter().filter(|r| r["kind"] == "all").collect()
}

/// `v` without the fields that are times or depend on the machine.
fn untimed(v: &Value) -> Value {
    let mut v = v.clone();
    for r in v["rows"].as_array_mut().unwrap() {
        let r = r.as_object_mut().unwrap();
        r.remove("median_us");
        r.remove("p99_us");
    }
    for t in v["targets"].as_array_mut().unwrap() {
        let t = t.as_object_mut().unwrap();
        if t["target"].as_str().unwrap().contains("µs") || t["target"].as_str().unwrap().contains("ms") {
            t.remove("met");
            t.remove("figure");
        }
    }
    v["header"].as_object_mut().unwrap().remove("command");
    v
}

#[test]
fn json_has_the_rows_columns_and_targets() {
    let v = run(&small(&[]));
    let h = &v["header"];
    assert_eq!(h["command"], "ikarus bench --paths --path-count 10 --samples 12 --json");
    assert_eq!(
        (h["paths"].as_u64(), h["fk_paths"].as_u64(), h["beyond_paths"].as_u64()),
        (Some(60), Some(36), Some(6))
    );
    assert_eq!((h["samples"].as_u64(), h["paths_per_set"].as_u64()), (Some(12), Some(10)));
    assert_eq!(h["kdl_version"], Value::Null);
    let rows = all_rows(&v);
    let keys: Vec<(String, bool, String)> = rows
        .iter()
        .map(|r| {
            (
                r["arm"].as_str().unwrap().to_owned(),
                r["limits"].as_bool().unwrap(),
                r["solver"].as_str().unwrap().to_owned(),
            )
        })
        .collect();
    let mut want = Vec::new();
    for arm in ["seed", "seven", "tentacle"] {
        for limits in [false, true] {
            for s in SOLVERS {
                want.push((arm.to_owned(), limits, s.to_owned()));
            }
        }
    }
    assert_eq!(keys, want);
    for r in &rows {
        assert_eq!(
            (r["paths"].as_u64(), r["samples"].as_u64(), r["fk_paths"].as_u64()),
            (Some(10), Some(120), Some(6))
        );
        for key in [
            "reached",
            "reached_percent",
            "beyond_samples",
            "flips",
            "paths_with_flips",
            "fk_paths_with_flips",
            "fk_samples_missed",
            "step_ratio_max",
            "max_step_deg",
            "velocity_deg_median",
            "acceleration_deg_median",
            "jerk_deg_median",
            "median_us",
            "p99_us",
        ] {
            assert!(r[key].is_number(), "{key}: {r}");
        }
        assert!(r["reached"].as_u64().unwrap() <= 120);
        assert!(r["beyond_samples"].as_u64().unwrap() > 0, "the beyond path leaves the reach: {r}");
        assert_eq!(r["limited"].is_number(), r["solver"] == "follow", "{r}");
        if r["solver"] == "follow" {
            // Never a step over the bound.
            assert_eq!(r["flips"], 0, "{r}");
            assert!(r["max_step_deg"].as_f64().unwrap() <= 10.0 + 1e-6, "{r}");
        }
    }
    // Per-kind rows too, in the JSON: 7 kinds × 3 solvers per set.
    assert_eq!(v["rows"].as_array().unwrap().len(), 6 * (3 + 7 * 3));
    let targets = v["targets"].as_array().unwrap();
    assert!(targets.iter().all(|t| t["met"].is_boolean() && t["figure"].is_string() && t["target"].is_string()));
    assert!(
        targets.iter().any(|t| t["target"] == "seed limits on: plan has 0 flips and reaches every sample on FK paths")
    );
}

#[test]
fn the_same_seed_gives_the_same_output_and_another_seed_another() {
    let a = run(&small(&["--arms", "seed,seven"]));
    let b = run(&small(&["--arms", "seed,seven"]));
    assert_eq!(untimed(&a), untimed(&b));
    let c = run(&small(&["--arms", "seed,seven", "--seed", "2"]));
    assert_ne!(untimed(&a)["rows"], untimed(&c)["rows"]);
}

#[test]
fn plan_has_no_flips_on_fk_paths_of_the_seed_arm() {
    let v =
        run(&["bench", "--paths", "--arms", "seed", "--path-count", "10", "--samples", "40", "--json"]
            .map(str::to_owned));
    for r in all_rows(&v).into_iter().filter(|r| r["solver"] == "plan") {
        assert_eq!((r["fk_paths_with_flips"].as_u64(), r["fk_samples_missed"].as_u64()), (Some(0), Some(0)), "{r}");
    }
}

#[test]
fn plan_has_no_flips_on_fk_paths_of_the_tentacle() {
    // Path 30 of seed 1 (a wave, limits on) is where a ladder of 8 candidates lost the
    // continuous track of the 20-link chain (one flip of 101.9°); one candidate per joint
    // keeps it.
    let v = run(&["bench", "--paths", "--arms", "tentacle", "--path-count", "31", "--json"].map(str::to_owned));
    let plans: Vec<&Value> = all_rows(&v).into_iter().filter(|r| r["solver"] == "plan").collect();
    assert_eq!(plans.len(), 2);
    for r in plans {
        assert_eq!((r["fk_paths_with_flips"].as_u64(), r["fk_samples_missed"].as_u64()), (Some(0), Some(0)), "{r}");
    }
}

#[test]
fn text_and_markdown_show_the_blocks_and_the_targets() {
    let args = ["bench", "--paths", "--arms", "seed", "--path-count", "3", "--samples", "5"];
    let text = succeeds(&args);
    assert!(text.starts_with("ikarus bench --paths: ikarus "), "{text}");
    assert!(text.contains("\nseed · limits off · 3 paths, 0 samples beyond the reach\n"), "{text}");
    assert!(text.contains("\nseed · limits on · 3 paths, 0 samples beyond the reach\n"), "{text}");
    assert!(text.contains("\ntargets: "), "{text}");
    let md = succeeds(&[&args[..], &["--markdown", "--by-kind"]].concat());
    assert!(md.starts_with("`ikarus bench --paths --arms seed --path-count 3 --samples 5 --markdown --by-kind`\n"));
    assert!(md.contains("| arm | limits | solver | kind |"));
    assert!(md.contains("| seed | on | plan | wave |"), "{md}");
}

/// A stand-in for `kdl_bench` in path mode: it answers every sample with the start pose.
fn fake_kdl(dir: &Path) -> String {
    let path = dir.join("kdl_bench");
    let body = r#"#!/bin/sh
awk '
  $1 == "start" { start = ""; for (i = 2; i <= NF; i++) start = start " " $i }
  $1 == "paths" { paths = 1 }
  $1 == "goals" { goals = $2 }
  END {
    if (!paths) exit 3
    print "kdl 0.0-fake"
    for (g = 0; g < goals; g++) print "lma", g, 1000, 3, "-5" start
  }' "$1"
"#;
    std::fs::write(&path, body).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    path.to_str().unwrap().to_owned()
}

#[test]
fn kdl_rows_follow_the_ikarus_rows() {
    let dir = tempfile::tempdir().unwrap();
    let kdl = fake_kdl(dir.path());
    let v = run(&small(&["--arms", "seed", "--kdl", &kdl]));
    assert_eq!(v["header"]["kdl_version"], "0.0-fake");
    let rows = all_rows(&v);
    let labels: Vec<&str> = rows.iter().map(|r| r["solver"].as_str().unwrap()).collect();
    assert_eq!(labels, ["follow", "plan", "scratch", "kdl lma warm", "follow", "plan", "scratch", "kdl lma warm"]);
    let kdl_row = rows[3];
    // The start pose every time: no step at all, and the samples are not reached.
    assert_eq!((kdl_row["flips"].as_u64(), kdl_row["max_step_deg"].as_f64()), (Some(0), Some(0.0)));
    assert_eq!(kdl_row["median_us"], 1.0);
}

#[test]
fn bad_flags_exit_2_with_one_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["bench", "--paths", "--samples", "2"], "'--samples <N>': 2: must be at least 3"),
        (&["bench", "--paths", "--samples", "x"], "'x' is not a whole number"),
        (&["bench", "--paths", "--path-count", "0"], "'--path-count <N>': 0: must be at least 1"),
        (&["bench", "--samples", "10"], "the following required arguments were not provided"),
        (&["bench", "--by-kind"], "the following required arguments were not provided"),
        (&["bench", "--paths", "--sets", "unreachable"], "'--paths' cannot be used with '--sets <SET,…>'"),
        (&["bench", "--paths", "--goals", "5"], "'--paths' cannot be used with '--goals <N>'"),
        (&["bench", "--paths", "--json", "--markdown"], "'--json' cannot be used with '--markdown'"),
        (&["bench", "--paths", "--kdl", "/nonexistent/kdl_bench"], "--kdl /nonexistent/kdl_bench: No such file"),
    ];
    for (args, want) in cases {
        let err = fails(args, 2);
        assert!(err.contains(want), "{args:?}: {err:?} lacks {want:?}");
    }
}
