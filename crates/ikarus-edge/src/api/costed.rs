//! The requests whose reading is more than one parse: `/api/pose` reads its character before
//! it runs, `/api/animate` and `/api/track` tell a character from an arm or a rig and read it.
//! Each is read once, here, into the value its job runs, and costed from what was read (a
//! character's bones and constraints, [`cost::Character`]).

use std::sync::Arc;

use ikarus::Interrupt;

use super::bodies::AnimateBody;
use super::character_motion::{self, AnimateCharacterReq, TrackCharacterReq, is_character};
use super::cost::{self, Character, Rules};
use super::jobs;
use super::pose::{PoseReq, Posing, stored_character};
use super::requests::TrackReq;
use super::wire::{Limits, Problem, Reply, parse_json};
use crate::character::store::Stored;

/// `/api/pose`'s request, its character read.
pub struct PoseJob {
    posing: Posing,
    cost: f64,
}

impl PoseJob {
    /// The request in `body`, its character read and its fields checked against it.
    pub fn parse(body: &[u8], limits: &Limits) -> Result<Self, Problem> {
        let req: PoseReq = parse_json(body)?;
        let rules = Rules::of(req.ik.as_deref(), req.goals.len() as f64, req.pins.len() as f64);
        let sent = req.rig.is_some();
        let posing = Posing::of(req, limits)?;
        let character = Character::of_loaded(&posing.stored.loaded, sent.then_some(posing.stored.text.as_str()));
        Ok(Self { cost: character.parse() + character.pose(rules), posing })
    }

    /// The work: reading the character (when it came with the request) and one pose.
    #[must_use]
    pub fn cost(&self) -> f64 {
        self.cost
    }

    /// The answer.
    pub fn run(self, interrupt: &Interrupt) -> Result<Reply, Problem> {
        super::pose::pose(&self.posing, interrupt)
    }
}

/// What a character's request names: its `rig` (the file's text), `character` (a kept one's id)
/// and `ik` (whose rules).
type Names<'a> = (Option<&'a str>, Option<&'a str>, Option<&'a str>);

/// A character's motion request (`/api/animate`'s or `/api/track`'s), its character read.
pub struct CharacterMotion<R> {
    req: R,
    stored: Arc<Stored>,
    cost: f64,
}

impl<R> CharacterMotion<R> {
    /// `req`'s character read (`names`: its `rig`, `character` and `ik`), and the cost of
    /// `poses` poses of it.
    fn read(req: R, names: fn(&R) -> Names<'_>, poses: fn(&R) -> f64, limits: &Limits) -> Result<Self, Problem> {
        let (rig, id, ik) = names(&req);
        let stored = stored_character(rig, id, limits)?;
        let character = Character::of_loaded(&stored.loaded, rig);
        let cost = character.parse() + poses(&req).max(1.0) * character.pose(Rules::of(ik, 0.0, 0.0));
        Ok(Self { req, stored, cost })
    }
}

/// `/api/animate`'s request: a character's motion, or an arm's or a rig's.
pub enum AnimateJob {
    /// A character's motion (`rig` holding a character file's text, or `character`).
    Character(Box<CharacterMotion<AnimateCharacterReq>>),
    /// An arm's or a rig's motion.
    Body(AnimateBody),
}

impl AnimateJob {
    /// The request in `body`: a character's (its `rig` a character file's text, or
    /// `character`; read now), else an arm's or a rig's.
    pub fn parse(body: &[u8], limits: &Limits) -> Result<Self, Problem> {
        if !is_character(body) {
            return AnimateBody::parse(body).map(AnimateJob::Body);
        }
        let req: AnimateCharacterReq = parse_json(body)?;
        let frames = |r: &AnimateCharacterReq| match &r.keys {
            Some(keys) => cost::key_frames(keys),
            None => {
                let duration = r.duration.unwrap_or(crate::character::motion::DEFAULT_DURATION);
                (duration * r.fps.unwrap_or(crate::character::motion::DEFAULT_FPS)).max(0.0)
            }
        };
        CharacterMotion::read(req, |r| (r.rig.as_deref(), r.character.as_deref(), r.ik.as_deref()), frames, limits)
            .map(|c| AnimateJob::Character(Box::new(c)))
    }

    /// The work at most ([`cost`]).
    #[must_use]
    pub fn cost(&self) -> f64 {
        match self {
            AnimateJob::Character(c) => c.cost,
            AnimateJob::Body(AnimateBody::Arm(r)) => cost::animate(r),
            AnimateJob::Body(AnimateBody::Rig(r)) => cost::animate(r),
        }
    }

    /// The answer.
    pub fn run(self, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
        match self {
            AnimateJob::Character(c) => {
                let CharacterMotion { req, stored, .. } = *c;
                character_motion::animate(req, &stored, limits, interrupt)
            }
            AnimateJob::Body(body) => jobs::animate(body, limits, interrupt),
        }
    }
}

/// `/api/track`'s request: a character's path, or an arm's or a rig's.
pub enum TrackJob {
    /// A character's path, followed by its `effector`'s tip.
    Character(Box<CharacterMotion<TrackCharacterReq>>),
    /// An arm's or a rig's path.
    Body(Box<TrackReq>),
}

impl TrackJob {
    /// The request in `body`, told apart as [`AnimateJob::parse`] tells it.
    pub fn parse(body: &[u8], limits: &Limits) -> Result<Self, Problem> {
        if !is_character(body) {
            return TrackReq::parse(body).map(|(_, req)| TrackJob::Body(Box::new(req)));
        }
        let req: TrackCharacterReq = parse_json(body)?;
        let samples = |r: &TrackCharacterReq| match &r.path {
            Some(path) if !path.is_empty() => path.len() as f64,
            _ => r.samples.unwrap_or(crate::track::DEFAULT_SAMPLES) as f64,
        };
        CharacterMotion::read(req, |r| (r.rig.as_deref(), r.character.as_deref(), r.ik.as_deref()), samples, limits)
            .map(|c| TrackJob::Character(Box::new(c)))
    }

    /// The work at most ([`cost`]).
    #[must_use]
    pub fn cost(&self) -> f64 {
        match self {
            TrackJob::Character(c) => c.cost,
            TrackJob::Body(r) => cost::track(r),
        }
    }

    /// The answer.
    pub fn run(self, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
        match self {
            TrackJob::Character(c) => {
                let CharacterMotion { req, stored, .. } = *c;
                character_motion::track(req, &stored, limits, interrupt)
            }
            TrackJob::Body(req) => jobs::track(*req, limits, interrupt),
        }
    }
}
