//! The rig sets of `ikarus bench --rigs`: target sets made by forward kinematics of seeded
//! random configurations inside the limits, so that every set is jointly reachable, for the
//! shipped puppet and hand.
//!
//! Each set has its own generator, seeded with `--seed` mixed with a stable hash of the rig's
//! and the set's names (as the chain sets are): a set does not change when others are added
//! or left out.

use std::f64::consts::{PI, TAU};

use clap::ValueEnum;
use ikarus::{Goal, Pin, Point2, RigGoal, RigTask, Skeleton};
use ikarus_edge::error::Error;
use ikarus_edge::rig::Rig;

use crate::sets::{SplitMix64, stable_hash};

ikarus::listed_enum! {
    /// The kinds of rig set.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
    pub enum RigSetName {
        /// The puppet, 4 goals: both hands and both feet.
        Puppet,
        /// The puppet, 2 goals (the hands) and 2 pins (the feet, where they start): the generating
        /// configuration keeps the legs at their start angles.
        PuppetPins,
        /// The hand, 5 goals: the fingertips (the bones without children).
        Hand,
    }
}

impl RigSetName {
    /// The name used on the command line and in the output.
    pub fn name(self) -> &'static str {
        match self {
            RigSetName::Puppet => "puppet",
            RigSetName::PuppetPins => "puppet-pins",
            RigSetName::Hand => "hand",
        }
    }

    /// The rig's name.
    pub fn rig(self) -> &'static str {
        match self {
            RigSetName::Puppet | RigSetName::PuppetPins => "puppet",
            RigSetName::Hand => "hand",
        }
    }

    /// The rig file's text, embedded so that the command works from any directory.
    fn text(self) -> &'static str {
        match self {
            RigSetName::Puppet | RigSetName::PuppetPins => include_str!("../../../../examples/rigs/puppet.toml"),
            RigSetName::Hand => include_str!("../../../../examples/rigs/hand.toml"),
        }
    }

    /// Loads the embedded rig.
    pub fn load(self) -> Result<Rig, Error> {
        Rig::parse(self.text(), &format!("built-in rig {}", self.rig()))
    }

    /// The names of the goal bones and of the pinned bones of the set, in their order.
    fn effectors(self, skeleton: &Skeleton) -> (Vec<String>, Vec<String>) {
        let names = |v: &[&str]| v.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
        match self {
            RigSetName::Puppet => (names(&["right_hand", "left_hand", "right_foot", "left_foot"]), Vec::new()),
            RigSetName::PuppetPins => (names(&["right_hand", "left_hand"]), names(&["right_foot", "left_foot"])),
            RigSetName::Hand => {
                let tips = (0..skeleton.len()).filter(|&i| skeleton.children(i).len() == 0);
                (tips.map(|i| skeleton.name(i).to_owned()).collect(), Vec::new())
            }
        }
    }
}

/// One target set: the configuration that generated it and where it puts each goal bone's tip.
#[derive(Debug, Clone)]
pub struct RigCase {
    /// The generating configuration, one angle per bone (radians, inside the limits): the
    /// tests check that it reaches every target.
    #[cfg_attr(not(test), allow(dead_code))]
    pub config: Vec<f64>,
    /// The goal bones' tips under `config`, in the order of [`RigSet::goals`].
    pub targets: Vec<Point2<f64>>,
    /// The goal bones' directions under `config`, radians from +x (not part of the goal:
    /// written to KDL's file for reference only).
    pub directions: Vec<f64>,
    /// The task the library is given: a position goal per goal bone, then the pins.
    pub task: RigTask,
}

/// The target sets of one kind on one rig, and what every solve starts from.
#[derive(Debug, Clone)]
pub struct RigSet {
    /// Which set this is.
    pub set: RigSetName,
    /// The rig's skeleton, with its limits (always enforced).
    pub skeleton: Skeleton,
    /// The start pose of every solve: the rig's.
    pub start: Vec<f64>,
    /// The goal bones, in order.
    pub goals: Vec<usize>,
    /// The pinned bones, in order.
    pub pins: Vec<usize>,
    /// Each pinned bone's tip and direction at the start pose.
    pub pin_targets: Vec<(Point2<f64>, f64)>,
    /// The target sets.
    pub cases: Vec<RigCase>,
}

impl RigSet {
    /// The set's name in the output and in goal files.
    pub fn name(&self) -> &'static str {
        self.set.name()
    }

    /// Every effector's bone: the goals, then the pins.
    pub fn effectors(&self) -> impl Iterator<Item = usize> + '_ {
        self.goals.iter().chain(&self.pins).copied()
    }
}

/// The tips and directions of every bone of `skeleton` at `angles` (tip of bone `i` at
/// `points[i + 1]`).
pub fn forward(skeleton: &Skeleton, angles: &[f64]) -> (Vec<Point2<f64>>, Vec<f64>) {
    let mut points = vec![Point2::origin(); skeleton.len() + 1];
    let mut directions = vec![0.0; skeleton.len()];
    skeleton.points_into(angles, &mut points, &mut directions);
    (points, directions)
}

/// Generates `count` target sets of `set`.
pub fn generate(set: RigSetName, count: usize, seed: u64) -> Result<RigSet, Error> {
    let skeleton = set.load()?.skeleton;
    Ok(generate_on(set, skeleton, count, seed))
}

/// Generates `count` target sets of `set` on `skeleton`, which must have the set's bones.
pub fn generate_on(set: RigSetName, skeleton: Skeleton, count: usize, seed: u64) -> RigSet {
    let index = |name: &String| skeleton.index_of(name).expect("the shipped rigs have the set's bones");
    let (goal_names, pin_names) = set.effectors(&skeleton);
    let goals: Vec<usize> = goal_names.iter().map(index).collect();
    let pins: Vec<usize> = pin_names.iter().map(index).collect();
    let start = skeleton.start_angles().to_vec();
    // The bones that move a pinned tip keep their start angles, so the pins hold where they
    // start.
    let mut frozen = vec![false; skeleton.len()];
    for &p in &pins {
        for b in skeleton.path_to_root(p) {
            frozen[b] = true;
        }
    }
    let (start_points, start_directions) = forward(&skeleton, &start);
    let pin_targets = pins.iter().map(|&p| (start_points[p + 1], start_directions[p])).collect();
    let mut rng = SplitMix64(seed ^ stable_hash(set.rig(), set.name()));
    let cases = (0..count)
        .map(|_| {
            let config: Vec<f64> = skeleton
                .limits()
                .iter()
                .enumerate()
                .map(|(i, lim)| {
                    // Drawn for every bone, frozen or not, so that the sequence stays aligned.
                    let u = rng.unit();
                    match lim {
                        _ if frozen[i] => start[i],
                        Some(l) => l.min() + u * (l.max() - l.min()),
                        None => -PI + u * TAU,
                    }
                })
                .collect();
            let (points, directions) = forward(&skeleton, &config);
            let targets: Vec<Point2<f64>> = goals.iter().map(|&g| points[g + 1]).collect();
            let task = RigTask::new(
                goals
                    .iter()
                    .zip(&targets)
                    .map(|(&g, t)| RigGoal::new(g, Goal::position(t.x, t.y).expect("generated targets are finite")))
                    .collect(),
                pins.iter().map(|&p| Pin::new(p)).collect(),
            );
            RigCase { targets, directions: goals.iter().map(|&g| directions[g]).collect(), config, task }
        })
        .collect();
    RigSet { set, skeleton, start, goals, pins, pin_targets, cases }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::judge::within;

    fn bits(set: &RigSet) -> Vec<u64> {
        set.cases
            .iter()
            .flat_map(|c| c.config.iter().copied().chain(c.targets.iter().flat_map(|t| [t.x, t.y])))
            .map(f64::to_bits)
            .collect()
    }

    #[test]
    fn the_sets_have_their_effectors() {
        let names =
            |s: &RigSet, bones: &[usize]| bones.iter().map(|&b| s.skeleton.name(b).to_owned()).collect::<Vec<_>>();
        let puppet = generate(RigSetName::Puppet, 3, 1).unwrap();
        assert_eq!(names(&puppet, &puppet.goals), ["right_hand", "left_hand", "right_foot", "left_foot"]);
        assert!(puppet.pins.is_empty());
        let pinned = generate(RigSetName::PuppetPins, 3, 1).unwrap();
        assert_eq!(names(&pinned, &pinned.goals), ["right_hand", "left_hand"]);
        assert_eq!(names(&pinned, &pinned.pins), ["right_foot", "left_foot"]);
        let hand = generate(RigSetName::Hand, 3, 1).unwrap();
        assert_eq!(
            names(&hand, &hand.goals),
            ["thumb_distal", "index_distal", "middle_distal", "ring_distal", "little_distal"]
        );
        for s in [&puppet, &pinned, &hand] {
            for c in &s.cases {
                c.task.validate(&s.skeleton).unwrap();
                assert_eq!(c.task.goals.len(), s.goals.len());
                assert_eq!(c.task.pins.len(), s.pins.len());
                assert!(c.task.pins.iter().all(|p| p.orientation), "pins hold the direction too");
            }
        }
    }

    #[test]
    fn every_set_is_jointly_reachable_by_its_configuration() {
        for kind in RigSetName::ALL {
            let s = generate(kind, 300, 4).unwrap();
            for c in &s.cases {
                // Inside the limits.
                for (&a, lim) in c.config.iter().zip(s.skeleton.limits()) {
                    let l = lim.unwrap();
                    assert!(l.contains(a) && within(a, l.min(), l.max()), "{}: {a}", s.name());
                }
                // Every target exactly at its bone's tip, every pin exactly where it starts.
                let (points, directions) = forward(&s.skeleton, &c.config);
                for ((&g, t), goal) in s.goals.iter().zip(&c.targets).zip(&c.task.goals) {
                    assert_eq!(points[g + 1], *t);
                    assert_eq!(goal.goal.target(), *t);
                    assert_eq!(goal.bone, g);
                }
                for (&p, (tip, phi)) in s.pins.iter().zip(&s.pin_targets) {
                    assert_eq!((points[p + 1], directions[p]), (*tip, *phi));
                }
            }
            // The start pose reaches none of them.
            let (points, _) = forward(&s.skeleton, &s.start);
            let far = s.cases.iter().filter(|c| (points[s.goals[0] + 1] - c.targets[0]).norm() > 1e-3).count();
            assert!(far > 290, "{}: {far}", s.name());
        }
    }

    #[test]
    fn sets_are_reproducible_and_independent() {
        for kind in RigSetName::ALL {
            let (a, b) = (generate(kind, 50, 7).unwrap(), generate(kind, 50, 7).unwrap());
            assert_eq!(bits(&a), bits(&b));
            assert_ne!(bits(&a), bits(&generate(kind, 50, 8).unwrap()));
            let short = generate(kind, 5, 7).unwrap();
            assert_eq!(bits(&short)[..], bits(&a)[..bits(&short).len()]);
        }
        // Two sets of one rig differ.
        let (p, q) = (generate(RigSetName::Puppet, 5, 1).unwrap(), generate(RigSetName::PuppetPins, 5, 1).unwrap());
        assert_ne!(p.cases[0].config, q.cases[0].config);
    }

    #[test]
    fn the_pinned_set_keeps_the_legs_still_and_moves_the_rest() {
        let s = generate(RigSetName::PuppetPins, 100, 2).unwrap();
        let legs: Vec<usize> = s.pins.iter().flat_map(|&p| s.skeleton.path(p).to_vec()).collect();
        assert_eq!(legs.len(), 6);
        for c in &s.cases {
            for b in 0..s.skeleton.len() {
                assert_eq!(c.config[b] == s.start[b], legs.contains(&b), "bone {}", s.skeleton.name(b));
            }
        }
    }
}
