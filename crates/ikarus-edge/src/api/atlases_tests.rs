use base64::Engine;
use ikarus::Interrupt;
use serde_json::{Value, json};

use super::super::{Endpoint, Limits, call, status};
use super::*;

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
const ATLAS: &str = include_str!("../../../../examples/characters/spineboy.atlas");
const PNG: &[u8] = include_bytes!("../../../../examples/characters/spineboy.png");

fn b64(bytes: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

fn ask(endpoint: Endpoint, body: &Value) -> Result<Value, super::Problem> {
    let reply = call(endpoint, body.to_string().as_bytes(), &Limits::default(), &Interrupt::new())?;
    Ok(serde_json::from_slice(&reply.body).unwrap())
}

/// A PNG's first 24 bytes claiming `w` × `h` pixels (nothing after the header).
fn header(w: u32, h: u32) -> Vec<u8> {
    let mut b = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
    b.extend_from_slice(&w.to_be_bytes());
    b.extend_from_slice(&h.to_be_bytes());
    b.extend_from_slice(&[8, 6, 0, 0, 0]);
    b
}

#[test]
fn an_atlas_alone_is_kept_with_its_pages_listed_and_without_images() {
    let a = ask(Endpoint::AtlasParse, &json!({ "atlas": ATLAS })).unwrap();
    let id = a["id"].as_str().unwrap();
    assert!(id.starts_with('a') && id.len() == 25, "{id}");
    assert_eq!(
        a["pages"],
        json!([{"file": "spineboy.png", "width": 1024, "height": 256, "pma": false, "image": false}])
    );
    assert_eq!(a["regions"], 40, "spineboy.atlas lists 40 regions");
    let kept = stored_atlas(id).unwrap();
    assert!(!kept.images && kept.art.pages.is_empty());
    // The same atlas again: the same id.
    assert_eq!(ask(Endpoint::AtlasParse, &json!({ "atlas": ATLAS })).unwrap()["id"], a["id"]);
}

#[test]
fn an_atlas_with_its_images_has_them_decoded_under_another_id() {
    let alone = ask(Endpoint::AtlasParse, &json!({ "atlas": ATLAS })).unwrap();
    let a = ask(Endpoint::AtlasParse, &json!({ "atlas": ATLAS, "pages": { "spineboy.png": b64(PNG) } })).unwrap();
    assert_ne!(a["id"], alone["id"]);
    assert_eq!(a["pages"][0]["image"], true);
    let kept = stored_atlas(a["id"].as_str().unwrap()).unwrap();
    assert!(kept.images);
    assert_eq!((kept.art.pages[0].width, kept.art.pages[0].height), (1024, 256));
    assert_eq!(kept.bytes(), ATLAS.len() + 1024 * 256 * 4);
}

#[test]
fn page_images_are_refused_naming_the_page_before_anything_is_decoded() {
    let refused = |pages: Value| {
        let e = ask(Endpoint::AtlasParse, &json!({ "atlas": ATLAS, "pages": pages })).unwrap_err();
        assert_eq!(e.status, status::UNPROCESSABLE_ENTITY, "{}", e.message);
        e.message
    };
    let m = refused(json!({ "spineboy.png": b64(PNG), "other.png": b64(PNG) }));
    assert_eq!(m, "pages.\"other.png\": the atlas names no such page; it names \"spineboy.png\"");
    let m = refused(json!({}));
    assert!(m.starts_with("pages: the atlas's page \"spineboy.png\" is missing"), "{m}");
    let m = refused(json!({ "spineboy.png": "not base64!" }));
    assert!(m.starts_with("pages.\"spineboy.png\": not base64"), "{m}");
    let m = refused(json!({ "spineboy.png": b64(b"GIF89a, not a PNG at all") }));
    assert_eq!(m, "pages.\"spineboy.png\": not a PNG image");
    // A header claiming a huge image is refused from the header alone.
    let m = refused(json!({ "spineboy.png": b64(&header(4097, 16)) }));
    assert_eq!(m, "pages.\"spineboy.png\": 4097×16 pixels; a page's sides must be between 1 and 4096 pixels");
    // A header within the caps but no image after it: the decoder's refusal, naming the page.
    let m = refused(json!({ "spineboy.png": b64(&header(16, 16)) }));
    assert!(m.starts_with("atlas: page 0 ") && m.contains("spineboy.png"), "{m}");
}

#[test]
fn an_atlas_whose_pages_together_pass_the_pixel_cap_is_refused_at_the_page_that_passes_it() {
    let atlas =
        "a.png\nsize: 4096, 4096\nr\nbounds: 0, 0, 1, 1\n\nb.png\nsize: 4096, 4096\n\nc.png\nsize: 4096, 4096\n";
    let pages = json!({ "a.png": b64(&header(4096, 4096)), "b.png": b64(&header(4096, 4096)), "c.png": b64(&header(4096, 4096)) });
    let e = ask(Endpoint::AtlasParse, &json!({ "atlas": atlas, "pages": pages })).unwrap_err();
    assert_eq!(e.message, "pages: more than 33554432 pixels of page images in one atlas (at page \"c.png\")");
}

#[test]
fn a_bad_atlas_and_an_unknown_id_are_refused_naming_atlas() {
    let e = ask(Endpoint::AtlasParse, &json!({ "atlas": "spineboy.png\nsize: 10\n" })).unwrap_err();
    assert!(e.message.starts_with("atlas: "), "{}", e.message);
    let e = ask(Endpoint::Pose, &json!({ "rig": SPINEBOY, "atlas": "a0" })).unwrap_err();
    assert_eq!(e.status, status::NOT_FOUND);
    assert!(e.message.starts_with("atlas: no atlas \"a0\" on the server"), "{}", e.message);
}

/// `/api/pose` with an atlas answers the library's drawing of the same pose, number for number,
/// and the same bones as without it.
#[test]
fn a_pose_with_an_atlas_answers_its_drawing_as_the_library_draws_it() {
    let id = ask(Endpoint::AtlasParse, &json!({ "atlas": ATLAS })).unwrap()["id"].clone();
    let body = json!({ "rig": SPINEBOY, "animation": "walk", "time": 0.4, "physics": false });
    let plain = ask(Endpoint::Pose, &body).unwrap();
    let mut with = body.clone();
    with["atlas"] = id;
    let drawn = ask(Endpoint::Pose, &with).unwrap();
    assert_eq!(drawn["bones"], plain["bones"]);
    assert!(plain.get("art").is_none());

    let loaded = crate::character::load(SPINEBOY, "spineboy").unwrap();
    let c = &loaded.character;
    let ask = crate::pose::PoseAsk {
        animation: Some("walk".into()),
        time: Some(0.4),
        physics: crate::pose::PhysicsAsk::Off,
        ..crate::pose::PoseAsk::default()
    };
    let mut posed = ikarus::character::Posed::default();
    crate::pose::pose_kept(&loaded, &ask, &mut posed).unwrap();
    let regions = crate::character::atlas::read(ATLAS).unwrap().lookup();
    let mut list = ikarus::character::DrawList::default();
    let walk = c.clip_index("walk").unwrap();
    c.draw_list_at(&posed, c.default_skin(), Some((walk, 0.4)), &regions, &mut list).unwrap();

    let art = &drawn["art"];
    assert_eq!(art["pages"], json!(["spineboy.png"]));
    let slots = art["slots"].as_array().unwrap();
    assert_eq!(slots.len(), list.items.len());
    assert!(slots.len() > 15, "spineboy draws most of its slots: {}", slots.len());
    for (s, item) in slots.iter().zip(&list.items) {
        assert_eq!(s["slot"], c.art().slots[item.slot].name.as_str());
        let v: Vec<f64> = serde_json::from_value(s["vertices"].clone()).unwrap();
        let want: Vec<f64> = list.vertices[item.vertices.clone()].iter().flatten().copied().collect();
        assert_eq!(v, want, "slot {}", s["slot"]);
        let uv: Vec<f64> = serde_json::from_value(s["uvs"].clone()).unwrap();
        assert_eq!(uv.len(), v.len());
        assert!(uv.iter().all(|u| (0.0..=1.0).contains(u)));
        let t: Vec<u32> = serde_json::from_value(s["triangles"].clone()).unwrap();
        assert!(t.len() % 3 == 0 && t.iter().all(|&i| (i as usize) < v.len() / 2));
        assert_eq!(s["blend"], "normal");
        assert_eq!(s["page"], 0);
    }
    let head = slots.iter().find(|s| s["slot"] == "head").unwrap();
    assert_eq!(head["attachment"], "head");
    assert_eq!(head["color"], json!([1.0, 1.0, 1.0, 1.0]));
}

#[test]
fn a_region_the_atlas_lacks_is_refused_naming_it_and_its_slot() {
    let atlas = "spineboy.png\nsize: 1024, 256\ncrosshair\nbounds: 352, 7, 45, 45\n";
    let id = ask(Endpoint::AtlasParse, &json!({ "atlas": atlas })).unwrap()["id"].clone();
    let e = ask(Endpoint::Pose, &json!({ "rig": SPINEBOY, "atlas": id })).unwrap_err();
    assert_eq!(e.status, status::UNPROCESSABLE_ENTITY);
    assert!(e.message.starts_with("atlas: the atlas has no region \""), "{}", e.message);
    assert!(e.message.contains("(slot \""), "{}", e.message);
}
