"""Crank-rocker by the stroke-time ratio ``K``, the rocker and its swing.

The auxiliary circle, its two arcs and the forbidden arc between the lines
``D C1`` and ``D C2`` (see :mod:`linkage_sym.synthesis.kratio`): the design
frame (:class:`_RockerFrame`), the pivot that meets the one more condition
(ground or crank length, or the largest minimum transmission angle) and the
four-bar scene built from it.  NumPy only (import contract in
``pyproject.toml``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from linkage_sym.synthesis import builders
from linkage_sym.synthesis.common import (
    PI,
    Design,
    SynthesisError,
    cross,
    fmt_deg,
    fmt_len,
    number,
    positive,
)
from linkage_sym.synthesis.kratio_check import checked
from linkage_sym.synthesis.kratio_common import best, check_design, extreme_position_angle

__all__ = ["crank_rocker"]

_ARC_NAME = {1: "arc away from D", -1: "arc on D's side"}
"""The two auxiliary arcs by side, as the messages and notes name them."""


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
        pivot has (the message gives the admissible ranges), or whose pivot is
        so close to an end of an admissible arc that the four-bar is a change
        point (:data:`~linkage_sym.structure.grashof.CHANGE_POINT_TOL`).

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
    theta, psi_deg, fr, arcs = _rocker_request(K, rocker, swing_deg, ground, crank)
    K = float(K)
    if ground is not None:
        found, how, exact = _by_ground(fr, arcs, ground)
    elif crank is not None:
        found, how, exact = _by_crank(fr, arcs, crank)
    else:
        found, how, exact = _by_transmission(fr, arcs), None, {}
    side, alpha, notes = _choose(fr, found, how)
    _check_rocker(K, fr, alpha, side, exact, psi_deg)
    field = "ground" if ground is not None else "crank" if crank is not None else "K"
    design = _rocker_design(fr, alpha, side, name, steps, speed, exact)
    if design.K is None:  # the builder's Grashof class: not a crank-rocker
        raise SynthesisError(field, f"the crank pivot of this request is next to an end of an "
                                    "admissible arc (A almost in line with D and C1 or C2), where "
                                    f"the four-bar is no crank-rocker: {design.notes[0]}; its "
                                    "limit positions, which fix K, are ill-conditioned there (a "
                                    "limit position's triangle A C D is nearly flat); ask for "
                                    f"another {field}")
    extra = {**design.extra, "arc": "far" if side == 1 else "near", "alpha": alpha,
             "pivot_design_frame": fr.pivot(alpha, side).tolist()}
    design = dataclasses.replace(design, K=K, theta=theta, notes=(*design.notes, *notes), extra=extra)
    return checked(design, K, field, f"ask for another {field}")


def _rocker_request(K, rocker, swing_deg, ground, crank) -> tuple:
    """``(theta, psi_deg, frame, arcs)`` of a request, refused where it has no pivot at all
    (``arcs``: the admissible intervals of ``alpha`` by side)."""
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
    if not (arcs[1] or arcs[-1]):
        t_max = PI / 2 + psi / 2
        raise SynthesisError("K", f"K = {K:g} (θ = {fmt_deg(theta)}) leaves no admissible crank "
                             f"pivot for the swing {psi_deg:g}°: every point of the auxiliary arcs "
                             "is on the forbidden arc between the lines D-C1 and D-C2; a "
                             f"crank-rocker needs θ < 90° + ψ/2 = {fmt_deg(t_max)}, i.e. "
                             f"K < {(PI + t_max) / (PI - t_max):.6g}")
    return theta, psi_deg, fr, arcs


def _by_ground(fr, arcs, ground) -> tuple:
    """``(found, how, exact)``: the admissible pivots ``(side, alpha)`` at the ground length."""
    d_req = positive("ground", ground)
    on_arcs = [(side, alpha) for side in (1, -1) for alpha in _alpha_at_ground(fr, side, d_req)]
    found = [(side, alpha) for side, alpha in on_arcs if _inside(alpha, arcs[side])]
    if not found:
        ranges = _ranges(fr, arcs, lambda alpha, side: fr.design_lengths(alpha, side)[3], _ARC_NAME)
        why = ("the crank pivots at that distance lie on the forbidden arc between the lines "
               "D-C1 and D-C2 (the rocker's extreme positions would be in different assembly "
               "modes)" if on_arcs else "no point of the auxiliary arcs is at that distance")
        raise SynthesisError("ground", f"no admissible crank pivot is {fmt_len(d_req)} from D: "
                             f"{why}; admissible ground lengths: {ranges}")
    return found, f"the ground length {fmt_len(d_req)}", {"ground": d_req}


def _by_crank(fr, arcs, crank) -> tuple:
    """``(found, how, exact)``: the admissible pivots ``(side, alpha)`` of the crank length."""
    theta = fr.theta
    a_req = positive("crank", crank)
    found = []
    q = a_req / (2 * fr.R * math.sin(theta / 2))
    if q < 1:
        alpha = math.acos(q) - theta / 2
        found = [(side, alpha) for side in (1, -1) if _inside(alpha, arcs[side])]
    if not found:
        ranges = _ranges(fr, arcs, lambda alpha, side: fr.design_lengths(alpha, side)[0], _ARC_NAME)
        raise SynthesisError("crank", f"no admissible crank pivot gives a crank of "
                             f"{fmt_len(a_req)} (it is at most half the chord C1C2, "
                             f"{fmt_len(fr.s)}, and pivots on the forbidden arc between the "
                             "lines D-C1 and D-C2 are refused); admissible crank lengths: "
                             f"{ranges}")
    return found, f"the crank length {fmt_len(a_req)}", {"crank": a_req}


def _by_transmission(fr, arcs) -> list:
    """The pivot ``(side, alpha)`` of each arc with the largest minimum transmission angle."""
    found = []
    for side in (1, -1):
        if not arcs[side]:
            continue
        val, alpha, _ = best(lambda x, s=side: _gamma_min_vec(*fr.design_lengths(x, s)),
                             lambda x, s=side: float(_gamma_min_vec(*fr.design_lengths(x, s))),
                             arcs[side])
        found.append((side, alpha))
    return found


def _choose(fr, found, how) -> tuple:
    """``(side, alpha, notes)``: of the pivots found, the one with the largest minimum
    transmission angle, and the note saying so (``how``: the condition met, None: none)."""
    c = fr.c
    notes = []
    scored = []
    for side, alpha in found:
        a, b, _, d = (float(v) for v in fr.design_lengths(alpha, side))
        scored.append((builders.fourbar_gamma_min(a, b, c, d)[0], side, alpha))
    scored.sort(reverse=True)
    gmin, side, alpha = scored[0]
    if how is None:
        notes.append("no extra condition (ground or crank length) given: the crank pivot is the "
                     "one of the admissible arcs of the auxiliary circles with the largest minimum "
                     f"transmission angle ({fmt_deg(gmin)}, on the {_ARC_NAME[side]})")
    elif len(scored) > 1:
        other = scored[1]
        notes.append(f"two crank pivots meet {how} (one on each auxiliary arc): chosen the one with "
                     f"the larger minimum transmission angle, {fmt_deg(gmin)} on the "
                     f"{_ARC_NAME[side]} (the other: {fmt_deg(other[0])} on the {_ARC_NAME[other[1]]})")
    return side, alpha, notes


def _check_rocker(K, fr, alpha, side, exact, psi_deg) -> None:
    """:func:`~linkage_sym.synthesis.kratio_common.check_design` of the four-bar of pivot
    ``alpha`` on arc ``side`` (``exact``: the requested length, as given)."""
    theta, c, psi = fr.theta, fr.c, fr.psi
    a, b, _, d = (float(v) for v in fr.design_lengths(alpha, side))
    a, d = exact.get("crank", a), exact.get("ground", d)
    # at C1 the crank and coupler are in line: |AC1| = a + b; |BD| <= min(a + d, b + c)
    scale, value = ("ground", d) if "ground" in exact and d >= c else ("rocker", c)
    short = None  # K too close to 1: the linkage grows as 1/sin(theta) about a crank <= the chord
    if "crank" in exact:
        short = ("crank", "the crank asked for", "; ask for a longer crank")
    elif math.sin(psi / 2) < math.sin(theta):  # the chord, and the crank, shrink with the swing
        short = ("swing_deg", f"the swing {psi_deg:g}° is too small for this request: the crank",
                 "; ask for a larger swing")
    check_design(K, theta, {"crank": a, "coupler": b, "rocker": c, "ground": d}, d + c,
                 max(a + b, c, d, min(a + d, b + c)), scale, value, not exact, short)


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
