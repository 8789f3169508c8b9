"""Ctrl-C stops a long call: the work runs on a worker thread with the GIL released while the
calling thread watches for signals; on SIGINT the call's interrupt token is set, the worker ends,
and ``KeyboardInterrupt`` is raised. The calls below would run for hours uninterrupted (a
billion iterations per attempt on a goal no pose meets) or minutes (a character's tangle of IK
constraints); the only clock here is a generous bound on "it ends at all" — without the fix the
call does not return within it."""

from __future__ import annotations

import json
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
HANG_BOUND_S = 30.0


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


def _tangle() -> ikarus.Rig:
    """A 1,024-bone chain, each bone under a one-bone IK constraint aiming it at another bone of
    the chain: posed all together by ikarus's solver (``ik="ikarus"``), over a minute of work
    (256 bones under 16,384 such constraints took 6.4 s of CPU)."""
    n, m = 1024, 1024
    bones = [{"name": "root"}] + [
        {"name": f"b{i}", "parent": "root" if i == 0 else f"b{i - 1}", "length": 1, "x": 0 if i == 0 else 1, "rotation": 0.1}
        for i in range(n)
    ]
    ik = []
    for k in range(m):
        i = k % n
        j = (i + 1 + (k * 37) % (n - 1)) % n
        ik.append({"name": f"aim{k}", "order": k, "bones": [f"b{i}"], "target": f"b{j}"})
    return ikarus.Rig.from_json(json.dumps({"skeleton": {"spine": "4.2.11"}, "bones": bones, "ik": ik}))


def _pose() -> object:
    return _TANGLE["rig"].pose(ik="ikarus")


_TANGLE: dict = {}


@pytest.mark.parametrize("call", [_solve, _batch, _call, _pose], ids=["Chain.solve", "Chain.solve_batch", "ikarus.call", "Rig.pose"])
def test_ctrl_c_stops_a_long_call(call) -> None:
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    if call is _pose:
        _TANGLE["rig"] = _tangle()  # read before the clock and the signal: the pose is what is stopped
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
