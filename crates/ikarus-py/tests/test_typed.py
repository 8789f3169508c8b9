"""One style for chains and rigs (issue 25, point 6): the same methods with the same typed
results, equal to the CLI's JSON; typed options checked against the backend's own lists."""

from __future__ import annotations

import dataclasses
import re
import typing

import numpy as np
import pytest

import ikarus
from ikarus import _types
from conftest import ROOT, cli_json

PUPPET = "examples/rigs/puppet.toml"


def names(items: list) -> tuple:
    return tuple(item["name"] for item in items)


def test_the_literal_names_are_the_backends():
    meta = ikarus.call("meta")
    assert typing.get_args(ikarus.Method) == names(meta["methods"])
    assert typing.get_args(ikarus.LimitMode) == names(meta["limit_modes"])
    assert typing.get_args(_types.EaseName) == names(meta["eases"])
    assert typing.get_args(_types.Interpolation) == names(meta["interpolations"])
    assert set(typing.get_args(_types.Status)) == set(ikarus._ikarus._status_names())


def unknown_option_fields() -> list:
    """The option names the API accepts, from its line for an unknown one."""
    with pytest.raises(ValueError) as e:
        ikarus.Chain().solve((2.0, 3.0), no_such_option=1)
    listed = re.search(r"expected one of (.*)$", str(e.value)).group(1)
    return re.findall(r"`([a-z_0-9]+)`", listed)


def test_the_options_typeddict_is_the_apis_option_set():
    want = {"lambda_" if f == "lambda" else f for f in unknown_option_fields()}
    assert set(ikarus.SolveOptions.__annotations__) == want
    assert ikarus.SolveOptions.__total__ is False
    track = {"solver_max_step_deg" if f == "max_step_deg" else f for f in want}
    assert set(ikarus.TrackSolveOptions.__annotations__) == track
    # animate's and track's keywords: their own settings over the solver's options.
    motion = {"frames", "duration", "fps", "ease", "k1", "k2", "interpolation", "from_solve", "start_deg"}
    assert set(ikarus.MotionOptions.__annotations__) == want | motion
    path = {"line", "circle", "figure8", "samples", "mode", "max_step_deg", "bound_first", "start_deg"}
    assert set(ikarus.TrackOptions.__annotations__) == track | path


def test_a_rig_solve_is_an_outcome_with_typed_effectors():
    args = ["solve", "--rig", PUPPET, "--goal", "right_hand=0.6451,1.0024", "--goal", "left_hand=0.8118,0.5652,-30", "--pin", "left_foot", "--limits", "--record-every", "5"]
    want = cli_json(*args)
    rig = ikarus.Rig.from_toml(ROOT / PUPPET)
    out = rig.solve({"right_hand": (0.6451, 1.0024), "left_hand": (0.8118, 0.5652, -30.0)}, pins=["left_foot"], limits=True, record_every=5)
    assert type(out) is ikarus.Outcome and type(out) is type(ikarus.Chain().solve((2.0, 3.0)))
    assert (out.status, out.iterations, out.restarts, out.error, out.angle_error_deg) == (
        want["status"], want["iterations"], want["restarts"], want["error"], want["angle_error_deg"])
    assert out.reached == (want["status"] == "reached") and out.reach_distance is None
    assert out.angles_deg.tolist() == [want["angles_deg"][b] for b in rig.bones]
    assert out.joints.tolist() == [[0.0, 0.0]] + [want["joints"][b] for b in rig.bones]
    assert [dataclass_like(e) for e in out.effectors] == want["effectors"]
    assert [e.name for e in out.effectors] == ["right_hand", "left_hand", "left_foot"]
    assert [e.pinned for e in out.effectors] == [False, False, True]
    # Frames: the rig's recorded poses, as the chain's are laid out.
    assert out.frame_iterations.tolist() == [f["iteration"] for f in want["frames"]]
    assert out.frames.tolist() == [f["angles_deg"] for f in want["frames"]]
    assert out.frame_joints.tolist() == [f["joints"] for f in want["frames"]]
    assert out.frames.shape == (len(want["frames"]), 16) and out.frame_joints.shape == (len(want["frames"]), 17, 2)
    # The old dict style still reads the JSON's fields.
    assert out["angles_deg"] == want["angles_deg"] and out["status"] == want["status"]
    with pytest.raises(KeyError):
        out["no_such_field"]
    # A chain's single tip and goal have no meaning for a rig: one line pointing to effectors.
    for field in ("goal", "end_effector"):
        with pytest.raises(AttributeError, match=rf"^{field}: a chain's alone; .*Outcome\.effectors"):
            getattr(out, field)
    assert "<svg" in out._repr_svg_()


def dataclass_like(e: ikarus.Effector) -> dict:
    return {"name": e.name, "pinned": e.pinned, "status": e.status, "error": e.error, "angle_error_deg": e.angle_error_deg, "tip": list(e.tip), "target": list(e.target)}


def test_a_chain_outcome_has_its_tip_as_one_effector():
    out = ikarus.Chain().solve((2.0, 3.0, 120.0), limits=True)
    (tip,) = out.effectors
    assert isinstance(tip, ikarus.Effector)
    assert dataclass_like(tip) == {"name": "tip", "pinned": False, "status": out.status, "error": out.error, "angle_error_deg": out.angle_error_deg, "tip": list(out.end_effector[:2]), "target": list(out.goal[:2])}
    assert tip == out.effectors[0] and tip != ikarus.Chain().solve((2.0, 2.0)).effectors[0]
    assert repr(tip).startswith("Effector(name='tip', pinned=False, status='unreachable', error=")
    with pytest.raises(AttributeError):
        tip.error = 0.0  # frozen


def test_a_chain_motion_is_typed_columns():
    want = cli_json("animate", "--goal=-2,3", "--via", "4,1.5", "--frames", "12")
    motion = ikarus.Chain().animate((-2.0, 3.0), via=[(4.0, 1.5)], frames=12)
    assert isinstance(motion, ikarus.Motion) and isinstance(motion.frames, ikarus.MotionFrames)
    assert (motion.body, motion.bones, motion.ease, motion.duration, motion.solves) == ("seed", None, want["ease"], want["duration"], want["solves"])
    assert motion.frames.time.tolist() == [f["time"] for f in want["frames"]]
    assert motion.frames.angles_deg.tolist() == [f["angles_deg"] for f in want["frames"]]
    assert motion.frames.joints.tolist() == [f["joints"] for f in want["frames"]]
    assert motion.frames.angles_deg.dtype == np.float64 and motion.frames.joints.shape == (12, 4, 2) and len(motion.frames) == 12
    with pytest.raises(dataclasses.FrozenInstanceError):
        motion.ease = "linear"  # type: ignore[misc]
    assert motion["arm"] == "seed" and motion["frames"]["time"] is motion.frames.time
    with pytest.raises(KeyError):
        motion["rig"] if motion.bones is not None else motion["no_such_key"]


def test_a_rig_motion_equals_the_cli():
    want = cli_json("animate", "--rig", PUPPET, "--goal", "right_hand=0.6,1.0", "--via", "right_hand=0.5,0.6", "--pin", "left_foot", "--pin", "right_foot", "--limits", "--frames", "9")
    rig = ikarus.Rig.shipped("puppet")
    motion = rig.animate({"right_hand": (0.6, 1.0)}, via=[{"right_hand": (0.5, 0.6)}], pins=["left_foot", "right_foot"], limits=True, frames=9)
    assert (motion.body, motion.bones, motion.ease, motion.duration) == ("puppet", tuple(rig.bones), want["ease"], want["duration"])
    assert motion.solves == want["solves"] and [s["effectors"][0]["name"] for s in motion.solves] == ["right_hand"] * 2
    assert motion.frames.time.tolist() == [f["time"] for f in want["frames"]]
    assert motion.frames.angles_deg.tolist() == [[f["angles_deg"][b] for b in rig.bones] for f in want["frames"]]
    assert motion.frames.joints.tolist() == [[[0.0, 0.0]] + [f["joints"][b] for b in rig.bones] for f in want["frames"]]
    assert motion.frames.joints.shape == (9, 17, 2)


def test_a_rig_track_equals_the_cli():
    want = cli_json("track", "--rig", PUPPET, "--effector", "right_hand", "--circle", "0.3,0.8,0.2", "--samples", "7", "--pin", "left_foot", "--pin", "right_foot")
    rig = ikarus.Rig.shipped("puppet")
    track = rig.track("right_hand", circle=(0.3, 0.8, 0.2), samples=7, pins=["left_foot", "right_foot"])
    assert isinstance(track, ikarus.Track) and isinstance(track.samples, ikarus.TrackSamples)
    assert (track.body, track.effector, track.mode, track.summary) == ("puppet", "right_hand", want["mode"], want["summary"])
    s = track.samples
    assert s.goal.tolist() == [x["goal"] for x in want["samples"]]
    assert s.status.tolist() == [x["status"] for x in want["samples"]]
    assert s.error.tolist() == [x["error"] for x in want["samples"]]
    assert s.step_deg.tolist() == [x["step_deg"] for x in want["samples"]]
    assert s.angles_deg.tolist() == [[x["angles_deg"][b] for b in rig.bones] for x in want["samples"]]
    assert s.joints.tolist() == [[[0.0, 0.0]] + [x["joints"][b] for b in rig.bones] for x in want["samples"]]
    assert s.angle_deg is None and len(s) == 7


def test_an_oriented_track_answer_has_its_angle_column():
    # The API's paths are positions only; the CLI's JSON adds "angle_deg" to an oriented
    # sample (a --path file with an angle column): the conversion keeps it as a column.
    row = {"goal": [2.0, 1.0], "status": "reached", "error": 0.0, "angles_deg": [1.0, 2.0], "joints": [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]], "step_deg": 0.0}
    answer = {"arm": "a", "mode": "plan", "samples": [dict(row, angle_deg=90.0), row], "summary": {}}
    track = ikarus.Track._of(answer)
    assert track.samples.angle_deg.tolist()[0] == 90.0 and np.isnan(track.samples.angle_deg[1])
    assert track.samples["angle_deg"] is track.samples.angle_deg
    assert ikarus.Track._of(dict(answer, samples=[row])).samples.angle_deg is None
    with pytest.raises(KeyError):
        ikarus.Track._of(dict(answer, samples=[row])).samples["angle_deg"]
    assert track.bones is None and track.effector is None and track.samples.joints.shape == (2, 3, 2)


def test_chain_and_rig_share_their_methods():
    shared = {"solve", "animate", "track", "render", "_repr_svg_"}
    for cls in (ikarus.Chain, ikarus.Rig):
        assert shared <= set(dir(cls)), cls
    # The backend builds the exact region and the batch for chains alone.
    assert {"workspace", "reach", "solve_batch"} <= set(dir(ikarus.Chain))
    assert not {"workspace", "reach", "solve_batch"} & set(dir(ikarus.Rig))


def test_options_are_keyword_only():
    arm = ikarus.Chain()
    with pytest.raises(TypeError):
        arm.solve_batch(np.zeros((2, 2)), 2)
    with pytest.raises(TypeError):
        arm.workspace(True)
    with pytest.raises(TypeError):
        arm.reach((1.0, 1.0), True)
    with pytest.raises(TypeError):
        arm.solve((2.0, 3.0), "dls")


@pytest.mark.parametrize("options,line", [
    ({"lamda": 0.1}, "lamda: unknown field `lamda`, expected one of `method`, `lambda`, "),
    ({"lambda_": -1}, "lambda = -1: must be a finite number ≥ 0"),
    ({"limit_mode": "lok"}, "limit_mode: unknown variant `lok`, expected one of `ignore`, "),
    ({"tolerance": float("nan")}, "tolerance = NaN: must be a finite number"),
])
def test_a_bad_option_is_one_line_naming_it_for_every_method(options, line):
    arm, rig = ikarus.Chain(), ikarus.Rig.shipped("puppet")
    calls = {
        "Chain.solve": lambda: arm.solve((2.0, 3.0), **options),
        "Chain.solve_batch": lambda: arm.solve_batch(np.array([[2.0, 3.0]]), **options),
        "Chain.animate": lambda: arm.animate((2.0, 3.0), **options),
        "Chain.track": lambda: arm.track(line=(2.0, 1.0, 2.0, 2.0), **options),
        "Rig.solve": lambda: rig.solve({"right_hand": (0.6, 1.0)}, **options),
        "Rig.animate": lambda: rig.animate({"right_hand": (0.6, 1.0)}, **options),
        "Rig.track": lambda: rig.track("right_hand", line=(0.3, 0.8, 0.4, 0.8), **options),
    }
    for name, call in calls.items():
        with pytest.raises(ValueError) as e:
            call()
        message = str(e.value)
        assert message.startswith(line) and "\n" not in message and " at line " not in message, (name, message)
