"""Shared look of every plot: colours, units, the shading of unsolved steps.

Nothing here computes kinematics; these helpers only choose how results are
shown (which unit a length is printed in, which colour a link has, where a
band of unsolved steps is drawn).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from matplotlib.transforms import blended_transform_factory

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.result import OK, SINGULAR, UNASSEMBLABLE

PALETTE = (
    "#1f77b4",
    "#d62728",
    "#2ca02c",
    "#9467bd",
    "#ff7f0e",
    "#8c564b",
    "#e377c2",
    "#17becf",
    "#bcbd22",
    "#7f7f7f",
)
"""Qualitative colours (Matplotlib's tab10, reordered so neighbours contrast)."""

BAND_STYLE = {
    UNASSEMBLABLE: {"facecolor": "0.82", "edgecolor": "none", "hatch": None},
    SINGULAR: {"facecolor": "0.90", "edgecolor": "0.6", "hatch": "///"},
}
"""How a run of steps of each non-``ok`` status is shaded."""

DPI = 120

LABEL_SIZE = 8.5
"""Font size (pt) of the written label of a band of unsolved steps."""


def new_figure(width: float, height: float) -> Figure:
    """A figure that needs neither pyplot nor a backend switch.

    Parameters
    ----------
    width, height : float
        Size in inches.

    Returns
    -------
    matplotlib.figure.Figure
        Saved with :meth:`~matplotlib.figure.Figure.savefig` through the Agg
        canvas Matplotlib picks for PNG files.
    """
    return Figure(figsize=(width, height), dpi=DPI, layout="constrained")


def save(fig: Figure, path) -> Path:
    """Write ``fig`` as a PNG at ``path`` (its folder created) and return the path.

    The one place every plot is written, at :data:`DPI`.
    """
    path = Path(path)
    ensure_dir(path.parent)
    fig.savefig(path, dpi=DPI)
    return path


def link_colors(scene: Scene) -> dict:
    """Colour of every moving link, by name, in scene order."""
    return {name: PALETTE[i % len(PALETTE)] for i, name in enumerate(scene.link_names)}


def joint_colors(scene: Scene) -> dict:
    """Colour of every joint, by name: the colour of the link its point is fixed on.

    A joint whose ``links[1]`` is the ground takes the colour of ``links[0]``.
    Joints sharing a link are told apart by line style (see :func:`joint_style`).
    """
    lc = link_colors(scene)
    out = {}
    for joint in scene.joints:
        on = joint.links[1] if joint.links[1] != GROUND else joint.links[0]
        out[joint.name] = lc.get(on, "0.3")
    return out


def length_unit(scene: Scene) -> tuple[str, float]:
    """Unit lengths are printed in: ``("mm", 1000.0)`` below 1 m, else ``("m", 1.0)``.

    The choice follows the scene's characteristic length (largest distance
    between two joints of the assembly configuration), so one scene is always
    drawn in one unit.

    Examples
    --------
    >>> from linkage_sym.model import Driver, Joint, Link, Scene
    >>> s = Scene("s", (Link("a"),), (Joint("A", "R", ("ground", "a"), (0.0, 0.0)),
    ...           Joint("B", "R", ("a", "ground"), (0.1, 0.0))),
    ...           (Driver("A", "R", 0.0, 1.0, 2, 1.0, toward="B"),))
    >>> length_unit(s)
    ('mm', 1000.0)
    """
    return ("mm", 1000.0) if scene.characteristic_length() < 1.0 else ("m", 1.0)


def safe_stem(text) -> str:
    r"""``text`` made safe as part of a file name on any system: path separators, characters
    Windows refuses, white space and control characters (a NUL ends a path) become ``_``.

    Examples
    --------
    >>> safe_stem("a/b\\c\n..\x00z"), safe_stem(" "), safe_stem("crank-rocker")
    ('a_b_c_.._z', 'scene', 'crank-rocker')
    """
    stem = re.sub(r"[\\/:*?\"<>|\s\x00-\x1f\x7f]+", "_", str(text)).strip("_")
    return stem or "scene"


def file_stem(scene: Scene, prefix: str | None) -> str:
    """File-name stem: ``prefix`` or the scene name, made safe for a path (:func:`safe_stem`)."""
    return safe_stem(prefix if prefix is not None else scene.name)


def ensure_dir(path) -> Path:
    """Create ``path`` (and its parents) if needed; return it as a Path."""
    p = Path(path)
    p.mkdir(parents=True, exist_ok=True)
    return p


def status_runs(status) -> list:
    """Runs of consecutive steps of one non-``ok`` status.

    Returns
    -------
    list of (str, int, int)
        ``(status, first, last)`` with inclusive step indices.

    Examples
    --------
    >>> status_runs(["ok", "singular", "unassemblable", "unassemblable", "ok"])
    [('singular', 1, 1), ('unassemblable', 2, 3)]
    """
    runs = []
    for i, st in enumerate(status):
        st = str(st)
        if st == OK:
            continue
        if runs and runs[-1][0] == st and runs[-1][2] == i - 1:
            runs[-1] = (st, runs[-1][1], i)
        else:
            runs.append((st, i, i))
    return runs


def shade_bad_steps(axes, x, status, *, label_ax=None) -> list:
    """Shade the runs of non-``ok`` steps with light grey bands.

    A band reaches half a step either side of its run, so a single bad step
    between two good ones is visible as a gap in every curve *and* a band.

    Parameters
    ----------
    axes : sequence of matplotlib.axes.Axes
        Every axis sharing the x coordinate.
    x : ndarray, shape (N,)
        The x value of each step (finite).
    status : sequence of str, shape (N,)
        Step status from :attr:`Analysis.status`.
    label_ax : matplotlib.axes.Axes, optional
        Axis on which each band gets a small written label (its status).

    Returns
    -------
    list of matplotlib.patches.Patch
        One legend handle per status that was shaded.
    """
    x = np.asarray(x, dtype=float)
    n = len(x)
    if n == 0:
        return []
    steps = np.diff(x)
    half = 0.5 * (float(np.median(np.abs(steps))) if n > 1 else 1.0)
    sign = 1.0 if n < 2 or x[-1] >= x[0] else -1.0
    seen = {}
    for st, first, last in status_runs(status):
        lo = x[first] - sign * half
        hi = x[last] + sign * half
        lo, hi = min(lo, hi), max(lo, hi)
        style = BAND_STYLE.get(st, BAND_STYLE[UNASSEMBLABLE])
        for ax in axes:
            ax.axvspan(lo, hi, zorder=0, linewidth=0.5, **style)
        if label_ax is not None:
            # dark text on a white box above the grid: legible on the grey band; across a
            # band wide enough for it, else along it
            tr = blended_transform_factory(label_ax.transData, label_ax.transAxes)
            wide = (hi - lo) >= 0.15 * max(float(np.ptp(x)), 1e-300)
            label_ax.text(
                0.5 * (lo + hi), 0.97, st, transform=tr, rotation=0 if wide else 90,
                ha="center", va="top", fontsize=LABEL_SIZE, color="0.1", clip_on=True,
                zorder=5, bbox={"boxstyle": "round,pad=0.2", "facecolor": "white",
                                "edgecolor": "none", "alpha": 0.9},
            )
        seen.setdefault(st, Patch(label=f"{st} step", **style))
    return list(seen.values())


def fmt_number(value: float) -> str:
    """A number with 3 significant digits, no exponent for ordinary magnitudes."""
    if value == 0.0 or 1e-3 <= abs(value) < 1e5:
        return f"{value:.3g}"
    return f"{value:.2e}"


def no_data_note(ax, text: str) -> None:
    """A boxed note in the middle of an axes that has nothing to plot."""
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, color="0.3",
            fontsize=9, zorder=10,
            bbox={"boxstyle": "round,pad=0.3", "facecolor": "white", "edgecolor": "0.7"})


def driver_ticks(ax, x, xlabel, unit):
    """Label the driver axis; in degrees, ticks every 15..180 deg (at most 13 of them)."""
    from matplotlib.ticker import MultipleLocator

    ax.set_xlabel(xlabel)
    if unit == "deg":
        span = float(np.max(x) - np.min(x))
        for step in (15.0, 30.0, 45.0, 60.0, 90.0, 180.0):
            if span / step <= 13:
                ax.xaxis.set_major_locator(MultipleLocator(step))
                break
