"""The names and option sets of the API, as types: ``Literal`` names and ``TypedDict``
records, read by type checkers (the stub ``_ikarus.pyi`` and ``__init__.py`` use them) and
checked against the backend's lists (``POST /api/meta``) by the tests."""

from __future__ import annotations

from typing import TYPE_CHECKING, List, Literal, Sequence, TypedDict

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

# The solver's methods (``--method``), as ``/api/meta`` lists them.
Method = Literal["transpose", "pinv", "dls", "sdls", "lm", "ccd", "fabrik", "analytic"]
# How joint ranges are enforced (``--limit-mode``).
LimitMode = Literal["ignore", "clamp", "lock", "nullspace", "weighted"]
# Ease curves (``--ease``).
EaseName = Literal["linear", "sine", "parent", "smoothstep"]
# How a motion passes its keyframes (``--interpolation``).
Interpolation = Literal["spline", "linear"]
# How a path is tracked (``--mode``).
TrackMode = Literal["plan", "follow"]
# What a solve ended with (``Outcome.status``; a track's samples add ``limited`` and ``off_path``).
Status = Literal["reached", "unreachable", "stalled", "iteration_limit", "interrupted"]
# ``render``'s figures and formats.
Figure = Literal["arm", "motion", "workspace", "ease", "rig"]
PictureFormat = Literal["svg", "png", "gif"]


class _SolverOptions(TypedDict, total=False):
    method: Method
    lambda_: float
    tolerance: float
    angle_tolerance_deg: float
    max_iterations: int
    gain: float
    rates: Sequence[float]
    backtrack: int
    stall_window: int
    stall_epsilon_deg: float
    limits: bool
    limit_mode: LimitMode
    restarts: int
    restart_seed: int
    time_budget_ms: float
    no_closed_form: bool
    record_every: int


class SolveOptions(_SolverOptions, total=False):
    """The solver's keyword options, the API's ``options`` (the CLI's flags by name), over the
    arm or rig file's ``[solver]`` table. ``lambda`` is a Python keyword: ``lambda_``."""

    max_step_deg: float


class TrackSolveOptions(_SolverOptions, total=False):
    """:class:`SolveOptions` for ``track``, whose ``max_step_deg`` is the flip bound: the
    solver's own step cap is ``solver_max_step_deg`` there (``--solver-max-step-deg``)."""

    solver_max_step_deg: float


class MotionOptions(SolveOptions, total=False):
    """``animate``'s keywords: the motion's settings (``ikarus animate``'s flags by name), then
    the solver's options."""

    frames: int
    duration: float
    fps: float
    ease: EaseName
    k1: float
    k2: float
    interpolation: Interpolation
    from_solve: bool
    start_deg: Sequence[float]


class TrackOptions(TrackSolveOptions, total=False):
    """``track``'s keywords: the path's settings (``ikarus track``'s flags by name; one of
    ``line``, ``circle``, ``figure8`` unless a ``path`` is given), then the solver's options."""

    line: Sequence[float]
    circle: Sequence[float]
    figure8: Sequence[float]
    samples: int
    mode: TrackMode
    max_step_deg: float
    bound_first: bool
    start_deg: Sequence[float]


class RigGoal(TypedDict, total=False):
    """A rig's goal on a bone's tip, as the API's ``goals`` items (less ``bone``, the key)."""

    x: float
    y: float
    angle_deg: float
    weight: float
    priority: Literal["primary", "secondary"]
    bend: Literal["ccw", "cw"]
    softness: float


class EffectorRecord(TypedDict):
    """An effector of a motion's solve, as the JSON has it (``Outcome.effectors`` holds
    :class:`Effector` objects with the same fields)."""

    name: str
    pinned: bool
    status: str
    error: float
    angle_error_deg: float
    tip: List[float]
    target: List[float]


class _SolveRecord(TypedDict):
    status: str
    iterations: int
    error: float


class MotionSolve(_SolveRecord, total=False):
    """One solve of a motion (each via, then the goal), as the JSON has it: ``status``,
    ``iterations``, ``error``, and an arm's ``goal`` ``[x, y]`` or a rig's ``effectors``."""

    goal: List[float]
    effectors: List[EffectorRecord]


class TrackSummary(TypedDict):
    """A track's summary, as ``ikarus track --format json`` prints it."""

    samples: int
    reached: int
    limited: int
    unreachable: int
    stalled: int
    off_path: int
    flips: int
    flip_samples: List[int]
    step_bound_deg: float
    max_step_deg: float
    max_error: float
    max_velocity_deg_per_sample: float
    max_acceleration_deg_per_sample2: float
    max_jerk_deg_per_sample3: float


class BatchColumns(TypedDict):
    """What ``Chain.solve_batch`` returns, one row per goal: the rows of
    ``ikarus solve --batch``'s CSV as NumPy columns."""

    angles_deg: npt.NDArray[np.float64]
    status: npt.NDArray[np.str_]
    error: npt.NDArray[np.float64]
    iterations: npt.NDArray[np.uint32]
