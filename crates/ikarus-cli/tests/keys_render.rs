//! `POST /api/render` with figure `motion`, a rig and its `keys`: the keyed motion drawn as
//! `ikarus render motion --rig FILE --keys KEYS.json --out FILE` draws it, byte for byte, and
//! the fields that keys replace refused, naming them.

mod common;
#[path = "common/rigs.rs"]
mod rigs;

use serde_json::{Value, json};

const WALK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/keys/puppet-walk.json");

fn walk() -> Value {
    serde_json::from_str(&std::fs::read_to_string(WALK).unwrap()).unwrap()
}

#[test]
fn the_api_draws_the_keyed_walk_as_the_command_line_does() {
    let dir = std::env::temp_dir().join(format!("ikarus-keys-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let puppet = rigs::path("puppet").to_str().unwrap().to_owned();
    let s = common::server::start(&[]);
    for format in ["gif", "svg"] {
        let out = dir.join(format!("walk.{format}"));
        let args =
            ["render", "motion", "--rig", &puppet, "--keys", WALK, "--limits", "--width", "240", "--height", "200"];
        common::succeeds(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
        let cli = std::fs::read(&out).unwrap();
        let body = json!({"figure": "motion", "format": format, "width": 240, "height": 200,
            "rig": rigs::json("puppet"), "keys": walk(), "options": {"limits": true}});
        let api = s.post("/api/render", &body);
        assert_eq!(api.status, 200, "{format}: {}", api.text());
        assert!(cli.len() > 1000, "{format}: {} bytes", cli.len());
        assert!(
            api.body == cli,
            "{format}: the API's {} bytes differ from the command line's {}",
            api.body.len(),
            cli.len()
        );
    }
    // 28 frames: a GIF animates them (a GIF's frames each start with an image descriptor).
    let gif = std::fs::read(dir.join("walk.gif")).unwrap();
    assert_eq!(&gif[..6], b"GIF89a");
}

#[test]
fn what_keys_replace_is_refused_naming_the_field() {
    let s = common::server::start(&[]);
    let rig = rigs::json("puppet");
    let with = |extra: Value| {
        let mut body = json!({"figure": "motion", "rig": rig, "keys": walk()});
        body.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        s.post("/api/render", &body).error(422)
    };
    let not = |name: &str| {
        format!(
            "{name}: not with keys (the keys give the targets, pins, bends and fps; the motion starts at the rig's start pose)"
        )
    };
    assert_eq!(with(json!({"goal": {"x": 1, "y": 0}})), not("goal"));
    assert_eq!(with(json!({"fps": 10})), not("fps"));
    assert_eq!(with(json!({"workspace": true})), not("workspace"));
    assert_eq!(with(json!({"keys": null})), "rig: the figure motion draws a rig's keyed motion: give its keys");
    let bad = with(json!({"keys": {"tracks": {"left_foot": [{"time": 0, "x": "a", "y": 0}]}}}));
    assert!(bad.contains("keys.tracks"), "{bad}");
    let unknown = with(json!({"keys": {"tracks": {"nose": [{"time": 0, "x": 0, "y": 0}]}}}));
    assert!(unknown.starts_with("keys.tracks.nose"), "{unknown}");
    let too_big = with(json!({"format": "gif", "width": 4096, "height": 4096}));
    assert!(too_big.contains("more than the cap"), "{too_big}");
}
