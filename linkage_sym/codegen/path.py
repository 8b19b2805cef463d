"""A compiled mechanism's positions along a run's solving path (NumPy only).

The runtime (:class:`~linkage_sym.codegen.runtime.CompiledMechanism`) walks the position
steps over every point of the solving path at once (:meth:`Evaluator.walk
<linkage_sym.codegen.evaluator.Evaluator.walk>` with a :class:`PathContext`); a group
without a closed form is a :class:`GroupPathProblem` for the continuation policy both
runtimes share (:func:`linkage_sym.numeric.continuation.solve_path`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["GroupPathProblem", "PathContext", "ScaledGroup"]


class PathContext:
    """What the position steps of a run read: the parameters, the driver values along the
    solving path (a list, and the (D, K) array), and each path point's first failing group."""

    def __init__(self, P, Q, Qpath, K, failed):
        self.P, self.Q, self.Qpath, self.K, self.failed = P, Q, Qpath, K, failed


class ScaledGroup:
    """A Newton step's generated function (residuals, then the Jacobian row by row) as a
    problem in scaled unknowns and rows, for :mod:`linkage_sym.numeric.continuation`:
    slides over the size ``L``, loop projections over ``L``.  The runtime's path problem
    (:class:`GroupPathProblem`) and the design sweep's parameter continuation
    (:class:`linkage_sym.design.newton_groups.ParameterContinuation`) are this one
    evaluation with their own inputs.

    Parameters
    ----------
    evaluator : Evaluator
        Its ``functions`` and ``art``.
    step : NewtonStep
    known : list of int
        The coordinates solved before the step (the function reads them).
    L : float
        The mechanism's size.
    """

    def __init__(self, evaluator, step, known, L):
        art = evaluator.art
        self.f = evaluator.functions[step.function]
        self.cols = list(step.x)
        self.n = len(self.cols)
        self.m = evaluator.m
        self.known = known
        self.scale = np.where(art.is_angle[self.cols], 1.0, L)
        self.angles = art.is_angle[self.cols]
        r0, r1 = art.group(step.group).rows
        self.row_scale = np.where(np.array(art.rows_length[r0:r1], bool), 1.0 / L, 1.0)

    def evaluate(self, u, ctx):
        r, J = self.evaluate_many(np.asarray(u, float)[None, :], ctx)
        return r[0], J[0]

    def scaled(self, U, P, Q, xk):
        """Scaled residuals (k, n) and Jacobians (k, n, n) at the rows of ``U`` (scaled
        unknowns), with parameters ``P``, driver values ``Q`` and the known coordinates
        ``xk`` (each a number or a row over the ``k`` points)."""
        k = len(U)
        Xs = [None] * self.m
        for c, v in zip(self.known, xk):
            Xs[c] = v
        for c, v in zip(self.cols, (U * self.scale).T):
            Xs[c] = v
        out = self.f(Xs, None, None, list(Q), None, None, None, P)
        n = self.n
        vals = np.empty((len(out), k))
        for i, v in enumerate(out):
            vals[i] = v
        R = vals[:n].T * self.row_scale
        J = vals[n:].T.reshape(k, n, n) * self.row_scale[:, None] * self.scale[None, :]
        return R, J


class GroupPathProblem(ScaledGroup):
    """A group without a closed form at every point of a run's solving path, for
    :func:`~linkage_sym.numeric.continuation.solve_path`: the path points' driver values
    and the coordinates solved before it are its inputs."""

    def __init__(self, cm, step, X, Qpath, failed):
        super().__init__(cm, step, [c for c in range(cm.m) if X[c] is not None], cm.L)
        self.params = cm.params
        self.X = X
        self.Q = Qpath
        self.failed = failed

    def at(self, i):
        if self.failed[i] >= 0:
            return None
        return self.Q[:, i], np.array([self.X[c][i] for c in self.known])

    def blend(self, a, b, t):
        return (1 - t) * a[0] + t * b[0], (1 - t) * a[1] + t * b[1]

    def available(self):
        return self.failed < 0

    def evaluate_points(self, U, idx):
        """Rows of ``U`` at the path points ``idx`` (drivers and known coordinates there)."""
        return self.evaluate_many(U, (self.Q[:, idx], [self.X[c][idx] for c in self.known]))

    def evaluate_many(self, U, ctx):
        q, xk = ctx
        return self.scaled(U, self.params, q, xk)
