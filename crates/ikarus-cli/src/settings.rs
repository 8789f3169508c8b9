//! The solver flags of the commands, made into the edge's [`SolverSettings`] (whose checks and
//! conversion into the library's options live in [`ikarus_edge::settings`]), and `--limits` of
//! the commands that look at the reachable region.

use clap::Args;
use clap::builder::ArgPredicate;
use ikarus::{LimitMode, Method};
pub use ikarus_edge::settings::*;

use crate::options::{named, parse_at_least_one, parse_non_negative, parse_positive};

/// The solver flags of the commands: [`SolverSettings`] as flags (`-` for `_`), with
/// `--no-limits` and the command line's `--restarts` cap, `--max-restarts`.
#[derive(Debug, Clone, Args)]
pub struct SolverFlags {
    /// Solver method [default: lm]
    #[arg(long, value_parser = named::<Method>(), hide_possible_values = false)]
    pub method: Option<Method>,
    /// Damping λ of dls, and the starting damping of lm, ≥ 0, in length units [default: 0.1]
    #[arg(long, value_parser = parse_non_negative)]
    pub lambda: Option<f64>,
    /// Distance to the goal that counts as reached, > 0 [default: 1e-6]
    #[arg(long, value_parser = parse_positive)]
    pub tolerance: Option<f64>,
    /// With --goal-angle: orientation error that counts as reached, degrees, > 0 [default: 5.7e-5]
    #[arg(long, value_parser = parse_positive, value_name = "DEG")]
    pub angle_tolerance_deg: Option<f64>,
    /// Iteration cap of one solve [default: 1000]
    #[arg(long, value_name = "N")]
    pub max_iterations: Option<u32>,
    /// Record a frame every K iterations (a flag of each command, whose defaults differ)
    #[arg(skip)]
    pub record_every: Option<u32>,
    /// Multiplier of every step, > 0 [default: 1]
    #[arg(long, value_parser = parse_positive)]
    pub gain: Option<f64>,
    /// Per-joint step multipliers, one per joint (the seed's a,b,c) [default: all 1]
    #[arg(long, value_name = "A,B,…", value_delimiter = ',', value_parser = parse_non_negative)]
    pub rates: Option<Vec<f64>>,
    /// Largest change of any joint angle in one iteration, degrees; 0 removes the cap
    /// [default: 28.65 (0.5 rad)]
    #[arg(long, value_parser = parse_non_negative, value_name = "DEG")]
    pub max_step_deg: Option<f64>,
    /// Halvings of a step that does not lower the error enough, at most 64; 0 takes every step as computed
    /// (the textbook iteration) [default: 10]
    #[arg(long, value_name = "N")]
    pub backtrack: Option<u32>,
    /// Stop as stalled after this many iterations without movement [default: 10]
    #[arg(long, value_parser = parse_at_least_one, value_name = "K")]
    pub stall_window: Option<u32>,
    /// Largest joint change, degrees, that counts as no movement [default: 5.7e-8]
    #[arg(long, value_parser = parse_non_negative, value_name = "DEG")]
    pub stall_epsilon_deg: Option<f64>,
    /// Enforce the arm's joint ranges (the built-in arm's are the seed's), as --limit-mode says
    #[arg(
        long,
        num_args = 0,
        default_missing_value = "true",
        overrides_with = "no_limits",
        default_value_if("limit_mode", ArgPredicate::IsPresent, Some("true"))
    )]
    pub limits: Option<bool>,
    /// Do not enforce joint ranges, even if the arm file's [solver] table asks to
    #[arg(long, overrides_with = "limits")]
    pub no_limits: bool,
    /// How enforced ranges are handled; implies --limits [default: lock; clamp for ccd and fabrik]
    #[arg(long, value_parser = named::<LimitMode>(), hide_possible_values = false, conflicts_with = "no_limits")]
    pub limit_mode: Option<LimitMode>,
    /// Restarts from other start poses when a solve stalls; 0 solves once [default: 16]
    #[arg(long, value_name = "N")]
    pub restarts: Option<u32>,
    /// Largest --restarts accepted (the command line's cap; the server has its own)
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_RESTARTS)]
    pub max_restarts: u32,
    /// Largest --max-iterations accepted, as `ikarus serve --max-iterations` caps a request's
    #[arg(long, value_name = "N", default_value_t = DEFAULT_ITERATION_CAP)]
    pub iteration_cap: u32,
    /// Seed of the restarts' start poses (the same seed gives the same result) [default: 0]
    #[arg(long, value_name = "S")]
    pub restart_seed: Option<u64>,
    /// Start no restart after this many milliseconds of one solve; results then depend on the
    /// machine's speed [default: none]
    #[arg(long, value_parser = parse_positive, value_name = "MS")]
    pub time_budget_ms: Option<f64>,
    /// Iterate even where a closed form applies (2 links, or 3 links with --goal-angle)
    #[arg(long, num_args = 0, default_missing_value = "true")]
    pub no_closed_form: Option<bool>,
}

impl SolverFlags {
    /// Each solver flag as written and whether it was given (`--max-restarts` and
    /// `--iteration-cap`, which have defaults, are not told apart from their default).
    #[must_use]
    pub fn given(&self) -> [(&'static str, bool); 18] {
        [
            ("--method", self.method.is_some()),
            ("--lambda", self.lambda.is_some()),
            ("--tolerance", self.tolerance.is_some()),
            ("--angle-tolerance-deg", self.angle_tolerance_deg.is_some()),
            ("--max-iterations", self.max_iterations.is_some()),
            ("--gain", self.gain.is_some()),
            ("--rates", self.rates.is_some()),
            ("--max-step-deg", self.max_step_deg.is_some()),
            ("--backtrack", self.backtrack.is_some()),
            ("--stall-window", self.stall_window.is_some()),
            ("--stall-epsilon-deg", self.stall_epsilon_deg.is_some()),
            ("--limits", self.limits.is_some()),
            ("--no-limits", self.no_limits),
            ("--limit-mode", self.limit_mode.is_some()),
            ("--restarts", self.restarts.is_some()),
            ("--restart-seed", self.restart_seed.is_some()),
            ("--time-budget-ms", self.time_budget_ms.is_some()),
            ("--no-closed-form", self.no_closed_form.is_some()),
        ]
    }

    /// The settings the flags give.
    #[must_use]
    pub fn settings(&self) -> SolverSettings {
        SolverSettings {
            method: self.method,
            lambda: self.lambda,
            tolerance: self.tolerance,
            angle_tolerance_deg: self.angle_tolerance_deg,
            max_iterations: self.max_iterations,
            record_every: self.record_every,
            gain: self.gain,
            rates: self.rates.clone(),
            max_step_deg: self.max_step_deg,
            backtrack: self.backtrack,
            stall_window: self.stall_window,
            stall_epsilon_deg: self.stall_epsilon_deg,
            limits: self.limits,
            no_limits: self.no_limits,
            limit_mode: self.limit_mode,
            restarts: self.restarts,
            max_restarts: self.max_restarts,
            iteration_cap: self.iteration_cap,
            restart_seed: self.restart_seed,
            time_budget_ms: self.time_budget_ms,
            no_closed_form: self.no_closed_form,
        }
    }
}

/// `--limits` / `--no-limits` of the commands that look at the reachable region (`workspace`,
/// `reach`, `render arm`, `render workspace`): over the arm file's `[solver] limits`.
#[derive(Debug, Clone, Args)]
pub struct LimitsArgs {
    /// Respect the arm's joint ranges (the built-in arm's are the seed's)
    #[arg(long, overrides_with = "no_limits")]
    pub limits: bool,
    /// Ignore the joint ranges, even if the arm file's [solver] table enforces them
    #[arg(long, overrides_with = "limits")]
    pub no_limits: bool,
}

impl LimitsArgs {
    /// What the flags ask: `Some(true)`, `Some(false)`, or `None` (the arm file decides).
    pub fn asked(&self) -> Option<bool> {
        match (self.limits, self.no_limits) {
            (true, _) => Some(true),
            (false, true) => Some(false),
            (false, false) => None,
        }
    }
}
