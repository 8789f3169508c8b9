//! [`Scratch`]: the buffers one [`Solver`](super::Solver) reuses across iterations and
//! solves, so that the loop does not allocate.

use nalgebra::{Matrix3xX, Point2};

/// Scratch space reused across iterations and solves.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    pub(super) joints: Vec<Point2<f64>>,
    pub(super) trial_joints: Vec<Point2<f64>>,
    /// `J`, its orientation row scaled by the orientation weight (zero without an orientation
    /// goal).
    pub(super) jacobian: Matrix3xX<f64>,
    /// `J` with column `i` scaled by `scale[i]` (zero for a locked joint).
    pub(super) weighted: Matrix3xX<f64>,
    /// Square roots of the joint weights of [`LimitMode::Weighted`](super::LimitMode::Weighted);
    /// 1 otherwise.
    pub(super) scale: Vec<f64>,
    /// Joints locked at a limit this iteration (lock and null-space modes).
    pub(super) locked: Vec<bool>,
    /// The method's step in weighted coordinates.
    pub(super) step: Vec<f64>,
    pub(super) delta: Vec<f64>,
    pub(super) trial: Vec<f64>,
    /// The best pose of a non-descent method (CCD, FABRIK).
    pub(super) best: Vec<f64>,
    /// The start pose of a restart.
    pub(super) restart: Vec<f64>,
    /// The final pose of the best attempt so far, when a solve restarts.
    pub(super) best_attempt: Vec<f64>,
}

impl Scratch {
    /// Sizes every buffer for a model of `n` joints whose forward kinematics writes `points`
    /// points (`n + 1` for a chain); no allocation once they have grown to it.
    pub(super) fn fit(&mut self, n: usize, points: usize) {
        self.joints.resize(points, Point2::origin());
        self.trial_joints.resize(points, Point2::origin());
        for v in [
            &mut self.scale,
            &mut self.step,
            &mut self.delta,
            &mut self.trial,
            &mut self.best,
            &mut self.restart,
            &mut self.best_attempt,
        ] {
            v.resize(n, 0.0);
        }
        self.locked.resize(n, false);
        if self.jacobian.ncols() != n {
            self.jacobian = Matrix3xX::zeros(n);
            self.weighted = Matrix3xX::zeros(n);
        }
    }
}
