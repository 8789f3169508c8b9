//! Skipping the deferred bones in a pose's first pass changes nothing: random characters (random
//! trees, inherit modes, one- and two-bone constraints by both rules in a random order, targets
//! anywhere in the tree, a clip) posed with the skip and without it give the same world and
//! local transforms, bit for bit.

use super::*;
use crate::character::{CharacterParts, Inherit};
use crate::fixtures::{character_bone, rotate_clip, spine_ik};
use crate::rng::SplitMix64;

fn random_character(rng: &mut SplitMix64) -> Character {
    let n = 2 + (rng.next_u64() % 14) as usize;
    let mut bones = vec![character_bone("b0", None, 0.0, 0.3)];
    for i in 1..n {
        let parent = (rng.next_u64() % i as u64) as usize;
        let mut b = character_bone(&format!("b{i}"), Some(parent), rng.range(-5.0, 10.0), rng.range(-2.0, 2.0));
        b.inherit = Inherit::ALL[(rng.next_u64() % 5) as usize];
        b.setup.scale_x = rng.range(0.5, 1.5);
        bones.push(b);
    }
    let mut constraints = Vec::new();
    for k in 0..(rng.next_u64() % 5) as usize {
        let b = (rng.next_u64() % n as u64) as usize;
        let target = (rng.next_u64() % n as u64) as usize;
        let settings = IkSettings { mix: rng.range(0.2, 1.0), bend_positive: rng.chance(0.5), ..IkSettings::default() };
        let two = bones[b].parent.filter(|_| rng.chance(0.6));
        let ik_bones = match two {
            Some(parent) => IkBones::Two { parent, child: b },
            None => IkBones::One(b),
        };
        let mut c = spine_ik(&format!("ik{k}"), (rng.next_u64() % 4) as u32, ik_bones, target, settings);
        if rng.chance(0.3) {
            c.rule = IkRule::DragonBones;
        }
        constraints.push(c.into());
    }
    let clips = vec![rotate_clip(n - 1, [(0.0, 0.0), (1.0, 1.5)], crate::character::Interpolation::Linear, vec![])];
    Character::new(CharacterParts { bones, constraints, clips, ..CharacterParts::default() }).unwrap()
}

#[test]
fn the_skip_gives_the_same_bits() {
    let mut rng = SplitMix64(27);
    let mut skipped = 0;
    for _ in 0..3000 {
        let c = random_character(&mut rng);
        let mut full = c.clone();
        full.deferred.fill(false);
        skipped += c.deferred.iter().filter(|&&d| d).count();
        let (mut a, mut b) = (Posed::default(), Posed::default());
        for request in [
            PoseRequest::default(),
            PoseRequest { clip: Some((0, 0.4)), targets: &[], bends: &[], turns: &[], skin: None },
        ] {
            // Poses before fill the buffers with other values, as a reused `Posed` has.
            c.pose(&PoseRequest { clip: Some((0, 0.9)), targets: &[], bends: &[], turns: &[], skin: None }, &mut a)
                .unwrap();
            c.pose(&request, &mut a).unwrap();
            full.pose(&request, &mut b).unwrap();
            for i in 0..c.bones.len() {
                assert_eq!(format!("{:?}", a.world(i)), format!("{:?}", b.world(i)), "bone {i} of {c:?}");
                assert_eq!(format!("{:?}", a.local(i)), format!("{:?}", b.local(i)), "bone {i}");
            }
        }
    }
    // The skip is exercised.
    assert!(skipped > 3000, "{skipped} bones skipped");
}
