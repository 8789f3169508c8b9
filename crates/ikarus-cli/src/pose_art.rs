//! `ikarus pose --atlas FILE.atlas`: the character drawn with its art, under its bones or alone
//! (`--art-only`). The atlas and its pages are read, and the pose turned into art, by the edge
//! ([`AtlasArt`]); the pixels are the renderer's.
//!
//! Refused, in one line: `--art-only` without `--atlas`; `--atlas` with a DragonBones file
//! (its art is not read), or with a report that is not a picture (text, JSON); an atlas or a
//! page image that cannot be read (the page's name and the folder searched); an attachment the
//! pose draws whose region is not in the atlas (its name and its slot).

use ikarus::character::{DrawList, Posed};
use ikarus_edge::character::Format;
use ikarus_edge::character::Loaded;
use ikarus_edge::character::art_draw::AtlasArt;
use ikarus_edge::pose::{PoseAsk, clip_at, pose_kept, skin_index};

use std::path::Path;

use crate::error::Error;
use crate::picture::SizeArgs;
pub(crate) use ikarus_edge::picture::pose_drawn as drawn;

/// What `ikarus pose --atlas` was asked to draw: the files, whether the art goes alone, the
/// picture's size and format.
pub struct ArtAsk<'a> {
    /// `--rig`.
    pub rig: &'a Path,
    /// `--atlas`.
    pub atlas: Option<&'a Path>,
    /// `--art-only`.
    pub art_only: bool,
    /// `--width`, `--height`.
    pub size: &'a SizeArgs,
    /// An SVG picture, else a PNG; `None` for a report that is not a picture (text, JSON).
    pub svg: Option<bool>,
}

/// The atlas `--atlas` names, read with its pages, or `None` without it; the refusals of the
/// module's doc that come before posing.
pub fn atlas_of(args: &ArtAsk, loaded: &Loaded) -> Result<Option<AtlasArt>, Error> {
    let Some(path) = args.atlas else {
        if args.art_only {
            return Err(Error::input("--art-only draws a character's art: give its atlas with --atlas FILE.atlas"));
        }
        return Ok(None);
    };
    if loaded.format == Format::DragonBones {
        return Err(Error::input(format!(
            "--atlas {}: DragonBones characters are drawn as bones only (their art is not read); leave out --atlas",
            path.display()
        )));
    }
    if args.svg.is_none() {
        return Err(Error::input(format!(
            "--atlas {}: the art is drawn in a picture: give --out FILE.png or FILE.svg (or --format png|svg)",
            path.display()
        )));
    }
    AtlasArt::read_file(path).map(Some)
}

/// The pose `ask` of `loaded` drawn with `atlas`'s art in `format` (PNG or SVG), at the size of
/// `args`: the art alone with `--art-only`, else under the bones, captioned by `caption`.
pub fn draw(
    args: &ArtAsk,
    loaded: &Loaded,
    ask: &PoseAsk,
    atlas: &AtlasArt,
    caption: &dyn Fn() -> String,
) -> Result<Vec<u8>, Error> {
    let label = format!("rig file {}", args.rig.display());
    let c = &loaded.character;
    let mut posed = Posed::default();
    let report = pose_kept(loaded, ask, &mut posed).map_err(|m| Error::input(format!("{label}: {m}")))?;
    let skin = skin_index(c, ask.skin.as_deref()).map_err(|m| Error::input(format!("{label}: {m}")))?;
    let atlas_label = args.atlas.map_or_else(String::new, |p| format!("atlas file {}: ", p.display()));
    let clip = clip_at(c, ask.animation.as_deref(), ask.time).map_err(|m| Error::input(format!("{label}: {m}")))?;
    let art = atlas
        .art(c, &posed, (skin, clip), &mut DrawList::default())
        .map_err(|m| Error::input(format!("{atlas_label}{m}")))?;
    let (width, height) = (args.size.width, args.size.height);
    let bytes = match (args.svg, args.art_only) {
        (Some(false), true) => ikarus_render::art_only_png(&art, width, height),
        (Some(true), true) => ikarus_render::art_only_svg(&art, width, height).map(String::into_bytes),
        (Some(false), false) => ikarus_render::character_art_png(&report.figure(Some(caption())), &art, width, height),
        (Some(true), false) => ikarus_render::character_art_svg(&report.figure(Some(caption())), &art, width, height)
            .map(String::into_bytes),
        (None, _) => {
            return Err(Error::input("--atlas: the art is drawn in a picture: give --out FILE.png or FILE.svg"));
        }
    };
    bytes.map_err(drawn)
}
