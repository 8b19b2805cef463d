"""The shaking force polar diagram of the balancing plots (see :mod:`linkage_sym.plotting.balance`).

The tip of each series' shaking force vector traced in the ``F_x``–``F_y``
plane with equal axes, the origin marked, the curve closed over whole turns,
arrow heads along the direction of travel, gaps where steps are not ``ok``,
and a zoom panel for the series much smaller than the largest.

Examples
--------
>>> import numpy as np
>>> from types import SimpleNamespace
>>> q = np.linspace(0.0, 2 * np.pi, 73)
>>> before = SimpleNamespace(label="before", q=q, status=np.full(73, "ok"),
...                          force=np.stack([np.cos(q), 0.5 * np.sin(q)], axis=-1),
...                          moment=0.1 * np.sin(2 * q))
>>> after = SimpleNamespace(label="after", q=q, status=np.full(73, "ok"),
...                         force=0.01 * before.force, moment=0.0 * q)
>>> len(shaking_force_polar_figure([before, after]).axes)
2
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle

from linkage_sym.plotting import style
from linkage_sym.plotting.balance_series import (
    SMALL_RATIO,
    Series,
    at_text,
    cyclic,
    finish,
    gap_note,
    read_series,
    readable_ticks,
    scales,
    skipped_text,
    zoom_factor,
)

__all__ = ["shaking_force_polar", "shaking_force_polar_figure"]


def _arrows(ax, v: np.ndarray, good: np.ndarray, color: str, scale: float) -> None:
    """Arrow heads at a quarter, half and three quarters of the steps (direction of travel)."""
    n = len(v)
    for frac in (0.25, 0.5, 0.75):
        k = int(frac * (n - 1))
        a = next((i for i in range(k, n - 1) if good[i] and good[i + 1]
                  and np.hypot(*(v[i + 1] - v[i])) > 1e-9 * scale), None)
        if a is None:
            continue
        ax.annotate("", xy=tuple(v[a + 1]), xytext=tuple(v[a]),
                    arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.2,
                                "mutation_scale": 13, "shrinkA": 0, "shrinkB": 0},
                    zorder=6)


def _gap_edges(good: np.ndarray, closed: bool) -> np.ndarray:
    """Solved steps next to a skipped one (where a curve is broken)."""
    prev = np.roll(good, 1)
    nxt = np.roll(good, -1)
    if not closed:
        prev[0] = nxt[-1] = True
    return np.flatnonzero(good & ~(prev & nxt))


def _polar_curve(ax, s: Series, zero: bool, closed: bool, label, scale: float) -> Line2D:
    """Draw one series' force hodograph on ``ax``; return the artist that carries ``label``."""
    v = s.values
    good = s.ok
    if zero:
        # the curve is a point at the origin: a diamond makes it visible
        (art,) = ax.plot([0.0], [0.0], marker="D", ms=10, color=s.color, mec="black", mew=0.8,
                         ls="none", zorder=4, label=label)
        return art
    x, y = v[:, 0], v[:, 1]
    if closed and good[0] and good[-1]:
        x, y = np.append(x, x[0]), np.append(y, y[0])
    (art,) = ax.plot(x, y, color=s.color, lw=1.8, ls=s.linestyle, label=label, zorder=3)
    if good.any():
        i0 = int(np.flatnonzero(good)[0])
        ax.plot([v[i0, 0]], [v[i0, 1]], marker="o", ms=6, color=s.color, mec="black", mew=0.8,
                ls="none", zorder=5)
        _arrows(ax, v, good, s.color, scale)
        edges = _gap_edges(good, closed)
        if edges.size:
            ax.plot(v[edges, 0], v[edges, 1], marker="o", ms=4.5, mfc="white", mec=s.color,
                    mew=1.2, ls="none", zorder=5)
    return art


def _mark_origin(ax) -> None:
    ax.axhline(0.0, color="0.6", lw=0.7, zorder=0.5)
    ax.axvline(0.0, color="0.6", lw=0.7, zorder=0.5)
    ax.plot([0.0], [0.0], marker="+", ms=13, mew=1.8, color="black", ls="none", zorder=7)


def _square_limits(points: np.ndarray, pad: float = 0.12) -> tuple[float, float, float]:
    """``(cx, cy, half)``: a square around ``points`` (and the origin), padded."""
    pts = np.vstack([points.reshape(-1, 2), [[0.0, 0.0]]])
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c = 0.5 * (lo + hi)
    half = 0.5 * float(np.max(hi - lo)) * (1.0 + pad)
    return float(c[0]), float(c[1]), half if half > 0 else 1.0


def _polar_axes(ax, limits) -> None:
    cx, cy, half = limits
    ax.set_xlim(cx - half, cx + half)
    ax.set_ylim(cy - half, cy + half)
    ax.set_aspect("equal", adjustable="box")  # the limits are kept: the zoom square is exact
    ax.set_xlabel("shaking force $F_x$ (N)")
    ax.set_ylabel("shaking force $F_y$ (N)")
    ax.grid(True, color="0.9", lw=0.6)
    readable_ticks(ax, "both")


def _force_label(s: Series, zero: bool, driver_kind: str, zoom: float | None) -> str:
    pk = s.peak()
    if pk is None:
        return f"{s.label}: no solved step{gap_note(s)}"
    peak, k = pk
    if zero:
        return f"{s.label}: numerically zero (peak |F| = {style.fmt_number(peak)} N){gap_note(s)}"
    text = f"{s.label}: peak |F| = {style.fmt_number(peak)} N at {at_text(s, k, driver_kind)}"
    if zoom is not None:
        text += " (also in the zoom panel)"
    return text + gap_note(s)


def shaking_force_polar_figure(series_list, title: str | None = None, *, driver_kind: str = "R"):
    """Draw the shaking force polar diagram of every series; return the figure (not saved).

    The tip of each series' shaking force vector is traced in the
    ``F_x``–``F_y`` plane (N), equal axes, origin marked with a black ``+``.
    The curve is closed when the driver sweeps whole turns; a dot marks the
    first solved step and arrow heads the direction of travel.  All series
    share one figure and one legend, which gives each series' label, its peak
    ``|F|`` and the driver angle of the peak.

    A series whose peak is below ``SMALL_RATIO`` (20 %) of the largest is
    drawn again in a second panel, to the right, at its own scale; a dashed
    square on the main panel shows the region the second panel magnifies.  A
    second panel is used rather than an inset because the polar diagram of
    an unbalanced mechanism usually encircles the origin, which is exactly
    where a well-balanced series lies: an inset anywhere inside the main
    panel would hide part of one or the other, while a side panel keeps both
    whole and gives the small series readable tick labels of its own.  A
    numerically zero series (peak at most ``max(ZERO_ABS, ZERO_REL * largest
    peak)``) is a diamond at the origin, labelled "numerically zero" with its peak value;
    it needs no zoom panel.

    Parameters
    ----------
    series_list : sequence of BalanceSeries
        Or one series.  Each has ``label``, ``q`` (N,), ``status`` (N,),
        ``force`` (N, 2) in N.  Steps whose status is not ``ok`` are gaps.
    title : str, optional
        First line of the figure title; default "shaking force polar diagram".
    driver_kind : {"R", "P"}, optional
        Kind of the driver ``q`` belongs to: ``R`` (radians, shown in degrees,
        the default) or ``P`` (metres).

    Returns
    -------
    matplotlib.figure.Figure
        ``fig.axes[0]`` the main panel (every series, one labelled curve or
        marker per series), ``fig.axes[1]`` the zoom panel if there is one;
        ``fig.legends[0]`` the series legend (one entry per series), below
        the panels with the key to the markers.

    Raises
    ------
    ValueError
        If there is no series or a series' arrays do not match in length.
    """
    series = read_series(series_list, "force")
    zero, small, largest = scales(series)
    with_zoom = any(small)
    fig = style.new_figure(12.8 if with_zoom else 7.6, 7.6 if with_zoom else 8.4)
    if with_zoom:
        ax, zax = fig.subplots(1, 2, gridspec_kw={"width_ratios": (1.0, 1.0)})
    else:
        ax, zax = fig.add_subplot(1, 1, 1), None
    scale = largest if largest > 0 else 1.0
    zoom = zoom_factor(series, small, largest) if with_zoom else None

    handles = []
    for s, z, m in zip(series, zero, small):
        closed = cyclic(s.q, driver_kind)
        label = _force_label(s, z, driver_kind, zoom if m else None)
        handles.append(_polar_curve(ax, s, z, closed, label, scale))
        if zax is not None and (m or z):
            _polar_curve(zax, s, z, closed, None, scale)
    _mark_origin(ax)
    every = np.vstack([s.values for s in series])
    if not np.isfinite(every).any():
        style.no_data_note(ax, "no solved step in any series")
    _polar_axes(ax, _square_limits(every))

    if zax is not None:
        _polar_zoom_panel(ax, zax, series, small, zoom)

    _polar_legend(fig, handles, series, title, driver_kind)
    return fig


def _polar_zoom_panel(ax, zax, series: list, small: list, zoom: float) -> None:
    """The zoom panel ``zax`` of the small series, and the dashed square it magnifies on ``ax``."""
    _mark_origin(zax)
    lim = _square_limits(np.vstack([s.values for s, m in zip(series, small) if m]))
    ax.set_title("all series, common scale", fontsize=10)
    _polar_axes(zax, lim)
    cx, cy, half = lim
    ax.add_patch(Rectangle((cx - half, cy - half), 2 * half, 2 * half, fill=False,
                           ls="--", lw=1.0, ec="0.35", zorder=2))
    ax.annotate("zoom", (cx + half, cy + half), xytext=(3, 3), textcoords="offset points",
                fontsize=8, color="0.35")
    zax.set_title(f"zoom ×{style.fmt_number(zoom)}: series below {SMALL_RATIO:.0%} of the largest "
                  "peak, own scale\n(the dashed square on the left)", fontsize=10)


def _polar_legend(fig, handles: list, series: list, title: str | None, driver_kind: str) -> None:
    """The series legend below the panels, and the title with the key to the markers."""
    fig.legend(handles=handles, loc="outside lower center", ncols=1, fontsize=9, frameon=False)
    closed_any = any(cyclic(s.q, driver_kind) for s in series)
    gaps = " ○ the ends of a gap," if any(s.n_bad for s in series) else ""
    finish(fig, title or "shaking force polar diagram", [
        "tip of the shaking force F on the frame over the "
        + ("cycle" if closed_any else "sweep") + " (equal axes)",
        f"● first solved step,{gaps} ▸ direction of travel, + origin F = 0",
        skipped_text(series),
    ])


def shaking_force_polar(series_list, path, title: str | None = None, *,
                        driver_kind: str = "R") -> Path:
    """Write the shaking force polar diagram of every series as one PNG.

    See :func:`shaking_force_polar_figure` for what is drawn.

    Parameters
    ----------
    series_list : sequence of BalanceSeries
        Or one series.
    path : str or os.PathLike
        PNG file to write; its folder is created if needed.
    title : str, optional
        First line of the figure title.
    driver_kind : {"R", "P"}, optional
        Kind of the driver ``q`` belongs to (default ``R``).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return style.save(shaking_force_polar_figure(series_list, title, driver_kind=driver_kind), path)
