//! The goal sets of `ikarus bench`: for each arm, five sets of goals drawn from a small,
//! portable, seeded generator, so that every machine (and KDL) solves the same goals, bit for
//! bit.
//!
//! Each set has its own generator, seeded with `--seed` mixed with a stable hash of the arm's
//! and the set's names: a set does not change when other arms or sets are added or left out.

use std::f64::consts::{PI, TAU};

use clap::ValueEnum;
use ikarus::kinematics::end_effector;
use ikarus::solve::wrap_angle;
use ikarus::{Chain, Goal};
use ikarus_edge::arm::{Arm, DEFAULT_ARM};
use ikarus_edge::error::Error;

/// Goals of the `unreachable` set lie this many maximal reaches from the base, at the least…
const BEYOND_MIN: f64 = 1.05;
/// …and at the most.
const BEYOND_MAX: f64 = 2.0;
/// Goals in the inner hole lie at most this share of the minimal reach from the base.
const HOLE_MAX: f64 = 0.95;

ikarus::listed_enum! {
    /// The arms `ikarus bench` knows, embedded in the binary so that the command works from any
    /// directory.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
    pub enum ArmName {
        /// The built-in seed arm: 3 links of lengths 3, 2, 1.
        Seed,
        /// `examples/arms/seven.toml`: 7 tapering links.
        Seven,
        /// `examples/arms/tentacle.toml`: 20 short links.
        Tentacle,
    }
}

impl ArmName {
    /// The name used on the command line and in the output.
    pub fn name(self) -> &'static str {
        match self {
            ArmName::Seed => "seed",
            ArmName::Seven => "seven",
            ArmName::Tentacle => "tentacle",
        }
    }

    /// The arm file's text.
    fn text(self) -> &'static str {
        match self {
            ArmName::Seed => DEFAULT_ARM,
            ArmName::Seven => include_str!("../../../examples/arms/seven.toml"),
            ArmName::Tentacle => include_str!("../../../examples/arms/tentacle.toml"),
        }
    }

    /// Loads the embedded arm.
    pub fn load(self) -> Result<Arm, Error> {
        Arm::parse(self.text(), &format!("built-in arm {}", self.name()))
    }
}

ikarus::listed_enum! {
    /// The kinds of goal set.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
    pub enum SetName {
        /// Positions of configurations drawn with every joint free; limits off.
        FreePosition,
        /// The same, with the tip's orientation part of the goal.
        FreeOriented,
        /// Positions of configurations drawn inside the joint limits; limits enforced.
        LimitsPosition,
        /// The same, with the tip's orientation part of the goal.
        LimitsOriented,
        /// Positions no pose can reach (beyond the outer radius, or inside the inner hole);
        /// limits off. "Reached" means the best pose: as close as the arm can get.
        Unreachable,
    }
}

impl SetName {
    /// The name used on the command line and in the output.
    pub fn name(self) -> &'static str {
        match self {
            SetName::FreePosition => "free-position",
            SetName::FreeOriented => "free-oriented",
            SetName::LimitsPosition => "limits-position",
            SetName::LimitsOriented => "limits-oriented",
            SetName::Unreachable => "unreachable",
        }
    }

    /// Whether the goals include the tip's orientation.
    pub fn oriented(self) -> bool {
        matches!(self, SetName::FreeOriented | SetName::LimitsOriented)
    }

    /// Whether the joint limits are enforced (and judged).
    pub fn limited(self) -> bool {
        matches!(self, SetName::LimitsPosition | SetName::LimitsOriented)
    }
}

/// One goal as written to a goal file: a position and the orientation `phi` of the last link
/// (radians from +x, in [−π, π)). `phi` is kept for position goals too, because KDL's NR_JL
/// solver cannot leave the orientation free.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchGoal {
    /// Goal x.
    pub x: f64,
    /// Goal y.
    pub y: f64,
    /// Orientation of the last link: of the configuration that generated the goal, or, for
    /// the `unreachable` set, the direction of the goal seen from the base.
    pub phi: f64,
    /// The joint angles that generated the goal; empty for the `unreachable` set.
    pub config: Vec<f64>,
}

/// The goals of one arm and set, and what a solve of them starts from.
#[derive(Debug, Clone)]
pub struct GoalSet {
    /// The arm's name.
    pub arm: &'static str,
    /// Which set this is.
    pub set: SetName,
    /// The arm's chain, with its limits (whether they are enforced depends on the set).
    pub chain: Chain,
    /// The start pose of every solve: the arm's start pose, clamped into the limits for the
    /// limits sets.
    pub start: Vec<f64>,
    /// The goals, as generated.
    pub goals: Vec<BenchGoal>,
    /// The same goals as the library takes them (with the orientation for oriented sets).
    pub targets: Vec<Goal>,
}

impl GoalSet {
    /// Builds a set from its goals.
    pub fn new(arm: &'static str, set: SetName, chain: Chain, goals: Vec<BenchGoal>) -> Self {
        let mut start = chain.start_pose().angles().to_vec();
        if set.limited() {
            for (a, lim) in start.iter_mut().zip(chain.limits()) {
                if let Some(l) = lim {
                    *a = l.clamp(*a);
                }
            }
        }
        let targets = goals
            .iter()
            .map(|g| {
                if set.oriented() { Goal::with_orientation(g.x, g.y, g.phi) } else { Goal::position(g.x, g.y) }
                    .expect("generated goals are finite")
            })
            .collect();
        Self { arm, set, chain, start, goals, targets }
    }

    /// `ARM-SET`, the set's name in goal files and file names.
    pub fn name(&self) -> String {
        format!("{}-{}", self.arm, self.set.name())
    }
}

/// Generates `count` goals of `set` for the arm `arm` with `chain`.
pub fn generate(arm: &'static str, chain: &Chain, set: SetName, count: usize, seed: u64) -> GoalSet {
    let mut rng = SplitMix64(seed ^ stable_hash(arm, set.name()));
    let goals = (0..count)
        .map(|i| {
            if set == SetName::Unreachable {
                unreachable_goal(chain, i, &mut rng)
            } else {
                reachable_goal(chain, set, &mut rng)
            }
        })
        .collect();
    GoalSet::new(arm, set, chain.clone(), goals)
}

/// A configuration drawn uniformly (inside the limits for the limits sets, else every angle in
/// [−π, π)), and its tip.
fn reachable_goal(chain: &Chain, set: SetName, rng: &mut SplitMix64) -> BenchGoal {
    let config: Vec<f64> = chain
        .limits()
        .iter()
        .map(|lim| {
            let u = rng.unit();
            match lim {
                Some(l) if set.limited() => l.min() + u * (l.max() - l.min()),
                _ => -PI + u * TAU,
            }
        })
        .collect();
    let tip = end_effector(chain, &config);
    BenchGoal { x: tip.position.x, y: tip.position.y, phi: wrap_angle(tip.orientation), config }
}

/// Goal `index` of the `unreachable` set: a uniformly random direction, at a distance uniform
/// in [1.05, 2]·max_reach from the base; if the arm has an inner hole, every odd goal lies in
/// it instead, at a distance uniform in [0, 0.95]·min_reach.
fn unreachable_goal(chain: &Chain, index: usize, rng: &mut SplitMix64) -> BenchGoal {
    let direction = -PI + rng.unit() * TAU;
    let u = rng.unit();
    let distance = if chain.min_reach() > 0.0 && index % 2 == 1 {
        u * HOLE_MAX * chain.min_reach()
    } else {
        (BEYOND_MIN + u * (BEYOND_MAX - BEYOND_MIN)) * chain.max_reach()
    };
    let base = chain.base();
    BenchGoal {
        x: base.x + distance * direction.cos(),
        y: base.y + distance * direction.sin(),
        phi: direction,
        config: Vec::new(),
    }
}

/// FNV-1a (64 bits) of `arm`, a zero byte and `set`: a hash that does not change between
/// Rust versions or machines.
pub(crate) fn stable_hash(arm: &str, set: &str) -> u64 {
    let mut h: u64 = 0xCBF2_9CE4_8422_2325;
    for &b in arm.as_bytes().iter().chain(&[0u8]).chain(set.as_bytes()) {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01B3);
    }
    h
}

pub use ikarus::rng::SplitMix64;

#[cfg(test)]
mod tests {
    use super::*;

    fn all_sets(count: usize, seed: u64) -> Vec<GoalSet> {
        let mut sets = Vec::new();
        for arm in ArmName::ALL {
            let chain = arm.load().unwrap().chain;
            for set in SetName::ALL {
                sets.push(generate(arm.name(), &chain, set, count, seed));
            }
        }
        sets
    }

    fn bits(set: &GoalSet) -> Vec<u64> {
        set.goals
            .iter()
            .flat_map(|g| [g.x, g.y, g.phi].into_iter().chain(g.config.iter().copied()))
            .map(f64::to_bits)
            .collect()
    }

    #[test]
    fn sets_are_reproducible_bit_for_bit() {
        let (a, b) = (all_sets(100, 7), all_sets(100, 7));
        for (a, b) in a.iter().zip(&b) {
            assert_eq!(bits(a), bits(b), "{}", a.name());
            assert_eq!(
                a.start.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                b.start.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
            );
        }
        // Another seed, another set; the same seed with fewer goals, the same first goals.
        let c = all_sets(100, 8);
        assert_ne!(bits(&a[0]), bits(&c[0]));
        let short = all_sets(10, 7);
        assert_eq!(bits(&short[3])[..], bits(&a[3])[..bits(&short[3]).len()]);
    }

    #[test]
    fn a_set_does_not_depend_on_the_others() {
        let chain = ArmName::Seven.load().unwrap().chain;
        let alone = generate("seven", &chain, SetName::LimitsOriented, 20, 1);
        let among = &all_sets(20, 1)[3 + 5];
        assert_eq!(among.name(), "seven-limits-oriented");
        assert_eq!(bits(&alone), bits(among));
    }

    #[test]
    fn the_first_goal_of_seed_limits_position_is_pinned() {
        // Pinned so that a change of the generator (or of the seed arm) is noticed: goal files
        // written by earlier versions would no longer be what `ikarus bench` solves.
        let chain = ArmName::Seed.load().unwrap().chain;
        let set = generate("seed", &chain, SetName::LimitsPosition, 1, 1);
        let g = &set.goals[0];
        assert_eq!([g.x.to_bits(), g.y.to_bits(), g.phi.to_bits()], PINNED_SEED_LIMITS_POSITION);
    }

    /// Bits of x, y, phi of the first goal of `seed`/`limits-position` with seed 1:
    /// 3.583011516082418, -1.843249808515066, -1.7370233428393749 (checked against an
    /// independent Python implementation of the generator; y moved by one ulp, from
    /// -1.8432498085150661, when forward kinematics took its own sine and cosine, `lanes.rs`).
    const PINNED_SEED_LIMITS_POSITION: [u64; 3] = [0x400C_AA01_F116_1F77, 0xBFFD_7DF3_82DE_E335, 0xBFFB_CAD8_FD1E_23AE];

    #[test]
    fn limits_configurations_are_inside_the_limits() {
        for set in all_sets(500, 3).iter().filter(|s| s.set.limited()) {
            assert!(set.chain.has_limits());
            for g in &set.goals {
                for (a, lim) in g.config.iter().zip(set.chain.limits()) {
                    let l = lim.unwrap();
                    assert!(l.contains(*a), "{}: {a} outside [{}, {}]", set.name(), l.min(), l.max());
                }
            }
            for (a, lim) in set.start.iter().zip(set.chain.limits()) {
                assert!(lim.unwrap().contains(*a));
            }
        }
    }

    #[test]
    fn goals_are_inside_or_outside_the_annulus() {
        for set in all_sets(500, 5) {
            let (inner, outer) = (set.chain.min_reach(), set.chain.max_reach());
            for g in &set.goals {
                let d = (g.x - set.chain.base().x).hypot(g.y - set.chain.base().y);
                if set.set == SetName::Unreachable {
                    assert!(d > outer * 1.04 || d < inner * 0.96, "{}: {d}", set.name());
                    assert!(g.config.is_empty());
                } else {
                    assert!(d >= inner - 1e-12 && d <= outer + 1e-12, "{}: {d}", set.name());
                    let tip = end_effector(&set.chain, &g.config);
                    assert_eq!((tip.position.x, tip.position.y), (g.x, g.y));
                    assert!((-PI..PI).contains(&g.phi));
                    assert!(wrap_angle(tip.orientation - g.phi).abs() < 1e-12);
                }
            }
            assert_eq!(set.targets.len(), set.goals.len());
            assert_eq!(set.targets[0].orientation().is_some(), set.set.oriented());
        }
    }

    #[test]
    fn the_inner_hole_gets_half_of_the_unreachable_goals() {
        let chain =
            ikarus::Chain::new([1.0, -2.0], &[ikarus::Link::new(5.0, 0.0), ikarus::Link::new(1.0, 0.0)]).unwrap();
        let set = generate("lopsided", &chain, SetName::Unreachable, 100, 1);
        let inside =
            set.goals.iter().filter(|g| (g.x - 1.0).hypot(g.y + 2.0) <= HOLE_MAX * chain.min_reach() + 1e-12).count();
        assert_eq!(inside, 50);
        assert!(set.goals.iter().all(|g| Goal::position(g.x, g.y).unwrap().is_out_of_reach(&chain, 1e-6)));
    }
}
