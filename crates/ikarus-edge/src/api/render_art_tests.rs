//! Figure `motion` of `POST /api/render` with a character and its atlas: spineboy's front foot
//! keyed over its `walk`, drawn with its art as the command line draws it (the edge's
//! `motion_art`), alone with `art_only`; the refusals, one line each.

use base64::Engine;
use ikarus::Interrupt;
use serde_json::{Value, json};

use super::super::{Endpoint, Limits, Problem, call, status};
use crate::character::art_draw::AtlasArt;
use crate::character::motion::Motion;
use crate::character::motion_art::{art_drawing, posed_with_art};
use crate::picture::{PictureFormat, draw};

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
const ATLAS: &str = include_str!("../../../../examples/characters/spineboy.atlas");
const PNG: &[u8] = include_bytes!("../../../../examples/characters/spineboy.png");
const RAPTOR_ATLAS: &str = include_str!("../../../../examples/characters/raptor.atlas");
const RAPTOR_PNG: &[u8] = include_bytes!("../../../../examples/characters/raptor.png");
const SIDE: u32 = 160;

fn ask(endpoint: Endpoint, body: &Value) -> Result<Vec<u8>, Problem> {
    call(endpoint, body.to_string().as_bytes(), &Limits::default(), &Interrupt::new()).map(|r| r.body)
}

/// The id of `atlas` sent to `/api/atlas/parse`, with its page `png` named `page` when given.
fn atlas_id(atlas: &str, page: Option<(&str, &[u8])>) -> Value {
    let mut body = json!({ "atlas": atlas });
    if let Some((name, png)) = page {
        body["pages"] = json!({ name: base64::engine::general_purpose::STANDARD.encode(png) });
    }
    let answer: Value = serde_json::from_slice(&ask(Endpoint::AtlasParse, &body).unwrap()).unwrap();
    answer["id"].clone()
}

/// Spineboy's front foot keyed up and forward over 0.2 s of its walk, at 20 fps: 5 frames.
fn keys() -> Value {
    let key = |t: f64, x: f64, y: f64| json!({ "time": t, "x": x, "y": y });
    json!({ "fps": 20, "tracks": { "front-leg-target": [key(0.0, 0.0, 0.0), key(0.2, 40.0, 30.0)] } })
}

fn body(atlas: &Value) -> Value {
    json!({
        "figure": "motion", "format": "gif", "rig": SPINEBOY, "keys": keys(), "animation": "walk",
        "atlas": atlas, "width": SIDE, "height": SIDE,
    })
}

/// The GIF's number of frames, and whether its first frame (whole) leaves many pixels
/// transparent.
fn frames_and_clear(gif: &[u8]) -> (usize, bool) {
    let mut decoder = gif::DecodeOptions::new().read_info(gif).unwrap();
    let (mut frames, mut whole_transparent) = (0, false);
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        if frames == 0 {
            let clear = frame.transparent;
            whole_transparent = clear.is_some_and(|t| frame.buffer.iter().filter(|&&i| i == t).count() > 1000);
        }
        frames += 1;
    }
    (frames, whole_transparent)
}

/// The server's GIF is the one the edge's motion art draws for the same motion (the command
/// line's path): the same frames, the same bytes; under the bones or alone.
#[test]
fn the_servers_motion_gif_with_art_is_the_edges() {
    let id = atlas_id(ATLAS, Some(("spineboy.png", PNG)));
    let served = ask(Endpoint::Render, &body(&id)).unwrap();
    let mut alone = body(&id);
    alone["art_only"] = json!(true);
    let served_alone = ask(Endpoint::Render, &alone).unwrap();

    let loaded = crate::character::load(SPINEBOY, "spineboy").unwrap();
    let keys = crate::keys::KeysFile::parse(&keys().to_string()).unwrap();
    let (course, fps) = crate::character::motion::keyed(&loaded, &keys, Some("walk".into()), 1000, "cap").unwrap();
    let motion = Motion::new(&loaded, course, fps).unwrap();
    let atlas = AtlasArt::read(ATLAS, "atlas", &mut |_| Ok(PNG.to_vec())).unwrap();
    let expect = |placement| {
        let drawn = posed_with_art(&motion, &atlas).unwrap();
        assert_eq!(drawn.arts.len(), 5);
        let drawing = art_drawing(&motion, &drawn.poses, drawn.arts, placement);
        draw(&drawing, PictureFormat::Gif, SIDE, SIDE, &|_, _| {}).unwrap()
    };
    assert_eq!(served, expect(ikarus_render::ArtPlacement::UnderBones));
    assert_eq!(served_alone, expect(ikarus_render::ArtPlacement::Alone));

    // Five frames, the first whole; the background transparent alone, opaque under the bones.
    assert_eq!(frames_and_clear(&served), (5, false));
    assert_eq!(frames_and_clear(&served_alone), (5, true));
}

#[test]
fn refusals_name_the_field_in_one_line() {
    let refused = |body: Value, code: u16| {
        let e = ask(Endpoint::Render, &body).unwrap_err();
        assert_eq!(e.status, code, "{}", e.message);
        assert!(!e.message.contains('\n'), "{}", e.message);
        e.message
    };
    let invalid = status::UNPROCESSABLE_ENTITY;
    let without_images = atlas_id(ATLAS, None);
    assert_eq!(
        refused(body(&without_images), invalid),
        "atlas: sent without its page images (spineboy.png): send them to /api/atlas/parse as \"pages\" to draw the art"
    );
    let mut art_only = body(&Value::Null);
    art_only["art_only"] = json!(true);
    assert!(refused(art_only, invalid).starts_with("art_only: draws a character's art: give its atlas"));
    let m = refused(body(&json!("a0123")), status::NOT_FOUND);
    assert!(m.starts_with("atlas: no atlas \"a0123\" on the server"), "{m}");
    // Another character's atlas lacks the regions spineboy draws.
    let raptor = atlas_id(RAPTOR_ATLAS, Some(("raptor.png", RAPTOR_PNG)));
    let m = refused(body(&raptor), invalid);
    assert!(m.starts_with("atlas: the atlas has no region") && m.contains("slot"), "{m}");
    let spineboy = atlas_id(ATLAS, Some(("spineboy.png", PNG)));
    let mut skin = body(&spineboy);
    skin["skin"] = json!("gold");
    let m = refused(skin, invalid);
    assert!(m.starts_with("skin \"gold\": no such skin"), "{m}");
    // The server's GIF cap holds before any frame is posed.
    let mut huge = body(&spineboy);
    huge["width"] = json!(4096);
    huge["height"] = json!(4096);
    huge["keys"]["tracks"]["front-leg-target"][1]["time"] = json!(30.0);
    let m = refused(huge, invalid);
    assert!(m.contains("GIF") || m.contains("gif"), "{m}");
}
