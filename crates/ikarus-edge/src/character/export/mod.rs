//! A character's motion written back as a Spine animation: the input file's own text with one
//! animation added under `animations`.
//!
//! Every top-level field and every animation already in the file is copied as it was written
//! (its text, byte for byte, in its order; only the whitespace between top-level fields is
//! ours). The new animation comes in one of two forms ([`Form`]):
//!
//! - [`Form::Editable`] (the default, `editable`): what the animator keyed, as a Spine
//!   animator keys it. Under the runtime's rules the IK constraints stay on; the clip under the
//!   keys is carried (its bone and IK timelines copied, looped as the motion loops it), the
//!   target bones get `translate` keys at the key times with Bézier curves fitted to ikarus's
//!   tracks, and bend keys become `bendPositive` keys of the constraints' IK timelines. Under
//!   ikarus's solver every bone the solve moves gets fitted keys at the key times (and the
//!   clip's), and every constraint of every kind is keyed to mix 0 (the solver replaces the IK
//!   ones; the keys hold what the others did).
//! - [`Form::Bake`] (`bake`): every bone at every frame, linear keys, with bisection keys
//!   where a line strays, and every constraint (IK, transform, path, physics) at mix 0.
//!
//! Physics: the bake is made of the motion played as a game plays it
//! ([`super::motion::Motion::play_at`]), so its keys hold what the physics did. The editable
//! form is fitted to the motion without physics; under the runtime's rules its physics
//! constraints stay on and play on top of the keys in a game as they play on the motion's
//! frames (keyed to mix 0 when the motion has them off); under ikarus's solver they are
//! switched off with the rest, and the export is the motion without physics.
//!
//! Either way every key time is written as the 32-bit float Spine's runtime reads
//! ([`written_time`]), the keys are posed at that time, and a fit is accepted when the pose the
//! keys give stays within [`tolerance`] of the motion's at every point checked. The keys added
//! beyond the key times (or the frames) are bounded per frame (4 per timeline for a fit, 16 over
//! the whole bake), so the memory an export takes is bounded by the motion's frame caps.

mod bake;
mod clip_copy;
mod curves;
mod editable;
mod ik_keys;
mod sampler;

use ikarus::character::Posed;
use serde_json::Value;
use serde_json::value::RawValue;

use super::Format;
use super::clips::Ordered;
use super::motion::Motion;
use crate::error::Error;
use crate::pose::{PoseAsk, pose_into};

/// The largest distance, in the file's units, between a bone's world origin or tip as the keys
/// pose it and as the motion poses it that a fit is left with, for a character up to
/// 1,000 units across ([`RELATIVE_TOLERANCE`] beyond): the promise is 1e-2, this is half for
/// margin.
pub const TOLERANCE: f64 = 5e-3;

/// The tolerance as a fraction of the character's size (the diagonal of its setup pose's
/// bounding box) for characters over 1,000 units across: a character scaled by 10⁶ is fitted
/// as closely, relative to its size, as one of 1,000 units, instead of to 5e-3 absolute (which
/// its keys' 32-bit floats cannot hold, and which refined every interval).
pub const RELATIVE_TOLERANCE: f64 = 5e-6;

/// The default animation name.
pub const DEFAULT_NAME: &str = "ikarus";

/// Which form the new animation takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Form {
    /// What the animator keyed, with fitted curves and the constraints on (Spine's rules).
    #[default]
    Editable,
    /// Every bone keyed at every frame, the constraints at mix 0 (`--bake`).
    Bake,
}

impl Form {
    /// The form a `bake` switch asks for (`--bake` on the command line, `"bake": true` in a
    /// request): [`Form::Bake`] when set, else [`Form::Editable`].
    #[must_use]
    pub fn asked(bake: bool) -> Self {
        if bake { Form::Bake } else { Form::Editable }
    }
}

/// What to export: the new animation's name and form.
#[derive(Debug, Clone, Copy)]
pub struct Export<'a> {
    /// The new animation's name.
    pub name: &'a str,
    /// Its form.
    pub form: Form,
}

/// `text` (the Spine file `motion` was loaded from) with the motion added as the animation
/// `export` names, in its form. Refusals are one line naming the field.
pub fn spine(motion: &Motion<'_>, text: &str, export: &Export<'_>) -> Result<String, Error> {
    let loaded = motion.loaded;
    let name = export.name;
    if loaded.format != Format::Spine {
        return Err(Error::input(format!(
            "format spine: the Spine export takes a Spine file, and this is a {} file",
            loaded.format.name()
        )));
    }
    if name.is_empty() {
        return Err(Error::input("animation name: must not be empty"));
    }
    let text = text.trim_start_matches('\u{feff}');
    let top: Ordered<Box<RawValue>> =
        serde_json::from_str(text).map_err(|e| Error::input(format!("malformed JSON: {e}")))?;
    let mut animations: Ordered<Box<RawValue>> = match top.0.iter().find(|(k, _)| k == "animations") {
        Some((_, raw)) => serde_json::from_str(raw.get()).map_err(|e| Error::input(format!("animations: {e}")))?,
        None => Ordered::default(),
    };
    if animations.0.iter().any(|(k, _)| k == name) {
        return Err(Error::input(format!("animation name {name:?}: the file already has an animation of that name")));
    }
    let legacy = loaded.version.starts_with("3.");
    let tolerance = tolerance(motion)?;
    let animation = match export.form {
        Form::Bake => bake::animation(motion, tolerance, legacy)?,
        Form::Editable => {
            let clip = match motion.clip() {
                Some(clip) => Some(clip_json(&animations, clip)?),
                None => None,
            };
            editable::animation(motion, clip.as_ref(), tolerance, legacy)?
        }
    };
    let raw =
        RawValue::from_string(animation.to_string()).map_err(|e| Error::input(format!("cannot write JSON: {e}")))?;
    animations.0.push((name.to_owned(), raw));
    let animations = RawValue::from_string(object(&animations, "    "))
        .map_err(|e| Error::input(format!("cannot write JSON: {e}")))?;
    let mut out = top;
    match out.0.iter_mut().find(|(k, _)| k == "animations") {
        Some((_, v)) => *v = animations,
        None => out.0.push(("animations".to_owned(), animations)),
    }
    let mut text = object(&out, "  ");
    text.push('\n');
    Ok(text)
}

/// The clip `name`'s JSON, as the file has it (the last of that name, as the reader takes it).
fn clip_json(animations: &Ordered<Box<RawValue>>, name: &str) -> Result<Value, Error> {
    match animations.0.iter().rev().find(|(k, _)| k == name) {
        Some((_, raw)) => serde_json::from_str(raw.get()).map_err(|e| Error::input(format!("animations.{name}: {e}"))),
        None => Err(Error::input(format!("animation {name:?}: not in the file"))),
    }
}

/// `{` the entries, one per line indented by `indent`, `}`.
fn object(entries: &Ordered<Box<RawValue>>, indent: &str) -> String {
    let close = &indent[..indent.len().saturating_sub(2)];
    let body: Vec<String> =
        entries.0.iter().map(|(k, v)| format!("{indent}{}: {}", Value::String(k.clone()), v.get())).collect();
    if body.is_empty() { "{}".to_owned() } else { format!("{{\n{}\n{close}}}", body.join(",\n")) }
}

/// The tolerance of `motion`'s character: [`TOLERANCE`], or [`RELATIVE_TOLERANCE`] of its
/// size, whichever is larger (the size: the diagonal of the box around every bone's origin
/// and tip in the setup pose).
pub fn tolerance(motion: &Motion<'_>) -> Result<f64, Error> {
    let mut setup = Posed::default();
    pose_into(motion.loaded, &PoseAsk::default(), &mut setup)?;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for i in 0..setup.len() {
        for p in [setup.origin(i), setup.tip(i)] {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    Ok(if size.is_finite() { TOLERANCE.max(size * RELATIVE_TOLERANCE) } else { TOLERANCE })
}

/// The 32-bit float nearest `t`, as Spine's runtime reads a key's time, as an `f64` whose
/// shortest decimal is the float's (`0.46666667` for 14/30): what a key's `time` is written as.
#[must_use]
pub fn written_time(t: f64) -> f64 {
    let f = t as f32;
    format!("{f}").parse().unwrap_or(f64::from(f))
}

/// `t` as the runtime reads it: the nearest 32-bit float.
#[must_use]
pub fn read_time(t: f64) -> f64 {
    f64::from(t as f32)
}
