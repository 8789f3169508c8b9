//! End-to-end tests of `ikarus bench --characters`: the JSON's shape, every shipped character
//! present with its bone count and clip, the figures finite and positive, the text and
//! Markdown tables, and bad flags. No test asserts a time.

mod common;

use common::{fails, json, succeeds};

const FILES: [(&str, u64, &str); 5] = [
    ("spine-spineboy-pro.json", 67, "walk"),
    ("spine-raptor-pro.json", 76, "walk"),
    ("spine-stretchyman-pro.json", 55, "sneak"),
    ("spine-celestial-circus-pro.json", 60, "swing"),
    ("dragonbones-mecha_1406_ske.json", 17, "walk"),
];

#[test]
fn json_has_every_shipped_character_and_finite_positive_figures() {
    let v = json(&["bench", "--characters", "--poses", "20", "--json"]);
    let h = &v["header"];
    assert_eq!(h["command"], "ikarus bench --characters --poses 20 --json");
    assert_eq!((h["poses"].as_u64(), h["threads"].as_u64(), h["ik"].as_str()), (Some(20), Some(1), Some("runtime")));
    assert!((h["step_s"].as_f64().unwrap() - 1.0 / 60.0).abs() < 1e-15);
    let rows = v["characters"].as_array().unwrap();
    let files: Vec<(&str, u64, &str)> = rows
        .iter()
        .map(|r| (r["file"].as_str().unwrap(), r["bones"].as_u64().unwrap(), r["clip"].as_str().unwrap()))
        .collect();
    assert_eq!(files, FILES);
    for r in rows {
        for key in ["pose_us", "animated_pose_us", "p99_us", "pose_p99_us"] {
            let x = r[key].as_f64().unwrap_or_else(|| panic!("{key}: {r}"));
            assert!(x.is_finite() && x > 0.0, "{key}: {r}");
        }
        // A percentile is at least the median of the same times.
        assert!(r["pose_p99_us"].as_f64() >= r["pose_us"].as_f64(), "{r}");
        assert!(r["p99_us"].as_f64() >= r["animated_pose_us"].as_f64(), "{r}");
    }
}

#[test]
fn the_text_and_markdown_tables_have_a_line_per_character() {
    let text = succeeds(&["bench", "--characters", "--poses", "5"]);
    assert!(text.starts_with("ikarus bench --characters: 5 poses of each kind"), "{text}");
    assert!(text.contains("load average"), "{text}");
    for (file, bones, clip) in FILES {
        let line = text.lines().find(|l| l.contains(file)).unwrap_or_else(|| panic!("{file}: {text}"));
        let cells: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(cells.len(), 7, "{line}");
        assert_eq!((cells[1], cells[2]), (bones.to_string().as_str(), clip));
    }
    let md = succeeds(&["bench", "--characters", "--poses", "5", "--markdown"]);
    assert_eq!(md.lines().filter(|l| l.starts_with("| ")).count(), 2 + FILES.len(), "{md}");
}

#[test]
fn bad_flags_are_refused() {
    let err = fails(&["bench", "--characters", "--poses", "0"], 2);
    assert!(err.contains("--poses") && err.contains('0'), "{err}");
    let err = fails(&["bench", "--poses", "10"], 2);
    assert!(err.contains("--characters"), "{err}");
    let err = fails(&["bench", "--characters", "--rigs"], 2);
    assert!(err.contains("--rigs"), "{err}");
}
