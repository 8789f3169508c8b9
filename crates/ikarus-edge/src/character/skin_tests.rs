//! Skins read from a Spine file and chosen by name when posing.

use crate::pose::{PoseAsk, pose};

use super::tests::{load_ok, refused};

/// root → arm → hand; `cape` (skin-required) under root, with `tip` below it; `aim` at (0, 10).
/// The IK constraint `reach` (skin-required) turns the arm toward aim; the transform constraint
/// `follow` puts tip on aim. The skin `hero` lists cape and reach.
fn dressed(skins: &str) -> String {
    format!(
        r#"{{"skeleton": {{"spine": "4.2.22"}},
            "bones": [{{"name": "root"}}, {{"name": "arm", "parent": "root", "length": 10}},
              {{"name": "hand", "parent": "arm", "x": 10}}, {{"name": "cape", "parent": "root", "x": 3, "skin": true}},
              {{"name": "tip", "parent": "cape", "x": 5}}, {{"name": "aim", "parent": "root", "y": 10}}],
            "ik": [{{"name": "reach", "bones": ["arm"], "target": "aim", "skin": true}}],
            "transform": [{{"name": "follow", "order": 1, "bones": ["tip"], "target": "aim"}}],
            "skins": {skins}}}"#
    )
}

const SKINS: &str = r#"[{"name": "default"}, {"name": "hero", "bones": ["cape"], "ik": ["reach"]}]"#;

#[test]
fn a_skin_chosen_by_name_turns_its_bones_and_constraints_on() {
    let l = load_ok(&dressed(SKINS));
    let c = &l.character;
    assert_eq!(c.skins().iter().map(|s| s.name.as_str()).collect::<Vec<_>>(), ["default", "hero"]);
    assert_eq!((c.skins()[1].bones.as_slice(), c.skins()[1].constraints.as_slice()), (&[3][..], &[0][..]));
    let hero = pose(&l, &PoseAsk { skin: Some("hero".into()), ..PoseAsk::default() }).unwrap();
    assert!(hero.bones.iter().all(|b| b.active));
    assert!((hero.bones[1].rotation_deg - 90.0).abs() < 1e-9, "{:?}", hero.bones[1]);
    assert!((hero.bones[4].x).abs() < 1e-9 && (hero.bones[4].y - 10.0).abs() < 1e-9, "{:?}", hero.bones[4]);
    // Without a skin named: `default`, which turns neither on.
    let plain = pose(&l, &PoseAsk::default()).unwrap();
    let active: Vec<bool> = plain.bones.iter().map(|b| b.active).collect();
    assert_eq!(active, [true, true, true, false, false, true]);
    assert_eq!(plain.bones[1].rotation_deg, 0.0);
    // The answer says `"active": false` for the inactive bones only.
    let json = serde_json::to_value(&plain).unwrap();
    assert_eq!(json["bones"][3]["active"], serde_json::Value::Bool(false));
    assert!(json["bones"][0].get("active").is_none());
    assert!(plain.text().ends_with("inactive bone \"cape\": the skin does not turn it on (not posed)\ninactive bone \"tip\": the skin does not turn it on (not posed)\n"), "{}", plain.text());
}

#[test]
fn skins_naming_what_does_not_exist_are_refused_in_one_line() {
    assert_eq!(
        refused(&dressed(r#"[{"name": "hero", "bones": ["cap"]}]"#)),
        r#"f: skins[0] ("hero").bones[0] = "cap": no bone of that name"#
    );
    assert_eq!(
        refused(&dressed(r#"[{"name": "hero", "transform": ["reach"]}]"#)),
        r#"f: skins[0] ("hero").transform[0] = "reach": no transform constraint of that name"#
    );
    let l = load_ok(&dressed(SKINS));
    let e = pose(&l, &PoseAsk { skin: Some("villain".into()), ..PoseAsk::default() }).unwrap_err();
    assert_eq!(e, r#"skin "villain": no such skin (the file has: default, hero)"#);
    // An object of skins (older exports): names only.
    let l = load_ok(&dressed(r#"{"default": {}, "hero": {"cape": {}}}"#));
    assert_eq!(l.character.skins().len(), 2);
    assert!(l.character.skins()[1].bones.is_empty());
}
