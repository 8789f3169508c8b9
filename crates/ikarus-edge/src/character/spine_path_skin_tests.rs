//! A path constraint follows the path the chosen skin shows: the skin's own attachment of the
//! slot's setup attachment name, else the default skin's (Spine's attachment lookup), and only
//! the deform timelines of that attachment.

use serde_json::{Value, json};

use crate::pose::{PoseAsk, pose};

use super::super::tests::load_ok;

/// A straight open path of one curve from `from` to `to` (handles a third of the way out on
/// the line, the control points beyond the ends), unweighted, in the root's frame.
fn straight(from: [f64; 2], to: [f64; 2]) -> Value {
    let d = [(to[0] - from[0]) / 3.0, (to[1] - from[1]) / 3.0];
    let p = |k: f64| [from[0] + d[0] * k, from[1] + d[1] * k];
    let v: Vec<f64> = [-1.0, 0.0, 1.0, 2.0, 3.0, 4.0].iter().flat_map(|&k| p(k)).collect();
    let length = 3.0 * d[0].hypot(d[1]);
    json!({"type": "path", "lengths": [length, 2.0 * length], "vertexCount": 6, "vertices": v})
}

/// Bone `a` (under root, at (0, 10)) put half way along the path slot `s` shows (percent
/// position 0.5, turned along its tangent) by constraint `p`, `skin` marking it skin-only.
/// Skins: `default` shows the path (0, 0) → (90, 0); `b` its own `p`, (0, 0) → (0, 60); `c`
/// nothing on `s` (falls back to the default's); `d` a region called `p` on `s` (no path);
/// `e` nothing, but lists the constraint. Clip `lift`: the default's path raised 5, b's moved
/// 7 along x (deform timelines).
fn file(skin: bool) -> String {
    let lift = |dx: f64, dy: f64| {
        let v = [dx, dy].repeat(6);
        json!({"deform": [{"vertices": v}]})
    };
    json!({
        "skeleton": {"spine": "4.2.43"},
        "bones": [{"name": "root"}, {"name": "a", "parent": "root", "y": 10}],
        "slots": [{"name": "s", "bone": "root", "attachment": "p"}],
        "path": [{"name": "p", "skin": skin, "bones": ["a"], "target": "s", "position": 0.5, "spacingMode": "fixed"}],
        "skins": [
            {"name": "default", "attachments": {"s": {"p": straight([0.0, 0.0], [90.0, 0.0])}}},
            {"name": "b", "path": ["p"], "attachments": {"s": {"p": straight([0.0, 0.0], [0.0, 60.0])}}},
            {"name": "c", "attachments": {}},
            {"name": "d", "attachments": {"s": {"p": {"x": 1, "width": 2, "height": 2}}}},
            {"name": "e", "path": ["p"]},
        ],
        "animations": {"lift": {"attachments": {
            "default": {"s": {"p": lift(0.0, 5.0)}},
            "b": {"s": {"p": lift(7.0, 0.0)}},
        }}},
    })
    .to_string()
}

/// Bone `a`'s world origin and rotation (degrees) posed with `skin`, in clip `lift` or not.
fn a(text: &str, skin: Option<&str>, lift: bool) -> [f64; 3] {
    let l = load_ok(text);
    let ask =
        PoseAsk { skin: skin.map(str::to_owned), animation: lift.then(|| "lift".to_owned()), ..PoseAsk::default() };
    let b = &pose(&l, &ask).unwrap().bones[1];
    [b.x, b.y, b.rotation_deg]
}

fn near(got: [f64; 3], want: [f64; 3]) {
    assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-9), "{got:?}, expected {want:?}");
}

#[test]
fn the_chosen_skin_gives_the_path_else_the_default_skin() {
    let text = file(false);
    // Half of 90 along x; half of 60 up y, turned a quarter.
    near(a(&text, None, false), [45.0, 0.0, 0.0]);
    near(a(&text, Some("default"), false), [45.0, 0.0, 0.0]);
    near(a(&text, Some("b"), false), [0.0, 30.0, 90.0]);
    near(a(&text, Some("c"), false), [45.0, 0.0, 0.0]);
    // A region of that name hides the default's path: the bone stays where its parent puts it.
    near(a(&text, Some("d"), false), [0.0, 10.0, 0.0]);
}

#[test]
fn a_deform_timeline_changes_only_its_own_skins_path() {
    let text = file(false);
    near(a(&text, None, true), [45.0, 5.0, 0.0]);
    near(a(&text, Some("b"), true), [7.0, 30.0, 90.0]);
    near(a(&text, Some("c"), true), [45.0, 5.0, 0.0]);
    near(a(&text, Some("d"), true), [0.0, 10.0, 0.0]);
}

#[test]
fn a_skin_only_constraint_acts_only_with_a_skin_that_lists_it() {
    let text = file(true);
    // Not listed by default nor c: the bone stays.
    near(a(&text, None, false), [0.0, 10.0, 0.0]);
    near(a(&text, Some("c"), false), [0.0, 10.0, 0.0]);
    // b lists it and has its own path; e lists it and shows the default's.
    near(a(&text, Some("b"), false), [0.0, 30.0, 90.0]);
    near(a(&text, Some("e"), false), [45.0, 0.0, 0.0]);
}

#[test]
fn the_constraint_carries_the_default_path_and_each_skins_own() {
    let l = load_ok(&file(false));
    let p = l.character.constraints()[0].path().unwrap();
    assert!(p.path.is_some());
    let own: Vec<(usize, bool)> = p.skin_paths.iter().map(|s| (s.skin, s.path.is_some())).collect();
    assert_eq!(own, [(1, true), (3, false)]);
    assert_eq!((p.path_source(None), p.path_source(Some(0)), p.path_source(Some(1))), (None, None, Some(1)));
    assert_eq!(p.path_source(Some(2)), None);
}
