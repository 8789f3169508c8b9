//! `ikarus animate --rig` and `ikarus track --rig` through the binary: the JSON shapes (angles
//! and tips keyed by bone name), the motion from the start pose to the solved pose, the track's
//! effector on its path with the pins held, CSV and text, pictures, and bad input (exit 2, one
//! line). The tests that check `reached` need the real rig solver.

mod common;
#[path = "common/rigs.rs"]
mod rigs;

use common::{dist, fails, ikarus, json, point, stderr, stdout, succeeds};
use rigs::{puppet, puppet_start_tip as start_tip};

/// The targets of both hands, as `--goal NAME=X,Y` values.
fn hand_goals() -> Vec<String> {
    rigs::puppet_hand_targets().iter().map(|(n, [x, y])| format!("{n}={x},{y}")).collect()
}

#[test]
fn a_rig_motion_runs_from_the_start_pose_to_the_solved_pose_in_json() {
    let rig = puppet();
    let goals = hand_goals();
    let args = [
        "animate",
        "--rig",
        &rig,
        "--goal",
        &goals[0],
        "--goal",
        &goals[1],
        "--pin",
        "left_foot",
        "--pin",
        "right_foot",
        "--limits",
        "--frames",
        "20",
        "--format",
        "json",
    ];
    let v = json(&args);
    assert_eq!(v["rig"], "puppet");
    assert_eq!(v["ease"], "sine");
    assert_eq!(v["duration"], 1.0);
    let solves = v["solves"].as_array().unwrap();
    assert_eq!(solves.len(), 1);
    let effectors: Vec<&str> =
        solves[0]["effectors"].as_array().unwrap().iter().map(|e| e["name"].as_str().unwrap()).collect();
    assert_eq!(effectors, ["right_hand", "left_hand", "left_foot", "right_foot"]);
    assert_eq!(solves[0]["status"], "reached", "{}", solves[0]);
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 20);
    let file = rigs::json("puppet");
    let names = rigs::names(&file);
    // Keyed by bone name (in the rig's order: see the text check below); the first frame is
    // the start pose.
    let first = frames[0]["angles_deg"].as_object().unwrap();
    assert_eq!(first.len(), names.len());
    for (name, deg) in names.iter().zip(rigs::start_deg(&file)) {
        assert!((first[name].as_f64().unwrap() - deg).abs() < 1e-9, "{name}");
    }
    assert_eq!(frames[0]["joints"].as_object().unwrap().len(), names.len());
    // The last frame is the solved pose: hands on their targets, feet where they started.
    let last = &frames[19]["joints"];
    for (hand, target) in rigs::puppet_hand_targets() {
        assert!(dist(point(&last[hand]), target) < 1e-5, "{hand}: {}", last[hand]);
    }
    for foot in ["left_foot", "right_foot"] {
        assert!(dist(point(&last[foot]), start_tip(foot)) < 1e-5, "{foot}: {}", last[foot]);
    }
    // Times from 0 to 1.
    assert_eq!(frames[0]["time"], 0.0);
    assert_eq!(frames[19]["time"], 1.0);
}

#[test]
fn a_rig_motion_passes_through_each_via_goal_set() {
    let rig = puppet();
    let goals = hand_goals();
    let [x, y] = rigs::puppet_hand_targets()[0].1;
    let via = format!("right_hand={},{}", x - 0.1, y - 0.2);
    let args = [
        "animate",
        "--rig",
        &rig,
        "--via",
        &via,
        "--goal",
        &goals[0],
        "--pin",
        "left_foot",
        "--limits",
        "--frames",
        "9",
        "--format",
        "json",
    ];
    let v = json(&args);
    let solves = v["solves"].as_array().unwrap();
    assert_eq!(solves.len(), 2, "the via set, then the goal set");
    assert_eq!(solves[0]["effectors"][0]["target"], serde_json::json!([x - 0.1, y - 0.2]));
    assert!(solves.iter().all(|s| s["status"] == "reached"), "{solves:?}");
    assert_eq!(v["frames"].as_array().unwrap().len(), 9);
    let text = succeeds(&[
        "animate",
        "--rig",
        &rig,
        "--via",
        &via,
        "--goal",
        &goals[0],
        "--pin",
        "left_foot",
        "--limits",
        "--frames",
        "9",
        "--format",
        "text",
    ]);
    assert!(text.starts_with("rig       puppet (16 bones)\n"), "{text}");
    assert!(text.contains("\nvia       right_hand ("), "{text}");
    assert!(text.contains("left_foot pinned: reached"), "{text}");
    assert!(text.contains("motion    9 frames over 1 s, sine ease"), "{text}");
}

#[test]
fn a_rig_motion_in_csv_has_a_column_per_bone_angle_and_tip() {
    let rig = puppet();
    // Not reached (the start pose is far from it) or reached: the shape is the same; the
    // message about an unreached set goes to stderr.
    let o = ikarus(&["animate", "--rig", &rig, "--goal", "right_hand=0.5,0.9", "--frames", "5", "--format", "csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 6);
    let header: Vec<&str> = lines[0].split(',').collect();
    assert_eq!(header.len(), 1 + 16 + 32);
    assert_eq!(&header[..3], ["time", "pelvis_deg", "spine_deg"]);
    assert_eq!(&header[17..19], ["pelvis.x", "pelvis.y"]);
    assert_eq!(header[48], "right_foot.y");
    assert!(lines[1..].iter().all(|l| l.split(',').count() == header.len()));
    // The JSON objects keyed by bone name keep the rig's order, as the text is written.
    let o = ikarus(&["animate", "--rig", &rig, "--goal", "right_hand=0.5,0.9", "--frames", "2", "--format", "json"]);
    let out = stdout(&o);
    let frame = &out[out.find("\"frames\"").unwrap()..];
    let angles = &frame[frame.find("\"angles_deg\"").unwrap()..frame.find("\"joints\"").unwrap()];
    let at: Vec<usize> = rigs::names(&rigs::json("puppet"))
        .iter()
        .map(|n| angles.find(&format!("\"{n}\":")).unwrap_or_else(|| panic!("{n} missing: {angles}")))
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "not in the rig's order: {angles}");
}

#[test]
fn a_rig_motion_draws_the_skeleton() {
    let dir = std::env::temp_dir().join(format!("ikarus-rig-motion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let rig = puppet();
    let goals = hand_goals();
    for (ext, magic) in [("svg", &b"<svg"[..]), ("png", &b"\x89PNG"[..]), ("gif", &b"GIF89a"[..])] {
        let out = dir.join(format!("motion.{ext}"));
        let o = ikarus(&[
            "animate",
            "--rig",
            &rig,
            "--goal",
            &goals[0],
            "--pin",
            "left_foot",
            "--limits",
            "--frames",
            "6",
            "--width",
            "200",
            "--height",
            "200",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(o.stdout.is_empty(), "with --out stdout stays quiet");
        let bytes = std::fs::read(&out).unwrap();
        assert!(bytes.starts_with(magic), "{ext}");
        if ext == "svg" {
            let svg = String::from_utf8(bytes.clone()).unwrap();
            assert!(svg.contains("id=\"bone15\""), "every bone drawn");
        }
        if ext == "gif" {
            let mut decoder = gif::DecodeOptions::new().read_info(bytes.as_slice()).unwrap();
            let mut frames = 0;
            while decoder.read_next_frame().unwrap().is_some() {
                frames += 1;
            }
            assert_eq!(frames, 6, "one GIF frame per motion frame");
        }
    }
    // `ikarus render motion` draws the same motion.
    let out = dir.join("render.svg");
    let o = ikarus(&[
        "render",
        "motion",
        "--rig",
        &rig,
        "--goal",
        &goals[0],
        "--pin",
        "left_foot",
        "--frames",
        "4",
        "--width",
        "200",
        "--height",
        "200",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("id=\"bone15\""), "render motion --rig draws the skeleton");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_rig_motions_are_one_line_errors() {
    let rig = puppet();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--rig", &rig, "--goal", "1,2"], "--goal 1,2: a rig's goal names its bone: --goal NAME=X,Y[,DEG]"),
        (vec!["--rig", &rig, "--goal", "nose=1,2"], "--goal nose=1,2: no bone named \"nose\" in the rig"),
        (vec!["--rig", &rig, "--goal", "left_hand=1,2", "--via", "1,1"], "--via 1,1: a rig's via is a goal set"),
        (
            vec!["--rig", &rig, "--goal", "left_hand=1,2", "--via", "left_hand=1,1;nose=0,1"],
            "--via left_hand=1,1;nose=0,1: no bone named \"nose\"",
        ),
        (vec!["--rig", &rig, "--goal", "left_hand=1,2", "--method", "ccd"], "method ccd: solves chains only"),
        (vec!["--rig", &rig, "--goal", "left_hand=1,2", "--pin", "left_hand"], "bone \"left_hand\" already has a goal"),
        (
            vec!["--rig", &rig, "--goal", "left_hand=1,2", "--goal-angle", "30"],
            "the argument '--rig <FILE>' cannot be used with '--goal-angle <DEG>'",
        ),
        (vec!["--goal", "left_hand=1,2"], "--goal left_hand=1,2: a goal on a named bone needs --rig FILE"),
        (vec!["--goal", "1,2", "--goal", "2,1"], "--goal: an arm has one tip, so one --goal X,Y, got 2"),
        (
            vec!["--goal", "1,2", "--via", "left_hand=1,1"],
            "--via left_hand=1,1: a goal set on named bones needs --rig FILE",
        ),
        (
            vec!["--goal", "1,2", "--pin", "left_hand"],
            "the following required arguments were not provided: --rig <FILE>",
        ),
    ];
    for (args, want) in cases {
        let mut all = vec!["animate"];
        all.extend(args.iter().copied());
        let e = fails(&all, 2);
        assert!(e.contains(want), "{all:?}: {e}");
    }
}

#[test]
fn a_rig_effector_follows_a_path_while_the_feet_stay_planted() {
    let rig = puppet();
    let [x, y] = rigs::puppet_hand_targets()[0].1;
    let circle = format!("{},{},0.08", x - 0.08, y);
    let args = [
        "track",
        "--rig",
        &rig,
        "--effector",
        "right_hand",
        "--circle",
        &circle,
        "--samples",
        "24",
        "--pin",
        "left_foot",
        "--pin",
        "right_foot",
        "--limits",
        "--format",
        "json",
    ];
    let v = json(&args);
    assert_eq!(
        (v["rig"].as_str(), v["effector"].as_str(), v["mode"].as_str()),
        (Some("puppet"), Some("right_hand"), Some("follow"))
    );
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 24);
    assert_eq!(v["summary"]["reached"], 24, "{}", v["summary"]);
    assert_eq!(v["summary"]["flips"], 0);
    let bound = v["summary"]["step_bound_deg"].as_f64().unwrap();
    for (k, s) in samples.iter().enumerate() {
        let joints = &s["joints"];
        assert!(dist(point(&joints["right_hand"]), point(&s["goal"])) < 1e-5, "sample {k}: {s}");
        for foot in ["left_foot", "right_foot"] {
            assert!(dist(point(&joints[foot]), start_tip(foot)) < 1e-5, "sample {k}: {foot} moved: {}", joints[foot]);
        }
        if k > 0 {
            assert!(s["step_deg"].as_f64().unwrap() <= bound * (1.0 + 1e-9), "sample {k}: a step over the bound");
        }
        assert_eq!(s["angles_deg"].as_object().unwrap().len(), 16);
    }
}

#[test]
fn a_rig_track_in_csv_and_text_and_its_bad_input() {
    let rig = puppet();
    let base = ["track", "--rig", &rig, "--effector", "left_hand", "--line", "-0.6,0.6,-0.7,0.9", "--samples", "4"];
    let out = succeeds_or_unreached(&[&base[..], &["--format", "csv"]].concat());
    let header = out.lines().next().unwrap();
    assert!(header.starts_with("sample,x,y,status,error,step_deg,pelvis_deg,"), "{header}");
    assert!(header.ends_with(",right_foot_deg"), "{header}");
    assert_eq!(out.lines().count(), 5);
    let text = succeeds_or_unreached(&[&base[..], &["--pin", "right_foot", "--format", "text"]].concat());
    assert!(text.starts_with("rig       puppet (16 bones)\neffector  left_hand; held: right_foot pinned\n"), "{text}");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--rig", &rig, "--circle", "0,1,0.1"], "--effector: required with --rig"),
        (
            vec!["--rig", &rig, "--effector", "left_hand", "--circle", "0,1,0.1", "--mode", "plan"],
            "--mode plan: a rig's effector is followed online only",
        ),
        (
            vec!["--rig", &rig, "--effector", "left_hand", "--circle", "0,1,0.1", "--pin", "left_hand"],
            "--effector left_hand: the bone is also pinned",
        ),
        (
            vec!["--rig", &rig, "--effector", "left_hand", "--circle", "0,1,0.1", "--goal", "left_hand=0,1"],
            "--effector left_hand: the bone also has a goal",
        ),
        (vec!["--rig", &rig, "--effector", "tail", "--circle", "0,1,0.1"], "--effector tail: no bone named \"tail\""),
        (
            vec!["--rig", &rig, "--effector", "left_hand", "--circle", "0,1,0.1", "--method", "fabrik"],
            "method fabrik: solves chains only",
        ),
        (vec!["--effector", "left_hand", "--circle", "0,1,0.1"], "required arguments were not provided: --rig <FILE>"),
        (vec!["--goal", "left_hand=0,1", "--circle", "0,1,0.1"], "required arguments were not provided: --rig <FILE>"),
    ];
    for (args, want) in cases {
        let mut all = vec!["track"];
        all.extend(args.iter().copied());
        let e = fails(&all, 2);
        assert!(e.contains(want), "{all:?}: {e}");
    }
}

/// Runs a command that must succeed (an unreached sample is data, not an error), its stdout.
fn succeeds_or_unreached(args: &[&str]) -> String {
    let o = ikarus(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stdout(&o)
}

#[test]
fn a_rig_track_draws_the_skeleton_one_frame_per_sample() {
    let dir = std::env::temp_dir().join(format!("ikarus-rig-track-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("track.gif");
    let rig = puppet();
    let o = ikarus(&[
        "track",
        "--rig",
        &rig,
        "--effector",
        "right_hand",
        "--circle",
        "0.5,1.2,0.1",
        "--samples",
        "5",
        "--width",
        "160",
        "--height",
        "160",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&out).unwrap();
    let mut decoder = gif::DecodeOptions::new().read_info(bytes.as_slice()).unwrap();
    let mut frames = 0;
    while decoder.read_next_frame().unwrap().is_some() {
        frames += 1;
    }
    assert_eq!(frames, 5);
    std::fs::remove_dir_all(&dir).unwrap();
}
