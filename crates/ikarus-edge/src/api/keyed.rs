//! `POST /api/animate` with `keys` and a rig: the keyed motion of [`crate::keys`], the same
//! workflow and answer as `ikarus animate --rig FILE --keys KEYS.json --format json`, under
//! `--max-frames`, frames × bones at most [`MAX_BONE_FRAMES`], and the server's time budget
//! (the solver options carry its interrupt, and it is asked between frames).

use ikarus::Interrupt;

use super::character_motion::MAX_BONE_FRAMES;
use super::fields::{RIG_KEYS_GIVE, json_response, options_for, refuse_given, stopped};
use super::requests::AnimateReq;
use super::wire::{Limits, Problem, Reply};
use crate::error::Error;
use crate::keys::KeysFile;
use crate::keys::motion::KeyedMotion;
use crate::rig::Rig;
use crate::settings::SolverSettings;

/// The keyed motion of `rig`: every other motion field refused, naming it.
pub fn animate<V>(
    rig: &Rig,
    keys: &KeysFile,
    req: &AnimateReq<V>,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Reply, Problem> {
    let given = [
        ("via", !req.via.is_empty()),
        ("goal", req.goal.is_some()),
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
    refuse_given(&given, RIG_KEYS_GIVE)?;
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
    let plan = keys.check(s, limits.max_frames, "--max-frames").map_err(Problem::from)?;
    if plan.frames() * s.len() > MAX_BONE_FRAMES {
        return Err(Problem::invalid(format!(
            "keys: {} frames × {} bones, more than the cap of {MAX_BONE_FRAMES}",
            plan.frames(),
            s.len()
        )));
    }
    let stop = || if interrupt.is_interrupted() { Err(Error::input("interrupted")) } else { Ok(()) };
    let motion = plan.run(rig, s.start_angles(), options, &stop);
    stopped(interrupt)?;
    let motion = motion.map_err(Problem::from)?;
    Ok((motion, plan.track_names(s), limits_on))
}
