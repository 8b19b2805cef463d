"""Animations of a sweep: the mechanism moving, its paths growing, optional layers.

:func:`animate` makes a :class:`MechanismAnimation` of a scene's
:class:`~linkage_sym.numeric.results.result.Analysis`, drawn with Matplotlib's
animation machinery on a :class:`~matplotlib.figure.Figure` (no pyplot, no
global state).  Each frame shows one step of the sweep:

* the links as every still picture draws them
  (:func:`~linkage_sym.plotting.paths.mechanism_snapshot`: bars, polygons,
  pins, ground symbols, slots, cams), with the joints' paths and the traced
  points' coupler curves (:func:`~linkage_sym.plotting.paths.traced_paths`)
  grown up to the step;
* the layers asked for: ``velocity`` and ``acceleration`` arrows of the moving
  joints and traced points; ``forces``, the joint reactions as arrows (the
  force a joint's ``links[0]`` exerts on its ``links[1]``, at the joint) and
  the driving effort (an ``R`` driver's torque as a curved arrow about its
  joint whose sweep is proportional to the torque, a ``P`` driver's force as
  an arrow along its slide); ``centres``, the instant centres with the
  three-centre lines Kennedy's construction used
  (:mod:`linkage_sym.centres`, drawn as
  :func:`~linkage_sym.plotting.centres.centres_figure` draws them);
  ``transmission``, the transmission angle of every RRR dyad
  (:mod:`linkage_sym.numeric.results.transmission`) as an arc at its inner
  joint with its value.

Every arrow of a layer has one scale over the whole animation (its largest
value is drawn :data:`ARROW_SHARE` mechanism sizes long); the legend gives it.

A step that is not ``ok`` is never skipped: its frame says so in a red box
(the status and the solver's message).  An ``unassemblable`` step has no
pose: its frame draws the last solved pose before it faded (alpha
:data:`FADED`), or nothing when no step before it was solved.  A
``singular`` step has its pose (drawn as usual) but no velocities,
accelerations nor forces: its layers are empty and the box says so.

The animation is written as a GIF (Pillow, which Matplotlib needs anyway), an
MP4 (ffmpeg, where Matplotlib finds it) or one self-contained HTML file
(:meth:`~matplotlib.animation.Animation.to_jshtml`: the frames embedded as
PNG, the player's script inline); in a notebook the object shows itself
through :meth:`MechanismAnimation._repr_html_`.

The numeric core imports no Matplotlib, so this is a function of the plotting
layer and not a method of ``Analysis``: ``linkage_sym.animate(scene,
analysis, velocity=True)`` (or :func:`animate` here).
"""

from __future__ import annotations

import math
import os
import re
import secrets
import textwrap
from pathlib import Path

import numpy as np
from matplotlib import animation as mpl_animation
from matplotlib import rc_context
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Arc, FancyArrowPatch
from matplotlib.path import Path as MplPath

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.result import OK, SINGULAR, Analysis
from linkage_sym.plotting import style
from linkage_sym.plotting.centres import KIND_STYLE, _kind, three_centre_segments
from linkage_sym.plotting.motion import driver_axis
from linkage_sym.plotting.paths import (
    _valid_steps,
    cam_outline,
    mechanism_snapshot,
    points_on_link,
    traced_paths,
)

__all__ = ["ARROW_SHARE", "DEFAULT_FPS", "DEFAULT_FRAMES", "FADED", "LAYERS", "SUFFIXES",
           "AnimationError", "MechanismAnimation", "animate", "check_fps", "frame_steps",
           "output_kind", "require_ffmpeg", "self_contained"]

LAYERS = ("velocity", "acceleration", "forces", "centres", "transmission")
"""The layers an animation may draw over the mechanism, in drawing order."""

DEFAULT_FRAMES = 120
"""Frames of an animation whose count is not given (every step of a shorter sweep)."""

DEFAULT_FPS = 20.0
"""Frames per second of an animation whose rate is not given."""

DPI = 80
"""Dots per inch of the written frames (a frame about 690 pixels wide)."""

ARROW_SHARE = 0.35
"""Length of a layer's longest arrow over the sweep, in mechanism sizes
(:meth:`~linkage_sym.model.Scene.characteristic_length`)."""

TORQUE_SWEEP = 300.0
"""Sweep (degrees) of the curved arrow of the largest driving torque."""

MARGINS = (0.75, 0.55, 0.4, 2.75)
"""Room (inches) left, below, above the drawing and right of it (the legend)."""

FADED = 0.25
"""Opacity of the last solved pose drawn on the frame of an ``unassemblable`` step."""

SUFFIXES = {".gif": "GIF (Pillow)", ".mp4": "MP4 (ffmpeg)", ".html": "HTML (one self-contained file)"}
"""The files an animation is written to, by suffix."""

EMBED_LIMIT_MB = 1000.0
"""Size (MB) up to which an HTML animation embeds every frame (Matplotlib's default, 20 MB,
would drop the frames past it)."""

COLORS = {"velocity": "#00838f", "acceleration": "#c2185b", "reactions": "0.1",
          "driving": "#e65100", "transmission": "#6a1b9a"}
"""Colours of the layers' arrows (apart from the links' colours)."""


class AnimationError(ValueError):
    """An animation that cannot be made or written as asked: ``field`` names the
    argument (``frames``, ``fps``, ``path``, or a layer: ``forces`` ...), ``reason`` says why.

    Examples
    --------
    >>> str(AnimationError("frames", "at most the sweep's 37 steps, got 40"))
    "frames: at most the sweep's 37 steps, got 40"
    """

    def __init__(self, field: str, reason: str):
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}")


def frame_steps(n_steps: int, frames: int | None = None) -> np.ndarray:
    """The steps shown by ``frames`` frames: the sweep sampled evenly, first and last step
    included.

    Parameters
    ----------
    n_steps : int
        Steps of the sweep.
    frames : int, optional
        Frames wanted, 1 to ``n_steps``; default ``min(n_steps, DEFAULT_FRAMES)``.

    Returns
    -------
    ndarray of int, shape (frames,)
        Increasing, all different (a spacing of at least one step rounds to distinct steps).

    Raises
    ------
    AnimationError
        ``frames`` not a whole number from 1 to ``n_steps``.

    Examples
    --------
    >>> frame_steps(361, 5).tolist(), frame_steps(4).tolist(), frame_steps(37, 1).tolist()
    ([0, 90, 180, 270, 360], [0, 1, 2, 3], [0])
    """
    if n_steps < 1:
        raise AnimationError("frames", "the analysis has no step to show")
    if frames is None:
        frames = min(n_steps, DEFAULT_FRAMES)
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)):
        raise AnimationError("frames", f"a whole number of frames is expected, got {frames!r}")
    if not 1 <= frames <= n_steps:
        raise AnimationError("frames", f"from 1 to the sweep's {n_steps} steps (one frame a "
                             f"step at most), got {frames}")
    if frames == 1:
        return np.zeros(1, dtype=int)
    return np.rint(np.linspace(0.0, n_steps - 1, int(frames))).astype(int)


def _positive(field: str, value, what: str) -> float:
    """``value`` as a positive finite float, else :class:`AnimationError` naming ``field``."""
    if not isinstance(value, bool):
        try:
            number = float(value)
        except (TypeError, ValueError):
            number = math.nan
        if math.isfinite(number) and number > 0.0:
            return number
    raise AnimationError(field, f"a positive number of {what} is expected, got {value!r}")


def check_fps(fps) -> float:
    """``fps`` as a positive finite float, else :class:`AnimationError` (field ``fps``).

    Examples
    --------
    >>> check_fps(12), check_fps("2.5")
    (12.0, 2.5)
    """
    return _positive("fps", fps, "frames per second")


def output_kind(path) -> str:
    """``"gif"``, ``"mp4"`` or ``"html"`` from ``path``'s suffix (any case).

    Raises
    ------
    AnimationError
        Another suffix (field ``path``).

    Examples
    --------
    >>> output_kind("motion.GIF"), output_kind("a/b.html")
    ('gif', 'html')
    >>> output_kind("motion.png")
    Traceback (most recent call last):
    ...
    linkage_sym.plotting.animation.AnimationError: path: 'motion.png': an animation is written as .gif, .mp4 or .html, not '.png'
    """
    suffix = Path(path).suffix.lower()
    if suffix not in SUFFIXES:
        given = f"{suffix!r}" if suffix else "a name without a suffix"
        raise AnimationError("path", f"{str(path)!r}: an animation is written as .gif, .mp4 "
                             f"or .html, not {given}")
    return suffix[1:]


def require_ffmpeg() -> None:
    """Raise :class:`AnimationError` (field ``path``) if Matplotlib finds no ffmpeg for MP4."""
    if not mpl_animation.writers.is_available("ffmpeg"):
        raise AnimationError("path", "an MP4 file is written by ffmpeg, which is not found "
                             "(not on the PATH, nor set in Matplotlib's animation.ffmpeg_path); "
                             "a .gif or .html file needs nothing more")


def _finite_rows(values) -> np.ndarray:
    v = np.asarray(values, dtype=float).reshape(-1, 2)
    return v[np.all(np.isfinite(v), axis=-1)]


class MechanismAnimation:
    """The animation of one analysed sweep (see the module's description).

    Made by :func:`animate`; drawing happens frame by frame (:meth:`draw`) when it is
    saved or shown.

    Attributes
    ----------
    scene : Scene
    analysis : Analysis
    steps : ndarray of int
        The step each frame shows (:func:`frame_steps`).
    fps : float
    dpi : float
    layers : tuple of str
        The layers drawn, in :data:`LAYERS` order.
    figure : matplotlib.figure.Figure
    ax : matplotlib.axes.Axes
    unit, unit_scale : str, float
        The unit of the drawing's axes and its factor from metres.
    scales : dict
        Drawing length (axis units) of one unit of each arrow layer's value:
        ``velocity`` per m/s, ``acceleration`` per m/s², ``reactions`` per N, and
        ``driving`` degrees of sweep per N·m (``R`` drivers) or axis units per N
        (``driving force``).
    centres : InstantCentres or None
        The instant centres, with the ``centres`` layer.
    """

    def __init__(self, scene: Scene, analysis: Analysis, *, frames=None, fps=DEFAULT_FPS,
                 dpi=DPI, velocity=False, acceleration=False, forces=False, centres=False,
                 transmission=False):
        asked = {"velocity": velocity, "acceleration": acceleration, "forces": forces,
                 "centres": centres, "transmission": transmission}
        for name, on in asked.items():
            if not isinstance(on, (bool, np.bool_)):
                raise AnimationError(name, f"True or False is expected, got {on!r}")
        self.scene = scene
        self.analysis = analysis
        self.steps = frame_steps(analysis.n_steps, frames)
        self.fps = check_fps(fps)
        self.dpi = _positive("dpi", dpi, "dots per inch")
        self.layers = tuple(name for name in LAYERS if asked[name])
        self._check_layers()
        self.unit, self.unit_scale = style.length_unit(scene)
        self.L = scene.characteristic_length() or 1.0
        self.valid = _valid_steps(analysis)
        self.paths = traced_paths(scene, analysis)
        self.centres = None
        if "centres" in self.layers:
            from linkage_sym.centres import instant_centres

            self.centres = instant_centres(scene, analysis)
        self.dyads = []
        if "transmission" in self.layers:
            from linkage_sym.numeric.results.transmission import rrr_dyads

            self.dyads = [d for d in rrr_dyads(scene) if d[0] in analysis.transmission_angles]
        self.x, _, self.x_unit = driver_axis(scene, analysis)
        self.scales = self._scales()
        self._animation = None
        self._setup_figure()

    # -- what can be drawn ------------------------------------------------------------

    def _check_layers(self) -> None:
        a = self.analysis
        for layer, stage in (("velocity", "velocity"), ("acceleration", "acceleration"),
                             ("centres", "velocity")):
            if layer in self.layers and stage not in a.stages:
                why = "the instant centres need velocities, and " if layer == "centres" else ""
                plural = {"velocity": "velocities", "acceleration": "accelerations"}[stage]
                raise AnimationError(layer, f"{why}the analysis has no {plural}: its {stage} "
                                     "stage did not run (the scene's outputs do not list "
                                     "kinematics)")
        if "forces" in self.layers and a.forces is None:
            raise AnimationError("forces", "the analysis has no forces: its forces stage did "
                                 "not run (the scene's outputs list none of reactions, driving, "
                                 "frame)")
        if "transmission" in self.layers and not a.transmission_angles:
            raise AnimationError("transmission", "the analysis has no transmission angles: "
                                 "the mechanism has no RRR dyad (or the scene's outputs do not "
                                 "list kinematics)")

    def _vectors(self, kind: str) -> list:
        """``[(name, positions (N, 2), vectors (N, 2))]`` of the moving joints and traced
        points for ``kind`` ``"velocity"`` or ``"acceleration"``."""
        out = []
        for joint in self.scene.joints:
            if joint.links[1] == GROUND:
                continue
            jk = self.analysis.joints.get(joint.name)
            vec = None if jk is None else getattr(jk, kind)
            if vec is not None:
                out.append((joint.name, np.asarray(jk.position, dtype=float),
                            np.asarray(vec, dtype=float)))
        for name, pk in (self.analysis.points or {}).items():
            vec = getattr(pk, kind)
            if vec is not None:
                out.append((name, np.asarray(pk.position, dtype=float),
                            np.asarray(vec, dtype=float)))
        return out

    def _reactions(self) -> list:
        """``[(joint, positions (N, 2), reactions (N, 2))]`` of every joint with a reaction."""
        f = self.analysis.forces
        out = []
        for name, r in f.reactions.items():
            jk = self.analysis.joints.get(name)
            if jk is not None:
                out.append((name, np.asarray(jk.position, dtype=float), np.asarray(r, dtype=float)))
        return out

    def _drivers(self) -> list:
        """``[(joint, type, values (N,))]`` of the driving efforts."""
        f = self.analysis.forces
        names = {j.name for j in self.scene.joints}
        return [(name, self.scene.joint(name).type, np.asarray(v, dtype=float))
                for name, v in f.driving.items() if name in names]

    def _scales(self) -> dict:
        """Axis units per unit of value of each arrow layer: its largest value drawn
        :data:`ARROW_SHARE` mechanism sizes long (or a torque :data:`TORQUE_SWEEP` degrees)."""
        reach = ARROW_SHARE * self.L * self.unit_scale
        ok = self.analysis.ok

        def per(vectors):
            biggest = max((float(np.max(np.hypot(*_finite_rows(v[ok]).T), initial=0.0))
                           for v in vectors), default=0.0)
            return reach / biggest if biggest > 0.0 else 0.0

        out = {}
        for layer in ("velocity", "acceleration"):
            if layer in self.layers:
                out[layer] = per([v for _, _, v in self._vectors(layer)])
        if "forces" in self.layers:
            out["reactions"] = per([r for _, _, r in self._reactions()])
            drivers = self._drivers()
            for kind, key, full in (("R", "driving", TORQUE_SWEEP), ("P", "driving force", reach)):
                values = [np.abs(v[ok & np.isfinite(v)]) for _, t, v in drivers if t == kind]
                biggest = max((float(np.max(v, initial=0.0)) for v in values), default=0.0)
                if values:
                    out[key] = full / biggest if biggest > 0.0 else 0.0
        return out

    # -- the figure -------------------------------------------------------------------

    def _extent(self):
        """Corners (axis units) of everything drawn over the frames."""
        a, s = self.analysis, self.unit_scale
        pts = [np.asarray(j.at, dtype=float)[None, :] for j in self.scene.joints]
        pts += [np.asarray(jk.position, dtype=float) for jk in a.joints.values()]
        pts += [np.asarray(pk.position, dtype=float) for pk in (a.points or {}).values()]
        pts += [np.asarray(lk.com, dtype=float) for lk in a.links.values() if lk.com is not None]
        shown = [int(i) for i in self.steps if self.valid[i]]
        for joint in self.scene.cams:  # a cam is its profile
            outline = cam_outline(joint)[0]
            pts += [points_on_link(a, joint.links[0], i, outline) for i in shown]
        ok = a.ok[self.steps]
        arrows = []
        for layer in ("velocity", "acceleration"):
            if layer in self.layers:
                arrows += [(p, v, self.scales[layer] / s) for _, p, v in self._vectors(layer)]
        if "forces" in self.layers:
            arrows += [(p, r, self.scales["reactions"] / s) for _, p, r in self._reactions()]
        for p, v, k in arrows:
            pts.append(p[self.steps][ok] + k * v[self.steps][ok])
        allp = np.concatenate([_finite_rows(p) for p in pts], axis=0)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = 0.06 * float((hi - lo).max()) + 0.1 * self.L  # the ground symbols, the labels
        return (lo - pad) * s, (hi + pad) * s

    def _setup_figure(self) -> None:
        """The figure: an equal-aspect drawing of fixed limits (inches: margins
        :data:`MARGINS`), the legend beside it; nothing of it moves between frames."""
        lo, hi = self._extent()
        dx, dy = float(hi[0] - lo[0]), float(hi[1] - lo[1])
        ax_w = 6.0
        ax_h = float(np.clip(ax_w * dy / dx, 2.5, 7.0))
        # the short side widened to the drawing's proportions: equal scales fill it
        mid, half = 0.5 * (lo + hi), 0.5 * np.array([dx, dy])
        if dy / dx < ax_h / ax_w:
            half[1] = half[0] * ax_h / ax_w
        else:
            half[0] = half[1] * ax_w / ax_h
        left, bottom, top, legend = MARGINS
        width, height = left + ax_w + legend, bottom + ax_h + top
        fig = Figure(figsize=(width, height), dpi=self.dpi)
        FigureCanvasAgg(fig)
        ax = fig.add_axes((left / width, bottom / height, ax_w / width, ax_h / height))
        ax.set_xlim(mid[0] - half[0], mid[0] + half[0])
        ax.set_ylim(mid[1] - half[1], mid[1] + half[1])
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel(f"x ({self.unit})")
        ax.set_ylabel(f"y ({self.unit})")
        ax.grid(True, color="0.92", lw=0.6, zorder=0)
        handles = [Line2D([], [], color=p.color, lw=p.lw, ls=p.ls, label=p.label)
                   for p in self.paths]
        handles += self._layer_handles()
        if handles:
            fig.legend(handles=handles, loc="upper left", fontsize=7, frameon=False,
                       bbox_to_anchor=((left + ax_w + 0.1) / width, 1.0 - top / height))
        ax.set_title(self._title(int(self.steps[0])), fontsize=10)
        self.figure, self.ax = fig, ax
        self._static = set(ax.get_children())

    def _layer_handles(self) -> list:
        unit = self.unit
        out = []

        def arrow_handle(color, label):
            return Line2D([], [], color=color, lw=1.4, marker=">", markevery=[-1], ms=5,
                          label=label)

        if "velocity" in self.layers:
            out.append(arrow_handle(COLORS["velocity"], "velocity: 1 m/s drawn "
                                    f"{style.fmt_number(self.scales['velocity'])} {unit}"))
        if "acceleration" in self.layers:
            out.append(arrow_handle(COLORS["acceleration"], "acceleration: 1 m/s² drawn "
                                    f"{style.fmt_number(self.scales['acceleration'])} {unit}"))
        if "forces" in self.layers:
            out.append(arrow_handle(COLORS["reactions"], "joint reaction (links[0] on links[1]):"
                                    f"\n  1 N drawn {style.fmt_number(self.scales['reactions'])} {unit}"))
            if "driving" in self.scales:
                out.append(arrow_handle(COLORS["driving"], "driving torque: 1 N·m turns "
                                        f"{style.fmt_number(self.scales['driving'])}°"))
            if "driving force" in self.scales:
                out.append(arrow_handle(COLORS["driving"], "driving force: 1 N drawn "
                                        f"{style.fmt_number(self.scales['driving force'])} {unit}"))
        if "centres" in self.layers:
            out += [Line2D([], [], ls="none", label="instant centre at a joint", **KIND_STYLE["joint"]),
                    Line2D([], [], ls="none", label="instant centre by three-centre lines",
                           **KIND_STYLE["kennedy"]),
                    Line2D([], [], ls="none", label="instant centre from the velocities",
                           **KIND_STYLE["velocity"]),
                    Line2D([], [], color="#d62728", lw=0.7, ls=(0, (5, 3)),
                           label="three-centre line")]
        if "transmission" in self.layers:
            out.append(Line2D([], [], color=COLORS["transmission"], lw=1.4,
                              label="transmission angle γ of an RRR dyad"))
        return out

    def _title(self, step: int) -> str:
        drv = self.scene.drivers[0]
        value = (f"{drv.joint} = {self.x[step]:.4g}°" if self.x_unit == "deg"
                 else f"{drv.joint} = {self.x[step]:.4g} m")
        return f"{self.scene.name}: step {step} (0 to {self.analysis.n_steps - 1}), {value}"

    # -- one frame --------------------------------------------------------------------

    def draw(self, frame: int) -> list:
        """Draw frame ``frame`` (the step ``steps[frame]``) in place of the one shown.

        Returns
        -------
        list
            The artists of the frame (the static ones, axes and legend, are kept).
        """
        ax = self.ax
        for artist in [a for a in ax.get_children() if a not in self._static]:
            artist.remove()
        step = int(self.steps[frame])
        status = str(self.analysis.status[step])
        s = self.unit_scale
        before = set(ax.get_children())
        ax.set_title(self._title(step), fontsize=10)
        for p in self.paths:  # grown up to the step
            pos = p.position[: step + 1] * s
            ax.plot(pos[:, 0], pos[:, 1], color=p.color, lw=p.lw, ls=p.ls, zorder=p.zorder,
                    gid=f"trace {p.label}")
        if self.valid[step]:
            mechanism_snapshot(self.scene, self.analysis, step, ax, unit_scale=s)
            pose = step
        else:
            solved = np.flatnonzero(self.valid[:step])
            pose = int(solved[-1]) if solved.size else None
            if pose is not None:
                mechanism_snapshot(self.scene, self.analysis, pose, ax, alpha=FADED,
                                   unit_scale=s)
        if status == OK:
            for layer in ("velocity", "acceleration"):
                if layer in self.layers:
                    self._arrows(layer, step)
            if "forces" in self.layers:
                self._forces(step)
            if "centres" in self.layers:
                self._centres(step)
        if "transmission" in self.layers and self.valid[step]:
            self._transmission(step)
        if status != OK:
            self._status_note(step, status, pose)
        return [a for a in ax.get_children() if a not in before]

    def _quiver(self, rows, scale, color, gid):
        """Arrows from each point along its vector times ``scale`` (axis units)."""
        rows = [(p, v) for p, v in rows if np.all(np.isfinite(p)) and np.all(np.isfinite(v))
                and np.hypot(*v) * scale > 1e-9 * self.L * self.unit_scale]
        if not rows:
            return None
        p = np.array([r[0] for r in rows]) * self.unit_scale
        v = np.array([r[1] for r in rows]) * scale
        return self.ax.quiver(p[:, 0], p[:, 1], v[:, 0], v[:, 1], angles="xy",
                              scale_units="xy", scale=1.0, color=color, width=0.004,
                              headwidth=4.0, headlength=5.0, headaxislength=4.5, zorder=7,
                              gid=gid)

    def _arrows(self, layer: str, step: int) -> None:
        rows = [(p[step], v[step]) for _, p, v in self._vectors(layer)]
        self._quiver(rows, self.scales[layer], COLORS[layer], layer)

    def _forces(self, step: int) -> None:
        rows = [(p[step], r[step]) for _, p, r in self._reactions()]
        self._quiver(rows, self.scales["reactions"], COLORS["reactions"], "reactions")
        s = self.unit_scale
        for name, kind, values in self._drivers():
            value = float(values[step])
            if not math.isfinite(value):
                continue
            p = np.asarray(self.analysis.joints[name].position[step], dtype=float) * s
            if kind == "R":
                sweep = math.radians(value * self.scales["driving"])
                r = 0.12 * self.L * s
                t = np.linspace(0.0, sweep, 40)
                ring = p + r * np.stack([np.cos(t), np.sin(t)], axis=-1)
                if abs(sweep) > 1e-6:
                    self.ax.add_patch(FancyArrowPatch(
                        path=MplPath(ring), arrowstyle="-|>", mutation_scale=10,
                        color=COLORS["driving"], lw=1.6, zorder=7, gid=f"driving {name}"))
                text = f"T {name} = {style.fmt_number(value)} N·m"
            else:
                axis = self.scene.joint(name).axis + self._turn(self.scene.joint(name).links[0], step)
                u = np.array([math.cos(axis), math.sin(axis)])
                self._quiver([(p / s, value * u)], self.scales["driving force"],
                             COLORS["driving"], f"driving {name}")
                text = f"F {name} = {style.fmt_number(value)} N"
            self.ax.annotate(text, tuple(p), xytext=(-8, -14), textcoords="offset points",
                             ha="right", va="top", fontsize=7.5, color=COLORS["driving"], zorder=9,
                             bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                                   "alpha": 0.75})

    def _turn(self, link: str, step: int) -> float:
        if link == GROUND:
            return 0.0
        return float(self.analysis.links[link].rotation[step])

    def _centres(self, step: int) -> None:
        c, s, ax = self.centres, self.unit_scale, self.ax
        for seg in three_centre_segments(c, step, self.L):
            seg = seg * s
            ax.plot(seg[:, 0], seg[:, 1], color="#d62728", lw=0.7, ls=(0, (5, 3)), alpha=0.55,
                    zorder=2)
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        groups, off = [], []
        for k in range(len(c.pairs)):
            label = c.label(k)
            if c.undefined[step, k]:
                continue
            if c.at_infinity[step, k]:
                off.append(f"{label} at infinity")
                continue
            p = c.position[step, k]
            if not np.all(np.isfinite(p)):
                continue
            q = p * s
            if not (x0 <= q[0] <= x1 and y0 <= q[1] <= y1):
                off.append(f"{label} off the drawing")
                continue
            kind = "velocity" if c.from_velocities[step, k] else _kind(c, k)
            ax.plot([q[0]], [q[1]], ls="none", zorder=8, gid=f"centre {label}", **KIND_STYLE[kind])
            for g in groups:  # centres close together share one label
                if np.hypot(*(g[0] - p)) <= 0.03 * self.L:
                    g[1].append(label)
                    break
            else:
                groups.append([p, [label], KIND_STYLE[kind]["mec"]])
        for p, labels, color in groups:
            ax.annotate(", ".join(labels), tuple(p * s), xytext=(5, -9), textcoords="offset points",
                        fontsize=7, color=color, zorder=9,
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.7})
        if off:
            ax.text(0.99, 0.01, textwrap.fill("; ".join(off), 60), transform=ax.transAxes, ha="right", va="bottom",
                    fontsize=7, color="0.3", zorder=9)

    def _transmission(self, step: int) -> None:
        s, ax = self.unit_scale, self.ax
        for inner, e1, e2 in self.dyads:
            gamma = float(self.analysis.transmission_angles[inner][step])
            if not math.isfinite(gamma):
                continue
            J = np.asarray(self.analysis.joints[inner].position[step], dtype=float)
            a1 = math.atan2(*(np.asarray(self.analysis.joints[e1].position[step]) - J)[::-1])
            a2 = math.atan2(*(np.asarray(self.analysis.joints[e2].position[step]) - J)[::-1])
            # the arc from the first link to the second, the short way (gamma <= 180 degrees)
            start, stop = (a1, a2) if (a2 - a1) % (2 * math.pi) <= math.pi else (a2, a1)
            r = 0.14 * self.L * s
            ax.add_patch(Arc(tuple(J * s), 2 * r, 2 * r, theta1=math.degrees(start),
                             theta2=math.degrees(stop), color=COLORS["transmission"], lw=1.4,
                             zorder=6, gid=f"transmission {inner}"))
            mid = start + 0.5 * ((stop - start) % (2 * math.pi))
            at = J * s + 1.25 * r * np.array([math.cos(mid), math.sin(mid)])
            deg = math.degrees(gamma)
            ax.annotate(f"γ {inner} = {deg:.1f}°", tuple(at), ha="center", va="center",
                        fontsize=7.5, color=COLORS["transmission"], zorder=9,
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.75})

    def _status_note(self, step: int, status: str, pose) -> None:
        message = self.analysis.messages[step] or ""
        if status == SINGULAR:
            what = "drawn: its pose; no velocities, accelerations or forces at this step"
        elif pose is not None:
            what = f"not drawn: no pose; faded: the last solved pose (step {pose})"
        else:
            what = "not drawn: no pose, and no step before it was solved"
        text = "\n".join(textwrap.fill(line, 64) for line in
                         (f"step {step}: {status}", message, what) if line)
        self.ax.text(0.02, 0.98, text, transform=self.ax.transAxes, ha="left", va="top",
                     fontsize=8, color="#b71c1c", zorder=20, gid=f"status {status}",
                     bbox={"boxstyle": "round,pad=0.3", "fc": "white", "ec": "#b71c1c",
                           "alpha": 0.92})

    # -- writing ----------------------------------------------------------------------

    @property
    def animation(self) -> mpl_animation.FuncAnimation:
        """Matplotlib's animation of the frames (made once)."""
        if self._animation is None:
            self._animation = mpl_animation.FuncAnimation(
                self.figure, self.draw, frames=len(self.steps), init_func=lambda: [],
                interval=1000.0 / self.fps, blit=False, repeat=True, cache_frame_data=False)
        return self._animation

    def to_jshtml(self) -> str:
        """The animation as one HTML fragment: every frame embedded as PNG, the player's
        script and style inline (nothing fetched)."""
        with rc_context({"animation.embed_limit": EMBED_LIMIT_MB}):
            html = self.animation.to_jshtml(fps=self.fps, embed_frames=True, default_mode="loop")
        return self_contained(html)

    def _repr_html_(self) -> str:
        """What a notebook shows: :meth:`to_jshtml`."""
        return self.to_jshtml()

    def save(self, path) -> Path:
        """Write the animation to ``path``: ``.gif`` (Pillow), ``.mp4`` (ffmpeg) or ``.html``.

        The file is written under a temporary name beside it and then renamed, so a
        failed write leaves no partial file; the folder is created if needed.

        Returns
        -------
        pathlib.Path

        Raises
        ------
        AnimationError
            Another suffix, or an MP4 where ffmpeg is not found (field ``path``).
        """
        path = Path(path)
        kind = output_kind(path)
        if kind == "mp4":
            require_ffmpeg()
        style.ensure_dir(path.parent)
        # a name of its own beside it (the writers create it, with the permissions any new
        # file gets), its suffix kept: Pillow and ffmpeg choose the format by it
        tmp = str(path.with_name(f".{path.stem}.{os.getpid()}.{secrets.token_hex(6)}{path.suffix}"))
        try:
            if kind == "html":
                Path(tmp).write_text(_html_page(self.scene.name, self.to_jshtml()),
                                     encoding="utf-8")
            else:
                writer = (mpl_animation.PillowWriter(fps=self.fps) if kind == "gif" else
                          mpl_animation.FFMpegWriter(fps=self.fps))
                self.animation.save(tmp, writer=writer, dpi=self.dpi)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
        return path


ICONS = {"fa fa-minus": "\u2212", "fa fa-fast-backward": "|\u25c0\u25c0",
         "fa fa-step-backward": "|\u25c0", "fa fa-play fa-flip-horizontal": "\u25c0",
         "fa fa-pause": "||", "fa fa-play": "\u25b6", "fa fa-step-forward": "\u25b6|",
         "fa fa-fast-forward": "\u25b6\u25b6|", "fa fa-plus": "+"}
"""The player's buttons as characters (triangles of the Geometric Shapes block, which common
fonts have), for the icon font Matplotlib's player fetches."""


def self_contained(html: str) -> str:
    """Matplotlib's player (:meth:`~matplotlib.animation.Animation.to_jshtml`) without its one
    outside reference: the stylesheet of an icon font (Font Awesome, from a CDN) is left out and
    the buttons' icons are written as characters (:data:`ICONS`).

    Examples
    --------
    >>> self_contained('<link rel="stylesheet"\\nhref="https://x/fa.css">'
    ...                '<button><i class="fa fa-play"></i></button>')
    '<button>\u25b6</button>'
    """
    html = re.sub(r"<link\b[^>]*\bhref\s*=\s*[\"']?https?://[^>]*>", "", html)
    return re.sub(r'<i class="(fa [^"]*)"></i>', lambda m: ICONS.get(m.group(1), "?"), html)


def _html_page(title: str, body: str) -> str:
    """One HTML document around the player (no reference outside the file)."""
    from html import escape

    return (f"<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{escape(title)}</title>\n</head>\n<body>\n{body}\n</body>\n</html>\n")


def animate(scene: Scene, analysis: Analysis, *, frames=None, fps=DEFAULT_FPS, dpi=DPI,
            velocity=False, acceleration=False, forces=False, centres=False,
            transmission=False) -> MechanismAnimation:
    """An animation of a scene's analysed sweep (see the module's description).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        The scene's sweep (:func:`linkage_sym.analyze`, :meth:`Plan.run`).
    frames : int, optional
        Frames, sampling the sweep evenly (:func:`frame_steps`), at most one a step;
        default every step up to :data:`DEFAULT_FRAMES`.
    fps : float, optional
        Frames per second.
    dpi : float, optional
        Dots per inch of the written frames.
    velocity, acceleration, forces, centres, transmission : bool, optional
        The layers to draw (:data:`LAYERS`).

    Returns
    -------
    MechanismAnimation
        ``.save(path)`` writes it; a notebook shows it inline.

    Raises
    ------
    AnimationError
        Frames or a rate that cannot be used, or a layer the analysis has no values for
        (``forces`` of an analysis without forces ...), named by its field.

    Examples
    --------
    >>> import tempfile, linkage_sym
    >>> from PIL import Image
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> anim = animate(scene, linkage_sym.analyze(scene), frames=3, dpi=30, velocity=True)
    >>> anim.steps.tolist()
    [0, 180, 360]
    >>> with tempfile.TemporaryDirectory() as d, Image.open(anim.save(f"{d}/motion.gif")) as gif:
    ...     gif.n_frames
    3
    """
    return MechanismAnimation(scene, analysis, frames=frames, fps=fps, dpi=dpi,
                              velocity=velocity, acceleration=acceleration, forces=forces,
                              centres=centres, transmission=transmission)
