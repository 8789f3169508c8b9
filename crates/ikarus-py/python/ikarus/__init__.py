"""ikarus: inverse kinematics for planar chains, from Python.

The computing is the Rust library's; this edge speaks degrees, as the command line does, and
its results equal ``ikarus solve/animate/track/workspace/reach --format json`` for the same
inputs, bit for bit::

    >>> import ikarus
    >>> arm = ikarus.Chain()                      # the seed arm: lengths 3, 2, 1
    >>> out = arm.solve((2.0, 3.0))
    >>> out.status, out.iterations
    ('reached', 7)
    >>> arm.solve_batch(goals)["status"]          # goals: float64 [N, 2] or [N, 3]

Options are keywords with the CLI's names (``method="dls"``, ``lambda_=0.2``, ``limits=True``,
``restarts=0``, …); a bad value raises ``ValueError`` with the CLI's one-line message.
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
from ._ikarus import Outcome, ease

if _typing.TYPE_CHECKING:
    import os

    from typing import Any, Iterable, Optional, Sequence

__all__ = ["Chain", "Rig", "Outcome", "ease", "plot", "call", "__version__"]
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


def _options(options: dict) -> dict:
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


def _columns(rows: Sequence[dict]) -> dict:
    """A list of objects with the same keys as a dict of columns (NumPy arrays where the
    values are numbers, booleans or strings)."""
    if not rows:
        return {}
    keys = list(rows[0].keys())
    for row in rows[1:]:
        keys.extend(k for k in row if k not in keys)
    out = {}
    for key in keys:
        values = [row.get(key) for row in rows]
        if any(v is None for v in values):
            if all(v is None or isinstance(v, (int, float)) for v in values):
                out[key] = _np.array([_np.nan if v is None else float(v) for v in values])
            else:
                out[key] = values
        elif all(isinstance(v, str) for v in values):
            out[key] = _np.array(values, dtype=str)
        elif all(isinstance(v, bool) for v in values):
            out[key] = _np.array(values, dtype=bool)
        elif all(isinstance(v, int) and not isinstance(v, bool) for v in values):
            out[key] = _np.array(values, dtype=_np.int64)
        else:
            try:
                out[key] = _np.array(values, dtype=_np.float64)
            except (ValueError, TypeError):
                out[key] = values
    return out


def _rebuild_chain(cls: type, toml: Optional[str]) -> "Chain":
    return cls() if toml is None else cls(toml=toml)


class Chain(_ikarus.Chain):
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

    def _request(self, endpoint: str, request: dict) -> Any:
        request = {"arm": self._arm(), **{k: v for k, v in request.items() if v is not None}}
        return call(endpoint, request)

    def animate(
        self,
        goal: Sequence[float],
        via: Optional[Iterable[Sequence[float]]] = None,
        *,
        frames: Optional[int] = None,
        duration: Optional[float] = None,
        fps: Optional[float] = None,
        ease: Optional[str] = None,
        k1: Optional[float] = None,
        k2: Optional[float] = None,
        interpolation: Optional[str] = None,
        from_solve: Optional[bool] = None,
        start_deg: Optional[Sequence[float]] = None,
        **options: Any,
    ) -> dict:
        """The motion of ``ikarus animate`` (``POST /api/animate``): solve for ``goal`` through
        each ``via`` point, then move along a smooth spline, eased.

        Returns the answer's fields (``arm``, ``ease``, ``duration``, ``solves``) with
        ``frames`` as columns: ``time`` [F], ``angles_deg`` [F, n], ``joints`` [F, n+1, 2]
        (NumPy arrays, the numbers of ``ikarus animate --format json``, bit for bit). Solver
        options are keywords, as for :meth:`solve`."""
        easing = {"kind": ease, "k1": k1, "k2": k2}
        request = {
            "goal": _goal(goal),
            "via": None if via is None else [list(_plain(p, f"via[{i}]")) for i, p in enumerate(via)],
            "frames": frames,
            "duration": duration,
            "fps": fps,
            "ease": {k: v for k, v in easing.items() if v is not None} or None,
            "interpolation": interpolation,
            "from_solve": from_solve,
            "start_deg": start_deg,
            "options": _options(options) or None,
        }
        answer = self._request("animate", request)
        answer["frames"] = _columns(answer["frames"])
        return answer

    def track(
        self,
        path: Optional[Any] = None,
        *,
        line: Optional[Sequence[float]] = None,
        circle: Optional[Sequence[float]] = None,
        figure8: Optional[Sequence[float]] = None,
        samples: Optional[int] = None,
        mode: Optional[str] = None,
        max_step_deg: Optional[float] = None,
        bound_first: Optional[bool] = None,
        start_deg: Optional[Sequence[float]] = None,
        **options: Any,
    ) -> dict:
        """The tip follows a path without flips, as ``ikarus track`` (``POST /api/track``):
        ``path`` (an array [N, 2] or [N, 3] of x, y[, angle_deg]) or one of ``line=(x0, y0, x1,
        y1)``, ``circle=(cx, cy, r)``, ``figure8=(cx, cy, a)`` with ``samples``; ``mode`` is
        ``"plan"`` (default) or ``"follow"``; ``max_step_deg`` the flip bound (10°).

        Returns ``arm``, ``mode``, ``summary`` (a dict, as the CLI's) and ``samples`` as
        columns: ``goal`` [N, 2], ``status`` [N] (str), ``error`` [N], ``angles_deg`` [N, n],
        ``joints`` [N, n+1, 2], ``step_deg`` [N] (and ``angle_deg`` for oriented goals). Solver
        options are keywords, as for :meth:`solve`; the solver's per-iteration step cap, which
        ``max_step_deg`` names elsewhere, is ``solver_max_step_deg`` here (as the CLI's
        ``ikarus track --solver-max-step-deg``)."""
        solver_options = _options(options)
        if "solver_max_step_deg" in solver_options:
            solver_options["max_step_deg"] = solver_options.pop("solver_max_step_deg")
        request = {
            "path": None if path is None else _plain(_np.asarray(path, dtype=float), "path"),
            "line": line,
            "circle": circle,
            "figure8": figure8,
            "samples": samples,
            "mode": mode,
            "max_step_deg": max_step_deg,
            "bound_first": bound_first,
            "start_deg": start_deg,
            "options": solver_options or None,
        }
        answer = self._request("track", request)
        answer["samples"] = _columns(answer["samples"])
        return answer

    def workspace(
        self,
        limits: Optional[bool] = None,
        *,
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
        array [resolution, resolution] (row 0 at the bottom)."""
        request = {"limits": limits, "grid": grid, "resolution": resolution, "samples": samples, "seed": seed}
        answer = self._request("workspace", request)
        if "grid" in answer:
            answer["cells"] = _np.array([[c == "1" for c in row] for row in answer["grid"]], dtype=bool)
        return answer

    def reach(
        self,
        points: Any,
        limits: Optional[bool] = None,
        tolerance: Optional[float] = None,
    ) -> dict:
        """Can the tip get there? As ``ikarus reach --format json`` (``POST /api/reach``), read
        off the exact region. One point ``(x, y)`` gives ``{"reachable", "distance",
        "nearest"}``; an array [N, 2] gives columns ``reachable`` bool [N], ``distance`` [N]
        and ``nearest`` [N, 2]."""
        arr = _np.asarray(points, dtype=float)
        if arr.ndim == 1:
            if arr.shape != (2,):
                raise ValueError(f"points: expected (x, y) or an array of shape (N, 2), got {arr.shape}")
            request = {"point": _plain(arr, "point"), "limits": limits, "tolerance": tolerance}
            return self._request("reach", request)
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise ValueError(f"points: expected (x, y) or an array of shape (N, 2), got {arr.shape}")
        request = {"points": _plain(arr, "points"), "limits": limits, "tolerance": tolerance}
        return _columns(self._request("reach", request))

    def render(
        self,
        figure: str = "arm",
        format: str = "svg",
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
        request = {"arm": self._arm(), **{k: v for k, v in request.items() if v is not None}}
        if figure == "ease":
            request.pop("arm")
        body = _json.dumps(_plain(request, "request"), allow_nan=False)
        return bytes(_ikarus._call("render", body))

    def plot(self, pose: Any = None, goal: Any = None, ax: Any = None, **kwargs: Any) -> Any:
        """Draws the chain with matplotlib: see :func:`ikarus.plot`."""
        from ._plot import plot as _plot

        return _plot(self, pose=pose, goal=goal, ax=ax, **kwargs)


class Rig:
    """A skeleton (a *rig*): a tree of named bones, solved for goals on any bones' tips with
    others pinned, through the API (``POST /api/solve`` with ``rig``), as
    ``ikarus solve --rig FILE``.

    ``Rig(rig)`` takes a rig file's fields as a dict (``{"name", "base", "bones": [{"name",
    "parent", "length", "angle_deg", "limits_deg"}], "solver"}``); ``Rig.from_toml(path)``
    reads a rig file; ``Rig.shipped("puppet")`` (or ``"hand"``) is one of
    ``examples/rigs/``."""

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
        return cls(answer["rig"])

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
        return [b["name"] for b in self.rig["bones"]]

    def __len__(self) -> int:
        return len(self.rig["bones"])

    def __repr__(self) -> str:
        return f"<ikarus.Rig {self.name!r}: {len(self)} bones>"

    def solve(
        self,
        goals: dict,
        pins: Sequence[str] = (),
        *,
        mix: Optional[float] = None,
        start_deg: Optional[Sequence[float]] = None,
        **options: Any,
    ) -> dict:
        """Solves every goal and pin together from the rig's start pose (or ``start_deg``, one
        angle per bone). ``goals`` maps a bone's name to ``(x, y)``, ``(x, y, angle_deg)`` or a
        dict with ``x``, ``y`` and optionally ``angle_deg``, ``weight``, ``priority``
        (``"primary"``/``"secondary"``), ``bend`` (``"ccw"``/``"cw"``), ``softness``;
        ``pins`` names bones held where they start. Options are the solver's keywords, as for
        :meth:`Chain.solve`. Returns the object of ``ikarus solve --rig --format json``:
        ``status``, ``effectors`` (goals in order, then pins), ``angles_deg`` and ``joints``
        keyed by bone name."""
        listed = []
        for bone, goal in goals.items():
            g = dict(goal) if isinstance(goal, dict) else _goal(goal, f"goals[{len(listed)}]")
            listed.append({"bone": bone, **g})
        request = {
            "rig": self.rig,
            "goals": listed,
            "pins": list(pins) or None,
            "mix": mix,
            "start_deg": start_deg,
            "options": _options(options) or None,
        }
        return call("solve", {k: v for k, v in request.items() if v is not None})

    def render(self, format: str = "svg", *, width: Optional[int] = None, height: Optional[int] = None, **fields: Any) -> bytes:
        """A picture of the rig by ikarus's renderer (``"figure": "rig"``): ``pose_deg``,
        ``goals`` (as the API's list), ``pins``, ``limits``, ``labels``."""
        request = {"figure": "rig", "format": format, "width": width, "height": height, "rig": self.rig, **fields}
        body = _json.dumps(_plain({k: v for k, v in request.items() if v is not None}, "request"), allow_nan=False)
        return bytes(_ikarus._call("render", body))

    def _repr_svg_(self) -> str:
        return self.render("svg", width=480, height=480).decode()


def plot(chain: Chain, pose: Any = None, goal: Any = None, ax: Any = None, **kwargs: Any) -> Any:
    """Draws ``chain`` in ``pose`` (its start pose, joint angles in degrees, or an
    :class:`Outcome`) with ``goal`` on matplotlib Axes ``ax`` (new ones by default), and with
    ``workspace=True`` the boundary of the region it reaches (``limits=`` as for
    :meth:`Chain.workspace`). Returns the Axes. Needs matplotlib (``pip install
    'ikarus[plot]'``)."""
    from ._plot import plot as _plot

    return _plot(chain, pose=pose, goal=goal, ax=ax, **kwargs)


# The future import's own name: not part of the API.
del annotations
