"""A character's picture with its art: ``ikarus.Atlas`` (an atlas and its page images, read
by the API in process) and ``Rig.picture`` (PNG bytes, ``ikarus pose --atlas``'s byte for
byte) / ``Rig.image`` (the same pixels as an H × W × 4 ``uint8`` array, straight RGBA).
The PNG is decoded here by a few lines of ``zlib`` (not by the package's own reader), so that
the array is checked against the bytes independently."""

from __future__ import annotations

import struct
import zlib

import numpy as np
import pytest

import ikarus

from conftest import ROOT, run_cli

CHARACTERS = ROOT / "examples" / "characters"
SPINEBOY = CHARACTERS / "spine-spineboy-pro.json"


def decode_png(data: bytes) -> np.ndarray:
    """An 8-bit RGBA, non-interlaced PNG's pixels (what ikarus's pictures are), by the PNG
    specification's filters."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat, size = 8, b"", (0, 0)
    while at < len(data):
        (length,) = struct.unpack(">I", data[at : at + 4])
        kind, body = data[at + 4 : at + 8], data[at + 8 : at + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 6, 0)
            size = (w, h)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    w, h = size
    raw, stride = zlib.decompress(idat), 4 * w
    out = bytearray(h * stride)
    for y in range(h):
        kind, line = raw[y * (stride + 1)], raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)]
        prev = out[(y - 1) * stride : y * stride] if y else bytes(stride)
        row = bytearray(line)
        for i in range(stride):
            a = row[i - 4] if i >= 4 else 0
            b = prev[i]
            c = prev[i - 4] if i >= 4 else 0
            if kind == 1:
                row[i] = (row[i] + a) & 255
            elif kind == 2:
                row[i] = (row[i] + b) & 255
            elif kind == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out[y * stride : (y + 1) * stride] = row
    return np.frombuffer(bytes(out), dtype=np.uint8).reshape(h, w, 4)


@pytest.fixture(scope="module")
def boy() -> ikarus.Rig:
    return ikarus.Rig.from_file(SPINEBOY)


@pytest.fixture(scope="module")
def atlas() -> ikarus.Atlas:
    return ikarus.Atlas.read(CHARACTERS / "spineboy.atlas")


def test_an_atlas_reads_its_pages(atlas: ikarus.Atlas) -> None:
    assert [(p["file"], p["image"], p["pma"]) for p in atlas.pages] == [("spineboy.png", True, False)]
    # A region is a line at the start of a line with no ":" after its page's settings: every
    # such line but the page's name.
    text = (CHARACTERS / "spineboy.atlas").read_text().splitlines()
    names = [line for line in text if line and not line[0].isspace() and ":" not in line]
    assert atlas.regions == len(names) - 1 and names[0] == "spineboy.png"
    assert atlas.id.startswith("a")
    given = ikarus.Atlas((CHARACTERS / "spineboy.atlas").read_text(), pages={"spineboy.png": (CHARACTERS / "spineboy.png").read_bytes()})
    assert given.id == atlas.id, "the same atlas is kept under the same id"


def test_the_setup_pose_array_has_the_arts_pixels(boy: ikarus.Rig, atlas: ikarus.Atlas) -> None:
    png = boy.picture(atlas, art_only=True, width=120, height=160)
    image = boy.image(atlas, art_only=True, width=120, height=160)
    assert image.shape == (160, 120, 4) and image.dtype == np.uint8
    assert np.array_equal(image, decode_png(png)), "the array is the PNG's pixels"
    # The art alone: a transparent background around spineboy, opaque in his middle, in the
    # page's colours (the red of his suit, the teal of his hair among them).
    alpha = image[:, :, 3]
    assert alpha[0, 0] == 0 and alpha[-1, -1] == 0
    opaque = image[alpha == 255][:, :3].astype(int)
    assert len(opaque) > 120 * 160 // 6
    page = boy.image(atlas, width=120, height=160)
    assert not np.array_equal(page, image), "under the bones the picture differs"
    reds = np.sum((opaque[:, 0] > 150) & (opaque[:, 1] < 80) & (opaque[:, 2] < 80))
    assert reds > 50, reds


def test_the_picture_is_the_command_lines(boy: ikarus.Rig, atlas: ikarus.Atlas, tmp_path) -> None:
    out = tmp_path / "walk.png"
    run_cli(
        "pose", "--rig", str(SPINEBOY), "--animation", "walk", "--time", "0.4", "--physics", "off",
        "--target", "front-leg-target=60,20", "--atlas", str(CHARACTERS / "spineboy.atlas"),
        "--art-only", "--width", "200", "--height", "150", "--out", str(out),
    )
    target = {"front-leg-target": (60, 20)}
    mine = boy.picture(atlas, "walk", 0.4, target, physics=False, art_only=True, width=200, height=150)
    assert mine == out.read_bytes()


def test_an_atlas_the_api_let_go_is_sent_again(boy: ikarus.Rig, atlas: ikarus.Atlas) -> None:
    kept = boy.picture(atlas, art_only=True, width=64, height=64)
    atlas._id = "a0000000000000000"
    assert boy.picture(atlas, art_only=True, width=64, height=64) == kept
    assert atlas.id != "a0000000000000000"


def test_errors_are_one_line(boy: ikarus.Rig, atlas: ikarus.Atlas, tmp_path) -> None:
    def refused(call, *start: str) -> str:
        with pytest.raises(ValueError) as e:
            call()
        message = str(e.value)
        assert "\n" not in message, message
        assert any(message.startswith(s) for s in start), message
        return message

    raptor = ikarus.Atlas.read(CHARACTERS / "raptor.atlas")
    m = refused(lambda: boy.picture(raptor), "atlas: the atlas has no region")
    assert "slot" in m
    refused(lambda: boy.picture(art_only=True), "art_only: draws a character's art")
    refused(lambda: boy.image(atlas, skin="gold"), 'skin "gold": no such skin')
    refused(lambda: boy.picture(atlas, width=4), "width")
    refused(lambda: ikarus.Atlas.read(tmp_path / "none.atlas"), f"atlas file {tmp_path / 'none.atlas'}: cannot read")
    lonely = tmp_path / "spineboy.atlas"
    lonely.write_text((CHARACTERS / "spineboy.atlas").read_text())
    refused(lambda: ikarus.Atlas.read(lonely), f"atlas file {lonely}: page 0 'spineboy.png': no such image in {tmp_path}")
    refused(lambda: ikarus.Atlas("spineboy.png\nsize: 2,2\nhead\nbounds: x\n"), "atlas: ", "atlas file")
    refused(lambda: ikarus.Atlas((CHARACTERS / "spineboy.atlas").read_text()), "atlas: no image for page 'spineboy.png'")
    refused(lambda: ikarus.Atlas((CHARACTERS / "spineboy.atlas").read_text(), pages={"spineboy.png": b"GIF89a"}), 'pages."spineboy.png": not a PNG image')
    refused(lambda: ikarus._ikarus._png_rgba(b"nope", "picture"), "picture: not a PNG image")
