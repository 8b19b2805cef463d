"""Independent closed-form kinematics references (the kinematics chapter [4]).

Nothing here imports ``linkage_sym``: these are the yardsticks the solver is
measured against, written from the closed vector loops of chapter 3 [4] and
re-derived by hand (the OCR of the printed formulas has typos).

Conventions (all angles in radians, counter-clockwise from +x):

* Four-bar ([4] fig. 3-11, eqs. 3-8..3-18): crank pivot A at the origin,
  rocker pivot D at ``(l4, 0)``; ``l1 = AB`` (crank, angle ``th1``),
  ``l2 = BC`` (coupler, angle ``th2`` of B->C), ``l3 = DC`` (rocker, angle
  ``th3`` of D->C).  Closure ``l1 e^{i th1} + l2 e^{i th2} = l4 + l3 e^{i th3}``.
* ``sigma`` selects the assembly mode.  For the RRR dyad it is the sign of the
  dyad's constraint-Jacobian determinant ``l2 l3 sin(th2 - th3)``, which is also
  the side of line D->B on which C lies (``cross(B - D, C - D)``).
* The driver may accelerate (``a1``); the printed formulas assume ``a1 = 0``.
  Every acceleration formula below keeps the ``a1`` terms.

Every function is vectorised over ``th1`` (NumPy) except the ``*_mp``
versions, which evaluate one state with mpmath at ``mp.dps`` digits (the
callers set 50).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np

# --------------------------------------------------------------------------
# four-bar: eqs. 3-9 / 3-10 of [4] (position), 3-13 / 3-14 (velocity),
# 3-16 / 3-17 (acceleration), 3-18 (coupler point)
# --------------------------------------------------------------------------


def fourbar_position(l1, l2, l3, l4, th1, sigma=1):
    """theta2, theta3 of the four-bar from eqs. 3-9/3-10, numerically stable.

    Eq. 3-10 is ``A sin th3 + B cos th3 + C = 0`` with
    ``A = 2 l1 l3 sin th1``, ``B = 2 l3 (l1 cos th1 - l4)``,
    ``C = l2^2 - l1^2 - l3^2 - l4^2 + 2 l1 l4 cos th1``.
    With ``d = |BD|``: ``A^2 + B^2 = (2 l3 d)^2`` and ``C = l2^2 - l3^2 - d^2``,
    so ``A^2 + B^2 - C^2 = (l3+d-l2)(l3+d+l2)(l2-l3+d)(l2+l3-d)``: a product of
    sums of three lengths, free of the cancellation that the half-angle form
    (3-11, division by ``B - C``) and the unfactored discriminant suffer.
    Then ``th3 = atan2(A, B) + sigma * atan2(sqrt(disc), -C)`` and ``th2``
    follows from eq. 3-9.  Returns NaN where the loop cannot close.
    """
    th1 = np.asarray(th1, dtype=float)
    bx, by = l1 * np.cos(th1), l1 * np.sin(th1)
    A = 2.0 * l3 * by
    B = 2.0 * l3 * (bx - l4)
    d = np.hypot(bx - l4, by)
    C = (l2 - l3) * (l2 + l3) - d * d
    disc = (l3 + d - l2) * (l3 + d + l2) * (l2 - l3 + d) * (l2 + l3 - d)
    with np.errstate(invalid="ignore"):
        root = np.sqrt(disc)
    th3 = np.arctan2(A, B) + sigma * np.arctan2(root, -C)
    # eq. 3-9: l2 e^{i th2} = l4 + l3 e^{i th3} - l1 e^{i th1}
    th2 = np.arctan2(l3 * np.sin(th3) - by, l4 + l3 * np.cos(th3) - bx)
    return th2, th3


def fourbar_velocity(l1, l2, l3, th1, th2, th3, w1):
    """omega2, omega3 from eqs. 3-14 and 3-13 (derived: eq. 3-12 times
    e^{-i th2}, resp. e^{-i th3}, imaginary part)."""
    w3 = w1 * l1 * np.sin(th1 - th2) / (l3 * np.sin(th3 - th2))  # eq. 3-13
    w2 = -w1 * l1 * np.sin(th1 - th3) / (l2 * np.sin(th2 - th3))  # eq. 3-14
    return w2, w3


def fourbar_acceleration(l1, l2, l3, th1, th2, th3, w1, w2, w3, a1=0.0):
    """alpha2, alpha3 from eqs. 3-16 / 3-17 with the driver's alpha1 kept.

    Derivation (eq. 3-15 with ``a1``):
    ``(i a1 - w1^2) l1 e^{i th1} + (i a2 - w2^2) l2 e^{i th2}
      = (i a3 - w3^2) l3 e^{i th3}``.
    Times ``e^{-i th2}``, real part, gives alpha3 (eq. 3-16 when a1 = 0);
    times ``e^{-i th3}``, real part, gives alpha2.  The printed 3-17 has
    ``sin(th2 - th2)`` in the denominator: it is ``sin(th2 - th3)``.
    """
    a3 = (
        l1 * a1 * np.sin(th1 - th2)
        + w1**2 * l1 * np.cos(th1 - th2)
        + w2**2 * l2
        - w3**2 * l3 * np.cos(th3 - th2)
    ) / (l3 * np.sin(th3 - th2))
    a2 = (
        -l1 * a1 * np.sin(th1 - th3)
        - w1**2 * l1 * np.cos(th1 - th3)
        - w2**2 * l2 * np.cos(th2 - th3)
        + w3**2 * l3
    ) / (l2 * np.sin(th2 - th3))
    return a2, a3


def fourbar(l1, l2, l3, l4, th1, w1, a1=0.0, sigma=1):
    """Full four-bar state: dict of th2, th3, w2, w3, a2, a3 and the points
    B, C (arrays (N, 2)) with their velocities/accelerations."""
    th1 = np.asarray(th1, dtype=float)
    th2, th3 = fourbar_position(l1, l2, l3, l4, th1, sigma)
    w2, w3 = fourbar_velocity(l1, l2, l3, th1, th2, th3, w1)
    a2, a3 = fourbar_acceleration(l1, l2, l3, th1, th2, th3, w1, w2, w3, a1)
    e1 = np.stack([np.cos(th1), np.sin(th1)], -1)
    n1 = np.stack([-np.sin(th1), np.cos(th1)], -1)
    e3 = np.stack([np.cos(th3), np.sin(th3)], -1)
    n3 = np.stack([-np.sin(th3), np.cos(th3)], -1)
    B = l1 * e1
    vB = l1 * w1 * n1
    aB = l1 * (a1 * n1 - w1**2 * e1)
    C = np.array([l4, 0.0]) + l3 * e3
    vC = l3 * w3[..., None] * n3
    aC = l3 * (a3[..., None] * n3 - (w3**2)[..., None] * e3)
    return dict(th2=th2, th3=th3, w2=w2, w3=w3, a2=a2, a3=a3,
                B=B, vB=vB, aB=aB, C=C, vC=vC, aC=aC)


def coupler_point(l1, th1, w1, a1, th2, w2, a2, a, b):
    """Point E of the coupler at ``a`` along BC and ``b`` normal to it (eq. 3-18):
    ``l_E = l1 e^{i th1} + a e^{i th2} + b e^{i(th2 + 90deg)}``, differentiated
    once and twice (eq. 3-19 and its acceleration, re-derived with a1)."""
    th1 = np.asarray(th1, dtype=float)
    z1 = np.exp(1j * th1)
    z2 = (a + 1j * b) * np.exp(1j * th2)
    E = l1 * z1 + z2
    vE = 1j * w1 * l1 * z1 + 1j * w2 * z2
    aE = (1j * a1 - w1**2) * l1 * z1 + (1j * a2 - w2**2) * z2
    as2 = lambda z: np.stack([z.real, z.imag], -1)  # noqa: E731
    return as2(E), as2(vE), as2(aE)


def fourbar_mp(l1, l2, l3, l4, th1, w1, a1=0, sigma=1):
    """One four-bar state with mpmath (same equations as :func:`fourbar`).

    Arguments are converted with ``mp.mpf`` (exactly, from floats); returns a
    dict of mpf: th2, th3, w2, w3, a2, a3, Cx, Cy, vCx, vCy, aCx, aCy, and
    ``det`` = ``sin(th2 - th3)`` (the dyad's dimensionless determinant; the
    rates are NaN where it is exactly 0).  Returns ``None`` if the loop cannot
    close.
    """
    l1, l2, l3, l4, th1, w1, a1 = (mp.mpf(v) for v in (l1, l2, l3, l4, th1, w1, a1))
    bx, by = l1 * mp.cos(th1), l1 * mp.sin(th1)
    A = 2 * l3 * by
    B = 2 * l3 * (bx - l4)
    d = mp.hypot(bx - l4, by)
    C = (l2 - l3) * (l2 + l3) - d * d
    disc = (l3 + d - l2) * (l3 + d + l2) * (l2 - l3 + d) * (l2 + l3 - d)
    if disc < 0:
        return None
    th3 = mp.atan2(A, B) + sigma * mp.atan2(mp.sqrt(disc), -C)
    th2 = mp.atan2(l3 * mp.sin(th3) - by, l4 + l3 * mp.cos(th3) - bx)
    s32 = mp.sin(th3 - th2)
    c3, s3 = mp.cos(th3), mp.sin(th3)
    if s32 == 0:  # exactly singular: positions only
        return dict(th2=th2, th3=th3, Cx=l4 + l3 * c3, Cy=l3 * s3, det=mp.mpf(0),
                    **{k: mp.nan for k in ("w2", "w3", "a2", "a3", "vCx", "vCy", "aCx", "aCy")})
    w3 = w1 * l1 * mp.sin(th1 - th2) / (l3 * s32)
    w2 = -w1 * l1 * mp.sin(th1 - th3) / (l2 * mp.sin(th2 - th3))
    a3 = (l1 * a1 * mp.sin(th1 - th2) + w1**2 * l1 * mp.cos(th1 - th2) + w2**2 * l2
          - w3**2 * l3 * mp.cos(th3 - th2)) / (l3 * s32)
    a2 = (-l1 * a1 * mp.sin(th1 - th3) - w1**2 * l1 * mp.cos(th1 - th3)
          - w2**2 * l2 * mp.cos(th2 - th3) + w3**2 * l3) / (l2 * mp.sin(th2 - th3))
    return dict(
        th2=th2, th3=th3, w2=w2, w3=w3, a2=a2, a3=a3,
        Cx=l4 + l3 * c3, Cy=l3 * s3,
        vCx=-l3 * w3 * s3, vCy=l3 * w3 * c3,
        aCx=-l3 * (a3 * s3 + w3**2 * c3), aCy=l3 * (a3 * c3 - w3**2 * s3),
        det=mp.sin(th2 - th3),
    )


def fourbar_limits_mp(l1, l2, l3, l4):
    """Crank angles (mpf, in [0, pi]) where |BD| = l2 + l3 or |l2 - l3|: the
    input's dead-centre (limit) positions; empty entries where not reached."""
    l1, l2, l3, l4 = (mp.mpf(v) for v in (l1, l2, l3, l4))
    out = []
    for dd in (l2 + l3, abs(l2 - l3)):
        c = (l1**2 + l4**2 - dd**2) / (2 * l1 * l4)
        if -1 <= c <= 1:
            out.append(mp.acos(c))
    return out


# --------------------------------------------------------------------------
# generic RRR dyad (for the six-bars): circle intersection, stable form
# --------------------------------------------------------------------------


def dyad_rrr(P, Q, vP, vQ, aP, aQ, r1, r2, sigma=1):
    """Point X with |X - P| = r1, |X - Q| = r2 on the side ``sigma`` of P->Q
    (``sigma = sign cross(Q - P, X - P)``), with its velocity and acceleration.

    Velocity: ``(X - P).(vX - vP) = 0`` and ``(X - Q).(vX - vQ) = 0`` (2x2);
    acceleration: ``(X - P).(aX - aP) + |vX - vP|^2 = 0``, likewise for Q.
    Arrays (N, 2).  NaN where the dyad cannot close.
    """
    P, Q, vP, vQ, aP, aQ = (np.asarray(v, dtype=float) for v in (P, Q, vP, vQ, aP, aQ))
    dv = Q - P
    d = np.hypot(dv[..., 0], dv[..., 1])
    u = dv / d[..., None]
    nrm = np.stack([-u[..., 1], u[..., 0]], -1)
    along = ((r1 - r2) * (r1 + r2) + d * d) / (2 * d)
    h2 = (r1 + r2 - d) * (r1 + r2 + d) * (d - r1 + r2) * (d + r1 - r2)
    with np.errstate(invalid="ignore"):
        h = np.sqrt(h2) / (2 * d)
    X = P + along[..., None] * u + sigma * h[..., None] * nrm
    rp, rq = X - P, X - Q
    M = np.stack([rp, rq], -2)  # rows: rp, rq
    rhs_v = np.stack([np.sum(rp * vP, -1), np.sum(rq * vQ, -1)], -1)
    vX = np.linalg.solve(M, rhs_v[..., None])[..., 0]
    wp, wq = vX - vP, vX - vQ
    rhs_a = np.stack([np.sum(rp * aP, -1) - np.sum(wp * wp, -1),
                      np.sum(rq * aQ, -1) - np.sum(wq * wq, -1)], -1)
    aX = np.linalg.solve(M, rhs_a[..., None])[..., 0]
    return X, vX, aX


def link_angle_rates(P, X, vP, vX, aP, aX):
    """Angle, omega, alpha of the link carrying points P and X (vector P->X)."""
    r = X - P
    rv = vX - vP
    ra = aX - aP
    L2 = np.sum(r * r, -1)
    th = np.arctan2(r[..., 1], r[..., 0])
    w = (r[..., 0] * rv[..., 1] - r[..., 1] * rv[..., 0]) / L2
    # d/dt of cross(r, rv) = cross(r, ra); |r| constant on a rigid link
    al = (r[..., 0] * ra[..., 1] - r[..., 1] * ra[..., 0]) / L2
    return th, w, al


# --------------------------------------------------------------------------
# offset slider-crank
# --------------------------------------------------------------------------


def slider_crank(l1, l2, e, th1, w1, a1=0.0, sigma=1):
    """Offset slider-crank: crank pivot at the origin, slider pin C on the line
    ``y = e`` sliding along +x; ``sigma = sign cos(th2)`` (+1: slider to the
    right of the crank pin).

    Closure ``l1 e^{i th1} + l2 e^{i th2} = x + i e``:
    ``sin th2 = (e - l1 sin th1) / l2``,
    ``cos th2 = sigma sqrt((l2 - m)(l2 + m)) / l2`` with ``m = e - l1 sin th1``;
    derivative of the y-row: ``l1 w1 cos th1 + l2 w2 cos th2 = 0``;
    of the x-row: ``v = -l1 w1 sin th1 - l2 w2 sin th2``; once more for the
    accelerations (with a1).
    """
    th1 = np.asarray(th1, dtype=float)
    m = e - l1 * np.sin(th1)
    with np.errstate(invalid="ignore"):
        c2 = sigma * np.sqrt((l2 - m) * (l2 + m)) / l2
    th2 = np.arctan2(m / l2, c2)
    s2, c2 = np.sin(th2), np.cos(th2)
    s1, c1 = np.sin(th1), np.cos(th1)
    x = l1 * c1 + l2 * c2
    w2 = -l1 * w1 * c1 / (l2 * c2)
    v = -l1 * w1 * s1 - l2 * w2 * s2
    a2 = (-l1 * a1 * c1 + l1 * w1**2 * s1 + l2 * w2**2 * s2) / (l2 * c2)
    a = -l1 * a1 * s1 - l1 * w1**2 * c1 - l2 * a2 * s2 - l2 * w2**2 * c2
    return dict(th2=th2, w2=w2, a2=a2, x=x, v=v, a=a)


def slider_crank_mp(l1, l2, e, th1, w1, a1=0, sigma=1):
    """One slider-crank state with mpmath (same equations); mpf dict with
    ``det = cos(th2)`` (dimensionless determinant of the rod-slider dyad)."""
    l1, l2, e, th1, w1, a1 = (mp.mpf(v) for v in (l1, l2, e, th1, w1, a1))
    m = e - l1 * mp.sin(th1)
    if (l2 - m) * (l2 + m) < 0:
        return None
    c2 = sigma * mp.sqrt((l2 - m) * (l2 + m)) / l2
    th2 = mp.atan2(m / l2, c2)
    s2, c2 = mp.sin(th2), mp.cos(th2)
    s1, c1 = mp.sin(th1), mp.cos(th1)
    x = l1 * c1 + l2 * c2
    w2 = -l1 * w1 * c1 / (l2 * c2)
    v = -l1 * w1 * s1 - l2 * w2 * s2
    a2 = (-l1 * a1 * c1 + l1 * w1**2 * s1 + l2 * w2**2 * s2) / (l2 * c2)
    a = -l1 * a1 * s1 - l1 * w1**2 * c1 - l2 * a2 * s2 - l2 * w2**2 * c2
    return dict(th2=th2, w2=w2, a2=a2, x=x, v=v, a=a, det=c2)


# --------------------------------------------------------------------------
# guide-bar (inverted slider-crank) of examples 3-1 / 3-6 of [4]
# --------------------------------------------------------------------------


def guide_bar(l1, l3, l4, gamma, th1, w1, a1=0.0, sigma=1):
    """Guide-bar of example 3-6: crank AB (A at the origin, angle th1), a block
    pinned at B slides on link 3; link 3 turns about D = (l4, 0) and carries
    the arm DC (length l3, angle th3) and the slide line through C at the
    angle ``th2 = th3 + gamma``; ``s2`` = signed distance C->B along it.

    Closure ``l1 e^{i th1} = l4 + l3 e^{i th3} + s2 e^{i th2}`` (example 3-6's
    loop ABCD).  Position: ``|B - D|^2 = l3^2 + 2 l3 s2 cos(gamma) + s2^2`` gives
    ``s2 = -l3 cos(gamma) + sigma sqrt(d^2 - (l3 sin gamma)^2)`` (factored), then
    ``th3 = arg(B - D) - arg(l3 + s2 e^{i gamma})``.  ``sigma`` is the sign of
    ``s2 + l3 cos(gamma)`` = the sign of the Jacobian determinant.
    Velocity (times e^{-i th2}; imaginary / real part):
    ``w3 = l1 w1 cos(th1 - th2) / (s2 + l3 cos gamma)`` (as example 3-6),
    ``ds2 = -l1 w1 sin(th1 - th2) - l3 w3 sin(gamma)``.
    Acceleration (derived here, with a1):
    ``a3 = [l1 a1 cos(th1-th2) - l1 w1^2 sin(th1-th2) - l3 w3^2 sin(gamma)
            - 2 ds2 w3] / (s2 + l3 cos gamma)``,
    ``dds2 = -l1 a1 sin(th1-th2) - l1 w1^2 cos(th1-th2) - l3 a3 sin(gamma)
             + l3 w3^2 cos(gamma) + s2 w3^2``.
    """
    th1 = np.asarray(th1, dtype=float)
    bx, by = l1 * np.cos(th1), l1 * np.sin(th1)
    d = np.hypot(bx - l4, by)
    p = l3 * abs(np.sin(gamma))
    with np.errstate(invalid="ignore"):
        s2 = -l3 * np.cos(gamma) + sigma * np.sqrt((d - p) * (d + p))
    th3 = np.arctan2(by, bx - l4) - np.arctan2(s2 * np.sin(gamma), l3 + s2 * np.cos(gamma))
    th2 = th3 + gamma
    den = s2 + l3 * np.cos(gamma)
    w3 = l1 * w1 * np.cos(th1 - th2) / den
    ds2 = -l1 * w1 * np.sin(th1 - th2) - l3 * w3 * np.sin(gamma)
    a3 = (l1 * a1 * np.cos(th1 - th2) - l1 * w1**2 * np.sin(th1 - th2)
          - l3 * w3**2 * np.sin(gamma) - 2 * ds2 * w3) / den
    dds2 = (-l1 * a1 * np.sin(th1 - th2) - l1 * w1**2 * np.cos(th1 - th2)
            - l3 * a3 * np.sin(gamma) + l3 * w3**2 * np.cos(gamma) + s2 * w3**2)
    C = np.stack([l4 + l3 * np.cos(th3), l3 * np.sin(th3)], -1)
    return dict(th3=th3, th2=th2, s2=s2, w3=w3, ds2=ds2, a3=a3, dds2=dds2, C=C)


# --------------------------------------------------------------------------
# shaper of example 3-7 of [4] (matrix method)
# --------------------------------------------------------------------------


def shaper_position(l1, l3, l4, l6, l6p, th1, sigma4=-1):
    """Shaper (example 3-7): guide pivot C at the origin, crank pivot A at
    ``(0, l6)``, crank l1 (angle th1), block at B slides on the guide CD
    (``s3 = |CB|``, angle th3), link DE (l4, angle th4), ram E on the line
    ``y = l6p`` at ``x = sE``.  Loop equations (example 3-7):
    ``s3 cos th3 = l1 cos th1``, ``s3 sin th3 = l6 + l1 sin th1``,
    ``l3 cos th3 + l4 cos th4 - sE = 0``, ``l3 sin th3 + l4 sin th4 = l6p``.
    ``sigma4`` = sign of ``cos th4`` (Table 3-1: th4 near 170 deg, so -1).
    """
    th1 = np.asarray(th1, dtype=float)
    bx, by = l1 * np.cos(th1), l6 + l1 * np.sin(th1)
    s3 = np.hypot(bx, by)
    th3 = np.arctan2(by, bx)
    m = l6p - l3 * np.sin(th3)
    with np.errstate(invalid="ignore"):
        c4 = sigma4 * np.sqrt((l4 - m) * (l4 + m))
    th4 = np.arctan2(m, c4)
    sE = l3 * np.cos(th3) + l4 * np.cos(th4)
    return s3, th3, th4, sE


def shaper_matrices(l1, l3, l4, s3, th3, th4):
    """The example 3-7 matrix ``A(x)`` of the unknowns x = (s3, th3, th4, sE):
    ``A xdot = w1 B`` with ``B = (-l1 sin th1, l1 cos th1, 0, 0)``."""
    c3, s3_, c4, s4 = np.cos(th3), np.sin(th3), np.cos(th4), np.sin(th4)
    return np.array([
        [c3, -s3 * s3_, 0.0, 0.0],
        [s3_, s3 * c3, 0.0, 0.0],
        [0.0, -l3 * s3_, -l4 * s4, -1.0],
        [0.0, l3 * c3, l4 * c4, 0.0],
    ])


def shaper(l1, l3, l4, l6, l6p, th1, w1, a1=0.0, sigma4=-1):
    """Shaper state by the matrix method of example 3-7, one 4x4 solve per
    step for velocities and one for accelerations:
    ``A xd = w1 B`` and ``A xdd = -Adot xd + w1 Bdot + a1 B`` (eq. 3-29 with the
    driver's acceleration added; ``Bdot = w1 (-l1 cos th1, -l1 sin th1, 0, 0)``).
    ``Adot`` is the time derivative of :func:`shaper_matrices` (as printed in
    example 3-7).  Returns dict of arrays s3, th3, th4, sE, ds3, w3, w4, vE,
    dds3, a3, a4, aE.
    """
    th1 = np.atleast_1d(np.asarray(th1, dtype=float))
    s3, th3, th4, sE = shaper_position(l1, l3, l4, l6, l6p, th1, sigma4)
    n = len(th1)
    w1s = np.broadcast_to(np.asarray(w1, dtype=float), (n,))
    a1s = np.broadcast_to(np.asarray(a1, dtype=float), (n,))
    xd = np.empty((n, 4))
    xdd = np.empty((n, 4))
    for k in range(n):
        w1, a1 = w1s[k], a1s[k]
        A = shaper_matrices(l1, l3, l4, s3[k], th3[k], th4[k])
        B = np.array([-l1 * np.sin(th1[k]), l1 * np.cos(th1[k]), 0.0, 0.0])
        xd[k] = np.linalg.solve(A, w1 * B)
        ds3, w3, w4, _ = xd[k]
        c3, sn3, c4, sn4 = np.cos(th3[k]), np.sin(th3[k]), np.cos(th4[k]), np.sin(th4[k])
        Adot = np.array([
            [-w3 * sn3, -ds3 * sn3 - s3[k] * w3 * c3, 0.0, 0.0],
            [w3 * c3, ds3 * c3 - s3[k] * w3 * sn3, 0.0, 0.0],
            [0.0, -l3 * w3 * c3, -l4 * w4 * c4, 0.0],
            [0.0, -l3 * w3 * sn3, -l4 * w4 * sn4, 0.0],
        ])
        Bdot = w1 * np.array([-l1 * np.cos(th1[k]), -l1 * np.sin(th1[k]), 0.0, 0.0])
        xdd[k] = np.linalg.solve(A, -Adot @ xd[k] + w1 * Bdot + a1 * B)
    return dict(s3=s3, th3=th3, th4=th4, sE=sE,
                ds3=xd[:, 0], w3=xd[:, 1], w4=xd[:, 2], vE=xd[:, 3],
                dds3=xdd[:, 0], a3=xdd[:, 1], a4=xdd[:, 2], aE=xdd[:, 3])


# Table 3-1 of [4] (example 3-7, l1 = 0.125 m, l3 = 0.600 m, l4 = 0.150 m,
# w1 = 1 rad/s): th1 [deg] -> th3 [deg], th4 [deg], sE [m], w3, w4 [rad/s],
# vE [m/s], a3, a4 [rad/s^2], aE [m/s^2], as printed.
TABLE_3_1 = {
    0: (65.55610, 169.93820, 0.10107, 0.17123, 0.28879, -0.10184, 0.24770, 0.29266, -0.16422),
    10: (67.46688, 172.02730, 0.08138, 0.20927, 0.32391, -0.12272, 0.19076, 0.11719, -0.13443),
    20: (69.71252, 175.32660, 0.05854, 0.23859, 0.33202, -0.13834, 0.14715, -0.01853, -0.11113),
    360: (65.55610, 169.93820, 0.10107, 0.17123, 0.28879, -0.10184, 0.24770, 0.29267, -0.16422),
}
TABLE_3_1_COLUMNS = ("th3", "th4", "sE", "w3", "w4", "vE", "a3", "a4", "aE")


# --------------------------------------------------------------------------
# Generic joint constraints of any scene, written independently of the solver
# (for loop-closure residuals and the per-Assur-group determinant sign).
# Duck-typed on the plain scene data (``scene.joints``, ``scene.drivers``):
# no linkage_sym import.
# --------------------------------------------------------------------------

GROUND = "ground"


def _rot(th):
    c, s = np.cos(th), np.sin(th)
    return c, s


def link_point(pose, p):
    """Global position of the point of a link whose assembly position is ``p``;
    ``pose = (ox, oy, th)``: the link's origin point and rotation from the
    assembly configuration (the link frame is the global frame in assembly)."""
    ox, oy, th = pose
    c, s = _rot(th)
    return np.array([ox + c * p[0] - s * p[1], oy + s * p[0] + c * p[1]])


def joint_equations(scene, joint, poses, q=None):
    """Residuals of one joint (2 values) plus its driving constraint (1 more)
    if ``q`` is given.  ``poses[name] = (ox, oy, th)``; ground is fixed.

    R joint: the points of links[0] and links[1] at ``at`` coincide.
    P joint: no relative rotation; links[1]'s reference point lies on the axis
    line (fixed on links[0]) -- the cross product with the axis direction.
    R driver: ``cross(e(q + th0), u)`` with ``u`` the vector from the joint to
    ``toward`` on links[1] (zero when the angle of u from links[0]'s x axis is q).
    P driver: displacement of the reference point along the axis minus ``q``.
    """
    l0, l1 = joint.links
    p0 = poses.get(l0, (0.0, 0.0, 0.0))
    p1 = poses.get(l1, (0.0, 0.0, 0.0))
    a0 = link_point(p0, joint.at)
    a1 = link_point(p1, joint.at)
    res = []
    if joint.type == "R":
        res += [a0[0] - a1[0], a0[1] - a1[1]]
    else:
        ang = joint.axis + p0[2]
        dx, dy = np.cos(ang), np.sin(ang)
        r = a1 - a0
        res += [p0[2] - p1[2], dx * r[1] - dy * r[0]]
    if q is not None:
        drv = [d for d in scene.drivers if d.joint == joint.name][0]
        if joint.type == "R":
            tw = [j for j in scene.joints if j.name == drv.toward][0]
            u = link_point(p1, tw.at) - a1
            ang = q + p0[2]
            res.append(np.cos(ang) * u[1] - np.sin(ang) * u[0])
        else:
            ang = joint.axis + p0[2]
            res.append(np.cos(ang) * (a1[0] - a0[0]) + np.sin(ang) * (a1[1] - a0[1]) - q)
    return res


def assur_groups(scene):
    """Own structural decomposition, by counting: starting from ground, the
    smallest set of unknown links whose joints (to known links or among
    themselves) give exactly 3 equations per link (2 per joint, 1 more per
    driven joint).  Returns a list of ``(links, joints)`` in solving order."""
    from itertools import combinations

    driven = {d.joint for d in scene.drivers}
    known = {GROUND}
    remaining = [lk.name for lk in scene.links]
    groups = []
    while remaining:
        found = None
        for n in range(1, len(remaining) + 1):
            for S in combinations(remaining, n):
                Sset = set(S)
                js = [j for j in scene.joints
                      if set(j.links) <= (known | Sset) and set(j.links) & Sset]
                if sum(2 + (j.name in driven) for j in js) == 3 * n:
                    found = (tuple(S), tuple(j.name for j in js))
                    break
            if found:
                break
        if not found:
            raise ValueError(f"no solvable group among {remaining}")
        groups.append(found)
        known |= set(found[0])
        remaining = [r for r in remaining if r not in found[0]]
    return groups


def group_jacobian_det(scene, group, poses, qs, size, h=1e-6):
    """Determinant of the constraint Jacobian of one group with respect to its
    links' poses ``(ox/size, oy/size, th)``, by central finite differences of
    :func:`joint_equations` (residuals divided by ``size``: dimensionless).
    ``qs`` maps driven joint names to the driver value."""
    links, joints = group
    jmap = {j.name: j for j in scene.joints}

    def resid(x):
        ps = dict(poses)
        for k, ln in enumerate(links):
            ps[ln] = (x[3 * k] * size, x[3 * k + 1] * size, x[3 * k + 2])
        out = []
        for jn in joints:
            out += joint_equations(scene, jmap[jn], ps, qs.get(jn))
        return np.array(out, dtype=float) / size

    x0 = []
    for ln in links:
        ox, oy, th = poses[ln]
        x0 += [ox / size, oy / size, th]
    x0 = np.array(x0)
    n = len(x0)
    J = np.empty((n, n))
    for k in range(n):
        e = np.zeros(n)
        e[k] = h
        J[:, k] = (resid(x0 + e) - resid(x0 - e)) / (2 * h)
    return np.linalg.det(J), np.linalg.cond(J)


# --------------------------------------------------------------------------
# Closure of a solved sweep at position, velocity and acceleration level,
# from the links' poses and rates only (duck-typed on the solver's result:
# ``res.links[name].origin/rotation/omega/alpha/origin_velocity/...``).
# --------------------------------------------------------------------------


class _LinkTrack:
    """Pose and rates of one link over the steps (ground: all zero)."""

    def __init__(self, lk, n):
        z2, z1 = np.zeros((n, 2)), np.zeros(n)
        if lk is None:
            self.o, self.th, self.w, self.a, self.vo, self.ao = z2, z1, z1, z1, z2, z2
        else:
            self.o = np.asarray(lk.origin, dtype=float)
            self.th = np.asarray(lk.rotation, dtype=float)
            self.w = z1 if lk.omega is None else np.asarray(lk.omega, dtype=float)
            self.a = z1 if lk.alpha is None else np.asarray(lk.alpha, dtype=float)
            self.vo = z2 if lk.origin_velocity is None else np.asarray(lk.origin_velocity, float)
            self.ao = z2 if lk.origin_acceleration is None else np.asarray(
                lk.origin_acceleration, float)

    def material(self, p):
        """Position (N, 2) of the material point whose assembly position is p."""
        c, s = np.cos(self.th), np.sin(self.th)
        return self.o + np.stack([c * p[0] - s * p[1], s * p[0] + c * p[1]], -1)

    def vel_at(self, x):
        """Velocity of the link's material point currently at x (N, 2)."""
        r = x - self.o
        return self.vo + self.w[:, None] * np.stack([-r[:, 1], r[:, 0]], -1)

    def acc_at(self, x):
        r = x - self.o
        perp = np.stack([-r[:, 1], r[:, 0]], -1)
        return self.ao + self.a[:, None] * perp - (self.w**2)[:, None] * r


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _dot(a, b):
    return np.sum(a * b, -1)


def closure_residuals(scene, res):
    """Per-step residuals of every joint and driver, from the poses/rates of
    the result's links.  Returns ``{check_name: array (N,)}`` with

    * ``pos:<joint>`` (length): R -- distance between the two links' points;
      P -- distance of links[1]'s reference point from the axis line;
    * ``rot:<joint>`` (rad): P -- relative rotation of its two links;
    * ``report:<joint>`` (length): the reported joint position vs links[1]'s
      material point;
    * ``vel:<joint>`` / ``acc:<joint>`` (m/s, m/s^2): time derivatives of the
      same constraints (R: relative velocity/acceleration of the coincident
      material points; P: of the line constraint, Coriolis term included) and
      the reported joint velocity/acceleration vs links[1]'s;
    * ``drv:<joint>``, ``drvd:<joint>``, ``drvdd:<joint>``: driver coordinate
      recomputed from the poses minus ``q`` (R: wrapped to (-pi, pi], rad;
      P: m), and likewise its first and second time derivatives vs qd, qdd.
    """
    n = len(res.status)
    T = {"ground": _LinkTrack(None, n)}
    for name in scene.link_names:
        T[name] = _LinkTrack(res.links[name], n)
    jn = {j.name: j for j in scene.joints}
    out = {}
    for j in scene.joints:
        L0, L1 = T[j.links[0]], T[j.links[1]]
        P1 = L1.material(j.at)
        rep = res.joints[j.name]
        out[f"report:{j.name}"] = np.hypot(*(np.asarray(rep.position) - P1).T)
        v1, a1 = L1.vel_at(P1), L1.acc_at(P1)
        if rep.velocity is not None:
            out[f"vel-report:{j.name}"] = np.hypot(*(np.asarray(rep.velocity) - v1).T)
        if rep.acceleration is not None:
            out[f"acc-report:{j.name}"] = np.hypot(*(np.asarray(rep.acceleration) - a1).T)
        if j.type == "R":
            P0 = L0.material(j.at)
            out[f"pos:{j.name}"] = np.hypot(*(P0 - P1).T)
            out[f"vel:{j.name}"] = np.hypot(*(L0.vel_at(P1) - v1).T)
            out[f"acc:{j.name}"] = np.hypot(*(L0.acc_at(P1) - a1).T)
        else:
            P0 = L0.material(j.at)
            ang = j.axis + L0.th
            e = np.stack([np.cos(ang), np.sin(ang)], -1)
            ep = np.stack([-np.sin(ang), np.cos(ang)], -1)
            r = P1 - P0
            rd = v1 - L0.vel_at(P0)
            rdd = a1 - L0.acc_at(P0)
            w0, al0 = L0.w, L0.a
            out[f"rot:{j.name}"] = np.abs(L1.th - L0.th)
            out[f"pos:{j.name}"] = np.abs(_cross(e, r))
            # c = cross(e, r); e' = w0 ep; cross(ep, r) = -dot(e, r)
            out[f"vel:{j.name}"] = np.abs(-w0 * _dot(e, r) + _cross(e, rd))
            out[f"acc:{j.name}"] = np.abs(-al0 * _dot(e, r) - w0**2 * _dot(ep, r)
                                          - 2 * w0 * _dot(e, rd) + _cross(e, rdd))
            out[f"omega:{j.name}"] = np.abs(L1.w - w0)
            out[f"alpha:{j.name}"] = np.abs(L1.a - al0)
    for d in scene.drivers:
        j = jn[d.joint]
        L0, L1 = T[j.links[0]], T[j.links[1]]
        q = np.asarray(res.drivers[d.joint]["q"], dtype=float)
        qd = np.asarray(res.drivers[d.joint]["qd"], dtype=float)
        qdd = np.asarray(res.drivers[d.joint]["qdd"], dtype=float)
        if j.type == "R":
            u = L1.material(jn[d.toward].at) - L1.material(j.at)
            phi = np.arctan2(u[:, 1], u[:, 0]) - L0.th
            out[f"drv:{j.name}"] = np.abs(np.remainder(phi - q + np.pi, 2 * np.pi) - np.pi)
            out[f"drvd:{j.name}"] = np.abs(L1.w - L0.w - qd)
            out[f"drvdd:{j.name}"] = np.abs(L1.a - L0.a - qdd)
        else:
            P0, P1 = L0.material(j.at), L1.material(j.at)
            ang = j.axis + L0.th
            e = np.stack([np.cos(ang), np.sin(ang)], -1)
            ep = np.stack([-np.sin(ang), np.cos(ang)], -1)
            r = P1 - P0
            rd = L1.vel_at(P1) - L0.vel_at(P0)
            rdd = L1.acc_at(P1) - L0.acc_at(P0)
            w0, al0 = L0.w, L0.a
            out[f"drv:{j.name}"] = np.abs(_dot(e, r) - q)
            out[f"drvd:{j.name}"] = np.abs(w0 * _dot(ep, r) + _dot(e, rd) - qd)
            out[f"drvdd:{j.name}"] = np.abs(al0 * _dot(ep, r) - w0**2 * _dot(e, r)
                                            + 2 * w0 * _dot(ep, rd) + _dot(e, rdd) - qdd)
    return out


def closure_failures(scene, res, pos_tol, rate_tol):
    """Which closure checks of :func:`closure_residuals` fail, as messages.

    Positions (steps ok or singular): ``pos_tol`` x the mechanism's size
    (lengths), ``10 pos_tol`` rad (angles: rotations of a few turns carry
    rounding of ~1e-15 rad).  Rates (ok steps): ``rate_tol`` x the sweep's
    largest joint speed / acceleration (or link omega / alpha x size)."""
    size = scene.characteristic_length()
    ok = res.ok
    pos_steps = ok | (res.status == "singular")
    r = closure_residuals(scene, res)
    vscale = max(np.nanmax(np.abs(np.asarray(jk.velocity)[ok])) for jk in res.joints.values()
                 if jk.velocity is not None) if ok.any() and "velocity" in res.stages else 0.0
    ascale = max(np.nanmax(np.abs(np.asarray(jk.acceleration)[ok])) for jk in
                 res.joints.values() if jk.acceleration is not None) \
        if ok.any() and "acceleration" in res.stages else 0.0
    wscale = max(np.nanmax(np.abs(np.asarray(lk.omega)[ok])) for lk in res.links.values()) \
        if ok.any() and "velocity" in res.stages else 0.0
    ascale_ang = max(np.nanmax(np.abs(np.asarray(lk.alpha)[ok])) for lk in res.links.values()) \
        if ok.any() and "acceleration" in res.stages else 0.0
    fails = []
    for key, vals in r.items():
        kind = key.split(":")[0]
        if kind in ("pos", "report"):
            tol, steps = pos_tol * size, pos_steps
        elif kind in ("rot", "drv"):
            tol, steps = pos_tol * 10, pos_steps  # rad; ~40 ulp of a few turns
        elif kind in ("vel", "vel-report", "drvd", "omega"):
            tol, steps = rate_tol * max(vscale, wscale * size) / (size if kind in
                                                                   ("drvd", "omega") else 1), ok
        else:  # acc, acc-report, drvdd, alpha
            tol, steps = rate_tol * max(ascale, ascale_ang * size) / (size if kind in
                                                                      ("drvdd", "alpha") else 1), ok
        if kind == "drv" and key.split(":")[1] in [d.joint for d in scene.drivers if d.kind == "P"]:
            tol = pos_tol * size
        v = np.asarray(vals)[steps]
        if v.size and not np.all(v <= tol):
            k = int(np.nanargmax(np.where(np.isnan(v), np.inf, v)))
            fails.append(f"{key}: {v[k]:.3e} > {tol:.3e} at step {np.nonzero(steps)[0][k]}")
    return fails


def _assembly_q(scene, d):
    jn = {j.name: j for j in scene.joints}
    if d.kind == "P":
        return 0.0
    a, b = jn[d.joint].at, jn[d.toward].at
    return math.atan2(b[1] - a[1], b[0] - a[0])


def determinant_signs(scene, res, steps=None):
    """Own groups; (groups, sign at assembly (G,), signs at the steps (N, G) --
    0 where not evaluated, cond (N, G))."""
    groups = assur_groups(scene)
    size = scene.characteristic_length()
    n = len(res.status)
    zero = {ln: (0.0, 0.0, 0.0) for ln in scene.link_names}
    qa = {d.joint: _assembly_q(scene, d) for d in scene.drivers}
    s0 = np.array([np.sign(group_jacobian_det(scene, g, zero, qa, size)[0])
                   for g in groups])
    signs = np.zeros((n, len(groups)))
    conds = np.full((n, len(groups)), np.nan)
    idx = np.nonzero(res.ok)[0] if steps is None else steps
    for i in idx:
        poses = {ln: (float(res.links[ln].origin[i, 0]), float(res.links[ln].origin[i, 1]),
                      float(res.links[ln].rotation[i])) for ln in scene.link_names}
        qs = {d.joint: float(res.drivers[d.joint]["q"][i]) for d in scene.drivers}
        for k, g in enumerate(groups):
            det, cond = group_jacobian_det(scene, g, poses, qs, size)
            signs[i, k] = np.sign(det)
            conds[i, k] = cond
    return groups, s0, signs, conds
