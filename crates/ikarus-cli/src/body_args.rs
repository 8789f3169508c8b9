//! The body flags of `ikarus solve` and `ikarus animate` (and `ikarus render motion`): `--arm`,
//! `--rig`, the rig's task flags and the solver's, declared once and flattened into each
//! command; each command says in its own words what its rig does ([`BodyHelp`]).

use std::marker::PhantomData;
use std::path::PathBuf;

use clap::Args;

use crate::body::Body;
use crate::error::Error;
use crate::goal_args::RigTaskArgs;
use crate::settings::SolverFlags;

/// The help lines of a command's `--arm` and `--rig`.
pub trait BodyHelp {
    /// `--arm FILE`'s.
    const ARM: &'static str;
    /// `--rig FILE`'s.
    const RIG: &'static str;
}

/// `--arm FILE` or `--rig FILE`, then the rig's task flags (`--pin`, `--weight`, …) and the
/// solver's, in that order in the help; `H` gives the help lines of the first two.
#[derive(Debug, Args)]
pub struct BodyArgs<H: BodyHelp + Send + Sync + 'static> {
    #[arg(long, value_name = "FILE", help = H::ARM)]
    pub arm: Option<PathBuf>,
    #[arg(long, value_name = "FILE", conflicts_with = "arm", help = H::RIG)]
    pub rig: Option<PathBuf>,
    #[command(flatten)]
    pub rig_task: RigTaskArgs,
    #[command(flatten)]
    pub solver: SolverFlags,
    #[arg(skip)]
    help: PhantomData<H>,
}

impl<H: BodyHelp + Send + Sync + 'static> BodyArgs<H> {
    /// The body the flags name: `--rig FILE`, else `--arm FILE`, else the built-in seed arm.
    pub fn load(&self) -> Result<Body, Error> {
        Body::load(self.arm.as_deref(), self.rig.as_deref())
    }

    /// The body as a rig: `--rig FILE`, else the one-branch rig of the arm (bones `link0`, …).
    pub fn load_as_rig(&self) -> Result<ikarus_edge::rig::Rig, Error> {
        Body::load_as_rig(self.arm.as_deref(), self.rig.as_deref())
    }
}

#[cfg(test)]
mod tests {
    use clap::error::ErrorKind;
    use clap::{Args, Command};

    use super::BodyHelp;
    use crate::animate::{AnimateBody, MotionArgs};
    use crate::solve::{SolveArgs, SolveBody};

    /// Each command's flags in the order of its help: id and help line.
    fn flags(command: &Command) -> Vec<(String, String)> {
        command
            .get_arguments()
            .map(|a| (a.get_id().to_string(), a.get_help().map(ToString::to_string).unwrap_or_default()))
            .collect()
    }

    /// The flattened flags stand where each command declared them before (after `--goal-angle`
    /// in solve, after `--via` in animate), with the command's own help, followed by the task's
    /// `--pin`; and `--rig` still conflicts with `--arm`.
    #[test]
    fn each_command_keeps_its_body_flags_in_place_with_its_own_help() {
        let solve = SolveArgs::augment_args(Command::new("solve"));
        let animate = MotionArgs::augment_args(Command::new("animate"));
        for (command, before, arm, rig) in [
            (&solve, "goal_angle", SolveBody::ARM, SolveBody::RIG),
            (&animate, "via", AnimateBody::ARM, AnimateBody::RIG),
        ] {
            let flags = flags(command);
            let at = flags.iter().position(|(id, _)| id == before).expect("the flag before");
            assert_eq!(flags[at + 1], ("arm".to_owned(), arm.to_owned()));
            assert_eq!(flags[at + 2], ("rig".to_owned(), rig.to_owned()));
            assert_eq!(flags[at + 3].0, "pin");
            let both =
                command.clone().try_get_matches_from(["x", "--arm", "a.toml", "--rig", "r.toml", "--goal", "1,1"]);
            assert_eq!(both.map(|_| ()).unwrap_err().kind(), ErrorKind::ArgumentConflict);
        }
        assert_ne!(SolveBody::ARM, AnimateBody::ARM);
        assert!(
            SolveBody::RIG.contains("are solved together") && AnimateBody::RIG.contains("eases the pose through them")
        );
    }
}
