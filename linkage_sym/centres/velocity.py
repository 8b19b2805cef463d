"""Instant centres from velocities: where two links' velocity fields agree.

A link ``k`` in plane motion has the velocity field ``v_k(p) = v_k(c) +
w_k J (p - c)`` (``J`` the rotation by +90 degrees).  The instant centre of
links ``i`` and ``j`` is the point where ``v_i(p) = v_j(p)`` (the textbook
chapter *Kinematic analysis of planar mechanisms*, README Sources [4], section 3-2: the coincident
points of equal velocity), so

    p = c + J (v_i(c) - v_j(c)) / (w_i - w_j).

Where ``w_i = w_j`` the relative motion is a translation: no finite point
has zero relative velocity, and the centre lies at infinity in the direction
normal to the relative velocity ``v_i(c) - v_j(c)``.  Where both vanish the
links are at rest relative to each other and every point is a centre: the
centre is undefined.

This module reads only the links' solved rates (``omega``,
``origin_velocity``, ``origin``, ``rotation``) and the joints' positions (for
a reference point near the mechanism); it shares no code with Kennedy's
construction (:mod:`linkage_sym.centres.kennedy`), which it checks, and it
fills the pairs that construction cannot reach.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.model import GROUND

__all__ = ["FAR", "REST", "VelocityCentres", "velocity_centres"]

FAR = 1e9
"""A centre farther than this many mechanism sizes from the mechanism is at infinity.

In float64 ``w_i - w_j`` is only known to about 1e-16 of the angular
velocities; a centre 1e9 sizes away means a difference 1e-9 of them, below
which the position has no significant digits to speak of.
"""

REST = 1e-12
"""Links whose relative motion (``|w_i - w_j| L + |v_i(c) - v_j(c)|``) is below
this fraction of the mechanism's speed (the largest ``|w_k| L + |v_k(c)|``)
are at rest relative to each other: their centre is undefined."""


@dataclass
class VelocityCentres:
    """Instant centres of every pair of links from their velocity fields.

    Attributes
    ----------
    links : tuple of str
        ``ground`` then the moving links, in the order of ``analysis.links``.
    pairs : tuple of (str, str)
        ``(links[i], links[j])`` for ``i < j``, in the order ``(0, 1), (0, 2), ...``.
    position : ndarray, shape (N, P, 2)
        Centre (m); NaN where at infinity, undefined or without rates.
    direction : ndarray, shape (N, P, 2)
        Unit direction of a centre at infinity; NaN elsewhere.
    at_infinity, undefined : ndarray of bool, shape (N, P)
    relative_omega : ndarray, shape (N, P)
        ``w_j - w_i`` (rad/s) of pair ``(links[i], links[j])``: the angular
        velocity of ``links[j]`` relative to ``links[i]``.
    """

    links: tuple
    pairs: tuple
    position: np.ndarray
    direction: np.ndarray
    at_infinity: np.ndarray
    undefined: np.ndarray
    relative_omega: np.ndarray


def velocity_centres(analysis) -> VelocityCentres:
    """Instant centres of every pair of links (the ground included) at every step.

    Parameters
    ----------
    analysis : Analysis
        A sweep solved with the ``velocity`` stage.

    Returns
    -------
    VelocityCentres

    Examples
    --------
    The coupler of the crank-rocker turns about the point where its velocity
    is zero:

    >>> import numpy as np, linkage_sym
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> vc = velocity_centres(res)
    >>> k = vc.pairs.index(("ground", "coupler"))
    >>> p = vc.position[40, k]
    >>> cp = res.links["coupler"]
    >>> local = np.array([[np.cos(-cp.rotation[40]), -np.sin(-cp.rotation[40])],
    ...                   [np.sin(-cp.rotation[40]), np.cos(-cp.rotation[40])]]) @ (p - cp.origin[40])
    >>> bool(np.abs(cp.point_velocity(tuple(local))[40]).max() < 1e-12)
    True
    """
    names = (GROUND, *analysis.links)
    N = len(analysis.status)
    joints = [np.asarray(jk.position, dtype=float) for jk in analysis.joints.values()]
    c = np.mean(joints, axis=0)  # (N, 2): a reference point inside the mechanism at each step
    spread = np.stack(joints) - c
    L = np.nanmax(np.linalg.norm(spread, axis=-1)) if np.isfinite(spread).any() else 1.0
    L = float(L) if L > 0 else 1.0

    w = [np.zeros(N)]
    vc = [np.zeros((N, 2))]
    for lk in analysis.links.values():
        om = np.asarray(lk.omega, dtype=float)
        r = c - np.asarray(lk.origin, dtype=float)
        w.append(om)
        vc.append(np.asarray(lk.origin_velocity, dtype=float)
                  + np.stack([-om * r[:, 1], om * r[:, 0]], axis=-1))
    speed = np.max([np.abs(wk) * L + np.linalg.norm(vk, axis=-1) for wk, vk in zip(w, vc)], axis=0)

    pairs, pos, dirs, inf, undef, rel = [], [], [], [], [], []
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            pairs.append((names[i], names[j]))
            dw = w[j] - w[i]
            dv = vc[j] - vc[i]
            dv_norm = np.linalg.norm(dv, axis=-1)
            still = np.abs(dw) * L + dv_norm <= REST * speed
            far = ~still & (np.abs(dw) * L * FAR <= dv_norm)
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                # v_j(p) - v_i(p) = dv + dw J (p - c) = 0  =>  p = c + J dv / dw
                p = c + np.stack([-dv[:, 1], dv[:, 0]], axis=-1) / dw[:, None]
                u = np.stack([-dv[:, 1], dv[:, 0]], axis=-1) / dv_norm[:, None]
            rates = np.isfinite(dw) & np.all(np.isfinite(dv), axis=-1)
            finite = rates & ~still & ~far
            pos.append(np.where(finite[:, None], p, np.nan))
            dirs.append(np.where((rates & far)[:, None], u, np.nan))
            inf.append(rates & far)
            undef.append(rates & still)
            rel.append(dw)
    return VelocityCentres(
        links=names,
        pairs=tuple(pairs),
        position=np.stack(pos, axis=1),
        direction=np.stack(dirs, axis=1),
        at_infinity=np.stack(inf, axis=1),
        undefined=np.stack(undef, axis=1),
        relative_omega=np.stack(rel, axis=1),
    )
