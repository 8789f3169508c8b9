//! `ikarus animate --rig FILE.json` and `ikarus track --rig FILE.json`: with a character file
//! (Spine, DragonBones) in place of a rig file, the commands move bones of the character
//! ([`ikarus_edge::character::motion`]) and write its frames (`--format json`, or `csv`), or the
//! file with the motion added as a Spine animation (`--format spine`,
//! [`ikarus_edge::character::export`]), or draw it (`--out x.svg|png|gif`,
//! [`ikarus_edge::character::motion_files`]; with its art, `--atlas`: [`crate::motion_art`]).

use std::io::Write;
use std::path::Path;

use ikarus_edge::character::export;
use ikarus_edge::character::motion::{Motion, StreamError};
use ikarus_edge::character::{Loaded, is_json, load, motion_files};

use crate::error::Error;
use crate::motion_art::{ArtOut, MotionArtArgs};
use crate::output::{self, PendingFile};
use crate::picture::{PictureArgs, PictureFormat, draw_for_command};

/// A character file given as `--rig FILE`: its text, read, and its label (`rig file s.json`).
pub struct CharacterFile {
    pub text: String,
    pub loaded: Loaded,
    pub label: String,
}

/// The character file `--rig` names, read (its warnings on stderr); `None` without `--rig`, or
/// for a file that cannot be read or is not JSON (a Spine `.skel` is read as its JSON) (the rig's own reader says what it says of it); a
/// Spine texture atlas is refused as one ([`ikarus_edge::character::atlas`]).
pub fn character(rig: Option<&Path>) -> Option<Result<CharacterFile, Error>> {
    let path = rig?;
    let label = format!("rig file {}", path.display());
    let bytes = crate::input::read(path, &label).ok()?;
    // A Spine binary export (`.skel`) reads as its JSON; bytes that are neither it nor text are
    // refused with what the binary reader found.
    let text = match ikarus_edge::character::text_of(bytes, &label) {
        Ok(text) => text,
        Err(e) => return Some(Err(e)),
    };
    if ikarus_edge::character::atlas::is_atlas(&text) {
        return Some(Err(Error::input(format!("{label}: {}", ikarus_edge::character::atlas::ATLAS))));
    }
    let text = Some(text).filter(|t| is_json(t))?;
    Some(load(&text, &label).map(|loaded| {
        for warning in &loaded.warnings {
            eprintln!("ikarus: {label}: {warning}");
        }
        CharacterFile { text, loaded, label }
    }))
}

/// What a character's motion is written as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Written {
    /// `{"frames": […], "unsupported": […]}`.
    Frames,
    /// The frames as CSV, one row per bone per frame ([`motion_files::write_csv`]).
    Csv,
    /// The file with the motion added as a Spine animation.
    Spine,
}

/// What `--format` asks a character's motion to be written as: the frames (`json`), their CSV
/// (`csv`) or the file with a Spine animation (`spine`); `None` without `--format`; any other
/// format is refused.
pub fn written<F: clap::ValueEnum>(format: Option<F>) -> Result<Option<Written>, Error> {
    let name = format.and_then(|f| f.to_possible_value()).map(|v| v.get_name().to_owned());
    match name.as_deref() {
        None => Ok(None),
        Some("json") => Ok(Some(Written::Frames)),
        Some("csv") => Ok(Some(Written::Csv)),
        Some("spine") => Ok(Some(Written::Spine)),
        Some(other) => Err(Error::input(format!(
            "--format {other}: a character's motion is written as json (its frames), csv or spine"
        ))),
    }
}

/// How the motion is written: the form asked for (`None`: the frames, or nothing on stdout
/// when a picture is drawn), the new animation's name, and where (`--out`, its size).
pub struct Output<'a> {
    pub written: Option<Written>,
    pub animation_name: Option<&'a str>,
    /// The Spine export's form (`--bake` or not).
    pub form: export::Form,
    pub picture: &'a PictureArgs,
    /// How the command makes fewer frames, for the GIF cap's refusal (`a lower --fps or a
    /// shorter --duration`).
    pub fewer: &'a str,
    /// `--atlas`, `--art-only`, `--skin`: the picture drawn with the character's art.
    pub art: &'a MotionArtArgs,
}

/// The first flag of `given` (`(flag, given)`) that is given: refused in one line, since it means
/// something only for an ikarus rig or arm.
pub fn refuse_foreign(given: &[(&str, bool)]) -> Result<(), Error> {
    match given.iter().find(|(_, g)| *g) {
        Some((flag, _)) => {
            Err(Error::input(format!("{flag}: not with a character file (it is for rig files and arms)")))
        }
        None => Ok(()),
    }
}

/// The flags of a character's motion given without a character file: refused in one line.
pub fn refuse_without(given: &[(&str, bool)]) -> Result<(), Error> {
    match given.iter().find(|(_, g)| *g) {
        Some((flag, _)) => {
            Err(Error::input(format!("{flag}: only with a character file (--rig FILE.json, Spine or DragonBones)")))
        }
        None => Ok(()),
    }
}

/// Writes `motion` of `file` as `output` says: with `--out x.svg|png|gif` its picture there
/// (and the form asked for, if one is, on stdout); else the form to `--out` (whole or not at
/// all) or stdout.
pub fn write(file: &CharacterFile, motion: &Motion<'_>, output: &Output<'_>) -> Result<(), Error> {
    let fail = |m: Error| Error::input(format!("{}: {m}", file.label));
    if output.animation_name.is_some() && output.written != Some(Written::Spine) {
        return Err(Error::input("--animation-name: only with --format spine"));
    }
    if output.form == export::Form::Bake && output.written != Some(Written::Spine) {
        return Err(Error::input("--bake: only with --format spine"));
    }
    let out = output.picture.out.as_ref();
    let ext = out.and_then(|p| p.extension()).and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let picture = if ext.as_deref().is_some_and(|e| ["svg", "png", "gif"].contains(&e)) {
        output.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?
    } else {
        None
    };
    let atlas = crate::motion_art::atlas_of(output.art, file.loaded.format, picture.as_ref().map(|p| p.format))?;
    let pending = if picture.is_some() { None } else { out.map(|p| PendingFile::create(p, "--out")).transpose()? };
    if let Some(picture) = picture {
        let (frames, bones) = (motion.frame_count(), file.loaded.character.bones().len());
        if frames.saturating_mul(bones) > motion_files::MAX_DRAWN_BONES {
            return Err(Error::input(format!(
                "--out: a picture of {frames} frames × {bones} bones draws more than the cap of {} bones ({})",
                motion_files::MAX_DRAWN_BONES,
                output.fewer
            )));
        }
        if picture.format == PictureFormat::Gif {
            crate::picture::gif_within_cap(output.picture, motion.frame_count(), output.fewer)?;
        }
        let bytes = match &atlas {
            Some(atlas) => {
                let out = ArtOut { format: picture.format, picture: output.picture, fewer: output.fewer };
                crate::motion_art::draw(&file.label, motion, (output.art, atlas), &out)?
            }
            None => {
                let poses = motion.poses().map_err(fail)?;
                let drawing = motion_files::drawing(motion, &poses);
                draw_for_command(&drawing, picture.format, output.picture, poses.len())?
            }
        };
        picture.commit(&bytes)?;
        if output.written.is_none() {
            return Ok(());
        }
    }
    let stream = match output.written.unwrap_or(Written::Frames) {
        Written::Frames => motion_files::write_json,
        Written::Csv => motion_files::write_csv,
        Written::Spine => {
            let ask = export::Export { name: output.animation_name.unwrap_or(export::DEFAULT_NAME), form: output.form };
            let bytes = export::spine(motion, &file.text, &ask).map_err(fail)?.into_bytes();
            return match pending {
                Some(p) => p.commit(&bytes),
                None => output::stdout(|w: &mut dyn Write| w.write_all(&bytes)),
            };
        }
    };
    // The frames are written as they are posed, never all held at once: to the temporary file
    // (renamed into place at the end, removed on a refusal) or to stdout.
    let json = output.written.unwrap_or(Written::Frames) == Written::Frames;
    let mut refused = None;
    let mut write = |w: &mut dyn Write| {
        let written =
            stream(motion, w).and_then(|()| if json { w.write_all(b"\n").map_err(StreamError::Io) } else { Ok(()) });
        match written {
            Ok(()) => Ok(()),
            Err(StreamError::Io(e)) => Err(e),
            Err(StreamError::Motion(m)) => {
                refused = Some(fail(m));
                Err(std::io::Error::other("refused"))
            }
        }
    };
    let result = match pending {
        Some(p) => p.commit_with(&mut write),
        None => output::stdout(&mut write),
    };
    match refused {
        Some(e) => Err(e),
        None => result,
    }
}
