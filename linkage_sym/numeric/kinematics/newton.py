"""Newton solver of a group's own loop equations (class-III and other groups).

Positions: the group's constraint equations in pose coordinates, solved along
the path from the assembly configuration by the continuation policy both
runtimes share (:mod:`linkage_sym.numeric.continuation`: predictor, damped
Newton, the assembly mode's determinant sign, bisected sub-steps, limits
located, re-entry after a gap by deflation, ambiguous modes reported).

Velocities and accelerations: the group's linear systems ``J v = r``, solved
for all steps at once (``numpy.linalg.solve`` on stacked matrices).
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND
from linkage_sym.numeric import continuation
from linkage_sym.numeric.continuation import batched_path
from linkage_sym.numeric.continuation import messages as continuation_messages
from linkage_sym.numeric.kinematics.constraints import jacobian, stack_rows
from linkage_sym.numeric.kinematics.state import LinkState
from linkage_sym.numeric.results.jumps import JumpNote

SINGULAR_IND = 1e-14
"""Indicator (reciprocal condition of the group block) below which no rate is solved."""


def above_ratio(J: np.ndarray, threshold: float) -> np.ndarray:
    """Whether ``sigma_min / sigma_max > threshold`` for every matrix of ``J`` (k, n, n).

    ``sigma_min sigma_max^(n-1) >= |det J|`` and ``sigma_max <= |J|_F``, so
    ``sigma_min / sigma_max >= |det J| / |J|_F^n``: where that bound clears
    twice the threshold (every step but nearly singular ones) the matrix is
    above it without its singular values; the others are decided by
    :func:`~linkage_sym.numeric.continuation.batched_path.singular_value_ratio`.  (The
    rate stages' screen: a determinant costs a fifth of the eigenvalues.)
    """
    sign, logdet = np.linalg.slogdet(J)
    with np.errstate(divide="ignore"):
        lognorm = np.log(np.linalg.norm(J, axis=(1, 2)))
    out = (sign != 0) & (logdet - J.shape[-1] * lognorm > math.log(2 * threshold))
    unsure = np.flatnonzero(~out)
    if len(unsure):
        out[unsure] = batched_path.singular_value_ratio(J[unsure]) > threshold
    return out


class NewtonSolver:
    """Solver of any group by Newton's method on its own equations."""

    wraps = False  # followed continuously from the assembly configuration

    def __init__(self, scene, group, constraints, L):
        self.group = group
        self.links = group.links
        self.L = L
        cons = []
        for name in group.joints:
            cons.append(constraints[name].joint)
        for name in group.drivers:
            cons.append(constraints[name].driver)
        self.cons = cons
        self.nvar = 3 * len(self.links)
        self.length_rows = np.concatenate([c.length_rows for c in cons])
        # assembly configuration: every link at the identity pose
        S = {n: LinkState() for n in scene.link_names}
        S["ground"] = LinkState()
        J = jacobian(cons, S, self.links, 1, L)[0]
        sv = np.linalg.svd(J, compute_uv=False)
        if sv[-1] <= 1e-10 * sv[0]:
            raise SceneError(
                [
                    f"joints: the assembly configuration is a singular position of the "
                    f"{group.label} ({', '.join(self.links)}): its assembly mode is undefined"
                ]
            )
        self.det_sign = float(np.sign(np.linalg.det(J)))
        self.driver_kinds = {d.joint: scene.joint(d.joint).type for d in scene.drivers}
        self.notes = []
        # the links whose poses enter the group's equations (its own and those it is attached to)
        self._involved = [n for n in [GROUND, *scene.link_names]
                          if any(c.involves(n) for c in cons)]
        self._rates_cache = None

    # -- positions -----------------------------------------------------------
    def position(self, S, q):
        """Poses of the group's links at every path point (continuation policy:
        :mod:`linkage_sym.numeric.continuation`); returns the indicator."""
        n_steps = len(next(iter(q.values())))
        self._rates_cache = None
        problem = self._problem(S, q)
        sol = continuation.solve_path(problem, n_steps, np.zeros(self.nvar))
        kinds = {k: self.driver_kinds.get(k, "R") for k in q}
        where = lambda i: lambda t: continuation_messages.driver_values_text(q, kinds, i, t)  # noqa: E731
        self.messages = {
            i: continuation_messages.failure_message(self.group.label, self.links, f, where(i))
            for i, f in sol.failures.items()
        }
        self.notes = [
            JumpNote(i, lambda step, n=n, i=i: continuation_messages.note_message(
                self.group.label, self.links, n, step, where(i)),
                self.group.label, tuple(self.links), n[1] is not None)
            for n in sol.notes
            for i in [n[0]]
        ]
        self._set_poses(S, problem, sol)
        return sol.indicator

    def _problem(self, S, q):
        return PoseProblem(self, S, q)

    def _set_poses(self, S, problem, sol):
        out = sol.u * problem.scale
        for k, n in enumerate(self.links):
            S[n].set_pose(out[:, 3 * k + 2], out[:, 3 * k], out[:, 3 * k + 1])

    def failure(self, S, i) -> str:
        return self.messages.get(
            i, f"{self.group.label} ({', '.join(self.links)}): cannot be assembled"
        )


    # -- rates ---------------------------------------------------------------
    def _rate_block(self, S, n_steps):
        """The group block ``J`` of the rate problems at the poses of ``S``, and the
        steps where it is solvable; computed once for the velocities and the
        accelerations (the same poses: the same arrays)."""
        poses = [getattr(S[n], a) for n in self._involved for a in ("th", "dx", "dy")]
        cached = self._rates_cache
        if cached is not None and all(a is b for a, b in zip(cached[0], poses)):
            return cached[1], cached[2]
        J = jacobian(self.cons, S, self.links, n_steps)
        solvable = np.isfinite(J).all(axis=(1, 2))
        if solvable.any():
            # steps whose group block is (numerically) singular get no rates; judged on
            # the dimensionless block (rows over L, translation columns times L), so a
            # mechanism's size does not decide it
            row = np.where(self.length_rows, 1.0 / self.L, 1.0)
            col = np.tile([self.L, self.L, 1.0], len(self.links))
            good = np.flatnonzero(solvable)
            solvable[good] = above_ratio(J[good] * row[:, None] * col[None, :], SINGULAR_IND)
        self._rates_cache = (poses, J, solvable)
        return J, solvable

    def _solve_rates(self, S, rows_fn, attrs):
        n_steps = len(np.atleast_1d(S[self.links[0]].dx))
        for n in self.links:
            for a in attrs:
                setattr(S[n], a, 0.0)
        rhs = -stack_rows([v for c in self.cons for v in rows_fn(c)])
        rhs = np.broadcast_to(rhs, (n_steps, rhs.shape[-1]))
        J, solvable = self._rate_block(S, n_steps)
        x = np.full((n_steps, self.nvar), np.nan)
        idx = np.flatnonzero(solvable & np.isfinite(rhs).all(axis=1))
        if len(idx):
            x[idx] = np.linalg.solve(J[idx], rhs[idx][..., None])[..., 0]
        for k, n in enumerate(self.links):
            for m, a in enumerate(attrs):
                setattr(S[n], a, x[:, 3 * k + (2 if m == 0 else m - 1)])

    def velocity(self, S, q, qd):
        self._solve_rates(S, lambda c: c.rate(S, qd), ("w", "vx", "vy"))

    def acceleration(self, S, q, qd, qdd):
        self._solve_rates(S, lambda c: c.accel(S, qdd), ("al", "ax", "ay"))
        self._rates_cache = None  # the last rate stage: its block is not needed any more


class PoseProblem:
    """A Newton group in pose coordinates, for :func:`continuation.solve_path`.

    Unknowns ``u``: each link's ``(dx / L, dy / L, theta)``; inputs at a path
    point: the poses of the links the group is attached to and the drivers.
    """

    def __init__(self, solver: NewtonSolver, S, q):
        self.sv = solver
        self.q = q
        self.known = {
            n: st for n, st in S.items()
            if n not in solver.links and any(c.involves(n) for c in solver.cons)
        }
        self.local = {n: LinkState() for n in solver.links}
        self.scale = np.tile([solver.L, solver.L, 1.0], len(solver.links))
        self.angles = np.tile([False, False, True], len(solver.links))
        self.row_scale = np.where(solver.length_rows, 1.0 / solver.L, 1.0)

    def at(self, i):
        Si = {n: st.take(i) for n, st in self.known.items()}
        if any(not np.isfinite(st.dx) for st in Si.values()):
            return None
        return Si, {k: v[i] for k, v in self.q.items()}

    def blend(self, a, b, t):
        Sa, qa = a
        Sb, qb = b
        S = {
            n: LinkState((1 - t) * x.th + t * Sb[n].th, (1 - t) * x.dx + t * Sb[n].dx,
                         (1 - t) * x.dy + t * Sb[n].dy)
            for n, x in Sa.items()
        }
        return S, {k: (1 - t) * v + t * qb[k] for k, v in qa.items()}

    def available(self):
        ok = np.ones(len(next(iter(self.q.values()))), bool)
        for st in self.known.values():
            ok &= np.isfinite(st.dx)
        return ok

    def evaluate(self, u, ctx):
        r, J = self.evaluate_many(u[None, :], ctx)
        return r[0], J[0]

    def evaluate_points(self, U, idx):
        """Rows of ``U`` at the path points ``idx``: the known poses and drivers taken there."""
        Sk = {n: st.take(idx) for n, st in self.known.items()}
        return self.evaluate_many(U, (Sk, {k: v[idx] for k, v in self.q.items()}))

    def evaluate_many(self, U, ctx):
        Sk, qk = ctx
        S = dict(Sk)
        S.update(self.local)
        Z = U * self.scale
        for k, n in enumerate(self.sv.links):
            S[n].set_pose(Z[:, 3 * k + 2], Z[:, 3 * k], Z[:, 3 * k + 1])
        R = stack_rows([v for c in self.sv.cons for v in c.residual(S, qk)])
        R = np.broadcast_to(R, (len(U), R.shape[-1])) * self.row_scale
        J = jacobian(self.sv.cons, S, self.sv.links, len(U), self.sv.L)
        return R, J
