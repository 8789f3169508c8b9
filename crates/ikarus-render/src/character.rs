//! Still pictures of a posed character (a Spine or DragonBones skeleton): each bone as the
//! editors draw it, a slim kite from its origin to its tip (a ring for a bone of length 0, which
//! is only a frame), its name as the tooltip, and the IK targets as goals.
//!
//! The picture takes the world positions the pose computed; it knows nothing of how they were
//! computed (the runtime's rules or ikarus's solver), so both draw alike.

use ikarus::Point2;

use crate::RenderError;
use crate::error::check_point;
use crate::raster::{check_size, svg_to_png};
use crate::scene::Scene;
use crate::style;
use crate::svg::{PathData, Svg, num};
use crate::view::View;

/// One bone as posed: its name, world origin and world tip.
#[derive(Debug, Clone, PartialEq)]
pub struct PosedBone<'a> {
    /// The bone's name (the tooltip).
    pub name: &'a str,
    /// Where it starts.
    pub origin: Point2<f64>,
    /// Where it ends: its origin for a bone of length 0.
    pub tip: Point2<f64>,
}

/// What a still picture of a posed character shows.
///
/// ```
/// # use ikarus::Point2;
/// # use ikarus_render::{CharacterFigure, PosedBone, character_svg};
/// let figure = CharacterFigure {
///     bones: vec![
///         PosedBone { name: "root", origin: Point2::new(0.0, 0.0), tip: Point2::new(0.0, 0.0) },
///         PosedBone { name: "thigh", origin: Point2::new(0.0, 100.0), tip: Point2::new(10.0, 50.0) },
///     ],
///     targets: vec![Point2::new(20.0, 0.0)],
///     caption: Some("a leg".into()),
/// };
/// let svg = character_svg(&figure, 400, 400)?;
/// assert!(svg.contains("<title>thigh</title>"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct CharacterFigure<'a> {
    /// The bones, parents before children (drawn in this order).
    pub bones: Vec<PosedBone<'a>>,
    /// The IK targets' positions: red goals.
    pub targets: Vec<Point2<f64>>,
    /// A line of text under the plot.
    pub caption: Option<String>,
}

impl CharacterFigure<'_> {
    /// The world box `(min, max)` of the bones and targets.
    #[must_use]
    pub fn extent(&self) -> (Point2<f64>, Point2<f64>) {
        let mut points = self.bones.iter().flat_map(|b| [b.origin, b.tip]).chain(self.targets.iter().copied());
        let first = points.next().unwrap_or_else(Point2::origin);
        points.fold((first, first), |(min, max), p| (min.inf(&p), max.sup(&p)))
    }

    /// The view this figure is drawn in at `width` × `height`: fitted to its extent.
    #[must_use]
    pub fn view(&self, width: u32, height: u32) -> View {
        let (min, max) = self.extent();
        View::fitting(min, max, width, height)
    }

    pub(crate) fn check(&self) -> Result<(), RenderError> {
        for (i, b) in self.bones.iter().enumerate() {
            check_point(Some(b.origin), &format!("bones[{i}].origin"))?;
            check_point(Some(b.tip), &format!("bones[{i}].tip"))?;
        }
        for (i, &t) in self.targets.iter().enumerate() {
            check_point(Some(t), &format!("targets[{i}]"))?;
        }
        Ok(())
    }
}

/// The figure as an SVG document of `width` × `height` pixels: grid, bones (each a `<g
/// class="bone">` holding its `<title>` and its shape, so a browser shows the name on hover),
/// targets, caption.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096; [`RenderError::NonFinite`] for a bone's
/// origin or tip, or a target, that is not finite.
pub fn character_svg(figure: &CharacterFigure, width: u32, height: u32) -> Result<String, RenderError> {
    check_size(width, height)?;
    figure.check()?;
    Ok(character_svg_in(figure, &[], figure.view(width, height), width, height))
}

/// `figure` drawn in `view` with `ghosts` (earlier poses, checked by the caller) faded under
/// it: grid, ghosts' bones, the figure's bones, its targets, its caption.
pub(crate) fn character_svg_in(
    figure: &CharacterFigure,
    ghosts: &[&CharacterFigure],
    view: View,
    width: u32,
    height: u32,
) -> String {
    character_layers(figure, ghosts, view, (width, height), Layers::All)
}

/// Which parts of a character's picture an SVG holds: all of them; the grid alone, or the
/// bones, targets and caption alone on a transparent page (a picture with art drawn between);
/// or all of them with an image (the art, a `data:` URL) over the grid.
#[derive(Clone, Copy)]
pub(crate) enum Layers<'a> {
    All,
    Grid,
    Bones,
    WithImage(&'a str),
}

/// [`character_svg_in`]'s picture, the `layers` asked for.
pub(crate) fn character_layers(
    figure: &CharacterFigure,
    ghosts: &[&CharacterFigure],
    view: View,
    (width, height): (u32, u32),
    layers: Layers<'_>,
) -> String {
    let base = figure.bones.first().map_or_else(Point2::origin, |b| b.origin);
    let scene = Scene { base, max_reach: 0.0, min_reach: 0.0, view, goal: None, workspace: None, show_reach: false };
    let mut svg = Svg::new(width, height);
    if !matches!(layers, Layers::Bones) {
        scene.background(&mut svg);
    }
    if let Layers::WithImage(href) = layers {
        svg.comment("art");
        svg.image(0.0, 0.0, f64::from(width), f64::from(height), href);
    }
    if matches!(layers, Layers::Grid) {
        return svg.finish();
    }
    let u = scene.view.layout().unit;
    if !ghosts.is_empty() {
        svg.comment("ghosts");
        for ghost in ghosts {
            for bone in &ghost.bones {
                draw_bone(&scene, &mut svg, bone, u, GHOST_OPACITY);
            }
        }
    }
    svg.comment("bones");
    for bone in &figure.bones {
        svg.group("class=\"bone\"");
        svg.title(bone.name);
        draw_bone(&scene, &mut svg, bone, u, SOLID_OPACITY);
        svg.end_group();
    }
    for &t in &figure.targets {
        scene.goal_at(&mut svg, t);
    }
    scene.caption(&mut svg, figure.caption.as_deref(), None);
    svg.finish()
}

/// The figure as PNG bytes: [`character_svg`] rasterised with [`svg_to_png`].
///
/// # Errors
/// As [`character_svg`], and [`RenderError::Encode`] if encoding fails.
pub fn character_png(figure: &CharacterFigure, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    svg_to_png(&character_svg(figure, width, height)?)
}

/// How opaque a bone's kite is drawn: the pose's, and an earlier pose's (a ghost).
const SOLID_OPACITY: f64 = 0.85;
const GHOST_OPACITY: f64 = 0.12;

/// A bone: a kite from the origin, widest a sixth of the way along (a tenth of its drawn
/// length wide, at most 9 px), to the tip, on a white edge, `opacity` opaque; a bone shorter
/// than 2 px on screen is a small ring at its origin (not drawn for a ghost).
fn draw_bone(scene: &Scene, svg: &mut Svg, bone: &PosedBone, u: f64, opacity: f64) {
    let ghost = opacity < SOLID_OPACITY;
    let (x0, y0) = scene.view.world_to_pixel(bone.origin);
    let (x1, y1) = scene.view.world_to_pixel(bone.tip);
    let (dx, dy) = (x1 - x0, y1 - y0);
    let len = dx.hypot(dy);
    if len < 2.0 * u {
        if !ghost {
            svg.circle(
                x0,
                y0,
                3.0 * u,
                &format!("fill=\"#ffffff\" stroke=\"{}\" stroke-width=\"{}\"", style::INK, num(1.4 * u)),
            );
        }
        return;
    }
    let half = (0.05 * len).min(4.5 * u);
    let (nx, ny) = (-dy / len * half, dx / len * half);
    let (mx, my) = (x0 + dx / 6.0, y0 + dy / 6.0);
    let mut d = PathData::new();
    d.move_to(x0, y0).line_to(mx + nx, my + ny).line_to(x1, y1).line_to(mx - nx, my - ny).close();
    let edge = if ghost {
        String::new()
    } else {
        format!(" stroke=\"#ffffff\" stroke-width=\"{}\" stroke-linejoin=\"round\"", num(0.8 * u))
    };
    svg.path(&d, &format!("fill=\"{}\" fill-opacity=\"{}\"{edge}", style::INK, num(opacity)));
    if !ghost {
        svg.circle(x0, y0, 1.8 * u, "fill=\"#ffffff\"");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leg<'a>() -> CharacterFigure<'a> {
        CharacterFigure {
            bones: vec![
                PosedBone { name: "root", origin: Point2::new(0.0, 0.0), tip: Point2::new(0.0, 0.0) },
                PosedBone { name: "thigh <L>", origin: Point2::new(0.0, 100.0), tip: Point2::new(10.0, 50.0) },
                PosedBone { name: "shin", origin: Point2::new(10.0, 50.0), tip: Point2::new(0.0, 5.0) },
            ],
            targets: vec![Point2::new(0.0, 5.0)],
            caption: None,
        }
    }

    #[test]
    fn every_bone_is_one_group_with_its_escaped_name() {
        let svg = character_svg(&leg(), 300, 300).unwrap();
        assert_eq!(svg.matches("<g class=\"bone\">").count(), 3);
        assert!(svg.contains("<title>thigh &lt;L&gt;</title>"), "{svg}");
        // The frame bone is a ring; the other two are kites.
        assert_eq!(svg.matches("fill-opacity=\"0.85\"").count(), 2);
        assert!(svg.contains("<!-- goal -->"));
    }

    #[test]
    fn the_view_holds_every_bone_and_target() {
        let f = leg();
        let (min, max) = f.extent();
        assert_eq!((min.x, min.y, max.x, max.y), (0.0, 0.0, 10.0, 100.0));
        let view = f.view(300, 300);
        for b in &f.bones {
            for p in [b.origin, b.tip] {
                let (x, y) = view.world_to_pixel(p);
                assert!(view.plot_area().contains(x, y), "{p:?}");
            }
        }
    }

    #[test]
    fn a_point_not_finite_is_named() {
        let mut f = leg();
        f.bones[2].tip.y = f64::NAN;
        let e = character_svg(&f, 300, 300).unwrap_err();
        assert!(e.to_string().contains("bones[2].tip.y"), "{e}");
        assert!(character_png(&leg(), 200, 200).unwrap().starts_with(b"\x89PNG"));
    }
}
