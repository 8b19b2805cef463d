"""Pictures of function and path generation: the structural error, the coupler curves.

Only numbers the caller measured are drawn (the solver's); nothing is solved here.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from linkage_sym.plotting import style


def structural_error_figure(x, error_deg, x_points, title: str):
    """The structural error (deg) against ``x``, the precision points marked.

    Examples
    --------
    >>> import numpy as np
    >>> fig = structural_error_figure(np.linspace(1, 10, 5), np.zeros(5), [2.0, 5.5, 9.0], "f")
    >>> fig.axes[0].get_ylabel()
    'structural error (deg)'
    """
    fig = style.new_figure(8.0, 4.2)
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(x, error_deg, color="tab:blue", lw=1.6, label="linkage minus function (solver)")
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.plot(x_points, np.zeros(len(x_points)), "o", color="tab:red", label="precision points")
    ax.set_xlabel("x")
    ax.set_ylabel("structural error (deg)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return fig


def coupler_curves_figure(targets, designs, title: str):
    """Each design's coupler curve (full turn dotted, first to last target solid) and linkage
    at the first target, with the targets.

    ``designs``: ``(label, curve_full (k, 2), curve_motion (m, 2), joints {A, B, C, D, P})``;
    a slider-crank's joints ``{A, B, C, P, guide}`` (``guide``: the guide's unit direction,
    drawn dashed through ``C`` over the span of the curves).
    """
    fig = style.new_figure(7.5, 7.0)
    ax = fig.add_subplot(1, 1, 1)
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink"]
    for k, (label, full, motion, J) in enumerate(designs):
        c = colors[k % len(colors)]
        ax.plot(full[:, 0], full[:, 1], ":", color=c, lw=0.9)
        ax.plot(motion[:, 0], motion[:, 1], "-", color=c, lw=1.8, label=label)
        if k == 0:
            _linkage(ax, J, full)
    T = np.asarray(targets)
    ax.plot(T[:, 0], T[:, 1], "x", color="tab:red", ms=10, mew=2, label="targets")
    for i, (x, y) in enumerate(T):
        ax.annotate(str(i + 1), (x, y), textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return fig


def _linkage(ax, J, curve):
    """The linkage at the first target: a four-bar's bars, or a slider-crank's and its guide."""
    bars = (("A", "B"), ("B", "C"), ("C", "D"), ("B", "P"), ("C", "P"))
    for a, b in (bars if "D" in J else bars[:2] + bars[3:]):
        ax.plot([J[a][0], J[b][0]], [J[a][1], J[b][1]], "-", color="0.25", lw=1.4)
    for n in ("A", "D") if "D" in J else ("A",):
        ax.plot(*J[n], "^", color="0.2", ms=9)
    if "guide" in J:
        pts = np.array([J[n] for n in ("A", "B", "C", "P")] + [p for p in curve if np.isfinite(p).all()])
        u = np.asarray(J["guide"])
        s = (pts - np.asarray(J["C"])) @ u
        line = np.asarray(J["C"]) + np.outer([s.min(), s.max()], u)
        ax.plot(line[:, 0], line[:, 1], "--", color="0.2", lw=1.0, label="slider's guide")
        ax.plot(*J["C"], "s", color="0.2", ms=9, mfc="none", mew=1.5)


def save(fig, path) -> Path:
    """Write the figure (PNG, SVG or PDF by the suffix)."""
    return style.save(fig, path)
