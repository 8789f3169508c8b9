//! The reachable workspace of a chain: where its tip can go.
//!
//! [`exact`] computes the region exactly, as arcs, under the limits ([`Region`]); the rest of
//! this module samples it onto a grid ([`sample`], [`Workspace`]).
//!
//! Orientation is ignored throughout: a point is reachable when some pose within the joint
//! ranges puts the tip there, whichever way the last link points.
//!
//! # Without limits: an annulus, exactly
//!
//! When every joint turns freely the reachable set is the closed annulus about the base with
//! outer radius `Σl` and inner radius `max(0, l_max − (Σl − l_max))` ([`Annulus::of`]).
//!
//! # The occupancy grid
//!
//! [`sample`] rasterises the reachable set into a square grid of `resolution × resolution` cells
//! covering `[base − R, base + R]²` with `R = Σl` (no margin: the set lies in the closed disk of
//! radius `R`, and a point on the square's right or top edge belongs to the last column or row).
//!
//! **A cell is occupied when its centre is reachable**, the rule a renderer uses to fill a shape.
//! The alternative, marking every cell the set touches, is what rasterising sampled tip
//! positions converges to, and it over-counts the area by about `0.64 · h · perimeter` for a
//! cell size `h`: +0.9 % for the seed arm's disk and +1.6 % for the annulus of lengths
//! (5, 1, 1) at resolution 256. The centre rule is unbiased (−0.008 % and −0.02 % there), so
//! `area() = occupied cells × h²` estimates the true area. The price is that a reachable point
//! within about half a cell of the boundary may sit in a cell whose centre is not reachable,
//! and the other way round: [`Workspace::contains`] is exact only up to the cell.
//!
//! When every joint is free (limits off, or none set) the grid is the annulus, rasterised
//! directly. Otherwise it is computed as follows.
//!
//! # Method: exact two-joint slices, sampled over the other joints
//!
//! Fix every joint but the last two. The last two links then reach an exactly known 2D slice,
//! and a square root and a few products decide whether a point lies in it: the law of cosines
//! gives the elbow angle, a complex division the shoulder direction, and both are checked
//! against their ranges as sectors of directions, without trigonometry. So the grid is the
//! union, over a joint-space sample of the other joints, of the centre-rule rasterisation of
//! each sample's slice. With `m` sampled joints:
//!
//! - `m = 0` (two joints): one slice, the grid is exact;
//! - `m = 1`: a regular grid of `n` angles over the joint's range, ends included;
//! - `m = 2`: a regular `n₀ × n₁ ≤ n` grid, split so that both joints move the tip by the same
//!   step;
//! - `m ≥ 3`: the Kronecker sequence of Roberts' generalised golden ratio ("R_d"), shifted by
//!   `seed`, with extra weight on the angles that make the boundary (each range's ends, and
//!   straight; see below).
//!
//! The count `n` is [`WorkspaceOptions::samples`] if set, and by default grows with `m`:
//! `min(4096 · 4^(m−1), 262144)` ([`WorkspaceOptions::automatic_samples`], where the
//! measurements behind it are).
//!
//! Each slice is a 2D region, so the union fills the set from the inside: consecutive slices
//! overlap and no holes open between samples as they do between sampled curves. Where the slices
//! sweep past the boundary smoothly the shortfall is second order in the joint step; near the
//! trace of a slice's corner it can be up to the tip's travel between samples,
//! `Σ_k lever_k · step_k`, which is 0.0023 on the seed arm with the default options, a twentieth
//! of a cell at resolution 256. (In fact 129 samples already give the seed arm the same grid as
//! 65537 at resolutions 256 and 512.)
//!
//! For `m ≥ 3`, uniform samples almost never draw the poses that make the boundary: at a pose
//! whose tip lies on the boundary, every joint off its limits must move the tip along the
//! boundary, so it lies on the boundary's normal through the tip: it is at a limit or aligned,
//! and straight is the commonest alignment. A fraction `p = min(½, 2/m)` of each joint's sample
//! values is therefore put on its two ends and on 0 (a third each), about two such joints per
//! sample. With 4096 samples at resolution 256 this finds 4–5 % more area on five- and seven-link
//! arms than the plain sequence, and 0.7 % less on a twenty-link arm.
//!
//! Joints whose whole range moves the tip by less than a sixteenth of a cell are locked at the
//! middle of their range and folded into a rigid link, so that a locked wrist does not make every
//! slice a curve. A chain with fewer than two joints left to move reaches a curve or a point,
//! which has no area and so occupies no cells (a one-link chain's annulus has area 0 as well).
//!
//! # Guarantees
//!
//! - **Sound**: every occupied cell's centre is reachable within the limits (up to rounding in
//!   the last bits of the membership test).
//! - **Exact** ([`Workspace::is_exact`]) when every joint is free or at most two move.
//! - **Complete** up to the shortfall above for three or four movable joints. For more, the
//!   sample is sparse in joint space and regions that need rare poses are under-covered, which
//!   the automatic count makes up for up to about seven movable joints: on the seven-link
//!   example arm at resolution 256 it finds 215.45 where 4096 samples find 205.0 and 4194304
//!   find 215.76. On a twenty-link arm of ±60° joints it finds 268.0 (4096: 233.5), and the
//!   area still grows by about 1 % per doubling beyond (278.9 at 4194304).
//! - **Deterministic**: every sample is a pure function of `(chain, options, index)`, and the
//!   grids of all samples are merged by OR, which does not depend on order. The result is the
//!   same bit for bit whatever the number of threads, and with `parallel` on or off. No random
//!   number generator is needed: the grids and the R_d sequence are addressed by index, so
//!   chunks need no separate streams; `seed` only matters for five or more movable joints.
//!
//! # Cost
//!
//! Work is `samples × (cells within reach of the last two links)`, each a handful of
//! floating-point operations without allocation; cells outside a slice's cone of directions are
//! rejected after a few products, and cells already occupied are skipped. Memory is one bit per
//! cell while sampling (shared by all threads) and one `bool` per cell in the result. Both are
//! bounded by the validated options.

pub mod exact;
pub use exact::{BoundarySegment, Membership, Region, RegionError, RegionOptions, Verdict};
mod outline;
pub use outline::{OUTLINE_AVERAGING, OUTLINE_SMOOTHING};
mod raster;
mod region;
mod sampling;
mod skeleton;
pub use skeleton::{SKELETON_SAMPLES_PER_CELL, sample_skeleton};
#[cfg(test)]
mod tests;

use std::f64::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};

use nalgebra::Point2;
use rayon::prelude::*;
use thiserror::Error;

use crate::chain::Chain;
use raster::{Raster, cell_centre, cell_index};
use region::Sampler;
use sampling::{Plan, Range, Reduced};

/// The set reachable by a chain whose joints all turn freely: the closed annulus
/// `inner ≤ |p − center| ≤ outer`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Annulus {
    /// The chain's base.
    pub center: Point2<f64>,
    /// Inner radius, `max(0, l_max − (Σl − l_max))`.
    pub inner: f64,
    /// Outer radius, `Σl`.
    pub outer: f64,
}

impl Annulus {
    /// The annulus of `chain`, ignoring its limits.
    ///
    /// The tip is `base + Σ l_k e^{iφ_k}`. By the triangle inequality its distance from the base
    /// is at most `Σl` and at least `l_max − (Σl − l_max)`; every distance in between is
    /// attained (it is continuous on the connected set of poses), and turning the first joint
    /// turns the tip about the base, so the set is the whole annulus.
    #[must_use]
    pub fn of(chain: &Chain) -> Annulus {
        Annulus { center: chain.base(), inner: chain.min_reach(), outer: chain.max_reach() }
    }

    /// `π (outer² − inner²)`.
    #[must_use]
    pub fn area(&self) -> f64 {
        PI * (self.outer + self.inner) * (self.outer - self.inner)
    }

    /// Whether `inner ≤ |p − center| ≤ outer`, with no tolerance.
    #[must_use]
    pub fn contains(&self, p: Point2<f64>) -> bool {
        let d = crate::math::distance_between(self.center, p);
        self.inner <= d && d <= self.outer
    }
}

/// How [`sample`] computes a [`Workspace`]. Build with `..WorkspaceOptions::default()`.
#[derive(Debug, Clone, PartialEq)]
pub struct WorkspaceOptions {
    /// Cells along each side of the square grid, in `8..=4096`. Default 256.
    pub resolution: u32,
    /// Respect the chain's joint limits; `false` lets every joint make a full turn.
    /// Default `true`.
    pub limits: bool,
    /// Joint-space samples of the joints before the last two (each sample contributes an
    /// exactly rasterised 2D slice): `Some(n)` with `n` in `1..=10⁹`, or `None` for
    /// [`automatic_samples`](Self::automatic_samples) of the number of sampled joints. Ignored
    /// when every joint is free or at most two move. Default `None`.
    pub samples: Option<u64>,
    /// Shifts the quasi-random sequence used for five or more movable joints. Default 0.
    pub seed: u64,
    /// Spread the samples over rayon's global thread pool; `false` stays on the calling
    /// thread. The result is identical either way. Default `false`: the library starts no
    /// thread it was not asked for (a command line that samples one large grid asks; a server
    /// whose workers already run side by side does not).
    pub parallel: bool,
    /// Stops the sampling when set (checked before every joint-space sample): [`sample`]
    /// returns [`ReachError::Interrupted`]. Default `None`.
    pub interrupt: Option<crate::Interrupt>,
}

impl WorkspaceOptions {
    /// Smallest allowed [`resolution`](Self::resolution).
    pub const MIN_RESOLUTION: u32 = 8;
    /// Largest allowed [`resolution`](Self::resolution) (16.8 million cells).
    pub const MAX_RESOLUTION: u32 = 4096;
    /// Largest allowed [`samples`](Self::samples).
    pub const MAX_SAMPLES: u64 = 1_000_000_000;

    /// The sample count when [`samples`](Self::samples) is `None`, for `m` sampled joints (the
    /// movable joints before the last two, after locking the narrow ones):
    /// `min(4096 · 4^(m−1), 262144)`, that is 4096 for one (or none), 16384 for two, 65536 for
    /// three and 262144 for four or more.
    ///
    /// One sampled joint needs no more: on the seed arm the tip moves about 0.002 between
    /// neighbouring samples, a twentieth of a cell at resolution 256, and the area is the same
    /// from 1024 samples to 1048576. With more sampled joints a fixed count is ever sparser in
    /// joint space: the shortfall at 4096 samples is up to 1.4 % for two to four (depending on
    /// the arm more than on `m`), 5 % for five (the seven-link arm) and 16 % for eighteen (a
    /// twenty-link arm). Measured at resolution 256 in release on two cores (times vary by
    /// about 15 % between runs), area and time with 4096 samples, with the automatic count, and
    /// with the most samples tried:
    ///
    /// | arm | `m` | 4096 | automatic | most |
    /// |-----|-----|------|-----------|------|
    /// | seed (3, 2, 1) | 1 | 41.247, 50 ms | the same | 41.247 at 2²⁰ |
    /// | four links 0.5, ±60° | 2 | 6.726, 0.13 s | 6.782, 0.5 s | 6.822 at 2¹⁹ |
    /// | five links 0.5, ±60° | 3 | 14.371, 53 ms | 14.531, 0.7 s | 14.557 at 2²⁰ |
    /// | `seven.toml`, first six links | 4 | 183.01, 13 ms | 185.42, 0.8 s | 185.43 at 2²⁰ |
    /// | `seven.toml` | 5 | 205.00, 8 ms | 215.45, 0.4 s | 215.76 at 2²² |
    /// | twenty links 0.5, ±60° | 18 | 233.5, 8 ms | 268.0, 0.3 s | 278.9 at 2²² |
    ///
    /// So the automatic count stays within 0.6 % of the most samples tried for up to five
    /// sampled joints, where 4096 samples fall up to 5 % short; many more joints would need
    /// far more samples than the cap (pass `Some(n)`). The time per sample varies tenfold
    /// between arms, with the number of cells the last two links sweep; at resolution 512 it is
    /// about four times as much.
    #[must_use]
    pub const fn automatic_samples(sampled_joints: usize) -> u64 {
        let k = if sampled_joints < 4 { sampled_joints.saturating_sub(1) } else { 3 };
        4096 << (2 * k)
    }

    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), ReachError> {
        let (lo, hi) = (Self::MIN_RESOLUTION, Self::MAX_RESOLUTION);
        if !(lo..=hi).contains(&self.resolution) {
            return Err(ReachError::OutOfRange {
                field: "resolution",
                expected: "8..=4096",
                value: u64::from(self.resolution),
            });
        }
        if let Some(samples) = self.samples.filter(|n| !(1..=Self::MAX_SAMPLES).contains(n)) {
            return Err(ReachError::OutOfRange { field: "samples", expected: "1..=1000000000", value: samples });
        }
        Ok(())
    }
}

impl Default for WorkspaceOptions {
    fn default() -> Self {
        Self { resolution: 256, limits: true, samples: None, seed: 0, parallel: false, interrupt: None }
    }
}

/// Why [`WorkspaceOptions`] are invalid. Every variant names the field and the value.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ReachError {
    /// A number is out of its range.
    #[error("{field}: must be in {expected}, got {value}")]
    OutOfRange {
        /// The option's name.
        field: &'static str,
        /// The allowed range.
        expected: &'static str,
        /// The offending value.
        value: u64,
    },
    /// [`WorkspaceOptions::interrupt`] was set before the sampling was done.
    #[error("interrupted")]
    Interrupted,
}

/// The reachable region of a chain as an occupancy grid; see the [module docs](self) for what a
/// cell means and how it is computed.
///
/// Cell `(ix, iy)` is column `ix` (x ascending) and row `iy` (y ascending); it covers
/// `origin + h·[ix, ix + 1) × h·[iy, iy + 1)` with `h = cell_size()`.
#[derive(Debug, Clone, PartialEq)]
pub struct Workspace {
    annulus: Annulus,
    resolution: u32,
    origin: Point2<f64>,
    cell_size: f64,
    limits: bool,
    samples: u64,
    exact: bool,
    cells: Vec<bool>,
    occupied: u64,
}

impl Workspace {
    /// The chain's annulus (exact, ignoring limits): the region when `limits` is off, and a
    /// superset of it when on.
    #[must_use]
    pub fn annulus(&self) -> Annulus {
        self.annulus
    }

    /// Cells along each side.
    #[must_use]
    pub fn resolution(&self) -> u32 {
        self.resolution
    }

    /// Side of a cell: `2 Σl / resolution`.
    #[must_use]
    pub fn cell_size(&self) -> f64 {
        self.cell_size
    }

    /// Lower-left corner of cell `(0, 0)`: `base − (Σl, Σl)`.
    #[must_use]
    pub fn origin(&self) -> Point2<f64> {
        self.origin
    }

    /// Centre of cell `(ix, iy)`: `origin + h·(ix + ½, iy + ½)` (computed for any indices).
    #[must_use]
    pub fn cell_center(&self, ix: u32, iy: u32) -> Point2<f64> {
        Point2::new(cell_centre(self.origin.x, self.cell_size, ix), cell_centre(self.origin.y, self.cell_size, iy))
    }

    /// The cell holding `p`, or `None` outside the closed square (or for a non-finite `p`).
    /// Points on the square's right or top edge belong to the last column or row.
    #[must_use]
    pub fn cell_of(&self, p: Point2<f64>) -> Option<(u32, u32)> {
        let index = |v: f64, o: f64| cell_index(v, o, self.cell_size, self.resolution);
        Some((index(p.x, self.origin.x)?, index(p.y, self.origin.y)?))
    }

    /// Whether cell `(ix, iy)` is occupied; `false` outside the grid.
    #[must_use]
    pub fn is_occupied(&self, ix: u32, iy: u32) -> bool {
        ix < self.resolution && iy < self.resolution && self.cells[self.at(ix, iy)]
    }

    /// Whether the cell holding `p` is occupied; `false` outside the grid.
    #[must_use]
    pub fn contains(&self, p: Point2<f64>) -> bool {
        self.cell_of(p).is_some_and(|(ix, iy)| self.is_occupied(ix, iy))
    }

    /// Number of occupied cells.
    #[must_use]
    pub fn occupied_cells(&self) -> u64 {
        self.occupied
    }

    /// Occupied cells × `cell_size²`: an estimate of the reachable area.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.occupied as f64 * self.cell_size * self.cell_size
    }

    /// The grid row by row, bottom row (`iy = 0`) first; each row runs from `ix = 0`.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = &[bool]> {
        self.cells.chunks_exact(self.resolution as usize)
    }

    /// Whether the joint limits were respected.
    #[must_use]
    pub fn limits(&self) -> bool {
        self.limits
    }

    /// Joint-space samples actually taken: 0 when every joint is free (the grid is then the
    /// annulus, rasterised exactly) or fewer than two joints move, 1 for two movable joints,
    /// `n₀ n₁ ≤ n` for four, else `n`, where `n` is the
    /// [`samples`](WorkspaceOptions::samples) asked for or else the
    /// [automatic count](WorkspaceOptions::automatic_samples).
    #[must_use]
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Whether the grid is exactly the set of cells whose centre is reachable (up to rounding):
    /// when every joint is free (the annulus), or when at most two joints move and none was
    /// locked for being narrower than a sixteenth of a cell. Otherwise it is sampled.
    #[must_use]
    pub fn is_exact(&self) -> bool {
        self.exact
    }

    fn new(annulus: Annulus, raster: Raster, limits: bool, samples: u64, exact: bool) -> Workspace {
        let (resolution, cell_size) = (raster.resolution, raster.h);
        let origin = Point2::new(raster.origin[0], raster.origin[1]);
        let cells = raster.into_cells();
        let occupied = cells.iter().filter(|&&c| c).count() as u64;
        Workspace { annulus, resolution, origin, cell_size, limits, samples, exact, cells, occupied }
    }

    fn at(&self, ix: u32, iy: u32) -> usize {
        iy as usize * self.resolution as usize + ix as usize
    }
}

/// Samples the reachable region of `chain`; see the [module docs](self).
pub fn sample(chain: &Chain, options: &WorkspaceOptions) -> Result<Workspace, ReachError> {
    sample_with_progress(chain, options, &|_, _| {})
}

/// [`sample`], calling `progress(done, total)` with the number of joint-space samples finished:
/// once with `(0, total)` first, after each of at most 1024 chunks, and once with
/// `(total, total)` last. With `parallel` the calls in between come from the pool's threads and
/// may arrive out of order.
pub fn sample_with_progress(
    chain: &Chain,
    options: &WorkspaceOptions,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Workspace, ReachError> {
    run(chain, options, progress, false)
}

/// [`sample_with_progress`]; with `force_sampling` it samples even when every joint is free
/// (the tests compare that with the annulus).
fn run(
    chain: &Chain,
    options: &WorkspaceOptions,
    progress: &(dyn Fn(u64, u64) + Sync),
    force_sampling: bool,
) -> Result<Workspace, ReachError> {
    options.validate()?;
    let resolution = options.resolution;
    let reach = chain.max_reach();
    let cell_size = 2.0 * reach / f64::from(resolution);
    let origin = Point2::new(chain.base().x - reach, chain.base().y - reach);
    let annulus = Annulus::of(chain);
    let raster = Raster::new([origin.x, origin.y], cell_size, resolution);
    let free = chain.limits().iter().all(|&l| Range::of(l, options.limits).full);
    if free && !force_sampling {
        progress(0, 0);
        let [cx, cy] = [annulus.center.x, annulus.center.y];
        let bounds = [cx - reach, cx + reach, cy - reach, cy + reach];
        raster.paint_disk([cx, cy], reach, bounds, |q| annulus.contains(Point2::new(q[0], q[1])));
        progress(0, 0);
        return Ok(Workspace::new(annulus, raster, options.limits, 0, true));
    }
    let reduced = Reduced::new(chain, options.limits, cell_size / 16.0);
    let sampled_joints = reduced.segments.len().saturating_sub(2);
    let samples = options.samples.unwrap_or(WorkspaceOptions::automatic_samples(sampled_joints));
    let sampler = Sampler::new(&reduced, samples, options.seed);
    let exact = !reduced.rounded && sampler.as_ref().is_none_or(|s| s.plan == Plan::Single);

    let total = sampler.as_ref().map_or(0, Sampler::count);
    if let Some(sampler) = &sampler {
        paint_samples(total, options, progress, || (), |(), i| raster.paint(&sampler.slice(i)))?;
    } else {
        // No sample: the grid is empty, or the two-joint slice of a chain that is not sampled.
        paint_samples(0, options, progress, || (), |(), _| {})?;
    }
    Ok(Workspace::new(annulus, raster, options.limits, total, exact))
}

/// Runs `each(scratch, i)` for every joint-space sample `i < total`, in at most 1024 chunks
/// (each with its own `scratch()`), on rayon's pool with `options.parallel`; checks the
/// interrupt before every sample and calls `progress` as [`sample_with_progress`] says.
fn paint_samples<S>(
    total: u64,
    options: &WorkspaceOptions,
    progress: &(dyn Fn(u64, u64) + Sync),
    scratch: impl Fn() -> S + Sync,
    each: impl Fn(&mut S, u64) + Sync,
) -> Result<(), ReachError> {
    progress(0, total);
    const MAX_CHUNKS: u64 = 1024;
    let chunk = total.div_ceil(MAX_CHUNKS).max(1);
    // At most 1024 chunks, so the cast is exact.
    let chunks = total.div_ceil(chunk) as usize;
    let done = AtomicU64::new(0);
    let run = |k: usize| {
        let start = k as u64 * chunk;
        let end = (start + chunk).min(total);
        let mut s = scratch();
        for i in start..end {
            if crate::interrupt::is_set(options.interrupt.as_ref()) {
                return;
            }
            each(&mut s, i);
        }
        let now = done.fetch_add(end - start, Ordering::Relaxed) + (end - start);
        if now < total {
            progress(now, total);
        }
    };
    if options.parallel {
        (0..chunks).into_par_iter().for_each(run);
    } else {
        (0..chunks).for_each(run);
    }
    if crate::interrupt::is_set(options.interrupt.as_ref()) {
        return Err(ReachError::Interrupted);
    }
    progress(total, total);
    Ok(())
}
