//! Issue 25: rig files with offsets and prismatic joints (`examples/joints/`: an RRP arm, a
//! PRR arm, a hand whose fingers start across the palm) solve from the command line and from
//! `POST /api/solve`, the answers checked by a forward kinematics written here from the file's
//! keys (not the library's); and the new keys' bad values are one line naming the field.

mod common;

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use common::{fails, json, server, succeeds};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/joints").join(format!("{name}.toml"))
}

fn file(name: &str) -> Value {
    toml::from_str(&std::fs::read_to_string(example(name)).unwrap()).unwrap()
}

fn pair(v: &Value) -> Option<[f64; 2]> {
    let a = v.as_array()?;
    Some([a[0].as_f64().unwrap(), a[1].as_f64().unwrap()])
}

/// Every bone's tip from the answer's `angles_deg` and `extensions` by the file's definition:
/// origin = parent's origin + R(parent's direction) (offset + d · unit slide), offset by
/// default the parent's tip, a prismatic bone's slide by default along its own angle.
fn tips(rig: &Value, answer: &Value) -> Vec<(String, [f64; 2])> {
    let bones = rig["bones"].as_array().unwrap();
    let index = |name: &str| bones.iter().position(|b| b["name"] == name).unwrap();
    fn place(bones: &[Value], answer: &Value, index: &dyn Fn(&str) -> usize, i: usize) -> ([f64; 2], f64) {
        let b = &bones[i];
        let (origin, phi, len) = match b["parent"].as_str() {
            Some(p) => {
                let j = index(p);
                let (o, phi) = place(bones, answer, index, j);
                (o, phi, bones[j]["length"].as_f64().unwrap())
            }
            None => ([0.0, 0.0], 0.0, 0.0),
        };
        let name = b["name"].as_str().unwrap();
        let angle = answer["angles_deg"][name].as_f64().unwrap().to_radians();
        let [mut x, mut y] = pair(&b["offset"]).unwrap_or([len, 0.0]);
        if b["joint"] == "prismatic" {
            let d = answer["extensions"][name].as_f64().unwrap();
            let [sx, sy] = pair(&b["slide"]).unwrap_or([angle.cos(), angle.sin()]);
            let norm = sx.hypot(sy);
            x += d * sx / norm;
            y += d * sy / norm;
        }
        let (s, c) = phi.sin_cos();
        ([origin[0] + c * x - s * y, origin[1] + s * x + c * y], phi + angle)
    }
    (0..bones.len())
        .map(|i| {
            let (o, phi) = place(bones, answer, &index, i);
            let l = bones[i]["length"].as_f64().unwrap();
            (bones[i]["name"].as_str().unwrap().to_owned(), [o[0] + l * phi.cos(), o[1] + l * phi.sin()])
        })
        .collect()
}

/// Checks an answer: reached, every reported tip where the file's forward kinematics puts it,
/// the goals' targets within the tolerance, every extension within its limits.
fn check(name: &str, answer: &Value, goals: &[Target]) {
    let rig = file(name);
    assert_eq!(answer["status"], "reached", "{name}: {answer}");
    for (bone, tip) in tips(&rig, answer) {
        let got = pair(&answer["joints"][&bone]).unwrap();
        assert!((got[0] - tip[0]).hypot(got[1] - tip[1]) < 1e-12, "{name} {bone}: {got:?} vs {tip:?}");
        if let Some((_, target)) = goals.iter().find(|(b, _)| *b == bone) {
            assert!((tip[0] - target[0]).hypot(tip[1] - target[1]) <= 1e-6, "{name} {bone}: {tip:?}");
        }
    }
    for b in rig["bones"].as_array().unwrap() {
        let bone = b["name"].as_str().unwrap();
        match (b["joint"].as_str(), pair(&b["limits"])) {
            (Some("prismatic"), Some([lo, hi])) => {
                let d = answer["extensions"][bone].as_f64().unwrap();
                assert!((lo..=hi).contains(&d), "{name} {bone}: {d} outside [{lo}, {hi}]");
            }
            (Some("prismatic"), None) => assert!(answer["extensions"][bone].is_f64()),
            _ => assert!(answer["extensions"].get(bone).is_none()),
        }
    }
}

/// A goal: a bone's name and its target.
type Target = (&'static str, [f64; 2]);

const CASES: [(&str, &[Target]); 3] = [
    ("rrp", &[("ram", [1.2, 1.3])]),
    ("prr", &[("lower", [1.4, 0.9])]),
    ("palm", &[("index_tip", [0.029, 0.1228]), ("thumb_tip", [-0.0638, 0.0847])]),
];

#[test]
fn the_joint_examples_solve_from_the_command_line_and_the_api_alike() {
    let s = server::start(&[]);
    for (name, goals) in CASES {
        let path = example(name);
        let mut args = vec!["solve".to_owned(), "--rig".to_owned(), path.to_str().unwrap().to_owned()];
        for (bone, [x, y]) in goals {
            args.extend(["--goal".to_owned(), format!("{bone}={x},{y}")]);
        }
        args.extend(["--limits", "--restarts", "8", "--format", "json"].map(str::to_owned));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let cli = json(&args);
        check(name, &cli, goals);
        // Only the rigs with a prismatic joint say "extensions".
        assert_eq!(cli.get("extensions").is_some(), name != "palm", "{name}");
        let goals_json: Vec<Value> = goals.iter().map(|(b, [x, y])| json!({"bone": b, "x": x, "y": y})).collect();
        let body = json!({"rig": file(name), "goals": goals_json, "options": {"limits": true, "restarts": 8}});
        let api = s.post("/api/solve", &body).json();
        check(name, &api, goals);
        assert_eq!(api["angles_deg"], cli["angles_deg"], "{name}: the API's pose is the command line's");
        assert_eq!(api["extensions"], cli["extensions"], "{name}");
        // The rig as `POST /api/rig/parse` reads the file (what Python's `Rig.from_toml` and the
        // page send back) keeps its joint keys: it solves as the file does.
        let text = std::fs::read_to_string(&path).unwrap();
        let parsed = s.post_raw("/api/rig/parse", "application/toml", text.as_bytes()).json();
        let body = json!({"rig": parsed["rig"], "goals": goals_json, "options": {"limits": true, "restarts": 8}});
        let again = s.post("/api/solve", &body).json();
        check(name, &again, goals);
        assert_eq!(again["angles_deg"], cli["angles_deg"], "{name}: the parsed rig's pose is the file's");
        assert_eq!(again["extensions"], cli["extensions"], "{name}");
    }
}

#[test]
fn bad_joint_keys_are_one_line_naming_the_field_and_the_value() {
    let dir = tempfile::tempdir().unwrap();
    let base = "[[bones]]\nname = \"a\"\nlength = 1\n[[bones]]\nname = \"s\"\nparent = \"a\"\nlength = 0.5\n";
    for (extra, want) in [
        ("joint = \"prismatic\"\nslide = [0, 0]\n", "bones[1] (\"s\").slide: must not be zero, got [0, 0]"),
        (
            "joint = \"prismatic\"\nextension = 0.9\nlimits = [0, 0.5]\n",
            "bones[1] (\"s\").extension: 0.9 lies outside the limits [0, 0.5]",
        ),
        ("joint = \"prismatic\"\nlimits = [0.5, 0]\n", "bones[1] (\"s\").limits = [0.5, 0]"),
        ("joint = \"prismatic\"\nlimits_deg = [0, 10]\n", "bones[1] (\"s\").limits_deg: not for a prismatic joint"),
        ("slide = [1, 0]\n", "bones[1] (\"s\").slide: not for a revolute joint"),
        ("offset = [nan, 0]\n", "bones[1] (\"s\").offset: must be finite numbers, got [NaN, 0]"),
        ("joint = \"helical\"\n", "line 8, column 9: unknown variant `helical`, expected `revolute` or `prismatic`"),
    ] {
        let path = dir.path().join("r.toml");
        std::fs::write(&path, format!("{base}{extra}")).unwrap();
        let err = fails(&["solve", "--rig", path.to_str().unwrap(), "--goal", "s=1,0"], 2);
        assert!(err.contains(want) && err.trim_end().lines().count() == 1, "{extra}: {err}");
    }
}

/// Checks one frame (or sample) of a motion, a track or a recorded solve: every reported tip
/// where the file's forward kinematics puts it from the frame's own `angles_deg` and
/// `extensions` (a prismatic value printed as an angle, or a missing extension, fails here).
fn check_frame(name: &str, what: &str, frame: &Value) {
    check_frame_of(&file(name), &format!("{name} {what}"), frame);
}

/// [`check_frame`] of a frame of `rig` (a rig file's fields as JSON), `label` in messages.
fn check_frame_of(rig: &Value, label: &str, frame: &Value) {
    for (bone, tip) in tips(rig, frame) {
        let got = pair(&frame["joints"][&bone]).unwrap();
        assert!((got[0] - tip[0]).hypot(got[1] - tip[1]) < 1e-12, "{label} {bone}: {got:?} vs {tip:?}");
    }
}

/// A CSV's rows as column name → value.
fn csv_rows(text: &str) -> Vec<std::collections::HashMap<String, String>> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines.map(|l| header.iter().map(|h| h.to_string()).zip(l.split(',').map(str::to_owned)).collect()).collect()
}

/// A CSV row's pose as an answer's `angles_deg` and `extensions` (`NAME_deg`, `NAME_ext`).
fn csv_pose(name: &str, row: &std::collections::HashMap<String, String>) -> Value {
    let (mut angles, mut extensions) = (serde_json::Map::new(), serde_json::Map::new());
    for b in file(name)["bones"].as_array().unwrap() {
        let bone = b["name"].as_str().unwrap();
        let number = |c: String| json!(row[&c].parse::<f64>().unwrap());
        angles.insert(bone.to_owned(), number(format!("{bone}_deg")));
        match b["joint"].as_str() {
            Some("prismatic") => extensions.insert(bone.to_owned(), number(format!("{bone}_ext"))),
            _ => row.get(&format!("{bone}_ext")).map(|_| panic!("{name}: {bone}_ext for a revolute bone")),
        };
    }
    json!({"angles_deg": angles, "extensions": extensions})
}

#[test]
fn motions_tracks_and_recorded_frames_of_prismatic_rigs_report_angles_and_extensions() {
    for (name, goals, effector) in [("rrp", CASES[0].1, "ram"), ("prr", CASES[1].1, "lower")] {
        let path = example(name);
        let path = path.to_str().unwrap();
        let goal = goals.iter().map(|(b, [x, y])| format!("{b}={x},{y}")).next().unwrap();
        let motion = ["animate", "--rig", path, "--goal", &goal, "--limits", "--restarts", "8", "--frames", "9"];
        let answer = json(&[&motion[..], &["--format", "json"]].concat());
        let frames = answer["frames"].as_array().unwrap();
        assert_eq!(frames.len(), 9, "{name}");
        for (k, f) in frames.iter().enumerate() {
            assert!(f["extensions"].is_object(), "{name} frame {k}: {f}");
            check_frame(name, &format!("frame {k}"), f);
        }
        // The CSV: the same pose, with `NAME_ext` columns for the prismatic bones only.
        let csv = common::succeeds(&[&motion[..], &["--format", "csv"]].concat());
        let rows = csv_rows(&csv);
        assert_eq!(rows.len(), frames.len(), "{name}");
        for (k, (row, f)) in rows.iter().zip(frames).enumerate() {
            let pose = csv_pose(name, row);
            assert_eq!(pose["angles_deg"], f["angles_deg"], "{name} csv row {k}");
            assert_eq!(pose["extensions"], f["extensions"], "{name} csv row {k}");
            for (bone, tip) in tips(&file(name), &pose) {
                let got =
                    [row[&format!("{bone}.x")].parse::<f64>().unwrap(), row[&format!("{bone}.y")].parse().unwrap()];
                assert!((got[0] - tip[0]).hypot(got[1] - tip[1]) < 1e-12, "{name} csv row {k} {bone}");
            }
        }
        // A track: the effector's tip along a short line near where it starts.
        let start = json(&["solve", "--rig", path, "--goal", &goal, "--max-iterations", "0", "--format", "json"]);
        let [x, y] = pair(&start["joints"][effector]).unwrap();
        let line = format!("{x},{y},{},{}", x - 0.1, y + 0.05);
        let track = ["track", "--rig", path, "--effector", effector, "--line", &line, "--samples", "6"];
        let answer = json(&[&track[..], &["--format", "json"]].concat());
        let samples = answer["samples"].as_array().unwrap();
        assert_eq!(samples.len(), 6, "{name}: {answer}");
        for (k, s) in samples.iter().enumerate() {
            check_frame(name, &format!("sample {k}"), s);
        }
        let csv = common::succeeds(&[&track[..], &["--format", "csv"]].concat());
        for (k, (row, s)) in csv_rows(&csv).iter().zip(samples).enumerate() {
            let pose = csv_pose(name, row);
            assert_eq!(pose["angles_deg"], s["angles_deg"], "{name} track csv row {k}");
            assert_eq!(pose["extensions"], s["extensions"], "{name} track csv row {k}");
        }
        // A recorded solve: each frame's angles in bone order, its extensions by name, and the
        // base then every tip.
        let solve = ["solve", "--rig", path, "--goal", &goal, "--limits", "--record-every", "1", "--format", "json"];
        let answer = json(&solve);
        let recorded = answer["frames"].as_array().unwrap();
        assert!(recorded.len() > 1, "{name}: {answer}");
        let rig = file(name);
        let names: Vec<&str> = rig["bones"].as_array().unwrap().iter().map(|b| b["name"].as_str().unwrap()).collect();
        for (k, f) in recorded.iter().enumerate() {
            let angles: serde_json::Map<String, Value> = names
                .iter()
                .zip(f["angles_deg"].as_array().unwrap())
                .map(|(n, a)| (n.to_string(), a.clone()))
                .collect();
            let joints: serde_json::Map<String, Value> = names
                .iter()
                .zip(&f["joints"].as_array().unwrap()[1..])
                .map(|(n, p)| (n.to_string(), p.clone()))
                .collect();
            let frame = json!({"angles_deg": angles, "extensions": f["extensions"], "joints": joints});
            check_frame(name, &format!("recorded frame {k}"), &frame);
        }
    }
}

/// A pose in degrees says nothing about a slide: `render rig --pose-deg` on a prismatic bone, and
/// the API's `pose_deg` for a rig with one, are refused in one line naming the bone (they used to
/// read 30° as 0.52 length units).
#[test]
fn a_pose_in_degrees_is_refused_for_a_prismatic_bone() {
    let path = example("rrp");
    let path = path.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rrp.svg");
    let err = fails(&["render", "rig", "--rig", path, "--pose-deg", "ram=30", "--out", out.to_str().unwrap()], 2);
    assert!(err.contains("--pose-deg ram=30: bone \"ram\" is prismatic"), "{err}");
    assert!(!out.exists(), "no picture written");
    // A revolute bone of the same rig still takes degrees.
    common::succeeds(&["render", "rig", "--rig", path, "--pose-deg", "elbow=45", "--out", out.to_str().unwrap()]);
    let s = server::start(&[]);
    let rig = file("rrp");
    let answer = s.post("/api/render", &json!({"figure": "rig", "format": "svg", "rig": rig, "pose_deg": [30, 30, 0]}));
    let err = answer.error(422);
    assert!(err.starts_with("pose_deg: bone \"ram\" is prismatic"), "{err}");
}

/// An arm file's links as the rig the answers speak of: bone `link{i}` on `link{i-1}`, with
/// the link's keys.
fn arm_as_rig(path: &Path) -> Value {
    let arm: Value = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let bones: Vec<Value> = arm["links"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let mut b = l.clone();
            b["name"] = json!(format!("link{i}"));
            if i > 0 {
                b["parent"] = json!(format!("link{}", i - 1));
            }
            b
        })
        .collect();
    json!({"bones": bones})
}

/// Issue 25: an arm file's links take the joint keys. The shipped RRP arm reaches, from the
/// command line (`--goal X,Y`, on the last link) and from `POST /api/solve` with `arm`, a goal
/// farther than its links' lengths (and its start extension) reach: only the slide gets there.
/// Every tip is checked by the forward kinematics above, written from the file's keys.
#[test]
fn an_arm_file_with_a_slide_solves_from_the_command_line_and_the_api() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/rrp.toml");
    let rig = arm_as_rig(&path);
    let links = rig["bones"].as_array().unwrap();
    let lengths: f64 = links.iter().map(|b| b["length"].as_f64().unwrap()).sum();
    let start = links[2]["extension"].as_f64().unwrap();
    let [lo, hi] = pair(&links[2]["limits"]).unwrap();
    let goal: [f64; 2] = [0.5, 2.5];
    assert!(goal[0].hypot(goal[1]) > lengths + start + 0.2, "the goal must need the slide");
    let check = |answer: &Value| {
        assert_eq!(answer["status"], "reached", "{answer}");
        assert_eq!(answer["rig"], "rrp");
        assert_eq!(answer["effectors"][0]["name"], "link2");
        for (bone, tip) in tips(&rig, answer) {
            let got = pair(&answer["joints"][&bone]).unwrap();
            assert!((got[0] - tip[0]).hypot(got[1] - tip[1]) < 1e-12, "{bone}: {got:?} vs {tip:?}");
        }
        let tip = tips(&rig, answer)[2].1;
        assert!((tip[0] - goal[0]).hypot(tip[1] - goal[1]) <= 1e-6, "{tip:?}");
        let d = answer["extensions"]["link2"].as_f64().unwrap();
        assert!(d > start + 0.2 && (lo..=hi).contains(&d), "extension {d}");
        assert_eq!(answer["extensions"].as_object().unwrap().len(), 1);
    };
    let goal_arg = format!("{},{}", goal[0], goal[1]);
    let cli = json(&["solve", "--arm", path.to_str().unwrap(), "--goal", &goal_arg, "--limits", "--format", "json"]);
    check(&cli);
    // `track` follows with the last link's tip unless --effector says otherwise.
    let line = format!("1,1,{},{}", goal[0], goal[1]);
    let track = json(&["track", "--arm", path.to_str().unwrap(), "--line", &line, "--samples", "4", "--limits"]);
    assert_eq!(track["effector"], "link2");
    for sample in track["samples"].as_array().unwrap() {
        check_frame_of(&rig, "rrp arm track", sample);
    }
    let s = server::start(&[]);
    let arm: Value = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let body = json!({"arm": arm, "goal": {"x": goal[0], "y": goal[1]}, "options": {"limits": true}});
    let api = s.post("/api/solve", &body).json();
    check(&api);
    assert_eq!(api["angles_deg"], cli["angles_deg"]);
    assert_eq!(api["extensions"], cli["extensions"]);
    // A bad key of the arm is named as the arm's link, on either edge.
    let mut bad = arm.clone();
    bad["links"][2]["limits"] = json!([0.6, 0.0]);
    let answer = s.post("/api/solve", &json!({"arm": bad, "goal": {"x": 1, "y": 1}}));
    assert_eq!(answer.error(422), "arm: links[2].limits = [0.6, 0]: min must not exceed max");
}

/// The joint keys of an arm file's links: problems named by the link, one line each; a
/// command that takes a chain only says so, naming the first key.
#[test]
fn bad_joint_keys_of_an_arm_are_one_line_naming_the_link() {
    let dir = tempfile::tempdir().unwrap();
    let base = "[[links]]\nlength = 1\n[[links]]\nlength = 0.5\n";
    for (extra, want) in [
        ("joint = \"prismatic\"\nslide = [0, 0]\n", "links[1].slide: must not be zero, got [0, 0]"),
        ("joint = \"prismatic\"\nextension = 0.9\nlimits = [0, 0.5]\n", "links[1].extension: 0.9 lies outside"),
        ("joint = \"prismatic\"\nlimits_deg = [0, 10]\n", "links[1].limits_deg: not for a prismatic joint"),
        ("limits = [0, 1]\n", "links[1].limits: not for a revolute joint"),
        ("offset = [nan, 0]\n", "links[1].offset: must be finite numbers, got [NaN, 0]"),
        ("joint = \"prismatic\"\nextension = inf\n", "links[1].extension = inf: must be a finite number"),
    ] {
        let path = dir.path().join("a.toml");
        std::fs::write(&path, format!("{base}{extra}")).unwrap();
        let err = fails(&["solve", "--arm", path.to_str().unwrap(), "--goal", "1,0"], 2);
        let want = format!("arm file {}: {want}", path.display());
        assert!(err.starts_with(&format!("ikarus: {want}")) && err.trim_end().lines().count() == 1, "{extra}: {err}");
    }
    // A command that takes a chain only refuses it in one line; `animate` takes it as the rig
    // of its links, its goal on the last link's tip.
    let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/rrp.toml");
    let arm = arm.to_str().unwrap();
    let err = fails(&["reach", "--arm", arm, "--point", "1,1"], 2);
    assert!(err.contains("rrp.toml: links[2].joint: an arm with offsets or slides is a one-branch rig"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let answer = json(&["animate", "--arm", arm, "--goal", "1,1", "--frames", "5", "--format", "json"]);
    let last = &answer["frames"][4];
    let tip = last["joints"]["link2"].as_array().unwrap();
    let (x, y) = (tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap());
    assert!((x - 1.0).hypot(y - 1.0) < 1e-5, "{last}");
    assert!(last["extensions"]["link2"].is_f64(), "{last}");
}

/// Issue 25: `workspace` over the body. A rig the exact region cannot take (the PRR arm: a slide,
/// an offset) gets the sampled region of its last bone's tip (or `--bone`'s), `"exact": false`,
/// every occupied cell within the rig's reach; a rig that is a chain gets the chain's exact
/// region, the same JSON as the arm file of the same links.
#[test]
fn workspace_takes_a_rig_sampled_unless_it_is_a_chain() {
    let prr = example("prr");
    let ws = json(&["workspace", "--rig", prr.to_str().unwrap(), "--resolution", "64", "--format", "json"]);
    assert_eq!((&ws["arm"], &ws["bone"], &ws["exact"]), (&json!("prr"), &json!("lower"), &json!(false)), "{ws}");
    let grid = ws["grid"].as_array().unwrap();
    assert_eq!(grid.len(), 64);
    let (h, origin, reach) =
        (ws["cell_size"].as_f64().unwrap(), pair(&ws["origin"]).unwrap(), ws["outer_radius"].as_f64().unwrap());
    let mut occupied = 0;
    for (iy, row) in grid.iter().enumerate() {
        for (ix, c) in row.as_str().unwrap().chars().enumerate() {
            if c == '1' {
                occupied += 1;
                let (x, y) = (origin[0] + h * (ix as f64 + 0.5), origin[1] + h * (iy as f64 + 0.5));
                assert!(x.hypot(y) <= reach + h, "cell {ix},{iy}");
            }
        }
    }
    assert!((f64::from(occupied) * h * h - ws["area"].as_f64().unwrap()).abs() < 1e-9);
    // The carriage's tip runs along the rail: one row of cells.
    let carriage = json(&["workspace", "--rig", prr.to_str().unwrap(), "--bone", "carriage", "--resolution", "64"]);
    let rows = carriage["grid"].as_array().unwrap().iter().filter(|r| r.as_str().unwrap().contains('1')).count();
    assert_eq!((rows, &carriage["exact"]), (1, &json!(false)));
    let text = succeeds(&["workspace", "--rig", prr.to_str().unwrap(), "--resolution", "16", "--format", "text"]);
    assert!(text.contains("sampled: "), "{text}");
    // The seed arm written as a rig: the same exact region, byte for byte but the name.
    let dir = tempfile::tempdir().unwrap();
    let rig = dir.path().join("seed-rig.toml");
    std::fs::write(
        &rig,
        "name = \"seed\"\n[[bones]]\nname = \"a\"\nlength = 3\nangle_deg = 5\nlimits_deg = [-45, 45]\n\
         [[bones]]\nname = \"b\"\nparent = \"a\"\nlength = 2\nangle_deg = 5\nlimits_deg = [-90, 90]\n\
         [[bones]]\nname = \"c\"\nparent = \"b\"\nlength = 1\nangle_deg = 5\nlimits_deg = [-170, 170]\n",
    )
    .unwrap();
    for limits in [&[][..], &["--limits"][..]] {
        let mut args = vec!["workspace", "--rig", rig.to_str().unwrap(), "--format", "json"];
        args.extend(limits);
        let from_rig = succeeds(&args);
        let mut args = vec!["workspace", "--format", "json"];
        args.extend(limits);
        assert_eq!(from_rig, succeeds(&args), "{limits:?}");
        assert!(from_rig.contains("\"exact\":true"));
    }
    let err = fails(&["workspace", "--bone", "a"], 2);
    assert!(err.contains("--bone a: only for a rig or an arm with slides"), "{err}");
    // The API: the same answers, by `rig` (and `bone`), or an arm with a slide.
    let s = server::start(&[]);
    let api = s.post("/api/workspace", &json!({"rig": file("prr"), "resolution": 64})).json();
    assert_eq!(api, ws, "the API's region is the command line's");
    let api = s.post("/api/workspace", &json!({"rig": file("prr"), "bone": "carriage", "resolution": 64})).json();
    assert_eq!(api, carriage);
    let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/rrp.toml");
    let cli = json(&["workspace", "--arm", arm.to_str().unwrap(), "--resolution", "32", "--limits"]);
    let arm: Value = toml::from_str(&std::fs::read_to_string(&arm).unwrap()).unwrap();
    let api = s.post("/api/workspace", &json!({"arm": arm, "resolution": 32, "limits": true})).json();
    assert_eq!((&api, &api["exact"], &api["bone"]), (&cli, &json!(false), &json!("link2")));
    let e = s.post("/api/workspace", &json!({"rig": file("prr"), "bone": "nose"})).error(422);
    assert!(e.starts_with("bone = \"nose\": no bone named \"nose\""), "{e}");
}
