//! The handle's contract natively: the numbers JavaScript writes in, the numbers it reads out,
//! and the one-line errors.

use ikarus::character::{Character, Inherit, Placement, PoseRequest, Posed, spine_bone_numbers};
use ikarus_spine::{FRAME_NUMBERS, GOAL_NUMBERS, SpineRig};

fn spineboy() -> Character {
    let file = "spine-spineboy-pro.json";
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    ikarus_edge::character::load(&std::fs::read_to_string(path).unwrap(), file).unwrap().character
}

fn rig_of(c: &Character) -> SpineRig {
    let parents: Vec<i32> = c.bones().iter().map(|b| b.parent.map_or(-1, |p| p as i32)).collect();
    let lengths: Vec<f64> = c.bones().iter().map(|b| b.length).collect();
    let inherits: Vec<u8> =
        c.bones().iter().map(|b| Inherit::ALL.iter().position(|&i| i == b.inherit).unwrap() as u8).collect();
    let limits = vec![f64::NAN; 2 * parents.len()];
    SpineRig::attach(&parents, &lengths, &inherits, &limits).unwrap()
}

/// Spineboy walking at `time`, its numbers written into the rig's frame.
fn write_frame(c: &Character, rig: &mut SpineRig, time: f64) -> Posed {
    let mut posed = Posed::default();
    let walk = c.clip_index("walk").unwrap();
    let request = PoseRequest { clip: Some((walk, time)), targets: &[], bends: &[], turns: &[], skin: None };
    c.pose(&request, &mut posed).unwrap();
    for i in 0..posed.len() {
        let (w, l) = (posed.world(i), posed.local(i));
        let v = spine_bone_numbers(&w, &l);
        rig.frame_mut()[i * FRAME_NUMBERS..(i + 1) * FRAME_NUMBERS].copy_from_slice(&v);
    }
    posed
}

fn bone(c: &Character, name: &str) -> usize {
    c.bones().iter().position(|b| b.name == name).unwrap()
}

const PLACED: Placement = Placement { position: [0.0, 0.0], scale: [1.0, 1.0] };

#[test]
fn a_goal_written_at_goals_ptr_moves_the_fist_and_the_rest_keeps_the_frames_numbers() {
    let c = spineboy();
    let mut rig = rig_of(&c);
    let posed = write_frame(&c, &mut rig, 0.4);
    let fist = bone(&c, "front-fist");
    let tip = posed.tip(fist);
    let g = [fist as f64, tip[0] - 40.0, tip[1] + 30.0, 3.0, f64::NAN, 1.0, 0.0, 0.0];
    rig.goals_mut()[..GOAL_NUMBERS].copy_from_slice(&g);
    assert_eq!(rig.max_goals(), c.bones().len());
    assert_eq!(rig.solve(PLACED, 1.0, 0.0).unwrap(), 3);
    assert_eq!(rig.moved()[..3], [fist as f64 - 2.0, fist as f64 - 1.0, fist as f64]);
    assert!(rig.errors()[0] < 1e-3, "{}", rig.errors()[0]);
    for i in (0..c.bones().len()).filter(|&i| i + 2 < fist || i > fist) {
        assert_eq!(rig.rotations()[i].to_bits(), rig.frame()[i * FRAME_NUMBERS + 8].to_bits(), "bone {i}");
    }
    assert_ne!(rig.rotations()[fist - 1], rig.frame()[(fist - 1) * FRAME_NUMBERS + 8]);
}

#[test]
fn bad_input_is_one_line_naming_the_field_and_the_value() {
    let c = spineboy();
    let mut rig = rig_of(&c);
    let posed = write_frame(&c, &mut rig, 0.4);
    let n = c.bones().len();
    let fist = bone(&c, "front-fist");
    let tip = posed.tip(fist);
    let good = [fist as f64, tip[0], tip[1], 3.0, f64::NAN, 1.0, 0.0, 0.0];
    let cases: [(usize, f64, &str); 10] = [
        (0, n as f64, &format!("goals[0].bone: must be a bone index from 0 to {}, got {n}", n - 1)),
        (0, 2.5, &format!("goals[0].bone: must be a bone index from 0 to {}, got 2.5", n - 1)),
        (3, 0.0, "goals[0].bones: must be 1 to"),
        (3, 99.0, "goals[0].bones: must be 1 to"),
        (1, f64::NAN, "goals[0].x: must be finite, got NaN"),
        (4, f64::INFINITY, "goals[0].angle: must be finite or NaN (none), got inf"),
        (5, 0.0, "goals[0].weight: must be finite and > 0, got 0"),
        (5, -1.0, "goals[0].weight: must be finite and > 0, got -1"),
        (6, 2.0, "goals[0].priority: must be 0 (primary) or 1 (secondary), got 2"),
        (7, 0.5, "goals[0].bend: must be 0, 1 or −1, got 0.5"),
    ];
    for (at, v, message) in cases {
        let mut g = good;
        g[at] = v;
        rig.goals_mut()[..GOAL_NUMBERS].copy_from_slice(&g);
        let e = rig.solve(PLACED, 1.0, 0.0).unwrap_err();
        assert!(e.starts_with(message) && !e.contains('\n'), "{e}");
    }
    rig.goals_mut()[..GOAL_NUMBERS].copy_from_slice(&good);
    let e = rig.solve(PLACED, n as f64 + 1.0, 0.0).unwrap_err();
    assert_eq!(e, format!("goals: must be a whole number from 0 to {n}, got {}", n + 1));
    rig.pins_mut()[0] = -1.0;
    let e = rig.solve(PLACED, 1.0, 1.0).unwrap_err();
    assert_eq!(e, format!("pins[0]: must be a bone index from 0 to {}, got -1", n - 1));
    let e = rig.solve(Placement { position: [0.0, f64::NAN], scale: [1.0, 1.0] }, 1.0, 0.0).unwrap_err();
    assert_eq!(e, "y: must be finite, got NaN");
    rig.frame_mut()[3 * FRAME_NUMBERS + 8] = f64::NAN;
    let e = rig.solve(PLACED, 1.0, 0.0).unwrap_err();
    assert_eq!(e, "frame[3].rotation: must be finite, got NaN");
    // applyFrame answers a refusal as −1 with the same line in lastError, and a solve as its count.
    assert_eq!(rig.apply_frame(0.0, 0.0, 1.0, 1.0, 1.0, 0.0), -1.0);
    assert_eq!(rig.last_error(), "frame[3].rotation: must be finite, got NaN");
    write_frame(&c, &mut rig, 0.4);
    assert_eq!(rig.apply_frame(0.0, 0.0, 1.0, 1.0, 1.0, 0.0), 3.0);
}

/// Parents, lengths, inherits, limits and the message they get.
type Skeleton<'a> = (&'a [i32], &'a [f64], &'a [u8], &'a [f64], &'a str);

#[test]
fn a_bad_skeleton_is_refused_in_one_line() {
    let nan = f64::NAN;
    let cases: [Skeleton; 6] = [
        (&[-1, 0], &[1.0], &[0, 0], &[nan; 4], "lengths: must be 2 (one per parent), got 1"),
        (&[-1, 1], &[1.0, 1.0], &[0, 0], &[nan; 4], "parents[1]: must be −1 or a bone before 1, got 1"),
        (&[-1, 0], &[1.0, -2.0], &[0, 0], &[nan; 4], "lengths[1]: must be finite and ≥ 0, got -2"),
        (&[-1, 0], &[1.0, 1.0], &[0, 5], &[nan; 4], "inherits[1]: must be 0 to 4, got 5"),
        (
            &[-1, 0],
            &[1.0, 1.0],
            &[0, 0],
            &[nan, nan, 10.0, -10.0],
            "limits[2..4]: must be NaN, NaN or finite and in order, got 10, -10",
        ),
        (
            &[-1, 0],
            &[1.0, 1.0],
            &[0, 0],
            &[nan, 1.0, nan, nan],
            "limits[0..2]: must be NaN, NaN or finite and in order, got NaN, 1",
        ),
    ];
    for (parents, lengths, inherits, limits, message) in cases {
        let e = SpineRig::attach(parents, lengths, inherits, limits).err().unwrap();
        assert_eq!(e, message);
    }
}
