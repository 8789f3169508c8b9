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
