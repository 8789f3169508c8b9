"""Characters as rigs: ``Rig.from_json``/``Rig.from_file`` and ``Rig.pose``, whose columns are
``ikarus pose --format json``'s numbers bit for bit (one code path: the edge's pose job), and
within 1e-3 of Spine's runtime on the reference outputs."""

from __future__ import annotations

import json
import pickle

import numpy as np
import pytest

import ikarus

from conftest import ROOT, run_cli

CHARACTERS = ROOT / "examples" / "characters"
REFERENCE = ROOT / "crates" / "ikarus-edge" / "tests" / "reference"
FILES = {"spineboy": "spine-spineboy-pro.json", "raptor": "spine-raptor-pro.json"}
# Per character: a target bone moved (its limb follows) in the cases below.
TARGETS = {"spineboy": ("front-leg-target", (120.0, 40.0)), "raptor": ("front-foot-target", (400.0, -20.0))}


def rig(name: str) -> ikarus.Rig:
    return ikarus.Rig.from_file(CHARACTERS / FILES[name])


def cli_pose(name: str, *args: str) -> dict:
    out = run_cli("pose", "--rig", f"examples/characters/{FILES[name]}", "--format", "json", *args).stdout
    return json.loads(out)


@pytest.mark.parametrize("name", sorted(FILES))
@pytest.mark.parametrize("case", ["setup", "walk", "target", "walk+target"])
def test_pose_is_the_clis_bit_for_bit(name: str, case: str) -> None:
    bone, (x, y) = TARGETS[name]
    kwargs: dict = {}
    args: list = []
    if "walk" in case:
        kwargs.update(animation="walk", time=0.4)
        args += ["--animation", "walk", "--time", "0.4"]
    if "target" in case:
        kwargs["targets"] = {bone: (x, y)}
        args += ["--target", f"{bone}={x},{y}"]
    pose = rig(name).pose(**kwargs)
    want = cli_pose(name, *args)
    assert isinstance(pose, ikarus.Pose)
    assert pose.name == [b["name"] for b in want["bones"]]
    for column, key in [("x", "x"), ("y", "y"), ("rotation_deg", "rotation_deg")]:
        got = getattr(pose, column)
        assert got.dtype == np.float64 and got.shape == (len(want["bones"]),)
        assert got.tolist() == [b[key] for b in want["bones"]], column  # exactly, not nearly
    assert pose.tip_x.tolist() == [b["tip"][0] for b in want["bones"]]
    assert pose.tip_y.tolist() == [b["tip"][1] for b in want["bones"]]
    assert pose.unsupported == want["unsupported"]
    assert pose.bone(want["bones"][5]["name"]) == want["bones"][5]
    # The API's answer for the same request is the same bytes' numbers.
    request = {"rig": (CHARACTERS / FILES[name]).read_text(encoding="utf-8")}
    request.update({k: v for k, v in kwargs.items() if k != "targets"})
    if "targets" in kwargs:
        request["targets"] = [{"bone": bone, "x": x, "y": y}]
    assert ikarus.call("pose", request) == want
    if "target" in case:
        i = pose.name.index(bone)
        assert abs(pose.x[i] - x) < 1e-9 and abs(pose.y[i] - y) < 1e-9


def _worst(pose: ikarus.Pose, reference: dict, skip: set) -> tuple:
    position = rotation = tip = 0.0
    for i, name in enumerate(pose.name):
        if name in skip:
            continue
        r = reference["bones"][name]
        position = max(position, float(np.hypot(pose.x[i] - r["x"], pose.y[i] - r["y"])))
        turn = (pose.rotation_deg[i] - r["rot"]) % 360.0
        rotation = max(rotation, float(min(turn, 360.0 - turn)))
        tip = max(tip, float(np.hypot(pose.tip_x[i] - r["tip"][0], pose.tip_y[i] - r["tip"][1])))
    return position, rotation, tip


def _below(pose: ikarus.Pose, top: str, c: dict) -> set:
    parents = {b["name"]: b.get("parent") for b in c["bones"]}
    out = {top}
    for name in pose.name:
        if parents[name] in out:
            out.add(name)
    return out


def test_the_raptor_walking_is_within_1e_3_of_spines_runtime() -> None:
    reference = json.loads((REFERENCE / "ref-raptor-walk-t0.4-spinecore4.2.119.json").read_text())
    worst = _worst(rig("raptor").pose(animation="walk", time=0.4), reference, set())
    assert all(w < 1e-3 for w in worst), worst


def test_spineboy_setup_is_within_1e_3_of_spines_runtime() -> None:
    # Every bone, back-shoulder's too: ikarus applies the transform constraint `shoulder` as the
    # runtime did; what it leaves out is spineboy's bounding box (it poses no bone; its clipping
    # attachment clips the art).
    reference = json.loads((REFERENCE / "ref-spineboy-setup-spinecore4.2.119.json").read_text())
    boy = rig("spineboy")
    pose = boy.pose()
    assert pose.unsupported == [
        {"kind": "bounding box attachment", "name": "head (skin default, slot head-bb)"},
    ]
    worst = _worst(pose, reference, set())
    assert all(w < 1e-3 for w in worst), worst


def test_a_character_loads_from_text_and_from_a_path() -> None:
    text = (CHARACTERS / FILES["raptor"]).read_text(encoding="utf-8")
    a, b = ikarus.Rig.from_json(text), rig("raptor")
    assert a.format == b.format == "spine"
    assert a.bones == b.bones and len(a) == 76 and "walk" in a.animations
    assert a.pose(animation="walk", time=0.4).x.tolist() == b.pose(animation="walk", time=0.4).x.tolist()
    copy = pickle.loads(pickle.dumps(b))
    assert copy.pose().y.tolist() == b.pose().y.tolist()
    dragon = ikarus.Rig.from_file(CHARACTERS / "dragonbones-mecha_1406_ske.json")
    assert dragon.format == "dragonbones" and len(dragon) == len(dragon.pose().x)
    # A rig file through the path loader is the rig of from_toml.
    puppet = ROOT / "examples" / "rigs" / "puppet.toml"
    assert ikarus.Rig.from_file(puppet).rig == ikarus.Rig.from_toml(puppet).rig


def test_refusals_are_the_clis_line() -> None:
    path = f"examples/characters/{FILES['spineboy']}"
    boy = ikarus.Rig.from_file(ROOT / path)
    label = f"rig file {ROOT / path}"
    cases = [
        ({"animation": "wlk"}, ["--animation", "wlk"]),
        ({"targets": {"toe": (1.0, 2.0)}}, ["--target", "toe=1,2"]),
    ]
    for kwargs, args in cases:
        with pytest.raises(ValueError) as e:
            boy.pose(**kwargs)
        # stderr: the reader's warning (the transform constraints left inactive), then the refusal.
        result = run_cli("pose", "--rig", path, *args, check=False)
        assert result.returncode == 2
        line = result.stderr.strip().splitlines()[-1].removeprefix("ikarus: ")
        assert str(e.value) == line.replace(f"rig file {path}", label)
    with pytest.raises(ValueError, match=r"^rig file .*: time: only with an animation$"):
        boy.pose(time=1.0)
    with pytest.raises(ValueError, match=r'^rig file .*: target "hip": the point must be finite, got \(inf, 0\)$'):
        boy.pose(targets={"hip": (float("inf"), 0.0)})
    # A bad file: the CLI's line, after the label.
    with pytest.raises(ValueError, match=r'^rig: .*bones'):
        ikarus.Rig.from_json('{"skeleton": {"spine": "4.2.0"}, "bones": [{"name": "a", "parent": "b"}]}')
    # A rig file's rig is not posed; a character is not solved; Rig.from_toml still names the format.
    with pytest.raises(ValueError, match=r"^Rig 'puppet': pose takes a character"):
        ikarus.Rig.shipped("puppet").pose()
    with pytest.raises(ValueError, match=r"a Spine character, which solve, animate, track and render do not take"):
        boy.solve({"front-foot": (0.0, 0.0)})
    with pytest.raises(ValueError, match=r"a Spine character \(67 bones, 7 IK constraints\), which Rig does not take"):
        ikarus.Rig.from_toml(ROOT / path)


@pytest.mark.parametrize("name", sorted(FILES))
def test_ik_ikarus_is_the_clis_bit_for_bit(name: str) -> None:
    bone, (x, y) = TARGETS[name]
    pose = rig(name).pose(animation="walk", time=0.4, targets={bone: (x, y)}, ik="ikarus")
    want = cli_pose(name, "--animation", "walk", "--time", "0.4", "--target", f"{bone}={x},{y}", "--ik", "ikarus")
    assert pose.x.tolist() == [b["x"] for b in want["bones"]]
    assert pose.rotation_deg.tolist() == [b["rotation_deg"] for b in want["bones"]]
    assert pose.ik == want["ik"] and pose.ik["solver"] == "ikarus"
    assert rig(name).pose(ik="runtime").ik is None
    with pytest.raises(ValueError, match=r'^ik = "ikarous": expected "runtime" or "ikarus"$'):
        rig(name).pose(ik="ikarous")


def test_goals_on_bones_are_the_clis_solve_bit_for_bit() -> None:
    """``rig.pose(ik="ikarus", goals=…)`` is ``ikarus solve --rig CHARACTER.json`` (issue 26)."""
    boy = rig("spineboy")
    pose = boy.pose(ik="ikarus", goals={"front-fist": {"x": 60.0, "y": 300.0, "bones": 3}}, pins=["head"])
    out = run_cli(
        "solve", "--rig", f"examples/characters/{FILES['spineboy']}", "--goal", "front-fist=60,300",
        "--bones", "front-fist=3", "--pin", "head", "--format", "json",
    ).stdout
    want = json.loads(out)
    assert pose.x.tolist() == [b["x"] for b in want["bones"]]
    assert pose.tip_y.tolist() == [b["tip"][1] for b in want["bones"]]
    assert pose.ik == want["ik"] and pose.ik["goals"][0]["error"] < 1e-6
    fist = boy.bones.index("front-fist")
    assert abs(pose.tip_x[fist] - 60.0) < 1e-6 and abs(pose.tip_y[fist] - 300.0) < 1e-6
    with pytest.raises(ValueError, match=r'^goals: only with "ik": "ikarus"'):
        boy.pose(goals={"front-fist": (1.0, 2.0)})
    with pytest.raises(ValueError, match=r"^goals\[0\]\.bones: 10: must be from 1 \(the bone alone\) to 9"):
        boy.pose(ik="ikarus", goals={"front-fist": {"x": 1.0, "y": 2.0, "bones": 10}})


@pytest.mark.parametrize("physics", [True, False])
def test_physics_and_skin_are_the_clis_bit_for_bit(physics: bool) -> None:
    # Celestial-circus swings under its physics constraints: played from 0 at 30 frames a second
    # (or left out), with its one skin named, it is `ikarus pose`'s pose to the bit.
    circus = ikarus.Rig.from_file(CHARACTERS / "spine-celestial-circus-pro.json")
    pose = circus.pose("swing", 1.0, skin="default", physics=physics, fps=30.0)
    args = ["--animation", "swing", "--time", "1", "--skin", "default", "--fps", "30"]
    args += [] if physics else ["--physics", "off"]
    out = run_cli("pose", "--rig", "examples/characters/spine-celestial-circus-pro.json", "--format", "json", *args).stdout
    want = json.loads(out)["bones"]
    assert pose.name == [b["name"] for b in want]
    assert np.array_equal(pose.x, np.array([b["x"] for b in want]))
    assert np.array_equal(pose.y, np.array([b["y"] for b in want]))
    with pytest.raises(ValueError, match="no such skin"):
        circus.pose(skin="villain")
