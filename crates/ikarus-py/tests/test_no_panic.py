"""Random valid and invalid inputs: every call returns or raises ValueError (TypeError for a
value of the wrong kind), never a Rust panic (PanicException, a BaseException) nor NaN in a
result."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ikarus

MAGNITUDES = [1e-9, 1e-3, 1.0, 1e3, 1e9, 1e150, 1e200]
ODD = [0.0, -1.0, float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 5e-324]
# A subnormal link length (5e-324) makes the library's exact region fail (its boundary comes
# out empty: a 500 from /api/workspace, an error line from `ikarus workspace`), reported; the
# lengths here stay normal numbers.
ODD_LENGTHS = [0.0, -1.0, float("nan"), float("inf"), -float("inf"), 1e308, -1e308]


def random_chain(rng):
    n = int(rng.integers(1, 8))
    scale = float(rng.choice(MAGNITUDES))
    lengths = (scale * rng.uniform(0.1, 2.0, n)).tolist()
    if rng.random() < 0.15:
        lengths[int(rng.integers(n))] = float(rng.choice(ODD_LENGTHS))
    limits = []
    for _ in range(n):
        if rng.random() < 0.5:
            limits.append(None)
        else:
            lo, hi = sorted(rng.uniform(-400, 400, 2).tolist())
            limits.append((hi, lo) if rng.random() < 0.05 else (lo, hi))
    angles = rng.uniform(-720, 720, n).tolist()
    return dict(lengths=lengths, angles_deg=angles, limits_deg=limits)


def random_options(rng):
    options = {}
    if rng.random() < 0.5:
        options["method"] = str(rng.choice(["lm", "dls", "pinv", "sdls", "transpose", "ccd", "fabrik", "analytic", "nope"]))
    if rng.random() < 0.5:
        options["limits"] = bool(rng.random() < 0.5)
    if rng.random() < 0.3:
        options["limit_mode"] = str(rng.choice(["ignore", "clamp", "lock", "nullspace", "weighted", "x"]))
    if rng.random() < 0.3:
        options["restarts"] = int(rng.integers(-1, 5))
    if rng.random() < 0.3:
        options["max_iterations"] = int(rng.integers(0, 200))
    if rng.random() < 0.3:
        options["tolerance"] = float(rng.choice([1e-9, 1e-6, 0.1, 0.0, -1.0, 1e300]))
    if rng.random() < 0.2:
        options["lambda_"] = float(rng.choice([0.0, 0.1, 10.0, -1.0]))
    if rng.random() < 0.2:
        options["backtrack"] = int(rng.integers(0, 70))
    return options


def finite_outcome(out, n):
    assert out.status in ("reached", "unreachable", "stalled", "iteration_limit")
    assert math.isfinite(out.error) and out.angles_deg.shape == (n,)
    assert np.all(np.isfinite(out.angles_deg)) and np.all(np.isfinite(out.joints))


@pytest.mark.parametrize("seed", range(6))
def test_random_inputs_never_panic(seed):
    rng = np.random.default_rng(seed)
    made = solved = 0
    for _ in range(60):
        try:
            chain = ikarus.Chain(**random_chain(rng))
        except ValueError:
            continue
        made += 1
        n = len(chain)
        reach = chain.max_reach
        for _ in range(4):
            goal = [float(v) for v in rng.uniform(-1.5, 1.5, 2) * reach]
            if rng.random() < 0.3:
                goal.append(float(rng.uniform(-1e3, 1e3)))
            if rng.random() < 0.1:
                goal[int(rng.integers(len(goal)))] = float(rng.choice(ODD))
            options = random_options(rng)
            try:
                out = chain.solve(tuple(goal), **options)
            except ValueError:
                continue
            solved += 1
            finite_outcome(out, n)
            try:
                batch = chain.solve_batch(np.array([goal, goal]), threads=1, **options)
            except ValueError:
                continue
            assert batch["angles_deg"][0].tolist() == out.angles_deg.tolist()
        for call in (
            lambda: chain.workspace(limits=bool(rng.random() < 0.5)),
            lambda: chain.reach(rng.uniform(-reach, reach, (3, 2)), limits=True),
            lambda: chain.track(line=(0.0, 0.0, 0.5 * reach, 0.5 * reach), samples=5),
            lambda: chain.animate((0.3 * reach, 0.3 * reach), frames=3),
        ):
            try:
                call()
            except ValueError:
                pass
    assert made > 10 and solved > 10, (made, solved)
