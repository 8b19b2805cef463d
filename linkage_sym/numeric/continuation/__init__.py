"""The one continuation policy of groups solved by Newton's method (NumPy only).

Class-III triads, driven (actuator) groups and every other group without a
closed form are solved by Newton's method on their own loop equations, step
after step along the solving path.  Both runtimes -- the numeric plan
(:mod:`linkage_sym.numeric.kinematics.newton`, pose coordinates) and the compiled
symbolic mechanism (:mod:`linkage_sym.codegen.runtime`, the derived angles
and slides) -- hand this module a :class:`~.roots.Problem` and get the same policy:

* **Continuity.**  A path point is reached from the previous solved one by
  natural-parameter continuation: a predictor (linear from the two previous
  points, when they are consecutive), damped Newton to a scaled residual of
  :data:`~.roots.TOL`, and the solution is *accepted* only if it keeps the assembly
  configuration's Jacobian-determinant sign and lies within
  :data:`~.roots.MAX_CORRECTION` (dimensionless: radians, lengths over the
  mechanism's size) of the predictor.  Otherwise the interval is bisected
  (adaptive sub-steps, down to :data:`~.roots.MIN_FRACTION` of it).  A solution is
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
  its angles): Newton with a bounded step (:data:`~.roots.SEARCH_STEP`) from each.
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
hands continuous stretches and gaps to :mod:`linkage_sym.numeric.continuation.batched_path`,
which evaluates this policy on blocks of points (the same predictors, the
same Newton iteration, the same acceptance test and root searches) and
leaves every point where the direct step is not taken to :meth:`Walk.step`:
the results are the point-by-point walk's (tested against it).

Everything is dimensionless: a :class:`~.roots.Problem` evaluates the scaled
residual (length rows over the mechanism size ``L``) and its Jacobian with
respect to the scaled unknowns ``u`` (lengths over ``L``, angles as they
are).

This package's own module is the walk (:class:`Walk`, :func:`solve_path`); its
pieces are :mod:`~.roots` (Newton's iteration, its constants and the root
searches), :mod:`~.batched_path` (many points at once) and :mod:`~.messages`
(the failures and jumps worded alike by both runtimes).
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.numeric.continuation.roots import (  # noqa: F401 -- the policy's names, used by both runtimes
    SAME_ROOT,
    TOL,
    Problem,
    Solution,
    continue_to,
    det_sign,
    indicator,
    newton,
    roots_near,
)


BATCHED = True
"""Whether :func:`solve_path` solves continuous stretches many points at once
(:mod:`linkage_sym.numeric.continuation.batched_path`: the same policy and the same results)
or point after point.  The point-by-point walk stays for comparison and for
problems without :meth:`Problem.evaluate_points`."""


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
            if float(np.linalg.norm(rw)) <= TOL and det_sign(Jw) == sign:
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
        self.sign = det_sign(J)
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
            ok = res <= TOL and det_sign(J) == sign
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
    points at once (:func:`linkage_sym.numeric.continuation.batched_path.walk_path`), with the
    same results as the point-by-point walk; ``False`` walks point by point.
    """
    walk = Walk(problem, n_points, u_assembly)
    if batched is None:
        batched = BATCHED
    if batched and hasattr(problem, "evaluate_points"):
        from linkage_sym.numeric.continuation import batched_path  # it builds on this module

        batched_path.walk_path(walk, n_points)
    else:
        for i in range(n_points):
            walk.step(i)
    return walk.sol
