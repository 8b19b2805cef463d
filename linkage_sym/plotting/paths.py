"""Coupler curves, joint paths and drawings of the mechanism.

A link is drawn from its joints' points: the point of a joint at a step is the
link's point whose assembly position is the joint's ``at``
(:meth:`~linkage_sym.numeric.results.result.LinkKinematics.point`); points on the ground
do not move.  Two points make a bar, more make the convex polygon of them.
Ground pivots are small hatched triangles, sliding pairs a slot along the axis
with a block on it.  A cam is its profile (the closed curve of its ``cam``
joint, :class:`~linkage_sym.numeric.kinematics.cam_profile.CamProfile`, in the cam's
frame) turning with it; the follower's element is drawn on the follower: a
roller's circle, a flat face's straight edge (a knife is its bar's end).

Only results are read here; nothing is solved.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.patches import Circle, Polygon

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.result import Analysis
from linkage_sym.plotting import style
from linkage_sym.plotting.breaks import (frame_passages, gap_label, gaps_of, note_jumps,
                                         passage_view, with_breaks)
from linkage_sym.plotting.cam_drawing import draw_cam


def _hull(points) -> list:
    """Convex hull of 2-D points, counter-clockwise (monotone chain)."""
    pts = sorted({(float(x), float(y)) for x, y in points})
    if len(pts) <= 2:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def link_points(scene: Scene) -> dict:
    """Assembly positions of the points that outline each moving link.

    A link's points are those of its ``R`` joints, of the ``P`` joints whose
    reference point is fixed on it (``links[1]``) and of the traced points
    (``points``) on it; the element point of a ``cam`` joint belongs to the
    follower (``links[1]``) only: the cam is drawn as its profile.  The guide of a ``P`` joint
    (``links[0]``) also gets the reference point when it has fewer than two
    other points, so that it is drawn as a bar.

    Returns
    -------
    dict
        ``{link: [(x, y), ...]}`` without repeated points.
    """
    pts = {name: [] for name in scene.link_names}
    guides = []
    for joint in scene.joints:
        for k, link in enumerate(joint.links):
            if link == GROUND or link not in pts:
                continue
            if joint.type == "P" and k == 0:
                guides.append((link, joint.at))
                continue
            if joint.type == "cam" and k == 0:  # the cam: its profile, not a bar to the follower
                continue
            if tuple(joint.at) not in pts[link]:
                pts[link].append(tuple(joint.at))
    for link, at in guides:
        if len(pts[link]) < 2 and tuple(at) not in pts[link]:
            pts[link].append(tuple(at))
    for pt in scene.points:  # a traced point is part of its link's body
        if pt.link in pts and tuple(pt.at) not in pts[pt.link]:
            pts[pt.link].append(tuple(pt.at))
    return pts


def valid_steps(analysis: Analysis) -> np.ndarray:
    """Mask of the steps at which every link has a position."""
    mask = np.ones(analysis.n_steps, dtype=bool)
    for lk in analysis.links.values():
        mask &= np.isfinite(np.asarray(lk.rotation, dtype=float))
        mask &= np.all(np.isfinite(np.asarray(lk.origin, dtype=float)), axis=-1)
    return mask


def _placer(analysis: Analysis, step):
    """Function ``(link, local xy) -> global xy`` at ``step`` (``None``: assembly)."""

    def place(link, local):
        local = np.asarray(local, dtype=float)
        if step is None or link == GROUND:
            return local
        return np.asarray(analysis.links[link].point(tuple(local))[step], dtype=float)

    def turn(link):
        if step is None or link == GROUND:
            return 0.0
        return float(analysis.links[link].rotation[step])

    return place, turn


def _ground_symbol(ax, p, size, alpha, zorder):
    """A hatched triangle under a ground pivot at ``p``."""
    x, y = p
    tri = Polygon([(x, y), (x - 0.6 * size, y - size), (x + 0.6 * size, y - size)],
                  closed=True, facecolor="0.85", edgecolor="0.2", lw=1.0, alpha=alpha,
                  zorder=zorder)
    ax.add_patch(tri)
    base = y - size
    ax.plot([x - 0.9 * size, x + 0.9 * size], [base, base], color="0.2", lw=1.0,
            alpha=alpha, zorder=zorder)
    for k in range(5):
        hx = x - 0.8 * size + k * 0.4 * size
        ax.plot([hx, hx - 0.3 * size], [base, base - 0.3 * size], color="0.2", lw=0.8,
                alpha=alpha, zorder=zorder)
    return [tri]


def _block(ax, centre, angle, length, width, color, alpha, zorder, gid=None):
    c, s = math.cos(angle), math.sin(angle)
    u, n = np.array([c, s]), np.array([-s, c])
    centre = np.asarray(centre, dtype=float)
    corners = [centre + a * 0.5 * length * u + b * 0.5 * width * n
               for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    patch = Polygon(corners, closed=True, facecolor=color, edgecolor="0.15", lw=1.0,
                    alpha=alpha, zorder=zorder, gid=gid)
    ax.add_patch(patch)
    return patch


def mechanism_snapshot(scene: Scene, analysis: Analysis, step, ax, *, alpha: float = 1.0,
                       labels: bool = False, unit_scale: float | None = None,
                       ground: bool = True) -> list:
    """Draw the mechanism at one step of a sweep on a Matplotlib axis.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        Only read when ``step`` is not ``None``.
    step : int or None
        Step index; ``None`` draws the assembly configuration of the scene.
    ax : matplotlib.axes.Axes
        Axis to draw on (give it an equal aspect).
    alpha : float, optional
        Opacity, e.g. 0.25 for faded snapshots.
    labels : bool, optional
        Write the joints' names next to their points.
    unit_scale : float, optional
        Factor from metres to the axis unit; default that of
        :func:`~linkage_sym.plotting.style.length_unit`.
    ground : bool, optional
        Draw the ground pivots and fixed slots (they do not move, so a
        caller drawing several snapshots draws them once).

    Returns
    -------
    list
        The artists drawn; empty when the step has no position (e.g. an
        ``unassemblable`` step).  The pin of an ``R`` joint (a circle centred on
        the joint's point) and the block of a ``P`` joint have the gid
        ``"joint NAME"``.
    """
    if unit_scale is None:
        unit_scale = style.length_unit(scene)[1]
    if step is not None and not valid_steps(analysis)[step]:
        return []
    place, turn = _placer(analysis, step)
    colors = style.link_colors(scene)
    L = scene.characteristic_length() or 1.0
    size = 0.045 * L * unit_scale
    base_z = 3 if alpha >= 1.0 else 2

    def P(link, local):
        return place(link, local) * unit_scale

    artists = _links(scene, ax, P, colors, alpha, base_z)
    artists += _sliding_pairs(scene, analysis, ax, P, turn, colors, alpha, base_z, unit_scale,
                              size, L, ground)
    for joint in scene.cams:  # the profile turning with the cam, the follower's roller or face
        artists += draw_cam(scene, analysis, joint, step, ax, unit_scale, alpha, base_z, colors)
    artists += _pins(scene, ax, P, alpha, base_z, size, ground)
    artists += _centres_of_mass(scene, ax, P, colors, alpha, base_z)
    if labels:
        artists += _joint_labels(scene, ax, P, size)
    return artists


def _links(scene, ax, P, colors, alpha, base_z) -> list:
    """Each link: a bar, or a convex polygon through its joints' points; the artists."""
    artists = []
    for link, local_pts in link_points(scene).items():
        pts = [P(link, q) for q in local_pts]
        col = colors.get(link, "0.3")
        if len(pts) == 2:
            (line,) = ax.plot([pts[0][0], pts[1][0]], [pts[0][1], pts[1][1]], color=col,
                              lw=4.0 if alpha >= 1.0 else 2.5, alpha=alpha,
                              solid_capstyle="round", zorder=base_z)
            artists.append(line)
        elif len(pts) > 2:
            hull = _hull(pts)
            poly = Polygon(hull, closed=True, facecolor=col, edgecolor=col,
                           alpha=0.35 * alpha, lw=2.0, zorder=base_z)
            edge = Polygon(hull, closed=True, fill=False, edgecolor=col, lw=2.0,
                           alpha=alpha, zorder=base_z)
            ax.add_patch(poly)
            ax.add_patch(edge)
            artists += [poly, edge]
    return artists


def _sliding_pairs(scene, analysis, ax, P, turn, colors, alpha, base_z, unit_scale, size, L,
                   ground) -> list:
    """Each sliding pair: a slot on ``links[0]`` (a fixed one only with ``ground``), a block
    fixed on ``links[1]`` (gid ``"joint NAME"``); the artists."""
    artists = []
    for joint in scene.joints:
        if joint.type != "P":
            continue
        guide, slider = joint.links
        angle = joint.axis + turn(guide)
        centre = P(slider, joint.at)
        u = np.array([math.cos(angle), math.sin(angle)])
        if guide != GROUND:
            half = 0.18 * L * unit_scale
            (slot,) = ax.plot(*np.transpose([centre - half * u, centre + half * u]),
                              color=colors.get(guide, "0.3"), lw=7.0, alpha=0.45 * alpha,
                              solid_capstyle="butt", zorder=base_z)
            artists.append(slot)
        elif ground:
            artists += _ground_slot(scene, analysis, joint, ax, unit_scale, alpha)
        blk_col = colors.get(slider, "0.6") if slider != GROUND else "0.85"
        artists.append(_block(ax, centre, angle, 2.2 * size, 1.3 * size, blk_col, alpha,
                              base_z + 1, gid=f"joint {joint.name}"))
    return artists


def _pins(scene, ax, P, alpha, base_z, size, ground) -> list:
    """Each ``R`` joint's pin (gid ``"joint NAME"``) and, with ``ground``, the ground symbol
    of a pivot; the artists."""
    artists = []
    for joint in scene.joints:
        on = joint.links[1] if joint.links[1] != GROUND else joint.links[0]
        p = P(on, joint.at)
        if joint.type == "R":
            if GROUND in joint.links and ground:
                artists += _ground_symbol(ax, p, size, alpha, base_z - 0.5)
            pin = Circle(p, 0.22 * size, facecolor="white", edgecolor="0.1", lw=1.2,
                         alpha=alpha, zorder=base_z + 2, gid=f"joint {joint.name}")
            ax.add_patch(pin)
            artists.append(pin)
    return artists


def _centres_of_mass(scene, ax, P, colors, alpha, base_z) -> list:
    """Each link's centre of mass, a circle with a cross; the artists."""
    artists = []
    for link in scene.links:
        if link.com is None:
            continue
        c = P(link.name, link.com)
        ms = 7 if alpha >= 1.0 else 5
        (m,) = ax.plot([c[0]], [c[1]], marker="o", ms=ms, mfc="white",
                       mec=colors.get(link.name), mew=1.3, ls="none", alpha=alpha,
                       zorder=base_z + 2)
        (x,) = ax.plot([c[0]], [c[1]], marker="+", ms=ms, mec=colors.get(link.name),
                       mew=1.3, ls="none", alpha=alpha, zorder=base_z + 2)
        artists += [m, x]
    return artists


def _ground_slot(scene, analysis, joint, ax, unit_scale, alpha):
    """The fixed slot of a slider on the ground, long enough for its travel."""
    u = np.array([math.cos(joint.axis), math.sin(joint.axis)])
    at = np.asarray(joint.at, dtype=float)
    s = [0.0]
    lk = analysis.links.get(joint.links[1]) if analysis is not None else None
    if lk is not None:
        pos = np.asarray(lk.point(joint.at), dtype=float)
        d = (pos - at) @ u
        d = d[np.isfinite(d)]
        if d.size:
            s += [float(d.min()), float(d.max())]
    L = scene.characteristic_length() or 1.0
    lo, hi = min(s) - 0.12 * L, max(s) + 0.12 * L
    a, b = (at + lo * u) * unit_scale, (at + hi * u) * unit_scale
    (slot,) = ax.plot([a[0], b[0]], [a[1], b[1]], color="0.55", lw=9.0, alpha=0.35 * alpha,
                      solid_capstyle="butt", zorder=1)
    return [slot]


def _joint_labels(scene, ax, P, size):
    """Names of the joints at their points; coincident joints share one label."""
    out = []
    for p, names in joint_label_groups(scene, P, size):
        t = ax.annotate(", ".join(names), xy=p, xytext=(7, 7), textcoords="offset points",
                        fontsize=10, fontweight="bold", color="0.1", zorder=10,
                        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                              "alpha": 0.7})
        out.append(t)
    return out


def joint_label_groups(scene, P, size) -> list:
    """``[(point, [joint names])]``: the joints' points, coincident ones (closer than
    ``1e-3 size``) in one group; ``P(link, local)`` places a point in the drawing."""
    groups = []
    for joint in scene.joints:
        on = joint.links[1] if joint.links[1] != GROUND else joint.links[0]
        p = P(on, joint.at)
        for g in groups:
            if np.hypot(*(g[0] - p)) < 1e-3 * size:
                g[1].append(joint.name)
                break
        else:
            groups.append([p, [joint.name]])
    return [(p, names) for p, names in groups]


def _still(path, scene) -> bool:
    """Whether a path (N, 2) has no finite point or does not move."""
    path = np.asarray(path, dtype=float)
    finite = path[np.all(np.isfinite(path), axis=-1)]
    if finite.size == 0:
        return True
    span = float(np.max(np.ptp(finite, axis=0)))
    return span <= 1e-9 * (scene.characteristic_length() or 1.0)


def _figure_for(scene, analysis, view=None):
    """A figure whose axis has roughly the aspect of the drawing (equal scales); of the box
    ``view`` (:func:`~linkage_sym.plotting.breaks.passage_view`) when given."""
    pts = [np.asarray(j.at, dtype=float)[None, :] for j in scene.joints]
    if view is not None:
        pts = [np.asarray(view, dtype=float)]
    for jk in analysis.joints.values() if view is None else ():
        pts.append(np.asarray(jk.position, dtype=float))
    for lk in analysis.links.values() if view is None else ():
        if lk.com is not None:
            pts.append(np.asarray(lk.com, dtype=float))
    allp = np.concatenate(pts, axis=0)
    allp = allp[np.all(np.isfinite(allp), axis=-1)]
    L = scene.characteristic_length() or 1.0
    dx, dy = (np.ptp(allp, axis=0) if allp.size else (L, L))
    dx, dy = max(dx, 0.2 * L), max(dy, 0.2 * L)
    ax_w = 7.2
    ax_h = float(np.clip(ax_w * dy / dx, 3.0, 8.5))
    return style.new_figure(ax_w + 2.8, ax_h + 1.4)


def _same_path(a, b) -> bool:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return False
    fa, fb = np.isfinite(a), np.isfinite(b)
    return bool(np.array_equal(fa, fb) and np.allclose(a[fa], b[fb], rtol=0, atol=1e-12))


@dataclass(frozen=True)
class TracedPath:
    """One path the pictures of a sweep draw (:func:`traced_paths`).

    Attributes
    ----------
    position : ndarray, shape (N, 2)
        The path over the sweep (m), NaN where a step has no position.
    label : str
        Legend entry: ``path of B, C`` (coincident joints share one path) or
        ``point P (on coupler)``.
    color : str
        The colour of the link the point is fixed on.
    ls : str or tuple
        Line style, telling apart paths of one colour.
    lw : float
        Line width: traced points (the coupler curves) bold.
    zorder : float
    point : ScenePoint or None
        The traced point of the scene, for a traced point's path.
    gaps : tuple of int
        The steps after which the path breaks: a passage through infinity carries its
        point off between them and the next (:func:`~linkage_sym.plotting.breaks.gaps_of`).
    """

    position: np.ndarray
    label: str
    color: str
    ls: object
    lw: float
    zorder: float
    point: object = None
    gaps: tuple = ()

    def drawn(self, upto: int | None = None) -> np.ndarray:
        """The path as it is drawn: up to step ``upto`` (default the last), with a NaN row
        after each of :attr:`gaps` (a break in the line)."""
        stop = len(self.position) if upto is None else upto + 1
        return with_breaks([g for g in self.gaps if g + 1 < stop], self.position[:stop])[0]


PATH_STYLES = ("-", (0, (6, 2)), (0, (1, 1.5)), (0, (6, 2, 1, 2)))
"""Line styles of paths that share a colour, in turn."""


def joint_point_links(joint) -> tuple:
    """The links whose poses place a joint's point: both links of a pin or a cam's contact,
    the link a slide's or a mesh's point is fixed on (:attr:`Joint.moves_with`)."""
    return tuple(joint.links) if joint.type in ("R", "cam") else (joint.moves_with,)


def traced_paths(scene: Scene, analysis: Analysis) -> list:
    """The paths of the moving joints, then of the traced points, as they are drawn.

    Every joint point fixed on a moving ``links[1]`` that moves (a pivot on a
    crank's ground axis does not), coincident paths merged into one entry; then
    the coupler curve of every traced point of the scene (``points``), bold.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis

    Returns
    -------
    list of TracedPath
    """
    jcolors = style.joint_colors(scene)
    lcolors = style.link_colors(scene)
    drawn = []  # (path, legend entry) to merge coincident joints
    for joint in scene.joints:
        if joint.links[1] == GROUND:
            continue
        jk = analysis.joints.get(joint.name)
        if jk is None:
            continue
        pos = np.asarray(jk.position, dtype=float)
        if _still(pos, scene):
            continue  # a pivot that does not move (e.g. on a crank's ground axis)
        for entry in drawn:
            if _same_path(entry[0], pos):
                entry[1].append(joint.name)
                break
        else:
            drawn.append([pos, [joint.name], jcolors.get(joint.name)])
    out = []
    per_color = {}
    for pos, names, col in drawn:
        k = per_color.get(col, 0)
        per_color[col] = k + 1
        gaps = gaps_of(analysis, [k for n in names for k in joint_point_links(scene.joint(n))])
        out.append(TracedPath(pos, f"path of {', '.join(names)}", col,
                              PATH_STYLES[k % len(PATH_STYLES)], 1.6, 4, gaps=gaps))
    points = getattr(analysis, "points", {}) or {}
    for k, pt in enumerate(scene.points):
        pk = points.get(pt.name)
        if pk is None:
            continue
        out.append(TracedPath(np.asarray(pk.position, dtype=float),
                              f"point {pt.name} (on {pt.link})", lcolors.get(pt.link),
                              PATH_STYLES[k % len(PATH_STYLES)], 2.4, 5, pt,
                              gaps_of(analysis, [pt.link])))
    return out


def snapshot_steps(analysis: Analysis, count: int = 4) -> list:
    """``count`` step indices spread over the solved steps (at 1/8, 3/8, ... of them)."""
    valid = np.flatnonzero(valid_steps(analysis))
    if valid.size == 0:
        return []
    count = min(count, valid.size)
    picks = [valid[int((2 * k + 1) * valid.size / (2 * count))] for k in range(count)]
    return sorted({int(p) for p in picks})


def coupler_curves(scene: Scene, analysis: Analysis, out_file) -> Path:
    """Write :func:`coupler_curves_figure` as a PNG at ``out_file``; returns the path."""
    return style.save(coupler_curves_figure(scene, analysis), out_file)


def coupler_curves_figure(scene: Scene, analysis: Analysis):
    """The paths of the joints, traced points and centres of mass over the sweep.

    The figure shows, with an equal aspect ratio, the path of every moving
    joint point (the point fixed on the joint's ``links[1]``; a point on the
    ground has none), bold the coupler curve of every traced point of the
    scene (``points``), dashed the path of every link's centre of mass, the
    mechanism in its assembly configuration with the joints' names, and faded
    the mechanism at four steps spread over the sweep.  Steps without a
    solution break the paths.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis

    Returns
    -------
    matplotlib.figure.Figure
    """
    unit, scale = style.length_unit(scene)
    view = passage_view(scene, analysis, joint_point_links)
    fig = _figure_for(scene, analysis, view)
    ax = fig.subplots()
    ax.set_aspect("equal", adjustable="datalim")

    # faded snapshots first, then the bold assembly configuration on top
    snaps = snapshot_steps(analysis)
    for step in snaps:
        mechanism_snapshot(scene, analysis, step, ax, alpha=0.22, unit_scale=scale,
                           ground=False)
    mechanism_snapshot(scene, analysis, None, ax, alpha=1.0, labels=True, unit_scale=scale)

    for path in traced_paths(scene, analysis):
        pos = path.drawn() * scale
        ax.plot(pos[:, 0], pos[:, 1], color=path.color, lw=path.lw, ls=path.ls,
                zorder=path.zorder, label=gap_label(path.label, path.gaps))
        if path.point is not None:
            pt = path.point
            ax.plot([pt.at[0] * scale], [pt.at[1] * scale], marker="o", ms=6, mfc="white",
                    mec=path.color, mew=1.6, zorder=6, ls="none")
            ax.annotate(pt.name, (pt.at[0] * scale, pt.at[1] * scale), textcoords="offset points",
                        xytext=(6, 4), fontsize=10, fontweight="bold", color="0.1", zorder=6)
    lcolors = style.link_colors(scene)
    for link in scene.links:
        lk = analysis.links.get(link.name)
        if lk is None or lk.com is None:
            continue
        com = np.asarray(lk.com, dtype=float)
        if _still(com, scene):
            continue
        gaps = gaps_of(analysis, [link.name])
        com = with_breaks(gaps, com)[0]
        ax.plot(com[:, 0] * scale, com[:, 1] * scale, color=lcolors.get(link.name), lw=1.0,
                ls=(0, (2, 2)), alpha=0.9, zorder=4,
                label=gap_label(f"centre of mass of {link.name}", gaps))

    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.grid(True, color="0.92", lw=0.6, zorder=0)
    ax.autoscale_view()
    ax.margins(0.08)
    if view is not None:  # the points carried through infinity leave the drawing
        frame_passages(ax, scene, analysis, view, scale)
    else:
        note_jumps(ax, scene, analysis)
    where = ", ".join(str(s) for s in snaps)
    ax.set_title(f"{scene.name}: {'coupler curves, ' if scene.points else ''}joint and centre-of-mass paths\n"
                 f"bold: assembly configuration; faded: steps {where}" if snaps else
                 f"{scene.name}: assembly configuration (no solved step)", fontsize=11)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    return fig
