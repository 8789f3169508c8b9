use super::*;
use crate::character::{
    Character, CharacterParts, Constraint, IkBones, IkSettings, PoseError, PoseRequest, Posed, TransformConstraint,
    TransformMode, TransformOffsets, TransformSettings, TransformSpace,
};
use crate::fixtures::{character_bone, spine_ik};

/// root → arm (10 along x) → hand, and a skin-required `cape` under root with a child `tip`;
/// `aim` (a bone under root at (0, 10)); an IK constraint turning `arm` toward `aim`, skin
/// required; a transform constraint moving `tip` onto `aim`, not skin-required but moving a bone
/// below the skin bone `cape`. Skins: `default` (nothing), `hero` (cape and the IK constraint).
fn dressed() -> Character {
    let bone = |name: &str, parent: Option<usize>, x: f64| character_bone(name, parent, x, 0.0);
    let transform = TransformConstraint {
        name: "follow".into(),
        order: 1,
        bones: vec![4],
        target: 5,
        offsets: TransformOffsets::default(),
        space: TransformSpace::World,
        mode: TransformMode::Absolute,
        setup: TransformSettings::default(),
    };
    Character::new(CharacterParts {
        bones: vec![
            bone("root", None, 0.0),
            bone("arm", Some(0), 0.0),
            bone("hand", Some(1), 10.0),
            bone("cape", Some(0), 3.0),
            bone("tip", Some(3), 5.0),
            {
                let mut aim = bone("aim", Some(0), 0.0);
                aim.setup.y = 10.0;
                aim
            },
        ],
        constraints: vec![
            Constraint::Ik(spine_ik("reach", 0, IkBones::One(1), 5, IkSettings::default())),
            Constraint::Transform(transform),
        ],
        skins: vec![
            Skin { name: "default".into(), ..Skin::default() },
            Skin { name: "hero".into(), bones: vec![3], constraints: vec![0] },
        ],
        skin_required: SkinRequired { bones: vec![3], constraints: vec![0] },
        ..CharacterParts::default()
    })
    .unwrap()
}

fn posed(c: &Character, skin: Option<usize>) -> Posed {
    let mut out = Posed::default();
    c.pose(&PoseRequest { skin, ..PoseRequest::default() }, &mut out).unwrap();
    out
}

#[test]
fn a_skin_turns_on_its_bones_and_constraints() {
    let c = dressed();
    assert_eq!((c.default_skin(), c.skin_index("hero"), c.skin_index("villain")), (Some(0), Some(1), None));
    let hero = posed(&c, Some(1));
    assert!((0..6).all(|i| hero.is_active(i)));
    // The IK constraint turned the arm up toward aim; the transform constraint put tip on aim.
    assert!((hero.rotation(1) - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    let [x, y] = hero.origin(4);
    assert!(x.abs() < 1e-12 && (y - 10.0).abs() < 1e-12, "{x} {y}");
    for skin in [None, Some(0)] {
        let plain = posed(&c, skin);
        // cape and tip (below it) are off and left at zeros; the IK constraint does nothing, and
        // the transform constraint, whose bone is off, neither.
        assert_eq!((0..6).map(|i| plain.is_active(i)).collect::<Vec<_>>(), [true, true, true, false, false, true]);
        assert_eq!(plain.matrix(3), [0.0; 4]);
        assert_eq!(plain.origin(4), [0.0, 0.0]);
        assert_eq!(plain.rotation(1), 0.0);
        assert_eq!(plain.origin(2), [10.0, 0.0]);
    }
}

#[test]
fn a_listed_bone_turns_its_parents_on_and_an_unlisted_parent_turns_its_children_off() {
    let c = dressed();
    let mut parts = CharacterParts {
        bones: c.bones().to_vec(),
        skin_required: SkinRequired { bones: vec![1, 2], constraints: vec![] },
        skins: vec![Skin { name: "hand".into(), bones: vec![2], constraints: vec![] }],
        ..CharacterParts::default()
    };
    let c = Character::new(parts.clone()).unwrap();
    // Listing the hand turns the arm on too.
    let on = posed(&c, Some(0));
    assert!(on.is_active(1) && on.is_active(2));
    let off = posed(&c, None);
    assert!(!off.is_active(1) && !off.is_active(2));
    // A bone not skin-required below an inactive one is inactive.
    parts.skin_required.bones = vec![1];
    parts.skins.clear();
    let off = posed(&Character::new(parts).unwrap(), None);
    assert!(!off.is_active(1) && !off.is_active(2) && off.is_active(3));
}

#[test]
fn unknown_skins_and_indices_are_refused() {
    let c = dressed();
    let mut out = Posed::default();
    assert_eq!(
        c.pose(&PoseRequest { skin: Some(2), ..PoseRequest::default() }, &mut out),
        Err(PoseError::UnknownSkin(2))
    );
    let parts = CharacterParts {
        bones: c.bones().to_vec(),
        skins: vec![Skin { name: "x".into(), bones: vec![9], constraints: vec![] }],
        ..CharacterParts::default()
    };
    assert_eq!(Character::new(parts).unwrap_err().to_string(), "skins[0]: bone 9 does not exist");
    let parts = CharacterParts {
        bones: c.bones().to_vec(),
        skin_required: SkinRequired { bones: vec![], constraints: vec![2] },
        ..CharacterParts::default()
    };
    assert_eq!(Character::new(parts).unwrap_err().to_string(), "skin-required: constraint 2 does not exist");
}

#[test]
fn a_target_on_an_inactive_bone_is_refused() {
    let c = dressed();
    let mut out = Posed::default();
    let targets = [(4, [1.0, 2.0])];
    for skin in [None, Some(0)] {
        let request = PoseRequest { targets: &targets, skin, ..PoseRequest::default() };
        assert_eq!(c.pose(&request, &mut out), Err(PoseError::InactiveTarget(4)));
    }
    assert_eq!(PoseError::InactiveTarget(4).to_string(), "target: bone 4 is inactive: the skin does not turn it on");
    // With the skin that turns it on, the target moves the cape's tip (before `follow` puts it on aim).
    let request = PoseRequest { targets: &[(3, [1.0, 2.0])], skin: Some(1), ..PoseRequest::default() };
    c.pose(&request, &mut out).unwrap();
    assert_eq!(out.origin(3), [1.0, 2.0]);
}
