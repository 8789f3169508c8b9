//! Posing watches its interrupt: a set token stops the runtime's pose and a solve together, and
//! an unset one changes no bit of the pose.

use crate::Interrupt;
use crate::character::{
    Character, CharacterBone, CharacterParts, Constraint, IkBones, IkConstraint, IkRule, IkSettings, Inherit,
    LocalTransform, PoseError, PoseRequest, Posed, Together, TogetherError,
};
use crate::solve::{SolveOptions, Solver};

/// A chain of `n` bones of length 1 under a root target, each with a one-bone constraint
/// aiming it at the target (the chain a hostile file uses to make each pose n² work).
fn aimed_chain(n: usize) -> Character {
    let mut bones = vec![CharacterBone {
        name: "target".into(),
        parent: None,
        length: 0.0,
        setup: LocalTransform { x: 3.0, y: 4.0, ..LocalTransform::default() },
        inherit: Inherit::Normal,
    }];
    for i in 0..n {
        bones.push(CharacterBone {
            name: format!("b{i}"),
            parent: i.checked_sub(1).map(|p| p + 1),
            length: 1.0,
            setup: LocalTransform { x: if i == 0 { 0.0 } else { 1.0 }, rotation: 0.1, ..LocalTransform::default() },
            inherit: Inherit::Normal,
        });
    }
    let constraints = (0..n)
        .map(|i| IkConstraint {
            name: format!("aim{i}"),
            order: i as u32,
            bones: IkBones::One(i + 1),
            target: 0,
            setup: IkSettings::default(),
            uniform: false,
            rule: IkRule::Spine,
        })
        .map(Constraint::from)
        .collect();
    Character::new(CharacterParts { bones, constraints, ..CharacterParts::default() }).unwrap()
}

#[test]
fn an_unset_token_changes_no_bit_and_a_set_one_stops_the_pose() {
    let c = aimed_chain(40);
    let request = PoseRequest::default();
    let (mut plain, mut watched) = (Posed::default(), Posed::default());
    c.pose(&request, &mut plain).unwrap();
    let token = Interrupt::new();
    c.pose_watched(&request, &mut watched, &token).unwrap();
    for i in 0..c.bones().len() {
        assert_eq!(format!("{:?}", plain.world(i)), format!("{:?}", watched.world(i)));
    }
    token.interrupt();
    assert_eq!(c.pose_watched(&request, &mut watched, &token), Err(PoseError::Interrupted));
}

#[test]
fn a_solve_together_stops_on_its_solvers_interrupt() {
    let c = aimed_chain(40);
    let token = Interrupt::new();
    let options = SolveOptions { restarts: None, interrupt: Some(token.clone()), ..SolveOptions::default() };
    let mut solver = Solver::new(options).unwrap();
    let mut out = Posed::default();
    let report = c.pose_together(&PoseRequest::default(), &Together::default(), &mut solver, &mut out).unwrap();
    assert!(report.rounds >= 1, "an unset token lets it solve");
    token.interrupt();
    let e = c.pose_together(&PoseRequest::default(), &Together::default(), &mut solver, &mut out).unwrap_err();
    assert_eq!(e, TogetherError::Pose(PoseError::Interrupted));
    assert_eq!(e.to_string(), "interrupted");
}

/// A chain with a constraint on every bone keeps at most [`LISTED_PER_BONE`] subtree entries a
/// bone (listing them all would be n²/2), and the constraints whose subtree is not listed update
/// the same bones in the same order: the pose is the same, bit for bit, as with every list kept.
#[test]
fn a_constraint_on_every_bone_of_a_chain_keeps_linear_lists_and_the_same_bits() {
    use super::super::flat::{Flat, LISTED_PER_BONE};
    let n = 300;
    let mut c = aimed_chain(n);
    let bones = c.bones().len();
    assert!(c.flat.listed() <= LISTED_PER_BONE * bones, "{} entries for {bones} bones", c.flat.listed());
    let mut lean = Posed::default();
    c.pose(&PoseRequest::default(), &mut lean).unwrap();
    c.flat = Flat::within(&c.bones, c.constraints.iter().map(Constraint::updates), usize::MAX);
    assert_eq!(c.flat.listed(), (1..=n).sum::<usize>(), "every subtree listed");
    let mut full = Posed::default();
    c.pose(&PoseRequest::default(), &mut full).unwrap();
    for i in 0..bones {
        assert_eq!(format!("{:?}", lean.world(i)), format!("{:?}", full.world(i)), "bone {i}");
    }
}
