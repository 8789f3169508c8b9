//! A character made by hand with the art features Spine's shipped examples use and the four
//! reference characters do not, drawn as `ikarus pose --rig … --atlas … [--skin …] --art-only`
//! draws it ([`AtlasArt::read_file`] on an atlas and PNG pages written here, then
//! [`ikarus_render::art_only_pixmap`]), each pixel checked against the documented rules:
//!
//! - a legacy (3.x) atlas page: a blank first line, `size`/`format`/`filter`/`repeat`, region
//!   fields `rotate: true`, `xy`, `size`, `orig`, `offset`, `index` (Spine's texture atlas
//!   format: `size` is the image as it stands; rotated, it lies on the page turned by 90°,
//!   `orig`/`offset` give the whitespace stripped, and the quad shrinks to the packed part);
//! - a second page in the 4.x spelling (`bounds`, `offsets`), found by its regions;
//! - a linked mesh in a skin other than `default`, its parent mesh in the default skin (JSON
//!   format, "Linked mesh attachments"): with `--skin`, the parent's geometry with its own
//!   region; without, the default skin's mesh;
//! - a region with a `sequence` (`start` 1, `digits` 2, `setup` 1): it shows region
//!   `flame02` (the path, then `start + setup` written with 2 digits);
//! - a clipping attachment (user guide, "Clipping attachments"): its concave polygon (an L)
//!   cuts what is drawn from its slot to its end slot, inclusive (`middle`, whichever skin
//!   shows it), and nothing after (`seq`); it is not listed as unsupported.
//!
//! The pictures are written to `target/tmp/art_features/` (`default.png`, `blue.png`).

use ikarus::character::{DrawList, Posed};
use ikarus_edge::character::art_draw::AtlasArt;
use ikarus_edge::pose::{IkChoice, PhysicsAsk, PoseAsk, pose_kept, skin_index};

/// The skeleton: four slots on the root (the clipping polygon's over `middle`).
const SKELETON: &str = r#"{
  "skeleton": {"spine": "4.2.22"},
  "bones": [{"name": "root"}],
  "slots": [
    {"name": "left", "bone": "root", "attachment": "halves"},
    {"name": "clip", "bone": "root", "attachment": "clip"},
    {"name": "middle", "bone": "root", "attachment": "shape"},
    {"name": "seq", "bone": "root", "attachment": "flame"}
  ],
  "skins": [
    {"name": "default", "attachments": {
      "left": {"halves": {"x": -20, "width": 20, "height": 10}},
      "middle": {"shape": {"type": "mesh", "path": "grey", "hull": 4,
        "uvs": [0, 1, 1, 1, 1, 0, 0, 0], "triangles": [0, 1, 2, 2, 3, 0],
        "vertices": [0, -5, 10, -5, 10, 5, 0, 5], "width": 10, "height": 10}},
      "clip": {"clip": {"type": "clipping", "end": "middle", "vertexCount": 6,
        "vertices": [-1, -6, 11, -6, 11, 0, 5, 0, 5, 6, -1, 6]}},
      "seq": {"flame": {"x": 20, "width": 10, "height": 10,
        "sequence": {"count": 3, "start": 1, "digits": 2, "setup": 1}}}
    }},
    {"name": "blue", "attachments": {
      "middle": {"shape": {"type": "linkedmesh", "path": "blue", "parent": "shape", "skin": "default"}}
    }}
  ]
}"#;

/// Two pages: `a.png` (3.x spelling) holds `halves`, turned on the page, its original image
/// twice as wide as the packed part (the left half stripped); `b.png` (4.x spelling) the rest.
const ATLAS: &str = "
a.png
size: 8,8
format: RGBA8888
filter: Linear,Linear
repeat: none
halves
  rotate: true
  xy: 3, 2
  size: 4, 2
  orig: 8, 2
  offset: 4, 0
  index: -1

b.png
size: 8, 4
filter: Linear, Linear
grey
  bounds: 0, 0, 2, 2
blue
  bounds: 2, 0, 2, 2
  offsets: 0, 0, 2, 2
flame01
  bounds: 0, 2, 2, 2
flame02
  bounds: 2, 2, 2, 2
flame03
  bounds: 4, 2, 2, 2
";

const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];
const GREY: [u8; 4] = [128, 128, 128, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];
const FLAMES: [[u8; 4]; 3] = [[255, 255, 0, 255], [255, 128, 0, 255], [0, 255, 255, 255]];

/// A straight RGBA PNG of `w` × `h` pixels, `pixel(x, y)` each (y down).
fn png(w: u32, h: u32, pixel: impl Fn(u32, u32) -> [u8; 4]) -> Vec<u8> {
    let data: Vec<u8> = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).flat_map(|(x, y)| pixel(x, y)).collect();
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.write_header().unwrap().write_image_data(&data).unwrap();
    out
}

/// Writes the atlas and its pages into a folder of their own and reads them as the command
/// line does.
fn atlas() -> AtlasArt {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("art_features");
    std::fs::create_dir_all(&dir).unwrap();
    // `halves` on page a: columns 3 and 4, rows 2 to 5. Turned by 90°, the image's top edge
    // runs up the left side, so its left half (red) lies on rows 4 and 5, its right half
    // (green) on rows 2 and 3. The rest of the page is transparent.
    let a = png(8, 8, |x, y| match (x, y) {
        (3..=4, 2..=3) => GREEN,
        (3..=4, 4..=5) => RED,
        _ => [0; 4],
    });
    let b = png(8, 4, |x, y| match (x, y) {
        (0..=1, 0..=1) => GREY,
        (2..=3, 0..=1) => BLUE,
        (0..=5, 2..=3) => FLAMES[x as usize / 2],
        _ => [0; 4],
    });
    std::fs::write(dir.join("a.png"), a).unwrap();
    std::fs::write(dir.join("b.png"), b).unwrap();
    std::fs::write(dir.join("features.atlas"), ATLAS).unwrap();
    AtlasArt::read_file(&dir.join("features.atlas")).unwrap()
}

/// The art-only picture (800 × 800) with skin `skin`, its drawn box, and the file's unsupported
/// features as `(kind, name)`.
fn draw(skin: Option<&str>) -> (ikarus_render::Pixmap, [f64; 4], Vec<(String, String)>) {
    let loaded = ikarus_edge::character::load(SKELETON, "features.json").unwrap();
    let c = &loaded.character;
    let ask = PoseAsk {
        animation: None,
        time: None,
        targets: Vec::new(),
        ik: IkChoice::Runtime,
        bends: Vec::new(),
        turns: Vec::new(),
        skin: skin.map(str::to_owned),
        physics: PhysicsAsk::Off,
    };
    let mut posed = Posed::default();
    pose_kept(&loaded, &ask, &mut posed).unwrap();
    let skin_name = skin.unwrap_or("default");
    let skin = skin_index(c, skin).unwrap();
    let atlas = atlas();
    let art = atlas.art(c, &posed, (skin, None), &mut DrawList::default()).unwrap();
    let (lo, hi) = art.extent().unwrap();
    let pixmap = ikarus_render::art_only_pixmap(&art, 800, 800).unwrap();
    let picture = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("art_features/{}.png", skin_name));
    std::fs::write(picture, ikarus_render::pixmap_png(&pixmap).unwrap()).unwrap();
    let unsupported = c.unsupported().iter().map(|u| (u.kind.clone(), u.name.clone())).collect();
    (pixmap, [lo.x, lo.y, hi.x, hi.y], unsupported)
}

/// The straight RGBA8 colour at world point `(x, y)`. The drawn box is x −20 to 25, y −5 to 5
/// (see the test): 45 units wide fill 90 % of 800 px, 16 px a unit, centred on (2.5, 0).
fn at(pixmap: &ikarus_render::Pixmap, x: f64, y: f64) -> [u8; 4] {
    let (px, py) = (400.0 + 16.0 * (x - 2.5), 400.0 - 16.0 * y);
    let c = pixmap.pixel(px as u32, py as u32).unwrap().demultiply();
    [c.red(), c.green(), c.blue(), c.alpha()]
}

#[test]
fn a_hand_made_character_with_every_feature_draws_by_the_documented_rules() {
    let (plain, bounds, unsupported) = draw(None);
    // `halves`: 20 × 10 around (−20, 0), the packed part the original's right half: offset 4 of
    // 8 pixels, so x from −30 + 4 · 20/8 = −20 to −20 + 4 · 20/8 = −10. `shape`: x 0 to 10;
    // `flame`: 10 wide around 20; every quad 10 high around 0; the clipping polygon is not
    // drawn, so it is not in the box.
    assert_eq!(bounds, [-20.0, -5.0, 25.0, 5.0]);
    // The packed image's left half is red, its right half green; whitespace is not drawn.
    assert_eq!(at(&plain, -18.0, 0.0), RED);
    assert_eq!(at(&plain, -12.0, 2.0), GREEN);
    assert_eq!(at(&plain, -12.0, -2.0), GREEN);
    // The default skin's mesh shows region `grey` (page b), cut to the L: its top right quarter
    // (x > 5, y > 0) is gone.
    assert_eq!(at(&plain, 2.5, 2.5), GREY);
    assert_eq!(at(&plain, 7.5, -2.5), GREY);
    assert_eq!(at(&plain, 7.5, 2.5)[3], 0);
    // Between the quads nothing is drawn.
    assert_eq!(at(&plain, 12.5, 0.0)[3], 0);
    // The sequence shows its setup frame, `flame02`, whole: clipping ended at `middle`.
    assert_eq!(at(&plain, 20.0, 0.0), FLAMES[1]);
    assert_eq!(at(&plain, 21.0, 1.0), FLAMES[1]);
    assert_eq!(unsupported, [("sequence".to_owned(), "flame (skin default, slot seq)".to_owned())]);
    // With skin `blue` the linked mesh: its parent's geometry, its own region.
    let (blue, bounds, _) = draw(Some("blue"));
    assert_eq!(bounds, [-20.0, -5.0, 25.0, 5.0]);
    assert_eq!(at(&blue, 2.5, 2.5), BLUE);
    assert_eq!(at(&blue, 7.5, 2.5)[3], 0);
    assert_eq!(at(&blue, -18.0, 0.0), RED);
    assert_eq!(at(&blue, 20.0, 0.0), FLAMES[1]);
}
