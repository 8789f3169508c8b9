//! The moving bones of a together solve frozen into an ikarus skeleton at the runtime's pose,
//! the solve's task built on it, and its answer thawed back into the character's local
//! rotations (steps 2 and 3 of [`super`]'s doc).

use super::super::pose::Posed;
use super::super::world::{Affine, world_transform};
use super::super::{Character, IkBones, IkRule, IkSettings, Inherit, LocalTransform, Placement};
use super::goal_slots::GoalSlots;
use super::rules::{GoalEnd, LimbRule, Together, TogetherError};
use crate::angle::wrap_angle;
use crate::goal::Goal;
use crate::limits::JointLimits;
use crate::math;
use crate::skeleton::{Bone, Refit, Skeleton};
use crate::solve::{Bend, Pin, Priority, RigGoal, RigTask};

/// The moving bones as an ikarus skeleton: `bones[k]` is the character's bone of the
/// skeleton's bone `k`.
#[derive(Debug, Clone)]
pub(super) struct Frozen {
    pub(super) skeleton: Skeleton,
    pub(super) bones: Vec<usize>,
    pub(super) start: Vec<f64>,
}

/// What freezing reads of a posed skeleton: its tree and each bone's world placement and
/// local rotation, from a [`Posed`] character or from a runtime's raw arrays.
pub(super) trait PoseView {
    /// Bone `i`'s parent.
    fn parent(&self, i: usize) -> Option<usize>;
    /// Bone `i`'s world origin.
    fn origin(&self, i: usize) -> [f64; 2];
    /// Bone `i`'s world direction, radians.
    fn rotation(&self, i: usize) -> f64;
    /// Bone `i`'s tip in the world.
    fn tip(&self, i: usize) -> [f64; 2];
    /// Bone `i`'s local rotation, radians.
    fn local_rotation(&self, i: usize) -> f64;
    /// Bone `i`'s name for the frozen skeleton.
    fn name(&self, i: usize) -> String;
}

/// A posed character as a [`PoseView`].
struct CharacterView<'a>(&'a Character, &'a Posed);

impl PoseView for CharacterView<'_> {
    fn parent(&self, i: usize) -> Option<usize> {
        self.0.bones[i].parent
    }
    fn origin(&self, i: usize) -> [f64; 2] {
        self.1.origin(i)
    }
    fn rotation(&self, i: usize) -> f64 {
        self.1.rotation(i)
    }
    fn tip(&self, i: usize) -> [f64; 2] {
        self.1.tip(i)
    }
    fn local_rotation(&self, i: usize) -> f64 {
        self.1.local(i).rotation
    }
    fn name(&self, i: usize) -> String {
        self.0.bones[i].name.clone()
    }
}

/// The `moving` bones (ascending) of `view` frozen as an ikarus skeleton, each bone's
/// `(limits of its local rotation, stiffness)` from `rule`.
pub(super) fn freeze_view(
    view: &impl PoseView,
    moving: &[usize],
    rule: impl Fn(usize) -> Option<(Option<[f64; 2]>, f64)>,
) -> Result<Frozen, TogetherError> {
    let mut bones = Vec::with_capacity(moving.len());
    let mut start = Vec::with_capacity(moving.len());
    for &m in moving {
        let (up, geometry) = frozen_bone(view, moving, m, rule(m).and_then(|(limits, _)| limits))?;
        let mut bone = Bone::new(view.name(m), geometry.length, geometry.angle).with_offset(geometry.offset);
        if let Some(p) = up {
            bone = bone.with_parent(view.name(p));
        }
        if let Some((_, stiffness)) = rule(m) {
            if let Some(l) = geometry.limits {
                bone = bone.with_limits(l);
            }
            bone = bone.with_stiffness(stiffness);
        }
        start.push(bone.angle);
        bones.push(bone);
    }
    let skeleton = Skeleton::new([0.0, 0.0], &bones).map_err(|e| TogetherError::Solve(e.to_string()))?;
    Ok(Frozen { skeleton, bones: moving.to_vec(), start })
}

/// [`freeze_view`] again into `frozen`, a freeze of the same `moving` bones of the same tree
/// without stiffness, in place: its skeleton refitted ([`Skeleton::refit`]), nothing
/// allocated; `geometry` is scratch. The same skeleton and start as [`freeze_view`]'s, bit for
/// bit.
pub(super) fn refreeze_view(
    view: &impl PoseView,
    frozen: &mut Frozen,
    limits: impl Fn(usize) -> Option<[f64; 2]>,
    geometry: &mut Vec<Refit>,
) -> Result<(), TogetherError> {
    geometry.clear();
    frozen.start.clear();
    for &m in &frozen.bones {
        let (_, g) = frozen_bone(view, &frozen.bones, m, limits(m))?;
        frozen.start.push(g.angle);
        geometry.push(g);
    }
    frozen.skeleton.refit([0.0, 0.0], |k| geometry[k]).map_err(|e| TogetherError::Solve(e.to_string()))
}

/// Moving bone `m` as the frozen skeleton has it: its parent there (its nearest moving
/// ancestor) and its geometry, its angle clamped into `limits` (of its local rotation).
fn frozen_bone(
    view: &impl PoseView,
    moving: &[usize],
    m: usize,
    limits: Option<[f64; 2]>,
) -> Result<(Option<usize>, Refit), TogetherError> {
    let index = |b: usize| moving.binary_search(&b).ok();
    let mut up = view.parent(m);
    while let Some(p) = up.filter(|&p| index(p).is_none()) {
        up = view.parent(p);
    }
    let [x, y] = view.origin(m);
    let theta = view.rotation(m);
    let [tx, ty] = view.tip(m);
    // A bone of length 0 keeps a length (its children hang on offsets, not on its tip).
    let length = math::distance(tx - x, ty - y).max(1e-9);
    let (mut angle, offset) = match up {
        Some(p) => {
            let [px, py] = view.origin(p);
            let tp = view.rotation(p);
            let (s, c) = math::sin_cos(tp);
            let (dx, dy) = (x - px, y - py);
            (wrap_angle(theta - tp), [c * dx + s * dy, -s * dx + c * dy])
        }
        None => (theta, [x, y]),
    };
    let limits = match limits {
        Some([lo, hi]) => {
            // The limits are on the local rotation; the skeleton's angle differs from it by
            // what the bones between (and the parent's shear) add, constant here.
            let shift = angle - view.local_rotation(m);
            let l = JointLimits::new(lo + shift, hi + shift).map_err(|e| TogetherError::Rule(e.to_string()))?;
            angle = angle.clamp(lo + shift, hi + shift);
            Some(l)
        }
        None => None,
    };
    Ok((up, Refit { length, angle, offset, limits }))
}

impl Character {
    /// The moving bones frozen at `posed` as an ikarus skeleton.
    pub(super) fn freeze(&self, posed: &Posed, moving: &[usize], rules: &Together) -> Result<Frozen, TogetherError> {
        let mut bone_rules = vec![None; self.bones.len()];
        for r in rules.bones.iter().rev() {
            bone_rules[r.bone] = Some(r);
        }
        freeze_view(&CharacterView(self, posed), moving, |m| bone_rules[m].map(|r| (r.limits, r.stiffness)))
    }

    pub(super) fn task(
        &self,
        posed: &Posed,
        frozen: &Frozen,
        (rules, limb_rules): (&Together, &[Option<&LimbRule>]),
        goals: &[usize],
    ) -> Result<RigTask, TogetherError> {
        let index = |b: usize| frozen.bones.binary_search(&b).ok();
        let mut task = RigTask::new(Vec::new(), Vec::new());
        // One goal per skeleton bone: a later one on the same bone replaces an earlier one and
        // goes last, as a removal and a push would put it, without a scan of the goals.
        let mut slots = GoalSlots::new(frozen.bones.len());
        for &k in goals {
            let (Some(c), Some(settings)) = (self.ik(k), posed.ik_settings(k)) else { continue };
            let last = last_bone(c.bones);
            let Some(i) = index(last) else { continue };
            let [x, y] = posed.origin(c.target);
            let goal =
                Goal::position(x, y).map_err(|e| TogetherError::Solve(format!("constraint {:?}: {e}", c.name)))?;
            let rule = limb_rules[k];
            let mut g =
                RigGoal::new(i, goal).with_weight(rule.map_or(1.0, |r| r.weight)).with_softness(settings.softness);
            if matches!(c.bones, IkBones::One(_)) || rule.is_some_and(|r| r.secondary) {
                g = g.with_priority(Priority::Secondary);
            }
            if matches!(c.bones, IkBones::Two { .. }) && frozen.skeleton.parent(i).is_some() {
                g = g.with_bend(bend_of(frozen.start[i], &settings, posed, c.bones, c.rule));
            }
            // One goal per bone: a later constraint on the same bone replaces an earlier one.
            slots.put(i, g);
        }
        for g in &rules.goals {
            let Some(i) = index(g.goal.bone) else { continue };
            let mut goal = g.goal.clone();
            goal.bone = i;
            // A bend needs a joint: the goal's bone must turn with its parent.
            if frozen.skeleton.parent(i).is_none() {
                goal.bend = None;
            }
            slots.put(i, goal);
        }
        for &p in &rules.pins {
            if let Some(i) = index(p) {
                slots.clear(i);
                task.pins.push(Pin::new(i));
            }
        }
        task.goals = slots.goals();
        Ok(task)
    }

    /// Writes the solved directions back as local rotations, parents first, recomputing the
    /// world transforms as the runtime does; `points` gets the skeleton's solved points (its
    /// root's origin, then each bone's tip).
    pub(super) fn thaw(&self, out: &mut Posed, frozen: &Frozen, angles: &[f64], points: &mut [nalgebra::Point2<f64>]) {
        let n = frozen.bones.len();
        let mut directions = vec![0.0; n];
        frozen.skeleton.points_into(angles, points, &mut directions);
        let (mut bones, ..) = out.bones(self);
        for (k, &m) in frozen.bones.iter().enumerate() {
            let parent = self.bones[m].parent.map(|p| bones.world[p]);
            let r =
                rotation_for(&bones.local[m], self.bones[m].inherit, parent.as_ref(), self.placement, directions[k]);
            bones.local[m].rotation = r;
            bones.update_below(m);
        }
    }

    /// How far the tips of the moving bones in `out` are from the skeleton's solved `points`
    /// (0 when the pose the constraints make is the solve's).
    pub(super) fn drift(&self, out: &Posed, frozen: &Frozen, points: &[nalgebra::Point2<f64>]) -> f64 {
        let mut drift: f64 = 0.0;
        for (k, &m) in frozen.bones.iter().enumerate() {
            let tip = out.tip(m);
            let p = points[k + 1];
            // A bone of length 0 was given a tiny length; its tip is its origin.
            let d = if self.bones[m].length > 0.0 { math::distance(tip[0] - p.x, tip[1] - p.y) } else { 0.0 };
            drift = drift.max(d);
        }
        drift
    }

    /// How far constraint `k` misses its target: a two-bone one, its tip's distance from it; a
    /// one-bone one (an aim: its tip reaches only by chance), the target's distance from the
    /// bone's ray (0 when it points right at it).
    pub(super) fn miss(&self, k: usize, out: &Posed) -> f64 {
        let Some(c) = self.ik(k) else { return 0.0 };
        let [tx, ty] = out.origin(c.target);
        let b = last_bone(c.bones);
        match c.bones {
            IkBones::Two { .. } => {
                let [x, y] = out.tip(b);
                math::distance(x - tx, y - ty)
            }
            IkBones::One(_) => {
                let [x, y] = out.origin(b);
                let (s, co) = math::sin_cos(out.rotation(b));
                let (dx, dy) = (tx - x, ty - y);
                let along = co * dx + s * dy;
                let across = (-s * dx + co * dy).abs();
                if along >= 0.0 { across } else { math::distance(dx, dy) }
            }
        }
    }

    /// The largest distance of a bone's origin from the skeleton's, a scale for tolerances.
    pub(super) fn size(&self, posed: &Posed) -> f64 {
        (0..self.bones.len()).map(|i| posed.origin(i)).fold(0.0, |m: f64, [x, y]| m.max(x.abs()).max(y.abs()))
    }
}

/// How far the tip of `goal`'s bone ended from it.
pub(super) fn goal_end(goal: &RigGoal, out: &Posed) -> GoalEnd {
    let [x, y] = out.tip(goal.bone);
    let t = goal.goal.target();
    GoalEnd {
        bone: goal.bone,
        error: math::distance(x - t.x, y - t.y),
        angle_error: goal.goal.orientation().map(|a| wrap_angle(out.rotation(goal.bone) - a)),
    }
}

pub(super) fn last_bone(bones: IkBones) -> usize {
    match bones {
        IkBones::One(b) => b,
        IkBones::Two { child, .. } => child,
    }
}

/// The side a two-bone limb bends, as the skeleton's angle of its child: for Spine's rule, the
/// side its constraint names (counter-clockwise for `bendPositive`, unless the parent's world
/// frame is mirrored); for DragonBones', the side the runtime's pose has it (`angle`, the child's
/// angle at the start), counter-clockwise when straight.
fn bend_of(angle: f64, s: &IkSettings, posed: &Posed, bones: IkBones, rule: IkRule) -> Bend {
    let positive = match (rule, bones) {
        (IkRule::Spine, IkBones::Two { parent, .. }) => {
            let [a, b, c, d] = posed.matrix(parent);
            s.bend_positive != (a * d - b * c < 0.0)
        }
        (IkRule::Spine, IkBones::One(_)) | (IkRule::DragonBones, _) => angle >= -1e-9,
    };
    if positive { Bend::Positive } else { Bend::Negative }
}

/// The local rotation that points `bone`'s world x axis along `direction` under its inherit
/// mode, from its current local transform: Newton's method on the world direction as a
/// function of the rotation, its derivative by a central difference (±1 for a normal bone
/// under a parent without shear; other modes and shears bend it).
pub(super) fn rotation_for(
    local: &LocalTransform,
    inherit: Inherit,
    parent: Option<&Affine>,
    placement: Placement,
    direction: f64,
) -> f64 {
    let world_dir = |r: f64| {
        let t = LocalTransform { rotation: r, ..*local };
        world_transform(&t, inherit, parent, placement).rotation()
    };
    let mut r = local.rotation;
    for _ in 0..8 {
        let miss = wrap_angle(direction - world_dir(r));
        if miss.abs() < 1e-14 {
            break;
        }
        let h = 1e-6;
        let slope = wrap_angle(world_dir(r + h) - world_dir(r - h)) / (2.0 * h);
        if slope.abs() < 1e-6 {
            break;
        }
        r += miss / slope;
    }
    r
}
