//! The exact region at the edges (issue 13): `ikarus workspace`'s JSON and picture, `ikarus
//! reach` (one point, a batch), `POST /api/reach` and the workspace endpoint, checked against
//! the library's `Region` and against each other (the same bytes for the same input).
//!
//! The library here is built with the test profile's `opt-level = 3` (the workspace's
//! `Cargo.toml`), the binary's with the dev profile's 0; their results may differ in the last
//! bit (seen: 113.09733552923257 against …55), and serde_json (without its `float_roundtrip`
//! feature) may read a number 1 ulp off; so numbers are compared with the library's within
//! [`SAME`], and the binary's bytes with the server's bit for bit.

mod common;

use std::path::{Path, PathBuf};

use common::server::start;
use common::{dist, fails, ikarus, json, stdout, succeeds};
use ikarus::reach::{Region, Verdict};
use ikarus::{Chain, JointLimits, Link, Point2};
use serde_json::{Value, json};

/// The built-in arm (the seed's), as the library sees it.
fn seed() -> Chain {
    let lim = |d: f64| JointLimits::new(-d.to_radians(), d.to_radians()).unwrap();
    let a = 5f64.to_radians();
    Chain::new(
        [0.0, 0.0],
        &[
            Link::new(3.0, a).with_limits(lim(45.0)),
            Link::new(2.0, a).with_limits(lim(90.0)),
            Link::new(1.0, a).with_limits(lim(170.0)),
        ],
    )
    .unwrap()
}

/// Relative difference allowed between this test's library and the binary's (see above).
const SAME: f64 = 1e-12;

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME * a.abs().max(b.abs()).max(1.0)
}

/// `got` (JSON) is the library's verdict `want`, to the last bits.
fn assert_verdict(got: &Value, want: &Verdict) {
    assert_eq!(got["reachable"], want.reachable, "{got}");
    assert!(same(got["distance"].as_f64().unwrap(), want.distance), "{got} vs {want:?}");
    assert!(same(got["nearest"][0].as_f64().unwrap(), want.nearest.x), "{got} vs {want:?}");
    assert!(same(got["nearest"][1].as_f64().unwrap(), want.nearest.y), "{got} vs {want:?}");
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms").join(name)
}

/// A segment's end points from its JSON (`line` or `arc`, degrees).
fn ends(seg: &Value) -> ([f64; 2], [f64; 2]) {
    if let Some(line) = seg.get("line") {
        let p = |i: usize| [line[i][0].as_f64().unwrap(), line[i][1].as_f64().unwrap()];
        return (p(0), p(1));
    }
    let arc = &seg["arc"];
    let (cx, cy) = (arc["center"][0].as_f64().unwrap(), arc["center"][1].as_f64().unwrap());
    let r = arc["radius"].as_f64().unwrap();
    let at = |deg: f64| [cx + r * deg.to_radians().cos(), cy + r * deg.to_radians().sin()];
    (at(arc["from_deg"].as_f64().unwrap()), at(arc["to_deg"].as_f64().unwrap()))
}

/// Every loop closes: each segment starts where the one before it ends (the last before the
/// first), within 1e-9.
fn assert_loops_close(boundary: &Value) {
    let loops = boundary.as_array().unwrap();
    assert!(!loops.is_empty());
    for (i, l) in loops.iter().enumerate() {
        let segs = l.as_array().unwrap();
        assert!(!segs.is_empty());
        for k in 0..segs.len() {
            let (_, end) = ends(&segs[k]);
            let (start, _) = ends(&segs[(k + 1) % segs.len()]);
            assert!(dist(end, start) < 1e-9, "loop {i}, segment {k}: ends at {end:?}, next starts at {start:?}");
        }
    }
}

#[test]
fn workspace_json_is_the_exact_region() {
    let v = json(&["workspace", "--limits", "--format", "json"]);
    let region = Region::of(&seed(), true);
    assert_eq!(v["exact"], true);
    assert_eq!(v["limits"], true);
    assert!(same(v["area"].as_f64().unwrap(), region.area()), "{} vs {}", v["area"], region.area());
    assert_eq!(v["boundary"].as_array().unwrap().len(), region.boundary().len());
    assert_eq!(v["curves"], json!([]));
    assert!(v.get("grid").is_none() && v.get("resolution").is_none(), "no grid fields: {v}");
    assert_loops_close(&v["boundary"]);

    // Without limits the same code gives the annulus: one full circle of radius 6.
    let v = json(&["workspace", "--no-limits", "--format", "json"]);
    assert!(same(v["area"].as_f64().unwrap(), Region::of(&seed(), false).area()));
    assert!((v["area"].as_f64().unwrap() - 36.0 * std::f64::consts::PI).abs() < 1e-9);
    assert_eq!(v["boundary"].as_array().unwrap().len(), 1);
    let circle = &v["boundary"][0][0]["arc"];
    assert_eq!(circle["radius"], 6.0);
    assert!((circle["to_deg"].as_f64().unwrap() - circle["from_deg"].as_f64().unwrap() - 360.0).abs() < 1e-9);
    assert_loops_close(&v["boundary"]);

    // Seven links with limits, with holes or not: every loop closes, the area is the library's.
    let seven = example("seven.toml");
    let v = json(&["workspace", "--arm", seven.to_str().unwrap(), "--limits", "--format", "json"]);
    assert_eq!(v["arm"], "seven");
    assert_loops_close(&v["boundary"]);
    assert!(v["area"].as_f64().unwrap() > 0.0);
}

#[test]
fn the_grid_is_kept_with_grid() {
    let v = json(&["workspace", "--limits", "--grid", "--format", "json"]);
    assert_eq!(v["exact"], false);
    assert_eq!(v["resolution"], 256);
    assert_eq!(v["grid"].as_array().unwrap().len(), 256);
    assert!(v.get("boundary").is_none());
    // The sampled area is near the exact one.
    let exact = Region::of(&seed(), true).area();
    let grid = v["area"].as_f64().unwrap();
    assert!((grid - exact).abs() / exact < 0.01, "{grid} vs {exact}");
    // A sampling flag asks for the grid too.
    assert_eq!(json(&["workspace", "--resolution", "32", "--format", "json"])["exact"], false);
}

#[test]
fn a_region_without_area_answers_with_its_curve() {
    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("one.toml");
    std::fs::write(&arm, "name = \"one\"\n[[links]]\nlength = 2.0\nlimits_deg = [-30.0, 60.0]\n").unwrap();
    let arm = arm.to_str().unwrap();
    let v = json(&["workspace", "--arm", arm, "--limits", "--format", "json"]);
    assert_eq!(v["area"], 0.0);
    assert_eq!(v["boundary"], json!([]));
    let arc = &v["curves"][0]["arc"];
    assert_eq!(arc["radius"], 2.0);
    assert!((arc["from_deg"].as_f64().unwrap() + 30.0).abs() < 1e-9);
    assert!((arc["to_deg"].as_f64().unwrap() - 60.0).abs() < 1e-9);
    let text = succeeds(&["workspace", "--arm", arm, "--limits", "--format", "text"]);
    assert!(text.contains("no area: a curve of 1 piece"), "{text}");
    let svg = dir.path().join("one.svg");
    succeeds(&["workspace", "--arm", arm, "--limits", "--out", svg.to_str().unwrap()]);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("reachable workspace (a curve"));
    // On the curve, and off it.
    let v = json(&["reach", "--arm", arm, "--limits", "--point", "2,0", "--format", "json"]);
    assert_eq!(v, json!({"reachable": true, "distance": 0.0, "nearest": [2.0, 0.0]}));
    let v = json(&["reach", "--arm", arm, "--limits", "--point", "0,0", "--format", "json"]);
    assert_eq!(v["reachable"], false);
    assert!((v["distance"].as_f64().unwrap() - 2.0).abs() < 1e-12);
}

#[test]
fn the_picture_is_drawn_with_arcs() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("w.svg");
    let seed_file = example("seed.toml");
    succeeds(&["workspace", "--arm", seed_file.to_str().unwrap(), "--limits", "--out", svg.to_str().unwrap()]);
    let svg = std::fs::read_to_string(svg).unwrap();
    let area = svg.split("reachable workspace -->").nth(1).unwrap().split("/>").next().unwrap();
    // The seed's region is 7 arcs: no straight pieces, no staircase.
    assert_eq!(area.matches('A').count(), 7, "{area}");
    assert_eq!(area.matches('L').count(), 0, "{area}");
    assert!(svg.contains("(exact)"));
}

/// Points inside, outside and near the boundary of the seed arm's limited region, with the
/// library's verdicts at the default tolerance (1e-6).
fn cases() -> Vec<([f64; 2], Verdict)> {
    let region = Region::of(&seed(), true);
    // (6, 0) is on the outer arc; 1e-7 beyond it is within the tolerance, 1e-5 is not.
    let points = [[2.0, 3.0], [4.0, 0.0], [-3.0, -1.0], [0.0, 0.0], [6.0, 0.0], [6.0 + 1e-7, 0.0], [6.00001, 0.0]];
    points.iter().map(|&p| (p, region.verdict(Point2::new(p[0], p[1]), 1e-6))).collect()
}

#[test]
fn reach_agrees_with_the_library() {
    let cases = cases();
    let kinds: Vec<bool> = cases.iter().map(|(_, v)| v.reachable).collect();
    assert!(kinds.contains(&true) && kinds.contains(&false));
    assert_eq!(cases[0].1.distance, 0.0);
    assert!(cases[5].1.reachable && cases[5].1.distance > 0.0, "near the boundary, outside, within tolerance");
    assert!(!cases[6].1.reachable);
    for (p, want) in &cases {
        let point = format!("{},{}", p[0], p[1]);
        let v = json(&["reach", "--limits", "--point", &point, "--format", "json"]);
        assert_verdict(&v, want);
        // The text: three lines, the same verdict.
        let text = succeeds(&["reach", "--limits", "--point", &point, "--format", "text"]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text}");
        let reachable = lines[0].strip_prefix("reachable  ").unwrap();
        let distance: f64 = lines[1].strip_prefix("distance   ").unwrap().parse().unwrap();
        let nearest = lines[2].strip_prefix("nearest    [").unwrap().strip_suffix(']').unwrap();
        let (x, y) = nearest.split_once(", ").unwrap();
        let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
        assert_verdict(&json!({"reachable": reachable == "true", "distance": distance, "nearest": [x, y]}), want);
    }

    // The batch: one row per point, in order, numbers that read back exactly.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("points.csv");
    let rows: Vec<String> = cases.iter().map(|(p, _)| format!("{:?},{:?}", p[0], p[1])).collect();
    std::fs::write(&file, format!("x,y\n{}\n", rows.join("\n"))).unwrap();
    let out = succeeds(&["reach", "--limits", "--batch", file.to_str().unwrap()]);
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("x,y,reachable,distance,nearest_x,nearest_y"));
    for (line, (p, want)) in lines.by_ref().zip(&cases) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 6, "{line}");
        assert_eq!([f[0].parse::<f64>().unwrap(), f[1].parse().unwrap()], *p);
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        assert_verdict(&json!({"reachable": f[2] == "true", "distance": num(3), "nearest": [num(4), num(5)]}), want);
        assert!(f[2] == "true" || f[2] == "false", "{line}");
    }
    assert_eq!(out.lines().count(), cases.len() + 1);

    // --out writes the same bytes to a file.
    let to = dir.path().join("verdicts.csv");
    let quiet = succeeds(&["reach", "--limits", "--batch", file.to_str().unwrap(), "--out", to.to_str().unwrap()]);
    assert!(quiet.is_empty());
    assert_eq!(std::fs::read_to_string(&to).unwrap(), out);
}

#[test]
fn the_tolerance_comes_from_the_flag_or_the_arm_file() {
    // 1e-5 beyond the outer arc: unreachable at 1e-6, reachable at 1e-4.
    assert_eq!(json(&["reach", "--limits", "--point", "6.00001,0", "--format", "json"])["reachable"], false);
    let v = json(&["reach", "--limits", "--point", "6.00001,0", "--tolerance", "1e-4", "--format", "json"]);
    assert_eq!(v["reachable"], true);
    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("arm.toml");
    let text = std::fs::read_to_string(example("seed.toml")).unwrap();
    std::fs::write(&arm, format!("{text}\n[solver]\ntolerance = 1e-4\nlimits = true\n")).unwrap();
    let v = json(&["reach", "--arm", arm.to_str().unwrap(), "--point", "6.00001,0", "--format", "json"]);
    assert_eq!(v["reachable"], true, "the arm file's tolerance and limits");
    let v = json(&["reach", "--arm", arm.to_str().unwrap(), "--point", "6.00001,0", "--tolerance", "1e-6"]);
    assert_eq!(v["reachable"], false, "the flag over the file");
}

#[test]
fn bad_input_is_one_line_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_owned()
    };
    let e = fails(&["reach", "--point", "1,nan"], 2);
    assert!(e.contains("--point") && e.contains("y: must be a finite number, got nan"), "{e}");
    let e = fails(&["reach", "--point", "1"], 2);
    assert!(e.contains("expected two numbers X,Y"), "{e}");
    let e = fails(&["reach", "--point", "1,2", "--tolerance", "0"], 2);
    assert!(e.contains("--tolerance") && e.contains('0'), "{e}");
    fails(&["reach"], 2);

    let bad_number = write("a.csv", "x,y\n1,2\n3,abc\n");
    let e = fails(&["reach", "--batch", &bad_number], 2);
    assert!(e.ends_with(&format!("batch file {bad_number}: line 3: y: 'abc' is not a number\n")), "{e}");
    let nan = write("b.csv", "x,y\nnan,2\n");
    let e = fails(&["reach", "--batch", &nan], 2);
    assert!(e.contains("line 2: x: must be a finite number, got nan"), "{e}");
    let missing = write("c.csv", "x,y\n1,2\n3\n");
    let e = fails(&["reach", "--batch", &missing], 2);
    assert!(e.contains(&missing) && e.contains("line: 3"), "{e}");
    let header = write("d.csv", "x,z\n1,2\n");
    let e = fails(&["reach", "--batch", &header], 2);
    assert!(e.contains("line 1: header must be `x,y`, got `x,z`"), "{e}");
    let angle = write("e.csv", "x,y,angle_deg\n1,2,3\n");
    fails(&["reach", "--batch", &angle], 2);
    let empty = write("f.csv", "x,y\n");
    let e = fails(&["reach", "--batch", &empty], 2);
    assert!(e.contains("no points"), "{e}");
    let e = fails(&["reach", "--batch", &write("g.csv", "x,y\n1,2\n"), "--format", "text"], 2);
    assert!(e.contains("--format text"), "{e}");
    let arm = write("bad.toml", "[[links]]\nlength = -2\n");
    let e = fails(&["reach", "--arm", &arm, "--point", "1,1"], 2);
    assert!(e.contains("links[0].length = -2"), "{e}");

    // Nothing half-written: a bad batch leaves no output file behind.
    let out = dir.path().join("out.csv");
    fails(&["reach", "--batch", &bad_number, "--out", out.to_str().unwrap()], 2);
    assert!(!out.exists());
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().starts_with(".ikarus-"))
        .collect();
    assert!(leftovers.is_empty());

    // Sampling flags belong to the grid; over its cap is refused.
    fails(&["workspace", "--samples", "2000000"], 2);
}

/// The command line and the server are one workflow: the same input gives the same bytes.
#[test]
fn the_cli_and_the_api_answer_the_same_bytes() {
    let s = start(&[]);
    let post = |path: &str, body: Value| {
        let a = s.post(path, &body);
        assert_eq!(a.status, 200, "{}", a.text());
        assert_eq!(a.content_type, "application/json");
        a.text()
    };
    let cli = |args: &[&str]| {
        let out = succeeds(args);
        out.strip_suffix('\n').unwrap().to_owned()
    };
    for (p, _) in cases() {
        assert_eq!(
            post("/api/reach", json!({"point": p, "limits": true})),
            cli(&["reach", "--limits", "--point", &format!("{:?},{:?}", p[0], p[1]), "--format", "json"])
        );
    }
    // A batch: the array of the same objects, in order.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("p.csv");
    let points: Vec<[f64; 2]> = cases().iter().map(|(p, _)| *p).collect();
    let rows: Vec<String> = points.iter().map(|p| format!("{:?},{:?}", p[0], p[1])).collect();
    std::fs::write(&file, format!("x,y\n{}\n", rows.join("\n"))).unwrap();
    assert_eq!(
        post("/api/reach", json!({"points": points, "limits": true, "tolerance": 1e-4})),
        cli(&["reach", "--limits", "--batch", file.to_str().unwrap(), "--format", "json", "--tolerance", "1e-4"])
    );
    // Another arm, as a file and as JSON.
    let seven = example("seven.toml");
    let arm: toml::Value = toml::from_str(&std::fs::read_to_string(&seven).unwrap()).unwrap();
    let arm = serde_json::to_value(arm).unwrap();
    assert_eq!(
        post("/api/reach", json!({"arm": arm, "point": [1.5, -2.0], "limits": true})),
        cli(&["reach", "--arm", seven.to_str().unwrap(), "--limits", "--point", "1.5,-2", "--format", "json"])
    );
    // The workspace: the exact region's JSON.
    for limits in [true, false] {
        let flag = if limits { "--limits" } else { "--no-limits" };
        assert_eq!(post("/api/workspace", json!({"limits": limits})), cli(&["workspace", flag, "--format", "json"]));
    }
    let answer = post("/api/workspace", json!({"arm": arm, "limits": true}));
    assert_eq!(answer, cli(&["workspace", "--arm", seven.to_str().unwrap(), "--limits", "--format", "json"]));
    assert_eq!(serde_json::from_str::<Value>(&answer).unwrap()["exact"], true);
    // The figures: `render_figures_equal_the_clis` in serve.rs.
}

#[test]
fn the_api_refuses_bad_reach_requests_with_422() {
    let s = start(&["--max-samples", "10"]);
    let e = s.post("/api/reach", &json!({"point": [1, 2], "tolerance": 0})).error(422);
    assert_eq!(e, "tolerance = 0: must be a finite number greater than 0");
    let e = s.post("/api/reach", &json!({"point": [1, 2], "points": [[1, 2]]})).error(422);
    assert!(e.contains("point, points"), "{e}");
    let e = s.post("/api/reach", &json!({})).error(422);
    assert!(e.contains("point or points"), "{e}");
    let e = s.post("/api/reach", &json!({"points": vec![[0.0, 0.0]; 11]})).error(422);
    assert_eq!(e, "points: 11 points, more than the cap of 10 (--max-samples)");
    let e = s.post("/api/reach", &json!({"point": [1]})).error(422);
    assert!(e.contains("point"), "{e}");
    let e = s.post("/api/reach", &json!({"point": [1, 2], "arm": {"links": [{"length": -2}]}})).error(422);
    assert!(e.contains("links[0].length = -2"), "{e}");
    let e = s.post("/api/reach", &json!({"point": [1, 2], "goal": 3})).error(422);
    assert!(e.contains("unknown field `goal`"), "{e}");
    let e = s.post("/api/workspace", &json!({"grid": false, "resolution": 64})).error(422);
    assert!(e.contains("resolution = 64") && e.contains("grid = false"), "{e}");
    // The cap allows 10.
    let a = s.post("/api/reach", &json!({"points": vec![[0.0, 0.0]; 10]}));
    assert_eq!(a.status, 200);
    assert_eq!(a.json().as_array().unwrap().len(), 10);
    s.assert_healthy();
}

#[test]
fn help_lists_reach() {
    let o = ikarus(&["--help"]);
    assert!(stdout(&o).contains("reach"));
}

/// An arm whose exact region the library could not build (its union lost every boundary
/// piece, at the time of writing): the edges answer a failure in one line (exit 1), never a
/// panic nor an empty region; whatever the library does, the answer is one of those two.
#[test]
fn a_region_the_library_cannot_build_is_a_failure_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("r85.toml");
    let links = [
        (1.03053, -53.4661, 146.802),
        (2.35434, -9.74987, 39.8313),
        (0.74521, -27.4461, 61.9628),
        (1.65765, -111.596, 152.043),
        (1.7568, -39.9121, 104.896),
    ];
    let text: String =
        links.iter().map(|(l, lo, hi)| format!("[[links]]\nlength = {l}\nlimits_deg = [{lo}, {hi}]\n")).collect();
    std::fs::write(&arm, text).unwrap();
    let arm = arm.to_str().unwrap();
    for args in [
        vec!["reach", "--arm", arm, "--limits", "--point", "1,1", "--format", "json"],
        vec!["workspace", "--arm", arm, "--limits", "--format", "json"],
    ] {
        let o = ikarus(&args);
        match o.status.code() {
            Some(0) => {
                let v: Value = serde_json::from_slice(&o.stdout).unwrap();
                if args[0] == "workspace" {
                    assert!(v["area"].as_f64().unwrap() > 0.0 && !v["boundary"].as_array().unwrap().is_empty());
                }
            }
            Some(1) => {
                let e = common::stderr(&o);
                assert_eq!(e.lines().count(), 1, "{e}");
                assert!(e.contains("could not build the exact region"), "{e}");
                assert!(o.stdout.is_empty());
            }
            other => panic!("{args:?}: exit {other:?}: {}", common::stderr(&o)),
        }
    }
}
