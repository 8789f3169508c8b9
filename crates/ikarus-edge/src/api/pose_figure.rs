//! Figure `pose` of `POST /api/render`: a character in one pose, drawn as `ikarus pose --out
//! x.png|svg` draws it: its bones and targets, with an atlas its art under them, with
//! `art_only` the art alone (transparent, the art's box fitted at 90 %).
//!
//! Refused, in one line: `art_only` without `atlas`; an atlas sent without its page images
//! (the page draws the art itself from `/api/pose`'s `art`; a picture needs the images);
//! `format` `gif` (one pose does not animate); and what `/api/pose` refuses.

use ikarus::Interrupt;
use ikarus::character::DrawList;

use super::atlases::drawable;
use super::fields::picture;
use super::figures::PoseFigureReq;
use super::pose::Posing;
use super::wire::{Limits, Problem};
use crate::picture::{PictureFormat, pose_drawn};

/// The picture of `r` in `format`, `w` × `h` pixels.
pub(super) fn pose_figure(
    r: PoseFigureReq,
    (format, w, h): (PictureFormat, u32, u32),
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    let (req, art_only) = r.into_pose();
    let posing = Posing::of(req, limits)?;
    drawable(posing.atlas.as_deref(), art_only)?;
    let drawn = posing.drawn(interrupt)?;
    let c = &posing.stored.loaded.character;
    let figure = || drawn.report.figure(None);
    let bytes = match &posing.atlas {
        None => match format {
            PictureFormat::Svg => ikarus_render::character_svg(&figure(), w, h).map(String::into_bytes),
            _ => ikarus_render::character_png(&figure(), w, h),
        },
        Some(atlas) => {
            let art = atlas
                .art
                .art(c, &drawn.posed, (drawn.skin, drawn.clip), &mut DrawList::default())
                .map_err(|e| Problem::invalid(format!("atlas: {e}")))?;
            match (format, art_only) {
                (PictureFormat::Svg, true) => ikarus_render::art_only_svg(&art, w, h).map(String::into_bytes),
                (PictureFormat::Svg, false) => {
                    ikarus_render::character_art_svg(&figure(), &art, w, h).map(String::into_bytes)
                }
                (_, true) => ikarus_render::art_only_png(&art, w, h),
                (_, false) => ikarus_render::character_art_png(&figure(), &art, w, h),
            }
        }
    };
    picture(bytes.map_err(pose_drawn), interrupt)
}

#[cfg(test)]
#[path = "pose_figure_tests.rs"]
mod tests;
