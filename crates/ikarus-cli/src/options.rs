//! Flags shared by the commands, their parsers, and how they combine with an arm file's
//! `[solver]` table into the library's `SolveOptions`.
//!
//! Precedence: flag, then the arm file's `[solver]` table, then the library default.

use clap::{Args, ValueEnum};
use ikarus::{LimitMode, Method, Restarts, SolveOptions, StallDetection};
use serde::Deserialize;

use crate::arm::SolverTable;
use crate::error::CliError;

/// The solver method, as named at the edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MethodArg {
    /// Jacobian transpose with the error-minimising step length.
    Transpose,
    /// Jacobian pseudoinverse (truncated at singular values below 1e-6).
    Pinv,
    /// Damped least squares with damping --lambda.
    Dls,
    /// Selectively damped least squares (Buss & Kim).
    Sdls,
    /// Levenberg–Marquardt: damped least squares with adaptive damping, starting at --lambda.
    Lm,
    /// Cyclic coordinate descent, one joint at a time from the tip.
    Ccd,
    /// FABRIK, forward and backward reaching on the joint positions.
    Fabrik,
    /// Closed form: 2 links with a position goal, 3 links with --goal-angle.
    Analytic,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Self {
        match m {
            MethodArg::Transpose => Method::Transpose,
            MethodArg::Pinv => Method::PseudoInverse,
            MethodArg::Dls => Method::DampedLeastSquares,
            MethodArg::Sdls => Method::SelectivelyDamped,
            MethodArg::Lm => Method::LevenbergMarquardt,
            MethodArg::Ccd => Method::CyclicCoordinateDescent,
            MethodArg::Fabrik => Method::Fabrik,
            MethodArg::Analytic => Method::Analytic,
        }
    }
}

/// How enforced joint limits are handled, as named at the edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LimitModeArg {
    /// Clamp every step into the ranges (the seed's method; can get stuck).
    Clamp,
    /// Clamp and lock: a joint at its limit is held and the step re-solved for the others.
    Lock,
    /// Lock, plus a push toward the middle of the ranges in the null space of the task.
    Nullspace,
    /// Weighted least norm: joints slow down as they near a limit.
    Weighted,
}

impl From<LimitModeArg> for LimitMode {
    fn from(m: LimitModeArg) -> Self {
        match m {
            LimitModeArg::Clamp => LimitMode::Clamp,
            LimitModeArg::Lock => LimitMode::Lock,
            LimitModeArg::Nullspace => LimitMode::NullSpace,
            LimitModeArg::Weighted => LimitMode::Weighted,
        }
    }
}

/// Solver flags. Each overrides the arm file's `[solver]` table.
#[derive(Debug, Clone, Default, Args)]
pub struct SolverArgs {
    /// Solver method [default: lm]
    #[arg(long, value_enum, hide_possible_values = false)]
    pub method: Option<MethodArg>,
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
    /// Halvings of a step that does not lower the error enough; 0 takes every step as computed
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
    #[arg(long, overrides_with = "no_limits")]
    pub limits: bool,
    /// Do not enforce joint ranges, even if the arm file's [solver] table asks to
    #[arg(long, overrides_with = "limits")]
    pub no_limits: bool,
    /// How enforced ranges are handled; implies --limits [default: lock]
    #[arg(long, value_enum, hide_possible_values = false, conflicts_with = "no_limits")]
    pub limit_mode: Option<LimitModeArg>,
    /// Restarts from other start poses when a solve stalls; 0 solves once [default: 16]
    #[arg(long, value_name = "N")]
    pub restarts: Option<u32>,
    /// Seed of the restarts' start poses (the same seed gives the same result) [default: 0]
    #[arg(long, value_name = "S")]
    pub restart_seed: Option<u64>,
    /// Start no restart after this many milliseconds of one solve; results then depend on the
    /// machine's speed [default: none]
    #[arg(long, value_parser = parse_positive, value_name = "MS")]
    pub time_budget_ms: Option<f64>,
    /// Iterate even where a closed form applies (2 links, or 3 links with --goal-angle)
    #[arg(long)]
    pub no_closed_form: bool,
}

impl SolverArgs {
    /// Library options from flags over `table` over the defaults. `record_every` is passed
    /// in because its default differs between commands.
    pub fn resolve(&self, table: &SolverTable, record_every: Option<u32>) -> Result<SolveOptions, CliError> {
        let d = SolveOptions::default();
        let stall = StallDetection {
            window: self.stall_window.or(table.stall_window).unwrap_or(d.stall.unwrap_or_default().window),
            epsilon: self
                .stall_epsilon_deg
                .or(table.stall_epsilon_deg)
                .map_or(d.stall.unwrap_or_default().epsilon, f64::to_radians),
        };
        let mode = self.limit_mode.or(table.limit_mode);
        let limits = limits_enforced(self.limits || self.limit_mode.is_some(), self.no_limits, table);
        let attempts = self.restarts.or(table.restarts).unwrap_or(Restarts::default().attempts);
        let restarts = (attempts > 0).then(|| Restarts {
            attempts,
            seed: self.restart_seed.or(table.restart_seed).unwrap_or(Restarts::default().seed),
            time_budget: self
                .time_budget_ms
                .or(table.time_budget_ms)
                .map(|ms| std::time::Duration::from_secs_f64(ms / 1000.0)),
        });
        let options = SolveOptions {
            method: self.method.or(table.method).map_or(d.method, Method::from),
            lambda: self.lambda.or(table.lambda).unwrap_or(d.lambda),
            tolerance: self.tolerance.or(table.tolerance).unwrap_or(d.tolerance),
            angle_tolerance: self
                .angle_tolerance_deg
                .or(table.angle_tolerance_deg)
                .map_or(d.angle_tolerance, f64::to_radians),
            max_iterations: self.max_iterations.or(table.max_iterations).unwrap_or(d.max_iterations),
            gain: self.gain.or(table.gain).unwrap_or(d.gain),
            rates: self.rates.clone().or_else(|| table.rates.clone()).unwrap_or_default(),
            max_step: match self.max_step_deg.or(table.max_step_deg) {
                None => d.max_step,
                Some(0.0) => None,
                Some(deg) => Some(deg.to_radians()),
            },
            backtrack: self.backtrack.or(table.backtrack).unwrap_or(d.backtrack),
            stall: Some(stall),
            record_every,
            limits: if limits { mode.map_or(d.limits, LimitMode::from) } else { LimitMode::Ignore },
            restarts,
            closed_form: !(self.no_closed_form || table.no_closed_form == Some(true)),
            ..d
        };
        options.validate().map_err(|e| CliError::input(e.to_string()))?;
        Ok(options)
    }
}

/// Whether joint ranges are enforced: `--limits`, else not with `--no-limits`, else the arm
/// file's `[solver] limits`, else off.
pub fn limits_enforced(limits: bool, no_limits: bool, table: &SolverTable) -> bool {
    limits || (!no_limits && table.limits.unwrap_or(false))
}

/// Parses a finite float, naming what was wrong with the text.
pub fn parse_finite(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_finite() { Ok(v) } else { Err(format!("must be a finite number, got {s}")) }
}

pub fn positive(v: f64) -> Result<f64, String> {
    if v.is_finite() && v > 0.0 { Ok(v) } else { Err(format!("{v}: must be a finite number greater than 0")) }
}

pub fn non_negative(v: f64) -> Result<f64, String> {
    if v.is_finite() && v >= 0.0 { Ok(v) } else { Err(format!("{v}: must be a finite number ≥ 0")) }
}

pub fn at_least_one(v: u32) -> Result<u32, String> {
    if v >= 1 { Ok(v) } else { Err(format!("{v}: must be at least 1")) }
}

fn parse_positive(s: &str) -> Result<f64, String> {
    positive(parse_finite(s)?)
}

fn parse_non_negative(s: &str) -> Result<f64, String> {
    non_negative(parse_finite(s)?)
}

pub fn parse_at_least_one(s: &str) -> Result<u32, String> {
    let v: u32 = s.trim().parse().map_err(|_| format!("'{s}' is not a whole number"))?;
    at_least_one(v)
}

/// Parses `X,Y` into two finite numbers.
pub fn parse_point(s: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = s.split(',').collect();
    let [x, y] = parts[..] else {
        return Err(format!("expected two numbers X,Y, got {} part(s)", parts.len()));
    };
    let x = parse_finite(x).map_err(|m| format!("x: {m}"))?;
    let y = parse_finite(y).map_err(|m| format!("y: {m}"))?;
    Ok([x, y])
}

/// Parses an angle in degrees (finite).
pub fn parse_angle(s: &str) -> Result<f64, String> {
    parse_finite(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_parse_and_name_the_bad_part() {
        assert_eq!(parse_point("1.5,-2"), Ok([1.5, -2.0]));
        assert_eq!(parse_point(" 3 , 4 "), Ok([3.0, 4.0]));
        assert_eq!(parse_point("1,nan"), Err("y: must be a finite number, got nan".to_owned()));
        assert_eq!(parse_point("inf,1"), Err("x: must be a finite number, got inf".to_owned()));
        assert_eq!(parse_point("a,1"), Err("x: 'a' is not a number".to_owned()));
        assert_eq!(parse_point("1"), Err("expected two numbers X,Y, got 1 part(s)".to_owned()));
        assert_eq!(parse_point("1,2,3"), Err("expected two numbers X,Y, got 3 part(s)".to_owned()));
    }

    #[test]
    fn ranges() {
        assert!(parse_positive("0").is_err());
        assert!(parse_positive("1e-9").is_ok());
        assert!(parse_non_negative("0").is_ok());
        assert!(parse_non_negative("-0.1").is_err());
        assert!(parse_at_least_one("0").is_err());
        assert!(parse_at_least_one("-3").is_err());
    }
}
