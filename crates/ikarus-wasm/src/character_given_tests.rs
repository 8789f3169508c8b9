use super::super::tests_support::spineboy;
use super::*;

fn walk_at(time: f64) -> Character {
    let mut c = Character::new(&spineboy()).unwrap();
    c.set_animation(Some("walk".to_owned())).unwrap();
    c.sample_into(time).unwrap();
    c
}

#[test]
fn a_sample_given_back_is_the_pose_of_the_animation() {
    let mut c = walk_at(0.4);
    c.world_into([0.0, 0.0, 1.0, 1.0], 0, 0.0).unwrap();
    let mut pose = vec![0.0; c.pose_len()];
    c.pose(0.4, &[], &mut pose).unwrap();
    for (i, (w, p)) in c.given.world.chunks_exact(WORLD).zip(pose.chunks_exact(5)).enumerate() {
        // Degrees to radians and back: within rounding of the pose's numbers.
        assert!((w[4] - p[0]).abs() < 1e-9 && (w[5] - p[1]).abs() < 1e-9, "bone {i}: {w:?} {p:?}");
        assert!((w[2].atan2(w[0]).to_degrees() - p[2]).abs() < 1e-9, "bone {i}");
    }
}

#[test]
fn the_ik_buffer_and_the_placement_are_the_ones_posed() {
    let mut c = walk_at(0.4);
    let names = c.ik_names();
    let leg = names.iter().position(|n| n == "front-leg-ik").unwrap();
    let thigh = c.bones().iter().position(|b| b == "front-thigh").unwrap();
    c.world_into([0.0, 0.0, 1.0, 1.0], 0, 0.0).unwrap();
    let keyed = c.given.world.clone();
    c.given.ik[IK * leg] = 0.0; // mix 0: the thigh keeps the walk's own rotation
    c.world_into([0.0, 0.0, 1.0, 1.0], 0, 0.0).unwrap();
    let off = c.given.world.clone();
    assert_ne!(off[WORLD * thigh..WORLD * thigh + 4], keyed[WORLD * thigh..WORLD * thigh + 4]);
    let l = &c.given.local[LOCAL * thigh..];
    let parent = c.bone_data()[3 * thigh] as usize;
    let p = &off[WORLD * parent..];
    let want = (p[2].atan2(p[0]).to_degrees() + l[2]).rem_euclid(360.0);
    let got = off[WORLD * thigh + 2].atan2(off[WORLD * thigh]).to_degrees().rem_euclid(360.0);
    assert!((got - want).abs() < 1e-9, "{got} {want}");
    c.world_into([5.0, 7.0, -1.0, 1.0], 0, 0.0).unwrap();
    for (i, (m, o)) in c.given.world.chunks_exact(WORLD).zip(off.chunks_exact(WORLD)).enumerate() {
        assert!((m[4] - (5.0 - o[4])).abs() < 1e-9 && (m[5] - (7.0 + o[5])).abs() < 1e-9, "bone {i}");
    }
    let data = c.ik_data();
    assert_eq!(data.len(), 4 * names.len());
    assert_eq!(data[4 * leg + 1] as usize, thigh);
    assert_eq!(c.bone_data().len(), 3 * c.bones().len());
    // The walk moves the thigh (its IK constraint turns it) and keys the leg's IK constraint;
    // it never scales the root.
    let keyed = c.keyed_locals();
    assert_eq!(keyed.len(), LOCAL * c.bones().len());
    assert_eq!([keyed[LOCAL * thigh], keyed[LOCAL * thigh + 1], keyed[LOCAL * thigh + 2], keyed[3]], [1, 1, 0, 0]);
    let keyed_iks = c.keyed_iks();
    assert_eq!(keyed_iks.len(), names.len());
    assert_eq!(keyed_iks[leg], 1);
    assert_eq!(keyed_iks[names.iter().position(|n| n == "aim-ik").unwrap()], 0);
    assert_eq!(c.locals_ptr(), c.given.local.as_ptr() as usize);
    assert_eq!(c.ik_ptr(), c.given.ik.as_ptr() as usize);
    assert_eq!(c.worlds_ptr(), c.given.world.as_ptr() as usize);
}

#[test]
fn bad_numbers_are_refused_naming_them() {
    let mut c = walk_at(0.2);
    let e = c.world_into([0.0, f64::NAN, 1.0, 1.0], 0, 0.0).unwrap_err();
    assert!(e.starts_with("placement: NaN"), "{e:?}");
    let e = c.world_into([0.0, 0.0, 1.0, 1.0], 4, 0.0).unwrap_err();
    assert!(e.starts_with("physics: 4"), "{e:?}");
    c.given.local[LOCAL + 2] = f64::INFINITY;
    let e = c.world_into([0.0, 0.0, 1.0, 1.0], 0, 0.0).unwrap_err();
    assert!(e.starts_with(&format!("bone {:?}: local number 2 is inf", c.bones()[1])), "{e:?}");
    c.sample_into(0.2).unwrap();
    c.given.ik[1] = f64::NAN;
    let e = c.world_into([0.0, 0.0, 1.0, 1.0], 0, 0.0).unwrap_err();
    assert!(e.starts_with(&format!("IK constraint {:?}: number 1 is NaN", c.ik_names()[0])), "{e:?}");
    assert!(c.sample_into(f64::NAN).unwrap_err().starts_with("time: must be"));
    assert!(!c.sample_here(f64::INFINITY) && c.given_error().starts_with("time: must be"));
    assert!(c.sample_here(0.2) && c.given_error().is_empty());
    assert!(!c.world_here(0.0, 0.0, 1.0, 1.0, 9, 0.0) && c.given_error().starts_with("physics: 9"));
}
