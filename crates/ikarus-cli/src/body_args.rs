//! The body flags of `ikarus solve` and `ikarus animate` (and `ikarus render motion`): `--arm`,
//! `--rig`, the rig's task flags and the solver's, declared once and flattened into each
//! command; each command says in its own words what its rig does ([`BodyHelp`]).

use std::marker::PhantomData;
use std::path::PathBuf;

use clap::Args;

use crate::body::Body;
use crate::error::CliError;
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
    pub fn load(&self) -> Result<Body, CliError> {
        Body::load(self.arm.as_deref(), self.rig.as_deref())
    }
}
