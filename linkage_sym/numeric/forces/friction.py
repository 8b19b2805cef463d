"""Coulomb friction in the joints (contract, second part: ``joints[i].friction``).

The friction of a joint is what its ``links[0]`` exerts on its ``links[1]``:

* ``R`` joint: the couple ``mu = -rho |R| sign(w1 - w0)`` about the pin, ``rho = f r``
  the friction circle's radius, ``R`` the joint's reaction;
* ``P`` joint: the force ``mu = -f |N| sign(v)`` along the slide's axis, applied at
  the joint's reference point, ``N`` the reaction's normal force and ``v`` the slip
  velocity of ``links[1]`` relative to ``links[0]`` along the axis.

The sign comes from the relative velocity; where it is zero (below
:data:`ZERO_RATE` of the mechanism's largest at the step), from the relative
acceleration (the impending motion); where both are zero the joint has no
friction at that step, and a warning names the joint and the steps
(:meth:`FrictionSet.notes`).

Each group's equilibrium (solved by its linear routine: closed form, Dang and
Zhang's superposition, or a dense solve) is linear in the applied wrenches.
The friction magnitudes ``mu`` (one per joint of the group with friction) are
then the unknowns of ``g(mu) = mu + rho s |R0 + C mu| = 0`` per step, where
``R0`` are the frictionless reactions and ``C`` the reactions caused by a unit
friction at each joint, both from the group's own linear routine (for a
class-III group: the superposition, so the superposition is only ever applied to
the linear problem, and the friction is an outer Newton around it).
:func:`solve_group` solves it by Newton's method from ``mu = 0`` (the
frictionless solution), vectorised over the steps, to rounding.

Self-locking
------------
Write ``g_lam(mu) = mu + lam rho s |R0 + C mu|``, the friction scaled by ``lam``.
At ``lam = 0`` the solution is ``mu = 0`` with Jacobian ``dg/dmu = I``.  The
motion the driver imposes is the solution on the branch that continues it as
``lam`` grows to 1, along which ``det dg/dmu > 0``.  Where that determinant
reaches 0 the friction a unit increase of itself calls for (through the
reactions) is a unit increase: friction and reactions grow together without
bound, so no finite effort moves the mechanism -- the step is self-locking.
(For one joint ``g`` is piecewise linear, ``det = 1 + rho s c sign(N)``, and the
branch's effort is finite exactly while it is positive: the friction-angle
criterion of the textbooks.)  A step is marked self-locking when Newton from
``mu = 0`` at ``lam = 1`` meets ``det <= 0`` or does not converge, and again when
followed in :data:`STAGES` steps of ``lam``; the joints named are those of the
determinant's null direction (the smallest singular vector of ``dg/dmu``).
"""

from __future__ import annotations

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.forces.loads import Wrench
from linkage_sym.numeric.results.wording import steps_text

__all__ = ["ZERO_RATE", "FrictionSet", "active_joints", "add_friction", "fold", "solve_group"]

ZERO_RATE = 1e-12
"""A relative velocity (or acceleration) at most this fraction of the mechanism's largest at
the step (see :func:`_rel_rates`) counts as zero: rounding, not a direction.  Each step on its
own, so a sweep solved in chunks has the signs of the whole."""
MAX_NEWTON = 60
"""Newton iterations per stage before a step is taken as having no solution on its branch."""
STAGES = 8
"""Stages of the friction scale ``lam`` in which a step that Newton at ``lam = 1`` fails is
followed again before it is called self-locking."""


def active_joints(scene: Scene) -> tuple:
    """The joints whose friction acts: a positive coefficient, with ``effects.friction``."""
    if not scene.effects.friction:
        return ()
    return tuple(j for j in scene.joints if j.friction is not None and j.friction.coefficient > 0)


def _point_rates(st, px, py):
    """Velocity and acceleration of the point of link state ``st`` at ``(px, py)``."""
    rx, ry = px - st.dx, py - st.dy
    w2 = st.w * st.w
    return ((st.vx - st.w * ry, st.vy + st.w * rx),
            (st.ax - st.al * ry - w2 * rx, st.ay + st.al * rx - w2 * ry))


def _rel_rates(joint, S, geo):
    """``(v, a, v_scale, a_scale)``: the relative velocity and acceleration of the joint
    (angular for ``R``, along the axis for ``P``) and, at each step, the sizes they are
    compared with: the mechanism's largest of the same kind at that step (the links' angular
    rates; the velocities and accelerations of every link's point at the joint)."""
    s0, s1 = S[joint.links[0]], S[joint.links[1]]
    moving = [st for n, st in S.items() if n != GROUND]
    if joint.type == "R":
        ws = [np.abs(st.w) for st in moving]
        als = [np.abs(st.al) + st.w * st.w for st in moving]
        return s1.w - s0.w, s1.al - s0.al, np.maximum.reduce(ws), np.maximum.reduce(als)
    px, py = geo.point(joint.name)
    _, _, tx, ty = geo.normal(joint.name)
    (v1x, v1y), (a1x, a1y) = _point_rates(s1, px, py)
    (v0x, v0y), (a0x, a0y) = _point_rates(s0, px, py)
    v = (v1x - v0x) * tx + (v1y - v0y) * ty
    a = (a1x - a0x) * tx + (a1y - a0y) * ty
    rates = [_point_rates(st, px, py) for st in moving]
    vs = np.maximum.reduce([np.hypot(*va[0]) for va in rates])
    as_ = np.maximum.reduce([np.hypot(*va[1]) for va in rates])
    return v, a, vs, as_


class FrictionSet:
    """The friction joints of a scene at the solved steps: arms, signs, relative speeds.

    Parameters
    ----------
    scene : Scene
    S : dict of LinkState
        Link states at the ``K`` solved steps (velocities and accelerations).
    geo : Geometry
    K : int
    """

    def __init__(self, scene: Scene, S, geo, K: int):
        self.scene = scene
        self.K = K
        self.arm, self.sign, self.rate, self.moving = {}, {}, {}, {}
        for j in active_joints(scene):
            v, a, vs, as_ = (np.broadcast_to(np.asarray(x, float), (K,)) for x in _rel_rates(j, S, geo))
            moving = np.abs(v) > ZERO_RATE * vs
            accel = ~moving & (np.abs(a) > ZERO_RATE * as_)
            self.sign[j.name] = np.where(moving, np.sign(v), np.where(accel, np.sign(a), 0.0))
            self.arm[j.name] = j.friction.arm
            self.rate[j.name] = v
            self.moving[j.name] = moving

    def notes(self, idx) -> list:
        """Warnings naming each joint and the steps where it has no friction (neither its
        relative velocity nor its acceleration is non-zero); ``idx``: the sweep's step of
        each solved step (``None``: the same)."""
        out = []
        for name, s in self.sign.items():
            bad = np.flatnonzero(s == 0)
            if len(bad):
                steps = bad if idx is None else np.asarray(idx)[bad]
                out.append(f"joint {name}: neither its relative velocity nor its relative "
                           f"acceleration is non-zero at {len(steps)} step(s) (steps "
                           f"{steps_text(steps, len(steps))}): its friction, whose direction "
                           "opposes them, is taken as zero there")
        return out

    def power(self, mu: dict):
        """The power the friction dissipates (W, >= 0) at the solved steps."""
        p = np.zeros(self.K)
        for name, m in mu.items():
            p = p + np.where(self.moving[name], -m * self.rate[name], 0.0)
        return p


def add_friction(W, joint, mu, geo, only=None) -> None:
    """Add the friction ``mu`` of ``joint`` (on ``links[1]``; its opposite on ``links[0]``)
    to the wrenches ``W`` of the links in ``only`` (default: every link in ``W``)."""
    px, py = geo.point(joint.name)
    for link, s in ((joint.links[1], 1.0), (joint.links[0], -1.0)):
        if link not in W or (only is not None and link not in only):
            continue
        if joint.type == "R":
            W[link].add_couple(s * mu)
        else:
            _, _, tx, ty = geo.normal(joint.name)
            W[link].add_force(s * mu * tx, s * mu * ty, px, py)


def fold(joint, reaction, mu, geo):
    """A joint's reaction with its friction added: ``(fx, fy, m)`` of everything
    ``links[0]`` exerts on ``links[1]`` at the joint (for pushing to other links)."""
    fx, fy, m = reaction
    if mu is None:
        return reaction
    if joint.type == "R":
        return fx, fy, m + mu
    _, _, tx, ty = geo.normal(joint.name)
    return fx + mu * tx, fy + mu * ty, m


def _vec(x, K):
    return np.broadcast_to(np.asarray(x, float), (K,))


def solve_group(solve, base, scene, names, W, geo, fset: FrictionSet, skip):
    """A group's reactions and efforts with the friction of its joints (module docstring).

    Parameters
    ----------
    solve : callable
        ``solve(W) -> (reactions, efforts)``: the group's linear routine.
    base : tuple
        ``solve(W)``: the frictionless reactions and efforts under the applied wrenches.
    names : sequence of str
        The group's joints.
    W : dict of Wrench
        Applied wrenches (loads and the reactions of the groups solved before).
    skip : ndarray of bool (K,)
        Steps to leave out (locked by a group solved before): NaN there.

    Returns
    -------
    reactions, efforts : dict
    mu : dict
        Joint -> friction (K,), of the group's friction joints.
    locked : ndarray of bool (K,)
        The steps at which this group self-locks.
    lockers : dict
        Step -> names of the joints whose friction locks it.
    """
    K = fset.K
    fj = [n for n in names if n in fset.arm]
    reactions, efforts = base
    if not fj:
        return reactions, efforts, {}, np.zeros(K, bool), {}
    unit = []
    for n in fj:
        W0 = {k: Wrench(w.rx, w.ry) for k, w in W.items()}
        add_friction(W0, scene.joint(n), 1.0, geo)
        unit.append(solve(W0))
    A = np.stack([np.stack([_vec(reactions[n][0], K), _vec(reactions[n][1], K)], -1) for n in fj], 1)
    C = np.stack([np.stack([np.stack([_vec(u[0][n][0], K), _vec(u[0][n][1], K)], -1)
                            for u in unit], 1) for n in fj], 1)  # (K, j, k, 2)
    rs = np.stack([fset.arm[n] * fset.sign[n] for n in fj], 1)  # (K, m)
    mu, locked, J = _friction_newton(A, C, rs, skip)
    lockers = {}
    for i in np.flatnonzero(locked):
        _, _, vt = np.linalg.svd(J[i])
        v = np.abs(vt[-1])
        lockers[int(i)] = [n for n, x in zip(fj, v) if x >= 0.1 * v.max()]
    mu[locked | skip] = np.nan
    out_r, out_e = {}, {}
    for n, (fx, fy, m) in reactions.items():
        fx, fy, m = _vec(fx, K).copy(), _vec(fy, K).copy(), _vec(m, K).copy()
        for k, u in enumerate(unit):
            ux, uy, um = u[0][n]
            fx += mu[:, k] * ux
            fy += mu[:, k] * uy
            m += mu[:, k] * um
        out_r[n] = (fx, fy, m)
    for n, e in efforts.items():
        e = _vec(e, K).copy()
        for k, u in enumerate(unit):
            e += mu[:, k] * u[1][n]
        out_e[n] = e
    return out_r, out_e, {n: mu[:, k] for k, n in enumerate(fj)}, locked, lockers


def _residual(A, C, rs, mu, lam):
    """``g`` and ``dg/dmu`` at ``mu`` (K, m), friction scaled by ``lam``."""
    Rx = A[..., 0] + (C[..., 0] * mu[:, None, :]).sum(-1)  # (K, j): sum over the frictions k
    Ry = A[..., 1] + (C[..., 1] * mu[:, None, :]).sum(-1)
    nR = np.hypot(Rx, Ry)
    g = mu + lam * rs * nR
    with np.errstate(divide="ignore", invalid="ignore"):
        ux, uy = np.where(nR > 0, Rx / nR, 0.0), np.where(nR > 0, Ry / nR, 0.0)
    dR = ux[..., None] * C[..., 0] + uy[..., None] * C[..., 1]  # d|R_j| / d mu_k
    J = np.eye(mu.shape[1]) + (lam * rs)[..., None] * dR
    return g, J


def _newton(A, C, rs, mu, lam):
    """Newton on ``g_lam``; ``(mu, ok, J)``: ``ok`` where it converged with ``det J > 0`` at
    every iterate (see the module docstring)."""
    K = len(mu)
    ok = np.ones(K, bool)
    done = np.zeros(K, bool)
    J = np.broadcast_to(np.eye(mu.shape[1]), (K,) + (mu.shape[1],) * 2).copy()
    for _ in range(MAX_NEWTON):
        live = ok & ~done
        if not live.any():
            break
        g, Jl = _residual(A[live], C[live], rs[live], mu[live], lam)
        J[live] = Jl
        det = np.linalg.det(Jl)
        good = det > 0
        d = np.zeros_like(g)
        d[good] = -np.linalg.solve(Jl[good], g[good][..., None])[..., 0]
        li = np.flatnonzero(live)
        ok[li[~good]] = False
        mu[li] += d
        Al = A[live]
        size = (np.abs(mu[li]).max(axis=1)
                + np.abs(lam * rs[live] * np.hypot(Al[..., 0], Al[..., 1])).max(axis=1))
        done[li[good & (np.abs(d).max(axis=1) <= 1e-12 * size)]] = True
    return mu, ok & done, J


def _friction_newton(A, C, rs, skip):
    """``(mu, locked, J)``: Newton from the frictionless solution at every step not skipped,
    then the steps it fails followed in :data:`STAGES` stages of the friction's scale."""
    K, m = rs.shape
    live = ~skip
    mu = np.zeros((K, m))
    sub = np.flatnonzero(live)
    mu_l, ok, J_l = _newton(A[sub], C[sub], rs[sub], mu[sub], 1.0)
    J = np.broadcast_to(np.eye(m), (K, m, m)).copy()
    mu[sub], J[sub] = mu_l, J_l
    locked = np.zeros(K, bool)
    again = sub[~ok]
    if len(again):
        mu_a = np.zeros((len(again), m))
        fine = np.ones(len(again), bool)
        for lam in np.arange(1, STAGES + 1) / STAGES:
            mu_a, ok_a, J_a = _newton(A[again], C[again], rs[again], mu_a, lam)
            fine &= ok_a
        mu[again], J[again] = mu_a, J_a
        locked[again[~fine]] = True
    return mu, locked, J
