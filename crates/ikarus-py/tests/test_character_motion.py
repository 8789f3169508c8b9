"""A character's motion and its Spine export through the typed API (``Rig.character_motion``,
``Rig.export_spine``): the numbers of ``ikarus animate --rig CHARACTER.json`` bit for bit, and
its file byte for byte; a motion over the caps refused naming the cap; a pose or motion whose
numbers are not finite refused, never answered; ``ikarus.plot`` draws a character's bones."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import ikarus

from conftest import ROOT, run_cli

SPINEBOY = "examples/characters/spine-spineboy-pro.json"


@pytest.fixture(scope="module")
def spineboy() -> ikarus.Rig:
    return ikarus.Rig.from_file(ROOT / SPINEBOY)


def _keys(spineboy: ikarus.Rig) -> dict:
    """spineboy's front foot target keyed over four keys from where its setup pose has it (the
    keys of the CLI's tests)."""
    b = spineboy.pose().bone("front-leg-target")
    x, y = b["x"], b["y"]
    key = lambda t, dx, dy: {"time": t, "x": x + dx, "y": y + dy}  # noqa: E731
    return {"fps": 30, "tracks": {"front-leg-target": [key(0.0, 0, 0), key(0.3, 40, 60), key(0.6, 80, 20), key(0.9, 20, 0)]}}


def _assert_columns(got: ikarus.CharacterMotion, want: dict) -> None:
    frames = want["frames"]
    assert got.time.tolist() == [f["time"] for f in frames]
    assert got.name == [b["name"] for b in frames[0]["bones"]]
    assert got.x.shape == (len(frames), len(got.name)) and got.x.dtype == np.float64
    for column in ("x", "y", "rotation_deg"):
        assert getattr(got, column).tolist() == [[b[column] for b in f["bones"]] for f in frames], column  # exactly
    assert got.tip_x.tolist() == [[b["tip"][0] for b in f["bones"]] for f in frames]
    assert got.tip_y.tolist() == [[b["tip"][1] for b in f["bones"]] for f in frames]
    assert got.unsupported == want["unsupported"]


def test_keyed_motion_and_export_are_the_clis(spineboy: ikarus.Rig, tmp_path: Path) -> None:
    keys = _keys(spineboy)
    path = tmp_path / "keys.json"
    path.write_text(json.dumps(keys), encoding="utf-8")
    args = ["animate", "--rig", SPINEBOY, "--keys", str(path), "--animation", "walk", "--format"]
    motion = spineboy.character_motion(keys=keys, animation="walk")
    _assert_columns(motion, json.loads(run_cli(*args, "json").stdout))
    assert len(motion) == 28  # 0.9 s at 30 fps
    assert motion.pose(3).bone("front-leg-target")["x"] == motion.x[3][motion.name.index("front-leg-target")]
    # The keys file's path is taken as --keys takes it.
    assert spineboy.character_motion(keys=path, animation="walk").x.tolist() == motion.x.tolist()
    exported = spineboy.export_spine(keys=keys, animation="walk", animation_name="ikarus")
    assert exported == run_cli(*args, "spine").stdout
    assert "ikarus" in json.loads(exported)["animations"]


def test_eased_targets_are_the_clis(spineboy: ikarus.Rig) -> None:
    got = spineboy.character_motion({"front-leg-target": (120.0, 40.0)}, duration=0.5, fps=10, ease="smoothstep")
    cli = run_cli("animate", "--rig", SPINEBOY, "--target", "front-leg-target=120,40", "--duration", "0.5", "--fps", "10", "--ease", "smoothstep", "--format", "json")
    _assert_columns(got, json.loads(cli.stdout))


def test_a_motion_over_the_caps_is_refused_naming_the_cap(spineboy: ikarus.Rig) -> None:
    with pytest.raises(ValueError, match="cap"):
        spineboy.export_spine({"front-leg-target": (120.0, 40.0)}, duration=1000.0, fps=240.0)
    with pytest.raises(ValueError, match=r"^fps"):
        spineboy.character_motion({"front-leg-target": (120.0, 40.0)}, fps=-1.0)
    with pytest.raises(ValueError, match="character_motion and export_spine take a character"):
        ikarus.Rig.shipped("puppet").character_motion({"hand": (0.0, 0.0)})


def _overflowing() -> ikarus.Rig:
    """Finite numbers whose pose is not: a bone at x 1e308 under a parent at x 1e308."""
    text = {
        "skeleton": {"spine": "4.2.11"},
        "bones": [{"name": "root"}, {"name": "far", "parent": "root", "x": 1e308}, {"name": "farther", "parent": "far", "x": 1e308}],
    }
    return ikarus.Rig.from_json(json.dumps(text))


def test_a_pose_that_is_not_finite_is_refused() -> None:
    rig = _overflowing()
    with pytest.raises(ValueError, match=r"farther.*finite|finite.*farther|overflow"):
        rig.pose()
    with pytest.raises(ValueError, match=r"farther.*finite|finite.*farther|overflow"):
        rig.character_motion({"far": (0.0, 1.0)}, duration=0.1, fps=10)


def test_plot_draws_a_character(spineboy: ikarus.Rig) -> None:
    plt = pytest.importorskip("matplotlib.pyplot")
    ax = ikarus.plot(spineboy)
    lines = ax.get_lines()
    xs = lines[0].get_xdata()
    assert np.count_nonzero(np.isnan(xs)) == len(spineboy.bones)  # one segment per bone
    pose = spineboy.pose(animation="walk", time=0.4)
    ax = ikarus.plot(spineboy, pose, goal=(0.0, 100.0))
    assert ax.get_lines()[0].get_xdata()[1] == pose.tip_x[0]
    ikarus.plot(pose)
    with pytest.raises(TypeError, match="Rig.render"):
        ikarus.plot(ikarus.Rig.shipped("puppet"))
    plt.close("all")
