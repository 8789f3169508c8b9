//! `POST /api/pose`: a character file posed as its runtime does, the JSON of `ikarus pose
//! --format json` ([`crate::pose`]).

use std::collections::BTreeMap;

use serde::Deserialize;

use super::atlases::KeptAtlas;

use super::bodies::{effectors_within, field_name, named_goals};
use super::fields::{json_response, stopped};
use super::requests::request;
use super::wire::{Limits, Problem, Reply, status};
use crate::character::art_json::ArtJson;
use crate::character::store::{self, Stored};
use crate::character::{is_json, load_within};
use crate::keys::BendName;
use crate::keys::character::{bend_constraint, bend_positive};
use crate::pose::{
    IkChoice, PhysicsAsk, PoseAsk, PoseReport, add_goals, clip_at, pose_kept_watched, pose_watched as posed, skin_index,
};
use crate::rig::BoneCap;
use ikarus::Interrupt;
use ikarus::character::{Character, DrawList, Posed};
use std::sync::Arc;

request! {
    /// `{"rig": "<the file's text>", "animation": "walk", "time": 0.4, "targets": [{"bone", "x",
    /// "y"}, …], "ik": "ikarus", "ik_file": "<TOML>", "goals": [{"bone", "x", "y", "bones", …}],
    /// "pins": ["BONE", …], "bends": {"front-shin": "cw"}, "rotations": {"head": 30}, "skin":
    /// "default"}`: every field but `rig` optional;
    /// `goals` and `pins` only with `"ik": "ikarus"`. `bends` sets the side of the two-bone IK
    /// constraints whose lower bones it names, as a keys file's bend key does (the page poses a
    /// drag in Key mode with the bends in force at the playhead); `rotations` turns bones by hand
    /// (each one's local rotation, degrees, in place of the clip's), as a rotation key does;
    /// `skin` chooses the skin whose skin-required bones and constraints take part (default: the
    /// skin called `default`, if any), and the answer's inactive bones carry `"active": false`.
    /// `"physics": false` leaves a character's physics constraints out (`--physics off`);
    /// otherwise the animation is played from 0 at `fps` frames a second (default 60) with them.
    /// `"atlas": ID` (the id `/api/atlas/parse` answered) adds the pose's drawing, `"art"`
    /// ([`crate::character::art_json`]).
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct PoseReq {
        ..pose,
    }
}

/// `POST /api/pose`: the character (at most `--max-bones` bones, counted first), at most as many
/// targets as it has bones; with `atlas`, the pose's drawing too.
pub fn pose(posing: &Posing, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let Some(atlas) = &posing.atlas else {
        let report = posed(&posing.stored.loaded, &posing.ask, interrupt);
        stopped(interrupt)?;
        return json_response(&report.map_err(Problem::from)?);
    };
    let drawn = posing.drawn(interrupt)?;
    let a = &atlas.art;
    let c = &posing.stored.loaded.character;
    let mut list = DrawList::default();
    c.draw_list_at(&drawn.posed, drawn.skin, drawn.clip, &a.regions, &mut list)
        .map_err(|e| Problem::invalid(e.to_string()))?;
    let art = ArtJson::of(c, &list, &a.atlas, &a.regions).map_err(|e| Problem::invalid(format!("atlas: {e}")))?;
    json_response(&PoseWithArt { report: drawn.report, art })
}

/// `/api/pose`'s answer with `"atlas"`: the pose and its drawing.
#[derive(Debug, serde::Serialize)]
struct PoseWithArt {
    #[serde(flatten)]
    report: PoseReport,
    art: ArtJson,
}

/// A pose request read and checked: the character, what to pose, and the atlas to draw it with.
pub struct Posing {
    /// The character.
    pub stored: Arc<Stored>,
    /// The pose asked for.
    pub ask: PoseAsk,
    /// The atlas `atlas` names.
    pub atlas: Option<Arc<KeptAtlas>>,
}

/// A pose, with what drawing its art takes.
pub struct Drawn {
    /// The pose's report (the bones, the solve).
    pub report: PoseReport,
    /// The pose itself.
    pub posed: Posed,
    /// The skin it was posed with.
    pub skin: Option<usize>,
    /// The clip at its time.
    pub clip: Option<(usize, f64)>,
}

impl Posing {
    /// The request `req` checked against its character (its targets at most one per bone, its
    /// IK, bends and rotations naming what the character has) and its atlas looked up.
    pub fn of(req: PoseReq, limits: &Limits) -> Result<Self, Problem> {
        let atlas = req.atlas.as_deref().map(super::atlases::stored_atlas).transpose()?;
        let stored = stored_character(req.rig.as_deref(), req.character.as_deref(), limits)?;
        let loaded = &stored.loaded;
        let bones = loaded.character.bones().len();
        if req.targets.len() > bones {
            return Err(Problem::invalid(format!(
                "targets: {} targets for {bones} bones; at most one per bone",
                req.targets.len()
            )));
        }
        let ik =
            IkReq { ik: req.ik, ik_file: req.ik_file, goals: req.goals, pins: req.pins }.choice(&loaded.character)?;
        let ask = PoseAsk {
            animation: req.animation,
            time: req.time,
            targets: req.targets.into_iter().map(|t| (t.bone, [t.x, t.y])).collect(),
            ik,
            bends: bends(loaded, &req.bends)?,
            turns: turns(loaded, &req.rotations)?,
            physics: match req.physics {
                Some(false) => PhysicsAsk::Off,
                Some(true) | None => PhysicsAsk::Play { fps: req.fps.unwrap_or(60.0) },
            },
            skin: req.skin,
        };
        Ok(Self { stored, ask, atlas })
    }

    /// The pose (kept, to draw its art from).
    pub fn drawn(&self, interrupt: &Interrupt) -> Result<Drawn, Problem> {
        let (loaded, ask) = (&self.stored.loaded, &self.ask);
        let c = &loaded.character;
        let mut posed = Posed::default();
        let report = pose_kept_watched(loaded, ask, &mut posed, interrupt);
        stopped(interrupt)?;
        let report = report.map_err(Problem::from)?;
        let skin = skin_index(c, ask.skin.as_deref()).map_err(Problem::from)?;
        let clip = clip_at(c, ask.animation.as_deref(), ask.time).map_err(Problem::from)?;
        Ok(Drawn { report, posed, skin, clip })
    }
}

/// The character of a request: `rig`, the file's text (read now), or `character`, the id
/// `/api/rig/parse` answered (kept by [`store`]); exactly one of them. An id not kept (never
/// sent, or let go) is a 404 naming the field, after which the page sends the file again.
pub fn stored_character(rig: Option<&str>, id: Option<&str>, limits: &Limits) -> Result<Arc<Stored>, Problem> {
    match (rig, id) {
        (Some(_), Some(_)) => Err(Problem::invalid(
            "rig, character: give one (the character file's text, or the id /api/rig/parse answered for it)",
        )),
        (Some(text), None) => {
            Ok(Arc::new(Stored { loaded: character(text, limits)?, text: text.to_owned() }))
        }
        (None, Some(id)) => store::global().get(id).ok_or_else(|| {
            Problem::new(
                status::NOT_FOUND,
                format!(
                    "character: no character {id:?} on the server (never read, or let go for newer ones): send its file to /api/rig/parse again"
                ),
            )
        }),
        (None, None) => Err(Problem::invalid(
            "rig: required: the character file's text (or character: the id /api/rig/parse answered for it)",
        )),
    }
}

/// The request's `bends` as `(constraint, bendPositive)`; a name that is not a two-bone IK
/// constraint's lower bone is refused naming `bends.NAME`.
fn bends(loaded: &crate::character::Loaded, bends: &BTreeMap<String, BendName>) -> Result<Vec<(usize, bool)>, Problem> {
    bends
        .iter()
        .map(|(name, side)| {
            let k = bend_constraint(loaded, &format!("bends.{name}"), name).map_err(Problem::from)?;
            Ok((k, bend_positive(loaded, side.bend())))
        })
        .collect()
}

/// The request's `rotations` (bone → its local rotation, degrees, in place of the clip's: a
/// bone turned by hand, as a keys file's rotation key sets it) as `(bone, degrees)`; an unknown
/// bone is refused naming `rotations.NAME`.
fn turns(loaded: &crate::character::Loaded, rotations: &BTreeMap<String, f64>) -> Result<Vec<(usize, f64)>, Problem> {
    let c = &loaded.character;
    rotations
        .iter()
        .map(|(name, &deg)| {
            let bone = c.bone_index(name).ok_or_else(|| {
                Problem::invalid(format!("rotations.{name}: no bone named {name:?} in the character"))
            })?;
            Ok((bone, deg))
        })
        .collect()
}

/// The character file `rig` of a pose request (its text, Spine or DragonBones JSON, at most
/// `--max-bones` bones, counted first), or the refusal `/api/pose` answers for it.
pub fn character(rig: &str, limits: &Limits) -> Result<crate::character::Loaded, Problem> {
    if crate::character::atlas::is_atlas(rig) {
        return Err(Problem::invalid(format!("rig: {}", crate::character::atlas::ATLAS)));
    }
    if !is_json(rig) {
        return Err(Problem::invalid(
            "rig: pose takes a character file's text (Spine or DragonBones JSON); a rig file (TOML) is posed by /api/solve",
        ));
    }
    Ok(load_within(rig, "rig", BoneCap::flag(limits.max_bones))?)
}

request! {
    /// The IK part of a pose request: whose rules, the IK file, and with ikarus's, goals on
    /// bones' tips and pins (`/api/pose`'s fields; Python's `rig.pose` sends them as one object).
    #[derive(Debug, Default, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct IkReq {
        ..ik_goals,
    }
}

impl IkReq {
    /// The rules asked for on `c` ([`crate::pose::ik_choice`]), with the goals and pins, which
    /// need ikarus's; problems name the field (`goals[0].bones`).
    pub fn choice(&self, c: &Character) -> Result<IkChoice, Problem> {
        let mut ik = crate::pose::ik_choice(self.ik.as_deref(), self.ik_file.as_deref(), "ik_file", c)?;
        effectors_within(&self.goals, &self.pins)?;
        match &mut ik {
            IkChoice::Ikarus(rules) => {
                let bones: Vec<Option<usize>> = self.goals.iter().map(|g| g.bones).collect();
                add_goals(rules, c, &named_goals(&self.goals), &bones, &self.pins, &field_name)
                    .map_err(Problem::from)?;
            }
            IkChoice::Runtime if !self.goals.is_empty() || !self.pins.is_empty() => {
                let which = if self.goals.is_empty() { "pins" } else { "goals" };
                return Err(Problem::invalid(format!(
                    "{which}: only with \"ik\": \"ikarus\" (the runtime's rules know only the file's constraints)"
                )));
            }
            IkChoice::Runtime => {}
        }
        Ok(ik)
    }
}

#[cfg(test)]
#[path = "pose_tests.rs"]
mod tests;
