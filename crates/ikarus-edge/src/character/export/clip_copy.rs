//! The clip under a keyed course, carried into the editable export: its bone and IK timelines
//! copied key for key (values and curves as the file has them), repeated as the motion loops
//! the clip, and its bend keys merged into the IK timelines.
//!
//! Looping: the motion poses the clip at `time mod length` once past its length, so cycle r
//! (r ≥ 1) is every key shifted by r · length (Spine 4's Bézier control times shifted too;
//! 3.8's curves are relative to their segment). Between cycles the motion holds each
//! timeline's last key until the next cycle starts and then jumps to its first: the last key
//! of a cycle is made `stepped` where its time is before the clip's end; a timeline whose first
//! key is after 0 gets a key of the setup value at each cycle's start (the runtime gives the
//! setup value before a timeline's first key); a last key at the clip's end equal to the next
//! cycle's first is written once. Other timelines of the clip (slots, events, draw order,
//! deform, other constraints') are copied once, as they are.

use serde_json::{Map, Value, json};

use super::written_time;
use crate::error::Error;

/// The most keys the copied clip may hold (its keys × the cycles the motion runs it for).
pub const MAX_COPIED_KEYS: usize = 1 << 20;

/// A key's time (0 when absent).
pub(super) fn time_of(key: &Value) -> f64 {
    key.get("time").and_then(Value::as_f64).unwrap_or(0.0)
}

/// How many cycles of a clip of `length` seconds a motion of `duration` runs, and the refusal
/// when `keys` keys in that many cycles would pass [`MAX_COPIED_KEYS`].
pub(super) fn cycles(length: f64, duration: f64, keys: usize, clip: &str) -> Result<usize, Error> {
    let cycles = if length > 0.0 && duration > length { (duration / length).ceil() } else { 1.0 };
    if cycles * keys as f64 > MAX_COPIED_KEYS as f64 {
        return Err(Error::input(format!(
            "animation {clip:?}: its {keys} keys over {cycles} cycles of the motion are more than the export's cap of {MAX_COPIED_KEYS} keys"
        )));
    }
    Ok(cycles as usize)
}

/// The number of keys of every timeline of `timelines` (an object of timeline name → keys, or
/// of name → object of those).
pub(super) fn count_keys(value: &Value) -> usize {
    match value {
        Value::Array(keys) => keys.len(),
        Value::Object(map) => map.values().map(count_keys).sum(),
        _ => 0,
    }
}

/// `keys` over `cycles` cycles of `length` seconds; `setup` is the key of the setup value for
/// a timeline whose first key is after 0.
pub(super) fn looped(keys: &[Value], cycles: usize, length: f64, legacy: bool, setup: &Value) -> Vec<Value> {
    let mut out: Vec<Value> = keys.to_vec();
    if keys.is_empty() || cycles <= 1 {
        return out;
    }
    let first = time_of(&keys[0]);
    let last = time_of(&keys[keys.len() - 1]);
    for r in 1..cycles {
        let shift = r as f64 * length;
        if last < length {
            if let Some(k) = out.last_mut().and_then(Value::as_object_mut) {
                k.insert("curve".to_owned(), json!("stepped"));
            }
        }
        // Where the cycle before ends with a key at the clip's end, the two cycles meet at one
        // time: the same values once (the key dropped), else a jump, placed where the motion
        // has it ([`super::super::motion::Motion`] poses the clip at its end at exactly its
        // length, and at its start at every later multiple of it): just after the first loop
        // point, just before the later ones.
        let meets = last >= length;
        let mut after = false;
        if first <= 0.0 && meets && same_values(&keys[keys.len() - 1], &keys[0]) {
            out.pop();
        } else if meets && r == 1 {
            after = true;
        } else if meets {
            just_before(&mut out, shift, legacy);
        }
        let start = out.len();
        if first > 0.0 {
            let mut k = setup.clone();
            k["time"] = json!(written_time(shift));
            k["curve"] = json!("stepped");
            out.push(k);
        }
        for key in keys {
            out.push(shifted(key, shift, legacy));
        }
        if after {
            just_after(&mut out[start], shift);
        }
    }
    out
}

/// Moves `key` to the smallest 32-bit time after `time`, and its own curve's control times (a
/// Spine 4 key's) no earlier than that.
fn just_after(key: &mut Value, time: f64) {
    let after = written_time(f64::from(f32::from_bits((time as f32).to_bits() + 1)));
    key["time"] = json!(after);
    if let Some(Value::Array(curve)) = key.get_mut("curve") {
        for (i, c) in curve.iter_mut().enumerate() {
            if let (0, Some(t)) = (i % 2, c.as_f64()) {
                *c = json!(t.max(after));
            }
        }
    }
}

/// Moves the last key of `out` to the largest 32-bit time before `time`, and the control times
/// of the curve that ends at it (a Spine 4 key's, on the key before) no later than that.
fn just_before(out: &mut [Value], time: f64, legacy: bool) {
    let at = time as f32;
    if at <= 0.0 {
        return;
    }
    let before = written_time(f64::from(f32::from_bits(at.to_bits() - 1)));
    let n = out.len();
    if let Some(last) = out.last_mut() {
        last["time"] = json!(before);
    }
    if legacy || n < 2 {
        return;
    }
    if let Some(Value::Array(curve)) = out[n - 2].get_mut("curve") {
        for (i, c) in curve.iter_mut().enumerate() {
            if let (0, Some(t)) = (i % 2, c.as_f64()) {
                *c = json!(t.min(before));
            }
        }
    }
}

/// Whether two keys hold the same values (every field but `time` and the curve's).
fn same_values(a: &Value, b: &Value) -> bool {
    let strip = |v: &Value| -> Map<String, Value> {
        let mut m = v.as_object().cloned().unwrap_or_default();
        for f in ["time", "curve", "c2", "c3", "c4"] {
            m.remove(f);
        }
        m
    };
    strip(a) == strip(b)
}

/// `key` moved `shift` seconds later (its Spine 4 curve's control times too).
fn shifted(key: &Value, shift: f64, legacy: bool) -> Value {
    let mut k = key.clone();
    k["time"] = json!(written_time(time_of(key) + shift));
    if !legacy {
        if let Some(Value::Array(curve)) = k.get_mut("curve") {
            for (i, c) in curve.iter_mut().enumerate() {
                if let (0, Some(t)) = (i % 2, c.as_f64()) {
                    *c = json!(t + shift);
                }
            }
        }
    }
    k
}

/// The point at parameter `u` of the cubic `q`, and the control points of its two halves.
fn split(q: [f64; 4], u: f64) -> (f64, [f64; 2], [f64; 2]) {
    let l = |a: f64, b: f64| a + (b - a) * u;
    let (q01, q12, q23) = (l(q[0], q[1]), l(q[1], q[2]), l(q[2], q[3]));
    let (q012, q123) = (l(q01, q12), l(q12, q23));
    (l(q012, q123), [q01, q012], [q123, q23])
}

/// Inserts into an IK timeline `keys` (Spine 4, or 3.8 when `legacy`) a key at `time` whose
/// settings are `at` (mix, softness, compress, stretch as the motion has them there), unless a
/// key is already at that time; a Spine 4 Bézier segment it falls in is split in two at it (the
/// same curve), so the keys around it play as before. Returns the index of the key at `time`.
pub(super) fn insert_ik_key(keys: &mut Vec<Value>, time: f64, at: &Value, legacy: bool) -> usize {
    let written = written_time(time);
    if let Some(i) = keys.iter().position(|k| written_time(time_of(k)) == written) {
        return i;
    }
    let i = keys.partition_point(|k| time_of(k) < written);
    let mut key = at.clone();
    key["time"] = json!(written);
    if i > 0 && i < keys.len() {
        let (t0, t1) = (time_of(&keys[i - 1]), time_of(&keys[i]));
        let prev = keys[i - 1].clone();
        match prev.get("curve") {
            Some(Value::String(s)) if s == "stepped" => {
                for f in ["mix", "softness"] {
                    key[f] = prev.get(f).cloned().unwrap_or(json!(if f == "mix" { 1.0 } else { 0.0 }));
                }
                key["curve"] = json!("stepped");
            }
            Some(Value::Array(c)) if !legacy && c.len() >= 8 => {
                let c: Vec<f64> = c.iter().map(|v| v.as_f64().unwrap_or(0.0)).collect();
                let (mut left, mut right) = (Vec::with_capacity(8), Vec::with_capacity(8));
                for (ch, field, default) in [(0, "mix", 1.0), (1, "softness", 0.0)] {
                    let v0 = prev.get(field).and_then(Value::as_f64).unwrap_or(default);
                    let v1 = keys[i].get(field).and_then(Value::as_f64).unwrap_or(default);
                    let xs = [t0, c[4 * ch], c[4 * ch + 2], t1];
                    let ys = [v0, c[4 * ch + 1], c[4 * ch + 3], v1];
                    // The parameter where the curve's time is `written` (its time is monotone).
                    let (mut lo, mut hi) = (0.0, 1.0);
                    for _ in 0..60 {
                        let u = (lo + hi) / 2.0;
                        if split(xs, u).0 < written { lo = u } else { hi = u }
                    }
                    let u = (lo + hi) / 2.0;
                    let (x, xl, xr) = split(xs, u);
                    let (y, yl, yr) = split(ys, u);
                    let _ = x;
                    key[field] = json!(y);
                    left.extend([xl[0], yl[0], xl[1], yl[1]]);
                    right.extend([xr[0], yr[0], xr[1], yr[1]]);
                }
                keys[i - 1]["curve"] = json!(left);
                key["curve"] = json!(right);
            }
            _ => {}
        }
    }
    keys.insert(i, key);
    i
}
