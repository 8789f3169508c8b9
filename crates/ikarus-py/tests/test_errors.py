"""Each class of bad input raises one clear line (ValueError, or FileNotFoundError for a
missing file), never a Rust panic (which would reach Python as a PanicException, a
BaseException that `pytest.raises(ValueError)` does not catch)."""

from __future__ import annotations

import re

import numpy as np
import pytest

import ikarus
from conftest import ROOT, cli_error


def one_line(excinfo) -> str:
    message = str(excinfo.value)
    assert "\n" not in message and message, message
    return message


def api_error(request: dict) -> str:
    """The API's line for the request, as it names an option for Python: the keyword, not the
    request's field (`lambda = -1: …`, not `options.lambda = -1: …`), without the JSON text's
    position (` at line 1 column 54`)."""
    with pytest.raises(ValueError) as e:
        ikarus.call("solve", request)
    message = one_line(e)
    message = re.sub(r" at line \d+ column \d+$", "", message)
    return message.removeprefix("request body: ").removeprefix("options.").removeprefix("options: ")


@pytest.mark.parametrize(
    "text,fragment",
    [
        ("[[links]]\nlength = -2.0\n", "links[0].length = -2"),
        ("[[links]]\nlength = 1.0\nlimits_deg = [10.0, -10.0]\n", "links[0]"),
        ("[[links]]\nlength = 1.0\nangle_deg = nan\n", "links[0].angle_deg"),
        ("[[links]]\nlength = 1.0\nbogus = 1\n", "bogus"),
        ("[[links]]\nlength = 1.0\n[solver]\nlambda = -1.0\n", "lambda"),
    ],
)
def test_a_bad_arm_file_gives_the_cli_line(tmp_path, text, fragment):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    want = cli_error("solve", "--arm", str(path), "--goal", "1,1")
    with pytest.raises(ValueError) as e:
        ikarus.Chain.from_toml(path)
    assert one_line(e) == want
    assert fragment in want


@pytest.mark.parametrize(
    "kwargs,fragment",
    [
        ({"lengths": [3.0, -2.0, 1.0]}, "links[1].length = -2"),
        ({"lengths": [3.0, float("nan")]}, "links[1].length"),
        ({"lengths": [1.0, 1.0], "limits_deg": [(10.0, -10.0), None]}, "links[0]"),
        ({"lengths": [1.0, 1.0], "angles_deg": [90.0, 0.0], "limits_deg": [(0.0, 45.0), None]}, "links[0]"),
        ({"lengths": [1e200, 1e200]}, "reach"),
        ({"lengths": []}, "links"),
    ],
)
def test_bad_lengths_and_limits(kwargs, fragment):
    with pytest.raises(ValueError) as e:
        ikarus.Chain(**kwargs)
    assert fragment in one_line(e)


def test_lengths_and_the_arm_file_agree_on_the_message(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[[links]]\nlength = 3.0\n\n[[links]]\nlength = -2.0\n")
    want = cli_error("solve", "--arm", str(path), "--goal", "1,1")
    with pytest.raises(ValueError) as e:
        ikarus.Chain([3.0, -2.0])
    assert one_line(e).split(": ", 1)[1] == want.split(": ", 1)[1]


def test_mismatched_angles_or_limits():
    with pytest.raises(ValueError, match="angles_deg: expected 2"):
        ikarus.Chain([1.0, 1.0], angles_deg=[0.0])
    with pytest.raises(ValueError, match="limits_deg: expected 2"):
        ikarus.Chain([1.0, 1.0], limits_deg=[None])


@pytest.mark.parametrize(
    "options,request_options",
    [
        ({"lambda_": -1.0}, {"lambda": -1.0}),
        ({"tolerance": 0.0}, {"tolerance": 0.0}),
        ({"method": "xyz"}, {"method": "xyz"}),
        ({"limit_mode": "sideways"}, {"limit_mode": "sideways"}),
        ({"restarts": -1}, {"restarts": -1}),
        ({"max_iterations": -5}, {"max_iterations": -5}),
        ({"gain": "fast"}, {"gain": "fast"}),
        ({"rates": [1.0, 2.0]}, {"rates": [1.0, 2.0]}),
        ({"backtrack": 65}, {"backtrack": 65}),
        ({"limits": "yes"}, {"limits": "yes"}),
    ],
)
def test_a_bad_option_gives_the_api_line(options, request_options):
    want = api_error({"goal": {"x": 2, "y": 3}, "options": request_options})
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve((2.0, 3.0), **options)
    assert one_line(e) == want
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve_batch(np.array([[2.0, 3.0]]), **options)
    assert one_line(e) == want


def test_a_method_without_a_closed_form_for_the_goal():
    want = api_error({"goal": {"x": 2, "y": 3}, "options": {"method": "analytic"}})
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve((2.0, 3.0), method="analytic")
    assert one_line(e) == want


def test_an_unknown_option_is_named():
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve((2.0, 3.0), lamda=0.1)
    message = one_line(e)
    assert "lamda" in message and "lambda" in message


def test_a_non_finite_option_is_named():
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve((2.0, 3.0), tolerance=float("nan"))
    assert one_line(e) == "tolerance = NaN: must be a finite number"


@pytest.mark.parametrize(
    "goal,fragment",
    [((1.0,), "goal: expected (x, y) or (x, y, angle_deg), got 1 values"), ((1.0, 2.0, 3.0, 4.0), "got 4 values"), ((1.0, float("nan")), "goal.y: must be a finite number, got NaN"), ((float("inf"), 1.0), "goal.x: must be a finite number, got inf"), ((1.0, 1.0, float("nan")), "goal.angle")],
)
def test_bad_goals(goal, fragment):
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve(goal)
    assert fragment in one_line(e)


def test_a_goal_that_is_not_numbers():
    with pytest.raises((ValueError, TypeError)):
        ikarus.Chain().solve(("a", "b"))
    with pytest.raises((ValueError, TypeError)):
        ikarus.Chain().solve(None)


@pytest.mark.parametrize(
    "goals,fragment",
    [
        (np.zeros((3, 4)), "got (3, 4)"),
        (np.zeros(3), "goals: expected an array of numbers of shape (N, 2) or (N, 3), got (3,)"),
        (np.zeros((2, 2, 2), dtype=np.int64), "got (2, 2, 2)"),
        (np.array([["a", "b"]]), "goals: expected an array of numbers of shape (N, 2) or (N, 3), got (1, 2) of <U1"),
        (np.zeros((3, 2), dtype=bool), "got (3, 2) of bool"),
        (np.zeros((3, 2), dtype=complex), "got (3, 2) of complex128"),
        (np.array([[1.0, None]]), "got (1, 2) of object"),
        ([[1.0, 2.0], [3.0]], "goals: expected an array of numbers of shape (N, 2) or (N, 3), got list"),
        (np.array([[1.0, 2.0], [np.nan, 1.0]]), "goals[1].x: must be a finite number, got NaN"),
        (np.array([[1.0, 2.0], [np.inf, 1.0]], dtype=np.float32), "goals[1].x: must be a finite number, got inf"),
    ],
)
def test_bad_batch_goals(goals, fragment):
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve_batch(goals)
    assert fragment in one_line(e)


@pytest.mark.parametrize("threads", [0, -1, 100000])
def test_bad_threads(threads):
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve_batch(np.zeros((1, 2)), threads=threads)
    assert one_line(e).startswith(f"threads = {threads}: must be a whole number from 1 to 4096")


def test_a_missing_arm_file(tmp_path):
    with pytest.raises(FileNotFoundError):
        ikarus.Chain.from_toml(tmp_path / "nowhere.toml")


def test_bad_requests_of_the_api_methods():
    arm = ikarus.Chain()
    with pytest.raises(ValueError, match="frames"):
        arm.animate((2.0, 3.0), frames=0)
    with pytest.raises(ValueError, match="ease"):
        arm.animate((2.0, 3.0), ease="bouncy")
    with pytest.raises(ValueError):
        arm.track()
    with pytest.raises(ValueError, match="samples"):
        arm.track(line=(1, 1, 2, 2), samples=0)
    with pytest.raises(ValueError, match="resolution"):
        arm.workspace(resolution=0)
    with pytest.raises(ValueError, match="points"):
        arm.reach([[1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match="finite"):
        arm.reach((float("nan"), 1.0))
    with pytest.raises(ValueError):
        ikarus.ease("bouncy", 0.5)
    with pytest.raises(ValueError, match="k1"):
        ikarus.ease("parent", 0.5, k1=2.0)
    with pytest.raises(ValueError, match="t = 2"):
        ikarus.ease("sine", np.array([0.5, 2.0]))
