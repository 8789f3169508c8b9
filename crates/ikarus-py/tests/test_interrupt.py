"""Ctrl-C stops a long call: the work runs on a worker thread with the GIL released while the
calling thread watches for signals; on SIGINT the call's interrupt token is set, the worker ends,
and ``KeyboardInterrupt`` is raised. The calls below would run for hours uninterrupted (a
billion iterations per attempt on a goal no pose meets); the only clock here is a generous
bound on "it ends at all" — without the fix the call never returns within it."""

from __future__ import annotations

import signal
import threading
import time

import pytest

import ikarus

# A goal whose heading the limited seed arm cannot take, no stall or convergence test that could
# end a solve early, and a billion iterations per attempt: each attempt runs to its cap.
ENDLESS = dict(
    limits=True,
    tolerance=1e-300,
    angle_tolerance_deg=1e-300,
    max_iterations=1_000_000_000,
    restarts=64,
    stall_window=1_000_000_000,
    stall_epsilon_deg=1e-300,
    backtrack=0,
    method="transpose",
    no_closed_form=True,
)
GOAL = (2.0, 3.0, -170.0)
HANG_BOUND_S = 60.0


def _ctrl_c_after(seconds: float) -> threading.Timer:
    """SIGINT to the main thread after ``seconds``, as Ctrl-C in a terminal sends it."""
    timer = threading.Timer(seconds, signal.pthread_kill, (threading.main_thread().ident, signal.SIGINT))
    timer.start()
    return timer


def _solve() -> object:
    return ikarus.Chain().solve(GOAL, **ENDLESS)


def _batch() -> object:
    return ikarus.Chain().solve_batch([list(GOAL)] * 8, threads=2, **ENDLESS)


def _call() -> object:
    options = {("lambda" if k == "lambda_" else k): v for k, v in ENDLESS.items()}
    return ikarus.call("solve", {"goal": {"x": GOAL[0], "y": GOAL[1], "angle_deg": GOAL[2]}, "options": options})


@pytest.mark.parametrize("call", [_solve, _batch, _call], ids=["Chain.solve", "Chain.solve_batch", "ikarus.call"])
def test_ctrl_c_stops_a_long_call(call) -> None:
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    started = time.monotonic()
    timer = _ctrl_c_after(0.3)
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()
    assert time.monotonic() - started < HANG_BOUND_S, "the call ran on after Ctrl-C"
    # The next call is not interrupted: each call has its own token.
    assert ikarus.Chain().solve((2.0, 3.0), method="dls", max_iterations=200_000).status == "reached"
