//! The one place that tells a request's body apart: `POST /api/solve`, `/api/animate`,
//! `/api/track` and the figures `arm`/`rig` of `/api/render` take an arm (`arm`, or the
//! built-in arm without one) or a rig (`rig`), in one request type per job
//! ([`super::requests`], [`super::figures`]). A body is read once for its keys ([`Keys`]), then
//! as the request, whose fields for the other body are refused by `fields_of`, each in the words of a
//! field serde does not know (`pins: unknown field `pins`, …`). The bodies are loaded here too,
//! under the server's caps ([`load`]), and a rig's goals and pins become its task ([`task`]).

use ikarus::{Bend, Priority, RigTask};
use serde::Deserialize;
use serde::de::IgnoredAny;

use super::requests::{AnimateReq, BendReq, PriorityReq, RigGoalReq, SolveReq, TrackReq};
use super::wire::{Limits, Problem, parse_json};
use crate::arm::{Arm, ArmFile};
use crate::body::Body;
use crate::error::FieldPath;
use crate::goal::{self, Field, NamedGoal};
use crate::rig::{BoneCap, Rig, RigFile};

/// Most effectors (goals and pins together) of a request.
pub const MAX_EFFECTORS: usize = 64;

/// Which body a request is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BodyKind {
    /// An arm (`arm`, or the built-in arm when the request has neither body).
    Arm,
    /// A rig (`rig`).
    Rig,
}

/// What a body has, read without judging anything else.
#[derive(Debug, Deserialize)]
#[serde(expecting = "struct SolveReq")]
pub struct Keys {
    /// Whether the request has `arm`.
    #[serde(default)]
    pub arm: Option<IgnoredAny>,
    /// Whether the request has `rig`.
    #[serde(default)]
    pub rig: Option<IgnoredAny>,
    /// Whether the request has `goal` (an arm's).
    #[serde(default)]
    pub goal: Option<IgnoredAny>,
    /// Whether the request has `goals` (a rig's).
    #[serde(default)]
    pub goals: Option<IgnoredAny>,
}

impl Keys {
    /// The body of a job's request: a rig's when it has `rig`; an arm's, which has no `goals`,
    /// otherwise.
    pub fn of(body: &[u8]) -> Result<BodyKind, Problem> {
        let keys: Keys = parse_json(body)?;
        match (keys.arm.is_some(), keys.rig.is_some()) {
            (true, true) => Err(Problem::invalid("arm, rig: give one or the other, not both")),
            (_, true) if keys.goal.is_some() => {
                Err(Problem::invalid("goal: a rig takes goals, a list of {\"bone\", \"x\", \"y\"}"))
            }
            (_, true) => Ok(BodyKind::Rig),
            (_, false) if keys.goals.is_some() => {
                Err(Problem::invalid("goals: only with rig (an arm takes one goal, {\"x\", \"y\"})"))
            }
            (_, false) => Ok(BodyKind::Arm),
        }
    }
}

/// Refuses the first field given that the body does not take: `arm_only` for a rig,
/// `rig_only` for an arm, each `(name, given)`; then the field the body needs, `required`,
/// when absent. As serde words them, the latter with the body's end as its position.
pub(super) fn fields_of(
    kind: BodyKind,
    arm_only: &[(&str, bool)],
    rig_only: &[(&str, bool)],
    required: (&str, bool),
    body: &[u8],
) -> Result<(), Problem> {
    let (foreign, whose) = match kind {
        BodyKind::Arm => (rig_only, "only with rig"),
        BodyKind::Rig => (arm_only, "not with rig"),
    };
    if let Some((name, _)) = foreign.iter().find(|(_, given)| *given) {
        return Err(Problem::invalid(format!("request body: {name}: unknown field `{name}`, {whose}")));
    }
    match required {
        (name, false) => Err(Problem::invalid(format!("request body: missing field `{name}` at {}", end(body)))),
        _ => Ok(()),
    }
}

/// `line L column C` of a JSON body's last character, where serde reports a missing field.
fn end(body: &[u8]) -> String {
    let last = body.iter().rposition(|b| !matches!(b, b' ' | b'\t' | b'\n' | b'\r')).unwrap_or(0);
    let line = body[..last].iter().filter(|&&b| b == b'\n').count() + 1;
    let column = last - body[..last].iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
    format!("line {line} column {column}")
}

impl SolveReq {
    /// The body of `POST /api/solve`: which body it is about, and the request.
    pub fn parse(body: &[u8]) -> Result<(BodyKind, Self), Problem> {
        let kind = Keys::of(body)?;
        let req: Self = parse_json(body)?;
        let rig_only = [("pins", req.pins.is_some()), ("mix", req.mix.is_some())];
        let goal = ("goal", kind == BodyKind::Rig || req.goal.is_some());
        fields_of(kind, &[], &rig_only, goal, body)?;
        Ok((kind, req))
    }
}

/// An arm's `via` entry: a point `[x, y]`.
pub type ArmVia = [f64; 2];
/// A rig's `via` entry: a goal set.
pub type RigVia = Vec<RigGoalReq>;

/// The body of `POST /api/animate`, read with the `via` entries of its body.
#[derive(Debug)]
pub enum AnimateBody {
    /// An arm's motion: each `via` entry a point `[x, y]`.
    Arm(Box<AnimateReq<ArmVia>>),
    /// A rig's motion: each `via` entry a goal set.
    Rig(Box<AnimateReq<RigVia>>),
}

impl AnimateBody {
    /// The request, its `via` read as its body's.
    pub fn parse(body: &[u8]) -> Result<Self, Problem> {
        match Keys::of(body)? {
            BodyKind::Arm => {
                let req: AnimateReq<ArmVia> = parse_json(body)?;
                // Keyed, the arm is the one-branch rig of its links, its fields checked there.
                if req.keys.is_none() {
                    let rig_only = [("pins", req.pins.is_some()), ("mix", req.mix.is_some())];
                    fields_of(BodyKind::Arm, &[], &rig_only, ("goal", req.goal.is_some()), body)?;
                }
                Ok(AnimateBody::Arm(Box::new(req)))
            }
            BodyKind::Rig => Ok(AnimateBody::Rig(parse_json(body)?)),
        }
    }
}

impl TrackReq {
    /// The body of `POST /api/track`: which body it is about, and the request.
    pub fn parse(body: &[u8]) -> Result<(BodyKind, Self), Problem> {
        let kind = Keys::of(body)?;
        let req: Self = parse_json(body)?;
        let rig_only = [("effector", req.effector.is_some()), ("pins", req.pins.is_some()), ("mix", req.mix.is_some())];
        fields_of(kind, &[], &rig_only, ("", true), body)?;
        Ok((kind, req))
    }
}

/// The request's body: its rig, else its arm, else the built-in seed arm (as [`load_rig`] and
/// [`load_arm`] check them). An arm with offsets or slides ([`ArmFile::joint_key`]) is the
/// one-branch rig of its links ([`Body::from_arm_file`]: bones `link0`, `link1`, …, its goal on
/// the last), checked as an arm so that a problem names the link (`arm: links[2].limits = …`).
pub fn load(arm: Option<ArmFile>, rig: Option<RigFile>, limits: &Limits) -> Result<Body, Problem> {
    match (rig, arm) {
        (Some(rig), _) => Ok(Body::Rig(Box::new(load_rig(rig, limits)?))),
        (None, Some(arm)) if arm.joint_key().is_some() => {
            links_cap(&arm, limits)?;
            Ok(Body::from_arm_file(arm, "arm")?)
        }
        (None, arm) => Ok(Body::Chain(Box::new(load_arm(arm, limits)?))),
    }
}

/// The request's arm, or the built-in seed arm; at most `--max-links` links.
pub fn load_arm(file: Option<ArmFile>, limits: &Limits) -> Result<Arm, Problem> {
    match file {
        None => Ok(Arm::load(None)?),
        Some(file) => {
            links_cap(&file, limits)?;
            Ok(Arm::from_file(file, "arm")?)
        }
    }
}

/// The one-branch rig of a request's arm (the built-in arm without one): bones `link0`,
/// `link1`, … ([`Rig::from_arm`]), at most `--max-links` of them.
pub fn load_arm_as_rig(file: Option<ArmFile>, limits: &Limits) -> Result<Rig, Problem> {
    let file = match file {
        None => ArmFile::read(crate::arm::DEFAULT_ARM, "built-in arm")?,
        Some(file) => {
            links_cap(&file, limits)?;
            file
        }
    };
    Ok(Rig::from_arm(&file, "arm")?)
}

/// At most `--max-links` links in a request's arm.
fn links_cap(file: &ArmFile, limits: &Limits) -> Result<(), Problem> {
    if file.links.len() > limits.max_links {
        return Err(Problem::invalid(format!(
            "arm.links: {} links, more than the cap of {} (--max-links)",
            file.links.len(),
            limits.max_links
        )));
    }
    Ok(())
}

/// The request's rig, checked as a rig file is (errors start with `rig:`); at most
/// `--max-bones` bones (counted first).
pub fn load_rig(file: RigFile, limits: &Limits) -> Result<Rig, Problem> {
    Ok(Rig::from_file(file, "rig", BoneCap::flag(limits.max_bones))?)
}

/// The task of a request's `goals`, `pins` and `mix` on `rig`; problems name the field
/// (`goals[1].bone`, `pins[0]`); at most [`MAX_EFFECTORS`] goals and pins together. `need_one`:
/// a solve needs a goal or a pin, a picture does not.
pub fn task(
    rig: &Rig,
    goals: &[RigGoalReq],
    pins: &[String],
    mix: Option<f64>,
    need_one: bool,
) -> Result<RigTask, Problem> {
    task_named(rig, goals, pins, mix, need_one, &field_name)
}

/// [`task`] of `goals` and `pins` whose problems name the fields with `field` (a set of `via`
/// goals: `via[1][0].bone`).
pub(super) fn task_named(
    rig: &Rig,
    goals: &[RigGoalReq],
    pins: &[String],
    mix: Option<f64>,
    need_one: bool,
    field: &dyn Fn(Field) -> String,
) -> Result<RigTask, Problem> {
    let effectors = effectors_within(goals, pins)?;
    if !need_one && effectors == 0 {
        return Ok(RigTask::default());
    }
    if let Some(i) = goals.iter().position(|g| g.bones.is_some()) {
        return Err(Problem::invalid(format!(
            "{}: only for a character's goal (/api/pose); a rig's goal turns every bone above it",
            field(Field::Bones(i))
        )));
    }
    let goals = named_goals(goals);
    goal::build(&rig.skeleton, &goals, pins, mix.unwrap_or(1.0), field).map_err(Problem::from)
}

/// How many goals and pins there are together, refused over [`MAX_EFFECTORS`].
pub(super) fn effectors_within(goals: &[RigGoalReq], pins: &[String]) -> Result<usize, Problem> {
    let effectors = goals.len() + pins.len();
    if effectors > MAX_EFFECTORS {
        return Err(Problem::invalid(format!(
            "goals, pins: {effectors} effectors (goals and pins together), more than the cap of {MAX_EFFECTORS}"
        )));
    }
    Ok(effectors)
}

/// A request's goals by name, in the edge's units.
pub(super) fn named_goals(goals: &[RigGoalReq]) -> Vec<NamedGoal> {
    goals
        .iter()
        .map(|g| NamedGoal {
            weight: g.weight.unwrap_or(1.0),
            priority: match g.priority {
                None | Some(PriorityReq::Primary) => Priority::Primary,
                Some(PriorityReq::Secondary) => Priority::Secondary,
            },
            bend: g.bend.map(|b| match b {
                BendReq::Ccw => Bend::Positive,
                BendReq::Cw => Bend::Negative,
            }),
            softness: g.softness.unwrap_or(0.0),
            ..NamedGoal::new(g.bone.clone(), g.x, g.y, g.angle_deg)
        })
        .collect()
}

/// A goal's or a pin's field as a request names it (`goals[1].weight`, `pins[0]`).
pub(super) fn field_name(f: Field) -> String {
    f.path_in(FieldPath::new().field("goals")).to_string()
}

#[cfg(test)]
#[path = "bodies_tests.rs"]
mod tests;
