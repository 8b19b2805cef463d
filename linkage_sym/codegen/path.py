"""A compiled mechanism's positions along a run's solving path (NumPy only).

The runtime (:class:`~linkage_sym.codegen.runtime.CompiledMechanism`) walks the position
steps over every point of the solving path at once (:meth:`Evaluator.walk
<linkage_sym.codegen.evaluator.Evaluator.walk>` with a :class:`PathContext`); a group
without a closed form is a :class:`GroupPathProblem` for the continuation policy both
runtimes share (:func:`linkage_sym.numeric.continuation.solve_path`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["GroupPathProblem", "PathContext"]


class PathContext:
    """What the position steps of a run read: the parameters, the driver values along the
    solving path (a list, and the (D, K) array), and each path point's first failing group."""

    def __init__(self, P, Q, Qpath, K, failed):
        self.P, self.Q, self.Qpath, self.K, self.failed = P, Q, Qpath, K, failed


class GroupPathProblem:
    """A group without a closed form in the derived coordinates (angles, slides), for
    :func:`continuation.solve_path`: unknowns over the scale (slides over ``L``),
    residual rows over their scale (loop projections over ``L``)."""

    def __init__(self, cm, step, group, X, Qpath, failed):
        self.f = cm.functions[step.function]
        self.params = cm.params
        self.cols = list(step.x)
        self.n = len(self.cols)
        self.m = cm.m
        self.X = X
        self.Q = Qpath
        self.failed = failed
        self.known = [c for c in range(cm.m) if X[c] is not None]
        self.scale = np.where(cm.is_angle[self.cols], 1.0, cm.L)
        self.angles = cm.is_angle[self.cols]
        r0, r1 = group.rows
        self.row_scale = np.where(np.array(cm.art.rows_length[r0:r1], bool), 1.0 / cm.L, 1.0)

    def at(self, i):
        if self.failed[i] >= 0:
            return None
        return self.Q[:, i], np.array([self.X[c][i] for c in self.known])

    def blend(self, a, b, t):
        return (1 - t) * a[0] + t * b[0], (1 - t) * a[1] + t * b[1]

    def available(self):
        return self.failed < 0

    def evaluate(self, u, ctx):
        r, J = self.evaluate_many(u[None, :], ctx)
        return r[0], J[0]

    def evaluate_points(self, U, idx):
        """Rows of ``U`` at the path points ``idx`` (drivers and known coordinates there)."""
        return self.evaluate_many(U, (self.Q[:, idx], [self.X[c][idx] for c in self.known]))

    def evaluate_many(self, U, ctx):
        q, xk = ctx
        k = len(U)
        Xs = [None] * self.m
        for c, v in zip(self.known, xk):
            Xs[c] = v
        for c, v in zip(self.cols, (U * self.scale).T):
            Xs[c] = v
        out = self.f(Xs, None, None, list(q), None, None, None, self.params)
        n = self.n
        vals = np.empty((len(out), k))
        for i, v in enumerate(out):
            vals[i] = v
        R = vals[:n].T * self.row_scale
        J = vals[n:].T.reshape(k, n, n) * self.row_scale[:, None] * self.scale[None, :]
        return R, J
