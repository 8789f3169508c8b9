//! A skeleton's geometry changed in place, its tree kept: for a solve repeated every frame on
//! the same bones (the `ikarus-spine` add-on's), without building a skeleton (its names, its
//! index, its tree's tables) each time.

use super::{BoneField, Joint, MAX_REACH, Skeleton, SkeletonError, check_angles};
use crate::limits::{Bounds, JointLimits};
use crate::math;

/// A revolute bone's new geometry for [`Skeleton::refit`], as [`Bone`](super::Bone) gives it:
/// its length, its angle, its offset from its parent's origin in the parent's frame (a root's
/// from the origin) and its limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Refit {
    pub(crate) length: f64,
    pub(crate) angle: f64,
    pub(crate) offset: [f64; 2],
    pub(crate) limits: Option<JointLimits>,
}

impl Skeleton {
    /// Whether [`Skeleton::refit`] can change this skeleton: every bone revolute, placed by
    /// an offset, without stiffness.
    pub(crate) fn can_refit(&self) -> bool {
        self.joints.iter().all(|j| *j == Joint::Revolute)
            && self.offsets.iter().all(Option::is_some)
            && !self.has_rest_pose()
    }

    /// Gives every bone `i` the geometry `bone(i)` and the skeleton the base `base`, checked as
    /// [`Skeleton::new`] checks them, so that the skeleton equals the one `new` builds of the
    /// same bones (same names and parents) bit for bit; allocates nothing unless it fails.
    /// Only for a skeleton that [`can_refit`](Skeleton::can_refit); on an error the skeleton is
    /// left half changed, to be built again.
    pub(crate) fn refit(&mut self, base: [f64; 2], bone: impl Fn(usize) -> Refit) -> Result<(), SkeletonError> {
        debug_assert!(self.can_refit(), "ikarus: refit of a skeleton that cannot be refitted");
        let [x, y] = base;
        if !x.is_finite() || !y.is_finite() {
            return Err(SkeletonError::NonFiniteBase { x, y });
        }
        self.base = nalgebra::Point2::new(x, y);
        for i in 0..self.len() {
            let b = bone(i);
            let name = || self.names[i].clone();
            if !b.length.is_finite() {
                return Err(SkeletonError::NonFinite {
                    index: i,
                    name: name(),
                    field: BoneField::Length,
                    value: b.length,
                });
            }
            if b.length <= 0.0 {
                return Err(SkeletonError::NonPositiveLength { index: i, name: name(), value: b.length });
            }
            let [ox, oy] = b.offset;
            if !ox.is_finite() || !oy.is_finite() {
                return Err(SkeletonError::NonFinitePair {
                    index: i,
                    name: name(),
                    field: BoneField::Offset,
                    x: ox,
                    y: oy,
                });
            }
            self.lengths[i] = b.length;
            self.start[i] = b.angle;
            self.rest[i] = b.angle;
            self.limits[i] = b.limits;
            self.offsets[i] = Some(b.offset);
        }
        for i in 0..self.len() {
            let [ox, oy] = self.offsets[i].unwrap_or_default();
            self.shifts[i] = Some([ox - self.parents[i].map_or(0.0, |p| self.lengths[p]), oy]);
        }
        check_angles(&self.names, &self.joints, &self.start, Bounds::new(&self.limits))?;
        // (The rest angles are the start angles, within the limits as they were checked.)
        self.fill_reach()
    }

    /// The skeleton with its reach computed ([`Skeleton::new`]'s last step).
    pub(super) fn with_reach(mut self) -> Result<Self, SkeletonError> {
        self.fill_reach()?;
        Ok(self)
    }

    /// Computes the path to each tip and the reach, checked against [`MAX_REACH`].
    fn fill_reach(&mut self) -> Result<(), SkeletonError> {
        // The length of the path to each tip, summed root first in the order of a chain's
        // `Σ lᵢ` (so that a chain's reach is its own, bit for bit).
        // A bone with an offset or a slide adds, to the path to its parent's origin, the
        // offset's length and the slide's largest travel (within its limits, or the nominal
        // range of an unlimited slide: its start ± its length).
        let (parents, lengths, offsets, joints) = (&self.parents, &self.lengths, &self.offsets, &self.joints);
        let to_tip = &mut self.to_tip;
        for &i in &self.order {
            let above = parents[i].map_or(0.0, |p| to_tip[p]);
            to_tip[i] = if offsets[i].is_none() && joints[i] == Joint::Revolute {
                above + lengths[i]
            } else {
                let origin = match (parents[i], offsets[i]) {
                    (Some(p), Some([x, y])) => above - lengths[p] + math::hypot(x, y),
                    (None, Some([x, y])) => math::hypot(x, y),
                    (_, None) => above,
                };
                let travel = match joints[i] {
                    Joint::Revolute => 0.0,
                    Joint::Prismatic { .. } => match self.limits[i] {
                        Some(l) => l.min().abs().max(l.max().abs()),
                        None => self.start[i].abs() + lengths[i],
                    },
                };
                origin + travel + lengths[i]
            };
        }
        self.reach = to_tip.iter().copied().fold(0.0, f64::max);
        let extent = math::hypot(self.base.x, self.base.y) + self.reach;
        if extent.is_nan() || extent > MAX_REACH {
            return Err(SkeletonError::ReachTooLarge { reach: extent });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Bone;

    /// Three bones placed by offsets, a branch at the first: `k` varies their geometry.
    fn bones(k: f64) -> Vec<Bone> {
        let limits = JointLimits::new(-1.0 - k, 1.5 + k).unwrap();
        vec![
            Bone::new("a", 2.0 + k, 0.3 + k).with_offset([1.0, -k]),
            Bone::new("b", 1.5 * (1.0 + k), -0.2).with_offset([2.0 + k, 0.1]).with_parent("a").with_limits(limits),
            Bone::new("c", 0.5, 0.7 - k).with_offset([0.5, 0.5 + k]).with_parent("a"),
        ]
    }

    #[test]
    fn a_refitted_skeleton_equals_the_one_built_of_the_same_bones_bit_for_bit() {
        let mut s = Skeleton::new([0.0, 0.0], &bones(0.0)).unwrap();
        assert!(s.can_refit());
        for k in [0.25, 3.0, 0.0] {
            let b = bones(k);
            let fresh = Skeleton::new([k, -k], &b).unwrap();
            s.refit([k, -k], |i| Refit {
                length: b[i].length,
                angle: b[i].angle,
                offset: b[i].offset.unwrap(),
                limits: b[i].limits,
            })
            .unwrap();
            assert_eq!(s, fresh, "k = {k}");
        }
        let short =
            |i: usize| Refit { length: if i == 1 { -1.0 } else { 1.0 }, angle: 0.0, offset: [0.0; 2], limits: None };
        let e = s.refit([0.0, 0.0], short).unwrap_err().to_string();
        assert_eq!(e, "bones[1] (\"b\").length: must be greater than 0, got -1");
        assert!(!Skeleton::new([0.0, 0.0], &[Bone::new("plain", 1.0, 0.0)]).unwrap().can_refit());
    }
}
