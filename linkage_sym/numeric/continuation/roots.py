"""Newton's iteration of one group at one path point, its constants, and the root searches.

The pieces of the continuation policy (:mod:`linkage_sym.numeric.continuation`)
that the point-by-point walk and the batched walk
(:mod:`linkage_sym.numeric.continuation.batched_path`) both use: what a
runtime hands the policy (:class:`Problem`) and gets back (:class:`Solution`),
damped Newton to a scaled residual of :data:`TOL` (:func:`newton`), the
continuation of one interval with its acceptance test and bisection
(:func:`continue_to`), the conditioning indicator (:func:`indicator`) and the
re-entry search from seeds around the known configurations
(:func:`roots_near`).  Everything is dimensionless (see the policy's
docstring).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

TOL = 1e-13
"""Convergence: scaled residual norm (lengths over the mechanism size)."""
MAX_ITER = 40
STALL_ITER = 6
"""Give up when the residual has not halved over this many iterations."""
POLISH_FLOOR = 1e-12
"""Polishing (Newton steps after the residual reaches :data:`TOL`) goes on while the last
correction was larger than this (max-norm, dimensionless).

Where the group's Jacobian is well conditioned a residual below ``TOL`` puts the
point within about ``TOL`` of the root, and one step takes it to rounding.  Near a
limit or singular position (smallest singular value ``s``) the point may still be
``TOL / s`` away, and one step leaves about ``(TOL / s)^2 / s``: the next steps
take it to rounding too (a class-III group ``1e-10`` rad from its singular position,
positions about 20 times closer to the 50-digit solution than with one step)."""
MAX_POLISH = 6
"""Most polishing steps."""
MAX_CORRECTION = 0.1
"""Largest accepted distance (max-norm, dimensionless) between a predictor and its root.

A root farther than this from the predictor is not taken as the continuation
of the previous point (it may be another solution of the same sign): the
interval is bisected instead.  The solving path moves a driver by at most 2
degrees (or 2 % of the size) between points, so a solution on the branch is
normally within a few thousandths of its predictor; near a limit position it
moves faster and the bisection follows it."""
MIN_FRACTION = 1.0 / 4096
"""Smallest sub-step, as a fraction of the interval between two path points."""
SAME_ROOT = 1e-7
"""Two roots closer than this (max-norm, dimensionless) are one."""
TURNED_SEEDS = 48
"""Seeds with turned angles tried at a re-entry.

With bounded steps (:data:`SEARCH_STEP`) a seed reaches a root near it, so
the seeds must cover the circle of every angle: 16 missed one root that full
steps from 16 seeds found (the second root of the assembly sign of the tests'
``scenes.triad_jump``), 24 and more found it."""
SEARCH_ITER = 40
"""Iterations of the search's Newton (:func:`search_newton`) from one seed of a re-entry search."""
SEARCH_STEP = 1.0
"""Largest step (max-norm, dimensionless: radians, lengths over the mechanism size) of
one iteration of a re-entry search.

Full Newton steps from a seed far from every root pass near singular
Jacobians and are flung far: where they land then depends on the rounding
of the seed.  Bounded steps follow the Newton direction, so seeds that
differ by rounding reach the same root.  Measured once on 356 searches of
160 random class-III triads and knees (each repeated 5 times with its
reference configurations moved by 1e-13): full steps from 16 seeds found a
different set of roots in 10 searches, this step from 48 seeds in none; of
the 80 roots of the assembly sign that 800 random seeds per search found,
full steps from 16 seeds found 77, steps bounded to 1.0 from 48 seeds all 80
(bounded to 0.5: 78)."""


class Problem(Protocol):
    """What a runtime gives the continuation for one group.

    ``ctx`` objects are opaque to this module: the known inputs of the group
    (driver values, poses of the links solved before it) at a path point, or
    blended between two path points.
    """

    angles: np.ndarray
    """(n,) bool: which unknowns are angles (shifted by whole turns at a re-entry)."""

    def at(self, i: int) -> Any:
        """Inputs at path point ``i``, or ``None`` if an upstream group failed there."""

    def blend(self, a: Any, b: Any, t: float) -> Any:
        """Inputs a fraction ``t`` of the way from ``a`` to ``b`` (linear)."""

    def evaluate(self, u: np.ndarray, ctx: Any) -> tuple[np.ndarray, np.ndarray]:
        """Scaled residual (n,) and Jacobian (n, n) with respect to ``u``."""

    def evaluate_many(self, U: np.ndarray, ctx: Any) -> tuple[np.ndarray, np.ndarray]:
        """The same for the rows of ``U`` (k, n) at once: (k, n) and (k, n, n)."""

    def evaluate_points(self, U: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Residual (k, n) and Jacobian (k, n, n) of row ``U[j]`` at path point ``idx[j]``.

        Row ``j`` equals ``evaluate(U[j], at(idx[j]))``; used by the batched walk
        (:mod:`linkage_sym.numeric.continuation.batched_path`).  Optional: a problem without it
        is solved point by point.
        """

    def available(self) -> np.ndarray:
        """(n_points,) bool: the path points whose inputs are known (``at(i)`` is not ``None``)."""


@dataclass
class Solution:
    """Result of :func:`solve_path`."""

    u: np.ndarray
    """(K, n) scaled unknowns at each path point; NaN where not solved."""
    indicator: np.ndarray
    """(K,) the group Jacobian's conditioning indicator (:func:`indicator`); NaN where not
    solved."""
    failures: dict = field(default_factory=dict)
    """path point -> (reason, detail): ``"limit"`` with the interval fraction reached,
    ``"no_root"``, ``"other_mode"`` (only roots of the other determinant sign)."""
    notes: list = field(default_factory=list)
    """(path point, number of roots with the assembly sign) of ambiguous re-entries."""


def det_sign(J) -> float:
    return float(np.sign(np.linalg.det(J)))


def inverses(J: np.ndarray) -> np.ndarray:
    """``J[k]^-1`` of every matrix of ``J`` (k, n, n); infinite where one is singular."""
    try:
        return np.linalg.inv(J)
    except np.linalg.LinAlgError:  # a singular matrix among them: one by one
        out = np.full_like(J, np.inf)
        for k in range(len(J)):
            try:
                out[k] = np.linalg.inv(J[k])
            except np.linalg.LinAlgError:
                pass
        return out


def indicator(J: np.ndarray, inverse: np.ndarray | None = None) -> np.ndarray:
    """The conditioning indicator of every matrix of ``J`` (k, n, n): ``1 / (|J|_F |J^-1|_F)``.

    The reciprocal condition number in the Frobenius norm.  With ``r =
    sigma_min / sigma_max``, ``|J|_F`` lies in ``[1, sqrt(n)] sigma_max`` and
    ``|J^-1|_F`` in ``[1, sqrt(n)] / sigma_min``, so the indicator lies in
    ``[r / n, r]``: never above ``r`` (a screen on it flags every step the
    exact ratio would), and its scale is calibrated against the exact condition
    number (:mod:`linkage_sym.numeric.results.accuracy`).  An inverse and two norms: a
    third of the singular values' cost on the small blocks of a group.  ``0``
    where ``J`` is singular, NaN where it is not finite; ``inverse``: ``J^-1`` if
    the caller has it.
    """
    J = np.asarray(J, dtype=float)
    finite = np.isfinite(J).all(axis=(1, 2))
    if finite.all():  # the usual case: no copies
        rows, Jf = slice(None), J
        inv = inverses(J) if inverse is None else inverse
    else:
        rows = np.flatnonzero(finite)
        Jf = J[rows]
        inv = inverses(Jf) if inverse is None else np.asarray(inverse)[rows]
    out = np.full(len(J), np.nan)
    with np.errstate(over="ignore", invalid="ignore"):
        prod = np.sqrt(np.einsum("kij,kij->k", Jf, Jf) * np.einsum("kij,kij->k", inv, inv))
        out[rows] = np.where(np.isfinite(prod), 1.0 / prod, 0.0)
    return out


def newton(problem: Problem, u: np.ndarray, ctx):
    """Damped Newton from ``u`` (the step halved while it does not decrease the residual).

    Once the residual is below :data:`TOL`, polishing steps follow while the last
    one's correction is above :data:`POLISH_FLOOR` (at most :data:`MAX_POLISH`),
    each kept only if it does not make the residual worse.

    Returns ``(u, residual norm, J)``.
    """
    r, J = problem.evaluate(u, ctx)
    res = float(np.linalg.norm(r))
    history = []
    polished, last = 0, math.inf  # polishing steps taken, the last one's correction
    for it in range(MAX_ITER):
        history.append(res)
        if it >= STALL_ITER and res > TOL and res > 0.5 * history[-STALL_ITER]:
            break  # no root here: the residual stalls at a least-squares minimum
        if res <= TOL:
            if polished and (last <= POLISH_FLOOR or polished >= MAX_POLISH):
                break
            polished += 1  # one more step: quadratic convergence to ~1e-16
        try:
            d = np.linalg.solve(J, r)
        except np.linalg.LinAlgError:
            return u, math.inf, J
        if not np.all(np.isfinite(d)):
            return u, math.inf, J
        step = 1.0
        while True:
            un = u - step * d
            rn, Jn = problem.evaluate(un, ctx)
            resn = float(np.linalg.norm(rn))
            if resn < res or res <= TOL or step < 1e-4:
                break
            step *= 0.5
        if res <= TOL and not resn <= res:
            break  # polishing made it worse: keep the converged point
        if res <= TOL:
            last = float(np.max(np.abs(d)))
        u, r, J, res = un, rn, Jn, resn
    return u, res, J


def search_newton(evaluate, U: np.ndarray):
    """Undamped Newton with a bounded step from every row of ``U`` at once, for a re-entry search.

    Each iteration takes the Newton step, shortened to :data:`SEARCH_STEP`
    (max-norm) when it is longer; there is no line search.  Damped Newton
    from a seed far from every root stalls at least-squares minima of the
    residual; these steps reach a root from many more seeds (the search
    keeps only roots, and checks their sign, so where it lands is all that
    matters), and, unlike full steps, reach the same root from seeds that
    differ by rounding.  ``evaluate(V, rows)`` gives the residuals and
    Jacobians of the rows ``V`` of ``U[rows]``; each row's iteration depends
    on that row alone.  Returns the last iterates and which rows reached
    :data:`TOL`.
    """
    U = np.array(U, dtype=float)
    active = np.ones(len(U), bool)
    done = np.zeros(len(U), bool)
    res0 = None
    for _ in range(SEARCH_ITER):
        idx = np.flatnonzero(active)
        if not len(idx):
            break
        R, J = evaluate(U[idx], idx)
        with np.errstate(invalid="ignore", over="ignore"):
            res = np.linalg.norm(R, axis=1)
        if res0 is None:
            res0 = np.maximum(res, 1.0)
        conv = res <= TOL
        done[idx[conv]] = True
        # diverging, or not finite: dropped
        drop = ~np.isfinite(res) | (res > 1e6 * res0[idx]) | ~np.isfinite(J).all(axis=(1, 2))
        keep = ~conv & ~drop
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            det = np.linalg.det(J)
        keep &= np.isfinite(det) & (det != 0.0)
        active[idx[~keep]] = False
        k = idx[keep]
        if len(k):
            d = np.linalg.solve(J[keep], R[keep][..., None])[..., 0]
            with np.errstate(invalid="ignore", over="ignore"):
                length = np.max(np.abs(d), axis=1)
            scale = np.where(length > SEARCH_STEP, SEARCH_STEP / np.where(length > 0, length, 1.0), 1.0)
            U[k] -= scale[:, None] * d
    return U, done


def _newton_search(problem: Problem, U: np.ndarray, ctx):
    """:func:`search_newton` from every row of ``U`` at ``ctx``; returns the ``(u, J)``
    of each seed that reached a root, polished by :func:`newton`."""
    U, done = search_newton(lambda V, rows: problem.evaluate_many(V, ctx), U)
    out = []
    for u in U[done]:
        v, res, Jv = newton(problem, u, ctx)  # polish
        if res <= TOL:
            out.append((v, Jv))
    return out


def _accept(res, J, sign, u, seed) -> bool:
    return (
        res <= TOL
        and det_sign(J) == sign
        and float(np.max(np.abs(u - seed))) <= MAX_CORRECTION
    )


def continue_to(problem: Problem, u0, a, b, sign, u_before=None):
    """Continue the root ``u0`` at inputs ``a`` to inputs ``b``.

    A direct step from the predictor first (``u0 + (u0 - u_before)`` when the
    previous path point ``u_before`` is given), then bisected sub-steps.

    Returns ``(u, J, None)`` on success, or ``(u_reached, None, t_reached)``:
    the last root reached and the fraction of the interval where the
    continuation stopped.
    """
    seed = u0 if u_before is None else 2 * u0 - u_before
    u, res, J = newton(problem, seed.copy(), b)
    if _accept(res, J, sign, u, seed):
        return u, J, None
    t, dt, u, slope = 0.0, 0.5, u0, None
    while t < 1.0:
        t1 = min(1.0, t + dt)
        seed = u if slope is None else u + slope * (t1 - t)
        ctx = b if t1 == 1.0 else problem.blend(a, b, t1)
        v, res, J = newton(problem, seed.copy(), ctx)
        if _accept(res, J, sign, v, seed):
            slope = (v - u) / (t1 - t)
            u, t = v, t1
            dt = min(2 * dt, 0.5)
            continue
        dt *= 0.5
        if dt < MIN_FRACTION:
            return u, None, t
    return u, J, None


def _nearest_turns(u, ref, angles):
    """``u`` with its angles shifted by whole turns to the values nearest ``ref``."""
    out = u.copy()
    out[angles] -= 2 * math.pi * np.round((u[angles] - ref[angles]) / (2 * math.pi))
    return out


def _turned_seeds(u, angles, count=None):
    """``u`` with its angles turned by fixed offsets spread over the circle.

    The offsets are the same at every path point (a golden-ratio sequence, one
    per angle), so what a re-entry finds does not depend on the sweep.
    """
    count = TURNED_SEEDS if count is None else count
    k = int(np.count_nonzero(angles))
    phi = (np.sqrt(5.0) - 1) / 2
    out = []
    for m in range(1, count + 1):
        v = u.copy()
        v[angles] += 2 * math.pi * (((m * phi * (1 + np.arange(k)) + 0.5 * np.arange(k)) % 1.0) - 0.5)
        out.append(v)
    return out


def _project(problem: Problem, u, ctx):
    """``u`` with its lengths (translations, slides) fitted to its angles.

    The loop equations of a planar group are linear in its lengths once its
    angles are given, so one least-squares step puts a seed on the best
    configuration of those angles: a seed with turned angles then starts as
    close to a root as the angles allow.
    """
    lin = ~problem.angles
    if not lin.any():
        return u
    r, J = problem.evaluate(u, ctx)
    d = np.linalg.lstsq(J[:, lin], -r, rcond=None)[0]
    if not np.all(np.isfinite(d)):
        return u
    v = u.copy()
    v[lin] += d
    return v


def _angle_distance(u, v, angles):
    return float(np.max(np.abs(u[angles] - v[angles]), initial=0.0))


def search_seeds(ref, others, angles) -> np.ndarray:
    """The seeds of a root search around ``ref``: ``ref``, ``others``, ``ref`` turned."""
    return np.array([ref, *others, *_turned_seeds(ref, angles)])


def distinct_roots(roots, ref, angles, sign):
    """The roots of a search (``(u, J)`` pairs in seed order) as :func:`roots_near` returns them.

    Each shifted by whole turns to the angles nearest ``ref``, duplicates
    dropped, sorted by the distance of their angles from ``ref`` (then of all
    unknowns), split by determinant sign: ``(same_sign, other_sign)``.
    """
    found = []
    for u, J in roots:
        u = _nearest_turns(u, ref, angles)
        if not any(float(np.max(np.abs(u - z))) <= SAME_ROOT for z, _ in found):
            found.append((u, J))
    found.sort(key=lambda p: (round(_angle_distance(p[0], ref, angles), 9),
                              float(np.max(np.abs(p[0] - ref)))))
    same = [(u, J) for u, J in found if det_sign(J) == sign]
    other = [(u, J) for u, J in found if det_sign(J) != sign]
    return same, other


def roots_near(problem: Problem, ctx, ref, others, sign):
    """Roots of the group at ``ctx`` found from seeds around ``ref``: ``(same_sign, other_sign)``.

    Seeds: ``ref``, the configurations ``others``, and ``ref`` with its
    angles turned by fixed offsets (:func:`_turned_seeds`), each with its
    lengths fitted to its angles (:func:`_project`); Newton with bounded steps
    from each (:func:`search_newton`).  Every root is shifted by whole turns to the
    angles nearest ``ref``; duplicates are dropped.  Each list holds
    ``(u, J)`` pairs sorted by the distance of their angles from ``ref``
    (then of all unknowns), so both runtimes choose alike
    (:func:`distinct_roots`).
    """
    seeds = [_project(problem, v, ctx) for v in search_seeds(ref, others, problem.angles)]
    return distinct_roots(_newton_search(problem, np.array(seeds), ctx), ref, problem.angles, sign)
