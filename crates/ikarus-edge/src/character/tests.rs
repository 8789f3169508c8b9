//! The shipped characters load as NOTES.md counts them, values read as the files write them,
//! defaults apply, and bad files are refused with one line naming the field and the value.

use ikarus::character::{BoneProperty, Character, IkBones, IkRule, Inherit, Interpolation};

use super::*;

const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
const RAPTOR: &str = include_str!("../../../../examples/characters/spine-raptor-pro.json");
const STRETCHYMAN: &str = include_str!("../../../../examples/characters/spine-stretchyman-pro.json");
const MECHA: &str = include_str!("../../../../examples/characters/dragonbones-mecha_1406_ske.json");

pub(super) fn load_ok(text: &str) -> Loaded {
    match load(text, "f") {
        Ok(l) => l,
        Err(e) => panic!("refused: {e}"),
    }
}

pub(super) fn refused(text: &str) -> String {
    match load(text, "f") {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => {
            let e = e.to_string();
            assert!(!e.contains('\n'), "more than one line: {e}");
            e
        }
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn kinds(c: &Character) -> Vec<(String, String)> {
    c.unsupported().iter().map(|u| (u.kind.clone(), u.name.clone())).collect()
}

#[test]
fn every_shipped_character_loads_with_notes_counts() {
    for (text, format, bones, ik, clips) in [
        (SPINEBOY, Format::Spine, 67, 7, 11),
        (RAPTOR, Format::Spine, 76, 9, 5),
        (STRETCHYMAN, Format::Spine, 55, 4, 2),
        (MECHA, Format::DragonBones, 17, 4, 8),
    ] {
        let l = load_ok(text);
        let c = &l.character;
        assert_eq!(
            (l.format, c.bones().len(), c.ik_constraints().count(), c.clips().len()),
            (format, bones, ik, clips)
        );
    }
    let stretchy = load_ok(STRETCHYMAN);
    let transform = kinds(&stretchy.character).iter().filter(|(k, _)| k == "transform").count();
    let path = kinds(&stretchy.character).iter().filter(|(k, _)| k == "path").count();
    // Its 2 transform and 4 path constraints are read (after the IK ones), none unsupported.
    assert_eq!((transform, path, stretchy.character.unsupported().len()), (0, 0, 0));
    let kinds: Vec<&str> = stretchy.character.constraints().iter().map(|k| k.kind()).collect();
    assert_eq!(kinds, ["ik", "ik", "ik", "ik", "transform", "transform", "path", "path", "path", "path"]);
    assert!(stretchy.warnings.is_empty(), "{:?}", stretchy.warnings);
    let boy = load_ok(SPINEBOY);
    let transforms = boy.character.constraints().iter().filter(|c| c.kind() == "transform").count();
    assert_eq!(transforms, 8);
    // Its head's bounding box is what ikarus leaves out (not drawn; its clipping attachment
    // clips the art), said in the unsupported list and a warning.
    let listed: Vec<(&str, &str)> =
        boy.character.unsupported().iter().map(|u| (u.kind.as_str(), u.name.as_str())).collect();
    assert_eq!(listed, [("bounding box attachment", "head (skin default, slot head-bb)")]);
    assert_eq!(
        boy.warnings,
        ["not used by ikarus (left out): bounding box attachment \"head (skin default, slot head-bb)\""]
    );
    assert!(load_ok(RAPTOR).character.unsupported().is_empty() && load_ok(RAPTOR).warnings.is_empty());
    let mecha = load_ok(MECHA);
    assert_eq!(mecha.version, "5.5");
    // Its 8 animations are read (as clips), not listed as unsupported; all its frames ease linearly.
    assert!(mecha.character.unsupported().is_empty() && mecha.warnings.is_empty(), "{:?}", mecha.warnings);
}

#[test]
fn spineboys_values_read_as_the_file_writes_them() {
    let l = load_ok(SPINEBOY);
    assert_eq!(l.version, "4.2.22");
    let c = &l.character;
    // The skeleton's x, y are its bounds, not a placement.
    assert_eq!(c.placement(), ikarus::character::Placement::default());
    let b = |name: &str| &c.bones()[c.bone_index(name).unwrap()];
    assert!(close(b("root").setup.rotation, 0.05f64.to_radians()));
    assert_eq!((b("hip").parent, b("hip").setup.y, b("hip").length), (Some(0), 247.27, 0.0));
    let tip = b("back-foot-tip");
    assert_eq!(tip.parent, c.bone_index("rear-foot"));
    assert_eq!(
        (tip.length, tip.setup.x, tip.setup.y, tip.inherit),
        (50.3, 51.17, 0.24, Inherit::NoRotationOrReflection)
    );
    assert!(close(tip.setup.rotation, (-0.85f64).to_radians()));
    let portal = b("portal-root");
    assert_eq!((portal.setup.scale_x, portal.setup.scale_y, portal.setup.shear_x), (2.0334, 2.0334, 0.0));
    let k = &c.ik(c.ik_constraints().map(|(_, k)| k).position(|k| k.name == "front-leg-ik").unwrap()).unwrap();
    let (thigh, shin) = (c.bone_index("front-thigh").unwrap(), c.bone_index("front-shin").unwrap());
    assert_eq!(
        (k.order, k.bones, k.target),
        (4, IkBones::Two { parent: thigh, child: shin }, c.bone_index("front-leg-target").unwrap())
    );
    assert_eq!((k.setup.mix, k.setup.softness, k.setup.bend_positive, k.rule), (1.0, 0.0, false, IkRule::Spine));
    assert_eq!(c.ik(0).unwrap().setup.mix, 0.0); // aim-ik writes "mix": 0
    // walk: rear-foot-target's first rotate key and translate key, front-leg-ik's keys.
    let walk = &c.clips()[c.clip_index("walk").unwrap()];
    assert_eq!(walk.duration, 1.0);
    let rear = c.bone_index("rear-foot-target").unwrap();
    let rotate = walk.bones.iter().find(|t| t.bone == rear && t.property == BoneProperty::Rotate).unwrap();
    assert_eq!((rotate.keys.len(), rotate.keys[0].time, rotate.keys[1].time), (7, 0.0, 0.1));
    assert!(close(rotate.keys[0].values[0], (-32.82f64).to_radians()));
    let Interpolation::Bezier { c1, c2 } = rotate.keys[0].curves[0] else { panic!("{:?}", rotate.keys[0].curves) };
    assert!(close(c1[0], 0.035) && close(c1[1], (-42.69f64).to_radians()));
    assert!(close(c2[0], 0.057) && close(c2[1], (-70.49f64).to_radians()));
    assert_eq!(rotate.keys[4].curves[0], Interpolation::Linear);
    let translate = walk.bones.iter().find(|t| t.bone == rear && t.property == BoneProperty::Translate).unwrap();
    assert_eq!(translate.keys[0].values, [-167.32, 0.58]);
    assert_eq!(
        translate.keys[0].curves,
        [
            Interpolation::Bezier { c1: [0.022, -180.55], c2: [0.075, -235.51] },
            Interpolation::Bezier { c1: [0.045, 0.58], c2: [0.075, 30.12] }
        ]
    );
    let leg = walk.constraints.iter().find(|t| c.ik(t.constraint).unwrap().name == "front-leg-ik").unwrap();
    let key = &leg.keys.ik().unwrap()[1];
    assert_eq!(
        (key.time, key.settings.mix, key.settings.softness, key.settings.bend_positive),
        (0.0333, 1.0, 9.9, false)
    );
    assert_eq!(key.curves[1], Interpolation::Bezier { c1: [0.15, 9.9], c2: [0.383, 43.2] });
    // Durations count every timeline (death's last key is a slot's or an event's at 4.9333).
    assert_eq!(c.clips()[c.clip_index("death").unwrap()].duration, 4.9333);
    assert_eq!(c.clips().iter().map(|k| k.name.as_str()).collect::<Vec<_>>()[..3], ["aim", "death", "hoverboard"]);
}

const MINIMAL: &str = r#"{"skeleton": {"spine": "4.2.22", "x": -5, "y": 7, "width": 10, "height": 20},
  "bones": [{"name": "root"}, {"name": "a", "parent": "root"}, {"name": "b", "parent": "a"}, {"name": "t", "parent": "root"}],
  "ik": [{"name": "k", "bones": ["a", "b"], "target": "t"}], "slots": [{"name": "s", "bone": "root"}],
  "animations": {"go": {"bones": {"a": {"rotate": [{"value": 10}, {"time": 0.5, "curve": "stepped"}, {"time": 1}],
    "scale": [{}], "inherit": [{"inherit": "noScale"}]}},
    "ik": {"k": [{}]}, "slots": {"s": {"rgba": [{"time": 3, "color": "ffffffff"}]}}}}}"#;

#[test]
fn absent_fields_take_the_formats_defaults() {
    let l = load_ok(MINIMAL);
    let c = &l.character;
    let a = &c.bones()[1];
    assert_eq!((a.length, a.inherit, a.setup), (0.0, Inherit::Normal, ikarus::character::LocalTransform::default()));
    let k = &c.ik(0).unwrap();
    assert_eq!((k.order, k.setup, k.uniform), (0, ikarus::character::IkSettings::default(), false));
    let go = &c.clips()[0];
    assert_eq!(go.duration, 3.0); // the slot's key counts
    assert_eq!(go.bones.len(), 2); // rotate and scale; the inherit timeline is skipped
    let rotate = &go.bones[0];
    assert_eq!(rotate.keys.iter().map(|k| k.values[0]).collect::<Vec<_>>(), [10f64.to_radians(), 0.0, 0.0]);
    assert_eq!(rotate.keys[1].curves, [Interpolation::Stepped; 2]);
    assert_eq!(go.bones[1].keys[0].values, [1.0, 1.0]);
    assert_eq!(go.constraints[0].keys.ik().unwrap()[0].settings, ikarus::character::IkSettings::default());
}

#[test]
fn spine_38_names_and_curves_are_read() {
    let text = r#"{"skeleton": {"spine": "3.8.99"},
      "bones": [{"name": "root"}, {"name": "a", "parent": "root", "transform": "noScale"}],
      "animations": {"go": {"bones": {"a": {"rotate": [{"angle": 10, "curve": 0.25, "c3": 0.75}, {"time": 2, "angle": 30}],
        "translate": [{"x": 1, "y": 2, "curve": 0.5, "c2": 0.1, "c3": 0.6, "c4": 0.9}, {"time": 1, "x": 3, "y": 6}]}}}}}"#;
    let l = load_ok(text);
    assert!(l.warnings.is_empty());
    let c = &l.character;
    assert_eq!(c.bones()[1].inherit, Inherit::NoScale);
    let rotate = &c.clips()[0].bones[0];
    let Interpolation::Bezier { c1, c2 } = rotate.keys[0].curves[0] else { panic!() };
    assert!(close(c1[0], 0.5) && close(c1[1], 10f64.to_radians()));
    assert!(close(c2[0], 1.5) && close(c2[1], 30f64.to_radians()));
    let translate = &c.clips()[0].bones[1];
    let [x, y] = translate.keys[0].curves;
    let (Interpolation::Bezier { c1: x1, c2: x2 }, Interpolation::Bezier { c1: y1, c2: y2 }) = (x, y) else { panic!() };
    assert!(close(x1[0], 0.5) && close(x1[1], 1.2) && close(x2[0], 0.6) && close(x2[1], 2.8));
    assert!(close(y1[0], 0.5) && close(y1[1], 2.4) && close(y2[0], 0.6) && close(y2[1], 5.6));
    let e = load_ok(&text.replace("3.8.99", "3.7.94"));
    assert_eq!(e.warnings.len(), 1, "{:?}", e.warnings);
}

/// A bone's world matrix and origin, y up, composed as the model's doc says (every bone
/// inherits normally).
fn world_up(c: &Character, i: usize) -> ([f64; 4], [f64; 2]) {
    let b = &c.bones()[i];
    let t = &b.setup;
    let (r, sx, sy) = (t.rotation, t.scale_x, t.scale_y);
    let local = [
        (r + t.shear_x).cos() * sx,
        (r + std::f64::consts::FRAC_PI_2 + t.shear_y).cos() * sy,
        (r + t.shear_x).sin() * sx,
        (r + std::f64::consts::FRAC_PI_2 + t.shear_y).sin() * sy,
    ];
    match b.parent {
        None => (local, [t.x, t.y]),
        Some(p) => {
            let ([a, bb, cc, d], [px, py]) = world_up(c, p);
            let m = [
                a * local[0] + bb * local[2],
                a * local[1] + bb * local[3],
                cc * local[0] + d * local[2],
                cc * local[1] + d * local[3],
            ];
            (m, [a * t.x + bb * t.y + px, cc * t.x + d * t.y + py])
        }
    }
}

/// The same in DragonBones' own terms (y down), from the file's numbers.
fn world_down(bones: &[serde_json::Value], name: &str) -> ([f64; 4], [f64; 2]) {
    let b = bones.iter().find(|b| b["name"] == name).unwrap();
    let t = &b["transform"];
    let n = |k: &str, d: f64| t.get(k).and_then(serde_json::Value::as_f64).unwrap_or(d);
    let (skx, sky) = (n("skX", 0.0).to_radians(), n("skY", 0.0).to_radians());
    let local =
        [sky.cos() * n("scX", 1.0), -skx.sin() * n("scY", 1.0), sky.sin() * n("scX", 1.0), skx.cos() * n("scY", 1.0)];
    let (x, y) = (n("x", 0.0), n("y", 0.0));
    match b["parent"].as_str() {
        None => (local, [x, y]),
        Some(p) => {
            let ([a, bb, cc, d], [px, py]) = world_down(bones, p);
            let m = [
                a * local[0] + bb * local[2],
                a * local[1] + bb * local[3],
                cc * local[0] + d * local[2],
                cc * local[1] + d * local[3],
            ];
            (m, [a * x + bb * y + px, cc * x + d * y + py])
        }
    }
}

#[test]
fn dragonbones_bones_are_the_files_flipped_upright() {
    let c = load_ok(MECHA).character;
    let file: serde_json::Value = serde_json::from_str(MECHA).unwrap();
    let bones = file["armature"][0]["bone"].as_array().unwrap();
    // thigh_l on the root (which has no transform): its origin by hand is (0.678, 112.465).
    let thigh = c.bone_index("thigh_l").unwrap();
    let (_, [x, y]) = world_up(&c, thigh);
    assert!(close(x, 0.678) && close(y, 112.465), "{x} {y}");
    // Down the left leg (skewed bones among them), every bone composed normally in both frames:
    // positions and axes match, flipped.
    for name in ["thigh_l", "thigh_1_l", "calf_l"] {
        let i = c.bone_index(name).unwrap();
        let ([a, b, cc, d], [x, y]) = world_up(&c, i);
        let ([a2, b2, c2, d2], [x2, y2]) = world_down(bones, name);
        for (up, down) in [(x, x2), (y, -y2), (a, a2), (b, -b2), (cc, -c2), (d, d2)] {
            assert!((up - down).abs() < 1e-9, "{name}: {up} vs {down}");
        }
    }
    assert_eq!(c.bones()[0].inherit, Inherit::NoScale); // inheritScale: false
    assert_eq!(c.bones()[thigh].inherit, Inherit::Normal);
    let calf = &c.ik(2).unwrap();
    let (calf_l, knee) = (c.bone_index("calf_l").unwrap(), c.bone_index("thigh_1_l").unwrap());
    assert_eq!(c.bones()[knee].inherit, Inherit::NoScale);
    assert_eq!(
        (calf.bones, calf.target, calf.rule),
        (IkBones::Two { parent: knee, child: calf_l }, c.bone_index("foot_l").unwrap(), IkRule::DragonBones)
    );
    assert!(!calf.setup.bend_positive);
    assert_eq!(
        (c.ik(0).unwrap().bones, c.ik(0).unwrap().setup.mix, c.ik(0).unwrap().order),
        (IkBones::One(thigh), 1.0, 0)
    );
}

#[test]
fn dragonbones_flags_may_be_strings() {
    let text = |bend: &str| {
        format!(
            r#"{{"version": "5.5", "frameRate": 24, "armature": [{{"bone": [{{"name": "root"}}, {{"name": "a", "parent": "root", "length": 5}},
            {{"name": "b", "parent": "a", "length": 5}}], "ik": [{{"name": "k", "bone": "b", "target": "root", "chain": 1, "bendPositive": {bend}}}]}}]}}"#
        )
    };
    assert!(!load_ok(&text("\"false\"")).character.ik(0).unwrap().setup.bend_positive);
    assert!(load_ok(&text("\"true\"")).character.ik(0).unwrap().setup.bend_positive);
    assert!(!load_ok(&text("false")).character.ik(0).unwrap().setup.bend_positive);
    let e = refused(&text("\"maybe\""));
    assert!(e.starts_with("f: armature[0].ik[0].bendPositive: expected true or false, got \"maybe\""), "{e}");
    let e = refused(&text("1"));
    assert!(e.starts_with("f: armature[0].ik[0].bendPositive: expected true or false, got 1"), "{e}");
    let e = refused(&text("true").replace("\"chain\": 1", "\"chain\": 2"));
    assert_eq!(e, "f: armature[0].ik[0] (\"k\").chain = 2: expected 0 (one bone) or 1 (two bones)");
}

#[test]
fn bad_files_are_refused_with_one_line_naming_field_and_value() {
    let e = refused(&MINIMAL.replace(r#""parent": "a"}"#, r#""parent": "x"}"#));
    assert_eq!(e, "f: bones[2] (\"b\").parent = \"x\": no bone of that name");
    let swapped = MINIMAL.replace(
        r#"{"name": "a", "parent": "root"}, {"name": "b", "parent": "a"}"#,
        r#"{"name": "b", "parent": "a"}, {"name": "a", "parent": "root"}"#,
    );
    assert_eq!(refused(&swapped), "f: bones[1] (\"b\").parent = \"a\": listed after this bone (a parent comes first)");
    let e = refused(&MINIMAL.replace(r#"{"name": "root"}"#, r#"{"name": "root", "rotation": "ten"}"#));
    assert!(e.starts_with("f: bones[0].rotation: invalid type: string \"ten\", expected f64"), "{e}");
    let e = refused(&MINIMAL.replace(r#""curve": "stepped""#, r#""curve": "smooth""#));
    assert!(e.starts_with("f: animations.go.bones.a.rotate[1].curve: invalid value: string \"smooth\""), "{e}");
    // (what is replaced, by what, the line)
    for (from, to, want) in [
        (r#""target": "t""#, r#""target": "z""#, r#"f: ik[0] ("k").target = "z": no bone of that name"#),
        (r#"["a", "b"]"#, r#"["a", "q"]"#, r#"f: ik[0] ("k").bones[1] = "q": no bone of that name"#),
        (r#"["a", "b"]"#, r#"["root", "b"]"#, r#"f: ik[0] ("k").bones[1] = "b": not a child of "root""#),
        (r#"["a", "b"]"#, r#"["root", "a", "b"]"#, r#"f: ik[0] ("k").bones: expected one or two bones, got 3"#),
        (
            r#""curve": "stepped""#,
            r#""curve": [0.1, 2, 0.3]"#,
            "f: animations.go.bones.a.rotate[1].curve: 3 numbers, expected 4 ([cx1, cy1, cx2, cy2] per channel)",
        ),
        (
            r#"{"time": 1}"#,
            r#"{"time": 0.5}"#,
            "f: animations.go.bones.a.rotate[2].time = 0.5: must be after the previous key's, 0.5",
        ),
        (r#""bones": {"a""#, r#""bones": {"zz""#, "f: animations.go.bones.zz: no bone of that name"),
        (r#""ik": {"k""#, r#""ik": {"kk""#, "f: animations.go.ik.kk: no IK constraint of that name"),
        (r#""target": "t"}"#, r#""target": "t", "mix": 2}"#, r#"f: ik[0] ("k").mix = 2: must be within 0 and 1"#),
        (
            r#""ik": {"k": [{}]"#,
            r#""ik": {"k": [{"mix": -1}]"#,
            "f: animations.go.ik.k[0].mix = -1: must be within 0 and 1",
        ),
        (
            r#"{"name": "t", "parent": "root"}"#,
            r#"{"name": "a", "parent": "root"}"#,
            r#"f: bones[3].name = "a": also the name of bones[1]"#,
        ),
        (
            r#"{"name": "root"}"#,
            r#"{"name": "root", "length": -1}"#,
            r#"f: bones[0] ("root").length = -1: must not be negative"#,
        ),
    ] {
        assert!(MINIMAL.contains(from), "{from}");
        assert_eq!(refused(&MINIMAL.replacen(from, to, 1)), want);
    }
    let e = refused(&MINIMAL[..MINIMAL.len() / 2]);
    assert!(e.starts_with("f: malformed JSON: EOF while parsing"), "{e}");
    assert!(refused("{\"bones\": []}").starts_with("f: not a character file: expected a Spine skeleton"));
}

#[test]
fn the_format_is_told_from_the_content_and_bones_are_capped() {
    assert!(is_json(" \n{") && !is_json("[[bones]]") && !is_json("name = \"{\""));
    let cap = BoneCap { max: 3, raise: "--max-bones" };
    let e = load_within(MINIMAL, "f", cap).unwrap_err().to_string();
    assert_eq!(e, "f: bones: 4 bones exceed the cap of 3 (--max-bones)");
    let e = load_within(MECHA, "f", cap).unwrap_err().to_string();
    assert_eq!(e, "f: bones: 17 bones exceed the cap of 3 (--max-bones)");
}

#[test]
fn a_character_file_given_for_a_rig_is_read_and_named_for_what_it_is() {
    let e = not_a_rig(SPINEBOY, "rig file s.json").unwrap_err().to_string();
    let want = "rig file s.json: a Spine character (67 bones, 7 IK constraints), which this command does not take: it takes rig files (TOML); pose, solve, animate and track take characters";
    assert_eq!(e, want);
    let e =
        not_a_rig("{\"skeleton\": {\"spine\": \"4.2\"}, \"bones\": [{}]}", "rig file s.json").unwrap_err().to_string();
    assert_eq!(e, "rig file s.json: bones[0]: missing field `name` at line 1 column 43");
    assert!(not_a_rig("[[bones]]\nname = \"a\"\nlength = 1\n", "r").is_ok());
    let body = crate::body::Body::load(
        None,
        Some(std::path::Path::new("../../examples/characters/dragonbones-mecha_1406_ske.json")),
    );
    let e = body.err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.ends_with("a DragonBones character (17 bones, 4 IK constraints), which this command does not take: it takes rig files (TOML); pose, solve, animate and track take characters"), "{e}");
}
