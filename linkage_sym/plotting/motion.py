"""Motion diagrams: positions, velocities and accelerations against the driver.

The three figures of a sweep, like the position, velocity and acceleration
diagrams of a shaper (linear and angular motion of the driven members against
the crank angle): the upper panel holds every rotating link's rotation,
angular velocity or angular acceleration; a lower panel, drawn when the
mechanism has sliders on the ground, holds the sliders' displacement,
velocity or acceleration along their axes.

This module only draws results: it reads an :class:`~linkage_sym.numeric.results.result.Analysis`
and never solves anything.  Steps that are not ``ok`` are NaN in the results,
which breaks the curves; they are also shaded and labelled.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.result import Analysis
from linkage_sym.plotting import style
from linkage_sym.plotting.breaks import JUMP, gap_label, gaps_of, mark_passages, with_breaks

QUANTITIES = ("position", "velocity", "acceleration")
_FILE_SUFFIX = {"position": "positions", "velocity": "velocities", "acceleration": "accelerations"}


def driver_axis(scene: Scene, analysis: Analysis) -> tuple[np.ndarray, str, str]:
    """The x values of the motion diagrams: the first driver's coordinate.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis

    Returns
    -------
    x : ndarray, shape (N,)
        Degrees for an ``R`` driver; metres for a ``P`` driver (the unit of the
        result files).
        Where the result has no value the prescribed sweep value is used, so
        ``x`` is always finite.
    label : str
        Axis label with its unit.
    unit : str
        ``"deg"`` or ``"m"``.
    """
    drv = scene.drivers[0]
    n = analysis.n_steps
    sweep = np.linspace(drv.start, drv.stop, n)
    q = analysis.drivers.get(drv.joint, {}).get("q")
    q = sweep if q is None else np.where(np.isfinite(q), np.asarray(q, dtype=float), sweep)
    more = f", first of {len(scene.drivers)} drivers" if len(scene.drivers) > 1 else ""
    if drv.kind == "R":
        toward = f", direction {drv.joint}→{drv.toward}" if drv.toward else ""
        return (np.degrees(q), f"driver angle θ at joint {drv.joint} (deg{toward}{more})",
                "deg")
    return q, f"driver displacement s at joint {drv.joint} (m{more})", "m"


def input_links(scene: Scene) -> set:
    """Links turned directly by an ``R`` driver mounted on the ground."""
    out = set()
    for drv in scene.drivers:
        joint = scene.joint(drv.joint)
        if drv.kind == "R" and GROUND in joint.links:
            other = joint.links[1] if joint.links[0] == GROUND else joint.links[0]
            out.add(other)
    return out


def ground_sliders(scene: Scene, analysis: Analysis, quantity: str) -> list:
    """Motion of every slider on the ground along its axis.

    A slider is the moving link of a ``P`` joint whose other link is the
    ground.  Its motion is read off the results (the joint's point, or the
    moving link's point at the joint, when the point is fixed on the ground)
    and projected on the joint's axis, which does not turn.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    quantity : {"position", "velocity", "acceleration"}

    Returns
    -------
    list of (str, str, ndarray)
        ``(slider link, legend label, values in m, m/s or m/s²)``; the position is the
        displacement from the assembly configuration.  Sliders whose
        ``quantity`` was not computed are left out.
    """
    out = []
    for joint in scene.joints:
        if joint.type != "P" or GROUND not in joint.links or joint.links == (GROUND, GROUND):
            continue
        u = np.array([math.cos(joint.axis), math.sin(joint.axis)])
        at = np.asarray(joint.at, dtype=float)
        if joint.links[1] != GROUND:
            moving = joint.links[1]
            jk = analysis.joints.get(joint.name)
            if jk is None:
                continue
            value = {"position": jk.position, "velocity": jk.velocity,
                     "acceleration": jk.acceleration}[quantity]
        else:
            moving = joint.links[0]
            lk = analysis.links.get(moving)
            if lk is None:
                continue
            have = {"position": True, "velocity": lk.omega is not None,
                    "acceleration": lk.alpha is not None}[quantity]
            if not have:
                continue
            value = {"position": lk.point, "velocity": lk.point_velocity,
                     "acceleration": lk.point_acceleration}[quantity](joint.at)
        if value is None:
            continue
        value = np.asarray(value, dtype=float)
        if quantity == "position":
            value = value - at
        label = f"{moving} at {joint.name} (along {math.degrees(joint.axis):.4g}°)"
        out.append((moving, label, value @ u))
    return out


def _link_series(analysis: Analysis, quantity: str) -> list:
    """``(link names, values)`` of every rotating link for ``quantity``.

    Links that turn together (e.g. a block sliding in a swinging guide) have
    one curve with both names, so no curve hides another.
    """
    out = []
    for name, lk in analysis.links.items():
        rot = np.asarray(lk.rotation, dtype=float)
        finite = rot[np.isfinite(rot)]
        if finite.size and np.max(np.abs(finite)) < 1e-12:
            continue  # a link that only translates: shown as a slider, if on the ground
        values = {"position": lk.rotation, "velocity": lk.omega, "acceleration": lk.alpha}[quantity]
        if values is None:
            continue
        values = np.asarray(values, dtype=float)
        if quantity == "position":
            values = np.degrees(values)
        for entry in out:
            if _same(entry[1], values):
                entry[0].append(name)
                break
        else:
            out.append([[name], values])
    return [(tuple(names), values) for names, values in out]


def _same(a, b) -> bool:
    fa, fb = np.isfinite(a), np.isfinite(b)
    if not np.array_equal(fa, fb):
        return False
    scale = max(float(np.max(np.abs(a[fa]), initial=0.0)), 1.0)
    return bool(np.allclose(a[fa], b[fb], rtol=0.0, atol=1e-9 * scale))


def _span(values) -> float:
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return float(v.max() - v.min()) if v.size else 0.0


_LINK_LABELS = {
    "position": ("link rotation from assembly configuration (deg)", "rotation"),
    "velocity": ("angular velocity ω (rad/s)", "ω"),
    "acceleration": ("angular acceleration α (rad/s²)", "α"),
}
_SLIDER_LABELS = {  # in the units of the result files
    "position": ("slider displacement s (m)", "s"),
    "velocity": ("slider velocity v (m/s)", "v"),
    "acceleration": ("slider acceleration a (m/s²)", "a"),
}
_TITLES = {"position": "Position diagram", "velocity": "Velocity diagram",
           "acceleration": "Acceleration diagram"}


def _has_stage(analysis: Analysis, quantity: str) -> bool:
    if quantity == "position":
        return True
    return quantity in analysis.stages


def motion_figure(scene: Scene, analysis: Analysis, quantity: str):
    """Draw one motion diagram and return the figure (not saved).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    quantity : {"position", "velocity", "acceleration"}

    Returns
    -------
    matplotlib.figure.Figure
    """
    if quantity not in QUANTITIES:
        raise ValueError(f"quantity must be one of {QUANTITIES}, not {quantity!r}")
    x, xlabel, xunit = driver_axis(scene, analysis)
    colors = style.link_colors(scene)
    links = _link_series(analysis, quantity)
    sliders = ground_sliders(scene, analysis, quantity)
    panels = 2 if (links and sliders) else 1
    fig = style.new_figure(9.5, 7.2 if panels == 2 else 4.8)
    axes = fig.subplots(panels, 1, sharex=True, squeeze=False)[:, 0]
    ax_links = axes[0] if links else None
    ax_sliders = axes[-1] if sliders else None
    twin = None

    if ax_links is not None:
        ylabel, sym = _LINK_LABELS[quantity]
        big = input_links(scene)
        other_span = max((_span(v) for n, v in links if not big & set(n)), default=0.0)
        # The crank's rotation (a whole turn) would flatten every other curve:
        # it gets its own axis on the right when it dwarfs them.
        split = quantity == "position" and any(
            big & set(n) and _span(v) > 3.0 * other_span for n, v in links
        ) and other_span > 0.0
        for names, values in links:
            is_input = bool(big & set(names))
            on_twin = split and is_input
            if on_twin and twin is None:
                twin = ax_links.twinx()
                twin.set_ylabel("input link rotation (deg)")
            target = twin if on_twin else ax_links
            # a Newton group's jump turns its links at once: not joined (a passage through
            # infinity carries a link off along its slides without turning it)
            gaps = tuple(g for g in gaps_of(analysis, names) if JUMP in g.why)
            target.plot(
                *with_breaks(gaps, x, values), color=colors.get(names[0]), lw=1.8,
                ls="--" if is_input else "-",
                label=gap_label(" = ".join(f"{sym} {n}" for n in names)
                                + (" (input, right axis)" if on_twin else " (input)"
                                   if is_input else ""), gaps),
            )
        ax_links.set_ylabel(ylabel)
        ax_links.axhline(0.0, color="0.5", lw=0.6, zorder=0.5)

    if ax_sliders is not None:
        ylabel, sym = _SLIDER_LABELS[quantity]
        for link, label, values in sliders:
            gaps = gaps_of(analysis, [link])  # a slider carried through infinity: not joined
            xs, values = with_breaks(gaps, x, values)
            ax_sliders.plot(xs, values, lw=1.8, color=colors.get(link),
                            label=gap_label(f"{sym}: {label}", gaps))
        ax_sliders.set_ylabel(ylabel)
        ax_sliders.axhline(0.0, color="0.5", lw=0.6, zorder=0.5)

    if not links and not sliders:
        axes[0].text(0.5, 0.5, f"no {quantity} results in this analysis", ha="center",
                     va="center", transform=axes[0].transAxes, color="0.4")

    band_handles = style.shade_bad_steps(axes, x, analysis.status, label_ax=axes[0])
    band_handles += mark_passages(axes, x, analysis)
    style.driver_ticks(axes[-1], x, xlabel, xunit)
    for ax in axes:
        ax.grid(True, color="0.9", lw=0.6)
        ax.set_xlim(float(np.min(x)), float(np.max(x)))
        ax.margins(x=0)
    for ax in axes:
        extra = []
        if ax is ax_links and twin is not None:
            extra = twin.get_legend_handles_labels()[0]
        handles = ax.get_legend_handles_labels()[0] + extra
        if ax is axes[0]:
            handles = handles + band_handles
        if handles:
            ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02 if twin is None
                      or ax is not ax_links else 1.10, 1.0), fontsize=8, frameon=False)
    fig.suptitle(f"{scene.name}: {_TITLES[quantity].lower()} against the driver")
    return fig




def motion_diagrams(scene: Scene, analysis: Analysis, out_dir, prefix: str | None = None) -> list:
    """Write the position, velocity and acceleration diagrams of a sweep as PNGs.

    Each figure plots, against the first driver's coordinate (degrees for an
    ``R`` driver, m for a ``P`` driver), every rotating link's rotation
    from the assembly configuration (deg), angular velocity (rad/s) or angular
    acceleration (rad/s²) and, in a second panel, the displacement, velocity or
    acceleration along its axis of every slider on the ground (m, m/s, m/s²: the
    units of the result files).  Links that only
    translate have no rotation curve.  Steps that are not ``ok`` break the
    curves and are shaded grey, labelled ``unassemblable`` or ``singular``.  A slider
    that a passage through infinity carries off (:attr:`Analysis.passages`) has its curve
    broken between the two steps, marked by a dotted vertical line.

    Parameters
    ----------
    scene : Scene
        The scene that was analysed.
    analysis : Analysis
        Its result.
    out_dir : str or os.PathLike
        Folder to write into; created if needed.
    prefix : str, optional
        File-name stem; default the scene's name.

    Returns
    -------
    list of pathlib.Path
        ``<stem>_positions.png``, ``<stem>_velocities.png`` and
        ``<stem>_accelerations.png``; a diagram whose stage did not run (see
        :attr:`Analysis.stages`) is not written and not listed.
    """
    out = style.ensure_dir(out_dir)
    stem = style.file_stem(scene, prefix)
    written = []
    for quantity in QUANTITIES:
        if not _has_stage(analysis, quantity):
            continue
        fig = motion_figure(scene, analysis, quantity)
        path = Path(out) / f"{stem}_{_FILE_SUFFIX[quantity]}.png"
        written.append(style.save(fig, path))
    return written
