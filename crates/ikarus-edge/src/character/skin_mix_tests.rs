//! Skin bones and skin constraints used as a mix-and-match character uses them (Spine's user
//! guide, "Skins": bones and constraints added to a skin are active only while it is; the
//! "Mix-and-match" example and the "Skin constraints for different proportions" post: a skin
//! holding a dress's bones and their constraints, a skin holding only a constraint that changes
//! the proportions). Expected positions are worked out by hand from the bones' setup values.

use serde_json::json;

use crate::pose::{IkChoice, PhysicsAsk, PoseAsk, PoseReport, pose};

use super::Loaded;
use super::tests::load_ok;

/// root; `hips` at (0, 100) with `leg` (50 long) hanging down; `small-at` at (0, 80) and `aim` at
/// (30, 40), plain bones. Skin-only: `dress` (40 long, down from the hips) with `dress-tip` (not
/// skin-only) at its end; `hat-base` at (0, 200) with `hat-top` 10 along x.
/// Constraints: `dress-ik` (skin-only) turns the dress toward `aim`; `tip-follow` (plain, after
/// it) puts `dress-tip` on `aim`; `small-hips` (skin-only) moves the hips onto `small-at`;
/// `reach-hat` (plain) turns the leg toward `hat-top`; `leg-sway` (skin-only physics) swings the
/// leg. Skins: `default` (none of them), `dress` (the dress's bone, IK and physics), `small` (the
/// proportions' transform only), `hat` (lists only `hat-top`: its parent comes with it).
fn mix_and_match() -> Loaded {
    let only_move = json!({"mixRotate": 0, "mixX": 1, "mixY": 1, "mixScaleX": 0, "mixScaleY": 0, "mixShearY": 0});
    let with = |mut t: serde_json::Value| {
        t.as_object_mut().unwrap().extend(only_move.as_object().unwrap().clone());
        t
    };
    let text = json!({
        "skeleton": {"spine": "4.2.43"},
        "bones": [
            {"name": "root"},
            {"name": "hips", "parent": "root", "y": 100},
            {"name": "leg", "parent": "hips", "length": 50, "rotation": -90},
            {"name": "small-at", "parent": "root", "y": 80},
            {"name": "aim", "parent": "root", "x": 30, "y": 40},
            {"name": "dress", "parent": "hips", "length": 40, "rotation": -90, "skin": true},
            {"name": "dress-tip", "parent": "dress", "x": 40},
            {"name": "hat-base", "parent": "root", "y": 200, "skin": true},
            {"name": "hat-top", "parent": "hat-base", "x": 10, "skin": true},
        ],
        "ik": [
            {"name": "dress-ik", "order": 1, "bones": ["dress"], "target": "aim", "skin": true},
            {"name": "reach-hat", "order": 3, "bones": ["leg"], "target": "hat-top"},
        ],
        "transform": [
            with(json!({"name": "small-hips", "order": 0, "bones": ["hips"], "target": "small-at", "skin": true})),
            with(json!({"name": "tip-follow", "order": 2, "bones": ["dress-tip"], "target": "aim"})),
        ],
        "physics": [{"name": "leg-sway", "order": 4, "bone": "leg", "x": 1, "skin": true}],
        "skins": [
            {"name": "default"},
            {"name": "dress", "bones": ["dress"], "ik": ["dress-ik"], "physics": ["leg-sway"]},
            {"name": "small", "transform": ["small-hips"]},
            {"name": "hat", "bones": ["hat-top"]},
        ],
        "animations": {"stride": {"bones": {"hips": {"translate": [{"x": 0}, {"time": 1, "x": 100}]}}}},
    });
    load_ok(&text.to_string())
}

fn posed(l: &Loaded, skin: &str) -> PoseReport {
    pose(l, &PoseAsk { skin: Some(skin.to_owned()), ..PoseAsk::default() }).unwrap()
}

/// Bone `name`'s origin, tip and rotation (degrees), and whether it is active.
fn bone(r: &PoseReport, name: &str) -> ([f64; 2], [f64; 2], f64, bool) {
    let b = r.bones.iter().find(|b| b.name == name).unwrap();
    ([b.x, b.y], b.tip, b.rotation_deg, b.active)
}

fn near(a: [f64; 2], b: [f64; 2]) {
    assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9, "{a:?}, expected {b:?}");
}

/// The names of the inactive bones.
fn inactive(r: &PoseReport) -> Vec<&str> {
    r.bones.iter().filter(|b| !b.active).map(|b| b.name.as_str()).collect()
}

#[test]
fn without_its_skin_a_skin_bone_and_what_hangs_from_it_are_inactive_and_unposed() {
    let l = mix_and_match();
    let r = posed(&l, "default");
    assert_eq!(inactive(&r), ["dress", "dress-tip", "hat-base", "hat-top"]);
    // Not posed: at zeros, reported inactive in the JSON, not drawn.
    assert_eq!(bone(&r, "dress-tip"), ([0.0, 0.0], [0.0, 0.0], 0.0, false));
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["bones"][6]["name"], "dress-tip");
    assert_eq!(json["bones"][6]["active"], false);
    let figure = r.figure(None);
    assert_eq!(figure.bones.len(), 5);
    assert!(figure.bones.iter().all(|b| !b.name.starts_with("dress") && !b.name.starts_with("hat")));
    // Every constraint is off: skin-only ones not listed, tip-follow's bone and reach-hat's
    // target inactive. The hips and leg stay as set up; reach-hat's target is not drawn.
    near(bone(&r, "hips").0, [0.0, 100.0]);
    near(bone(&r, "leg").1, [0.0, 50.0]);
    assert_eq!(figure.targets.len(), 1, "dress-ik's aim only");
}

#[test]
fn a_skin_turns_on_its_bones_and_constraints_and_the_plain_ones_that_need_them() {
    let l = mix_and_match();
    let r = posed(&l, "dress");
    assert_eq!(inactive(&r), ["hat-base", "hat-top"]);
    // dress-ik turns the dress from the hips (0, 100) toward aim (30, 40)...
    let (origin, _, rotation, _) = bone(&r, "dress");
    near(origin, [0.0, 100.0]);
    assert!((rotation - (-60.0f64).atan2(30.0).to_degrees()).abs() < 1e-9, "{rotation}");
    // ...and tip-follow, whose bone is now active, puts dress-tip on aim.
    near(bone(&r, "dress-tip").0, [30.0, 40.0]);
    // The proportions' skin moves the hips (and the leg with them) onto small-at.
    let r = posed(&l, "small");
    assert_eq!(inactive(&r), ["dress", "dress-tip", "hat-base", "hat-top"]);
    near(bone(&r, "hips").0, [0.0, 80.0]);
    near(bone(&r, "leg").1, [0.0, 30.0]);
}

#[test]
fn a_listed_bone_brings_its_parent_and_a_plain_constraint_its_target() {
    let l = mix_and_match();
    let r = posed(&l, "hat");
    assert_eq!(inactive(&r), ["dress", "dress-tip"]);
    near(bone(&r, "hat-top").0, [10.0, 200.0]);
    // reach-hat's target is active: the leg turns from (0, 100) toward (10, 200).
    let rotation = bone(&r, "leg").2;
    assert!((rotation - 100.0f64.atan2(10.0).to_degrees()).abs() < 1e-9, "{rotation}");
}

#[test]
fn a_skin_only_physics_constraint_plays_only_with_its_skin() {
    let l = mix_and_match();
    let at = |skin: &str, physics| {
        let ask = PoseAsk {
            skin: Some(skin.to_owned()),
            animation: Some("stride".to_owned()),
            time: Some(0.5),
            physics,
            ..PoseAsk::default()
        };
        bone(&pose(&l, &ask).unwrap(), "leg").1
    };
    let play = PhysicsAsk::Play { fps: 60.0 };
    // The hips half way (50, 100): the leg's tip below them as the clip puts it.
    near(at("dress", PhysicsAsk::Off), [50.0, 50.0]);
    // Without its skin leg-sway does nothing, played or not (the play's frames reach 0.5 s by
    // steps of 1/60, within rounding); with it, the leg lags behind.
    near(at("default", play), [50.0, 50.0]);
    let swung = at("dress", play);
    assert!((swung[0] - 50.0).abs() > 1e-3, "{swung:?}");
}

#[test]
fn a_target_on_an_inactive_bone_is_refused_in_one_line() {
    let l = mix_and_match();
    for ik in [IkChoice::Runtime, IkChoice::Ikarus(Box::default())] {
        let ask = PoseAsk {
            skin: Some("small".to_owned()),
            targets: vec![("dress-tip".to_owned(), [1.0, 2.0])],
            ik,
            ..PoseAsk::default()
        };
        assert_eq!(
            pose(&l, &ask).unwrap_err(),
            "target \"dress-tip\": the bone is inactive with skin \"small\" (a skin-only bone, or below one, that this skin does not turn on), so it cannot be moved"
        );
    }
    // With the skin that turns it on, the target moves it (then tip-follow puts it on aim).
    let ask = PoseAsk {
        skin: Some("dress".to_owned()),
        targets: vec![("dress".to_owned(), [5.0, 5.0])],
        ..PoseAsk::default()
    };
    near(bone(&pose(&l, &ask).unwrap(), "dress").0, [5.0, 5.0]);
}

#[test]
fn ikarus_solver_leaves_the_constraints_a_skin_turns_off_alone() {
    let l = mix_and_match();
    // Per skin, which IK constraints (dress-ik, reach-hat) the solver takes as goals: only
    // those the runtime applies (the skin turns them on, their bones and target are active).
    for (skin, on) in [("default", [false, false]), ("dress", [true, false]), ("hat", [false, true])] {
        let ask = PoseAsk { skin: Some(skin.to_owned()), ik: IkChoice::Ikarus(Box::default()), ..PoseAsk::default() };
        let solved = pose(&l, &ask).unwrap();
        let limbs: Vec<bool> = solved.ik.as_ref().unwrap().constraints.iter().map(|c| c.active).collect();
        assert_eq!(limbs, on, "{skin}");
        assert_eq!(inactive(&solved), inactive(&posed(&l, skin)), "{skin}");
    }
}

#[test]
fn ikarus_solver_refuses_a_goal_or_pin_on_an_inactive_bone() {
    use ikarus::character::{TipGoal, Together};
    use ikarus::{Goal, RigGoal};
    let l = mix_and_match();
    let goal = |bone| TipGoal { goal: RigGoal::new(bone, Goal::position(1.0, 2.0).unwrap()), bones: 1 };
    let ask = |skin: &str, rules: Together| PoseAsk {
        skin: Some(skin.to_owned()),
        ik: IkChoice::Ikarus(Box::new(rules)),
        ..PoseAsk::default()
    };
    // dress (bone 5) and hat-top (bone 8) are off with the default skin.
    let rules = Together { goals: vec![goal(5)], ..Together::default() };
    assert_eq!(
        pose(&l, &ask("default", rules.clone())).unwrap_err(),
        "bone \"dress\": inactive with this skin (a skin-only bone, or below one, that it does not turn on): no goal or pin on it"
    );
    let pins = Together { pins: vec![8], ..Together::default() };
    assert!(pose(&l, &ask("default", pins.clone())).unwrap_err().to_string().starts_with("bone \"hat-top\": inactive"));
    // With the skins that turn them on, they are solved and held.
    pose(&l, &ask("dress", rules)).unwrap();
    pose(&l, &ask("hat", pins)).unwrap();
}
