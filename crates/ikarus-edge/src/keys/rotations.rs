//! Bones turned by hand in a character's keys (forward kinematics): `"rotations": {"BONE":
//! [{"time": 0.2, "angle_deg": 30, "ease": "sine"}, …]}`.
//!
//! A key's `angle_deg` is the bone's local rotation, degrees, as the setup pose's `rotation` of a
//! Spine file gives it (relative to its parent, counter-clockwise in the file's y-up frame): it
//! replaces the rotation the clip (or the setup pose) gives the bone at that time, it is not
//! added to it. Between keys the angle is eased as a track's target is (`ease`, `k1`, `k2`, the
//! same rule and default), before the first key and after the last it holds the key. The turn
//! is applied after the clip and before the targets and the constraints, as Spine applies an
//! animation's rotate timeline before its constraints: an IK constraint on the bone overrides it
//! by its mix. Replacing (rather than adding) is what a drag on the page means: the bone stays at
//! the angle it was put at whatever the clip does there, and the Spine export writes the key as
//! the rotate timeline's value, `angle_deg` minus the setup pose's rotation.

use std::collections::BTreeMap;

use ikarus::EaseKind;
use ikarus::motion::KeyTrack;
use ikarus::number::Num;
use serde::Deserialize;

use super::{KeyedBone, key_ease, key_frames};
use crate::error::Error;

/// One rotation key: the bone's local rotation at `time`, and the ease from this key to the next.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationKeyReq {
    /// When the bone is at `angle_deg`, seconds: 0 for a bone's first key, on a frame, increasing.
    pub time: f64,
    /// The bone's local rotation, degrees, relative to its parent (replacing the clip's).
    pub angle_deg: f64,
    /// `linear`, `sine` (the default), `parent` or `smoothstep`.
    #[serde(default)]
    pub ease: Option<EaseKind>,
    /// The `parent` ease's end of acceleration (see `k2`).
    #[serde(default)]
    pub k1: Option<f64>,
    /// The `parent` ease's start of deceleration (with `k1`: `0 ≤ k1 ≤ k2 ≤ 1`).
    #[serde(default)]
    pub k2: Option<f64>,
}

/// The rotation tracks (`bone` finds a bone by name, its problem after the field): per bone a
/// track of one value, the angle in degrees, its knots on the keys' frames; `last` raised to
/// their last key's frame. Every problem names `keys.rotations.BONE[i].…` and the value.
pub(super) fn check(
    rotations: &BTreeMap<String, Vec<RotationKeyReq>>,
    bone: &dyn Fn(&str, &str) -> Result<usize, Error>,
    fps: f64,
    last: &mut usize,
) -> Result<Vec<KeyedBone>, Error> {
    let mut out = Vec::with_capacity(rotations.len());
    for (name, keys) in rotations {
        let field = format!("keys.rotations.{name}");
        let index = bone(&field, name)?;
        let frames = key_frames(&field, keys.iter().map(|k| k.time), fps)?;
        *last = (*last).max(*frames.last().expect("a track has a key"));
        let mut values = Vec::with_capacity(keys.len());
        let mut eases = Vec::with_capacity(keys.len());
        for (i, k) in keys.iter().enumerate() {
            if !k.angle_deg.is_finite() {
                return Err(Error::input(format!(
                    "{field}[{i}].angle_deg = {}: must be a finite number",
                    Num(k.angle_deg)
                )));
            }
            values.push(k.angle_deg);
            eases.push(key_ease(&format!("{field}[{i}]"), k.ease, k.k1, k.k2)?);
        }
        let times = frames.iter().map(|&f| f as f64 / fps).collect();
        let track = KeyTrack::new(1, times, values, eases).map_err(|e| Error::input(format!("{field}: {e}")))?;
        out.push(KeyedBone { bone: index, track, oriented: false });
    }
    Ok(out)
}
