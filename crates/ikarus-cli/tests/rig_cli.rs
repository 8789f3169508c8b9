//! `ikarus solve --rig` and `ikarus render rig` through the binary: the JSON, CSV and text of a
//! rig solve, batches of target sets, pictures, and every class of bad input (exit 2, one line
//! naming the flag, the column or the file's field).

mod common;
#[path = "common/rigs.rs"]
mod rigs;

use std::path::Path;

use serde_json::Value;

use common::{fails, floats, ikarus, json, point, stderr, stdout, succeeds};
use rigs::puppet;

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

/// A small rig whose names hold dots.
const DOTTED: &str = "name = \"fork\"\n\
    [[bones]]\nname = \"trunk\"\nlength = 1\nangle_deg = 90\n\
    [[bones]]\nname = \"arm.l\"\nparent = \"trunk\"\nlength = 1\nangle_deg = 45\n\
    [[bones]]\nname = \"arm.r\"\nparent = \"trunk\"\nlength = 1\nangle_deg = -45\n";

#[test]
fn the_json_of_a_rig_solve() {
    let rig = rigs::json("puppet");
    let names = rigs::names(&rig);
    let out = succeeds(&[
        "solve",
        "--rig",
        &puppet(),
        "--goal",
        "right_hand=0.3,0.8",
        "--goal",
        "left_hand=0.2,0.6,45",
        "--pin",
        "left_foot",
        "--limits",
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    let mut want = vec![
        "rig",
        "method",
        "limits",
        "limit_mode",
        "status",
        "iterations",
        "restarts",
        "error",
        "angle_error_deg",
        "tolerance",
        "solve_us",
        "effectors",
        "angles_deg",
        "joints",
        "frames",
    ];
    let mut sorted = keys.clone();
    sorted.sort_unstable();
    want.sort_unstable();
    assert_eq!(sorted, want);
    assert_eq!(v["rig"], "puppet");
    assert_eq!(v["method"], "lm");
    assert_eq!(v["limits"], true);
    assert_eq!(v["limit_mode"], "lock");
    assert_eq!(v["tolerance"], 1e-6);
    // Goals in order, then pins.
    let effectors = v["effectors"].as_array().unwrap();
    let got: Vec<(&str, bool)> =
        effectors.iter().map(|e| (e["name"].as_str().unwrap(), e["pinned"].as_bool().unwrap())).collect();
    assert_eq!(got, [("right_hand", false), ("left_hand", false), ("left_foot", true)]);
    assert_eq!(point(&effectors[0]["target"]), [0.3, 0.8]);
    for e in effectors {
        let keys: Vec<&str> = e.as_object().unwrap().keys().map(String::as_str).collect();
        assert_eq!(keys.len(), 7, "{keys:?}");
        for k in ["name", "pinned", "status", "error", "angle_error_deg", "tip", "target"] {
            assert!(e.get(k).is_some(), "{k} missing in {e}");
        }
    }
    // The largest effector error is the error.
    let largest = effectors.iter().map(|e| e["error"].as_f64().unwrap()).fold(0.0, f64::max);
    assert_eq!(v["error"].as_f64().unwrap(), largest);
    // Angles and joints are objects keyed by bone name, in the file's order.
    let angles = v["angles_deg"].as_object().unwrap();
    let joints = v["joints"].as_object().unwrap();
    assert_eq!(angles.len(), names.len());
    assert_eq!(joints.len(), names.len());
    let mut at = 0;
    let text = &out[out.find("\"angles_deg\"").unwrap()..out.find("\"joints\"").unwrap()];
    for name in &names {
        let k = text.find(&format!("\"{name}\"")).unwrap_or_else(|| panic!("{name} not in angles_deg"));
        assert!(k > at, "{name} out of order in {text}");
        at = k;
    }
    // The joints are the tips of the angles.
    let deg: Vec<f64> = names.iter().map(|n| angles[n].as_f64().unwrap()).collect();
    for (name, (tip, _)) in names.iter().zip(rigs::tips(&rig, &deg)) {
        let j = point(&joints[name]);
        assert!((j[0] - tip[0]).abs() < 1e-9 && (j[1] - tip[1]).abs() < 1e-9, "{name}: {j:?} vs {tip:?}");
    }
    // Effectors' tips are their bones' tips.
    for e in effectors {
        let j = point(&joints[e["name"].as_str().unwrap()]);
        assert_eq!(point(&e["tip"]), j);
    }
    // No frames unless asked for.
    assert_eq!(v["frames"], Value::Array(vec![]));
}

/// Real solving: both hands reach targets the puppet can reach (made by forward kinematics of
/// a pose inside its limits) with both feet planted, limits on.
#[test]
fn the_puppet_reaches_with_both_hands_while_its_feet_stay_planted() {
    let targets = rigs::puppet_hand_targets();
    let goals: Vec<String> = targets.iter().map(|(h, [x, y])| format!("{h}={x},{y}")).collect();
    let v = json(&[
        "solve",
        "--rig",
        &puppet(),
        "--goal",
        &goals[0],
        "--goal",
        &goals[1],
        "--pin",
        "left_foot",
        "--pin",
        "right_foot",
        "--limits",
        "--record-every",
        "5",
    ]);
    assert_eq!(v["status"], "reached", "{v}");
    let tolerance = v["tolerance"].as_f64().unwrap();
    for e in v["effectors"].as_array().unwrap() {
        assert_eq!(e["status"], "reached", "{e}");
        assert!(e["error"].as_f64().unwrap() <= tolerance, "{e}");
    }
    // The feet are where they started.
    let rig = rigs::json("puppet");
    let names = rigs::names(&rig);
    let start = rigs::tips(&rig, &rigs::start_deg(&rig));
    for foot in ["left_foot", "right_foot"] {
        let j = point(&v["joints"][foot]);
        let s = start[names.iter().position(|n| n == foot).unwrap()].0;
        assert!((j[0] - s[0]).hypot(j[1] - s[1]) <= tolerance, "{foot}: {j:?} from {s:?}");
    }
    // Frames: base and every tip, angles in bone order; the first is the start pose.
    let frames = v["frames"].as_array().unwrap();
    assert!(frames.len() >= 2, "{frames:?}");
    for f in frames {
        assert_eq!(f["angles_deg"].as_array().unwrap().len(), names.len());
        assert_eq!(f["joints"].as_array().unwrap().len(), names.len() + 1);
    }
    let first = floats(&frames[0]["angles_deg"]);
    for (a, s) in first.iter().zip(rigs::start_deg(&rig)) {
        assert!((a - s).abs() < 1e-9, "{first:?}");
    }
}

#[test]
fn csv_is_one_row_under_a_header_of_angles_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let rig = write(dir.path(), "fork.toml", DOTTED);
    let out = succeeds(&["solve", "--rig", &rig, "--goal", "arm.l=-1,1.5", "--format", "csv"]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert_eq!(lines[0], "status,iterations,error,trunk_deg,arm.l_deg,arm.r_deg");
    let row: Vec<&str> = lines[1].split(',').collect();
    assert_eq!(row.len(), 6, "{out}");
    assert!(["reached", "iteration_limit", "stalled", "unreachable"].contains(&row[0]), "{out}");
    for cell in &row[1..] {
        cell.parse::<f64>().unwrap_or_else(|_| panic!("{cell} in {out}"));
    }
}

#[test]
fn text_has_a_line_per_effector() {
    let out = succeeds(&[
        "solve",
        "--rig",
        &puppet(),
        "--goal",
        "right_hand=0.3,0.8",
        "--pin",
        "left_foot",
        "--pin",
        "right_foot",
        "--format",
        "text",
    ]);
    assert!(out.starts_with("rig       puppet (16 bones)\n"), "{out}");
    let effector_lines: Vec<&str> = out.lines().filter(|l| l.starts_with("  ")).collect();
    assert_eq!(effector_lines.len(), 3, "{out}");
    assert!(effector_lines[0].trim_start().starts_with("right_hand  goal (0.3, 0.8): "), "{out}");
    assert!(effector_lines[1].trim_start().starts_with("left_foot   pinned: "), "{out}");
    assert!(out.contains("limits off (the rig has ranges: --limits enforces them)"), "{out}");
}

#[test]
fn a_batch_of_target_sets_with_dotted_names() {
    let dir = tempfile::tempdir().unwrap();
    let rig = write(dir.path(), "fork.toml", DOTTED);
    // Columns in any order, a goal with an angle, names holding dots: split at the last dot.
    let goals = write(
        dir.path(),
        "g.csv",
        "arm.r.y,arm.l.x,arm.l.y,arm.r.x,arm.r.angle_deg\n1,-1,1.5,1,0\n1.2,-0.5,1.8,0.7,10\n0.5,-1.2,1.2,1.5,-20\n",
    );
    let summary = dir.path().join("s.json");
    let o = ikarus(&[
        "solve",
        "--rig",
        &rig,
        "--batch",
        &goals,
        "--pin",
        "trunk",
        "--threads",
        "2",
        "--summary-json",
        summary.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 4, "a header and one row per target set: {out}");
    assert_eq!(
        lines[0],
        "arm.r.y,arm.l.x,arm.l.y,arm.r.x,arm.r.angle_deg,status,error,iterations,trunk_deg,arm.l_deg,arm.r_deg"
    );
    assert!(lines[1].starts_with("1.0,-1.0,1.5,1.0,0.0,"), "{out}");
    for l in &lines[1..] {
        assert_eq!(l.split(',').count(), 11, "{l}");
    }
    // The summary line and file of a chain batch.
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("batch: 3 goals, "), "{err}");
    assert!(err.contains(" µs per solve, 2 threads"), "{err}");
    let s = common::batch_summary(&summary, &err, 3.0);
    assert_eq!(s["goals"], 3);
    assert_eq!(s["threads"], 2);
    assert_eq!(s["method"], "lm");
}

/// Real solving: jointly reachable target sets (the puppet's hands at poses inside its limits)
/// are all reached, feet planted.
#[test]
fn a_batch_of_reachable_target_sets_is_all_reached() {
    let dir = tempfile::tempdir().unwrap();
    let [(a, [ax, ay]), (b, [bx, by])] = rigs::puppet_hand_targets()[..] else { panic!() };
    let text = format!("{a}.x,{a}.y,{b}.x,{b}.y\n{ax},{ay},{bx},{by}\n{ax},{ay},{bx},{by}\n");
    let goals = write(dir.path(), "g.csv", &text);
    let o = ikarus(&[
        "solve",
        "--rig",
        &puppet(),
        "--batch",
        &goals,
        "--pin",
        "left_foot",
        "--pin",
        "right_foot",
        "--limits",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("batch: 2 goals, 2 reached (100.00%)"), "{}", stderr(&o));
}

#[test]
fn pictures_of_a_rig() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("p.svg");
    let png = dir.path().join("p.png");
    let out = succeeds(&[
        "solve",
        "--rig",
        &puppet(),
        "--goal",
        "right_hand=0.3,0.8",
        "--pin",
        "left_foot",
        "--limits",
        "--format",
        "csv",
        "--out",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(out.lines().count(), 2, "the data still goes to stdout");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"), "{text}");
    for i in 0..16 {
        assert!(text.contains(&format!("id=\"bone{i}\"")), "bone{i}");
    }
    assert!(text.contains("pinned") && text.contains("goal"), "the legend names goals and pins");
    // The same rig, no limits: no wedges (the limit wedges are the only difference in size).
    let plain = dir.path().join("q.svg");
    succeeds(&[
        "solve",
        "--rig",
        &puppet(),
        "--goal",
        "right_hand=0.3,0.8",
        "--pin",
        "left_foot",
        "--format",
        "csv",
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&plain).unwrap().len() < text.len());

    succeeds(&[
        "render",
        "rig",
        "--rig",
        &puppet(),
        "--pose-deg",
        "right_upper_arm=-90",
        "--goal",
        "right_hand=0.5,0.6,30",
        "--pin",
        "left_foot",
        "--labels",
        "--limits",
        "--out",
        png.to_str().unwrap(),
    ]);
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let labelled = dir.path().join("l.svg");
    succeeds(&["render", "rig", "--rig", &puppet(), "--labels", "--out", labelled.to_str().unwrap()]);
    assert!(std::fs::read_to_string(&labelled).unwrap().contains(">right_forearm<"));

    // An arm's solve draws too.
    let arm = dir.path().join("a.svg");
    succeeds(&["solve", "--goal", "2,3", "--format", "csv", "--out", arm.to_str().unwrap()]);
    assert!(std::fs::read_to_string(&arm).unwrap().starts_with("<svg"));
}

#[test]
fn bad_input_exits_2_with_one_line() {
    let p = puppet();
    let dir = tempfile::tempdir().unwrap();
    let gif = dir.path().join("x.gif");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["--goal", "right_hnd=1,1"],
            "--goal right_hnd=1,1: no bone named \"right_hnd\" in the rig (its bones: pelvis, spine,",
        ),
        (vec!["--goal", "right_hand=1,1", "--pin", "left_fot"], "--pin left_fot: no bone named \"left_fot\""),
        (
            vec!["--goal", "right_hand=1,1", "--goal", "right_hand=2,2"],
            "--goal right_hand=2,2: bone \"right_hand\" already has a goal (--goal right_hand=1,1); one goal or pin per bone",
        ),
        (
            vec!["--goal", "left_foot=1,1", "--pin", "left_foot"],
            "--pin left_foot: bone \"left_foot\" already has a goal (--goal left_foot=1,1)",
        ),
        (vec!["--pin", "left_foot", "--pin", "left_foot"], "--pin left_foot: bone \"left_foot\" already has a pin"),
        (vec!["--goal", "right_hand=1,nan"], "'--goal <X,Y>': right_hand: y: must be a finite number, got nan"),
        (vec!["--goal", "right_hand=1"], "right_hand=: expected X,Y or X,Y,DEG after the name, got 1 part(s)"),
        (vec!["--goal", "1,1"], "--goal 1,1: a rig's goal names its bone: --goal NAME=X,Y[,DEG]"),
        (vec![], "--goal: a rig solve needs at least one --goal NAME=X,Y or --pin NAME"),
        (vec!["--goal", "right_hand=1,1", "--weight", "right_hand=0"], "'--weight <NAME=W>': right_hand: 0: must be"),
        (
            vec!["--goal", "right_hand=1,1", "--weight", "left_hand=2"],
            "--weight left_hand=2: no goal on bone \"left_hand\"",
        ),
        (
            vec!["--goal", "right_hand=1,1", "--softness", "right_hand=-1"],
            "'--softness <NAME=S>': right_hand: -1: must be",
        ),
        (vec!["--goal", "right_hand=1,1", "--bend", "right_hand=up"], "right_hand: 'up': expected ccw"),
        (vec!["--goal", "pelvis=0,1", "--bend", "pelvis=cw"], "--bend pelvis: bone \"pelvis\" has no parent"),
        (vec!["--goal", "right_hand=1,1", "--secondary", "head"], "--secondary head: no goal on bone \"head\""),
        (vec!["--goal", "right_hand=1,1", "--mix", "1.5"], "'--mix <M>': 1.5: must be from 0 to 1"),
        (vec!["--goal", "right_hand=1,1", "--rates", "1,2"], "--rates: expected 16 values (one per joint), got 2"),
        (vec!["--goal", "right_hand=1,1", "--goal-angle", "3"], "cannot be used with"),
        (vec!["--goal", "right_hand=1,1", "--arm", "a.toml"], "'--rig <FILE>' cannot be used with '--arm <FILE>'"),
        (
            vec!["--goal", "right_hand=1,1", "--out", gif.to_str().unwrap()],
            "unsupported picture format (use .svg, .png)",
        ),
    ];
    for (extra, want) in &cases {
        let mut args = vec!["solve", "--rig", &p];
        args.extend(extra);
        let err = fails(&args, 2);
        assert!(err.contains(want), "{args:?}: {err:?} lacks {want:?}");
    }
    // Methods that solve chains only.
    for method in ["ccd", "fabrik", "analytic"] {
        let err = fails(&["solve", "--rig", &p, "--goal", "right_hand=1,1", "--method", method], 2);
        assert_eq!(
            err,
            format!("ikarus: method {method}: solves chains only; a rig needs transpose, pinv, dls, sdls or lm\n")
        );
    }
    // Rig flags need a rig; an arm takes one unnamed goal.
    let err = fails(&["solve", "--goal", "1,1", "--pin", "x"], 2);
    assert!(err.contains("required arguments were not provided: --rig <FILE>"), "{err}");
    let err = fails(&["solve", "--goal", "hand=1,1"], 2);
    assert!(err.contains("--goal hand=1,1: a goal on a named bone needs --rig FILE"), "{err}");
    let err = fails(&["solve", "--goal", "1,1", "--goal", "2,2"], 2);
    assert!(err.contains("--goal: an arm has one tip, so one --goal X,Y, got 2"), "{err}");
    let err = fails(&["render", "rig", "--rig", &p, "--pose-deg", "elbow=3", "--out", "x.svg"], 2);
    assert!(err.contains("--pose-deg elbow=3: no bone named \"elbow\""), "{err}");
}

#[test]
fn bad_rig_files_exit_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let a = "[[bones]]\nname = \"a\"\nlength = 1\n";
    let cases = [
        (
            "duplicate.toml",
            format!("{a}[[bones]]\nname = \"a\"\nlength = 1\n"),
            "bones[1] (\"a\").name = \"a\": the name of bones[0] already; names must be unique",
        ),
        (
            "cycle.toml",
            format!(
                "{a}[[bones]]\nname = \"b\"\nparent = \"c\"\nlength = 1\n[[bones]]\nname = \"c\"\nparent = \"b\"\nlength = 1\n"
            ),
            "bones[1] (\"b\").parent = \"c\": a cycle (b → c → b)",
        ),
        (
            "parent.toml",
            format!("{a}[[bones]]\nname = \"b\"\nparent = \"nope\"\nlength = 1\n"),
            "bones[1] (\"b\").parent = \"nope\": no bone of that name",
        ),
        // (Two roots: a one-branch rig is a chain, which CCD solves since issue 25.)
        (
            "solver.toml",
            format!("{a}[[bones]]\nname = \"b\"\nlength = 1\n[solver]\nmethod = \"ccd\"\n"),
            "method ccd: solves chains only",
        ),
    ];
    for (name, text, want) in cases {
        let path = write(d, name, &text);
        let err = fails(&["solve", "--rig", &path, "--goal", "a=1,1"], 2);
        assert!(err.contains(want), "{name}: {err}");
        if name != "solver.toml" {
            assert!(err.starts_with(&format!("ikarus: rig file {path}: ")), "{err}");
        }
    }
    let err = fails(&["solve", "--rig", "/nonexistent/rig.toml", "--goal", "a=1,1"], 2);
    assert_eq!(err, "ikarus: rig file /nonexistent/rig.toml: cannot read: No such file or directory\n");
}

#[test]
fn bad_batch_files_name_the_column_or_line() {
    let dir = tempfile::tempdir().unwrap();
    let rig = write(dir.path(), "fork.toml", DOTTED);
    let cases = [
        ("arm.l.x,arm.l.z\n1,2\n", "line 1: column 2 `arm.l.z`: expected NAME.x, NAME.y or NAME.angle_deg"),
        ("arm.x,arm.y\n1,2\n", "line 1: column 1 `arm.x`: no bone named \"arm\" in the rig"),
        ("arm.l.x,arm.l.y,arm.l.x\n1,2,3\n", "line 1: column 3 `arm.l.x`: the same as column 1"),
        ("arm.l.x,arm.r.x,arm.r.y\n1,2,3\n", "line 1: column 1 `arm.l.x`: no `arm.l.y` column"),
        ("arm.l.x,arm.l.y\n1,nan\n", "line 2: arm.l.y: must be a finite number, got nan"),
        ("arm.l.x,arm.l.y\n", "no target sets (expected a header and one target set per row)"),
        ("trunk.x,trunk.y\n1,1\n", "--pin trunk: bone \"trunk\" already has a goal"),
    ];
    for (i, (text, want)) in cases.iter().enumerate() {
        let goals = write(dir.path(), &format!("g{i}.csv"), text);
        let err = fails(&["solve", "--rig", &rig, "--batch", &goals, "--pin", "trunk"], 2);
        assert!(err.starts_with(&format!("ikarus: batch file {goals}: ")) || want.starts_with("--pin"), "{err}");
        assert!(err.contains(want), "{text:?}: {err}");
    }
    let goals = write(dir.path(), "ok.csv", "arm.l.x,arm.l.y\n1,1\n");
    let err = fails(&["solve", "--rig", &rig, "--batch", &goals, "--out", "x.svg"], 2);
    assert!(err.contains("--out x.svg: only applies to a single solve, not --batch"), "{err}");
}

/// A rig file's `[solver]` table applies as an arm file's does, and flags override it.
#[test]
fn the_rig_files_solver_table_applies_and_flags_override_it() {
    let dir = tempfile::tempdir().unwrap();
    let rig = write(dir.path(), "fork.toml", &format!("{DOTTED}[solver]\nmethod = \"dls\"\ntolerance = 0.001\n"));
    let v = json(&["solve", "--rig", &rig, "--goal", "arm.l=-1,1.5"]);
    assert_eq!((v["method"].as_str(), v["tolerance"].as_f64()), (Some("dls"), Some(0.001)));
    let v = json(&["solve", "--rig", &rig, "--goal", "arm.l=-1,1.5", "--method", "sdls", "--tolerance", "0.01"]);
    assert_eq!((v["method"].as_str(), v["tolerance"].as_f64()), (Some("sdls"), Some(0.01)));
    let bad = write(dir.path(), "rates.toml", &format!("{DOTTED}[solver]\nrates = [1, 2]\n"));
    let err = fails(&["solve", "--rig", &bad, "--goal", "arm.l=-1,1.5"], 2);
    assert_eq!(err, format!("ikarus: rig file {bad}: [solver].rates: expected 3 values (one per joint), got 2\n"));
}

/// `--mix M` takes M of the way from the start pose to the solution, every bone alike.
#[test]
fn mix_blends_the_start_pose_and_the_solution() {
    let p = puppet();
    let angles = |mix: &str| -> Vec<f64> {
        let v = json(&["solve", "--rig", &p, "--goal", "right_hand=0.3,0.8", "--pin", "left_foot", "--mix", mix]);
        let names = rigs::names(&rigs::json("puppet"));
        names.iter().map(|n| v["angles_deg"][n].as_f64().unwrap()).collect()
    };
    let start = rigs::start_deg(&rigs::json("puppet"));
    let (none, half, full) = (angles("0"), angles("0.5"), angles("1"));
    assert_ne!(full, start);
    for i in 0..start.len() {
        assert!((none[i] - start[i]).abs() < 1e-9, "{none:?}");
        assert!((half[i] - (start[i] + full[i]) / 2.0).abs() < 1e-9, "{half:?} vs {full:?}");
    }
}

/// `--bend NAME=cw|ccw` picks which of a two-bone limb's two solutions the solve ends in: the
/// sign of the bone's own angle.
#[test]
fn bend_picks_the_side_of_the_joint() {
    let dir = tempfile::tempdir().unwrap();
    let rig = write(dir.path(), "fork.toml", DOTTED);
    for (side, sign) in [("cw", -1.0), ("ccw", 1.0)] {
        let v = json(&["solve", "--rig", &rig, "--goal", "arm.l=1.2,0.8", "--bend", &format!("arm.l={side}")]);
        assert_eq!(v["status"], "reached", "{side}: {v}");
        let a = v["angles_deg"]["arm.l"].as_f64().unwrap();
        assert!(a * sign > 0.0, "{side}: arm.l at {a}°");
    }
}

/// A rig file of one chain of `n` bones (`b0` at the base, `b{n-1}` the tip).
fn chain_rig(dir: &Path, n: usize) -> String {
    let mut text = String::with_capacity(n * 48);
    for i in 0..n {
        let parent = if i == 0 { String::new() } else { format!("parent = \"b{}\"\n", i - 1) };
        text.push_str(&format!("[[bones]]\nname = \"b{i}\"\n{parent}length = 0.001\n"));
    }
    write(dir, &format!("chain{n}.toml"), &text)
}

/// Issue 24: a 100 000-bone chain (6.9 MB, under the input cap) made `ikarus solve --rig` ask for
/// 40 GB and abort (exit 134). Every command that reads a rig counts its bones first and
/// refuses it in one line, before a bone is checked or built; `--max-bones N` raises the cap.
#[test]
fn every_rig_command_refuses_a_rig_over_the_bone_cap_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let rig = chain_rig(dir.path(), 100_000);
    let out = dir.path().join("x.svg");
    let out = out.to_str().unwrap();
    let commands: [&[&str]; 4] = [
        &["solve", "--rig", &rig, "--goal", "b99999=1,0"],
        &["animate", "--rig", &rig, "--goal", "b99999=1,0", "--frames", "3"],
        &["track", "--rig", &rig, "--effector", "b99999", "--line", "0,0,1,1", "--samples", "3"],
        &["render", "rig", "--rig", &rig, "--out", out],
    ];
    for args in commands {
        let e = fails(args, 2);
        assert_eq!(
            e,
            format!(
                "ikarus: rig file {rig}: bones: 100000 bones exceed the cap of 10000 (raise it with --max-bones N)\n"
            )
        );
        let raised: Vec<&str> = ["--max-bones", "99999"].iter().chain(args).copied().collect();
        let e = fails(&raised, 2);
        assert!(e.contains(": bones: 100000 bones exceed the cap of 99999 (raise it with --max-bones N)"), "{e}");
    }
    assert!(!Path::new(out).exists());
}

/// With the cap raised, the same chain is read and solved: the skeleton's memory is linear in
/// its bones (before, its root-to-bone paths held n²/2 entries).
#[test]
fn a_chain_of_100000_bones_solves_once_the_cap_allows_it() {
    let dir = tempfile::tempdir().unwrap();
    let rig = chain_rig(dir.path(), 100_000);
    let v = json(&[
        "solve",
        "--rig",
        &rig,
        "--max-bones",
        "100000",
        "--goal",
        "b99999=50,50",
        "--max-iterations",
        "3",
        "--restarts",
        "0",
        "--format",
        "json",
    ]);
    assert_eq!(v["angles_deg"].as_object().unwrap().len(), 100_000);
    // The chain is 100 long: (50, 50) is within reach, and 3 iterations move the tip toward it.
    assert!(v["error"].as_f64().unwrap() < 100.0, "{}", v["error"]);
}
