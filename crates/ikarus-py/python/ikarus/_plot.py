"""ikarus.plot: a chain, a pose, a goal and the reachable region, or a character's bones,
drawn with matplotlib.

matplotlib is an optional dependency (``pip install 'ikarus[plot]'``), imported only here and
only when a plot is asked for.
"""

from __future__ import annotations

from typing import Any

import numpy as np

# The pictures' palette of ikarus-render (GET /api/meta's "palette"), so that these plots
# match the CLI's and the playground's pictures.
_FALLBACK = {"ink": "#1f2937", "joints": "#2563eb", "goal": "#dc2626", "workspace": "#93c5fd", "reach": "#cbd5e1"}


def _palette() -> dict:
    from . import call

    try:
        palette = call("meta").get("palette", {})
    except Exception:  # the picture does not depend on it
        palette = {}
    out = {**_FALLBACK, **{k: v for k, v in palette.items() if isinstance(v, str)}}
    joints = palette.get("joints")
    if isinstance(joints, list) and joints and isinstance(joints[0], str):
        out["joints"] = joints[0]
    return out


def _segment_points(segment: dict) -> np.ndarray:
    if "line" in segment:
        return np.array(segment["line"], dtype=float)
    arc = segment["arc"]
    a0, a1 = np.radians(arc["from_deg"]), np.radians(arc["to_deg"])
    steps = max(2, int(abs(a1 - a0) / (np.pi / 90)) + 1)
    t = np.linspace(a0, a1, steps)
    cx, cy = arc["center"]
    return np.column_stack([cx + arc["radius"] * np.cos(t), cy + arc["radius"] * np.sin(t)])


def _region_path(boundary: list) -> Any:
    from matplotlib.path import Path

    vertices, codes = [], []
    for loop in boundary:
        pts = np.concatenate([_segment_points(s) for s in loop])
        vertices.extend(pts.tolist())
        codes.extend([Path.MOVETO] + [Path.LINETO] * (len(pts) - 1))
        vertices.append(pts[0].tolist())
        codes.append(Path.CLOSEPOLY)
    return Path(vertices, codes)


def plot(chain: Any, pose: Any = None, goal: Any = None, ax: Any = None, workspace: bool = False, limits: Any = None) -> Any:
    """Draws ``chain`` in ``pose`` with ``goal``; returns the matplotlib Axes.

    ``pose``: None (the chain's start pose), joint angles in degrees, or an :class:`Outcome`
    (its pose, and its goal unless ``goal`` is given). ``goal``: ``(x, y)`` or
    ``(x, y, angle_deg)`` (drawn with an arrow for the heading). ``workspace=True`` shades the
    region the tip reaches (:meth:`Chain.workspace`, ``limits`` as there). ``ax``: the Axes to
    draw on (new ones by default).
    """
    try:
        import matplotlib.pyplot as plt
        from matplotlib.patches import PathPatch
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "ikarus.plot needs matplotlib: pip install 'ikarus[plot]' (or pip install matplotlib)"
        ) from e
    from ._ikarus import Outcome
    from ._results import Pose

    if isinstance(chain, Pose) or getattr(chain, "_character", None) is not None:
        return _plot_character(plt, chain, pose, goal, ax)
    if not hasattr(chain, "joints"):
        raise TypeError(
            f"ikarus.plot draws a Chain, a character (a Rig read from a Spine or DragonBones file) or a Pose, "
            f"not a {type(chain).__name__}; a rig file's rig is drawn by Rig.render"
        )
    if isinstance(pose, Outcome):
        if goal is None:
            x, y, a = pose.goal
            goal = (x, y) if a is None else (x, y, a)
        angles = pose.angles_deg
    elif pose is None:
        angles = chain.angles_deg
    else:
        angles = np.asarray(pose, dtype=float)
    joints = chain.joints(angles)
    colours = _palette()
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))

    reach = chain.max_reach
    bx, by = chain.base
    if workspace:
        region = chain.workspace(limits=limits)
        if region["boundary"]:
            ax.add_patch(PathPatch(_region_path(region["boundary"]), facecolor=colours["workspace"], edgecolor=colours["reach"], lw=1.2, zorder=1, label="reachable"))
        for segment in region.get("curves", []):
            pts = _segment_points(segment)
            ax.plot(pts[:, 0], pts[:, 1], color=colours["reach"], lw=1.2)
    ax.add_patch(plt.Circle((bx, by), reach, fill=False, ls=":", color=colours["reach"], lw=1.0))

    ax.plot(joints[:, 0], joints[:, 1], "-", color=colours["ink"], lw=3, solid_capstyle="round", zorder=3)
    ax.plot(joints[:-1, 0], joints[:-1, 1], "o", color=colours["joints"], ms=7, zorder=4)
    ax.plot(joints[-1, 0], joints[-1, 1], "o", color=colours["ink"], ms=4, zorder=4)
    ax.plot([bx], [by], "s", color=colours["ink"], ms=9, zorder=4)
    if goal is not None:
        g = [float(v) for v in goal]
        ax.plot(g[0], g[1], "x", color=colours["goal"], ms=10, mew=2.5, zorder=5, label="goal")
        if len(g) == 3:
            d = 0.12 * reach
            heading = np.radians(g[2])
            ax.annotate("", xy=(g[0] + d * np.cos(heading), g[1] + d * np.sin(heading)), xytext=(g[0], g[1]), arrowprops={"arrowstyle": "->", "color": colours["goal"], "lw": 2})
    pad = 1.08 * reach
    ax.set_xlim(bx - pad, bx + pad)
    ax.set_ylim(by - pad, by + pad)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{chain.name}: {len(chain)} links")
    return ax


def _plot_character(plt: Any, character: Any, pose: Any, goal: Any, ax: Any) -> Any:
    """A character's bones as segments from each bone's origin to its tip (``pose``: a
    :class:`Pose`, by default the character's setup pose; ``character`` may be the Pose itself),
    with ``goal`` (x, y) marked; y up, equal axes."""
    from ._results import Pose

    if isinstance(character, Pose):
        pose, title = character, "pose"
    else:
        if pose is None:
            pose = character.pose()
        elif not isinstance(pose, Pose):
            raise TypeError(f"pose: a character is drawn in a Pose (Rig.pose), not a {type(pose).__name__}")
        title = character.rig.get("name", "character")
    colours = _palette()
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))
    xs = np.column_stack([pose.x, pose.tip_x, np.full(len(pose), np.nan)]).ravel()
    ys = np.column_stack([pose.y, pose.tip_y, np.full(len(pose), np.nan)]).ravel()
    ax.plot(xs, ys, "-", color=colours["ink"], lw=2, solid_capstyle="round", zorder=3)
    ax.plot(pose.x, pose.y, "o", color=colours["joints"], ms=3, zorder=4)
    if goal is not None:
        g = [float(v) for v in goal]
        ax.plot(g[0], g[1], "x", color=colours["goal"], ms=10, mew=2.5, zorder=5, label="goal")
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{title}: {len(pose)} bones")
    return ax
