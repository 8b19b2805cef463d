"""The arrows' scale of an animation whose joints pass through infinity.

An arrow layer is drawn to one scale over the whole animation: its largest value is
:data:`~linkage_sym.plotting.animation.ARROW_SHARE` mechanism sizes long.  Near a passage
through infinity (:attr:`Analysis.passages <linkage_sym.numeric.results.result.Analysis>`)
the links carried off move unboundedly fast: the largest velocity (acceleration, reaction,
driving effort) of the sweep is that of a point far outside the drawing, and every other
arrow of every frame would be drawn a few pixels long.  With a passage, a layer's scale is
therefore set by the points no passage carries off (as the drawing would be without the
passage), or where all are carried off (and for the forces, which all carry their loads) by a
high percentile (:data:`PERCENTILE`) of its values at the points inside the drawing's view
(:func:`~linkage_sym.plotting.breaks.passage_view`) on the ``ok`` steps
(:func:`typical_size`); and an arrow longer than :data:`CUT` times the usual longest length
is drawn that long with a break mark across its shaft (:func:`cut_vectors`): its value is
larger than drawn.  Without a passage nothing changes (no arrow is cut: the longest is
drawn the usual length).
"""

from __future__ import annotations

import numpy as np

from matplotlib.lines import Line2D

__all__ = ["BREAK_MARK", "CUT", "PERCENTILE", "TORQUE_CUT", "cut_handle", "cut_vectors",
           "typical_size"]

PERCENTILE = 75.0
"""Which percentile of a layer's values inside the view is drawn at the usual longest
length when a passage through infinity makes its largest values unbounded."""

CUT = 2.0
"""Longest arrow drawn, in the usual longest length: a longer one is cut there and marked."""

TORQUE_CUT = 345.0
"""Largest sweep (degrees) of a driving torque's curved arrow: a larger torque is drawn
this far round (its value is written beside it)."""

BREAK_MARK = "$//$"
"""The mark across a cut arrow's shaft."""


def cut_handle(color="0.3") -> Line2D:
    """The legend entry of the cut arrows' mark."""
    return Line2D([], [], color=color, lw=1.4, marker=BREAK_MARK, ms=11,
                  label=f"arrow cut at {CUT:g}× the scale's longest:\n  its value is larger")


def typical_size(items, ok, view, carried=None) -> float:
    """The size a layer's scale draws at its usual longest length when a passage makes its
    largest values unbounded: the largest length of the vectors of the points no passage
    carries off (``carried`` false) on the ``ok`` steps, the mechanism as it would be drawn
    without the passage; when there is none (or ``carried`` is not given: every reaction
    carries the loads of the links carried off), the :data:`PERCENTILE` percentile of the
    lengths at the points inside ``view``; 0 when there is none either.

    Parameters
    ----------
    items : list of (positions (N, 2), vectors (N, 2))
    ok : ndarray of bool, shape (N,)
    view : (lo, hi)
        Corners of the drawing's view (m).
    carried : list of bool, optional
        Whether a passage carries off each item's point.

    Examples
    --------
    >>> p = np.zeros((5, 2)); v = np.array([[1.0, 0.0]] * 4 + [[1e6, 0.0]])
    >>> box = (np.full(2, -1.0), np.ones(2))
    >>> typical_size([(p, v)], np.ones(5, bool), box)
    1.0
    >>> typical_size([(p, v), (p, 0.5 * v[:1].repeat(5, 0))], np.ones(5, bool), box,
    ...              [True, False])
    0.5
    """
    near = [v for (_, v), c in zip(items, carried or ()) if not c]
    sizes = [np.hypot(*_rows(np.asarray(v, dtype=float)[ok]).T) for v in near]
    biggest = max((float(np.max(m, initial=0.0)) for m in sizes), default=0.0)
    if biggest > 0.0:
        return biggest
    lo, hi = (np.asarray(c, dtype=float) for c in view)
    mags = []
    for p, v in items:
        p, v = np.asarray(p, dtype=float)[ok], np.asarray(v, dtype=float)[ok]
        keep = (np.all((p >= lo) & (p <= hi), axis=-1) & np.all(np.isfinite(v), axis=-1))
        mags.append(np.hypot(v[keep, 0], v[keep, 1]))
    mags = np.concatenate(mags) if mags else np.empty(0)
    return float(np.percentile(mags, PERCENTILE)) if mags.size else 0.0


def _rows(v):
    v = v.reshape(-1, 2)
    return v[np.all(np.isfinite(v), axis=-1)]


def cut_vectors(v, scale: float, longest: float):
    """The drawn vectors ``v * scale`` shortened to ``longest`` (same unit) where longer,
    and which were.

    Examples
    --------
    >>> d, cut = cut_vectors(np.array([[3.0, 4.0], [0.3, 0.4]]), 1.0, 2.0)
    >>> np.round(d, 12).tolist(), cut.tolist()
    ([[1.2, 1.6], [0.3, 0.4]], [True, False])
    """
    d = np.asarray(v, dtype=float).reshape(-1, 2) * scale
    n = np.hypot(d[:, 0], d[:, 1])
    cut = n > longest
    d[cut] *= (longest / n[cut])[:, None]
    return d, cut
