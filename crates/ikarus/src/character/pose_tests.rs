use crate::character::{
    BoneKey, BoneProperty, BoneTimeline, Character, CharacterBone, CharacterParts, Clip, Inherit, Interpolation,
    LocalTransform, PoseError, PoseRequest, Posed,
};

fn bone(parent: Option<usize>, setup: LocalTransform, inherit: Inherit) -> CharacterBone {
    CharacterBone { name: format!("b{parent:?}"), parent, length: 3.0, setup, inherit }
}

/// A rotated, non-uniformly scaled root, a child, and a grandchild; a clip turning the child.
fn character() -> Character {
    let root =
        LocalTransform { x: 1.0, y: -2.0, rotation: 0.4, scale_x: 2.0, scale_y: 0.5, ..LocalTransform::default() };
    let child = LocalTransform { x: 3.0, y: 1.0, rotation: 0.1, ..LocalTransform::default() };
    let key = |time: f64, v: f64| BoneKey { time, values: [v, 0.0], curves: [Interpolation::Linear; 2] };
    Character::new(CharacterParts {
        bones: vec![
            bone(None, root, Inherit::Normal),
            bone(Some(0), child, Inherit::Normal),
            bone(Some(1), child, Inherit::OnlyTranslation),
        ],
        clips: vec![Clip {
            name: "turn".into(),
            duration: 1.0,
            bones: vec![BoneTimeline {
                bone: 1,
                property: BoneProperty::Rotate,
                keys: vec![key(0.0, 0.0), key(1.0, 1.0)],
            }],
            constraints: vec![],
        }],
        ..CharacterParts::default()
    })
    .unwrap()
}

#[test]
fn a_target_puts_the_bone_origin_on_the_point() {
    let c = character();
    let mut out = Posed::default();
    c.pose(
        &PoseRequest {
            clip: Some((0, 0.5)),
            targets: &[(2, [7.0, 8.0]), (1, [-1.0, 0.5])],
            bends: &[],
            turns: &[],
            skin: None,
        },
        &mut out,
    )
    .unwrap();
    let o = out.origin(1);
    assert!((o[0] + 1.0).abs() < 1e-12 && (o[1] - 0.5).abs() < 1e-12, "{o:?}");
    // The grandchild was placed before its parent moved, and moved with it.
    assert!((out.origin(2)[0] - 7.0).abs() > 1e-3);
    // Only translation: the grandchild's world rotation is its local one.
    assert!((out.rotation(2) - 0.1).abs() < 1e-12);
}

#[test]
fn the_clip_turns_the_bone_and_its_children_follow() {
    let c = character();
    let mut still = Posed::default();
    let mut turned = Posed::default();
    c.pose(&PoseRequest::default(), &mut still).unwrap();
    c.pose(&PoseRequest { clip: Some((0, 0.25)), targets: &[], bends: &[], turns: &[], skin: None }, &mut turned)
        .unwrap();
    assert!((turned.local(1).rotation - 0.35).abs() < 1e-7);
    assert_eq!(turned.origin(1), still.origin(1));
    assert_ne!(turned.origin(2), still.origin(2));
    // The tip is the origin plus the length along the x axis.
    let m = turned.matrix(1);
    let tip = turned.tip(1);
    assert!((tip[0] - turned.origin(1)[0] - 3.0 * m[0]).abs() < 1e-12);
    assert!((tip[1] - turned.origin(1)[1] - 3.0 * m[2]).abs() < 1e-12);
}

#[test]
fn bad_requests_are_refused_by_name() {
    let c = character();
    let mut out = Posed::default();
    let bad = |r: PoseRequest, out: &mut Posed| c.pose(&r, out).unwrap_err();
    assert_eq!(
        bad(PoseRequest { clip: Some((1, 0.0)), targets: &[], bends: &[], turns: &[], skin: None }, &mut out),
        PoseError::UnknownClip(1)
    );
    assert_eq!(
        bad(PoseRequest { clip: Some((0, f64::NAN)), targets: &[], bends: &[], turns: &[], skin: None }, &mut out)
            .to_string(),
        "time: must be finite, got NaN"
    );
    assert_eq!(
        bad(PoseRequest { clip: None, targets: &[(3, [0.0, 0.0])], bends: &[], turns: &[], skin: None }, &mut out),
        PoseError::UnknownBone(3)
    );
    assert!(matches!(
        bad(
            PoseRequest { clip: None, targets: &[(1, [f64::INFINITY, 0.0])], bends: &[], turns: &[], skin: None },
            &mut out
        ),
        PoseError::TargetPoint { bone: 1, .. }
    ));
    let k = c.constraints.len();
    assert_eq!(
        bad(PoseRequest { clip: None, targets: &[], bends: &[(k, true)], turns: &[], skin: None }, &mut out)
            .to_string(),
        format!("bend: no IK constraint {k}")
    );
}

#[test]
fn a_turn_replaces_the_clips_rotation_and_the_children_follow() {
    let c = character();
    let mut clip = Posed::default();
    let mut turned = Posed::default();
    c.pose(&PoseRequest { clip: Some((0, 0.25)), ..PoseRequest::default() }, &mut clip).unwrap();
    c.pose(&PoseRequest { clip: Some((0, 0.25)), turns: &[(1, -0.3)], ..PoseRequest::default() }, &mut turned).unwrap();
    // In place of the clip's 0.35, exactly; the bone stays where it is, its child moves.
    assert_eq!(turned.local(1).rotation, -0.3);
    assert_eq!(turned.origin(1), clip.origin(1));
    assert_ne!(turned.origin(2), clip.origin(2));
    let mut bad = Posed::default();
    assert_eq!(
        c.pose(&PoseRequest { turns: &[(3, 0.0)], ..PoseRequest::default() }, &mut bad).unwrap_err(),
        PoseError::UnknownTurn(3)
    );
    assert_eq!(
        c.pose(&PoseRequest { turns: &[(1, f64::NAN)], ..PoseRequest::default() }, &mut bad).unwrap_err().to_string(),
        "turn: bone 1's rotation must be finite, got NaN"
    );
}
