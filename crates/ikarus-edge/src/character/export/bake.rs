//! [`super::Form::Bake`]: the motion baked frame by frame. Per bone whose local transform
//! leaves its setup value during the motion, `rotate` (degrees, unwrapped so that consecutive
//! keys never differ by more than 180°), `translate`, `scale` and `shear` relative to the setup
//! pose, as Spine reads them and as [`super::super::clips`] reads them (3.8 files get `angle`
//! for a rotation, 4.x files `value`). Keys are linear: one per frame (posed at the frame's
//! time, written at the 32-bit float nearest it), and more by bisection wherever a straight
//! line between two keys would put a bone's world origin or tip more than the tolerance from
//! the motion posed at that time. The motion is played as a game plays it ([`Motion::play_at`]:
//! with its physics stepping frame by frame, unless it is asked off), so the keys hold what the
//! physics did too. Every constraint of the file (IK, transform, path, physics)
//! is keyed to mix 0 at time 0, so that the constraints leave the bones where the keys put them
//! (at mix 0 a constraint does nothing; the keys already hold what the constraints did).
//!
//! Memory: the keys hold every bone's local transform, so their number is bounded: at most
//! [`MAX_REFINED`] keys between two frames and, over the whole motion, [`ADDED_PER_FRAME`] per
//! frame (the motion's frames × bones is capped before it gets here).

use ikarus::character::{Affine, Character, LocalTransform, world_transform};
use serde_json::{Map, Value, json};

use super::written_time;
use crate::character::motion::{Motion, Playhead};
use crate::error::Error;

/// How many times an interval between two frames is halved at most (a key every
/// 1 / (fps · 2¹⁶) s at the finest, 5·10⁻⁷ s at 30 fps: about the resolution of a key's time,
/// a 32-bit float, a few seconds in). Deep, because a limb passing through full reach under
/// ikarus's solver swings like a square root of the time left, and a chord of √t strays
/// √h / 4 over an interval h: the raptor's four-bone leg carried beyond its reach (the README's
/// tour) needed 12 halvings at 30 fps to stay within the tolerance. The bisection only goes
/// deep where a line strays, about two keys a level near such a point; [`MAX_REFINED`] bounds it
/// where the motion strays everywhere.
const MAX_DEPTH: u32 = 16;

/// The most keys added between two frames: a motion that no line follows anywhere (a solution
/// that jumps back and forth) stops being refined there instead of taking 2¹⁶ poses.
const MAX_REFINED: usize = 256;

/// How many keys the bisection may add per frame of the motion, over the whole motion: the
/// keys' memory (every bone's transform per key) stays within 17 × frames × bones.
const ADDED_PER_FRAME: usize = 16;

/// One key: its time and every bone's local transform.
struct Key {
    time: f64,
    local: Vec<LocalTransform>,
}

/// The baked animation's JSON (see the module's doc), fitted to `tolerance`.
pub(super) fn animation(motion: &Motion<'_>, tolerance: f64, legacy: bool) -> Result<Value, Error> {
    let keys = keys(motion, tolerance)?;
    json_of(&motion.loaded.character, &keys, legacy)
}

/// The keys: one per frame, and the bisections that keep a straight line between two keys
/// within the tolerance of the motion.
fn keys(motion: &Motion<'_>, tolerance: f64) -> Result<Vec<Key>, Error> {
    let mut head = Playhead::default();
    let mut pose = |time: f64| -> Result<Key, Error> {
        let posed = motion.play_at(time, &mut head)?;
        Ok(Key { time, local: (0..posed.len()).map(|i| posed.local(i)).collect() })
    };
    let mut check = Playhead::default();
    let mut world = Vec::new();
    let times = motion.frame_times();
    let mut out = vec![pose(times[0])?];
    // Over the whole motion, at most ADDED_PER_FRAME added keys per frame.
    let mut total = ADDED_PER_FRAME * times.len();
    for &t1 in &times[1..] {
        let end = pose(t1)?;
        let mut budget = MAX_REFINED.min(total);
        let before = budget;
        refine(motion, (&mut check, &mut world), &end, &mut out, (0, &mut budget, tolerance), &mut pose)?;
        total -= before - budget;
        out.push(end);
    }
    Ok(out)
}

/// Keys inserted between the last of `out` and `end` (not pushed) wherever a straight line
/// between them strays more than the tolerance from the motion, `depth` halvings deep with
/// `budget` keys left to add.
fn refine(
    motion: &Motion<'_>,
    (check, world): (&mut Playhead, &mut Vec<Affine>),
    end: &Key,
    out: &mut Vec<Key>,
    (depth, budget, tolerance): (u32, &mut usize, f64),
    pose: &mut dyn FnMut(f64) -> Result<Key, Error>,
) -> Result<(), Error> {
    let start = out.last().expect("a first key");
    if depth >= MAX_DEPTH || *budget == 0 || stray(motion, (check, world), start, end)? <= tolerance {
        return Ok(());
    }
    // A key's time is read as a 32-bit float: the key is posed at the time it will be read at,
    // and halving stops where the two ends have no such time between them.
    let mid_time = f64::from(((start.time + end.time) / 2.0) as f32);
    if mid_time <= start.time || mid_time >= end.time {
        return Ok(());
    }
    *budget -= 1;
    let mid = pose(mid_time)?;
    refine(motion, (check, world), &mid, out, (depth + 1, &mut *budget, tolerance), pose)?;
    out.push(mid);
    refine(motion, (check, world), end, out, (depth + 1, budget, tolerance), pose)
}

/// The largest distance between a bone's origin or tip posed by the straight line between keys
/// `a` and `b` and posed by the motion, at a quarter, half and three quarters of the way.
fn stray(
    motion: &Motion<'_>,
    (head, world): (&mut Playhead, &mut Vec<Affine>),
    a: &Key,
    b: &Key,
) -> Result<f64, Error> {
    let c = &motion.loaded.character;
    let mut worst: f64 = 0.0;
    for f in [0.25, 0.5, 0.75] {
        let time = a.time + (b.time - a.time) * f;
        let check = motion.play_at(time, head)?;
        let local: Vec<LocalTransform> = a.local.iter().zip(&b.local).map(|(p, q)| between(p, q, f)).collect();
        world_of(c, &local, world);
        for (i, bone) in c.bones().iter().enumerate() {
            let w = &world[i];
            let tip = [w.x + w.a * bone.length, w.y + w.c * bone.length];
            for (p, q) in [([w.x, w.y], check.origin(i)), (tip, check.tip(i))] {
                worst = worst.max((p[0] - q[0]).hypot(p[1] - q[1]));
            }
        }
    }
    Ok(worst)
}

/// The local transform a fraction `f` of the way from `p` to `q`, as linear keys give it (the
/// rotation the short way round, as the unwrapped keys turn).
fn between(p: &LocalTransform, q: &LocalTransform, f: f64) -> LocalTransform {
    let lerp = |a: f64, b: f64| a + (b - a) * f;
    LocalTransform {
        x: lerp(p.x, q.x),
        y: lerp(p.y, q.y),
        rotation: p.rotation + wrap(q.rotation - p.rotation, std::f64::consts::TAU) * f,
        scale_x: lerp(p.scale_x, q.scale_x),
        scale_y: lerp(p.scale_y, q.scale_y),
        shear_x: lerp(p.shear_x, q.shear_x),
        shear_y: lerp(p.shear_y, q.shear_y),
    }
}

/// `v` less the whole turns (`turn`) that bring it into [−turn/2, turn/2].
fn wrap(v: f64, turn: f64) -> f64 {
    v - turn * (v / turn).round()
}

/// Every bone's world transform from its local one, parents first.
fn world_of(c: &Character, local: &[LocalTransform], world: &mut Vec<Affine>) {
    world.clear();
    for (b, t) in c.bones().iter().zip(local) {
        let w = world_transform(t, b.inherit, b.parent.map(|p| &world[p]), c.placement());
        world.push(w);
    }
}

/// The keys of one timeline less those that the straight line between the kept keys around
/// them gives within 1e-9 (a bone still, or moving evenly, for a while): the pose the keys give
/// does not change. A run of dropped keys is at most 64 long (the check is over the run).
fn thinned(series: Vec<(f64, [f64; 2])>) -> Vec<(f64, [f64; 2])> {
    const LINE: f64 = 1e-9;
    let n = series.len();
    if n <= 2 {
        return series;
    }
    let mut out = vec![series[0]];
    let mut kept = 0;
    for k in 1..n - 1 {
        let ((t0, v0), (t1, v1)) = (series[kept], series[k + 1]);
        let on_line = k - kept <= 64
            && series[kept + 1..=k].iter().all(|&(t, v)| {
                let f = (t - t0) / (t1 - t0);
                (0..2).all(|c| (v0[c] + (v1[c] - v0[c]) * f - v[c]).abs() <= LINE)
            });
        if !on_line {
            out.push(series[k]);
            kept = k;
        }
    }
    out.push(series[n - 1]);
    out
}

/// The animation's JSON: the bones' timelines (those that leave the setup pose) and every
/// constraint at mix 0.
fn json_of(c: &Character, keys: &[Key], legacy: bool) -> Result<Value, Error> {
    const SAME: f64 = 1e-12;
    let mut bones = Map::new();
    for (i, bone) in c.bones().iter().enumerate() {
        let s = &bone.setup;
        let moved = |f: &dyn Fn(&LocalTransform) -> [f64; 2]| {
            keys.iter().any(|k| {
                let (a, b) = (f(&k.local[i]), f(s));
                (a[0] - b[0]).abs() > SAME || (a[1] - b[1]).abs() > SAME
            })
        };
        let mut timelines = Map::new();
        let series = |f: &dyn Fn(&LocalTransform) -> [f64; 2]| -> Vec<(f64, [f64; 2])> {
            thinned(keys.iter().map(|k| (k.time, f(&k.local[i]))).collect())
        };
        if moved(&|l| [l.rotation, 0.0]) {
            let mut last = 0.0;
            let mut unwrapped = |l: &LocalTransform| {
                let d = (l.rotation - s.rotation).to_degrees();
                last += wrap(d - last, 360.0);
                last
            };
            let values: Vec<(f64, [f64; 2])> = keys.iter().map(|k| (k.time, [unwrapped(&k.local[i]), 0.0])).collect();
            let name = if legacy { "angle" } else { "value" };
            let rotate = thinned(values)
                .into_iter()
                .map(|(time, [v, _])| json!({"time": written_time(time), (name): v}))
                .collect();
            timelines.insert("rotate".to_owned(), Value::Array(rotate));
        }
        let two = |name: &str, f: &dyn Fn(&LocalTransform) -> [f64; 2], timelines: &mut Map<String, Value>| {
            let keys = series(f)
                .into_iter()
                .map(|(time, [x, y])| json!({"time": written_time(time), "x": x, "y": y}))
                .collect();
            timelines.insert(name.to_owned(), Value::Array(keys));
        };
        if moved(&|l| [l.x, l.y]) {
            two("translate", &|l| [l.x - s.x, l.y - s.y], &mut timelines);
        }
        if moved(&|l| [l.scale_x, l.scale_y]) {
            for (setup, axis) in [(s.scale_x, "scaleX"), (s.scale_y, "scaleY")] {
                if setup == 0.0 {
                    return Err(Error::input(format!(
                        "bone {:?}: its setup {axis} is 0, and the motion scales it (a scale key multiplies the setup's)",
                        bone.name
                    )));
                }
            }
            two("scale", &|l| [l.scale_x / s.scale_x, l.scale_y / s.scale_y], &mut timelines);
        }
        if moved(&|l| [l.shear_x, l.shear_y]) {
            two(
                "shear",
                &|l| [(l.shear_x - s.shear_x).to_degrees(), (l.shear_y - s.shear_y).to_degrees()],
                &mut timelines,
            );
        }
        if !timelines.is_empty() {
            bones.insert(bone.name.clone(), Value::Object(timelines));
        }
    }
    Ok(super::ik_keys::animation(bones, super::ik_keys::switched_off(c, legacy)))
}
