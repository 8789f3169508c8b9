"""solve_batch equals a loop of Chain.solve and `ikarus solve --batch`, whatever the threads."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

import ikarus
from conftest import ROOT, run_cli


def goals(n: int, seed: int, angle: bool = False) -> np.ndarray:
    rng = np.random.default_rng(seed)
    r = 6.5 * np.sqrt(rng.random(n))
    t = rng.uniform(-np.pi, np.pi, n)
    cols = [r * np.cos(t), r * np.sin(t)]
    if angle:
        cols.append(rng.uniform(-180, 180, n))
    return np.column_stack(cols)


def check_equals_loop(chain, g, batch, **options):
    for i, row in enumerate(g):
        out = chain.solve(tuple(row), **options)
        assert batch["status"][i] == out.status, i
        assert batch["error"][i] == out.error, i
        assert batch["iterations"][i] == out.iterations, i
        assert batch["angles_deg"][i].tolist() == out.angles_deg.tolist(), i


@pytest.mark.parametrize("options", [{}, {"limits": True}, {"method": "fabrik", "restarts": 2}])
def test_batch_equals_a_loop_of_solve(options):
    chain = ikarus.Chain()
    g = goals(200, 7)
    batch = chain.solve_batch(g, **options)
    assert batch["angles_deg"].shape == (200, 3) and batch["angles_deg"].dtype == np.float64
    assert batch["status"].shape == (200,) and batch["status"].dtype.kind == "U"
    assert batch["error"].dtype == np.float64 and batch["iterations"].dtype == np.uint32
    check_equals_loop(chain, g, batch, **options)


def test_batch_with_orientation_equals_a_loop():
    chain = ikarus.Chain.from_toml(ROOT / "examples" / "arms" / "seven.toml")
    g = goals(60, 8, angle=True)
    check_equals_loop(chain, g, chain.solve_batch(g, threads=2))


def test_threads_do_not_change_a_bit():
    chain = ikarus.Chain()
    g = goals(3000, 9)
    one, two, every = chain.solve_batch(g, threads=1), chain.solve_batch(g, threads=2), chain.solve_batch(g)
    for key in ("angles_deg", "status", "error", "iterations"):
        assert np.array_equal(one[key], two[key]) and np.array_equal(one[key], every[key]), key
    # Views and non-contiguous input give the same answer as a copy.
    wide = np.column_stack([g[:, 0], np.zeros(len(g)), g[:, 1]])[:, ::2]
    assert not wide.flags["C_CONTIGUOUS"]
    assert np.array_equal(chain.solve_batch(wide)["angles_deg"], one["angles_deg"])


@pytest.mark.parametrize("angle,args", [(False, []), (False, ["--limits"]), (True, ["--method", "dls"])])
def test_batch_equals_the_cli_batch(tmp_path, angle, args):
    g = goals(400, 11, angle=angle)
    path = tmp_path / "goals.csv"
    header = "x,y,angle_deg" if angle else "x,y"
    path.write_text(header + "\n" + "\n".join(",".join(repr(float(v)) for v in row) for row in g) + "\n")
    result = run_cli("solve", "--batch", str(path), "--threads", "2", *args)
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert len(rows) == len(g)
    options = {"method": "dls"} if "--method" in args else {"limits": True} if "--limits" in args else {}
    batch = ikarus.Chain().solve_batch(g, **options)
    for i, row in enumerate(rows):
        assert float(row["x"]) == g[i, 0] and float(row["y"]) == g[i, 1]
        assert batch["status"][i] == row["status"], i
        assert batch["error"][i] == float(row["error"]), i
        assert batch["iterations"][i] == int(row["iterations"]), i
        assert batch["angles_deg"][i].tolist() == [float(row[f"theta{k}_deg"]) for k in (1, 2, 3)], i


def test_an_empty_batch():
    out = ikarus.Chain().solve_batch(np.zeros((0, 2)))
    assert out["angles_deg"].shape == (0, 3) and out["status"].shape == (0,)


def test_python_threads_sharing_a_chain_get_the_same_bits():
    # solve releases the GIL; a thread that finds the cached solver busy uses a fresh one.
    from concurrent.futures import ThreadPoolExecutor

    chain = ikarus.Chain()
    g = [tuple(row) for row in goals(400, 12).tolist()]
    want = [chain.solve(x).angles_deg.tolist() for x in g]
    with ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda x: chain.solve(x).angles_deg.tolist(), g * 3))
    assert got == want * 3


@pytest.mark.parametrize("dtype", [np.int64, np.int32, np.uint8, np.float32, np.float16])
def test_goals_of_any_real_number_type_are_converted(dtype):
    # Integer and float32 goals are the float64 goals of the same values, as NumPy converts them.
    chain = ikarus.Chain()
    g = np.array([[2, 3], [1, 1], [0, 4], [7, 0], [5, 1]], dtype=dtype)
    want = chain.solve_batch(g.astype(np.float64))
    got = chain.solve_batch(g)
    for key in ("angles_deg", "status", "error", "iterations"):
        assert np.array_equal(got[key], want[key]), key


def test_goals_as_nested_lists_are_converted():
    chain = ikarus.Chain()
    want = chain.solve_batch(np.array([[2.0, 3.0, 45.0], [1.0, 1.0, 0.0]]))
    got = chain.solve_batch([[2, 3, 45], (1.0, 1, 0)])
    for key in ("angles_deg", "status", "error", "iterations"):
        assert np.array_equal(got[key], want[key]), key
