"""A character file (Spine, DragonBones JSON; Spine's binary ``.skel``) as a :class:`~ikarus.Rig`: what a rig has when it
holds a character (its reader, ``pose``, ``picture`` and ``image`` (with its art),
``character_motion``, ``export_spine``, ``format``,
``animations``, pickling), mixed into
``Rig``, whose rig-file methods ask :meth:`_CharacterRig._rig_file` for the rig file and so
refuse a character in one line."""

from __future__ import annotations

import json
import os
import typing

import numpy as np

from . import _ikarus
from ._atlas import Atlas
from ._results import CharacterMotion, Pose

if typing.TYPE_CHECKING:
    from typing import Any, Mapping, Optional, Sequence, Tuple, TypeVar, Union

    from ._types import EaseName

    C = TypeVar("C", bound="_CharacterRig")


def _rebuild_character(cls: "type[C]", text: str, name: str) -> "C":
    rig = cls.from_json(text)
    rig.rig = {"name": name}
    return rig


class _CharacterRig:
    rig: Any
    _character: Optional[_ikarus._Character] = None
    _text: Optional[str] = None

    @classmethod
    def from_json(cls: "type[C]", text: "Union[str, bytes]", *, label: str = "rig") -> "C":
        """A character from its file's text (Spine 4.0–4.2 or 3.8, DragonBones 5.x JSON, told
        by the content), or from its file's ``bytes``: a JSON file's, or a Spine 4.2 binary
        export's (``.skel``), decoded into the JSON text Spine's JSON export of it has, as
        ``ikarus pose --rig FILE.skel`` reads it; a bad one raises ``ValueError`` with the CLI's
        line, after ``label`` (``rig: bones[3] ("foot").parent = "hip": no bone of that name``)."""
        if isinstance(text, (bytes, bytearray, memoryview)):
            text = _ikarus._character_text(bytes(text), label)
        rig = cls.__new__(cls)
        rig._character = _ikarus._Character(text, label)
        rig._text = text
        rig.rig = {"name": os.path.splitext(os.path.basename(label))[0] if label != "rig" else "character"}
        return rig

    def __reduce__(self) -> Any:
        # Picklable: a character is rebuilt from its file's text.
        if self._character is None:
            return (type(self), (self.rig,))
        return (_rebuild_character, (type(self), self._text, self.rig["name"]))

    @property
    def format(self) -> str:
        """``"rig"`` for a rig file's rig; ``"spine"`` or ``"dragonbones"`` for a character."""
        return "rig" if self._character is None else self._character.format

    @property
    def animations(self) -> list:
        """A character's animations' names (a rig file has none)."""
        return [] if self._character is None else self._character.animations

    def pose(
        self,
        animation: Optional[str] = None,
        time: Optional[float] = None,
        targets: Optional[Mapping[str, Tuple[float, float]]] = None,
        *,
        ik: str = "runtime",
        ik_file: Optional[str] = None,
        goals: Optional[Mapping[str, Any]] = None,
        pins: Sequence[str] = (),
        skin: Optional[str] = None,
        physics: bool = True,
        fps: float = 60.0,
    ) -> Pose:
        """A character posed as its runtime does (``ikarus pose``, ``POST /api/pose``, by the
        same code): the setup pose, then ``animation`` at ``time`` seconds, then each bone of
        ``targets`` (``{"bone": (x, y)}``, in order) with its world origin put at (x, y), then
        the IK constraints in their order — by the runtime's rules (``ik="runtime"``) or all
        together by ikarus's rig solver (``ik="ikarus"``, ``ikarus pose --ik ikarus``, with an
        IK file's text ``ik_file``; the answer's ``ik`` then says what the solve did). With
        ``ik="ikarus"``, ``goals`` puts bones' tips on points as ``ikarus solve --rig
        CHARACTER.json`` does: ``{bone: (x, y[, angle_deg]) or {"x", "y", "bones", "weight",
        "priority", "bend", "softness", "angle_deg"}}``, ``bones`` how many bones the goal
        turns (2 by default, the bone and its parent); ``pins`` names bones held where they
        start. ``skin`` names the skin whose skin-only bones and constraints take part (default:
        the file's ``default``; inactive bones are left at zeros, as Spine's runtime leaves them);
        a character with physics constraints is played from 0 at ``fps`` frames a second up to
        ``time`` as a game shows it, unless ``physics=False`` leaves them out (``ikarus pose
        --skin``, ``--physics``, ``--fps``). Returns a :class:`Pose` (NumPy columns, the numbers of ``ikarus pose --format
        json`` bit for bit); a bad name or value raises ``ValueError`` with the CLI's line."""
        if self._character is None:
            raise ValueError(
                f"Rig {self.rig.get('name', 'rig')!r}: pose takes a character (Spine or DragonBones JSON, "
                "Rig.from_json or Rig.from_file); a rig file's rig is posed by solve"
            )
        pairs = []
        for bone, point in (targets or {}).items():
            x, y = point
            pairs.append((bone, (float(x), float(y))))
        asked: dict = {"ik": ik, "ik_file": ik_file, "goals": self._goal_list(goals or {}), "pins": list(pins)}
        text = json.dumps({k: v for k, v in asked.items() if v is not None}, allow_nan=False)
        answer = self._character.pose(
            animation, None if time is None else float(time), pairs, text, (skin, float(fps) if physics else None)
        )
        _refuse_non_finite(answer)
        if answer["ik"] is not None:
            answer["ik"] = json.loads(answer["ik"])
        return Pose(**answer)

    def picture(
        self,
        atlas: Optional[Atlas] = None,
        animation: Optional[str] = None,
        time: Optional[float] = None,
        targets: Optional[Mapping[str, Tuple[float, float]]] = None,
        *,
        skin: Optional[str] = None,
        art_only: bool = False,
        physics: bool = True,
        fps: float = 60.0,
        width: int = 800,
        height: int = 800,
    ) -> bytes:
        """A picture of the character posed as :meth:`pose` poses it, as PNG bytes (straight
        alpha): its bones and targets, with ``atlas`` (an :class:`Atlas`) its art under them
        (slot attachments, colours, draw order and deforms keyed by ``animation`` at ``time``),
        with ``art_only=True`` the art alone on a transparent background, the box of its
        vertices filling 90 % of ``width`` × ``height``, centred (as Spine's renderer fits a
        skeleton). With ``art_only``, the bytes of ``ikarus pose --atlas FILE.atlas --art-only
        --out x.png``; with the bones, the same picture without the command line's caption
        (``POST /api/render`` figure ``pose``, by the same code). A bad name or value raises
        ``ValueError`` with the API's line naming it (``atlas: the atlas has no region …``)."""
        if self._character is None:
            raise ValueError(
                f"Rig {self.rig.get('name', 'rig')!r}: picture takes a character (Spine or DragonBones JSON); "
                "a rig file's rig is drawn by render"
            )
        request: dict = {
            "figure": "pose",
            "format": "png",
            "rig": self._text,
            "animation": animation,
            "time": None if time is None else float(time),
            "targets": [{"bone": b, "x": float(p[0]), "y": float(p[1])} for b, p in (targets or {}).items()],
            "skin": skin,
            "physics": bool(physics),
            "fps": float(fps),
            "art_only": bool(art_only) or None,
            "width": int(width),
            "height": int(height),
        }

        def drawn(atlas_id: Optional[str]) -> bytes:
            asked = {**request, "atlas": atlas_id}
            body = json.dumps({k: v for k, v in asked.items() if v is not None}, allow_nan=False)
            return bytes(_ikarus._call("render", body))

        return drawn(None) if atlas is None else atlas._with(drawn)

    def image(
        self,
        atlas: Optional[Atlas] = None,
        animation: Optional[str] = None,
        time: Optional[float] = None,
        targets: Optional[Mapping[str, Tuple[float, float]]] = None,
        *,
        skin: Optional[str] = None,
        art_only: bool = False,
        physics: bool = True,
        fps: float = 60.0,
        width: int = 800,
        height: int = 800,
    ) -> np.ndarray:
        """:meth:`picture`'s pixels: a ``height`` × ``width`` × 4 ``uint8`` array, straight
        RGBA (not premultiplied), row 0 at the top (the PNG decoded)."""
        png = self.picture(
            atlas, animation, time, targets, skin=skin, art_only=art_only, physics=physics, fps=fps, width=width, height=height
        )
        w, h, rgba = _ikarus._png_rgba(png, "picture")
        return np.frombuffer(rgba, dtype=np.uint8).reshape(h, w, 4).copy()

    def character_motion(
        self,
        targets: Optional[Mapping[str, Tuple[float, float]]] = None,
        *,
        keys: Union[Mapping[str, Any], str, "os.PathLike[str]", None] = None,
        animation: Optional[str] = None,
        duration: Optional[float] = None,
        fps: Optional[float] = None,
        ease: Optional[EaseName] = None,
        k1: Optional[float] = None,
        k2: Optional[float] = None,
        ik: Optional[str] = None,
        ik_file: Optional[str] = None,
    ) -> CharacterMotion:
        """A character's motion, as ``ikarus animate --rig CHARACTER.json --format json``
        (``POST /api/animate`` with the file's text, by the same code): either ``targets``
        (``{"bone": (x, y)}``) moved there from where the setup pose has them over ``duration``
        seconds (1) at ``fps`` (30), eased by ``ease`` (``"sine"``; ``k1``, ``k2`` for
        ``"parent"``), or ``keys``, the keys file's object (or its path, ``--keys FILE``): bones
        keyed over time, over the clip ``animation`` if given. ``ik``: ``"runtime"`` (default)
        or ``"ikarus"`` (with an IK file's text ``ik_file``). Returns a
        :class:`CharacterMotion` (NumPy columns [frames, bones], the CLI's numbers bit for
        bit). A bad value, or a motion over the caps (frames, bones), raises ``ValueError``
        with the API's line naming it."""
        answer = self._motion_request(targets, keys, animation, "json", duration=duration, fps=fps, ease=ease, k1=k1, k2=k2, ik=ik, ik_file=ik_file)
        return CharacterMotion._of(json.loads(answer))

    def export_spine(
        self,
        targets: Optional[Mapping[str, Tuple[float, float]]] = None,
        *,
        keys: Union[Mapping[str, Any], str, "os.PathLike[str]", None] = None,
        animation: Optional[str] = None,
        animation_name: Optional[str] = None,
        duration: Optional[float] = None,
        fps: Optional[float] = None,
        ease: Optional[EaseName] = None,
        k1: Optional[float] = None,
        k2: Optional[float] = None,
        ik: Optional[str] = None,
        ik_file: Optional[str] = None,
    ) -> str:
        """The motion of :meth:`character_motion` exported as Spine JSON: the character's file
        with the motion added as animation ``animation_name`` (``"ikarus"``), the text of
        ``ikarus animate --rig CHARACTER.json --format spine`` byte for byte. A Spine
        character only; an export over the caps raises ``ValueError`` naming the cap."""
        answer = self._motion_request(
            targets, keys, animation, "spine", animation_name=animation_name, duration=duration, fps=fps, ease=ease, k1=k1, k2=k2, ik=ik, ik_file=ik_file
        )
        return bytes(answer).decode("utf-8")

    def _motion_request(
        self,
        targets: Optional[Mapping[str, Tuple[float, float]]],
        keys: Union[Mapping[str, Any], str, "os.PathLike[str]", None],
        animation: Optional[str],
        format: str,
        **fields: Any,
    ) -> bytes:
        """``POST /api/animate``'s answer for this character: the request's fields named as
        this method's keywords."""
        from . import _plain

        if self._character is None:
            raise ValueError(
                f"Rig {self.rig.get('name', 'rig')!r}: character_motion and export_spine take a character "
                "(Spine or DragonBones JSON); a rig file's rig moves by animate"
            )
        if isinstance(keys, (str, os.PathLike)):
            with open(os.fspath(keys), encoding="utf-8") as f:
                keys = json.load(f)
        request: dict = {
            "rig": self._text,
            "targets": [{"bone": bone, "x": point[0], "y": point[1]} for bone, point in (targets or {}).items()] or None,
            "keys": keys,
            "animation": animation,
            "format": format,
            **fields,
        }
        body = json.dumps(_plain({k: v for k, v in request.items() if v is not None}, "request"), allow_nan=False)
        return _ikarus._call("animate", body, keywords=True)

    def _goal_list(self, goals: Mapping[str, Any]) -> list:
        """Goals by bone as the API's list (the rig's reader of goals, given by ``Rig``)."""
        raise NotImplementedError

    def _rig_file(self) -> Any:
        """The rig file's fields, for the methods that take a rig file only."""
        if self._character is not None:
            kind = {"spine": "Spine", "dragonbones": "DragonBones"}[self._character.format]
            raise ValueError(
                f"Rig {self.rig['name']!r}: a {kind} character, which solve, animate, track and render do not "
                "take: they take rig files (TOML); pose poses it, pose(ik=\"ikarus\", goals=…) puts its bones' "
                "tips on goals as ikarus solve --rig does, character_motion moves it and export_spine exports that"
            )
        return self.rig


def _refuse_non_finite(answer: dict) -> None:
    """A pose whose numbers are not all finite is refused, naming the first bone and column
    (a library that answers NaN silently is worse than one that says so)."""
    for column in ("x", "y", "rotation_deg", "tip_x", "tip_y"):
        bad = np.flatnonzero(~np.isfinite(answer[column]))
        if bad.size:
            i = int(bad[0])
            value = float(answer[column][i])
            raise ValueError(f"bones[{i}] ({answer['name'][i]!r}).{column} = {value!r}: the pose is not a finite number")
