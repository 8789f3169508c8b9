//! `ikarus animate --rig FILE --keys KEYS.json`: the keyed motion of a rig (the edge's
//! [`ikarus_edge::keys`], the workflow and answer of `POST /api/animate` with `keys`), shown as
//! `animate --rig` shows its motions: JSON, CSV (one row per frame, `time` in seconds), a short
//! report, or a picture with `--out`.

use std::io::Write;
use std::path::Path;

use ikarus_edge::keys::KeysFile;
use ikarus_edge::keys::motion::KeyedMotion;

use super::{AnimateFormat, MotionArgs, ShownMotion};
use crate::columns::BodyColumns;
use crate::error::Error;
use crate::picture::Drawing;
use crate::rig::Rig;

/// A keyed motion of a rig, with the names of its tracked bones.
pub struct KeyedRun {
    rig: Rig,
    names: Vec<String>,
    motion: KeyedMotion,
    limits: bool,
}

impl KeyedRun {
    /// The motion of the rig of `--rig` (or the one-branch rig of `--arm` or the built-in
    /// arm: bones `link0`, `link1`, …) keyed by the file `keys`.
    pub fn of(args: &MotionArgs, keys: &Path) -> Result<Self, Error> {
        let rig = args.body.load_as_rig()?;
        let label = format!("--keys {}", keys.display());
        let text = crate::input::read_text(keys, &label)?;
        let file = KeysFile::parse(&text).map_err(|e| e.from_source(label.clone()))?;
        let s = &rig.skeleton;
        let plan = file
            .check(s, ikarus::motion::MAX_FRAMES, "the most frames of a motion")
            .map_err(|m| Error::input(format!("{label}: {m}")))?;
        let options = rig.solve_options(&args.body.solver.settings(), None)?;
        let limits = options.limits != ikarus::LimitMode::Ignore;
        let motion =
            plan.run(&rig, s.start_angles(), options, &|| Ok(())).map_err(|m| Error::input(format!("{label}: {m}")))?;
        let names = plan.track_names(s);
        let unreached = motion.frames.len() - motion.reached();
        if unreached > 0 {
            eprintln!(
                "ikarus: {unreached} of {} frames not reached, largest error {:.3e}; each goes on from the best pose found",
                motion.frames.len(),
                motion.max_error()
            );
        }
        Ok(Self { rig, names, motion, limits })
    }
}

impl ShownMotion for KeyedRun {
    fn drawing(&self) -> Drawing<'_> {
        self.motion.drawing(&self.rig, self.limits)
    }

    fn frames(&self) -> usize {
        self.motion.frames.len()
    }

    fn write(&self, w: &mut dyn Write, format: AnimateFormat) -> std::io::Result<()> {
        match format {
            AnimateFormat::Json => {
                serde_json::to_writer_pretty(&mut *w, &self.motion.json(&self.rig, &self.names))?;
                writeln!(w)
            }
            AnimateFormat::Csv => {
                let mut header = vec!["time".to_owned()];
                header.extend(self.rig.pose_columns());
                header.extend(self.rig.skeleton.names().iter().map(|n| format!("{n}.x,{n}.y")));
                writeln!(w, "{}", header.join(","))?;
                for f in &self.motion.animation.frames {
                    write!(w, "{:?}", f.time)?;
                    self.rig.write_pose(w, &f.angles)?;
                    for p in &f.joints[1..] {
                        write!(w, ",{:?},{:?}", p.x, p.y)?;
                    }
                    writeln!(w)?;
                }
                Ok(())
            }
            AnimateFormat::Text => {
                let m = &self.motion;
                writeln!(w, "rig       {} ({} bones)", self.rig.name, self.rig.skeleton.len())?;
                writeln!(w, "keys      {} tracks: {}", self.names.len(), self.names.join(", "))?;
                writeln!(w, "motion    {} frames over {} s at {} fps", m.frames.len(), m.animation.duration, m.fps)?;
                writeln!(
                    w,
                    "solves    {} of {} reached, largest error {:.3e}",
                    m.reached(),
                    m.frames.len(),
                    m.max_error()
                )?;
                writeln!(w, "frames    --format json or csv lists them; --out draws them (.svg, .png, .gif)")
            }
            AnimateFormat::Spine => unreachable!("--format spine is refused without a character file"),
        }
    }
}
