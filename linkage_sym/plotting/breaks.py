"""Lines that must not join two steps: a joint's passage through infinity.

A dyad of two slides whose slides become parallel between two steps carries its joint and
the links placed from it through infinity (:attr:`Analysis.passages
<linkage_sym.numeric.results.result.Analysis>`, :mod:`linkage_sym.numeric.results.passages`):
both steps are ``ok``, but a point on those links goes from one far end of its slides to the
other; a line from one step to the next would draw a motion the mechanism never makes.
Every curve of a point on those links (its path, its coordinate, velocity or acceleration
against the driver) gets a NaN between the two steps (:func:`with_breaks`), which Matplotlib
draws as a break.  Steps that are not ``ok`` break the curves already: their values are NaN.

Points carried off reach far beyond the mechanism near a passage; a drawing of the paths
frames the rest and lets them leave it (:func:`view_box`), and says so (:func:`passage_note`).

A Newton group that jumps to another configuration of its assembly mode between two ``ok``
steps (:attr:`Analysis.jumps <linkage_sym.numeric.results.result.Analysis>`,
:mod:`linkage_sym.numeric.results.jumps`) breaks the curves of the points on the links that
jump in the same way (:func:`gaps_of`: each break is a :class:`Gap` that says why), and is
said and marked alike (:func:`jump_note`, :func:`mark_passages`, :func:`jump_notes_text`).
"""

from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.lines import Line2D

from linkage_sym.model import GROUND
from linkage_sym.numeric.results import wording

__all__ = ["Gap", "frame_passages", "gap_label", "gaps_of", "jump_note", "jump_notes_text",
           "mark_passages", "note_jumps", "passage_note", "passage_view", "view_box", "with_breaks"]

INFINITY = "through infinity"
"""Why a curve breaks at a passage through infinity (its legend's words)."""

JUMP = "assembly-mode jump"
"""Why a curve breaks at a Newton group's jump (its legend's words)."""


class Gap(int):
    """A step after which a curve breaks (an ``int``), with why: :data:`INFINITY`,
    :data:`JUMP` or both joined by ``" and "``.

    Examples
    --------
    >>> g = Gap(4, JUMP)
    >>> g + 1, g.why
    (5, 'assembly-mode jump')
    """

    def __new__(cls, step: int, why: str = INFINITY):
        out = super().__new__(cls, step)
        out.why = why
        return out


def breaks_of(analysis, touches, jump_touches=None) -> tuple:
    """The :class:`Gap` of every passage and jump (step 0 on) whose links ``touches(links)``
    accepts (``jump_touches(links)`` for a jump, when given), increasing, one a step."""
    whys: dict = {}
    jump_touches = jump_touches or touches
    for record, why, test in ([(p, INFINITY, touches) for p in analysis.passages]
                              + [(j, JUMP, jump_touches) for j in getattr(analysis, "jumps", ())]):
        if record.before is not None and test(record.links):
            whys.setdefault(record.before, [])
            if why not in whys[record.before]:
                whys[record.before].append(why)
    return tuple(Gap(k, " and ".join(whys[k])) for k in sorted(whys))

REACH = 2.0
"""How far beyond the rest of a drawing (in its own size, or the mechanism's size if that is
larger) the paths carried through infinity may still widen its view."""


def gaps_of(analysis, links) -> tuple:
    """The steps after which a curve of a point fixed on one of ``links`` breaks: the step
    before every passage through infinity that carries one of them off and every Newton
    group's jump that moves one of them (increasing :class:`Gap`, no repeats; one before
    step 0 breaks nothing).  A jump moves the point only when it moves every one of
    ``links``: a pin between a link that jumps and one that does not stays on the latter.

    Parameters
    ----------
    analysis : Analysis
    links : iterable of str
        The links the curve's point is fixed on (several for coincident joints drawn as one
        path); the ground is never carried off.

    Returns
    -------
    tuple of int
    """
    links = set(links) - {GROUND}
    return breaks_of(analysis, lambda moved: bool(links & set(moved)),
                     lambda moved: bool(links) and links <= set(moved))


def with_breaks(gaps, *arrays) -> tuple:
    """Each array (``(N,)`` or ``(N, 2)``, step by step) with a NaN row inserted after each
    step of ``gaps``; the arrays unchanged (not copied) when there is none.

    Examples
    --------
    >>> x, y = with_breaks((1,), np.arange(4.0), np.arange(4.0) ** 2)
    >>> x.tolist(), y.tolist()
    ([0.0, 1.0, nan, 2.0, 3.0], [0.0, 1.0, nan, 4.0, 9.0])
    >>> with_breaks((), np.arange(3.0))[0].tolist()
    [0.0, 1.0, 2.0]
    """
    if not gaps:
        return arrays
    out = []
    for a in arrays:
        a = np.asarray(a, dtype=float)
        out.append(np.insert(a, np.asarray(gaps, dtype=int) + 1, np.nan, axis=0))
    return tuple(out)


def view_box(near, far, size: float):
    """The corners ``(lo, hi)`` of a drawing's view: every finite point of ``near`` and those
    of ``far`` (the points carried through infinity) within :data:`REACH` times the larger
    of ``size`` and the near points' extent beyond them.

    Parameters
    ----------
    near, far : list of array_like, each (K, 2)
    size : float
        The mechanism's size (same unit).

    Returns
    -------
    lo, hi : ndarray, shape (2,)

    Examples
    --------
    >>> lo, hi = view_box([[[0.0, 0.0], [1.0, 1.0]]], [[[2.5, 0.5], [40.0, 0.5]]], 1.0)
    >>> lo.tolist(), hi.tolist()
    ([0.0, 0.0], [2.5, 1.0])
    """
    def rows(parts):
        parts = [np.asarray(p, dtype=float).reshape(-1, 2) for p in parts]
        allp = np.concatenate(parts, axis=0) if parts else np.empty((0, 2))
        return allp[np.all(np.isfinite(allp), axis=-1)]

    base, out = rows(near), rows(far)
    if not base.size:
        base = out[:1]
    lo, hi = base.min(axis=0), base.max(axis=0)
    reach = REACH * max(float((hi - lo).max()), size)
    inside = np.all((out >= lo - reach) & (out <= hi + reach), axis=-1)
    kept = np.concatenate([base, out[inside]], axis=0)
    return kept.min(axis=0), kept.max(axis=0)


def passage_note(analysis, passage, kinds: dict) -> str:
    """One line saying where a joint passes through infinity and which paths break there,
    e.g. ``joint C passes through infinity between steps 4 and 5 (A = 3.33° and -3.33°):
    the paths of points on rod, block are not joined there``; the status of the step before
    it follows its number when it is not ``ok`` (e.g. the step where the slides are parallel).

    ``kinds`` maps each driven joint to ``"R"`` or ``"P"``.
    """
    status = str(analysis.status[passage.before])
    bad = "" if status == "ok" else f" ({status})"
    where = f"between steps {passage.before}{bad} and {passage.after}"
    q = {name: d["q"] for name, d in analysis.drivers.items()}

    def at(k):
        return wording.driver_values_text({n: float(v[k]) for n, v in q.items()}, kinds)

    values = f" ({at(passage.before)} and {at(passage.after)})" if q else ""
    return (f"joint {passage.joint} passes through infinity {where}{values}: the paths of "
            f"points on {', '.join(passage.links)} are not joined there")


def passage_view(scene, analysis, point_links):
    """The view box (m) of a drawing of the paths when a passage through infinity carries
    points off (:func:`view_box`), ``None`` when none does.

    The near points are the joints' assembly positions and the paths of the points no
    passage carries off; the far ones, the paths of those it does.  ``point_links(joint)``
    gives the links that place a joint's point.
    """
    far_set = {link for p in analysis.passages if p.before is not None for link in p.links}
    if not far_set:
        return None
    near = [np.asarray([j.at for j in scene.joints], dtype=float)]
    far = []
    series = [(jk.position, point_links(scene.joint(name)))
              for name, jk in analysis.joints.items()]
    series += [(pk.position, (pt.link,)) for pt in scene.points
               if (pk := analysis.points.get(pt.name)) is not None]
    series += [(lk.com, (name,)) for name, lk in analysis.links.items() if lk.com is not None]
    for values, links in series:
        (far if far_set & set(links) else near).append(np.asarray(values, dtype=float))
    return view_box(near, far, scene.characteristic_length() or 1.0)


def frame_passages(ax, scene, analysis, view, scale: float, note_at=(1.02, 0.0)) -> None:
    """Frame a drawing of the paths on its :func:`passage_view` ``view`` (m; axis units are
    ``scale`` per metre) with a margin, and write what each passage breaks
    (:func:`passage_note`) under the legend, at ``note_at`` in axes coordinates."""
    lo, hi = np.asarray(view[0]) * scale, np.asarray(view[1]) * scale
    pad = 0.08 * max(float((hi - lo).max()), 1e-12)
    lo, hi = lo - pad, hi + pad
    # the short side widened to the axis's proportions: equal scales fill it
    box = ax.get_position()
    width, height = ax.figure.get_size_inches()
    ratio = (box.height * height) / (box.width * width)
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    if half[1] < ratio * half[0]:
        half[1] = ratio * half[0]
    else:
        half[0] = half[1] / ratio
    ax.set_aspect("equal", adjustable="box")  # the limits stay; the axis takes their shape
    ax.set_xlim(mid[0] - half[0], mid[0] + half[0])
    ax.set_ylim(mid[1] - half[1], mid[1] + half[1])
    kinds = {d.joint: d.kind for d in scene.drivers}
    lines = [textwrap.fill(passage_note(analysis, p, kinds), 46) for p in analysis.passages
             if p.before is not None]
    lines += [text] if (text := jump_notes_text(scene, analysis)) else []
    ax.text(*note_at, "\n".join(lines), transform=ax.transAxes, ha="left", va="bottom",
            fontsize=8, color="0.2", gid="passages through infinity")


def note_jumps(ax, scene, analysis, note_at=(1.02, 0.0)) -> None:
    """Write what each Newton group's jump breaks (:func:`jump_note`) under the legend of a
    drawing of the paths without a passage through infinity (which :func:`frame_passages`
    writes with its own), at ``note_at`` in axes coordinates; nothing when there is none."""
    text = jump_notes_text(scene, analysis)
    if text:
        ax.text(*note_at, text, transform=ax.transAxes, ha="left", va="bottom", fontsize=8,
                color="0.2", gid="assembly-mode jumps")


def gap_label(label: str, gaps, sep: str = ", ") -> str:
    """A curve's legend entry, saying (after ``sep``) where a passage through infinity
    breaks it.

    Examples
    --------
    >>> gap_label("point P (on rod)", (4,)), gap_label("path of B", ())
    ('point P (on rod), through infinity after step 4', 'path of B')
    >>> gap_label("path of C", (Gap(13, JUMP), Gap(69, JUMP)))
    'path of C, assembly-mode jump after steps 13, 69'
    """
    if not gaps:
        return label
    whys: dict = {}
    for g in gaps:
        whys.setdefault(getattr(g, "why", INFINITY), []).append(str(int(g)))
    if set(whys) == {INFINITY}:  # the words of a passage's break, as they always were
        return f"{label}{sep}{INFINITY} after step {', '.join(whys[INFINITY])}"
    parts = [f"{why} after step{'s' if len(k) > 1 else ''} {', '.join(k)}"
             for why, k in whys.items()]
    return f"{label}{sep}{'; '.join(parts)}"


def mark_passages(axes, x, analysis) -> list:
    """A dotted vertical line on every axis of a diagram against the driver (``x``, one
    value a step) midway between the two steps of each passage through infinity; returns
    their legend handles (one a passage, for the first axis's legend)."""
    out = []
    look = {"color": "0.35", "lw": 0.9, "ls": (0, (1, 2))}
    for p in analysis.passages:
        if p.before is None:
            continue
        at = 0.5 * (float(x[p.before]) + float(x[p.after]))
        for ax in axes:
            ax.axvline(at, zorder=0.6, label="_passage", **look)
        out.append(Line2D([], [], label=f"joint {p.joint} through infinity between steps "
                          f"{p.before} and {p.after}", **look))
    look = {"color": "0.35", "lw": 0.9, "ls": (0, (4, 2, 1, 2))}
    for j in getattr(analysis, "jumps", ()):
        if j.before is None:
            continue
        at = 0.5 * (float(x[j.before]) + float(x[j.after]))
        for ax in axes:
            ax.axvline(at, zorder=0.6, label="_jump", **look)
        out.append(Line2D([], [], label=textwrap.fill(
            f"{j.group}: assembly-mode jump between steps {j.before} and {j.after}", 48),
            **look))
    return out


def jump_note(analysis, jump, kinds: dict) -> str:
    """One line saying where a Newton group jumps to another configuration of its assembly
    mode and which paths break there, e.g. ``triad (class III) (link_BC, lever, ...) jumps
    to another configuration of its assembly mode between steps 13 and 14 (A = 65.3° and
    66.3°): the paths of points on link_BC, ... are not joined there``.

    ``kinds`` maps each driven joint to ``"R"`` or ``"P"``.
    """
    how = "past a limit or singular position" if jump.limit else "as it is assembled again"
    q = {name: d["q"] for name, d in analysis.drivers.items()}

    def at(k):
        return wording.driver_values_text({n: float(v[k]) for n, v in q.items()}, kinds)

    values = f" ({at(jump.before)} and {at(jump.after)})" if q else ""
    return (f"{jump.group} jumps to another configuration of its assembly mode {how} "
            f"between steps {jump.before} and {jump.after}{values}: the paths of points on "
            f"{', '.join(jump.links)} alone are not joined there")


def jump_notes_text(scene, analysis, steps=None, width: int = 46) -> str:
    """The :func:`jump_note` of every jump (those around one of ``steps`` when given),
    wrapped to ``width`` characters, one paragraph each; ``""`` when there is none."""
    kinds = {d.joint: d.kind for d in scene.drivers}
    return "\n".join(textwrap.fill(jump_note(analysis, j, kinds), width)
                     for j in getattr(analysis, "jumps", ()) if j.before is not None
                     and (steps is None or set(steps) & {j.before, j.after}))
