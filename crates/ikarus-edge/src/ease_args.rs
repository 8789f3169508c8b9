//! Choosing an ease curve at the edges: one rule for the flags and the API.

use ikarus::{Ease, EaseKind};

/// Why a requested ease cannot be made, for each edge to word in its own field names.
#[derive(Debug)]
pub enum EaseProblem {
    /// k1 (`true`) or k2 (`false`) was given for a curve other than Parent's.
    KWithoutParent {
        /// `true` when k1 was given, `false` when only k2 was.
        k1: bool,
    },
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
