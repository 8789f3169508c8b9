"""Rigs with prismatic joints and offsets (``examples/joints/``) from Python: the solve's
``extensions``, and the ``extensions`` columns of ``animate`` and ``track``, equal the CLI's
JSON bit for bit; a rig without prismatic joints has none."""

from __future__ import annotations

import ikarus
from conftest import ROOT, cli_json

CASES = [("rrp", "ram", (1.2, 1.3)), ("prr", "lower", (1.4, 0.9))]


def _file(name: str) -> str:
    return str(ROOT / "examples" / "joints" / f"{name}.toml")


def test_a_prismatic_rigs_solve_reports_its_extensions_as_the_cli():
    for name, bone, (x, y) in CASES:
        want = cli_json("solve", "--rig", _file(name), "--goal", f"{bone}={x},{y}", "--limits", "--restarts", "8")
        got = ikarus.Rig.from_toml(_file(name)).solve({bone: (x, y)}, limits=True, restarts=8)
        assert got.status == want["status"] == "reached", name
        assert got.extensions == want["extensions"] and list(got.extensions) == list(want["extensions"]), name
        assert got.angles_deg.tolist() == list(want["angles_deg"].values()), name
        assert got.joints[1:].tolist() == list(want["joints"].values()), name
        d = got.to_dict()
        assert d["extensions"] == want["extensions"], name
    plain = ikarus.Rig.from_toml(_file("palm")).solve({"index_tip": (0.029, 0.1228)})
    assert plain.extensions == {} and "extensions" not in plain.to_dict()
    assert ikarus.Chain().solve((2.0, 1.0)).extensions == {}


def test_a_prismatic_rigs_motion_and_track_have_extension_columns_as_the_cli():
    for name, bone, (x, y) in CASES:
        rig = ikarus.Rig.from_toml(_file(name))
        want = cli_json("animate", "--rig", _file(name), "--goal", f"{bone}={x},{y}", "--limits", "--frames", "7")
        got = rig.animate({bone: (x, y)}, limits=True, frames=7)
        ext = got.frames.extensions
        assert ext is not None and list(ext) == list(want["frames"][0]["extensions"]), name
        for b, column in ext.items():
            assert column.tolist() == [f["extensions"][b] for f in want["frames"]], (name, b)
        assert got.frames.angles_deg.tolist() == [list(f["angles_deg"].values()) for f in want["frames"]], name
        line = f"{x},{y},{x - 0.1},{y + 0.05}"
        want = cli_json("track", "--rig", _file(name), "--effector", bone, "--line", line, "--samples", "5")
        got = rig.track(bone, line=(x, y, x - 0.1, y + 0.05), samples=5)
        ext = got.samples.extensions
        assert ext is not None and list(ext) == list(want["samples"][0]["extensions"]), name
        for b, column in ext.items():
            assert column.tolist() == [s["extensions"][b] for s in want["samples"]], (name, b)
    motion = ikarus.Rig.shipped("hand").animate({"little_distal": (0.03, 0.12)}, frames=3)
    assert motion.frames.extensions is None


def test_an_arm_file_with_a_slide_solves_through_the_api_and_chain_refuses_it():
    """``examples/arms/rrp.toml`` (an arm file whose last link slides) is a one-branch rig:
    ``ikarus.call("solve", {"arm": …})`` answers as ``ikarus solve --arm`` does, with the goal
    on the last link; ``Chain`` holds only revolute links at their parents' tips, so it refuses
    the file in one line naming the first joint key."""
    import tomllib

    import pytest

    path = ROOT / "examples" / "arms" / "rrp.toml"
    want = cli_json("solve", "--arm", str(path), "--goal", "0.5,2.5", "--limits")
    arm = tomllib.loads(path.read_text())
    got = ikarus.call("solve", {"arm": arm, "goal": {"x": 0.5, "y": 2.5}, "options": {"limits": True}})
    assert got["status"] == want["status"] == "reached"
    assert got["angles_deg"] == want["angles_deg"] and got["extensions"] == want["extensions"]
    assert list(got["extensions"]) == ["link2"] and got["extensions"]["link2"] > 0.3
    with pytest.raises(ValueError) as e:
        ikarus.Chain.from_toml(path)
    message = str(e.value)
    assert "links[2].joint: an arm with offsets or slides is a one-branch rig" in message, message
    assert "\n" not in message
