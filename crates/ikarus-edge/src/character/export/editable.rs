//! [`super::Form::Editable`]: the motion as an animator keys it in Spine.
//!
//! Under the runtime's rules ([`IkChoice::Runtime`], `--ik spine`), the IK constraints stay on
//! and do in Spine what they did in ikarus:
//! - the clip under a keyed course is carried ([`super::clip_copy`]): its timelines key for key,
//!   looped as the motion loops it, but for the target bones' translations;
//! - each target bone gets a `translate` timeline (relative to its setup pose, in its parent's
//!   frame, as Spine stores it) with keys at the course's key times (a keyed course's keys, an
//!   eased course's start and end, a path's samples) and, where the bone's parent moves with
//!   the clip, at the clip's key times on the parent and its ancestors too: the target's world
//!   track is ikarus's, and its local translation is that track seen from the moving parent,
//!   which the keys and their fitted curves follow ([`super::curves`]), with keys added where a
//!   fit strays past the tolerance;
//! - each bone turned by hand (a keyed course's rotation keys, in place of the clip's rotation)
//!   gets a `rotate` timeline in place of the clip's, keyed at the course's key times with
//!   fitted curves, keys added where a fit strays;
//! - bend keys become keys of the constraint's IK timeline with `bendPositive` (merged into the
//!   clip's IK keys: every key takes the side in force at its time, a bend at a time between
//!   two of the clip's keys splits their curve there). Spine 3.8 files, whose curve is one for
//!   all of a key's channels, get straight keys at every frame too, split where they stray.
//!
//! Under ikarus's solver ([`IkChoice::Ikarus`], `--ik ikarus`, for limbs Spine cannot solve),
//! every bone whose local transform the motion changes gets `rotate`, `translate`, `scale` and
//! `shear` timelines (those that change) keyed at the course's and the clip's key times and at
//! every frame (the solve is iterative, and its small frame-to-frame noise is not a curve) with
//! fitted curves between, keys added where a fit strays; every constraint of every kind is keyed
//! to mix 0 at time 0: the solver replaces the IK constraints, which would otherwise undo it, and
//! the keys already hold what the transform, path and physics constraints did to the pose (on,
//! they would apply a second time).

use ikarus::character::{Character, Interpolation, Posed};
use serde_json::{Map, Value, json};

use super::clip_copy::{count_keys, cycles, insert_ik_key, looped, time_of};
use super::curves::{FittedKey, Fitter, Sample, Shape, tenths};
use super::ik_keys::{animation as animation_json, settings, switched_off};
use super::sampler::Sampler;
use super::{read_time, written_time};
use crate::character::motion::{Motion, Physics};
use crate::error::Error;
use crate::pose::{IkChoice, PoseAsk, pose_into};

/// How many keys a timeline's fit may add per frame of the motion.
const ADDED_PER_FRAME: usize = 4;

/// The share of the tolerance a timeline's fit is held to: a bone's error adds to its
/// ancestors'. (A target's error is weighed by how far the IK constraints carry it,
/// [`Sampler::gain`].)
const FIT_SHARE: f64 = 0.5;

/// The editable animation's JSON (see the module's doc). `clip` is the JSON of the clip under
/// a keyed course.
pub(super) fn animation(
    motion: &Motion<'_>,
    clip: Option<&Value>,
    tolerance: f64,
    legacy: bool,
) -> Result<Value, Error> {
    // Keys added where a fit strays: at most a few per frame per timeline (the keys' memory
    // stays within timelines × frames, and timelines are at most four per bone).
    let budget = ADDED_PER_FRAME * motion.frame_count();
    let shape = if legacy { Shape::Linear } else { Shape::Bezier };
    let mut sampler = Sampler::new(motion);
    let mut job = Job { motion, sampler: &mut sampler, budget, shape, tolerance, legacy };
    match &motion.ik {
        IkChoice::Runtime => job.spine_rules(clip),
        IkChoice::Ikarus(_) => job.solved(),
    }
}

/// One export's state.
struct Job<'j, 'm, 'a> {
    motion: &'m Motion<'a>,
    sampler: &'j mut Sampler<'m, 'a>,
    /// Keys each timeline's fit may add.
    budget: usize,
    shape: Shape,
    tolerance: f64,
    legacy: bool,
}

impl<'a> Job<'_, '_, 'a> {
    fn character(&self) -> &'a Character {
        &self.motion.loaded.character
    }

    /// The clip's index, its length, and how many cycles the motion runs it for.
    fn clip(&self, clip_json: Option<&Value>) -> Result<Option<(usize, f64, usize)>, Error> {
        let Some(name) = self.motion.clip() else { return Ok(None) };
        let c = self.character();
        let i = c.clip_index(name).ok_or_else(|| Error::input(format!("animation {name:?}: not in the character")))?;
        let length = c.clips()[i].duration;
        let keys = clip_json.map_or(0, count_keys).max(1);
        Ok(Some((i, length, cycles(length, self.motion.duration, keys, name)?)))
    }

    /// The course's key times and the clip's key times on the timelines `on` picks, as the
    /// runtime reads times, increasing, within the motion.
    fn anchors(&self, on: &dyn Fn(usize) -> bool) -> Result<Vec<f64>, Error> {
        let end = read_time(self.motion.duration);
        let mut times: Vec<f64> = self.motion.key_times().into_iter().map(read_time).collect();
        if let Some((i, length, _)) = self.clip(None)? {
            let clip = &self.character().clips()[i];
            // Each key's time, and inside a Bézier segment the times of the runtime's samples,
            // between which it plays the segment as a straight line: a bone in a frame that
            // moves so is followed by curves between those times, not across them.
            let mut own: Vec<f64> = Vec::new();
            for t in clip.bones.iter().filter(|t| on(t.bone)) {
                for (j, k) in t.keys.iter().enumerate() {
                    own.push(k.time);
                    let Some(next) = t.keys.get(j + 1) else { continue };
                    for curve in &k.curves[..t.property.channels()] {
                        if let Interpolation::Bezier { c1, c2 } = curve {
                            own.extend(tenths([k.time, c1[0], c2[0], next.time]));
                        }
                    }
                }
            }
            // The anchors of every cycle the motion runs, within the copied keys' cap.
            let cycles = cycles(length, self.motion.duration, own.len().max(1), &clip.name)?;
            for r in 0..cycles {
                times.extend(own.iter().map(|t| read_time(t + r as f64 * length)).filter(|t| *t <= end));
            }
        }
        times.sort_by(f64::total_cmp);
        times.dedup();
        Ok(times)
    }

    /// Keys fitted to the channel `value` reads from the motion (`period` for angles).
    fn fit(
        &mut self,
        anchors: &[f64],
        (channels, period): (usize, Option<f64>),
        value: &dyn Fn(&super::sampler::Snapshot) -> Sample,
    ) -> Result<Vec<FittedKey>, Error> {
        let mut budget = self.budget;
        let mut fitter =
            Fitter { channels, period, shape: self.shape, tolerance: self.tolerance * FIT_SHARE, budget: &mut budget };
        let sampler = &mut *self.sampler;
        fitter.fit(anchors, &mut |t| sampler.at(t).map(|s| value(&s)))
    }

    /// The runtime's rules: the clip carried, the targets keyed, the bends merged.
    fn spine_rules(&mut self, clip_json: Option<&Value>) -> Result<Value, Error> {
        let c = self.character();
        let targets: Vec<usize> =
            self.motion.targets_at(0.0).iter().filter_map(|(name, _)| c.bone_index(name)).collect();
        let turned = self.motion.turned_bones();
        let mut bones = Map::new();
        let mut ik = Map::new();
        let mut out = Map::new();
        if let (Some(clip), Some((_, length, cycles))) = (clip_json, self.clip(clip_json)?) {
            for (field, value) in clip.as_object().into_iter().flatten() {
                if field != "bones" && field != "ik" {
                    out.insert(field.clone(), value.clone());
                }
            }
            for (bone, timelines) in clip.get("bones").and_then(Value::as_object).into_iter().flatten() {
                let target = c.bone_index(bone).is_some_and(|b| targets.contains(&b));
                let turns = c.bone_index(bone).is_some_and(|b| turned.contains(&b));
                let mut own = Map::new();
                for (kind, keys) in timelines.as_object().into_iter().flatten() {
                    if target && matches!(kind.as_str(), "translate" | "translatex" | "translatey") {
                        continue;
                    }
                    if turns && kind == "rotate" {
                        continue;
                    }
                    let keys = keys.as_array().map_or(&[][..], Vec::as_slice);
                    own.insert(kind.clone(), Value::Array(looped(keys, cycles, length, self.legacy, &json!({}))));
                }
                if !own.is_empty() {
                    bones.insert(bone.clone(), Value::Object(own));
                }
            }
            for (name, keys) in clip.get("ik").and_then(Value::as_object).into_iter().flatten() {
                let setup =
                    c.ik_constraints().find(|(_, k)| &k.name == name).map_or(json!({}), |(_, k)| settings(&k.setup));
                let keys = keys.as_array().map_or(&[][..], Vec::as_slice);
                ik.insert(name.clone(), Value::Array(looped(keys, cycles, length, self.legacy, &setup)));
            }
        }
        for &b in &targets {
            let c = self.character();
            let parent = c.bones()[b].parent;
            let setup = c.bones()[b].setup;
            let ancestors = ancestors(c, parent);
            let mut anchors = self.anchors(&|bone| ancestors.contains(&bone))?;
            if self.shape == Shape::Linear {
                // Straight keys (3.8) follow a curve only closely spaced: one at every frame
                // too, split further where they stray.
                anchors.extend(self.motion.frame_times().into_iter().map(read_time));
                anchors.sort_by(f64::total_cmp);
                anchors.dedup();
            }
            let step = self.tolerance;
            let mut budget = self.budget;
            let mut fitter = Fitter {
                channels: 2,
                period: None,
                shape: self.shape,
                tolerance: self.tolerance * FIT_SHARE,
                budget: &mut budget,
            };
            let sampler = &mut *self.sampler;
            let keys = fitter.fit(&anchors, &mut |t| {
                let s = sampler.at(t)?;
                let gain = sampler.gain(t, step)?;
                Ok(Sample {
                    values: [s.local[b].x - setup.x, s.local[b].y - setup.y],
                    weight: parent.map_or(1.0, |p| norm(&s.world[p])) * gain,
                })
            })?;
            let name = self.character().bones()[b].name.clone();
            let entry = bones.entry(name).or_insert_with(|| json!({}));
            entry["translate"] = Value::Array(keys.iter().map(two).collect());
        }
        self.turns(&turned, &mut bones)?;
        for (k, bends) in self.motion.bend_keys().iter().filter(|(_, b)| !b.is_empty()) {
            let name = self.character().constraints()[*k].name().to_owned();
            let mut keys = match ik.remove(&name) {
                Some(Value::Array(keys)) => keys,
                _ => Vec::new(),
            };
            for &(time, _) in bends {
                let s = self.sampler.at(read_time(time))?;
                insert_ik_key(&mut keys, time, &settings(&s.settings[*k]), self.legacy);
            }
            for key in &mut keys {
                let t = time_of(key);
                let side = bends.iter().rev().find(|(b, _)| written_time(*b) <= t).unwrap_or(&bends[0]).1;
                key["bendPositive"] = json!(side);
            }
            ik.insert(name, Value::Array(keys));
        }
        out.insert("bones".to_owned(), Value::Object(bones));
        if !ik.is_empty() {
            out.insert("ik".to_owned(), Value::Object(ik));
        }
        if self.motion.physics == Physics::Off {
            // A motion asked without physics: the game leaves it out too (every physics
            // constraint keyed to mix 0; on, they play on top of the keys as on the motion).
            if let Some(off) = switched_off(self.character(), self.legacy).remove("physics") {
                out.insert("physics".to_owned(), off);
            }
        }
        Ok(Value::Object(out))
    }

    /// The `rotate` timelines of the bones turned by hand: the keyed local rotation (in place of
    /// the clip's, as the runtime's rotate timeline sets it before the constraints), relative to
    /// the setup's, fitted between the course's key times (every frame too for 3.8's straight
    /// keys), its error weighed by how far a turn of the bone swings its subtree.
    fn turns(&mut self, turned: &[usize], bones: &mut Map<String, Value>) -> Result<(), Error> {
        if turned.is_empty() {
            return Ok(());
        }
        let reach = reach(self.motion)?;
        let mut anchors: Vec<f64> = self.motion.key_times().into_iter().map(read_time).collect();
        if self.shape == Shape::Linear {
            anchors.extend(self.motion.frame_times().into_iter().map(read_time));
            anchors.sort_by(f64::total_cmp);
            anchors.dedup();
        }
        for (j, &b) in turned.iter().enumerate() {
            let setup = self.character().bones()[b].setup.rotation.to_degrees();
            let weight = reach[b].to_radians();
            let mut budget = self.budget;
            let mut fitter = Fitter {
                channels: 1,
                period: Some(360.0),
                shape: self.shape,
                tolerance: self.tolerance * FIT_SHARE,
                budget: &mut budget,
            };
            let motion = self.motion;
            let keys = fitter.fit(&anchors, &mut |t| {
                let deg = motion.turns_at(t).get(j).map_or(setup, |turn| turn.1);
                Ok(Sample { values: [deg - setup, 0.0], weight })
            })?;
            let name = if self.legacy { "angle" } else { "value" };
            let bone = self.character().bones()[b].name.clone();
            let entry = bones.entry(bone).or_insert_with(|| json!({}));
            entry["rotate"] = Value::Array(keys.iter().map(|k| one(k, name)).collect());
        }
        Ok(())
    }

    /// ikarus's solver: every bone the motion moves keyed, every constraint at mix 0.
    fn solved(&mut self) -> Result<Value, Error> {
        let c = self.character();
        let reach = reach(self.motion)?;
        // What moves: every bone's local transform at every frame and key time.
        let mut times: Vec<f64> = self.motion.frame_times();
        times.extend(self.anchors(&|_| true)?);
        let n = c.bones().len();
        let mut moved = vec![[false; 4]; n];
        for t in times {
            let s = self.sampler.at(t)?;
            for (i, bone) in c.bones().iter().enumerate() {
                let (l, s0) = (&s.local[i], &bone.setup);
                let m = &mut moved[i];
                m[0] |= differs([l.rotation, 0.0], [s0.rotation, 0.0]);
                m[1] |= differs([l.x, l.y], [s0.x, s0.y]);
                m[2] |= differs([l.scale_x, l.scale_y], [s0.scale_x, s0.scale_y]);
                m[3] |= differs([l.shear_x, l.shear_y], [s0.shear_x, s0.shear_y]);
            }
        }
        // ikarus's solve is iterative: its rotations carry the solver's own small noise from
        // one time to the next, which no curve across many frames follows within the
        // tolerance; keys at every frame (the solve's own samples) with curves between them.
        let mut anchors = self.anchors(&|_| true)?;
        anchors.extend(self.motion.frame_times().into_iter().map(read_time));
        anchors.sort_by(f64::total_cmp);
        anchors.dedup();
        let mut bones = Map::new();
        for (i, m) in moved.iter().enumerate() {
            let bone = self.character().bones()[i].clone();
            let s0 = bone.setup;
            let parent = bone.parent;
            let r = reach[i];
            let mut timelines = Map::new();
            if m[0] {
                let keys = self.fit(&anchors, (1, Some(360.0)), &|s| Sample {
                    values: [(s.local[i].rotation - s0.rotation).to_degrees(), 0.0],
                    weight: r.to_radians(),
                })?;
                let name = if self.legacy { "angle" } else { "value" };
                timelines.insert("rotate".to_owned(), Value::Array(keys.iter().map(|k| one(k, name)).collect()));
            }
            if m[1] {
                let keys = self.fit(&anchors, (2, None), &|s| Sample {
                    values: [s.local[i].x - s0.x, s.local[i].y - s0.y],
                    weight: parent.map_or(1.0, |p| norm(&s.world[p])),
                })?;
                timelines.insert("translate".to_owned(), Value::Array(keys.iter().map(two).collect()));
            }
            if m[2] {
                for (setup, axis) in [(s0.scale_x, "scaleX"), (s0.scale_y, "scaleY")] {
                    if setup == 0.0 {
                        return Err(Error::input(format!(
                            "bone {:?}: its setup {axis} is 0, and the motion scales it (a scale key multiplies the setup's)",
                            bone.name
                        )));
                    }
                }
                let w = r * s0.scale_x.abs().max(s0.scale_y.abs());
                let keys = self.fit(&anchors, (2, None), &|s| Sample {
                    values: [s.local[i].scale_x / s0.scale_x, s.local[i].scale_y / s0.scale_y],
                    weight: w,
                })?;
                timelines.insert("scale".to_owned(), Value::Array(keys.iter().map(two).collect()));
            }
            if m[3] {
                let keys = self.fit(&anchors, (2, Some(360.0)), &|s| Sample {
                    values: [
                        (s.local[i].shear_x - s0.shear_x).to_degrees(),
                        (s.local[i].shear_y - s0.shear_y).to_degrees(),
                    ],
                    weight: r.to_radians(),
                })?;
                timelines.insert("shear".to_owned(), Value::Array(keys.iter().map(two).collect()));
            }
            if !timelines.is_empty() {
                bones.insert(bone.name.clone(), Value::Object(timelines));
            }
        }
        Ok(animation_json(bones, switched_off(self.character(), self.legacy)))
    }
}

/// Whether two pairs of values differ (beyond rounding).
fn differs(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() > 1e-12 || (a[1] - b[1]).abs() > 1e-12
}

/// `bone` and its ancestors.
fn ancestors(c: &Character, mut bone: Option<usize>) -> Vec<usize> {
    let mut out = Vec::new();
    while let Some(b) = bone {
        out.push(b);
        bone = c.bones()[b].parent;
    }
    out
}

/// How far a world matrix can stretch a unit vector at most (its Frobenius norm, over it).
fn norm(w: &ikarus::character::Affine) -> f64 {
    (w.a * w.a + w.b * w.b + w.c * w.c + w.d * w.d).sqrt()
}

/// Per bone, the farthest its own or a descendant's origin or tip is from its origin in the
/// setup pose (what a turn of the bone swings), at least 1e-9 of the character's units.
fn reach(motion: &Motion<'_>) -> Result<Vec<f64>, Error> {
    let c = &motion.loaded.character;
    let mut setup = Posed::default();
    pose_into(motion.loaded, &PoseAsk::default(), &mut setup)?;
    let mut reach = vec![1e-9_f64; c.bones().len()];
    for j in 0..c.bones().len() {
        for p in [setup.origin(j), setup.tip(j)] {
            let mut i = Some(j);
            while let Some(b) = i {
                let o = setup.origin(b);
                reach[b] = reach[b].max((p[0] - o[0]).hypot(p[1] - o[1]));
                i = c.bones()[b].parent;
            }
        }
    }
    Ok(reach)
}

/// A one-value key (`value`, or 3.8's `angle`).
fn one(k: &FittedKey, name: &str) -> Value {
    let mut key = json!({"time": written_time(k.time), (name): k.values[0]});
    if let Some(c) = k.curve {
        key["curve"] = json!(c[0]);
    }
    key
}

/// A two-value key (`x`, `y`).
fn two(k: &FittedKey) -> Value {
    let mut key = json!({"time": written_time(k.time), "x": k.values[0], "y": k.values[1]});
    if let Some(c) = k.curve {
        key["curve"] = json!([c[0][0], c[0][1], c[0][2], c[0][3], c[1][0], c[1][1], c[1][2], c[1][3]]);
    }
    key
}
