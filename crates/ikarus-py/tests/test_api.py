"""animate, track, workspace, reach, pictures and ease equal the CLI's JSON, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import ikarus
from conftest import ROOT, cli_json


def test_animate_equals_the_cli():
    want = cli_json("animate", "--goal=-2,3", "--via", "4,1.5", "--ease", "parent", "--k1", "0.3", "--k2", "0.7", "--frames", "24")
    got = ikarus.Chain().animate((-2.0, 3.0), via=[(4.0, 1.5)], ease="parent", k1=0.3, k2=0.7, frames=24)
    assert got["ease"] == want["ease"] and got["duration"] == want["duration"] and got["solves"] == want["solves"]
    frames = got["frames"]
    assert frames["time"].tolist() == [f["time"] for f in want["frames"]]
    assert frames["angles_deg"].tolist() == [f["angles_deg"] for f in want["frames"]]
    assert frames["joints"].tolist() == [f["joints"] for f in want["frames"]]
    assert frames["angles_deg"].shape == (24, 3) and frames["joints"].shape == (24, 4, 2)


def test_animate_with_options_and_timing_equals_the_cli():
    want = cli_json("animate", "--goal", "2,3", "--duration", "0.5", "--fps", "20", "--limits", "--method", "dls", "--interpolation", "linear")
    got = ikarus.Chain().animate((2.0, 3.0), duration=0.5, fps=20, limits=True, method="dls", interpolation="linear")
    assert got["solves"] == want["solves"]
    assert got["frames"]["angles_deg"].tolist() == [f["angles_deg"] for f in want["frames"]]


def test_track_equals_the_cli():
    want = cli_json("track", "--figure8", "2,1,2", "--samples", "40")
    got = ikarus.Chain().track(figure8=(2.0, 1.0, 2.0), samples=40)
    assert got["summary"] == want["summary"]
    s = got["samples"]
    assert s["angles_deg"].tolist() == [x["angles_deg"] for x in want["samples"]]
    assert s["status"].tolist() == [x["status"] for x in want["samples"]]
    assert s["error"].tolist() == [x["error"] for x in want["samples"]]
    assert s["goal"].tolist() == [x["goal"] for x in want["samples"]]


def test_track_a_path_in_follow_mode_equals_the_cli(tmp_path):
    t = np.linspace(0, np.pi, 15)
    path = np.column_stack([4.5 * np.cos(t), 4.5 * np.sin(t)])
    csv = tmp_path / "path.csv"
    csv.write_text("x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in path.tolist()) + "\n")
    want = cli_json("track", "--path", str(csv), "--mode", "follow", "--limits", "--max-step-deg", "8")
    got = ikarus.Chain().track(path, mode="follow", limits=True, max_step_deg=8.0)
    assert got["summary"] == want["summary"]
    assert got["samples"]["angles_deg"].tolist() == [x["angles_deg"] for x in want["samples"]]


@pytest.mark.parametrize("limits", [False, True])
def test_workspace_equals_the_cli(limits):
    want = cli_json("workspace", *(["--limits"] if limits else []))
    got = ikarus.Chain().workspace(limits=limits)
    assert got == want
    assert (got["area"] < 41.25) == limits


def test_workspace_grid_equals_the_cli():
    want = cli_json("workspace", "--limits", "--resolution", "16")
    got = ikarus.Chain().workspace(limits=True, resolution=16)
    cells = got.pop("cells")
    assert got == want
    assert cells.shape == (16, 16) and cells.sum() * got["cell_size"] ** 2 == got["area"]


def test_workspace_of_an_arm_file():
    want = cli_json("workspace", "--arm", "examples/arms/seven.toml", "--limits")
    assert ikarus.Chain.from_toml(ROOT / "examples/arms/seven.toml").workspace(limits=True) == want


def test_reach_equals_the_cli():
    want = cli_json("reach", "--point=-3,-1", "--limits")
    assert ikarus.Chain().reach((-3.0, -1.0), limits=True) == want
    many = cli_json("reach", "--batch", "examples/points.csv", "--limits")
    points = np.array([[2.0, 3.0], [-3.0, -1.0], [6.0, 0.0], [0.0, -4.0]])
    got = ikarus.Chain().reach(points, limits=True)
    assert got["reachable"].tolist() == [w["reachable"] for w in many]
    assert got["distance"].tolist() == [w["distance"] for w in many]
    assert got["nearest"].tolist() == [w["nearest"] for w in many]


def test_pictures():
    arm = ikarus.Chain()
    svg = arm._repr_svg_()
    assert svg.lstrip().startswith("<svg") or svg.lstrip().startswith("<?xml")
    assert "<svg" in svg
    out = arm.solve((2.0, 3.0))
    assert "<svg" in out._repr_svg_()
    png = arm.render("workspace", "png", width=64, height=64, limits=True)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_ease_against_the_library_and_the_cli():
    # The library's documented value of Parent's ease (k1 0.3, k2 0.75) at 0.5.
    assert abs(ikarus.ease("parent", 0.5, k1=0.3, k2=0.75) - 0.488646) < 1e-6
    t = np.linspace(0, 1, 11)
    s = ikarus.ease("sine", t)
    assert s.shape == (11,) and s[0] == 0.0 and s[-1] == 1.0
    assert np.all(np.diff(s) > 0)
    grid = ikarus.ease("smoothstep", t.reshape(11, 1))
    assert grid.shape == (11, 1)
    assert ikarus.ease("linear", 0.25) == 0.25
    assert ikarus.ease("linear", 0.25, velocity=True) == 1.0
    # A one-link arm's animate moves its angle by the ease: frames' angles against ease(t).
    one = ikarus.Chain([1.0])
    motion = one.animate((0.0, 1.0), frames=11, ease="parent", k1=0.2, k2=0.6)
    angle = motion["frames"]["angles_deg"][:, 0]
    want = angle[0] + (angle[-1] - angle[0]) * ikarus.ease("parent", motion["frames"]["time"], k1=0.2, k2=0.6)
    assert np.allclose(angle, want, rtol=0, atol=1e-9)


def test_plot_returns_axes_and_draws(tmp_path):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    arm = ikarus.Chain()
    out = arm.solve((2.0, 3.0, 120.0), limits=True)
    ax = ikarus.plot(arm, out, workspace=True, limits=True)
    assert isinstance(ax, matplotlib.axes.Axes)
    assert ax.lines and ax.patches
    path = tmp_path / "plot.png"
    ax.figure.savefig(path, dpi=80)
    assert path.stat().st_size > 1000
    ax.figure.savefig("/tmp/ikarus-plot.png", dpi=100)
    plt.close("all")
    ax = arm.plot(pose=[0, 45, 90], goal=(1, 4))
    assert ax.lines
    plt.close("all")
    # Drawing imported the drawing module; `ikarus.plot` is still the function, not that module.
    assert callable(ikarus.plot) and ikarus.plot(arm).lines
    plt.close("all")


def test_the_namespace_is_the_api():
    # `dir(ikarus)` and `from ikarus import *` give the API and nothing the package uses inside.
    public = sorted(name for name in dir(ikarus) if not name.startswith("_"))
    assert public == sorted(name for name in ikarus.__all__ if not name.startswith("_")), public
    assert public == sorted(
        ["Chain", "Rig", "Outcome", "Effector", "Motion", "MotionFrames", "Track", "TrackSamples", "Pose", "CharacterMotion", "Atlas", "call", "ease", "plot"]
        + ["SolveOptions", "TrackSolveOptions", "MotionOptions", "TrackOptions", "RigGoal", "MotionSolve", "TrackSummary"]
        + ["Method", "LimitMode"]
    )
    names: dict = {}
    exec("from ikarus import *", names)
    assert sorted(k for k in names if k != "__builtins__") == sorted(ikarus.__all__)
    for name in ikarus.__all__:
        assert getattr(ikarus, name) is not None, name


def test_a_rig_solve_equals_the_cli():
    want = cli_json("solve", "--rig", "examples/rigs/puppet.toml", "--goal", "right_hand=0.6451,1.0024", "--goal", "left_hand=0.8118,0.5652", "--pin", "left_foot", "--pin", "right_foot", "--limits")
    rig = ikarus.Rig.from_toml(ROOT / "examples/rigs/puppet.toml")
    assert rig.name == "puppet" and len(rig) == 16 and rig.bones[0] == "pelvis"
    got = rig.solve({"right_hand": (0.6451, 1.0024), "left_hand": (0.8118, 0.5652)}, pins=["left_foot", "right_foot"], limits=True)
    want.pop("solve_us")
    assert got.to_dict() == want
    assert ikarus.Rig.shipped("puppet").rig == rig.rig
    assert "<svg" in rig._repr_svg_()


def test_rig_errors():
    rig = ikarus.Rig.shipped("puppet")
    with pytest.raises(ValueError, match='no bone named "right_hnd"'):
        rig.solve({"right_hnd": (0.3, 0.8)})
    with pytest.raises(ValueError, match="unknown rig 'robot'"):
        ikarus.Rig.shipped("robot")


def test_a_bad_rig_file_gives_the_cli_line(tmp_path):
    from conftest import cli_error

    path = tmp_path / "bad.toml"
    path.write_text('bones = [{name = "a", parent = "b", length = 1}]\n')
    want = cli_error("solve", "--rig", str(path), "--goal", "a=1,1")
    with pytest.raises(ValueError) as e:
        ikarus.Rig.from_toml(path)
    assert str(e.value) == want


def test_a_character_file_is_named_for_what_it_is():
    """Issue 26: a Spine or DragonBones file given as a rig says what it is instead of failing on a key."""
    for name, kind, bones, ik in [("spine-raptor-pro.json", "Spine", 76, 9), ("dragonbones-mecha_1406_ske.json", "DragonBones", 17, 4)]:
        path = ROOT / "examples" / "characters" / name
        with pytest.raises(ValueError) as e:
            ikarus.Rig.from_toml(path)
        assert str(e.value).startswith(f"rig file {path}: a {kind} character ({bones} bones, {ik} IK constraints), which Rig does not take")


def test_a_rig_over_the_bone_cap_is_refused_before_it_is_built(tmp_path):
    """Issue 24: a rig's bones are counted first (the command line's cap, 10 000), in a file and in a dict."""
    n = 10_001
    bones = [{"name": f"b{i}", "length": 0.001, **({"parent": f"b{i - 1}"} if i else {})} for i in range(n)]
    with pytest.raises(ValueError, match=r"^rig: bones: 10001 bones exceed the cap of 10000"):
        ikarus.Rig({"bones": bones}).solve({f"b{n - 1}": (1.0, 0.0)})
    path = tmp_path / "chain.toml"
    path.write_text("".join(f'[[bones]]\nname = "b{i}"\n' + (f'parent = "b{i - 1}"\n' if i else "") + "length = 0.001\n" for i in range(n)))
    with pytest.raises(ValueError, match=rf"^rig file {path}: bones: 10001 bones exceed the cap of 10000"):
        ikarus.Rig.from_toml(path)
    # At the cap, a long chain is solved (its memory is linear in its bones).
    out = ikarus.Rig({"bones": bones[:10_000]}).solve({"b9999": (5.0, 5.0)}, max_iterations=3, restarts=0)
    assert len(out["angles_deg"]) == 10_000
