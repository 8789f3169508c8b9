"""Spine's binary export (``.skel``) read as its JSON export is: ``Rig.from_file`` of a
``.skel`` path and ``Rig.from_json`` of its ``bytes`` give the character ``ikarus pose --rig
FILE.skel`` poses, bit for bit; bytes that are not a character raise ``ValueError`` with the
CLI's one line."""

from __future__ import annotations

import json
import pickle

import numpy as np
import pytest

import ikarus

from conftest import ROOT, run_cli

CHARACTERS = ROOT / "examples" / "characters"
SKEL = CHARACTERS / "spine-spineboy-pro.skel"
JSON = CHARACTERS / "spine-spineboy-pro.json"


def cli_pose(*args: str) -> dict:
    out = run_cli("pose", "--rig", "examples/characters/spine-spineboy-pro.skel", "--format", "json", *args).stdout
    return json.loads(out)


@pytest.mark.parametrize("source", ["path", "bytes"])
def test_a_skel_poses_as_the_cli_poses_it(source: str) -> None:
    rig = ikarus.Rig.from_file(SKEL) if source == "path" else ikarus.Rig.from_json(SKEL.read_bytes())
    assert rig.format == "spine"
    assert rig.bones == ikarus.Rig.from_file(JSON).bones
    assert len(rig.bones) == 67
    assert "walk" in rig.animations
    pose = rig.pose(animation="walk", time=0.4, targets={"front-leg-target": (120.0, 40.0)})
    want = cli_pose("--animation", "walk", "--time", "0.4", "--target", "front-leg-target=120.0,40.0")
    assert pose.name == [b["name"] for b in want["bones"]]
    for column in ("x", "y", "rotation_deg"):
        assert np.array_equal(getattr(pose, column), np.array([b[column] for b in want["bones"]])), column
    # Picklable as a JSON character is: rebuilt from the decoded text.
    again = pickle.loads(pickle.dumps(rig))
    assert np.array_equal(again.pose().x, rig.pose().x)


def test_the_setup_pose_is_the_json_files_within_rounding() -> None:
    skel, text = ikarus.Rig.from_file(SKEL).pose(), ikarus.Rig.from_file(JSON).pose()
    assert np.max(np.hypot(skel.x - text.x, skel.y - text.y)) < 0.15


def test_bytes_that_are_not_a_character_raise_one_line() -> None:
    data = SKEL.read_bytes()
    with pytest.raises(ValueError) as cut:
        ikarus.Rig.from_json(data[: len(data) // 3], label="spineboy.skel")
    message = str(cut.value)
    assert message.startswith("spineboy.skel: skel: byte "), message
    assert "\n" not in message
    with pytest.raises(ValueError, match=r"^rig: cannot read: not UTF-8 text"):
        ikarus.Rig.from_json(b"\x89PNG\r\n\x1a\n\xff\xfe")
