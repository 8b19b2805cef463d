"""Designs whose groups have no closed form: one design at a time.

Class-III triads, driven (actuator) groups and every other group without a
closed form are solved by Newton continuation, step after step; a chunk of
such designs is not one vectorised call.  Each design is then

1. **assembled** at the scene's driver values ``q0``: the closed forms as for
   every design (many designs per call), each Newton group by continuation
   *in the parameters* from the scene's own assembly configuration to the
   design's (:class:`ParameterContinuation`: the inputs of the group -- the
   parameters, the coordinates solved before it -- blended from the scene's
   to the design's, every sub-step by the continuation policy the runtimes
   share, :func:`linkage_sym.numeric.continuation.continue_to`: damped Newton,
   the assembly configuration's Jacobian-determinant sign kept, bisected
   where a root is not within reach of its predictor).  The design's assembly
   mode is therefore the one reached continuously from the scene's; a design
   the continuation cannot reach cannot be assembled (every metric empty);
2. **solved** by the numeric plan of its own scene (the one ``--write-scenes``
   writes, :func:`~linkage_sym.design.scenes.design_scene`):
   ``compile_plan(scene).run()``, the Newton continuation from that
   design's assembly configuration over the scene's sweep, with the forces
   when a metric needs them; for ``K`` and ``swing`` a second run of its
   kinematics with the rates along the steps (``qd = dq/dt``, ``qdd = 0``,
   as :func:`linkage_sym.numeric.extremes.find_extremes` does), which also
   evaluates it between the steps where a limit position is located;
3. **measured** by the same metric code as every design
   (:class:`~linkage_sym.design.metrics.MetricPlan` on a
   :class:`PlanSolution`: the same arrays, read from the plan's result).

Chunks are whole designs and each design's numbers are its own, so the
table does not depend on the chunks or on who ran them.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from linkage_sym.codegen.path import ScaledGroup
from linkage_sym.design.solution import Solution
from linkage_sym.model import OUTPUTS
from linkage_sym.numeric import continuation
from linkage_sym.numeric.results.result import OK, SELF_LOCKING, UNASSEMBLABLE

__all__ = ["ParameterContinuation", "PlanSolution", "solve_designs", "DEFAULT_CHUNK"]

DEFAULT_CHUNK = 8
"""Designs per chunk of a sweep whose designs run one at a time (a progress bar that
moves, and chunks small enough to share among workers)."""


class ParameterContinuation(ScaledGroup):
    """One Newton group of a compiled mechanism at fixed driver values, its inputs
    ``(P, Q, known coordinates)`` blended between two designs: a
    :class:`linkage_sym.numeric.continuation.Problem` (scaled unknowns: slides over the
    size ``L``; scaled rows: loop projections over ``L``)."""

    def __init__(self, model, step):
        cm, art = model.cm, model.art
        k = art.steps.index(step)
        super().__init__(model, step, [c for st in art.steps[:k] for c in st.x], cm.L)
        # the scene's own assembly configuration: where every design's continuation starts
        self.u_scene = cm.x0[self.cols] / self.scale
        self.ctx_scene = (np.array(model.params, float), np.array(model.q0, float),
                          cm.x0[self.known].astype(float))
        _, J = self.evaluate(self.u_scene, self.ctx_scene)
        self.sign = float(np.sign(np.linalg.det(J)))

    def blend(self, a, b, t):
        return tuple((1 - t) * x + t * y for x, y in zip(a, b))

    def evaluate_many(self, U, ctx):
        P, Q, xk = ctx
        return self.scaled(U, list(P), Q, xk)

    def solve(self, P, Q, X, n, start=None):
        """The group's coordinates (len(cols), n) for ``n`` designs (parameters ``P``,
        driver values ``Q``, the coordinates ``X`` solved before it), each continued from
        ``start(d) -> (u, ctx)`` (default: the scene's assembly configuration); NaN where
        the continuation does not reach the design.  Also the designs' inputs."""
        out = np.full((self.n, n), np.nan)
        ctxs = [None] * n
        for d in range(n):
            xk = np.array([float(X[c][d]) if np.ndim(X[c]) else float(X[c]) for c in self.known])
            if not np.all(np.isfinite(xk)):
                continue
            Pd = np.array([float(v[d]) if np.ndim(v) else float(v) for v in P])
            ctx = (Pd, np.array([float(q[d]) for q in Q]), xk)
            ctxs[d] = ctx
            u0, ctx0 = (self.u_scene, self.ctx_scene) if start is None else start(d)
            if u0 is None:
                continue
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                u, J, _ = continuation.continue_to(self, u0, ctx0, ctx, self.sign)
            if J is not None:
                out[:, d] = u * self.scale
        return out, ctxs


@dataclasses.dataclass
class PlanSolution(Solution):
    """A chunk's designs solved one at a time by the numeric plan: the arrays of a
    :class:`~linkage_sym.design.solution.Solution` (angles only in ``X``, ``rate_t`` and
    ``XDD``; slides are not read by any metric) and the plan's own forces and points."""

    model_rates = False  # rate_at runs each design's plan

    runs: list = dataclasses.field(default_factory=list)  # per design: its result or None
    kin: list = dataclasses.field(default_factory=list)  # per design: (kinematics plan, link)

    def _stack(self, get):
        out = np.full((self.n, self.N), np.nan)
        for d, r in enumerate(self.runs):
            if r is not None:
                out[d] = get(r)
        return out

    def reaction(self, joint):
        return self._stack(lambda r: np.hypot(*r.forces.reactions[joint].T))

    def effort(self, driver):
        return self._stack(lambda r: r.forces.driving[driver])

    def com(self, link):
        return (self._stack(lambda r: r.links[link].com[:, 0]),
                self._stack(lambda r: r.links[link].com[:, 1]),
                self._stack(lambda r: r.links[link].com_acceleration[:, 0]),
                self._stack(lambda r: r.links[link].com_acceleration[:, 1]))

    def alpha(self, link):
        return self._stack(lambda r: r.links[link].alpha)

    def traced(self, point):
        x = self._stack(lambda r: r.points[point].position[:, 0])
        y = self._stack(lambda r: r.points[point].position[:, 1])
        return np.where(self.pos_ok, x, np.nan), np.where(self.pos_ok, y, np.nan)

    def rate_at(self, d, t, col):
        """As :meth:`Model.rate_at`: each design's kinematics plan run at its points ``t``
        (sorted; the path from its assembly configuration through them)."""
        model = self.model
        rate, drate, value = (np.full(len(t), np.nan) for _ in range(3))
        link = next(k for k, c in model.angle_of.items() if c == col)
        for k in np.unique(d):
            sel = np.flatnonzero((d == k) & np.isfinite(t))  # NaN: a root not found
            uniq, inv = np.unique(t[sel], return_inverse=True)
            plan = self.kin[k]
            r = plan.run(*_rates_along(model, uniq))
            ok = np.isin(r.status, (OK, SELF_LOCKING))  # kinematics solved at both
            lk = r.links[link]
            rate[sel] = np.where(ok, lk.omega, np.nan)[inv]
            drate[sel] = np.where(ok, lk.alpha, np.nan)[inv]
            value[sel] = np.where(ok, self.X0[col, k] + lk.rotation, np.nan)[inv]
        return rate, drate, value


def _rates_along(model, t):
    """Driver values at fractional steps ``t`` with the rates along the steps
    (``qd = dq/dt``, ``qdd = 0``): dicts for ``Plan.run``."""
    q, qd, qdd = dict(zip(model.art.q, model.drivers_at(t))), {}, {}
    for k, name in enumerate(model.art.q):
        qd[name] = np.full(len(t), model.slope[k])
        qdd[name] = np.zeros(len(t))
    return q, qd, qdd


def solve_designs(model, P, n, need) -> PlanSolution:
    """Solve ``n`` designs one at a time (see the module docstring); ``need`` as
    :meth:`Model.solve`'s."""
    from linkage_sym.design.scenes import design_scene
    from linkage_sym.numeric.plan import compile_plan

    P, X0, assembled, joints0, L = model.assemble(P, n)
    N, m = model.N, model.m
    X = np.full((m, n, N), np.nan)
    rate_t = np.full((m, n, N), np.nan) if "rate_t" in need else None
    status = np.full((n, N), UNASSEMBLABLE, dtype=object)
    runs, kin = [None] * n, [None] * n
    stages = need & {"forces", "points"}
    outputs = OUTPUTS if "forces" in need else ("kinematics",)
    for d in np.flatnonzero(assembled):
        scene = design_scene(model, P, X0, joints0, int(d), f"{model.scene.name}-design")
        res = None
        if stages or rate_t is None:
            res = compile_plan(dataclasses.replace(scene, outputs=outputs)).run()
        if rate_t is not None:
            kplan = compile_plan(dataclasses.replace(scene, outputs=("kinematics",)))
            rk = kplan.run(*_rates_along(model, np.arange(N, dtype=float)))
            kin[d] = kplan
            for lk, c in model.angle_of.items():
                rate_t[c, d] = rk.links[lk].omega
            res = res if res is not None else rk
        runs[d] = res
        status[d] = res.status
        for lk, c in model.angle_of.items():
            X[c, d] = X0[c, d] + res.links[lk].rotation
    locked = status == SELF_LOCKING  # ok kinematically, as Model.solve counts it
    ok = (status == OK) | locked
    pos_ok = status != UNASSEMBLABLE
    X[:, ~pos_ok] = np.nan
    with np.errstate(invalid="ignore"):
        C, S = np.cos(X), np.sin(X)
    return PlanSolution(n, N, P, assembled, X0, joints0, L, X, pos_ok, ok, rate_t=rate_t,
                        C=C, S=S, model=model, runs=runs, kin=kin,
                        locked=locked if "forces" in need else None)
