"""Guide dyads (RP) of Burmester theory: a fixed pivot that a line of the coupler passes through.

An RP dyad pins a block to the ground at ``G`` and lets a line of the coupler
slide through it: in every pose the coupler's line passes through ``G`` (the
inverted slider-crank, the coupler the guide; its circle point lies at
infinity, its centre point ``G`` on the centre-point curve).  It is the
kinematic inversion of the slider (PR) dyad of
:mod:`~linkage_sym.synthesis.burmester_slider`: seen from the coupler, the
ground moves and its point ``G`` moves on a line of the coupler.  So the poses
are inverted -- the ground frame expressed in the coupler frame of pose
``j``, with pose 1's origin moved to 0::

    Q_j = -e^{-i theta_j} (P_j - P_1),   angle -theta_j

-- and the slider dyads of the inverted poses are the guide dyads: the
slider's point (in the moving frame, here the ground's) is ``G - P_1``, its
line (in the fixed frame, here the coupler's) the guide.  The counts are
the slider's (Sandor and Erdman, *Advanced Mechanism Design: Analysis and
Synthesis*, Vol. 2, 1984, ch. 2, dyads with a pivot at infinity):

* **Four poses**: one guide dyad (the slider's cubic form has one real
  direction) -- the circle-point curve's real point at infinity, its centre
  point on the centre-point curve, the one-parameter family of fixed pivots;
* **Five poses**: none for general poses; poses of a linkage with a coupler
  line through a fixed pivot (an inverted slider-crank) give that guide back.

Every dyad is checked against all its poses
(:data:`~linkage_sym.synthesis.burmester.RESIDUAL`).  NumPy only.

Examples
--------
Five poses of a coupler whose line ``y = 0.2`` (frame coordinates) passes through ``(1, 1)``:

>>> import math
>>> th = [0.0, 10.0, 25.0, 40.0, 60.0]
>>> def pose(k, t):
...     c, s = math.cos(math.radians(t)), math.sin(math.radians(t))
...     u = 0.3 * k - 0.5  # the pivot's abscissa on the line, frame coordinates
...     return [1.0 - (c * u - s * 0.2), 1.0 - (s * u + c * 0.2), t]
>>> [(tuple(round(v, 9) for v in g.pivot), round(math.degrees(g.angle), 9))
...  for g in guide_points([pose(k, t) for k, t in enumerate(th)])]
[((1.0, 1.0), 0.0)]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.synthesis.burmester import read_poses
from linkage_sym.synthesis.burmester_slider import slider_points
from linkage_sym.synthesis.common import SynthesisError

DEGENERATE = 1e-9
"""Poses whose coupler turns by no more than this (rad) between pose 1 and every other,
or whose poles with pose 1 all lie within this fraction of the poses' spread of one
point, fix no guide dyad."""


@dataclass(frozen=True)
class GuideDyad:
    """A guide of the coupler: a fixed pivot and the line of the coupler through it.

    Attributes
    ----------
    pivot : (float, float)
        The fixed pivot ``G`` (m): a centre point whose circle point is at infinity.
    local : (float, float)
        ``G`` in the coupler frame of pose 1 (m): a point of the coupler's line.
    angle : float
        The line's direction in the coupler frame (rad, -pi/2 .. pi/2).
    axis : float
        The line's direction at pose 1 (rad, from ``+x``): pose 1's angle plus ``angle``.
    travel : tuple of float
        ``G``'s position along the coupler's line in each pose, from pose 1's (m).
    residual : float
        Largest distance of ``G`` from the line in a pose, in fractions of the poses' spread.
    """

    pivot: tuple
    local: tuple
    angle: float
    axis: float
    travel: tuple
    residual: float


def _refuse_degenerate(P: np.ndarray) -> None:
    """Refuse poses that fix no guide: a coupler that does not turn, or turns about one point."""
    R = np.exp(1j * P[:, 2])
    Z = P[:, 0] + 1j * P[:, 1]
    if float(np.max(np.abs(R[1:] / R[0] - 1))) <= DEGENERATE:
        raise SynthesisError("poses", "the coupler does not turn between the poses: a line of it "
                                      "keeps its direction, and one through a fixed pivot in "
                                      "every pose would have to carry the whole motion")
    spread = float(np.max(np.abs(Z - Z[0])))
    if float(np.min(np.abs(R[1:] - R[0]))) <= DEGENERATE:
        return  # a pose translated from pose 1: its pole is at infinity, the poses turn about none
    poles = Z[0] + R[0] * (Z[1:] - Z[0]) / (R[0] - R[1:])
    if spread == 0 or float(np.max(np.abs(poles - poles[0]))) <= DEGENERATE * spread:
        x, y = (float(v) for v in (poles[0].real, poles[0].imag))
        raise SynthesisError("poses", f"the poses differ by rotations about one point ({x:.6g}, "
                                      f"{y:.6g}) only: every line of the coupler through it "
                                      "passes it in every pose, so the guide is not determined")


def guide_points(poses) -> list[GuideDyad]:
    """Every guide (RP) dyad through four or five poses: fixed pivots on a line of the coupler.

    Parameters
    ----------
    poses : sequence of 4 or 5 ``[x, y, angle_deg]``
        The coupler frame's origin (m) and angle (degrees) in each pose.

    Returns
    -------
    list of GuideDyad
        Distinct dyads, each meeting all its poses to
        :data:`~linkage_sym.synthesis.burmester.RESIDUAL`: one for four poses (none
        where the pivot is not determined), none for five general poses.

    Raises
    ------
    SynthesisError
        Malformed poses; a coupler that does not turn, or only turns about one point
        (field ``poses``).
    """
    P = read_poses(poses)
    _refuse_degenerate(P)
    origin = complex(P[0, 0], P[0, 1])
    Z = P[:, 0] + 1j * P[:, 1] - origin
    Q = -Z * np.exp(-1j * P[:, 2])
    # the angles negated as given (degrees), not converted back from radians
    inverted = [[float(q.real), float(q.imag), -float(row[2])] for q, row in zip(Q, poses)]
    out = []
    for s in slider_points(inverted):
        g = origin + complex(*s.local)
        axis = math.remainder(float(P[0, 2]) + s.angle, 2 * math.pi)
        out.append(GuideDyad((g.real, g.imag), tuple(s.circle), s.angle, axis, s.travel,
                             s.residual))
    return out


__all__ = ["DEGENERATE", "GuideDyad", "guide_points"]
