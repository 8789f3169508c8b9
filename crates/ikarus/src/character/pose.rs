//! Posing a character as its runtime does: the setup pose, then a clip at a time, then the
//! targets moved, then the constraints of every kind one after another in their order.

use super::ik;
use super::path;
use super::path::apply::PathPose;
use super::timeline;
use super::timeline::Reader;
use super::transform::{self, TransformSettings};
use super::world::{Affine, BoneTrig, Bones, Trig};
use super::{
    Character, Constraint, ConstraintKeys, IkBones, IkRule, IkSettings, LocalTransform, PhysicsInput, PhysicsMode,
    PhysicsState, PhysicsWorld, Placement, Settings,
};
use crate::Interrupt;

/// What to pose: a clip at a time (seconds), bones whose world origin is put at a point after
/// the clip and before the constraints, and constraints' bend sides.
#[derive(Debug, Clone, Copy, Default)]
pub struct PoseRequest<'a> {
    /// The clip's index and the time in it (before its first key a timeline leaves the setup
    /// pose; after its last key it holds the last key's value).
    pub clip: Option<(usize, f64)>,
    /// `(bone, [x, y])`: the bone's world origin goes to `(x, y)` (its local x and y are set
    /// from its parent's world transform after the clip), in this order.
    pub targets: &'a [(usize, [f64; 2])],
    /// `(constraint, bend_positive)`: the constraint's `bendPositive` in place of what the clip
    /// (or the setup pose) gives it, as a key of its IK timeline would set it.
    pub bends: &'a [(usize, bool)],
    /// `(bone, rotation)`: the bone's local rotation (radians, in its parent's frame, as the
    /// setup pose's) in place of what the clip (or the setup pose) gives it, before the targets
    /// and the constraints, as a rotate key of the clip would set it: a bone turned by hand.
    pub turns: &'a [(usize, f64)],
    /// The skin (its index in [`Character::skins`]) whose skin-required bones and constraints
    /// take part; `None`: no skin, so only those not skin-required do (the edge asks for
    /// [`Character::default_skin`] unless told otherwise; see [`Skin`](super::Skin)).
    pub skin: Option<usize>,
}

/// A posed character: every bone's local transform as posing left it and its world transform.
/// Reuse one across poses: once its buffers have grown to the character's size, posing
/// allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct Posed {
    local: Vec<LocalTransform>,
    world: Vec<Affine>,
    length: Vec<f64>,
    below: Vec<bool>,
    settings: Vec<Settings>,
    /// Per bone, the sines and cosines its world transform last needed (kept across poses).
    trig: Vec<BoneTrig>,
    /// Which bones and constraints the skin turns on.
    active: super::skin::Active,
    /// Per timeline of the clip last posed (bone timelines first), the number of keys at or
    /// before the time last asked: where the next time's key is looked for first.
    keys: Vec<u32>,
    /// The path constraints' deform offsets and buffers.
    path: PathPose,
    /// Per constraint, its physics simulation (kept from frame to frame of a play).
    pub(crate) physics: Vec<PhysicsState>,
    /// Per constraint, whether a `reset` key of the clip was passed in this frame.
    restart: Vec<bool>,
}

/// What posing keeps per constraint and per bone besides the bones, borrowed beside them.
struct Scratch<'a> {
    physics: &'a mut [PhysicsState],
    restart: &'a [bool],
    path: &'a mut PathPose,
    active: &'a super::skin::Active,
}

/// How a pose treats the physics constraints: left out (Spine's `Physics.none`: the bones stay
/// as posed), or as one frame of a play ([`Character::play`]).
#[derive(Debug, Clone, Copy)]
pub(crate) enum Frame {
    /// Physics constraints do nothing.
    Still,
    /// A frame of a play: the simulation restarts (`Reset`) or steps (`Update`) to `clock`;
    /// `reset` keys after `from` and up to the clip's time restart their constraints.
    Play {
        /// Restart or step.
        mode: PhysicsMode,
        /// The skeleton's clock, seconds.
        clock: f64,
        /// The clip time of the frame before.
        from: f64,
        /// Wind, gravity and reference scale.
        world: PhysicsWorld,
    },
}

impl Posed {
    /// How many bones.
    pub fn len(&self) -> usize {
        self.world.len()
    }

    /// Whether there are no bones (before the first pose).
    pub fn is_empty(&self) -> bool {
        self.world.is_empty()
    }

    /// Whether bone `i` took part in the pose (see [`Skin`](super::Skin)): an inactive bone is not
    /// posed, its world transform all zeros. Panics if `i` is not a bone.
    pub fn is_active(&self, i: usize) -> bool {
        self.active.bones[i]
    }

    /// Which bones and constraints the last pose's skin turned on.
    pub(crate) fn activity(&self) -> &super::skin::Active {
        &self.active
    }

    /// Bone `i`'s world origin. Panics if `i` is not a bone.
    pub fn origin(&self, i: usize) -> [f64; 2] {
        [self.world[i].x, self.world[i].y]
    }

    /// The world direction of bone `i`'s x axis, radians in `[−π, π]`: `atan2(c, a)`.
    pub fn rotation(&self, i: usize) -> f64 {
        self.world[i].rotation()
    }

    /// Bone `i`'s tip: its origin plus its length along its world x axis, `(x + a·l, y + c·l)`.
    pub fn tip(&self, i: usize) -> [f64; 2] {
        let w = &self.world[i];
        [w.x + w.a * self.length[i], w.y + w.c * self.length[i]]
    }

    /// Bone `i`'s world matrix `[a, b, c, d]` (rows `[a, b]`, `[c, d]`).
    pub fn matrix(&self, i: usize) -> [f64; 4] {
        let w = &self.world[i];
        [w.a, w.b, w.c, w.d]
    }

    /// Bone `i`'s whole world transform.
    pub fn world(&self, i: usize) -> Affine {
        self.world[i]
    }

    /// Bone `i`'s local transform as posing left it (the clip's, the target's, the
    /// constraints').
    pub fn local(&self, i: usize) -> LocalTransform {
        self.local[i]
    }

    /// Constraint `k`'s settings as the clip left them.
    pub fn settings(&self, k: usize) -> Settings {
        self.settings[k]
    }

    /// Constraint `k`'s settings as the clip left them, if it is an IK constraint.
    pub fn ik_settings(&self, k: usize) -> Option<IkSettings> {
        self.settings.get(k).and_then(Settings::ik).copied()
    }

    /// The bones of `c` as posing left them, to change their local transforms (and the world
    /// transforms below), their lengths, and the constraints' settings.
    pub(crate) fn bones<'a>(&'a mut self, c: &'a Character) -> (Bones<'a>, &'a [f64], &'a [Settings]) {
        let (bones, length, settings, _) = self.parts(c, c.placement);
        (bones, length, settings)
    }

    /// [`Posed::bones`] (the skeleton placed at `placement`) and what posing keeps besides the
    /// bones, borrowed side by side.
    fn parts<'a>(
        &'a mut self,
        c: &'a Character,
        placement: Placement,
    ) -> (Bones<'a>, &'a [f64], &'a [Settings], Scratch<'a>) {
        let bones = Bones {
            bones: &c.bones,
            links: &c.flat.links,
            placement,
            local: &mut self.local,
            world: &mut self.world,
            below: &mut self.below,
            trig: &mut self.trig,
        };
        let scratch =
            Scratch { physics: &mut self.physics, restart: &self.restart, path: &mut self.path, active: &self.active };
        (bones, &self.length, &self.settings, scratch)
    }
}

impl Character {
    /// Poses the character into `out`: every bone reset to its setup pose and every
    /// constraint to its setup settings; the clip's timelines applied at the time, then the
    /// turns and bends asked for; the world
    /// transforms computed; each target's bone moved (its local x, y set so that its world
    /// origin is the point, given its parent's world transform then); then the constraints in
    /// increasing `order` (ties in the order listed), each seeing the world transforms as
    /// updated so far and followed by an update of the bones below its bones, so that a later
    /// constraint can undo what an earlier one did, as in the runtime.
    pub fn pose(&self, request: &PoseRequest, out: &mut Posed) -> Result<(), PoseError> {
        self.pose_frame(request, out, None, (Frame::Still, &[]))
    }

    /// [`Character::pose`], stopped with [`PoseError::Interrupted`] once `interrupt` is set: it
    /// is checked before each constraint (a character's constraints are most of a pose's work;
    /// each costs at most its bones' subtree), so a server's deadline or a Ctrl-C ends even a
    /// pose of a hostile character soon.
    pub fn pose_watched(&self, request: &PoseRequest, out: &mut Posed, interrupt: &Interrupt) -> Result<(), PoseError> {
        self.pose_frame(request, out, Some(interrupt), (Frame::Still, &[]))
    }

    /// [`Character::pose`] watching `interrupt` when there is one, the IK constraints `off` left
    /// out (at mix 0, whatever the clip keys; their other settings as the clip has them), the
    /// physics constraints treated as `frame` says.
    pub(crate) fn pose_frame(
        &self,
        request: &PoseRequest,
        out: &mut Posed,
        interrupt: Option<&Interrupt>,
        (frame, off): (Frame, &[usize]),
    ) -> Result<(), PoseError> {
        self.sample_frame(request, out, frame)?;
        for &k in off {
            if let Some(Settings::Ik(s)) = out.settings.get_mut(k) {
                s.mix = 0.0;
            }
        }
        self.constrain(request, out, interrupt, frame, self.placement)
    }

    /// Sizes `out`'s buffers for a pose with `skin` and finds what the skin turns on; the local
    /// transforms, the settings and the paths' deforms are left to the caller.
    fn begin(&self, out: &mut Posed, skin: Option<usize>) {
        let n = self.bones.len();
        out.length.clear();
        out.length.extend_from_slice(&self.flat.length);
        out.world.resize(n, Affine::default());
        out.below.resize(n, false);
        out.trig.resize(n, [Trig::ZERO; 3]);
        // What only physics constraints read, kept only for characters that have them.
        if self.kinds.physics {
            out.physics.resize(self.constraints.len(), PhysicsState::default());
            out.restart.clear();
            out.restart.resize(self.constraints.len(), false);
        }
        self.activity.compute(&self.bones, skin.map(|s| &self.skins[s]), &mut out.active);
    }

    /// The first half of [`Character::pose_frame`]: the setup pose, the clip at its time, the
    /// turns and the bends, into `out`'s local transforms and settings (no world transform).
    fn sample_frame(&self, request: &PoseRequest, out: &mut Posed, frame: Frame) -> Result<(), PoseError> {
        self.check(request)?;
        out.local.clear();
        out.local.extend_from_slice(&self.flat.setup);
        out.settings.clear();
        out.settings.extend_from_slice(&self.setup);
        // What only path constraints read, kept only for characters that have them.
        if self.kinds.path {
            out.path.reset(self.constraints.len());
        }
        self.begin(out, request.skin);
        if let Some(&(bone, _)) = request.targets.iter().find(|(b, _)| !out.active.bones[*b]) {
            return Err(PoseError::InactiveTarget(bone));
        }

        if let Some((c, time)) = request.clip {
            let clip = &self.clips[c];
            let curves = self.curves.clip(c);
            out.keys.resize(clip.bones.len() + clip.constraints.len(), 0);
            let (bone_keys, ik_keys) = out.keys.split_at_mut(clip.bones.len());
            for (k, (t, last)) in clip.bones.iter().zip(bone_keys).enumerate() {
                let mut r = Reader::new(curves, k, last);
                timeline::apply_bone_at(&mut r, t, &self.bones[t.bone].setup, &mut out.local[t.bone], time);
            }
            for (k, (t, last)) in clip.constraints.iter().zip(ik_keys).enumerate() {
                let mut r = Reader::new(curves, clip.bones.len() + k, last);
                match &t.keys {
                    ConstraintKeys::Ik(keys) => {
                        if let Some(s) = timeline::ik_settings_at(&mut r, keys, time) {
                            out.settings[t.constraint] = Settings::Ik(s);
                        }
                    }
                    ConstraintKeys::PathDeform { skin, keys } => {
                        let k = t.constraint;
                        let Constraint::Path(c) = &self.constraints[k] else { continue };
                        // Only the attachment the skin shows is deformed.
                        if c.path_source(request.skin) != *skin {
                            continue;
                        }
                        // Room for every coordinate at once, so that later times allocate nothing.
                        out.path.deform[k].reserve(c.path_for(request.skin).map_or(0, |p| p.vertices.deform_len()));
                        out.path.deformed[k] = path::deform::at(keys, time, &mut out.path.deform[k]);
                    }
                    keys @ (ConstraintKeys::PathPosition(v)
                    | ConstraintKeys::PathSpacing(v)
                    | ConstraintKeys::PathMix(v)) => {
                        let Some(x) = timeline::channels_at(&mut r, v, keys.channels(), time) else { continue };
                        if let Settings::Path(s) = &mut out.settings[t.constraint] {
                            match keys {
                                ConstraintKeys::PathPosition(_) => s.position = x[0],
                                ConstraintKeys::PathSpacing(_) => s.spacing = x[0],
                                _ => [s.mix_rotate, s.mix_x, s.mix_y] = [x[0], x[1], x[2]],
                            }
                        }
                    }
                    ConstraintKeys::Physics { property, keys } => {
                        let value = timeline::channels_at(&mut r, keys, 1, time);
                        if let (Some(v), Settings::Physics(s)) = (value, &mut out.settings[t.constraint]) {
                            property.set(s, v[0]);
                        }
                    }
                    ConstraintKeys::PhysicsReset(keys) => {
                        if let Frame::Play { from, .. } = frame {
                            let passed =
                                keys.iter().any(|k| from < timeline::f32ed(k.time) && timeline::f32ed(k.time) <= time);
                            out.restart[t.constraint] |= passed;
                        }
                    }
                    ConstraintKeys::Transform(keys) => {
                        if let Some(v) = timeline::channels_at(&mut r, keys, 6, time) {
                            out.settings[t.constraint] = Settings::Transform(TransformSettings::from_values(&v));
                        }
                    }
                }
            }
        }
        for &(bone, rotation) in request.turns {
            out.local[bone].rotation = rotation;
        }
        for &(k, bend_positive) in request.bends {
            if let Settings::Ik(s) = &mut out.settings[k] {
                s.bend_positive = bend_positive;
            }
        }
        Ok(())
    }

    /// The targets and the constraints of [`Character::pose_frame`], after the clip, the
    /// skeleton placed at `placement`.
    fn constrain(
        &self,
        request: &PoseRequest,
        out: &mut Posed,
        interrupt: Option<&Interrupt>,
        frame: Frame,
        placement: Placement,
    ) -> Result<(), PoseError> {
        let (mut bones, length, settings, Scratch { physics, restart, path: path_pose, active }) =
            out.parts(self, placement);
        if request.targets.is_empty() {
            bones.update_all_but(&self.deferred);
        } else {
            bones.update_all();
        }
        for &(bone, [x, y]) in request.targets {
            let [lx, ly] = bones.parent_world(bone).to_local(x, y).ok_or(PoseError::SingularParent(bone))?;
            bones.local[bone].x = lx;
            bones.local[bone].y = ly;
            bones.update_below(bone);
        }
        let skins_matter = self.activity.any;
        for &k in &self.order {
            if crate::interrupt::is_set(interrupt) {
                return Err(PoseError::Interrupted);
            }
            if skins_matter && !self.is_active(k, active) {
                // It does nothing, but the bones the first pass left to its update are computed.
                bones.update_subtree(self.flat.below(k));
                continue;
            }
            match &self.constraints[k] {
                Constraint::Ik(c) => {
                    let Settings::Ik(s) = &settings[k] else { continue };
                    let target = bones.world[c.target].origin();
                    match (c.bones, c.rule) {
                        (IkBones::One(b), _) => {
                            let s = if c.rule == IkRule::Spine {
                                *s
                            } else {
                                IkSettings { compress: false, stretch: false, ..*s }
                            };
                            ik::spine_one(&mut bones, b, target, &s, c.uniform);
                        }
                        (IkBones::Two { parent, child }, IkRule::Spine) => {
                            ik::spine_two(&mut bones, (parent, child), target, s, c.uniform);
                        }
                        (IkBones::Two { parent, child }, IkRule::DragonBones) => {
                            ik::dragonbones_two(&mut bones, (parent, child), self.flat.below(k), target, s);
                        }
                    }
                }
                Constraint::Transform(c) => {
                    let Settings::Transform(s) = &settings[k] else { continue };
                    transform::apply(&mut bones, c, s);
                }
                Constraint::Path(c) => {
                    let Settings::Path(s) = &settings[k] else { continue };
                    path::apply::apply(&mut bones, (k, c, request.skin), s, path_pose);
                }
                Constraint::Physics(c) => {
                    let (Settings::Physics(s), Frame::Play { mode, clock, world, .. }) = (&settings[k], frame) else {
                        bones.update_subtree(self.flat.below(k));
                        continue;
                    };
                    let mode = if restart[k] { PhysicsMode::Reset } else { mode };
                    let input =
                        PhysicsInput { constraint: c, settings: *s, world, time: clock, length: length[c.bone] };
                    let mut w = bones.world[c.bone];
                    physics[k].apply(&input, mode, &mut w);
                    bones.set_world(c.bone, w);
                }
            }
            bones.update_subtree(self.flat.below(k));
        }
        if self.activity.any {
            // The runtime leaves an inactive bone unposed, at zeros.
            let zero = Affine { a: 0.0, b: 0.0, c: 0.0, d: 0.0, x: 0.0, y: 0.0 };
            for (w, _) in bones.world.iter_mut().zip(&active.bones).filter(|(_, on)| !**on) {
                *w = zero;
            }
        }
        Ok(())
    }

    /// Whether constraint `k` takes part in a pose whose skin turned on `active`: the skin turns
    /// it on and its target and bones are active (see [`super::skin`]).
    pub(crate) fn is_active(&self, k: usize, active: &super::skin::Active) -> bool {
        if !self.activity.any {
            return true;
        }
        let on = |b: usize| active.bones[b];
        active.constraints[k]
            && match &self.constraints[k] {
                Constraint::Ik(c) => {
                    on(c.target)
                        && match c.bones {
                            IkBones::One(b) => on(b),
                            IkBones::Two { parent, child } => on(parent) && on(child),
                        }
                }
                Constraint::Transform(c) => on(c.target) && c.bones.iter().all(|&b| on(b)),
                Constraint::Path(c) => on(c.slot_bone) && c.bones.iter().all(|&b| on(b)),
                Constraint::Physics(c) => on(c.bone),
            }
    }
}

#[path = "given.rs"]
mod given;
pub use given::GivenPose;

#[path = "pose_error.rs"]
mod pose_error;
pub use pose_error::PoseError;

#[cfg(test)]
#[path = "pose_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "deferred_tests.rs"]
mod deferred_tests;

#[cfg(test)]
#[path = "watch_tests.rs"]
mod watch_tests;
