use ikarus::character::{Constraint, PathConstraint, PathVertices, PositionMode, RotateMode, SpacingMode};
use serde_json::{Value, json};

/// A file with bones `root`, `a`, `b`, a slot `s` on `root` showing path `p`, and `path` as
/// its path constraints; `attachment` replaces the path attachment.
fn file(path: Value, attachment: Option<Value>) -> String {
    let p = attachment.unwrap_or(json!({
        "type": "path", "lengths": [90, 180], "vertexCount": 6,
        "vertices": [-30, 0, 0, 0, 30, 0, 60, 0, 90, 0, 120, 0]
    }));
    json!({
        "skeleton": {"spine": "4.2.43"},
        "bones": [{"name": "root"}, {"name": "a", "parent": "root"}, {"name": "b", "parent": "a"}],
        "slots": [{"name": "s", "bone": "root", "attachment": "p"}],
        "skins": [{"name": "default", "attachments": {"s": {"p": p}}}],
        "path": path,
    })
    .to_string()
}

fn error(path: Value, attachment: Option<Value>) -> String {
    let e = crate::character::load(&file(path, attachment), "t.json").err().unwrap().to_string();
    e.strip_prefix("t.json: ").unwrap_or(&e).to_owned()
}

/// The path constraints of a file's text.
fn paths(text: &str) -> Vec<PathConstraint> {
    let c = crate::character::load(text, "t.json").unwrap().character;
    c.constraints()
        .iter()
        .filter_map(|k| match k {
            Constraint::Path(p) => Some(p.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn defaults_and_modes_are_read() {
    let text = file(json!([{"name": "p", "bones": ["a", "b"], "target": "s"}]), None);
    let p = &paths(&text)[0];
    assert_eq!(
        (p.position_mode, p.spacing_mode, p.rotate_mode),
        (PositionMode::Percent, SpacingMode::Length, RotateMode::Tangent)
    );
    assert_eq!(p.bones, vec![1, 2]);
    assert_eq!((p.setup.mix_rotate, p.setup.mix_x, p.setup.mix_y), (1.0, 1.0, 1.0));
    let path = p.path.as_ref().unwrap();
    assert!(path.constant_speed && !path.closed);
    assert!(matches!(&path.vertices, PathVertices::Plain(v) if v.len() == 6));

    let text = file(
        json!([{"name": "p", "bones": ["a"], "target": "s", "positionMode": "fixed", "spacingMode": "proportional",
                "rotateMode": "chainScale", "rotation": 90, "mixX": 0.5}]),
        None,
    );
    let p = &paths(&text)[0];
    assert_eq!(
        (p.position_mode, p.spacing_mode, p.rotate_mode),
        (PositionMode::Fixed, SpacingMode::Proportional, RotateMode::ChainScale)
    );
    assert_eq!((p.setup.mix_x, p.setup.mix_y), (0.5, 0.5), "mixY defaults to mixX");
    assert!((p.rotation - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
}

#[test]
fn spine_3_8_mix_names_are_read() {
    let text =
        file(json!([{"name": "p", "bones": ["a"], "target": "s", "rotateMix": 0.25, "translateMix": 0.75}]), None);
    let p = &paths(&text)[0];
    assert_eq!((p.setup.mix_rotate, p.setup.mix_x, p.setup.mix_y), (0.25, 0.75, 0.75));
}

#[test]
fn weighted_vertices_are_read() {
    let weighted = json!({"type": "path", "closed": true, "constantSpeed": false, "lengths": [1, 2, 3], "vertexCount": 3,
        "vertices": [1, 1, 5, 6, 1, 2, 1, 2, 1, 0.5, 0, 0, 0.5, 0.5, 1, 2, 1, 2, 1]});
    let text = file(json!([{"name": "p", "bones": ["a"], "target": "s"}]), Some(weighted));
    let p = &paths(&text)[0];
    let path = p.path.as_ref().unwrap();
    assert!(path.closed && !path.constant_speed);
    let PathVertices::Weighted(v) = &path.vertices else { panic!("not weighted") };
    assert_eq!(v.iter().map(Vec::len).collect::<Vec<_>>(), vec![1, 2, 1]);
    assert_eq!((v[1][1].bone, v[1][1].point, v[1][1].weight), (0, [0.0, 0.5], 0.5));
}

#[test]
fn bad_fields_are_refused_naming_the_field_and_value() {
    let one = |extra: Value| {
        let mut p = json!({"name": "aim", "bones": ["a"], "target": "s"});
        p.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        error(json!([p]), None)
    };
    assert_eq!(one(json!({"mixRotate": 3})), "path[0] (\"aim\").mixRotate = 3: must be within −1 and 1");
    assert_eq!(
        one(json!({"rotateMode": "spin"})),
        "path[0] (\"aim\").rotateMode = \"spin\": expected one of tangent, chain, chainScale"
    );
    assert_eq!(one(json!({"target": "t"})), "path[0] (\"aim\").target = \"t\": no slot of that name");
    assert_eq!(one(json!({"bones": ["z"]})), "path[0] (\"aim\").bones[0] = \"z\": no bone of that name");
    assert_eq!(one(json!({"bones": []})), "path[0] (\"aim\").bones: expected at least one bone, got none");
    let bad = json!({"type": "path", "lengths": [1], "vertexCount": 1, "vertices": [1, 7, 0, 0, 1]});
    assert_eq!(
        error(json!([]), Some(bad)),
        "skins[0] (\"default\").attachments.s.p.vertices[1] = 7: no bone of that index (3 bones)"
    );
    let short = json!({"type": "path", "lengths": [1], "vertexCount": 4, "vertices": [0, 0]});
    assert_eq!(
        error(json!([]), Some(short)),
        "skins[0] (\"default\").attachments.s.p.vertexCount = 4: expected a whole number of vertices, at most 2"
    );
}

/// Bone `a` (at (0, 10)) on the straight path from (0, 0) to (90, 0), half way along it, and
/// clips keying the constraint: `slide` its position, `mix` its mixes, `lift` the path's
/// vertices (a deform timeline).
fn keyed() -> ikarus::character::Character {
    let mut v: Value = serde_json::from_str(&file(
        json!([{"name": "p", "bones": ["a"], "target": "s", "position": 0.5, "spacingMode": "fixed"}]),
        None,
    ))
    .unwrap();
    v["bones"][1]["y"] = json!(10);
    v["animations"] = json!({
        "slide": {"path": {"p": {"position": [{"value": 0}, {"time": 1, "value": 0.5}]}}},
        "mix": {"path": {"p": {"mix": [{"mixX": 0.5}]}}},
        "lift": {"attachments": {"default": {"s": {"p": {"deform": [
            {"vertices": [0, 5, 0, 5, 0, 5, 0, 5, 0, 5, 0, 5]}
        ]}}}}},
    });
    crate::character::load(&v.to_string(), "t.json").unwrap().character
}

#[test]
fn clips_key_the_position_the_mixes_and_the_path() {
    use ikarus::character::{PoseRequest, Posed};
    let c = keyed();
    let mut posed = Posed::default();
    let mut at = |clip: Option<&str>, time: f64| {
        let clip = clip.map(|n| (c.clip_index(n).unwrap(), time));
        c.pose(&PoseRequest { clip, ..PoseRequest::default() }, &mut posed).unwrap();
        posed.origin(1)
    };
    let near = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9;
    assert!(near(at(None, 0.0), [45.0, 0.0]));
    // Position 0.25 of the way at half time.
    assert!(near(at(Some("slide"), 0.5), [22.5, 0.0]), "{:?}", at(Some("slide"), 0.5));
    // mixX 0.5, and mixY as mixX.
    assert!(near(at(Some("mix"), 0.0), [22.5, 5.0]), "{:?}", at(Some("mix"), 0.0));
    assert!(near(at(Some("lift"), 0.0), [45.0, 5.0]), "{:?}", at(Some("lift"), 0.0));
}

#[test]
fn bad_timelines_are_refused_naming_the_key() {
    let mut v: Value =
        serde_json::from_str(&file(json!([{"name": "p", "bones": ["a"], "target": "s"}]), None)).unwrap();
    v["animations"] = json!({"m": {"path": {"p": {"mix": [{"mixRotate": 2}]}}}});
    let e = crate::character::load(&v.to_string(), "t.json").err().unwrap().to_string();
    assert!(e.ends_with("animations.\"m\".path.\"p\".mix[0].mixRotate = 2: must be within −1 and 1"), "{e}");
    v["animations"] = json!({"m": {"path": {"q": {"mix": []}}}});
    let e = crate::character::load(&v.to_string(), "t.json").err().unwrap().to_string();
    assert!(e.ends_with("animations.\"m\".path.\"q\": no path constraint of that name"), "{e}");
}

#[test]
fn extreme_and_degenerate_paths_pose_without_panicking() {
    use ikarus::character::{PoseRequest, Posed};
    let degenerate = [
        json!({"type": "path", "lengths": [], "vertexCount": 0, "vertices": []}),
        json!({"type": "path", "closed": true, "lengths": [0, 0], "vertexCount": 6, "vertices": vec![0; 12]}),
        json!({"type": "path", "constantSpeed": false, "lengths": [0, 0], "vertexCount": 6, "vertices": vec![0; 12]}),
        json!({"type": "path", "closed": true, "lengths": [1, 2], "vertexCount": 6,
               "vertices": [-30, 0, 0, 0, 30, 0, 60, 0, 90, 0, 120, 0]}),
    ];
    for attachment in degenerate {
        for (position, spacing) in [(0.0, 0.0), (1e300, -1e300), (-1e300, 1e300), (-0.5, 2.0)] {
            for mode in ["tangent", "chain", "chainScale"] {
                for spacing_mode in ["length", "fixed", "percent", "proportional"] {
                    let text = file(
                        json!([{"name": "p", "bones": ["a", "b"], "target": "s", "position": position, "spacing": spacing,
                                "rotateMode": mode, "spacingMode": spacing_mode}]),
                        Some(attachment.clone()),
                    );
                    let c = crate::character::load(&text, "t.json").unwrap().character;
                    c.pose(&PoseRequest::default(), &mut Posed::default()).unwrap();
                }
            }
        }
    }
}
