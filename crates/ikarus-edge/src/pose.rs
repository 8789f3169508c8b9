//! The `pose` job, shared by `ikarus pose` and `POST /api/pose`: a character file posed as its
//! runtime does (the setup pose, then an animation at a time, then bones moved to targets, then
//! the IK constraints in their order), answered as every bone's world origin, rotation and tip.
//!
//! Names are resolved here, once, into the library's indices; each refusal is one line naming
//! the field and the value, and for a name that does not exist, the names that do.

use ikarus::character::{
    Character, Play, PlayFrame, PoseError, PoseRequest, Posed, TIP_GOAL_BONES, TipGoal, Together, TogetherError,
    TogetherReport,
};
use ikarus::{Interrupt, SolveOptions, Solver};

use crate::character::Loaded;
use crate::error::Error;
use crate::goal::{Field, NamedGoal};
use crate::names::{Quoted, cell, listed};
pub use crate::pose_report::{GoalJson, IkJson, LimbJson, PoseReport, PosedBoneJson};

/// What to pose, by name, as the user gave it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PoseAsk {
    /// The animation sampled, by name; `None`: the setup pose.
    pub animation: Option<String>,
    /// Seconds into the animation (only with an animation).
    pub time: Option<f64>,
    /// `(bone, [x, y])`: the bone's world origin is put at (x, y) after the animation and before
    /// the constraints, in this order.
    pub targets: Vec<(String, [f64; 2])>,
    /// Whose rules solve the IK constraints.
    pub ik: IkChoice,
    /// `(constraint, bend_positive)`: the constraints' bend sides in place of the clip's
    /// ([`ikarus::character::PoseRequest::bends`]).
    pub bends: Vec<(usize, bool)>,
    /// `(bone, rotation_deg)`: bones turned by hand, each one's local rotation in degrees in
    /// place of the clip's ([`ikarus::character::PoseRequest::turns`]).
    pub turns: Vec<(usize, f64)>,
    /// The skin whose skin-required bones and constraints take part, by name; `None`: the
    /// skin called `default` if the file has one, else none.
    pub skin: Option<String>,
    /// What the physics constraints do (a character without any is posed the same either way).
    pub physics: PhysicsAsk,
}

/// What a pose at a time does with the character's physics constraints (`--physics`, `--fps`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PhysicsAsk {
    /// They do nothing (`--physics off`; Spine's `Physics.none`).
    Off,
    /// The animation is played from 0 at `fps` frames a second with them stepping, as a game
    /// shows it ([`Character::play`]); the default, at 60.
    Play {
        /// Frames a second.
        fps: f64,
    },
}

impl Default for PhysicsAsk {
    fn default() -> Self {
        PhysicsAsk::Play { fps: 60.0 }
    }
}

/// Whose rules solve a character's IK constraints.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum IkChoice {
    /// The runtime's: one constraint after another, in their order (the default).
    #[default]
    Runtime,
    /// ikarus's rig solver, every constraint at once ([`Character::pose_together`]), with the
    /// IK file's rules (an empty [`Together`] without one).
    Ikarus(Box<Together>),
}

/// Poses `loaded` as `ask` says. Errors are one line without a label: `--animation "wlk": no
/// such animation; spineboy has: aim, death, …`.
pub fn pose(loaded: &Loaded, ask: &PoseAsk) -> Result<PoseReport, Error> {
    pose_until(loaded, ask, None)
}

/// [`pose`], stopped once `interrupt` is set (a server's deadline, Ctrl-C): the pose checks it
/// before each IK constraint, ikarus's solver as it iterates. An interrupted pose is refused
/// with `interrupted`; the caller tells that from a bad request by the token.
pub fn pose_watched(loaded: &Loaded, ask: &PoseAsk, interrupt: &Interrupt) -> Result<PoseReport, Error> {
    pose_until(loaded, ask, Some(interrupt))
}

fn pose_until(loaded: &Loaded, ask: &PoseAsk, interrupt: Option<&Interrupt>) -> Result<PoseReport, Error> {
    pose_keeping(loaded, ask, &mut Posed::default(), interrupt)
}

/// [`pose`], the pose itself left in `posed` (to draw the character's art from it).
pub fn pose_kept(loaded: &Loaded, ask: &PoseAsk, posed: &mut Posed) -> Result<PoseReport, Error> {
    pose_keeping(loaded, ask, posed, None)
}

/// [`pose_kept`], stopped as [`pose_watched`] is.
pub fn pose_kept_watched(
    loaded: &Loaded,
    ask: &PoseAsk,
    posed: &mut Posed,
    interrupt: &Interrupt,
) -> Result<PoseReport, Error> {
    pose_keeping(loaded, ask, posed, Some(interrupt))
}

fn pose_keeping(
    loaded: &Loaded,
    ask: &PoseAsk,
    posed: &mut Posed,
    interrupt: Option<&Interrupt>,
) -> Result<PoseReport, Error> {
    let together = pose_into_until(loaded, ask, posed, interrupt)?;
    let mut report = PoseReport::of(&loaded.character, posed);
    report.ik = together.map(|t| IkJson::of(&loaded.character, &t));
    if let IkChoice::Ikarus(rules) = &ask.ik {
        report.targets.extend(rules.goals.iter().map(|g| [g.goal.goal.target().x, g.goal.goal.target().y]));
    }
    Ok(report)
}

/// Poses `loaded` as `ask` says into `out` (reuse one `out` across poses: a motion's frames),
/// refusing what [`pose`] refuses; with [`IkChoice::Ikarus`], what the solve did.
pub fn pose_into(loaded: &Loaded, ask: &PoseAsk, out: &mut Posed) -> Result<Option<TogetherReport>, Error> {
    pose_into_until(loaded, ask, out, None)
}

/// [`pose_into`], stopped once `interrupt` is set, as [`pose_watched`] is.
pub fn pose_into_watched(
    loaded: &Loaded,
    ask: &PoseAsk,
    out: &mut Posed,
    interrupt: &Interrupt,
) -> Result<Option<TogetherReport>, Error> {
    pose_into_until(loaded, ask, out, Some(interrupt))
}

/// [`pose_into`], watching `interrupt` when there is one.
pub(crate) fn pose_into_until(
    loaded: &Loaded,
    ask: &PoseAsk,
    out: &mut Posed,
    interrupt: Option<&Interrupt>,
) -> Result<Option<TogetherReport>, Error> {
    pose_as(loaded, ask, out, (interrupt, None))
}

/// [`pose_into_until`] as one frame of a game's loop with physics (a motion's frame, played):
/// the physics constraints step from the state `out` kept from the frame before `frame` (or
/// restart on the first), whatever `ask.physics` says; under ikarus's solver, in every pose of
/// its rounds ([`Character::pose_together_frame`]).
pub(crate) fn pose_frame_into(
    loaded: &Loaded,
    ask: &PoseAsk,
    out: &mut Posed,
    (interrupt, frame): (Option<&Interrupt>, &PlayFrame),
) -> Result<Option<TogetherReport>, Error> {
    pose_as(loaded, ask, out, (interrupt, Some(frame)))
}

/// The pose of [`pose_into_until`], or with `frame`, of [`pose_frame_into`].
fn pose_as(
    loaded: &Loaded,
    ask: &PoseAsk,
    out: &mut Posed,
    (interrupt, frame): (Option<&Interrupt>, Option<&PlayFrame>),
) -> Result<Option<TogetherReport>, Error> {
    let c = &loaded.character;
    let clip = clip_at(c, ask.animation.as_deref(), ask.time)?;
    let mut targets = Vec::with_capacity(ask.targets.len());
    for (name, [x, y]) in &ask.targets {
        let bone =
            c.bone_index(name).ok_or_else(|| Error::input(format!("target {}: no bone of that name", Quoted(name))))?;
        targets.push((bone, target_point(name, [*x, *y])?));
    }
    let mut turns = Vec::with_capacity(ask.turns.len());
    for &(bone, deg) in &ask.turns {
        if !deg.is_finite() {
            let name = c.bones().get(bone).map_or("?", |b| b.name.as_str());
            return Err(Error::input(format!("rotations.{}: the angle must be finite, got {deg}", cell(name))));
        }
        turns.push((bone, deg.to_radians()));
    }
    let skin = skin_index(c, ask.skin.as_deref())?;
    let request = PoseRequest { clip, targets: &targets, bends: &ask.bends, turns: &turns, skin };
    let report = match &ask.ik {
        IkChoice::Runtime => match (frame, ask.physics, c.constraints().iter().any(|k| k.kind() == "physics")) {
            (Some(frame), ..) => match interrupt {
                Some(token) => c.play_frame_watched(&request, frame, out, token),
                None => c.play_frame(&request, frame, out),
            },
            (None, PhysicsAsk::Play { fps }, true) => {
                let play = Play { fps, world: c.physics_world() };
                match interrupt {
                    Some(token) => c.play_watched(&request, &play, out, token),
                    None => c.play(&request, &play, out),
                }
            }
            _ => match interrupt {
                Some(token) => c.pose_watched(&request, out, token),
                None => c.pose(&request, out),
            },
        }
        .map(|()| None)
        .map_err(|e| Error::input(refusal(c, skin, &e))),
        IkChoice::Ikarus(rules) => {
            let options = SolveOptions { interrupt: interrupt.cloned(), ..character_options() };
            let mut solver = Solver::new(options).map_err(|e| Error::input(e.to_string()))?;
            match frame {
                Some(frame) => c.pose_together_frame(&request, rules, &mut solver, frame, out),
                None => c.pose_together(&request, rules, &mut solver, out),
            }
            .map(Some)
            .map_err(|e| {
                Error::input(match e {
                    TogetherError::Pose(e) => refusal(c, skin, &e),
                    e => e.to_string(),
                })
            })
        }
    }?;
    let asked =
        crate::pose_finite::Asked { targets: &ask.targets, animation: ask.animation.as_deref(), time: ask.time };
    crate::pose_finite::check(loaded, &asked, out)?;
    Ok(report)
}

/// A pose's refusal in one line, the library's indices named: a target on a bone the skin
/// leaves inactive (not posed, so not movable) names the bone and the skin.
fn refusal(c: &Character, skin: Option<usize>, e: &PoseError) -> String {
    match e {
        PoseError::InactiveTarget(b) => {
            let bone = c.bones().get(*b).map_or("?", |b| b.name.as_str());
            let skin = skin.map_or_else(|| "no skin".to_owned(), |s| format!("skin {}", Quoted(&c.skins()[s].name)));
            format!(
                "target {}: the bone is inactive with {skin} (a skin-only bone, or below one, that this skin does not turn on), so it cannot be moved",
                Quoted(bone)
            )
        }
        e => e.to_string(),
    }
}

/// The clip `animation` names at `time` (seconds, 0 when not given) as the library's index, or
/// `None` for the setup pose; the one-line refusals of [`pose`] (an unknown name lists the
/// file's animations; a time without an animation, or not finite).
pub fn clip_at(c: &Character, animation: Option<&str>, time: Option<f64>) -> Result<Option<(usize, f64)>, Error> {
    match animation {
        Some(name) => {
            let i = c.clip_index(name).ok_or_else(|| {
                Error::input({
                    let has = listed(c.clips().iter().map(|k| k.name.as_str()));
                    format!("animation {}: no such animation (the file has: {has})", Quoted(name))
                })
            })?;
            Ok(Some((i, finite_time(time.unwrap_or(0.0))?)))
        }
        None if time.is_some() => Err(Error::input("time: only with an animation")),
        None => Ok(None),
    }
}

/// The skin `name` names as the library's index (`None`: the one called `default`, if any), or
/// `skin "x": no such skin (the file has: default, hero)`.
pub fn skin_index(c: &Character, name: Option<&str>) -> Result<Option<usize>, Error> {
    match name {
        None => Ok(c.default_skin()),
        Some(name) => c.skin_index(name).map(Some).ok_or_else(|| {
            Error::input({
                let has = if c.skins().is_empty() {
                    "none".to_owned()
                } else {
                    listed(c.skins().iter().map(|s| s.name.as_str()))
                };
                format!("skin {}: no such skin (the file has: {has})", Quoted(name))
            })
        }),
    }
}

/// `time` if it is a finite number of seconds, else [`pose`]'s refusal.
pub fn finite_time(time: f64) -> Result<f64, Error> {
    if time.is_finite() {
        Ok(time)
    } else {
        Err(Error::input(format!("time: must be a finite number of seconds, got {time}")))
    }
}

/// The point of the target on bone `name` if both its coordinates are finite, else [`pose`]'s
/// refusal.
pub fn target_point(name: &str, [x, y]: [f64; 2]) -> Result<[f64; 2], Error> {
    if x.is_finite() && y.is_finite() {
        Ok([x, y])
    } else {
        Err(Error::input(format!("target {}: the point must be finite, got ({x}, {y})", Quoted(name))))
    }
}

/// The rules asked for: `ik` is `runtime` (the default) or `ikarus`; `ik_file` the text of an
/// IK file (only with `ikarus`), named `label` in messages.
pub fn ik_choice(ik: Option<&str>, ik_file: Option<&str>, label: &str, c: &Character) -> Result<IkChoice, Error> {
    rules_choice(IkRules::named(ik)?, ik_file, label, c)
}

/// Whose rules solve a character's IK constraints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IkRules {
    /// The runtime's: each constraint on its one or two bones, one after another.
    Runtime,
    /// ikarus's rig solver: every constraint at once.
    Ikarus,
}

impl IkRules {
    /// The rules a request names (`ik`: `"runtime"`, the default, or `"ikarus"`).
    pub fn named(ik: Option<&str>) -> Result<Self, Error> {
        match ik.unwrap_or("runtime") {
            "runtime" => Ok(IkRules::Runtime),
            "ikarus" => Ok(IkRules::Ikarus),
            other => Err(Error::input(format!("ik = {other:?}: expected \"runtime\" or \"ikarus\""))),
        }
    }
}

/// The IK rules `rules` for `c`: with ikarus's, the IK file's text `ik_file` (`label` starts
/// its problems) read and checked against it; an IK file with the runtime's rules is refused.
pub fn rules_choice(rules: IkRules, ik_file: Option<&str>, label: &str, c: &Character) -> Result<IkChoice, Error> {
    match (rules, ik_file) {
        (IkRules::Runtime, None) => Ok(IkChoice::Runtime),
        (IkRules::Runtime, Some(_)) => {
            Err(Error::input(format!("{label}: an IK file is read only with ik = \"ikarus\"")))
        }
        (IkRules::Ikarus, None) => Ok(IkChoice::Ikarus(Box::default())),
        (IkRules::Ikarus, Some(text)) => {
            Ok(IkChoice::Ikarus(Box::new(crate::character::ik_file::read(text, label, c)?)))
        }
    }
}

/// Adds goals on bones' tips and pins, by name, to the rules of ikarus's solver
/// (`ikarus solve --rig CHARACTER.json`, `/api/pose`'s `goals` and `pins`), checked as a rig's
/// are ([`crate::goal::goals_and_pins`]); `bones[i]` is how many bones goal `i` turns, counted up
/// from its bone (`None`: [`TIP_GOAL_BONES`], or fewer for a bone nearer its root), from 1 to
/// its depth plus one. Each problem is one line, its field named by `field`.
pub fn add_goals(
    rules: &mut Together,
    c: &Character,
    goals: &[NamedGoal],
    bones: &[Option<usize>],
    pins: &[String],
    field: &dyn Fn(Field) -> String,
) -> Result<(), Error> {
    let (solved, pinned) = crate::goal::goals_and_pins(c, goals, pins, field)?;
    for (i, goal) in solved.into_iter().enumerate() {
        let mut depth = 1;
        let mut up = c.bones()[goal.bone].parent;
        while let Some(p) = up {
            depth += 1;
            up = c.bones()[p].parent;
        }
        let count = match bones.get(i).copied().flatten() {
            Some(n) if n == 0 || n > depth => {
                return Err(Error::input(format!(
                    "{}: {n}: must be from 1 (the bone alone) to {depth} (bone {:?} and all above it)",
                    field(Field::Bones(i)),
                    Quoted(&c.bones()[goal.bone].name)
                )));
            }
            Some(n) => n,
            None => TIP_GOAL_BONES.min(depth),
        };
        if goal.bend.is_some() && count < 2 {
            return Err(Error::input(format!(
                "{}: the goal on {:?} turns one bone, so no joint to bend (give it 2 bones or more)",
                field(Field::Bend(i)),
                Quoted(&c.bones()[goal.bone].name)
            )));
        }
        rules.goals.push(TipGoal { goal, bones: count });
    }
    for p in pinned {
        if !rules.pins.contains(&p) {
            rules.pins.push(p);
        }
    }
    Ok(())
}

/// The solver's options for a character: Levenberg–Marquardt from the runtime's pose, without
/// restarts (a restart starts from a random pose: it would lose the animation's look and the
/// bends, and an aim that cannot be met exactly would restart every solve), at most 200
/// iterations.
#[must_use]
pub fn character_options() -> SolveOptions {
    SolveOptions { restarts: None, max_iterations: 200, ..SolveOptions::default() }
}

#[cfg(test)]
#[path = "pose_tests.rs"]
mod tests;
