//! End-to-end tests of the `ikarus` binary: the JSON contract, the formats, batch mode, and
//! every class of bad input (exit code 2, one line on stderr naming the field and value).

mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;

use common::{fails, floats, ikarus, json, stderr, stdout};

fn arms() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms")
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

#[test]
fn json_contract_of_a_single_solve() {
    // Not a terminal, so JSON is the default format.
    let v = json(&["solve", "--goal", "2,3"]);
    assert_eq!(v["status"], "reached");
    assert_eq!(v["method"], "lm");
    assert_eq!(v["limits"], false);
    assert_eq!(v["limit_mode"], "ignore");
    assert_eq!(v["restarts"], 0);
    let iterations = v["iterations"].as_u64().unwrap();
    assert!(iterations > 0 && iterations <= 1000);
    let error = v["error"].as_f64().unwrap();
    assert!(error <= 1e-6, "{error}");
    let angles = floats(&v["angles_deg"]);
    assert_eq!(angles.len(), 3);
    let joints = v["joints"].as_array().unwrap();
    assert_eq!(joints.len(), 4, "base first, tip last");
    assert_eq!(floats(&joints[0]), vec![0.0, 0.0]);
    let tip = floats(&joints[3]);
    assert!(((tip[0] - 2.0).powi(2) + (tip[1] - 3.0).powi(2)).sqrt() <= 1e-6, "{tip:?}");
    // The tip follows from the angles (degrees) by forward kinematics of lengths 3, 2, 1.
    let (mut x, mut y, mut phi) = (0.0, 0.0, 0.0);
    for (a, l) in angles.iter().zip([3.0, 2.0, 1.0]) {
        phi += a.to_radians();
        x += l * phi.cos();
        y += l * phi.sin();
    }
    assert!((x - tip[0]).abs() < 1e-9 && (y - tip[1]).abs() < 1e-9);

    let frames = v["frames"].as_array().unwrap();
    assert!(frames.len() >= 2);
    assert_eq!(frames[0]["iteration"], 0);
    assert_eq!(floats(&frames[0]["angles_deg"]), vec![5.0, 5.0, 5.0], "the first frame is the start pose");
    assert_eq!(frames.last().unwrap()["iteration"].as_u64().unwrap(), iterations, "the last frame is the end");
    assert_eq!(floats(&frames.last().unwrap()["angles_deg"]), angles);
    for f in frames {
        assert_eq!(f["angles_deg"].as_array().unwrap().len(), 3);
        assert_eq!(f["joints"].as_array().unwrap().len(), 4);
    }
}

#[test]
fn frames_are_recorded_every_k_iterations() {
    let v = json(&["solve", "--goal", "-4,1", "--method", "transpose", "--record-every", "5"]);
    let its: Vec<u64> = v["frames"].as_array().unwrap().iter().map(|f| f["iteration"].as_u64().unwrap()).collect();
    let last = v["iterations"].as_u64().unwrap();
    assert!(last > 10, "needs a long solve, took {last}");
    for (i, it) in its.iter().enumerate() {
        if i + 1 < its.len() {
            assert_eq!(*it, 5 * i as u64);
        }
    }
    assert_eq!(*its.last().unwrap(), last);
}

#[test]
fn statuses_reach_the_output() {
    let v = json(&["solve", "--goal", "10,3"]);
    assert_eq!(v["status"], "unreachable");
    let error = v["error"].as_f64().unwrap();
    let expected = (10f64.hypot(3.0)) - 6.0;
    assert!((error - expected).abs() <= 1e-6, "{error} vs {expected}");

    // A goal behind the arm that no pose within the seed's ranges reaches: the exact region
    // says so at once, with the distance, and the tip at the region's nearest point.
    let v = json(&["solve", "--goal", "-3,-1", "--limits"]);
    assert_eq!(v["status"], "unreachable");
    assert_eq!((v["iterations"].as_u64(), v["restarts"].as_u64()), (Some(1), Some(0)));
    let d = v["reach_distance"].as_f64().unwrap();
    assert!((d - 3.491277).abs() < 1e-6 && (v["error"].as_f64().unwrap() - d).abs() < 1e-9, "{v}");
    assert_eq!(v["limits"], true);
    let a = floats(&v["angles_deg"]);
    assert!((-45.0..=45.0).contains(&a[0]) && (-90.0..=90.0).contains(&a[1]) && (-170.0..=170.0).contains(&a[2]));

    let v = json(&["solve", "--goal", "-3,-1", "--max-iterations", "2", "--method", "transpose", "--restarts", "0"]);
    assert_eq!(v["status"], "iteration_limit");
    assert_eq!(v["iterations"], 2);
}

#[test]
fn orientation_goal() {
    let v = json(&["solve", "--goal", "4,2", "--goal-angle", "0"]);
    assert_eq!(v["status"], "reached");
    assert_eq!(v["goal"]["angle_deg"], 0.0);
    assert!(v["end_effector"]["angle_deg"].as_f64().unwrap().abs() < 1e-3);
    assert!(v["angle_error_deg"].as_f64().unwrap() < 1e-3);
}

#[test]
fn csv_and_text_formats() {
    let o = ikarus(&["solve", "--goal", "2,3", "--format", "csv", "--record-every", "1"]);
    assert!(o.status.success());
    let text = stdout(&o);
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "iteration,theta1_deg,theta2_deg,theta3_deg,x0,y0,x1,y1,x2,y2,x3,y3");
    let rows: Vec<&str> = lines.collect();
    let v = json(&["solve", "--goal", "2,3", "--record-every", "1"]);
    assert_eq!(rows.len(), v["frames"].as_array().unwrap().len());
    assert!(rows.iter().all(|r| r.split(',').count() == 12));

    let o = ikarus(&["solve", "--goal", "2,3", "--format", "text"]);
    let text = stdout(&o);
    assert!(text.contains("status    reached after"), "{text}");
    assert!(text.contains("limits off (the arm has ranges: --limits enforces them)"), "{text}");
}

#[test]
fn shipped_arms_solve_and_solver_tables_apply() {
    for (file, n) in [("seed.toml", 3), ("seven.toml", 7), ("tentacle.toml", 20)] {
        let arm = arms().join(file);
        let v = json(&["solve", "--arm", arm.to_str().unwrap(), "--goal", "2,4", "--limits"]);
        assert_eq!(v["angles_deg"].as_array().unwrap().len(), n, "{file}");
        assert_eq!(v["status"], "reached", "{file}: {v}");
    }
    let dir = tempfile::tempdir().unwrap();
    let arm = write(
        dir.path(),
        "a.toml",
        "name = \"two\"\nbase = [1.0, 1.0]\n[[links]]\nlength = 1\n[[links]]\nlength = 1\n[solver]\nmethod = \"transpose\"\ntolerance = 1e-3\n",
    );
    let v = json(&["solve", "--arm", &arm, "--goal", "2,2"]);
    assert_eq!(v["arm"], "two");
    assert_eq!(v["method"], "transpose");
    assert_eq!(v["tolerance"], 1e-3);
    assert_eq!(floats(&v["joints"][0]), vec![1.0, 1.0], "the base is where the file puts it");
    let v = json(&["solve", "--arm", &arm, "--goal", "2,2", "--method", "pinv"]);
    assert_eq!(v["method"], "pinv", "flags override the [solver] table");
}

fn batch_file(dir: &Path) -> String {
    let mut text = String::from("x,y\n");
    for i in 0..50 {
        let a = f64::from(i) * 0.37;
        let r = 1.0 + 0.1 * f64::from(i % 40);
        text.push_str(&format!("{},{}\n", r * a.cos(), r * a.sin()));
    }
    text.push_str("10,0\n"); // out of reach
    write(dir, "goals.csv", &text)
}

#[test]
fn batch_mode() {
    let dir = tempfile::tempdir().unwrap();
    let goals = batch_file(dir.path());
    let summary = dir.path().join("summary.json");
    let o = ikarus(&["solve", "--batch", &goals, "--threads", "2", "--summary-json", summary.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "x,y,status,error,iterations,theta1_deg,theta2_deg,theta3_deg");
    assert_eq!(lines.len(), 52, "a header and one row per goal");
    let last: Vec<&str> = lines[51].split(',').collect();
    assert_eq!(&last[..3], &["10.0", "0.0", "unreachable"]);
    let reached = lines[1..].iter().filter(|l| l.split(',').nth(2) == Some("reached")).count();
    assert_eq!(reached, 50);

    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "one summary line: {err}");
    assert!(err.contains("51 goals, 50 reached (98.03%)") && err.contains("2 threads"), "{err}");
    let s = common::batch_summary(&summary, &err, 51.0);
    assert_eq!(s["goals"], 51);
    assert_eq!(s["reached"], 50);
    assert_eq!(s["threads"], 2);
    assert!(s["median_us"].as_f64().unwrap() > 0.0);
    assert!(s["p99_us"].as_f64().unwrap() >= s["median_us"].as_f64().unwrap());
    let leftovers: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(leftovers.len(), 2, "only the goals and the summary: {leftovers:?}");

    // Results do not depend on the number of threads.
    let one = ikarus(&["solve", "--batch", &goals, "--threads", "1"]);
    assert_eq!(stdout(&one), out);
}

/// `n` goals spread over the seed arm's reach and beyond it (one in eight out of reach), with
/// long digits, and some that `{:?}` writes in scientific notation.
fn many_goals(n: u32) -> String {
    let mut text = String::from("x,y\n");
    for i in 0..n {
        let a = f64::from(i) * 0.618_033_988_749_894_9;
        let r = if i % 8 == 7 { 6.5 + f64::from(i % 5) } else { 0.3 + 5.6 * f64::from(i % 97) / 97.0 };
        match i % 50 {
            // Tiny and huge coordinates: `1.2345e-5`, `1e-7`, a tie that `{:?}` rounds up.
            3 => text.push_str("1.2345e-5,-1e-7\n"),
            13 => text.push_str(&format!("{:?},{:?}\n", 1.2345e-5 * f64::from(i), -1e-7 * f64::from(i))),
            4 => text.push_str("1299689300638963.25,1e16\n"),
            _ => text.push_str(&format!("{:?},{:?}\n", r * a.cos(), r * a.sin())),
        }
    }
    text
}

/// Every float of a batch's rows is `{:?}`'s text of the number it reads back as.
fn floats_as_debug(out: &str) {
    for line in out.lines().skip(1) {
        for (i, field) in line.split(',').enumerate() {
            if i == 2 || i == 4 {
                continue; // status, iterations
            }
            let v: f64 = field.parse().unwrap_or_else(|_| panic!("{field} in {line}"));
            assert_eq!(field, format!("{v:?}"), "{line}");
        }
    }
}

/// The rows do not depend on the threads, nor on the reader (a plain file is read by the fast
/// reader, in pieces on the batch's threads; the same goals with CRLF line ends by the csv
/// crate); a bad row is reported the same (the first one, by its line) and nothing is written.
#[test]
fn batch_rows_do_not_depend_on_the_threads() {
    let dir = tempfile::tempdir().unwrap();
    // 3000 goals: about 120 KB, so two pieces of the parallel reader and 47 blocks of solves.
    let text = many_goals(3000);
    let goals = write(dir.path(), "g.csv", &text);
    let crlf = write(dir.path(), "crlf.csv", &text.replace('\n', "\r\n"));
    let runs: Vec<String> = [(&goals, "1"), (&goals, "2"), (&goals, "3"), (&crlf, "2")]
        .iter()
        .map(|(file, threads)| {
            let o = ikarus(&["solve", "--batch", file, "--threads", threads]);
            assert!(o.status.success(), "{}", stderr(&o));
            stdout(&o)
        })
        .collect();
    for r in &runs[1..] {
        assert!(r == &runs[0], "the same bytes");
    }
    let out = &runs[0];
    assert_eq!(out.lines().count(), 3001);
    let unreachable = out.lines().filter(|l| l.split(',').nth(2) == Some("unreachable")).count();
    // An exact count: the goals and the verdicts are deterministic.
    assert_eq!(unreachable, 405, "rows unreachable");
    assert!(out.contains("\n1.2345e-5,-1e-7,") && out.contains("\n1299689300638963.3,1e16,unreachable,"));
    floats_as_debug(out);

    let mut lines: Vec<&str> = text.lines().collect();
    lines[2500] = "0.5,abc";
    lines[2900] = "1,2,3";
    let bad = write(dir.path(), "bad.csv", &(lines.join("\n") + "\n"));
    for threads in ["1", "2"] {
        let o = ikarus(&["solve", "--batch", &bad, "--threads", threads]);
        assert_eq!(o.status.code(), Some(2));
        assert_eq!(stdout(&o), "");
        assert_eq!(stderr(&o), format!("ikarus: batch file {bad}: line 2501: y: 'abc' is not a number\n"));
    }
}

#[test]
fn batch_with_orientations() {
    let dir = tempfile::tempdir().unwrap();
    let goals = write(dir.path(), "g.csv", "x,y,angle_deg\n4,2,0\n3,3,90\n");
    let o = ikarus(&["solve", "--batch", &goals]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert_eq!(out.lines().filter(|l| l.contains(",reached,")).count(), 2, "{out}");
}

#[test]
fn bad_flags_exit_2_with_one_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["solve", "--goal", "1,nan"], "'--goal <X,Y>': y: must be a finite number, got nan"),
        (&["solve", "--goal", "inf,1"], "x: must be a finite number, got inf"),
        (&["solve", "--goal", "1"], "expected two numbers X,Y, got 1 part(s)"),
        (&["solve", "--goal", "a,b"], "x: 'a' is not a number"),
        (&["solve", "--goal", "1,1", "--goal-angle", "nan"], "'--goal-angle <DEG>'"),
        (&["solve", "--goal", "1,1", "--lambda", "-1"], "'--lambda <LAMBDA>': -1: must be a finite number ≥ 0"),
        (&["solve", "--goal", "1,1", "--tolerance", "0"], "'--tolerance <TOLERANCE>': 0: must be"),
        (&["solve", "--goal", "1,1", "--method", "newton"], "invalid value 'newton' for '--method"),
        (&["solve", "--goal", "1,1", "--record-every", "0"], "'--record-every <K>': 0: must be at least 1"),
        (&["solve", "--goal", "1,1", "--rates", "1,2"], "--rates: expected 3 values (one per joint), got 2"),
        (&["solve", "--goal", "1,1", "--rates", "1,-2,1"], "'--rates <A,B,…>': -2: must be"),
        (&["solve", "--goal", "1,1", "--max-iterations", "-5"], "'--max-iterations <N>'"),
        (&["solve", "--goal", "1,1", "--frobnicate"], "unexpected argument '--frobnicate'"),
        (&["solve"], "required arguments were not provided: --goal <X,Y>"),
        (&["solve", "--goal", "1,1", "--threads", "2"], "--threads 2: only applies with --batch"),
        (&["solve", "--goal", "1,1", "--summary-json", "s.json"], "--summary-json s.json: only applies with --batch"),
    ];
    for (args, want) in cases {
        let err = fails(args, 2);
        assert!(err.contains(want), "{args:?}: {err:?} lacks {want:?}");
    }
}

#[test]
fn bad_arm_files_exit_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases = [
        ("unknown.toml", "[[links]]\nlength = 1\ncolour = 2\n", "line 3, column 1: unknown field `colour`"),
        ("negative.toml", "[[links]]\nlength = -1\n", "links[0].length = -1: must be greater than 0"),
        ("nan.toml", "[[links]]\nlength = 1\nangle_deg = nan\n", "links[0].angle_deg = NaN: must be a finite number"),
        (
            "outside.toml",
            "[[links]]\nlength = 1\nangle_deg = 60\nlimits_deg = [-45, 45]\n",
            "links[0].angle_deg = 60: outside limits_deg [-45, 45]",
        ),
        (
            "inverted.toml",
            "[[links]]\nlength = 1\nlimits_deg = [1, -1]\n",
            "limits_deg = [1, -1]: min must not exceed max",
        ),
        ("empty.toml", "name = \"nothing\"\n", "links: an arm needs at least one [[links]] entry"),
        ("broken.toml", "[[links]\nlength = 1\n", "line 1"),
        ("solver.toml", "[[links]]\nlength = 1\n[solver]\ntolerance = -1\n", "[solver].tolerance = -1: must be"),
    ];
    for (name, text, want) in cases {
        let path = write(d, name, text);
        let err = fails(&["solve", "--arm", &path, "--goal", "0.5,0.5"], 2);
        assert!(err.contains(&format!("arm file {path}: ")), "{err}");
        assert!(err.contains(want), "{name}: {err:?} lacks {want:?}");
    }
    let err = fails(&["solve", "--arm", "/nonexistent/arm.toml", "--goal", "1,1"], 2);
    assert!(err.contains("arm file /nonexistent/arm.toml: cannot read: No such file or directory"), "{err}");
}

#[test]
fn bad_batch_files_exit_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases = [
        ("header.csv", "a,b\n1,2\n", "header must be `x,y` or `x,y,angle_deg`, got `a,b`"),
        ("nan.csv", "x,y\n1,2\n3,nan\n", "line 3: y: must be a finite number, got nan"),
        ("word.csv", "x,y\n1,2\nthree,4\n", "line 3: x: 'three' is not a number"),
        ("short.csv", "x,y\n1,2\n3\n", "found record with 1 fields"),
        ("empty.csv", "x,y\n", "no goals"),
    ];
    for (name, text, want) in cases {
        let path = write(d, name, text);
        let err = fails(&["solve", "--batch", &path], 2);
        assert!(err.contains(&format!("batch file {path}")), "{err}");
        assert!(err.contains(want), "{name}: {err:?} lacks {want:?}");
    }
    fails(&["solve", "--batch", "/nonexistent/goals.csv"], 2);
    let ok = write(d, "ok.csv", "x,y\n1,1\n");
    let err = fails(&["solve", "--batch", &ok, "--threads", "0"], 2);
    assert!(err.contains("'--threads <N>': 0: must be at least 1"), "{err}");
}

#[test]
fn an_unwritable_summary_is_reported_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let goals = write(dir.path(), "g.csv", "x,y\n1,1\n");
    let err = fails(&["solve", "--batch", &goals, "--summary-json", "/nonexistent/dir/s.json"], 1);
    assert!(err.contains("--summary-json /nonexistent/dir/s.json: cannot write"), "{err}");
    let err = fails(&["solve", "--batch", &goals, "--summary-json", dir.path().to_str().unwrap()], 1);
    assert!(err.contains("is a directory"), "{err}");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 1, "{names:?}");
}

#[test]
fn help_and_version_succeed() {
    let o = ikarus(&["--version"]);
    assert!(o.status.success());
    assert!(stdout(&o).starts_with("ikarus "));
    let o = ikarus(&["solve", "--help"]);
    assert!(o.status.success());
    assert!(stdout(&o).contains("--batch <GOALS.csv>"));
    // The help says what serve does today (it once said the page "comes later"), and lists
    // every figure of render.
    let help = stdout(&ikarus(&["--help"]));
    assert!(!help.contains("later"), "{help}");
    assert!(help.contains("Serve the playground page and the JSON API"), "{help}");
    let render = stdout(&ikarus(&["render", "--help"]));
    for figure in ["arm", "motion", "workspace", "ease"] {
        assert!(render.lines().any(|l| l.trim_start().starts_with(figure)), "{figure}: {render}");
    }
}

/// Every method and limit mode is reachable from the command line, and limits hold.
#[test]
fn every_method_and_limit_mode_from_the_command_line() {
    for method in ["transpose", "pinv", "dls", "sdls", "lm", "ccd", "fabrik"] {
        let v = json(&["solve", "--goal", "2,3", "--method", method, "--max-iterations", "5000"]);
        assert_eq!(v["method"], method);
        assert_eq!(v["status"], "reached", "{method}: {v}");
    }
    // The closed form: 3 links with an orientation goal.
    let v = json(&["solve", "--goal", "4,2", "--goal-angle", "0", "--method", "analytic"]);
    assert_eq!(
        (v["method"].as_str(), v["status"].as_str(), v["iterations"].as_u64()),
        (Some("analytic"), Some("reached"), Some(1))
    );
    for mode in ["clamp", "lock", "nullspace", "weighted"] {
        // (0, −4) is reachable within the seed's ranges; clamping alone sticks there, restarts get
        // every mode to it.
        let v = json(&["solve", "--goal", "0,-4", "--limit-mode", mode]);
        assert_eq!(v["limits"], true, "--limit-mode implies --limits");
        assert_eq!(v["limit_mode"], mode);
        assert_eq!(v["status"], "reached", "{mode}: {v}");
        let a = floats(&v["angles_deg"]);
        assert!((-45.0..=45.0).contains(&a[0]) && (-90.0..=90.0).contains(&a[1]) && (-170.0..=170.0).contains(&a[2]));
    }
    // Without restarts, clamping stalls on it; the default combination reaches it.
    let v = json(&["solve", "--goal", "0,-4", "--limit-mode", "clamp", "--restarts", "0"]);
    assert_eq!(v["status"], "stalled");
    assert_eq!(v["restarts"], 0);
    let v = json(&["solve", "--goal", "0,-4", "--limits"]);
    assert_eq!(
        (v["status"].as_str(), v["limit_mode"].as_str(), v["method"].as_str()),
        (Some("reached"), Some("lock"), Some("lm"))
    );
    // Restarts are deterministic for a seed.
    let run = |seed: &str| {
        let mut v = json(&["solve", "--goal", "0,-4", "--limit-mode", "clamp", "--restart-seed", seed]);
        v["solve_us"] = Value::Null;
        v
    };
    assert_eq!(run("5"), run("5"));
}

#[test]
fn bad_solver_flags_name_the_flag() {
    for (args, needle) in [
        (&["solve", "--goal", "1,1", "--limit-mode", "sticky"][..], "--limit-mode"),
        (&["solve", "--goal", "1,1", "--method", "magic"][..], "--method"),
        (&["solve", "--goal", "1,1", "--restarts", "-1"][..], "--restarts"),
        (&["solve", "--goal", "1,1", "--time-budget-ms", "0"][..], "--time-budget-ms"),
        // Past what a duration holds: an error, not a panic.
        (&["solve", "--goal", "1,1", "--time-budget-ms", "1e300"][..], "time_budget_ms: must be"),
        (&["solve", "--goal", "1,1", "--backtrack", "4294967295"][..], "backtrack: must be at most 64"),
        (&["solve", "--goal", "1,1", "--limit-mode", "lock", "--no-limits"][..], "--limit-mode"),
        (&["solve", "--goal", "1,1", "--method", "analytic"][..], "method analytic"),
    ] {
        let o = ikarus(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// A goal `method` reaches, and the arm file (none: the seed arm) on which it applies: the
/// closed form needs two links for a position goal.
fn reachable_case(method: ikarus::Method, dir: &Path) -> (Vec<String>, &'static str) {
    let mut args: Vec<String> = vec!["solve".into(), "--method".into(), method.name().into()];
    let goal = if method == ikarus::Method::Analytic {
        let arm = write(dir, "two.toml", "[[links]]\nlength = 3\n[[links]]\nlength = 2\nangle_deg = 30\n");
        args.extend(["--arm".into(), arm]);
        "1,3"
    } else {
        args.extend(["--max-iterations".into(), "5000".into()]);
        "2,3"
    };
    args.extend(["--goal".into(), goal.into()]);
    (args, goal)
}

/// Every method the library has solves through the command line, named by the library's table.
#[test]
fn every_library_method_solves_through_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    for &method in ikarus::Method::ALL.iter() {
        let (args, goal) = reachable_case(method, dir.path());
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let v = json(&args);
        assert_eq!(v["method"], method.name());
        assert_eq!(v["status"], "reached", "{method} to {goal}: {v}");
    }
}

/// Every limit mode works where the method supports it (and is the mode reported); an
/// unsupported pair is refused with one line naming both, from a flag or an arm file alike.
#[test]
fn every_library_limit_mode_and_unsupported_pairs() {
    for &mode in ikarus::LimitMode::ALL.iter() {
        let v = json(&["solve", "--goal", "0,-4", "--limit-mode", mode.name()]);
        assert_eq!(v["limit_mode"], mode.name());
        assert_eq!(v["limits"], mode != ikarus::LimitMode::Ignore);
        assert_eq!(v["status"], "reached", "{mode}: {v}");
    }
    let dir = tempfile::tempdir().unwrap();
    for &method in ikarus::Method::ALL.iter() {
        if method == ikarus::Method::Analytic {
            continue; // supports every mode; needs its own arm (above)
        }
        // With --limits and no mode, the method's default mode.
        let v = json(&["solve", "--goal", "0,-4", "--method", method.name(), "--limits", "--restarts", "0"]);
        assert_eq!(v["limit_mode"], method.default_limit_mode().name(), "{method}");
        for &mode in ikarus::LimitMode::ALL.iter() {
            let flags = ["solve", "--goal", "0,-4", "--method", method.name(), "--limit-mode", mode.name()];
            let table = format!(
                "[[links]]\nlength = 3\n[[links]]\nlength = 2\n[[links]]\nlength = 1\n[solver]\nmethod = \"{method}\"\nlimits = true\nlimit_mode = \"{mode}\"\n"
            );
            let arm = write(dir.path(), "arm.toml", &table);
            let from_file = ["solve", "--goal", "0,-4", "--arm", arm.as_str()];
            for args in [&flags[..], &from_file[..]] {
                if method.supports(mode) {
                    assert_eq!(json(args)["limit_mode"], mode.name(), "{args:?}");
                } else {
                    let e = fails(args, 2);
                    let want = if args[3] == "--arm" {
                        // Named where they came from: the arm file's [solver] table.
                        format!("{arm}: [solver].method {method}: does not support [solver].limit_mode {mode}")
                    } else {
                        format!("--method {method}: does not support --limit-mode {mode}")
                    };
                    assert!(e.contains(&want), "{args:?}: {e}");
                }
            }
        }
    }
}

#[test]
fn max_iterations_is_held_to_the_cap_as_the_api_holds_it() {
    // The flag: the cap of `ikarus serve --max-iterations`, 100 000, by default.
    let v = json(&["solve", "--goal", "2,3", "--max-iterations", "100000"]);
    assert_eq!(v["status"], "reached");
    let err = fails(&["solve", "--goal", "2,3", "--max-iterations", "100001"], 2);
    assert_eq!(
        err.trim(),
        "ikarus: --max-iterations 100001: more than the cap of 100000 (raise it with --iteration-cap N)"
    );
    let v = json(&["solve", "--goal", "2,3", "--max-iterations", "100001", "--iteration-cap", "100001"]);
    assert_eq!(v["status"], "reached");
    // An arm file's [solver] table is held to it too, and named.
    let dir = tempfile::tempdir().unwrap();
    let arm = write(
        dir.path(),
        "a.toml",
        "[[links]]\nlength = 1\n[[links]]\nlength = 1\n[solver]\nmax_iterations = 200000\n",
    );
    let err = fails(&["solve", "--arm", &arm, "--goal", "1,1"], 2);
    assert_eq!(
        err.trim(),
        format!(
            "ikarus: arm file {arm}: [solver].max_iterations 200000: more than the cap of 100000 (raise it with --iteration-cap N)"
        )
    );
    // A rig's solve and the other commands share the check.
    let rig = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs/puppet.toml");
    let err = fails(&["solve", "--rig", rig.to_str().unwrap(), "--goal", "head=0,3", "--max-iterations", "100001"], 2);
    assert!(err.starts_with("ikarus: --max-iterations 100001: more than the cap of 100000"), "{err}");
    let err = fails(&["track", "--line", "1,1,2,2", "--max-iterations", "100001"], 2);
    assert!(err.starts_with("ikarus: --max-iterations 100001: more than the cap of 100000"), "{err}");
}
