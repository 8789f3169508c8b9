//! Characters on the server under hostile files: reading a file runs on the pool (the runtime's
//! threads stay free for `/api/health`), a character job is costed from its file (heavy ones in
//! the long lane) and stops at its deadline, freeing its worker.
//!
//! The only wall-clock bounds are generous "it answers at all" bounds, where a hang is the bug:
//! before these fixes each guarded event took minutes.

mod common;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

use common::server::{Answer, Server};
use serde_json::{Value, json};

/// How long a test waits for an event before it calls it a hang (never a measure of speed).
const HANG: Duration = Duration::from_secs(120);

fn start(args: &[&str]) -> Server {
    let args: Vec<&str> = ["--max-iterations", "100000000"].iter().chain(args).copied().collect();
    Server::start(&args, Some(HANG))
}

/// A Spine chain of 256 bones with 1,024 one-bone IK constraints (4 a bone, the most a file may
/// have), four on each bone but the root, each aiming its bone at the root: every constraint's
/// update recomputes the bones below its own (130,000 bone updates a pose), and ikarus's rules
/// solve 255 joints toward 255 goals at once.
fn heavy_chain() -> String {
    let mut bones = vec![json!({"name": "b0"})];
    bones.extend(
        (1..256).map(|i| json!({"name": format!("b{i}"), "parent": format!("b{}", i - 1), "length": 1, "x": 1})),
    );
    let ik: Vec<Value> = (0..1024)
        .map(|i| json!({"name": format!("k{i}"), "bones": [format!("b{}", 1 + i % 255)], "target": "b0", "order": i}))
        .collect();
    json!({"skeleton": {"spine": "4.2"}, "bones": bones, "ik": ik}).to_string()
}

/// The heaviest motion of the heavy chain the caps allow: 781 frames (frames × bones within
/// 200,000), each posed by ikarus's solver.
fn heavy_animate() -> Value {
    json!({"rig": heavy_chain(), "targets": [{"bone": "b255", "x": 3, "y": 4}], "duration": 26, "fps": 30, "ik": "ikarus"})
}

/// A solve whose worst case is long (10⁸ iterations) but that reaches its goal at once: it runs
/// in the long lane, and answers as soon as it has a long worker.
fn long_but_brief_solve() -> Value {
    json!({ "goal": { "x": 2.0, "y": 3.0 }, "options": { "max_iterations": 100_000_000 } })
}

/// A 64-link arm whose joints may turn by 1° only and a goal out of its limited reach, every
/// attempt run to its 10⁸-iteration cap (`serve_limits.rs`'s): hours.
fn endless_solve() -> Value {
    let link = json!({ "length": 0.1, "angle_deg": 0.0, "limits_deg": [-1.0, 1.0] });
    json!({
        "arm": { "links": vec![link; 64] },
        "goal": { "x": -3.0, "y": -1.0 },
        "options": {
            "limits": true, "restarts": 64, "backtrack": 0, "max_iterations": 100_000_000,
            "stall_window": 4294967295u64, "tolerance": 5e-324, "gain": 1e-9
        }
    })
}

/// Sends a POST on a raw connection, without reading the answer.
fn send_raw(s: &Server, path: &str, content_type: &str, body: &[u8]) -> TcpStream {
    let mut c = TcpStream::connect(&s.addr).unwrap();
    write!(
        c,
        "POST {path} HTTP/1.1\r\nHost: localhost\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\n\r\n",
        body.len()
    )
    .unwrap();
    c.write_all(body).unwrap();
    c
}

/// Polls a brief request of the long lane until it is answered 200 (the long worker is free);
/// a hang after [`HANG`].
fn long_lane_frees(s: &Server) {
    let began = Instant::now();
    loop {
        let a = s.post("/api/solve", &long_but_brief_solve());
        if a.status == 200 {
            return;
        }
        assert_eq!(a.status, 503, "{}", a.text());
        assert!(began.elapsed() < HANG, "the long worker was not freed: {}", a.text());
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A character's motion far over its budget answers 503 naming the budget, and its worker is
/// free for the next long request. Before, character work never looked at its interrupt: the
/// client got 503 at the budget and the work ran on to its end (minutes here), holding the
/// only long worker, so every later long request was 503 too.
#[test]
fn a_character_motion_over_budget_answers_503_and_frees_its_worker() {
    let s = start(&["--workers", "2", "--long-workers", "1", "--request-budget-ms", "1500"]);
    let e = s.post("/api/animate", &heavy_animate()).error(503);
    assert!(e.contains("--request-budget-ms"), "{e}");
    long_lane_frees(&s);
    // A pose of it too (one pose, ikarus's rules with 64 goals on bones' tips besides).
    let goals: Vec<Value> =
        (0..64).map(|i| json!({"bone": format!("b{}", 4 * i + 3), "x": 3, "y": i, "bones": 2})).collect();
    let pose = json!({"rig": heavy_chain(), "ik": "ikarus", "goals": goals});
    let a = s.post("/api/pose", &pose);
    if a.status != 200 {
        let e = a.error(503);
        assert!(e.contains("--request-budget-ms"), "{e}");
    }
    long_lane_frees(&s);
}

/// With the only long worker held by endless work and no queue, a heavy character job is
/// turned away as long work (503 "server busy": it was costed from its file, where it was
/// costed as quick before), and a small character pose is still answered. (Without a queue no
/// request here ever waits: a brief one sent before the endless one arrives just runs.)
#[test]
fn a_heavy_character_job_is_long_and_a_small_pose_quick() {
    let s = start(&["--workers", "2", "--long-workers", "1", "--max-queued", "0"]);
    let endless = endless_solve().to_string();
    let mut held = send_raw(&s, "/api/solve", "application/json", endless.as_bytes());
    let began = Instant::now();
    loop {
        let a = s.post("/api/solve", &long_but_brief_solve());
        if a.status == 503 && a.text().contains("server busy") {
            break;
        }
        assert!(began.elapsed() < HANG, "the endless solve never filled the long lane: {}", a.text());
        // The endless one may have arrived while a brief one ran, and been turned away (no
        // queue): answered, it is sent again.
        held.set_read_timeout(Some(Duration::from_millis(20))).unwrap();
        if held.read(&mut [0u8; 1]).is_ok() {
            held = send_raw(&s, "/api/solve", "application/json", endless.as_bytes());
        }
    }
    let heavy_pose = json!({"rig": heavy_chain(), "ik": "ikarus"});
    for (path, body) in [("/api/animate", heavy_animate()), ("/api/pose", heavy_pose)] {
        let e = s.post(path, &body).error(503);
        // Turned away at admission by the long lane, not stopped after running as quick work
        // ("this one was stopped after … ms"), which is what a quick costing would give.
        assert!(e.contains("server busy") && e.contains("--max-queued"), "{path}: {e}");
    }
    let spineboy = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/characters/spine-spineboy-pro.json"
    ))
    .unwrap();
    let a = s.post("/api/pose", &json!({"rig": spineboy, "animation": "walk", "time": 0.3}));
    assert_eq!(a.status, 200, "{}", a.text());
}

/// 73,000 animations named "a" and one with 36,500 keys (1,047,500 bytes, under the 1 MiB
/// body cap) took 45–115 s to read, on the runtime's own threads: two such requests stopped
/// `/api/health` and every endpoint. The file is now read on the pool, refused at its second
/// "a", and the server answers its health check while such requests arrive.
#[test]
fn a_hostile_parse_is_refused_at_once_and_health_answers_meanwhile() {
    let mut text = String::from(r#"{"skeleton": {"spine": "4.2"}, "bones": [{"name": "root"}], "animations": {"#);
    for _ in 0..73_000 {
        text.push_str(r#""a":{},"#);
    }
    text.push_str(r#""a": {"bones": {"root": {"rotate": ["#);
    let keys: Vec<String> = (0..36_500).map(|k| format!(r#"{{"time":{}}}"#, k % 10)).collect();
    text.push_str(&keys.join(","));
    text.push_str("]}}}}}");
    assert!(text.len() > 900_000 && text.len() <= 1 << 20, "{} bytes", text.len());
    let s = Server::start(&[], Some(Duration::from_secs(30)));
    let _hostile: Vec<TcpStream> =
        (0..2).map(|_| send_raw(&s, "/api/rig/parse", "application/toml", text.as_bytes())).collect();
    s.assert_healthy();
    let a: Answer = s.post_raw("/api/rig/parse", "application/toml", text.as_bytes());
    assert_eq!(a.status, 200, "{}", a.text());
    let problem = a.json()["problem"].as_str().unwrap().to_owned();
    assert!(problem.contains(r#"animations: "a" is listed twice"#), "{problem}");
    s.assert_healthy();
}

const RAPTOR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/characters/spine-raptor-pro.json");

/// The raptor with its walk copied under sixteen more names, 2.0 MB: a real character past the
/// 1 MiB request cap.
fn big_raptor() -> String {
    let mut raptor: Value = serde_json::from_str(&std::fs::read_to_string(RAPTOR).unwrap()).unwrap();
    let animations = raptor["animations"].as_object_mut().unwrap();
    let walk = animations["walk"].clone();
    for i in 0..16 {
        animations.insert(format!("walk{i}"), walk.clone());
    }
    serde_json::to_string_pretty(&raptor).unwrap()
}

/// `/api/rig/parse` of a character answers its `id`; the file's text is read once, and each
/// pose of playback refers to it: a request of a few hundred bytes where it was the whole file
/// (the raptor's export, 1.91 MB, was over the 1 MiB request cap and could not be opened).
#[test]
fn a_character_is_read_once_and_posed_by_its_id() {
    let s = start(&[]);
    // The raptor's export, made with the command line, opens.
    let dir = tempfile::tempdir().unwrap();
    let export = dir.path().join("raptor-export.json");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_ikarus"))
        .args(["animate", "--rig", RAPTOR, "--target", "front-leg-target=300,20", "--format", "spine", "--out"])
        .arg(&export)
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read(&export).unwrap();
    let a = s.post_raw("/api/rig/parse", "application/toml", &text);
    assert_eq!(a.status, 200, "{}", a.text());
    assert!(a.json()["character"]["id"].is_string(), "{}", a.text());
    // A character past the request cap opens too, and is posed by its id.
    let big = big_raptor();
    assert!(big.len() > 3 << 19, "{} bytes", big.len());
    let parsed = s.post_raw("/api/rig/parse", "application/toml", big.as_bytes());
    assert_eq!(parsed.status, 200, "{}", parsed.text());
    let id = parsed.json()["character"]["id"].as_str().unwrap().to_owned();
    let by_id = json!({"character": id, "animation": "walk7", "time": 0.4,
        "targets": [{"bone": "front-leg-target", "x": 300, "y": 20}]});
    assert!(by_id.to_string().len() < 1024, "{} bytes a pose", by_id.to_string().len());
    let a = s.post("/api/pose", &by_id);
    assert_eq!(a.status, 200, "{}", a.text());
    let by_text = s.post(
        "/api/pose",
        &json!({"rig": std::fs::read_to_string(RAPTOR).unwrap(), "animation": "walk", "time": 0.4,
            "targets": [{"bone": "front-leg-target", "x": 300, "y": 20}]}),
    );
    assert_eq!(a.json()["bones"], by_text.json()["bones"], "the same pose as from the file's text");
    // A motion by id, and its Spine export (the kept text is what it adds to).
    let motion = json!({"character": id, "targets": [{"bone": "front-leg-target", "x": 300, "y": 20}], "fps": 10});
    let a = s.post("/api/animate", &motion);
    assert_eq!(a.status, 200, "{}", a.text());
    // An id the server does not keep is a 404 naming the field; both or neither are refused.
    let e = s.post("/api/pose", &json!({"character": "c0123"})).error(404);
    assert!(e.starts_with("character: no character \"c0123\" on the server"), "{e}");
    let e = s.post("/api/pose", &json!({"character": id, "rig": "{}"})).error(422);
    assert!(e.starts_with("rig, character: give one"), "{e}");
    let e = s.post("/api/animate", &json!({"character": "nope", "targets": []})).error(404);
    assert!(e.starts_with("character: "), "{e}");
}
