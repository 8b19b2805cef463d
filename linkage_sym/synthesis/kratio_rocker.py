"""Synthesis by the stroke-time ratio ``K``: crank-rocker, offset slider-crank, guide-bar.

The textbook section *Design of four-bar mechanisms* (Sources [2] of the
README; "design by a given stroke-time ratio", Fig. 2-65) designs a linkage
with quick return from ``K``, the ratio of the slower stroke's time to the
faster's.  The crank turns through ``pi + theta`` in one stroke and
``pi - theta`` in the other, so (eq. 2-2)::

    theta = pi (K - 1) / (K + 1)        (180 deg (K - 1)/(K + 1))

the *extreme-position angle*: the angle at the crank pivot ``A`` between the
lines to the output's two extreme positions ``C1`` (crank and coupler
extended, ``AC1 = b + a``) and ``C2`` (overlapping, ``AC2 = b - a``).

**Auxiliary circle.**  Every point that sees the chord ``C1 C2`` under the
angle ``theta`` lies on one of two arcs of radius ``R = |C1C2| / (2 sin theta)``
through ``C1`` and ``C2``, mirror images in the chord's line (the section draws
the one on the side away from the rocker's pivot ``D``; the other one, on
``D``'s side, gives valid crank-rockers too).  With ``alpha`` the angle
``A C1 C2``, the law of sines gives ``AC1 = 2R sin(theta + alpha)`` and
``AC2 = 2R sin(alpha)``, hence the crank ``a = (AC1 - AC2)/2 =
2R sin(theta/2) cos(alpha + theta/2)`` and the coupler ``b = (AC1 + AC2)/2``.
Each arc's two halves (either side of the chord's perpendicular bisector,
which passes through ``D``) are mirror images giving the same linkage, so
``alpha`` runs over ``(0, (pi - theta)/2)`` on each arc.

**The forbidden arc.**  At the extreme positions the dyad ``B C D`` has its
assembly mode given by the side of line ``AD`` that ``C1`` (or ``C2``) lies on;
both extremes are reached in one assembly mode only if ``C1`` and ``C2`` lie on
one side of ``AD``.  A pivot ``A`` between the lines ``D C1`` and ``D C2`` (the
double wedge they form at ``D``) puts them on opposite sides: it is refused.
On its boundary ``A``, ``D`` and an extreme position are in line and the
transmission angle there is 0.  Elsewhere the triangle inequalities of
``A C1 D`` and ``A C2 D`` are exactly Grashof's conditions with the crank
shortest: every admissible pivot gives a crank-rocker whose rocker swings
through ``psi`` with the ratio ``K``.

**Which requests have a solution.**  The line ``D C1`` meets the arc away
from ``D`` (besides ``C1``) only if ``theta + psi/2 < 90`` degrees, and that
arc's admissible part ends there; the arc on ``D``'s side has an admissible
part exactly when ``theta < 90 + psi/2`` degrees.  So a crank-rocker with
swing ``psi`` exists for ``theta < 90 + psi/2`` degrees (tested against the
side-of-line criterion itself); larger ``K`` is refused.

**One more condition.**  The section notes the infinitely many solutions
until one more is given: the ground length ``AD`` (the circle of radius ``d``
about ``D`` meets each arc at most once per half), the crank length (``alpha``
in closed form above), or -- when neither is given -- the largest minimum
transmission angle, found over the admissible arcs (a grid of
:data:`GRID` points per interval, then golden-section search to
:data:`ALPHA_TOL` in ``alpha``).

**Slider-crank** (stroke ``H``): the chord is the stroke on the slider's
line; the foot of ``A`` on that line must lie outside the stroke (else the
two extremes are in different assembly modes), which needs ``theta < 90``
degrees and an offset ``0 < e < H cot(theta)``; then ``e = AC1 sin(alpha)``,
``alpha`` over ``(0, pi/2 - theta)``, and the minimum transmission angle is
``acos((a + e)/b)``.

**Guide-bar** (frame ``d``): at the extremes the guide is tangent to the
crank circle, so the guide's swing equals ``theta`` and ``a = d sin(theta/2)``;
its transmission angle is 90 degrees throughout.

NumPy only (import contract in ``pyproject.toml``); the same relations
derived with SymPy are in :mod:`linkage_sym.synthesis.equations`.
"""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction

import numpy as np

from linkage_sym.synthesis import builders
from linkage_sym.synthesis.common import (
    COINCIDENCE,
    MAX_LENGTH,
    MIN_LENGTH,
    PI,
    Design,
    SynthesisError,
    coordinate,
    crank_apart,
    cross,
    fmt_deg,
    fmt_len,
    number,
    positive,
)

GRID = 4001
"""Points per admissible interval of ``alpha`` in the search for the best design."""

ALPHA_TOL = 1e-13
"""Golden-section search stops when the bracket of ``alpha`` (rad) is this narrow."""

_GOLD = (math.sqrt(5.0) - 1.0) / 2.0

K_RTOL = 1e-9
"""A design is written only if the stroke-time ratio of its scene's joint coordinates is
the requested ``K`` to this fraction of it (:func:`scene_K`)."""


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
                                  "('linkage-sym new')")
    theta = PI * ((K - 1.0) / (K + 1.0))  # the ratio first: PI * (K - 1) overflows for K near 1e308
    if not theta < PI:
        raise SynthesisError("K", f"K = {K:g} is too large: θ = 180°·(K - 1)/(K + 1) rounds to 180° "
                                  "in float64 (it does from about K = 1e16 on), and the faster stroke "
                                  "would take no crank angle (π - θ = 0): no linkage has such extreme "
                                  "positions; each design has a smaller bound (a slider-crank K < 3, "
                                  "a crank-rocker θ < 90° + ψ/2, a guide-bar K < "
                                  f"{_GUIDE_K_MAX:.3g})")
    return theta


def _check_design(K, theta, lengths: dict, reach: float, size: float, scale: str, value: float,
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


def _golden_max(f, lo: float, hi: float, tol: float = ALPHA_TOL) -> float:
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


def _best(f_vec, f, intervals) -> tuple:
    """``(value, alpha, interval index)`` of the largest ``f`` over the intervals (grid, then golden)."""
    best = None
    for k, (lo, hi) in enumerate(intervals):
        x = np.linspace(lo, hi, GRID + 2)[1:-1]
        v = f_vec(x)
        i = int(np.nanargmax(v))
        a, b = x[max(i - 1, 0)] if i > 0 else lo, x[i + 1] if i + 1 < len(x) else hi
        xs = _golden_max(f, a, b)
        val = f(xs)
        if best is None or val > best[0]:
            best = (val, xs, k)
    return best


# ------------------------------------------------------------------ crank-rocker


@dataclasses.dataclass(frozen=True)
class _RockerFrame:
    """The design frame of a crank-rocker: chord ``C1 C2`` on the x-axis, its midpoint at the origin."""

    theta: float
    c: float
    psi: float

    @property
    def s(self) -> float:  # half the chord
        return self.c * math.sin(self.psi / 2)

    @property
    def R(self) -> float:
        return self.s / math.sin(self.theta)

    @property
    def C1(self):
        return np.array([-self.s, 0.0])

    @property
    def C2(self):
        return np.array([self.s, 0.0])

    @property
    def D(self):
        return np.array([0.0, -self.c * math.cos(self.psi / 2)])

    def centre(self, side: int):
        return np.array([0.0, side * self.R * math.cos(self.theta)])

    def lengths(self, alpha):
        """``(AC1, AC2)`` at ``alpha`` (arrays allowed)."""
        return 2 * self.R * np.sin(self.theta + alpha), 2 * self.R * np.sin(alpha)

    def pivot(self, alpha, side: int):
        l1, _ = self.lengths(alpha)
        return np.stack([-self.s + l1 * np.cos(alpha), side * l1 * np.sin(alpha)], axis=-1)

    def admissible(self, A) -> bool:
        """``C1`` and ``C2`` strictly on one side of the line ``A D``."""
        D = self.D
        return cross(A - D, self.C1 - D) * cross(A - D, self.C2 - D) > 0

    def intervals(self, side: int) -> list:
        """Admissible open intervals of ``alpha`` on the half arc ``(0, (pi - theta)/2)``."""
        top = (PI - self.theta) / 2
        alpha_f = PI / 2 + side * self.psi / 2  # A on the line D C1
        cuts = []
        if 0 < alpha_f < PI - self.theta:
            cuts = [x for x in (alpha_f, PI - self.theta - alpha_f) if 0 < x < top]
        edges = [0.0, *sorted(cuts), top]
        out = []
        for lo, hi in zip(edges[:-1], edges[1:]):
            if hi > lo and self.admissible(self.pivot(0.5 * (lo + hi), side)):
                out.append((lo, hi))
        return out

    def design_lengths(self, alpha, side: int):
        """``(a, b, c, d)`` at ``alpha`` on arc ``side`` (arrays allowed)."""
        l1, l2 = self.lengths(alpha)
        A = self.pivot(alpha, side)
        d = np.hypot(A[..., 0] - self.D[0], A[..., 1] - self.D[1])
        return (l1 - l2) / 2, (l1 + l2) / 2, self.c, d


def _gamma_min_vec(a, b, c, d):
    """Vectorised :func:`builders.fourbar_gamma_min` (its value only)."""
    def acute_angle(r):
        g = np.arccos(np.clip((b * b + c * c - r * r) / (2 * b * c), -1.0, 1.0))
        return np.minimum(g, PI - g)
    return np.minimum(acute_angle(np.abs(d - a)), acute_angle(d + a))


def crank_rocker(K, rocker, swing_deg, *, ground=None, crank=None, name="crank-rocker", steps=361,
                 speed=1.0) -> Design:
    """Crank-rocker with stroke-time ratio ``K``, rocker length and swing angle.

    Parameters
    ----------
    K : float
        Stroke-time ratio, > 1.
    rocker : float
        Rocker length ``CD`` (m).
    swing_deg : float
        The rocker's swing angle ``psi`` (degrees, 0 < psi < 180).
    ground, crank : float, optional
        The extra condition: the frame length ``AD`` or the crank length
        ``AB`` (m); at most one.  Without either, the design with the
        largest minimum transmission angle over the admissible arcs.
    name, steps, speed
        The scene's name, the sweep's steps and the crank's speed (rad/s).

    Returns
    -------
    Design
        A four-bar scene (see :func:`linkage_sym.synthesis.builders.fourbar`)
        assembled at the rocker's extreme position ``C1`` (crank and coupler
        extended), the driver turning one full turn from there; ``K`` and
        ``theta`` as requested, ``gamma_min`` and where, ``extra["swing"]``,
        ``extra["arc"]`` (``"far"``: the auxiliary arc on the side of ``C1C2``
        away from ``D``, as the textbook draws it; ``"near"``: on ``D``'s
        side), and ``notes`` with the choice made.

    Raises
    ------
    SynthesisError
        ``K <= 1``; ``theta >= 90 + psi/2`` degrees (no admissible pivot);
        a length not > 0; ``psi`` outside (0, 180); both
        ``ground`` and ``crank``; a ``ground`` or ``crank`` that no admissible
        pivot has (the message gives the admissible ranges).

    Examples
    --------
    >>> d = crank_rocker(1.5, 0.075, 45.0, ground=0.1)
    >>> {k: round(v, 9) for k, v in d.lengths.items()}
    {'crank': 0.025224106, 'coupler': 0.05098873, 'rocker': 0.075, 'ground': 0.1}
    >>> round(math.degrees(d.theta), 9), round(math.degrees(d.gamma_min), 6), d.extra["arc"]
    (36.0, 12.868054, 'far')
    >>> crank_rocker(1.5, 0.075, 45.0, ground=0.3)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: ground: no admissible crank pivot is 0.3 m from D: no point of the auxiliary arcs is at that distance; admissible ground lengths: 0.075 m to 0.126027 m (arc away from D), 0.0199607 m to 0.075 m (arc on D's side)
    >>> crank_rocker(1.5, 0.075, 45.0, ground=0.13)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: ground: no admissible crank pivot is 0.13 m from D: the crank pivots at that distance lie on the forbidden arc between the lines D-C1 and D-C2 (the rocker's extreme positions would be in different assembly modes); admissible ground lengths: 0.075 m to 0.126027 m (arc away from D), 0.0199607 m to 0.075 m (arc on D's side)
    """
    theta = extreme_position_angle(K)
    K = float(K)
    c = positive("rocker", rocker)
    psi_deg = number("swing_deg", swing_deg)
    if not 0 < psi_deg < 180:
        raise SynthesisError("swing_deg", "a crank-rocker's rocker swings through more than 0° "
                                          f"and less than 180°; got {psi_deg:g}°")
    if ground is not None and crank is not None:
        raise SynthesisError("ground", "give one extra condition, ground or crank, not both")
    psi = math.radians(psi_deg)
    fr = _RockerFrame(theta, c, psi)
    arcs = {side: fr.intervals(side) for side in (1, -1)}
    arc_name = {1: "arc away from D", -1: "arc on D's side"}
    if not (arcs[1] or arcs[-1]):
        t_max = PI / 2 + psi / 2
        raise SynthesisError("K", f"K = {K:g} (θ = {fmt_deg(theta)}) leaves no admissible crank "
                             f"pivot for the swing {psi_deg:g}°: every point of the auxiliary arcs "
                             "is on the forbidden arc between the lines D-C1 and D-C2; a "
                             f"crank-rocker needs θ < 90° + ψ/2 = {fmt_deg(t_max)}, i.e. "
                             f"K < {(PI + t_max) / (PI - t_max):.6g}")
    notes = []
    if ground is not None:
        d_req = positive("ground", ground)
        on_arcs = [(side, alpha) for side in (1, -1) for alpha in _alpha_at_ground(fr, side, d_req)]
        found = [(side, alpha) for side, alpha in on_arcs if _inside(alpha, arcs[side])]
        if not found:
            ranges = _ranges(fr, arcs, lambda alpha, side: fr.design_lengths(alpha, side)[3], arc_name)
            why = ("the crank pivots at that distance lie on the forbidden arc between the lines "
                   "D-C1 and D-C2 (the rocker's extreme positions would be in different assembly "
                   "modes)" if on_arcs else "no point of the auxiliary arcs is at that distance")
            raise SynthesisError("ground", f"no admissible crank pivot is {fmt_len(d_req)} from D: "
                                 f"{why}; admissible ground lengths: {ranges}")
        how = f"the ground length {fmt_len(d_req)}"
        exact = {"ground": d_req}
    elif crank is not None:
        a_req = positive("crank", crank)
        found = []
        q = a_req / (2 * fr.R * math.sin(theta / 2))
        if q < 1:
            alpha = math.acos(q) - theta / 2
            found = [(side, alpha) for side in (1, -1) if _inside(alpha, arcs[side])]
        if not found:
            ranges = _ranges(fr, arcs, lambda alpha, side: fr.design_lengths(alpha, side)[0], arc_name)
            raise SynthesisError("crank", f"no admissible crank pivot gives a crank of "
                                 f"{fmt_len(a_req)} (it is at most half the chord C1C2, "
                                 f"{fmt_len(fr.s)}, and pivots on the forbidden arc between the "
                                 "lines D-C1 and D-C2 are refused); admissible crank lengths: "
                                 f"{ranges}")
        how = f"the crank length {fmt_len(a_req)}"
        exact = {"crank": a_req}
    else:
        found = []
        for side in (1, -1):
            if not arcs[side]:
                continue
            val, alpha, _ = _best(lambda x, s=side: _gamma_min_vec(*fr.design_lengths(x, s)),
                                  lambda x, s=side: float(_gamma_min_vec(*fr.design_lengths(x, s))),
                                  arcs[side])
            found.append((side, alpha))
        how, exact = None, {}
    scored = []
    for side, alpha in found:
        a, b, _, d = (float(v) for v in fr.design_lengths(alpha, side))
        scored.append((builders.fourbar_gamma_min(a, b, c, d)[0], side, alpha))
    scored.sort(reverse=True)
    gmin, side, alpha = scored[0]
    if how is None:
        notes.append("no extra condition (ground or crank length) given: the crank pivot is the "
                     "one of the admissible arcs of the auxiliary circles with the largest minimum "
                     f"transmission angle ({fmt_deg(gmin)}, on the {arc_name[side]})")
    elif len(scored) > 1:
        other = scored[1]
        notes.append(f"two crank pivots meet {how} (one on each auxiliary arc): chosen the one with "
                     f"the larger minimum transmission angle, {fmt_deg(gmin)} on the "
                     f"{arc_name[side]} (the other: {fmt_deg(other[0])} on the {arc_name[other[1]]})")
    a, b, _, d = (float(v) for v in fr.design_lengths(alpha, side))
    a, d = exact.get("crank", a), exact.get("ground", d)
    # at C1 the crank and coupler are in line: |AC1| = a + b; |BD| <= min(a + d, b + c)
    scale, value = ("ground", d) if ground is not None and d >= c else ("rocker", c)
    short = None  # K too close to 1: the linkage grows as 1/sin(theta) about a crank <= the chord
    if crank is not None:
        short = ("crank", "the crank asked for", "; ask for a longer crank")
    elif math.sin(psi / 2) < math.sin(theta):  # the chord, and the crank, shrink with the swing
        short = ("swing_deg", f"the swing {psi_deg:g}° is too small for this request: the crank",
                 "; ask for a larger swing")
    _check_design(K, theta, {"crank": a, "coupler": b, "rocker": c, "ground": d}, d + c,
                  max(a + b, c, d, min(a + d, b + c)), scale, value, how is None, short)
    design = _rocker_design(fr, alpha, side, name, steps, speed, exact)
    extra = {**design.extra, "arc": "far" if side == 1 else "near", "alpha": alpha,
             "pivot_design_frame": fr.pivot(alpha, side).tolist()}
    design = dataclasses.replace(design, K=K, theta=theta, notes=(*design.notes, *notes), extra=extra)
    field = "ground" if ground is not None else "crank" if crank is not None else "K"
    return _checked(design, K, field, f"ask for another {field}")


def _inside(alpha: float, intervals) -> bool:
    return any(lo < alpha < hi for lo, hi in intervals)


def _alpha_at_ground(fr: _RockerFrame, side: int, d: float) -> list:
    """``alpha`` of the pivot on arc ``side``'s half that is ``d`` from ``D`` (none or one)."""
    O, D = fr.centre(side), fr.D
    dy = D[1] - O[1]
    if dy == 0.0:
        return []
    y = 0.5 * (O[1] + D[1]) + (fr.R ** 2 - d * d) / (2.0 * dy)
    x2 = fr.R ** 2 - (y - O[1]) ** 2
    if x2 < 0 or side * y <= 0:
        return []
    A = np.array([math.sqrt(x2), y])  # the half of the arc on C2's side (x >= 0)
    alpha = math.atan2(side * (A[1] - fr.C1[1]), A[0] - fr.C1[0])
    return [alpha] if 0 < alpha < (PI - fr.theta) / 2 else []


def _ranges(fr, arcs, quantity, arc_name) -> str:
    """The admissible ranges of a quantity monotone on each interval, as text."""
    parts = []
    for side, intervals in arcs.items():
        for lo, hi in intervals:
            v = sorted(float(quantity(x, side)) for x in (lo, hi))
            parts.append(f"{fmt_len(v[0])} to {fmt_len(v[1])} ({arc_name[side]})")
    return ", ".join(parts) if parts else "none"


def _rocker_design(fr: _RockerFrame, alpha: float, side: int, name, steps, speed, exact) -> Design:
    """The four-bar of pivot ``alpha`` on arc ``side``, in the builders' frame (A at 0, D on +x).

    ``exact``: the requested length (``crank`` or ``ground``), used as given
    instead of its value recomputed from the pivot (equal to rounding).
    """
    a, b, c, _ = (float(v) for v in fr.design_lengths(alpha, side))
    A = fr.pivot(alpha, side)
    u = fr.D - A
    d = float(math.hypot(*u))
    u = u / d
    a, d = exact.get("crank", a), exact.get("ground", d)

    def to_frame(P):
        w = P - A
        return np.array([w @ u, cross(u, w)])

    C1 = to_frame(fr.C1)
    phi0 = math.atan2(C1[1], C1[0])
    B = a * np.array([math.cos(phi0), math.sin(phi0)])
    branch = "open" if cross(np.array([d, 0.0]) - B, C1 - B) > 0 else "crossed"
    return builders.fourbar(a, b, c, d, crank_deg=math.degrees(phi0), branch=branch, name=name,
                            steps=steps, speed=speed)


# ------------------------------------------------------------------ slider-crank


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
        val, alpha, _ = _best(gamma, lambda x: float(gamma(x)), [(0.0, top)])
        notes.append("no extra condition (offset or crank length) given: the crank pivot is the one "
                     "of the auxiliary circle's admissible arc with the largest minimum transmission "
                     f"angle ({fmt_deg(val)})")
    a, b, e = (float(v) for v in _slider_lengths(R, theta, alpha))
    if offset is not None:  # the requested values as given (the recomputed ones equal to rounding)
        e = abs(float(offset))
    elif crank is not None:
        a = float(crank)
    # at the far extreme A, B and C are in line: |AC1| = a + b is the size and the reach
    _check_design(K, theta, {"crank": a, "connecting rod": b}, a + b, a + b, "stroke", H,
                  offset is None and crank is None)
    C1 = np.array([-H / 2, 0.0])
    l1 = a + b
    A = C1 + l1 * np.array([math.cos(alpha), math.sin(alpha)])
    C1f = A - C1  # rotated by pi about A: the slider's line at y = +e, the stroke on +x
    C1f[1] *= sign
    phi0 = math.atan2(C1f[1], C1f[0])
    design = builders.slider_crank(a, b, sign * e, crank_deg=math.degrees(phi0), branch="right",
                                   name=name, steps=steps, speed=speed)
    extra = {**design.extra, "alpha": alpha}
    design = dataclasses.replace(design, K=K, theta=theta, notes=(*design.notes, *notes), extra=extra)
    if offset is not None:
        return _checked(design, K, "offset", "ask for a larger offset: with a small one the crank "
                        "and the connecting rod are nearly equal, and K rests on their difference")
    if crank is not None:
        return _checked(design, K, "crank", "ask for another crank")
    return _checked(design, K, "K", "ask for another K")


def _slider_lengths(R, theta, alpha):
    """``(a, b, e)`` of the slider-crank whose pivot is at ``alpha`` (arrays allowed)."""
    l1, l2 = 2 * R * np.sin(theta + alpha), 2 * R * np.sin(alpha)
    return (l1 - l2) / 2, (l1 + l2) / 2, l1 * np.sin(alpha)


# ------------------------------------------------------------------ guide-bar


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
                                  f"undefined; the guide-bar needs K < {_GUIDE_K_MAX:.6g}")
    # the joints A, B (the block's too) and D: the size is d (|AB| = a < d, |BD| = sqrt(d² - a²))
    t_min = 2.0 * math.asin(COINCIDENCE)
    _check_design(K, theta, {"crank": a, "ground": d}, d, d, "ground", d, True,
                  ("K", f"K = {K:.17g} (θ = {fmt_deg(theta)}) is too close to 1 for a guide-bar: "
                   "its crank d·sin(θ/2)", "; the guide-bar needs K > "
                   f"{(PI + t_min) / (PI - t_min):.12g}"))
    design = builders.guide_bar(a, d, crank_deg=90.0 - math.degrees(theta) / 2, name=name,
                                steps=steps, speed=speed)
    design = dataclasses.replace(design, K=K, theta=theta)
    return _checked(design, K, "K", "the crank d·sin(θ/2) is then so close to the frame distance d "
                    "that float64 cannot place it; ask for a smaller K")


_GUIDE_K_MAX = PI / (2.0 * math.asin(math.sqrt(builders.GUIDE_CLEARANCE / 2.0))) - 1.0
"""Largest ``K`` of a guide-bar: ``a = d sin(theta/2) = d cos(pi/(K + 1))`` is within
``GUIDE_CLEARANCE d`` of ``d`` from there on (about 2.2e6)."""

# ------------------------------------------------------------------ the check of a design


def _joint_points(scene: dict) -> dict:
    return {j["name"]: (Fraction(j["at"][0]), Fraction(j["at"][1])) for j in scene["joints"]}


def _sq(p, q) -> Fraction:
    """Squared distance of two points, exact (the scene's coordinates are binary fractions)."""
    return (p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2


def _diff_of_roots(p2: Fraction, q2: Fraction) -> float:
    """``sqrt(p2) - sqrt(q2)`` to rounding: ``(p2 - q2) / (sqrt(p2) + sqrt(q2))`` with the
    difference of the squares exact."""
    return float(p2 - q2) / (math.sqrt(float(p2)) + math.sqrt(float(q2)))


def _angle_at(p2: Fraction, q2: Fraction, r2: Fraction) -> float:
    """The angle between the sides ``p`` and ``q`` of a triangle of squared sides ``p2``,
    ``q2``, ``r2`` (opposite side ``r``): ``atan2(4 area, p2 + q2 - r2)`` with the squared
    area ``16 area^2 = 4 p2 q2 - (p2 + q2 - r2)^2`` exact."""
    m = p2 + q2 - r2
    s16 = 4 * p2 * q2 - m * m
    return math.atan2(math.sqrt(max(float(s16), 0.0)), float(m))


def _ratio(turn: float) -> float:
    """The stroke-time ratio of a crank that turns through ``turn`` (rad) in one stroke."""
    turn %= 2 * PI
    return max(turn, 2 * PI - turn) / min(turn, 2 * PI - turn)


def scene_K(design: Design) -> float:
    """The stroke-time ratio of a design's scene, from its joints' coordinates as written.

    An evaluation independent of the synthesis: the crank angles of the output's two
    limit positions in closed form from the scene's geometry (squared distances exact,
    from the coordinates' binary values), and ``K`` the larger over the smaller of the
    crank's two turns between them.

    * four-bar ``A B C D``: at the limits ``|AC| = b + a`` (extended) and ``b - a``
      (overlapping), ``|DC| = c``; the angle ``CAD`` of each triangle ``A C D``, ``C`` on
      the assembly configuration's side of ``AD``; the crank points at ``C`` when
      extended and away from it when overlapping;
    * slider-crank ``A B C`` on a slide through ``C``: at the limits ``C`` lies on the
      slide's line at ``b + a`` and ``b - a`` from ``A``;
    * guide-bar ``A B D``: at the limits the guide is tangent to the crank circle,
      ``AB`` perpendicular to ``BD``: the crank at ``+-acos(a/d)`` from ``AD``.

    Examples
    --------
    >>> round(scene_K(guide_bar(2.0, 0.4)), 12)
    2.0
    """
    sc = design.scene
    P = _joint_points(sc)
    A, B = P["A"], P["B"]
    a2 = _sq(A, B)
    if design.kind == "guide-bar":
        D = P["D"]
        d2 = _sq(A, D)
        # beta = acos(a/d) = atan2(sqrt(d^2 - a^2), a)
        beta = math.atan2(math.sqrt(float(d2 - a2)), math.sqrt(float(a2)))
        return _ratio(2 * beta)
    if design.kind == "slider-crank":
        C = P["C"]
        guide = next(j for j in sc["joints"] if j["type"] == "P")
        b2 = _sq(B, C)
        # the slide's line: through C along the axis; A's offset from it, and its foot F
        t = math.radians(guide["axis_deg"])
        ux, uy = math.cos(t), math.sin(t)
        cx, cy = float(C[0] - A[0]), float(C[1] - A[1])
        e = ux * cy - uy * cx
        f = ux * cx + uy * cy  # C's position along the line from the foot
        b, a = math.sqrt(float(b2)), math.sqrt(float(a2))
        s1 = math.sqrt(max((b + a - e) * (b + a + e), 0.0))
        bma = _diff_of_roots(b2, a2)
        s2 = math.sqrt(max((bma - e) * (bma + e), 0.0))
        side = math.copysign(1.0, f)  # the slider on the side of the foot it starts on
        phi1 = math.atan2(e, side * s1)  # the crank toward C1, in the line's frame
        phi2 = math.atan2(e, side * s2) + PI  # away from C2
        return _ratio(phi2 - phi1)
    C, D = P["C"], P["D"]
    b2, c2, d2 = _sq(B, C), _sq(C, D), _sq(A, D)
    # |AC| at the limits: b + a and b - a; the angle CAD of the triangle ACD at each
    ac1 = math.sqrt(float(b2)) + math.sqrt(float(a2))
    ac2 = _diff_of_roots(b2, a2)
    g1 = _angle_at(d2, Fraction(ac1) ** 2, c2)
    g2 = _angle_at(d2, Fraction(ac2) ** 2, c2)
    return _ratio(g2 + PI - g1)


def _checked(design: Design, K: float, field: str, change: str) -> Design:
    """``design`` if its scene holds ``K`` to :data:`K_RTOL` (:func:`scene_K`), else the refusal
    naming ``field``."""
    got = scene_K(design)
    if abs(got - K) <= K_RTOL * K:
        return design
    raise SynthesisError(field, f"the linkage's joint coordinates (float64) do not hold K = {K!r}: "
                                f"its limit positions give K = {got:.10g} (off by {abs(got - K) / K:.2g} "
                                f"of K, more than {K_RTOL:g}); {change}")


__all__ = ["crank_rocker", "extreme_position_angle", "guide_bar", "scene_K", "slider_crank"]
