//! Which lane a computation runs in ([`super::pool::Lane`]), by what its request costs at most:
//! the edge's estimate in link steps, read from the typed request its job runs
//! (`ikarus_edge::api::Request::cost`, the model in `ikarus_edge::api::cost`), against
//! [`QUICK_COST`]. A request the estimate gets wrong is still caught: a quick one running past
//! [`super::pool::LONG_AFTER`] must move to the long lane.

use super::pool::Lane;
use crate::api::cost::file_bytes;
use crate::api::rigs::FileBody;

/// The largest estimate (link steps) of a quick request: about a tenth of a second of work in its
/// worst case.
pub const QUICK_COST: f64 = 2.5e6;

/// The lane of work that costs `cost` link steps.
pub fn lane(cost: f64) -> Lane {
    if cost <= QUICK_COST { Lane::Quick } else { Lane::Long }
}

/// The lane of `/api/rig/parse` with a body held as `given`, from its bytes alone (a `.skel`'s
/// as the most text they may decode into), before it is read.
pub fn file_lane(given: FileBody, body: &[u8]) -> Lane {
    lane(file_bytes(given, body))
}

#[cfg(test)]
#[path = "cost_tests.rs"]
mod tests;
