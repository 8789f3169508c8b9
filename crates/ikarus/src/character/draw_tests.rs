//! Drawing by hand-made characters: a region's quad shrunk to its packed image (whitespace
//! offsets), the page UVs of every rotation, a mesh's UVs through offsets, colours, and a slot
//! whose attachment is not drawn, a clipping polygon.

use std::collections::HashMap;

use super::*;
use crate::character::{
    Art, AtlasRegion, CharacterParts, ClippingAttachment, PathVertices, PoseRequest, Skin, SkinArt, Slot, WHITE, Weight,
};
use crate::fixtures::character_bone;

fn region(name: &str, degrees: u16) -> AtlasRegion {
    // A 20 × 10 image with 2 pixels stripped on the left, 1 at the bottom: packed 10 × 6 at
    // (30, 40) on a 100 × 200 page.
    AtlasRegion {
        name: name.into(),
        page: 0,
        page_size: [100.0, 200.0],
        bounds: [30.0, 40.0, 10.0, 6.0],
        offsets: [2.0, 1.0],
        original: [20.0, 10.0],
        degrees,
        pma: false,
    }
}

/// One bone at (5, 7) turned 90°, one slot showing `attachment`.
fn character(attachment: Attachment) -> (Character, Posed) {
    let mut bone = character_bone("root", None, 0.0, 0.0);
    bone.setup.x = 5.0;
    bone.setup.y = 7.0;
    bone.setup.rotation = std::f64::consts::FRAC_PI_2;
    let slot = Slot {
        name: "s".into(),
        bone: 0,
        color: [0.5, 1.0, 1.0, 0.5],
        dark: None,
        blend: BlendMode::Multiply,
        attachment: Some("a".into()),
    };
    let skin = SkinArt { slots: vec![HashMap::from([("a".to_owned(), attachment)])] };
    let parts = CharacterParts {
        bones: vec![bone],
        skins: vec![Skin { name: "default".into(), ..Skin::default() }],
        art: Art { slots: vec![slot], skins: vec![skin], ..Art::default() },
        ..CharacterParts::default()
    };
    let c = Character::new(parts).unwrap();
    let mut posed = Posed::default();
    c.pose(&PoseRequest { skin: c.default_skin(), ..PoseRequest::default() }, &mut posed).unwrap();
    (c, posed)
}

fn near(a: &[[f64; 2]], b: &[[f64; 2]]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| (p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12)
}

#[test]
fn a_regions_quad_shrinks_to_its_packed_image_and_each_rotation_maps_its_corners() {
    // 100 × 50 units for a 20 × 10 image: 5 units a pixel. Packed part: from x = −50 + 2·5 = −40
    // to −40 + 10·5 = 10, y = −25 + 1·5 = −20 to −20 + 6·5 = 10; at (1, 2), not turned, scaled
    // by 2 along x: x from −80 to 20, then +1; y +2. The bone turns 90°: (x, y) → (−y, x),
    // then + (5, 7).
    let r = RegionAttachment {
        path: "r".into(),
        x: 1.0,
        y: 2.0,
        rotation: 0.0,
        scale_x: 2.0,
        scale_y: 1.0,
        width: 100.0,
        height: 50.0,
        color: [1.0, 0.5, 1.0, 1.0],
    };
    let (c, posed) = character(Attachment::Region(r));
    let local = [[-79.0, -18.0], [-79.0, 12.0], [21.0, 12.0], [21.0, -18.0]];
    let world: Vec<[f64; 2]> = local.iter().map(|[x, y]| [5.0 - y, 7.0 + x]).collect();
    // Page pixels of the corners bottom-left, top-left, top-right, bottom-right per rotation:
    // the packed image is 10 × 6; turned 90° or 270° it takes 6 × 10 on the page.
    for (degrees, pixels) in [
        (0, [[30.0, 46.0], [30.0, 40.0], [40.0, 40.0], [40.0, 46.0]]),
        (90, [[36.0, 50.0], [30.0, 50.0], [30.0, 40.0], [36.0, 40.0]]),
        (180, [[40.0, 40.0], [40.0, 46.0], [30.0, 46.0], [30.0, 40.0]]),
        (270, [[30.0, 40.0], [36.0, 40.0], [36.0, 50.0], [30.0, 50.0]]),
    ] {
        let regions = Regions::new(vec![region("r", degrees)]);
        let mut list = DrawList::default();
        c.draw_list(&posed, c.default_skin(), &regions, &mut list);
        assert!(near(&list.vertices, &world), "{degrees}: {:?}", list.vertices);
        let uvs: Vec<[f64; 2]> = pixels.iter().map(|[x, y]| [x / 100.0, y / 200.0]).collect();
        assert!(near(&list.uvs, &uvs), "{degrees}: {:?}", list.uvs);
        let item = &list.items[0];
        assert_eq!((item.region, item.blend, item.color), (Some(0), BlendMode::Multiply, [0.5, 0.5, 1.0, 0.5]));
    }
    // Without the atlas's region: the whole quad, UVs over the image.
    let mut list = DrawList::default();
    c.draw_list(&posed, c.default_skin(), &Regions::default(), &mut list);
    let local = [[-99.0, -23.0], [-99.0, 27.0], [101.0, 27.0], [101.0, -23.0]];
    let world: Vec<[f64; 2]> = local.iter().map(|[x, y]| [5.0 - y, 7.0 + x]).collect();
    assert!(near(&list.vertices, &world), "{:?}", list.vertices);
    assert_eq!(list.items[0].region, None);
}

#[test]
fn a_meshs_uvs_go_through_the_stripped_whitespace_and_a_weighted_vertex_sums_its_bones() {
    // UV (0.5, 0.5) of the 20 × 10 original is pixel (10, 5) from its top-left; the packed image
    // starts 2 pixels right and 10 − 1 − 6 = 3 down: (8, 2) in it, page (38, 42). UV (0.1, 0.3):
    // pixel (2, 3), packed (0, 0), page (30, 40).
    let mesh = MeshAttachment {
        path: "r".into(),
        uvs: vec![[0.5, 0.5], [0.1, 0.3], [0.0, 0.0]],
        triangles: vec![0, 1, 2],
        vertices: PathVertices::Weighted(vec![
            vec![
                Weight { bone: 0, point: [1.0, 0.0], weight: 0.25 },
                Weight { bone: 0, point: [0.0, 3.0], weight: 0.75 },
            ],
            vec![Weight { bone: 0, point: [0.0, 0.0], weight: 1.0 }],
            vec![Weight { bone: 0, point: [2.0, 2.0], weight: 1.0 }],
        ]),
        hull: 3,
        width: 0.0,
        height: 0.0,
        color: WHITE,
    };
    let (c, posed) = character(Attachment::Mesh(mesh));
    let mut list = DrawList::default();
    c.draw_list(&posed, c.default_skin(), &Regions::new(vec![region("r", 0)]), &mut list);
    assert!(near(&list.uvs[..2], &[[0.38, 0.21], [0.30, 0.20]]), "{:?}", list.uvs);
    // Bone: (x, y) → (5 − y, 7 + x). 0.25·(5, 8) + 0.75·(2, 7) = (2.75, 7.25).
    assert!(near(&list.vertices, &[[2.75, 7.25], [5.0, 7.0], [3.0, 9.0]]), "{:?}", list.vertices);
    assert_eq!(list.triangles, [0, 1, 2]);
}

#[test]
fn an_attachment_that_is_not_drawn_draws_nothing_and_bad_art_is_refused() {
    let (c, posed) = character(Attachment::NotDrawn);
    let mut list = DrawList::default();
    c.draw_list(&posed, c.default_skin(), &Regions::default(), &mut list);
    assert!(list.items.is_empty() && list.vertices.is_empty());
    let bad = MeshAttachment {
        path: "m".into(),
        uvs: vec![[0.0, 0.0]],
        triangles: vec![0, 0, 1],
        vertices: PathVertices::Plain(vec![[0.0, 0.0]]),
        hull: 0,
        width: 0.0,
        height: 0.0,
        color: WHITE,
    };
    let parts = CharacterParts {
        bones: vec![character_bone("root", None, 0.0, 0.0)],
        skins: vec![Skin::default()],
        art: Art {
            slots: vec![],
            skins: vec![SkinArt { slots: vec![HashMap::from([("m".to_owned(), Attachment::Mesh(bad))])] }],
            ..Art::default()
        },
        ..CharacterParts::default()
    };
    assert_eq!(Character::new(parts).unwrap_err().to_string(), "art: skins[0]: attachments for 1 slots of 0");
}

#[test]
fn a_clipping_polygon_cuts_the_slots_after_it_through_its_bone() {
    // Slot 0 shows a clipping polygon, the square 0..10 × 0..10 in the bone's frame, ending at
    // slot 1; slot 1 a 20 × 20 region around the bone's origin (no atlas region: UVs 0 to 1).
    let mut bone = character_bone("root", None, 0.0, 0.0);
    (bone.setup.x, bone.setup.y, bone.setup.rotation) = (5.0, 7.0, std::f64::consts::FRAC_PI_2);
    let slot = |name: &str| Slot {
        name: name.into(),
        bone: 0,
        color: WHITE,
        dark: None,
        blend: BlendMode::Normal,
        attachment: Some(name.into()),
    };
    let square = PathVertices::Plain(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]);
    let clip = |end: usize, vertices: PathVertices| Attachment::Clipping(ClippingAttachment { end, vertices });
    let quad = RegionAttachment {
        path: "q".into(),
        x: 0.0,
        y: 0.0,
        rotation: 0.0,
        scale_x: 1.0,
        scale_y: 1.0,
        width: 20.0,
        height: 20.0,
        color: WHITE,
    };
    let parts = |clipping: Attachment| CharacterParts {
        bones: vec![bone.clone()],
        skins: vec![Skin { name: "default".into(), ..Skin::default() }],
        art: Art {
            slots: vec![slot("c"), slot("q")],
            skins: vec![SkinArt {
                slots: vec![
                    HashMap::from([("c".to_owned(), clipping)]),
                    HashMap::from([("q".to_owned(), Attachment::Region(quad.clone()))]),
                ],
            }],
            ..Art::default()
        },
        ..CharacterParts::default()
    };
    let c = Character::new(parts(clip(1, square.clone()))).unwrap();
    let mut posed = Posed::default();
    c.pose(&PoseRequest { skin: c.default_skin(), ..PoseRequest::default() }, &mut posed).unwrap();
    let mut list = DrawList::default();
    c.draw_list(&posed, c.default_skin(), &Regions::default(), &mut list);
    assert_eq!(list.items.len(), 1, "the clipping slot draws nothing");
    // What is kept is the square: a quarter of the quad, area 100, in the world (bone: (x, y) →
    // (5 − y, 7 + x)) x −5 to 5, y 7 to 17. Each vertex keeps the quad's UVs at its place:
    // local (lx, ly) = (Y − 7, 5 − X), u = (lx + 10)/20, v = (10 − ly)/20.
    let area: f64 = list
        .triangles
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| list.vertices[t[k] as usize]);
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs()
        })
        .sum();
    assert!((area - 100.0).abs() < 1e-9, "{area}");
    for (p, uv) in list.vertices.iter().zip(&list.uvs) {
        assert!((-5.0 - 1e-9..=5.0 + 1e-9).contains(&p[0]) && (7.0 - 1e-9..=17.0 + 1e-9).contains(&p[1]), "{p:?}");
        let (lx, ly) = (p[1] - 7.0, 5.0 - p[0]);
        assert!((uv[0] - (lx + 10.0) / 20.0).abs() < 1e-12 && (uv[1] - (10.0 - ly) / 20.0).abs() < 1e-12);
    }
    // A polygon of two vertices, or ending at a slot that does not exist, is refused.
    let two = PathVertices::Plain(vec![[0.0, 0.0], [1.0, 0.0]]);
    let e = Character::new(parts(clip(1, two))).unwrap_err().to_string();
    assert!(e.contains("a clipping polygon of 2 vertices (3 to 256)"), "{e}");
    let e = Character::new(parts(clip(2, square))).unwrap_err().to_string();
    assert!(e.contains("end slot 2: only 2 slots"), "{e}");
}
