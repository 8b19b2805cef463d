"""Force plots: driving effort, joint-reaction hodographs and frame loads.

Three figures of a force analysis:

* the *driving effort* (torque of an ``R`` driver, axial force of a ``P``
  driver) against the first driver's coordinate;
* the *hodograph* of every joint reaction: the tip of the reaction vector
  over the cycle on a polar plot (angle = direction of the force from the
  global x axis, radius = its magnitude);
* the *frame loads*: hodograph of the force the moving links exert on the
  ground, and its moment about the global origin against the driver.  When
  inertia is the only effect of the scene these are the *shaking force* and
  *shaking moment* and are labelled so.

This module only draws results: it reads
:attr:`Analysis.forces <linkage_sym.numeric.results.result.Analysis.forces>` (a
:class:`~linkage_sym.numeric.results.result.Forces`) and never solves anything.
Steps that are not ``ok`` are NaN in the results: they break the curves, and
on plots against the driver they are also shaded and labelled.  A passage of a joint through
infinity between two steps breaks every curve whose force it makes unbounded there
(:mod:`linkage_sym.plotting.force_breaks`), and is marked and said.
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.numeric.results.cycle_average import cycle_rms, whole_period
from linkage_sym.numeric.results.result import Analysis
from linkage_sym.plotting import style
from linkage_sym.plotting.breaks import gap_label, mark_passages, with_breaks
from linkage_sym.plotting.force_breaks import effort_gaps, frame_gaps, reaction_gaps
from linkage_sym.plotting.motion import driver_axis

_TORQUE = "N·m"
_FORCE = "N"


# --------------------------------------------------------------------------- helpers


def inertia_only(scene: Scene) -> bool:
    """Whether inertia is the only effect of ``scene`` (frame loads are then *shaking* loads).

    True when ``scene.effects.inertia`` is set, there is no gravity and no
    external load acts (loads switched off, or none given).

    Examples
    --------
    >>> from linkage_sym.model import Effects, Scene
    >>> s = Scene("s", (), (), (), effects=Effects(inertia=True, gravity=None))
    >>> inertia_only(s)
    True
    """
    eff = scene.effects
    return bool(eff.inertia) and eff.gravity is None and (not eff.loads or not scene.loads)


def frame_words(scene: Scene) -> tuple[str, str]:
    """Names of the frame force and moment: ``("shaking force", "shaking moment")``
    under inertia only (see :func:`inertia_only`), else ``("frame force", "frame moment")``."""
    word = "shaking" if inertia_only(scene) else "frame"
    return f"{word} force", f"{word} moment"


def _finite(values) -> np.ndarray:
    v = np.asarray(values, dtype=float)
    return v[np.isfinite(v)]


def _stats(values, periodic: bool) -> tuple[float, float, int] | None:
    """``(rms, signed peak, step of the peak)`` over the finite values, or None; the RMS
    over the cycle (``periodic``: the sweep is a whole period, its repeated end point
    counted once, :mod:`linkage_sym.numeric.results.cycle_average`)."""
    v = np.asarray(values, dtype=float)
    good = np.isfinite(v)
    if not good.any():
        return None
    rms = float(cycle_rms(v, good, periodic))
    k = int(np.nanargmax(np.where(good, np.abs(v), -np.inf)))
    return rms, float(v[k]), k






def _bad_note(analysis: Analysis) -> str:
    bad = int(analysis.n_steps - np.count_nonzero(analysis.ok))
    if bad == 0:
        return ""
    return f"{bad} of {analysis.n_steps} steps not ok: gaps in the curves"


def _passages_note(analysis: Analysis) -> str:
    """What the passages through infinity and the Newton groups' jumps do to the
    hodographs, or ``""``."""
    words = [f"joint {p.joint} through infinity between steps {p.before} and {p.after}"
             for p in analysis.passages if p.before is not None]
    groups: dict = {}
    for j in analysis.jumps:
        if j.before is not None:
            groups.setdefault(j.group.split(" (")[0], []).append(f"{j.before} and {j.after}")
    jumps = [f"{g} jumps assembly mode between steps {', '.join(k)}" for g, k in groups.items()]
    out = [f"{'; '.join(words)}: the reactions it makes unbounded are not joined there"] if words else []
    out += [f"{'; '.join(jumps)}: the reactions it moves are not joined there"] if jumps else []
    return "\n".join(textwrap.fill(line, 100) for line in out)


def _forces_or_raise(analysis: Analysis):
    if analysis.forces is None:
        raise ValueError(
            f"analysis of {analysis.scene!r} has no forces (the forces stage did not run)"
        )
    return analysis.forces


def _cyclic(scene: Scene) -> bool:
    """Whether the first driver sweeps a whole number of turns (the last step closes the cycle)."""
    drv = scene.drivers[0]
    if drv.kind != "R" or drv.steps < 3:
        return False
    span = abs(drv.stop - drv.start)
    turns = round(span / (2 * math.pi))
    step = span / (drv.steps - 1)
    return turns >= 1 and abs(span - 2 * math.pi * turns) <= 1.5 * step


# ----------------------------------------------------------------- driving effort


def _driver_order(scene: Scene, driving: dict) -> list:
    names = [d.joint for d in scene.drivers if d.joint in driving]
    return names + [n for n in driving if n not in names]


def _effort_kind(scene: Scene, name: str) -> str:
    try:
        return scene.joint(name).type
    except KeyError:
        for drv in scene.drivers:
            if drv.joint == name:
                return drv.kind
    return "R"


def driving_effort_figure(scene: Scene, analysis: Analysis):
    """Draw the driving effort against the first driver and return the figure (not saved).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.forces` set.

    Returns
    -------
    matplotlib.figure.Figure
        One panel of torques (N·m) and/or one of forces (N), sharing the x axis.

    Raises
    ------
    ValueError
        If the analysis has no forces.
    """
    forces = _forces_or_raise(analysis)
    x, xlabel, xunit = driver_axis(scene, analysis)
    names = _driver_order(scene, forces.driving)
    kinds = {n: _effort_kind(scene, n) for n in names}
    groups = [k for k in ("R", "P") if any(v == k for v in kinds.values())] or ["R"]
    fig = style.new_figure(9.5, 7.2 if len(groups) == 2 else 4.8)
    axes = fig.subplots(len(groups), 1, sharex=True, squeeze=False)[:, 0]

    for ax, kind in zip(axes, groups):
        unit, sym, word = (_TORQUE, "T", "torque") if kind == "R" else (_FORCE, "F", "force")
        ax.set_ylabel(f"driving {word} {sym} ({unit})")
        ax.axhline(0.0, color="0.45", lw=0.8, zorder=0.5)
        mine = [n for n in names if kinds[n] == kind]
        for name in mine:
            values = np.asarray(forces.driving[name], dtype=float)
            col = style.PALETTE[names.index(name) % len(style.PALETTE)]
            try:
                on = scene.joint(name).links
                between = f" ({on[0]} on {on[1]})"
            except KeyError:
                between = ""
            st = _stats(values, whole_period(scene))
            if st is None:
                label = f"{sym} at {name}{between}: no solved step"
            else:
                rms, peak, k = st
                label = (f"{sym} at {name}{between}\n  RMS {style.fmt_number(rms)} {unit}, "
                         f"peak {style.fmt_number(peak)} {unit} at {style.fmt_number(float(x[k]))} {xunit}")
            ls = ("-", "--", "-.", ":")[mine.index(name) % 4]  # equal efforts stay visible
            gaps = effort_gaps(analysis, scene, name)  # unbounded at a passage: not joined
            ax.plot(*with_breaks(gaps, x, values), color=col, lw=1.8, ls=ls,
                    label=gap_label(label, gaps, ",\n  "))
            if st is not None:
                ax.plot([x[st[2]]], [st[1]], marker="o", ms=6, mfc="white", mec=col,
                        mew=1.6, ls="none", zorder=3, clip_on=False)
        if not any(_finite(forces.driving[n]).size for n in mine):
            style.no_data_note(ax, "no driving effort: no solved step" if mine
                     else "no driver effort in this analysis")

    band_handles = style.shade_bad_steps(axes, x, analysis.status, label_ax=axes[0])
    band_handles += mark_passages(axes, x, analysis)
    style.driver_ticks(axes[-1], x, xlabel, xunit)
    for ax in axes:
        ax.grid(True, color="0.9", lw=0.6)
        ax.set_xlim(float(np.min(x)), float(np.max(x)))
        ax.margins(x=0)
        handles = ax.get_legend_handles_labels()[0]
        if ax is axes[0]:
            handles = handles + band_handles
        if handles:
            ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                      fontsize=8, frameon=False)
    sub = "○ marks the peak; the effort is applied by the driven joint's links[0] on its links[1]"
    fig.suptitle(f"{scene.name}: driving effort against the driver\n{sub}", fontsize=11)
    return fig


def driving_effort(scene: Scene, analysis: Analysis, path) -> Path:
    """Write the driving effort of every driver against the first driver's coordinate.

    Torques of ``R`` drivers (N·m) and axial forces of ``P`` drivers (N) are
    drawn on separate panels when both kinds exist.  The legend gives each
    effort's RMS and its peak (largest magnitude, with sign), which is also
    marked on the curve; a horizontal line marks zero.  The x axis is the
    first driver's coordinate (degrees for an ``R`` driver).  Steps that are
    not ``ok`` break the curves and are shaded.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.forces` set.
    path : str or os.PathLike
        PNG file to write; its folder is created if needed.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return style.save(driving_effort_figure(scene, analysis), path)


# --------------------------------------------------------------------- hodographs


def _grid(n: int) -> tuple[int, int]:
    """``(rows, cols)`` of a grid of ``n`` panels, at most 4 columns, few empty cells."""
    if n <= 4:
        return 1, max(n, 1)
    cols = min((3, 4), key=lambda c: (-(-n // c) * c - n, -c))
    return -(-n // cols), cols


def hodograph(ax, vectors, *, color="C0", closed=False, label=None, gaps=()) -> float | None:
    """Draw the hodograph of a force vector on a polar axis.

    The angle is the direction of the force from the global x axis, the
    radius its magnitude.  Non-finite steps break the curve; the first solved
    step is marked with a filled circle, and arrow heads at a quarter, half
    and three quarters of the solved steps show the direction of travel.

    Parameters
    ----------
    ax : matplotlib.projections.polar.PolarAxes
    vectors : ndarray, shape (N, 2)
        The force at every step (N).
    color : color
    closed : bool
        Join the last step to the first (the sweep is a whole cycle).
    label : str, optional
        Legend label of the curve.
    gaps : tuple of int, optional
        Steps after which the curve breaks though both ends are finite: a passage through
        infinity lies between them and the next
        (:func:`~linkage_sym.plotting.force_breaks.reaction_gaps`).

    Returns
    -------
    float or None
        The peak magnitude, or None when no step is finite (the axis then
        carries a note instead of a curve).
    """
    from matplotlib.ticker import MaxNLocator

    ax.tick_params(axis="y", labelsize=7, labelcolor="0.35")
    ax.tick_params(axis="x", labelsize=7, pad=1)
    ax.grid(True, color="0.85", lw=0.6)
    v = with_breaks(gaps, np.asarray(vectors, dtype=float).reshape(-1, 2))[0]
    good = np.all(np.isfinite(v), axis=1)
    if not good.any():
        ax.set_rmax(1.0)
        ax.set_yticklabels([])
        style.no_data_note(ax, "no solved step")
        return None
    mag = np.hypot(v[:, 0], v[:, 1])
    ang = np.arctan2(v[:, 1], v[:, 0])
    mag[~good] = np.nan
    ang[~good] = np.nan
    t, r = ang, mag
    if closed and good[0] and good[-1] and len(v) > 2:
        t, r = np.append(t, t[0]), np.append(r, r[0])
    ax.plot(t, r, color=color, lw=1.6, label=label, zorder=3)
    idx = np.flatnonzero(good)
    ax.plot([ang[idx[0]]], [mag[idx[0]]], marker="o", ms=6, color=color, mec="black",
            mew=0.8, ls="none", zorder=5)
    # arrow heads along the curve, from one solved step to the next solved one
    for frac in (0.25, 0.5, 0.75):
        k = int(frac * (len(v) - 1))
        a = next((i for i in range(k, len(v) - 1) if good[i] and good[i + 1]
                  and np.hypot(*(v[i + 1] - v[i])) > 1e-12 * max(np.nanmax(mag), 1e-300)), None)
        if a is None:
            continue
        ax.annotate("", xy=(ang[a + 1], mag[a + 1]), xytext=(ang[a], mag[a]),
                    arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.2,
                                "mutation_scale": 14, "shrinkA": 0, "shrinkB": 0},
                    zorder=6)
    peak = float(np.nanmax(mag))
    ax.set_rlim(0.0, peak * 1.12 if peak > 0 else 1.0)
    ax.yaxis.set_major_locator(MaxNLocator(4))
    ax.set_rlabel_position(112.5)
    return peak


def _legend_handles(color="0.3"):
    from matplotlib.lines import Line2D

    return [
        Line2D([], [], marker="o", ms=6, color=color, mec="black", mew=0.8, ls="none",
               label="first solved step"),
        Line2D([], [], marker=r"$\rightarrow$", ms=12, color=color, ls="none",
               label="direction of travel"),
    ]


def reaction_hodographs_figure(scene: Scene, analysis: Analysis, joints=None):
    """Draw the hodograph of every joint reaction and return the figure (not saved).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.forces` set.
    joints : sequence of str, optional
        Joints to draw, in this order; default every joint with a reaction,
        in scene order.

    Returns
    -------
    matplotlib.figure.Figure
        One polar axis per joint.

    Raises
    ------
    ValueError
        If the analysis has no forces, or a requested joint has no reaction.
    """
    forces = _forces_or_raise(analysis)
    if joints is None:
        names = [j.name for j in scene.joints if j.name in forces.reactions]
        names += [n for n in forces.reactions if n not in names]
    else:
        names = [str(n) for n in joints]
        missing = [n for n in names if n not in forces.reactions]
        if missing:
            raise ValueError(f"no reaction for joint(s) {missing} in this analysis")
    by_name = {j.name: j for j in scene.joints}
    rows, cols = _grid(len(names))
    fig = style.new_figure(max(3.3 * cols, 6.4), 3.45 * rows + 1.0)
    closed = _cyclic(scene)
    jcolors = style.joint_colors(scene)
    if not names:
        ax = fig.add_subplot(1, 1, 1, projection="polar")
        hodograph(ax, np.full((1, 2), np.nan))
        ax.texts[-1].set_text("no joint reactions in this analysis")
    for i, name in enumerate(names):
        ax = fig.add_subplot(rows, cols, i + 1, projection="polar")
        joint = by_name.get(name)
        gaps = reaction_gaps(analysis, scene, name)
        peak = hodograph(ax, forces.reactions[name], color=jcolors.get(name, "C0"),
                         closed=closed, gaps=gaps)
        if joint is not None:
            kind = ", normal to the slide" if joint.type == "P" else ""
            head = f"{name}: {joint.links[0]} on {joint.links[1]}{kind}"
        else:
            head = name
        tail = f"peak |R| = {style.fmt_number(peak)} N" if peak is not None else "no solved step"
        tail = gap_label(tail, gaps, ",\n")
        if joint is not None and joint.type == "P" and name in forces.reaction_moments:
            st = _stats(forces.reaction_moments[name], whole_period(scene))
            if st is not None:
                tail += f", |M| ≤ {style.fmt_number(abs(st[1]))} N·m"
        ax.set_title(f"{head}\n{tail}", fontsize=9, pad=10)
    span = "cycle" if closed else "sweep"
    lines = [f"{scene.name}: joint reaction hodographs over the {span}",
             "reaction R = force of a joint's links[0] on its links[1]",
             "angle: direction from global +x, radius: |R| (N)", _bad_note(analysis)]
    lines = [line for line in lines if line]
    if cols >= 3:  # wide enough for two lines
        lines = [lines[0], "; ".join(lines[1:])]
    lines += [note] if (note := _passages_note(analysis)) else []
    fig.suptitle("\n".join(lines), fontsize=11)
    fig.legend(handles=_legend_handles(), loc="outside lower center", ncols=2, fontsize=8,
               frameon=False)
    # A polar axis places its title above the angle labels only when drawn:
    # one draw first lets the layout of the saved figure see where it is.
    fig.draw_without_rendering()
    return fig


def reaction_hodographs(scene: Scene, analysis: Analysis, path, joints=None) -> Path:
    """Write polar hodographs of the joint reactions over the cycle.

    One polar panel per joint, in a grid of at most four columns: the angle is
    the direction of the reaction (the force the joint's ``links[0]`` exerts
    on its ``links[1]``) from the global x axis, the radius its magnitude in N.
    The curve is closed when the first driver sweeps whole turns; the first
    solved step is marked with a dot and arrow heads show the direction of
    travel.  Each panel's title gives the joint, its two links and the peak
    magnitude.  Steps that are not ``ok`` are gaps in the curves.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.forces` set.
    path : str or os.PathLike
        PNG file to write; its folder is created if needed.
    joints : sequence of str, optional
        Joints to draw; default all, in scene order.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return style.save(reaction_hodographs_figure(scene, analysis, joints), path)


# ---------------------------------------------------------------------- frame loads


def frame_loads_figure(scene: Scene, analysis: Analysis):
    """Draw the frame (or shaking) force hodograph and moment; return the figure (not saved).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.forces` set.

    Returns
    -------
    matplotlib.figure.Figure
        Left a polar axis (force hodograph), right the moment against the
        driver.

    Raises
    ------
    ValueError
        If the analysis has no forces.
    """
    forces = _forces_or_raise(analysis)
    fword, mword = frame_words(scene)
    x, xlabel, xunit = driver_axis(scene, analysis)
    closed = _cyclic(scene)
    fig = style.new_figure(12.5, 5.4)
    gs = fig.add_gridspec(1, 2, width_ratios=(1.0, 1.35))
    polar = fig.add_subplot(gs[0, 0], projection="polar")
    ax = fig.add_subplot(gs[0, 1])

    gaps = frame_gaps(analysis, scene)  # unbounded at a passage through infinity: not joined
    peak = hodograph(polar, forces.frame_force, color=style.PALETTE[0], closed=closed,
                     gaps=gaps)
    tail = f"peak |F| = {style.fmt_number(peak)} N" if peak is not None else "no solved step"
    tail = gap_label(tail, gaps)
    polar.set_title(f"{fword} on the ground (N)\n{tail}", fontsize=10)
    polar.legend(handles=_legend_handles(style.PALETTE[0]), loc="upper center",
                 bbox_to_anchor=(0.5, -0.08), ncols=2, fontsize=8, frameon=False)

    moment = np.asarray(forces.frame_moment, dtype=float)
    st = _stats(moment, whole_period(scene))
    if st is None:
        label = f"{mword}: no solved step"
    else:
        rms, pk, k = st
        label = (f"{mword}\n  RMS {style.fmt_number(rms)} N·m, peak {style.fmt_number(pk)} N·m "
                 f"at {style.fmt_number(float(x[k]))} {xunit}")
    ax.plot(*with_breaks(gaps, x, moment), color=style.PALETTE[1], lw=1.8,
            label=gap_label(label, gaps, ",\n  "))
    if st is not None:
        ax.plot([x[st[2]]], [st[1]], marker="o", ms=6, mfc="white", mec=style.PALETTE[1],
                mew=1.6, ls="none", zorder=3, clip_on=False)
    else:
        style.no_data_note(ax, f"no {mword}: no solved step")
    ax.axhline(0.0, color="0.45", lw=0.8, zorder=0.5)
    ax.set_ylabel(f"{mword} M about the global origin (N·m)")
    band_handles = style.shade_bad_steps([ax], x, analysis.status, label_ax=ax)
    band_handles += mark_passages([ax], x, analysis)
    style.driver_ticks(ax, x, xlabel, xunit)
    ax.grid(True, color="0.9", lw=0.6)
    ax.set_xlim(float(np.min(x)), float(np.max(x)))
    ax.margins(x=0)
    ax.set_title(f"{mword} on the ground against the driver", fontsize=10)
    ax.legend(handles=ax.get_legend_handles_labels()[0] + band_handles, loc="upper center",
              bbox_to_anchor=(0.5, -0.16), ncols=2, fontsize=8, frameon=False)
    what = ("inertia only: the loads the moving links' inertia puts on the frame"
            if inertia_only(scene) else "what the moving links exert on the ground")
    note = _bad_note(analysis)
    fig.suptitle(f"{scene.name}: {fword} and {mword}\n{what}" + (f" ({note})" if note else ""),
                 fontsize=11)
    fig.draw_without_rendering()  # let the layout see the polar title (see above)
    return fig


def frame_loads(scene: Scene, analysis: Analysis, path) -> Path:
    """Write the frame (or shaking) force hodograph and moment as one PNG.

    Left, a polar hodograph of the force the moving links exert on the
    ground (angle from the global x axis, radius in N; the first solved step
    marked, arrow heads in the direction of travel); right, the moment about
    the global origin (N·m) against the first driver's coordinate, with its
    RMS and peak.  Under inertia only (:func:`inertia_only`) they are labelled
    *shaking force* and *shaking moment*, else *frame force* and *frame
    moment*.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        With :attr:`~linkage_sym.numeric.results.result.Analysis.forces` set.
    path : str or os.PathLike
        PNG file to write; its folder is created if needed.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return style.save(frame_loads_figure(scene, analysis), path)
