"""The numba backend of the design sweep: the generated closed forms compiled, one loop over
a chunk's designs in blocks, steps outer and designs inner.

:class:`NumbaModel` is :class:`~linkage_sym.design.evaluate.Model` (the NumPy backend of
the designs) whose :meth:`~NumbaModel.solve` runs the chunk's positions, singularity
screen, rates along the steps and transmission angles in one compiled loop (printed per
artifact by :func:`~linkage_sym.design.numba_block.block_source`: over a block of designs
at each step without a branch, so that the compiler vectorises it, the rare entries
after, one at a time, by :func:`~linkage_sym.design.numba_kernel.entry_source`), with the
artifact's own functions printed as scalar code (:mod:`linkage_sym.codegen.scalar`) and
compiled by ``numba.njit``; the limit positions' Newton iteration is compiled too
(:meth:`~NumbaModel.compiled_roots`, :mod:`linkage_sym.design.numba_newton`).  The
designs' assembly configurations (a few operations per design) and the metric columns
stay NumPy's.  The numbers are the NumPy backend's within a few rounding errors (the same
formulas in the same order, evaluated one entry at a time instead of over arrays;
observed: equal bit for bit).

It serves the metrics that read positions and the rates along the steps:
:data:`SUPPORTED` (``assemblable``, ``grashof``, ``K``, ``min_transmission_deg``), for a
scene whose positions are closed forms given as directions (every group a dyad or an
input link: :class:`~linkage_sym.codegen.artifact.ClosedStep` with ``directions``) and
whose blocks are at most 3x3.  Anything else is refused by :func:`check_support`, saying
why.

Compiled functions are kept per artifact in this process (:func:`compiled_functions`):
the first chunk pays the compilation, the others reuse it.  They are not cached on disk
(numba's ``cache=True``): numba caches a function by its source file, and the generated
functions are executed from text.
"""

from __future__ import annotations

import hashlib
import math
import re

import numpy as np

from linkage_sym.codegen.evaluator import numpy_namespace
from linkage_sym.codegen.scalar import scalar_function, scalar_helpers
from linkage_sym.design.errors import SweepError
from linkage_sym.design.evaluate import Model
from linkage_sym.design.solution import Solution
from linkage_sym.numeric.engine.run import SCREEN, SINGULAR_COND
from linkage_sym.numeric.kinematics.loci import _EPS, TANGENT_ULPS

__all__ = ["BACKENDS", "SUPPORTED", "NumbaModel", "check_support", "compiled_functions",
           "require_numba"]

BACKENDS = ("numpy", "numba")
"""The design sweep's backends: NumPy arrays over designs x steps (the default), or a loop
compiled by numba."""

SUPPORTED = ("assemblable", "grashof", "K", "min_transmission_deg")
"""The metrics the numba backend computes."""


def require_numba():
    """The ``numba`` module, or a :class:`SweepError` naming the extra that installs it."""
    try:
        import numba
    except ImportError:
        raise SweepError("backend", "the numba backend needs numba, which is not installed: "
                                    "pip install 'linkage_sym[numba]'") from None
    return numba


def check_support(model: Model, metrics, need, unwrap) -> None:
    """Refuse what the numba backend does not compute, saying why: metrics other than
    :data:`SUPPORTED`, groups without a closed form, positions not given as directions,
    blocks larger than 3x3."""
    other = [m for m in metrics if m not in SUPPORTED]
    if other or unwrap or need - {"rate_t"}:
        raise SweepError("backend", f"the numba backend computes {', '.join(SUPPORTED)}; "
                                    f"not {', '.join(other)} (it reads the angles themselves, "
                                    "velocities, points or forces, which its compiled loop "
                                    "does not evaluate): use the NumPy backend")
    if model.newton_groups:
        raise SweepError("backend", "the numba backend solves closed forms only; scene "
                                    f"{model.scene.name!r} has groups without one "
                                    f"({', '.join(model.newton_groups)}), solved by Newton's "
                                    "method design by design: use the NumPy backend")
    if model.directions is None:
        raise SweepError("backend", f"the numba backend evaluates the positions as directions "
                                    f"(cosines and sines, no angle); scene {model.scene.name!r}"
                                    "'s rate equations read the angles themselves (or its "
                                    "closed forms come in several steps): use the NumPy backend")
    big = [g.title for g in model.art.groups if len(g.cols) > 3]
    if big:
        raise SweepError("backend", f"the numba backend solves blocks of up to 3 coordinates; "
                                    f"{', '.join(big)} has more: use the NumPy backend")


_COMPILED: dict = {}
"""Compiled scalar functions by the generated sources' digest (this process)."""


def compiled_functions(art, names) -> tuple:
    """``({name: (function, pre_function, outputs, hoisted, scalar)}, namespace)``: the
    artifact's generated functions ``names`` printed as scalar code
    (:class:`~linkage_sym.codegen.scalar.ScalarFunction` ``scalar``) and compiled by
    ``numba.njit``, and the namespace that holds them and their helpers (kept per
    artifact for this process)."""
    numba = require_numba()
    digest = hashlib.sha256("\0".join(art.functions[n] for n in names).encode()).hexdigest()
    got = _COMPILED.get(digest)
    if got is not None:
        return got
    scalars = {n: scalar_function(art.functions[n], n) for n in names}
    arities: dict = {}
    for s in scalars.values():
        for h, ks in s.arities.items():
            arities.setdefault(h, set()).update(ks)
    ns = numpy_namespace()
    ns.update(TANGENT_ULPS=TANGENT_ULPS, EPS=_EPS, nan=np.nan)
    jit = numba.njit(error_model="numpy", inline="always")
    _define(ns, scalar_helpers(arities), jit)
    fns = {}
    for n, s in scalars.items():
        fns[n] = (_define(ns, s.source, jit), _define(ns, s.pre_source, jit), s.outputs,
                  s.hoisted, s)
    got = _COMPILED[digest] = (fns, ns)
    return got


def _define(ns: dict, source: str, jit):
    """Execute ``source`` in ``ns``, each function it defines replaced by its compiled
    form; the last one (None when it defines none)."""
    exec(compile(source, "<linkage_sym scalar>", "exec"), ns)
    names = re.findall(r"^def (\w+)\(", source, re.M)
    for name in names:
        ns[name] = jit(ns[name])
    return ns[names[-1]] if names else None


def compiled_kernel(model, step, dyads, col):
    """The compiled loop of ``model``'s artifact for the ``dyads`` and the rate of ``col``
    (:func:`~linkage_sym.design.numba_block.block_source`, which calls
    :func:`~linkage_sym.design.numba_kernel.entry_source`'s ``entry``; kept per artifact in
    this process)."""
    numba = require_numba()
    names = [step.directions, "rates"]
    fns, fns_ns = compiled_functions(model.art, names + ["accelerations", step.function])
    from linkage_sym.design import numba_block, numba_kernel, numba_newton

    layout = (step.x, step.forms, model.art.blocks, model.art.pattern, model.m, dyads, col)
    entry = numba_kernel.entry_source(step.directions, "rates", *layout)
    scalars = {n: fns[n][4] for n in names}
    loop = numba_block.block_source(scalars, step.directions, "rates", *layout,
                                    len(model.params), len(model.Q))
    key = hashlib.sha256((entry + loop + "\0".join(model.art.functions[n] for n in names))
                         .encode()).hexdigest()
    got = _COMPILED.get(key)
    if got is None:
        ns = dict(fns_ns)
        ns.update({"np": np, "nan": np.nan, "inf": np.inf, "sqrt": math.sqrt,
                   "unit_direction": numba_kernel.unit_direction, "fmax": numba_kernel.fmax,
                   "fmax_select": numba_kernel.fmax_select, "singular": numba_kernel.singular})
        _define(ns, entry, numba.njit(error_model="numpy"))
        # the loop's own helpers: math.sqrt, which the compiler vectorises (NumPy's sqrt,
        # a library call, it does not); the same correctly rounded square root
        arities: dict = {}
        for s in scalars.values():
            for h, ks in s.arities.items():
                arities.setdefault(h, set()).update(ks)
        ns["sqrt"] = math.sqrt
        _define(ns, scalar_helpers(arities), numba.njit(error_model="numpy", inline="always"))
        _define(ns, numba_newton.newton_source(step.function, step.x, model.art.blocks,
                                               model.art.pattern, model.m, col, len(model.Q)),
                numba.njit(error_model="numpy"))
        got = _COMPILED[key] = (_define(ns, loop, numba.njit(error_model="numpy")), ns["newton"])
    return fns, got


class NumbaModel(Model):
    """The numba backend of the design sweep (see the module docstring).

    Parameters
    ----------
    scene : Scene
    plan : MetricPlan
        The metrics asked for (checked by :func:`check_support`); its dyads' transmission
        angles and its output's limit positions are found in the compiled loop.
    forces : bool
        Compile the force blocks too (a varied mass or load: the functions the loop
        calls are the same).
    """

    chunk_entries = 1 << 22
    """Designs x steps per chunk by default: the loop keeps no array over the coordinates
    (a block of designs' rates and codes only), so chunks larger than the NumPy backend's
    (:data:`~linkage_sym.design.execute.TARGET_ENTRIES`) cost no cache, and spare Python's
    overhead per chunk (measured, the benchmark's 40,000 crank-rockers at load 6, best of 4:
    2^20 entries 0.34-0.38 CPU s, 2^22 0.33-0.35 s)."""

    def __init__(self, scene, plan, forces: bool = False):
        require_numba()
        super().__init__(scene, forces)
        check_support(self, plan.metrics, plan.need, plan.unwrap(self))
        self.plan = plan
        step = self.directions
        rates = plan.rates(self)
        self.col = rates[0] if rates else None
        self.dyads = [(self.angle_of[a], self.angle_of[b]) for _, _, _, a, b in plan.dyads]
        self.fn, (self.kernel, self._newton) = compiled_kernel(self, step, self.dyads, self.col)
        self.rows_length = np.array(self.art.rows_length, dtype=bool)
        self.cols_length = np.array(self.art.cols_length, dtype=bool)
        self.pattern_array = np.array(self.art.pattern, dtype=np.int64).reshape(-1, 2)
        self.Qs = np.ascontiguousarray(self.Q.T)
        self.QDs = np.array(self.slope, dtype=float)
        self.QDDs = np.zeros(len(self.QDs))
        self.H = {name: self._hoisted(name) for name in (step.directions, "rates")}
        f = self.fn
        used = (step.function, "rates", "accelerations")  # by the compiled Newton
        self.newton_sizes = np.array([max(f[n][3], 1) for n in used] + [f[n][2] for n in used],
                                     dtype=np.int64)
        self.screen_args = np.array([SCREEN * SCREEN, SINGULAR_COND, self.fn[step.directions][2],
                                     self.fn["rates"][2]], dtype=float)

    def _hoisted(self, name):
        """The hoisted terms (N, k) of function ``name`` at every step."""
        _, pre, _, k, _ = self.fn[name]
        H = np.zeros((self.N, max(k, 1)))
        for t in range(self.N):
            pre(self.Qs[t], self.QDs, self.QDDs, H[t])
        return H

    def compiled_roots(self, P, a, fa, fb, col):
        """``(t, kind)`` of :func:`~linkage_sym.design.limits.roots` on the brackets (steps
        ``a``, rates ``fa``, ``fb``; ``P``: the brackets' designs' parameters) of the
        output's coordinate ``col`` by the compiled Newton
        (:mod:`linkage_sym.design.numba_newton`); None for a coordinate other than the
        output the model was compiled for."""
        if col != self.col:
            return None
        k = len(a)
        PB = np.empty((k, len(P)))
        for i, v in enumerate(P):
            PB[:, i] = v
        t, kind = np.empty(k), np.empty(k, np.int64)
        self._newton(PB, np.ascontiguousarray(a, dtype=float), np.ascontiguousarray(fa, dtype=float),
                     np.ascontiguousarray(fb, dtype=float), self.Qs, self.QDs, self.QDDs, t, kind,
                     self.newton_sizes)
        return t, kind

    def solve(self, P, n, need, unwrap=(), assembly=None, rates=None) -> Solution:
        """Solve ``n`` designs at the sweep's steps in the compiled loop: the positions'
        status (``pos_ok``, ``ok``), in :attr:`~Solution.brackets` the steps between which
        the output's rate along the steps changes sign, in :attr:`~Solution.transmission`
        each dyad's smallest transmission ratio (see :meth:`Model.solve` for the
        arguments; ``need``, ``unwrap`` and ``rates`` are the plan's, checked when the
        model was made)."""
        P, X0, assembled, joints0, L = self.assemble(P, n) if assembly is None else assembly
        N = self.N
        offsets = self.plan.transmission_offsets(self, joints0, X0)
        k = len(offsets)
        cc = np.array([c for _, _, c, _ in offsets]).reshape(k, n)
        sc = np.array([s for _, _, _, s in offsets]).reshape(k, n)
        D = np.empty((len(P) + 2 * k + 1, n))  # what the loop over designs reads
        for i, v in enumerate(P):
            D[i] = v
        D[len(P):len(P) + k], D[len(P) + k:len(P) + 2 * k] = cc, sc
        D[-1] = assembled
        pos_ok, ok = np.empty((n, N), bool), np.empty((n, N), bool)
        tmin = np.empty((k, n))
        args = (D, np.ascontiguousarray(D[:len(P)].T), self.H[self.directions.directions],
                self.H["rates"], self.Qs, self.QDs, self.QDDs, assembled,
                np.ascontiguousarray(L, dtype=float), cc, sc, self.screen_args,
                self.rows_length, self.cols_length, self.pattern_array, pos_ok, ok, tmin)
        cap = 4 * n + 64  # two limit positions a design, as a rule
        while True:
            bd, bi = np.empty(cap, np.int64), np.empty(cap, np.int64)
            bfa, bfb = np.empty(cap), np.empty(cap)
            nb = self.kernel(*args, bd, bi, bfa, bfb)
            if nb <= cap:
                break
            cap = nb  # more brackets than the arrays held: again, with room for all
        sol = Solution(n, N, P, assembled, X0, joints0, L, None, pos_ok, ok, model=self)
        sol.transmission = tmin if k else None
        if self.col is not None:
            sol.brackets = (bd[:nb].copy(), bi[:nb].copy(), bfa[:nb].copy(), bfb[:nb].copy())
        return sol
