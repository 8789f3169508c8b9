"""Chain.solve equals `ikarus solve --format json` for the same inputs, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import ikarus
from conftest import ROOT, cli_json

# (chain, goal, keyword options, the CLI's arguments for the same solve)
CASES = [
    ("seed", (2.0, 3.0), {}, ["--goal", "2,3"]),
    ("seed", (4.0, 2.0, 0.0), {}, ["--goal", "4,2", "--goal-angle", "0"]),
    ("seed", (0.0, -4.0), {"limits": True}, ["--goal=0,-4", "--limits"]),
    ("seed", (-3.0, -1.0), {"limits": True}, ["--goal=-3,-1", "--limits"]),
    # `--limit-mode` implies `--limits` on the command line; the API's (and so this edge's)
    # `limit_mode` does not, so `limits=True` goes with it.
    ("seed", (0.0, -4.0), {"limits": True, "limit_mode": "clamp", "restarts": 0}, ["--goal=0,-4", "--limit-mode", "clamp", "--restarts", "0"]),
    ("seed", (1.5, 2.5), {"method": "dls"}, ["--goal", "1.5,2.5", "--method", "dls"]),
    ("seed", (1.5, 2.5), {"method": "dls", "lambda": 0.25}, ["--goal", "1.5,2.5", "--method", "dls", "--lambda", "0.25"]),
    ("seed", (1.5, 2.5), {"method": "dls", "lambda_": 0.25}, ["--goal", "1.5,2.5", "--method", "dls", "--lambda", "0.25"]),
    ("seed", (-2.0, 3.0), {"method": "ccd", "record_every": 3}, ["--goal=-2,3", "--method", "ccd", "--record-every", "3"]),
    ("seed", (-2.0, 3.0), {"method": "fabrik", "tolerance": 1e-9}, ["--goal=-2,3", "--method", "fabrik", "--tolerance", "1e-9"]),
    ("seed", (2.0, 1.0, 30.0), {"method": "pinv", "no_closed_form": True}, ["--goal", "2,1", "--goal-angle", "30", "--method", "pinv", "--no-closed-form"]),
    ("seed", (7.0, 0.5), {}, ["--goal", "7,0.5"]),
    ("seven", (1.0, 2.0), {}, ["--goal", "1,2", "--arm", "examples/arms/seven.toml"]),
    ("seven", (-1.5, 0.7, 120.0), {"limits": True, "rates": [1, 0.5, 1, 1, 1, 1, 1]}, ["--goal=-1.5,0.7", "--goal-angle", "120", "--arm", "examples/arms/seven.toml", "--limits", "--rates", "1,0.5,1,1,1,1,1"]),
    ("tentacle", (2.0, -1.0), {"method": "sdls", "max_iterations": 50}, ["--goal=2,-1", "--arm", "examples/arms/tentacle.toml", "--method", "sdls", "--max-iterations", "50"]),
]


def chain_of(name: str) -> ikarus.Chain:
    return ikarus.Chain() if name == "seed" else ikarus.Chain.from_toml(ROOT / "examples" / "arms" / f"{name}.toml")


def same(a, b) -> bool:
    """Equal bit for bit (floats compared with ==, arrays elementwise, shapes too)."""
    return np.array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float))


@pytest.mark.parametrize("name,goal,options,args", CASES, ids=[" ".join(c[3]) for c in CASES])
def test_solve_equals_the_cli_bit_for_bit(name, goal, options, args):
    want = cli_json("solve", *args)
    out = chain_of(name).solve(goal, **options)
    assert out.status == want["status"]
    assert out.iterations == want["iterations"]
    assert out.restarts == want["restarts"]
    assert out.error == want["error"]
    assert out.angle_error_deg == want["angle_error_deg"]
    assert out.reach_distance == want["reach_distance"]
    assert out.end_effector == (want["end_effector"]["x"], want["end_effector"]["y"], want["end_effector"]["angle_deg"])
    assert out.goal == (want["goal"]["x"], want["goal"]["y"], want["goal"]["angle_deg"])
    assert out.angles_deg.tolist() == want["angles_deg"]
    assert out.joints.tolist() == want["joints"]
    assert out.angles_deg.dtype == np.float64 and out.joints.shape == (len(want["angles_deg"]) + 1, 2)
    assert out.frames.tolist() == [f["angles_deg"] for f in want["frames"]]
    assert out.frame_joints.tolist() == [f["joints"] for f in want["frames"]]
    assert out.frame_iterations.tolist() == [f["iteration"] for f in want["frames"]]
    d = out.to_dict()
    for key in ("arm", "method", "limits", "limit_mode", "goal", "status", "iterations", "restarts", "error", "angle_error_deg", "tolerance", "reach_distance", "end_effector"):
        assert d[key] == want[key], key
    assert same(d["angles_deg"], want["angles_deg"]) and same(d["joints"], want["joints"])
    assert len(d["frames"]) == len(want["frames"])


def test_a_plain_solve_twice_gives_the_same_bits_and_reuses_nothing_visible():
    arm = ikarus.Chain()
    a, b = arm.solve((2.0, 3.0)), arm.solve([2.0, 3.0])
    c = arm.solve(np.array([2.0, 3.0]))
    assert a.angles_deg.tolist() == b.angles_deg.tolist() == c.angles_deg.tolist()
    # An options solve between two plain ones does not change the cached defaults.
    arm.solve((2.0, 3.0), method="ccd", restarts=0)
    assert arm.solve((2.0, 3.0)).angles_deg.tolist() == a.angles_deg.tolist()


def fields(out: ikarus.Outcome) -> tuple:
    """Every field of a chain's outcome, as plain Python values."""
    return (
        out.status, out.iterations, out.restarts, out.error, out.angle_error_deg, out.reach_distance,
        out.end_effector, out.goal, out.angles_deg.tolist(), out.joints.tolist(), out.frames.tolist(),
        out.frame_joints.tolist(), out.frame_iterations.tolist(),
    )


def test_outcomes_let_go_lend_their_buffers_to_later_solves_and_change_nothing():
    # A chain keeps the buffers of outcomes Python has dropped for its next solves; whatever
    # they held (more frames, a reach distance, another method's answer) must never show.
    seed = [(goal, options) for name, goal, options, _ in CASES if name == "seed"]
    fresh = [fields(ikarus.Chain().solve(goal, **options)) for goal, options in seed]
    arm = ikarus.Chain()
    for order in (range(len(seed)), reversed(range(len(seed)))):
        for i in order:
            assert fields(arm.solve(seed[i][0], **seed[i][1])) == fresh[i], seed[i]
    held = [arm.solve(goal, **options) for goal, options in seed]
    assert [fields(out) for out in held] == fresh
    del held
    assert [fields(arm.solve(goal, **options)) for goal, options in seed] == fresh


def test_outcome_fields():
    out = ikarus.Chain().solve((2.0, 3.0))
    assert out.status == "reached" and out.reached
    assert isinstance(out.iterations, int) and isinstance(out.error, float)
    assert out.reach_distance is None
    assert "reached" in repr(out)
    limited = ikarus.Chain().solve((-3.0, -1.0), limits=True)
    assert limited.status == "unreachable" and limited.reach_distance > 3.49


def test_a_chain_from_lengths_equals_its_arm_file(tmp_path):
    text = """name = "mine"
base = [0.5, -0.25]

[[links]]
length = 2.5
angle_deg = 10.0
limits_deg = [-60.0, 60.0]

[[links]]
length = 1.5
angle_deg = -20.0

[[links]]
length = 0.75
limits_deg = [-120.0, 120.0]
"""
    path = tmp_path / "mine.toml"
    path.write_text(text)
    built = ikarus.Chain([2.5, 1.5, 0.75], angles_deg=[10, -20, 0], limits_deg=[(-60, 60), None, (-120, 120)], base=(0.5, -0.25), name="mine")
    read = ikarus.Chain.from_toml(path)
    assert built.name == read.name == "mine"
    assert built.limits_deg == read.limits_deg
    for goal, options, args in [((2.0, 2.0), {}, []), ((1.0, -2.0), {"limits": True}, ["--limits"])]:
        want = cli_json("solve", "--arm", str(path), f"--goal={goal[0]},{goal[1]}", *args)
        for chain in (built, read):
            out = chain.solve(goal, **options)
            assert out.angles_deg.tolist() == want["angles_deg"]
            assert out.status == want["status"] and out.error == want["error"]
            assert out.to_dict()["arm"] == want["arm"]


def test_chain_properties():
    arm = ikarus.Chain()
    assert len(arm) == 3 and arm.name == "seed"
    assert arm.lengths.tolist() == [3.0, 2.0, 1.0]
    assert arm.max_reach == 6.0
    assert np.allclose(arm.angles_deg, [5.0, 5.0, 5.0], rtol=0, atol=1e-12)
    assert arm.limits_deg[0] == pytest.approx((-45.0, 45.0))
    assert arm.joints([0, 0, 0]).tolist() == [[0.0, 0.0], [3.0, 0.0], [5.0, 0.0], [6.0, 0.0]]
    assert "seed" in repr(arm)


def test_a_chain_pickles(tmp_path):
    import pickle

    for chain in (ikarus.Chain(), ikarus.Chain([2.0, 1.5], limits_deg=[(-90, 90), None], name="two"), ikarus.Chain.from_toml(ROOT / "examples/arms/seven.toml")):
        back = pickle.loads(pickle.dumps(chain))
        assert type(back) is ikarus.Chain and back.name == chain.name
        assert back.solve((1.0, 1.5), limits=True).angles_deg.tolist() == chain.solve((1.0, 1.5), limits=True).angles_deg.tolist()
