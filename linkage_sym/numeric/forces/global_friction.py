"""The global method with joint friction: every link's equilibrium and every joint's friction
law in one nonlinear system per step.

The unknowns are those of :mod:`~linkage_sym.numeric.forces.global_statics` (every
reaction and effort) and one per joint with friction, its friction (``mu/L`` for an
``R`` joint's couple, ``mu`` for a ``P`` joint's axial force).  The rows are every
moving link's three equilibrium equations, with the friction among the joint forces,
and one friction law per such joint: ``mu + rho s |R| = 0`` (``R`` joint, row divided
by ``L``; ``R = (Rx, Ry)``, two unknowns of the system) or ``mu + f s |N| = 0`` (``P``
joint).  Newton's method solves the whole system of each step from the frictionless
solution, all the steps as one batch of dense systems, to rounding.

It shares no solving code with the group routines and their friction
(:mod:`~linkage_sym.numeric.forces.friction`): it takes from there only the data of
the joints (arms, the signs of their relative motion).  Self-locking is decided on the
whole system by the same criterion, written for it: the Jacobian of the full system
over that of the frictionless one (the determinant of the friction rows' Schur
complement) must stay positive along the branch from the frictionless solution;
where Newton at full friction meets a non-positive one or does not converge, the
step is followed again in :data:`STAGES` stages of the friction's scale, and is
self-locking when it still does.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric.forces.global_statics import assemble, dense_system, unpack

__all__ = ["solve_global_friction"]

STAGES = 8
"""Stages of the friction's scale in which a step Newton fails at full friction is followed."""
MAX_ITER = 60
"""Newton iterations per stage."""


def _system(scene, geo, W, L, K, fset):
    """The linear rows with the friction columns, and the friction joints' data."""
    links = list(scene.link_names)
    joints = [j.name for j in scene.joints]
    drivers = [d.joint for d in scene.drivers]
    entries, b, cols, ncols = assemble(scene, links, joints, drivers, geo, W, L)
    nrows = 3 * len(links)
    fj = [scene.joint(n) for n in fset.arm]
    n = ncols + len(fj)
    A, rhs = dense_system(entries, b, nrows, ncols, K)
    M = np.zeros((K, n, n))
    M[:, :nrows, :ncols] = A
    r = np.zeros((K, n))
    r[:, :nrows] = rhs
    row = {name: 3 * i for i, name in enumerate(links)}
    for k, j in enumerate(fj):
        c = ncols + k
        px, py = geo.point(j.name)
        for link, s in ((j.links[1], 1.0), (j.links[0], -1.0)):
            if link not in row:
                continue
            i, w = row[link], W[link]
            if j.type == "R":  # the couple mu = L y
                M[:, i + 2, c] += s
            else:
                _, _, tx, ty = geo.normal(j.name)
                M[:, i, c] += s * tx
                M[:, i + 1, c] += s * ty
                M[:, i + 2, c] += s * ((px - w.rx) * ty - (py - w.ry) * tx) / L
    return M, r, cols, ncols, nrows, fj, (links, joints, drivers)


def _laws(x, fj, cols, ncols, nrows, arms, lam):
    """The friction rows' residuals (K, m) and their derivatives, as ``(rows, (k, col, value))``."""
    res, parts = [], []
    for k, j in enumerate(fj):
        c, a = cols[j.name], arms[:, k]
        if j.type == "R":
            Rx, Ry = x[:, c], x[:, c + 1]
            nR = np.hypot(Rx, Ry)
            with np.errstate(divide="ignore", invalid="ignore"):
                ux, uy = np.where(nR > 0, Rx / nR, 0.0), np.where(nR > 0, Ry / nR, 0.0)
            res.append(x[:, ncols + k] + lam * a * nR)
            parts += [(k, c, lam * a * ux), (k, c + 1, lam * a * uy)]
        else:
            N = x[:, c]
            res.append(x[:, ncols + k] + lam * a * np.abs(N))
            parts.append((k, c, lam * a * np.sign(N)))
    return np.stack(res, 1), parts


def _newton(M, r, x, fj, cols, ncols, nrows, arms, lam, sign0):
    """Newton on the whole system; ``(x, ok, Jac)`` per step (``ok``: converged with the
    determinant's sign that of the frictionless system at every iterate)."""
    K, n = x.shape
    ok, done = np.ones(K, bool), np.zeros(K, bool)
    Jac = M.copy()
    for _ in range(MAX_ITER):
        live = ok & ~done
        if not live.any():
            break
        xl = x[live]
        F = np.einsum("kij,kj->ki", M[live], xl) - r[live]
        law, parts = _laws(xl, fj, cols, ncols, nrows, arms[live], lam)
        F[:, nrows:] = law
        Jl = M[live].copy()
        for k in range(len(fj)):
            Jl[:, nrows + k, ncols + k] = 1.0
        for k, c, v in parts:
            Jl[:, nrows + k, c] = v
        Jac[live] = Jl
        sgn, _ = np.linalg.slogdet(Jl)
        good = sgn * sign0[live] > 0
        d = np.zeros_like(xl)
        d[good] = -np.linalg.solve(Jl[good], F[good][..., None])[..., 0]
        li = np.flatnonzero(live)
        ok[li[~good]] = False
        x[li] += d
        small = np.abs(d).max(axis=1) <= 1e-12 * np.abs(x[li]).max(axis=1)
        done[li[good & small]] = True
    return x, ok & done, Jac


def solve_global_friction(scene, geo, W, L, K, fset):
    """Reactions, efforts and friction of every joint with friction from one nonlinear system
    per step (module docstring).

    Returns
    -------
    reactions, efforts : dict
        As :func:`~linkage_sym.numeric.forces.global_statics.solve_global`'s.
    mu : dict
        Joint -> friction (K,) (couple N·m or axial force N).
    locked : ndarray of bool (K,)
    lockers : dict
        Step -> names of the joints whose friction locks it.
    """
    M, r, cols, ncols, nrows, fj, (links, joints, drivers) = _system(scene, geo, W, L, K, fset)
    m = len(fj)
    # the friction rows of an R joint are divided by L (its unknown is mu / L)
    arms = np.stack([fset.arm[j.name] * fset.sign[j.name] / (L if j.type == "R" else 1.0)
                     for j in fj], 1)
    M0 = M.copy()
    for k in range(m):
        M0[:, nrows + k, ncols + k] = 1.0
    sign0, _ = np.linalg.slogdet(M0)
    x0 = np.linalg.solve(M0, r[..., None])[..., 0]  # the frictionless solution
    x, ok, Jac = _newton(M, r, x0.copy(), fj, cols, ncols, nrows, arms, 1.0, sign0)
    locked = np.zeros(K, bool)
    again = np.flatnonzero(~ok)
    if len(again):
        xa, fine = x0[again].copy(), np.ones(len(again), bool)
        for lam in np.arange(1, STAGES + 1) / STAGES:
            xa, ok_a, Ja = _newton(M[again], r[again], xa, fj, cols, ncols, nrows,
                                   arms[again], lam, sign0[again])
            fine &= ok_a
        x[again], Jac[again] = xa, Ja
        locked[again[~fine]] = True
    lockers = {}
    for i in np.flatnonzero(locked):
        v = np.abs(np.linalg.svd(Jac[i])[2][-1, ncols:])
        lockers[int(i)] = [j.name for j, e in zip(fj, v) if e >= 0.1 * v.max()]
    x[locked] = np.nan
    reactions, efforts = unpack(scene, x[:, :ncols], cols, joints, drivers, geo, L)
    mu = {j.name: x[:, ncols + k] * (L if j.type == "R" else 1.0) for k, j in enumerate(fj)}
    return reactions, efforts, mu, locked, lockers
