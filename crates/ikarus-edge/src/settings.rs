//! The solver settings of the edges: one type for the flags, an arm file's `[solver]` table
//! and the API's `options`, combined with [`SolverSettings::over`] and turned into the
//! library's options with [`SolverSettings::to_options_for`].
//!
//! Precedence: flag, then the arm file's `[solver]` table, then the library default (the API:
//! the request's `options`, then the arm's `solver` table, then the default).

use ikarus::{LimitMode, Method, OptionsError, Restarts, SolveOptions, Solver, StallDetection};
use serde::Deserialize;

use crate::error::Error;

/// Solver settings; every one is optional and falls back on the next source. Field names are
/// the arm files' and the API's, and the flags' with `-` for `_`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSettings {
    /// Solver method [default: lm]
    pub method: Option<Method>,
    /// Damping λ of dls, and the starting damping of lm, ≥ 0, in length units [default: 0.1]
    pub lambda: Option<f64>,
    /// Distance to the goal that counts as reached, > 0 [default: 1e-6]
    pub tolerance: Option<f64>,
    /// With --goal-angle: orientation error that counts as reached, degrees, > 0 [default: 5.7e-5]
    pub angle_tolerance_deg: Option<f64>,
    /// Iteration cap of one solve [default: 1000]
    pub max_iterations: Option<u32>,
    /// Record a frame every K iterations (a flag of each command, whose defaults differ)
    pub record_every: Option<u32>,
    /// Multiplier of every step, > 0 [default: 1]
    pub gain: Option<f64>,
    /// Per-joint step multipliers, one per joint (the seed's a,b,c) [default: all 1]
    pub rates: Option<Vec<f64>>,
    /// Largest change of any joint angle in one iteration, degrees; 0 removes the cap
    /// [default: 28.65 (0.5 rad)]
    pub max_step_deg: Option<f64>,
    /// Halvings of a step that does not lower the error enough, at most 64; 0 takes every step as computed
    /// (the textbook iteration) [default: 10]
    pub backtrack: Option<u32>,
    /// Stop as stalled after this many iterations without movement [default: 10]
    pub stall_window: Option<u32>,
    /// Largest joint change, degrees, that counts as no movement [default: 5.7e-8]
    pub stall_epsilon_deg: Option<f64>,
    /// Enforce the arm's joint ranges (the built-in arm's are the seed's), as --limit-mode says
    pub limits: Option<bool>,
    /// Do not enforce joint ranges, even if the arm file's [solver] table asks to
    #[serde(skip)]
    pub no_limits: bool,
    /// How enforced ranges are handled; implies --limits [default: lock; clamp for ccd and fabrik]
    pub limit_mode: Option<LimitMode>,
    /// Restarts from other start poses when a solve stalls; 0 solves once [default: 16]
    pub restarts: Option<u32>,
    /// Largest --restarts accepted (the command line's cap; the server has its own)
    #[serde(skip, default = "default_max_restarts")]
    pub max_restarts: u32,
    /// Largest `max_iterations` accepted (the command line's cap; the server has its own)
    #[serde(skip, default = "default_iteration_cap")]
    pub iteration_cap: u32,
    /// Seed of the restarts' start poses (the same seed gives the same result) [default: 0]
    pub restart_seed: Option<u64>,
    /// Start no restart after this many milliseconds of one solve; results then depend on the
    /// machine's speed [default: none]
    pub time_budget_ms: Option<f64>,
    /// Iterate even where a closed form applies (2 links, or 3 links with --goal-angle)
    pub no_closed_form: Option<bool>,
}

/// The default cap of `--restarts` on the command line: 10 000 restarts for a goal the
/// built-in arm cannot reach take 0.2 s (10⁸ took 1100 s).
pub const DEFAULT_MAX_RESTARTS: u32 = 10_000;

fn default_max_restarts() -> u32 {
    DEFAULT_MAX_RESTARTS
}

/// The default cap of `max_iterations` on every edge: the command line's (`--iteration-cap`)
/// and the API's (`ikarus serve --max-iterations`), for Python and WebAssembly too.
pub const DEFAULT_ITERATION_CAP: u32 = 100_000;

fn default_iteration_cap() -> u32 {
    DEFAULT_ITERATION_CAP
}

/// Frames a solve records when nothing says `record_every`: every 20 iterations, as the seed
/// program did (`ikarus solve`, `POST /api/solve`, Python's and WebAssembly's solves).
pub const DEFAULT_RECORD_EVERY: u32 = 20;

/// A value above its cap, in one line for every edge: `what` names the field and the value as
/// the edge does (`--max-iterations 200000`, `options.max_iterations = 200000`), `raise` says
/// how the cap is raised.
#[must_use]
pub fn over_cap(what: &str, cap: u32, raise: &str) -> String {
    format!("{what}: more than the cap of {cap} ({raise})")
}

/// Why settings do not make options for a chain; each edge words it in its own field names.
#[derive(Debug)]
pub enum SettingsError {
    /// The options are invalid on their own.
    Options(OptionsError),
    /// `rates` does not have one value per joint.
    Rates {
        /// The chain's joints.
        expected: usize,
        /// The values given.
        got: usize,
    },
    /// Limits are enforced in a mode the method does not support.
    Unsupported {
        /// The method asked for.
        method: Method,
        /// The limit mode it does not support.
        mode: LimitMode,
    },
}

impl SettingsError {
    /// The problem in one line, `field` naming a setting as this edge does (`--method`,
    /// `options.method`).
    pub fn describe(&self, field: impl Fn(&str) -> String) -> String {
        match self {
            Self::Options(e) => e.to_string(),
            Self::Rates { expected, got } => {
                format!("{}: expected {expected} values (one per joint), got {got}", field("rates"))
            }
            Self::Unsupported { method, mode } => {
                let supported: Vec<&str> =
                    LimitMode::ALL.iter().filter(|&&m| method.supports(m)).map(|m| m.name()).collect();
                format!(
                    "{} {method}: does not support {} {mode} (it supports {})",
                    field("method"),
                    field("limit_mode"),
                    supported.join(", ")
                )
            }
        }
    }
}

impl SolverSettings {
    /// These settings, falling back on `base` for each one they leave out. `--no-limits` counts
    /// as `limits = false`.
    #[must_use]
    pub fn over(&self, base: &SolverSettings) -> SolverSettings {
        SolverSettings {
            method: self.method.or(base.method),
            lambda: self.lambda.or(base.lambda),
            tolerance: self.tolerance.or(base.tolerance),
            angle_tolerance_deg: self.angle_tolerance_deg.or(base.angle_tolerance_deg),
            max_iterations: self.max_iterations.or(base.max_iterations),
            record_every: self.record_every.or(base.record_every),
            gain: self.gain.or(base.gain),
            rates: self.rates.clone().or_else(|| base.rates.clone()),
            max_step_deg: self.max_step_deg.or(base.max_step_deg),
            backtrack: self.backtrack.or(base.backtrack),
            stall_window: self.stall_window.or(base.stall_window),
            stall_epsilon_deg: self.stall_epsilon_deg.or(base.stall_epsilon_deg),
            limits: if self.no_limits { Some(false) } else { self.limits.or(base.limits) },
            no_limits: false,
            limit_mode: self.limit_mode.or(base.limit_mode),
            restarts: self.restarts.or(base.restarts),
            max_restarts: self.max_restarts,
            iteration_cap: self.iteration_cap,
            restart_seed: self.restart_seed.or(base.restart_seed),
            time_budget_ms: self.time_budget_ms.or(base.time_budget_ms),
            no_closed_form: self.no_closed_form.or(base.no_closed_form),
        }
    }

    /// Whether the setting `field` (as [`SettingsError::describe`] names it) is given here.
    pub fn is_set(&self, field: &str) -> bool {
        match field {
            "method" => self.method.is_some(),
            "rates" => self.rates.is_some(),
            "limit_mode" => self.limit_mode.is_some(),
            _ => false,
        }
    }

    /// The limit mode: [`LimitMode::Ignore`] unless limits are enforced, then the named mode,
    /// else the method's default ([`Method::default_limit_mode`]). A mode the method does not
    /// support is an error, whether a flag or a table named it.
    pub fn limit_mode(&self, method: Method) -> Result<LimitMode, SettingsError> {
        if self.limits != Some(true) {
            return Ok(LimitMode::Ignore);
        }
        let mode = self.limit_mode.unwrap_or_else(|| method.default_limit_mode());
        if method.supports(mode) { Ok(mode) } else { Err(SettingsError::Unsupported { method, mode }) }
    }

    /// The library's options for a body of `joints` joints (a chain's links, a skeleton's
    /// bones), over the defaults; `rates` one per joint. `record_every` is passed in because
    /// its default differs between commands.
    pub fn to_options_for(&self, joints: usize, record_every: Option<u32>) -> Result<SolveOptions, SettingsError> {
        let d = SolveOptions::default();
        let stall = d.stall.unwrap_or_default();
        let stall = StallDetection {
            window: self.stall_window.unwrap_or(stall.window),
            epsilon: self.stall_epsilon_deg.map_or(stall.epsilon, f64::to_radians),
        };
        let attempts = self.restarts.unwrap_or(Restarts::default().attempts);
        // A duration holds at most about 1.8e22 s: a larger budget is an error, not a panic.
        let time_budget = match self.time_budget_ms {
            None => None,
            Some(ms) => Some(std::time::Duration::try_from_secs_f64(ms / 1000.0).map_err(|_| {
                SettingsError::Options(OptionsError::OutOfRange {
                    field: "time_budget_ms",
                    expected: "a finite number > 0 below 1.8e22",
                    value: ms,
                })
            })?),
        };
        let restarts = (attempts > 0).then(|| Restarts {
            attempts,
            seed: self.restart_seed.unwrap_or(Restarts::default().seed),
            time_budget,
        });
        let method = self.method.unwrap_or(d.method);
        let options = SolveOptions {
            method,
            lambda: self.lambda.unwrap_or(d.lambda),
            tolerance: self.tolerance.unwrap_or(d.tolerance),
            angle_tolerance: self.angle_tolerance_deg.map_or(d.angle_tolerance, f64::to_radians),
            max_iterations: self.max_iterations.unwrap_or(d.max_iterations),
            gain: self.gain.unwrap_or(d.gain),
            rates: self.rates.clone().unwrap_or_default(),
            max_step: match self.max_step_deg {
                None => d.max_step,
                Some(0.0) => None,
                Some(deg) => Some(deg.to_radians()),
            },
            backtrack: self.backtrack.unwrap_or(d.backtrack),
            stall: Some(stall),
            record_every,
            limits: self.limit_mode(method)?,
            restarts,
            closed_form: self.no_closed_form != Some(true),
            ..d
        };
        options.validate().map_err(SettingsError::Options)?;
        if !options.rates.is_empty() && options.rates.len() != joints {
            return Err(SettingsError::Rates { expected: joints, got: options.rates.len() });
        }
        Ok(options)
    }

    /// Range checks of values that did not come through the flags' parsers, naming the field;
    /// the caller prefixes `[solver].` or `options.`.
    pub fn check(&self) -> Result<(), Error> {
        use crate::options::{at_least_one, non_negative, positive};
        let field = |name: &str, r: Result<f64, Error>| r.map(drop).map_err(|m| Error::input(format!("{name} = {m}")));
        type Rule = fn(f64) -> Result<f64, Error>;
        let checks: [(&str, Option<f64>, Rule); 7] = [
            ("lambda", self.lambda, non_negative),
            ("tolerance", self.tolerance, positive),
            ("angle_tolerance_deg", self.angle_tolerance_deg, positive),
            ("gain", self.gain, positive),
            ("max_step_deg", self.max_step_deg, non_negative),
            ("stall_epsilon_deg", self.stall_epsilon_deg, non_negative),
            ("time_budget_ms", self.time_budget_ms, positive),
        ];
        for (name, value, rule) in checks {
            if let Some(v) = value {
                field(name, rule(v))?;
            }
        }
        if let Some(v) = self.record_every {
            at_least_one(v).map_err(|m| Error::input(format!("record_every = {m}")))?;
        }
        if let Some(v) = self.stall_window {
            at_least_one(v).map_err(|m| Error::input(format!("stall_window = {m}")))?;
        }
        if let Some(rates) = &self.rates {
            for (i, &r) in rates.iter().enumerate() {
                field(&format!("rates[{i}]"), non_negative(r))?;
            }
        }
        Ok(())
    }
}

/// The options of a command: `flags` over a file's `[solver]` table `file` over the defaults,
/// for a body of `joints` joints; problems name the flag, or the `[solver]` field of the file
/// (`label`, as its error messages start) a setting came from. Arm and rig files share it.
pub fn command_options(
    flags: &SolverSettings,
    file: &SolverSettings,
    label: &str,
    joints: usize,
    record_every: Option<u32>,
) -> Result<SolveOptions, Error> {
    let restarts = flags.restarts.or(file.restarts);
    if let Some(n) = restarts.filter(|&n| n > flags.max_restarts) {
        let field =
            if flags.restarts.is_some() { "--restarts".to_owned() } else { format!("{label}: [solver].restarts") };
        return Err(Error::input(over_cap(
            &format!("{field} {n}"),
            flags.max_restarts,
            "raise it with --max-restarts N",
        )));
    }
    let iterations = flags.max_iterations.or(file.max_iterations);
    if let Some(n) = iterations.filter(|&n| n > flags.iteration_cap) {
        let field = if flags.max_iterations.is_some() {
            "--max-iterations".to_owned()
        } else {
            format!("{label}: [solver].max_iterations")
        };
        return Err(Error::input(over_cap(
            &format!("{field} {n}"),
            flags.iteration_cap,
            "raise it with --iteration-cap N",
        )));
    }
    flags.over(file).to_options_for(joints, record_every).map_err(|e| {
        // A setting the flags left out came from the file's [solver] table: named as that,
        // after the file.
        let from_file = std::cell::Cell::new(false);
        let message = e.describe(|field| {
            if flags.is_set(field) || !file.is_set(field) {
                format!("--{}", field.replace('_', "-"))
            } else {
                from_file.set(true);
                format!("[solver].{field}")
            }
        });
        Error::input(if from_file.get() { format!("{label}: {message}") } else { message })
    })
}

/// A solver for options already checked by [`SolverSettings::to_options_for`].
pub fn solver(options: SolveOptions) -> Result<Solver, Error> {
    Solver::new(options).map_err(|e| Error::input(e.to_string()))
}
