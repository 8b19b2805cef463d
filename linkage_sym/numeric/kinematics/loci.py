"""Loci of a dyad's internal point: circles and lines carried by known links.

A dyad's internal point ``Y`` lies on two loci, each fixed to a link already
solved: a *circle* (around an external revolute joint, radius the link's
length) or a *line* (the slide of an external prismatic joint).  Positions
come from closed forms written to stay accurate near tangency (no half-angle
formula: the half-chord is computed from products of differences, Heron
style); velocities and accelerations from the two differentiated locus
equations, a 2x2 linear system solved by Cramer's rule over all steps.
"""

from __future__ import annotations

import math

import numpy as np

TANGENT_ULPS = 8.0
"""A locus miss within this many units of rounding of the coordinates is a tangency.

Positions, lengths and centres carry rounding errors of a few ulps of the
largest coordinate involved, so a distance that should equal a sum or a
difference of radii exactly (a flat parallelogram, a toggle position) can
come out a few ulps outside the reach.  Such a step is a tangency (half-chord
0): assemblable and singular, found by the singularity screen, instead of
being reported unassemblable.
"""
_EPS = float(np.finfo(float).eps)


def clamp_tangent(prod, factors, scale, inplace=False):
    """``prod`` (a product of ``factors``) with rounding-level misses set to 0, real misses to NaN.

    ``scale()`` gives the size of the coordinates the factors were computed
    from (called only when needed; a :class:`Size` is evaluated at the negative
    entries only); a factor above ``-TANGENT_ULPS * eps * scale`` counts as zero.
    Only the (rare) negative entries are examined.  ``inplace``: ``prod`` is the
    caller's own temporary array, clamped where it is (else a copy is).
    """
    prod = np.asarray(prod, dtype=float)
    neg = prod < 0.0
    if not neg.any():
        return prod
    if not (inplace and prod.flags.c_contiguous and prod.flags.writeable):
        prod = prod.copy()
    # the negative entries' indices (row-major, as a mask selects them): gathering them
    # from each array costs only the few entries
    at = Entries(neg)
    size = scale.at(at) if isinstance(scale, Size) else at.take(scale())
    tol = TANGENT_ULPS * _EPS * size
    worst = at.take(factors[0])
    for f in factors[1:]:
        worst = np.minimum(worst, at.take(f))
    at.put(prod, np.where(worst >= -tol, 0.0, np.nan))
    return prod


class Entries:
    """The entries where ``mask`` (a boolean array) is true, in row-major order (the order
    ``array[mask]`` gives): :meth:`take` gathers them from an array broadcasting to the
    mask's shape, reading only those entries (a (n, 1) or (N,) array by its own index);
    :meth:`put` writes them into an array of the mask's shape."""

    def __init__(self, mask):
        self.shape = mask.shape
        self.flat = np.flatnonzero(mask)
        self.index = np.unravel_index(self.flat, mask.shape) if mask.ndim else None

    def take(self, v) -> np.ndarray:
        """``np.broadcast_to(v, shape)[mask]``, the same numbers."""
        v = np.asarray(v, dtype=float)
        k = len(self.flat)
        if v.shape == self.shape and v.flags.c_contiguous:
            return v.ravel().take(self.flat)
        if v.ndim == 0 or self.index is None:
            return np.broadcast_to(v, self.shape).reshape(-1)[self.flat] if v.ndim else np.full(k, v)
        lead = len(self.shape) - v.ndim  # v broadcasts along its missing and length-1 axes
        idx = tuple(0 if n == 1 else i for n, i in zip(v.shape, self.index[lead:]))
        return np.broadcast_to(v[idx], (k,))

    def put(self, a, values) -> None:
        """``a[mask] = values`` (``a`` of the mask's shape, C-contiguous)."""
        a.reshape(-1)[self.flat] = values


def coordinate_size(*values):
    """Largest magnitude among scalars/arrays (elementwise), for rounding tolerances."""
    out = 0.0
    for v in values:
        out = np.maximum(out, np.abs(v))
    return out


class Size:
    """:func:`coordinate_size` of ``values``, computed when asked: in whole
    (``size()``) or at some entries only (``size.at(entries)``, :class:`Entries`;
    the same numbers)."""

    __slots__ = ("values",)

    def __init__(self, values):
        self.values = values

    def __call__(self):
        return coordinate_size(*self.values)

    def at(self, entries):
        """The size at ``entries`` (:class:`Entries`): the values of one shape reduced to
        their largest magnitude before the gather (a maximum is exact in any order)."""
        by_shape: dict = {}
        for v in self.values:
            v = np.asarray(v, dtype=float)
            by_shape[v.shape] = np.maximum(by_shape.get(v.shape, 0.0), np.abs(v))
        return coordinate_size(*(entries.take(v) for v in by_shape.values()))


class Circle:
    """Points at distance ``r`` from the point ``C`` (local) of link ``link``."""

    def __init__(self, link, C, r):
        self.link, self.C, self.r = link, C, r

    def center(self, S):
        return S[self.link].point(self.C)

    def vel_row(self, S, Y, cache):
        Cx, Cy = cache
        vCx, vCy = S[self.link].point_velocity(self.C)
        ax, ay = Y[0] - Cx, Y[1] - Cy
        return ax, ay, ax * vCx + ay * vCy, (vCx, vCy)

    def acc_row(self, S, Y, vY, cache, vcache):
        Cx, Cy = cache
        vCx, vCy = vcache
        aCx, aCy = S[self.link].point_acceleration(self.C)
        ax, ay = Y[0] - Cx, Y[1] - Cy
        rvx, rvy = vY[0] - vCx, vY[1] - vCy
        return ax, ay, ax * aCx + ay * aCy - (rvx * rvx + rvy * rvy)


class Line:
    """The line through the point ``Q`` (local) of ``link`` along its direction ``u0``."""

    def __init__(self, link, Q, axis):
        self.link, self.Q = link, Q
        self.u0 = (math.cos(axis), math.sin(axis))

    def frame(self, S):
        st = S[self.link]
        Qx, Qy = st.point(self.Q)
        ux, uy = st.rot(self.u0)
        return Qx, Qy, ux, uy

    def vel_row(self, S, Y, cache):
        Qx, Qy, ux, uy = cache
        st = S[self.link]
        vQx, vQy = st.point_velocity(self.Q)
        nx, ny = -uy, ux
        rx, ry = Y[0] - Qx, Y[1] - Qy
        return nx, ny, nx * vQx + ny * vQy + st.w * (ux * rx + uy * ry), (vQx, vQy)

    def acc_row(self, S, Y, vY, cache, vcache):
        Qx, Qy, ux, uy = cache
        vQx, vQy = vcache
        st = S[self.link]
        aQx, aQy = st.point_acceleration(self.Q)
        nx, ny = -uy, ux
        rx, ry = Y[0] - Qx, Y[1] - Qy
        rvx, rvy = vY[0] - vQx, vY[1] - vQy
        w = st.w
        b = (
            nx * aQx
            + ny * aQy
            + 2 * w * (ux * rvx + uy * rvy)
            + st.al * (ux * rx + uy * ry)
            + w * w * (nx * rx + ny * ry)
        )
        return nx, ny, b


def circle_circle(C1, r1, C2, r2, sigma):
    """Intersection of two circles on the side ``sigma`` of the line C1->C2.

    Returns ``(Yx, Yy, h, d)``: the point, the half-chord (NaN where the
    circles do not meet) and the distance of the centres.

    Examples
    --------
    >>> Yx, Yy, h, d = circle_circle((0.0, 0.0), 5.0, (8.0, 0.0), 5.0, 1.0)
    >>> float(Yx), float(Yy), float(h)
    (4.0, 3.0, 3.0)
    """
    ex, ey = C2[0] - C1[0], C2[1] - C1[1]
    d = np.hypot(ex, ey)
    # Heron form of the half-chord: no cancellation near tangency
    with np.errstate(invalid="ignore", divide="ignore"):
        f1, f2, f3 = r1 + r2 - d, d + r1 - r2, d - r1 + r2
        prod = clamp_tangent(
            f1 * f2 * f3 * (r1 + r2 + d),
            (f1, f2, f3),
            lambda: coordinate_size(r1, r2, C1[0], C1[1], C2[0], C2[1]),
        )
        h = np.sqrt(prod) / (2.0 * d)
        a = (d * d + r1 * r1 - r2 * r2) / (2.0 * d)
        ex, ey = ex / d, ey / d
    Yx = C1[0] + a * ex - sigma * h * ey
    Yy = C1[1] + a * ey + sigma * h * ex
    return Yx, Yy, h, d


def circle_line(C, r, Qx, Qy, ux, uy, sigma):
    """Intersection of a circle with a line, on the side ``sigma`` along ``u``.

    Returns ``(Yx, Yy, h)`` with ``h`` the half-chord (NaN where they miss).

    Examples
    --------
    >>> Yx, Yy, h = circle_line((0.0, 0.0), 5.0, 0.0, 3.0, 1.0, 0.0, 1.0)
    >>> float(Yx), float(Yy), float(h)
    (4.0, 3.0, 4.0)
    """
    nx, ny = -uy, ux
    delta = nx * (C[0] - Qx) + ny * (C[1] - Qy)
    with np.errstate(invalid="ignore"):
        f1, f2 = r - delta, r + delta
        prod = clamp_tangent(f1 * f2, (f1, f2), lambda: coordinate_size(r, C[0], C[1], Qx, Qy))
        h = np.sqrt(prod)
    Fx, Fy = C[0] - delta * nx, C[1] - delta * ny
    return Fx + sigma * h * ux, Fy + sigma * h * uy, h


PARALLEL_ULPS = 8.0
"""Two slide directions (unit vectors) whose cross product is within this many units of
rounding of zero are parallel: their intersection is at infinity, and the dyad cannot be
assembled there (a rounding-level cross product of lines that are parallel would put the
joint some 1e15 sizes away)."""


def line_line(Q1x, Q1y, u1x, u1y, Q2x, Q2y, u2x, u2y):
    """Intersection of two lines (``u1``, ``u2`` unit directions); returns
    ``(Yx, Yy, sin_angle)``, the signed sine ``cross(u1, u2)`` NaN where the lines are
    parallel (within :data:`PARALLEL_ULPS`) or the point is not finite.

    Examples
    --------
    >>> Yx, Yy, s = line_line(0.0, 1.0, 1.0, 0.0, 2.0, 0.0, 0.0, 1.0)
    >>> float(Yx), float(Yy), float(s)
    (2.0, 1.0, 1.0)
    >>> float(line_line(0.0, 1.0, 1.0, 0.0, 2.0, 0.0, -1.0, 0.0)[2])
    nan
    """
    cr = u1x * u2y - u1y * u2x
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        if np.any(np.abs(cr) <= PARALLEL_ULPS * _EPS):
            cr = np.where(np.abs(cr) <= PARALLEL_ULPS * _EPS, np.nan, cr)
        t = ((Q2x - Q1x) * u2y - (Q2y - Q1y) * u2x) / cr
        Yx, Yy = Q1x + t * u1x, Q1y + t * u1y
        lost = ~(np.isfinite(Yx) & np.isfinite(Yy))
        if np.any(lost & np.isfinite(cr)):
            cr = np.where(lost, np.nan, cr)
    return Yx, Yy, cr


def solve2(a1x, a1y, b1, a2x, a2y, b2):
    """Solve ``[a1; a2] v = [b1; b2]`` for ``v`` by Cramer's rule (vectorised)."""
    # NaN rows (steps that could not be assembled) stay NaN without a warning
    with np.errstate(invalid="ignore", divide="ignore"):
        det = a1x * a2y - a1y * a2x
        inv = 1.0 / det
        return (b1 * a2y - b2 * a1y) * inv, (a1x * b2 - a2x * b1) * inv
