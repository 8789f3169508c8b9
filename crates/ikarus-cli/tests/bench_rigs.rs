//! End-to-end tests of `ikarus bench --rigs`: the rows, columns and targets of its JSON,
//! determinism, the Markdown and text outputs, KDL's tree solver through a fake `kdl_bench`
//! (and the rig goal file it is given), and bad flags. No test asserts a time.

mod common;

use std::path::Path;

use serde_json::Value;

use common::{fails, json, succeeds};

const SETS: [&str; 3] = ["puppet", "puppet-pins", "hand"];
const ROWS: [&str; 6] = ["default", "lm clamp", "lm lock", "lm nullspace", "lm weighted", "sequential"];

fn rows<'a>(v: &'a Value, set: &str) -> Vec<&'a Value> {
    v["rows"].as_array().unwrap().iter().filter(|r| r["set"] == set).collect()
}

fn labels(v: &Value, set: &str) -> Vec<String> {
    rows(v, set).iter().map(|r| r["solver"].as_str().unwrap().to_owned()).collect()
}

/// `v` without the fields that are times or depend on the machine.
fn untimed(v: &Value) -> Value {
    let mut v = v.clone();
    for r in v["rows"].as_array_mut().unwrap() {
        let r = r.as_object_mut().unwrap();
        for k in ["median_us", "p99_us", "vs_kdl_tree"] {
            r.remove(k);
        }
    }
    for t in v["targets"].as_array_mut().unwrap() {
        let t = t.as_object_mut().unwrap();
        if t["target"].as_str().unwrap().contains("µs") || t["target"].as_str().unwrap().contains("faster") {
            t.remove("met");
            t.remove("figure");
        }
    }
    v["header"].as_object_mut().unwrap().remove("command");
    v
}

#[test]
fn json_has_the_rows_columns_and_targets() {
    let v = json(&["bench", "--rigs", "--goals", "6", "--json"]);
    let h = &v["header"];
    assert_eq!(h["command"], "ikarus bench --rigs --goals 6 --json");
    assert_eq!((h["goals"].as_u64(), h["seed"].as_u64(), h["kdl_version"].clone()), (Some(6), Some(1), Value::Null));
    let sets: Vec<&str> = h["sets"].as_array().unwrap().iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(sets, SETS);
    assert_eq!(h["sets"][1]["goals"], serde_json::json!(["right_hand", "left_hand"]));
    assert_eq!(h["sets"][1]["pins"], serde_json::json!(["right_foot", "left_foot"]));
    assert_eq!(h["sets"][2]["goals"].as_array().unwrap().len(), 5);
    for set in SETS {
        assert_eq!(labels(&v, set), ROWS, "{set}");
        for r in rows(&v, set) {
            assert_eq!(r["goals"], 6);
            let reached = r["reached"].as_u64().unwrap();
            assert!(reached <= 6);
            assert_eq!(r["reached_percent"].as_f64().unwrap(), (1000.0 * reached as f64 / 6.0).floor() / 10.0);
            assert!(r["median_us"].as_f64().unwrap() > 0.0 && r["p99_us"].as_f64() >= r["median_us"].as_f64());
            assert_eq!((r["solve_errors"].as_u64(), r["vs_kdl_tree"].clone()), (Some(0), Value::Null));
            assert_ne!(r["limits"], "ignore");
        }
    }
    let targets = v["targets"].as_array().unwrap();
    assert_eq!(targets.len(), 4);
    assert_eq!(targets[2]["met"], Value::Null, "KDL's target is not measured without --kdl");
    assert_eq!(targets[3]["met"], true);
}

#[test]
fn runs_repeat_and_sets_are_chosen() {
    let args = ["bench", "--rigs", "--goals", "4", "--seed", "9", "--json"];
    let (a, b) = (json(&args), json(&args));
    assert_eq!(untimed(&a), untimed(&b));
    let hand = json(&["bench", "--rigs", "--goals", "4", "--seed", "9", "--rig-sets", "hand,hand", "--json"]);
    let sets: Vec<&Value> = hand["header"]["sets"].as_array().unwrap().iter().collect();
    assert_eq!(sets.len(), 1);
    assert_eq!(untimed(&hand)["rows"], Value::Array(untimed(&a)["rows"].as_array().unwrap()[12..].to_vec()));
}

#[test]
fn markdown_and_text() {
    let md = succeeds(&["bench", "--rigs", "--goals", "2", "--rig-sets", "puppet-pins", "--markdown"]);
    assert!(md.starts_with("`ikarus bench --rigs --goals 2 --rig-sets puppet-pins --markdown`\n\n"), "{md}");
    assert!(md.contains("| set | solver | limits | reached | median µs | p99 µs | iter | worst err | × KDL tree |"));
    assert!(md.contains("| puppet-pins | sequential | lock |"), "{md}");
    assert!(md.contains("- puppet-pins · puppet: goals right_hand left_hand, pins right_foot left_foot"), "{md}");
    assert!(md.contains("- not measured default ≥ 5× faster than KDL's tree solver"), "{md}");
    let text = succeeds(&["bench", "--rigs", "--goals", "2", "--rig-sets", "hand,puppet"]);
    assert!(text.starts_with("ikarus bench --rigs: ikarus "), "{text}");
    let hand = text.find("\nhand · hand: goals thumb_distal").unwrap();
    let puppet = text.find("\npuppet · puppet: goals right_hand").unwrap();
    assert!(hand < puppet, "in the order asked");
}

/// A stand-in for `kdl_bench`: it copies the rig goal file into `seen` and answers every
/// target set with the start pose, 5000 + i ns.
fn fake_kdl(dir: &Path, seen: &Path) -> String {
    let path = dir.join("kdl_bench");
    let body = format!(
        r#"#!/bin/sh
cp "$1" '{seen}/'
awk '
  $1 == "start" {{ start = ""; for (i = 2; i <= NF; i++) start = start " " $i }}
  $1 == "goals" {{ goals = $2 }}
  END {{ print "kdl 0.0-fake"; for (g = 0; g < goals; g++) print "tree", g, 5000 + g, -1, "-3" start }}' "$1"
"#,
        seen = seen.display()
    );
    std::fs::write(&path, body).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    path.to_str().unwrap().to_owned()
}

#[test]
fn kdl_rows_are_merged_and_judged() {
    let dir = tempfile::tempdir().unwrap();
    let seen = dir.path().join("seen");
    std::fs::create_dir(&seen).unwrap();
    let kdl = fake_kdl(dir.path(), &seen);
    let v = json(&["bench", "--rigs", "--goals", "3", "--kdl", &kdl, "--json"]);
    assert_eq!(v["header"]["kdl_version"], "0.0-fake");
    for set in SETS {
        let rs = rows(&v, set);
        let k = rs.last().unwrap();
        assert_eq!((k["solver"].as_str(), k["limits"].as_str()), (Some("kdl tree nr_jl"), Some("clamp")));
        // The start pose reaches none of the targets: judged by ikarus, not by KDL's word.
        assert_eq!((k["reached"].as_u64(), k["median_us"].as_f64()), (Some(0), Some(5.001)));
        assert_eq!(k["vs_kdl_tree"], 1.0);
        for r in &rs {
            let ratio = 5.001 / r["median_us"].as_f64().unwrap();
            assert!((r["vs_kdl_tree"].as_f64().unwrap() - ratio).abs() < 1e-9 * ratio, "{r}");
        }
        // The file it was given.
        let file = std::fs::read_to_string(seen.join(format!("{set}.rig-goals"))).unwrap();
        let lines: Vec<&str> = file.lines().collect();
        assert_eq!(lines[0], "ikarus-rig-goals 1");
        assert_eq!(lines[2], format!("name {set}"));
        assert!(file.ends_with('\n') && file.contains("\ngoals 3\n"), "{file}");
    }
    let pins = std::fs::read_to_string(seen.join("puppet-pins.rig-goals")).unwrap();
    assert!(pins.contains("\nbones 16\n") && pins.contains("\neffectors 9 6 15 12\npinned 0 0 1 1\n"), "{pins}");
    assert!(pins.contains("\nlambda 0.001\n"), "{pins}");
    let t = &v["targets"][2];
    assert_eq!(t["met"], false, "the fake KDL is as fast as it gets: {t}");
}

#[test]
fn a_broken_kdl_is_one_line_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("short");
    std::fs::write(&path, "#!/bin/sh\necho 'kdl 1.5.1'\necho 'tree 0 1 -1 0 0'\n").unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let p = path.to_str().unwrap();
    let err = fails(&["bench", "--rigs", "--goals", "2", "--rig-sets", "hand", "--kdl", p], 1);
    assert!(err.starts_with(&format!("ikarus: --kdl {p}: set hand: output line 2: expected 22 fields")), "{err}");
    let err = fails(&["bench", "--rigs", "--kdl", "/nonexistent/kdl_bench"], 2);
    assert!(err.contains("No such file or directory"), "{err}");
}

#[test]
fn bad_flags_exit_2_with_one_line() {
    let cases: [(&[&str], &str); 6] = [
        (&["bench", "--rigs", "--paths"], "'--rigs' cannot be used with '--paths'"),
        (&["bench", "--rigs", "--arms", "seed"], "'--rigs' cannot be used with '--arms <ARM,…>'"),
        (&["bench", "--rigs", "--methods", "dls"], "'--rigs' cannot be used with '--methods <METHOD,…>'"),
        (&["bench", "--rigs", "--rig-sets", "octopus"], "[possible values: puppet, puppet-pins, hand]"),
        (&["bench", "--rig-sets", "hand"], "the following required arguments were not provided"),
        (&["bench", "--rigs", "--goals", "0"], "'--goals <N>': 0: must be at least 1"),
    ];
    for (args, want) in cases {
        let err = fails(args, 2);
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

/// Needs the library's real rig solver (the placeholder returns the start pose): the default
/// options reach every one of the 40 jointly reachable target sets of each rig (an exact count:
/// the goals are seeded and the run is deterministic), and more than solving limb after limb
/// does wherever limbs share bones.
#[test]
fn the_default_reaches_what_the_sequential_baseline_misses() {
    let v = json(&["bench", "--rigs", "--goals", "40", "--json"]);
    for set in SETS {
        let rs = rows(&v, set);
        let reached = |label: &str| rs.iter().find(|r| r["solver"] == label).unwrap()["reached"].as_u64().unwrap();
        assert_eq!(reached("default"), 40, "{set}: target sets the default reached of 40");
        assert!(reached("default") > reached("sequential"), "{set}");
    }
}
