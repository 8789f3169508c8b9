//! The API with rigs over real HTTP: `POST /api/solve` with `rig`, `GET /api/rigs`,
//! `POST /api/rig/parse`, the figure `rig` of `POST /api/render`, the caps, and every class of
//! bad request (422 naming the field, 400 for malformed JSON).

#[path = "common/rigs.rs"]
mod rigs;
#[path = "common/server.rs"]
mod server;

use serde_json::{Value, json};

use server::start;

fn puppet_solve(extra: Value) -> Value {
    let mut body = json!({
        "rig": rigs::json("puppet"),
        "goals": [{"bone": "right_hand", "x": 0.3, "y": 0.8}],
        "pins": ["left_foot"],
    });
    for (k, v) in extra.as_object().unwrap() {
        body[k] = v.clone();
    }
    body
}

#[test]
fn the_shipped_rigs_parse_and_solve() {
    let s = start(&[]);
    let a = s.get("/api/rigs");
    assert_eq!(a.status, 200);
    assert_eq!(a.content_type, "application/json");
    let v = a.json();
    let rigs = v["rigs"].as_array().unwrap();
    let names: Vec<&str> = rigs.iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["puppet", "hand"]);
    for r in rigs {
        let rig = &r["rig"];
        assert_eq!(rig["name"], r["name"]);
        assert_eq!(rig["base"], json!([0.0, 0.0]));
        let file = rigs::json(r["name"].as_str().unwrap());
        assert_eq!(rigs::names(rig), rigs::names(&file));
        let first = &rig["bones"][0];
        assert_eq!(first["parent"], Value::Null, "a root's parent is null: {first}");
        assert!(first["limits_deg"].is_array(), "{first}");
        // What /api/rigs gives is a request's rig as it is.
        let bone = rigs::names(rig).pop().unwrap();
        let solved = s.post("/api/solve", &json!({"rig": rig, "pins": [bone]}));
        assert_eq!(solved.status, 200, "{}", solved.text());
    }

    // A rig file's text, as the page uploads it.
    let text = std::fs::read_to_string(rigs::path("hand")).unwrap();
    let a = s.post_raw("/api/rig/parse", "application/toml", text.as_bytes());
    assert_eq!(a.status, 200);
    assert_eq!(a.json()["rig"], rigs[1]["rig"]);
    for (text, want) in [
        (
            "[[bones]]\nname = \"a\"\nparent = \"b\"\nlength = 1\n",
            "rig file: bones[0] (\"a\").parent = \"b\": no bone of that name",
        ),
        (
            "[[bones]]\nname = \"a\"\nlength = 1\n[[bones]]\nname = \"a\"\nlength = 1\n",
            "rig file: bones[1] (\"a\").name = \"a\": the name of bones[0] already; names must be unique",
        ),
        (
            "[[bones]]\nname = \"a\"\nparent = \"b\"\nlength = 1\n[[bones]]\nname = \"b\"\nparent = \"a\"\nlength = 1\n",
            "rig file: bones[0] (\"a\").parent = \"b\": a cycle (a → b → a); a bone cannot be its own ancestor",
        ),
        ("[[bones]\n", "rig file: line 1"),
    ] {
        let a = s.post_raw("/api/rig/parse", "application/toml", text.as_bytes());
        assert_eq!(a.status, 200);
        let v = a.json();
        assert_eq!(v.as_object().unwrap().len(), 1, "{v}");
        let problem = v["problem"].as_str().unwrap();
        assert!(problem.starts_with(want) && !problem.contains('\n'), "{problem:?}, want {want:?}");
    }
    // The [solver] table is carried, and reads back.
    let a = s.post_raw(
        "/api/rig/parse",
        "application/toml",
        b"[[bones]]\nname = \"a\"\nlength = 1\n[solver]\nmethod = \"dls\"\ntolerance = 0.001\n",
    );
    let rig = &a.json()["rig"];
    assert_eq!(rig["solver"], json!({"method": "dls", "tolerance": 0.001}));
    let solved = s.post("/api/solve", &json!({"rig": rig, "goals": [{"bone": "a", "x": 0, "y": 1}]}));
    assert_eq!(solved.json()["method"], "dls");
    assert_eq!(solved.json()["tolerance"], 0.001);
}

#[test]
fn the_json_of_a_rig_solve_is_the_command_lines() {
    let s = start(&[]);
    let a = s.post(
        "/api/solve",
        &puppet_solve(json!({"goals": [{"bone": "right_hand", "x": 0.3, "y": 0.8, "angle_deg": 30, "weight": 2,
                                        "bend": "cw", "softness": 0.01},
                                       {"bone": "head", "x": 0.1, "y": 1.0, "priority": "secondary"}],
                             "mix": 1, "options": {"limits": true, "record_every": 1}})),
    );
    assert_eq!(a.status, 200, "{}", a.text());
    assert_eq!(a.content_type, "application/json");
    let v = a.json();
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "angle_error_deg",
            "angles_deg",
            "effectors",
            "error",
            "frames",
            "iterations",
            "joints",
            "limit_mode",
            "limits",
            "method",
            "restarts",
            "rig",
            "solve_us",
            "status",
            "tolerance"
        ]
    );
    assert_eq!(v["rig"], "puppet");
    assert_eq!(v["limits"], true);
    assert_eq!(v["limit_mode"], "lock");
    let names: Vec<&str> = v["effectors"].as_array().unwrap().iter().map(|e| e["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["right_hand", "head", "left_foot"]);
    assert_eq!(v["effectors"][2]["pinned"], true);
    // Objects keyed by bone name in the rig's order.
    let body = a.text();
    let angles = &body[body.find("\"angles_deg\":{").unwrap()..];
    let (pelvis, foot) = (angles.find("\"pelvis\"").unwrap(), angles.find("\"right_foot\"").unwrap());
    assert!(pelvis < foot, "{angles}");
    assert_eq!(v["angles_deg"].as_object().unwrap().len(), 16);
    assert_eq!(v["joints"].as_object().unwrap().len(), 16);

    // `start_deg` as the rig's start angles is the same solve as none.
    let start: Vec<f64> = rigs::start_deg(&rigs::json("puppet"));
    let b = s.post("/api/solve", &puppet_solve(json!({"start_deg": start})));
    let c = s.post("/api/solve", &puppet_solve(json!({})));
    assert_eq!(b.json()["angles_deg"], c.json()["angles_deg"]);
}

/// Real solving: the puppet reaches with both hands, feet planted, limits on.
#[test]
fn the_puppet_reaches_with_both_hands_while_its_feet_stay_planted() {
    let s = start(&[]);
    let goals: Vec<Value> =
        rigs::puppet_hand_targets().iter().map(|(h, [x, y])| json!({"bone": h, "x": x, "y": y})).collect();
    let a = s.post(
        "/api/solve",
        &puppet_solve(json!({"goals": goals, "pins": ["left_foot", "right_foot"], "options": {"limits": true}})),
    );
    let v = a.json();
    assert_eq!(v["status"], "reached", "{v}");
    for e in v["effectors"].as_array().unwrap() {
        assert_eq!(e["status"], "reached", "{e}");
        assert!(e["error"].as_f64().unwrap() <= 1e-6, "{e}");
    }
}

#[test]
fn bad_rig_requests_are_422_naming_the_field() {
    let s = start(&[]);
    let bones = |n: usize| -> Value {
        let list: Vec<Value> = (0..n)
            .map(|i| json!({"name": format!("b{i}"), "length": 1.0, "parent": (i > 0).then(|| format!("b{}", i - 1))}))
            .collect();
        json!({"bones": list})
    };
    let many_goals: Vec<Value> = (0..65).map(|i| json!({"bone": format!("b{i}"), "x": 0, "y": 0})).collect();
    let cases: Vec<(Value, &str)> = vec![
        (
            puppet_solve(json!({"goals": [{"bone": "right_hnd", "x": 1, "y": 1}]})),
            "goals[0]: no bone named \"right_hnd\" in the rig (its bones: pelvis,",
        ),
        (puppet_solve(json!({"pins": ["left_fot"]})), "pins[0]: no bone named \"left_fot\""),
        (
            puppet_solve(
                json!({"goals": [{"bone": "right_hand", "x": 1, "y": 1}, {"bone": "right_hand", "x": 0, "y": 1}]}),
            ),
            "goals[1]: bone \"right_hand\" already has a goal (goals[0]); one goal or pin per bone",
        ),
        (puppet_solve(json!({"pins": ["right_hand"]})), "pins[0]: bone \"right_hand\" already has a goal (goals[0])"),
        (puppet_solve(json!({"goals": [], "pins": []})), "goals: a rig solve needs at least one goal or pin, got none"),
        (
            puppet_solve(json!({"goals": [{"bone": "right_hand", "x": 1, "y": 1, "weight": 0}]})),
            "goals[0].weight: 0: must be a finite number > 0",
        ),
        (
            puppet_solve(json!({"goals": [{"bone": "right_hand", "x": 1, "y": 1, "softness": -1}]})),
            "goals[0].softness: -1: must be",
        ),
        (
            puppet_solve(json!({"goals": [{"bone": "pelvis", "x": 1, "y": 1, "bend": "cw"}]})),
            "goals[0].bend: bone \"pelvis\" has no parent",
        ),
        (
            puppet_solve(json!({"goals": [{"bone": "pelvis", "x": 1, "y": 1, "bend": "up"}]})),
            "goals[0].bend: unknown variant `up`",
        ),
        (puppet_solve(json!({"mix": 2})), "mix: must be from 0 to 1, got 2"),
        (puppet_solve(json!({"start_deg": [1, 2]})), "start_deg: expected 16 angles (one per joint), got 2"),
        (puppet_solve(json!({"options": {"method": "ccd"}})), "method ccd: solves chains only"),
        (puppet_solve(json!({"options": {"method": "fabrik"}})), "method fabrik: solves chains only"),
        (
            puppet_solve(json!({"options": {"rates": [1, 2]}})),
            "options.rates: expected 16 values (one per joint), got 2",
        ),
        (
            puppet_solve(json!({"options": {"max_iterations": 1_000_000}})),
            "options.max_iterations = 1000000: more than the cap",
        ),
        (
            puppet_solve(json!({"options": {"max_iterations": 100_000, "record_every": 1}})),
            "options.max_iterations = 100000, options.record_every = 1: the solve could record 100002 frames of 16 joints",
        ),
        (puppet_solve(json!({"arm": {"links": [{"length": 1}]}})), "arm, rig: give one or the other, not both"),
        (puppet_solve(json!({"goal": {"x": 1, "y": 1}})), "goal: a rig takes goals"),
        (json!({"goals": [{"bone": "a", "x": 1, "y": 1}]}), "goals: only with rig"),
        (puppet_solve(json!({"bogus": 1})), "unknown field `bogus`"),
        (
            json!({"rig": {"bones": [{"name": "a", "length": 1}, {"name": "a", "length": 1}]}, "pins": ["a"]}),
            "rig: bones[1] (\"a\").name = \"a\": the name of bones[0] already; names must be unique",
        ),
        (
            json!({"rig": {"bones": [{"name": "a", "parent": "b", "length": 1}, {"name": "b", "parent": "a", "length": 1}]}, "pins": ["a"]}),
            "rig: bones[0] (\"a\").parent = \"b\": a cycle (a → b → a)",
        ),
        (
            json!({"rig": {"bones": [{"name": "a", "parent": "nope", "length": 1}]}, "pins": ["a"]}),
            "rig: bones[0] (\"a\").parent = \"nope\": no bone of that name",
        ),
        (json!({"rig": {"bones": [{"name": "a", "length": -1}]}, "pins": ["a"]}), "rig: bones[0] (\"a\").length = -1"),
        (json!({"rig": bones(257), "pins": ["b0"]}), "rig: bones: 257 bones exceed the cap of 256 (--max-bones)"),
        (
            json!({"rig": bones(100), "goals": many_goals}),
            "goals, pins: 65 effectors (goals and pins together), more than the cap of 64",
        ),
    ];
    for (body, want) in cases {
        let a = s.post("/api/solve", &body);
        let e = a.error(422);
        assert!(e.contains(want), "{e:?} lacks {want:?}");
    }
    // At the caps: fine.
    let at_cap: Vec<Value> = (0..64).map(|i| json!({"bone": format!("b{i}"), "x": 0, "y": 0})).collect();
    let a = s.post(
        "/api/solve",
        &json!({"rig": bones(256), "goals": at_cap, "options": {"max_iterations": 1, "restarts": 0}}),
    );
    assert_eq!(a.status, 200, "{}", a.text());
    // Malformed JSON is a 400, as for arms.
    let a = s.post_raw("/api/solve", "application/json", b"{\"rig\": {\"bones\": [");
    assert_eq!(a.status, 400, "{}", a.text());
}

#[test]
fn the_figure_rig() {
    let s = start(&[]);
    let rig = rigs::json("puppet");
    let figure = |extra: Value| {
        let mut body = json!({"figure": "rig", "rig": rig, "goals": [{"bone": "right_hand", "x": 0.4, "y": 1.0, "angle_deg": 20}],
                              "pins": ["left_foot", "right_foot"]});
        for (k, v) in extra.as_object().unwrap() {
            body[k] = v.clone();
        }
        body
    };
    let a = s.post("/api/render", &figure(json!({"format": "svg", "limits": true, "labels": true})));
    assert_eq!(a.status, 200, "{}", a.text());
    assert_eq!(a.content_type, "image/svg+xml");
    let svg = a.text();
    assert!(svg.contains("id=\"bone15\"") && svg.contains(">right_hand<"), "bones and names drawn");
    // PNG by default; figure `arm` with `rig` in place of `arm` draws the same.
    let a = s.post("/api/render", &figure(json!({})));
    assert_eq!((a.status, a.content_type.as_str()), (200, "image/png"));
    let b = s.post("/api/render", &figure(json!({"figure": "arm"})));
    assert_eq!(b.status, 200);
    assert_eq!(a.body, b.body);
    // Without goals or pins, in a pose.
    let mut pose = rigs::start_deg(&rig);
    pose[7] = -90.0;
    let a = s.post("/api/render", &json!({"figure": "rig", "rig": rig, "pose_deg": pose, "format": "svg"}));
    assert_eq!(a.status, 200, "{}", a.text());
    for (body, want) in [
        (figure(json!({"format": "gif"})), "format = gif: only the figure motion animates"),
        (figure(json!({"pins": ["nose"]})), "pins[0]: no bone named \"nose\""),
        (figure(json!({"pose_deg": [1]})), "pose_deg: expected 16 angles"),
        (figure(json!({"width": 5})), "width = 5: must be between 16 and 4096 pixels"),
        (figure(json!({"workspace": true})), "unknown field `workspace`"),
        (json!({"figure": "rig"}), "missing field `rig`"),
    ] {
        let e = s.post("/api/render", &body).error(422);
        assert!(e.contains(want), "{e:?} lacks {want:?}");
    }
}

/// A rig solve runs under the request budget like every computation: a heavy one (256 bones,
/// 64 goals out of reach, 10⁵ iterations and 64 restarts each) answers 503 at the budget and
/// gives its only worker back, so that the next solve is answered.
#[test]
fn a_heavy_rig_solve_stops_at_its_budget() {
    let s = start(&["--workers", "1", "--request-budget-ms", "1000"]);
    let bones: Vec<Value> = (0..256)
        .map(|i| json!({"name": format!("b{i}"), "length": 1.0, "parent": (i > 0).then(|| format!("b{}", i - 1))}))
        .collect();
    let goals: Vec<Value> =
        (0..64).map(|i| json!({"bone": format!("b{}", 4 * i + 3), "x": f64::from(i % 9) * 50.0, "y": 500.0})).collect();
    let heavy =
        json!({"rig": {"bones": bones}, "goals": goals, "options": {"max_iterations": 100_000, "restarts": 64}});
    let e = s.post("/api/solve", &heavy).error(503);
    assert!(e.contains("budget of 1000 ms (--request-budget-ms)"), "{e}");
    // The event that shows the heavy solve stopped: the only worker is free again, and an
    // ordinary rig solve answers (behind a solve that ignored the interrupt it would wait past
    // its own budget and get 503). No clock: the order of the answers is the proof.
    let a = s.post("/api/solve", &puppet_solve(json!({})));
    assert_eq!(a.status, 200, "{}", a.text());
}

/// A rig file of one chain of `n` bones, as text.
fn chain_toml(n: usize) -> String {
    (0..n)
        .map(|i| {
            let parent = if i == 0 { String::new() } else { format!("parent = \"b{}\"\n", i - 1) };
            format!("[[bones]]\nname = \"b{i}\"\n{parent}length = 0.001\n")
        })
        .collect()
}

/// Issue 24: a 1 MB rig file of ~23 000 bones in one chain took 10.6 s and 2 GB to parse, and
/// three at once aborted the server. `/api/rig/parse` counts the bones first: over `--max-bones`
/// the file is its one-line problem, found before a bone is checked. The flag raises the cap,
/// for every request that carries a rig.
#[test]
fn a_rig_over_the_bone_cap_is_refused_before_it_is_built() {
    let s = start(&["--max-body-bytes", "16000000"]);
    let text = chain_toml(100_000);
    let a = s.post_raw("/api/rig/parse", "application/toml", text.as_bytes());
    assert_eq!(a.status, 200, "{}", a.text());
    assert_eq!(a.json(), json!({"problem": "rig file: bones: 100000 bones exceed the cap of 256 (--max-bones)"}));
    s.assert_healthy();
    let s = start(&["--max-bones", "300"]);
    let a = s.post_raw("/api/rig/parse", "application/toml", chain_toml(300).as_bytes());
    assert_eq!(a.json()["rig"]["bones"].as_array().unwrap().len(), 300, "{}", a.text());
    let a = s.post_raw("/api/rig/parse", "application/toml", chain_toml(301).as_bytes());
    assert_eq!(a.json()["problem"], "rig file: bones: 301 bones exceed the cap of 300 (--max-bones)");
    let bones: Vec<Value> = (0..301)
        .map(|i| json!({"name": format!("b{i}"), "length": 1.0, "parent": (i > 0).then(|| format!("b{}", i - 1))}))
        .collect();
    let mut rig = json!({"bones": bones});
    for path in ["/api/solve", "/api/animate", "/api/render"] {
        let body = json!({"rig": rig, "goals": [{"bone": "b299", "x": 1, "y": 1}], "figure": "rig"});
        let mut body = body.as_object().unwrap().clone();
        if path != "/api/render" {
            body.remove("figure");
        }
        let e = s.post(path, &Value::Object(body)).error(422);
        assert_eq!(e, "rig: bones: 301 bones exceed the cap of 300 (--max-bones)", "{path}");
    }
    let e = s.post("/api/track", &json!({"rig": rig, "effector": "b299", "line": [0, 0, 1, 1]})).error(422);
    assert_eq!(e, "rig: bones: 301 bones exceed the cap of 300 (--max-bones)");
    rig["bones"].as_array_mut().unwrap().pop();
    let a = s.post("/api/solve", &json!({"rig": rig, "goals": [{"bone": "b299", "x": 1, "y": 1}]}));
    assert_eq!(a.status, 200, "{}", a.text());
}
