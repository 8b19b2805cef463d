"""What every design by the stroke-time ratio ``K`` shares (see :mod:`linkage_sym.synthesis.kratio`).

The extreme-position angle ``theta`` of ``K`` (eq. 2-2), the refusal of a
design the scene format cannot hold (:func:`check_design`), and the search of
the best pivot along the auxiliary arcs (:func:`best`: a grid of :data:`GRID`
points per admissible interval, then golden-section search to
:data:`ALPHA_TOL`).  NumPy only (import contract in ``pyproject.toml``).
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.errors import POINTERS
from linkage_sym.synthesis import builders
from linkage_sym.synthesis.common import (
    MAX_LENGTH,
    MIN_LENGTH,
    PI,
    SynthesisError,
    crank_apart,
    fmt_deg,
    fmt_len,
    number,
)

__all__ = ["ALPHA_TOL", "GRID", "GUIDE_K_MAX", "best", "check_design", "extreme_position_angle",
           "golden_max"]

GRID = 4001
"""Points per admissible interval of ``alpha`` in the search for the best design."""

ALPHA_TOL = 1e-13
"""Golden-section search stops when the bracket of ``alpha`` (rad) is this narrow."""

_GOLD = (math.sqrt(5.0) - 1.0) / 2.0

GUIDE_K_MAX = PI / (2.0 * math.asin(math.sqrt(builders.GUIDE_CLEARANCE / 2.0))) - 1.0
"""Largest ``K`` of a guide-bar: ``a = d sin(theta/2) = d cos(pi/(K + 1))`` is within
``GUIDE_CLEARANCE d`` of ``d`` from there on (about 2.2e6)."""


def extreme_position_angle(K) -> float:
    """``theta = pi (K - 1)/(K + 1)`` (rad) of a stroke-time ratio ``K > 1`` (eq. 2-2).

    Raises
    ------
    SynthesisError
        ``K <= 1`` or not a finite number; ``K`` so large that ``theta``
        rounds to ``pi`` (180 degrees) in float64 (from about ``K = 1e16``).

    Examples
    --------
    >>> round(math.degrees(extreme_position_angle(1.5)), 12)
    36.0
    >>> extreme_position_angle(0.8)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: K: the stroke-time ratio is the slower stroke's time over the faster's, so K >= 1; got 0.8
    >>> extreme_position_angle(1e308)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: K: K = 1e+308 is too large: θ = 180°·(K - 1)/(K + 1) rounds to 180° in float64 ...
    """
    K = number("K", K)
    if K < 1:
        raise SynthesisError("K", "the stroke-time ratio is the slower stroke's time over the "
                                  f"faster's, so K >= 1; got {K:g}")
    if K == 1:
        raise SynthesisError("K", "K = 1 means no quick return (theta = 0): the auxiliary circle "
                                  "degenerates into the line C1C2 and fixes no crank pivot; build "
                                  "a linkage without quick return from its dimensions "
                                  f"({POINTERS['builders']})")
    theta = PI * ((K - 1.0) / (K + 1.0))  # the ratio first: PI * (K - 1) overflows for K near 1e308
    if not theta < PI:
        raise SynthesisError("K", f"K = {K:g} is too large: θ = 180°·(K - 1)/(K + 1) rounds to 180° "
                                  "in float64 (it does from about K = 1e16 on), and the faster stroke "
                                  "would take no crank angle (π - θ = 0): no linkage has such extreme "
                                  "positions; each design has a smaller bound (a slider-crank K < 3, "
                                  "a crank-rocker θ < 90° + ψ/2, a guide-bar K < "
                                  f"{GUIDE_K_MAX:.3g})")
    return theta


def check_design(K, theta, lengths: dict, reach: float, size: float, scale: str, value: float,
                 proportional: bool, short: tuple | None = None) -> None:
    """Refuse a design the scene format cannot hold, before the builders are asked for it.

    ``lengths``: the design's link lengths by name (the crank's is ``"crank"``);
    ``reach``: the farthest a joint comes from the crank pivot as the crank
    turns (the builders' bound); ``size``: a bound above the largest distance
    between two joints; ``scale``: the requested length (``value``) that sets
    the design's size, named in the refusals of a design too large or too
    small; ``proportional``: the design is ``value`` times a shape fixed by
    ``K`` (and the swing), so the bound on ``value`` can be given; ``short``:
    ``(field, why, hint)`` of the refusal of a crank too short against the
    size (by default ``K`` too close to 1).
    """
    field, why, hint = short or ("K", f"K = {K:.17g} (θ = {fmt_deg(theta)}) is too close to 1 for "
                                 "this request: the crank", "; ask for a larger K (the crank "
                                 "shrinks against the other links as K goes to 1)")
    crank_apart(field, lengths["crank"], size, why, hint)
    big = max(reach, *lengths.values())
    if not big <= MAX_LENGTH:
        bound = (f"; with this K the {scale} must be below {fmt_len(value * MAX_LENGTH / big)}"
                 if proportional else f"; ask for a smaller {scale}")
        raise SynthesisError(scale, f"with K = {K:g} (θ = {fmt_deg(theta)}) the linkage's joints "
                                    f"come up to {fmt_len(big)} from the crank pivot A, beyond the "
                                    f"scene format's +-{MAX_LENGTH:.0e} m on coordinates (the solver "
                                    "multiplies up to ten such lengths, and every product must stay "
                                    f"within the float64 range 1.8e308){bound}")
    which, small = min(lengths.items(), key=lambda item: item[1])
    if not small >= MIN_LENGTH:
        bound = (f"; with this K the {scale} must be at least {fmt_len(value * MIN_LENGTH / small)}"
                 if proportional else f"; ask for a larger {scale}")
        raise SynthesisError(scale, f"with K = {K:g} (θ = {fmt_deg(theta)}) the {which} would be "
                                    f"{fmt_len(small)}, below the scene format's smallest length "
                                    f"{MIN_LENGTH:.0e} m (products of up to ten lengths must stay "
                                    f"above float64's smallest normal number 2.2e-308){bound}")


def golden_max(f, lo: float, hi: float, tol: float = ALPHA_TOL) -> float:
    """Argument of the maximum of a unimodal ``f`` on ``[lo, hi]`` (golden-section search)."""
    x1, x2 = hi - _GOLD * (hi - lo), lo + _GOLD * (hi - lo)
    f1, f2 = f(x1), f(x2)
    while hi - lo > tol:
        if f1 < f2:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + _GOLD * (hi - lo)
            f2 = f(x2)
        else:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - _GOLD * (hi - lo)
            f1 = f(x1)
    return 0.5 * (lo + hi)


def best(f_vec, f, intervals) -> tuple:
    """``(value, alpha, interval index)`` of the largest ``f`` over the intervals (grid, then golden)."""
    best = None
    for k, (lo, hi) in enumerate(intervals):
        x = np.linspace(lo, hi, GRID + 2)[1:-1]
        v = f_vec(x)
        i = int(np.nanargmax(v))
        a, b = x[max(i - 1, 0)] if i > 0 else lo, x[i + 1] if i + 1 < len(x) else hi
        xs = golden_max(f, a, b)
        val = f(xs)
        if best is None or val > best[0]:
            best = (val, xs, k)
    return best
