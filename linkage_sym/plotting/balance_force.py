"""Balancing plots: shaking force polar diagram and shaking moment curve.

Two figures compare series of shaking loads, typically *before* and *after*
balancing, on one figure each:

* the *shaking force polar diagram*: the tip of the shaking force vector
  ``F = (F_x, F_y)`` traced over the cycle in the ``F_x``–``F_y`` plane with
  equal axes and the origin marked (a hodograph in Cartesian axes, the classic
  diagram of balancing texts);
* the *shaking moment curve*: the moment about the global origin against the
  first driver's coordinate (degrees for an ``R`` driver).

The inputs are :class:`~linkage_sym.balancing.series.BalanceSeries` objects
(or anything with the same attributes ``label``, ``q``, ``status``, ``force``
and ``moment``).  This module only reads them: it does not import
:mod:`linkage_sym.balancing` (which needs SymPy) nor SymPy, so the plotting
layer keeps consuming results only.

Steps whose status is not ``ok`` are gaps: their values are dropped (set to
NaN) whatever they hold, the curves are not joined across them, and the
figure says how many steps were skipped.

A series whose peak is a small fraction (below :data:`SMALL_RATIO`) of the
largest peak is drawn a second time in a *zoom panel* at its own scale, so a
well-balanced *after* series can be read next to the *before* series.  A
series that is numerically zero (see :data:`ZERO_ABS`, :data:`ZERO_REL`) is
drawn as a diamond at the origin (polar diagram) or a marked line on zero
(moment curve) and its legend entry says so, with the peak value it has.

Size: about 630 lines: the polar plot and the moment curve share the
before/after styling, the driver-value axis and the legend layout.

Examples
--------
>>> import numpy as np
>>> from types import SimpleNamespace
>>> q = np.linspace(0.0, 2 * np.pi, 73)
>>> before = SimpleNamespace(label="before", q=q, status=np.full(73, "ok"),
...                          force=np.stack([np.cos(q), 0.5 * np.sin(q)], axis=-1),
...                          moment=0.1 * np.sin(2 * q))
>>> fig = shaking_force_polar_figure([before])
>>> len(fig.legends[0].get_texts())
1
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle

from linkage_sym.numeric.results.cycle_average import cycle_rms, whole_turns
from linkage_sym.plotting import style

__all__ = [
    "SMALL_RATIO",
    "ZERO_ABS",
    "ZERO_REL",
    "shaking_force_polar",
    "shaking_force_polar_figure",
    "shaking_moment_curve",
    "shaking_moment_figure",
]

SMALL_RATIO = 0.2
"""A series whose peak is below this fraction of the largest peak also gets the zoom panel."""

ZERO_ABS = 1e-12
"""A peak at or below this (N or N·m) is numerically zero."""

ZERO_REL = 1e-9
"""A peak at or below this fraction of the largest peak is numerically zero."""

_OK = "ok"
_LINESTYLES = ("-", "--", "-.", ":")


# --------------------------------------------------------------------------- input


@dataclass
class _Series:
    """One input series, checked and with its non-``ok`` steps set to NaN."""

    label: str
    q: np.ndarray  # (N,) finite: NaN driver values interpolated over the step index
    status: np.ndarray  # (N,) str
    ok: np.ndarray  # (N,) bool: status ok and the value finite
    values: np.ndarray  # (N, 2) force or (N,) moment, NaN where not ok
    color: str
    linestyle: str
    q_known: bool = True  # False: no finite driver value, ``q`` is the step index

    @property
    def n(self) -> int:
        return len(self.q)

    @property
    def n_bad(self) -> int:
        """Steps whose status is not ``ok`` (skipped)."""
        return int(np.count_nonzero(self.status != _OK))

    def magnitude(self) -> np.ndarray:
        v = self.values
        return np.hypot(v[:, 0], v[:, 1]) if v.ndim == 2 else np.abs(v)

    def peak(self) -> tuple[float, int] | None:
        """``(largest magnitude, its step)`` over the solved steps, or None."""
        if not self.ok.any():
            return None
        mag = np.where(self.ok, self.magnitude(), -np.inf)
        k = int(np.argmax(mag))
        return float(mag[k]), k


def _fill_q(q: np.ndarray) -> np.ndarray:
    """``q`` with non-finite entries interpolated (or extrapolated flat) over the step index."""
    good = np.isfinite(q)
    if good.all():
        return q
    if not good.any():
        return np.arange(len(q), dtype=float)
    idx = np.arange(len(q))
    return np.interp(idx, idx[good], q[good])


def _series(series_list, quantity: str) -> list:
    """Check the inputs and return one :class:`_Series` per input, in order."""
    if hasattr(series_list, "status"):  # a single series
        series_list = [series_list]
    series_list = list(series_list)
    if not series_list:
        raise ValueError("no series to plot")
    out = []
    for i, s in enumerate(series_list):
        q = np.asarray(s.q, dtype=float).reshape(-1)
        n = len(q)
        status = np.asarray(s.status).astype(str).reshape(-1)
        if quantity == "force":
            values = np.array(s.force, dtype=float)
            if values.shape != (n, 2):
                raise ValueError(f"series {i} ({s.label!r}): force has shape {values.shape}, "
                                 f"expected ({n}, 2)")
            finite = np.all(np.isfinite(values), axis=1)
        else:
            values = np.array(s.moment, dtype=float)
            if values.shape != (n,):
                raise ValueError(f"series {i} ({s.label!r}): moment has shape {values.shape}, "
                                 f"expected ({n},)")
            finite = np.isfinite(values)
        if status.shape != (n,):
            raise ValueError(f"series {i} ({s.label!r}): status has shape {status.shape}, "
                             f"expected ({n},)")
        ok = (status == _OK) & finite
        values[~ok] = np.nan
        label = str(s.label) if str(s.label) else f"series {i + 1}"
        out.append(_Series(label, _fill_q(q), status, ok, values,
                           style.PALETTE[i % len(style.PALETTE)],
                           _LINESTYLES[i % len(_LINESTYLES)], bool(np.isfinite(q).any())))
    return out


def _scales(series: list) -> tuple[list, list, float]:
    """Which series are numerically zero, which go to the zoom panel, and the largest peak.

    Returns
    -------
    zero : list of bool
    small : list of bool
        Non-zero series whose peak is below ``SMALL_RATIO`` times the largest
        (only when some other series is large).
    largest : float
        Largest peak over all series (0.0 when none has a solved step).
    """
    peaks = [p[0] if p is not None else None for p in (s.peak() for s in series)]
    largest = max((p for p in peaks if p is not None), default=0.0)
    tol = max(ZERO_ABS, ZERO_REL * largest)
    zero = [p is not None and p <= tol for p in peaks]
    small = [p is not None and not z and p < SMALL_RATIO * largest
             for p, z in zip(peaks, zero)]
    return zero, small, largest


def _cyclic(q: np.ndarray, driver_kind: str) -> bool:
    """Whether the driver sweeps a whole number of turns (the last step closes the cycle)."""
    if driver_kind != "R" or len(q) < 3:
        return False
    span = abs(float(q[-1] - q[0]))
    step = span / (len(q) - 1)
    turns = round(span / (2 * math.pi))
    return turns >= 1 and abs(span - 2 * math.pi * turns) <= 1.5 * step


def _x_axis(q: np.ndarray, driver_kind: str, known: bool = True
            ) -> tuple[np.ndarray, str, str, str]:
    """``(x, axis label, unit, symbol)`` of the driver coordinate (the step when not ``known``)."""
    if not known:
        return q, "step (no driver value known)", "", "step"
    if driver_kind == "R":
        return np.degrees(q), "driver angle θ (deg)", "deg", "θ"
    return q, "driver displacement s (m)", "m", "s"


def _at(s: _Series, k: int, driver_kind: str) -> str:
    x, _, unit, sym = _x_axis(s.q[k:k + 1], driver_kind, s.q_known)
    return f"{sym} = {style.fmt_number(float(x[0]))}{'°' if unit == 'deg' else ' ' + unit}".rstrip()


def _skipped_text(series: list) -> str:
    """The figure's note on skipped steps ("" when every step is ok)."""
    if not any(s.n_bad for s in series):
        return ""
    counts = {(s.n_bad, s.n) for s in series}
    if len(counts) == 1:
        bad, n = counts.pop()
        who = "in every series" if len(series) > 1 else ""
        return f"{bad} of {n} steps skipped {who} (status not ok): gaps in the curves".replace(
            "  ", " ")
    parts = ", ".join(f"{s.label} {s.n_bad} of {s.n}" for s in series if s.n_bad)
    return f"steps skipped (status not ok), gaps in the curves: {parts}"


def _gap_note(s: _Series) -> str:
    return f"; {s.n_bad} of {s.n} steps skipped (gaps)" if s.n_bad else ""


def _zoom_factor(series: list, small: list, largest: float) -> float:
    top = max(s.peak()[0] for s, m in zip(series, small) if m)
    return largest / top


def _finish(fig, head: str, lines: list) -> None:
    lines = [line for line in lines if line]
    fig.suptitle("\n".join([head] + lines), fontsize=11)


# ------------------------------------------------------------- shaking force polar


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


def _polar_curve(ax, s: _Series, zero: bool, closed: bool, label, scale: float) -> Line2D:
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
    _readable_ticks(ax, "both")


def _readable_ticks(ax, axis: str) -> None:
    """Few ticks, and a ×10ⁿ offset instead of long labels for very small or large values."""
    from matplotlib.ticker import MaxNLocator

    nice = [1, 2, 2.5, 5, 10]
    if axis in ("x", "both"):
        ax.xaxis.set_major_locator(MaxNLocator(7, steps=nice))
    if axis in ("y", "both"):
        ax.yaxis.set_major_locator(MaxNLocator(8, steps=nice))
    ax.ticklabel_format(axis=axis, style="sci", scilimits=(-3, 4), useMathText=True)


def _force_label(s: _Series, zero: bool, driver_kind: str, zoom: float | None) -> str:
    pk = s.peak()
    if pk is None:
        return f"{s.label}: no solved step{_gap_note(s)}"
    peak, k = pk
    if zero:
        return f"{s.label}: numerically zero (peak |F| = {style.fmt_number(peak)} N){_gap_note(s)}"
    text = f"{s.label}: peak |F| = {style.fmt_number(peak)} N at {_at(s, k, driver_kind)}"
    if zoom is not None:
        text += " (also in the zoom panel)"
    return text + _gap_note(s)


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
    series = _series(series_list, "force")
    zero, small, largest = _scales(series)
    with_zoom = any(small)
    fig = style.new_figure(12.8 if with_zoom else 7.6, 7.6 if with_zoom else 8.4)
    if with_zoom:
        ax, zax = fig.subplots(1, 2, gridspec_kw={"width_ratios": (1.0, 1.0)})
    else:
        ax, zax = fig.add_subplot(1, 1, 1), None
    scale = largest if largest > 0 else 1.0
    zoom = _zoom_factor(series, small, largest) if with_zoom else None

    handles = []
    for s, z, m in zip(series, zero, small):
        closed = _cyclic(s.q, driver_kind)
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

    fig.legend(handles=handles, loc="outside lower center", ncols=1, fontsize=9, frameon=False)
    closed_any = any(_cyclic(s.q, driver_kind) for s in series)
    gaps = " ○ the ends of a gap," if any(s.n_bad for s in series) else ""
    _finish(fig, title or "shaking force polar diagram", [
        "tip of the shaking force F on the frame over the "
        + ("cycle" if closed_any else "sweep") + " (equal axes)",
        f"● first solved step,{gaps} ▸ direction of travel, + origin F = 0",
        _skipped_text(series),
    ])
    return fig


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


# ------------------------------------------------------------ shaking moment curve


def _moment_label(s: _Series, zero: bool, driver_kind: str, in_zoom: bool) -> str:
    pk = s.peak()
    if pk is None:
        return f"{s.label}: no solved step{_gap_note(s)}"
    peak, k = pk
    # over the cycle: a whole turn's repeated end point counted once (numeric.results.cycle_average)
    rms = float(cycle_rms(s.values, s.ok, whole_turns(s.q, driver_kind)))
    if zero:
        return (f"{s.label}: numerically zero (peak |M| = {style.fmt_number(peak)} N·m, "
                f"RMS {style.fmt_number(rms)} N·m){_gap_note(s)}")
    text = (f"{s.label}: peak |M| = {style.fmt_number(peak)} N·m at {_at(s, k, driver_kind)}, "
            f"RMS {style.fmt_number(rms)} N·m")
    if in_zoom:
        text += " (also in the zoom panel)"
    return text + _gap_note(s)


def _moment_curve(ax, x: np.ndarray, s: _Series, zero: bool, label) -> Line2D:
    """Draw one series' moment on ``ax``; return the artist that carries ``label``."""
    if zero:
        # a line on zero would vanish under the zero axis: mark it
        every = max(1, s.n // 18)
        (art,) = ax.plot(x, s.values, color=s.color, lw=2.2, ls="-", marker="D", ms=5,
                         mec="black", mew=0.6, markevery=every, label=label, zorder=4)
        return art
    (art,) = ax.plot(x, s.values, color=s.color, lw=1.8, ls=s.linestyle, label=label, zorder=3)
    pk = s.peak()
    if pk is not None:
        k = pk[1]
        ax.plot([x[k]], [s.values[k]], marker="o", ms=6, mfc="white", mec=s.color, mew=1.6,
                ls="none", zorder=5, clip_on=False)
    return art


def _common_status(series: list) -> np.ndarray | None:
    """One status per step when every series has the same driver steps, else None.

    A step is not ``ok`` when it is not ``ok`` in any series (the first such
    status is kept).
    """
    first = series[0]
    if any(s.n != first.n or not np.allclose(s.q, first.q, rtol=1e-9, atol=1e-12)
           for s in series):
        return None
    status = first.status.copy()
    for s in series[1:]:
        take = (status == _OK) & (s.status != _OK)
        status[take] = s.status[take]
    return status


def shaking_moment_figure(series_list, title: str | None = None, *, driver_kind: str = "R"):
    """Draw the shaking moment of every series against the driver; return the figure (not saved).

    The shaking moment about the global origin (N·m) against the first
    driver's coordinate (degrees for an ``R`` driver), every series on the
    same axes, a horizontal line at zero, each peak marked with an open
    circle.  The legend gives each series' label, peak ``|M|`` (with the
    driver angle) and RMS.

    A series whose peak is below ``SMALL_RATIO`` (20 %) of the largest is
    drawn again on a second panel, below the first and sharing its x axis,
    at its own y scale: the angles of its features can be read against the
    main panel directly, and, unlike an inset, the panel covers no part of
    the main curves.  A numerically zero series is a line on zero marked with
    diamonds (a plain line would vanish under the zero axis), labelled
    "numerically zero" with its peak value.  When every series has the same driver steps, the
    steps not ``ok`` in any series are also shaded (see
    :func:`~linkage_sym.plotting.style.shade_bad_steps`).

    Parameters
    ----------
    series_list : sequence of BalanceSeries
        Or one series.  Each has ``label``, ``q`` (N,), ``status`` (N,),
        ``moment`` (N,) in N·m.  Steps whose status is not ``ok`` are gaps.
    title : str, optional
        First line of the figure title; default "shaking moment about the
        global origin".
    driver_kind : {"R", "P"}, optional
        Kind of the driver ``q`` belongs to: ``R`` (radians, shown in degrees,
        the default) or ``P`` (metres).

    Returns
    -------
    matplotlib.figure.Figure
        ``fig.axes[0]`` the main panel (one labelled curve per series),
        ``fig.axes[1]`` the zoom panel if there is one; ``fig.legends[0]``
        the legend (one entry per series, then the shaded statuses).

    Raises
    ------
    ValueError
        If there is no series or a series' arrays do not match in length.
    """
    series = _series(series_list, "moment")
    zero, small, largest = _scales(series)
    with_zoom = any(small)
    fig = style.new_figure(10.5, 8.6 if with_zoom else 6.4)
    if with_zoom:
        ax, zax = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": (1.25, 1.0)})
    else:
        ax, zax = fig.add_subplot(1, 1, 1), None
    axes = [a for a in (ax, zax) if a is not None]

    handles = []
    xs = []
    for s, z, m in zip(series, zero, small):
        x = _x_axis(s.q, driver_kind, s.q_known)[0]
        xs.append(x)
        label = _moment_label(s, z, driver_kind, m)
        handles.append(_moment_curve(ax, x, s, z, label))
        if zax is not None and (m or z):
            _moment_curve(zax, x, s, z, None)
    _, xlabel, unit, _ = _x_axis(series[0].q, driver_kind, series[0].q_known)
    if not any(s.ok.any() for s in series):
        style.no_data_note(ax, "no solved step in any series")

    status = _common_status(series)
    band_handles = []
    if status is not None:
        band_handles = style.shade_bad_steps(axes, xs[0], status, label_ax=ax)
    allx = np.concatenate(xs)
    for a in axes:
        a.axhline(0.0, color="0.45", lw=0.8, zorder=0.5)
        a.grid(True, color="0.9", lw=0.6)
        a.set_ylabel("shaking moment M (N·m)")
        a.set_xlim(float(allx.min()), float(allx.max()))
        a.margins(x=0)
        _readable_ticks(a, "y")
    style.driver_ticks(axes[-1], allx, xlabel, unit)
    if zax is not None:
        ax.tick_params(labelbottom=True)
        zoom = _zoom_factor(series, small, largest)
        ax.set_title("all series, common scale", fontsize=10)
        zax.set_title(f"zoom ×{style.fmt_number(zoom)}: series below {SMALL_RATIO:.0%} of the largest "
                      "peak, own scale", fontsize=10)
        zax.set_ylabel("shaking moment M (N·m)\nzoomed")
        top = max(s.peak()[0] for s, m in zip(series, small) if m)
        zax.set_ylim(-1.15 * top, 1.15 * top)
    fig.legend(handles=handles + band_handles, loc="outside lower center", ncols=1, fontsize=9,
               frameon=False)
    _finish(fig, title or "shaking moment about the global origin", [
        "○ marks each series' peak |M|", _skipped_text(series)])
    return fig


def shaking_moment_curve(series_list, path, title: str | None = None, *,
                         driver_kind: str = "R") -> Path:
    """Write the shaking moment of every series against the driver as one PNG.

    See :func:`shaking_moment_figure` for what is drawn.

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
    return style.save(shaking_moment_figure(series_list, title, driver_kind=driver_kind), path)
