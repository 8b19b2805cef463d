"""Newton solver of a group's own loop equations (class-III and other groups).

Positions: Newton–Raphson on the group's constraint equations, step after
step along the path from the assembly configuration, each step seeded by a
linear predictor from the two previous solutions; damped by step halving when
the residual grows.  Near a fold one step (or the predictor) can overshoot into
the other assembly mode: such a step is retried as a continuation in
sub-steps from the previous solution before it is given up.  A converged solution whose Jacobian determinant has the
other sign than in the assembly configuration is *not* accepted (that would
be a silent jump of assembly mode): the step is reported unassemblable with
the reason, and the next step is seeded from the last accepted one.

Velocities and accelerations: the group's linear systems ``J v = r``, solved
for all steps at once (``numpy.linalg.solve`` on stacked matrices).
"""

from __future__ import annotations

import numpy as np

from linkage_sym.errors import SceneError
from linkage_sym.numeric.constraints import jacobian, stack_rows
from linkage_sym.numeric.state import LinkState

TOL = 1e-13
"""Convergence: scaled residual norm (lengths over the mechanism size)."""
MAX_ITER = 40
STALL_ITER = 6
"""Give up when the residual has not halved over this many iterations."""
SUBSTEPS = 16
"""Sub-steps of the continuation retried when a step lands in the other mode or diverges."""
SINGULAR_IND = 1e-14
"""Indicator (reciprocal condition of the group block) below which no rate is solved."""


class NewtonSolver:
    """Solver of any group by Newton's method on its own equations."""

    def __init__(self, scene, group, constraints, L):
        self.group = group
        self.links = group.links
        self.L = L
        cons = []
        for name in group.joints:
            cons.append(constraints[name][0])
        for name in group.drivers:
            cons.append(constraints[name][1])
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

    # -- helpers -------------------------------------------------------------
    def _scaled_residual(self, S, q):
        r = np.atleast_2d(stack_rows([v for c in self.cons for v in c.residual(S, q)]))
        return r * np.where(self.length_rows, 1.0 / self.L, 1.0)

    def _set(self, S, z):
        for k, n in enumerate(self.links):
            S[n].set_pose(z[3 * k + 2], z[3 * k], z[3 * k + 1])

    # -- positions -----------------------------------------------------------
    def position(self, S, q):
        n_steps = len(next(iter(q.values())))
        known = {
            n: st for n, st in S.items() if n not in self.links and any(c.involves(n) for c in self.cons)
        }
        out = np.full((n_steps, self.nvar), np.nan)
        ind = np.full(n_steps, np.nan)
        self.messages = {}
        z_prev = np.zeros(self.nvar)  # the assembly configuration
        z_prev2 = None
        scale = np.tile([self.L, self.L, 1.0], len(self.links))
        local = {n: LinkState() for n in self.links}
        for i in range(n_steps):
            Si = {n: st.take(i) for n, st in known.items()}
            Si.update(local)
            qi = {k: v[i] for k, v in q.items()}
            if any(not np.isfinite(st.dx) for n, st in Si.items() if n in known):
                z_prev2 = None
                continue  # an upstream group failed here; reported there
            z = z_prev if z_prev2 is None else 2 * z_prev - z_prev2
            z, res, J = self._newton(Si, qi, z.copy(), scale)
            if (res > TOL or np.sign(np.linalg.det(J)) != self.det_sign) and i > 0 and (
                np.isfinite(out[i - 1, 0])
            ):
                # near a fold the predictor (or one long step) can overshoot into the
                # other mode: continue from the last solution in small sub-steps instead
                z, res, J = self._substeps(known, local, q, i, z_prev, scale)
            if res > TOL:
                self.messages[i] = (
                    f"{self.group.label} ({', '.join(self.links)}): Newton on the group's loop "
                    f"equations did not converge (scaled residual {res:.2e}): the group cannot be "
                    "assembled here"
                )
                z_prev2 = None
                continue
            if np.sign(np.linalg.det(J)) != self.det_sign:
                self.messages[i] = (
                    f"{self.group.label} ({', '.join(self.links)}): the only solution found near the "
                    "previous step is in the other assembly mode (the group passed through a "
                    "singular position); not accepted"
                )
                z_prev2 = None
                continue
            sv = np.linalg.svd(J, compute_uv=False)
            ind[i] = sv[-1] / sv[0]
            out[i] = z
            z_prev2 = z_prev if (i > 0 and np.isfinite(out[i - 1, 0])) else None
            z_prev = z
        for k, n in enumerate(self.links):
            S[n].set_pose(out[:, 3 * k + 2], out[:, 3 * k], out[:, 3 * k + 1])
        return ind

    def _substeps(self, known, local, q, i, z, scale, n_sub=SUBSTEPS):
        """Continuation from step ``i - 1`` (solution ``z``) to step ``i`` in ``n_sub`` sub-steps.

        The known links' poses and the drivers are interpolated linearly between
        the two steps: intermediate targets only need to be close to each other
        (a homotopy), the last one is step ``i`` exactly.  Every intermediate
        solution must stay in the assembly mode.
        """
        ends = {n: (st.take(i - 1), st.take(i)) for n, st in known.items()}
        for m in range(1, n_sub + 1):
            t = m / n_sub
            Si = dict(local)
            for n, (a, b) in ends.items():
                Si[n] = LinkState(
                    (1 - t) * a.th + t * b.th, (1 - t) * a.dx + t * b.dx, (1 - t) * a.dy + t * b.dy
                )
            qi = {k: (1 - t) * v[i - 1] + t * v[i] for k, v in q.items()}
            z, res, J = self._newton(Si, qi, z.copy(), scale)
            if res > TOL or np.sign(np.linalg.det(J)) != self.det_sign:
                break
        if m < n_sub:  # failed on the way: report what the direct attempt would
            Si = {n: b for n, (_, b) in ends.items()}
            Si.update(local)
            z, res, J = self._newton(Si, {k: v[i] for k, v in q.items()}, z.copy(), scale)
        return z, res, J

    def _newton(self, S, q, z, scale):
        self._set(S, z)
        r = self._scaled_residual(S, q)[0]
        res = np.linalg.norm(r)
        J = jacobian(self.cons, S, self.links, 1, self.L)[0]
        polished = False
        history = []
        for it in range(MAX_ITER):
            history.append(res)
            # no solution here: the residual stalls at the least-squares minimum
            if it >= STALL_ITER and res > TOL and res > 0.5 * history[-STALL_ITER]:
                break
            if res <= TOL:
                if polished:
                    break
                polished = True  # one more step: quadratic convergence to ~1e-16
            try:
                dz = np.linalg.solve(J, -r) * scale
            except np.linalg.LinAlgError:
                return z, np.inf, J
            step = 1.0
            while True:
                zn = z + step * dz
                self._set(S, zn)
                rn = self._scaled_residual(S, q)[0]
                resn = np.linalg.norm(rn)
                if resn < res or res <= TOL or step < 1e-4:
                    break
                step *= 0.5
            if res <= TOL and resn > res:
                self._set(S, z)
                break
            z, r, res = zn, rn, resn
            J = jacobian(self.cons, S, self.links, 1, self.L)[0]
        return z, res, J

    def failure(self, S, i) -> str:
        return self.messages.get(
            i, f"{self.group.label} ({', '.join(self.links)}): cannot be assembled"
        )

    # -- rates ---------------------------------------------------------------
    def _solve_rates(self, S, rows_fn, attrs):
        n_steps = len(np.atleast_1d(S[self.links[0]].dx))
        for n in self.links:
            for a in attrs:
                setattr(S[n], a, 0.0)
        rhs = -stack_rows([v for c in self.cons for v in rows_fn(c)])
        rhs = np.broadcast_to(rhs, (n_steps, rhs.shape[-1]))
        J = jacobian(self.cons, S, self.links, n_steps)
        x = np.full((n_steps, self.nvar), np.nan)
        good = np.isfinite(J).all(axis=(1, 2)) & np.isfinite(rhs).all(axis=1)
        if good.any():
            Jg = J[good]
            # steps whose group block is (numerically) singular get no rates
            sv = np.linalg.svd(Jg, compute_uv=False)
            ok = sv[:, -1] > SINGULAR_IND * sv[:, 0]
            idx = np.flatnonzero(good)[ok]
            x[idx] = np.linalg.solve(J[idx], rhs[idx][..., None])[..., 0]
        for k, n in enumerate(self.links):
            for m, a in enumerate(attrs):
                setattr(S[n], a, x[:, 3 * k + (2 if m == 0 else m - 1)])

    def velocity(self, S, q, qd):
        self._solve_rates(S, lambda c: c.rate(S, qd), ("w", "vx", "vy"))

    def acceleration(self, S, q, qd, qdd):
        self._solve_rates(S, lambda c: c.accel(S, qdd), ("al", "ax", "ay"))
