//! DragonBones 5.x animations into clips: each `armature[0].animation[]` with its bone timelines
//! (`translateFrame`, `rotateFrame`, `scaleFrame`) and IK timelines (`ik[].frame`); slot,
//! deform (`ffd`), event and action timelines are skipped.
//!
//! Frames are listed one after another: a frame's `duration` (frames at the armature's
//! `frameRate`, 1 by default) is how long it lasts, so a key's time is the sum of the durations
//! before it over the frame rate; the last frame (duration 0 by the exporter, or the rest of the
//! animation) is held. Values are relative to the setup pose, in DragonBones' y-down terms, and
//! flipped as the bones are ([`super::dragonbones`]): a translation `(x, y)` keys `(x, −y)`, a
//! rotation `rotate` (degrees) keys `−rotate`, its `skew` the shear y `−skew`; a scale `(x, y)`
//! (default 1) multiplies the setup scale. Consecutive rotations turn the short way round unless
//! the earlier frame's `clockwise` says otherwise (n > 0: at least one turn in y-down's positive
//! sense, n − 1 more full turns; n < 0 the other way). IK frames key `weight` (percent, 100 by
//! default) as the mix and `bendPositive` (true by default).
//!
//! Toward the next frame: `tweenEasing` absent or null holds the value (stepped), 0 is linear,
//! other values ease as DragonBones' runtime eases them — e in [−1, 1] `p + e·(p − p²)`
//! (quadratic in or out), e > 1 the linear blend by e − 1 of `(1 − cos πp)/2` — and `curve`
//! (`[x1, y1, x2, y2]`, the segment scaled to the unit square) is a cubic Bezier. The clip
//! model's curves are linear, stepped and Bezier, and its Bezier is sampled at tenths as Spine's
//! runtime samples it: the quadratic eases are written as the Bezier they are, the cosine one as
//! the nearest cubic, and each such segment is then within about 1 % of its change of
//! DragonBones' own curve; one warning line says when a file has them.

use ikarus::character::{
    BoneKey, BoneProperty, BoneTimeline, Clip, ConstraintKeys, ConstraintTimeline, IkKey, IkSettings, Interpolation,
};
use serde::{Deserialize, Deserializer};

use super::clips::unit_bezier;
use crate::error::Error;
use crate::names::Quoted;

/// One animation as written.
#[derive(Deserialize)]
pub(super) struct AnimationJson {
    pub name: String,
    /// In frames.
    #[serde(default)]
    duration: f64,
    #[serde(default)]
    bone: Vec<BoneTimelinesJson>,
    #[serde(default)]
    ik: Vec<IkTimelineJson>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct BoneTimelinesJson {
    name: String,
    #[serde(default)]
    translate_frame: Vec<FrameJson>,
    #[serde(default)]
    rotate_frame: Vec<FrameJson>,
    #[serde(default)]
    scale_frame: Vec<FrameJson>,
}

#[derive(Deserialize)]
struct IkTimelineJson {
    name: String,
    #[serde(default)]
    frame: Vec<FrameJson>,
}

/// A frame of any timeline read here (the fields of the others are ignored).
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct FrameJson {
    #[serde(default = "super::one")]
    duration: f64,
    #[serde(default)]
    tween_easing: Option<f64>,
    #[serde(default)]
    curve: Option<Vec<f64>>,
    x: Option<f64>,
    y: Option<f64>,
    rotate: Option<f64>,
    skew: Option<f64>,
    #[serde(default)]
    clockwise: f64,
    #[serde(default, deserialize_with = "some_flag")]
    bend_positive: Option<bool>,
    weight: Option<f64>,
}

fn some_flag<'de, D: Deserializer<'de>>(d: D) -> Result<Option<bool>, D::Error> {
    super::flag(d).map(Some)
}

/// What the timelines' names resolve to, and the frame rate.
pub(super) struct Context<'a> {
    pub bones: &'a std::collections::HashMap<String, usize>,
    /// The IK constraints' names to indices (the first of a name listed twice).
    pub constraints: &'a std::collections::HashMap<&'a str, usize>,
    pub frame_rate: f64,
}

/// What reading the animations found beyond the clips: frames whose easing is approximated,
/// instant changes read as the next frame.
#[derive(Default)]
pub(super) struct Notes {
    pub approximated: usize,
    pub instant: usize,
}

/// The clip of animation `i`.
pub(super) fn clip(i: usize, a: &AnimationJson, cx: &Context<'_>, notes: &mut Notes) -> Result<Clip, Error> {
    let at = format!("armature[0].animation[{i}] ({:?})", Quoted(&a.name));
    let mut bones = Vec::new();
    let mut latest = 0.0f64;
    for (j, t) in a.bone.iter().enumerate() {
        let here = format!("{at}.bone[{j}] ({:?})", Quoted(&t.name));
        let bone = super::bone(cx.bones, &t.name, &format!("{here}.name"))?;
        let mut push = |property, frames: &[FrameJson], kind: &str, value: &dyn Fn(usize, &FrameJson) -> [f64; 2]| {
            let keys: Vec<BoneKey> = keys(frames, &format!("{here}.{kind}"), cx.frame_rate, notes, value)?
                .into_iter()
                .map(|(_, k)| k)
                .collect();
            latest = keys.iter().map(|k| k.time).fold(latest, f64::max);
            bones.push(BoneTimeline { bone, property, keys });
            Ok::<(), Error>(())
        };
        if !t.translate_frame.is_empty() {
            push(BoneProperty::Translate, &t.translate_frame, "translateFrame", &|_, f| {
                [f.x.unwrap_or(0.0), -f.y.unwrap_or(0.0)]
            })?;
        }
        if !t.rotate_frame.is_empty() {
            let turns = unwrapped(&t.rotate_frame);
            push(BoneProperty::Rotate, &t.rotate_frame, "rotateFrame", &|k, _| [-turns[k].to_radians(), 0.0])?;
            if t.rotate_frame.iter().any(|f| f.skew.is_some()) {
                push(BoneProperty::ShearY, &t.rotate_frame, "rotateFrame", &|_, f| {
                    [-f.skew.unwrap_or(0.0).to_radians(), 0.0]
                })?;
            }
        }
        if !t.scale_frame.is_empty() {
            push(BoneProperty::Scale, &t.scale_frame, "scaleFrame", &|_, f| [f.x.unwrap_or(1.0), f.y.unwrap_or(1.0)])?;
        }
    }
    let mut constraints = Vec::new();
    for (j, t) in a.ik.iter().enumerate() {
        let here = format!("{at}.ik[{j}] ({:?})", Quoted(&t.name));
        let constraint = cx.constraints.get(t.name.as_str()).copied().ok_or_else(|| {
            Error::input(format!("{here}.name = {:?}: no IK constraint of that name", Quoted(&t.name)))
        })?;
        let path = format!("{here}.frame");
        let read = keys(&t.frame, &path, cx.frame_rate, notes, &|_, f| [f.weight.unwrap_or(100.0) / 100.0, 0.0])?;
        let mut out = Vec::with_capacity(read.len());
        for (k, key) in read {
            let mix = key.values[0];
            if !(0.0..=1.0).contains(&mix) {
                return Err(Error::input(format!("{path}[{k}].weight = {}: must be within 0 and 100", mix * 100.0)));
            }
            let bend_positive = t.frame[k].bend_positive.unwrap_or(true);
            let settings = IkSettings { mix, bend_positive, ..IkSettings::default() };
            latest = latest.max(key.time);
            out.push(IkKey { time: key.time, settings, curves: key.curves });
        }
        constraints.push(ConstraintTimeline { constraint, keys: ConstraintKeys::Ik(out) });
    }
    let duration = (a.duration / cx.frame_rate).max(latest);
    Ok(Clip { name: a.name.clone(), duration, bones, constraints })
}

/// Each rotation in degrees, after the one before it: the short way round, or as the earlier
/// frame's `clockwise` says.
fn unwrapped(frames: &[FrameJson]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(frames.len());
    for (k, f) in frames.iter().enumerate() {
        let r = f.rotate.unwrap_or(0.0);
        let r = match out.last() {
            None => r,
            Some(&prev) => {
                let cw = frames[k - 1].clockwise;
                let short = prev + (r - prev + 180.0).rem_euclid(360.0) - 180.0;
                if cw > 0.0 {
                    let up = prev + (r - prev).rem_euclid(360.0);
                    up + 360.0 * (cw - 1.0)
                } else if cw < 0.0 {
                    let down = prev - (prev - r).rem_euclid(360.0);
                    down - 360.0 * (-cw - 1.0)
                } else {
                    short
                }
            }
        };
        out.push(r);
    }
    out
}

/// The keys of one timeline's frames, each with its frame's index: times from the durations,
/// values by `value` (of the frame's index and the frame), curves from each frame's easing
/// toward the next.
fn keys(
    frames: &[FrameJson],
    path: &str,
    rate: f64,
    notes: &mut Notes,
    value: &dyn Fn(usize, &FrameJson) -> [f64; 2],
) -> Result<Vec<(usize, BoneKey)>, Error> {
    let mut out = Vec::with_capacity(frames.len());
    let mut start = 0.0;
    for (k, f) in frames.iter().enumerate() {
        if !(f.duration >= 0.0 && f.duration.is_finite()) {
            return Err(Error::input(format!(
                "{path}[{k}].duration = {}: must be a number of frames, at least 0",
                f.duration
            )));
        }
        let time = start / rate;
        start += f.duration;
        let values = value(k, f);
        if let Some(next) = frames.get(k + 1) {
            if f.duration == 0.0 {
                // An instant change: the next frame starts at the same time and wins.
                notes.instant += 1;
                continue;
            }
            let there = value(k + 1, next);
            let curves = easing(f, &format!("{path}[{k}]"), notes)?;
            let curves = [0, 1].map(|c| match curves {
                Ease::Unit(p) => unit_bezier([time, values[c]], [start / rate, there[c]], p),
                Ease::Exact(i) => i,
            });
            out.push((k, BoneKey { time, values, curves }));
        } else {
            out.push((k, BoneKey { time, values, curves: [Interpolation::Linear; 2] }));
        }
    }
    Ok(out)
}

/// A frame's easing toward the next: an interpolation of the model, or a Bezier in the unit
/// square.
#[derive(Clone, Copy)]
enum Ease {
    Exact(Interpolation),
    Unit([f64; 4]),
}

/// The easing of frame `f` (at `path`).
fn easing(f: &FrameJson, path: &str, notes: &mut Notes) -> Result<Ease, Error> {
    if let Some(c) = &f.curve {
        let [x1, y1, x2, y2] = <[f64; 4]>::try_from(c.as_slice()).map_err(|_| {
            Error::input(format!(
                "{path}.curve: {} numbers, expected 4 ([x1, y1, x2, y2] of one cubic Bezier)",
                c.len()
            ))
        })?;
        notes.approximated += 1;
        return Ok(Ease::Unit([x1, y1, x2, y2]));
    }
    Ok(match f.tween_easing {
        None => Ease::Exact(Interpolation::Stepped),
        Some(0.0) => Ease::Exact(Interpolation::Linear),
        Some(e) if !e.is_finite() => {
            return Err(Error::input(format!("{path}.tweenEasing = {e}: must be a finite number")));
        }
        Some(e) => {
            notes.approximated += 1;
            if e <= 1.0 {
                // p + e·(p − p²): a quadratic, exactly this cubic with x at thirds.
                Ease::Unit([1.0 / 3.0, (1.0 + e) / 3.0, 2.0 / 3.0, (2.0 + e) / 3.0])
            } else {
                // The blend by e − 1 of (1 − cos πp)/2, its cosine as the cubic 3p² − 2p³.
                let w = e - 1.0;
                Ease::Unit([1.0 / 3.0, (1.0 - w) / 3.0, 2.0 / 3.0, w + (1.0 - w) * 2.0 / 3.0])
            }
        }
    })
}

#[cfg(test)]
#[path = "dragonbones_tests.rs"]
mod tests;
