//! Deform timelines of path attachments (Spine's `attachments.SKIN.SLOT.ATTACHMENT.deform`):
//! keys of offsets added to the attachment's vertex coordinates (for a weighted path, to each
//! bone's point of each vertex), interpolated between keys by one curve.
//!
//! As the runtime does: key times and offsets are 32-bit floats; before the first key there is
//! no deform (the setup vertices), after the last key the last key's offsets hold; between two
//! keys each offset goes `a + (b − a)·p`, `p` the key's curve from 0 to 1 at the time (a Bézier
//! sampled at tenths, as every timeline's).

use super::super::Interpolation;
use super::super::timeline;

/// One key of a deform timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct DeformKey {
    /// Seconds from the clip's start (`time`, default 0).
    pub time: f64,
    /// Where `offsets` start among the path's coordinates (`offset`, default 0).
    pub start: usize,
    /// The offsets, two per point (x, y), from `start` on (the file's `vertices`); every other
    /// coordinate's offset is 0 (a key without `vertices` is all zeros).
    pub offsets: Vec<f64>,
    /// Toward the next key: from 0 to 1 (`curve`; linear when absent).
    pub curve: Interpolation,
}

/// A clip's deform timeline of the path a slot shows.
#[derive(Debug, Clone, PartialEq)]
pub struct PathDeform {
    /// The slot's index in the file's `slots`.
    pub slot: usize,
    /// The keys, in time order.
    pub keys: Vec<DeformKey>,
}

/// A value rounded to the runtime's `f32`.
fn f32ed(v: f64) -> f64 {
    v as f32 as f64
}

impl PathDeform {
    /// The offsets at `time` into `out` (cleared first); `false` (and `out` empty) before the
    /// first key.
    pub fn at(&self, time: f64, out: &mut Vec<f64>) -> bool {
        at(&self.keys, time, out)
    }
}

/// Key `k`'s offset of coordinate `j`.
fn offset(k: &DeformKey, j: usize) -> f64 {
    j.checked_sub(k.start).and_then(|i| k.offsets.get(i)).map_or(0.0, |&v| f32ed(v))
}

/// How many coordinates key `k` reaches.
fn reach(k: &DeformKey) -> usize {
    k.start.saturating_add(k.offsets.len())
}

/// The offsets of `keys` at `time` into `out` (cleared first; coordinates past its end have
/// none); `false` (and `out` empty) before the first key.
pub(crate) fn at(keys: &[DeformKey], time: f64, out: &mut Vec<f64>) -> bool {
    out.clear();
    let i = keys.partition_point(|k| f32ed(k.time) <= time);
    let Some(i) = i.checked_sub(1) else { return false };
    let k = &keys[i];
    let Some(next) = keys.get(i + 1) else {
        out.extend((0..reach(k)).map(|j| offset(k, j)));
        return true;
    };
    let p = timeline::segment(k.curve, (f32ed(k.time), 0.0), (f32ed(next.time), 1.0), time);
    out.extend((0..reach(k).max(reach(next))).map(|j| {
        let (a, b) = (offset(k, j), offset(next, j));
        a + (b - a) * p
    }));
    true
}
