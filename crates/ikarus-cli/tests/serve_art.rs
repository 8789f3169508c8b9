//! The character's art over HTTP: `POST /api/atlas/parse` (an atlas and its page images, JSON,
//! under `--max-file-bytes` rather than `--max-body-bytes`), `/api/pose` with `"atlas"` (the
//! pose's drawing) and `/api/render` figure `pose` (the picture, as `ikarus pose --atlas` draws
//! it, byte for byte).

mod common;

use common::server::start;
use common::{b64, ikarus, stdout};
use serde_json::{Value, json};

const JSON: &str = "../../examples/characters/spine-spineboy-pro.json";
const ATLAS: &str = "../../examples/characters/spineboy.atlas";
const PAGE: &str = "../../examples/characters/spineboy.png";

fn atlas_body() -> Value {
    let page = std::fs::read(PAGE).unwrap();
    json!({ "atlas": std::fs::read_to_string(ATLAS).unwrap(), "pages": { "spineboy.png": b64(&page) } })
}

#[test]
fn an_atlas_with_its_images_is_a_file_under_the_file_cap() {
    // The body (the page's 245 kB as base64) is over --max-body-bytes but under --max-file-bytes.
    let s = start(&["--max-body-bytes", "100000"]);
    let answer = s.post("/api/atlas/parse", &atlas_body());
    assert_eq!(answer.status, 200, "{}", answer.text());
    assert_eq!(answer.json()["pages"][0]["image"], true);
    let small = start(&["--max-file-bytes", "100000"]);
    let answer = small.post("/api/atlas/parse", &atlas_body());
    assert_eq!(answer.status, 413, "{}", answer.text());
    assert!(answer.text().contains("--max-file-bytes"), "{}", answer.text());
    let answer = s.post_raw("/api/atlas/parse", "application/toml", b"{}");
    assert_eq!(answer.status, 415, "{}", answer.text());
}

#[test]
fn the_servers_picture_of_a_pose_with_its_art_is_the_command_lines() {
    let s = start(&[]);
    let id = s.post("/api/atlas/parse", &atlas_body()).json()["id"].clone();
    let character = s.post_raw("/api/rig/parse", "application/toml", std::fs::read(JSON).unwrap().as_slice()).json();
    let pose = json!({
        "character": character["character"]["id"], "animation": "walk", "time": 0.4, "physics": false, "atlas": id,
        "targets": [{ "bone": "front-leg-target", "x": 60, "y": 20 }],
    });
    let answer = s.post("/api/pose", &pose);
    assert_eq!(answer.status, 200, "{}", answer.text());
    let slots = answer.json()["art"]["slots"].as_array().unwrap().len();
    assert!(slots > 15, "{slots} slots drawn");

    let mut picture = pose.clone();
    picture["figure"] = json!("pose");
    picture["art_only"] = json!(true);
    picture["width"] = json!(320);
    picture["height"] = json!(240);
    let served = s.post("/api/render", &picture);
    assert_eq!(served.status, 200, "{}", served.text());
    let out = std::env::temp_dir().join(format!("ikarus-serve-art-{}.png", std::process::id()));
    let o = ikarus(&[
        "pose",
        "--rig",
        JSON,
        "--atlas",
        ATLAS,
        "--animation",
        "walk",
        "--time",
        "0.4",
        "--physics",
        "off",
        "--target",
        "front-leg-target=60,20",
        "--art-only",
        "--width",
        "320",
        "--height",
        "240",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stdout(&o));
    assert_eq!(served.body, std::fs::read(&out).unwrap(), "the same picture, byte for byte");
    let _ = std::fs::remove_file(out);
}
