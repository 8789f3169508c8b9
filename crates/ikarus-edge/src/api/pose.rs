//! `POST /api/pose`: a character file posed as its runtime does, the JSON of `ikarus pose
//! --format json` ([`crate::pose`]).

use serde::Deserialize;

use super::fields::json_response;
use super::{Limits, Problem, Reply, parse_json};
use crate::character::{is_json, load_within};
use crate::pose::{PoseAsk, pose as posed};
use crate::rig::BoneCap;

/// `{"rig": "<the file's text>", "animation": "walk", "time": 0.4, "targets": [{"bone", "x",
/// "y"}, …], "ik": "ikarus", "ik_file": "<TOML>"}`: every field but `rig` optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PoseReq {
    rig: String,
    #[serde(default)]
    animation: Option<String>,
    #[serde(default)]
    time: Option<f64>,
    #[serde(default)]
    targets: Vec<TargetReq>,
    /// `"runtime"` (the default) or `"ikarus"`.
    #[serde(default)]
    ik: Option<String>,
    /// With `"ik": "ikarus"`: an IK file's text (TOML; see `ikarus pose --ik-file`).
    #[serde(default)]
    ik_file: Option<String>,
}

/// A bone's world origin put at (x, y).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TargetReq {
    bone: String,
    x: f64,
    y: f64,
}

/// `POST /api/pose`: the character (at most `--max-bones` bones, counted first), at most as many
/// targets as it has bones.
pub fn pose(body: &[u8], limits: &Limits) -> Result<Reply, Problem> {
    let req: PoseReq = parse_json(body)?;
    if !is_json(&req.rig) {
        return Err(Problem::invalid(
            "rig: pose takes a character file's text (Spine or DragonBones JSON); a rig file (TOML) is posed by /api/solve",
        ));
    }
    let loaded = load_within(&req.rig, "rig", BoneCap::flag(limits.max_bones))?;
    let bones = loaded.character.bones().len();
    if req.targets.len() > bones {
        return Err(Problem::invalid(format!(
            "targets: {} targets for {bones} bones; at most one per bone",
            req.targets.len()
        )));
    }
    let ik = crate::pose::ik_choice(req.ik.as_deref(), req.ik_file.as_deref(), "ik_file", &loaded.character)?;
    let ask = PoseAsk {
        animation: req.animation,
        time: req.time,
        targets: req.targets.into_iter().map(|t| (t.bone, [t.x, t.y])).collect(),
        ik,
    };
    let report = posed(&loaded, &ask).map_err(Problem::invalid)?;
    json_response(&report)
}
