"""The typed results of ``animate`` and ``track``, for chains and rigs alike: frozen classes
whose per-frame and per-sample values are NumPy columns. The numbers are those of
``ikarus animate|track --format json``, bit for bit; only their arrangement differs (columns
instead of a list of objects, and a rig's bones in its order instead of objects keyed by name).

For old code, ``motion["frames"]["angles_deg"]`` still reads ``motion.frames.angles_deg``: each
class maps the JSON's keys to its attributes (``"arm"`` and ``"rig"`` to ``body``)."""

from __future__ import annotations

import dataclasses
import typing

import numpy as np

if typing.TYPE_CHECKING:
    from typing import Any, Dict, List, Optional, Sequence, Tuple

    import numpy.typing as npt

    from ._types import MotionSolve, TrackSummary


class _ByKey:
    """``result[key]``: the attribute of that name (``"arm"``/``"rig"``: ``body``), as the dicts
    these classes replace were read; a key whose value is absent (None) is a ``KeyError``."""

    _ALIASES: typing.ClassVar[dict] = {}

    def __getitem__(self, key: str) -> Any:
        name = self._ALIASES.get(key, key)
        value = getattr(self, name, None) if name in self._fields() else None
        if value is None:
            raise KeyError(key)
        return value

    @classmethod
    def _fields(cls) -> List[str]:
        return [f.name for f in dataclasses.fields(cls)]  # type: ignore[arg-type]


def _points(rows: Sequence[Any], base: Optional[Sequence[float]], bones: Optional[Sequence[str]]) -> npt.NDArray[np.float64]:
    """Joint positions [k, n+1, 2]: an arm's lists as they are; a rig's tips by bone name, in
    its bones' order, after its base."""
    if bones is None:
        return np.array(rows, dtype=np.float64).reshape(len(rows), -1, 2)
    base = list(base if base is not None else (0.0, 0.0))
    return np.array([[base, *(row[b] for b in bones)] for row in rows], dtype=np.float64).reshape(len(rows), len(bones) + 1, 2)


def _extensions(rows: Sequence[Any], bones: Optional[Sequence[str]]) -> Optional[Dict[str, npt.NDArray[np.float64]]]:
    """A rig's prismatic bones' displacements as columns [k] by name, in its bones' order; None
    when the rows have none (a chain, or a rig whose joints all turn)."""
    if bones is None or not rows or rows[0] is None:
        return None
    return {b: np.array([row[b] for row in rows], dtype=np.float64) for b in bones if b in rows[0]}


def _angles(rows: Sequence[Any], bones: Optional[Sequence[str]]) -> npt.NDArray[np.float64]:
    """Angles [k, n]: an arm's lists as they are; a rig's by bone name, in its bones' order."""
    if bones is None:
        return np.array(rows, dtype=np.float64).reshape(len(rows), -1)
    return np.array([[row[b] for b in bones] for row in rows], dtype=np.float64).reshape(len(rows), len(bones))


@dataclasses.dataclass(frozen=True, eq=False)
class MotionFrames(_ByKey):
    """A motion's frames as columns: ``time`` [F] (seconds), ``angles_deg`` [F, n] (each joint
    or bone, degrees), ``joints`` [F, n+1, 2] (the base, then each link's or bone's tip) and,
    for a rig with prismatic joints, ``extensions`` (each such bone's displacement [F] by name;
    None otherwise)."""

    time: npt.NDArray[np.float64]
    angles_deg: npt.NDArray[np.float64]
    joints: npt.NDArray[np.float64]
    extensions: Optional[Dict[str, npt.NDArray[np.float64]]] = None

    def __len__(self) -> int:
        return len(self.time)


@dataclasses.dataclass(frozen=True, eq=False)
class Motion(_ByKey):
    """The motion of ``animate`` (``ikarus animate --format json``): ``body`` (the arm's or
    rig's name), ``bones`` (a rig's bone names, the columns' order; None for a chain),
    ``ease``, ``duration`` (seconds), ``solves`` (each via, then the goal: ``status``,
    ``iterations``, ``error``, and an arm's ``goal`` or a rig's ``effectors``, as the JSON has
    them) and ``frames`` (:class:`MotionFrames`)."""

    body: str
    bones: Optional[Tuple[str, ...]]
    ease: str
    duration: float
    solves: List[MotionSolve]
    frames: MotionFrames

    _ALIASES: typing.ClassVar[dict] = {"arm": "body", "rig": "body"}

    @classmethod
    def _of(cls, answer: dict, bones: Optional[Sequence[str]] = None, base: Optional[Sequence[float]] = None) -> Motion:
        rows = answer["frames"]
        frames = MotionFrames(
            time=np.array([f["time"] for f in rows], dtype=np.float64),
            angles_deg=_angles([f["angles_deg"] for f in rows], bones),
            joints=_points([f["joints"] for f in rows], base, bones),
            extensions=_extensions([f.get("extensions") for f in rows], bones),
        )
        body = answer["rig"] if bones is not None else answer["arm"]
        return cls(
            body=body,
            bones=None if bones is None else tuple(bones),
            ease=answer["ease"],
            duration=answer["duration"],
            solves=answer["solves"],
            frames=frames,
        )


@dataclasses.dataclass(frozen=True, eq=False)
class TrackSamples(_ByKey):
    """A track's samples as columns: ``goal`` [N, 2], ``angle_deg`` [N] (oriented goals' only,
    else None), ``status`` [N] (str: ``reached``, ``limited``, ``unreachable``, ``stalled``,
    ``iteration_limit``, ``off_path``), ``error`` [N], ``angles_deg`` [N, n], ``joints``
    [N, n+1, 2] (the base, then each tip) and ``step_deg`` [N] (the largest joint change from
    the sample before); for a rig with prismatic joints, ``extensions`` (each such bone's
    displacement [N] by name; None otherwise)."""

    goal: npt.NDArray[np.float64]
    angle_deg: Optional[npt.NDArray[np.float64]]
    status: npt.NDArray[np.str_]
    error: npt.NDArray[np.float64]
    angles_deg: npt.NDArray[np.float64]
    joints: npt.NDArray[np.float64]
    step_deg: npt.NDArray[np.float64]
    extensions: Optional[Dict[str, npt.NDArray[np.float64]]] = None

    def __len__(self) -> int:
        return len(self.status)


@dataclasses.dataclass(frozen=True, eq=False)
class Track(_ByKey):
    """A tracked path (``ikarus track --format json``): ``body`` (the arm's or rig's name),
    ``bones`` (a rig's bone names; None for a chain), ``effector`` (a rig's bone whose tip
    follows the path; None for a chain), ``mode`` (``"plan"`` or ``"follow"``), ``samples``
    (:class:`TrackSamples`) and ``summary`` (the JSON's, a :class:`~ikarus.TrackSummary`)."""

    body: str
    bones: Optional[Tuple[str, ...]]
    effector: Optional[str]
    mode: str
    samples: TrackSamples
    summary: TrackSummary

    _ALIASES: typing.ClassVar[dict] = {"arm": "body", "rig": "body"}

    @classmethod
    def _of(cls, answer: dict, bones: Optional[Sequence[str]] = None, base: Optional[Sequence[float]] = None) -> Track:
        rows = answer["samples"]
        oriented = [r.get("angle_deg") for r in rows]
        samples = TrackSamples(
            goal=np.array([r["goal"] for r in rows], dtype=np.float64).reshape(len(rows), 2),
            angle_deg=None
            if all(a is None for a in oriented)
            else np.array([np.nan if a is None else a for a in oriented], dtype=np.float64),
            status=np.array([r["status"] for r in rows], dtype=str),
            error=np.array([r["error"] for r in rows], dtype=np.float64),
            angles_deg=_angles([r["angles_deg"] for r in rows], bones),
            joints=_points([r["joints"] for r in rows], base, bones),
            step_deg=np.array([r["step_deg"] for r in rows], dtype=np.float64),
            extensions=_extensions([r.get("extensions") for r in rows], bones),
        )
        return cls(
            body=answer["rig"] if bones is not None else answer["arm"],
            bones=None if bones is None else tuple(bones),
            effector=answer.get("effector"),
            mode=answer["mode"],
            samples=samples,
            summary=answer["summary"],
        )


@dataclasses.dataclass(frozen=True, eq=False)
class Pose(_ByKey):
    """A character posed as its runtime does (``ikarus pose --format json``, bit for bit), one
    row per bone in the file's order: ``name`` (the bones' names), ``x``, ``y`` (world origin),
    ``rotation_deg`` (the world direction of the bone's x axis), ``tip_x``, ``tip_y`` (origin
    plus length along that axis), float64 columns [n] in the file's units, y up; and
    ``unsupported`` (the constraints left inactive, ``{"kind", "name"}``); with
    ``ik="ikarus"``, ``ik`` (the JSON's: ``solver``, ``status``, ``rounds``, ``constraints``)."""

    name: List[str]
    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    rotation_deg: npt.NDArray[np.float64]
    tip_x: npt.NDArray[np.float64]
    tip_y: npt.NDArray[np.float64]
    unsupported: List[Dict[str, str]]
    ik: Optional[Dict[str, Any]] = None

    def __len__(self) -> int:
        return len(self.name)

    def bone(self, name: str) -> Dict[str, Any]:
        """One bone's row as ``ikarus pose --format json`` has it: ``{"name", "x", "y",
        "rotation_deg", "tip": [x, y]}``."""
        i = self.name.index(name)
        return {
            "name": name,
            "x": float(self.x[i]),
            "y": float(self.y[i]),
            "rotation_deg": float(self.rotation_deg[i]),
            "tip": [float(self.tip_x[i]), float(self.tip_y[i])],
        }


def _finite_column(rows: Sequence[Any], key: str, where: str) -> npt.NDArray[np.float64]:
    """``row[key]`` of each row as float64, refusing a value that is not a finite number (JSON
    has no NaN: a non-finite answer would come back as ``null``) with a line naming it."""
    values = [row[key] for row in rows]
    column = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(column))
    if bad.size:
        i = int(bad[0])
        shown = "null" if values[i] is None else repr(values[i])
        raise ValueError(f"{where.format(i=i, name=rows[i].get('name', ''))}.{key} = {shown}: the answer is not a finite number")
    return column


@dataclasses.dataclass(frozen=True, eq=False)
class CharacterMotion(_ByKey):
    """A character's motion (``ikarus animate --rig CHARACTER.json --format json``, ``POST
    /api/animate`` with the character's text, bit for bit), as columns: ``name`` (the bones,
    the file's order), ``time`` [F] (seconds), and per frame and bone ``x``, ``y`` (world
    origin), ``rotation_deg``, ``tip_x``, ``tip_y``, float64 [F, n]; ``unsupported`` (the
    constraints left inactive, ``{"kind", "name"}``)."""

    name: List[str]
    time: npt.NDArray[np.float64]
    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    rotation_deg: npt.NDArray[np.float64]
    tip_x: npt.NDArray[np.float64]
    tip_y: npt.NDArray[np.float64]
    unsupported: List[Dict[str, Any]]

    def __len__(self) -> int:
        return len(self.time)

    def pose(self, frame: int) -> Pose:
        """Frame ``frame`` as a :class:`Pose`."""
        return Pose(
            name=list(self.name),
            x=self.x[frame].copy(),
            y=self.y[frame].copy(),
            rotation_deg=self.rotation_deg[frame].copy(),
            tip_x=self.tip_x[frame].copy(),
            tip_y=self.tip_y[frame].copy(),
            unsupported=list(self.unsupported),
        )

    @classmethod
    def _of(cls, answer: dict) -> CharacterMotion:
        frames = answer["frames"]
        names = [b["name"] for b in frames[0]["bones"]] if frames else []
        n = len(names)
        time = _finite_column(frames, "time", "frames[{i}]")
        keys = ("x", "y", "rotation_deg", "tip_x", "tip_y")
        columns = {key: np.empty((len(frames), n), dtype=np.float64) for key in keys}
        for f, frame in enumerate(frames):
            bones = frame["bones"]
            where = f"frames[{f}].bones[{{i}}] ({{name!r}})"
            for key in ("x", "y", "rotation_deg"):
                columns[key][f] = _finite_column(bones, key, where)
            tips = [{"name": b["name"], "tip_x": b["tip"][0], "tip_y": b["tip"][1]} for b in bones]
            for key in ("tip_x", "tip_y"):
                columns[key][f] = _finite_column(tips, key, where)
        return cls(name=names, time=time, unsupported=answer.get("unsupported", []), **columns)
