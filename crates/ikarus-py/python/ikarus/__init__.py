"""ikarus: inverse kinematics for planar chains and skeletons, from Python.

The computing is the Rust library's; this edge speaks degrees, as the command line does, and
its results equal ``ikarus solve/animate/track/workspace/reach --format json`` for the same
inputs, bit for bit::

    >>> import ikarus
    >>> arm = ikarus.Chain()                      # the seed arm: lengths 3, 2, 1
    >>> out = arm.solve((2.0, 3.0))
    >>> out.status, out.iterations
    ('reached', 7)
    >>> arm.solve_batch(goals)["status"]          # goals: float64 [N, 2] or [N, 3]

A :class:`Chain` and a :class:`Rig` have the same methods with the same typed results:
``solve`` gives an :class:`Outcome`, ``animate`` a :class:`Motion`, ``track`` a :class:`Track`
(frozen classes with NumPy columns), ``render`` a picture's bytes. Options are keyword-only,
with the CLI's names (``method="dls"``, ``lambda_=0.2``, ``limits=True``, ``restarts=0``, …;
typed as :class:`SolveOptions`); a bad name or value raises ``ValueError`` with the CLI's
one-line message.
"""

from __future__ import annotations

# Helpers under private names, so that the package's namespace (``dir(ikarus)``, completion in
# an editor) holds only its API, ``__all__``. The annotations are strings (the future import
# above), read by type checkers, which see the typing names below.
import json as _json
import math as _math
import os as _os
import typing as _typing

import numpy as _np

from . import _ikarus
from ._ikarus import Effector, Outcome, ease
from ._atlas import Atlas
from ._character import _CharacterRig
from ._results import CharacterMotion, Motion, MotionFrames, Pose, Track, TrackSamples
from ._types import (
    LimitMode,
    Method,
    MotionOptions,
    MotionSolve,
    RigGoal,
    SolveOptions,
    TrackOptions,
    TrackSolveOptions,
    TrackSummary,
)

if _typing.TYPE_CHECKING:
    import os

    from typing import Any, Iterable, Mapping, Optional, Sequence, Tuple, Union

    import numpy.typing as npt
    from typing_extensions import Unpack

    from ._ikarus import Goal
    from ._types import Figure, PictureFormat

__all__ = [
    "Chain",
    "Rig",
    "Outcome",
    "Effector",
    "Motion",
    "MotionFrames",
    "Track",
    "TrackSamples",
    "Pose",
    "CharacterMotion",
    "Atlas",
    "SolveOptions",
    "TrackSolveOptions",
    "MotionOptions",
    "TrackOptions",
    "RigGoal",
    "MotionSolve",
    "TrackSummary",
    "Method",
    "LimitMode",
    "ease",
    "plot",
    "call",
    "__version__",
]
__version__ = _ikarus.__version__


def _plain(value: Any, field: str) -> Any:
    """A request's value as JSON data: NumPy arrays and scalars as lists and numbers; a
    non-finite number (which JSON cannot carry) refused here, naming the field."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, _np.ndarray):
        return _plain(value.tolist(), field)
    if isinstance(value, (int, _np.integer)) and not isinstance(value, _np.bool_):
        return int(value)
    if isinstance(value, _np.bool_):
        return bool(value)
    if isinstance(value, (float, _np.floating)):
        x = float(value)
        if not _math.isfinite(x):
            raise ValueError(f"{field} = {x!r}: must be a finite number".replace("nan", "NaN"))
        return x
    if isinstance(value, dict):
        return {k: _plain(v, f"{field}.{k}") for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{field}[{i}]") for i, v in enumerate(value)]
    raise TypeError(f"{field}: cannot use a {type(value).__name__} here")


def _options(options: Mapping[str, object]) -> dict:
    """Keyword options under the CLI's names (``lambda_`` is ``lambda``); None = the default."""
    out = {}
    for key, value in options.items():
        if value is None:
            continue
        name = "lambda" if key == "lambda_" else key
        out[name] = _plain(value, name)
    return out


def _goal(goal: Any, field: str = "goal") -> dict:
    values = list(goal) if not isinstance(goal, dict) else None
    if values is None:
        return _plain(goal, field)
    if len(values) not in (2, 3):
        raise ValueError(f"{field}: expected (x, y) or (x, y, angle_deg), got {len(values)} values")
    out = {"x": _plain(values[0], f"{field}.x"), "y": _plain(values[1], f"{field}.y")}
    if len(values) == 3:
        out["angle_deg"] = _plain(values[2], f"{field}.angle_deg")
    return out


def call(endpoint: str, request: Optional[dict] = None) -> Any:
    """Asks the API without HTTP: what ``ikarus serve`` answers for ``POST /api/<endpoint>``
    with this request (a dict), parsed from JSON (or the bytes of a picture). A refused request
    raises ``ValueError`` with the server's one-line ``{"error": …}`` message."""
    body = _json.dumps(_plain(request or {}, "request"), allow_nan=False)
    reply = _ikarus._call(endpoint, body)
    try:
        return _json.loads(reply)
    except (UnicodeDecodeError, _json.JSONDecodeError):
        return reply


def _rebuild_chain(cls: type, toml: Optional[str]) -> "Chain":
    return cls() if toml is None else cls(toml=toml)


def _track_options(options: Mapping[str, object]) -> Optional[dict]:
    """``track``'s solver options: ``solver_max_step_deg`` is the solver's ``max_step_deg``."""
    solver_options = _options(options)
    if "solver_max_step_deg" in solver_options:
        solver_options["max_step_deg"] = solver_options.pop("solver_max_step_deg")
    return solver_options or None


# The keywords of ``animate`` and ``track`` that are the API's request fields of the same names
# (the rest are the ease's and the solver's options).
_MOTION_FIELDS = ("frames", "duration", "fps", "interpolation", "from_solve", "start_deg")
_TRACK_FIELDS = ("line", "circle", "figure8", "samples", "mode", "max_step_deg", "bound_first", "start_deg")


class _Body:
    """What a chain and a rig share: their requests to the API (``animate``, ``track``,
    ``render``) written once, each body adding its own key (``arm`` or ``rig``) and goals."""

    def _body(self) -> dict:
        """The request's body: ``{"arm": …}`` or ``{"rig": …}``."""
        raise NotImplementedError

    def _columns(self) -> Tuple[Optional[Sequence[str]], Optional[Sequence[float]]]:
        """A rig's bone names and base (how its answers' objects become columns); None for a chain."""
        return None, None

    def _request(self, endpoint: str, request: dict) -> Any:
        """The API's answer to this body's request; a refused option is named as its keyword."""
        request = {**self._body(), **{k: v for k, v in request.items() if v is not None}}
        body = _json.dumps(_plain(request, "request"), allow_nan=False)
        return _json.loads(_ikarus._call(endpoint, body, keywords=True))

    def _animate(self, request: dict, options: Mapping[str, object]) -> Motion:
        """A motion: ``request`` (the body's goals) with ``animate``'s keywords, the motion's
        settings (``MotionOptions``) and then the solver's options."""
        keywords = dict(options)
        fields = {k: keywords.pop(k, None) for k in _MOTION_FIELDS}
        easing = {k: keywords.pop(k, None) for k in ("ease", "k1", "k2")}
        easing["kind"] = easing.pop("ease")
        request = {
            **request,
            **fields,
            "ease": {k: v for k, v in easing.items() if v is not None} or None,
            "options": _options(keywords) or None,
        }
        bones, base = self._columns()
        return Motion._of(self._request("animate", request), bones, base)

    def _track(self, request: dict, options: Mapping[str, object]) -> Track:
        """A tracked path: ``request`` (the body's part and ``path``) with ``track``'s keywords,
        the path's settings (``TrackOptions``) and then the solver's options."""
        keywords = dict(options)
        fields = {k: keywords.pop(k, None) for k in _TRACK_FIELDS}
        path = request.get("path")
        request = {
            **request,
            **fields,
            "path": None if path is None else _plain(_np.asarray(path, dtype=float), "path"),
            "options": _track_options(keywords),
        }
        bones, base = self._columns()
        return Track._of(self._request("track", request), bones, base)

    def _render(self, request: dict) -> bytes:
        request = {**self._body(), **{k: v for k, v in request.items() if v is not None}}
        body = _json.dumps(_plain(request, "request"), allow_nan=False)
        return bytes(_ikarus._call("render", body))


class Chain(_Body, _ikarus.Chain):
    __doc__ = _ikarus.Chain.__doc__

    @classmethod
    def from_toml(cls, path: "os.PathLike[str] | str") -> "Chain":
        """Reads an arm file (TOML, the format of ``ikarus solve --arm FILE``). A missing file
        raises ``FileNotFoundError``; a bad one ``ValueError`` with the CLI's line
        (``arm file PATH: links[1].length = -2: must be greater than 0``)."""
        path = _os.fspath(path)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        return cls(toml=text, label=f"arm file {path}")

    @classmethod
    def seed(cls) -> "Chain":
        """The built-in seed arm (the CLI's arm without ``--arm``)."""
        return cls()

    def __reduce__(self):
        # Picklable (for Dask, multiprocessing): rebuilt from the arm file's text.
        return (_rebuild_chain, (type(self), self._toml))

    def _arm(self) -> dict:
        return _json.loads(self._arm_json)

    def _body(self) -> dict:
        return {"arm": self._arm()}

    def animate(
        self,
        goal: Goal,
        via: Optional[Iterable[Sequence[float]]] = None,
        **options: Unpack[MotionOptions],
    ) -> Motion:
        """The motion of ``ikarus animate`` (``POST /api/animate``): solve for ``goal`` through
        each ``via`` point, then move along a smooth spline, eased.

        Returns a :class:`Motion`: ``body`` (the arm's name), ``ease``, ``duration``,
        ``solves``, and ``frames`` as columns: ``time`` [F], ``angles_deg`` [F, n], ``joints``
        [F, n+1, 2] (NumPy arrays, the numbers of ``ikarus animate --format json``, bit for
        bit). Solver options are keywords, as for :meth:`solve`."""
        request = {
            "goal": _goal(goal),
            "via": None if via is None else [list(_plain(p, f"via[{i}]")) for i, p in enumerate(via)],
        }
        return self._animate(request, options)

    def track(
        self,
        path: Optional[npt.ArrayLike] = None,
        **options: Unpack[TrackOptions],
    ) -> Track:
        """The tip follows a path without flips, as ``ikarus track`` (``POST /api/track``):
        ``path`` (an array [N, 2] of x, y) or one of ``line=(x0, y0, x1,
        y1)``, ``circle=(cx, cy, r)``, ``figure8=(cx, cy, a)`` with ``samples``; ``mode`` is
        ``"plan"`` (default) or ``"follow"``; ``max_step_deg`` the flip bound (10°).

        Returns a :class:`Track`: ``body``, ``mode``, ``summary`` (the CLI's, a dict) and
        ``samples`` as columns: ``goal`` [N, 2], ``status`` [N] (str), ``error`` [N],
        ``angles_deg`` [N, n], ``joints`` [N, n+1, 2], ``step_deg`` [N]. Solver options are keywords, as for :meth:`solve`; the solver's
        per-iteration step cap, which ``max_step_deg`` names elsewhere, is
        ``solver_max_step_deg`` here (as the CLI's ``ikarus track --solver-max-step-deg``)."""
        return self._track({"path": path}, options)

    def workspace(
        self,
        *,
        limits: Optional[bool] = None,
        grid: Optional[bool] = None,
        resolution: Optional[int] = None,
        samples: Optional[int] = None,
        seed: Optional[int] = None,
    ) -> dict:
        """The region the tip reaches, as ``ikarus workspace --format json``
        (``POST /api/workspace``): ``area`` (exact), ``inner_radius``, ``outer_radius``,
        ``annulus_area``, ``boundary`` (loops of ``{"line": …}`` / ``{"arc": …}`` segments,
        degrees) and ``curves``. ``limits`` enforces the joint ranges (default: the arm file's
        ``[solver] limits``, else off). With ``grid=True`` (or ``resolution``, ``samples``,
        ``seed``) the sampled grid instead; its rows are then also given as ``cells``, a bool
        array [resolution, resolution] (row 0 at the bottom). A chain's alone: the exact
        region is built for chains (``POST /api/workspace`` takes an ``arm``)."""
        request = {"limits": limits, "grid": grid, "resolution": resolution, "samples": samples, "seed": seed}
        answer = self._request("workspace", request)
        if "grid" in answer:
            answer["cells"] = _np.array([[c == "1" for c in row] for row in answer["grid"]], dtype=bool)
        return answer

    def reach(
        self,
        points: npt.ArrayLike,
        *,
        limits: Optional[bool] = None,
        tolerance: Optional[float] = None,
    ) -> dict:
        """Can the tip get there? As ``ikarus reach --format json`` (``POST /api/reach``), read
        off the exact region. One point ``(x, y)`` gives ``{"reachable", "distance",
        "nearest"}``; an array [N, 2] gives columns ``reachable`` bool [N], ``distance`` [N]
        and ``nearest`` [N, 2]. A chain's alone, as :meth:`workspace`."""
        arr = _np.asarray(points, dtype=float)
        if arr.ndim == 1:
            if arr.shape != (2,):
                raise ValueError(f"points: expected (x, y) or an array of shape (N, 2), got {arr.shape}")
            request = {"point": _plain(arr, "point"), "limits": limits, "tolerance": tolerance}
            return self._request("reach", request)
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise ValueError(f"points: expected (x, y) or an array of shape (N, 2), got {arr.shape}")
        request = {"points": _plain(arr, "points"), "limits": limits, "tolerance": tolerance}
        answer = self._request("reach", request)
        return {
            "reachable": _np.array([v["reachable"] for v in answer], dtype=bool),
            "distance": _np.array([v["distance"] for v in answer], dtype=_np.float64),
            "nearest": _np.array([v["nearest"] for v in answer], dtype=_np.float64).reshape(len(answer), 2),
        }

    def render(
        self,
        figure: Figure = "arm",
        format: PictureFormat = "svg",
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        **fields: Any,
    ) -> bytes:
        """A picture by ikarus's own renderer (``POST /api/render``, ``ikarus render``):
        ``figure`` is ``"arm"`` (with ``pose_deg``, ``goal``, ``workspace``), ``"motion"`` (the
        fields of :meth:`animate`), ``"workspace"`` or ``"ease"``; ``format`` ``"svg"``,
        ``"png"`` or ``"gif"``. Returns the file's bytes."""
        request = {"figure": figure, "format": format, "width": width, "height": height, **fields}
        if "goal" in request and request["goal"] is not None and not isinstance(request["goal"], dict):
            request["goal"] = _goal(request["goal"])
        if figure == "ease":
            body = _json.dumps(_plain({k: v for k, v in request.items() if v is not None}, "request"), allow_nan=False)
            return bytes(_ikarus._call("render", body))
        return self._render(request)

    def plot(self, pose: Any = None, goal: Any = None, ax: Any = None, **kwargs: Any) -> Any:
        """Draws the chain with matplotlib: see :func:`ikarus.plot`."""
        from ._plot import plot as _plot

        return _plot(self, pose=pose, goal=goal, ax=ax, **kwargs)


def _rig_goals(goals: Mapping[str, Union[Goal, RigGoal]], field: str = "goals") -> list:
    """A rig's goals, ``{bone: (x, y[, angle_deg]) or {"x", "y", …}}``, as the API's list."""
    listed: list = []
    for bone, goal in goals.items():
        g = dict(goal) if isinstance(goal, dict) else _goal(goal, f"{field}[{len(listed)}]")
        listed.append({"bone": bone, **g})
    return listed


class Rig(_CharacterRig, _Body):
    """A skeleton (a *rig*): a tree of named bones, solved for goals on any bones' tips with
    others pinned, through the API (``POST /api/solve`` with ``rig``), as
    ``ikarus solve --rig FILE``.

    ``Rig(rig)`` takes a rig file's fields as a dict (``{"name", "base", "bones": [{"name",
    "parent", "length", "angle_deg", "limits_deg"}], "solver"}``); ``Rig.from_toml(path)``
    reads a rig file; ``Rig.shipped("puppet")`` (or ``"hand"``) is one of
    ``examples/rigs/``. It has a chain's methods with the same results (``solve`` an
    :class:`Outcome`, ``animate`` a :class:`Motion`, ``track`` a :class:`Track`, ``render``),
    goals by bone name; not ``workspace``, ``reach`` and ``solve_batch``, which the backend
    computes for chains alone (the exact region is a chain's; ``POST /api/solve/batch`` takes
    an arm).

    A character (Spine or DragonBones JSON, or Spine's binary ``.skel``) is a rig too:
    ``Rig.from_json(text)`` reads one from its text (or a file's ``bytes``, a ``.skel``'s
    included), ``Rig.from_file(path)`` from a file (a rig file or a character, told by the
    content, as ``--rig FILE``); its :meth:`pose` poses it as its runtime does
    (``ikarus pose``). Its other methods take rig files only, and say so."""

    def __init__(self, rig: dict) -> None:
        self.rig = _plain(rig, "rig")

    @classmethod
    def from_toml(cls, path: "os.PathLike[str] | str") -> "Rig":
        """Reads a rig file (TOML, ``ikarus solve --rig FILE``); a bad one raises
        ``ValueError`` with the CLI's line."""
        path = _os.fspath(path)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        answer = _json.loads(_ikarus._call("rig/parse", text))
        if "problem" in answer:
            problem = answer["problem"]
            if problem.startswith("rig file: "):
                problem = f"rig file {path}: " + problem[len("rig file: "):]
            raise ValueError(problem)
        if "character" in answer:
            c = answer["character"]
            kind = {"spine": "Spine", "dragonbones": "DragonBones"}.get(c["format"], c["format"])
            raise ValueError(
                f"rig file {path}: a {kind} character ({len(c['bones'])} bones, {len(c['ik'])} IK constraints), "
                "which Rig does not take: it takes rig files (TOML); `ikarus pose --rig FILE` poses it"
            )
        return cls(answer["rig"])

    @classmethod
    def from_file(cls, path: "os.PathLike[str] | str") -> "Rig":
        """Reads a rig file (TOML, as :meth:`from_toml`) or a character file (JSON, or Spine's
        binary ``.skel``, as :meth:`from_json`), told by the content as ``--rig FILE`` tells
        it; messages start ``rig file PATH:`` as the CLI's."""
        path = _os.fspath(path)
        with open(path, "rb") as f:
            data = f.read()
        label = f"rig file {path}"
        text = _ikarus._character_text(data, label)
        if text.lstrip("\ufeff").lstrip().startswith("{"):
            return cls.from_json(text, label=label)
        return cls.from_toml(path)

    @classmethod
    def shipped(cls, name: str) -> "Rig":
        """A shipped rig (``GET /api/rigs``): ``"puppet"`` or ``"hand"``."""
        rigs = call("rigs")["rigs"]
        for r in rigs:
            if r["name"] == name:
                return cls(r["rig"])
        raise ValueError(f"unknown rig '{name}' (expected one of: {', '.join(r['name'] for r in rigs)})")

    @property
    def name(self) -> str:
        return self.rig.get("name", "rig")

    @property
    def bones(self) -> list:
        """The bones' names, in the file's order."""
        if self._character is not None:
            return self._character.bones
        return [b["name"] for b in self.rig["bones"]]

    def __len__(self) -> int:
        return len(self.bones)

    def __repr__(self) -> str:
        return f"<ikarus.Rig {self.name!r}: {len(self)} bones>"

    def _body(self) -> dict:
        return {"rig": self._rig_file()}

    def _columns(self) -> Tuple[Optional[Sequence[str]], Optional[Sequence[float]]]:
        return self.bones, self.rig.get("base")

    def _goal_list(self, goals: Mapping[str, Any]) -> list:
        return _plain(_rig_goals(goals), "goals")

    def solve(
        self,
        goals: Mapping[str, Union[Goal, RigGoal]],
        pins: Sequence[str] = (),
        *,
        mix: Optional[float] = None,
        start_deg: Optional[Sequence[float]] = None,
        **options: Unpack[SolveOptions],
    ) -> Outcome:
        """Solves every goal and pin together from the rig's start pose (or ``start_deg``, one
        angle per bone). ``goals`` maps a bone's name to ``(x, y)``, ``(x, y, angle_deg)`` or a
        dict with ``x``, ``y`` and optionally ``angle_deg``, ``weight``, ``priority``
        (``"primary"``/``"secondary"``), ``bend`` (``"ccw"``/``"cw"``), ``softness``;
        ``pins`` names bones held where they start. Options are the solver's keywords, as for
        :meth:`Chain.solve`. Returns an :class:`Outcome`, as a chain's: ``status``,
        ``angles_deg`` and ``joints`` in the bones' order (the base first), ``effectors`` (the
        goals in order, then the pins); ``to_dict()`` is the object of
        ``ikarus solve --rig --format json`` (but ``solve_us``)."""
        request = {
            "rig": self._rig_file(),
            "goals": _rig_goals(goals),
            "pins": list(pins) or None,
            "mix": mix,
            "start_deg": start_deg,
            "options": _options(options) or None,
        }
        body = _json.dumps(_plain({k: v for k, v in request.items() if v is not None}, "request"), allow_nan=False)
        return _ikarus._solve_rig(body)

    def animate(
        self,
        goals: Mapping[str, Union[Goal, RigGoal]],
        via: Optional[Iterable[Mapping[str, Union[Goal, RigGoal]]]] = None,
        *,
        pins: Sequence[str] = (),
        mix: Optional[float] = None,
        **options: Unpack[MotionOptions],
    ) -> Motion:
        """The motion of ``ikarus animate --rig`` (``POST /api/animate`` with ``rig``): solve
        each ``via`` set of goals in turn, then ``goals``, each from where the last ended, with
        ``pins`` held, then move every bone along one spline, eased. ``goals`` and each ``via``
        set are as for :meth:`solve`. Returns a :class:`Motion` whose columns are the bones in
        the rig's order (``bones``): ``angles_deg`` [F, n], ``joints`` [F, n+1, 2] (the base,
        then each bone's tip)."""
        request = {
            "goals": _rig_goals(goals),
            "via": None if via is None else [_rig_goals(g, f"via[{i}]") for i, g in enumerate(via)],
            "pins": list(pins) or None,
            "mix": mix,
        }
        return self._animate(request, options)

    def track(
        self,
        effector: str,
        path: Optional[npt.ArrayLike] = None,
        *,
        goals: Optional[Mapping[str, Union[Goal, RigGoal]]] = None,
        pins: Sequence[str] = (),
        mix: Optional[float] = None,
        **options: Unpack[TrackOptions],
    ) -> Track:
        """The tip of bone ``effector`` follows a path (``ikarus track --rig --effector``,
        ``POST /api/track`` with ``rig``) while ``goals`` hold and ``pins`` stay: ``path`` [N,
        2] or ``line``, ``circle``, ``figure8`` with ``samples``, as for :meth:`Chain.track`
        (``mode`` ``"follow"``, the only one for a rig). Returns a :class:`Track` whose columns
        are the bones in the rig's order."""
        request = {
            "effector": effector,
            "goals": None if goals is None else _rig_goals(goals),
            "pins": list(pins) or None,
            "mix": mix,
        }
        return self._track({**request, "path": path}, options)

    def render(
        self,
        format: PictureFormat = "svg",
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        **fields: Any,
    ) -> bytes:
        """A picture of the rig by ikarus's renderer (``"figure": "rig"``): ``pose_deg``,
        ``goals`` (as the API's list), ``pins``, ``limits``, ``labels``."""
        return self._render({"figure": "rig", "format": format, "width": width, "height": height, **fields})

    def _repr_svg_(self) -> Optional[str]:
        if self._character is not None:
            return None  # a character is not drawn by render; Jupyter shows its repr
        return self.render("svg", width=480, height=480).decode()


def plot(chain: Union[Chain, Rig, Pose], pose: Any = None, goal: Any = None, ax: Any = None, **kwargs: Any) -> Any:
    """Draws ``chain`` in ``pose`` (its start pose, joint angles in degrees, or an
    :class:`Outcome`) with ``goal`` on matplotlib Axes ``ax`` (new ones by default), and with
    ``workspace=True`` the boundary of the region it reaches (``limits=`` as for
    :meth:`Chain.workspace`). A character (a :class:`Rig` read from a Spine or DragonBones
    file) is drawn as its bones, origin to tip, in ``pose`` (a :class:`Pose`; its setup pose by
    default), as is a :class:`Pose` given alone. Returns the Axes. Needs matplotlib (``pip
    install 'ikarus[plot]'``)."""
    from ._plot import plot as _plot

    return _plot(chain, pose=pose, goal=goal, ax=ax, **kwargs)


# The future import's own name: not part of the API.
del annotations
