//! [`Problem`]: what one solve borrows (model, goal, options, the limits it enforces), built
//! once and passed to every part of the loop instead of a dozen parameters.

use super::model::Model;
use super::{LimitMode, SolveOptions};
use crate::chain::Chain;
use crate::limits::Bounds;

/// One solve's borrowed context, for a body of type `M` (a [`Chain`] unless said otherwise).
pub(super) struct Problem<'a, M: Model = Chain> {
    pub(super) model: &'a M,
    pub(super) goal: &'a M::Goal,
    pub(super) opts: &'a SolveOptions,
    /// The limits the solve enforces: the model's, or none when the options ignore them or
    /// the model has none.
    pub(super) bounds: Bounds<'a>,
    /// The limit mode in effect: [`LimitMode::Ignore`] whenever `bounds` is free.
    pub(super) mode: LimitMode,
    /// The iteration cap of an attempt: [`SolveOptions::max_iterations`], or less for the
    /// probe of a seeded solve (see `restarts`).
    pub(super) max_iterations: u32,
}

// By hand: derived impls would ask `M: Clone`/`M: Copy`, and only references are copied.
impl<M: Model> Clone for Problem<'_, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: Model> Copy for Problem<'_, M> {}

impl<'a, M: Model> Problem<'a, M> {
    /// The context of a solve of `model` for `goal` under `opts`.
    pub(super) fn new(model: &'a M, goal: &'a M::Goal, opts: &'a SolveOptions) -> Self {
        let bounds = match opts.limits {
            LimitMode::Ignore => Bounds::free(),
            LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => model.bounds(),
        };
        Self::with_bounds(model, goal, opts, bounds)
    }

    /// The context with explicit `bounds` (the mode of `opts` applies unless they are free).
    pub(super) fn with_bounds(model: &'a M, goal: &'a M::Goal, opts: &'a SolveOptions, bounds: Bounds<'a>) -> Self {
        let mode = if bounds.is_free() { LimitMode::Ignore } else { opts.limits };
        Self { model, goal, opts, bounds, mode, max_iterations: opts.max_iterations }
    }
}
