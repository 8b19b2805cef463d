"""Pictures of the instant centres, the centrodes and the velocity and acceleration polygons.

Three figures of one step of a sweep, drawn as the textbook chapter *Kinematic analysis of planar mechanisms* draws
them (README Sources [4]: Figs. 3-1, 3-2, 3-4, 3-6):

:func:`centres_figure`
    The linkage with every instant centre, named ``P13`` (the ground is link
    1) and the three-centre lines Kennedy's construction used.
:func:`centrodes_figure`
    The fixed centrode of each floating link, and its moving centrode carried
    to the step, touching the fixed one at the instant centre.
:func:`polygons_figure`
    The velocity polygon (pole ``p``) and the acceleration polygon (pole
    ``p'``) to scale, with the normal and tangential components about each
    link's first pivot and, for a sliding pair, the Coriolis and slip terms.

Only results are read here (:mod:`linkage_sym.centres`); nothing is solved.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import FancyArrowPatch

from linkage_sym.model import GROUND
from linkage_sym.plotting import style
from linkage_sym.plotting.cam_drawing import cam_outline, points_on_link
from linkage_sym.plotting.paths import joint_label_groups, mechanism_snapshot

__all__ = ["centres_figure", "centrodes_figure", "polygons_figure", "three_centre_segments"]

VIEW = 2.5
"""Centres and centrode points farther than this many mechanism sizes from the
mechanism's middle are listed beside the drawing instead of drawn."""

KIND_STYLE = {
    "joint": {"marker": "o", "mfc": "0.1", "mec": "0.1", "ms": 6},
    "kennedy": {"marker": "o", "mfc": "#d62728", "mec": "#d62728", "ms": 7},
    "velocity": {"marker": "s", "mfc": "white", "mec": "#1f77b4", "ms": 7},
}


def _middle(scene, analysis, step):
    """Middle (m) of the joints at ``step`` and the mechanism's size (m)."""
    pts = np.array([analysis.joints[j.name].position[step] for j in scene.joints], dtype=float)
    return pts.mean(axis=0), scene.characteristic_length() or 1.0


def centre_kind(centres, k):
    """How centre ``k`` was found: ``"kennedy"`` (three-centre lines), ``"velocity"`` (from the
    velocities, where the lines do not reach it) or ``"joint"``."""
    src = centres.source[k]
    return "kennedy" if src == "three-centre lines" else ("velocity" if src == "unreachable" else "joint")


def _fmt_point(p, scale, unit):
    return f"({p[0] * scale:.4g}, {p[1] * scale:.4g}) {unit}"


def three_centre_segments(centres, step, L) -> list:
    """The three-centre lines Kennedy's construction used at ``step``, as drawn segments.

    Each centre found by three-centre lines lies on two lines through two known
    centres each (``P_ik``, ``P_kj`` and ``P_ij`` on one line); each line is
    drawn through its centres and a little beyond, or, where one of them is at
    infinity, through the finite ones along its direction.

    Parameters
    ----------
    centres : InstantCentres
    step : int
    L : float
        The mechanism's size (m): the shortest segment drawn is ``0.3 L``.

    Returns
    -------
    list of ndarray, shape (2, 2)
        The ends of each segment (m), each line once per centre it finds.
    """
    k_all = centres.kennedy
    pos = centres.position[step]
    names = centres.links

    def centre_at(i, j):
        """Finite position or ('inf', direction) of pair (links i, j) at the step, or None."""
        k = centres.index(names[i], names[j])
        if centres.at_infinity[step, k]:
            return "inf", centres.direction[step, k]
        p = pos[k]
        return ("pt", p) if np.all(np.isfinite(p)) else None

    # three-centre lines of the Kennedy centres: P_ik, P_kj, P_ij on one line
    drawn = set()
    out = []
    for k, (a, b) in enumerate(centres.pairs):
        if centre_kind(centres, k) != "kennedy" or centres.undefined[step, k] or centres.at_infinity[step, k]:
            continue
        i, j = names.index(a), names.index(b)
        target = pos[k]
        for third in k_all.via[step, k]:
            if third < 0:
                continue
            ends = [centre_at(i, third), centre_at(third, j)]
            if any(e is None for e in ends):
                continue
            line = tuple(sorted((frozenset((i, third)), frozenset((third, j))), key=sorted))
            pts = [target] + [e[1] for e in ends if e[0] == "pt"]
            dirs = [e[1] for e in ends if e[0] == "inf"]
            if dirs:  # through a point along the direction of the centre at infinity
                u = dirs[0]
                t = [(p - pts[0]) @ u for p in pts]
                span = max(max(t) - min(t), 0.3 * L)
                seg = [pts[0] + (min(t) - 0.15 * span) * u, pts[0] + (max(t) + 0.15 * span) * u]
            else:
                u = pts[1] - pts[0] if len(pts) > 1 else np.array([1.0, 0.0])
                n = np.hypot(*u)
                u = u / n if n > 0 else np.array([1.0, 0.0])
                t = [(p - pts[0]) @ u for p in pts]
                span = max(max(t) - min(t), 0.3 * L)
                seg = [pts[0] + (min(t) - 0.08 * span) * u, pts[0] + (max(t) + 0.08 * span) * u]
            if (line, k) in drawn:
                continue
            drawn.add((line, k))
            out.append(np.array(seg))
    return out


def centres_figure(scene, analysis, centres, step, out_file):
    """Write the linkage at ``step`` with its instant centres and three-centre lines (PNG).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    centres : InstantCentres
        From :func:`linkage_sym.centres.instant_centres`.
    step : int
    out_file : str or os.PathLike

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, linkage_sym
    >>> from linkage_sym.centres import instant_centres
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     path = centres_figure(scene, res, instant_centres(scene, res), 40, f"{d}/c.png")
    ...     path.name, path.read_bytes()[:4]
    ('c.png', b'\\x89PNG')
    """
    unit, scale = style.length_unit(scene)
    mid, L = _middle(scene, analysis, step)
    fig = style.new_figure(10.5, 7.0)
    ax = fig.subplots()
    ax.set_aspect("equal", adjustable="box")
    mechanism_snapshot(scene, analysis, step, ax, labels=False, unit_scale=scale)
    pos = centres.position[step]
    names = centres.links
    listed = []  # text beside the drawing

    def near(p):
        return bool(np.all(np.isfinite(p))) and np.hypot(*(p - mid)) <= VIEW * L

    for seg in three_centre_segments(centres, step, L):
        seg = seg * scale
        ax.plot(seg[:, 0], seg[:, 1], color="#d62728", lw=0.7, ls=(0, (5, 3)), alpha=0.55,
                zorder=2)

    labels = []  # [position, [labels], colour]
    drawn_at = []  # every centre drawn (m): a label keeps off them
    far = []  # (tip, label) of the centres at infinity shown at their slides
    for k in range(len(centres.pairs)):
        label = centres.label(k)
        a, b = centres.pairs[k]
        if centres.undefined[step, k]:
            listed.append(f"{label} ({a}, {b}): undefined (no relative motion)")
            continue
        if centres.at_infinity[step, k]:
            u = centres.direction[step, k]
            listed.append(f"{label} ({a}, {b}): at infinity, direction ({u[0]:.3f}, {u[1]:.3f})")
            src = centres.source[k]
            if src.startswith("joint ") and src.endswith(" (slide)"):  # show it at the slide
                at = np.asarray(analysis.joints[src[6:-8]].position[step], dtype=float)
                for sign in (1.0, -1.0):
                    _arrow(ax, at * scale, (at + sign * 0.16 * L * u) * scale, "0.1", lw=0.9, z=8)
                far.append(((at + 0.16 * L * u) * scale, label + " → ∞"))
            continue
        p = pos[k]
        if not np.all(np.isfinite(p)):
            continue
        kind = "velocity" if centres.from_velocities[step, k] else centre_kind(centres, k)
        if not near(p):
            listed.append(f"{label} ({a}, {b}): {_fmt_point(p, scale, unit)}, off the drawing")
            continue
        st = KIND_STYLE[kind]
        ax.plot([p[0] * scale], [p[1] * scale], ls="none", zorder=8, **st)
        drawn_at.append(p)
        for group in labels:  # centres close together share one label
            if np.hypot(*(group[0] - p)) <= 0.03 * L:
                group[1].append(label)
                break
        else:
            labels.append([p, [label], st["mec"]])

    text = _key(ax, centres, step, listed)
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.grid(True, color="0.92", lw=0.6, zorder=0)
    n = len(names)
    ax.set_title(f"{scene.name}: {n * (n - 1) // 2} = {n}·{n - 1}/2 instant centres at step {step}",
                 fontsize=11)
    # the drawing fills the axes: limits around what is drawn, a figure of its proportions
    lo, hi = _drawn_box(scene, analysis, step, drawn_at, L)
    _fit(fig, ax, lo * scale, hi * scale, text.count("\n") + 1 + len(listed))
    points = [np.asarray(analysis.joints[j.name].position[step], dtype=float) * scale
              for j in scene.joints] + [p * scale for p in drawn_at]
    # the joints' names, then the centres' (none covers another, nor a point)

    def place(link, local):
        if link == GROUND:
            return np.asarray(local, dtype=float) * scale
        return np.asarray(analysis.links[link].point(tuple(local))[step], dtype=float) * scale

    size = 0.045 * L * scale
    joints = [(p, ", ".join(n), "0.1") for p, n in joint_label_groups(scene, place, size)]
    place_labels(fig, ax, joints, points, size=10, weight="bold", offsets=JOINT_OFFSETS)
    place_labels(fig, ax, [(p, text, "0.1") for p, text in far], points)
    place_labels(fig, ax, [(p * scale, ", ".join(n), c) for p, n, c in labels], points)
    return style.save(fig, out_file)


def _key(ax, centres, step, listed) -> str:
    """The legend of the markers and lines, and beside the drawing the links' numbering with
    the centres not drawn (``listed``); returns that text."""
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], ls="none", label="centre at a joint", **KIND_STYLE["joint"]),
               Line2D([], [], ls="none", label="centre by three-centre lines (Kennedy)",
                      **KIND_STYLE["kennedy"]),
               Line2D([], [], color="#d62728", lw=0.7, ls=(0, (5, 3)), label="three-centre line")]
    if centres.from_velocities[step].any():
        handles.insert(2, Line2D([], [], ls="none", label="centre from the velocities "
                                 "(three-centre lines run out)", **KIND_STYLE["velocity"]))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8,
              frameon=False)
    numbers = ", ".join(f"{i + 1} {n}" for i, n in enumerate(centres.links))
    text = "numbering: " + numbers + ("\n" + "\n".join(listed) if listed else "")
    ax.text(1.02, 0.0, text, transform=ax.transAxes, fontsize=7.5, va="bottom", ha="left",
            color="0.2", wrap=True, gid="numbering")
    return text


def _drawn_box(scene, analysis, step, centres_drawn, L):
    """Corners (m) of what the centres figure draws at ``step``: joints, traced points,
    centres of mass and the centres drawn, with room for the ground symbols and labels."""
    pts = [np.asarray(analysis.joints[j.name].position[step], dtype=float) for j in scene.joints]
    pts += [np.asarray(pk.position[step], dtype=float)
            for pk in (getattr(analysis, "points", {}) or {}).values()]
    pts += [np.asarray(lk.com[step], dtype=float) for lk in analysis.links.values()
            if lk.com is not None]
    pts += list(centres_drawn)
    for joint in scene.cams:  # a cam is its profile
        pts += list(points_on_link(analysis, joint.links[0], step, cam_outline(joint)[0]))
    pts = np.array([p for p in pts if np.all(np.isfinite(p))])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.06 * float((hi - lo).max()) + 0.08 * L
    return lo - pad, hi + pad


def _fit(fig, ax, lo, hi, text_lines):
    """Size ``fig`` so that an equal-aspect axes showing ``lo``..``hi`` fills its room
    (beside it: the legend and ``text_lines`` lines of notes)."""
    dx, dy = float(hi[0] - lo[0]), float(hi[1] - lo[1])
    ax_w, ax_h = 7.0, 7.0 * dy / dx
    if ax_h > 7.5:
        ax_h = 7.5
        ax_w = max(7.5 * dx / dy, 3.5)
    ax_h = max(ax_h, 3.0, 1.2 + 0.16 * text_lines)  # room for the legend and the notes
    fig.set_size_inches(ax_w + 3.7, ax_h + 1.0)
    ax.set_aspect("auto")
    fig.draw_without_rendering()  # the room the layout leaves the axes
    box = ax.get_window_extent()
    # widen the short side to the room's proportions: equal scales, no room left over
    mid, half = 0.5 * (np.asarray(lo) + np.asarray(hi)), 0.5 * np.array([dx, dy])
    if dy / dx < box.height / box.width:
        half[1] = half[0] * box.height / box.width
    else:
        half[0] = half[1] * box.width / box.height
    ax.set_xlim(mid[0] - half[0], mid[0] + half[0])
    ax.set_ylim(mid[1] - half[1], mid[1] + half[1])
    ax.set_aspect("equal", adjustable="box")


OFFSETS = tuple((r * dx, r * dy) for r in (1.0, 2.2, 3.4) for dx, dy in
                ((6, -8), (6, 6), (-6, 6), (-6, -8), (0, -12), (0, 10), (9, 0), (-9, 0)))
"""Where a centre's label may go (points from the centre, nearest first)."""

JOINT_OFFSETS = OFFSETS[1:2] + OFFSETS[:1] + OFFSETS[2:]
"""A joint's name: above right first, as every other drawing of the mechanism has it."""


def place_labels(fig, ax, items, points, size=9, weight="normal", offsets=OFFSETS):
    """Write each label next to its point where it covers no other label nor point.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Laid out here (the labels are placed in its final pixels).
    ax : matplotlib.axes.Axes
        Its texts already written (the joints' names) are kept clear of.
    items : list of (ndarray, str, colour)
        Point (axis units), text and colour of each label.
    points : list of ndarray
        Points (axis units) no label may cover: the joints, the centres.
    size : float
        Font size.
    weight : str
        Font weight.
    offsets : sequence of (float, float)
        The places tried, in points from the point, in order.

    Returns
    -------
    list of matplotlib.text.Annotation
        Placed at the first of :data:`OFFSETS` that overlaps nothing inside the axes
        (by the renderer's extents), else where it overlaps least; a label away from its
        point gets a thin leader line.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.transforms import Bbox

    if not items:
        return []
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    fig.draw_without_rendering()  # the final layout and limits
    renderer = canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = [t.get_window_extent(renderer).padded(2)
             for t in ax.texts if t.get_visible() and t.get_gid() != "numbering"]
    r = 4.0 * fig.dpi / 72.0  # a marker's half size, pixels
    for p in points:
        if np.all(np.isfinite(p)):
            x, y = ax.transData.transform(p)
            taken.append(Bbox([[x - r, y - r], [x + r, y + r]]))

    def overlap(a, b):
        w = min(a.x1, b.x1) - max(a.x0, b.x0)
        h = min(a.y1, b.y1) - max(a.y0, b.y0)
        return w * h if w > 0 and h > 0 else 0.0

    out = []
    for p, text, color in items:
        best = None
        for dx, dy in offsets:
            ha = "left" if dx > 0 else "right" if dx < 0 else "center"
            va = "bottom" if dy > 0 else "top" if dy < 0 else "center"
            leader = ({"arrowstyle": "-", "color": color, "lw": 0.6, "shrinkA": 0,
                       "shrinkB": 3} if math.hypot(dx, dy) > 16 else None)  # away from its point
            t = ax.annotate(text, tuple(p), xytext=(dx, dy), textcoords="offset points",
                            ha=ha, va=va, fontsize=size, fontweight=weight, color=color,
                            zorder=9,
                            bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                                  "alpha": 0.75}, arrowprops=leader)
            box = t.get_window_extent(renderer).padded(1)
            outside = not (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0
                           and box.y1 <= frame.y1)
            cost = sum(overlap(box, b) for b in taken) + (1e9 if outside else 0.0)
            if best is None or cost < best[0]:
                if best is not None:
                    best[1].remove()
                best = (cost, t, box)
            else:
                t.remove()
            if cost == 0.0:
                break
        _, t, box = best
        taken.append(box)
        out.append(t)
    return out


def _broken(path, mid, L):
    """A centrode (N, 2) with its far points NaN and breaks where it jumps."""
    path = np.array(path, dtype=float)
    far = ~np.all(np.isfinite(path), axis=-1) | (np.hypot(*(path - mid).T) > VIEW * L)
    path[far] = np.nan
    jump = np.hypot(*np.diff(path, axis=0).T) > 0.5 * L
    path[1:][jump] = np.nan
    return path


def centrodes_figure(scene, analysis, centres, step, centrodes, out_file):
    """Write the fixed and moving centrodes of the floating links (PNG).

    The mechanism is drawn at ``step`` of ``analysis``; each fixed centrode is
    solid, its moving centrode (fixed on the link) is dashed where the link
    is at that step, and the two touch at the link's instant centre (marked).
    Points more than ``VIEW`` mechanism sizes away (the centre runs off to
    infinity where the link stops turning) are left out.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        The solved step to draw (a sweep, or one step solved on its own).
    centres : InstantCentres
        The centres of ``analysis``.
    step : int
        Step of ``analysis``.
    centrodes : dict of str to Centrode
        The curves, from a sweep (:func:`linkage_sym.centres.centrodes`).
    out_file : str or os.PathLike

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, linkage_sym
    >>> from linkage_sym.centres import centrodes, instant_centres
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> ic = instant_centres(scene, res)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     path = centrodes_figure(scene, res, ic, 40, centrodes(scene, res, ic), f"{d}/c.png")
    ...     path.read_bytes()[:4]
    b'\\x89PNG'
    """
    unit, scale = style.length_unit(scene)
    mid, L = _middle(scene, analysis, step)
    colors = style.link_colors(scene)
    fig = style.new_figure(12.5, 7.0)
    ax = fig.subplots()
    ax.set_aspect("equal", adjustable="box")
    mechanism_snapshot(scene, analysis, step, ax, labels=True, unit_scale=scale)
    for name, c in centrodes.items():
        col = colors.get(name, "0.3")
        fixed = _broken(c.fixed, mid, L) * scale
        moving = _broken(c.moving_at(analysis, step), mid, L) * scale
        ax.plot(fixed[:, 0], fixed[:, 1], color=col, lw=2.0, zorder=5,
                label=f"fixed centrode of {name} (on the ground)")
        ax.plot(moving[:, 0], moving[:, 1], color=col, lw=1.6, ls=(0, (5, 2)), zorder=5,
                label=f"moving centrode of {name} (on {name}, at step {step})")
        p = centres.position[step, centres.index(GROUND, name)]
        if np.all(np.isfinite(p)) and np.hypot(*(p - mid)) <= VIEW * L:
            ax.plot([p[0] * scale], [p[1] * scale], marker="o", ms=8, mfc="white", mec=col,
                    mew=2.0, zorder=7, ls="none", label=f"instant centre of {name} and the ground")
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.grid(True, color="0.92", lw=0.6, zorder=0)
    ax.set_xlim((mid[0] - VIEW * L) * scale, (mid[0] + VIEW * L) * scale)
    ax.set_ylim((mid[1] - VIEW * L) * scale, (mid[1] + VIEW * L) * scale)
    ax.set_title(f"{scene.name}: centrodes over the sweep; the moving one rolls on the fixed one\n"
                 f"(drawn at step {step}; points beyond {VIEW:g} mechanism sizes left out)",
                 fontsize=11)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    return style.save(fig, out_file)


def _arrow(ax, a, b, color, lw=1.4, ls="-", z=4):
    if np.hypot(*(np.asarray(b) - np.asarray(a))) == 0.0:
        return
    ax.add_patch(FancyArrowPatch(tuple(a), tuple(b), arrowstyle="-|>", mutation_scale=11,
                                 color=color, lw=lw, ls=ls, zorder=z, shrinkA=0, shrinkB=0))


def _labels(ax, vertices, prime):
    """Vertex names (lower case, as the textbook writes them), merged where vertices coincide."""
    groups = []
    span = max(float(np.ptp(np.array([v for _, v in vertices]), axis=0).max()), 1e-300)
    for name, v in vertices:
        for g in groups:
            if np.hypot(*(g[0] - v)) <= 1e-6 * span:
                g[1].append(name)
                break
        else:
            groups.append([v, [name]])
    for v, names in groups:
        # the textbook's lower-case vertex names; a point named P... keeps its capital (p: the pole)
        low = [n[0].lower() + n[1:] for n in names]
        text = ", ".join((n if lo.startswith("p") else lo) + prime for n, lo in zip(names, low))
        ax.annotate(text, tuple(v), xytext=(5, 4), textcoords="offset points", fontsize=9,
                    color="0.1", zorder=9,
                    bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.75})


def polygons_figure(scene, polygons, out_file):
    """Write the velocity and acceleration polygons of one step, to scale (PNG).

    Left, the velocity polygon: from the pole ``p`` (zero velocity: every
    ground point) an arrow to each point's vertex (its absolute velocity); the
    vertices of one link's points make that link's velocity image; a sliding
    pair adds its slip velocity from the guide's coincident point to the
    slider's (``b4 -> b3``).  Right, the acceleration polygon from the pole
    ``p'``: absolute accelerations; about each link's first pivot the normal
    component (to ``n'``) and the tangential one (on to the point's vertex);
    for a sliding pair the Coriolis term (to ``k'``) and the slip
    acceleration (on to the slider's vertex).

    Parameters
    ----------
    scene : Scene
    polygons : Polygons
        From :func:`linkage_sym.centres.polygon_quantities`.
    out_file : str or os.PathLike

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, linkage_sym
    >>> from linkage_sym.centres import polygon_quantities
    >>> scene = linkage_sym.load_example("guide_bar_quick_return")
    >>> pq = polygon_quantities(scene, linkage_sym.analyze(scene), 0)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     polygons_figure(scene, pq, f"{d}/p.png").read_bytes()[:4]
    b'\\x89PNG'
    """
    colors = style.link_colors(scene)
    fig = style.new_figure(13.0, 6.6)
    axv, axa = fig.subplots(1, 2)
    moving = [p for p in polygons.points if p.link != GROUND]
    for ax, what, prime, unit in ((axv, "velocity", "", "m/s"), (axa, "acceleration", "'", "m/s²")):
        ax.set_aspect("equal", adjustable="datalim")
        ax.plot([0], [0], marker="o", ms=5, color="0.1", zorder=6)
        ax.annotate("p" + prime, (0, 0), xytext=(-12, -12), textcoords="offset points", fontsize=10,
                    fontweight="bold", zorder=9)
        vertices = []
        for p in moving:
            v = getattr(p, what)
            _arrow(ax, (0.0, 0.0), v, colors.get(p.link, "0.3"), lw=1.3)
            vertices.append((p.label, np.asarray(v)))
        # each link's image: its points' vertices joined in order
        for link in scene.link_names:
            pts = [getattr(p, what) for p in moving if p.link == link]
            if len(pts) >= 2:
                ring = np.array(pts + ([pts[0]] if len(pts) > 2 else []))
                ax.plot(ring[:, 0], ring[:, 1], color=colors.get(link, "0.3"), lw=0.8, alpha=0.6,
                        zorder=3)
        if vertices:
            _labels(ax, vertices, prime)
        ax.axhline(0, color="0.85", lw=0.6, zorder=0)
        ax.axvline(0, color="0.85", lw=0.6, zorder=0)
        ax.grid(True, color="0.94", lw=0.5, zorder=0)
        ax.set_xlabel(f"{what} x ({unit})")
        ax.set_ylabel(f"{what} y ({unit})")
    by_name = {(p.name, p.link): p for p in polygons.points}
    # acceleration: normal then tangential component about each link's first pivot
    shown = set()
    for r in polygons.relative:
        if r.link in shown or (r.about, r.link) not in by_name or (r.point, r.link) not in by_name:
            continue
        first = next(x for x in polygons.relative if x.link == r.link)
        if r.about != first.about:
            continue
        base = by_name[(r.about, r.link)].acceleration
        n = base + r.normal
        col = colors.get(r.link, "0.3")
        _arrow(axa, base, n, col, lw=1.0, ls=(0, (4, 2)), z=5)
        _arrow(axa, n, n + r.tangential, col, lw=1.0, ls=(0, (1, 1.5)), z=5)
    for s in polygons.sliding:
        g = by_name.get((s.point, s.guide))
        sl = by_name.get((s.point, s.slider))
        if g is None or sl is None:
            continue
        _arrow(axv, g.velocity, sl.velocity, "0.15", lw=1.6, z=6)
        k = g.acceleration + s.coriolis
        _arrow(axa, g.acceleration, k, "#9467bd", lw=1.6, z=6)
        _arrow(axa, k, sl.acceleration, "0.15", lw=1.6, z=6)
        axa.annotate("k'", tuple(k), xytext=(5, -12), textcoords="offset points", fontsize=9,
                     color="#9467bd", zorder=9)
    from matplotlib.lines import Line2D

    handles_v = [Line2D([], [], color=colors[n], lw=1.3, label=f"points of {n}") for n in scene.link_names]
    handles_a = list(handles_v) + [Line2D([], [], color="0.4", lw=1.0, ls=(0, (4, 2)),
                                          label="normal component about the link's first pivot"),
                                   Line2D([], [], color="0.4", lw=1.0, ls=(0, (1, 1.5)),
                                          label="tangential component")]
    if polygons.sliding:
        handles_v.append(Line2D([], [], color="0.15", lw=1.6, label="slip velocity (sliding pair)"))
        handles_a += [Line2D([], [], color="#9467bd", lw=1.6, label="Coriolis 2ω×v_rel"),
                      Line2D([], [], color="0.15", lw=1.6, label="slip acceleration")]
    axv.legend(handles=handles_v, loc="best", fontsize=7, framealpha=0.8)
    axa.legend(handles=handles_a, loc="best", fontsize=7, framealpha=0.8)
    axv.set_title(f"velocity polygon (pole p), step {polygons.step}", fontsize=11)
    axa.set_title(f"acceleration polygon (pole p'), step {polygons.step}", fontsize=11)
    fig.suptitle(f"{scene.name}: polygons to scale (equal axes)", fontsize=12)
    return style.save(fig, out_file)
