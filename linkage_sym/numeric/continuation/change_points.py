"""Change points of an RRR dyad between two points of the solving path (NumPy only).

An RRR dyad whose two links are equally long (to rounding) can have its outer joints at one
point: a change-point linkage (Grashof's equality ``s + l = p + q`` with the coupler as long
as the rocker, e.g. the four-bar 3, 1, 1, 3).  There the inner joint can be anywhere on one
circle about them, and two branches go on from that configuration: the dyad keeps its
assembly mode (the sign of its closed form: the inner joint on the same side of the line from
one outer joint to the other, a line whose direction has turned a half turn), both its links
a half turn from where they were; or it changes mode and its links go on without that turn.
Both are motions of the mechanism.  A closed form keeps its mode; a step where the outer
joints coincide to rounding is reported (``unassemblable``, or ``singular`` where the symbolic
runtime's closed form gives a value there), but where that happens *between* two path points
every step is solved and nothing else would tell.  Both runtimes find those passages here,
each with its own solved positions (:mod:`linkage_sym.numeric.kinematics.closed_form`,
:mod:`linkage_sym.codegen.change_points`), and word them alike
(:func:`~linkage_sym.numeric.continuation.messages.change_point_note`):

* **Screen** (:func:`intervals`, vectorised over the path): the vector ``e`` from one outer
  joint to the other at consecutive solved path points ``a``, ``b``.  Between them ``e`` runs
  along a smooth curve that stays within its chord's length of the chord (the path's points
  are at most 2 degrees or 2 % of the size apart, over which a joint's path bends far less
  than that); so where the origin is farther than the chord's length from the chord, ``e``
  does not pass through zero there, and nothing more is done.  Path points between two
  solved ones where the dyad itself cannot be assembled make an interval too: a passage
  when its outer joints coincide to rounding at all of them, else screened as the others
  (where a closed form has no value at the passage itself).
* **Minimisation** (:func:`through_zero`), in the few intervals the screen keeps: ``|e|`` on
  :data:`GRID` driver values spread over the interval (interpolated linearly between the two
  path points, as the path is), the grid zoomed :data:`ROUNDS` times onto its smallest value,
  then the distance from the origin to the last grid's two segments about it (there ``e`` is
  linear to far below rounding).  The outer joints pass through one point when that is within
  the tolerance of the solvers' own coincidence test (``COINCIDE_ULPS`` units of rounding of
  the mechanism's coordinates), so a four-bar 3, 1, 1, 3.001, whose joints stay 0.001 apart,
  is no change point: its links turn fast, but continuously, and there is one motion.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric.continuation import messages

__all__ = ["GRID", "ROUNDS", "between", "intervals", "through_zero", "change_point_notes"]

GRID = 33
"""Driver values per round of :func:`through_zero` (the grid shrinks 16-fold a round)."""
ROUNDS = 5
"""Zooming rounds of :func:`through_zero`: the last grid's segments span 1/2097152 of the
interval (2e-8 rad of a 2-degree one), along which the outer joints' vector departs from a
straight line by ``|e''| w^2 / 8``, 4e-17 of the size for a joint turning on a radius of
the size, far below the coincidence tolerance (64 units of rounding)."""


def intervals(ex, ey, solved, own, tol) -> list:
    """The intervals of the path where the outer joints may pass through one point.

    Parameters
    ----------
    ex, ey : ndarray (K,)
        The vector from one outer joint to the other at each path point (NaN where it is
        not known).
    solved : ndarray of bool (K,)
        Where the dyad is solved.
    own : ndarray of bool (K,)
        Where the dyad itself cannot be assembled (the groups before it solved).
    tol : float
        Distance (m) within which the outer joints coincide.

    Returns
    -------
    list of (int, int, bool)
        ``(a, b, known)``: consecutive solved path points ``a < b``, the outer joints apart
        at both, with only points between them where the dyad itself fails or its outer
        joints coincide; ``known`` true when they all coincide (a passage: nothing to
        minimise), else kept by the screen.

    Examples
    --------
    >>> import numpy as np
    >>> x, no = np.array([4.0, 3.0, 0.5, -0.5, -3.0, -4.0]), np.zeros(6, bool)
    >>> intervals(x, np.zeros(6), ~no, no, 1e-12)
    [(1, 2, False), (2, 3, False), (3, 4, False)]
    >>> x, own = np.array([2.0, 1.0, 0.0, -1.0]), np.array([False, False, True, False])
    >>> intervals(x, np.zeros(4), ~own, own, 1e-12)
    [(0, 1, False), (1, 3, True)]
    """
    ex, ey = np.asarray(ex, float), np.asarray(ey, float)
    d = np.hypot(ex, ey)
    with np.errstate(invalid="ignore"):
        coincide = d <= tol
    idx = np.flatnonzero(np.asarray(solved) & ~coincide & np.isfinite(d))
    if len(idx) < 2:
        return []
    a, b = idx[:-1], idx[1:]
    # what lies between a and b: only the dyad's own failures or coincidences, all coincident?
    other = np.concatenate([[0], np.cumsum(~(np.asarray(own) | coincide))])
    n_coincide = np.concatenate([[0], np.cumsum(coincide)])
    inside = other[b] - other[a + 1] == 0
    known = (b > a + 1) & (n_coincide[b] - n_coincide[a + 1] == b - a - 1)
    px, py = ex[a], ey[a]
    sx, sy = ex[b] - px, ey[b] - py
    s2 = sx * sx + sy * sy
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.clip(np.where(s2 > 0, -(px * sx + py * sy) / s2, 0.0), 0.0, 1.0)
    near = np.hypot(px + t * sx, py + t * sy) <= np.sqrt(s2) + tol
    keep = np.flatnonzero(inside & (known | near))
    return [(int(a[k]), int(b[k]), bool(known[k])) for k in keep]


def between(q: dict, a: int, b: int, t) -> dict:
    """Driver values a fraction ``t`` (array) of the way from path point ``a`` to ``b``.

    Examples
    --------
    >>> import numpy as np
    >>> between({"A": np.array([0.0, 1.0, 3.0])}, 1, 2, np.array([0.0, 0.5]))["A"].tolist()
    [1.0, 2.0]
    """
    t = np.asarray(t, float)
    return {n: float(v[a]) + t * (float(v[b]) - float(v[a])) for n, v in q.items()}


def through_zero(evaluate, tol: float) -> bool:
    """Whether the outer joints' vector passes within ``tol`` of zero on an interval.

    ``evaluate(t)`` gives ``(ex, ey)`` at the fractions ``t`` (an array in ``[0, 1]``) of the
    interval (NaN where it is not known: a point where the dyad cannot be assembled, which
    the grid's brackets then span).  See the module docstring.
    """
    lo, hi = 0.0, 1.0
    for _ in range(ROUNDS):
        t = np.linspace(lo, hi, GRID)
        ex, ey = (np.asarray(v, float) for v in evaluate(t))
        d = np.hypot(ex, ey)
        known = np.flatnonzero(np.isfinite(d))
        if len(known) < 2:
            return bool(len(known)) and bool(d[known[0]] <= tol)
        j = int(np.argmin(d[known]))
        if d[known[j]] <= tol:
            return True
        near = known[max(j - 1, 0):j + 2]  # the smallest value and its known neighbours
        lo, hi = t[near[0]], t[near[-1]]
    # the last grid's segments on either side of its smallest value: e is linear along them
    for i, k in zip(near[:-1], near[1:]):
        sx, sy = ex[k] - ex[i], ey[k] - ey[i]
        s2 = sx * sx + sy * sy
        s = min(max(-(ex[i] * sx + ey[i] * sy) / s2, 0.0), 1.0) if s2 > 0 else 0.0
        if np.hypot(ex[i] + s * sx, ey[i] + s * sy) <= tol:
            return True
    return False


def change_point_notes(e, solved, own, tol, q, kinds, evaluate, names) -> list:
    """The notes of an RRR dyad's change points along the path, for the run's warnings.

    Parameters
    ----------
    e : tuple of ndarray
        ``(ex, ey)``: the vector from one outer joint to the other at each path point.
    solved : ndarray of bool
        Where the dyad is solved.
    own : ndarray of bool
        Where the dyad itself cannot be assembled (the groups before it solved).
    tol : float
        Distance (m) within which the outer joints coincide.
    q : dict
        Each driven joint's values along the path.
    kinds : dict
        Each driven joint's type (``"R"``, ``"P"``), for the wording.
    evaluate : callable or None
        ``evaluate(qs)``: ``(ex, ey)`` at the driver values ``qs`` (a dict of arrays, as
        ``q``), the runtime's own solution of the groups before the dyad; ``None`` where
        they cannot be solved at any driver value (a group by continuation): then only
        path points where the joints coincide are found.
    names : tuple
        ``(head, (outer joint, outer joint), inner joint, (link, link))`` of the dyad.

    Returns
    -------
    list
        ``(first path point past the passage, text(step))`` pairs
        (:func:`~linkage_sym.numeric.continuation.messages.step_warnings`).
    """
    out = []
    for a, b, known in intervals(*e, solved, own, tol):
        if not known:
            if evaluate is None or not through_zero(
                    lambda t, a=a, b=b: evaluate(between(q, a, b, t)), tol):
                continue
        before = messages.driver_values_text(q, kinds, a)
        after = messages.driver_values_text(q, kinds, b)
        out.append((b, lambda step, before=before, after=after: messages.change_point_note(
            *names, before, after, step)))
    return out
