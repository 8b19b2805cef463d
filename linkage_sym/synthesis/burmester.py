"""Burmester theory: the dyads that carry a coupler through four or five given poses.

A pose ``j`` is the coupler frame's origin ``P_j`` (a complex number) and its
angle ``theta_j``.  A dyad (a crank turning about a fixed *centre point*
``G``, its moving pivot the *circle point* ``M`` of the coupler) meets the
poses when, with ``W = M_1 - G`` and ``Z = P_1 - M_1`` at pose 1, the
*standard form* holds (Sandor and Erdman, *Advanced Mechanism Design:
Analysis and Synthesis*, Vol. 2, 1984, ch. 2)::

    W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = delta_j,   j = 2 .. n

with ``alpha_j = theta_j - theta_1``, ``delta_j = P_j - P_1`` and the
crank's rotations ``beta_j`` unknown.  Linear in ``(W, Z, -1)``, three such
equations have a solution only when the determinant of their rows vanishes:
the *compatibility equation*::

    Delta_2 e^{i beta_2} + Delta_3 e^{i beta_3} + Delta_4 e^{i beta_4} = Delta_2 + Delta_3 + Delta_4

(the ``Delta_k`` the cofactors of the first column).

* **Four poses** (:func:`burmester_curves`): one compatibility equation; for
  each ``beta_2`` it is a triangle with sides ``|Delta_3|``, ``|Delta_4|``
  and ``|sum - Delta_2 e^{i beta_2}|``, closed in two ways (0 or 2 real
  ``beta_3``).  ``W`` and ``Z`` follow; the centre points ``G(beta_2)`` trace
  the *centre-point curve*, the circle points ``M_1(beta_2)`` the
  *circle-point curve* (cubics).
* **Five poses** (:func:`burmester_points`): two compatibility equations (poses
  2, 3, 4 and 2, 3, 5) share ``beta_2`` and ``beta_3``.  Each gives, for a
  given ``beta_2``, one equation linear in ``(cos beta_3, sin beta_3)``; the
  two solved by Cramer's rule, ``cos^2 + sin^2 = 1`` leaves one equation in
  ``beta_2``: a trigonometric polynomial of degree 4, solved as a polynomial
  of degree 8 in ``e^{i beta_2}`` (its coefficients by the discrete Fourier
  transform of samples; its roots on the unit circle are the real
  solutions, each refined by Newton's method).  The roots of the trivial
  solutions (``beta_j = 0`` and ``beta_j = alpha_j``, where ``W`` and ``Z``
  are not determined) are dropped; 0, 2 or 4 *Burmester point pairs* remain.

Every dyad is checked against all its poses (:data:`RESIDUAL`).  Lengths are
computed with the poses moved to ``P_1 = 0`` and scaled by their spread.

NumPy only.

Examples
--------
>>> poses = [[0.0, 0.0, 0.0], [1.0, 0.2, 10.0], [1.8, 0.7, 25.0], [2.3, 1.5, 45.0], [2.5, 2.4, 70.0]]
>>> dyads = burmester_points(poses)
>>> len(dyads) in (0, 2, 4)
True
>>> all(d.residual < 1e-9 for d in dyads)
True
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.synthesis.common import SynthesisError, coordinate

RESIDUAL = 1e-9
"""A dyad is kept when every standard-form equation holds to this fraction of the
poses' spread (the largest ``|P_j - P_1|``)."""

TRIVIAL = 1e-7
"""A root whose rotations are all 0, or all equal to the coupler's, within this (rad)
is a trivial solution (``W`` and ``Z`` undetermined) and dropped."""

UNIT_CIRCLE = 1e-4
"""Roots of the degree-8 polynomial within this of the unit circle are taken as real
solutions (a double root -- two Burmester points merging -- splits off it by about the
square root of rounding); each is refined and checked against :data:`RESIDUAL`."""


@dataclass(frozen=True)
class Dyad:
    """A crank of the coupler: its fixed pivot and its moving pivot.

    Attributes
    ----------
    centre : (float, float)
        The fixed pivot ``G`` (m): a centre point.
    circle : (float, float)
        The moving pivot ``M_1`` at pose 1 (m): a circle point.
    local : (float, float)
        The moving pivot in the coupler frame (m).
    beta : tuple of float
        The crank's rotation from pose 1 at each pose (rad; 0 at pose 1).
    residual : float
        Largest error of the standard-form equations, in fractions of the poses' spread.
    """

    centre: tuple
    circle: tuple
    local: tuple
    beta: tuple
    residual: float


def read_poses(poses, counts=(4, 5)) -> np.ndarray:
    """The poses ``[[x, y, angle_deg], ...]`` as an (n, 3) array (angles in rad), checked.

    Examples
    --------
    >>> read_poses([[0, 0, 0], [1, 0, 0]])
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: poses: 4 or 5 poses [x, y, angle_deg] are expected, got 2
    """
    if not isinstance(poses, (list, tuple)) or len(poses) not in counts:
        n = len(poses) if isinstance(poses, (list, tuple)) else type(poses).__name__
        want = " or ".join(str(c) for c in counts)
        raise SynthesisError("poses", f"{want} poses [x, y, angle_deg] are expected, got {n}")
    rows = []
    for i, row in enumerate(poses):
        if not isinstance(row, (list, tuple)) or len(row) != 3:
            raise SynthesisError(f"poses[{i}]", f"three numbers [x, y, angle_deg] are expected, "
                                                f"got {row!r}")
        x, y, t = (coordinate(f"poses[{i}][{k}]", v) for k, v in enumerate(row))
        rows.append((x, y, math.radians(t)))
    out = np.array(rows)
    for i in range(1, len(out)):
        for j in range(i):
            if (np.hypot(*(out[i, :2] - out[j, :2])) == 0
                    and math.remainder(out[i, 2] - out[j, 2], 2 * math.pi) == 0):
                raise SynthesisError(f"poses[{i}]", f"is poses[{j}] again: a pose repeated fixes "
                                                    "nothing")
    return out


def _standard(poses: np.ndarray) -> tuple:
    """``(b, delta, scale, origin)``: ``b_j = e^{i alpha_j} - 1`` and ``delta_j`` (scaled by the
    poses' spread) for j = 2 .. n, the scale and ``P_1``."""
    P = poses[:, 0] + 1j * poses[:, 1]
    origin = P[0]
    scale = float(np.max(np.abs(P - origin)))
    if scale == 0:
        raise SynthesisError("poses", "the coupler frame's origin does not move: the poses "
                                      "differ by a rotation about one point only")
    alpha = poses[1:, 2] - poses[0, 2]
    return np.exp(1j * alpha) - 1, (P[1:] - origin) / scale, scale, origin


def _cofactors(b, delta, rows) -> tuple:
    """Cofactors ``(C_a, C_b, C_c)`` of the first column of the 3x3 rows ``rows`` of
    ``[a, b, delta]``."""
    i, j, k = rows
    return (b[j] * delta[k] - b[k] * delta[j], -(b[i] * delta[k] - b[k] * delta[i]),
            b[i] * delta[j] - b[j] * delta[i])


def _dyad(e, b, delta, scale, origin, theta1) -> Dyad | None:
    """The dyad of the crank rotations ``e_j = e^{i beta_j}`` (j = 2 .. n) by least squares,
    or None for a trivial or inconsistent one."""
    beta = np.angle(e)
    if np.all(np.abs(beta) < TRIVIAL) or np.all(np.abs(np.angle(e / (b + 1))) < TRIVIAL):
        return None
    M = np.stack([e - 1, b], axis=1)
    sv = np.linalg.svd(M, compute_uv=False)
    if sv[-1] < TRIVIAL * sv[0]:
        return None
    (W, Z), *_ = np.linalg.lstsq(M, delta, rcond=None)
    if len(e) == 4:  # five poses: as many equations as unknowns, refined by Newton's method
        W, Z, e = _polish(W, Z, beta, b, delta)
        beta = np.angle(e)
        M = np.stack([e - 1, b], axis=1)
    res = float(np.max(np.abs(M @ np.array([W, Z]) - delta)))
    if not res <= RESIDUAL:
        return None
    m1 = origin + scale * (-Z)  # M_1 = P_1 - Z
    g = m1 - scale * W
    local = (m1 - origin) * cmath.exp(-1j * theta1)
    return Dyad((float(g.real), float(g.imag)), (float(m1.real), float(m1.imag)),
                (float(local.real), float(local.imag)), (0.0, *(float(x) for x in beta)), res)


def _polish(W, Z, beta, b, delta, steps: int = 6) -> tuple:
    """Newton's method on the four standard-form equations of five poses in ``W``, ``Z`` and
    ``beta_2 .. beta_5`` (eight real equations, eight unknowns); ``(W, Z, e^{i beta})``."""
    beta = np.array(beta, dtype=float)
    n = len(beta)
    for _ in range(steps):
        e = np.exp(1j * beta)
        r = W * (e - 1) + Z * b - delta
        J = np.zeros((n, 4 + n), dtype=complex)
        J[:, 0], J[:, 1], J[:, 2], J[:, 3] = e - 1, 1j * (e - 1), b, 1j * b
        J[np.arange(n), 4 + np.arange(n)] = 1j * W * e
        Jr = np.vstack([J.real, J.imag])
        if np.linalg.cond(Jr) > 1e12:
            break
        dx = np.linalg.solve(Jr, -np.concatenate([r.real, r.imag]))
        W, Z = W + complex(dx[0], dx[1]), Z + complex(dx[2], dx[3])
        beta = beta + dx[4:]
        if np.max(np.abs(dx)) < 1e-16:
            break
    return W, Z, np.exp(1j * beta)


def _five_equations(b, delta) -> tuple:
    """The compatibility equations of poses 2, 3, 4 and 2, 3, 5: each ``(C2, C3, Ck, S)``."""
    eqs = []
    for k in (2, 3):
        c2, c3, ck = _cofactors(b, delta, (0, 1, k))
        eqs.append((c2, c3, ck, c2 + c3 + ck))
    return tuple(eqs)


def _cramer(beta2, eqs) -> tuple:
    """``(cnum, snum, det)``: Cramer's numerators and determinant of the two equations linear
    in ``(cos beta_3, sin beta_3)`` at ``beta_2`` (arrays)."""
    e2 = np.exp(1j * np.asarray(beta2, dtype=float))
    K, H = [], []
    for c2, c3, ck, s in eqs:
        R = s - c2 * e2
        k = np.conj(R) * c3
        K.append(k)
        H.append(0.5 * (np.abs(R) ** 2 + abs(c3) ** 2 - abs(ck) ** 2))
    # Re(K e^{i b3}) = Kr cos - Ki sin = H
    a11, a12, a21, a22 = K[0].real, -K[0].imag, K[1].real, -K[1].imag
    det = a11 * a22 - a12 * a21
    return H[0] * a22 - a12 * H[1], a11 * H[1] - H[0] * a21, det


def _scalar(beta2, eqs):
    cnum, snum, det = _cramer(beta2, eqs)
    return cnum ** 2 + snum ** 2 - det ** 2


def _roots(eqs) -> list:
    """Real roots ``beta_2`` of the compatibility in ``beta_2`` (rad)."""
    n = 16  # > 2 * 4 + 1 samples of a trigonometric polynomial of degree 4
    t = 2 * np.pi * np.arange(n) / n
    f = np.fft.fft(_scalar(t, eqs)) / n  # f[k]: coefficient of e^{i k t}
    coeffs = np.array([f[k % n] for k in range(4, -5, -1)])  # z^8 .. z^0 of z^4 F
    if not np.any(np.abs(coeffs) > 1e-14 * np.max(np.abs(f))):
        raise SynthesisError("poses", "the compatibility equation holds for every crank "
                                      "rotation: the poses are degenerate (e.g. a pure translation "
                                      "or rotation repeated)")
    lead = np.flatnonzero(np.abs(coeffs) > 1e-13 * np.max(np.abs(coeffs)))[0]
    z = np.roots(coeffs[lead:])
    out = []
    for r in z:
        if abs(abs(r) - 1) <= UNIT_CIRCLE:
            out.append(_newton(float(np.angle(r)), eqs))
    return out


def _newton(x: float, eqs, steps: int = 30) -> float:
    h = 1e-7
    for _ in range(steps):
        f = float(_scalar(x, eqs))
        d = float((_scalar(x + h, eqs) - _scalar(x - h, eqs)) / (2 * h))
        if d == 0:
            break
        dx = f / d
        x -= max(-0.1, min(0.1, dx))
        if abs(dx) < 1e-15:
            break
    return x


def _five_rotations(beta2: float, eqs) -> np.ndarray | None:
    """``e^{i beta_j}`` for j = 2 .. 5 at ``beta_2``, or None where Cramer's rule fails."""
    cnum, snum, det = _cramer(beta2, eqs)
    if abs(det) < 1e-12 * max(abs(cnum), abs(snum), 1e-300):
        return None
    e3 = complex(cnum / det, snum / det)
    e3 /= abs(e3)
    e2 = cmath.exp(1j * beta2)
    e = [e2, e3]
    for c2, c3, ck, s in eqs:
        ek = (s - c2 * e2 - c3 * e3) / ck
        if abs(ek) == 0:
            return None
        e.append(ek / abs(ek))
    return np.array(e)


def burmester_points(poses) -> list[Dyad]:
    """Every dyad through five poses: the Burmester point pairs (0, 2 or 4).

    Parameters
    ----------
    poses : sequence of 5 ``[x, y, angle_deg]``
        The coupler frame's origin (m) and angle (degrees) in each pose.

    Returns
    -------
    list of Dyad
        Distinct dyads, each meeting all five poses to :data:`RESIDUAL`.
    """
    P = read_poses(poses, counts=(5,))
    b, delta, scale, origin = _standard(P)
    eqs = _five_equations(b, delta)
    if any(abs(eq[2]) == 0 for eq in eqs):
        raise SynthesisError("poses", "three of the poses are related by a rotation and a "
                                      "translation that fix no compatibility equation")
    out: list[Dyad] = []
    for beta2 in _roots(eqs):
        e = _five_rotations(beta2, eqs)
        if e is None:
            continue
        d = _dyad(e, b, delta, scale, origin, P[0, 2])
        if d is None:
            continue
        if all(math.dist(d.centre, o.centre) > 1e-6 * scale for o in out):
            out.append(d)
    return out


@dataclass(frozen=True)
class Curves:
    """The centre-point and circle-point curves of four poses, sampled.

    Attributes
    ----------
    beta2 : ndarray, shape (N,)
        The crank's rotation to pose 2 of each sample (rad).
    centre, circle : ndarray, shape (2, N, 2)
        The centre point and the circle point (at pose 1) of each of the two
        solutions at each ``beta2`` (NaN where the triangle does not close or the
        solution is trivial).
    dyads : list of list of Dyad
        The dyads of the samples, per solution.
    """

    beta2: np.ndarray
    centre: np.ndarray
    circle: np.ndarray
    dyads: list


DEGENERATE = 1e-12
"""A cofactor of the four poses' compatibility equation no larger than this (its terms are
dimensionless, of order one) vanishes: the poses are degenerate."""


def _four(poses) -> tuple:
    P = read_poses(poses, counts=(4,))
    b, delta, scale, origin = _standard(P)
    c2, c3, c4 = _cofactors(b, delta, (0, 1, 2))
    # b and delta are dimensionless, at most 2 and 1: a cofactor at rounding's size vanishes
    # (a coupler that translates between the poses gives b = 0 up to rounding)
    if min(abs(c3), abs(c4)) <= DEGENERATE:
        raise SynthesisError("poses", "the compatibility equation of the four poses degenerates "
                                      "(a cofactor vanishes): the poses are degenerate")
    return P, b, delta, scale, origin, (c2, c3, c4, c2 + c3 + c4)


def _dyads_at(t: float, P, b, delta, scale, origin, eq) -> list:
    c2, c3, c4, s = eq
    e2 = cmath.exp(1j * t)
    R = s - c2 * e2
    K = R.conjugate() * c3
    H = 0.5 * (abs(R) ** 2 + abs(c3) ** 2 - abs(c4) ** 2)
    if abs(K) == 0 or abs(H) > abs(K):
        return [None, None]
    kappa, w = cmath.phase(K), math.acos(H / abs(K))
    out = []
    for sign in (1.0, -1.0):
        e3 = cmath.exp(1j * (-kappa + sign * w))
        e4 = (R - c3 * e3) / c4
        out.append(_dyad(np.array([e2, e3, e4 / abs(e4)]), b, delta, scale, origin, P[0, 2]))
    return out


def dyads_at(poses, beta2: float) -> list:
    """The two dyads through four poses whose crank turns by ``beta2`` (rad) to pose 2.

    Returns
    -------
    list of (Dyad or None)
        The two closures of the compatibility triangle; None where it does not
        close or the solution is trivial.
    """
    return _dyads_at(float(beta2), *_four(poses))


def burmester_curves(poses, samples: int = 720) -> Curves:
    """The centre-point and circle-point curves of four poses.

    Parameters
    ----------
    poses : sequence of 4 ``[x, y, angle_deg]``
        The coupler frame's origin (m) and angle (degrees) in each pose.
    samples : int
        Values of ``beta_2`` over a turn.

    Returns
    -------
    Curves
    """
    data = _four(poses)
    beta2 = 2 * np.pi * np.arange(samples) / samples
    centre = np.full((2, samples, 2), np.nan)
    circle = np.full((2, samples, 2), np.nan)
    dyads: list = [[], []]
    for i, t in enumerate(beta2):
        for branch, d in enumerate(_dyads_at(t, *data)):
            if d is not None:
                centre[branch, i] = d.centre
                circle[branch, i] = d.circle
                dyads[branch].append(d)
    return Curves(beta2, centre, circle, dyads)


__all__ = ["Curves", "Dyad", "RESIDUAL", "burmester_curves", "burmester_points", "dyads_at", "read_poses"]
