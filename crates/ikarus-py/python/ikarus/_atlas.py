"""A Spine texture atlas and its page images, for pictures of a character with its art
(:meth:`ikarus.Rig.picture`, :meth:`ikarus.Rig.image`): read once by the API in process
(``POST /api/atlas/parse``, the code ``ikarus serve`` answers with), kept by it under an id, and
sent again by itself if the API's store has let it go (it keeps the most recent atlases)."""

from __future__ import annotations

import base64
import json
import os
import typing

from . import _ikarus

if typing.TYPE_CHECKING:
    from typing import Any, Callable, Mapping, Optional, TypeVar

    T = TypeVar("T")


class Atlas:
    """A Spine texture atlas (``.atlas``, the text Spine's texture packer writes) with its
    pages' PNG images: ``Atlas(text, pages={"spineboy.png": png_bytes})``, or
    :meth:`Atlas.read` of an atlas file with its pages beside it. A bad atlas line, a page
    that is not a PNG image or a page not given raises ``ValueError`` in one line naming it.

    ``pages`` lists the atlas's pages as the API read them: ``{"file", "width", "height",
    "pma", "image"}`` each; ``regions`` counts its regions."""

    def __init__(self, text: str, pages: Optional[Mapping[str, bytes]] = None) -> None:
        self._text = text
        self._images = {str(name): bytes(png) for name, png in (pages or {}).items()}
        self._id = ""
        answer = self._send()
        missing = [p["file"] for p in answer["pages"] if not p["image"]]
        if missing:
            raise ValueError(
                f"atlas: no image for page {missing[0]!r}: give it in pages={{name: PNG bytes}} "
                "(a picture with the art needs every page's image)"
            )
        self.pages: list = answer["pages"]
        self.regions: int = answer["regions"]

    @classmethod
    def read(cls, path: "os.PathLike[str] | str") -> "Atlas":
        """The atlas file at ``path`` with its pages' images read from its folder, the files
        the atlas names (as ``ikarus pose --atlas FILE`` reads them); a page not there raises
        ``ValueError`` naming it and the folder."""
        path = os.fspath(path)
        label = f"atlas file {path}"
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise ValueError(f"{label}: cannot read: {e.strerror}") from None
        names = _page_names(text, label)
        folder = os.path.dirname(path) or "."
        pages = {}
        for i, name in enumerate(names):
            at = os.path.join(folder, name)
            if not os.path.isfile(at):
                raise ValueError(f"{label}: page {i} {name!r}: no such image in {folder}")
            with open(at, "rb") as f:
                pages[name] = f.read()
        return cls(text, pages)

    @property
    def id(self) -> str:
        """The id the API answered for this atlas (``"atlas"`` of ``/api/render``)."""
        return self._id

    def _send(self) -> Any:
        """``POST /api/atlas/parse`` with the text and the images: its answer; the id kept."""
        request: dict = {"atlas": self._text}
        if self._images:
            request["pages"] = {name: base64.b64encode(png).decode("ascii") for name, png in self._images.items()}
        body = json.dumps(request)
        answer = json.loads(_ikarus._call("atlas/parse", body))
        self._id = answer["id"]
        return answer

    def _with(self, call: "Callable[[str], T]") -> "T":
        """``call(id)``, sending the atlas again once if the API no longer keeps it."""
        try:
            return call(self._id)
        except ValueError as e:
            if not str(e).startswith("atlas: no atlas "):
                raise
        self._send()
        return call(self._id)

    def __repr__(self) -> str:
        files = ", ".join(p["file"] for p in self.pages)
        return f"Atlas(pages=[{files}], regions={self.regions})"


def _page_names(text: str, label: str) -> list:
    """The page image names of an atlas's text, as the API reads them (its answer's
    ``pages``)."""
    try:
        answer = json.loads(_ikarus._call("atlas/parse", json.dumps({"atlas": text})))
    except ValueError as e:
        message = str(e)
        raise ValueError(f"{label}: {message[len('atlas: '):] if message.startswith('atlas: ') else message}") from None
    return [p["file"] for p in answer["pages"]]
