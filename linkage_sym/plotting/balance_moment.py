"""The shaking moment curve of the balancing plots (see :mod:`linkage_sym.plotting.balance`).

The shaking moment about the global origin against the first driver's
coordinate, every series on the same axes, each peak marked, the steps not
``ok`` in any series shaded, and a zoom panel below for the series much
smaller than the largest.

Examples
--------
>>> import numpy as np
>>> from types import SimpleNamespace
>>> q = np.linspace(0.0, 2 * np.pi, 73)
>>> s = SimpleNamespace(label="s", q=q, status=np.full(73, "ok"),
...                     force=np.zeros((73, 2)), moment=0.1 * np.sin(2 * q))
>>> fig = shaking_moment_figure([s])
>>> fig.axes[0].get_ylabel()
'shaking moment M (N·m)'
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D

from linkage_sym.numeric.results.cycle_average import cycle_rms, whole_turns
from linkage_sym.plotting import style
from linkage_sym.plotting.balance_series import (
    OK_STATUS,
    SMALL_RATIO,
    Series,
    at_text,
    finish,
    gap_note,
    read_series,
    readable_ticks,
    scales,
    skipped_text,
    x_axis,
    zoom_factor,
)

__all__ = ["shaking_moment_curve", "shaking_moment_figure"]


def _moment_label(s: Series, zero: bool, driver_kind: str, in_zoom: bool) -> str:
    pk = s.peak()
    if pk is None:
        return f"{s.label}: no solved step{gap_note(s)}"
    peak, k = pk
    # over the cycle: a whole turn's repeated end point counted once (numeric.results.cycle_average)
    rms = float(cycle_rms(s.values, s.ok, whole_turns(s.q, driver_kind)))
    if zero:
        return (f"{s.label}: numerically zero (peak |M| = {style.fmt_number(peak)} N·m, "
                f"RMS {style.fmt_number(rms)} N·m){gap_note(s)}")
    text = (f"{s.label}: peak |M| = {style.fmt_number(peak)} N·m at {at_text(s, k, driver_kind)}, "
            f"RMS {style.fmt_number(rms)} N·m")
    if in_zoom:
        text += " (also in the zoom panel)"
    return text + gap_note(s)


def _moment_curve(ax, x: np.ndarray, s: Series, zero: bool, label) -> Line2D:
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
        take = (status == OK_STATUS) & (s.status != OK_STATUS)
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
    series = read_series(series_list, "moment")
    zero, small, largest = scales(series)
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
        x = x_axis(s.q, driver_kind, s.q_known)[0]
        xs.append(x)
        label = _moment_label(s, z, driver_kind, m)
        handles.append(_moment_curve(ax, x, s, z, label))
        if zax is not None and (m or z):
            _moment_curve(zax, x, s, z, None)
    _, xlabel, unit, _ = x_axis(series[0].q, driver_kind, series[0].q_known)
    if not any(s.ok.any() for s in series):
        style.no_data_note(ax, "no solved step in any series")

    status = _common_status(series)
    band_handles = []
    if status is not None:
        band_handles = style.shade_bad_steps(axes, xs[0], status, label_ax=ax)
    _moment_axes(axes, np.concatenate(xs), xlabel, unit)
    if zax is not None:
        _moment_zoom_panel(ax, zax, series, small, largest)
    fig.legend(handles=handles + band_handles, loc="outside lower center", ncols=1, fontsize=9,
               frameon=False)
    finish(fig, title or "shaking moment about the global origin", [
        "○ marks each series' peak |M|", skipped_text(series)])
    return fig


def _moment_axes(axes: list, allx: np.ndarray, xlabel: str, unit: str) -> None:
    """Both panels' zero line, grid, y label and limits; the driver ticks on the lowest."""
    for a in axes:
        a.axhline(0.0, color="0.45", lw=0.8, zorder=0.5)
        a.grid(True, color="0.9", lw=0.6)
        a.set_ylabel("shaking moment M (N·m)")
        a.set_xlim(float(allx.min()), float(allx.max()))
        a.margins(x=0)
        readable_ticks(a, "y")
    style.driver_ticks(axes[-1], allx, xlabel, unit)


def _moment_zoom_panel(ax, zax, series: list, small: list, largest: float) -> None:
    """The zoom panel ``zax`` of the small series, at their own y scale below ``ax``."""
    ax.tick_params(labelbottom=True)
    zoom = zoom_factor(series, small, largest)
    ax.set_title("all series, common scale", fontsize=10)
    zax.set_title(f"zoom ×{style.fmt_number(zoom)}: series below {SMALL_RATIO:.0%} of the largest "
                  "peak, own scale", fontsize=10)
    zax.set_ylabel("shaking moment M (N·m)\nzoomed")
    top = max(s.peak()[0] for s, m in zip(series, small) if m)
    zax.set_ylim(-1.15 * top, 1.15 * top)


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
