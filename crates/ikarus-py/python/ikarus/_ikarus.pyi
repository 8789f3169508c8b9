"""Type stubs of the native module ``ikarus._ikarus`` (PyO3). Angles are degrees."""

from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import Unpack

from ._types import BatchColumns, EaseName, SolveOptions

__version__: str

Goal = Union[Tuple[float, float], Tuple[float, float, float], Sequence[float], npt.NDArray[np.float64]]

class Effector:
    """One goal or pin of a solve and how close its tip came (a chain's solve has one, ``"tip"``)."""

    @property
    def name(self) -> str:
        """The bone whose tip it moves (``"tip"`` for a chain's last link)."""
    @property
    def pinned(self) -> bool:
        """A pin (the tip held where it started) rather than a goal."""
    @property
    def status(self) -> str:
        """``"reached"``, … for this effector alone."""
    @property
    def error(self) -> float:
        """Distance from the tip to its target."""
    @property
    def angle_error_deg(self) -> float:
        """Orientation error, degrees (0 without a direction)."""
    @property
    def tip(self) -> Tuple[float, float]:
        """Where the tip ended."""
    @property
    def target(self) -> Tuple[float, float]:
        """Where it was asked to be."""

class Outcome:
    """The result of :meth:`Chain.solve` and :meth:`Rig.solve`: the fields of
    ``ikarus solve --format json`` (``--rig`` for a rig)."""

    @property
    def status(self) -> str:
        """``"reached"``, ``"unreachable"``, ``"stalled"`` or ``"iteration_limit"``."""
    @property
    def reached(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def restarts(self) -> int: ...
    @property
    def error(self) -> float:
        """Distance from the tip to the goal (a rig's: the largest over its effectors)."""
    @property
    def angle_error_deg(self) -> float: ...
    @property
    def reach_distance(self) -> Optional[float]:
        """A chain's with limits on: the goal's distance from the exact region; else None."""
    @property
    def angles_deg(self) -> npt.NDArray[np.float64]:
        """float64 [n]: each joint's (a rig's bones in its order)."""
    @property
    def joints(self) -> npt.NDArray[np.float64]:
        """float64 [n+1, 2]: the base, then each link's (bone's) tip."""
    @property
    def extensions(self) -> Dict[str, float]:
        """Each prismatic bone's displacement (length units) by name, in the rig's order; empty
        for a chain or a rig without prismatic joints (whose ``to_dict()`` has no
        ``"extensions"``)."""
    @property
    def effectors(self) -> Tuple[Effector, ...]:
        """The goals in order, then the pins (a chain's: one, ``"tip"``)."""
    @property
    def end_effector(self) -> Tuple[float, float, float]:
        """A chain's tip ``(x, y, angle_deg)``; ``AttributeError`` for a rig (see ``effectors``)."""
    @property
    def frames(self) -> npt.NDArray[np.float64]:
        """float64 [k, n]: the recorded poses."""
    @property
    def frame_iterations(self) -> npt.NDArray[np.uint32]: ...
    @property
    def frame_joints(self) -> npt.NDArray[np.float64]:
        """float64 [k, n+1, 2]."""
    @property
    def goal(self) -> Tuple[float, float, Optional[float]]:
        """A chain's goal ``(x, y, angle_deg or None)``; ``AttributeError`` for a rig."""
    def to_dict(self) -> dict[str, Any]: ...
    def _repr_svg_(self) -> str: ...

class Chain:
    """A planar chain of links joined by revolute joints (degrees at this edge)."""

    def __init__(
        self,
        lengths: Optional[Sequence[float]] = None,
        angles_deg: Optional[Sequence[float]] = None,
        limits_deg: Optional[Sequence[Optional[Tuple[float, float]]]] = None,
        base: Optional[Tuple[float, float]] = None,
        name: Optional[str] = None,
        *,
        toml: Optional[str] = None,
        label: Optional[str] = None,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def lengths(self) -> npt.NDArray[np.float64]: ...
    @property
    def angles_deg(self) -> npt.NDArray[np.float64]: ...
    @property
    def limits_deg(self) -> list[Optional[Tuple[float, float]]]: ...
    @property
    def base(self) -> Tuple[float, float]: ...
    @property
    def max_reach(self) -> float: ...
    @property
    def _arm_json(self) -> str: ...
    @property
    def _toml(self) -> Optional[str]: ...
    def __len__(self) -> int: ...
    def joints(self, angles_deg: Optional[Sequence[float]] = None) -> npt.NDArray[np.float64]: ...
    def solve(self, goal: Goal, **options: Unpack[SolveOptions]) -> Outcome:
        """Solve for ``goal`` from the start pose; options by keyword with the CLI's names
        (``method``, ``lambda_``, ``tolerance``, ``limits``, ``limit_mode``, ``restarts``, …)."""
    def solve_batch(self, goals: npt.ArrayLike, *, threads: Optional[int] = None, **options: Unpack[SolveOptions]) -> BatchColumns:
        """Solve every row of ``goals`` ([N, 2] or [N, 3], numbers, converted to float64) in
        parallel: ``angles_deg`` [N, n],
        ``status`` <U15 [N], ``error`` [N], ``iterations`` uint32 [N]."""
    def _repr_svg_(self) -> str: ...

class _Character:
    def __init__(self, text: str, label: str) -> None: ...
    @property
    def format(self) -> str: ...
    @property
    def version(self) -> str: ...
    @property
    def bones(self) -> list[str]: ...
    @property
    def animations(self) -> list[str]: ...
    @property
    def warnings(self) -> list[str]: ...
    def pose(
        self,
        animation: Optional[str] = None,
        time: Optional[float] = None,
        targets: Sequence[Tuple[str, Tuple[float, float]]] = ...,
        ik: Optional[str] = None,
        look: Tuple[Optional[str], Optional[float]] = (None, 60.0),
    ) -> dict[str, Any]: ...

def ease(kind: EaseName, t: Union[float, npt.ArrayLike], k1: Optional[float] = None, k2: Optional[float] = None, velocity: bool = False) -> Any:
    """An ease curve's position s(t) (or velocity) at t in [0, 1]; the shape of ``t``."""

def _status_names() -> list[str]: ...
def _call(endpoint: str, body: str, *, keywords: bool = False) -> bytes: ...
def _solve_rig(request: str) -> Outcome: ...
def _character_text(data: bytes, label: str) -> str: ...
def _png_rgba(data: bytes, label: str) -> tuple[int, int, bytes]: ...
