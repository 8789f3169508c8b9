//! Ctrl-C during a long call. The work runs on a worker thread with the GIL released; the
//! calling thread waits for it in short slices and between them asks Python whether a signal
//! came (`check_signals`, which runs the Python handlers: SIGINT's raises `KeyboardInterrupt`).
//! When one did, the call's [`Interrupt`] is set, the worker is joined (every job the edge runs
//! checks the token as it goes and ends soon), and the handler's exception is raised.
//!
//! Why a worker thread: Python runs signal handlers on the main thread only, between bytecodes
//! or when native code calls `PyErr_CheckSignals`; a computation that holds the calling thread
//! (with the GIL released, so other Python threads run) never gives it that chance, and Ctrl-C
//! waited for the end of the job.

use std::thread;
use std::time::Duration;

use ikarus::Interrupt;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// Most iterations (over every attempt) a solve may be allowed for it to run on the calling
/// thread: the default cap's. A chain's solve is the hot path (microseconds; a thread per solve
/// would cost more than the solve), so only one whose options allow more work goes through
/// [`interruptible`].
const INLINE_ITERATIONS: u64 = crate::edge::DEFAULT_ITERATION_CAP as u64;

/// Whether a solve with `options` may run long enough to need Ctrl-C: more iterations over its
/// attempts than the default cap.
pub(crate) fn may_run_long(options: &ikarus::SolveOptions) -> bool {
    let attempts = 1 + options.restarts.as_ref().map_or(0, |r| u64::from(r.attempts));
    u64::from(options.max_iterations).saturating_mul(attempts) > INLINE_ITERATIONS
}

/// How long the calling thread sleeps between two looks at Python's signals (the worker wakes
/// it as soon as it is done, so a short job costs no slice).
const SLICE: Duration = Duration::from_millis(20);

/// `work()` on a worker thread, the GIL released, while the calling thread watches for signals:
/// its value, or the exception a signal handler raised (`KeyboardInterrupt` for Ctrl-C) once
/// `token` is set and the worker has ended. `work` should stop soon after `token` is set (the
/// token it was given, or one inside its options). A panic inside is a `RuntimeError`.
pub(crate) fn interruptible<T, F>(py: Python<'_>, token: &Interrupt, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    thread::scope(|scope| {
        let caller = thread::current();
        let worker = scope.spawn(move || {
            let out = work();
            caller.unpark();
            out
        });
        let mut signalled = None;
        while !worker.is_finished() {
            py.detach(|| thread::park_timeout(SLICE));
            if signalled.is_none()
                && let Err(e) = py.check_signals()
            {
                token.interrupt();
                signalled = Some(e);
            }
        }
        let out = py.detach(|| worker.join());
        match (signalled, out) {
            (Some(e), _) => Err(e),
            (None, Ok(value)) => Ok(value),
            (None, Err(panic)) => Err(PyRuntimeError::new_err(format!("internal error: {}", panic_message(&panic)))),
        }
    })
}

/// The message a panic carried, if it was text.
fn panic_message(panic: &Box<dyn std::any::Any + Send>) -> &str {
    panic
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| panic.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("a panic")
}
