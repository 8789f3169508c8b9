//! [`Problem`]: what one solve borrows (chain, goal, options, the limits it enforces), built
//! once and passed to every part of the loop instead of a dozen parameters.

use super::{LimitMode, SolveOptions};
use crate::chain::Chain;
use crate::goal::Goal;
use crate::limits::Bounds;

/// One solve's borrowed context.
#[derive(Debug, Clone, Copy)]
pub(super) struct Problem<'a> {
    pub(super) chain: &'a Chain,
    pub(super) goal: &'a Goal,
    pub(super) opts: &'a SolveOptions,
    /// The limits the solve enforces: the chain's, or none when the options ignore them or
    /// the chain has none.
    pub(super) bounds: Bounds<'a>,
    /// The limit mode in effect: [`LimitMode::Ignore`] whenever `bounds` is free.
    pub(super) mode: LimitMode,
}

impl<'a> Problem<'a> {
    /// The context of a solve of `chain` for `goal` under `opts`.
    pub(super) fn new(chain: &'a Chain, goal: &'a Goal, opts: &'a SolveOptions) -> Self {
        let bounds = match opts.limits {
            LimitMode::Ignore => Bounds::free(),
            LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => chain.bounds(),
        };
        Self::with_bounds(chain, goal, opts, bounds)
    }

    /// The context with explicit `bounds` (the mode of `opts` applies unless they are free).
    pub(super) fn with_bounds(chain: &'a Chain, goal: &'a Goal, opts: &'a SolveOptions, bounds: Bounds<'a>) -> Self {
        let mode = if bounds.is_free() { LimitMode::Ignore } else { opts.limits };
        Self { chain, goal, opts, bounds, mode }
    }
}
