"""Run a compiled mechanism over a sweep (NumPy only: no SymPy here).

A :class:`CompiledMechanism` holds the generated functions of one topology
(:mod:`linkage_sym.codegen.compile`) and the parameter values of one scene.
:meth:`CompiledMechanism.run` evaluates the stages a scene needs:

1. positions: the closed forms, vectorised over a path from the assembly
   configuration through the steps; groups without a closed form by Newton
   on their loop equations, step by step (sub-stepped where a step fails);
2. ``A xd = B qd`` and ``A xdd = rhs``: the generated entries, solved group
   block by group block (Cramer for 2x2 blocks, LU otherwise; :class:`_RateSystem`);
3. points and the force blocks ``A_g F_g = b_g - C_g F_later``, solved from
   the last group back; the frame loads from the ground's reactions.

The result is the same :class:`~linkage_sym.numeric.results.result.Analysis` the
numeric solver returns, with ``forces.method == "symbolic"``.

Made once, when the mechanism is bound to a scene (as ``compile_plan`` does
for the numeric plan): the assembly modes, the accuracy calibration on the
scene's own sweep, and the memory a run of that sweep takes, warmed
(:mod:`linkage_sym.numeric.engine.heap`); every run, the first one too, only solves.

Size: about 700 lines: the run's three stages share the bound functions,
the block structure and the coordinate layout of one compiled mechanism; the
bookkeeping both runtimes share is in :mod:`linkage_sym.numeric.engine.sweep` and
:mod:`linkage_sym.numeric.engine.block`.
"""

from __future__ import annotations

import linecache
import math

import numpy as np

from linkage_sym.codegen import cache
from linkage_sym.errors import SceneError
from linkage_sym.numeric.results import accuracy
from linkage_sym.numeric import continuation
from linkage_sym.numeric.continuation import messages as continuation_messages
from linkage_sym.numeric.engine.block import ResultLayout
from linkage_sym.numeric.forces.loads import load_factor
from linkage_sym.numeric.kinematics.constraints import jacobian
from linkage_sym.numeric.kinematics.joint_rows import scene_constraints
from linkage_sym.numeric.kinematics.gears import pulling_note
from linkage_sym.numeric.kinematics.loci import clamp_tangent, coordinate_size
from linkage_sym.numeric.kinematics.state import LinkState
from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.result import OK, Analysis, Forces, GroupForces
from linkage_sym.numeric.engine.run import (
    unwrap_angles as _unwrap,
    Calibration,
    finish,
    ground_driven,
    interrupted,
    mark_singular,
    nearest_across_gaps,
    new_analysis,
    scene_sweep,
    solving_path,
    step_status,
)
from linkage_sym.structure import decompose
from linkage_sym.structure.parameters import driver_q0, evaluate, ident, link_frames

SCREEN = 1e-3
"""A group block whose Hadamard ratio (by rows or by columns) is below this gets the
exact condition number."""
ASSEMBLY_MATCH = 1e-6
"""Closed forms must reproduce the assembly configuration to this (rad, or fraction of size)."""


class _GroupProblem:
    """A group without a closed form in the derived coordinates (angles, slides), for
    :func:`continuation.solve_path`: unknowns over the scale (slides over ``L``),
    residual rows over their scale (loop projections over ``L``)."""

    def __init__(self, cm, step, group, X, Qpath, failed):
        self.f = cm.functions[step["function"]]
        self.params = cm.params
        self.cols = step["x"]
        self.n = len(self.cols)
        self.m = cm.m
        self.X = X
        self.Q = Qpath
        self.failed = failed
        self.known = [c for c in range(cm.m) if X[c] is not None]
        self.scale = np.where(cm.is_angle[self.cols], 1.0, cm.L)
        self.angles = cm.is_angle[self.cols]
        r0, r1 = group["rows"]
        self.row_scale = np.where(np.array(cm.art["rows_length"][r0:r1], bool), 1.0 / cm.L, 1.0)

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


def _tangent_sqrt(scale, *factors):
    """``sqrt`` of the product of ``factors``, a rounding-level miss of a tangency taken as
    the tangency (0) and a real miss as NaN: the numeric solver's rule
    (:func:`~linkage_sym.numeric.kinematics.loci.clamp_tangent`), for the generated code's
    :func:`~linkage_sym.symbolic.tangent.tangent_sqrt`."""
    prod = factors[0]
    for f in factors[1:]:
        prod = prod * f
    prod = clamp_tangent(prod, factors, lambda: scale)
    with np.errstate(invalid="ignore"):
        return np.sqrt(prod)


def _coordinate_size(*values):
    """The largest magnitude of ``values`` (arrays or numbers), elementwise."""
    return coordinate_size(*values)


def _namespace() -> dict:
    ns: dict = {}
    exec("from numpy import *", ns)  # the names lambdify's NumPy printer uses
    ns["numpy"] = np
    ns["_tangent_sqrt"] = _tangent_sqrt
    ns["_coordinate_size"] = _coordinate_size
    return ns


def load_functions(artifact: dict, label: str) -> dict:
    """Execute the generated sources; their text stays readable by ``inspect``."""
    ns = _namespace()
    out = {}
    for name, src in artifact["functions"].items():
        fname = f"<linkage_sym {label}:{name}>"
        linecache.cache[fname] = (len(src), None, src.splitlines(True), fname)
        exec(compile(src, fname, "exec"), ns)
        out[name] = ns[name]
    return out


def _full(v, K):
    """A generated function's output as an array over the ``K`` steps (a constant
    output comes back as a scalar: broadcast, read-only)."""
    if isinstance(v, np.ndarray) and v.shape == (K,) and v.dtype == np.float64:
        return v
    return np.broadcast_to(np.asarray(v, float), (K,))


def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


class _RateSystem:
    """``A`` of the rate problems at ``K`` steps, kept as its generated entries.

    ``A`` is block lower-triangular (one block per group, in solving order) and
    sparse; the generated ``rates`` function gives its non-zero entries, each an
    array over the steps.  They stay coordinate-major: a group's 2x2 or 3x3
    block is contiguous arrays, its determinant is formed once and serves the
    singularity screen, the velocities and the accelerations (Cramer's rule,
    as the 2x2 blocks always had; LU for larger blocks); the coupling to
    earlier groups is a sum over the pattern's entries.  A dense ``(K, m, m)``
    matrix is formed only for the steps whose condition number is computed.
    """

    def __init__(self, entries: dict, blocks, m: int, K: int):
        self.entries, self.blocks, self.m, self.K = entries, blocks, m, K
        zero = np.zeros(K)
        self._solvers = []
        for r0, r1, c0, c1 in blocks:
            n = c1 - c0
            get = lambda i, j: entries.get((i, j), zero)  # noqa: E731
            coupling = [(i - r0, j, v) for (i, j), v in entries.items() if r0 <= i < r1 and j < c0]
            if n == 1:
                own = (get(r0, c0),)
            elif n == 2:
                a, b, c, d = get(r0, c0), get(r0, c0 + 1), get(r0 + 1, c0), get(r0 + 1, c0 + 1)
                with np.errstate(invalid="ignore", over="ignore"):
                    own = (a, b, c, d, a * d - b * c)
            elif n == 3:  # the rows, and the adjugate's first column with the determinant
                R = [[get(r0 + i, c0 + j) for j in range(3)] for i in range(3)]
                (a, b, c), (d, e, f), (g, h, k) = R
                with np.errstate(invalid="ignore", over="ignore"):
                    co = (e * k - f * h, f * g - d * k, d * h - e * g)
                    own = (R, co, a * co[0] + b * co[1] + c * co[2])
            else:
                M = np.empty((K, n, n))
                for i in range(n):
                    for j in range(n):
                        M[:, i, j] = get(r0 + i, c0 + j)
                own = (M,)
            self._solvers.append((c0, n, coupling, own))

    @classmethod
    def of(cls, pattern, values, blocks, m, K):
        """From the generated function's outputs (the pattern's entries, in order)."""
        return cls({tuple(ij): _full(v, K) for ij, v in zip(pattern, values)}, blocks, m, K)

    def take(self, sel) -> "_RateSystem":
        """The system at the steps ``sel`` (a boolean mask)."""
        return _RateSystem({ij: v[sel] for ij, v in self.entries.items()}, self.blocks, self.m,
                           int(np.count_nonzero(sel)))

    def ratios(self) -> list:
        """Each group block's Hadamard ratio (``|det|`` over the product of its row norms,
        and of its column norms, whichever is smaller) at every step; ``None`` for a 1x1
        block."""
        out = []
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for c0, n, _, own in self._solvers:
                if n == 1:
                    out.append(None)
                elif n == 2:
                    # a row that vanishes as a whole (every term of a loop projection zero)
                    # leaves the row ratio near one, the column ratio catches it, and the
                    # other way round
                    a, b, c, d, det = own
                    a2, b2, c2, d2 = a * a, b * b, c * c, d * d
                    out.append(np.abs(det) / np.sqrt(np.fmax((a2 + b2) * (c2 + d2),
                                                             (a2 + c2) * (b2 + d2))))
                elif n == 3:
                    R, _, det = own
                    sq = [[v * v for v in row] for row in R]
                    rows = np.sqrt((sq[0][0] + sq[0][1] + sq[0][2]) * (sq[1][0] + sq[1][1] + sq[1][2])
                                   * (sq[2][0] + sq[2][1] + sq[2][2]))
                    cols = np.sqrt((sq[0][0] + sq[1][0] + sq[2][0]) * (sq[0][1] + sq[1][1] + sq[2][1])
                                   * (sq[0][2] + sq[1][2] + sq[2][2]))
                    out.append(np.abs(det) / np.fmax(rows, cols))
                else:
                    M = own[0]
                    det = np.abs(np.linalg.det(M))
                    out.append(np.fmin(det / np.prod(np.linalg.norm(M, axis=2), axis=1),
                                       det / np.prod(np.linalg.norm(M, axis=1), axis=1)))
        return out

    def dense(self, steps) -> np.ndarray:
        """``A`` (len(steps), m, m) at the steps ``steps``."""
        A = np.zeros((len(steps), self.m, self.m))
        for (i, j), v in self.entries.items():
            A[:, i, j] = v[steps]
        return A

    def solve(self, rhs) -> np.ndarray:
        """``x`` (m, K) of ``A x = rhs``, ``rhs`` a sequence of ``m`` arrays over the steps."""
        x = np.zeros((self.m, self.K))
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for (r0, r1, _, _), (c0, n, coupling, own) in zip(self.blocks, self._solvers):
                b = [rhs[r0 + i] for i in range(r1 - r0)]
                for i, j, v in coupling:
                    b[i] = b[i] - v * x[j]
                if n == 1:
                    np.divide(b[0], own[0], out=x[c0])
                elif n == 2:
                    a, bb, c, d, det = own
                    x[c0] = (b[0] * d - b[1] * bb) / det
                    x[c0 + 1] = (a * b[1] - c * b[0]) / det
                elif n == 3:  # Cramer: x = adj(M) b / det
                    ((a, bb, c), (d, e, f), (g, h, k)), co, det = own
                    x[c0] = (co[0] * b[0] + (c * h - bb * k) * b[1] + (bb * f - c * e) * b[2]) / det
                    x[c0 + 1] = (co[1] * b[0] + (a * k - c * g) * b[1] + (c * d - a * f) * b[2]) / det
                    x[c0 + 2] = (co[2] * b[0] + (bb * g - a * h) * b[1] + (a * e - bb * d) * b[2]) / det
                else:
                    x[c0:c0 + n] = np.linalg.solve(own[0], np.stack(b, axis=1)[..., None])[..., 0].T
        return x


class CompiledMechanism:
    """Generated functions of one topology bound to one scene's values.

    Attributes
    ----------
    functions : dict of str to callable
        The generated functions (``inspect.getsource`` shows their code and
        their docstring the argument order).
    params : list of float
        Values of the ``P`` argument: the scene's parameters, then the
        assembly-mode signs.
    """

    def __init__(self, artifact: dict, scene: Scene):
        self.art = art = artifact
        self.scene = scene
        self.functions = load_functions(art, scene.name)
        frames = link_frames(scene)
        self.frames = frames
        self.param_names = [n for n, _ in art["params"]]
        self.params = [evaluate(scene, tuple(r), frames) for _, r in art["params"]]
        self.n_params = len(self.params)  # then the assembly-mode signs, then the flanks
        self.params += [1.0] * art["sigmas"]
        self.flanks = art.get("flanks", [])
        self.params += [1.0] * len(self.flanks)
        self.L = scene.characteristic_length() or 1.0
        self.x_names = art["x"]
        self.m = len(self.x_names)
        self.q0 = driver_q0(scene)
        xi = {n: i for i, n in enumerate(self.x_names)}
        self.angle_of = {n: xi["theta_" + ident(n)] for n in scene.link_names}
        self.x0 = np.zeros(self.m)
        for n, c in self.angle_of.items():
            self.x0[c] = frames[n].theta0
        self.is_angle = np.array([n.startswith("theta_") for n in self.x_names])
        # the angles unwrapped along the path: all but those of links turned by a driver on
        # the ground, whose closed form is the driver's value itself (never wrapped)
        self._driven = [self.angle_of[n] for n in ground_driven(scene)]
        self._wrapped = [c for c in np.flatnonzero(self.is_angle) if c not in self._driven]
        self.blocks = [
            (g["rows"][0], g["rows"][1], g["cols"][0], g["cols"][-1] + 1) for g in art["groups"]
        ]
        self._choose_branches()
        self._pose_constraints = None
        self._calibration = Calibration()  # accuracy: the indicator-to-condition ratio
        self._layout = ResultLayout(scene, tuple(art["stages"]))  # where a run writes its results
        self._own = None  # the scene's own sweep: driver arrays and solving path, made once
        self._decomposition = None
        # the scene's own sweep and solving path, the accuracy calibration and the memory of
        # a run belong to the scene: made here, once, so that every run, the first one too,
        # only solves (as the numeric plan does)
        n_steps = self._drivers(None, None, None)[3].shape[1]
        self._calibration.ratio(self.sweep, self.run)
        self._layout.warm(n_steps, "symbolic")

    # -- positions -----------------------------------------------------------------
    def _call(self, name, X=None, XD=None, XDD=None, Q=None, QD=None, QDD=None, F=None, P=None,
              CS=(None, None)):
        return self.functions[name](
            X, XD, XDD, Q, QD, QDD, F, self.params if P is None else P, CS[0], CS[1]
        )

    def _choose_branches(self):
        """Assembly-mode signs: the ones whose closed forms give the assembly configuration."""
        art = self.art
        k = art["sigmas"]
        if k == 0:
            return
        combos = np.array(np.meshgrid(*[[1.0, -1.0]] * k, indexing="ij")).reshape(k, -1)
        n = self.n_params
        P = self.params[:n] + list(combos) + self.params[n + k:]
        Q = [self.q0[n] for n in art["q"]]
        X = list(self.x0)
        err = np.zeros(combos.shape[1])
        with np.errstate(invalid="ignore", divide="ignore"):
            for step in art["steps"]:
                if step["kind"] != "closed":
                    continue
                out = self._call(step["function"], X=X, Q=Q, P=P)
                for c, v in zip(step["x"], out):
                    v = np.broadcast_to(np.asarray(v, float), err.shape)
                    d = _wrap(v - self.x0[c]) if self.is_angle[c] else (v - self.x0[c]) / self.L
                    err = np.fmax(err, np.where(np.isfinite(d), np.abs(d), np.inf))
        best = int(np.argmin(err))
        if not err[best] <= ASSEMBLY_MATCH:  # pragma: no cover - a derivation bug
            raise RuntimeError(
                f"{self.scene.name}: the closed forms do not reproduce the assembly "
                f"configuration (error {err[best]:.3g})"
            )
        for i in range(k):
            flipped = combos[:, best].copy()
            flipped[i] = -flipped[i]
            j = int(np.flatnonzero((combos == flipped[:, None]).all(axis=0))[0])
            if err[j] <= ASSEMBLY_MATCH:
                g = next(g for g in art["groups"] if g["sigma"] == n + i)
                raise SceneError(
                    [
                        f"joints: the assembly configuration is a singular position of the "
                        f"{g['label']} ({', '.join(g['links'])}): its assembly mode is undefined; "
                        "move the joints' `at` points off the dead-centre position"
                    ]
                )
        for i in range(k):
            self.params[n + i] = float(combos[i, best])

    def _path(self, Q: np.ndarray):
        """Driver values from the assembly configuration through the steps (refined),
        and the path index of each step."""
        P, out, _ = solving_path(self.scene, self.art["q"], self.q0, self.L, Q)
        return P, out

    def _drivers(self, q, qd, qdd):
        """The driver arrays (D, N) in the order of ``artifact["q"]``, the solving path and
        the steps' path indices; for the scene's own sweep (``q`` None) made once."""
        if q is None and self._own is not None:
            return self._own
        own = q is None
        if own:
            q, qd, qdd = self.sweep()
        names = self.art["q"]
        Qs = np.array([np.asarray(q[n], float) for n in names])
        QDs = np.array([np.asarray(qd[n], float) for n in names])
        QDDs = np.array([np.asarray(qdd[n], float) for n in names])
        Qpath, out = self._path(Qs)
        # the steps as a slice of the path when they are contiguous: views, no copies
        sel = slice(int(out[0]), int(out[0]) + len(out)) if len(out) and np.all(np.diff(out) == 1) else out
        got = (q, qd, qdd, Qs, QDs, QDDs, Qpath, out, sel)
        if own:
            for a in (Qs, QDs, QDDs, Qpath, out):
                a.flags.writeable = False
            self._own = got
        return got

    def positions(self, Qpath: np.ndarray):
        """Coordinates (m, K) along a path of driver values (D, K), and the first
        failing group at each point (-1 where every group is solved)."""
        art = self.art
        K = Qpath.shape[1]
        X = [None] * self.m
        failed = np.full(K, -1)
        self.newton_messages, self.newton_notes = {}, []
        gidx = {c: g["index"] for g in art["groups"] for c in g["cols"]}
        Q = list(Qpath)
        with np.errstate(invalid="ignore", divide="ignore"):
            for step in art["steps"]:
                if step["kind"] == "closed":
                    out = self._call(step["function"], X=X, Q=Q)
                    for c, v in zip(step["x"], out):
                        X[c] = np.array(_full(v, K))
                        bad = ~np.isfinite(X[c]) & (failed < 0)
                        failed[bad] = gidx[c]
                else:
                    self._newton(step, X, Qpath, failed)
        return np.array(X), failed

    def _newton(self, step, X, Qpath, failed):
        """One group without a closed form at every path point: the continuation policy
        both runtimes share (:mod:`linkage_sym.numeric.continuation`)."""
        g = step["group"]
        group = next(gr for gr in self.art["groups"] if gr["index"] == g)
        problem = _GroupProblem(self, step, group, X, Qpath, failed)
        sol = continuation.solve_path(problem, Qpath.shape[1], self.x0[step["x"]] / problem.scale)
        x = (sol.u * problem.scale).T
        for k, c in enumerate(step["x"]):
            X[c] = x[k]
        kinds = {n: self.scene.joint(n).type for n in self.art["q"]}
        qpath = dict(zip(self.art["q"], Qpath))

        def where(i):
            return lambda t: continuation_messages.driver_values_text(qpath, kinds, i, t)

        for i, f in sol.failures.items():
            failed[i] = g
            self.newton_messages[i] = continuation_messages.failure_message(
                group["label"], group["links"], f, where(i))
        self.newton_notes += [
            (n[0], lambda step_text, n=n: continuation_messages.note_message(
                group["label"], group["links"], n, step_text, where(n[0])))
            for n in sol.notes
        ]

    # -- the run ---------------------------------------------------------------------
    def sweep(self):
        """Driver values ``(q, qd, qdd)`` of the scene's sweep: dicts of (N,) arrays."""
        return scene_sweep(self.scene)

    def evaluate(self, q, qd, qdd) -> dict:
        """The lambdified kinematics at given driver values, without bookkeeping.

        Positions by the closed forms at the given values (no path from the
        assembly configuration, no unwrapping, no singularity screen), then
        ``A xd = B qd``, ``A xdd = rhs`` and the points.  For mechanisms
        whose groups all have closed forms; :meth:`run` is the full analysis.

        Returns
        -------
        dict
            ``"x"``, ``"xd"``, ``"xdd"``: arrays (m, N) in the order of
            :attr:`x_names`; ``"points"``: the points function's outputs
            (layout ``artifact["layout"]``).
        """
        art = self.art
        if any(st["kind"] != "closed" for st in art["steps"]):
            raise ValueError(
                "evaluate: a group of this mechanism has no closed form (Newton needs the "
                "path from the assembly configuration); use run()"
            )
        Q = [np.asarray(q[n], float) for n in art["q"]]
        QD = [np.asarray(qd[n], float) for n in art["q"]]
        QDD = [np.asarray(qdd[n], float) for n in art["q"]]
        N = len(Q[0])
        X = [None] * self.m
        with np.errstate(invalid="ignore", divide="ignore"):
            for st in art["steps"]:
                for c, v in zip(st["x"], self._call(st["function"], X=X, Q=Q)):
                    X[c] = np.broadcast_to(v, (N,))
            X = np.array(X)
            CS = (list(np.cos(X)), list(np.sin(X)))
            A, Bqd = self.rate_system(X, Q, QD, CS)
            XD = A.solve(Bqd)
            r = self._call("accelerations", X=list(X), XD=list(XD), Q=Q, QD=QD, QDD=QDD, CS=CS)
            XDD = A.solve([_full(v, N) for v in r])
            pts = self._call(
                "points", X=list(X), XD=list(XD), XDD=list(XDD), Q=Q, QD=QD, QDD=QDD, CS=CS
            )
        return {"x": X, "xd": XD, "xdd": XDD, "points": pts}

    def rate_system(self, X, Q, QD, CS=None):
        """``A`` (a :class:`_RateSystem`) and ``B qd`` (a list of ``m`` arrays over the steps)
        at coordinates ``X`` (m, K)."""
        K = X.shape[1]
        if CS is None:
            CS = (list(np.cos(X)), list(np.sin(X)))
        out = self._call("rates", X=list(X), Q=Q, QD=QD, CS=CS)
        pat = self.art["pattern"]
        A = _RateSystem.of(pat, out[:len(pat)], self.blocks, self.m, K)
        return A, [_full(v, K) for v in out[len(pat):]]

    def condition_numbers(self, A):
        """Dimensionless condition number of ``A`` (K, m, m)."""
        rl = np.where(self.art["rows_length"], 1.0 / self.L, 1.0)
        cl = np.where(self.art["cols_length"], self.L, 1.0)
        sv = np.linalg.svd(A * rl[None, :, None] * cl[None, None, :], compute_uv=False)
        with np.errstate(divide="ignore"):
            return sv[:, 0] / sv[:, -1]

    def pose_condition(self, res, steps) -> np.ndarray:
        """Condition number of the dimensionless pose Jacobian (every link's ``dx, dy,
        theta``; the numeric solver's) at ``steps`` of a result, for its accuracy."""
        if self._pose_constraints is None:
            self._pose_constraints = [c for jr in scene_constraints(self.scene, self.q0).values()
                                      for c in jr.rows]
        S = {GROUND: LinkState()}
        for n in self.scene.link_names:
            lk = res.links[n]
            S[n] = LinkState(lk.rotation[steps], lk.origin[steps, 0], lk.origin[steps, 1])
        J = jacobian(self._pose_constraints, S, list(self.scene.link_names), len(steps), self.L)
        sv = np.linalg.svd(J, compute_uv=False)
        with np.errstate(divide="ignore"):
            return sv[:, 0] / sv[:, -1]

    def _accuracy(self, res, indicator) -> dict | None:
        """Each ok step's relative accuracies (as the numeric plan's): ``K`` of the pose
        Jacobian where a block was screened, else ``G / indicator`` with ``G`` calibrated
        once on the scene's own sweep (:class:`~linkage_sym.numeric.engine.sweep.Calibration`)."""
        ok = res.status == OK
        flagged = np.flatnonzero(ok & np.isfinite(res.condition))
        pose_k = np.full(len(ok), np.nan)
        if len(flagged):
            pose_k[flagged] = self.pose_condition(res, flagged)
        if self._calibration.active:
            good = np.flatnonzero(ok)
            pose_k[good] = self.pose_condition(res, good)
            self._calibration.record(pose_k, ok, indicator)
            return None
        G = self._calibration.ratio(self.sweep, self.run)
        K = accuracy.condition_estimate(pose_k, ok, indicator, G)
        return accuracy.accuracy(K, ok, tuple(self.art["stages"]), accuracy.amplification_of(res.forces),
                                 floor={"position": accuracy.magnitude_floor(res, self.L)})

    def step_positions(self, q, qd, qdd):
        """Positions at the steps, solved along the path from the assembly configuration.

        ``q`` ``None``: the scene's own sweep (its arrays and path made once).
        Returns ``(Q, QD, QDD, X, failed, out)``: the driver arrays (D, N) in the
        order of ``artifact["q"]``, the coordinates (m, N) with angles continuous
        from the assembly configuration, the first failing group at each step
        (-1 where solved) and the path index of each step.
        """
        Qs, QDs, QDDs, Qpath, out, sel = self._drivers(q, qd, qdd)[3:]
        Xp, failed_p = self.positions(Qpath)
        valid = failed_p < 0
        every = bool(valid.all())
        for c in self._wrapped:
            th = _unwrap(Xp[c] if every else Xp[c, valid])
            # continuous from the assembly configuration (path point 0)
            th = th - 2 * np.pi * np.round((th[0] - self.x0[c]) / (2 * np.pi))
            if every:
                Xp[c] = th
            else:
                Xp[c, valid] = th
        for c in self._driven:  # the driver's value, counted from the assembly configuration
            Xp[c] -= 2 * np.pi * np.round((Xp[c, 0] - self.x0[c]) / (2 * np.pi))
        X, failed = Xp[:, sel], failed_p[sel]
        if not every:  # the scene format's rule for rotations across a gap
            solved = failed < 0
            broken = interrupted(valid, sel, solved)
            if broken.any():
                X = np.array(X)
                for c in self._wrapped:
                    X[c] = nearest_across_gaps(X[c], solved, broken)
        return Qs, QDs, QDDs, X, failed, out

    def run(self, q=None, qd=None, qdd=None, exact_condition=False) -> Analysis:
        """Evaluate the compiled mechanism over a sweep (the scene's by default)."""
        art = self.art
        Qs, QDs, QDDs, X, failed, out = self.step_positions(q, qd, qdd)  # None: the scene's
        q, qd, qdd = self._drivers(q, qd, qdd)[:3]
        N = Qs.shape[1]
        groups = {g["index"]: g for g in art["groups"]}

        def message_of(i):
            g = groups[int(failed[i])]
            if g["closed"]:
                return (f"{g['label']} ({', '.join(g['links'])}) cannot be assembled: "
                        "its closed form has no real solution")
            return self.newton_messages[int(out[i])]

        status, messages = step_status(failed, message_of)
        pos_ok = failed < 0
        idx = np.flatnonzero(pos_ok)
        if len(idx) == N:  # every step assembled: the arrays themselves, no copies
            Xk, Qk, QDk, QDDk = X, list(Qs), list(QDs), list(QDDs)
        else:
            Xk = X[:, idx]
            Qk, QDk, QDDk = list(Qs[:, idx]), list(QDs[:, idx]), list(QDDs[:, idx])
        CS = (np.cos(Xk), np.sin(Xk))
        A, Bqd = self.rate_system(Xk, Qk, QDk, (list(CS[0]), list(CS[1])))
        # singular steps: a block's Hadamard ratio screens, the exact condition number decides
        condition = np.full(N, np.nan)
        screen = np.ones(len(idx), bool) if exact_condition else np.zeros(len(idx), bool)
        ratio_min = np.full(len(idx), np.inf)  # the blocks' indicators, for the accuracy
        for ratio in A.ratios():
            if ratio is not None:
                screen |= ~(ratio >= SCREEN)
                ratio_min = np.fmin(ratio_min, ratio)
        if screen.any():
            steps = np.flatnonzero(screen)
            mark_singular(status, messages, condition, idx[steps],
                          self.condition_numbers(A.dense(steps)))
        ok = status == OK
        rate_ok = ok[idx]
        stages = tuple(art["stages"])
        K = len(idx)
        # the steps with rates: a slice (views, no copies) when every step has them
        every = bool(rate_ok.all())
        sel = slice(None) if every else rate_ok
        n_sel = int(rate_ok.sum())
        As = A if every else A.take(rate_ok)
        XD = np.full((self.m, K), np.nan)
        XDD = np.full((self.m, K), np.nan)
        if "velocity" in stages and n_sel:
            XD[:, sel] = As.solve([v[sel] for v in Bqd])
        if "acceleration" in stages and n_sel:
            r = self._call(
                "accelerations", X=list(Xk[:, sel]), XD=list(XD[:, sel]),
                CS=(list(CS[0][:, sel]), list(CS[1][:, sel])),
                Q=[v[sel] for v in Qk], QD=[v[sel] for v in QDk], QDD=[v[sel] for v in QDDk],
            )
            XDD[:, sel] = As.solve([_full(v, n_sel) for v in r])
        P0 = self._load_params(dict(zip(art["q"], Qk)))

        def points(flanks=None, arrays=True):
            """The points function's outputs at the K steps; ``flanks``: each mesh's flank
            at every step (the parameters' +1 otherwise); ``arrays`` false: a constant
            output stays a scalar (the result block's rows broadcast it)."""
            P = P0
            if flanks is not None:
                P = list(self.params if P0 is None else P0)
                at = self.n_params + art["sigmas"]
                P[at:at + len(flanks)] = list(flanks)
            with np.errstate(invalid="ignore"):
                got = self._call("points", X=list(Xk), XD=list(XD), XDD=list(XDD), Q=Qk, QD=QDk,
                                 QDD=QDDk, CS=(list(CS[0]), list(CS[1])), P=P)
            return [_full(v, K) for v in got] if arrays else got

        pts = points(arrays="forces" in stages)  # the force solve indexes every output
        forces = None
        if "forces" in stages:
            forces = self._forces(pts, points, Xk, CS, rate_ok, idx, N)
        res = self._analysis(X, XD, XDD, CS, pts, idx, status, messages, condition, forces,
                             q, qd, qdd)
        if self._decomposition is None:  # for the transmission angles, made once
            self._decomposition = decompose(self.scene)
        finish(res, self.scene, self.newton_notes, out, self._decomposition)
        # accuracy (numeric.results.accuracy): K of the pose Jacobian (the numeric solver's), exact
        # where a block was screened, else from the blocks' ratios calibrated on it
        indicator = np.full(N, np.inf)
        indicator[idx] = ratio_min
        res.accuracy = self._accuracy(res, indicator)
        return res

    def _load_params(self, q) -> list | None:
        """The parameters with the forces and torques of loads that vary over the cycle
        scaled by their factors at the driver values ``q`` (``None``: no such load)."""
        scaled = [(i, ld) for i, ld in enumerate(self.scene.loads) if ld.driver is not None]
        if not scaled or "forces" not in self.art["stages"]:
            return None
        P = list(self.params)
        for i, ld in scaled:
            k = load_factor(ld, q)
            for j, (_, recipe) in enumerate(self.art["params"]):
                if recipe[0] in ("Fx", "Fy", "T") and recipe[1] == i:
                    P[j] = self.params[j] * k
        return P

    def _get(self, pts, key):
        a, b = self.art["layout"][key]
        return pts[a:b]

    def _forces(self, pts, points, Xk, CS, rate_ok, idx, N):
        """Forces at the steps with rates.  A gear mesh's tooth load must press: solved with
        every flank +1, then again with the flanks the tooth loads show (as the numeric
        solver does, :mod:`linkage_sym.numeric.forces.kinetostatics`)."""
        art = self.art
        sel = rate_ok
        Kk = int(sel.sum())
        fidx = {nm: i for i, nm in enumerate(art["force_names"])}
        ok_idx = idx[sel]
        flank = np.ones((len(self.flanks), len(sel)))
        solves = 1 + 2 * len(self.flanks)
        for _ in range(solves):
            Fv = self._force_solve(pts, sel, Kk)
            pulling = {}
            for m, name in enumerate(self.flanks):
                neg = Fv[fidx[f"Fn_{ident(name)}"]] < 0
                if neg.any():
                    flank[m, np.flatnonzero(sel)[neg]] *= -1.0
                    pulling[name] = np.flatnonzero(neg)
            if not pulling:
                break
            pts = points(flank)
        notes = [pulling_note(name, ok_idx[bad], solves) for name, bad in pulling.items()]
        P = None
        if len(self.flanks):  # the frame's mesh forces on the flanks settled on
            P = list(self.params)
            at = self.n_params + art["sigmas"]
            P[at:at + len(self.flanks)] = [f[sel] for f in flank]
        return self._force_records(pts, Fv, Xk, CS, sel, ok_idx, N, fidx, notes, P)

    def _force_solve(self, pts, sel, Kk):
        """The group blocks solved from the last group back, at the steps ``sel``."""
        art = self.art
        Fv = np.zeros((len(art["force_names"]), Kk))
        for g, lay in reversed(list(zip(art["groups"], art["forces"]))):
            k = g["index"]
            unk = lay["unknowns"]
            n = len(unk)
            A = np.zeros((Kk, n, n))
            for (i, j), v in zip(lay["A"], self._get(pts, f"A:{k}")):
                A[:, i, j] = v[sel]
            b = np.stack([v[sel] for v in self._get(pts, f"b:{k}")], axis=1)
            for (i, fi), v in zip(lay["C"], self._get(pts, f"C:{k}")):
                b[:, i] -= v[sel] * Fv[fi]
            if Kk:
                Fv[unk] = np.linalg.solve(A, b[..., None])[..., 0].T
        return Fv

    def _force_records(self, pts, Fv, Xk, CS, sel, ok_idx, N, fidx, notes, P):
        art = self.art
        Kk = len(ok_idx)
        fx, fy, mz = (
            np.broadcast_to(np.asarray(v, float), (Kk,))
            for v in self._call(
                "frame", X=list(Xk[:, sel]), F=list(Fv),
                CS=(list(CS[0][:, sel]), list(CS[1][:, sel])), P=P,
            )
        )
        def spread(v):
            out = np.full(N, np.nan)
            out[ok_idx] = v
            return out

        reactions, moments = {}, {}
        for j in self.scene.joints:
            n = ident(j.name)
            if j.type == "R":
                rx, ry = Fv[fidx[f"R_{n}x"]], Fv[fidx[f"R_{n}y"]]
                mm = np.zeros(Kk)
            elif j.type == "G":  # the tooth load on the line of action (gear a on gear b)
                ux, uy = (v[sel] for v in self._get(pts, f"mesh:{j.name}"))
                Fn = Fv[fidx[f"Fn_{n}"]]
                rx, ry, mm = ux * Fn, uy * Fn, np.zeros(Kk)
            else:
                ux, uy = (v[sel] for v in self._get(pts, f"slide:{j.name}"))
                Nn = Fv[fidx[f"N_{n}"]]
                rx, ry, mm = -uy * Nn, ux * Nn, Fv[fidx[f"M_{n}"]]
            reactions[j.name] = np.stack([spread(rx), spread(ry)], axis=-1)
            moments[j.name] = spread(mm)
        driving = {}
        for d in self.scene.drivers:
            n = ident(d.joint)
            driving[d.joint] = spread(Fv[fidx[("tau_" if d.kind == "R" else "f_") + n]])
        return Forces(
            method="symbolic",
            reactions=reactions,
            reaction_moments=moments,
            driving=driving,
            frame_force=np.stack([spread(fx), spread(fy)], axis=-1),
            frame_moment=spread(mz),
            groups=[GroupForces(tuple(g["links"]), "symbolic") for g in art["groups"]],
            notes=notes,
        )

    def _analysis(self, X, XD, XDD, CS, pts, idx, status, messages, condition, forces, q, qd, qdd):
        """Write the results into a result block (:class:`ResultLayout`, as the numeric
        plan does): the values at the steps ``idx`` where positions were solved; the
        layout blanks the steps without a solution."""
        scene, art = self.scene, self.art
        N = len(status)
        stages = tuple(art["stages"])
        has_v, has_a = "velocity" in stages, "acceleration" in stages
        lay = self._layout
        block = np.empty((lay.n_rows, N))
        if len(idx) < N:
            block[:] = np.nan
        links, joints, points = lay.records(scene, block, stages)
        every = len(idx) == N
        motion = {}  # link -> cos, sin of its rotation, origin (, omega, its velocity, alpha, ...)

        def put(dest, v):  # a row (N,), or a pair of rows (2, N) given as two values
            if dest.ndim == 2:
                if every:
                    dest[0], dest[1] = v[0], v[1]
                else:
                    dest[0, idx], dest[1, idx] = v[0], v[1]
            elif every:
                dest[...] = v
            else:
                dest[idx] = v

        for j in scene.joints:
            rec = joints[j.name]
            put(rec.position.T, self._get(pts, f"joint:{j.name}:0"))
            if has_v:
                put(rec.velocity.T, self._get(pts, f"joint:{j.name}:1"))
            if has_a:
                put(rec.acceleration.T, self._get(pts, f"joint:{j.name}:2"))
        for link in scene.links:
            n, lk = link.name, links[link.name]
            c = self.angle_of[n]
            fr = self.frames[n]
            lk.rotation[...] = X[c] - fr.theta0
            # the rotation's cosine and sine from those of the coordinate (no new cos/sin)
            ct, st = math.cos(fr.theta0), math.sin(fr.theta0)
            cr, sr = CS[0][c] * ct + CS[1][c] * st, CS[1][c] * ct - CS[0][c] * st
            # the link point at the global origin in the assembly configuration
            Ux, Uy = fr.origin
            dx, dy = -(cr * Ux - sr * Uy), -(sr * Ux + cr * Uy)
            ux, uy = self._get(pts, f"origin:{n}:0")
            motion[n] = m = [cr, sr, ux + dx, uy + dy]
            put(lk.origin.T, m[2:4])
            if has_v:
                w = XD[c]
                vx, vy = self._get(pts, f"origin:{n}:1")
                m += [w, vx - w * dy, vy + w * dx]
                put(lk.omega, w)
                put(lk.origin_velocity.T, m[5:7])
            if has_a:
                w, al = XD[c], XDD[c]
                ax, ay = self._get(pts, f"origin:{n}:2")
                m += [al, ax - al * dy - w * w * dx, ay + al * dx - w * w * dy]
                put(lk.alpha, al)
                put(lk.origin_acceleration.T, m[8:10])
            if link.com is not None:
                put(lk.com.T, self._get(pts, f"com:{n}:0"))
                if has_v:
                    put(lk.com_velocity.T, self._get(pts, f"com:{n}:1"))
                if has_a:
                    put(lk.com_acceleration.T, self._get(pts, f"com:{n}:2"))
        # traced points (the format's ``points`` extension): rigid with their link, from its
        # rotation and origin motion at the solved steps (not part of the generated code)
        for pt in scene.points:
            rec, m = points[pt.name], motion[pt.link]
            cr, sr = m[0], m[1]
            rx, ry = cr * pt.at[0] - sr * pt.at[1], sr * pt.at[0] + cr * pt.at[1]
            put(rec.position.T, (m[2] + rx, m[3] + ry))
            if has_v:
                w = m[4]
                put(rec.velocity.T, (m[5] - w * ry, m[6] + w * rx))
            if has_a:
                w, al = m[4], m[7]
                put(rec.acceleration.T, (m[8] - al * ry - w * w * rx, m[9] + al * rx - w * w * ry))
        lay.invalidate(block, status)
        return new_analysis(scene, stages, status, messages, {k: q[k] for k in art["q"]}, qd, qdd,
                            joints, links, points, condition, forces)


def load_compiled(scene: Scene) -> CompiledMechanism | None:
    """The compiled mechanism of ``scene``'s topology from the cache, or ``None``.

    Needs neither SymPy nor a derivation: the cached functions are bound to
    this scene's parameter values.
    """
    art = cache.load(cache.key_of(cache.signature(scene)))
    return None if art is None else CompiledMechanism(art, scene)
