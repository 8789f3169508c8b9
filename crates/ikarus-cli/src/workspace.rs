//! `ikarus workspace`: the region the arm's tip can reach, as numbers, a grid, and a picture.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ikarus::reach::{Annulus, ReachError, Workspace, WorkspaceOptions};

use crate::arm::Arm;
use crate::error::CliError;
use crate::options::parse_at_least_one;
use crate::picture::{PictureArgs, PictureFormat, draw, progress_bar, workspace_drawing};
use crate::{output, report};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WorkspaceFormat {
    /// Radii, areas and the occupancy grid
    Json,
    /// A short report for people
    Text,
}

/// The sampling flags of a workspace: `ikarus workspace`, `ikarus render workspace` and
/// `ikarus render arm --workspace`.
#[derive(Debug, Args)]
pub struct SamplingArgs {
    /// Respect the arm's joint ranges (the built-in arm's are the seed's)
    #[arg(long, overrides_with = "no_limits")]
    pub limits: bool,
    /// Ignore the joint ranges, even if the arm file's [solver] table enforces them
    #[arg(long, overrides_with = "limits")]
    pub no_limits: bool,
    /// Grid cells along each side of the square around the reach, 8 to 4096
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub resolution: u32,
    /// Joint-space samples, at most --max-samples [default: the library's]
    #[arg(long, value_parser = parse_at_least_one)]
    pub samples: Option<u32>,
    /// Largest --samples accepted
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_SAMPLES)]
    pub max_samples: u32,
    /// Seed of the sampling
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// The default cap of `--samples`: about four times the library's largest default (262 144),
/// the server's cap too; 10⁷ samples of a seven-link arm with limits take most of a minute.
pub const DEFAULT_MAX_SAMPLES: u32 = 1_000_000;

impl SamplingArgs {
    /// The request of these flags, or an error if `--samples` is over its cap.
    pub fn request(&self) -> Result<WorkspaceRequest, CliError> {
        if let Some(n) = self.samples {
            if n > self.max_samples {
                return Err(CliError::input(format!(
                    "--samples {n}: more than the cap of {} (raise it with --max-samples N)",
                    self.max_samples
                )));
            }
        }
        let limits = match (self.limits, self.no_limits) {
            (true, _) => Some(true),
            (false, true) => Some(false),
            (false, false) => None,
        };
        Ok(WorkspaceRequest { limits, resolution: self.resolution, samples: self.samples, seed: self.seed })
    }

    /// Samples `arm`'s workspace as the flags say, with a progress bar on a terminal.
    pub fn sample(&self, arm: &Arm) -> Result<Workspace, CliError> {
        let request = self.request()?;
        let bar = progress_bar(100, "sampling the workspace");
        let report = |done: u64, total: u64| {
            if let Some(bar) = &bar {
                bar.set_length(total);
                bar.set_position(done);
            }
        };
        let workspace = request.sample(arm, &report).map_err(|e| CliError::input(format!("--{e}")))?;
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        Ok(workspace)
    }
}

/// Compute the reachable region of the arm's tip.
#[derive(Debug, Args)]
pub struct WorkspaceArgs {
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    #[command(flatten)]
    pub sampling: SamplingArgs,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out]
    #[arg(long, value_enum)]
    pub format: Option<WorkspaceFormat>,
    #[command(flatten)]
    pub picture: PictureArgs,
}

/// What a workspace request asks for, from the flags or the API: `limits` over the arm file's
/// `[solver] limits` (off when neither says), and the sampling.
pub struct WorkspaceRequest {
    pub limits: Option<bool>,
    pub resolution: u32,
    pub samples: Option<u32>,
    pub seed: u64,
}

impl WorkspaceRequest {
    /// Whether `arm`'s joint ranges are respected.
    pub fn limits(&self, arm: &Arm) -> bool {
        self.limits.or(arm.solver.limits).unwrap_or(false)
    }

    /// Samples `arm`'s workspace, telling `progress(done, total)` how far it got.
    pub fn sample(&self, arm: &Arm, progress: &(dyn Fn(u64, u64) + Sync)) -> Result<Workspace, ReachError> {
        let options = WorkspaceOptions {
            resolution: self.resolution,
            limits: self.limits(arm),
            samples: self.samples.map(u64::from),
            seed: self.seed,
            ..WorkspaceOptions::default()
        };
        ikarus::reach::sample_with_progress(&arm.chain, &options, progress)
    }
}

pub fn run(args: &WorkspaceArgs) -> Result<(), CliError> {
    let arm = Arm::load(args.arm.as_deref())?;
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png])?;
    let workspace = args.sampling.sample(&arm)?;
    let limits = workspace.limits();

    let drew = picture.is_some();
    if let Some(out) = picture {
        let bytes = draw(
            &workspace_drawing(&arm, &workspace),
            out.format,
            args.picture.width,
            args.picture.height,
            &|_, _| {},
        )?;
        out.commit(&bytes)?;
    }

    let annulus = workspace.annulus();
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let format = match (args.format, drew) {
        (Some(f), _) => f,
        (None, true) => return Ok(()),
        (None, false) if std::io::stdout().is_terminal() => WorkspaceFormat::Text,
        (None, false) => WorkspaceFormat::Json,
    };
    output::stdout(|w| match format {
        WorkspaceFormat::Json => {
            serde_json::to_writer(&mut *w, &report::workspace_json(&arm, limits, &workspace))?;
            writeln!(w)
        }
        WorkspaceFormat::Text => text(w, &arm, &workspace, &annulus, limits),
    })
}

fn text(w: &mut dyn Write, arm: &Arm, ws: &Workspace, annulus: &Annulus, limits: bool) -> std::io::Result<()> {
    writeln!(w, "arm          {} ({} links)", arm.name, arm.chain.len())?;
    writeln!(w, "limits       {}", if limits { "on" } else { "off" })?;
    writeln!(
        w,
        "annulus      inner radius {}, outer radius {}, area {:.4}",
        annulus.inner,
        annulus.outer,
        annulus.area()
    )?;
    writeln!(
        w,
        "reachable    {:.4} ({:.1}% of the annulus), {} of {} cells of {:.4}",
        ws.area(),
        100.0 * ws.area() / annulus.area(),
        ws.occupied_cells(),
        u64::from(ws.resolution()).pow(2),
        ws.cell_size()
    )
}
