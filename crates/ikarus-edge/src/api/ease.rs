//! `POST /api/ease`: an ease curve's progress `s(t)` at evenly spaced times, so that the page
//! draws and plays the library's ease ([`ikarus::Ease::position`]) instead of a copy of its
//! formulas.

use ikarus::EaseKind;
use serde::{Deserialize, Serialize};

use super::fields::ease;
use super::requests::EaseReq;
use super::wire::{Problem, Reply};

/// Most samples of one curve.
pub const MAX_SAMPLES: u32 = 10_001;

/// `POST /api/ease`: `ease` (as a motion's request sends it; default sine) and `samples`, at
/// least 2: the times `t_i = i / (samples − 1)`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseCurveReq {
    #[serde(default)]
    ease: Option<EaseReq>,
    samples: u32,
}

/// The answer: the times and the progress at each, `s[i] = position(t[i])`, from 0 to 1.
#[derive(Debug, Serialize)]
struct EaseCurve {
    t: Vec<f64>,
    s: Vec<f64>,
}

/// The curve of the request `body`.
pub fn curve(req: &EaseCurveReq) -> Result<Reply, Problem> {
    if !(2..=MAX_SAMPLES).contains(&req.samples) {
        return Err(Problem::invalid(format!("samples: {}, must be from 2 to {MAX_SAMPLES}", req.samples)));
    }
    let e = ease(req.ease.as_ref(), EaseKind::Sine)?;
    let last = f64::from(req.samples - 1);
    let t: Vec<f64> = (0..req.samples).map(|i| f64::from(i) / last).collect();
    let s = t.iter().map(|&t| e.position(t)).collect();
    Reply::json(&EaseCurve { t, s })
}

#[cfg(test)]
#[path = "ease_tests.rs"]
mod tests;
