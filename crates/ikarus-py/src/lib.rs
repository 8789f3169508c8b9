//! `ikarus._ikarus`: the Python bindings of ikarus (re-exported by the `ikarus` package).
//!
//! One workflow per job: arms, settings, defaults, messages and JSON answers come from the shared
//! facade (named in one place, `edge`), as for the command line and the server. The hot path
//! (`Chain.solve`, `Chain.solve_batch`) uses its typed pieces and `ikarus::Solver` directly; a
//! rig's solve (`_solve_rig`) posts the API's request to `edge::call` and reads its answer into
//! the same `Outcome` a chain's solve gives; the rest (animate, track, workspace, reach,
//! pictures) posts the API's request and hands its JSON answer to the Python side
//! (`python/ikarus/`), which turns it into typed objects with NumPy columns. Angles are degrees
//! at this edge, as in the CLI.
//!
//! By concern: `chain` (the `Chain` class, its solves), `character` (a character file read
//! once and posed by the shared pose job), `arm` (what a chain holds, shared with
//! its outcomes), `outcome` (`Outcome` of a chain or a rig, `Effector`), `options` (keyword
//! options as the API's JSON, this edge's caps), `goals` (goals and goal arrays), `batch`
//! (`solve_batch`'s pools and status codes), `errors` (refusals as Python exceptions), `api`
//! (requests without HTTP), `picture` (a PNG's pixels), `signals` (Ctrl-C during a long call), `easing` (`ease`), and `edge`, the one place that names the shared
//! facade.

mod api;
mod arm;
mod batch;
mod chain;
mod character;
mod easing;
mod edge;
mod errors;
mod goals;
mod options;
mod outcome;
mod picture;
mod signals;

use pyo3::prelude::*;

use crate::api::_call;
use crate::batch::_status_names;
use crate::chain::PyChain;
use crate::character::{_character_text, PyCharacter};
use crate::easing::ease;
use crate::outcome::{_solve_rig, PyEffector, PyOutcome};
use crate::picture::_png_rgba;

#[pymodule]
fn _ikarus(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyChain>()?;
    m.add_class::<PyOutcome>()?;
    m.add_class::<PyEffector>()?;
    m.add_class::<PyCharacter>()?;
    m.add_function(wrap_pyfunction!(ease, m)?)?;
    m.add_function(wrap_pyfunction!(_status_names, m)?)?;
    m.add_function(wrap_pyfunction!(_call, m)?)?;
    m.add_function(wrap_pyfunction!(_solve_rig, m)?)?;
    m.add_function(wrap_pyfunction!(_character_text, m)?)?;
    m.add_function(wrap_pyfunction!(_png_rgba, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
