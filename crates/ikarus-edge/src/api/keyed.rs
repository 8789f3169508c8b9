//! `POST /api/animate` with `keys` and a rig: the keyed motion of [`crate::keys`], the same
//! workflow and answer as `ikarus animate --rig FILE --keys KEYS.json --format json`, under
//! `--max-frames`, frames × bones at most [`MAX_BONE_FRAMES`], and the server's time budget
//! (the solver options carry its interrupt, and it is asked between frames).

use ikarus::Interrupt;

use super::character_motion::MAX_BONE_FRAMES;
#[cfg(feature = "render")]
use super::fields::picture;
use super::fields::{json_response, options_for, stopped};
#[cfg(feature = "render")]
use super::figures::MotionFigureReq;
use super::requests::{AnimateReq, RigGoalReq};
use super::{Limits, Problem, Reply};
use crate::keys::KeysFile;
use crate::keys::motion::KeyedMotion;
#[cfg(feature = "render")]
use crate::picture::{PictureFormat, draw};
use crate::rig::Rig;
use crate::settings::SolverSettings;

/// The keyed motion of `rig`: every other motion field refused, naming it.
pub fn animate(
    rig: &Rig,
    keys: &KeysFile,
    req: &AnimateReq<Vec<RigGoalReq>>,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Reply, Problem> {
    let given = [
        ("via", !req.via.is_empty()),
        ("goals", req.goals.is_some()),
        ("pins", req.pins.is_some()),
        ("mix", req.mix.is_some()),
        ("start_deg", req.start_deg.is_some()),
        ("frames", req.frames.is_some()),
        ("duration", req.duration.is_some()),
        ("fps", req.fps.is_some()),
        ("ease", req.ease.is_some()),
        ("interpolation", req.interpolation.is_some()),
        ("from_solve", req.from_solve),
    ];
    if let Some((name, _)) = given.iter().find(|(_, g)| *g) {
        return Err(Problem::invalid(format!(
            "{name}: not with keys (the keys give the targets, pins, bends and fps; the motion starts at the rig's start pose)"
        )));
    }
    let (motion, names, _) = keyed_motion(rig, keys, req.options.as_ref(), limits, interrupt)?;
    json_response(&motion.json(rig, &names))
}

/// The keyed motion of `rig` with the solver `options` over the rig's `[solver]`, under the
/// server's caps (`--max-frames`, frames × bones, its time budget): the motion, its tracks'
/// names, and whether the solve enforced the limits (a picture's wedges).
pub(super) fn keyed_motion(
    rig: &Rig,
    keys: &KeysFile,
    options: Option<&SolverSettings>,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<(KeyedMotion, Vec<String>, bool), Problem> {
    let s = &rig.skeleton;
    let options = options_for(&rig.solver, s.len(), options, None, limits, interrupt)?;
    let limits_on = options.limits != ikarus::LimitMode::Ignore;
    let plan = keys.check(s, limits.max_frames, "--max-frames").map_err(Problem::invalid)?;
    if plan.frames() * s.len() > MAX_BONE_FRAMES {
        return Err(Problem::invalid(format!(
            "keys: {} frames × {} bones, more than the cap of {MAX_BONE_FRAMES}",
            plan.frames(),
            s.len()
        )));
    }
    let stop = || if interrupt.is_interrupted() { Err("interrupted".to_owned()) } else { Ok(()) };
    let motion = plan.run(rig, s.start_angles(), options, &stop);
    stopped(interrupt)?;
    let motion = motion.map_err(Problem::invalid)?;
    Ok((motion, plan.track_names(s), limits_on))
}

/// Figure `motion` of `POST /api/render` with a rig and its `keys`: the keyed motion drawn as
/// `ikarus render motion --rig FILE --keys KEYS.json --out` draws it; the fields of an arm's
/// motion and of its area refused, naming them.
#[cfg(feature = "render")]
pub(super) fn figure(
    r: &MotionFigureReq,
    format: PictureFormat,
    width: u32,
    height: u32,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    let (Some(file), Some(keys)) = (&r.rig, &r.keys) else {
        return Err(Problem::invalid(match r.rig {
            None => crate::keys::NEEDS_RIG,
            Some(_) => "rig: the figure motion draws a rig's keyed motion: give its keys",
        }));
    };
    let given = [
        ("arm", r.arm.is_some()),
        ("goal", r.goal.is_some()),
        ("via", !r.via.is_empty()),
        ("start_deg", r.start_deg.is_some()),
        ("frames", r.frames.is_some()),
        ("duration", r.duration.is_some()),
        ("fps", r.fps.is_some()),
        ("ease", r.ease.is_some()),
        ("interpolation", r.interpolation.is_some()),
        ("from_solve", r.from_solve),
        ("workspace", r.workspace),
        ("limits", r.limits.is_some()),
        ("grid", r.grid.is_some()),
        ("resolution", r.resolution.is_some()),
        ("samples", r.samples.is_some()),
        ("seed", r.seed.is_some()),
        ("traces", r.traces.is_some()),
        ("ghosts", r.ghosts),
    ];
    if let Some((name, _)) = given.iter().find(|(_, g)| *g) {
        return Err(Problem::invalid(format!(
            "{name}: not with keys (the keys give the targets, pins, bends and fps; the motion starts at the rig's start pose)"
        )));
    }
    let rig = super::bodies::load_rig(file.clone(), limits)?;
    let (motion, _, limits_on) = keyed_motion(&rig, keys, r.options.as_ref(), limits, interrupt)?;
    if format == PictureFormat::Gif {
        super::render::gif_cap(motion.animation.frames.len(), width, height)?;
    }
    picture(draw(&motion.drawing(&rig, limits_on), format, width, height, &|_, _| {}), interrupt)
}
