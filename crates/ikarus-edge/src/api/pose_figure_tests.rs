use std::path::Path;

use base64::Engine;
use ikarus::Interrupt;
use ikarus::character::{DrawList, Posed};
use serde_json::{Value, json};

use super::super::{Endpoint, Limits, Problem, call, status};

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
const ATLAS: &str = include_str!("../../../../examples/characters/spineboy.atlas");
const PNG: &[u8] = include_bytes!("../../../../examples/characters/spineboy.png");

fn ask(endpoint: Endpoint, body: &Value) -> Result<Vec<u8>, Problem> {
    call(endpoint, body.to_string().as_bytes(), &Limits::default(), &Interrupt::new()).map(|r| r.body)
}

fn atlas_id(pages: bool) -> Value {
    let body = if pages {
        json!({ "atlas": ATLAS, "pages": { "spineboy.png": base64::engine::general_purpose::STANDARD.encode(PNG) } })
    } else {
        json!({ "atlas": ATLAS })
    };
    let answer: Value = serde_json::from_slice(&ask(Endpoint::AtlasParse, &body).unwrap()).unwrap();
    answer["id"].clone()
}

/// The server's picture of a pose with its art is the command line's, byte for byte: the same
/// pose, the same drawing, the same encoder.
#[test]
fn the_servers_art_picture_is_the_command_lines() {
    let body = json!({
        "figure": "pose", "rig": SPINEBOY, "animation": "walk", "time": 0.4, "physics": false,
        "targets": [{ "bone": "front-leg-target", "x": 60, "y": 20 }],
        "atlas": atlas_id(true), "width": 300, "height": 300,
    });
    let mut art_only = body.clone();
    art_only["art_only"] = json!(true);
    let served = ask(Endpoint::Render, &art_only).unwrap();
    let with_bones = ask(Endpoint::Render, &body).unwrap();
    assert_ne!(served, with_bones, "the bones are drawn over the art unless art_only");

    let loaded = crate::character::load(SPINEBOY, "spineboy").unwrap();
    let c = &loaded.character;
    let pose_ask = crate::pose::PoseAsk {
        animation: Some("walk".into()),
        time: Some(0.4),
        targets: vec![("front-leg-target".into(), [60.0, 20.0])],
        physics: crate::pose::PhysicsAsk::Off,
        ..crate::pose::PoseAsk::default()
    };
    let mut posed = Posed::default();
    crate::pose::pose_kept(&loaded, &pose_ask, &mut posed).unwrap();
    let atlas = crate::character::art_draw::AtlasArt::read_file(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/characters/spineboy.atlas"),
    )
    .unwrap();
    let walk = c.clip_index("walk").unwrap();
    let art = atlas.art(c, &posed, (c.default_skin(), Some((walk, 0.4))), &mut DrawList::default()).unwrap();
    assert_eq!(served, ikarus_render::art_only_png(&art, 300, 300).unwrap());
}

#[test]
fn a_pose_without_an_atlas_is_drawn_as_bones_and_the_art_needs_the_images() {
    let png =
        ask(Endpoint::Render, &json!({ "figure": "pose", "rig": SPINEBOY, "width": 200, "height": 200 })).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let svg = ask(Endpoint::Render, &json!({ "figure": "pose", "rig": SPINEBOY, "format": "svg" })).unwrap();
    assert!(String::from_utf8(svg).unwrap().starts_with("<svg"));

    let refused = |body: Value| {
        let e = ask(Endpoint::Render, &body).unwrap_err();
        assert_eq!(e.status, status::UNPROCESSABLE_ENTITY, "{}", e.message);
        e.message
    };
    let m = refused(json!({ "figure": "pose", "rig": SPINEBOY, "atlas": atlas_id(false) }));
    assert_eq!(
        m,
        "atlas: sent without its page images (spineboy.png): send them to /api/atlas/parse as \"pages\" to draw the art"
    );
    let m = refused(json!({ "figure": "pose", "rig": SPINEBOY, "art_only": true }));
    assert!(m.starts_with("art_only: draws a character's art"), "{m}");
    let m = refused(json!({ "figure": "pose", "rig": SPINEBOY, "format": "gif" }));
    assert!(m.starts_with("format = gif: only the figure motion animates"), "{m}");
    let m = refused(json!({ "figure": "pose", "rig": SPINEBOY, "goal": [1, 2] }));
    assert!(m.contains("unknown field `goal`"), "{m}");
}
