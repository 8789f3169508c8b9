//! The sequential-limb baseline: each effector's limb solved alone as a chain, one after
//! another, as Spine's IK constraints and Unity's 2D limb solvers do.
//!
//! For each effector in order (the goals, then the pins), the bones on its path from the root
//! ([`Skeleton::path`]) form a chain whose first link starts at the base; the other bones keep
//! the angles they have. A chain [`Solver`] solves it from the limb's current angles, and the
//! answer is written back before the next effector's turn, so that a later limb can undo what
//! an earlier one did to the bones they share (the puppet's pelvis and spine, the hand's
//! wrist and palm). A pinned limb is solved, in its turn, to its tip's start position and
//! direction.

use ikarus::{Chain, Goal, Link, Outcome, SolveError, SolveOptions, Solver};

use super::set::{RigCase, RigSet};

/// One limb: its bones, root first, and their chain.
#[derive(Debug, Clone)]
struct Limb {
    bones: Vec<usize>,
    chain: Chain,
}

/// The baseline's solver for one set: a chain per effector, built once, and buffers reused
/// across solves.
#[derive(Debug, Clone)]
pub struct Sequential {
    limbs: Vec<Limb>,
    /// Each pin's goal: its start position and direction.
    pin_goals: Vec<Goal>,
    solver: Solver,
    out: Outcome,
    /// The limb's current angles, the start of its solve.
    limb_start: Vec<f64>,
    /// The whole skeleton's angles, updated limb after limb.
    angles: Vec<f64>,
}

impl Sequential {
    /// The baseline for `set`, each limb solved with `options`.
    pub fn new(set: &RigSet, options: SolveOptions) -> Self {
        let s = &set.skeleton;
        let base = s.base();
        let limbs = set
            .effectors()
            .map(|e| {
                let bones = s.path(e);
                let links: Vec<Link> = bones
                    .iter()
                    .map(|&b| {
                        let link = Link::new(s.lengths()[b], s.start_angles()[b]);
                        match s.limits()[b] {
                            Some(l) => link.with_limits(l),
                            None => link,
                        }
                    })
                    .collect();
                let chain = Chain::new([base.x, base.y], &links).expect("a skeleton's path is a valid chain");
                Limb { bones, chain }
            })
            .collect();
        let pin_goals = set
            .pin_targets
            .iter()
            .map(|(tip, phi)| Goal::with_orientation(tip.x, tip.y, *phi).expect("start tips are finite"))
            .collect();
        let solver = Solver::new(options).expect("the benchmark's options are valid");
        Self {
            limbs,
            pin_goals,
            solver,
            out: Outcome::default(),
            limb_start: Vec::new(),
            angles: Vec::with_capacity(s.len()),
        }
    }

    /// Solves `case` from `start` limb after limb; returns the final angles of every bone and
    /// the iterations of all the limbs' solves together.
    pub fn solve(&mut self, start: &[f64], case: &RigCase) -> Result<(&[f64], u64), SolveError> {
        self.angles.clear();
        self.angles.extend_from_slice(start);
        let mut iterations = 0;
        for (k, limb) in self.limbs.iter().enumerate() {
            let goal = match case.task.goals.get(k) {
                Some(g) => &g.goal,
                None => &self.pin_goals[k - case.task.goals.len()],
            };
            self.limb_start.clear();
            self.limb_start.extend(limb.bones.iter().map(|&b| self.angles[b]));
            self.solver.solve_into(&limb.chain, &self.limb_start, goal, &mut self.out)?;
            for (&b, &a) in limb.bones.iter().zip(self.out.pose.angles()) {
                self.angles[b] = a;
            }
            iterations += u64::from(self.out.iterations);
        }
        Ok((&self.angles, iterations))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigs::judge::Judge;
    use crate::rigs::set::{RigSetName, forward, generate};

    #[test]
    fn limbs_are_the_paths_from_the_root() {
        let s = generate(RigSetName::PuppetPins, 2, 1).unwrap();
        let seq = Sequential::new(&s, SolveOptions::default());
        let names = |l: &Limb| l.bones.iter().map(|&b| s.skeleton.name(b)).collect::<Vec<_>>().join(" ");
        let limbs: Vec<String> = seq.limbs.iter().map(names).collect();
        assert_eq!(
            limbs,
            [
                "pelvis spine right_upper_arm right_forearm right_hand",
                "pelvis spine left_upper_arm left_forearm left_hand",
                "right_thigh right_shin right_foot",
                "left_thigh left_shin left_foot",
            ]
        );
        // Each limb's chain puts its tip where the skeleton puts the bone's, at any pose.
        let (points, _) = forward(&s.skeleton, &s.cases[1].config);
        for (limb, e) in seq.limbs.iter().zip(s.effectors()) {
            let q: Vec<f64> = limb.bones.iter().map(|&b| s.cases[1].config[b]).collect();
            let tip = ikarus::kinematics::end_effector(&limb.chain, &q).position;
            assert!((tip - points[e + 1]).norm() < 1e-12);
        }
    }

    #[test]
    fn a_later_limb_undoes_an_earlier_one_on_shared_bones() {
        // Both hands hang from the spine: solving the left hand moves the pelvis and spine the
        // right hand was placed with, so sequential solving misses targets that the
        // generating configuration reaches together; the legs share nothing and are reached.
        let s = generate(RigSetName::Puppet, 60, 1).unwrap();
        let mut seq = Sequential::new(&s, SolveOptions::default());
        let mut judge = Judge::default();
        let (mut missed, mut right_missed, mut rest) = (0, 0, 0);
        let within = |points: &[ikarus::Point2<f64>], k: usize, c: &crate::rigs::set::RigCase| {
            (points[s.goals[k] + 1] - c.targets[k]).norm() <= 1e-6
        };
        for c in &s.cases {
            let (angles, _) = seq.solve(&s.start, c).unwrap();
            let angles = angles.to_vec();
            missed += usize::from(!judge.judge(&s, c, &angles).reached);
            let (points, _) = forward(&s.skeleton, &angles);
            // The left hand (the last limb on the pelvis and spine) and the feet (limbs of
            // their own) are where their solves put them; the right hand was pulled away.
            right_missed += usize::from(!within(&points, 0, c));
            rest += usize::from((1..4).all(|k| within(&points, k, c)));
            // The bones outside the four limbs keep their start angles.
            for b in ["neck", "head"] {
                let i = s.skeleton.index_of(b).unwrap();
                assert_eq!(angles[i], s.start[i]);
            }
        }
        assert!(right_missed > 50 && missed >= right_missed, "right hand missed {right_missed} of 60");
        assert!(rest > 50, "the last limbs' solves reach: {rest} of 60");
    }

    #[test]
    fn pinned_limbs_stay_where_they_start() {
        let s = generate(RigSetName::PuppetPins, 20, 1).unwrap();
        let mut seq = Sequential::new(&s, SolveOptions::default());
        for c in &s.cases {
            let (angles, _) = seq.solve(&s.start, c).unwrap();
            let (points, dirs) = forward(&s.skeleton, angles);
            for (&p, (tip, phi)) in s.pins.iter().zip(&s.pin_targets) {
                assert!((points[p + 1] - tip).norm() <= 1e-6 && (dirs[p] - phi).abs() <= 1e-6);
            }
        }
    }
}
