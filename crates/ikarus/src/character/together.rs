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
use super::{Character, IkBones};
use crate::angle::wrap_angle;
use crate::limits::JointLimits;
use crate::solve::{RigTaskError, SolveError, Solver};
use freeze::{goal_end, last_bone};

#[path = "together_freeze.rs"]
mod freeze;
#[path = "goal_slots.rs"]
mod goal_slots;
#[path = "together_rules.rs"]
mod rules;
#[path = "spine_rig.rs"]
mod spine_rig;
pub use rules::{
    BoneRule, GoalEnd, LimbEnd, LimbRule, TIP_GOAL_BONES, TipGoal, Together, TogetherError, TogetherReport,
};
pub use spine_rig::{SPINE_BONE_NUMBERS, SpineBone, SpineFrame, SpineRig, spine_bone_numbers, spine_local_numbers};

/// How many times at most the skeleton is rebuilt and solved again (see the module docs).
pub const ROUNDS: usize = 16;

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
}

#[cfg(test)]
#[path = "together_tests.rs"]
mod tests;
