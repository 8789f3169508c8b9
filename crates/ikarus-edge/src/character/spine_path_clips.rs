//! A Spine animation's path constraint timelines: `path` = `{constraint: {position: [key…],
//! spacing: [key…], mix: [key…]}}`. 4.x keys: `time` (0), `value` (position, spacing; 0),
//! `mixRotate` (1), `mixX` (1), `mixY` (`mixX`'s), `curve` (`"stepped"` or
//! `[cx1, cy1, cx2, cy2]` per channel); 3.8 keys: `position`, `spacing`, `rotateMix`,
//! `translateMix`, and one normalised curve (`curve`, `c2`, `c3`, `c4`) for every channel.
//! The deform timelines of the paths the constraints follow become timelines of those
//! constraints ([`super::spine_deform`]).

use std::collections::HashMap;

use ikarus::character::{ChannelKey, ConstraintKeys, ConstraintTimeline, Interpolation, MAX_CHANNELS};
use serde_json::Value;

use super::spine_deform::SkinDeform;
use super::spine_slots::number;
use crate::error::Error;
use crate::names::Quoted;

/// What a path timeline keys: its kind, its channels' fields (4.x, 3.8) and defaults.
struct Kind {
    make: fn(Vec<ChannelKey>) -> ConstraintKeys,
    fields: &'static [(&'static str, &'static str, f64)],
}

const POSITION: Kind = Kind { make: ConstraintKeys::PathPosition, fields: &[("value", "position", 0.0)] };
const SPACING: Kind = Kind { make: ConstraintKeys::PathSpacing, fields: &[("value", "spacing", 0.0)] };
const MIX: Kind = Kind {
    make: ConstraintKeys::PathMix,
    fields: &[("mixRotate", "rotateMix", 1.0), ("mixX", "translateMix", 1.0), ("mixY", "translateMix", f64::NAN)],
};

/// The path timelines of animation `anim` (its JSON, at `at`): `paths` maps the path
/// constraints' names to their indices in the character's list, `targets` gives per path
/// constraint its index, its slot and the attachment name it follows, `deforms` the
/// animation's deform timelines of every skin (each applies only while the pose follows its
/// skin's attachment).
pub(super) fn read(
    anim: &Value,
    at: &str,
    paths: &HashMap<&str, usize>,
    targets: &[(usize, usize, Option<&str>)],
    deforms: &[SkinDeform],
    legacy: bool,
) -> Result<Vec<ConstraintTimeline>, Error> {
    let mut out = Vec::new();
    if let Some(by_name) = anim.get("path").and_then(Value::as_object) {
        for (name, timelines) in by_name {
            let at = format!("{at}.path.{:?}", Quoted(name));
            let &constraint = paths
                .get(name.as_str())
                .ok_or_else(|| Error::input(format!("{at}: no path constraint of that name")))?;
            for (field, kind) in [("position", POSITION), ("spacing", SPACING), ("mix", MIX)] {
                let Some(keys) = timelines.get(field) else { continue };
                let keys = channel_keys(keys, &kind, legacy, &format!("{at}.{field}"))?;
                out.push(ConstraintTimeline { constraint, keys: (kind.make)(keys) });
            }
        }
    }
    for d in deforms {
        for &(constraint, slot, attachment) in targets {
            if slot == d.deform.slot && attachment == Some(d.attachment.as_str()) {
                let keys = ConstraintKeys::PathDeform { skin: d.source, keys: d.deform.keys.clone() };
                out.push(ConstraintTimeline { constraint, keys });
            }
        }
    }
    Ok(out)
}

/// The keys of one numeric path timeline.
fn channel_keys(keys: &Value, kind: &Kind, legacy: bool, at: &str) -> Result<Vec<ChannelKey>, Error> {
    let keys = keys.as_array().ok_or_else(|| Error::input(format!("{at}: expected a list of keys")))?;
    let mut out: Vec<ChannelKey> = Vec::with_capacity(keys.len());
    for (i, k) in keys.iter().enumerate() {
        let at = format!("{at}[{i}]");
        let time = number(k.get("time"), 0.0, &format!("{at}.time"))?;
        let mut values = [0.0; MAX_CHANNELS];
        for (ch, &(new, old, default)) in kind.fields.iter().enumerate() {
            let field = if legacy { old } else { new };
            // mixY defaults to the key's mixX.
            let default = if default.is_nan() { values[ch - 1] } else { default };
            values[ch] = number(k.get(field), default, &format!("{at}.{field}"))?;
        }
        if kind.fields.len() == 3 {
            for (ch, (field, _, _)) in kind.fields.iter().enumerate() {
                if !(-1.0..=1.0).contains(&values[ch]) {
                    return Err(Error::input(format!("{at}.{field} = {}: must be within −1 and 1", values[ch])));
                }
            }
        }
        out.push(ChannelKey { time, values, curves: [Interpolation::Linear; MAX_CHANNELS] });
    }
    for i in 0..out.len() {
        let Some(next) = out.get(i + 1).copied() else { break };
        let at = format!("{at}[{i}].curve");
        let n = kind.fields.len();
        let this = out[i];
        curves(&keys[i], (this.time, &this.values[..n]), (next.time, &next.values[..n]), legacy, &at)
            .map(|c| out[i].curves[..n].copy_from_slice(&c))?;
    }
    Ok(out)
}

/// Key `k`'s curves toward the next key, one per channel: `from` and `to` are the two keys'
/// times and values. 4.x: absent (linear), `"stepped"`, or `[cx1, cy1, cx2, cy2]` per channel in
/// absolute units; 3.8: `curve`, `c2`, `c3`, `c4` in the unit square, the same for every channel.
pub(super) fn curves(
    k: &Value,
    (t0, from): (f64, &[f64]),
    (t1, to): (f64, &[f64]),
    legacy: bool,
    at: &str,
) -> Result<Vec<Interpolation>, Error> {
    let n = from.len();
    let mut out = vec![Interpolation::Linear; n];
    match k.get("curve") {
        None => {}
        Some(Value::String(s)) if s == "stepped" => out.fill(Interpolation::Stepped),
        Some(Value::Array(p)) if !legacy && p.len() == 4 * n => {
            let p = p
                .iter()
                .enumerate()
                .map(|(j, x)| number(Some(x), 0.0, &format!("{at}[{j}]")))
                .collect::<Result<Vec<_>, _>>()?;
            for (ch, c) in out.iter_mut().enumerate() {
                let q = &p[4 * ch..4 * ch + 4];
                *c = Interpolation::Bezier { c1: [q[0], q[1]], c2: [q[2], q[3]] };
            }
        }
        Some(c @ Value::Number(_)) if legacy => {
            let q = [
                number(Some(c), 0.0, at)?,
                number(k.get("c2"), 0.0, &format!("{at}.c2"))?,
                number(k.get("c3"), 1.0, &format!("{at}.c3"))?,
                number(k.get("c4"), 1.0, &format!("{at}.c4"))?,
            ];
            for (ch, c) in out.iter_mut().enumerate() {
                *c = super::clips::unit_bezier([t0, from[ch]], [t1, to[ch]], q);
            }
        }
        Some(other) => {
            return Err(Error::input(format!(
                "{at} = {other}: expected \"stepped\" or {} numbers ([cx1, cy1, cx2, cy2] per channel)",
                4 * n
            )));
        }
    }
    Ok(out)
}
