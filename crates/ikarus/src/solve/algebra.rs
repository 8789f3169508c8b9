//! The task-space linear algebra of the Jacobian methods, behind one small interface so that
//! the loop, the line search and the limit modes are written once for every body.
//!
//! An [`Algebra`] holds, for the pose being stepped from, the task error `e`, the Jacobian `J`,
//! the column-weighted `J` of the limit modes, `A = J Jᵀ`, the task left to the step rule and
//! the linear prediction of the line search, and it runs the step rules on them. There are two:
//!
//! - [`Fixed3`], a chain's: one effector, three rows (x, y, orientation), `nalgebra`'s
//!   fixed-size types on the stack and the 3×3 kernels of `step.rs`, `dls.rs`, `pinv.rs`,
//!   `sdls.rs` — the chain solver's arithmetic, unchanged;
//! - [`Dynamic`](dynamic::Dynamic), a skeleton's: any number of effectors stacked, `m` rows,
//!   with the same rules on `m × m` matrices factorised in place, and two priority levels.
//!
//! The core is generic over the algebra and monomorphised per body, so a chain solve runs the
//! fixed-size code with no dynamic dispatch.

pub(super) mod dynamic;
mod kernels;

use nalgebra::{Matrix3, Matrix3xX, Vector3};

use super::step::{Rule, System, gram, method_step};
use super::{SolveOptions, pinv};

/// Which Jacobian a step works on: `J` itself, or `J` with its columns weighted by the limit
/// mode or the rest-pose preference ([`Algebra::set_weighted`]). Until a joint is locked or
/// weighted they are the same, and [`Columns::Plain`] skips the weighted copy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Columns {
    /// `J` itself (every column's factor 1).
    Plain,
    /// The weighted `J` of [`Algebra::set_weighted`].
    Weighted,
}

impl Columns {
    /// `plain` or `weighted`, as these columns say (the two borrowed apart, so that the caller
    /// may still change its other fields).
    #[inline]
    pub(super) fn pick<'a, M>(self, plain: &'a M, weighted: &'a M) -> &'a M {
        match self {
            Columns::Plain => plain,
            Columns::Weighted => weighted,
        }
    }
}

/// Task-space state and kernels of the Jacobian methods (see the [module docs](self)).
pub(super) trait Algebra: Default + Clone + std::fmt::Debug {
    /// Sizes the buffers for `n` joints; allocates only when they grow.
    fn fit(&mut self, n: usize);
    /// The line search's merit of `e`: `‖e‖²`, with the first priority level's rows weighted
    /// up when there are two levels (see [`dynamic::primary_merit`]).
    fn e_norm_squared(&self) -> f64;
    /// `‖e‖`.
    fn e_norm(&self) -> f64;
    /// `Jᵢ · e`.
    fn column_dot_e(&self, i: usize) -> f64;
    /// The task the step rule solves starts as `e`.
    fn reset_task(&mut self);
    /// Column `i` of the weighted Jacobian: `k Jᵢ`.
    fn set_weighted(&mut self, i: usize, k: f64);
    /// `A` of the Jacobian of `columns`.
    fn gram(&mut self, columns: Columns);
    /// The step of `rule` for the current task, in weighted joint coordinates, into `out`
    /// (`A` from [`Algebra::gram`] of the same `columns`).
    fn method_step(&mut self, columns: Columns, rule: Rule, opts: &SolveOptions, mu: f64, out: &mut [f64]);
    /// The null-space push: `delta += z − W A⁺ W z` over the free joints, `W` the Jacobian of
    /// `columns`, `z` one entry per joint.
    fn project_push(&mut self, columns: Columns, threshold: f64, z: &[f64], locked: &[bool], delta: &mut [f64]);
    /// `task −= d Jᵢ` (a joint locked after moving by `d`).
    fn task_sub_column(&mut self, i: usize, d: f64);
    /// The line search's prediction starts as `e`.
    fn predict_from_e(&mut self);
    /// `predicted −= d Jᵢ`.
    fn predict_sub_column(&mut self, i: usize, d: f64);
    /// The merit of `predicted`, as [`Algebra::e_norm_squared`]'s.
    fn predicted_norm_squared(&self) -> f64;
}

/// A chain's task space: one effector, x, y and orientation rows (see the [module docs](self)).
#[derive(Debug, Clone, Default)]
pub(super) struct Fixed3 {
    /// The task error: position, and the weighted orientation error (0 without an orientation
    /// goal).
    pub(super) e: Vector3<f64>,
    /// `J`, its orientation row scaled by the orientation weight (zero without an orientation
    /// goal).
    pub(super) jacobian: Matrix3xX<f64>,
    /// `J` with column `i` scaled by the limit mode's factor (zero for a locked joint).
    weighted: Matrix3xX<f64>,
    /// Whether the goal has an orientation (the third row counts).
    pub(super) oriented: bool,
    task: Vector3<f64>,
    a: Matrix3<f64>,
    predicted: Vector3<f64>,
}

impl Fixed3 {
    #[inline]
    fn j(&self, columns: Columns) -> &Matrix3xX<f64> {
        columns.pick(&self.jacobian, &self.weighted)
    }
}

impl Algebra for Fixed3 {
    fn fit(&mut self, n: usize) {
        if self.jacobian.ncols() != n {
            self.jacobian = Matrix3xX::zeros(n);
            self.weighted = Matrix3xX::zeros(n);
        }
    }

    #[inline]
    fn e_norm_squared(&self) -> f64 {
        self.e.norm_squared()
    }

    #[inline]
    fn e_norm(&self) -> f64 {
        self.e.norm()
    }

    #[inline]
    fn column_dot_e(&self, i: usize) -> f64 {
        self.jacobian.column(i).dot(&self.e)
    }

    #[inline]
    fn reset_task(&mut self) {
        self.task = self.e;
    }

    #[inline]
    fn set_weighted(&mut self, i: usize, k: f64) {
        let col = self.jacobian.column(i) * k;
        self.weighted.column_mut(i).copy_from(&col);
    }

    #[inline]
    fn gram(&mut self, columns: Columns) {
        self.a = gram(self.j(columns), self.oriented);
    }

    #[inline]
    fn method_step(&mut self, columns: Columns, rule: Rule, opts: &SolveOptions, mu: f64, out: &mut [f64]) {
        let sys = System { a: &self.a, weighted: self.j(columns), e: &self.task };
        method_step(rule, opts, self.oriented, sys, mu, out);
    }

    #[inline]
    fn project_push(&mut self, columns: Columns, threshold: f64, z: &[f64], locked: &[bool], delta: &mut [f64]) {
        let weighted = self.j(columns);
        let mut jz = Vector3::zeros();
        for (i, &zi) in z.iter().enumerate() {
            jz += weighted.column(i) * zi;
        }
        let y = pinv::task_step(&self.a, &jz, threshold);
        for (i, d) in delta.iter_mut().enumerate() {
            if !locked[i] {
                *d += z[i] - weighted.column(i).dot(&y);
            }
        }
    }

    #[inline]
    fn task_sub_column(&mut self, i: usize, d: f64) {
        self.task -= self.jacobian.column(i) * d;
    }

    #[inline]
    fn predict_from_e(&mut self) {
        self.predicted = self.e;
    }

    #[inline]
    fn predict_sub_column(&mut self, i: usize, d: f64) {
        self.predicted -= self.jacobian.column(i) * d;
    }

    #[inline]
    fn predicted_norm_squared(&self) -> f64 {
        self.predicted.norm_squared()
    }
}
