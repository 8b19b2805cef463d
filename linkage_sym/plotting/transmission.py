"""Transmission angles against the driver, the minimum marked.

One figure: the transmission angle of every RRR dyad
(:attr:`Analysis.transmission_angles <linkage_sym.numeric.results.result.Analysis.transmission_angles>`,
the angle between the dyad's two links at its inner joint, 0..180 degrees)
against the first driver's coordinate, with 90 degrees (the best) and the
minimum of ``min(gamma, 180 - gamma)`` -- the *minimum transmission angle* of
the four-bar design chapter of the textbook (*Design of four-bar mechanisms*,
Sources [2] of the README) -- drawn dotted for each dyad, its minimum marked on
that curve (where the value is read: a dyad at 132 degrees is 48 degrees from
folding).  Steps that are not
``ok`` break the curves and are shaded.

This module only draws results; it solves nothing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.numeric.results.result import Analysis
from linkage_sym.plotting import style
from linkage_sym.plotting.motion import driver_axis


def minimum(gamma) -> tuple[int, float] | None:
    """``(step, value)`` of the smallest ``min(gamma, pi - gamma)`` (rad), or None if no step has one.

    Examples
    --------
    >>> minimum(np.radians([80.0, 150.0, np.nan, 100.0]))
    (1, 0.5235987755982987)
    """
    g = np.asarray(gamma, dtype=float)
    dev = np.minimum(g, np.pi - g)
    good = np.isfinite(dev)
    if not good.any():
        return None
    k = int(np.argmin(np.where(good, dev, np.inf)))
    return k, float(dev[k])


def transmission_figure(scene: Scene, analysis: Analysis):
    """Draw the transmission angles against the driver and return the figure (not saved).

    Raises
    ------
    ValueError
        If the analysis has no transmission angles (no RRR dyad).

    Examples
    --------
    >>> import linkage_sym
    >>> scene = linkage_sym.load_example("watt_sixbar")
    >>> fig = transmission_figure(scene, linkage_sym.analyze(scene))
    >>> [line.get_label() for line in fig.axes[0].get_lines() if line.get_label().startswith("γ")]
    ['γ at C', 'γ at E']
    """
    angles = analysis.transmission_angles
    if not angles:
        raise ValueError(f"analysis of {analysis.scene!r} has no transmission angles (no RRR dyad)")
    x, xlabel, xunit = driver_axis(scene, analysis)
    fig = style.new_figure(9.5, 4.8)
    ax = fig.subplots()
    ax.axhline(90.0, color="0.45", lw=0.8, zorder=0.5)
    for k, (joint, gamma) in enumerate(angles.items()):
        col = style.PALETTE[k % len(style.PALETTE)]
        deg = np.degrees(np.asarray(gamma, dtype=float))
        # min(gamma, 180 - gamma), drawn where it is not gamma itself (gamma above 90 degrees)
        folded = np.where(deg > 90.0, 180.0 - deg, np.nan)
        m = minimum(gamma)
        ax.plot(x, deg, color=col, lw=1.8, ls=("-", "--", "-.", ":")[k % 4], label=f"γ at {joint}")
        if m is None:
            ax.plot([], [], color=col, lw=0.9, ls=":",
                    label=f"min(γ, 180° − γ) at {joint}: no step with positions")
            continue
        step, value = m
        at_deg, at_x = float(np.degrees(value)), float(x[step])
        # the minimum is a value of min(gamma, 180 - gamma): drawn on that curve, where it is read
        ax.plot(x, folded, color=col, lw=0.9, ls=":",
                label=f"min(γ, 180° − γ) at {joint}\n  minimum {style.fmt_number(at_deg)}° at "
                      f"{style.fmt_number(at_x)} {xunit}")
        if abs(deg[step] - at_deg) > 1e-9 * 180.0:  # gamma > 90 there: its reflection, joined
            ax.plot([at_x, at_x], [deg[step], at_deg], color=col, lw=0.8, ls=(0, (1, 2)),
                    zorder=2, label="_reflection")
        ax.plot([at_x], [at_deg], marker="o", ms=7, mfc="white", mec=col, mew=1.8,
                ls="none", zorder=3, clip_on=False, label="_minimum")
        right = at_x <= 0.5 * (float(np.min(x)) + float(np.max(x)))  # the text toward the middle
        ax.annotate(f"{style.fmt_number(at_deg)}°", (at_x, at_deg), xytext=(9 if right else -9, 0),
                    textcoords="offset points", ha="left" if right else "right", va="center",
                    fontsize=9, color=col,
                    zorder=4, bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                                    "alpha": 0.8})
    ax.set_ylim(0.0, 180.0)
    ax.set_yticks(range(0, 181, 30))
    ax.set_ylabel("transmission angle γ (deg)")
    band_handles = style.shade_bad_steps([ax], x, analysis.status, label_ax=ax)
    style.driver_ticks(ax, x, xlabel, xunit)
    ax.grid(True, color="0.9", lw=0.6)
    ax.set_xlim(float(np.min(x)), float(np.max(x)))
    ax.margins(x=0)
    ax.legend(handles=ax.get_legend_handles_labels()[0] + band_handles, loc="upper left",
              bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    fig.suptitle(f"{scene.name}: transmission angles of the RRR dyads\n○ marks the minimum "
                 "transmission angle min(γ, 180° − γ) (dotted where γ > 90°); 90° is best",
                 fontsize=11)
    return fig


def transmission_angles(scene: Scene, analysis: Analysis, path) -> Path:
    """Write the transmission angle of every RRR dyad against the first driver.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.transmission_angles`.
    path : str or os.PathLike
        PNG file to write; its folder is created if needed.

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib, linkage_sym
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "t.png"
    >>> transmission_angles(scene, linkage_sym.analyze(scene), out).read_bytes()[:4]
    b'\x89PNG'
    """
    return style.save(transmission_figure(scene, analysis), path)
