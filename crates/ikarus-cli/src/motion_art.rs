//! `ikarus animate|track --rig FILE.json --atlas FILE.atlas --out x.gif|png|svg`: a character's
//! motion drawn with its art, each GIF frame the frame's art under its bones, or alone
//! (`--art-only`, one fit for the whole motion); the PNG and SVG the last frame's art under every
//! frame's bones (the earlier as ghosts), or alone. The posing and the art are the edge's
//! ([`ikarus_edge::character::motion_art`]), the pixels the renderer's.
//!
//! Refused, in one line, as `ikarus pose --atlas` refuses them: `--art-only` without `--atlas`;
//! `--atlas` with a DragonBones file, or without a picture to draw (`--out x.gif|png|svg`); an
//! atlas or page image that cannot be read; a region the motion draws that the atlas lacks.

use std::path::PathBuf;

use ikarus_edge::character::Format;
use ikarus_edge::character::art_draw::AtlasArt;
use ikarus_edge::character::motion::Motion;
use ikarus_edge::character::motion_art::{MotionArtError, art_drawing, posed_with_art};
use ikarus_edge::picture::PictureFormat;
use ikarus_render::ArtPlacement;

use crate::error::Error;
use crate::picture::{PictureArgs, draw_for_command};

/// The art of a character's motion: its atlas, alone or under the bones, and the skin.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct MotionArtArgs {
    /// With a Spine character file: its texture atlas (.atlas), its PNG pages beside it; the
    /// picture (--out .gif, .png, .svg) draws the character's art under its bones (a GIF each
    /// frame's, a PNG or SVG the last frame's under the ghosts of the others)
    #[arg(long, value_name = "FILE")]
    pub atlas: Option<PathBuf>,
    /// With --atlas: the art alone on a transparent background, the box of every frame's art
    /// filling 90 % of --width × --height, centred (one fit for the whole motion)
    #[arg(long)]
    pub art_only: bool,
    /// With a character file: the skin every frame is posed and drawn with, by name [default:
    /// the skin called `default`, if the file has one]
    #[arg(long, value_name = "NAME")]
    pub skin: Option<String>,
}

impl MotionArtArgs {
    /// The flags as `(flag, given)`, for the refusal of a character's flags without one.
    #[must_use]
    pub fn given(&self) -> [(&'static str, bool); 3] {
        [("--atlas", self.atlas.is_some()), ("--art-only", self.art_only), ("--skin", self.skin.is_some())]
    }

    /// Where the art goes: alone with `--art-only`, else under the bones.
    fn placement(&self) -> ArtPlacement {
        if self.art_only { ArtPlacement::Alone } else { ArtPlacement::UnderBones }
    }
}

/// The atlas `--atlas` names, read with its pages, or `None` without it; the refusals of the
/// module's doc, for a character file of `format`, `picture` the format `--out` asks for
/// (`None`: no picture).
pub fn atlas_of(
    args: &MotionArtArgs,
    format: Format,
    picture: Option<PictureFormat>,
) -> Result<Option<AtlasArt>, Error> {
    let Some(path) = &args.atlas else {
        if args.art_only {
            return Err(Error::input("--art-only draws a character's art: give its atlas with --atlas FILE.atlas"));
        }
        return Ok(None);
    };
    if format == Format::DragonBones {
        return Err(Error::input(format!(
            "--atlas {}: DragonBones characters are drawn as bones only (their art is not read); leave out --atlas",
            path.display()
        )));
    }
    if picture.is_none() {
        return Err(Error::input(format!(
            "--atlas {}: the art is drawn in a picture: give --out FILE.gif, FILE.png or FILE.svg",
            path.display()
        )));
    }
    AtlasArt::read_file(path).map(Some)
}

/// What a motion's art is drawn as: the format `--out` asks for, at the size of its flags;
/// `fewer` says how the command makes fewer frames (for a cap's refusal).
pub struct ArtOut<'a> {
    /// `--out`'s format.
    pub format: PictureFormat,
    /// `--out`, `--width`, `--height`, the GIF cap.
    pub picture: &'a PictureArgs,
    /// `a lower --fps or a shorter --duration`, `fewer --samples`.
    pub fewer: &'a str,
}

/// `motion` drawn with `atlas`'s art as `out` asks; `label` names the character file in errors
/// (`rig file s.json`).
pub fn draw(
    label: &str,
    motion: &Motion<'_>,
    (args, atlas): (&MotionArtArgs, &AtlasArt),
    out: &ArtOut<'_>,
) -> Result<Vec<u8>, Error> {
    let fewer = out.fewer;
    let drawn = posed_with_art(motion, atlas).map_err(|e| match e {
        MotionArtError::Pose(m) => Error::input(format!("{label}: {m}")),
        MotionArtError::Art(m) => {
            let path = args.atlas.as_ref().map_or_else(String::new, |p| p.display().to_string());
            Error::input(format!("atlas file {path}: {m}"))
        }
        MotionArtError::Cap(m) => Error::input(format!("--out: {m} ({fewer})")),
    })?;
    let frames = drawn.poses.len();
    let drawing = art_drawing(motion, &drawn.poses, drawn.arts, args.placement());
    draw_for_command(&drawing, out.format, out.picture, frames)
}
