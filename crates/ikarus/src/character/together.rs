//! A character's IK constraints solved together by ikarus's rig solver, instead of one after
//! another by the runtime's one- and two-bone rules.
//!
//! The runtime applies its constraints in order, each on at most two bones, each blind to the
//! others: a later constraint can undo an earlier one, and a limb of three bones cannot be
//! solved at all. Here every active constraint (mix > 0, and turned on by the skin with its bones
//! and target: [`super::skin`]) becomes a goal on its last bone's tip
//! at its target bone's world origin, and one weighted least-squares solve
//! ([`Solver::solve_rig`]) moves every bone of every limb at once:
//!
//! 1. The runtime's own pose is the start ([`Character::pose`]): it has each two-bone limb bent
//!    the way its constraint says, and the solve keeps that side ([`Bend`]).
//! 2. The bones that move (each constraint's bones, extended up the hierarchy by
//!    [`LimbRule::bones`], and the pinned bones) become an ikarus [`Skeleton`] frozen at that
//!    pose: a bone's origin, world direction and world length as the runtime's world transforms
//!    have them, its parent the nearest moving ancestor (the bones between are rigid).
//! 3. After the solve, each moving bone's world direction is written back as the local rotation
//!    that gives it under the bone's own inherit mode, parents first. Each moving bone's local
//!    rotation is then held (as [`PoseRequest::turns`] holds a bone turned by hand, turned by
//!    what the solve turned it) and the character is posed again from the request, the solved
//!    IK constraints left out (as at mix 0) and every other constraint (transform, path, IK aims
//!    on bones of length 0) applied in its order on top: the answer is a pose the constraints
//!    produce, a transform constraint following a solved limb follows it. Where that pose is not
//!    the solve's (a constraint reads a solved bone and moves the limb, or a parent's scale is
//!    not uniform, so that a rotation is not rigid in the runtime's world), the skeleton is
//!    rebuilt from it and solved again (at most [`ROUNDS`] times in all) until the two agree:
//!    under a mild uneven scale (1.15 by 0.9) the gap shrinks about fourfold a round; under a
//!    strong one (1.6 by 0.6) a bone's world length changes so much with its rotation that the
//!    rounds need not close it. A constraint that itself turns or moves a goal's bones fights
//!    the goal: a partial mix gives way a round at a time (the held rotation moves by what the
//!    goal still needs), a full one does not; either way the report's errors are measured on
//!    the final pose, and say what is left.
//!
//! What the runtime's rules have that this does not: `stretch` and `compress` (the solve turns
//! bones; it never scales them) and a partial mix (a constraint with mix > 0 is solved fully;
//! mix 0 leaves it out). A one-bone constraint is a secondary goal on its bone's tip (the least
//! squares of a tip toward a point is the aim toward it), so that it turns its own bone in what
//! the limbs above it leave free instead of pulling them; on a bone of length 0 it has no tip to
//! aim, and the runtime's aim applies in its order when the pose is made again.

use super::pose::{Frame, PoseError, PoseRequest, Posed};
use super::world::{Affine, world_transform};
use super::{Character, IkBones, IkRule, IkSettings};
use crate::angle::wrap_angle;
use crate::goal::Goal;
use crate::limits::JointLimits;
use crate::math;
use crate::skeleton::{Bone, Skeleton};
use crate::solve::{Bend, Pin, Priority, RigGoal, RigTask, RigTaskError, SolveError, Solver};
use goal_slots::GoalSlots;

#[path = "goal_slots.rs"]
mod goal_slots;
#[path = "together_rules.rs"]
mod rules;
pub use rules::{
    BoneRule, GoalEnd, LimbEnd, LimbRule, TIP_GOAL_BONES, TipGoal, Together, TogetherError, TogetherReport,
};

/// How many times at most the skeleton is rebuilt and solved again (see the module docs).
pub const ROUNDS: usize = 16;

/// The moving bones as an ikarus skeleton: `bones[k]` is the character's bone of the
/// skeleton's bone `k`.
struct Frozen {
    skeleton: Skeleton,
    bones: Vec<usize>,
    start: Vec<f64>,
}

impl Character {
    /// Poses the character as [`Character::pose`] does, then solves its active constraints
    /// together with `solver` (a method that solves rigs), as the module docs say; `out` holds
    /// the final pose, its local transforms those that give it under the runtime's world
    /// transforms.
    ///
    /// The solver's [`interrupt`](crate::SolveOptions::interrupt), when it has one, is watched
    /// by the pose ([`Character::pose_watched`]) and between rounds: once it is set, the call
    /// ends with [`PoseError::Interrupted`] (inside [`TogetherError::Pose`]).
    ///
    /// The work besides the solves is linear in the bones, constraints and rules: every lookup
    /// by constraint or bone is indexed once, and a goal that replaces another on the same bone
    /// takes its place without a scan of the goals.
    pub fn pose_together(
        &self,
        request: &PoseRequest,
        rules: &Together,
        solver: &mut Solver,
        out: &mut Posed,
    ) -> Result<TogetherReport, TogetherError> {
        self.together(request, (rules, solver), out, Frame::Still)
    }

    /// [`Character::pose_together`] with the physics constraints treated as `frame` says: as
    /// one frame of a play, every pose of the rounds steps them from the state `out` kept
    /// from the frame before (restored before each round), so that the goals are met on the
    /// pose the constraints, physics included, produce at that frame.
    pub(super) fn together(
        &self,
        request: &PoseRequest,
        (rules, solver): (&Together, &mut Solver),
        out: &mut Posed,
        frame: Frame,
    ) -> Result<TogetherReport, TogetherError> {
        self.check_together(rules)?;
        let interrupt = solver.options().interrupt.clone();
        // The physics as the frame before left it: every round steps it from there.
        let kept = matches!(frame, Frame::Play { .. }).then(|| out.physics.clone());
        self.pose_frame(request, out, interrupt.as_ref(), (frame, &[]))?;
        // A goal or pin on a bone the skin leaves inactive (not posed) could only be met at a
        // made-up place.
        let goal_bones = rules.goals.iter().map(|g| g.goal.bone);
        if let Some(b) = goal_bones.chain(rules.pins.iter().copied()).find(|&b| !out.is_active(b)) {
            let name = &self.bones[b].name;
            return Err(TogetherError::Rule(format!(
                "bone {name:?}: inactive with this skin (a skin-only bone, or below one, that it does not turn on): no goal or pin on it"
            )));
        }
        let active: Vec<usize> = self
            .ik_constraints()
            .map(|(k, _)| k)
            .filter(|&k| out.ik_settings(k).is_some_and(|s| s.mix > 0.0) && self.is_active(k, out.activity()))
            .collect();
        let limb_rules = self.limb_rules(rules);
        let moving = self.moving(rules, &limb_rules, &active);
        let mut report = TogetherReport::default();
        let goals: Vec<usize> = active.iter().copied().filter(|&k| self.has_tip_goal(k)).collect();
        let anything = !goals.is_empty() || !rules.goals.is_empty();
        if !moving.is_empty() && anything {
            // The request's turns, then the moving bones' local rotations held as turns.
            let mut held: Vec<(usize, f64)> = request.turns.to_vec();
            let first = held.len();
            held.extend(moving.iter().map(|&m| (m, out.local(m).rotation)));
            let mut before = vec![0.0; moving.len()];
            let mut points = vec![nalgebra::Point2::origin(); moving.len() + 1];
            for round in 1..=ROUNDS {
                let frozen = self.freeze(out, &moving, rules)?;
                let task = self.task(out, &frozen, (rules, &limb_rules), &goals)?;
                let outcome = solver.solve_rig(&frozen.skeleton, &frozen.start, &task).map_err(|e| match e {
                    SolveError::Rig(RigTaskError::BendOutsideLimits { name }) => {
                        TogetherError::BendOutsideLimits { bone: name }
                    }
                    e => TogetherError::Solve(e.to_string()),
                })?;
                if outcome.status == crate::Status::Interrupted || crate::interrupt::is_set(interrupt.as_ref()) {
                    return Err(TogetherError::Pose(PoseError::Interrupted));
                }
                for (b, &m) in before.iter_mut().zip(&moving) {
                    *b = out.local(m).rotation;
                }
                self.thaw(out, &frozen, outcome.pose.angles(), &mut points);
                // Each held rotation turned by what the solve turned its bone, and the pose made
                // again from the request: the solved IK constraints left out, every other
                // constraint applied in its order on top of the held rotations.
                for (j, &m) in moving.iter().enumerate() {
                    held[first + j].1 += wrap_angle(out.local(m).rotation - before[j]);
                }
                let again = PoseRequest { turns: &held, ..*request };
                if let Some(kept) = &kept {
                    out.physics.clone_from(kept);
                }
                self.pose_frame(&again, out, interrupt.as_ref(), (frame, &goals))?;
                let drift = self.drift(out, &frozen, &points);
                report.rounds = round;
                report.outcome = Some(outcome);
                if drift <= 1e-9 * (1.0 + self.size(out)) {
                    break;
                }
            }
        }
        let mut is_active = vec![false; self.constraints.len()];
        for &k in &active {
            is_active[k] = true;
        }
        report.limbs = self
            .ik_constraints()
            .map(|(k, _)| {
                let on = is_active[k];
                let error = if on && self.has_tip_goal(k) { self.miss(k, out) } else { 0.0 };
                LimbEnd { constraint: k, active: on, error }
            })
            .collect();
        report.goals = rules.goals.iter().map(|g| goal_end(&g.goal, out)).collect();
        Ok(report)
    }

    /// Checks `rules` against the character: constraints and bones that exist, weights > 0,
    /// limb lengths from the constraint's own bones to its root, stiffness ≥ 0, limits in order.
    pub fn check_together(&self, rules: &Together) -> Result<(), TogetherError> {
        let n = self.bones.len();
        let depths = self.depths();
        for r in &rules.limbs {
            let c = self
                .ik(r.constraint)
                .ok_or_else(|| TogetherError::Rule(format!("limb: no IK constraint {}", r.constraint)))?;
            if !(r.weight > 0.0 && r.weight.is_finite()) {
                return Err(TogetherError::Rule(format!("limb {:?}: weight must be > 0, got {}", c.name, r.weight)));
            }
            let own = match c.bones {
                IkBones::One(_) => 1,
                IkBones::Two { .. } => 2,
            };
            if let Some(b) = r.bones {
                let depth = depths[last_bone(c.bones)] + 1;
                if b < own || b > depth {
                    return Err(TogetherError::Rule(format!(
                        "limb {:?}: bones must be from {own} (its own) to {depth} (up to its root), got {b}",
                        c.name
                    )));
                }
            }
        }
        for r in &rules.bones {
            let name =
                &self.bones.get(r.bone).ok_or_else(|| TogetherError::Rule(format!("bone: no bone {}", r.bone)))?.name;
            if !(r.stiffness >= 0.0 && r.stiffness.is_finite()) {
                return Err(TogetherError::Rule(format!("bone {name:?}: stiffness must be ≥ 0, got {}", r.stiffness)));
            }
            if let Some([lo, hi]) = r.limits {
                JointLimits::new(lo, hi).map_err(|e| TogetherError::Rule(format!("bone {name:?}: limits: {e}")))?;
            }
        }
        if let Some(&p) = rules.pins.iter().find(|&&p| p >= n) {
            return Err(TogetherError::Rule(format!("pin: no bone {p}")));
        }
        for g in &rules.goals {
            let b = g.goal.bone;
            let name = &self.bones.get(b).ok_or_else(|| TogetherError::Rule(format!("goal: no bone {b}")))?.name;
            let depth = depths[b] + 1;
            if g.bones < 1 || g.bones > depth {
                return Err(TogetherError::Rule(format!(
                    "goal on {name:?}: bones must be from 1 (the bone alone) to {depth} (up to its root), got {}",
                    g.bones
                )));
            }
            if !(g.goal.weight > 0.0 && g.goal.weight.is_finite()) {
                return Err(TogetherError::Rule(format!(
                    "goal on {name:?}: weight must be > 0, got {}",
                    g.goal.weight
                )));
            }
            if !(g.goal.softness >= 0.0 && g.goal.softness.is_finite()) {
                return Err(TogetherError::Rule(format!(
                    "goal on {name:?}: softness must be ≥ 0, got {}",
                    g.goal.softness
                )));
            }
        }
        Ok(())
    }

    /// Every bone's depth (a root's is 0), in one pass: parents come first.
    fn depths(&self) -> Vec<usize> {
        let mut depths = Vec::with_capacity(self.bones.len());
        for b in &self.bones {
            let d = b.parent.map_or(0, |p| depths[p] + 1);
            depths.push(d);
        }
        depths
    }

    /// Per constraint, the first limb rule naming it (a rule for a constraint that does not
    /// exist was refused by [`Character::check_together`]).
    fn limb_rules<'r>(&self, rules: &'r Together) -> Vec<Option<&'r LimbRule>> {
        let mut by = vec![None; self.constraints.len()];
        for r in rules.limbs.iter().rev() {
            by[r.constraint] = Some(r);
        }
        by
    }

    /// Whether constraint `k` is a goal of the solve: every two-bone one, and a one-bone one on
    /// a bone with a length.
    fn has_tip_goal(&self, k: usize) -> bool {
        match self.ik(k).map(|c| c.bones) {
            Some(IkBones::One(b)) => self.bones[b].length > 0.0,
            Some(IkBones::Two { .. }) => true,
            None => false,
        }
    }

    /// The moving bones, ascending (parents first): each active constraint's bones, up as far
    /// as its rule says, each goal's, and the pins.
    fn moving(&self, rules: &Together, limb_rules: &[Option<&LimbRule>], active: &[usize]) -> Vec<usize> {
        let mut on = vec![false; self.bones.len()];
        for &k in active.iter().filter(|&&k| self.has_tip_goal(k)) {
            let Some(c) = self.ik(k) else { continue };
            let own = match c.bones {
                IkBones::One(_) => 1,
                IkBones::Two { .. } => 2,
            };
            let count = limb_rules[k].and_then(|r| r.bones).unwrap_or(own);
            let mut b = Some(last_bone(c.bones));
            for _ in 0..count {
                let Some(i) = b else { break };
                on[i] = true;
                b = self.bones[i].parent;
            }
        }
        for g in &rules.goals {
            let mut b = Some(g.goal.bone);
            for _ in 0..g.bones {
                let Some(i) = b else { break };
                on[i] = true;
                b = self.bones[i].parent;
            }
        }
        for &p in &rules.pins {
            on[p] = true;
        }
        (0..on.len()).filter(|&i| on[i]).collect()
    }

    /// The moving bones frozen at `posed` as an ikarus skeleton.
    fn freeze(&self, posed: &Posed, moving: &[usize], rules: &Together) -> Result<Frozen, TogetherError> {
        let index = |b: usize| moving.binary_search(&b).ok();
        let mut bone_rules = vec![None; self.bones.len()];
        for r in rules.bones.iter().rev() {
            bone_rules[r.bone] = Some(r);
        }
        let mut bones = Vec::with_capacity(moving.len());
        let mut start = Vec::with_capacity(moving.len());
        for &m in moving {
            let mut up = self.bones[m].parent;
            while let Some(p) = up.filter(|&p| index(p).is_none()) {
                up = self.bones[p].parent;
            }
            let [x, y] = posed.origin(m);
            let theta = posed.rotation(m);
            let [tx, ty] = posed.tip(m);
            // A bone of length 0 keeps a length (its children hang on offsets, not on its tip).
            let length = math::distance(tx - x, ty - y).max(1e-9);
            let (angle, offset) = match up {
                Some(p) => {
                    let [px, py] = posed.origin(p);
                    let tp = posed.rotation(p);
                    let (s, c) = math::sin_cos(tp);
                    let (dx, dy) = (x - px, y - py);
                    (wrap_angle(theta - tp), [c * dx + s * dy, -s * dx + c * dy])
                }
                None => (theta, [x, y]),
            };
            let b = &self.bones[m];
            let mut bone = Bone::new(b.name.clone(), length, angle).with_offset(offset);
            if let Some(p) = up {
                bone = bone.with_parent(self.bones[p].name.clone());
            }
            if let Some(r) = bone_rules[m] {
                if let Some([lo, hi]) = r.limits {
                    // The limits are on the local rotation; the skeleton's angle differs from it
                    // by what the bones between (and the parent's shear) add, constant here.
                    let shift = angle - posed.local(m).rotation;
                    let l = JointLimits::new(lo + shift, hi + shift).map_err(|e| TogetherError::Rule(e.to_string()))?;
                    bone = bone.with_limits(l);
                    bone.angle = angle.clamp(lo + shift, hi + shift);
                }
                bone = bone.with_stiffness(r.stiffness);
            }
            start.push(bone.angle);
            bones.push(bone);
        }
        let skeleton = Skeleton::new([0.0, 0.0], &bones).map_err(|e| TogetherError::Solve(e.to_string()))?;
        Ok(Frozen { skeleton, bones: moving.to_vec(), start })
    }

    fn task(
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
    fn thaw(&self, out: &mut Posed, frozen: &Frozen, angles: &[f64], points: &mut [nalgebra::Point2<f64>]) {
        let n = frozen.bones.len();
        let mut directions = vec![0.0; n];
        frozen.skeleton.points_into(angles, points, &mut directions);
        let (mut bones, ..) = out.bones(self);
        for (k, &m) in frozen.bones.iter().enumerate() {
            let parent = self.bones[m].parent.map(|p| bones.world[p]);
            let r = rotation_for(&bones.local[m], &self.bones[m], parent.as_ref(), self.placement, directions[k]);
            bones.local[m].rotation = r;
            bones.update_below(m);
        }
    }

    /// How far the tips of the moving bones in `out` are from the skeleton's solved `points`
    /// (0 when the pose the constraints make is the solve's).
    fn drift(&self, out: &Posed, frozen: &Frozen, points: &[nalgebra::Point2<f64>]) -> f64 {
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
    fn miss(&self, k: usize, out: &Posed) -> f64 {
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
    fn size(&self, posed: &Posed) -> f64 {
        (0..self.bones.len()).map(|i| posed.origin(i)).fold(0.0, |m: f64, [x, y]| m.max(x.abs()).max(y.abs()))
    }
}

/// How far the tip of `goal`'s bone ended from it.
fn goal_end(goal: &RigGoal, out: &Posed) -> GoalEnd {
    let [x, y] = out.tip(goal.bone);
    let t = goal.goal.target();
    GoalEnd {
        bone: goal.bone,
        error: math::distance(x - t.x, y - t.y),
        angle_error: goal.goal.orientation().map(|a| wrap_angle(out.rotation(goal.bone) - a)),
    }
}

fn last_bone(bones: IkBones) -> usize {
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
        _ => angle >= -1e-9,
    };
    if positive { Bend::Positive } else { Bend::Negative }
}

/// The local rotation that points `bone`'s world x axis along `direction` under its inherit
/// mode, from its current local transform: Newton's method on the world direction as a
/// function of the rotation, its derivative by a central difference (±1 for a normal bone
/// under a parent without shear; other modes and shears bend it).
fn rotation_for(
    local: &super::LocalTransform,
    bone: &super::CharacterBone,
    parent: Option<&Affine>,
    placement: super::Placement,
    direction: f64,
) -> f64 {
    let world_dir = |r: f64| {
        let t = super::LocalTransform { rotation: r, ..*local };
        world_transform(&t, bone.inherit, parent, placement).rotation()
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

#[cfg(test)]
#[path = "together_tests.rs"]
mod tests;
