"""Solve many designs of one topology at once with the compiled mechanism's functions.

The compiled mechanism (:mod:`linkage_sym.codegen.runtime`) takes every named
parameter as an argument; passing arrays evaluates a whole chunk of designs in one
call of each generated function.  :class:`Model` is the designs' backend of the one
evaluator of generated code (:class:`~linkage_sym.codegen.evaluator.NumpyEvaluator`:
the calls, the walk over the position steps, the block solves
(:class:`~linkage_sym.codegen.blocks.BlockSystem`), the condition numbers, the force
blocks), its numbers arrays over designs x steps: (n, 1) parameters broadcast against
(N,) driver values, so that a value that does not depend on the design (the crank's
angle) is computed once per step.  For a chunk of designs :meth:`Model.solve` does
what ``CompiledMechanism.run`` does for one scene, with the same functions:

1. **the design's assembly configuration**: the closed forms at the scene's
   driver values ``q0`` with the scene's assembly-mode signs.  The assembly
   angles ``theta0_<link>`` (the constant angles of links joined by ``P``
   joints) are then the design's own: set to that configuration's angles and
   the closed forms evaluated again.  A design whose closed forms have no real
   root at ``q0`` cannot be assembled (every metric NaN, ``assemblable`` 0);
2. **positions** at the steps: the angles' cosines and sines by the closed steps'
   directions functions (the arctangents' arguments made a unit vector,
   :func:`~linkage_sym.codegen.evaluator.unit_direction`: no arctangent, no
   cosine), and the angles themselves only when a metric reads them (the swing,
   anything at the scene's speeds), along the scene's solving path
   (:func:`~linkage_sym.numeric.engine.run.solving_path`: from ``q0`` through the
   steps), unwrapped along it from the assembly configuration, as the runtimes do;
3. **the singularity screen**: each group block's Hadamard ratio against
   :data:`~linkage_sym.numeric.engine.run.SCREEN`
   (:meth:`~linkage_sym.codegen.blocks.BlockSystem.below`), then the dimensionless
   condition number (the design's own size) against
   :data:`~linkage_sym.numeric.engine.run.SINGULAR_COND`; a step is ``ok`` when it
   is assembled and not singular;
4. only what the metrics need: the velocities (along the sweep for limit
   positions, of the coordinates the metrics read; at the scene's speeds for forces),
   accelerations, the points
   function and the force blocks ``A_g F_g = b_g - C_g F_later`` from the last
   group back.

Every operation is elementwise per design or a per-matrix LAPACK call, and
chunks are made of whole designs: a design's numbers do not depend on the
chunk that carried it.  Groups without a closed form (class-III triads,
actuator groups) are continued from the scene's assembly configuration to each
design's, and such designs are then solved one at a time by the numeric plan
(:mod:`linkage_sym.design.newton_groups`).

Size: about 580 lines, one class -- :class:`Model` holds a chunk's broadcast
parameters, assembly signs and work arrays, which each of the four stages
above reads; the solved chunk (:class:`~linkage_sym.design.solution.Solution`),
the metrics (:mod:`~linkage_sym.design.metrics`) and the groups without a
closed form (:mod:`~linkage_sym.design.newton_groups`) are apart.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from linkage_sym.codegen.blocks import BlockSystem, full
from linkage_sym.codegen.evaluator import NumpyEvaluator, unit_direction
from linkage_sym.design.solution import Solution
from linkage_sym.design.unwrap import unwrap_fast
from linkage_sym.model import OUTPUTS
from linkage_sym.numeric.engine.run import (
    SCREEN,
    SINGULAR_COND,
    ground_driven,
    interrupted,
    nearest_across_gaps,
    scene_sweep,
    solving_path,
)
from linkage_sym.structure.parameters import driver_q0, ident
from linkage_sym.structure.recipes import AssemblyAngle

__all__ = ["Model", "Solution", "compiled"]


def compiled(scene):
    """The scene's compiled mechanism: from the cache when there (no SymPy), else derived."""
    from linkage_sym.codegen.runtime import load_compiled

    cm = load_compiled(scene)
    if cm is None:
        from linkage_sym.codegen.compile import compile_mechanism

        cm = compile_mechanism(scene)
    return cm


def _per_design(v) -> bool:
    """Whether a parameter of ``P`` is an array over the designs (else a number shared by
    all: ``np.ndim`` at the cost of an attribute)."""
    return isinstance(v, np.ndarray) and v.ndim > 0


_AT_SPEEDS = frozenset({"velocity", "acceleration", "points", "forces"})
"""What :meth:`Model.solve` computes at the scene's speeds (from the angles at the steps)."""


class _Designs:
    """What the position steps of a chunk read (:meth:`Model.positions`): the designs'
    parameters ``P``, the driver values ``Q`` and ``newton(step, X)``, a Newton group's
    coordinates (at assembly only)."""

    def __init__(self, P, Q, newton=None):
        self.P, self.Q, self.newton = P, Q, newton


class Model(NumpyEvaluator):
    """The compiled mechanism of a scene's topology, ready to solve chunks of designs: the
    designs' backend of the evaluator (:class:`~linkage_sym.codegen.evaluator.NumpyEvaluator`),
    its numbers arrays over designs x steps.

    Parameters
    ----------
    scene : Scene
    forces : bool
        Compile the force blocks (reactions, efforts) too.

    Attributes
    ----------
    params : list of float
        The scene's ``P`` (its parameters, then the assembly-mode signs); a chunk's is
        :meth:`design_params`.
    """

    def __init__(self, scene, forces: bool = False):
        self.scene = scene
        kin = dataclasses.replace(scene, outputs=OUTPUTS if forces else ("kinematics",))
        self.cm = cm = compiled(kin)
        super().__init__(cm.art, cm.functions, [float(v) for v in cm.params])
        art = self.art
        self.newton_groups = [g.label for g in art.groups if not g.closed]
        self.one_at_a_time = bool(self.newton_groups)
        self._continuations = None  # the Newton groups' ParameterContinuation, made on first use
        self.names = list(cm.param_names)
        self.index = {n: i for i, n in enumerate(self.names)}
        self.recipes = {p.recipe.key: i for i, p in enumerate(art.params)}
        q, qd, qdd = scene_sweep(scene)
        self.Q = np.array([q[k] for k in art.q])
        self.QD = np.array([qd[k] for k in art.q])
        self.QDD = np.array([qdd[k] for k in art.q])
        self.N = self.Q.shape[1]
        q0 = driver_q0(scene)
        self.q0 = np.array([q0[k] for k in art.q])
        self.path, self.out, _ = solving_path(scene, art.q, q0, cm.L, self.Q)
        self.slope = (np.zeros(len(art.q)) if self.N == 1
                      else (self.Q[:, -1] - self.Q[:, 0]) / (self.N - 1))
        self.theta0 = [(i, cm.angle_of[p.recipe.args[0]]) for i, p in enumerate(art.params)
                       if isinstance(p.recipe, AssemblyAngle)]
        self.angle_of = dict(cm.angle_of)
        # the angles of links turned by a driver on the ground: the driver's value at every
        # step, never moved by the rule for rotations across a gap
        self.driven_angles = {cm.angle_of[n] for n in ground_driven(scene)}
        self.frames = cm.frames
        self.simple_path = (self.path.shape[1] == self.N + 1
                            and np.array_equal(self.out, np.arange(1, self.N + 1)))
        self._tiles = {}
        # the closed steps' functions without arctangents, when the rates read no angle
        steps = art.steps
        self.directions = (steps[0] if len(steps) == 1 and getattr(steps[0], "directions", None)
                           and "] = X\n" not in art.functions["rates"] else None)

    # -- parameters -------------------------------------------------------------------------
    def value(self, P, recipe, default):
        """A parameter of the designs by its recipe's key (``default`` when the derivation
        has no such parameter: a constant of the topology's scene)."""
        i = self.recipes.get(recipe)
        return default if i is None else P[i]

    def design_params(self, names, values) -> list:
        """The ``P`` argument of a chunk: the scene's values with ``names`` set to the
        columns of ``values`` (n, k)."""
        P = list(self.params)
        for k, n in enumerate(names):
            P[self.index[n]] = np.ascontiguousarray(values[:, k], dtype=float)
        return P

    # -- the evaluator's hooks ----------------------------------------------------------------
    def block_system(self, entries, shape):
        """``A`` with its entries as the generated function returned them: one that does
        not depend on the design ((N,), or a number) is not broadcast, so that a block's
        determinant and solve compute it once per step."""
        return BlockSystem(entries, self.art.blocks, self.m, shape)

    def vector(self, values, shape):
        """A generated function's outputs as it returned them: a design-independent row of
        a right-hand side stays (N,) (or a number), as :meth:`block_system`'s entries."""
        return list(values)

    def newton_step(self, step, X, ctx):
        """A group without a closed form: ``ctx.newton`` (the parameter continuation)."""
        for c, v in zip(step.x, ctx.newton(step, X)):
            X[c] = v

    def positions(self, ctx: _Designs, E, keep=False):
        """Coordinates (m, *E) by the position steps at ``ctx`` (``E``: the entries' shape,
        an int or (n, N) with (n, 1) parameters and (N,) driver values).  With ``keep``,
        also each coordinate as the closed forms returned it (unbroadcast)."""
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            X = self.walk([None] * self.m, ctx)
        out = np.empty((self.m,) + ((E,) if isinstance(E, int) else tuple(E)))
        for c, v in enumerate(X):
            out[c] = v
        return (out, X) if keep else out

    def _newton_at_q0(self, P, Q, n, first=None):
        """A ``newton`` hook of :class:`_Designs` at the scene's driver values: each
        design's Newton groups continued in the parameters from the scene's assembly
        configuration (:class:`~linkage_sym.design.newton_groups.ParameterContinuation`),
        or from ``first`` (a previous call's record) when given.  Records the designs'
        inputs and roots in the returned dict."""
        from linkage_sym.design.newton_groups import ParameterContinuation

        if self._continuations is None:
            self._continuations = {st.function: ParameterContinuation(self, st)
                                   for st in self.art.newton_steps}
        record = {}

        def solve(step, X):
            pc = self._continuations[step.function]
            start = None
            if first is not None:
                x1, c1 = first[step.function]
                start = lambda d: ((None, None) if c1[d] is None or not np.isfinite(x1[:, d]).all()  # noqa: E731
                                   else (x1[:, d] / pc.scale, c1[d]))
            x, ctxs = pc.solve(P, Q, X, n, start)
            record[step.function] = (x, ctxs)
            return list(x)

        return solve, record

    def screen(self, A, L, valid=None):
        """Singular entries (bool, ``A.shape``), or ``None`` when there is none: a block's
        Hadamard ratio below :data:`SCREEN`
        (:meth:`~linkage_sym.codegen.blocks.BlockSystem.below`), then, at those entries
        only, the dimensionless condition number (size ``L``, broadcasting to the entries)
        above :data:`SINGULAR_COND`.  ``valid``: the entries with positions (default
        all)."""
        flag = None
        for low in A.below(SCREEN):
            if low is not None:
                flag = low if flag is None else flag | low
        if flag is None:
            return None
        flag = np.broadcast_to(flag, A.shape)
        if valid is not None:
            flag = flag & valid
        if not flag.any():
            return None
        cond = self.condition_numbers(A.dense(flag), np.broadcast_to(L, A.shape)[flag])
        sing = np.zeros(A.shape, bool)
        sing[flag] = ~(cond <= SINGULAR_COND)
        return sing if sing.any() else None

    # -- a chunk -------------------------------------------------------------------------------
    def assemble(self, P, n):
        """The designs' assembly configurations at ``q0`` (see the module docstring):
        ``(P with the designs' theta0, X0 (m, n), assembled (n,), joints0, L)``."""
        Q = [np.full(n, v) for v in self.q0]
        newton, first = self._newton_at_q0(P, Q, n) if self.one_at_a_time else (None, None)
        X0 = self.positions(_Designs(P, Q, newton), n)
        if self.theta0:
            P = list(P)
            for i, c in self.theta0:
                P[i] = X0[c].copy()
            if self.one_at_a_time:
                newton, _ = self._newton_at_q0(P, Q, n, first)
            X0 = self.positions(_Designs(P, Q, newton), n)
        assembled = np.isfinite(X0).all(axis=0)
        z = [np.zeros(n)] * self.m
        zq = [np.zeros(n)] * len(self.q0)
        with np.errstate(invalid="ignore", divide="ignore"):
            pts = self.call("points", P, X=list(X0), XD=z, XDD=z, Q=Q, QD=zq, QDD=zq,
                            CS=(list(np.cos(X0)), list(np.sin(X0))))
        def at(key):  # a point's position (2, n)
            return np.array([full(v, n) for v in self.art.rows(pts, key)])

        joints0 = {j.name: at(f"joint:{j.name}:0") for j in self.scene.joints}
        xy = np.array(list(joints0.values()))  # (J, 2, n)
        for lk in self.scene.link_names:  # the link frames' origins (a P joint's moves along it)
            joints0["origin:" + lk] = at(f"origin:{lk}:0")
        L = np.zeros(n)
        for i in range(len(xy)):
            for k in range(i + 1, len(xy)):
                L = np.fmax(L, np.hypot(*(xy[i] - xy[k])))
        return P, X0, assembled, joints0, L

    @staticmethod
    def assembly_of(assembly, a, b):
        """The designs ``a`` to ``b`` of an :meth:`assemble` of many (every number of a
        design's assembly is its own: the same as assembling them alone)."""
        P, X0, assembled, joints0, L = assembly
        return ([v[a:b] if _per_design(v) else v for v in P], X0[:, a:b], assembled[a:b],
                {k: v[:, a:b] for k, v in joints0.items()}, L[a:b])

    def _steps(self, n):
        """Driver values of ``n`` designs' steps, flattened design by design (cached)."""
        if self._tiles.get("n") != n:
            self._tiles = {"n": n, "Q": [np.tile(r, n) for r in self.Q],
                           "QD": [np.tile(r, n) for r in self.QD],
                           "QDD": [np.tile(r, n) for r in self.QDD]}
        return self._tiles

    def positions_at_steps(self, P, X0, assembled, n, unwrap):
        """Coordinates (m, n, N) at the steps, NaN where a design has no position, the angles
        of ``unwrap`` continuous from the assembly configuration along the solving path;
        which entries have positions (n, N); and each coordinate as the closed forms gave
        it (a value that does not depend on the design keeps its own shape: (N,) or scalar).

        ``P``: the designs' parameters, (n, 1) columns or floats; the driver values are
        (N,) rows, so every generated expression broadcasts to (n, N) and one that does not
        depend on the design (the crank's angle ``q``) is computed once per step.
        """
        N = self.N
        simple = self.simple_path  # the path is the assembly configuration, then the steps
        K = N if simple else self.path.shape[1]
        Q = list(self.Q) if simple else list(self.path)
        X, raw = self.positions(_Designs(P, Q), (n, K), keep=True)
        with np.errstate(invalid="ignore"):
            valid = np.isfinite(X).all(axis=0)
        valid &= assembled[:, None]
        every = bool(valid.all())
        if not every:
            X[:, ~valid] = np.nan
        for c in unwrap:
            X[c] = unwrap_fast(X[c], valid, X0[c] if simple else None, every)
            raw[c] = None
        path_valid = valid
        out = slice(None) if simple else self.out
        if not simple:
            X = np.ascontiguousarray(X[:, :, out])
            valid = valid[:, out]
            raw = [r[out] if r is not None and np.ndim(r) == 1 else None for r in raw]
        if unwrap and not every:  # the scene format's rule for rotations across a gap
            broken = interrupted(path_valid, out, valid)
            if broken.any():
                for c in unwrap:
                    if c not in self.driven_angles:
                        X[c] = nearest_across_gaps(X[c], valid, broken)
        if not simple:
            every = bool(valid.all())
        return X, valid, raw, every

    def _trig(self, X, raw, valid, every):
        """Cosines and sines (m, n, N) of the coordinates ``X``, NaN where no position: of a
        design-independent one (the crank's angle) by ``cos`` and ``sin`` at the N steps
        only; of the others from the tangent of the half angle ``t = tan(x/2)``,
        ``cos x = (1 - t^2)/(1 + t^2)``, ``sin x = 2t/(1 + t^2)`` (one vectorised ``tan``
        instead of ``cos`` and ``sin``, several times faster; within a few 1e-16 of them:
        tested against the numeric solver's results to 1e-12).  For a scene without
        :attr:`directions`."""
        m, n, N = X.shape
        C = np.empty_like(X)
        S = np.empty_like(X)
        t = np.empty((n, N))
        u = np.empty((n, N))
        with np.errstate(invalid="ignore", over="ignore"):
            for c in range(m):
                r = raw[c]
                if r is not None and np.ndim(r) <= 1:
                    C[c] = np.cos(r)
                    S[c] = np.sin(r)
                    if not every:
                        C[c][~valid] = np.nan
                        S[c][~valid] = np.nan
                    continue
                np.multiply(X[c], 0.5, out=t)
                np.tan(t, out=t)
                np.multiply(t, t, out=u)  # t^2
                np.subtract(1.0, u, out=C[c])
                np.add(u, 1.0, out=u)  # 1 + t^2
                np.divide(C[c], u, out=C[c])
                np.add(t, t, out=S[c])
                np.divide(S[c], u, out=S[c])
        return C, S

    def _directions_at_steps(self, P, n, assembled, valid=None):
        """The coordinates at the steps by :attr:`directions` (no arctangent:
        :func:`~linkage_sym.codegen.evaluator.unit_direction`): cosines and sines (m, n, N)
        of the angles, NaN where an entry has no position; the other coordinates' values
        (a list, None for an angle); which entries have positions (n, N); and the
        cosines, sines and values as the rate functions read them (lists: a value that
        does not depend on the design keeps its shape, (N,) or a number; NaN only where
        the closed forms gave it).  ``valid``: the entries with positions when known (the
        positions'), else the ``assembled`` (n,) designs' entries whose values are
        numbers."""
        N, m = self.N, self.m
        step = self.directions
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            out = iter(self.call(step.directions, P, X=[None] * m, Q=list(self.Q)))
        C, S = np.empty((m, n, N)), np.empty((m, n, N))
        V, raw = [None] * m, ([None] * m, [None] * m, [None] * m)
        finite = {}  # coordinate -> where its value is a number (its own shape)
        for c, form in zip(step.x, step.forms):
            if form == "value":
                C[c] = S[c] = np.nan  # never read: the functions read the angles' only
                V[c] = np.broadcast_to(next(out), (n, N)).copy()
                raw[2][c] = V[c]
                finite[c] = np.isfinite(V[c])
                continue
            if form == "unit":
                raw[0][c], raw[1][c] = next(out), next(out)
                C[c], S[c] = raw[0][c], raw[1][c]
            else:
                Y, X, cr, sr = (next(out) for _ in range(4))
                unit_direction(Y, X, cr, sr, out=(C[c], S[c]))
                raw[0][c], raw[1][c] = C[c], S[c]
            finite[c] = np.isfinite(raw[0][c])
        for c in range(m):
            if V[c] is None and c not in finite:
                C[c] = S[c] = np.nan  # a coordinate of no closed step (none in a batched run)
        known = valid is not None
        if not known:
            valid = np.repeat(assembled[:, None], N, axis=1)
            for f in finite.values():
                valid &= f
        count = np.count_nonzero(valid)
        if count < valid.size:
            # a coordinate that has a number at an entry without positions (an earlier
            # dyad's, the crank's, a design not assembled) is NaN there as the others; the
            # entries made here lie where every coordinate has a number, so one has a number
            # elsewhere exactly when it has more of them
            mask = ~valid
            for c in range(m):
                f = finite.get(c)
                if f is not None and not ((f & mask).any() if known else
                                          np.count_nonzero(f) * (valid.size // f.size) > count):
                    continue
                for a in ((C[c], S[c]) if V[c] is None else (V[c],)):
                    np.copyto(a, np.nan, where=mask)
        return C, S, V, valid, raw

    def solve(self, P, n, need, unwrap=(), assembly=None, rates=None) -> Solution:
        """Solve ``n`` designs (parameters ``P``, from :meth:`design_params`) at the sweep's
        steps; ``assembly``: their :meth:`assemble` when made already (for many chunks at
        once: :meth:`assembly_of`); ``rates``: the coordinates whose rates along the steps
        are read (default all; the others' are NaN).

        ``need``: a set of ``"rate_t"`` (rates along the steps), ``"velocity"``,
        ``"acceleration"``, ``"points"``, ``"forces"``; ``unwrap``: the coordinates
        whose angles must be continuous from the assembly configuration.  Designs
        with groups without a closed form are solved one at a time
        (:func:`~linkage_sym.design.newton_groups.solve_designs`).

        Positions, the singularity screen and the rates along the steps are evaluated
        over designs x steps by broadcasting ((n, 1) parameters, (N,) driver values);
        what a metric does not ask for is not computed: no velocities at the scene's
        speeds, accelerations, points or forces unless ``need`` names them, the exact
        condition number only where the screen flags a step.
        """
        if self.one_at_a_time:
            from linkage_sym.design.newton_groups import solve_designs

            return solve_designs(self, P, n, need)
        P, X0, assembled, joints0, L = self.assemble(P, n) if assembly is None else assembly
        N, m, E = self.N, self.m, n * self.N
        shape = (n, N)
        Pb = [v[:, None] if _per_design(v) else v for v in P]
        if unwrap or self.directions is None or (_AT_SPEEDS & need):
            X, pos_ok, raw, every = self.positions_at_steps(Pb, X0, assembled, n, unwrap)
            if self.directions is None:
                C, S = self._trig(X, raw, pos_ok, every)
            else:
                C, S, _, _, _ = self._directions_at_steps(Pb, n, assembled, pos_ok)
            Xl, CS = list(X), (list(C), list(S))
        else:  # only the angles' cosines and sines: no arctangent, no angle
            X = None
            C, S, _, pos_ok, (Cr, Sr, Xl) = self._directions_at_steps(Pb, n, assembled)
            every = bool(pos_ok.all())
            CS = (Cr, Sr)  # a crank's (N,): a design-independent entry of A stays (N,)
        sol = Solution(n, N, P, assembled, X0, joints0, L, X, pos_ok, pos_ok, model=self)
        sol.C, sol.S = C, S
        with np.errstate(invalid="ignore", over="ignore"):
            A, Bqt = self.rate_system(Xl, list(self.Q), [float(s) for s in self.slope], CS, Pb,
                                      shape)
        sing = self.screen(A, L[:, None], None if every else pos_ok)
        ok = pos_ok if sing is None else pos_ok & ~sing
        sol.ok = ok
        all_ok = sing is None and every
        if "rate_t" in need:
            rt = A.solve(Bqt, rates)
            if not all_ok:
                for c in range(m) if rates is None else rates:
                    np.copyto(rt[c], np.nan, where=~ok)
            sol.rate_t = rt
        if not (_AT_SPEEDS & need):
            return sol
        # the scene's speeds, points and forces: entry by entry (the ok ones)
        tiles = self._steps(n)
        idx = None if all_ok else np.flatnonzero(ok.ravel())
        sel = (lambda r: r) if idx is None else (lambda r: r[idx])
        Ko = E if idx is None else len(idx)
        Xk, Ck, Sk = (V.reshape(m, E) if idx is None else V.reshape(m, E)[:, idx] for V in (X, C, S))
        CSk = (list(Ck), list(Sk))
        Pk = [sel(np.repeat(v, N)) if np.ndim(v) else v for v in P]
        Qk, QDo, QDDo = ([sel(r) for r in tiles[k]] for k in ("Q", "QD", "QDD"))
        # A at the ok entries, flattened design by design: the first rate system's entries
        Ak = BlockSystem({ij: sel(np.broadcast_to(v, shape).reshape(E)) for ij, v in A.entries.items()},
                         self.art.blocks, m, Ko)
        with np.errstate(invalid="ignore", over="ignore"):
            Bqd = self.vector(self.rate_entries(list(Xk), Qk, QDo, CSk, Pk)[1], Ko)
        XD = Ak.solve(Bqd)
        XDD = Ak.solve(self.accelerations_rhs(list(Xk), list(XD), Qk, QDo, QDDo, CSk, Pk, Ko))
        sol.XD = self._spread_rows(XD, idx, n)
        sol.XDD = self._spread_rows(XDD, idx, n)
        if not ({"points", "forces"} & need):
            return sol
        # loads over the cycle scaled at each entry's driver values, as the runtimes do
        Pf = (self.loads_at(self.scene, dict(zip(self.art.q, Qk)), Pk) if "forces" in need
              else None) or Pk
        with np.errstate(invalid="ignore", divide="ignore"):
            pts = self.call("points", Pf, X=list(Xk), XD=list(XD), XDD=list(XDD), Q=Qk,
                            QD=QDo, QDD=QDDo, CS=CSk)
        pts = [full(v, Ko) for v in pts]
        sol.points = list(self._spread_rows(np.array(pts), idx, n))
        if sing is not None:  # a singular step keeps its positions (as the runtimes' results do)
            bad = np.flatnonzero((pos_ok & sing).ravel())
            if len(bad):
                self._positions_at(sol, bad, X.reshape(m, E)[:, bad],
                                   [np.repeat(v, N)[bad] if np.ndim(v) else v for v in P],
                                   [r[bad] for r in tiles["Q"]], C.reshape(m, E)[:, bad],
                                   S.reshape(m, E)[:, bad])
        if "forces" in need:
            F, fr = self.forces_and_friction(pts, P=Pf)
            sol.forces = self._spread_rows(np.array(F), idx, n)
            if fr is not None:  # the self-locking entries, False where no step was solved
                sol.locked = self._spread_rows(np.broadcast_to(fr.locked, (1, F[0].size)), idx, n)[0] == 1
        return sol

    def _positions_at(self, sol, where, X, P, Q, C, S):
        """The points function's positions (joints, link frames' origins, centres of mass)
        at the entries ``where`` of ``sol.points``, whose rates are not defined (singular
        steps); the other rows stay NaN there."""
        k = len(where)
        z, zq = [np.zeros(k)] * self.m, [np.zeros(k)] * len(self.q0)
        with np.errstate(invalid="ignore", divide="ignore"):
            pts = self.call("points", P, X=list(X), XD=z, XDD=z, Q=Q, QD=zq, QDD=zq,
                            CS=(list(C), list(S)))
        for key, (a, b) in self.art.layout.items():
            if key.endswith(":0") and key.startswith(("joint:", "origin:", "com:")):
                for r in range(a, b):
                    sol.points[r].ravel()[where] = full(pts[r], k)

    def _spread_rows(self, V, idx, n):
        """Rows (r, E') at the entries ``idx`` (None: every entry) as (r, n, N), NaN elsewhere."""
        if idx is None:
            return V.reshape(len(V), n, self.N)
        out = np.full((len(V), n * self.N), np.nan)
        out[:, idx] = V
        return out.reshape(len(V), n, self.N)

    # -- what the metrics read -----------------------------------------------------------------
    def point_rows(self, key):
        """Rows ``(a, b)`` of the points function's outputs under a layout key."""
        return self.art.layout[key]

    def reaction(self, sol, joint) -> np.ndarray:
        """Magnitude (n, N) of the reaction at ``joint`` (an ``R`` joint's force, a ``P``
        joint's normal force)."""
        n, fidx = ident(joint), self.art.force_index()
        if self.scene.joint(joint).type == "R":
            return np.hypot(sol.forces[fidx[f"R_{n}x"]], sol.forces[fidx[f"R_{n}y"]])
        return np.abs(sol.forces[fidx[f"N_{n}"]])

    def effort(self, sol, driver) -> np.ndarray:
        """The driving torque or force (n, N) at ``driver``."""
        d = next(d for d in self.scene.drivers if d.joint == driver)
        return sol.forces[self.art.force_index()[("tau_" if d.kind == "R" else "f_") + ident(driver)]]

    def drivers_at(self, t) -> list:
        """The driver values (a row per driver) at fractional steps ``t`` (B,), linear
        between the steps; NaN where ``t`` is not a number."""
        t = np.asarray(t, float)
        known = np.isfinite(t)
        i = np.clip(np.floor(np.where(known, t, 0.0)).astype(int), 0, max(self.N - 2, 0))
        f = np.where(known, t - i, np.nan)
        return [r[i] + f * (r[np.minimum(i + 1, self.N - 1)] - r[i]) for r in self.Q]

    def rate_at(self, P, d, t, col):
        """The rate along the steps of coordinate ``col`` of designs ``d`` at fractional
        steps ``t`` (arrays (B,)), the positions by the closed forms there; with the rate's
        own rate and the coordinate's value; NaN where ``t`` is (a root the metrics did
        not find)."""
        Q = self.drivers_at(t)
        B = len(t)
        Pd = [v[d] if _per_design(v) else v for v in P]
        X = self.positions(_Designs(Pd, Q), B)
        CS = (list(np.cos(X)), list(np.sin(X)))
        QD = [np.full(B, s) for s in self.slope]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            A, rhs = self.rate_system(list(X), Q, QD, CS, Pd, B)
            XD = A.solve(rhs)
            XDD = A.solve(self.accelerations_rhs(list(X), list(XD), Q, QD, [np.zeros(B)] * len(Q),
                                                 CS, Pd, B))
        return XD[col], XDD[col], X[col]

