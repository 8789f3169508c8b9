//! The one body of a command or a request: an arm (a chain, from an arm file) or a rig (a tree of
//! named bones, from a rig file), read by one reader. A job's workflow takes a body and chooses
//! what really differs between the two (the solver's entry point, the JSON's angles by index or
//! by bone name, the picture) by a `match` on it.

use std::path::Path;

use ikarus::{Goal, JointLimits, Outcome, RigTask, SolveError, Solver};

use crate::arm::{Arm, ArmFile, DEFAULT_ARM};
use crate::error::Error;
use crate::rig::Rig;
use crate::settings::SolverSettings;

/// An arm or a rig.
#[derive(Debug, Clone)]
pub enum Body {
    /// A chain: `--arm FILE`, the built-in seed arm without one, or a request's `arm`.
    Chain(Box<Arm>),
    /// A skeleton: `--rig FILE` or a request's `rig` (both boxed: a body is moved, not copied).
    Rig(Box<Rig>),
}

impl Body {
    /// `--rig FILE` when given, else `--arm FILE`, else the built-in seed arm; messages name the
    /// file as each reader does (`rig file r.toml: …`, `arm file a.toml: …`).
    pub fn load(arm: Option<&Path>, rig: Option<&Path>) -> Result<Self, Error> {
        match rig {
            Some(path) => Ok(Self::Rig(Box::new(load_rig(path)?))),
            None => {
                let (file, label) = read_arm_file(arm)?;
                Self::from_arm_file(file, &label)
            }
        }
    }

    /// The body as a rig: `--rig FILE`, else the one-branch rig of `--arm FILE` or of the
    /// built-in seed arm ([`Rig::from_arm`]: bones `link0`, `link1`, …), as keyed motion takes it.
    pub fn load_as_rig(arm: Option<&Path>, rig: Option<&Path>) -> Result<Rig, Error> {
        match rig {
            Some(path) => load_rig(path),
            None => {
                let (file, label) = read_arm_file(arm)?;
                Rig::from_arm(&file, &label)
            }
        }
    }

    /// The body of an arm file (or a request's `arm`): its chain when no link gives a joint key
    /// a chain cannot hold ([`ArmFile::joint_key`]), read exactly as [`Arm::from_file`] reads
    /// it; else the one-branch rig of its links ([`Rig::from_arm`]: bones `link0`, `link1`, …, a
    /// goal without a bone's name on the last). `label` starts every message, which names the
    /// link as an arm file does (`links[2].limits = [1, 0]: …`).
    pub fn from_arm_file(file: ArmFile, label: &str) -> Result<Self, Error> {
        match file.joint_key() {
            None => Ok(Self::Chain(Box::new(Arm::from_file(file, label)?))),
            Some(_) => Ok(Self::Rig(Box::new(Rig::from_arm(&file, label)?))),
        }
    }

    /// The arm or the rig, as what the workflows ask of either.
    #[must_use]
    pub fn jointed(&self) -> &dyn Jointed {
        match self {
            Self::Chain(arm) => &**arm,
            Self::Rig(rig) => &**rig,
        }
    }
}

/// The arm file at `arm`, else the built-in seed arm's, with the label its messages start with.
fn read_arm_file(arm: Option<&Path>) -> Result<(ArmFile, String), Error> {
    let (text, label) = match arm {
        None => (DEFAULT_ARM.to_owned(), "built-in arm".to_owned()),
        Some(p) => {
            let label = format!("arm file {}", p.display());
            (crate::input::read_text(p, &label)?, label)
        }
    };
    Ok((ArmFile::read(&text, &label)?, label))
}

/// The rig file at `path` (`--rig FILE`), a character file refused in one line that says what it
/// is and which commands take it ([`crate::character::not_a_rig`]).
pub fn load_rig(path: &Path) -> Result<Rig, Error> {
    let label = format!("rig file {}", path.display());
    let text = crate::input::read_character_text(path, &label)?;
    crate::character::not_a_rig(&text, &label)?;
    Rig::parse(&text, &label)
}

/// What a job's workflow asks of a body, an arm or a rig alike.
pub trait Jointed {
    /// Its name, as the answers give it.
    fn name(&self) -> &str;
    /// Its number of joints: an arm's links, a rig's bones.
    fn joints(&self) -> usize;
    /// Its file's `[solver]` table.
    fn solver(&self) -> &SolverSettings;
    /// Its start pose, one joint value per joint.
    fn start(&self) -> &[f64];
    /// Its joints' ranges, one per joint.
    fn limits(&self) -> &[Option<JointLimits>];
    /// The values a recorded frame of a solve holds: an arm's `n + 4` (as its cap has always
    /// counted them), a rig's `n` angles and `n + 1` points.
    fn frame_values(&self) -> u64;
}

impl Jointed for Arm {
    fn name(&self) -> &str {
        &self.name
    }
    fn joints(&self) -> usize {
        self.chain.len()
    }
    fn solver(&self) -> &SolverSettings {
        &self.solver
    }
    fn start(&self) -> &[f64] {
        self.chain.start_pose().angles()
    }
    fn limits(&self) -> &[Option<JointLimits>] {
        self.chain.limits()
    }
    fn frame_values(&self) -> u64 {
        self.chain.len() as u64 + 4
    }
}

impl Jointed for Rig {
    fn name(&self) -> &str {
        &self.name
    }
    fn joints(&self) -> usize {
        self.skeleton.len()
    }
    fn solver(&self) -> &SolverSettings {
        &self.solver
    }
    fn start(&self) -> &[f64] {
        self.skeleton.start_angles()
    }
    fn limits(&self) -> &[Option<JointLimits>] {
        self.skeleton.limits()
    }
    fn frame_values(&self) -> u64 {
        3 * self.skeleton.len() as u64 + 2
    }
}

/// A body and what a solve aims it at: an arm's tip at a goal, a rig's goals and pins. The
/// solver's entry point is the one thing a solve does differently for the two.
pub enum Aimed<'a> {
    /// An arm, its tip aimed at the goal (radians).
    Chain(&'a Arm, Goal),
    /// A rig, with its goals and pins.
    Rig(&'a Rig, RigTask),
}

impl Aimed<'_> {
    /// Solves from `start` into `out` (its buffers reused).
    pub fn solve_into(&self, solver: &mut Solver, start: &[f64], out: &mut Outcome) -> Result<(), SolveError> {
        match self {
            Aimed::Chain(arm, goal) => solver.solve_into(&arm.chain, start, goal, out),
            Aimed::Rig(rig, task) => solver.solve_rig_into(&rig.skeleton, start, task, out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rig_file_wins_and_no_file_is_the_seed_arm() {
        let rigs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs/puppet.toml");
        assert!(matches!(Body::load(None, Some(&rigs)), Ok(Body::Rig(r)) if r.name == "puppet"));
        assert!(matches!(Body::load(None, None), Ok(Body::Chain(a)) if a.chain.len() == 3));
        let Err(e) = Body::load(None, Some(Path::new("/nonexistent/r.toml"))) else { panic!("read a missing file") };
        assert!(e.to_string().starts_with("rig file /nonexistent/r.toml: "), "{e}");
    }

    /// An arm file's joint keys: `joint = "revolute"` alone keeps the same chain; a slide makes
    /// a one-branch rig of bones `link0…` whose unnamed goal is on the last link.
    #[test]
    fn an_arm_with_a_slide_is_a_one_branch_rig() {
        let plain = "[[links]]\nlength = 3\nangle_deg = 5\n[[links]]\nlength = 2\nlimits_deg = [-90, 90]\n";
        let revolute = plain.replace("length = 2\n", "length = 2\njoint = \"revolute\"\n");
        let chain = |text: &str| match Body::from_arm_file(ArmFile::read(text, "a").unwrap(), "a") {
            Ok(Body::Chain(arm)) => arm.chain,
            _ => panic!("not a chain: {text}"),
        };
        assert_eq!(chain(plain), chain(&revolute));
        let slide = format!("name = \"r\"\n{plain}[[links]]\nlength = 1\njoint = \"prismatic\"\nlimits = [0, 1]\n");
        let Ok(Body::Rig(rig)) = Body::from_arm_file(ArmFile::read(&slide, "a").unwrap(), "a") else {
            panic!("not a rig")
        };
        assert_eq!((rig.name.as_str(), rig.label.as_str(), rig.tip), ("r", "a", Some(2)));
        let s = &rig.skeleton;
        assert_eq!(s.names(), &["link0", "link1", "link2"]);
        assert_eq!(s.parents(), &[None, Some(0), Some(1)]);
        assert!(s.as_chain().is_none() && s.has_prismatic());
        assert_eq!(s.limits()[2].map(|l| (l.min(), l.max())), Some((0.0, 1.0)));
        // The chain-only reader names the first key it cannot hold.
        let e = Arm::parse(&slide, "a").unwrap_err().to_string();
        assert!(e.starts_with("a: links[2].joint: an arm with offsets or slides is a one-branch rig"), "{e}");
    }
}
