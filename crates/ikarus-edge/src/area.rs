//! The reachable area of an arm as the edges ask for it, one workflow for the command line and
//! the server: the exact region ([`Region::of`], the default) or, when asked, a sampled
//! occupancy grid (`--grid`, `"grid": true`).

use ikarus::Interrupt;
use ikarus::reach::{Region, RegionError, RegionOptions, Workspace, WorkspaceOptions};

use crate::arm::Arm;
use crate::body::Body;
use crate::error::Error;
use crate::rig::Rig;

/// The default of `--resolution` and of a request's `resolution`: the library's.
pub fn default_resolution() -> u32 {
    WorkspaceOptions::default().resolution
}

/// A computed reachable area.
pub enum ReachableArea {
    /// The exact region: loops of lines and arcs.
    Exact(Region),
    /// The occupancy grid sampled from joint space.
    Grid(Workspace),
}

impl ReachableArea {
    /// Whether the joint ranges were respected.
    pub fn limits(&self) -> bool {
        match self {
            ReachableArea::Exact(r) => r.limits(),
            ReachableArea::Grid(w) => w.limits(),
        }
    }

    /// The area: exact, or the occupied cells'.
    pub fn area(&self) -> f64 {
        match self {
            ReachableArea::Exact(r) => r.area(),
            ReachableArea::Grid(w) => w.area(),
        }
    }

    /// What a picture shades.
    pub fn layer(&self) -> ikarus_render::Reachable<'_> {
        match self {
            ReachableArea::Exact(r) => ikarus_render::Reachable::Exact(r),
            ReachableArea::Grid(w) => ikarus_render::Reachable::Grid(w),
        }
    }
}

/// Whose region a job computes: an arm's tip (a chain, the exact region by default), or the tip
/// of one bone of a rig the exact region cannot take (sampled, [`sampled`]).
pub enum Effector {
    /// An arm's tip.
    Chain(Box<Arm>),
    /// The tip of a rig's bone, by its index in the rig.
    Bone(Box<Rig>, usize),
}

impl Effector {
    /// The effector of `body` at bone `bone` (by name; default the last bone). A rig that is a
    /// chain, at its last bone, is that chain (its exact region, as an arm file's); `bone` for
    /// an arm is refused. `field` words the bone's field as the edge does (`--bone nose`,
    /// `bone = "nose"`).
    pub fn of(body: Body, bone: Option<&str>, field: impl Fn(&str) -> String) -> Result<Self, Error> {
        match body {
            Body::Chain(arm) => match bone {
                Some(name) => Err(Error::input(format!(
                    "{}: only for a rig or an arm with slides (an arm's region is its tip's)",
                    field(name)
                ))),
                None => Ok(Self::Chain(arm)),
            },
            Body::Rig(rig) => {
                let last = rig.skeleton.len() - 1;
                let bone = match bone {
                    Some(name) => crate::goal::index(&rig.skeleton, name)
                        .map_err(|m| Error::input(format!("{}: {m}", field(name))))?,
                    None => last,
                };
                let rig = *rig;
                Ok(match rig.skeleton.as_chain().filter(|_| bone == last) {
                    Some(chain) => {
                        Self::Chain(Box::new(Arm { name: rig.name, label: rig.label, chain, solver: rig.solver }))
                    }
                    None => Self::Bone(Box::new(rig), bone),
                })
            }
        }
    }
}

/// The sampled region of the tip of `bone` of `rig` ([`ikarus::reach::sample_skeleton`]) with
/// `grid`'s fields (the defaults without) over `run`'s other options (limits, threads,
/// interrupt); an error names the option (`samples: …`).
pub fn sampled(rig: &Rig, bone: usize, grid: Option<GridRequest>, run: WorkspaceOptions) -> Result<Workspace, Error> {
    let grid = grid.unwrap_or(GridRequest { resolution: default_resolution(), samples: None, seed: 0 });
    let options =
        WorkspaceOptions { resolution: grid.resolution, samples: grid.samples.map(u64::from), seed: grid.seed, ..run };
    ikarus::reach::sample_skeleton(&rig.skeleton, bone, &options).map_err(|e| Error::input(e.to_string()))
}

/// How to sample a grid: `--resolution`, `--samples`, `--seed` (or the request's fields).
#[derive(Debug, Clone, Copy)]
pub struct GridRequest {
    /// The grid's cells per side.
    pub resolution: u32,
    /// The random poses sampled [default: the library's, by the number of joints].
    pub samples: Option<u32>,
    /// The seed of the sampled poses (the same seed gives the same grid).
    pub seed: u64,
}

impl GridRequest {
    /// The grid asked for, if any: `grid` (`--grid`, `"grid": true`), or any of its fields
    /// given (asking how to sample is asking for the samples: scripts and pages written before
    /// the exact region keep their grid). `"grid": false` with a sampling field is refused
    /// (`name` words a field as the edge does: `resolution = 64`).
    pub fn of(
        grid: Option<bool>,
        resolution: Option<u32>,
        samples: Option<u32>,
        seed: Option<u64>,
        name: impl Fn(&str, String) -> String,
    ) -> Result<Option<GridRequest>, Error> {
        let given = [
            resolution.map(|v| name("resolution", v.to_string())),
            samples.map(|v| name("samples", v.to_string())),
            seed.map(|v| name("seed", v.to_string())),
        ];
        let sampling = given.iter().flatten().next();
        match (grid, sampling) {
            (Some(false), Some(field)) => Err(Error::input(format!(
                "{field}: only applies to the sampled grid, and grid = false asks for the exact region"
            ))),
            (Some(true), _) | (None, Some(_)) => Ok(Some(GridRequest {
                resolution: resolution.unwrap_or_else(default_resolution),
                samples,
                seed: seed.unwrap_or(0),
            })),
            (Some(false) | None, None) => Ok(None),
        }
    }

    /// The library's sampling options for these fields.
    pub fn options(&self, limits: bool) -> WorkspaceOptions {
        WorkspaceOptions {
            resolution: self.resolution,
            limits,
            samples: self.samples.map(u64::from),
            seed: self.seed,
            ..WorkspaceOptions::default()
        }
    }
}

/// The exact region of `arm`, within its ranges if `limits`, built within the library's work
/// cap ([`Region::try_of`]) and stopping when `interrupt` is set. An input error for an arm
/// whose region needs more than the cap (the edge suggests the sampled grid), or a run-time
/// error when the library could not build it: a region that lost every boundary piece, or no
/// area although two joints move (a fault of the library's union, seen on a few random arms
/// of 5 and 11 links; the edges answer it as a failure, never as an empty region). The server
/// reads an interrupted build as its interrupt ([`RegionError::Interrupted`] is a run-time
/// error here).
pub fn exact_region(arm: &Arm, limits: bool, interrupt: Option<&Interrupt>) -> Result<Region, Error> {
    let options = RegionOptions { limits, interrupt: interrupt.cloned(), ..RegionOptions::default() };
    let region = Region::try_of(&arm.chain, &options).map_err(|e| match e {
        RegionError::TooComplex { .. } => {
            Error::input(format!("{}: {e} (`--grid`, \"grid\": true, samples it)", arm.label))
        }
        e => Error::runtime(format!("{}: the exact region: {e}", arm.label)),
    })?;
    let moving = arm
        .chain
        .limits()
        .iter()
        .filter(|l| match l {
            Some(l) if limits => l.max() > l.min(),
            _ => true,
        })
        .count();
    // Links far shorter than the rounding of the reach (5e-324 beside 1, 1e-150 beside 1e150)
    // sweep nothing wider than a rounding error: such a region is a curve, and it passed its
    // self-check (the sampled tips lie on it).
    if region.pieces() == 0 || (moving >= 2 && !region.has_area() && !region.is_checked()) {
        return Err(Error::runtime(format!(
            "{}: the library could not build the exact region{} (a bug: its boundary came out empty); `--grid` (\"grid\": true) samples it instead",
            arm.label,
            if limits { " within the joint ranges" } else { "" }
        )));
    }
    Ok(region)
}

/// [`exact_region`] as a reachable area.
pub fn exact(arm: &Arm, limits: bool, interrupt: Option<&Interrupt>) -> Result<ReachableArea, Error> {
    exact_region(arm, limits, interrupt).map(ReachableArea::Exact)
}
