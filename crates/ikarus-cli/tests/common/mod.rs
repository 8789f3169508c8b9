//! Running the `ikarus` binary from the integration tests, shared by `cli.rs`, `bench.rs` and
//! `pictures.rs` (each uses some of it).
#![allow(dead_code)]

pub mod server;

use std::process::{Command, Output};

use serde_json::Value;

/// Runs the binary with `args`.
pub fn ikarus(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ikarus")).args(args).output().expect("the binary runs")
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// Runs a command that must succeed without a word on stderr, and returns its stdout.
pub fn succeeds(args: &[&str]) -> String {
    let o = ikarus(args);
    assert!(o.status.success(), "{args:?} failed: {}", stderr(&o));
    assert!(stderr(&o).is_empty(), "{args:?} wrote to stderr: {}", stderr(&o));
    stdout(&o)
}

/// Runs a command that must succeed and print JSON.
pub fn json(args: &[&str]) -> Value {
    let out = succeeds(args);
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {out}"))
}

/// Runs a command that must fail with `code`, and returns its single line of stderr.
pub fn fails(args: &[&str], code: i32) -> String {
    let o = ikarus(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?} printed more than one line: {err}");
    assert!(err.starts_with("ikarus: "), "{err}");
    assert!(!err.contains("panicked") && !err.contains("RUST_BACKTRACE"), "{err}");
    assert!(o.stdout.is_empty(), "{args:?} printed data: {}", stdout(&o));
    err
}

/// A JSON pair of numbers as a point.
pub fn point(v: &Value) -> [f64; 2] {
    [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()]
}

/// The distance between two points.
pub fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Every number of `a` and `b` the same bits, everything else equal; `at` names the place in
/// the failure.
pub fn same_bits(a: &Value, b: &Value, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            assert_eq!(x.as_f64().unwrap().to_bits(), y.as_f64().unwrap().to_bits(), "{at}: {x} vs {y}")
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}");
            x.iter().zip(y).enumerate().for_each(|(i, (p, q))| same_bits(p, q, &format!("{at}[{i}]")));
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.keys().collect::<Vec<_>>(), y.keys().collect::<Vec<_>>(), "{at}");
            x.iter().for_each(|(k, p)| same_bits(p, &y[k], &format!("{at}.{k}")));
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

/// Writes `text` to `NAME` in a directory of this test process's own (`ikarus-test-TAG-PID`)
/// and gives its path.
pub fn temp_file(tag: &str, name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("ikarus-test-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

/// A JSON array of numbers.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// The checks every batch summary passes, a chain's or a rig's: the JSON's keys, `wall_s` > 0,
/// `solves_per_s = goals / wall_s`, and the stderr line's wall time and rate. The summary
/// JSON is returned for the caller's own checks.
#[allow(dead_code)]
pub fn batch_summary(summary_json: &std::path::Path, err: &str, goals: f64) -> Value {
    let s: Value = serde_json::from_str(&std::fs::read_to_string(summary_json).unwrap()).unwrap();
    let mut keys: Vec<&str> = s.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "goal_median_us",
            "goal_p99_us",
            "goals",
            "goals_timed_alone",
            "median_us",
            "method",
            "p99_us",
            "reached",
            "reached_percent",
            "solves_per_s",
            "threads",
            "wall_s"
        ]
    );
    // Each goal timed alone, on one thread: every goal up to 10,000.
    let alone = s["goals_timed_alone"].as_f64().unwrap();
    assert_eq!(alone, goals.min(10_000.0), "{s}");
    let (median, p99) = (s["goal_median_us"].as_f64().unwrap(), s["goal_p99_us"].as_f64().unwrap());
    assert!(median > 0.0 && p99 >= median, "{s}");
    assert!(
        err.contains(&format!("; each alone: median {median:.2} µs, p99 {p99:.2} µs ({alone} goals, 1 thread)")),
        "{err}"
    );
    let (wall, rate) = (s["wall_s"].as_f64().unwrap(), s["solves_per_s"].as_f64().unwrap());
    assert!(wall > 0.0 && wall < 60.0, "{s}");
    assert!((rate * wall / goals - 1.0).abs() < 1e-9, "solves_per_s is goals / wall_s: {s}");
    assert!(err.contains(" ms wall, ") && err.contains(" solves/s; each alone: "), "{err}");
    s
}

/// spineboy's file, the character of the keyed-character tests (`keys.rs`, `character_exports.rs`).
pub const SPINEBOY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/characters/spine-spineboy-pro.json");

/// spineboy's front foot target keyed over four keys (from where its setup pose has it).
pub fn spineboy_keys() -> Value {
    let o = ikarus(&["pose", "--rig", SPINEBOY, "--format", "json"]);
    assert!(o.status.success(), "pose spineboy: {}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let b = v["bones"].as_array().unwrap().iter().find(|b| b["name"] == "front-leg-target").unwrap().clone();
    let (x, y) = (b["x"].as_f64().unwrap(), b["y"].as_f64().unwrap());
    let key = |t: f64, dx: f64, dy: f64| serde_json::json!({"time": t, "x": x + dx, "y": y + dy});
    serde_json::json!({"fps": 30, "tracks": {"front-leg-target": [key(0.0, 0.0, 0.0), key(0.3, 40.0, 60.0), key(0.6, 80.0, 20.0), key(0.9, 20.0, 0.0)]}})
}

/// Standard base64 (RFC 4648, padded), written here so the test does not lean on the server's
/// own decoder's crate to make its input.
pub fn b64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(A[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}
