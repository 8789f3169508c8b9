//! Transform constraints' timelines as Spine's JSON writes them.

use ikarus::character::{Constraint, ConstraintKeys, Interpolation};

use super::tests::{load_ok, refused};

/// A character of two bones and a transform constraint `t`, its animation `a` keyed by `keys`.
fn with_keys(keys: &str) -> String {
    format!(
        r#"{{"skeleton": {{"spine": "4.2.22"}}, "bones": [{{"name": "root"}}, {{"name": "arm", "parent": "root"}}],
            "transform": [{{"name": "t", "bones": ["arm"], "target": "root", "mixX": 0.5}}],
            "animations": {{"a": {{"transform": {{"t": {keys}}}}}}}}}"#
    )
}

#[test]
fn transform_keys_take_the_formats_defaults_and_a_curve_per_mix() {
    let curve: Vec<String> = (0..6).map(|i| format!("0.1, {i}, 0.2, 0.5")).collect();
    let keys = format!(
        r#"[{{"mixRotate": 0.5, "mixScaleX": 0.25, "curve": [{}]}}, {{"time": 1, "mixX": 0}}]"#,
        curve.join(",")
    );
    let l = load_ok(&with_keys(&keys));
    let t = &l.character.clips()[0].constraints[0];
    assert_eq!(t.constraint, 0);
    let ConstraintKeys::Transform(keys) = &t.keys else { panic!("{:?}", t.keys) };
    // Absent mixes are 1, mixY follows mixX and mixScaleY mixScaleX.
    assert_eq!(keys[0].values, [0.5, 1.0, 1.0, 0.25, 0.25, 1.0]);
    assert_eq!(keys[1].values, [1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    assert_eq!(keys[0].curves[3], Interpolation::Bezier { c1: [0.1, 3.0], c2: [0.2, 0.5] });
    assert_eq!(keys[1].time, 1.0);
    // The setup mixes: mixY as mixX.
    let Constraint::Transform(c) = &l.character.constraints()[0] else { panic!() };
    assert_eq!(c.setup.to_array(), [1.0, 0.5, 0.5, 1.0, 1.0, 1.0]);
}

#[test]
fn bad_transform_keys_are_one_line_naming_the_field_and_value() {
    assert_eq!(
        refused(&with_keys(r#"[{"mixShearY": 2}]"#)),
        "f: animations.a.transform.t[0].mixShearY = 2: must be within -1 and 1"
    );
    assert_eq!(
        refused(&with_keys(r#"[{"curve": [0, 0, 1, 1]}, {"time": 1}]"#)),
        "f: animations.a.transform.t[0].curve: 4 numbers, expected 24 ([cx1, cy1, cx2, cy2] per channel)"
    );
    let unknown = with_keys("[{}]").replace(r#""transform": {"t""#, r#""transform": {"u""#);
    assert_eq!(refused(&unknown), "f: animations.a.transform.u: no transform constraint of that name");
}
