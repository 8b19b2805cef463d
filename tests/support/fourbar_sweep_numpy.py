"""A four-bar design sweep written by hand in NumPy: the yardstick of the design sweep's
speed (benchmarks/bench_design_sweep.py) and of its ``K`` and ``min_transmission_deg``
(tests/design/test_design_sweep_reference.py).

Nothing here imports ``linkage_sym``: it is what a user who knows the four-bar's closed
forms would write instead of calling ``linkage_sym.sweep``, from the textbook's formulas
(Norton, *Design of Machinery*, 2004, ch. 4: the four-bar's positions by the law of
cosines, the transmission angle, the toggle positions; ch. 3: the time ratio).

Conventions: crank pivot A at the origin, rocker pivot D at ``(xd, yd)``; crank AB of
length ``a`` at the driver angle ``theta`` (counter-clockwise from +x), coupler BC of length
``b``, rocker DC of length ``c``.  ``sigma`` (+1 or -1) is the assembly mode: the side of
the line B -> D on which C lies (the sign of ``cross(D - B, C - B)``), kept along the
sweep (a crank-rocker never changes it).
"""

from __future__ import annotations

import numpy as np


def sweep_fourbar(a, b, c, xd, yd, theta, sigma=1, chunk=1024):
    """Positions of C at every driver angle of every design, the smallest transmission
    angle over the steps, and the time ratio from the rocker's toggle positions.

    Parameters
    ----------
    a, b, c : array_like
        Crank, coupler and rocker lengths, one value per design (n,) or a number.
    xd, yd : float
        The rocker's ground pivot (the crank's is the origin).
    theta : ndarray
        The driver angles (N,), radians.
    sigma : {1, -1}
        The assembly mode (see the module docstring).
    chunk : int
        Designs per block of the (designs, steps) arrays (the arrays of a block stay in
        the cache).

    Returns
    -------
    assembled : ndarray of bool, (n,)
        The design closes at every step (``|cos| <= 1`` in the law of cosines).
    min_transmission_deg : ndarray, (n,)
        The smallest ``min(mu, 180 - mu)`` over the steps that close, ``mu`` the angle
        BCD between coupler and rocker (degrees); NaN where no step closes.
    K : ndarray, (n,)
        The time ratio, the larger over the smaller crank interval between the two toggle
        positions (crank and coupler in line, extended and folded), where every step
        closes; NaN elsewhere.
    """
    a, b, c = np.broadcast_arrays(*(np.asarray(v, float).reshape(-1) for v in (a, b, c)))
    n = len(a)
    ct, st = np.cos(theta), np.sin(theta)
    assembled = np.zeros(n, bool)
    mu_min = np.full(n, np.nan)
    for s in range(0, n, chunk):
        A, B, C = a[s:s + chunk, None], b[s:s + chunk, None], c[s:s + chunk, None]
        # B, and the vector B -> D
        bx, by = A * ct, A * st
        ex, ey = xd - bx, yd - by
        r2 = ex * ex + ey * ey
        r = np.sqrt(r2)
        # the angle at B between B -> D and B -> C (law of cosines in triangle B C D)
        cphi = (B * B + r2 - C * C) / (2 * B * r)
        closes = np.abs(cphi) <= 1
        with np.errstate(invalid="ignore"):
            sphi = sigma * np.sqrt(1 - cphi * cphi)
        # C: B -> D turned by phi, scaled to the coupler's length
        k = B / r
        cx = bx + k * (cphi * ex - sphi * ey)
        cy = by + k * (sphi * ex + cphi * ey)
        # transmission angle mu at C between C -> B and C -> D; min(mu, pi - mu) from the
        # magnitudes of its sine and cosine (no loss near 0 or 90 degrees)
        ux, uy = bx - cx, by - cy
        vx, vy = xd - cx, yd - cy
        mu = np.arctan2(np.abs(ux * vy - uy * vx), np.abs(ux * vx + uy * vy))
        mu[~closes] = np.nan
        with np.errstate(invalid="ignore"):
            mu_min[s:s + chunk] = np.fmin.reduce(mu, axis=1)
        assembled[s:s + chunk] = closes.all(axis=1)
    # toggle positions: C on the crank's line at |AC| = b + a (extended) or b - a (folded);
    # in the ground's frame (x along A -> D) cos(crank angle) by the law of cosines, and the
    # side from sigma: extended, cross(D - B, C - B) = b d sin(th) -> sin(th) has sigma's
    # sign; folded, it is -b d sin(th) -> the opposite sign
    d = np.hypot(xd, yd)
    with np.errstate(invalid="ignore", divide="ignore"):
        ext = np.arccos(((b + a) ** 2 + d * d - c * c) / (2 * (b + a) * d))
        fold = np.arccos(((b - a) ** 2 + d * d - c * c) / (2 * (b - a) * d))
    th_ext = sigma * ext
    th_fold = np.pi + sigma * fold  # A -> C at sigma * fold, the crank opposite
    swept = np.mod(th_fold - th_ext, 2 * np.pi)
    K = np.maximum(swept, 2 * np.pi - swept) / np.minimum(swept, 2 * np.pi - swept)
    K[~assembled] = np.nan
    return assembled, np.degrees(mu_min), K
