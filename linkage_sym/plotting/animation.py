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
value is drawn :data:`ARROW_SHARE` mechanism sizes long); the legend gives it.  At a
passage through infinity, whose far points' values are unbounded, the scale is set by the
values inside the view instead and the longest arrows are cut and marked
(:mod:`linkage_sym.plotting.animation_scale`).

Where a dyad of two slides carries a joint through infinity between two steps
(:attr:`Analysis.passages <linkage_sym.numeric.results.result.Analysis>`), the paths
of the points carried off are not joined across it, the drawing frames the rest of the
mechanism (:func:`~linkage_sym.plotting.breaks.passage_view`: those points leave it
near the passage), and the frames of the two steps say so in a box.

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

import os
import secrets
import textwrap
from pathlib import Path

import numpy as np
from matplotlib import animation as mpl_animation
from matplotlib import rc_context
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.result import OK, SINGULAR, Analysis
from linkage_sym.plotting import style
from linkage_sym.plotting.animation_files import (
    DEFAULT_FRAMES,
    EMBED_LIMIT_MB,
    SUFFIXES,
    AnimationError,
    check_fps,
    frame_steps,
    html_page,
    output_kind,
    positive,
    require_ffmpeg,
    self_contained,
)
from linkage_sym.plotting.animation_layers import COLORS, Layers
from linkage_sym.plotting.centres import KIND_STYLE
from linkage_sym.plotting.motion import driver_axis
from linkage_sym.plotting.cam_drawing import cam_outline, points_on_link
from linkage_sym.plotting.animation_scale import (CUT, PERCENTILE, cut_handle, cut_vectors,
                                                  typical_size)
from linkage_sym.plotting.breaks import gap_label, jump_notes_text, passage_note, passage_view
from linkage_sym.plotting.paths import (joint_point_links, mechanism_snapshot, traced_paths,
                                        valid_steps)

__all__ = ["ARROW_SHARE", "DEFAULT_FPS", "DEFAULT_FRAMES", "FADED", "LAYERS", "SUFFIXES",
           "AnimationError", "MechanismAnimation", "animate", "check_fps", "frame_steps",
           "output_kind", "require_ffmpeg", "self_contained"]

LAYERS = ("velocity", "acceleration", "forces", "centres", "transmission")
"""The layers an animation may draw over the mechanism, in drawing order."""

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

def _finite_rows(values) -> np.ndarray:
    v = np.asarray(values, dtype=float).reshape(-1, 2)
    return v[np.all(np.isfinite(v), axis=-1)]


class MechanismAnimation(Layers):
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
        self.dpi = positive("dpi", dpi, "dots per inch")
        self.layers = tuple(name for name in LAYERS if asked[name])
        self._check_layers()
        self.unit, self.unit_scale = style.length_unit(scene)
        self.L = scene.characteristic_length() or 1.0
        self.valid = valid_steps(analysis)
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
        self.longest = CUT * ARROW_SHARE * self.L * self.unit_scale  # a longer arrow is cut
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
        view = passage_view(self.scene, self.analysis, joint_point_links)

        far = {link for p in self.analysis.passages if p.before is not None for link in p.links}

        def per(items, names=None):
            if view is not None:  # the far points' values are unbounded: the rest set it
                biggest = typical_size(items, ok, view, self._carried(names, far))
            else:
                biggest = max((float(np.max(np.hypot(*_finite_rows(v[ok]).T), initial=0.0))
                               for _, v in items), default=0.0)
            return reach / biggest if biggest > 0.0 else 0.0

        out = {}
        for layer in ("velocity", "acceleration"):
            if layer in self.layers:
                vectors = self._vectors(layer)
                out[layer] = per([(p, v) for _, p, v in vectors], [n for n, _, _ in vectors])
        if "forces" in self.layers:
            out["reactions"] = per([(p, r) for _, p, r in self._reactions()])
            drivers = self._drivers()
            for kind, key, full in (("R", "driving", TORQUE_SWEEP), ("P", "driving force", reach)):
                values = [np.abs(v[ok & np.isfinite(v)]) for _, t, v in drivers if t == kind]
                biggest = max((float(np.max(v, initial=0.0)) for v in values), default=0.0)
                if view is not None and values:
                    biggest = float(np.percentile(np.concatenate(values), PERCENTILE))
                if values:
                    out[key] = full / biggest if biggest > 0.0 else 0.0
        return out

    def _carried(self, names, far) -> list | None:
        """Whether a passage carries off each joint or traced point of ``names``."""
        if names is None:
            return None
        links = {pt.name: {pt.link} for pt in self.scene.points}
        return [bool(far & links.get(n, set())) if n in links
                else bool(far & set(joint_point_links(self.scene.joint(n)))) for n in names]

    # -- the figure -------------------------------------------------------------------

    def _extent(self):
        """Corners (axis units) of everything drawn over the frames."""
        a, s = self.analysis, self.unit_scale
        view = passage_view(self.scene, a, joint_point_links)
        if view is None:
            pts = [np.asarray(j.at, dtype=float)[None, :] for j in self.scene.joints]
            pts += [np.asarray(jk.position, dtype=float) for jk in a.joints.values()]
            pts += [np.asarray(pk.position, dtype=float) for pk in (a.points or {}).values()]
            pts += [np.asarray(lk.com, dtype=float) for lk in a.links.values()
                    if lk.com is not None]
        else:  # points carried through infinity leave the drawing (and take their arrows)
            pts = [np.asarray(view, dtype=float)]
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
            p, v = p[self.steps][ok], v[self.steps][ok]
            if view is not None:
                inside = np.all((p >= view[0]) & (p <= view[1]), axis=-1)
                p, v = p[inside], v[inside]
            pts.append(p + cut_vectors(v, k, self.longest / s)[0])
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
        handles = [Line2D([], [], color=p.color, lw=p.lw, ls=p.ls,
                          label=gap_label(p.label, p.gaps, ",\n  ")) for p in self.paths]
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
        if any(p.before is not None for p in self.analysis.passages) and (
                {"velocity", "acceleration", "forces"} & set(self.layers)):
            out.append(cut_handle())
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
        for p in self.paths:  # grown up to the step, broken where it passes through infinity
            pos = p.drawn(step) * s
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
        self._passage_note(step)
        return [a for a in ax.get_children() if a not in before]

    def _passage_note(self, step: int) -> None:
        """On the frames of the two steps around a passage through infinity, what it breaks."""
        kinds = {d.joint: d.kind for d in self.scene.drivers}
        lines = [textwrap.fill(passage_note(self.analysis, p, kinds), 64)
                 for p in self.analysis.passages if step in (p.before, p.after)]
        lines += [text] if (text := jump_notes_text(self.scene, self.analysis, (step,), 64)) else []
        if lines:
            self.ax.text(0.98, 0.02, "\n".join(lines), transform=self.ax.transAxes, ha="right",
                         va="bottom", fontsize=8, color="0.2", zorder=20,
                         gid="passage through infinity",
                         bbox={"boxstyle": "round,pad=0.3", "fc": "white", "ec": "0.5",
                               "alpha": 0.92})

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
                Path(tmp).write_text(html_page(self.scene.name, self.to_jshtml()),
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
