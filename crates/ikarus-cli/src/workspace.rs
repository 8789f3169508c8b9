//! `ikarus workspace`: the region the arm's tip can reach, as numbers, boundary loops (or a
//! sampled grid with `--grid`), and a picture.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ikarus::reach::{Annulus, BoundarySegment, WorkspaceOptions};

use crate::area::{self, Effector, GridRequest, ReachableArea};
use crate::arm::Arm;
use crate::body::Body;
use crate::error::Error;
use crate::options::parse_at_least_one;
use crate::picture::{PictureArgs, PictureFormat, draw, progress_bar, report_format, workspace_drawing};
use crate::rig::Rig;
use crate::settings::LimitsArgs;
use crate::{output, report};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WorkspaceFormat {
    /// Radii, the area and the boundary loops (the occupancy grid with --grid)
    Json,
    /// A short report for people
    Text,
}

/// The flags of a reachable area: `ikarus workspace`, `ikarus render workspace` and
/// `ikarus render arm --workspace`. The exact region unless `--grid` asks for the sampled grid.
#[derive(Debug, Args)]
pub struct AreaArgs {
    #[command(flatten)]
    pub limits: LimitsArgs,
    /// Sample an occupancy grid of the region instead of computing it exactly (any of the
    /// flags below asks for the grid too)
    #[arg(long)]
    pub grid: bool,
    /// With --grid: cells along each side of the square around the reach, 8 to 4096 [default: 256]
    #[arg(long, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub resolution: Option<u32>,
    /// With --grid: joint-space samples, at most --max-samples [default: the library's]
    #[arg(long, value_parser = parse_at_least_one)]
    pub samples: Option<u32>,
    /// Largest --samples accepted
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_SAMPLES)]
    pub max_samples: u32,
    /// With --grid: seed of the sampling [default: 0]
    #[arg(long)]
    pub seed: Option<u64>,
}

/// The default cap of `--samples`: about four times the library's largest default (262 144),
/// the server's cap too; 10⁷ samples of a seven-link arm with limits take most of a minute.
pub const DEFAULT_MAX_SAMPLES: u32 = 1_000_000;

impl AreaArgs {
    /// The grid the flags ask for (`None`: the exact region): `--grid`, or any sampling flag;
    /// an error for `--samples` over its cap.
    pub fn grid(&self) -> Result<Option<GridRequest>, Error> {
        let grid =
            GridRequest::of(self.grid.then_some(true), self.resolution, self.samples, self.seed, |field, value| {
                format!("--{field} {value}")
            })?;
        if let Some(n) = self.samples.filter(|&n| n > self.max_samples) {
            return Err(Error::input(format!(
                "--samples {n}: more than the cap of {} (raise it with --max-samples N)",
                self.max_samples
            )));
        }
        Ok(grid)
    }

    /// `arm`'s reachable area as the flags say: the exact region, or the grid sampled in
    /// parallel with a progress bar on a terminal.
    pub fn area(&self, arm: &Arm) -> Result<ReachableArea, Error> {
        let limits = arm.limits(self.limits.asked());
        let Some(grid) = self.grid()? else { return area::exact(arm, limits, None) };
        let bar = progress_bar(100, "sampling the workspace");
        let report = |done: u64, total: u64| {
            if let Some(bar) = &bar {
                bar.set_length(total);
                bar.set_position(done);
            }
        };
        // The command line samples one grid at a time: on every core.
        let options = WorkspaceOptions { parallel: true, ..grid.options(limits) };
        let workspace = ikarus::reach::sample_with_progress(&arm.chain, &options, &report)
            .map_err(|e| Error::input(format!("--{e}")))?;
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        Ok(ReachableArea::Grid(workspace))
    }
}

/// Compute the reachable region of the arm's tip (or of a rig's bone tip, sampled).
#[derive(Debug, Args)]
pub struct WorkspaceArgs {
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    /// Rig file (TOML): the region of one bone's tip, sampled (exact for a rig that is a chain)
    #[arg(long, value_name = "FILE", conflicts_with = "arm")]
    pub rig: Option<PathBuf>,
    /// With --rig (or an arm with slides): the bone whose tip's region is computed [default:
    /// the last bone]
    #[arg(long, value_name = "NAME")]
    pub bone: Option<String>,
    #[command(flatten)]
    pub area: AreaArgs,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out]
    #[arg(long, value_enum)]
    pub format: Option<WorkspaceFormat>,
    #[command(flatten)]
    pub picture: PictureArgs,
}

pub fn run(args: &WorkspaceArgs) -> Result<(), Error> {
    let body = Body::load(args.arm.as_deref(), args.rig.as_deref())?;
    let arm = match Effector::of(body, args.bone.as_deref(), |name| format!("--bone {name}"))? {
        Effector::Chain(arm) => *arm,
        Effector::Bone(rig, bone) => return run_sampled(args, &rig, bone),
    };
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png])?;
    let area = args.area.area(&arm)?;

    let drew = picture.is_some();
    if let Some(out) = picture {
        let bytes = draw(
            &workspace_drawing(&arm, &area),
            out.format,
            args.picture.size.width,
            args.picture.size.height,
            &|_, _| {},
        )?;
        out.commit(&bytes)?;
    }

    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let Some(format) = report_format(args.format, drew, WorkspaceFormat::Text, WorkspaceFormat::Json) else {
        return Ok(());
    };
    output::stdout(|w| match format {
        WorkspaceFormat::Json => {
            serde_json::to_writer(&mut *w, &report::workspace_json(&arm, &area))?;
            writeln!(w)
        }
        WorkspaceFormat::Text => text(w, &arm, &area),
    })
}

fn text(w: &mut dyn Write, arm: &Arm, area: &ReachableArea) -> std::io::Result<()> {
    let annulus = Annulus::of(&arm.chain);
    writeln!(w, "arm          {} ({} links)", arm.name, arm.chain.len())?;
    writeln!(w, "limits       {}", if area.limits() { "on" } else { "off" })?;
    writeln!(
        w,
        "annulus      inner radius {}, outer radius {}, area {:.4}",
        annulus.inner,
        annulus.outer,
        annulus.area()
    )?;
    let share = 100.0 * area.area() / annulus.area();
    match area {
        ReachableArea::Exact(region) if region.has_area() => {
            let loops = region.boundary();
            let segments = loops.iter().flatten();
            let arcs = segments.clone().filter(|s| matches!(s, BoundarySegment::Arc { .. })).count();
            let lines = segments.count() - arcs;
            writeln!(
                w,
                "reachable    {:.4} ({share:.1}% of the annulus), exact: {}, {}{}",
                region.area(),
                plural(loops.len(), "boundary loop", "boundary loops"),
                plural(arcs, "arc", "arcs"),
                if lines > 0 { format!(" and {}", plural(lines, "line", "lines")) } else { String::new() },
            )
        }
        ReachableArea::Exact(region) => writeln!(
            w,
            "reachable    no area: a curve of {} (fewer than two joints move, or the others sweep less than the rounding of the reach)",
            plural(region.pieces(), "piece", "pieces")
        ),
        ReachableArea::Grid(ws) => writeln!(
            w,
            "reachable    {:.4} ({share:.1}% of the annulus), {} of {} cells of {:.4}",
            ws.area(),
            ws.occupied_cells(),
            u64::from(ws.resolution()).pow(2),
            ws.cell_size()
        ),
    }
}

/// `n` and the noun that goes with it.
fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The sampled region of the tip of `bone` of a rig the exact region cannot take (offsets,
/// slides, a fork): [`ikarus::reach::sample_skeleton`], `"exact": false`.
fn run_sampled(args: &WorkspaceArgs, rig: &Rig, bone: usize) -> Result<(), Error> {
    if let Some(p) = &args.picture.out {
        return Err(Error::input(format!(
            "--out {}: the sampled region of a rig's bone is not drawn yet (JSON and text only)",
            p.display()
        )));
    }
    let limits = args.area.limits.asked().or(rig.solver.limits).unwrap_or(false);
    let run = WorkspaceOptions { limits, parallel: true, ..WorkspaceOptions::default() };
    let workspace = area::sampled(rig, bone, args.area.grid()?, run).map_err(|e| Error::input(format!("--{e}")))?;
    let Some(format) = report_format(args.format, false, WorkspaceFormat::Text, WorkspaceFormat::Json) else {
        return Ok(());
    };
    output::stdout(|w| match format {
        WorkspaceFormat::Json => {
            serde_json::to_writer(&mut *w, &report::rig_workspace_json(rig, bone, workspace))?;
            writeln!(w)
        }
        WorkspaceFormat::Text => {
            let disk = workspace.annulus();
            let s = &rig.skeleton;
            writeln!(w, "rig          {} ({} bones), the tip of {}", rig.name, s.len(), s.name(bone))?;
            writeln!(w, "limits       {}", if limits { "on" } else { "off" })?;
            writeln!(w, "disk         radius {} (no tip is farther), area {:.4}", disk.outer, disk.area())?;
            writeln!(
                w,
                "reachable    {:.4} ({:.1}% of the disk), sampled: {} of {} cells of {:.4}, {} joint-space samples",
                workspace.area(),
                100.0 * workspace.area() / disk.area(),
                workspace.occupied_cells(),
                u64::from(workspace.resolution()).pow(2),
                workspace.cell_size(),
                workspace.samples()
            )
        }
    })
}
