//! Pictures of planar arms and skeletons: SVG, PNG and animated GIF of poses, motions, workspaces and ease
//! curves.
//!
//! Every picture is first an SVG document written by this crate (the SVG is the master); PNG
//! and GIF are that SVG rasterised by resvg. Text is set in DejaVu Sans, embedded in the
//! binary: system fonts are never loaded, so a picture is the same on every machine.
//!
//! - [`arm_svg`] / [`arm_png`]: an [`ArmFigure`] — the arm at a pose over a grid, with the
//!   reach circle, the shaded reachable area ([`Reachable`]: the exact region with true arcs,
//!   or a sampled grid), ghosts of earlier poses, the paths of the joints, the
//!   goal and a caption. [`ArmFigure::of_animation`] overlays a whole motion.
//! - [`skeleton_svg`] / [`skeleton_png`]: a [`SkeletonFigure`] — a skeleton (a tree of bones)
//!   at a pose, with the limits as wedges, goals for bone tips ([`BoneGoal`]), pins and names.
//! - [`animation_gif`]: an animation as a looping GIF, one frame per animation frame;
//!   [`skeleton_gif`] the same for a skeleton's motion.
//! - [`ease_svg`] / [`ease_png`]: an ease curve's position and velocity against time.
//! - [`PathLayer`]: a tracked path over either (the wanted path, the tip's trace, flips).
//! - [`svg_to_png`]: any SVG to PNG with the embedded fonts.
//! - [`draw_art`] / [`art_pixmap`]: a character's [`Art`] (atlas [`Page`]s and textured
//!   [`ArtPiece`]s) rasterised into a premultiplied [`Pixmap`]; [`draw_svg_onto`] draws an SVG
//!   (the bones) over it and [`pixmap_png`] encodes it. [`character_art_png`] /
//!   [`character_art_svg`]: a posed character's art under its bones; [`art_only_png`] the art
//!   alone, fitted as Spine's reference pictures are. [`character_art_gif`]: a character's
//!   motion ([`CharacterArtMotion`]) with every frame's art, under the bones or alone;
//!   [`character_art_motion_png`] / [`character_art_motion_svg`] its last frame's art in one
//!   picture.
//!
//! [`View`] maps world coordinates to pixels, for callers that want to find something on the
//! picture.

mod animation;
mod arm;
mod art;
mod art_raster;
mod character;
mod character_art;
mod character_art_motion;
mod character_gif;
mod ease_plot;
mod error;
mod palette;
mod path;
mod raster;
mod reachable;
mod scene;
mod skeleton;
mod skeleton_gif;
mod style;
mod svg;
mod view;
mod wedge;

pub use animation::{MAX_FPS, Overlay, animation_gif, ghost_frames, with_interrupt};
pub use arm::{ArmFigure, MAX_ANIMATION_GHOSTS, arm_png, arm_svg};
pub use art::{Art, ArtPiece, Blend, MAX_PAGE_SIDE, Page, WorldToPixel};
pub use art_raster::{art_pixmap, draw_art};
pub use character::{CharacterFigure, PosedBone, character_png, character_svg};
pub use character_art::{ART_FILL, art_only_pixmap, art_only_png, art_only_svg, character_art_png, character_art_svg};
pub use character_art_motion::{
    ArtPlacement, CharacterArtMotion, character_art_gif, character_art_motion_png, character_art_motion_svg,
};
pub use character_gif::{CharacterMotionFigure, character_gif, character_motion_svg};
pub use ease_plot::{ease_png, ease_svg};
pub use error::RenderError;
pub use path::PathLayer;
pub use raster::{MAX_SIDE, MIN_SIDE, draw_svg_onto, pixmap_png, svg_to_png};
pub use reachable::Reachable;
/// The premultiplied RGBA8 picture [`draw_art`] draws on and [`draw_svg_onto`] draws over
/// (tiny-skia's, as resvg uses it).
pub use resvg::tiny_skia::Pixmap;
pub use scene::TrailStyle;
pub use skeleton::{BoneGoal, SkeletonFigure, skeleton_png, skeleton_svg};
pub use skeleton_gif::skeleton_gif;
pub use style::{COLOURS, Colours};
pub use view::{FIT_MARGIN, PixelRect, VIEW_PADDING, View};
