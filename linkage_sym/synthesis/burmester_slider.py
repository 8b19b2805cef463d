"""Slider dyads of Burmester theory: coupler points whose positions in the poses lie on a line.

A slider (PR) dyad guides a point ``M`` of the coupler along a fixed straight
line: its centre point lies at infinity (the circle of the moving pivot has
an infinite radius).  With the poses ``(P_j, theta_j)`` and ``M`` at ``m`` in
the coupler frame, ``M_j = P_j + e^{i theta_j} m``; the positions lie on a line
of direction ``phi`` when, for ``j = 2 .. n``::

    Im((delta_j + c_j m) e^{-i phi}) = 0,   delta_j = P_j - P_1,  c_j = e^{i theta_j} - e^{i theta_1}

linear in ``m`` for a given ``phi`` (Sandor and Erdman, *Advanced Mechanism
Design: Analysis and Synthesis*, Vol. 2, 1984, ch. 2, the slider as the dyad
with its centre point at infinity; for four infinitesimally separated poses
the point is Ball's point).

* **Four poses**: three equations in ``m`` (two unknowns) have a solution only
  where their 3x3 determinant vanishes -- a cubic form in ``(cos phi, sin phi)``
  with the factor ``cos^2 phi + sin^2 phi`` (on the isotropic directions its
  first two columns are proportional; the circle-point curve is a circular
  cubic, Bottema and Roth, *Theoretical Kinematics*, 1979): one direction
  (mod a half turn) with its point ``m``, one slider dyad.
* **Five poses**: the fourth equation must hold as well; a general set of
  five poses admits none, one from a slider-crank (or any linkage with a
  coupler point on a line) admits it.

Every dyad is checked against all its poses (:data:`~linkage_sym.synthesis.burmester.RESIDUAL`).
NumPy only.

Examples
--------
Five poses of a coupler whose point ``(0.5, 0)`` (frame coordinates) slides along ``y = 0``:

>>> import math
>>> th = [0.0, 10.0, 25.0, 40.0, 60.0]
>>> poses = [[1.0 - 0.5 * math.cos(math.radians(t)) + 0.3 * k, -0.5 * math.sin(math.radians(t)), t]
...          for k, t in enumerate(th)]
>>> [tuple(round(v, 9) for v in s.local) for s in slider_points(poses)]
[(0.5, 0.0)]
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.synthesis.burmester import RESIDUAL, read_poses

SAMPLES = 8
"""Directions at which the determinant is sampled to find its cubic form's coefficients."""


@dataclass(frozen=True)
class SliderDyad:
    """A slider of the coupler: its pin and the line the pin moves on.

    Attributes
    ----------
    circle : (float, float)
        The pin ``M_1`` at pose 1 (m): a circle point whose centre point is at infinity.
    local : (float, float)
        The pin in the coupler frame (m).
    angle : float
        The line's direction (rad, -pi/2 .. pi/2).
    travel : tuple of float
        The pin's position along the line in each pose, from ``M_1`` (m).
    residual : float
        Largest distance of a pose's pin from the line, in fractions of the poses' spread.
    """

    circle: tuple
    local: tuple
    angle: float
    travel: tuple
    residual: float


def _data(P: np.ndarray) -> tuple:
    """``(delta, c, scale)``: ``delta_j`` scaled by the poses' spread, ``c_j``, the spread."""
    Z = P[:, 0] + 1j * P[:, 1]
    scale = float(np.max(np.abs(Z - Z[0])))
    if scale == 0:
        scale = 1.0  # a rotation about one point: only the rotation scales nothing
    R = np.exp(1j * P[:, 2])
    return (Z[1:] - Z[0]) / scale, R[1:] - R[0], scale


def _rows(phi: float, delta, c) -> np.ndarray:
    """The equations ``[Im(c w), Re(c w), Im(delta w)]`` (``x Im + y Re = -Im(delta w)``)."""
    w = cmath.exp(-1j * phi)
    cw, dw = c * w, delta * w
    return np.column_stack([cw.imag, cw.real, dw.imag])


def _det(phi: float, delta, c) -> float:
    return float(np.linalg.det(_rows(phi, delta[:3], c[:3])))


def _directions(delta, c) -> list:
    """The directions (rad, -pi/2 .. pi/2) where poses 1 to 4's determinant vanishes."""
    t = np.pi * np.arange(SAMPLES) / SAMPLES
    f = np.array([_det(x, delta, c) for x in t])
    basis = np.column_stack([np.cos(t) ** (3 - k) * np.sin(t) ** k for k in range(4)])
    a, *_ = np.linalg.lstsq(basis, f, rcond=None)  # f = sum a_k cos^(3-k) sin^k
    big = float(np.max(np.abs(a)))
    if big == 0:
        return []
    out = []
    if abs(a[3]) <= 1e-12 * big:  # sin^3 absent: phi = pi/2 is a root
        out.append(math.pi / 2)
    lead = np.flatnonzero(np.abs(a[::-1]) > 1e-12 * big)[0]
    for r in np.roots(a[::-1][lead:]):  # in tan(phi)
        if abs(r.imag) <= 1e-7 * max(1.0, abs(r)):
            out.append(_newton(math.atan(r.real), delta, c))
    return out


def _newton(x: float, delta, c, steps: int = 30) -> float:
    h = 1e-7
    for _ in range(steps):
        d = (_det(x + h, delta, c) - _det(x - h, delta, c)) / (2 * h)
        if d == 0:
            break
        dx = _det(x, delta, c) / d
        x -= max(-0.1, min(0.1, dx))
        if abs(dx) < 1e-15:
            break
    return math.remainder(x, math.pi)


def _dyad(phi, P, delta, c, scale) -> SliderDyad | None:
    rows = _rows(phi, delta, c)
    M = rows[:, :2]
    sv = np.linalg.svd(M, compute_uv=False)
    if sv[-1] <= 1e-9 * max(sv[0], 1e-300):
        return None  # the point is not determined (e.g. a pure translation)
    m, *_ = np.linalg.lstsq(M, -rows[:, 2], rcond=None)
    res = float(np.max(np.abs(M @ m + rows[:, 2])))
    if not res <= RESIDUAL:
        return None
    local = complex(m[0], m[1]) * scale
    Z = P[:, 0] + 1j * P[:, 1]
    pins = Z + np.exp(1j * P[:, 2]) * local
    travel = ((pins - pins[0]) * cmath.exp(-1j * phi)).real
    return SliderDyad((float(pins[0].real), float(pins[0].imag)), (local.real, local.imag),
                      float(phi), tuple(float(v) for v in travel), res)


def slider_points(poses) -> list[SliderDyad]:
    """Every slider dyad through four or five poses: coupler points with collinear positions.

    Parameters
    ----------
    poses : sequence of 4 or 5 ``[x, y, angle_deg]``
        The coupler frame's origin (m) and angle (degrees) in each pose.

    Returns
    -------
    list of SliderDyad
        Distinct dyads, each meeting all its poses to
        :data:`~linkage_sym.synthesis.burmester.RESIDUAL`: one for four poses (none
        where the pin is not determined), none for five general poses.
    """
    P = read_poses(poses)
    delta, c, scale = _data(P)
    out: list[SliderDyad] = []
    for phi in _directions(delta, c):
        d = _dyad(phi, P, delta, c, scale)
        if d is not None and all(math.dist(d.local, o.local) > 1e-6 * scale for o in out):
            out.append(d)
    return out


__all__ = ["SliderDyad", "slider_points"]
