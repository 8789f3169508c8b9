//! What a stand-in for Spine's runtime needs of a [`Character`] (issue 41: the `ikarus-spine`
//! add-on's tests and demo drive a JavaScript skeleton posed here): the animation's local
//! transforms and IK settings at a time (what `AnimationState.apply` writes into the bones and
//! the IK constraints), and the world transforms of local transforms and IK settings JavaScript
//! wrote (what `Skeleton.updateWorldTransform` computes), with the character's constraints
//! applied in their order, the skeleton placed where JavaScript says. The numbers cross through
//! three buffers in the module's memory ([`LOCAL`] per bone, [`IK`] per IK constraint, [`WORLD`]
//! per bone); nothing is allocated per call once the character's buffers have grown.

use ikarus::character::{BoneProperty, ConstraintKeys, PoseRequest, Settings};
use ikarus::character::{
    Constraint, GivenPose, IkBones, IkSettings, LocalTransform, PhysicsMode, Placement, spine_local_numbers,
};
use wasm_bindgen::prelude::*;

use super::Character;

/// Numbers per bone in the locals buffer: x, y, rotation, scaleX, scaleY, shearX, shearY
/// (degrees for the angles), Spine's `Bone` fields.
pub const LOCAL: usize = 7;
/// Numbers per IK constraint in the IK buffer: mix, softness, bendDirection (1 or -1),
/// compress (1 or 0), stretch (1 or 0), Spine's `IkConstraint` fields.
pub const IK: usize = 5;
/// Numbers per bone in the worlds buffer: a, b, c, d, worldX, worldY, then the applied local
/// transform the constraints left (ax, ay, arotation, ascaleX, ascaleY, ashearX, ashearY,
/// degrees for the angles), Spine's `Bone` fields.
pub const WORLD: usize = 13;

/// The buffers of the stand-in's calls, sized on the first one.
#[derive(Debug, Default)]
pub(super) struct Given {
    /// [`LOCAL`] per bone, written by [`Character::sample_here`] and by JavaScript.
    local: Vec<f64>,
    /// 5 per IK constraint, written by [`Character::sample_here`] and by JavaScript.
    ik: Vec<f64>,
    /// 13 per bone, written by [`Character::world_here`].
    world: Vec<f64>,
    /// The IK constraints' indices among the character's constraints, in the file's order.
    iks: Vec<usize>,
    /// Every constraint's settings as the last sample left them (the IK ones replaced from
    /// [`Given::ik`] in each [`Character::world_here`]).
    settings: Vec<Settings>,
    /// The locals of [`Given::local`], as the library takes them.
    transforms: Vec<LocalTransform>,
    /// Why the last call refused, or empty.
    error: String,
}

impl Character {
    /// Sizes the stand-in's buffers (once).
    fn given_buffers(&mut self) {
        let c = &self.loaded.character;
        let g = &mut self.given;
        if g.local.len() == LOCAL * c.bones().len() {
            return;
        }
        g.iks = c
            .constraints()
            .iter()
            .enumerate()
            .filter(|(_, k)| matches!(k, Constraint::Ik(_)))
            .map(|(i, _)| i)
            .collect();
        g.local = vec![0.0; LOCAL * c.bones().len()];
        g.ik = vec![0.0; IK * g.iks.len()];
        g.world = vec![0.0; WORLD * c.bones().len()];
        g.transforms = vec![LocalTransform::default(); c.bones().len()];
        g.settings = c.constraints().iter().map(|k| k.setup()).collect();
    }
}

#[wasm_bindgen]
impl Character {
    /// Per bone, its parent's index (-1 for a root), its length and its inherit mode (0 normal,
    /// 1 onlyTranslation, 2 noRotationOrReflection, 3 noScale, 4 noScaleOrReflection: the order
    /// of Spine's `Inherit`): `3 × bones` numbers.
    #[wasm_bindgen(js_name = boneData)]
    pub fn bone_data(&self) -> Vec<f64> {
        let bones = self.loaded.character.bones();
        bones
            .iter()
            .flat_map(|b| {
                let inherit = ikarus::character::Inherit::ALL.iter().position(|&i| i == b.inherit).unwrap_or(0);
                [b.parent.map_or(-1.0, |p| p as f64), b.length, inherit as f64]
            })
            .collect()
    }

    /// The IK constraints' names, in the file's order (the IK buffer's order).
    #[wasm_bindgen(js_name = ikNames)]
    pub fn ik_names(&self) -> Vec<String> {
        self.ik_constraints().map(|(_, c)| c.name.clone()).collect()
    }

    /// Per IK constraint: its target bone, its first bone, its second bone (-1 for a one-bone
    /// constraint), and whether it scales uniformly (1 or 0): `4 × IK constraints` numbers.
    #[wasm_bindgen(js_name = ikData)]
    pub fn ik_data(&self) -> Vec<f64> {
        self.ik_constraints()
            .flat_map(|(_, c)| {
                let (first, second) = match c.bones {
                    IkBones::One(b) => (b as f64, -1.0),
                    IkBones::Two { parent, child } => (parent as f64, child as f64),
                };
                [c.target as f64, first, second, f64::from(u8::from(c.uniform))]
            })
            .collect()
    }

    /// Per bone, 7 flags (1 or 0): whether the chosen animation keys that number (x, y,
    /// rotation, scaleX, scaleY, shearX, shearY). A runtime's `AnimationState.apply` sets only
    /// those; a stand-in leaves the others as they are. All 0 without an animation.
    #[wasm_bindgen(js_name = keyedLocals)]
    pub fn keyed_locals(&self) -> Vec<u8> {
        let c = &self.loaded.character;
        let mut keyed = vec![0; LOCAL * c.bones().len()];
        for t in self.clip.iter().flat_map(|&i| &c.clips()[i].bones) {
            let numbers: &[usize] = match t.property {
                BoneProperty::Translate => &[0, 1],
                BoneProperty::TranslateX => &[0],
                BoneProperty::TranslateY => &[1],
                BoneProperty::Rotate => &[2],
                BoneProperty::Scale => &[3, 4],
                BoneProperty::ScaleX => &[3],
                BoneProperty::ScaleY => &[4],
                BoneProperty::Shear => &[5, 6],
                BoneProperty::ShearX => &[5],
                BoneProperty::ShearY => &[6],
            };
            for &n in numbers {
                keyed[LOCAL * t.bone + n] = 1;
            }
        }
        keyed
    }

    /// Per IK constraint (the IK buffer's order), 1 if the chosen animation keys it, else 0.
    #[wasm_bindgen(js_name = keyedIks)]
    pub fn keyed_iks(&self) -> Vec<u8> {
        let c = &self.loaded.character;
        let clip = self.clip.map(|i| &c.clips()[i]);
        self.ik_constraints()
            .map(|(k, _)| {
                let mut timelines = clip.iter().flat_map(|clip| &clip.constraints);
                u8::from(timelines.any(|t| t.constraint == k && matches!(t.keys, ConstraintKeys::Ik(_))))
            })
            .collect()
    }

    /// The chosen animation's duration, seconds (0 without one).
    #[wasm_bindgen(getter)]
    pub fn duration(&self) -> f64 {
        self.clip.map_or(0.0, |i| self.loaded.character.clips()[i].duration)
    }

    /// Writes the setup pose, then the chosen animation at `time` seconds (none: the setup pose
    /// alone), into the locals buffer (at [`locals_ptr`](Character::locals_ptr)) and the IK
    /// buffer (at [`ik_ptr`](Character::ik_ptr)): what `AnimationState.apply` leaves in the
    /// bones and IK constraints. `false` for a time that is not finite, the line at
    /// [`given_error`](Character::given_error) (a plain return: nothing allocated per call).
    #[wasm_bindgen(js_name = sampleHere)]
    pub fn sample_here(&mut self, time: f64) -> bool {
        let done = self.sample_into(time);
        self.keep_error(done)
    }

    /// Why the last [`sample_here`](Character::sample_here) or
    /// [`world_here`](Character::world_here) refused (empty when it did not).
    #[wasm_bindgen(getter, js_name = givenError)]
    pub fn given_error(&self) -> String {
        self.given.error.clone()
    }

    /// Computes the world transforms (into the worlds buffer at
    /// [`worlds_ptr`](Character::worlds_ptr)) of the locals buffer's transforms with the IK
    /// buffer's settings, the character's constraints applied in their order (the other kinds
    /// with the last sample's settings), the skeleton at (`x`, `y`) scaled by (`scale_x`,
    /// `scale_y`): `Skeleton.updateWorldTransform`. `physics` is Spine's `Physics` (0 none,
    /// 1 reset, 2 update, 3 pose: update to the same `clock`), `clock` the skeleton's time,
    /// seconds. `false` for a number that is not finite or a `physics` that is not one of those,
    /// the line naming it at [`given_error`](Character::given_error).
    #[wasm_bindgen(js_name = worldHere)]
    pub fn world_here(&mut self, x: f64, y: f64, scale_x: f64, scale_y: f64, physics: u8, clock: f64) -> bool {
        let done = self.world_into([x, y, scale_x, scale_y], physics, clock);
        self.keep_error(done)
    }

    /// Where the locals buffer lies in the module's memory (7 numbers per bone; a byte
    /// offset, fixed for the character's life once [`sample_here`](Character::sample_here) or
    /// [`world_here`](Character::world_here) has run).
    #[wasm_bindgen(getter, js_name = localsPtr)]
    pub fn locals_ptr(&mut self) -> usize {
        self.given_buffers();
        self.given.local.as_ptr() as usize
    }

    /// Where the IK buffer lies (5 numbers per IK constraint), as
    /// [`locals_ptr`](Character::locals_ptr).
    #[wasm_bindgen(getter, js_name = ikPtr)]
    pub fn ik_ptr(&mut self) -> usize {
        self.given_buffers();
        self.given.ik.as_ptr() as usize
    }

    /// Where the worlds buffer lies (13 numbers per bone), as
    /// [`locals_ptr`](Character::locals_ptr).
    #[wasm_bindgen(getter, js_name = worldsPtr)]
    pub fn worlds_ptr(&mut self) -> usize {
        self.given_buffers();
        self.given.world.as_ptr() as usize
    }
}

impl Character {
    /// [`sample_here`](Character::sample_here), its refusal as a line.
    fn sample_into(&mut self, time: f64) -> Result<(), String> {
        self.given_buffers();
        let c = &self.loaded.character;
        if !time.is_finite() {
            return Err(format!("time: must be a finite number of seconds, got {time}"));
        }
        let request =
            PoseRequest { clip: self.clip.map(|i| (i, time)), skin: c.default_skin(), ..PoseRequest::default() };
        c.sample(&request, &mut self.given_posed).map_err(|e| e.to_string())?;
        let g = &mut self.given;
        for (i, out) in g.local.chunks_exact_mut(LOCAL).enumerate() {
            let l = self.given_posed.local(i);
            out.copy_from_slice(&spine_local_numbers(&l));
        }
        for (k, s) in g.settings.iter_mut().enumerate() {
            *s = self.given_posed.settings(k);
        }
        for (&k, out) in g.iks.iter().zip(g.ik.chunks_exact_mut(IK)) {
            let s = self.given_posed.ik_settings(k).unwrap_or_default();
            let sign = |b: bool| if b { 1.0 } else { -1.0 };
            let one = |b: bool| f64::from(u8::from(b));
            out.copy_from_slice(&[s.mix, s.softness, sign(s.bend_positive), one(s.compress), one(s.stretch)]);
        }
        Ok(())
    }

    /// [`world_here`](Character::world_here), its refusal as a line.
    fn world_into(&mut self, placement: [f64; 4], physics: u8, clock: f64) -> Result<(), String> {
        self.given_buffers();
        let c = &self.loaded.character;
        let g = &mut self.given;
        let [x, y, scale_x, scale_y] = placement;
        if let Some(v) = [x, y, scale_x, scale_y].into_iter().find(|v| !v.is_finite()) {
            return Err(format!("placement: {v} is not a finite number"));
        }
        let mode = match physics {
            0 => PhysicsMode::None,
            1 => PhysicsMode::Reset,
            2 | 3 => PhysicsMode::Update,
            _ => return Err(format!("physics: {physics} is not 0 (none), 1 (reset), 2 (update) or 3 (pose)")),
        };
        if let Some(i) = g.local.iter().position(|v| !v.is_finite()) {
            let bone = &c.bones()[i / LOCAL].name;
            return Err(format!("bone {bone:?}: local number {} is {}, not finite", i % LOCAL, g.local[i]));
        }
        if let Some(i) = g.ik.iter().position(|v| !v.is_finite()) {
            let name = c.constraints()[g.iks[i / IK]].name();
            return Err(format!("IK constraint {name:?}: number {} is {}, not finite", i % IK, g.ik[i]));
        }
        for (t, l) in g.transforms.iter_mut().zip(g.local.chunks_exact(LOCAL)) {
            *t = LocalTransform {
                x: l[0],
                y: l[1],
                rotation: l[2].to_radians(),
                scale_x: l[3],
                scale_y: l[4],
                shear_x: l[5].to_radians(),
                shear_y: l[6].to_radians(),
            };
        }
        for (&k, n) in g.iks.iter().zip(g.ik.chunks_exact(IK)) {
            g.settings[k] = Settings::Ik(IkSettings {
                mix: n[0],
                softness: n[1],
                bend_positive: n[2] >= 0.0,
                compress: n[3] != 0.0,
                stretch: n[4] != 0.0,
            });
        }
        let given = GivenPose {
            local: &g.transforms,
            settings: &g.settings,
            placement: Placement { position: [x, y], scale: [scale_x, scale_y] },
            skin: c.default_skin(),
            physics: mode,
            clock,
        };
        c.pose_given(&given, &mut self.given_posed).map_err(|e| e.to_string())?;
        for (i, out) in g.world.chunks_exact_mut(WORLD).enumerate() {
            let (w, l) = (self.given_posed.world(i), self.given_posed.local(i));
            out[..10].copy_from_slice(&[w.a, w.b, w.c, w.d, w.x, w.y, l.x, l.y, l.rotation.to_degrees(), l.scale_x]);
            out[10..].copy_from_slice(&[l.scale_y, l.shear_x.to_degrees(), l.shear_y.to_degrees()]);
        }
        Ok(())
    }

    /// Keeps `done`'s refusal for [`given_error`](Character::given_error); whether it is done.
    fn keep_error(&mut self, done: Result<(), String>) -> bool {
        self.given.error.clear();
        match done {
            Ok(()) => true,
            Err(e) => {
                self.given.error = e;
                false
            }
        }
    }

    /// The IK constraints with their indices among the character's constraints.
    fn ik_constraints(&self) -> impl Iterator<Item = (usize, &ikarus::character::IkConstraint)> {
        self.loaded.character.constraints().iter().enumerate().filter_map(|(i, k)| match k {
            Constraint::Ik(c) => Some((i, c)),
            Constraint::Path(_) | Constraint::Physics(_) | Constraint::Transform(_) => None,
        })
    }
}

#[cfg(test)]
#[path = "character_given_tests.rs"]
mod tests;
