//! `ikarus animate --rig FILE.json --target BONE=X,Y …`: bones of a character moved from where
//! its setup pose has them to the targets, eased, the file's IK constraints posing the rest;
//! its frames (`--format json`) or the file with the motion added as a Spine animation
//! (`--format spine`).

use ikarus::EaseKind;
use ikarus_edge::character::motion::{
    Course, DEFAULT_DURATION, DEFAULT_FPS, MAX_FRAMES, Motion, count_text, frames_within,
};
use ikarus_edge::keys::KeysFile;

use super::AnimateArgs;
use crate::character_motion::{CharacterFile, Output, refuse_foreign, write};
use crate::error::Error;

/// The motion of the character `file` the flags ask for, written.
pub fn run(args: &AnimateArgs, file: &CharacterFile) -> Result<(), Error> {
    let m = &args.motion;
    let mut foreign = vec![
        ("--goal", !m.goal.is_empty()),
        ("--goal-angle", m.goal_angle.is_some()),
        ("--via", !m.via.is_empty()),
        ("--frames", m.frames.is_some()),
        ("--interpolation", m.interpolation.is_some()),
        ("--from-solve", m.from_solve),
        ("--record-every", m.record_every.is_some()),
    ];
    foreign.extend(m.body.rig_task.given());
    foreign.extend(m.body.solver.given());
    refuse_foreign(&foreign)?;
    let written = crate::character_motion::written(args.format)?;
    if let Some(keys) = &m.keys {
        if !args.target.is_empty() {
            return Err(Error::input("--target: not with --keys (the keys give the targets)"));
        }
        let label = format!("--keys {}", keys.display());
        let text = crate::input::read_text(keys, &label)?;
        let keys = KeysFile::parse(&text).map_err(|e| e.from_source(label.clone()))?;
        let (course, fps) = ikarus_edge::character::motion::keyed(
            &file.loaded,
            &keys,
            args.animation.clone(),
            ikarus::motion::MAX_FRAMES,
            "the most frames of a motion",
        )
        .map_err(|e| Error::input(format!("{label}: {e}")))?;
        let mut motion =
            Motion::new(&file.loaded, course, fps).map_err(|e| Error::input(format!("{}: {e}", file.label)))?;
        motion.ik = args.ik.choice(&file.loaded.character)?;
        motion.physics = crate::pose::PhysicsSwitch::motion(args.physics);
        motion.skin.clone_from(&args.art.skin);
        let out = Output {
            written,
            animation_name: args.animation_name.as_deref(),
            form: ikarus_edge::character::export::Form::asked(args.bake),
            picture: &args.picture,
            fewer: "keys that end sooner or a lower fps in the keys file",
            art: &args.art,
        };
        return write(file, &motion, &out);
    }
    if args.target.is_empty() {
        return Err(Error::input(
            "--target: give at least one BONE=X,Y with a character file (the bone's world origin at the end)",
        ));
    }
    let duration = m.duration.unwrap_or(DEFAULT_DURATION);
    if duration <= 0.0 {
        return Err(Error::input(format!("--duration {duration}: must be positive")));
    }
    let fps = m.fps.unwrap_or(DEFAULT_FPS);
    if fps <= 0.0 {
        return Err(Error::input(format!("--fps {fps}: must be positive")));
    }
    if let Err(n) = frames_within(duration, fps, MAX_FRAMES) {
        return Err(Error::input(format!(
            "--duration {}, --fps {}: {} frames, more than the cap of {MAX_FRAMES}",
            count_text(duration),
            count_text(fps),
            count_text(n)
        )));
    }
    let ease = m.ease.resolve(EaseKind::Sine)?;
    let course = Course::Eased { targets: args.target.clone(), ease, duration };
    let mut motion =
        Motion::new(&file.loaded, course, fps).map_err(|e| Error::input(format!("{}: {e}", file.label)))?;
    motion.ik = args.ik.choice(&file.loaded.character)?;
    motion.physics = crate::pose::PhysicsSwitch::motion(args.physics);
    motion.skin.clone_from(&args.art.skin);
    let out = Output {
        written,
        animation_name: args.animation_name.as_deref(),
        form: ikarus_edge::character::export::Form::asked(args.bake),
        picture: &args.picture,
        fewer: "a lower --fps or a shorter --duration",
        art: &args.art,
    };
    write(file, &motion, &out)
}
