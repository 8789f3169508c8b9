//! The drawn vertices against Spine's own renderer: each reference picture
//! (`tests/reference/render/`, spine-canvas 4.2, copied from `../shared/characters/reference/`)
//! fits the skeleton's bounds with its attachments at 90 % of 800 × 800, centred. The bounds of
//! ikarus's world vertices, fitted the same way, must hold the picture's opaque pixels: at most
//! one pixel beyond them (rounding), and at most 1 % of 720 pixels inside them (the images'
//! transparent edges are a few pixels).

use ikarus::character::{DrawList, PoseRequest, Posed};

fn read(path: &str) -> Vec<u8> {
    let path = format!("{}/{path}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The picture's opaque pixels' bounds: `[left, right, top, bottom]` (inclusive).
fn opaque(file: &str) -> [f64; 4] {
    let decoder = png::Decoder::new(std::io::Cursor::new(read(&format!("tests/reference/render/{file}"))));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.color_type, info.bit_depth), (png::ColorType::Rgba, png::BitDepth::Eight), "{file}");
    let (w, h) = (info.width as usize, info.height as usize);
    let mut b = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
    for y in 0..h {
        for x in 0..w {
            if buf[(y * w + x) * 4 + 3] > 0 {
                b = [b[0].min(x as f64), b[1].max(x as f64), b[2].min(y as f64), b[3].max(y as f64)];
            }
        }
    }
    b
}

#[test]
fn the_drawn_bounds_hold_spines_own_pictures_opaque_pixels() {
    for (skeleton, atlas, clip, picture) in [
        ("spine-spineboy-pro.json", "spineboy.atlas", None, "spineboy-setup.png"),
        ("spine-spineboy-pro.json", "spineboy.atlas", Some(("walk", 0.4)), "spineboy-walk-0.4.png"),
        ("spine-raptor-pro.json", "raptor.atlas", Some(("walk", 0.4)), "raptor-walk-0.4.png"),
        ("spine-stretchyman-pro.json", "stretchyman.atlas", None, "stretchyman-setup.png"),
        ("spine-celestial-circus-pro.json", "celestial-circus.atlas", None, "celestial-circus-setup.png"),
    ] {
        let text = String::from_utf8(read(&format!("../../examples/characters/{skeleton}"))).unwrap();
        let c = ikarus_edge::character::load(&text, skeleton).unwrap().character;
        let atlas_text = String::from_utf8(read(&format!("../../examples/characters/{atlas}"))).unwrap();
        let regions = ikarus_edge::character::atlas::read(&atlas_text).unwrap().lookup();
        let skin = c.default_skin();
        let clip = clip.map(|(name, time)| (c.clip_index(name).unwrap(), time));
        let mut posed = Posed::default();
        c.pose(&PoseRequest { clip, skin, ..PoseRequest::default() }, &mut posed).unwrap();
        let mut list = DrawList::default();
        c.draw_list(&posed, skin, &regions, &mut list);
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for v in &list.vertices {
            for k in 0..2 {
                (lo[k], hi[k]) = (lo[k].min(v[k]), hi[k].max(v[k]));
            }
        }
        // Fitted at 90 % and centred, y up: the picture's pixel edges of the bounds.
        let scale = 720.0 / (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let [w, h] = [(hi[0] - lo[0]) * scale, (hi[1] - lo[1]) * scale];
        let fitted = [400.0 - w / 2.0, 400.0 + w / 2.0, 400.0 - h / 2.0, 400.0 + h / 2.0];
        let seen = opaque(picture);
        // Opaque pixel columns run from `left` to `right` inclusive: edges `left` and `right + 1`.
        let edges = [seen[0], seen[1] + 1.0, seen[2], seen[3] + 1.0];
        for (k, side) in ["left", "right", "top", "bottom"].iter().enumerate() {
            let inside = if k % 2 == 0 { edges[k] - fitted[k] } else { fitted[k] - edges[k] };
            assert!(
                (-1.0..=7.2).contains(&inside),
                "{picture} {side}: opaque from {} px, bounds {:.1}",
                edges[k],
                fitted[k]
            );
        }
    }
}
