//! Refusals as Python exceptions: the facade's one-line `Problem`s as `ValueError` (bad input)
//! or `RuntimeError` (a failure inside), with the field named as a Python caller wrote it.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::edge::Problem;

/// A refused request as Python sees it: a bad value (422) or malformed request (400) is a
/// `ValueError` with the facade's one line; anything else (500) a `RuntimeError`, whose detail
/// goes to stderr as the server logs it.
pub(crate) fn problem(p: Problem) -> PyErr {
    if let Some(detail) = p.internal_detail() {
        eprintln!("ikarus: internal error: {detail}");
    }
    if (400..500).contains(&p.status) { PyValueError::new_err(p.message) } else { PyRuntimeError::new_err(p.message) }
}

/// The message less a trailing ` at line N column M`: where serde_json found the problem in
/// the JSON text this edge made from keywords, which the caller never saw.
fn without_position(message: &str) -> &str {
    if let Some(at) = message.rfind(" at line ") {
        let tail = &message[at + " at line ".len()..];
        let mut parts = tail.split(" column ");
        let digits = |s: Option<&str>| s.is_some_and(|s| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()));
        if digits(parts.next()) && digits(parts.next()) && parts.next().is_none() {
            return &message[..at];
        }
    }
    message
}

/// A refused option: the facade's line, without what only its JSON form had (an `options: `
/// before a field of a malformed value, the ` at line 1 column N` of the JSON text this edge
/// made from the keywords), so that it names the keyword and the value.
pub(crate) fn option_problem(p: Problem) -> PyErr {
    let message = without_position(p.message.strip_prefix("options: ").unwrap_or(&p.message)).to_owned();
    problem(p.with_message(message))
}

/// A refused request of a body's method (a rig's `solve`, `animate`, `track`): a line about
/// the request's `options` names the keyword as :meth:`Chain.solve`'s does (`lamda: unknown
/// field …`, `lambda = -1: …`), without the request's JSON path (`request body: options.`)
/// and position; any other line is the API's.
pub(crate) fn request_problem(p: Problem) -> PyErr {
    let line = p.message.strip_prefix("request body: ").unwrap_or(&p.message);
    match line.strip_prefix("options.").or_else(|| line.strip_prefix("options: ")) {
        Some(field) => {
            let message = without_position(field).to_owned();
            problem(p.with_message(message))
        }
        None => problem(p),
    }
}

/// A refused goal: the facade's line (`goal: goal.y: must be a finite number, got NaN`) with
/// the field once (`goal.y: …`), or for row `row` of a batch, `goals[row].y: …`.
pub(crate) fn goal_problem(p: Problem, row: Option<usize>) -> PyErr {
    let detail = p.message.strip_prefix("goal: ").unwrap_or(&p.message);
    let detail = if detail.starts_with("goal.") || detail.starts_with("goal:") { detail } else { &p.message };
    let message = match row {
        None => detail.to_owned(),
        Some(i) => match detail.strip_prefix("goal") {
            Some(rest) => format!("goals[{i}]{rest}"),
            None => format!("goals[{i}]: {detail}"),
        },
    };
    problem(p.with_message(message))
}
