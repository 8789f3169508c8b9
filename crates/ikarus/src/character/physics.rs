//! Spine 4.2's physics constraints: a bone that swings, lags and settles as a damped spring
//! under inertia, wind and gravity, stepped at a fixed rate.
//!
//! The JSON export format gives the fields and defaults; the user guide says what they do. The
//! rules below were inferred from Spine's runtime output (spine-core 4.2.119 posing
//! celestial-circus, `reference/full/`), not from its code; each is marked with how well the
//! vectors pin it.
//!
//! - **Time** (exact). The skeleton keeps a clock (`update(dt)` adds `dt`). At each pose with
//!   physics the constraint adds the clock's advance since its last pose to a remainder and takes
//!   as many steps of `1 / fps` as the remainder holds (`remainder −= step` per step, in `f64`):
//!   a clock advanced by `1/60` at 60 steps a second sometimes takes 0 steps, then 2.
//! - **Translation** (`x`, `y`; exact). The constraint remembers the bone's world origin `u`. When
//!   the bone has moved by `δ` since, its offset `o` loses `δ·inertia`, each axis cut to
//!   `±limit·step` (the simulated point stays behind by that share of the move), and `u` becomes
//!   the new origin. Each step, per axis: `v += (f − o·strength)·massInverse·step`, `o += v·step`,
//!   `v *= damping`, with the force `f = (wind·windDir + gravity·gravityDir)·referenceScale`
//!   (wind along +x, reference scale 100: exact; gravity's direction, down, is not in the
//!   vectors). The bone's world origin then moves by `o·mix·(x, y)`.
//! - **Rotation** (`rotate`, `shearX`; exact). The constraint remembers where
//!   the bone's tip was drawn (`p`) and its origin after the translation (`q`). A move of the
//!   origin beyond `±limit·step` per axis drags `p` along by the excess. The angle from the
//!   bone's direction `θ`, turned by the share of the offset the bone shows (`r·mix·(rotate +
//!   shearX)`), to `p` seen from the new origin adds `angle·inertia` to the rotation offset `r`.
//!   Each step: `ω += (τ − r·strength)·massInverse·step`, `r += ω·step`, `ω *= damping`, with the
//!   torque `τ = (f ⟂ the shown direction)·length / referenceScale²` (the bone's own length,
//!   unscaled: a world-scaled length leaves celestial-circus's wing tips 0.4° off). The x axis turns
//!   by `r·mix·(rotate + shearX)`, the y axis by `r·mix·rotate`.
//! - **Scale** (`scaleX`; exact). The origin's move (within the limit, per axis) along the
//!   bone's direction turned by the new `r·mix·(rotate + shearX)`, over the bone's world length,
//!   times `inertia`, is taken from the scale offset `s` (a bone pulled along its length
//!   stretches behind). Each step the spring above with the pull `(f · the shown direction) /
//!   referenceScale`. The x axis is scaled by `1 + s·mix·scaleX`.
//! - The powers of `referenceScale` (the file's, [`super::Character::reference_scale`]) are
//!   what the runtime API reference's words require: it is the "baseline scale factor for
//!   applying physics and other effects based on distance to non-scalable properties, such as
//!   angle or scale", so a skeleton drawn `k` times as large with `k` times the reference scale
//!   must move the same, `k` times as large: forces give distances (× `referenceScale`), the
//!   torque is an angle (÷ `referenceScale²` with the length), the pull a scale (÷
//!   `referenceScale`). `tests/rules_physics.rs` in ikarus-edge checks it; the vectors have
//!   only the default 100.
//! - **Reset** (`Physics.reset`, a clip's `reset` key): offsets and velocities to 0, the
//!   remembered points to the bone's as posed, the remainder to 0.
//! - **None** (`Physics.none`): the bone is left as posed.

use super::world::Affine;
use crate::math;
use std::f64::consts::PI;

/// A physics constraint as the file gives it (Spine's `PhysicsConstraintData`).
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicsConstraint {
    /// Its name in the file (`name`).
    pub name: String,
    /// Where it stands in the update order among every constraint (`order`, default 0).
    pub order: u32,
    /// Whether it belongs to a skin, active only while that skin is set (`skin`, default false).
    pub skin: bool,
    /// The bone it moves (`bone`), an index.
    pub bone: usize,
    /// How much of the simulated offset each property shows, 0 to 1 (default 0 each).
    pub shares: PhysicsShares,
    /// The bone's largest speed the simulation follows, per world axis, units a second (`limit`,
    /// default 5000).
    pub limit: f64,
    /// Steps a second (`fps`, default 60); the step is `1 / fps` seconds.
    pub fps: f64,
    /// The settings before any clip keys them.
    pub setup: PhysicsSettings,
    /// Which settings a clip's timelines for every constraint (`""`) key (the `…Global` flags).
    pub global: PhysicsGlobal,
}

/// How much of the simulated offset each property of the bone shows (Spine's `x`, `y`,
/// `rotate`, `scaleX`, `shearX`; 0 to 1, default 0: not simulated).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PhysicsShares {
    /// World x of the origin (`x`).
    pub x: f64,
    /// World y of the origin (`y`).
    pub y: f64,
    /// Rotation of both axes (`rotate`).
    pub rotate: f64,
    /// Scale along the x axis (`scaleX`).
    pub scale_x: f64,
    /// Rotation of the x axis alone (`shearX`).
    pub shear_x: f64,
}

/// The settings a clip can key (Spine's physics timelines).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicsSettings {
    /// How much of the bone's movement becomes simulated movement, 0 to 1 (`inertia`, default 1).
    pub inertia: f64,
    /// The spring's stiffness pulling the offsets back to 0 (`strength`, default 100).
    pub strength: f64,
    /// The velocities' factor per step, 0 to 1 (`damping`, default 1: none lost).
    pub damping: f64,
    /// `1 / mass` (`mass`, default 1, stored inverted as the runtime does).
    pub mass_inverse: f64,
    /// Force along the skeleton's wind direction (`wind`, default 0).
    pub wind: f64,
    /// Force along the skeleton's gravity direction (`gravity`, default 0).
    pub gravity: f64,
    /// How much of the simulation the bone shows, 0 to 1 (`mix`, default 1).
    pub mix: f64,
}

impl Default for PhysicsSettings {
    fn default() -> Self {
        PhysicsSettings {
            inertia: 1.0,
            strength: 100.0,
            damping: 1.0,
            mass_inverse: 1.0,
            wind: 0.0,
            gravity: 0.0,
            mix: 1.0,
        }
    }
}

/// Which settings follow the timelines keyed for every constraint at once (the file's
/// `inertiaGlobal`, `strengthGlobal`, … flags, default false).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PhysicsGlobal {
    /// `inertiaGlobal`.
    pub inertia: bool,
    /// `strengthGlobal`.
    pub strength: bool,
    /// `dampingGlobal`.
    pub damping: bool,
    /// `massGlobal`.
    pub mass: bool,
    /// `windGlobal`.
    pub wind: bool,
    /// `gravityGlobal`.
    pub gravity: bool,
    /// `mixGlobal`.
    pub mix: bool,
}

/// The skeleton's side of the simulation: the directions wind and gravity push along and the
/// scale forces are given in (Spine's `windX`, `windY` (1, 0), `gravityX`, `gravityY` (0, 1),
/// `referenceScale` (100) times the skeleton's scale).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicsWorld {
    /// The wind's direction.
    pub wind: [f64; 2],
    /// The gravity's direction.
    pub gravity: [f64; 2],
    /// Units per unit of force (`referenceScale`, default 100).
    pub reference_scale: f64,
}

impl Default for PhysicsWorld {
    fn default() -> Self {
        PhysicsWorld { wind: [1.0, 0.0], gravity: [0.0, -1.0], reference_scale: 100.0 }
    }
}

/// What a pose does with the physics constraints (Spine's `Physics`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhysicsMode {
    /// The bones are left as posed (`Physics.none`).
    None,
    /// The simulation restarts from the pose (`Physics.reset`).
    Reset,
    /// The simulation steps by the clock's advance (`Physics.update`).
    Update,
}

/// One constraint's simulation, carried from pose to pose.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PhysicsState {
    /// The clock at the last pose.
    last_time: f64,
    /// Seconds not yet stepped.
    remaining: f64,
    /// The bone's world origin at the last pose.
    u: [f64; 2],
    /// The translation offset and its velocity.
    offset: [f64; 2],
    velocity: [f64; 2],
    /// The tip as drawn at the last pose, and the bone's origin as posed before the constraint.
    tip: [f64; 2],
    origin: [f64; 2],
    /// The rotation offset (radians) and its velocity.
    rotate: f64,
    rotate_velocity: f64,
    /// The scale offset and its velocity.
    scale: f64,
    scale_velocity: f64,
}

/// What a constraint is applied with: its data, its settings now, the skeleton's side and the
/// clock.
#[derive(Debug, Clone, Copy)]
pub struct PhysicsInput<'a> {
    /// The constraint.
    pub constraint: &'a PhysicsConstraint,
    /// Its settings as the clip left them.
    pub settings: PhysicsSettings,
    /// The skeleton's wind, gravity and reference scale.
    pub world: PhysicsWorld,
    /// The skeleton's clock, seconds.
    pub time: f64,
    /// The bone's length.
    pub length: f64,
}

/// `x` wrapped to `[−π, π)`.
fn wrap(x: f64) -> f64 {
    x - 2.0 * PI * ((x + PI) / (2.0 * PI)).floor()
}

impl PhysicsState {
    /// Applies the constraint to its bone's world transform `bone` (as posed so far), in
    /// `mode`; the caller recomputes the bone's applied local transform and its children after.
    /// The rules are in the module's doc.
    pub fn apply(&mut self, input: &PhysicsInput, mode: PhysicsMode, bone: &mut Affine) {
        match mode {
            PhysicsMode::None => {}
            PhysicsMode::Reset => self.reset(input, bone),
            PhysicsMode::Update => self.update(input, bone),
        }
    }

    /// Restarts from `bone` as posed: nothing moves.
    fn reset(&mut self, input: &PhysicsInput, bone: &Affine) {
        *self = PhysicsState {
            last_time: input.time,
            u: [bone.x, bone.y],
            tip: [bone.x + input.length * bone.a, bone.y + input.length * bone.c],
            origin: [bone.x, bone.y],
            ..PhysicsState::default()
        };
    }

    fn update(&mut self, input: &PhysicsInput, bone: &mut Affine) {
        let c = input.constraint;
        let s = &input.settings;
        let sh = &c.shares;
        let step = 1.0 / c.fps;
        self.remaining += (input.time - self.last_time).max(0.0);
        self.last_time = input.time;
        // Bounded: a clock far ahead (or a tiny step) is stepped at most `MAX_STEPS` times and
        // the rest dropped.
        let mut steps = 0u32;
        while self.remaining >= step {
            self.remaining -= step;
            steps += 1;
            if steps >= MAX_STEPS {
                self.remaining = 0.0;
                break;
            }
        }
        let limit = c.limit * step;
        let w = input.world;
        let force = [
            (s.wind * w.wind[0] + s.gravity * w.gravity[0]) * w.reference_scale,
            (s.wind * w.wind[1] + s.gravity * w.gravity[1]) * w.reference_scale,
        ];
        if sh.x != 0.0 || sh.y != 0.0 {
            let d = [clamp((bone.x - self.u[0]) * s.inertia, limit), clamp((bone.y - self.u[1]) * s.inertia, limit)];
            self.offset = [self.offset[0] - d[0], self.offset[1] - d[1]];
            self.u = [bone.x, bone.y];
            for _ in 0..steps {
                for ((v, o), f) in self.velocity.iter_mut().zip(self.offset.iter_mut()).zip(force) {
                    *v += (f - *o * s.strength) * s.mass_inverse * step;
                    *o += *v * step;
                    *v *= s.damping;
                }
            }
            bone.x += self.offset[0] * s.mix * sh.x;
            bone.y += self.offset[1] * s.mix * sh.y;
        }
        if sh.rotate != 0.0 || sh.scale_x != 0.0 || sh.shear_x != 0.0 {
            self.turn(input, bone, Turn { steps, limit, force });
        }
        self.tip = [bone.x + input.length * bone.a, bone.y + input.length * bone.c];
    }

    /// The rotation, shear and scale part of [`PhysicsState::update`], on the bone as the
    /// translation part left it.
    fn turn(&mut self, input: &PhysicsInput, bone: &mut Affine, t: Turn) {
        let s = &input.settings;
        let sh = &input.constraint.shares;
        let step = 1.0 / input.constraint.fps;
        // A move faster than the limit (per axis) drags the remembered tip along with its excess.
        let d = [bone.x - self.origin[0], bone.y - self.origin[1]];
        let kept = [clamp(d[0], t.limit), clamp(d[1], t.limit)];
        self.tip = [self.tip[0] + d[0] - kept[0], self.tip[1] + d[1] - kept[1]];
        self.origin = [bone.x, bone.y];
        let to_tip = [self.tip[0] - bone.x, self.tip[1] - bone.y];
        let direction = bone.rotation();
        let length = input.length * math::hypot(bone.a, bone.c);
        let turned = s.mix * (sh.rotate + sh.shear_x);
        let scaled = s.mix * sh.scale_x;
        let angle = wrap(math::atan2(to_tip[1], to_tip[0]) - direction - self.rotate * turned);
        self.rotate += angle * s.inertia;
        if length > 0.0 {
            // The origin's move (within the limit) along the bone's new shown direction.
            let (sin, cos) = math::sin_cos(direction + self.rotate * turned);
            self.scale -= (kept[0] * cos + kept[1] * sin) / length * s.inertia;
        }
        let r2 = input.world.reference_scale;
        for _ in 0..t.steps {
            let (sin, cos) = math::sin_cos(direction + self.rotate * turned);
            let torque = (cos * t.force[1] - sin * t.force[0]) * input.length / (r2 * r2);
            self.rotate_velocity += (torque - self.rotate * s.strength) * s.mass_inverse * step;
            self.rotate += self.rotate_velocity * step;
            self.rotate_velocity *= s.damping;
            let pull = (cos * t.force[0] + sin * t.force[1]) / r2;
            self.scale_velocity += (pull - self.scale * s.strength) * s.mass_inverse * step;
            self.scale += self.scale_velocity * step;
            self.scale_velocity *= s.damping;
        }
        let r = self.rotate * s.mix * sh.rotate;
        let (sx, cx) = math::sin_cos(r + self.rotate * s.mix * sh.shear_x);
        let (sy, cy) = math::sin_cos(r);
        let k = 1.0 + self.scale * scaled;
        let (a, c) = (bone.a, bone.c);
        bone.a = (cx * a - sx * c) * k;
        bone.c = (sx * a + cx * c) * k;
        let (b, d) = (bone.b, bone.d);
        bone.b = cy * b - sy * d;
        bone.d = sy * b + cy * d;
    }
}

/// What the rotation part needs from the update: how many steps, the limit per step and the
/// force.
#[derive(Debug, Clone, Copy)]
struct Turn {
    steps: u32,
    limit: f64,
    force: [f64; 2],
}

/// `x` within `[−limit, limit]`.
fn clamp(x: f64, limit: f64) -> f64 {
    x.max(-limit).min(limit)
}

impl PhysicsConstraint {
    /// Checks it against the character's `bones` (constraint `k` of the list): its bone exists,
    /// `fps` and `mass` are positive, `limit` and `strength` not negative, every other number
    /// finite.
    pub(crate) fn check(&self, k: usize, bones: &[super::CharacterBone]) -> Result<(), super::CharacterError> {
        if self.bone >= bones.len() {
            return Err(super::CharacterError::PhysicsBone { constraint: k, bone: self.bone });
        }
        let (sh, s) = (&self.shares, &self.setup);
        let bad = |field: &'static str, value: f64| super::CharacterError::PhysicsValue { constraint: k, field, value };
        for (field, value, ok) in [
            ("fps", self.fps, self.fps > 0.0),
            ("mass", 1.0 / s.mass_inverse, s.mass_inverse > 0.0),
            ("limit", self.limit, self.limit >= 0.0),
            ("strength", s.strength, s.strength >= 0.0),
            ("x", sh.x, true),
            ("y", sh.y, true),
            ("rotate", sh.rotate, true),
            ("scaleX", sh.scale_x, true),
            ("shearX", sh.shear_x, true),
            ("inertia", s.inertia, true),
            ("damping", s.damping, true),
            ("wind", s.wind, true),
            ("gravity", s.gravity, true),
            ("mix", s.mix, true),
        ] {
            if !(ok && value.is_finite()) {
                return Err(bad(field, value));
            }
        }
        Ok(())
    }
}

/// The most steps one pose takes (a clock moved hours ahead at once is not replayed).
pub const MAX_STEPS: u32 = 10_000;

#[cfg(test)]
#[path = "physics_tests.rs"]
mod tests;
