//! Arms take keys: `ikarus animate --keys KEYS.json` with the built-in seed arm (or `--arm
//! FILE`) and `POST /api/animate` with `keys` (and `arm`) solve the arm as its one-branch rig,
//! bones `link0`, `link1`, …; the command line and the API answer the same bits.

mod common;

use common::same_bits;
use serde_json::{Value, json};

/// A 3-key track on the seed arm's tip (links 3, 2, 1 long), every target in reach.
fn keys() -> Value {
    json!({"fps": 10, "tracks": {"link2": [
        {"time": 0, "x": 4.0, "y": 2.0},
        {"time": 0.5, "x": 2.0, "y": 4.0, "ease": "linear"},
        {"time": 1.0, "x": -1.0, "y": 3.5}]}})
}

#[test]
fn the_seed_arm_keyed_answers_the_same_bits_through_the_command_line_and_the_api() {
    let file = common::temp_file("keys-arm", "arm.json", &keys().to_string());
    let cli = common::json(&["animate", "--keys", &file, "--format", "json"]);
    let frames = cli["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 11);
    for (k, key) in [(0, [4.0, 2.0]), (5, [2.0, 4.0]), (10, [-1.0, 3.5])] {
        let tip = &frames[k]["joints"]["link2"];
        let d = (tip[0].as_f64().unwrap() - key[0]).hypot(tip[1].as_f64().unwrap() - key[1]);
        assert!(d < 1e-3, "frame {k}: the tip {tip} is {d} from the key {key:?}");
        assert_eq!(frames[k]["status"], "reached", "frame {k}");
    }
    let s = common::server::start(&[]);
    let api = s.post("/api/animate", &json!({"keys": keys()}));
    assert_eq!(api.status, 200, "{}", api.text());
    same_bits(&cli, &api.json(), "answer");
    // An arm file given, as a request's `arm`: the same arm, the same bits.
    let seed = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/arms/seed.toml");
    let with_arm = common::json(&["animate", "--arm", seed, "--keys", &file, "--format", "json"]);
    same_bits(&cli["frames"], &with_arm["frames"], "--arm seed.toml");
    // An arm's goal is refused beside keys, naming it.
    let a = s.post("/api/animate", &json!({"keys": keys(), "goal": {"x": 1, "y": 1}}));
    assert!(a.error(422).starts_with("goal: not with keys"));
}
