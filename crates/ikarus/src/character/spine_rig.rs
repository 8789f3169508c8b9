//! A solve on a skeleton given as a runtime's raw numbers (issue 41: the core the
//! `ikarus-spine` add-on's WebAssembly calls each frame), without a [`Character`](super::super::Character).
//!
//! Once ([`SpineRig::new`]): per bone its parent, length, inherit mode and optional limits on its
//! local rotation, degrees. Each frame ([`SpineRig::solve`]): per bone the world transform and the
//! local transform the runtime left ([`SPINE_BONE_NUMBERS`] numbers, in the runtime's terms:
//! degrees), the goals ([`TipGoal`]: a bone, its goal, how many bones up it moves) and the pins.
//! The moving bones (each goal's bones, and each pin below one of them: a pin under no moving
//! bone cannot move and stays out) are frozen into an ikarus skeleton at the runtime's pose
//! with the same code as [`Character::pose_together`](super::super::Character::pose_together)
//! (`freeze_view`; from the second frame with the same moving bones, the kept skeleton is
//! refitted in place, `refreeze_view`, so that a frame allocates nothing), solved by the rig
//! solver warm-started from that pose (so that a limb keeps its bend side frame to frame), and
//! thawed into local rotations under each bone's inherit mode
//! (`rotation_for`), parents first; a moving bone below bones that do not move is carried
//! rigidly by its nearest moving ancestor, as the frozen skeleton has it. Bones that do not move
//! keep their rotation.

use super::super::world::{Affine, aim_frame, world_transform};
use super::super::{Inherit, LocalTransform, Placement};
use super::freeze::{Frozen, PoseView, freeze_view, refreeze_view, rotation_for};
use super::rules::{TipGoal, TogetherError};
use crate::angle::wrap_angle;
use crate::math;
use crate::skeleton::Refit;
use crate::solve::{Outcome, Pin, RigTask, SolveError, Solver};

/// Numbers per bone in a frame: world `a, b, c, d, worldX, worldY`, then local `x, y, rotation,
/// scaleX, scaleY, shearX, shearY` (rotation and shears in degrees), as the runtime names them.
pub const SPINE_BONE_NUMBERS: usize = 13;

/// A local transform as the runtime's 7 local numbers: `x, y, rotation, scaleX, scaleY,
/// shearX, shearY` (rotation and shears in degrees).
pub fn spine_local_numbers(l: &LocalTransform) -> [f64; 7] {
    [l.x, l.y, l.rotation.to_degrees(), l.scale_x, l.scale_y, l.shear_x.to_degrees(), l.shear_y.to_degrees()]
}

/// A bone's [`SPINE_BONE_NUMBERS`] numbers in a frame's order: `world`'s `a, b, c, d, x, y`,
/// then [`spine_local_numbers`] of `local`.
pub fn spine_bone_numbers(world: &Affine, local: &LocalTransform) -> [f64; SPINE_BONE_NUMBERS] {
    let l = spine_local_numbers(local);
    [world.a, world.b, world.c, world.d, world.x, world.y, l[0], l[1], l[2], l[3], l[4], l[5], l[6]]
}

/// At most this many rounds of freeze, solve and thaw per frame (see [`SpineRig::solve`]).
const ROUNDS: usize = 8;

/// A round's pose is the frozen skeleton's when its moved tips are this close to the frozen
/// ones (in the skeleton's units).
const DRIFT: f64 = 1e-7;

/// The runtime's names of a bone's [`SPINE_BONE_NUMBERS`] numbers, in their order.
const SPINE_BONE_FIELDS: [&str; SPINE_BONE_NUMBERS] =
    ["a", "b", "c", "d", "worldX", "worldY", "x", "y", "rotation", "scaleX", "scaleY", "shearX", "shearY"];

/// One bone of a [`SpineRig`], as the runtime's bone data has it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpineBone {
    /// The parent's index, lower than this bone's; `None` for a root.
    pub parent: Option<usize>,
    /// Length along the local x axis, ≥ 0.
    pub length: f64,
    /// What it takes from its parent.
    pub inherit: Inherit,
    /// The range of its local rotation, degrees, when it moves.
    pub limits_deg: Option<[f64; 2]>,
}

/// One frame of a [`SpineRig`]: the runtime's numbers and what to solve.
#[derive(Debug, Clone, Copy)]
pub struct SpineFrame<'a> {
    /// [`SPINE_BONE_NUMBERS`] per bone, in the bones' order.
    pub numbers: &'a [f64],
    /// The skeleton's own position and scale (a root bone's world transform includes it).
    pub placement: Placement,
    /// Goals on bones' tips, in the skeleton's world coordinates.
    pub goals: &'a [TipGoal],
    /// Bones whose tip (position and direction) stays where the runtime put it.
    pub pins: &'a [usize],
}

/// A skeleton's bone tree, attached once, with the buffers each frame's solve reuses.
#[derive(Debug, Clone)]
pub struct SpineRig {
    bones: Vec<SpineBone>,
    depths: Vec<usize>,
    world: Vec<Affine>,
    local: Vec<LocalTransform>,
    solved: Vec<Affine>,
    on: Vec<bool>,
    moving: Vec<usize>,
    errors: Vec<f64>,
    points: Vec<nalgebra::Point2<f64>>,
    directions: Vec<f64>,
    /// The bones the solve before moved and their answers, local rotations in radians: the
    /// next solve of the same bones starts there.
    last_moved: Vec<usize>,
    last: Vec<f64>,
    /// The task and the outcome, their buffers kept from frame to frame.
    task: RigTask,
    outcome: Outcome,
    /// The frozen skeleton of the solve before, refitted when the same bones move, and the
    /// scratch of its refit.
    frozen: Option<Frozen>,
    geometry: Vec<Refit>,
}

impl SpineRig {
    /// The rig of `bones`: parents before children, lengths finite and ≥ 0, limits in order.
    pub fn new(bones: Vec<SpineBone>) -> Result<Self, TogetherError> {
        let mut depths = Vec::with_capacity(bones.len());
        for (i, b) in bones.iter().enumerate() {
            if let Some(p) = b.parent.filter(|&p| p >= i) {
                return Err(TogetherError::Rule(format!("bones[{i}].parent: must be below {i}, got {p}")));
            }
            if !(b.length >= 0.0 && b.length.is_finite()) {
                return Err(TogetherError::Rule(format!("bones[{i}].length: must be ≥ 0, got {}", b.length)));
            }
            if let Some([lo, hi]) = b.limits_deg
                && !(lo <= hi && lo.is_finite() && hi.is_finite())
            {
                return Err(TogetherError::Rule(format!("bones[{i}].limits: must be in order, got [{lo}, {hi}]")));
            }
            depths.push(b.parent.map_or(0, |p: usize| depths[p] + 1));
        }
        let n = bones.len();
        Ok(SpineRig {
            bones,
            depths,
            world: vec![Affine::default(); n],
            local: vec![LocalTransform::default(); n],
            solved: vec![Affine::default(); n],
            on: vec![false; n],
            moving: Vec::with_capacity(n),
            errors: Vec::new(),
            points: Vec::with_capacity(n + 1),
            directions: Vec::with_capacity(n),
            last_moved: Vec::with_capacity(n),
            last: Vec::with_capacity(n),
            task: RigTask::new(Vec::new(), Vec::new()),
            outcome: Outcome::default(),
            frozen: None,
            geometry: Vec::with_capacity(n),
        })
    }

    /// The bones the last solve moved, ascending.
    pub fn moved(&self) -> &[usize] {
        &self.moving
    }

    /// Per goal of the last solve, its bone's tip's distance from it after the solve.
    pub fn errors(&self) -> &[f64] {
        &self.errors
    }

    /// Solves `frame` with `solver` (a method that solves rigs) and writes every bone's local
    /// rotation, degrees, into `rotations` (one per bone: a moved bone's new one, the others
    /// the runtime's); the solve's outcome, `None` when there was no goal.
    pub fn solve(
        &mut self,
        frame: &SpineFrame,
        solver: &mut Solver,
        rotations: &mut [f64],
    ) -> Result<Option<&Outcome>, TogetherError> {
        self.read(frame, rotations)?;
        // The runtime's own numbers, bit for bit, for every bone that does not move.
        for (r, v) in rotations.iter_mut().zip(frame.numbers.chunks_exact(SPINE_BONE_NUMBERS)) {
            *r = v[8];
        }
        self.on.fill(false);
        for g in frame.goals {
            let mut b = Some(g.goal.bone);
            for _ in 0..g.bones {
                let Some(i) = b else { break };
                self.on[i] = true;
                b = self.bones[i].parent;
            }
        }
        // A pin under no moving bone cannot move (nothing above it turns, its own turn is
        // held): it stays out of the solve.
        for &p in frame.pins {
            let mut up = Some(p);
            while let Some(q) = up.filter(|&q| !self.on[q]) {
                up = self.bones[q].parent;
            }
            if up.is_some() {
                self.on[p] = true;
            }
        }
        self.moving.clear();
        self.moving.extend((0..self.on.len()).filter(|&i| self.on[i]));
        self.errors.clear();
        if frame.goals.is_empty() {
            self.moving.clear();
            return Ok(None);
        }
        let mut frozen = self.freeze()?;
        // A pin holds its bone's tip where the solve starts: started from the answer before,
        // it would hold the foot where that frame had it, drifting frame by frame. With a pin
        // in the solve it starts from this frame's pose.
        if !frame.pins.iter().any(|&p| self.on[p]) {
            self.warm_start(&mut frozen);
        }
        self.fill_task(&frozen, frame);
        for round in 0..ROUNDS {
            if round > 0 {
                // The frozen skeleton is the runtime's pose to first order: where a bone's
                // parent is scaled unevenly or sheared, or a bone does not take its parent's
                // rotation, turning it does not carry what hangs on it rigidly. Solved again
                // from the pose made, the error shrinks to second order each round.
                self.refreeze_solved(&mut frozen)?;
            }
            solver
                .solve_rig_into(&frozen.skeleton, &frozen.start, &self.task, &mut self.outcome)
                .map_err(|e: SolveError| TogetherError::Solve(e.to_string()))?;
            let angles = std::mem::take(&mut self.outcome.pose);
            let drift = self.thaw(&frozen, angles.angles(), frame.placement);
            self.outcome.pose = angles;
            if drift <= DRIFT {
                break;
            }
        }
        self.frozen = Some(frozen);
        self.last_moved.clear();
        self.last_moved.extend_from_slice(&self.moving);
        self.last.clear();
        for &m in &self.moving {
            rotations[m] = self.local[m].rotation.to_degrees();
            self.last.push(self.local[m].rotation);
        }
        for g in frame.goals {
            let w = &self.solved[g.goal.bone];
            let l = self.bones[g.goal.bone].length;
            let t = g.goal.goal.target();
            self.errors.push(math::distance(w.x + w.a * l - t.x, w.y + w.c * l - t.y));
        }
        Ok(Some(&self.outcome))
    }

    /// The moving bones frozen at the frame's pose: the kept skeleton refitted when it has the
    /// same bones (nothing allocated), else a new one.
    fn freeze(&mut self) -> Result<Frozen, TogetherError> {
        let limits =
            |bones: &[SpineBone], m: usize| bones[m].limits_deg.map(|[lo, hi]| [lo.to_radians(), hi.to_radians()]);
        if let Some(mut frozen) = self.frozen.take().filter(|f| f.bones == self.moving && f.skeleton.can_refit()) {
            let mut geometry = std::mem::take(&mut self.geometry);
            let view = RawView { rig: self, world: &self.world };
            let refitted = refreeze_view(&view, &mut frozen, |m| limits(&self.bones, m), &mut geometry);
            self.geometry = geometry;
            refitted?;
            return Ok(frozen);
        }
        freeze_view(&RawView { rig: self, world: &self.world }, &self.moving, |m| {
            limits(&self.bones, m).map(|l| (Some(l), 0.0))
        })
    }

    /// The kept frozen skeleton refitted at the pose the last round made.
    fn refreeze_solved(&mut self, frozen: &mut Frozen) -> Result<(), TogetherError> {
        let limits =
            |bones: &[SpineBone], m: usize| bones[m].limits_deg.map(|[lo, hi]| [lo.to_radians(), hi.to_radians()]);
        let mut geometry = std::mem::take(&mut self.geometry);
        let view = RawView { rig: self, world: &self.solved };
        let refitted = refreeze_view(&view, frozen, |m| limits(&self.bones, m), &mut geometry);
        self.geometry = geometry;
        refitted
    }

    /// Starts the solve from the answer of the solve before when it moved the same bones: each
    /// skeleton angle turned by what that answer's local rotation differs from the runtime's
    /// (within the bone's limits), so that a redundant limb does not jump between answers
    /// frame to frame; otherwise from the runtime's pose, as frozen.
    fn warm_start(&self, frozen: &mut Frozen) {
        if self.last_moved != self.moving {
            return;
        }
        for (k, &m) in self.moving.iter().enumerate() {
            let (now, last) = (self.local[m].rotation, self.last[k]);
            let (now, last) = match self.bones[m].limits_deg {
                Some([lo, hi]) => {
                    (now.clamp(lo.to_radians(), hi.to_radians()), last.clamp(lo.to_radians(), hi.to_radians()))
                }
                None => (now, last),
            };
            frozen.start[k] += wrap_angle(last - now);
        }
    }

    /// Checks the frame and reads its numbers into the world and local transforms.
    fn read(&mut self, frame: &SpineFrame, rotations: &[f64]) -> Result<(), TogetherError> {
        let n = self.bones.len();
        if frame.numbers.len() != n * SPINE_BONE_NUMBERS {
            return Err(TogetherError::Rule(format!(
                "numbers: must be {} ({SPINE_BONE_NUMBERS} per bone), got {}",
                n * SPINE_BONE_NUMBERS,
                frame.numbers.len()
            )));
        }
        if rotations.len() != n {
            return Err(TogetherError::Rule(format!("rotations: must be {n} (one per bone), got {}", rotations.len())));
        }
        for g in frame.goals {
            let b = g.goal.bone;
            let depth = self.depths.get(b).ok_or_else(|| TogetherError::Rule(format!("goal: no bone {b}")))? + 1;
            if g.bones < 1 || g.bones > depth {
                return Err(TogetherError::Rule(format!(
                    "goal on bone {b}: bones must be from 1 to {depth} (up to its root), got {}",
                    g.bones
                )));
            }
        }
        if let Some(&p) = frame.pins.iter().find(|&&p| p >= n) {
            return Err(TogetherError::Rule(format!("pin: no bone {p}")));
        }
        // A skeleton scaled unevenly stretches each bone by its direction, which the frozen
        // skeleton's rigid bones do not follow: the rounds then settle tens of units off the
        // goal. Refused rather than answered wrong.
        let [sx, sy] = frame.placement.scale;
        if (sx.abs() - sy.abs()).abs() > 1e-9 * sx.abs().max(sy.abs()) {
            return Err(TogetherError::Rule(format!(
                "skeleton scale: must be even (|scaleX| = |scaleY|, either may be negative), got scaleX {sx}, scaleY {sy}"
            )));
        }
        for (i, v) in frame.numbers.chunks_exact(SPINE_BONE_NUMBERS).enumerate() {
            if let Some((k, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                let field = SPINE_BONE_FIELDS[k];
                return Err(TogetherError::Rule(format!("frame[{i}].{field}: must be finite, got {x}")));
            }
            self.world[i] = Affine { a: v[0], b: v[1], c: v[2], d: v[3], x: v[4], y: v[5] };
            self.local[i] = LocalTransform {
                x: v[6],
                y: v[7],
                rotation: v[8].to_radians(),
                scale_x: v[9],
                scale_y: v[10],
                shear_x: v[11].to_radians(),
                shear_y: v[12].to_radians(),
            };
        }
        Ok(())
    }

    /// The goals and pins on the frozen skeleton's bones into the kept task: a later goal on a
    /// bone replaces an earlier one, a pin wins over a goal on its bone.
    fn fill_task(&mut self, frozen: &Frozen, frame: &SpineFrame) {
        let index = |b: usize| frozen.bones.binary_search(&b).ok();
        self.task.goals.clear();
        self.task.pins.clear();
        for &p in frame.pins {
            if let Some(i) = index(p) {
                self.task.pins.push(Pin::new(i));
            }
        }
        for g in frame.goals {
            let Some(i) = index(g.goal.bone) else { continue };
            if frame.pins.contains(&g.goal.bone) {
                continue;
            }
            self.task.goals.retain(|o| o.bone != i);
            let mut goal = g.goal.clone();
            goal.bone = i;
            if frozen.skeleton.parent(i).is_none() {
                goal.bend = None;
            }
            self.task.goals.push(goal);
        }
    }

    /// The solved directions written back as local rotations (within the bones' limits),
    /// parents first; `solved` gets the moved bones' new world transforms. Returns how far the
    /// moved bones' tips in that pose are from the frozen skeleton's solved ones.
    fn thaw(&mut self, frozen: &Frozen, angles: &[f64], placement: Placement) -> f64 {
        let n = frozen.bones.len();
        self.points.resize(n + 1, nalgebra::Point2::origin());
        self.directions.resize(n, 0.0);
        frozen.skeleton.points_into(angles, &mut self.points, &mut self.directions);
        let mut drift: f64 = 0.0;
        for (k, &m) in frozen.bones.iter().enumerate() {
            let parent = self.bones[m].parent.map(|p| self.parent_world(p));
            let inherit = self.bones[m].inherit;
            let mut r = rotation_toward(&self.local[m], inherit, parent.as_ref(), placement, self.directions[k]);
            if let Some([lo, hi]) = self.bones[m].limits_deg {
                r = r.clamp(lo.to_radians(), hi.to_radians());
            }
            self.local[m].rotation = r;
            let w = world_transform(&self.local[m], inherit, parent.as_ref(), placement);
            let l = self.bones[m].length;
            let p = self.points[k + 1];
            drift = drift.max(math::distance(w.x + w.a * l - p.x, w.y + w.c * l - p.y));
            self.solved[m] = w;
        }
        drift
    }

    /// Bone `p`'s world transform after the moved bones above it turned: its solved one if it
    /// moved, else its own carried rigidly by its nearest moved ancestor (unchanged without one).
    fn parent_world(&self, p: usize) -> Affine {
        if self.on[p] {
            return self.solved[p];
        }
        let mut up = self.bones[p].parent;
        while let Some(q) = up {
            if self.on[q] {
                return match relative(&self.world[q], &self.world[p]) {
                    Some(r) => self.solved[q].times(&r),
                    None => self.world[p],
                };
            }
            up = self.bones[q].parent;
        }
        self.world[p]
    }
}

/// The local rotation that points a bone's world x axis along `direction`: in closed form
/// where its frame is a fixed matrix ([`aim_frame`]: the normal, onlyTranslation and
/// noRotationOrReflection modes; a root under the placement), by [`rotation_for`]'s Newton
/// steps for the noScale modes (or a singular frame). The nearest to its current rotation.
fn rotation_toward(
    local: &LocalTransform,
    inherit: Inherit,
    parent: Option<&Affine>,
    placement: Placement,
    direction: f64,
) -> f64 {
    let (frame, theta) = match (parent, inherit) {
        (None, _) => (Affine::of_placement(placement), 0.0),
        (Some(p), Inherit::Normal | Inherit::OnlyTranslation | Inherit::NoRotationOrReflection) => {
            aim_frame(inherit, p, placement)
        }
        (Some(_), Inherit::NoScale | Inherit::NoScaleOrReflection) => {
            return rotation_for(local, inherit, parent, placement, direction);
        }
    };
    // The world x axis is `frame · (cos(r + shx − θ), sin(r + shx − θ)) · scaleX`.
    let (s, c) = math::sin_cos(direction);
    let Some([u, v]) = Affine { x: 0.0, y: 0.0, ..frame }.to_local(c, s) else {
        return rotation_for(local, inherit, parent, placement, direction);
    };
    let mut r = math::atan2(v, u) + theta - local.shear_x;
    if local.scale_x < 0.0 {
        r += std::f64::consts::PI;
    }
    local.rotation + wrap_angle(r - local.rotation)
}

/// `p` in `q`'s frame: `q⁻¹ · p`, `None` when `q` is singular.
fn relative(q: &Affine, p: &Affine) -> Option<Affine> {
    let [x, y] = q.to_local(p.x, p.y)?;
    let [a, c] = q.to_local(q.x + p.a, q.y + p.c)?;
    let [b, d] = q.to_local(q.x + p.b, q.y + p.d)?;
    Some(Affine { a, b, c, d, x, y })
}

/// A rig's frame as a [`PoseView`].
struct RawView<'a> {
    rig: &'a SpineRig,
    /// The bones' world transforms: the frame's, or those of the pose a round made.
    world: &'a [Affine],
}

impl PoseView for RawView<'_> {
    fn parent(&self, i: usize) -> Option<usize> {
        self.rig.bones[i].parent
    }
    fn origin(&self, i: usize) -> [f64; 2] {
        [self.world[i].x, self.world[i].y]
    }
    fn rotation(&self, i: usize) -> f64 {
        self.world[i].rotation()
    }
    fn tip(&self, i: usize) -> [f64; 2] {
        let w = &self.world[i];
        let l = self.rig.bones[i].length;
        [w.x + w.a * l, w.y + w.c * l]
    }
    fn local_rotation(&self, i: usize) -> f64 {
        self.rig.local[i].rotation
    }
    fn name(&self, i: usize) -> String {
        i.to_string()
    }
}
