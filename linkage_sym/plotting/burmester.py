"""Pictures of a motion generation: the poses with a linkage in each, the Burmester curves
(and the slider dyads' lines, the guide dyads' pivots and coupler lines).

Only the synthesis' results are read here (:class:`~linkage_sym.synthesis.motion.MotionSynthesis`):
the linkage in pose ``j`` is its fixed pivots and its moving pivots carried by
the coupler frame of pose ``j``.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import Polygon

from linkage_sym.plotting import style


def _frame(ax, x, y, t, size, color, label):
    """A pose: the coupler frame's origin and its x axis (an arrow)."""
    ax.annotate("", xy=(x + size * math.cos(t), y + size * math.sin(t)), xytext=(x, y),
                arrowprops={"arrowstyle": "->", "color": color, "lw": 1.6})
    ax.plot([x], [y], "o", color=color, ms=4)
    ax.annotate(label, (x, y), textcoords="offset points", xytext=(4, -10), color=color, fontsize=8)


def _at(pose, local):
    x, y, t = pose
    c, s = math.cos(t), math.sin(t)
    return x + c * local[0] - s * local[1], y + s * local[0] + c * local[1]


def _line(guide, pose):
    """``(point, direction)``: a guide dyad's coupler line in a pose (through ``G``'s place on it
    in pose 1)."""
    t = pose[2] + guide.angle
    return _at(pose, guide.local), (math.cos(t), math.sin(t))


def _spread(poses) -> float:
    return float(max(np.max(np.hypot(*(poses[:, :2] - poses[0, :2]).T)), 1e-300))


def plot_poses(result, path, design: int = 0):
    """The poses, each with the linkage ``result.designs[design]`` in it; written to ``path``.

    Parameters
    ----------
    result : MotionSynthesis
        A motion generation's result.
    path : str or Path
        The PNG to write.
    design : int
        Which design (0: the best).

    Returns
    -------
    Path
        The file written.
    """
    d = result.designs[design]
    if d.kind in ("inverted slider-crank", "guide-slider"):
        return _plot_guide_poses(result, d, path)
    slider = d.kind == "slider-crank"
    crank = result.dyads[d.crank]
    rocker = result.sliders[d.rocker] if slider else result.dyads[d.rocker]
    fig = style.new_figure(6.4, 5.4)
    ax = fig.add_subplot()
    size = 0.15 * _spread(result.poses)
    A = crank.centre
    for j, pose in enumerate(result.poses):
        color = style.PALETTE[j % len(style.PALETTE)]
        B, C = _at(pose, crank.local), _at(pose, rocker.local)
        ax.add_patch(Polygon([B, C, pose[:2]], closed=True, facecolor=color, alpha=0.15,
                             edgecolor=color))
        chain = [A, B, C] if slider else [A, B, C, rocker.centre]
        ax.plot([p[0] for p in chain], [p[1] for p in chain], "-o", color=color, lw=1.2, ms=3)
        if slider:
            ax.plot(*C, "s", color=color, ms=8, mfc="none")
        _frame(ax, pose[0], pose[1], pose[2], size, color, f"pose {j + 1}")
    if slider:
        _guide(ax, rocker)
        ax.plot(*A, "^", color="k", ms=9, label="fixed pivot A")
    else:
        D = rocker.centre
        ax.plot([A[0], D[0]], [A[1], D[1]], "^", color="k", ms=9, label="fixed pivots A, D")
    return _finish(fig, ax, d, path)


def _finish(fig, ax, d, path):
    c = d.check
    state = "no defect" if c.defect_free else "; ".join(n.split(":")[0] for n in c.notes)
    ax.set_title(f"{d.scene['name']}: {c.grashof}, min transmission angle "
                 f"{math.degrees(c.gamma_min):.1f}°, {state}", fontsize=9)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, lw=0.3)
    return style.save(fig, path)


def _plot_guide_poses(result, d, path):
    """An inverted slider-crank or a guide-slider in every pose: the coupler's line through the
    block's pivot (the block a square), the crank or the slider's pin (a square) and guide, the
    coupler's triangle (its pin, the pin's foot on the line, ``P``)."""
    gs = d.kind == "guide-slider"
    guide = result.guides[d.crank if gs else d.rocker]
    pin = result.sliders[d.rocker] if gs else result.dyads[d.crank]
    fig = style.new_figure(6.4, 5.4)
    ax = fig.add_subplot()
    size = 0.15 * _spread(result.poses)
    D = guide.pivot
    t = np.array(guide.travel)
    for j, pose in enumerate(result.poses):
        color = style.PALETTE[j % len(style.PALETTE)]
        B = _at(pose, pin.local)
        p, u = _line(guide, pose)
        # the line from the pin's foot on it past D, as far as D travels along it and a quarter more
        foot = (B[0] - p[0]) * u[0] + (B[1] - p[1]) * u[1]
        ends = [min(foot, t.min(), 0.0), max(foot, t.max(), 0.0)]
        pad = 0.25 * (ends[1] - ends[0])
        line = np.asarray(p) + np.outer([ends[0] - pad, ends[1] + pad], u)
        ax.plot(line[:, 0], line[:, 1], "-", color=color, lw=1.4)
        F = (p[0] + foot * u[0], p[1] + foot * u[1])
        ax.add_patch(Polygon([B, F, pose[:2]], closed=True, facecolor=color, alpha=0.15,
                             edgecolor=color))
        if gs:
            ax.plot(*B, "s", color=color, ms=8, mfc="none")
        else:
            ax.plot([pin.centre[0], B[0]], [pin.centre[1], B[1]], "-o", color=color, lw=1.2, ms=3)
        ax.plot(*D, "s", color=color, ms=14, mfc="none")
        _frame(ax, pose[0], pose[1], pose[2], size, color, f"pose {j + 1}")
    if gs:
        _guide(ax, pin)
        ax.plot(*D, "^", color="k", ms=9, label="fixed pivot A (the driven block)")
    else:
        A = pin.centre
        ax.plot([A[0], D[0]], [A[1], D[1]], "^", color="k", ms=9, label="fixed pivots A, D (block)")
    return _finish(fig, ax, d, path)


def _guide(ax, slider, label="slider's guide"):
    """A slider dyad's line, over its pin's travel and a quarter of it either side."""
    t = np.array(slider.travel)
    lo, hi = t.min(), t.max()
    pad = 0.25 * max(hi - lo, 1e-300)
    u = np.array([math.cos(slider.angle), math.sin(slider.angle)])
    ends = np.asarray(slider.circle) + np.outer([lo - pad, hi + pad], u)
    ax.plot(ends[:, 0], ends[:, 1], "--", color="k", lw=1.0, label=label)


def plot_curves(result, path):
    """The centre-point and circle-point curves (four poses) or the Burmester point pairs
    (five), with the poses and the dyads combined; written to ``path``.

    Parameters
    ----------
    result : MotionSynthesis
        A motion generation's result.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        The file written.
    """
    fig = style.new_figure(6.4, 5.4)
    ax = fig.add_subplot()
    if result.curves is not None:
        for branch in range(2):
            for pts, color, name in ((result.curves.centre[branch], "#1f77b4", "centre-point curve"),
                                     (result.curves.circle[branch], "#d62728", "circle-point curve")):
                ax.plot(pts[:, 0], pts[:, 1], ".", color=color, ms=1.2,
                        label=name if branch == 0 else None)
        title = f"four poses: Burmester curves, {len(result.dyads)} dyads sampled"
    else:
        title = f"five poses: {len(result.dyads)} Burmester point pairs"
    if len(result.guides):
        title += f", {len(result.guides)} guide dyad{'s' if len(result.guides) > 1 else ''}"
    for k, dy in enumerate(result.dyads):
        ax.plot([dy.centre[0], dy.circle[0]], [dy.centre[1], dy.circle[1]], "-", color="0.5", lw=0.8)
        ax.plot([dy.centre[0]], [dy.centre[1]], "^", color="#1f77b4", ms=7,
                label="centre points (fixed pivots)" if k == 0 else None)
        ax.plot([dy.circle[0]], [dy.circle[1]], "o", color="#d62728", ms=5,
                label="circle points (moving pivots, pose 1)" if k == 0 else None)
    for k, sl in enumerate(result.sliders):
        _guide(ax, sl, "slider lines (centre points at infinity)" if k == 0 else None)
        ax.plot([sl.circle[0]], [sl.circle[1]], "s", color="#2ca02c", ms=6,
                label="slider pins (pose 1)" if k == 0 else None)
    for k, g in enumerate(result.guides):
        p, u = _line(g, result.poses[0])
        t = np.array(g.travel)
        pad = 0.25 * max(t.max() - t.min(), 1e-300)
        ends = np.asarray(p) + np.outer([t.min() - pad, t.max() + pad], u)
        ax.plot(ends[:, 0], ends[:, 1], ":", color="#9467bd", lw=1.4,
                label="guide lines of the coupler (pose 1)"
                if k == 0 else None)
        ax.plot([g.pivot[0]], [g.pivot[1]], "D", color="#9467bd", ms=7,
                label="guide pivots (their circle points at infinity)" if k == 0 else None)
    pts = np.array([*result.poses[:, :2], *(dy.centre for dy in result.dyads),
                    *(dy.circle for dy in result.dyads), *(sl.circle for sl in result.sliders),
                    *(g.pivot for g in result.guides)])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    mid, half = 0.5 * (lo + hi), 0.55 * float(max(hi - lo))
    for j, pose in enumerate(result.poses):
        _frame(ax, pose[0], pose[1], pose[2], 0.3 * _spread(result.poses), "k", str(j + 1))
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_aspect("equal", adjustable="box")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="best", fontsize=8, markerscale=2)
    ax.grid(True, lw=0.3)
    return style.save(fig, path)


__all__ = ["plot_curves", "plot_poses"]
