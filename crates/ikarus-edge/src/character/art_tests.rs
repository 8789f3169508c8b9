//! The art read from Spine files and drawn by the library: spineboy's setup pose (region
//! corners and a mesh against the documented formulas worked here by hand, the draw order), the
//! raptor's weighted meshes, slot colours and blend modes, linked meshes, inactive skin bones
//! and bad attachments.

use ikarus::character::{Affine, BlendMode, DrawList, PoseRequest, Posed, Regions};
use serde_json::{Value, json};

use super::atlas;
use super::tests::{load_ok, refused};

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
const RAPTOR: &str = include_str!("../../../../examples/characters/spine-raptor-pro.json");
const SPINEBOY_ATLAS: &str = include_str!("../../../../examples/characters/spineboy.atlas");
const RAPTOR_ATLAS: &str = include_str!("../../../../examples/characters/raptor.atlas");

/// The setup pose with the default skin, and its drawing.
fn setup(json: &str, atlas_text: &str) -> (ikarus::character::Character, Posed, DrawList, Regions) {
    let c = load_ok(json).character;
    let skin = c.default_skin();
    let mut posed = Posed::default();
    c.pose(&PoseRequest { skin, ..PoseRequest::default() }, &mut posed).unwrap();
    let regions = atlas::read(atlas_text).unwrap().lookup();
    let mut list = DrawList::default();
    c.draw_list(&posed, skin, &regions, &mut list);
    (c, posed, list, regions)
}

/// A region attachment's corners worked by hand: the quad `w × h` centred on `(x, y)`, scaled,
/// rotated by `deg`, then through the bone's world transform; bottom-left, top-left, top-right,
/// bottom-right.
fn corners(bone: Affine, [x, y, deg, sx, sy, w, h]: [f64; 7]) -> [[f64; 2]; 4] {
    let (s, c) = deg.to_radians().sin_cos();
    [(-w / 2.0, -h / 2.0), (-w / 2.0, h / 2.0), (w / 2.0, h / 2.0), (w / 2.0, -h / 2.0)].map(|(px, py)| {
        let (px, py) = (px * sx, py * sy);
        let (lx, ly) = (c * px - s * py + x, s * px + c * py + y);
        [bone.a * lx + bone.b * ly + bone.x, bone.c * lx + bone.d * ly + bone.y]
    })
}

fn near(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
}

#[test]
fn spineboys_regions_are_the_documented_quads_with_their_atlas_uvs() {
    let (c, posed, list, _) = setup(SPINEBOY, SPINEBOY_ATLAS);
    let slot = |name: &str| c.art().slots.iter().position(|s| s.name == name).unwrap();
    // (slot, its bone, the file's x, y, rotation, scaleX, scaleY, width, height, and the atlas
    // region's corners on the 1024 × 256 page: bottom-left, top-left, top-right, bottom-right).
    let cases = [
        // front-thigh: bounds 2, 2, 23, 56, rotate 90: on the page 56 wide and 23 high, the
        // image's top edge up the left side.
        (
            "front-thigh",
            [42.48, 4.45, 84.87, 1.0, 1.0, 45.0, 112.0],
            [[58.0, 25.0], [2.0, 25.0], [2.0, 2.0], [58.0, 2.0]],
        ),
        // front-fist-closed: bounds 786, 65, 38, 41, not rotated.
        (
            "front-fist",
            [35.5, 6.0, 67.16, 1.0, 1.0, 75.0, 82.0],
            [[786.0, 106.0], [786.0, 65.0], [824.0, 65.0], [824.0, 106.0]],
        ),
        // gun: bounds 798, 152, 105, 102.
        (
            "gun",
            [77.3, 16.4, 60.83, 1.0, 1.0, 210.0, 203.0],
            [[798.0, 254.0], [798.0, 152.0], [903.0, 152.0], [903.0, 254.0]],
        ),
        // rear-bracer: bounds 857, 67, 28, 36.
        (
            "rear-bracer",
            [11.15, -2.2, 66.17, 1.0, 1.0, 56.0, 72.0],
            [[857.0, 103.0], [857.0, 67.0], [885.0, 67.0], [885.0, 103.0]],
        ),
    ];
    for (name, numbers, page) in cases {
        let s = slot(name);
        let item = list.items.iter().find(|i| i.slot == s).unwrap_or_else(|| panic!("{name} not drawn"));
        let bone = c.art().slots[s].bone;
        let want = corners(posed.world(bone), numbers);
        let got = &list.vertices[item.vertices.clone()];
        assert!(got.iter().zip(&want).all(|(g, w)| near(*g, *w)), "{name}: {got:?} vs {want:?}");
        let uvs = &list.uvs[item.vertices.clone()];
        let want: Vec<[f64; 2]> = page.iter().map(|p| [p[0] / 1024.0, p[1] / 256.0]).collect();
        assert!(uvs.iter().zip(&want).all(|(g, w)| near(*g, *w)), "{name}: {uvs:?} vs {want:?}");
        assert_eq!(&list.triangles[item.triangles.clone()], &[0, 1, 2, 2, 3, 0]);
        assert_eq!((item.color, item.dark, item.blend), ([1.0; 4], None, BlendMode::Normal));
    }
}

#[test]
fn spineboys_unweighted_mesh_follows_its_bone_and_its_uvs_land_in_its_region() {
    let (c, posed, list, _) = setup(SPINEBOY, SPINEBOY_ATLAS);
    let file: Value = serde_json::from_str(SPINEBOY).unwrap();
    let shin = &file["skins"][0]["attachments"]["front-shin"]["front-shin"];
    let s = c.art().slots.iter().position(|s| s.name == "front-shin").unwrap();
    let item = list.items.iter().find(|i| i.slot == s).unwrap();
    let b = posed.world(c.bone_index("front-shin").unwrap());
    let v: Vec<f64> = shin["vertices"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let uv: Vec<f64> = shin["uvs"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(item.vertices.len(), 52);
    for (k, (got, got_uv)) in
        list.vertices[item.vertices.clone()].iter().zip(&list.uvs[item.vertices.clone()]).enumerate()
    {
        let (x, y) = (v[2 * k], v[2 * k + 1]);
        assert!(near(*got, [b.a * x + b.b * y + b.x, b.c * x + b.d * y + b.y]), "vertex {k}");
        // front-shin: bounds 665, 128, 41, 92, rotate 90: the image's (u, v) lies at page pixel
        // (665 + 92·v, 128 + 41 − 41·u).
        let (u, w) = (uv[2 * k], uv[2 * k + 1]);
        assert!(near(*got_uv, [(665.0 + 92.0 * w) / 1024.0, (169.0 - 41.0 * u) / 256.0]), "uv {k}");
    }
    let triangles: Vec<u32> =
        shin["triangles"].as_array().unwrap().iter().map(|x| x.as_u64().unwrap() as u32).collect();
    assert_eq!(&list.triangles[item.triangles.clone()], &triangles[..]);
}

#[test]
fn spineboys_draw_order_is_the_slots_that_show_a_region_or_mesh_in_file_order() {
    let (c, _, list, regions) = setup(SPINEBOY, SPINEBOY_ATLAS);
    let drawn: Vec<&str> = list.items.iter().map(|i| c.art().slots[i.slot].name.as_str()).collect();
    // The file's slots with a setup `attachment`, in order (the `clipping` slot shows none).
    let want = [
        "rear-upper-arm",
        "rear-bracer",
        "gun",
        "rear-foot",
        "rear-thigh",
        "rear-shin",
        "neck",
        "torso",
        "front-upper-arm",
        "head",
        "eye",
        "front-thigh",
        "front-foot",
        "front-shin",
        "mouth",
        "goggles",
        "front-bracer",
        "front-fist",
    ];
    assert_eq!(drawn, want);
    assert!(list.items.iter().all(|i| i.region.is_some()), "every region is in the atlas");
    let eye = list.items.iter().find(|i| c.art().slots[i.slot].name == "eye").unwrap();
    assert_eq!(regions.get(eye.region.unwrap()).unwrap().name, "eye-indifferent");
    // Slot colours and blend modes: portal-flare1 is `c3cbffff`, additive.
    let flare = c.art().slots.iter().find(|s| s.name == "portal-flare1").unwrap();
    assert_eq!((flare.color, flare.blend), ([195.0 / 255.0, 203.0 / 255.0, 1.0, 1.0], BlendMode::Additive));
    let glow = c.art().slots.iter().find(|s| s.name == "muzzle-glow").unwrap();
    assert_eq!(glow.color, [1.0, 1.0, 1.0, 0.0]);
}

#[test]
fn the_raptors_weighted_meshes_are_weighted_sums_of_their_bones() {
    let (c, posed, list, _) = setup(RAPTOR, RAPTOR_ATLAS);
    let file: Value = serde_json::from_str(RAPTOR).unwrap();
    let mut checked = 0;
    for (slot_name, attachments) in file["skins"][0]["attachments"].as_object().unwrap() {
        for (name, a) in attachments.as_object().unwrap() {
            let uvs = a["uvs"].as_array().map_or(0, Vec::len);
            let v: Vec<f64> =
                a["vertices"].as_array().map_or(vec![], |v| v.iter().map(|x| x.as_f64().unwrap()).collect());
            let s = c.art().slots.iter().position(|s| &s.name == slot_name).unwrap();
            let shown = c.art().slots[s].attachment.as_deref() == Some(name.as_str());
            if a["type"] != "mesh" || v.len() == uvs || !shown {
                continue;
            }
            let item = list.items.iter().find(|i| i.slot == s).unwrap();
            let got = &list.vertices[item.vertices.clone()];
            let (mut i, mut k) = (0, 0);
            while i < v.len() {
                let n = v[i] as usize;
                let mut sum = [0.0, 0.0];
                for j in 0..n {
                    let [bone, x, y, w] = [v[i + 1 + 4 * j], v[i + 2 + 4 * j], v[i + 3 + 4 * j], v[i + 4 + 4 * j]];
                    let m = posed.world(bone as usize);
                    sum[0] += (m.a * x + m.b * y + m.x) * w;
                    sum[1] += (m.c * x + m.d * y + m.y) * w;
                }
                assert!((got[k][0] - sum[0]).abs() < 1e-9 && (got[k][1] - sum[1]).abs() < 1e-9, "{name} vertex {k}");
                i += 1 + 4 * n;
                k += 1;
            }
            assert_eq!(k, got.len(), "{name}");
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked} weighted meshes checked");
}

/// A small character: `arm` is skin-required and the skin `armed` turns it on.
fn armed() -> Value {
    json!({
        "skeleton": {"spine": "4.2.0"},
        "bones": [{"name": "root"}, {"name": "arm", "parent": "root", "x": 10, "skin": true}],
        "slots": [
            {"name": "body", "bone": "root", "attachment": "body", "color": "ff000080", "dark": "00ff00", "blend": "screen"},
            {"name": "arm", "bone": "arm", "attachment": "arm"}
        ],
        "skins": [
            {"name": "default", "attachments": {
                "body": {"body": {"width": 4, "height": 2, "color": "80808080"}},
                "arm": {"arm": {"type": "mesh", "uvs": [0, 0, 1, 0, 0, 1], "triangles": [0, 1, 2], "vertices": [0, 0, 2, 0, 0, 2]}}
            }},
            {"name": "armed", "bones": ["arm"], "attachments": {
                "arm": {"arm": {"type": "linkedmesh", "parent": "arm", "skin": "default", "color": "ffffff00"}}
            }}
        ]
    })
}

#[test]
fn an_inactive_skin_bones_slot_is_not_drawn_and_a_skin_finds_its_own_attachments_first() {
    let c = load_ok(&armed().to_string()).character;
    let draw = |skin: Option<usize>| {
        let mut posed = Posed::default();
        c.pose(&PoseRequest { skin, ..PoseRequest::default() }, &mut posed).unwrap();
        let mut list = DrawList::default();
        c.draw_list(&posed, skin, &Regions::default(), &mut list);
        list
    };
    let plain = draw(c.default_skin());
    assert_eq!(plain.items.len(), 1, "the arm's bone is off without the skin `armed`");
    let body = &plain.items[0];
    assert_eq!((body.slot, body.region, body.blend, body.dark), (0, None, BlendMode::Screen, Some([0.0, 1.0, 0.0])));
    let half = 128.0 / 255.0;
    assert_eq!(body.color, [half, 0.0, 0.0, half * half]);
    assert_eq!(plain.vertices, [[-2.0, -1.0], [-2.0, 1.0], [2.0, 1.0], [2.0, -1.0]]);
    assert_eq!(plain.uvs, [[0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
    let mut by_index = armed();
    by_index["skins"][1]["attachments"]["arm"]["arm"]["skin"] = json!(0);
    let same = load_ok(&by_index.to_string()).character;
    assert_eq!(same.art(), c.art(), "a .skel's skin index finds the same parent");
    let armed = draw(c.skin_index("armed"));
    let slots: Vec<usize> = armed.items.iter().map(|i| i.slot).collect();
    assert_eq!(slots, [0, 1]);
    // `arm` shows the skin's own linked mesh (its colour), with the default skin's mesh's
    // geometry, on the arm bone at x = 10.
    assert_eq!(armed.items[1].color, [1.0, 1.0, 1.0, 0.0]);
    assert_eq!(&armed.vertices[armed.items[1].vertices.clone()], &[[10.0, 0.0], [12.0, 0.0], [10.0, 2.0]]);
    assert_eq!(&armed.triangles[armed.items[1].triangles.clone()], &[0, 1, 2]);
}

#[test]
fn bad_slots_and_attachments_are_refused_naming_field_and_value() {
    let with = |edit: &dyn Fn(&mut Value)| {
        let mut v = armed();
        edit(&mut v);
        refused(&v.to_string())
    };
    let e = with(&|v| v["slots"][0]["color"] = json!("ff00"));
    assert!(e.contains("slots[0] (\"body\").color = \"ff00\": expected 8 hex digits (RRGGBBAA)"), "{e}");
    let e = with(&|v| v["slots"][0]["blend"] = json!("overlay"));
    assert!(
        e.contains("slots[0] (\"body\").blend = \"overlay\": expected normal, additive, multiply or screen"),
        "{e}"
    );
    let e = with(&|v| v["skins"][0]["attachments"]["arm"]["arm"]["triangles"] = json!([0, 1, 3]));
    assert!(e.contains(".arm.arm.triangles[2] = 3: no vertex of that index (3 vertices)"), "{e}");
    let e = with(&|v| v["skins"][1]["attachments"]["arm"]["arm"]["parent"] = json!("leg"));
    assert!(e.contains(".arm.arm.parent = \"leg\": not a mesh of this slot in that skin"), "{e}");
    let e = with(&|v| v["skins"][1]["attachments"]["arm"]["arm"]["skin"] = json!(2));
    assert!(e.contains(".arm.arm.skin = 2: no such skin"), "{e}");
    let e = with(&|v| v["skins"][1]["attachments"]["arm"]["arm"]["skin"] = json!("dressed"));
    assert!(e.contains(".arm.arm.skin = \"dressed\": no such skin"), "{e}");
    let e = with(&|v| v["skins"][0]["attachments"]["arm"]["arm"]["type"] = json!("sprite"));
    assert!(e.contains(".arm.arm.type = \"sprite\": not an attachment type Spine writes"), "{e}");
}

#[test]
fn a_skel_draws_what_its_json_draws() {
    // The binary keeps 32-bit floats where the JSON rounds them: the same slots, regions and
    // triangles, vertices within 0.2 units (examples/characters/README.md: up to about 0.15).
    let bytes = include_bytes!("../../../../examples/characters/spine-spineboy-pro.skel").to_vec();
    let text = super::skel::text_of(bytes, "spineboy.skel").unwrap();
    let (_, _, json, _) = setup(SPINEBOY, SPINEBOY_ATLAS);
    let (c, _, skel, _) = setup(&text, SPINEBOY_ATLAS);
    let slots = |l: &DrawList| l.items.iter().map(|i| (i.slot, i.region, i.blend)).collect::<Vec<_>>();
    assert_eq!(slots(&skel), slots(&json));
    assert_eq!(skel.triangles, json.triangles);
    assert!(
        skel.vertices.iter().zip(&json.vertices).all(|(a, b)| (a[0] - b[0]).abs() < 0.2 && (a[1] - b[1]).abs() < 0.2)
    );
    // The JSON writes UVs with 5 decimals (±5e-6), and a region's share of its page is at most 1.
    assert!(skel.uvs.iter().zip(&json.uvs).all(|(a, b)| (a[0] - b[0]).abs() <= 5e-6 && (a[1] - b[1]).abs() <= 5e-6));
    let flare = c.art().slots.iter().find(|s| s.name == "portal-flare1").unwrap();
    assert_eq!((flare.color, flare.blend), ([195.0 / 255.0, 203.0 / 255.0, 1.0, 1.0], BlendMode::Additive));
}
