"""The check of a design by ``K``: the stroke-time ratio its scene holds (see
:mod:`linkage_sym.synthesis.kratio`).

:func:`scene_K` evaluates ``K`` from the joints' coordinates as written,
independently of the synthesis; :func:`checked` refuses a design whose scene
does not hold the requested ``K`` to :data:`K_RTOL`.  NumPy only (import
contract in ``pyproject.toml``).
"""

from __future__ import annotations

import math
from fractions import Fraction

from linkage_sym.synthesis.common import PI, Design, SynthesisError

__all__ = ["K_RTOL", "checked", "scene_K"]

K_RTOL = 1e-9
"""A design is written only if the stroke-time ratio of its scene's joint coordinates is
the requested ``K`` to this fraction of it (:func:`scene_K`)."""


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
    >>> from linkage_sym.synthesis.kratio import guide_bar
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


def checked(design: Design, K: float, field: str, change: str) -> Design:
    """``design`` if its scene holds ``K`` to :data:`K_RTOL` (:func:`scene_K`), else the refusal
    naming ``field``."""
    got = scene_K(design)
    if abs(got - K) <= K_RTOL * K:
        return design
    raise SynthesisError(field, f"the linkage's joint coordinates (float64) do not hold K = {K!r}: "
                                f"its limit positions give K = {got:.10g} (off by {abs(got - K) / K:.2g} "
                                f"of K, more than {K_RTOL:g}); {change}")
