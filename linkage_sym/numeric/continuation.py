"""The one continuation policy of groups solved by Newton's method (NumPy only).

Class-III triads, driven (actuator) groups and every other group without a
closed form are solved by Newton's method on their own loop equations, step
after step along the solving path.  Both runtimes -- the numeric plan
(:mod:`linkage_sym.numeric.newton`, pose coordinates) and the compiled
symbolic mechanism (:mod:`linkage_sym.codegen.runtime`, the derived angles
and slides) -- hand this module a :class:`Problem` and get the same policy:

* **Continuity.**  A path point is reached from the previous solved one by
  natural-parameter continuation: a predictor (linear from the two previous
  points, when they are consecutive), damped Newton to a scaled residual of
  :data:`TOL`, and the solution is *accepted* only if it keeps the assembly
  configuration's Jacobian-determinant sign and lies within
  :data:`MAX_CORRECTION` (dimensionless: radians, lengths over the
  mechanism's size) of the predictor.  Otherwise the interval is bisected
  (adaptive sub-steps, down to :data:`MIN_FRACTION` of it).  A solution is
  therefore the one reached continuously from the assembly configuration,
  whatever the number of steps of the sweep: a step's result does not depend
  on its neighbours.
* **Limits.**  When the continuation cannot go on (the group reaches a fold:
  a limit position beyond which it cannot be assembled, or a singular
  position where it would change assembly mode), the point is reported with
  the fraction of the interval where that happens, so the caller can name the
  driver value.
* **Re-entry after a gap.**  After points that could not be solved there is
  no continuous path.  The roots of the group are searched from seeds around
  the last solved configuration (that configuration, the one where the
  continuation stopped, the assembly configuration, and the last solved one
  with its angles turned by fixed offsets, each with its lengths fitted to
  its angles): Newton with a bounded step (:data:`SEARCH_STEP`) from each.
  The roots with the assembly
  configuration's determinant sign are kept, and the one whose angles are
  nearest to the last solved configuration is taken (angles shifted by whole
  turns to the nearest value, as the scene format asks of rotations across a
  gap).  More than one such root is reported as an ambiguous assembly mode.
  The same happens where the continuation stops at a limit: if a root of the
  assembly sign exists past it, the group goes on there (the assembly mode is
  the determinant sign, as for a closed-form dyad) and the jump is reported,
  once per limit: a search that only finds the last configuration continued
  (its angles a whole turn off the representation the equations hold, after an
  earlier search) is no jump, and is not reported (:func:`_turned_continuation`).

**Many points at once.**  By default (:data:`BATCHED`) :func:`solve_path`
hands continuous stretches and gaps to :mod:`linkage_sym.numeric.batched_path`,
which evaluates this policy on blocks of points (the same predictors, the
same Newton iteration, the same acceptance test and root searches) and
leaves every point where the direct step is not taken to :meth:`Walk.step`:
the results are the point-by-point walk's (tested against it).

Everything is dimensionless: a :class:`Problem` evaluates the scaled
residual (length rows over the mechanism size ``L``) and its Jacobian with
respect to the scaled unknowns ``u`` (lengths over ``L``, angles as they
are).
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
        (:mod:`linkage_sym.numeric.batched_path`).  Optional: a problem without it
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


def _det_sign(J) -> float:
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
    number (:mod:`linkage_sym.numeric.accuracy`).  An inverse and two norms: a
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
        and _det_sign(J) == sign
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


def _turned_continuation(problem: Problem, u_last, a, b, sign, u) -> bool:
    """Whether the root ``u`` found at inputs ``b`` is the continuation of the solved point
    ``u_last`` at inputs ``a``, up to whole turns of its angles.

    A root search shifts each angle by whole turns to the value nearest the last solved
    configuration (:func:`distinct_roots`); where the group's equations are not periodic
    in every angle (a driver row on a relative angle) that representation does not solve
    them, and a continuation from it converges to the same configuration a turn away and
    is refused at once, at every point after such a search.  So when the continuation
    could not take even its first sub-step, ``u_last`` is put back on its equations (one
    angle turned by up to :data:`_TURNS` whole turns, the representation whose residual
    at ``a`` is within :data:`TOL`) and continued again; if that reaches ``u`` up to whole
    turns (within :data:`SAME_ROOT`), the group passed no limit or singular position in
    the interval, and there is nothing to warn of.
    """
    u_last = np.array(u_last, dtype=float)
    r, _ = problem.evaluate(u_last, a)
    if not float(np.linalg.norm(r)) > TOL:
        return False  # it solves its equations: the continuation failed for another reason
    v = None
    for i in np.flatnonzero(problem.angles):
        for n in (1, -1, 2, -2)[:2 * _TURNS]:
            w = u_last.copy()
            w[i] += 2 * math.pi * n
            rw, Jw = problem.evaluate(w, a)
            if float(np.linalg.norm(rw)) <= TOL and _det_sign(Jw) == sign:
                v = w
                break
        if v is not None:
            break
    if v is None:
        return False
    w, _, t = continue_to(problem, v, a, b, sign)
    if t is not None:
        return False
    d = np.asarray(u, dtype=float) - w
    d[problem.angles] -= 2 * math.pi * np.round(d[problem.angles] / (2 * math.pi))
    return bool(np.all(np.isfinite(d))) and float(np.max(np.abs(d), initial=0.0)) <= SAME_ROOT


_TURNS = 2
"""Whole turns (either way) tried on each angle by :func:`_turned_continuation`."""


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
    same = [(u, J) for u, J in found if _det_sign(J) == sign]
    other = [(u, J) for u, J in found if _det_sign(J) != sign]
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


BATCHED = True
"""Whether :func:`solve_path` solves continuous stretches many points at once
(:mod:`linkage_sym.numeric.batched_path`: the same policy and the same results)
or point after point.  The point-by-point walk stays for comparison and for
problems without :meth:`Problem.evaluate_points`."""


class Walk:
    """The walk along the path: the state of the continuation and one point's step.

    :meth:`step` is the policy at one path point (continuation from the last
    solved point, else the root search); :meth:`accept` records points the
    batched walk solved at once, exactly as :meth:`step` would have.
    """

    def __init__(self, problem: Problem, n_points: int, u_assembly: np.ndarray):
        n = len(u_assembly)
        self.problem = problem
        self.u_assembly = u_assembly
        self.sol = Solution(np.full((n_points, n), np.nan), np.full(n_points, np.nan))
        _, J = problem.evaluate(u_assembly, problem.at(0))
        self.sign = _det_sign(J)
        self.last = None  # (point index, u, inputs or None until needed) of the last solved point
        self.before = None  # u at the point before ``last`` when consecutive with it
        self.stop = None  # the configuration where the continuation stopped (a limit)
        self.stretch = None  # first point of the continuous stretch that ends at ``last``
        self.jumped = None  # the last point reached by a root search, not by continuation

    def last_inputs(self):
        i, u, ctx = self.last
        if ctx is None:
            ctx = self.problem.at(i)
            self.last = (i, u, ctx)
        return ctx

    def search_from(self):
        """``(ref, others)`` of a root search now: the configuration where the branch
        ended (resolution-independent up to the bisection), else the last solved
        one, else the assembly; and the last solved one and the assembly."""
        last = self.last
        ref = self.stop if self.stop is not None else (
            last[1] if last is not None else self.u_assembly)
        others = ([last[1]] if last is not None else []) + [self.u_assembly]
        return ref, others

    def fail(self, i: int, failure) -> None:
        """Record that point ``i`` has no solution in the assembly mode."""
        self.sol.failures[i] = failure
        self.before = None

    def step(self, i: int) -> None:
        """Solve path point ``i`` by the policy, from the state left by point ``i - 1``."""
        problem, sol, last, sign = self.problem, self.sol, self.last, self.sign
        ctx = problem.at(i)
        if ctx is None:  # an upstream group failed here; reported there
            return
        limit = None
        ok = False
        if i == 0:
            u, res, J = newton(problem, self.u_assembly.copy(), ctx)
            ok = res <= TOL and _det_sign(J) == sign
        elif last is not None and last[0] == i - 1:
            u, J, limit = continue_to(problem, last[1], self.last_inputs(), ctx, sign, self.before)
            ok = limit is None
            self.stop = None if ok else u
        if not ok:
            # no continuous path from the last solved point (a gap, or a limit or
            # singular position passed in this interval): every root near the known
            # configurations, in the assembly mode's determinant sign
            ref, others = self.search_from()
            same, other = roots_near(problem, ctx, ref, others, sign)
            if same:
                u, J = same[0]
                ok = True
                self.jumped = i
                if not (limit == 0.0 and _turned_continuation(problem, last[1], self.last_inputs(),
                                                              ctx, sign, u)):
                    sol.notes.append((i, limit, len(same)))
            elif limit is not None:
                sol.failures[i] = ("limit", limit)
            else:
                sol.failures[i] = ("other_mode", len(other)) if other else ("no_root", None)
        if not ok:
            self.before = None
            return
        sol.indicator[i] = indicator(J[None])[0]
        sol.u[i] = u
        # the predictor extrapolates only along a continuous stretch
        continued = i > 0 and last is not None and last[0] == i - 1 and self.jumped != i
        self.before = last[1] if continued else None
        if not continued:
            self.stretch = i
        self.last = (i, u, ctx)

    def accept(self, idx: np.ndarray, U: np.ndarray, ind: np.ndarray) -> None:
        """Record the consecutive points ``idx`` (the first one after ``last``), each
        reached from the one before it by :func:`continue_to`'s direct step, with its
        indicator."""
        self.sol.u[idx] = U
        self.sol.indicator[idx] = ind
        self.before = U[-2] if len(idx) > 1 else self.last[1]
        self.last = (int(idx[-1]), U[-1], None)
        self.stop = None


def solve_path(problem: Problem, n_points: int, u_assembly: np.ndarray,
               batched: bool | None = None) -> Solution:
    """Solve the group at every path point (point 0 is the assembly configuration's inputs).

    Raises nothing for points without a solution: they are listed in
    ``Solution.failures``; jumps after a limit or a gap are listed in
    ``Solution.notes``; the caller words the messages.

    ``batched`` (default :data:`BATCHED`): solve continuous stretches many
    points at once (:func:`linkage_sym.numeric.batched_path.walk_path`), with the
    same results as the point-by-point walk; ``False`` walks point by point.
    """
    walk = Walk(problem, n_points, u_assembly)
    if batched is None:
        batched = BATCHED
    if batched and hasattr(problem, "evaluate_points"):
        from linkage_sym.numeric import batched_path  # it builds on this module

        batched_path.walk_path(walk, n_points)
    else:
        for i in range(n_points):
            walk.step(i)
    return walk.sol


def failure_message(label: str, links, failure, where) -> str:
    """The message of a path point the continuation could not solve (both runtimes).

    ``where(t)`` words the driver values a fraction ``t`` of the way from the
    previous path point to this one (e.g. ``"A = 123.45 deg"``).
    """
    head = f"{label} ({', '.join(links)})"
    kind, detail = failure
    if kind == "limit":
        return (
            f"{head}: reaches a limit or singular position at {where(detail)} and no solution "
            "in the assembly mode exists past it: the group cannot be assembled here"
        )
    if kind == "other_mode":
        return (
            f"{head}: the only solution(s) found ({detail}) are in the other assembly mode "
            "(determinant sign of the group's Jacobian); not accepted"
        )
    return f"{head}: Newton on the group's loop equations finds no solution: the group cannot be assembled here"


def note_message(label: str, links, note, step_text: str, where) -> str:
    """The warning of a point reached without a continuous path (both runtimes)."""
    _, limit, n_same = note
    head = f"{label} ({', '.join(links)})"
    how = (
        f"passes a limit or singular position at {where(limit)}"
        if limit is not None
        else "re-enters after steps that cannot be assembled"
    )
    text = (
        f"{head} {how}; at {step_text} it continues in the assembly mode (determinant sign), "
        "nearest to the last solved configuration"
    )
    if n_same > 1:
        text += f": the assembly mode is ambiguous there ({n_same} solutions with that sign)"
    return text


def driver_values_text(q: dict, kinds: dict, i: int, t: float | None = None) -> str:
    """Driver values at path point ``i`` (or a fraction ``t`` of the way from ``i - 1``), worded.

    ``q`` maps each driven joint to its values along the path, ``kinds`` to
    ``"R"`` (an angle, printed in degrees) or ``"P"`` (a slide, in metres).
    """
    parts = []
    for name, v in q.items():
        x = float(v[i]) if t is None or i == 0 else float(v[i - 1] + t * (v[i] - v[i - 1]))
        parts.append(f"{name} = {math.degrees(x):.6g} deg" if kinds[name] == "R" else f"{name} = {x:.6g} m")
    return ", ".join(parts)


def step_warnings(notes, step_points) -> list[str]:
    """Warnings of the Newton groups' jumps (a limit passed, a re-entry after a gap).

    ``notes`` are ``(path point, text(step))`` pairs; ``step_points`` the path
    point of every step, increasing.  A jump between two steps is reported at
    the step after it.
    """
    out = []
    step_points = np.asarray(step_points)
    for p, text in notes:
        k = int(np.searchsorted(step_points, p))
        if k >= len(step_points):
            continue  # on the way to the first step only: no step sees it
        where = f"step {k}" if step_points[k] == p else f"step {k} (reached from step {k - 1})"
        if k == 0 and step_points[0] != p:
            where = "step 0 (reached from the assembly configuration)"
        out.append(text(where))
    return out
