use super::*;

use crate::fixtures::{character_bone, rotate_clip, spine_ik};

fn leg() -> CharacterParts {
    let bone = |name: &str, parent: Option<usize>| character_bone(name, parent, 0.0, 0.0);
    CharacterParts {
        bones: vec![bone("root", None), bone("thigh", Some(0)), bone("shin", Some(1)), bone("target", Some(0))],
        constraints: vec![Constraint::Ik(spine_ik(
            "leg",
            0,
            IkBones::Two { parent: 1, child: 2 },
            3,
            IkSettings::default(),
        ))],
        ..CharacterParts::default()
    }
}

#[test]
fn a_well_formed_character_is_taken_and_its_names_found() {
    let c = Character::new(leg()).unwrap();
    assert_eq!(c.bone_index("shin"), Some(2));
    assert_eq!(c.bone_index("arm"), None);
    assert_eq!(c.placement(), Placement::default());
}

#[test]
fn broken_characters_are_refused_by_index() {
    let mut p = leg();
    p.bones[1].parent = Some(2);
    assert_eq!(Character::new(p).unwrap_err(), CharacterError::ParentOrder { bone: 1, parent: 2 });
    let mut p = leg();
    p.bones[2].setup.scale_x = f64::NAN;
    assert!(matches!(Character::new(p).unwrap_err(), CharacterError::NotFinite { bone: 2, field: "scaleX", .. }));
    let mut p = leg();
    let ik = p.constraints[0].ik_mut().unwrap();
    ik.bones = IkBones::Two { parent: 0, child: 2 };
    assert_eq!(Character::new(p).unwrap_err(), CharacterError::NotParentChild { constraint: 0, parent: 0, child: 2 });
    let mut p = leg();
    let ik = p.constraints[0].ik_mut().unwrap();
    ik.setup.mix = 1.5;
    assert_eq!(Character::new(p).unwrap_err().to_string(), "ik[0].mix: out of range, got 1.5");
    let mut p = leg();
    p.clips.push(rotate_clip(1, [(0.5, 0.0), (0.5, 1.0)], Interpolation::Linear, vec![]));
    assert_eq!(Character::new(p).unwrap_err(), CharacterError::KeyTime { clip: 0, time: 0.5 });
    assert_eq!(Character::new(CharacterParts::default()).unwrap_err(), CharacterError::NoBones);
}
