"""Homogeneous points and three-centre lines of Kennedy's construction, with their errors.

The geometry :func:`linkage_sym.centres.kennedy.kennedy_centres` builds on: a
centre is a unit homogeneous point of the scaled frame (coordinates about the
assembly's centre ``c`` in mechanism sizes ``L``), at infinity beyond
:data:`FAR` sizes; a three-centre line passes through two centres; each centre
carries an error estimate, each line the offset it may have, and the centre
sought is the intersection of the pair of lines with the smallest estimated
error (:func:`intersect_best`).  NumPy only; it reads no velocity.

Examples
--------
>>> import numpy as np
>>> h = snap(np.array([[3.0, 4.0, 1e-12]]))
>>> h.tolist(), to_global(h, np.zeros(2), 1.0).tolist()
([[0.6, 0.8, 0.0]], [[nan, nan]])
"""

from __future__ import annotations

import numpy as np

__all__ = ["DEGENERATE", "DISTINCT", "FAR", "ROUNDING", "UNCERTAIN", "intersect_best", "relative",
           "snap", "to_global", "unit"]

FAR = 1e9
"""A centre farther than this many mechanism sizes from the mechanism is at infinity.

Two lines through points of the mechanism that meet so far away are parallel
to within 1e-9 rad: in float64 their meeting point is only known to about
``1e-16 * (d / L)**2`` sizes, already 100 sizes at 1e9.  Such a centre is
reported by its direction, as an exact point at infinity.
"""

DEGENERATE = 1e-13
"""Two centres closer than this (relative, in the scaled frame) span no line.

Such a pair of centres gives no three-centre line at that step; the centre
sought is then found from the other lines, or not at that step.
"""

ROUNDING = 8 * float(np.finfo(float).eps)
"""Error estimate of a primary centre: of a pin, relative to its distance from the
global origin (at least one mechanism size); of a slide's direction, relative to
its angle (at least 1 rad)."""

DISTINCT = 1e3
"""Two nearly parallel three-centre lines meet at infinity only if they lie this many times
their possible offsets apart; closer, they may be one line, and they meet nowhere in
particular (the intersection is not used)."""

UNCERTAIN = 1e-3
"""An intersection whose estimated error exceeds this fraction of its distance (at least one
mechanism size) is not used: the lines are too nearly one."""


def unit(h):
    """Homogeneous vectors (..., 3) scaled to unit length (zero vectors become NaN)."""
    norm = np.linalg.norm(h, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.where(norm > 0.0, h / norm, np.nan)


def snap(h):
    """Unit homogeneous points with those beyond :data:`FAR` sizes set exactly at infinity."""
    h = unit(h)
    w = np.abs(h[..., 2])
    xy = np.linalg.norm(h[..., :2], axis=-1)
    far = w * FAR <= xy
    h = np.where(far[..., None], np.concatenate([h[..., :2], np.zeros_like(h[..., 2:])], -1), h)
    return unit(h)


def relative(h, err):
    """Error relative to a centre's distance (at least one size); angular error at infinity."""
    w = np.abs(h[..., 2])
    xy = np.linalg.norm(h[..., :2], axis=-1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.where(w > 0.0, err / np.maximum(1.0, xy / w), err)


def to_global(h, c, L):
    """Global position (N, 2) of unit homogeneous points of the scaled frame; NaN at infinity."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.where((h[:, 2] != 0.0)[:, None], c + L * h[:, :2] / h[:, 2:3], np.nan)


def _line(ha, pa, hb, pb, c, L):
    """The three-centre line through two centres, in the scaled frame (N, 3).

    ``(n, c0)`` with ``|n| = 1`` for the line ``n . x + c0 = 0``, ``(0, 0, 1)`` for the
    line at infinity (through two centres at infinity), NaN where the two centres
    span no line (they coincide, or one is missing).  The direction comes from the
    difference of the global positions (or is a centre's direction at infinity),
    never from a difference of shifted coordinates: two pins 1e-7 of the size apart
    give their line to rounding of their own coordinates, not 1e7 times that.
    """
    fa = np.all(np.isfinite(pa), axis=-1)
    fb = np.all(np.isfinite(pb), axis=-1)
    ia = np.all(np.isfinite(ha), axis=-1) & ~fa
    ib = np.all(np.isfinite(hb), axis=-1) & ~fb
    d = np.where((fa & fb)[:, None], pb - pa, np.where(fa[:, None], hb[:, :2], ha[:, :2]))
    span = np.linalg.norm(d, axis=-1)
    anchor = np.where(fa[:, None], pa, pb)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        nrm = np.stack([-d[:, 1], d[:, 0]], axis=-1) / span[:, None]
        c0 = -np.sum(nrm * (anchor - c), axis=-1) / L
    line = np.concatenate([nrm, c0[:, None]], axis=-1)
    finite_line = (fa & fb & (span > DEGENERATE * L)) | (fa & ib) | (ia & fb)
    apart = np.abs(ha[:, 0] * hb[:, 1] - ha[:, 1] * hb[:, 0]) > DEGENERATE
    at_inf = ia & ib & apart
    return np.where(finite_line[:, None], line,
                    np.where(at_inf[:, None], np.array([0.0, 0.0, 1.0]), np.nan))


def _line_error(pa, ea, pb, eb):
    """How far a three-centre line through centres at ``pa``, ``pb`` (scaled frame) may be off.

    ``pa``, ``pb`` are NaN for a centre at infinity, whose ``e`` is then the error of
    its direction (rad).  Returns ``(q, e0, slope, at_inf)``: the line may be displaced
    by ``e0 + slope * |X - q|`` at a point ``X``; ``at_inf`` marks the line at infinity
    (both centres at infinity), for which ``slope`` is the directions' error.
    """
    fa = np.all(np.isfinite(pa), axis=-1)
    fb = np.all(np.isfinite(pb), axis=-1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        span = np.linalg.norm(pa - pb, axis=-1)
        slope_ff = (ea + eb) / span
    q = np.where(fa[..., None], pa, pb)
    e0 = np.where(fa & fb, np.maximum(ea, eb), np.where(fa, ea, eb))
    slope = np.where(fa & fb, slope_ff, np.where(fa, eb, np.where(fb, ea, np.maximum(ea, eb))))
    return q, e0, slope, ~fa & ~fb


def intersect_best(H, PG, E, i, j, ks, c, L):
    """Centre ``P_ij`` from the best pair of three-centre lines through it.

    For every step, of the lines ``P_ik P_kj`` (``k`` in ``ks``) the pair whose
    intersection has the smallest estimated error (relative to its distance)
    is used: the error of each line, propagated from the error estimates of
    its two centres, divided by the sine of the angle between the lines.

    Returns
    -------
    h : ndarray (N, 3)
        Unit homogeneous centre, scaled frame (NaN where no pair of lines meets).
    err : ndarray (N,)
        Its error estimate: scaled length, or rad for a centre at infinity.
    angle : ndarray (N,)
        Angle between the two lines used (rad, ``pi/2`` with the line at infinity).
    via : ndarray of int (N, 2)
        Their third links ``k``, ``l``.
    """
    lines = np.stack([_line(H[i, k], PG[i, k], H[k, j], PG[k, j], c, L) for k in ks])
    model = [_line_error((PG[i, k] - c) / L, E[i, k], (PG[k, j] - c) / L, E[k, j]) for k in ks]
    K, N = lines.shape[:2]
    best_r = np.full(N, np.inf)
    best = np.full((N, 3), np.nan)
    best_err = np.full(N, np.nan)
    best_angle = np.full(N, np.nan)
    best_via = np.full((N, 2), -1, dtype=int)
    for a in range(K):
        for b in range(a + 1, K):
            la, lb = lines[a], lines[b]
            qa, ea, sa, ia = model[a]
            qb, eb, sb, ib = model[b]
            meet = np.cross(la, lb)
            # one line twice (or a line through a centre missing at that step) meets nothing
            valid = np.linalg.norm(meet, axis=-1) > DEGENERATE  # False for NaN too
            h = snap(meet)
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                sin = np.abs(la[:, 0] * lb[:, 1] - la[:, 1] * lb[:, 0]) / (
                    np.linalg.norm(la[:, :2], axis=-1) * np.linalg.norm(lb[:, :2], axis=-1))
                sin = np.minimum(np.where(ia | ib, 1.0, sin), 1.0)
                X = h[:, :2] / h[:, 2:3]
                off = (ea + sa * np.linalg.norm(X - qa, axis=-1)
                       + eb + sb * np.linalg.norm(X - qb, axis=-1))
                err = np.where(h[:, 2] != 0.0, off / sin,
                               np.where(ia, sb, np.where(ib, sa, np.maximum(sa, sb))))
                # Nearly parallel lines meet far away (at infinity after the snap) only if they
                # are two lines: apart, near the mechanism, by much more than either may be off
                # there.  Lines that one may be for all their errors meet anywhere.
                na = np.linalg.norm(la[:, :2], axis=-1)
                nb = np.linalg.norm(lb[:, :2], axis=-1)
                same_sense = np.sign(np.sum(la[:, :2] * lb[:, :2], axis=-1))
                apart = np.abs(la[:, 2] / na - same_sense * lb[:, 2] / nb)
                slack = (ea + sa * np.linalg.norm(qa, axis=-1) + eb + sb * np.linalg.norm(qb, axis=-1))
                two_lines = ia | ib | (apart > DISTINCT * slack)
            rel = relative(h, err)
            valid &= np.where(h[:, 2] == 0.0, two_lines, rel <= UNCERTAIN)
            r = np.where(valid, rel, np.inf)
            better = r < best_r
            if not better.any():
                continue
            best_r = np.where(better, r, best_r)
            best = np.where(better[:, None], h, best)
            best_err = np.where(better, err, best_err)
            best_angle = np.where(better, np.arcsin(sin), best_angle)
            best_via = np.where(better[:, None], [ks[a], ks[b]], best_via)
    ok = np.isfinite(best_r)
    return (np.where(ok[:, None], best, np.nan), np.where(ok, best_err, np.nan),
            np.where(ok, best_angle, np.nan), np.where(ok[:, None], best_via, -1))
