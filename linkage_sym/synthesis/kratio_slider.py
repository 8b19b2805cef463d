"""Offset slider-crank and rocking guide-bar by the stroke-time ratio ``K``.

The slider-crank's auxiliary circle over its stroke, with the offset, the
crank or the largest minimum transmission angle as the one more condition;
the guide-bar, its inversion, whose guide is tangent to the crank circle at
the extremes (see :mod:`linkage_sym.synthesis.kratio`).  NumPy only (import
contract in ``pyproject.toml``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from linkage_sym.synthesis import builders
from linkage_sym.synthesis.common import (
    COINCIDENCE,
    PI,
    Design,
    SynthesisError,
    coordinate,
    fmt_deg,
    fmt_len,
    positive,
)
from linkage_sym.synthesis.kratio_check import checked
from linkage_sym.synthesis.kratio_common import (
    GUIDE_K_MAX,
    best,
    check_design,
    extreme_position_angle,
)

__all__ = ["guide_bar", "slider_crank"]


def slider_crank(K, stroke, *, offset=None, crank=None, name="slider-crank", steps=361,
                 speed=1.0) -> Design:
    """Offset slider-crank with stroke-time ratio ``K`` and stroke ``H``.

    Parameters
    ----------
    K : float
        Stroke-time ratio, ``1 < K < 3`` (``theta < 90`` degrees).
    stroke : float
        The slider's stroke ``H`` (m).
    offset, crank : float, optional
        The extra condition (at most one): the offset ``e`` (m, not 0; its
        sign puts the slider's line at ``y = e``) or the crank length (m).
        Without either, the design with the largest minimum transmission
        angle, its line at ``y = +e``.
    name, steps, speed
        As for :func:`crank_rocker`.

    Returns
    -------
    Design
        A slider-crank scene (see :func:`linkage_sym.synthesis.builders.slider_crank`)
        assembled at the slider's far extreme (crank and rod extended).

    Raises
    ------
    SynthesisError
        ``K <= 1`` or ``K >= 3``; a stroke not > 0; both ``offset`` and
        ``crank``; an offset of 0 or ``|e| >= H cot(theta)`` (too large for the
        stroke); a crank outside ``(H tan(theta/2)/2, H/2)``.

    Examples
    --------
    >>> d = slider_crank(1.4, 0.1, offset=0.02)
    >>> {k: round(v, 9) for k, v in d.lengths.items()}
    {'crank': 0.047244585, 'coupler': 0.078943339, 'offset': 0.02}
    >>> round(d.extra["stroke"], 12), round(math.degrees(d.theta), 9)
    (0.1, 30.0)
    >>> slider_crank(1.4, 0.1, offset=0.2)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: offset: too large for the stroke: with K = 1.4 (θ = 30°) and the stroke 0.1 m the offset must be below H·cot θ = 0.173205 m (the foot of the crank pivot on the slider's line must lie outside the stroke); got 0.2 m
    """
    theta = extreme_position_angle(K)
    K = float(K)
    H = positive("stroke", stroke)
    if theta >= PI / 2:
        raise SynthesisError("K", f"K = {K:g} gives θ = {fmt_deg(theta)}: an offset slider-crank's "
                                  "extreme-position angle is below 90° (K < 3), since the foot of "
                                  "the crank pivot on the slider's line must lie outside the stroke")
    if offset is not None and crank is not None:
        raise SynthesisError("offset", "give one extra condition, offset or crank, not both")
    R = H / (2 * math.sin(theta))
    alpha, sign, notes = _slider_pivot(K, theta, H, R, offset, crank)
    a, b, e = (float(v) for v in _slider_lengths(R, theta, alpha))
    if offset is not None:  # the requested values as given (the recomputed ones equal to rounding)
        e = abs(float(offset))
    elif crank is not None:
        a = float(crank)
    # at the far extreme A, B and C are in line: |AC1| = a + b is the size and the reach
    check_design(K, theta, {"crank": a, "connecting rod": b}, a + b, a + b, "stroke", H,
                 offset is None and crank is None)
    design = _slider_design(a, b, e, H, alpha, sign, name, steps, speed)
    extra = {**design.extra, "alpha": alpha}
    design = dataclasses.replace(design, K=K, theta=theta, notes=(*design.notes, *notes), extra=extra)
    if offset is not None:
        return checked(design, K, "offset", "ask for a larger offset: with a small one the crank "
                       "and the connecting rod are nearly equal, and K rests on their difference")
    if crank is not None:
        return checked(design, K, "crank", "ask for another crank")
    return checked(design, K, "K", "ask for another K")


def _slider_pivot(K, theta, H, R, offset, crank) -> tuple:
    """``(alpha, sign, notes)``: the pivot's angle ``A C1 C2`` meeting the offset, the crank
    or (neither given) the largest minimum transmission angle, and the side of the offset."""
    top = PI / 2 - theta
    sign = 1.0
    notes = []
    if offset is not None:
        e = coordinate("offset", offset)
        if e == 0:
            raise SynthesisError("offset", "0 gives no quick return (θ = 0); K > 1 needs an offset")
        sign = math.copysign(1.0, e)
        e_max = H / math.tan(theta)
        if abs(e) >= e_max:
            raise SynthesisError("offset", f"too large for the stroke: with K = {K:g} "
                                 f"(θ = {fmt_deg(theta)}) and the stroke {fmt_len(H)} the offset must "
                                 f"be below H·cot θ = {fmt_len(e_max)} (the foot of the crank pivot "
                                 f"on the slider's line must lie outside the stroke); got "
                                 f"{fmt_len(abs(e))}")
        # cos(2 alpha + theta) = cos(theta) - |e|/R, solved through 1 - cos x = 2 sin^2(x/2):
        # acos(cos(theta) - |e|/R) loses every digit of a small theta or |e|/R (K near 1)
        alpha = math.asin(math.sqrt(math.sin(theta / 2) ** 2 + abs(e) / (2 * R))) - theta / 2
    elif crank is not None:
        a = positive("crank", crank)
        lo, hi = H * math.tan(theta / 2) / 2, H / 2
        if not lo < a < hi:
            raise SynthesisError("crank", f"with K = {K:g} (θ = {fmt_deg(theta)}) and the stroke "
                                 f"{fmt_len(H)} the crank must lie between H·tan(θ/2)/2 = "
                                 f"{fmt_len(lo)} (offset H·cot θ) and H/2 = {fmt_len(hi)} (offset 0); "
                                 f"got {fmt_len(a)}")
        alpha = math.acos(a / (2 * R * math.sin(theta / 2))) - theta / 2
    else:
        def gamma(x):
            a, b, e = _slider_lengths(R, theta, x)
            return np.arccos(np.clip((a + e) / b, -1.0, 1.0))
        val, alpha, _ = best(gamma, lambda x: float(gamma(x)), [(0.0, top)])
        notes.append("no extra condition (offset or crank length) given: the crank pivot is the one "
                     "of the auxiliary circle's admissible arc with the largest minimum transmission "
                     f"angle ({fmt_deg(val)})")
    return alpha, sign, notes


def _slider_design(a, b, e, H, alpha, sign, name, steps, speed) -> Design:
    """The slider-crank of pivot ``alpha``, assembled at the far extreme, its line at ``y = sign e``."""
    C1 = np.array([-H / 2, 0.0])
    l1 = a + b
    A = C1 + l1 * np.array([math.cos(alpha), math.sin(alpha)])
    C1f = A - C1  # rotated by pi about A: the slider's line at y = +e, the stroke on +x
    C1f[1] *= sign
    phi0 = math.atan2(C1f[1], C1f[0])
    return builders.slider_crank(a, b, sign * e, crank_deg=math.degrees(phi0), branch="right",
                                 name=name, steps=steps, speed=speed)


def _slider_lengths(R, theta, alpha):
    """``(a, b, e)`` of the slider-crank whose pivot is at ``alpha`` (arrays allowed)."""
    l1, l2 = 2 * R * np.sin(theta + alpha), 2 * R * np.sin(alpha)
    return (l1 - l2) / 2, (l1 + l2) / 2, l1 * np.sin(alpha)


def guide_bar(K, ground, *, name="guide-bar", steps=361, speed=1.0) -> Design:
    """Rocking guide-bar with stroke-time ratio ``K`` and frame distance ``AD``.

    The guide's swing equals ``theta`` and the crank is ``a = d sin(theta/2)``:
    at the extremes the guide is tangent to the crank circle.  The scene is
    assembled at one extreme (crank angle ``90 - theta/2`` degrees).

    ``K`` must leave a crank longer than 1e-9 of the frame distance (the scene
    format's coincidence tolerance: ``K`` above about ``1 + 1.3e-9``) and
    shorter than it by more than
    :data:`~linkage_sym.synthesis.builders.GUIDE_CLEARANCE` (``K`` below about 2.2e6);
    and, as every design by ``K``, its scene's coordinates must hold ``K`` to
    :data:`K_RTOL` (:func:`scene_K`), which float64 does up to ``K`` of about 1e4:
    beyond, ``d - a`` is a few ulp of ``d``.

    Examples
    --------
    >>> d = guide_bar(2.0, 0.4)
    >>> round(d.lengths["crank"], 15), round(math.degrees(d.extra["swing"]), 9)
    (0.2, 60.0)
    >>> guide_bar(1e7, 0.4)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: K: K = 1e+07 is too large for a guide-bar: ... the guide-bar needs K < 2.22144e+06
    """
    theta = extreme_position_angle(K)
    K = float(K)
    d = positive("ground", ground)
    a = d * math.sin(theta / 2)
    if not d - a > builders.GUIDE_CLEARANCE * d:
        raise SynthesisError("K", f"K = {K:g} is too large for a guide-bar: its crank d·sin(θ/2) "
                                  f"(θ = {fmt_deg(theta)}) would equal the frame distance to "
                                  f"{builders.GUIDE_CLEARANCE:g} of it, and the block would pass "
                                  "through the guide's pivot D, where the guide's direction is "
                                  f"undefined; the guide-bar needs K < {GUIDE_K_MAX:.6g}")
    # the joints A, B (the block's too) and D: the size is d (|AB| = a < d, |BD| = sqrt(d² - a²))
    t_min = 2.0 * math.asin(COINCIDENCE)
    check_design(K, theta, {"crank": a, "ground": d}, d, d, "ground", d, True,
                 ("K", f"K = {K:.17g} (θ = {fmt_deg(theta)}) is too close to 1 for a guide-bar: "
                   "its crank d·sin(θ/2)", "; the guide-bar needs K > "
                   f"{(PI + t_min) / (PI - t_min):.12g}"))
    design = builders.guide_bar(a, d, crank_deg=90.0 - math.degrees(theta) / 2, name=name,
                                steps=steps, speed=speed)
    design = dataclasses.replace(design, K=K, theta=theta)
    return checked(design, K, "K", "the crank d·sin(θ/2) is then so close to the frame distance d "
                    "that float64 cannot place it; ask for a smaller K")
