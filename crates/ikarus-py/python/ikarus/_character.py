"""A character file (Spine, DragonBones JSON) as a :class:`~ikarus.Rig`: what a rig has when it
holds a character (its reader, ``pose``, ``format``, ``animations``, pickling), mixed into
``Rig``, whose rig-file methods ask :meth:`_CharacterRig._rig_file` for the rig file and so
refuse a character in one line."""

from __future__ import annotations

import json
import os
import typing

from . import _ikarus
from ._results import Pose

if typing.TYPE_CHECKING:
    from typing import Any, Mapping, Optional, Sequence, Tuple, TypeVar

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
    def from_json(cls: "type[C]", text: str, *, label: str = "rig") -> "C":
        """A character from its file's text (Spine 4.0–4.2 or 3.8, DragonBones 5.x JSON, told
        by the content); a bad one raises ``ValueError`` with the CLI's line, after ``label``
        (``rig: bones[3] ("foot").parent = "hip": no bone of that name``)."""
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
        start. Returns a :class:`Pose` (NumPy columns, the numbers of ``ikarus pose --format
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
        answer = self._character.pose(animation, None if time is None else float(time), pairs, text)
        if answer["ik"] is not None:
            answer["ik"] = json.loads(answer["ik"])
        return Pose(**answer)

    def _goal_list(self, goals: Mapping[str, Any]) -> list:
        """Goals by bone as the API's list (the rig's reader of goals, given by ``Rig``)."""
        raise NotImplementedError

    def _rig_file(self) -> Any:
        """The rig file's fields, for the methods that take a rig file only."""
        if self._character is not None:
            kind = {"spine": "Spine", "dragonbones": "DragonBones"}[self._character.format]
            raise ValueError(
                f"Rig {self.rig['name']!r}: a {kind} character, which solve, animate, track and render do not "
                "take: they take rig files (TOML); pose poses it, and pose(ik=\"ikarus\", goals=…) puts its bones' "
                "tips on goals as ikarus solve --rig does"
            )
        return self.rig
