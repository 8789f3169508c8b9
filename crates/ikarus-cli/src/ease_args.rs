//! `--ease`, `--k1`, `--k2`: choosing an ease curve at the edge.

use clap::Args;
use ikarus::{Ease, EaseKind};

use crate::error::CliError;
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

/// Why a requested ease cannot be made, for each edge to word in its own field names.
#[derive(Debug)]
pub enum EaseProblem {
    /// k1 (`true`) or k2 (`false`) was given for a curve other than Parent's.
    KWithoutParent { k1: bool },
    /// Parent's parameters are invalid.
    Invalid(ikarus::EaseError),
}

/// The one rule for choosing an ease, shared by the flags and the API: the named `kind`, else
/// Parent's when k1 or k2 is given, else `default`; k1/k2 belong to Parent's alone and default
/// to [`ikarus::ease::DEFAULT_K1`] and [`ikarus::ease::DEFAULT_K2`].
pub fn choose_ease(
    kind: Option<EaseKind>,
    k1: Option<f64>,
    k2: Option<f64>,
    default: EaseKind,
) -> Result<Ease, EaseProblem> {
    let has_k = k1.is_some() || k2.is_some();
    let kind = kind.unwrap_or(if has_k { EaseKind::Parent } else { default });
    if has_k && kind != EaseKind::Parent {
        return Err(EaseProblem::KWithoutParent { k1: k1.is_some() });
    }
    kind.ease(k1, k2).map_err(EaseProblem::Invalid)
}

impl EaseArgs {
    /// The ease the flags ask for; `default` when none is named.
    pub fn resolve(&self, default: EaseKind) -> Result<Ease, CliError> {
        choose_ease(self.ease, self.k1, self.k2, default).map_err(|p| match p {
            EaseProblem::KWithoutParent { k1 } => {
                let flag = if k1 { "--k1" } else { "--k2" };
                CliError::input(format!("{flag}: only applies with --ease parent"))
            }
            EaseProblem::Invalid(e) => CliError::input(format!("--{e}")),
        })
    }
}
