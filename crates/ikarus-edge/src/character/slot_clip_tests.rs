//! Slot timelines read from Spine files and drawn: spineboy's `shoot` (a muzzle's attachment
//! and colour keys) and `hoverboard` (a weighted mesh's deform), the raptor's `walk` (a slot
//! colour) and `jump` (the draw order), each worked by hand at one time; 3.8's spellings; a
//! `.skel` reads the same timelines as its JSON; bad keys refused in one line; spineboy's
//! `portal` clipped to its clipping polygon.

use ikarus::character::{
    Character, DeformKey, DrawList, Interpolation, PathVertices, PoseRequest, Posed, Regions, SlotClip,
};
use serde_json::{Value, json};

use super::atlas;
use super::tests::{load_ok, refused};

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
const RAPTOR: &str = include_str!("../../../../examples/characters/spine-raptor-pro.json");
const SPINEBOY_ATLAS: &str = include_str!("../../../../examples/characters/spineboy.atlas");

/// `c` posed with clip `clip` at `time` (default skin) and its drawing.
fn drawn(c: &Character, clip: &str, time: f64, regions: &Regions) -> (Posed, DrawList) {
    let clip = Some((c.clip_index(clip).unwrap(), time));
    let skin = c.default_skin();
    let mut posed = Posed::default();
    c.pose(&PoseRequest { clip, skin, ..PoseRequest::default() }, &mut posed).unwrap();
    let mut list = DrawList::default();
    c.draw_list_at(&posed, skin, clip, regions, &mut list).unwrap();
    (posed, list)
}

fn slot(c: &Character, name: &str) -> usize {
    c.art().slots.iter().position(|s| s.name == name).unwrap()
}

fn f32ed(v: f64) -> f64 {
    v as f32 as f64
}

#[test]
fn spineboys_muzzle_shows_its_keyed_frame_fading_by_its_alpha_key() {
    // shoot, slot muzzle (no setup attachment, white): attachment keys 0.0333 muzzle01 …
    // 0.1333 muzzle04, 0.1667 muzzle05, 0.2 none; rgba keys 0.1333 ffffffff, 0.2 ffffff62,
    // linear. At 0.15 s: muzzle04, alpha 1 + (0x62/255 − 1)·(0.15 − 0.1333)/(0.2 − 0.1333).
    let c = load_ok(SPINEBOY).character;
    let regions = atlas::read(SPINEBOY_ATLAS).unwrap().lookup();
    let muzzle = slot(&c, "muzzle");
    let (_, list) = drawn(&c, "shoot", 0.15, &regions);
    let item = list.items.iter().find(|i| i.slot == muzzle).expect("the muzzle is drawn");
    assert_eq!(regions.get(item.region.unwrap()).unwrap().name, "muzzle04");
    let (t0, t1) = (f32ed(0.1333), f32ed(0.2));
    let alpha = 1.0 + (f32ed(98.0 / 255.0) - 1.0) * (0.15 - t0) / (t1 - t0);
    assert_eq!(item.color[..3], [1.0; 3]);
    assert!((item.color[3] - alpha).abs() < 1e-6, "{} vs {alpha}", item.color[3]);
    // Before its first key the setup (nothing), after the key without a name nothing.
    for time in [0.0, 0.25] {
        assert!(drawn(&c, "shoot", time, &regions).1.items.iter().all(|i| i.slot != muzzle), "{time}");
    }
}

#[test]
fn the_raptors_jaw_colour_is_interpolated_between_its_keys() {
    // walk, slot raptor-jaw-inside (setup 646464ff): rgba keys 0 646464ff, 0.6333 808080ff,
    // linear. At 0.3 s each of red, green, blue: 0x64/255 + (0x80 − 0x64)/255 · 0.3/0.6333.
    let c = load_ok(RAPTOR).character;
    let jaw = slot(&c, "raptor-jaw-inside");
    let (_, list) = drawn(&c, "walk", 0.3, &Regions::default());
    let item = list.items.iter().find(|i| i.slot == jaw).unwrap();
    let (a, b) = (f32ed(100.0 / 255.0), f32ed(128.0 / 255.0));
    let v = a + (b - a) * 0.3 / f32ed(0.6333);
    for ch in 0..3 {
        assert!((item.color[ch] - v).abs() < 1e-6, "{:?} vs {v}", item.color);
    }
    assert_eq!(item.color[3], 1.0);
}

#[test]
fn the_raptors_jump_moves_the_horn_and_the_front_thigh_in_the_draw_order() {
    // jump's one key: raptor-horn (slot 25) +4 → place 29, front-thigh (26) −5 → place 21;
    // the other slots keep their order in the other places.
    let c = load_ok(RAPTOR).character;
    let (_, list) = drawn(&c, "jump", 0.5, &Regions::default());
    let mut expected: Vec<usize> = (0..=20).collect();
    expected.extend([26, 21, 22, 23, 24, 27, 28, 29, 25]);
    expected.extend(30..36);
    assert_eq!(list.slots.order(), expected.as_slice());
    let drawn: Vec<usize> = list.items.iter().map(|i| i.slot).collect();
    let mut in_order = expected.clone();
    in_order.retain(|s| drawn.contains(s));
    assert_eq!(drawn, in_order, "items follow the order");
}

#[test]
fn spineboys_hoverboard_deforms_the_front_foots_weighted_mesh() {
    // hoverboard's one deform key of front-foot (time 0): offset 26, ten numbers: the weight
    // entries 13 to 17 move. Each vertex is Σ weight · world(bone)·(x + dx, y + dy).
    let c = load_ok(SPINEBOY).character;
    let value: Value = serde_json::from_str(SPINEBOY).unwrap();
    let key = &value["animations"]["hoverboard"]["attachments"]["default"]["front-foot"]["front-foot"]["deform"][0];
    let start = key["offset"].as_u64().unwrap() as usize;
    let deltas: Vec<f64> = key["vertices"].as_array().unwrap().iter().map(|v| f32ed(v.as_f64().unwrap())).collect();
    let foot = slot(&c, "front-foot");
    let (posed, list) = drawn(&c, "hoverboard", 0.5, &Regions::default());
    let item = list.items.iter().find(|i| i.slot == foot).unwrap();
    let skin = c.default_skin().unwrap();
    let Some(ikarus::character::Attachment::Mesh(mesh)) = c.art().skins[skin].get(foot, "front-foot") else {
        panic!("front-foot is a mesh")
    };
    let PathVertices::Weighted(vertices) = &mesh.vertices else { panic!("weighted") };
    let offset = |j: usize| j.checked_sub(start).and_then(|i| deltas.get(i)).copied().unwrap_or(0.0);
    let mut entry = 0;
    let mut moved = 0;
    for (k, weights) in vertices.iter().enumerate() {
        let mut sum = [0.0, 0.0];
        for w in weights {
            let (dx, dy) = (offset(2 * entry), offset(2 * entry + 1));
            moved += usize::from(dx != 0.0 || dy != 0.0);
            entry += 1;
            let m = posed.world(w.bone);
            let (x, y) = (w.point[0] + dx, w.point[1] + dy);
            sum[0] += (m.a * x + m.b * y + m.x) * w.weight;
            sum[1] += (m.c * x + m.d * y + m.y) * w.weight;
        }
        let got = list.vertices[item.vertices.start + k];
        assert!((got[0] - sum[0]).abs() < 1e-9 && (got[1] - sum[1]).abs() < 1e-9, "vertex {k}: {got:?} vs {sum:?}");
    }
    assert_eq!(moved, 5, "the key moves five weight entries");
}

/// Two curves alike: the same kind, control points within `t`.
fn same_curve(p: Interpolation, q: Interpolation, t: &dyn Fn(f64, f64) -> bool) -> bool {
    match (p, q) {
        (Interpolation::Bezier { c1, c2 }, Interpolation::Bezier { c1: d1, c2: d2 }) => {
            [c1, c2].iter().flatten().zip([d1, d2].iter().flatten()).all(|(x, y)| t(*x, *y))
        }
        _ => p == q,
    }
}

/// Two deform keys' offsets alike, coordinate by coordinate, within the JSON's rounding (its
/// export writes five decimals and leaves out a leading offset that small).
fn same_offsets(p: &DeformKey, q: &DeformKey) -> bool {
    let at = |k: &DeformKey, j: usize| j.checked_sub(k.start).and_then(|i| k.offsets.get(i)).copied().unwrap_or(0.0);
    let reach = (p.start + p.offsets.len()).max(q.start + q.offsets.len());
    (0..reach).all(|j| (at(p, j) - at(q, j)).abs() <= 2e-4)
}

/// `a` and `b` read alike: the same timelines, keys and values; times within the JSON's four
/// decimals and colour curves' control points within half its last digit (it writes them with
/// two: 0.76 for the `.skel`'s 0.7646) — the `.skel` holds the editor's `f32`s.
fn alike(a: &SlotClip, b: &SlotClip) -> bool {
    let t = |x: f64, y: f64| (x - y).abs() <= 1e-4;
    let curve = |x: f64, y: f64| (x - y).abs() <= 5e-3;
    let attachments = a.attachments.len() == b.attachments.len()
        && a.attachments.iter().zip(&b.attachments).all(|(x, y)| {
            x.slot == y.slot
                && x.keys.len() == y.keys.len()
                && x.keys.iter().zip(&y.keys).all(|(p, q)| t(p.time, q.time) && p.name == q.name)
        });
    let colors = a.colors.len() == b.colors.len()
        && a.colors.iter().zip(&b.colors).all(|(x, y)| {
            x.slot == y.slot
                && x.property == y.property
                && x.keys.len() == y.keys.len()
                && x.keys.iter().zip(&y.keys).all(|(p, q)| {
                    t(p.time, q.time)
                        && p.values == q.values
                        && p.curves.iter().zip(&q.curves).all(|(c, d)| same_curve(*c, *d, &curve))
                })
        });
    let order = a.draw_order.len() == b.draw_order.len()
        && a.draw_order.iter().zip(&b.draw_order).all(|(p, q)| t(p.time, q.time) && p.order == q.order);
    let deforms = a.deforms.len() == b.deforms.len()
        && a.deforms.iter().zip(&b.deforms).all(|(x, y)| {
            (x.skin, x.slot, &x.attachment) == (y.skin, y.slot, &y.attachment)
                && x.keys.len() == y.keys.len()
                && x.keys.iter().zip(&y.keys).all(|(p, q)| t(p.time, q.time) && same_offsets(p, q))
        });
    attachments && colors && order && deforms
}

#[test]
fn a_skel_reads_the_slot_timelines_its_json_reads() {
    let mut total = 0;
    for (name, json, bytes) in [
        ("spineboy", SPINEBOY, include_bytes!("../../../../examples/characters/spine-spineboy-pro.skel").as_slice()),
        ("raptor", RAPTOR, include_bytes!("../../../../examples/characters/spine-raptor-pro.skel").as_slice()),
        (
            "stretchyman",
            include_str!("../../../../examples/characters/spine-stretchyman-pro.json"),
            include_bytes!("../../../../examples/characters/spine-stretchyman-pro.skel").as_slice(),
        ),
        (
            "celestial-circus",
            include_str!("../../../../examples/characters/spine-celestial-circus-pro.json"),
            include_bytes!("../../../../examples/characters/spine-celestial-circus-pro.skel").as_slice(),
        ),
    ] {
        let text = super::skel::text_of(bytes.to_vec(), "f.skel").unwrap();
        let (skel, json) = (load_ok(&text).character, load_ok(json).character);
        let (a, b) = (&skel.art().clips, &json.art().clips);
        assert_eq!(a.len(), b.len());
        // (stretchyman's deforms are of paths: the path constraints read them.)
        total += b
            .iter()
            .map(|c| c.attachments.len() + c.colors.len() + c.deforms.len() + c.draw_order.len())
            .sum::<usize>();
        for (k, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(alike(x, y), "{name} clip {k} ({}): {x:?}\n{y:?}", json.clips()[k].name);
        }
    }
    assert!(total > 30, "{total} timelines");
}

/// A one-bone, two-slot character of `version` with animation `anim`.
fn file(version: &str, anim: Value) -> String {
    json!({
        "skeleton": {"spine": version},
        "bones": [{"name": "root"}],
        "slots": [
            {"name": "a", "bone": "root", "attachment": "x", "color": "ff000080"},
            {"name": "b", "bone": "root", "attachment": "y", "dark": "000000"}
        ],
        "skins": [{"name": "default", "attachments": {"a": {"x": {"width": 2, "height": 2}}, "b": {"y": {}}}}],
        "animations": {"go": anim}
    })
    .to_string()
}

#[test]
fn spine_38s_color_two_color_and_draworder_are_read() {
    // 3.8: `color` with a normalised curve (the same for every channel), `twoColor`,
    // `draworder`. Key 0 → 1 s, 00 → ff, curve (1/3, 1, 2/3, 1) in the unit square: time is
    // linear in u, the value 1 − (1 − u)³, at 0.5 s (u = 0.5, a sample) 0.875.
    let anim = json!({
        "slots": {
            "a": {"color": [
                {"time": 0, "color": "00000000", "curve": 1.0 / 3.0, "c2": 1, "c3": 2.0 / 3.0, "c4": 1},
                {"time": 1, "color": "ffffffff"}
            ]},
            "b": {"twoColor": [{"time": 0, "light": "ff8000ff", "dark": "0080ff"}]}
        },
        "draworder": [{"time": 0.25, "offsets": [{"slot": "b", "offset": -1}]}]
    });
    let c = load_ok(&file("3.8.99", anim)).character;
    let (_, list) = drawn(&c, "go", 0.5, &Regions::default());
    assert_eq!(list.slots.order(), &[1, 0]);
    let a = list.items.iter().find(|i| i.slot == 0).unwrap();
    assert!(a.color.iter().all(|v| (v - 0.875).abs() < 1e-6), "{:?}", a.color);
    let b = list.items.iter().find(|i| i.slot == 1).unwrap();
    assert_eq!(b.color, [1.0, f32ed(128.0 / 255.0), 0.0, 1.0]);
    assert_eq!(b.dark, Some([0.0, f32ed(128.0 / 255.0), 1.0]));
}

#[test]
fn spine_4s_colour_curves_are_per_channel() {
    // rgba 0 → 1 s, 00 → ff, a curve per channel with control times 1/3 and 2/3 (time linear in
    // u; at 0.5 s, u = 0.5, a sample): red (·, 0), (·, 0): u³ = 0.125; green (·, 1), (·, 1):
    // 1 − (1 − u)³ = 0.875; blue (·, 1/3), (·, 2/3): u = 0.5; alpha (·, 1), (·, 0):
    // 3u(1 − u)² + u³ = 0.5.
    let (a, b) = (1.0 / 3.0, 2.0 / 3.0);
    let curve = [a, 0.0, b, 0.0, a, 1.0, b, 1.0, a, a, b, b, a, 1.0, b, 0.0];
    let anim = json!({"slots": {"a": {"rgba": [
        {"time": 0, "color": "00000000", "curve": curve},
        {"time": 1, "color": "ffffffff"}
    ]}}});
    let c = load_ok(&file("4.2.0", anim)).character;
    let (_, list) = drawn(&c, "go", 0.5, &Regions::default());
    let got = list.items.iter().find(|i| i.slot == 0).unwrap().color;
    let want = [0.125, 0.875, 0.5, 0.5];
    assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-6), "{got:?}");
}

/// A slot `a` showing mesh `m` (vertices (0, 0), (10, 0), (0, 10)) in skin `default`, and in
/// skin `other` a linked mesh `m` of it (with `timelines` = `linked`, absent if `None`); the
/// animation deforms the default skin's `m`: vertex 1 by (1, 2).
fn linked_file(linked: Option<bool>) -> String {
    let mut link = json!({"type": "linkedmesh", "parent": "m", "skin": "default"});
    if let Some(t) = linked {
        link["timelines"] = Value::Bool(t);
    }
    json!({
        "skeleton": {"spine": "4.2.0"},
        "bones": [{"name": "root"}],
        "slots": [{"name": "a", "bone": "root", "attachment": "m"}],
        "skins": [
            {"name": "default", "attachments": {"a": {"m": {"type": "mesh", "uvs": [0, 0, 1, 0, 0, 1],
                "triangles": [0, 1, 2], "vertices": [0, 0, 10, 0, 0, 10], "hull": 3}}}},
            {"name": "other", "attachments": {"a": {"m": link}}}
        ],
        "animations": {"go": {"attachments": {"default": {"a": {"m": {"deform": [
            {"time": 0, "offset": 2, "vertices": [1, 2]}
        ]}}}}}}
    })
    .to_string()
}

#[test]
fn a_linked_mesh_takes_its_parents_deform_unless_told_not_to() {
    for (linked, moved) in [(None, true), (Some(true), true), (Some(false), false)] {
        let c = load_ok(&linked_file(linked)).character;
        let other = c.skins().iter().position(|s| s.name == "other");
        let clip = Some((0, 0.5));
        let mut posed = Posed::default();
        c.pose(&PoseRequest { clip, skin: other, ..PoseRequest::default() }, &mut posed).unwrap();
        let mut list = DrawList::default();
        c.draw_list_at(&posed, other, clip, &Regions::default(), &mut list).unwrap();
        let want = if moved { [11.0, 2.0] } else { [10.0, 0.0] };
        assert_eq!(list.vertices[1], want, "timelines {linked:?}");
    }
}

#[test]
fn bad_slot_keys_are_refused_in_one_line() {
    let e = refused(&file("4.2.0", json!({"slots": {"c": {"rgba": []}}})));
    assert!(e.contains(r#"animations."go".slots."c": no slot of that name"#), "{e}");
    let e = refused(&file("4.2.0", json!({"slots": {"a": {"rgb": [{"color": "ff00"}]}}})));
    assert!(e.contains(r#"animations."go".slots."a".rgb[0].color = "ff00": expected 6 hex digits"#), "{e}");
    let e = refused(&file("4.2.0", json!({"drawOrder": [{"offsets": [{"slot": "a", "offset": 2}]}]})));
    assert!(e.contains(r#"animations."go".drawOrder[0].offsets[0].offset = 2"#), "{e}");
    let e = refused(&file("4.2.0", json!({"slots": {"a": {"attachment": [{"time": 1}, {"time": 0.5}]}}})));
    assert!(e.contains(r#"animations."go".slots."a".attachment[1].time = 0.5: before the previous key's"#), "{e}");
}

#[test]
fn spineboys_portal_keeps_him_inside_its_clipping_polygon() {
    // portal keys slot `clipping` to show its clipping attachment (9 unweighted vertices, end
    // slot `head-bb`). The user guide's rule: every slot from `clipping` to `head-bb` in the
    // draw order is cut to the polygon, so every vertex they draw is inside it or on its edge:
    // at 1.1 s (his hand coming out of the portal) some lie on its edge (cut there), at 1.4 s
    // (half of him out) his slots are drawn.
    let c = load_ok(SPINEBOY).character;
    let regions = atlas::read(SPINEBOY_ATLAS).unwrap().lookup();
    let clipping = slot(&c, "clipping");
    let local = [
        [66.76, 509.48],
        [19.98, 434.54],
        [5.34, 336.28],
        [22.19, 247.93],
        [77.98, 159.54],
        [182.21, -97.56],
        [1452.26, -99.8],
        [1454.33, 843.61],
        [166.57, 841.02],
    ];
    let clipped_at = |time: f64| {
        let (posed, list) = drawn(&c, "portal", time, &regions);
        let bone = posed.world(c.art().slots[clipping].bone);
        let polygon: Vec<[f64; 2]> = local.iter().map(|&[x, y]| bone.to_world(x, y)).collect();
        let n = polygon.len();
        let on_edge = |p: [f64; 2]| {
            (0..n).any(|i| {
                let (a, b) = (polygon[i], polygon[(i + 1) % n]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
                (a[0] + t * dx - p[0]).hypot(a[1] + t * dy - p[1]) < 1e-6
            })
        };
        // Even-odd crossings of a ray to the right.
        let inside = |p: [f64; 2]| {
            (0..n)
                .filter(|&i| {
                    let (a, b) = (polygon[i], polygon[(i + 1) % n]);
                    (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                })
                .count()
                % 2
                == 1
        };
        let order = list.slots.order();
        let from = order.iter().position(|&s| s == clipping).unwrap();
        let to = order.iter().position(|&s| s == slot(&c, "head-bb")).unwrap();
        let clipped = &order[from..=to];
        let (mut items, mut cut) = (0, 0);
        for item in list.items.iter().filter(|i| clipped.contains(&i.slot)) {
            items += 1;
            for &p in &list.vertices[item.vertices.clone()] {
                let name = &c.art().slots[item.slot].name;
                assert!(inside(p) || on_edge(p), "{time} s: slot {name} draws {p:?} outside the portal");
                cut += usize::from(on_edge(p));
            }
        }
        (items, cut)
    };
    let (items, cut) = clipped_at(1.1);
    assert!(items > 0 && cut > 0, "1.1 s: {items} slots drawn, {cut} vertices on the polygon's edge");
    let (items, _) = clipped_at(1.4);
    assert!(items >= 10, "1.4 s: {items} slots drawn");
}
