//! [`Body`]: what a motion needs of the thing it moves — the number of angles, their limits,
//! and the points drawn for a pose — so that one motion code serves chains and skeletons.
//!
//! Everything a motion does between poses (unwrapping, the polyline, the spline, the timing)
//! works on angle vectors and is the same for both; only the validation against the limits and
//! the points of each frame depend on the body. A trait rather than an enum of bodies: the
//! motion functions are generic over it and monomorphised, so a chain's motion is the same code
//! as before skeletons existed (same operations, same bits), and no caller has to wrap its
//! chain. It is sealed: the motion's guarantees rest on these two bodies.

use nalgebra::Point2;

use crate::chain::Chain;
use crate::kinematics::joint_positions;
use crate::limits::JointLimits;
use crate::skeleton::Skeleton;

mod sealed {
    pub trait Sealed {}
    impl Sealed for crate::chain::Chain {}
    impl Sealed for crate::skeleton::Skeleton {}
}

/// A body a motion can move: a [`Chain`] or a [`Skeleton`].
pub trait Body: sealed::Sealed {
    /// The number of angles of a pose (joints of a chain, bones of a skeleton).
    fn angle_count(&self) -> usize;
    /// The limits, one entry per angle.
    fn angle_limits(&self) -> &[Option<JointLimits>];
    /// The points of a frame at `angles`: for a chain its joint positions, base first, tip
    /// last; for a skeleton the base, then every bone's tip in the skeleton's order (bone `i`'s
    /// tip at `i + 1`, as the solver's frames hold them). `angle_count() + 1` points either way.
    fn frame_points(&self, angles: &[f64]) -> Vec<Point2<f64>>;
}

impl Body for Chain {
    #[inline]
    fn angle_count(&self) -> usize {
        self.len()
    }

    #[inline]
    fn angle_limits(&self) -> &[Option<JointLimits>] {
        self.limits()
    }

    #[inline]
    fn frame_points(&self, angles: &[f64]) -> Vec<Point2<f64>> {
        joint_positions(self, angles)
    }
}

impl Body for Skeleton {
    #[inline]
    fn angle_count(&self) -> usize {
        self.len()
    }

    #[inline]
    fn angle_limits(&self) -> &[Option<JointLimits>] {
        self.limits()
    }

    fn frame_points(&self, angles: &[f64]) -> Vec<Point2<f64>> {
        let mut points = vec![Point2::origin(); self.len() + 1];
        let mut directions = vec![0.0; self.len()];
        self.points_into(angles, &mut points, &mut directions);
        points
    }
}
