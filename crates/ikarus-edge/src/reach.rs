//! The reach question shared by `ikarus reach` and `POST /api/reach`: the exact reachable
//! region of an arm, built once per request ([`ReachRequest::region`]), and the verdict on a
//! point; each answer is [`crate::report::VerdictJson`] in JSON.

use ikarus::Point2;
use ikarus::reach::{Region, Verdict};

use crate::arm::Arm;
use crate::error::Error;

/// What a reach request asks, from the flags or the API: `limits` over the arm file's
/// `[solver] limits` (off when neither says), and the tolerance over the arm file's
/// `[solver] tolerance` over the solver's default.
pub struct ReachRequest {
    /// Whether the joint limits bound the region [default: the arm file's `[solver] limits`, else off].
    pub limits: Option<bool>,
    /// The distance from the region that still counts as reachable [default: the arm file's `[solver] tolerance`, else the solver's].
    pub tolerance: Option<f64>,
}

impl ReachRequest {
    /// The distance from the region that counts as reachable.
    pub fn tolerance(&self, arm: &Arm) -> f64 {
        self.tolerance.or(arm.solver.tolerance).unwrap_or(ikarus::SolveOptions::default().tolerance)
    }

    /// The exact region of `arm` the verdicts are read from ([`crate::area::exact_region`]),
    /// stopping when `interrupt` is set.
    pub fn region(&self, arm: &Arm, interrupt: Option<&ikarus::Interrupt>) -> Result<Region, Error> {
        crate::area::exact_region(arm, arm.limits(self.limits), interrupt)
    }
}

/// The verdict on `p`.
pub fn verdict(region: &Region, p: [f64; 2], tolerance: f64) -> Verdict {
    region.verdict(Point2::new(p[0], p[1]), tolerance)
}
