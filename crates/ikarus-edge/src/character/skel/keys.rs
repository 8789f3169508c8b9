//! What the timelines of several kinds share in a `.skel`: a key's curve, a sequence key's mode.

use serde_json::{Map, Value};

use super::reader::Reader;
use super::skeleton::pick;
use crate::error::Error;

const SEQUENCE_MODES: [&str; 7] = ["hold", "once", "loop", "pingpong", "onceReverse", "loopReverse", "pingpongReverse"];

/// The curve byte of a key, and its Bezier handles.
pub(super) fn curve(r: &mut Reader<'_>, key: &mut Map<String, Value>, channels: usize) -> Result<(), Error> {
    let start = r.pos();
    match r.byte("curve")? {
        0 => {}
        1 => {
            key.insert("curve".into(), Value::from("stepped"));
        }
        2 => {
            key.insert("curve".into(), Value::Array(r.floats("curve", channels * 4)?));
        }
        b => return Err(r.fail_at(start, "curve", &format!("an unknown curve type (got {b})"))),
    }
    Ok(())
}

/// A sequence key's mode name.
pub(super) fn sequence_mode(r: &Reader<'_>, start: usize, mode: usize) -> Result<Value, Error> {
    pick(r, start, "mode", &SEQUENCE_MODES, mode)
}
