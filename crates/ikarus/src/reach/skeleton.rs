//! The sampled region of one bone's tip of a [`Skeleton`]: what [`super::sample`] does for a
//! chain, for a body its two-joint slices cannot take (offsets, slides, a tree). See
//! [`sample_skeleton`].

use nalgebra::Point2;

use super::raster::Raster;
use super::sampling::{Plan, Range};
use super::{Annulus, ReachError, Workspace, WorkspaceOptions, paint_samples};
use crate::skeleton::{Joint, Skeleton};

/// Joint-space samples per cell of the grid when [`WorkspaceOptions::samples`] is `None`
/// (4.2 million at resolution 256), at most 2²⁴ in all.
pub const SKELETON_SAMPLES_PER_CELL: u64 = 64;

/// The most samples taken when [`WorkspaceOptions::samples`] is `None`.
const MAX_AUTOMATIC: u64 = 1 << 24;

/// The range sampled for joint `j` of `skeleton` (see the [module docs](self)).
fn range(skeleton: &Skeleton, j: usize, use_limits: bool) -> Range {
    let limits = skeleton.limits()[j];
    match skeleton.joint(j) {
        Joint::Revolute => Range::of(limits, use_limits),
        Joint::Prismatic { .. } => match limits {
            Some(l) => Range { lo: l.min(), span: l.max() - l.min(), full: false },
            None => {
                let (start, length) = (skeleton.start_angles()[j], skeleton.lengths()[j]);
                Range { lo: start - length, span: 2.0 * length, full: false }
            }
        },
    }
}

/// Samples the region the tip of bone `bone` of `skeleton` reaches. Its errors are the
/// options'.
///
/// Every joint on the path from the root to the bone is sampled (the others stay at their start
/// values: they do not move the tip), by the same plans as a chain's sampled joints (a regular
/// grid for one or two, the warped R_d sequence for three or more; see the [module
/// docs](super)), and forward kinematics puts the tip of each sample into its cell. A joint
/// samples its range: a revolute one its limits (with `limits` on) or a full turn; a prismatic
/// one its limits whether or not `limits` is on (a slide's limits are its rail), or, without
/// limits, its start ± its bone's length, the range the solver's restarts draw a free slide
/// from. The grid is the square `base ± R`, `R` the skeleton's [`Skeleton::max_reach`] (no tip
/// gets farther), and [`Workspace::annulus`] is the disk of radius `R`, a superset.
///
/// So the grid is a sample, never exact ([`Workspace::is_exact`] is `false`): **sound** (each
/// occupied cell holds a reachable tip, a pose within the ranges), and **complete** only up to
/// the sampling: a cell the sampled tips miss stays empty, and a cell the region only touches
/// is occupied (the rule of rasterised points, which over-counts the area by about
/// `0.64 · h · perimeter` for a cell side `h`; a chain's grid uses cell centres instead). The
/// count is [`WorkspaceOptions::samples`], by default [`SKELETON_SAMPLES_PER_CELL`] per cell
/// of the grid (at most 2²⁴). Deterministic: each sample is a function of its index, and the
/// cells are merged by OR, whatever the threads.
///
/// # Panics
/// If `bone >= skeleton.len()`.
pub fn sample_skeleton(skeleton: &Skeleton, bone: usize, options: &WorkspaceOptions) -> Result<Workspace, ReachError> {
    options.validate()?;
    let resolution = options.resolution;
    let reach = skeleton.max_reach();
    let base = skeleton.base();
    let cell_size = 2.0 * reach / f64::from(resolution);
    let raster = Raster::new([base.x - reach, base.y - reach], cell_size, resolution);
    let mut path = skeleton.path(bone);
    path.sort_unstable();
    let ranges: Vec<Range> = path.iter().map(|&j| range(skeleton, j, options.limits)).collect();
    let travels: Vec<f64> = path
        .iter()
        .zip(&ranges)
        .map(|(&j, r)| match skeleton.joint(j) {
            Joint::Revolute => reach * r.span,
            Joint::Prismatic { .. } => r.span,
        })
        .collect();
    let cells = u64::from(resolution) * u64::from(resolution);
    let samples = options.samples.unwrap_or((cells * SKELETON_SAMPLES_PER_CELL).min(MAX_AUTOMATIC));
    let plan = Plan::over(&travels, samples, options.seed);
    let total = plan.count();
    let n = skeleton.len();
    let scratch = || (skeleton.start_angles().to_vec(), vec![Point2::origin(); n + 1], vec![0.0; n]);
    paint_samples(total, options, &|_, _| {}, scratch, |(angles, points, directions), i| {
        for (k, (&j, &r)) in path.iter().zip(&ranges).enumerate() {
            angles[j] = plan.angle(r, k, i);
        }
        skeleton.points_into(angles, points, directions);
        let tip = points[bone + 1];
        raster.mark([tip.x, tip.y]);
    })?;
    let disk = Annulus { center: base, inner: 0.0, outer: reach };
    Ok(Workspace::new(disk, raster, options.limits, total, false))
}
