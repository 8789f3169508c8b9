//! Slot timelines by hand: attachment keys (stepped, `None`), colour keys of every kind with
//! linear, stepped and Bézier curves, before the first key and after the last, Spine's draw
//! order offsets on a worked example, and a synthetic character drawn at clip times (the
//! attachment, colour, draw order and mesh deform all applied).

use std::collections::HashMap;

use super::*;
use crate::character::{
    Art, Attachment, BlendMode, Character, CharacterParts, Clip, DrawList, MeshAttachment, PathVertices, PoseRequest,
    Posed, RegionAttachment, Regions, Skin, SkinArt, Slot, WHITE,
};
use crate::fixtures::character_bone;

fn color_key(time: f64, values: &[f64], curve: Interpolation) -> ColorKey {
    let mut v = [0.0; COLOR_CHANNELS];
    v[..values.len()].copy_from_slice(values);
    ColorKey { time, values: v, curves: [curve; COLOR_CHANNELS] }
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
}

#[test]
fn draw_order_offsets_move_the_listed_slots_and_keep_the_others_in_order() {
    // Five slots; slot 1 moves 2 places (to place 3), slot 3 moves −3 (to place 0). The others,
    // 0, 2 and 4, keep their order in the places left (1, 2, 4): [3, 0, 2, 1, 4].
    assert_eq!(draw_order_from_offsets(5, &[(1, 2), (3, -3)]).unwrap(), vec![3, 0, 2, 1, 4]);
    // No offsets: the setup order.
    assert_eq!(draw_order_from_offsets(3, &[]).unwrap(), vec![0, 1, 2]);
    // The last slot to the front: [2, 0, 1].
    assert_eq!(draw_order_from_offsets(3, &[(2, -2)]).unwrap(), vec![2, 0, 1]);
    // Off the end, onto another listed slot, slots out of order.
    assert!(draw_order_from_offsets(5, &[(4, 1)]).unwrap_err().contains("offsets[0].offset = 1"));
    assert!(draw_order_from_offsets(5, &[(1, 1), (2, 0)]).unwrap_err().contains("offsets[1].offset = 0"));
    assert!(draw_order_from_offsets(5, &[(3, 0), (1, 0)]).unwrap_err().contains("offsets[1].slot = 1"));
}

#[test]
fn draw_order_keys_are_stepped_and_hold_the_setup_order_before_the_first() {
    let keys = [
        DrawOrderKey { time: 1.0, order: Some(vec![1, 0]) },
        DrawOrderKey { time: 2.0, order: None },
        DrawOrderKey { time: 3.0, order: Some(vec![1, 0]) },
    ];
    assert_eq!(draw_order_at(&keys, 0.5), None);
    assert_eq!(draw_order_at(&keys, 1.0), Some(&[1, 0][..]));
    assert_eq!(draw_order_at(&keys, 1.99), Some(&[1, 0][..]));
    assert_eq!(draw_order_at(&keys, 2.5), None);
    assert_eq!(draw_order_at(&keys, 9.0), Some(&[1, 0][..]));
}

#[test]
fn attachment_keys_are_stepped_and_none_hides() {
    let t = AttachmentTimeline {
        slot: 0,
        keys: vec![
            AttachmentKey { time: 0.5, name: Some("b".into()) },
            AttachmentKey { time: 1.0, name: None },
            AttachmentKey { time: 2.0, name: Some("a".into()) },
        ],
    };
    let name = |time: f64| t.key_at(time).map(|k| k.name.as_deref());
    assert_eq!(name(0.2), None);
    assert_eq!(name(0.5), Some(Some("b")));
    assert_eq!(name(0.99), Some(Some("b")));
    assert_eq!(name(1.5), Some(None));
    assert_eq!(name(3.0), Some(Some("a")));
}

#[test]
fn colour_keys_interpolate_per_channel_and_hold_before_and_after() {
    // rgba from (0.2, 0.4, 0.6, 0.8) at 1 s to (0.6, 0.8, 1, 0) at 3 s, linear: at 2 s the
    // midpoints (0.4, 0.6, 0.8, 0.4).
    let linear = ColorTimeline {
        slot: 0,
        property: ColorProperty::Rgba,
        keys: vec![
            color_key(1.0, &[0.2, 0.4, 0.6, 0.8], Interpolation::Linear),
            color_key(3.0, &[0.6, 0.8, 1.0, 0.0], Interpolation::Linear),
        ],
    };
    assert_eq!(linear.at(0.5), None);
    assert!(close(&linear.at(2.0).unwrap()[..4], &[0.4, 0.6, 0.8, 0.4]));
    assert!(close(&linear.at(7.0).unwrap()[..4], &[0.6, 0.8, 1.0, 0.0]));
    let mut color = [0.1; 4];
    let mut dark = None;
    linear.apply(0.5, &mut color, &mut dark);
    assert_eq!(color, [0.1; 4], "before the first key the colour stays");
    linear.apply(2.0, &mut color, &mut dark);
    assert!(close(&color, &[0.4, 0.6, 0.8, 0.4]) && dark.is_none());

    // Stepped: the first key's values up to the second key.
    let mut stepped = linear.clone();
    stepped.keys[0].curves = [Interpolation::Stepped; COLOR_CHANNELS];
    assert!(close(&stepped.at(2.99).unwrap()[..4], &[0.2, 0.4, 0.6, 0.8]));

    // Bézier on green only, control points (1 + 2/3, 0.8) and (1 + 4/3, 0.8) from (1, 0.4) to
    // (3, 0.8): time is linear in u (t = 1 + 2u), value B(u) = 0.4(1 − u)³ + 0.8(1 − (1 − u)³),
    // at 2 s (u = 0.5, a sample): 0.4/8 + 0.8·7/8 = 0.75. Red stays linear: 0.4.
    let mut bezier = linear.clone();
    bezier.keys[0].curves[1] = Interpolation::Bezier { c1: [1.0 + 2.0 / 3.0, 0.8], c2: [1.0 + 4.0 / 3.0, 0.8] };
    let v = bezier.at(2.0).unwrap();
    assert!(close(&v[..2], &[0.4, 0.75]), "{v:?}");
}

#[test]
fn rgb_alpha_and_two_colour_keys_set_only_their_channels() {
    let one = |property, values: &[f64]| ColorTimeline {
        slot: 0,
        property,
        keys: vec![color_key(0.0, values, Interpolation::Linear)],
    };
    let setup = [0.1, 0.2, 0.3, 0.4];
    let run = |t: ColorTimeline| {
        let (mut color, mut dark) = (setup, None);
        t.apply(1.0, &mut color, &mut dark);
        (color, dark)
    };
    assert_eq!(run(one(ColorProperty::Rgb, &[1.0, 0.5, 0.25])), ([1.0, 0.5, 0.25, 0.4], None));
    assert_eq!(run(one(ColorProperty::Alpha, &[0.5])), ([0.1, 0.2, 0.3, 0.5], None));
    let (c, d) = run(one(ColorProperty::Rgba2, &[1.0, 0.5, 0.25, 0.75, 0.5, 0.25, 0.125]));
    assert_eq!((c, d), ([1.0, 0.5, 0.25, 0.75], Some([0.5, 0.25, 0.125])));
    let (c, d) = run(one(ColorProperty::Rgb2, &[1.0, 0.5, 0.25, 0.5, 0.25, 0.125]));
    assert_eq!((c, d), ([1.0, 0.5, 0.25, 0.4], Some([0.5, 0.25, 0.125])));
}

fn quad(width: f64) -> Attachment {
    Attachment::Region(RegionAttachment {
        path: "missing".into(),
        x: 0.0,
        y: 0.0,
        rotation: 0.0,
        scale_x: 1.0,
        scale_y: 1.0,
        width,
        height: 2.0,
        color: WHITE,
    })
}

/// One bone at the origin; slots `s0` (region `a`, 2 wide, or `b`, 4 wide), `s1` (region `c`)
/// and `s2` (mesh `m`, a triangle (0, 0), (10, 0), (0, 10)); one clip keying them all.
fn character() -> Character {
    let slot = |name: &str, attachment: &str| Slot {
        name: name.into(),
        bone: 0,
        color: [1.0, 1.0, 1.0, 0.5],
        dark: None,
        blend: BlendMode::Normal,
        attachment: Some(attachment.into()),
    };
    let mesh = MeshAttachment {
        path: "missing".into(),
        uvs: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        triangles: vec![0, 1, 2],
        vertices: PathVertices::Plain(vec![[0.0, 0.0], [10.0, 0.0], [0.0, 10.0]]),
        hull: 3,
        width: 10.0,
        height: 10.0,
        color: WHITE,
    };
    let skin = SkinArt {
        slots: vec![
            HashMap::from([("a".to_owned(), quad(2.0)), ("b".to_owned(), quad(4.0))]),
            HashMap::from([("c".to_owned(), quad(2.0))]),
            HashMap::from([("m".to_owned(), Attachment::Mesh(mesh))]),
        ],
    };
    let clip = SlotClip {
        attachments: vec![AttachmentTimeline {
            slot: 0,
            keys: vec![AttachmentKey { time: 1.0, name: Some("b".into()) }, AttachmentKey { time: 2.0, name: None }],
        }],
        colors: vec![ColorTimeline {
            slot: 1,
            property: ColorProperty::Rgb,
            keys: vec![color_key(0.0, &[0.0, 0.5, 1.0], Interpolation::Linear)],
        }],
        // At 1.5 s the mesh's slot goes to the front.
        draw_order: vec![DrawOrderKey { time: 1.5, order: Some(vec![2, 0, 1]) }],
        // Vertex 1 moves by (2, 2) at 1 s, linearly from none at 0 s.
        deforms: vec![MeshDeform {
            skin: 0,
            slot: 2,
            attachment: "m".into(),
            keys: vec![
                DeformKey { time: 0.0, start: 0, offsets: vec![], curve: Interpolation::Linear },
                DeformKey { time: 1.0, start: 2, offsets: vec![2.0, 2.0], curve: Interpolation::Linear },
            ],
        }],
    };
    let parts = CharacterParts {
        bones: vec![character_bone("root", None, 0.0, 0.0)],
        skins: vec![Skin { name: "default".into(), ..Skin::default() }],
        clips: vec![Clip { name: "c".into(), duration: 2.0, bones: vec![], constraints: vec![] }],
        art: Art {
            slots: vec![slot("s0", "a"), slot("s1", "c"), slot("s2", "m")],
            skins: vec![skin],
            clips: vec![clip],
        },
        ..CharacterParts::default()
    };
    Character::new(parts).unwrap()
}

/// The slots drawn at `time` and the list.
fn drawn(c: &Character, time: Option<f64>) -> (Vec<usize>, DrawList) {
    let mut posed = Posed::default();
    let clip = time.map(|t| (0, t));
    c.pose(&PoseRequest { clip, skin: c.default_skin(), ..PoseRequest::default() }, &mut posed).unwrap();
    let mut list = DrawList::default();
    c.draw_list_at(&posed, c.default_skin(), clip, &Regions::default(), &mut list).unwrap();
    (list.items.iter().map(|i| i.slot).collect(), list)
}

#[test]
fn a_clip_draws_its_attachments_colours_order_and_deforms() {
    let c = character();
    // Setup: every slot in order, s1 white times its setup alpha.
    let (slots, setup) = drawn(&c, None);
    assert_eq!(slots, vec![0, 1, 2]);
    assert_eq!(setup.items[1].color, [1.0, 1.0, 1.0, 0.5]);
    let mut plain = DrawList::default();
    let mut posed = Posed::default();
    c.pose(&PoseRequest { skin: c.default_skin(), ..PoseRequest::default() }, &mut posed).unwrap();
    c.draw_list(&posed, c.default_skin(), &Regions::default(), &mut plain);
    assert_eq!(plain, setup);

    // 0.5 s: region a (2 wide: x from −1 to 1), s1's colour keyed (alpha stays), the mesh's
    // vertex 1 halfway deformed: (11, 1).
    let (slots, l) = drawn(&c, Some(0.5));
    assert_eq!(slots, vec![0, 1, 2]);
    assert_eq!(l.vertices[l.items[0].vertices.start][0], -1.0);
    assert_eq!(l.items[1].color, [0.0, 0.5, 1.0, 0.5]);
    let mesh = &l.vertices[l.items[2].vertices.clone()];
    assert!(close(&mesh.concat(), &[0.0, 0.0, 11.0, 1.0, 0.0, 10.0]), "{mesh:?}");

    // 1.5 s: region b (4 wide), the mesh first, fully deformed: (12, 2).
    let (slots, l) = drawn(&c, Some(1.5));
    assert_eq!(slots, vec![2, 0, 1]);
    assert_eq!(l.vertices[l.items[1].vertices.start][0], -2.0);
    assert!(close(&l.vertices[l.items[0].vertices.clone()].concat(), &[0.0, 0.0, 12.0, 2.0, 0.0, 10.0]));

    // 2.5 s: s0 shows nothing.
    assert_eq!(drawn(&c, Some(2.5)).0, vec![2, 1]);
}

#[test]
fn drawing_a_clip_the_character_does_not_have_is_an_error() {
    let c = character();
    let mut posed = Posed::default();
    c.pose(&PoseRequest::default(), &mut posed).unwrap();
    let mut list = DrawList::default();
    let err = c.draw_list_at(&posed, None, Some((3, 0.0)), &Regions::default(), &mut list).unwrap_err();
    assert_eq!(err.to_string(), "clip: no clip 3");
    let err = c.draw_list_at(&posed, None, Some((0, f64::NAN)), &Regions::default(), &mut list).unwrap_err();
    assert_eq!(err.to_string(), "time: must be finite, got NaN");
}

#[test]
fn a_draw_order_that_misses_a_slot_is_refused() {
    let c = character();
    let mut art = c.art().clone();
    art.clips[0].draw_order[0].order = Some(vec![0, 0, 1]);
    let parts = CharacterParts {
        bones: vec![character_bone("root", None, 0.0, 0.0)],
        skins: vec![Skin { name: "default".into(), ..Skin::default() }],
        clips: c.clips().to_vec(),
        art,
        ..CharacterParts::default()
    };
    assert_eq!(Character::new(parts).unwrap_err().to_string(), "art: clips[0].drawOrder[0]: not every slot once");
}
