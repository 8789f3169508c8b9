//! The bends of a skeleton solve: each bent joint's range intersected with its half-turn, and a
//! start on the wrong side mirrored to the other (θ → −θ, the limb folded the other way, as
//! Spine and Godot flip a bend) with its parent turned so that the limb's end stays where it was.
//! One rule for a goal's bend and a bend on a bone without a goal.

use super::skeleton_model::RigWork;
use super::task::{Bend, BoneBend, RigTask, RigTaskError};
use crate::angle::wrap_angle;
use crate::chain::JointLimits;
use crate::math;
use crate::skeleton::{Joint, Skeleton};
use std::f64::consts::PI;

impl RigWork {
    /// Narrows `self.limits` by the task's bends and turns `self.start`'s bent joints to their
    /// side. The forward kinematics buffer is left as `start` (the untouched start pose) has it:
    /// pins hold where the start pose has them.
    pub(super) fn apply_bends(
        &mut self,
        skeleton: &Skeleton,
        start: &[f64],
        task: &RigTask,
    ) -> Result<(), RigTaskError> {
        let mut turned_any = false;
        for BoneBend { bone, bend } in task.all_bends() {
            let name = || skeleton.name(bone).to_owned();
            if let Joint::Prismatic { .. } = skeleton.joint(bone) {
                return Err(RigTaskError::BendOnPrismatic { name: name() });
            }
            let (lo, hi) = match bend {
                Bend::Positive => (0.0, PI),
                Bend::Negative => (-PI, 0.0),
            };
            let (lo, hi) = match self.limits[bone] {
                Some(l) => (l.min().max(lo), l.max().min(hi)),
                None => (lo, hi),
            };
            let lim = JointLimits::new(lo, hi).map_err(|_| RigTaskError::BendOutsideLimits { name: name() })?;
            self.limits[bone] = Some(lim);
            let a = self.start[bone];
            let wrong_side = (a < 0.0 && lo >= 0.0) || (a > 0.0 && hi <= 0.0);
            if !wrong_side {
                self.start[bone] = lim.clamp(a);
                continue;
            }
            let mirrored = lim.clamp(-a);
            if mirrored == -a {
                self.turn_parent_to_keep_the_end(skeleton, bone);
                turned_any = true;
            }
            self.start[bone] = mirrored;
        }
        if turned_any {
            self.fk.compute(skeleton, start);
        }
        Ok(())
    }

    /// Turns the parent of `bone` (when it is a revolute joint) by twice the angle from the
    /// parent's root → `bone`'s origin to the parent's root → `bone`'s tip, so that mirroring
    /// `bone`'s angle (θ → −θ) mirrors its origin (the knee) about the line from the limb's root
    /// to its end and leaves that end where it was (exactly so for a plain two-bone limb). The
    /// parent's limits, if any, clamp the turn. Updates the forward kinematics to `self.start`
    /// before measuring, so that several bends see each other's turns.
    fn turn_parent_to_keep_the_end(&mut self, skeleton: &Skeleton, bone: usize) {
        let Some(parent) = skeleton.parent(bone) else { return };
        if let Joint::Prismatic { .. } = skeleton.joint(parent) {
            return;
        }
        self.fk.compute(skeleton, &self.start);
        let origin_of = |i: usize| match (self.fk.starts.is_empty(), skeleton.parent(i)) {
            (false, _) => self.fk.starts[i],
            (true, Some(p)) => self.fk.points[p + 1],
            (true, None) => skeleton.base(),
        };
        let root = origin_of(parent);
        let knee = origin_of(bone);
        let end = self.fk.points[bone + 1];
        let (u, l) = (knee - root, end - root);
        if u.norm() == 0.0 || l.norm() == 0.0 {
            return;
        }
        let delta = wrap_angle(2.0 * wrap_angle(math::atan2(l.y, l.x) - math::atan2(u.y, u.x)));
        let turned = self.start[parent] + delta;
        self.start[parent] = match self.limits[parent] {
            Some(lim) => lim.clamp(turned),
            None => turned,
        };
    }
}
