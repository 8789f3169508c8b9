//! `--ease`, `--k1`, `--k2`: choosing an ease curve on the command line, by the edge's one rule
//! ([`ikarus_edge::ease_args::choose_ease`]).

use clap::Args;
use ikarus::{Ease, EaseKind};
pub use ikarus_edge::ease_args::*;

use crate::error::Error;
use crate::options::{named, parse_finite};

#[derive(Debug, Clone, Args)]
pub struct EaseArgs {
    /// Ease curve of the motion [default: sine; parent when --k1 or --k2 is given]
    #[arg(long, value_parser = named::<EaseKind>())]
    pub ease: Option<EaseKind>,
    /// Parent's ease: end of the acceleration, in [0, 1] [default: 0.3]
    #[arg(long, value_parser = parse_finite, value_name = "A")]
    pub k1: Option<f64>,
    /// Parent's ease: start of the deceleration, in [k1, 1] [default: 0.7]
    #[arg(long, value_parser = parse_finite, value_name = "B")]
    pub k2: Option<f64>,
}

impl EaseArgs {
    /// The ease the flags ask for; `default` when none is named.
    pub fn resolve(&self, default: EaseKind) -> Result<Ease, Error> {
        choose_ease(self.ease, self.k1, self.k2, default).map_err(|p| match p {
            EaseProblem::KWithoutParent { k1 } => {
                let flag = if k1 { "--k1" } else { "--k2" };
                Error::input(format!("{flag}: only applies with --ease parent"))
            }
            EaseProblem::Invalid(e) => Error::input(format!("--{e}")),
        })
    }
}
