"""A cam's profile: a closed plane curve and what the contact needs of it (NumPy/SciPy only).

A profile is a closed curve ``C(u)``, ``u`` in ``[0, 2 pi)``, in the cam
link's frame (which is the scene's frame in the assembly configuration),
traversed counterclockwise, so that its outward unit normal is
``N = (y', -x') / |C'|`` and its signed curvature
``kappa = (x' y'' - y' x'') / |C'|^3`` is positive where the profile is convex.
Three forms (see "Extension: cam contacts" of ``docs/scene-format.md``):

``circle``
    ``C(u) = c + R (cos u, sin u)``: the eccentric circle, exact.
``polar``
    ``r(phi)`` samples about a ``centre`` (usually the cam's pivot), a
    periodic cubic spline of ``r`` in ``phi`` (``u = phi``):
    ``C = centre + r (cos phi, sin phi)``.
``points``
    a periodic cubic spline through the points, ``x(u)`` and ``y(u)``
    with ``u`` proportional to the chord length.

:class:`CamProfile` evaluates ``C`` and its first two derivatives over
arrays of ``u``, samples it densely for the checks of the scene reader
(closure, self-intersection, convexity) and finds the parameter of the
point nearest a given point (:meth:`CamProfile.nearest`) and of the
support point in a given direction (:meth:`CamProfile.support`).
"""

from __future__ import annotations

import math

import numpy as np

TWO_PI = 2.0 * math.pi

GRID = 720
"""Samples of ``u`` a contact search starts from (then refined to rounding)."""


class CamProfile:
    """A closed cam profile (see the module docstring).

    Parameters
    ----------
    kind : {"circle", "polar", "points"}
    data : tuple
        ``(centre, R)`` for a circle, ``(centre, phi, r)`` (radians, metres)
        for polar samples, ``(points,)`` for a spline through points.  The
        samples must be valid (the scene reader checks them first).
    """

    def __init__(self, kind: str, data: tuple):
        self.kind = kind
        if kind == "circle":
            (cx, cy), R = data
            self.centre, self.R = (float(cx), float(cy)), float(R)
        elif kind == "polar":
            from scipy.interpolate import CubicSpline  # on use: a scene without cams never loads it

            centre, phi, r = data
            self.centre = (float(centre[0]), float(centre[1]))
            phi = np.asarray(phi, float)
            r = np.asarray(r, float)
            if phi[-1] - phi[0] >= TWO_PI - 1e-12:  # the closing sample repeats the first
                phi, r = phi[:-1], r[:-1]
            shift = phi[0]
            self._phi0 = shift
            self._r = CubicSpline(np.append(phi - shift, TWO_PI), np.append(r, r[0]),
                                  bc_type="periodic")
        elif kind == "points":
            from scipy.interpolate import CubicSpline

            (pts,) = data
            P = np.asarray(pts, float)
            if np.allclose(P[0], P[-1]):
                P = P[:-1]
            x, y = P[:, 0], P[:, 1]
            if np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) < 0:  # clockwise: reversed
                P = P[::-1]
            closed = np.vstack([P, P[:1]])
            t = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
            t *= TWO_PI / t[-1]
            self._x = CubicSpline(t, closed[:, 0], bc_type="periodic")
            self._y = CubicSpline(t, closed[:, 1], bc_type="periodic")
        else:
            raise ValueError(f"unknown cam profile kind {kind!r}")

    # -- evaluation ----------------------------------------------------------
    def evaluate(self, u, order: int = 2):
        """``(x, y), (x', y'), (x'', y'')`` at ``u`` (derivatives wrt ``u``; up to ``order``)."""
        u = np.mod(np.asarray(u, float), TWO_PI)
        if self.kind == "circle":
            c, s = np.cos(u), np.sin(u)
            R = self.R
            out = [(self.centre[0] + R * c, self.centre[1] + R * s), (-R * s, R * c), (-R * c, -R * s)]
        elif self.kind == "polar":
            v = np.mod(u - self._phi0, TWO_PI)
            r, r1, r2 = self._r(v), self._r(v, 1), self._r(v, 2)
            c, s = np.cos(u), np.sin(u)
            out = [
                (self.centre[0] + r * c, self.centre[1] + r * s),
                (r1 * c - r * s, r1 * s + r * c),
                (r2 * c - 2 * r1 * s - r * c, r2 * s + 2 * r1 * c - r * s),
            ]
        else:
            out = [(self._x(u, k), self._y(u, k)) for k in range(3)]
        return out[: order + 1]

    def frame(self, u):
        """Point ``C``, unit tangent ``T``, outward unit normal ``N`` and curvature ``kappa`` at ``u``."""
        (x, y), (x1, y1), (x2, y2) = self.evaluate(u)
        speed = np.hypot(x1, y1)
        T = (x1 / speed, y1 / speed)
        N = (T[1], -T[0])
        kappa = (x1 * y2 - y1 * x2) / speed**3
        return (x, y), T, N, kappa

    def samples(self, n: int = 2048):
        """``u`` and the frame (see :meth:`frame`) at ``n`` equally spaced parameters."""
        u = np.linspace(0.0, TWO_PI, n, endpoint=False)
        return (u, *self.frame(u))

    # -- contact searches ----------------------------------------------------
    def nearest(self, px, py):
        """Parameter ``u`` of the profile point nearest each point ``(px, py)`` (arrays).

        A grid of :data:`GRID` samples, then Newton on ``(C - P) . C' = 0``.
        """
        px, py = np.atleast_1d(np.asarray(px, float)), np.atleast_1d(np.asarray(py, float))
        grid = np.linspace(0.0, TWO_PI, GRID, endpoint=False)
        (gx, gy), = self.evaluate(grid, 0)
        d2 = (gx[None, :] - px[:, None]) ** 2 + (gy[None, :] - py[:, None]) ** 2
        u = grid[np.argmin(d2, axis=1)]
        step = TWO_PI / GRID
        for _ in range(30):
            (x, y), (x1, y1), (x2, y2) = self.evaluate(u)
            g = (x - px) * x1 + (y - py) * y1
            dg = x1 * x1 + y1 * y1 + (x - px) * x2 + (y - py) * y2
            du = np.clip(-g / np.where(dg > 0, dg, np.inf), -step, step)
            u = u + du
            if np.all(np.abs(du) <= 1e-15 * TWO_PI):
                break
        return np.mod(u, TWO_PI)

    def support(self, mx, my):
        """Parameter ``u`` of the point of a convex profile farthest in direction ``(mx, my)``
        (there the outward normal is ``m``): a grid, then Newton on ``m . C' = 0``."""
        mx, my = np.atleast_1d(np.asarray(mx, float)), np.atleast_1d(np.asarray(my, float))
        grid = np.linspace(0.0, TWO_PI, GRID, endpoint=False)
        (gx, gy), = self.evaluate(grid, 0)
        u = grid[np.argmax(gx[None, :] * mx[:, None] + gy[None, :] * my[:, None], axis=1)]
        step = TWO_PI / GRID
        for _ in range(30):
            _, (x1, y1), (x2, y2) = self.evaluate(u)
            g = mx * x1 + my * y1
            dg = mx * x2 + my * y2
            du = np.clip(-g / np.where(dg < 0, dg, -np.inf), -step, step)
            u = u + du
            if np.all(np.abs(du) <= 1e-15 * TWO_PI):
                break
        return np.mod(u, TWO_PI)


def self_intersection(x, y):
    """The first pair ``(i, j)`` of crossing segments of the closed polygon ``x, y``, or ``None``.

    Adjacent segments (sharing a vertex) are not compared.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    n = len(x)
    ax, ay = x, y
    bx, by = np.roll(x, -1), np.roll(y, -1)

    def orient(px, py, qx, qy, rx, ry):
        return (qx - px) * (ry - py) - (qy - py) * (rx - px)

    for i in range(n):
        j = np.arange(i + 2, n)
        if i == 0:
            j = j[j != n - 1]
        if not len(j):
            continue
        o1 = orient(ax[i], ay[i], bx[i], by[i], ax[j], ay[j])
        o2 = orient(ax[i], ay[i], bx[i], by[i], bx[j], by[j])
        o3 = orient(ax[j], ay[j], bx[j], by[j], ax[i], ay[i])
        o4 = orient(ax[j], ay[j], bx[j], by[j], bx[i], by[i])
        hit = (o1 * o2 < 0) & (o3 * o4 < 0)
        if hit.any():
            return i, int(j[np.argmax(hit)])
    return None
