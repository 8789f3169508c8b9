//! DragonBones animations: constructed files with answers worked out from the format, the
//! shipped mecha's eight animations posed, and the two-bone bend side after the y flip.

use ikarus::character::{Character, PoseRequest, Posed};

use crate::character::load;

const MECHA: &str = include_str!("../../../../examples/characters/dragonbones-mecha_1406_ske.json");

/// A DragonBones file at 10 frames per second: `root`, `arm` (at (10, 5) y down, skY 30) and
/// the given `ik` and `animation` arrays' contents.
fn file(extra_bones: &str, ik: &str, animation: &str) -> String {
    format!(
        r#"{{"version": "5.5", "frameRate": 10, "armature": [{{"frameRate": 10, "bone": [
             {{"name": "root"}},
             {{"name": "arm", "parent": "root", "length": 4, "transform": {{"x": 10, "y": 5, "skX": 30, "skY": 30}}}}{extra_bones}],
           "ik": [{ik}], "animation": [{animation}]}}]}}"#
    )
}

fn pose(c: &Character, clip: usize, time: f64) -> Posed {
    let mut out = Posed::default();
    c.pose(&PoseRequest { clip: Some((clip, time)), targets: &[], bends: &[], turns: &[], skin: None }, &mut out)
        .unwrap();
    out
}

/// The difference of two angles in radians, wrapped to ±π.
fn turn(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

#[test]
fn frames_key_the_setup_pose_flipped_at_their_times() {
    let animation = r#"{"name": "go", "duration": 20, "bone": [{"name": "arm",
        "translateFrame": [{"duration": 10, "tweenEasing": 0, "x": 2, "y": 4}, {"duration": 10, "x": 6, "y": 8}],
        "rotateFrame": [{"duration": 10, "tweenEasing": 0, "rotate": 170}, {"duration": 0, "rotate": -170}],
        "scaleFrame": [{"duration": 20, "x": 2}]}]}"#;
    let l = load(&file("", "", animation), "f").unwrap();
    let c = &l.character;
    assert_eq!(c.clips()[0].duration, 2.0);
    let arm = c.bone_index("arm").unwrap();
    // Half-way through the first 10 frames (0.5 s): translate (4, 6) y down, rotate 180 (170 to
    // −170 the short way, through 180), scale x 2 (times the setup's 1).
    let p = pose(c, 0, 0.5);
    let local = p.local(arm);
    assert!((local.x - 14.0).abs() < 1e-9 && (local.y + 11.0).abs() < 1e-9, "{local:?}");
    assert!(turn(local.rotation, (-(30.0f64 + 180.0)).to_radians()) < 1e-6, "{}", local.rotation.to_degrees());
    assert!((local.scale_x - 2.0).abs() < 1e-12 && (local.scale_y - 1.0).abs() < 1e-12);
    // After 1 s the translation holds the second frame's (no tweenEasing: stepped).
    let local = pose(c, 0, 1.5).local(arm);
    assert!((local.x - 16.0).abs() < 1e-9 && (local.y + 13.0).abs() < 1e-9, "{local:?}");
    // Between: 0.9 s is 9/10 of the way, linearly.
    let local = pose(c, 0, 0.9).local(arm);
    assert!((local.x - (10.0 + 2.0 + 0.9 * 4.0)).abs() < 1e-6, "{local:?}");
}

#[test]
fn rotations_turn_the_short_way_unless_clockwise_says() {
    // From 0 to −90 (y down): the short way is −90; `clockwise: 1` turns the positive way, 270;
    // `clockwise: 2` a full turn more, 630; `clockwise: -1` the negative way, −90 (already so).
    for (clockwise, turned) in [(0.0, -90.0), (1.0, 270.0), (2.0, 630.0), (-1.0, -90.0)] {
        let animation = format!(
            r#"{{"name": "go", "duration": 10, "bone": [{{"name": "arm", "rotateFrame": [
                {{"duration": 10, "tweenEasing": 0, "rotate": 0, "clockwise": {clockwise}}}, {{"duration": 0, "rotate": -90}}]}}]}}"#
        );
        let l = load(&file("", "", &animation), "f").unwrap();
        // Half-way: half the turn, in y-down degrees (the model's rotation is its negative).
        let got = -pose(&l.character, 0, 0.5).local(1).rotation.to_degrees() - 30.0;
        assert!((got - turned / 2.0).abs() < 1e-4, "clockwise {clockwise}: {got}");
    }
}

#[test]
fn tween_easing_eases_as_dragonbones_does_within_one_percent() {
    // 0 → 100 degrees over 10 frames, eased by e: quadratic out (e in (0, 1]), in (e < 0), and
    // in-out (e > 1, the blend of (1 − cos πp)/2 by e − 1); p = 0.3 and 0.5.
    for e in [0.5, 1.0, -0.7, 1.6, 2.0] {
        let animation = format!(
            r#"{{"name": "go", "duration": 10, "bone": [{{"name": "arm",
                "rotateFrame": [{{"duration": 10, "tweenEasing": {e}, "rotate": 0}}, {{"duration": 0, "rotate": 100}}]}}]}}"#
        );
        let l = load(&file("", "", &animation), "f").unwrap();
        assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
        assert!(
            l.warnings[0].starts_with("animations: 1 frames ease by a tweenEasing other than 0"),
            "{:?}",
            l.warnings
        );
        for p in [0.3, 0.5] {
            let want = if e <= 1.0 {
                p + e * (p - p * p)
            } else {
                let s = (1.0 - (std::f64::consts::PI * p).cos()) / 2.0;
                (s - p) * (e - 1.0) + p
            };
            let got = -pose(&l.character, 0, p).local(1).rotation.to_degrees() - 30.0;
            assert!((got - 100.0 * want).abs() < 1.0, "e {e}, p {p}: {got} against {}", 100.0 * want);
        }
    }
    // null holds the value; a curve is the Bezier it names.
    let animation = r#"{"name": "go", "duration": 20, "bone": [{"name": "arm",
        "rotateFrame": [{"duration": 10, "tweenEasing": null, "rotate": 0}, {"duration": 10, "curve": [0.0, 0.0, 1.0, 1.0], "rotate": 40}, {"duration": 0, "rotate": 80}]}]}"#;
    let l = load(&file("", "", animation), "f").unwrap();
    let at = |t: f64| -pose(&l.character, 0, t).local(1).rotation.to_degrees() - 30.0;
    assert!(at(0.99).abs() < 1e-9 && (at(1.0) - 40.0).abs() < 1e-4, "{} {}", at(0.99), at(1.0));
    assert!((at(1.5) - 60.0).abs() < 1.0, "{}", at(1.5));
}

#[test]
fn ik_frames_key_the_weight_and_the_bend() {
    let bones = r#", {"name": "hand", "parent": "arm", "length": 3, "transform": {"x": 4}},
                   {"name": "goal", "parent": "root", "transform": {"x": 14, "y": 8}}"#;
    let ik = r#"{"name": "reach", "bone": "hand", "target": "goal", "chain": 1}"#;
    let animation = r#"{"name": "go", "duration": 10, "ik": [{"name": "reach", "frame": [
        {"duration": 10, "tweenEasing": 0, "weight": 50, "bendPositive": "false"}, {"duration": 0, "weight": 100}]}]}"#;
    let l = load(&file(bones, ik, animation), "f").unwrap();
    let s = pose(&l.character, 0, 0.0).ik_settings(0).unwrap();
    assert!((s.mix - 0.5).abs() < 1e-12 && !s.bend_positive, "{s:?}");
    let s = pose(&l.character, 0, 0.5).ik_settings(0).unwrap();
    assert!((s.mix - 0.75).abs() < 1e-6 && !s.bend_positive, "{s:?}");
    let s = pose(&l.character, 0, 1.0).ik_settings(0).unwrap();
    assert!((s.mix - 1.0).abs() < 1e-12 && s.bend_positive, "{s:?}");
}

#[test]
fn bad_frames_are_refused_in_one_line() {
    let bones = r#", {"name": "hand", "parent": "arm", "length": 3, "transform": {"x": 4}}"#;
    let ik = r#"{"name": "reach", "bone": "hand", "target": "root", "chain": 1}"#;
    for (animation, want) in [
        (
            r#"{"name": "go", "bone": [{"name": "leg", "rotateFrame": [{"rotate": 1}]}]}"#,
            r#"f: armature[0].animation[0] ("go").bone[0] ("leg").name = "leg": no bone of that name"#,
        ),
        (
            r#"{"name": "go", "bone": [{"name": "arm", "scaleFrame": [{"duration": -2}]}]}"#,
            r#"f: armature[0].animation[0] ("go").bone[0] ("arm").scaleFrame[0].duration = -2: must be a number of frames, at least 0"#,
        ),
        (
            r#"{"name": "go", "ik": [{"name": "reach", "frame": [{"weight": 150}]}]}"#,
            r#"f: armature[0].animation[0] ("go").ik[0] ("reach").frame[0].weight = 150: must be within 0 and 100"#,
        ),
        (
            r#"{"name": "go", "ik": [{"name": "grab", "frame": [{}]}]}"#,
            r#"f: armature[0].animation[0] ("go").ik[0] ("grab").name = "grab": no IK constraint of that name"#,
        ),
        (
            r#"{"name": "go", "bone": [{"name": "arm", "rotateFrame": [{"curve": [0, 1], "rotate": 1}, {"rotate": 2}]}]}"#,
            r#"f: armature[0].animation[0] ("go").bone[0] ("arm").rotateFrame[0].curve: 2 numbers, expected 4 ([x1, y1, x2, y2] of one cubic Bezier)"#,
        ),
    ] {
        let e = load(&file(bones, ik, animation), "f").unwrap_err().to_string();
        assert_eq!(e, want);
    }
}

/// The bend side, worked out from the format: DragonBones' y points down, and `bendPositive`
/// true bends the child by a positive angle there, i.e. turning from +x toward +y (down): the
/// child turns clockwise on the screen. With the root at the origin, the limb along +x and the
/// target on +x within reach, the child can only turn clockwise back onto the target if the
/// elbow is above the root–target line on the screen: y < 0 in the file's y-down terms, y > 0
/// once flipped to y up, and the child's local rotation negative (clockwise) in y-up terms.
/// `bendPositive` false is the mirror image.
#[test]
fn the_bend_side_is_the_formats_after_the_y_flip() {
    for (bend, side) in [("true", 1.0), ("false", -1.0)] {
        let text = format!(
            r#"{{"version": "5.5", "armature": [{{"bone": [
                 {{"name": "root"}},
                 {{"name": "thigh", "parent": "root", "length": 10}},
                 {{"name": "shin", "parent": "thigh", "length": 10, "transform": {{"x": 10}}}},
                 {{"name": "goal", "parent": "root", "transform": {{"x": 15}}}}],
               "ik": [{{"name": "leg", "bone": "shin", "target": "goal", "chain": 1, "bendPositive": {bend}}}]}}]}}"#
        );
        let c = load(&text, "f").unwrap().character;
        let mut p = Posed::default();
        c.pose(&PoseRequest { clip: None, targets: &[], bends: &[], turns: &[], skin: None }, &mut p).unwrap();
        let (shin, goal) = (c.bone_index("shin").unwrap(), c.bone_index("goal").unwrap());
        let elbow = p.origin(shin);
        // The elbow: 10 from the root and from the target at (15, 0): (7.5, ±√(100 − 56.25)).
        let h = (100.0f64 - 7.5 * 7.5).sqrt();
        assert!((elbow[0] - 7.5).abs() < 1e-9 && (elbow[1] - side * h).abs() < 1e-9, "bend {bend}: {elbow:?}");
        assert!(p.local(shin).rotation * side < 0.0, "bend {bend}: {}", p.local(shin).rotation);
        let (tip, target) = (p.tip(shin), p.origin(goal));
        assert!((tip[0] - target[0]).hypot(tip[1] - target[1]) < 1e-9);
    }
}

#[test]
fn the_mechas_animations_pose_with_the_feet_on_their_targets() {
    let l = load(MECHA, "f").unwrap();
    let c = &l.character;
    assert_eq!(c.clips().len(), 8);
    let walk = c.clip_index("walk").unwrap();
    assert!((c.clips()[walk].duration - 30.0 / 24.0).abs() < 1e-12);
    let mut p = Posed::default();
    let mut two_bone = 0;
    for (k, clip) in c.clips().iter().enumerate() {
        for step in 0..=40 {
            let time = clip.duration * f64::from(step) / 40.0;
            c.pose(&PoseRequest { clip: Some((k, time)), targets: &[], bends: &[], turns: &[], skin: None }, &mut p)
                .unwrap();
            for i in 0..c.bones().len() {
                let (o, t) = (p.origin(i), p.tip(i));
                assert!(o.iter().chain(&t).all(|v| v.is_finite()) && p.rotation(i).is_finite(), "{} {time}", clip.name);
            }
            for (j, k) in c.ik_constraints().map(|(_, k)| k).enumerate() {
                let ikarus::character::IkBones::Two { parent, child } = k.bones else { continue };
                two_bone += 1;
                let (root, elbow, tip, target) = (p.origin(parent), p.origin(child), p.tip(child), p.origin(k.target));
                let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
                let (l1, l2, d) = (dist(root, elbow), dist(elbow, tip), dist(root, target));
                // On the target when it is in reach, else straight toward it, as short as the limb;
                // within 0.5 (0.6 % of the limb): the thighs' skew (skX ≠ skY by up to 0.006°),
                // the animated scales and the children's inheritScale false keep the parent's
                // turn from moving the elbow rigidly, so the mecha's feet miss by 0.024 in the
                // setup pose already and by up to 0.24 in `walk` (the two-bone rule's limit
                // with such parents, not the clips'; open).
                let short = (d - (l1 + l2)).max(0.0);
                assert!(
                    (dist(tip, target) - short).abs() < 0.5,
                    "{} at {time}: constraint {j}: tip {tip:?}, target {target:?}, reach {}",
                    clip.name,
                    l1 + l2
                );
            }
        }
    }
    assert_eq!(two_bone, 8 * 41 * 2);
}
