"""Arbitrary precision: the derived equations evaluated in mpmath, rounded to float64.

``linkage_sym.analyze(scene, precision=50)`` (``linkage-sym analyze --precision 50``)
evaluates the mechanism's SymPy-derived equations (:mod:`linkage_sym.symbolic.mechanism`)
with mpmath at the given number of significant decimal digits, one step at a time:

1. **parameters** (lengths, angles, coordinates, masses, loads) from the scene's numbers
   by the same recipes as float64 (:mod:`linkage_sym.structure.recipes`), in mpmath:
   the binary64 numbers of the scene are the mechanism, converted exactly; and each
   step's **driver values** from the scene's numbers too: step ``i`` is
   ``start + i (stop - start) / (steps - 1)`` (an ``R`` driver's ``start_deg`` and
   ``stop_deg`` in degrees, converted with ``mpmath.pi``) at the working precision
   (:func:`driver_step_mp`), not the float64 sweep's rounding of it (180 degrees is
   ``float(pi)`` there: near a dead centre, where the output's rate against the driver is
   unbounded, that rounding alone moves positions by ~1e-8);
2. **positions**: the nested closed forms of input links and dyads (the assembly-mode
   signs chosen as the compiled mechanism chooses them); a group without a closed form
   by Newton's method on its loop equations in mpmath, from the float64 solution of the
   same path (quadratic convergence: 50 digits in three or four iterations), so the
   root is the one the continuation policy reached;
3. **rates**: ``A xd = B qd`` and ``A xdd = rhs`` by mpmath LU solves, group block by
   group block; joints, links' origins, centres of mass by the derived point equations;
4. **forces**: each group's equilibrium block ``A_g F_g = b_g - C_g F_later`` by mpmath
   LU solves from the last group back, then the frame force and moment.

Driver values a caller gives (``run_precise(scene, digits, q, qd, qdd)``) are taken as
the binary64 numbers they are, except values of the scene's own sweep, which stand for
their steps (:meth:`PreciseMechanism.driver_values`: so the command line's chunks of the
sweep get the exact steps).  The accuracy estimate is the float64 run's condition numbers,
times how much smaller the group blocks' indicator (their Hadamard ratios) is at the exact
driver value than at the float64 run's rounded one (:meth:`PreciseMechanism._gain`), with
``10^-digits`` for eps, plus the rounding to float64, plus, at a step whose driver value
still carries a rounding (steps of the sweep closer than an ulp), that rounding amplified
alike.

The statuses (unassemblable, singular), messages and warnings come from the float64
run of the same compiled mechanism, but for steps where this precision tells otherwise:
no real position (unassemblable), a group block exactly singular, or a condition number
so estimated above the singularity threshold (a step exactly at a dead centre, which
float64's rounded driver value kept a tangency's width away) -- singular, positions
only.  At the ``ok`` steps every value is then the
mpmath value rounded once to float64 (traced points and link origins are computed in
mpmath from the link's rotation too).  The result is the same
:class:`~linkage_sym.numeric.results.result.Analysis` as every other method's, with
``forces.method == "mpmath"``; :class:`PreciseResult` keeps the unrounded values.

The functions are the ones :func:`linkage_sym.codegen.compile.build_artifact` generates
for NumPy, printed for mpmath instead (rationals as quotients of ``mpf``), built once
per topology in a process.  :class:`PreciseMechanism` is their mpmath backend of the one
evaluator of generated code (:class:`~linkage_sym.codegen.evaluator.Evaluator`: the
calls, the walk over the position steps, the rate and force solves, the loads, the
reactions, a link's frame and its points written once); it says what a number is
(:class:`MpNumbers`, for the parameters' recipes too) and how a step, a block and a
group's forces are solved in mpmath.  Cost: mpmath in pure Python, about 10^3--10^4
times the float64 solver per position (see ``benchmarks/bench_accuracy.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import mpmath as mp
import numpy as np

from linkage_sym.codegen import cache
from linkage_sym.codegen.artifact import Artifact
from linkage_sym.codegen.compile import build_artifact, compile_mechanism
from linkage_sym.codegen.evaluator import Evaluator, frame_motion, load_functions, rigid_point
from linkage_sym.codegen.precise_friction import friction_record, friction_targets
from linkage_sym.codegen.runtime import CompiledMechanism
from linkage_sym.model import Scene
from linkage_sym.numeric.results import accuracy
from linkage_sym.numeric.results.result import OK, SINGULAR, UNASSEMBLABLE, GroupForces
from linkage_sym.numeric.engine.run import SINGULAR_COND
from linkage_sym.codegen.mp_numbers import (
    DOUBLE,
    MpBlocks,
    MpNumbers,
    NotReal,
    driver_numbers,
    driver_step_mp,
    MpOps,
    factor_mp,
    mp_namespace,
    parse_precision,
    real,
)
from linkage_sym.structure.recipes import Context

NEWTON_ITER = 30

_ARTIFACTS: dict[str, Artifact] = {}



def mp_artifact(scene: Scene) -> Artifact:
    """The mechanism's functions printed for mpmath (built once per topology and process)."""
    key = cache.key_of(cache.signature(scene))
    art = _ARTIFACTS.get(key)
    if art is None:
        art = build_artifact(scene, printer="mpmath")
        _ARTIFACTS[key] = art
    return art


@dataclass
class _StepContext:
    """What the position steps of one step read: the parameters, the driver values (mpf)
    and the float64 run's coordinates there (the root a group's Newton starts from, the
    turn an angle is counted in)."""

    P: list
    Q: list
    x_float: object


@dataclass
class PreciseResult:
    """What :func:`run_precise` computed.

    Attributes
    ----------
    analysis : Analysis
        The usual result, every value at an ``ok`` step the mpmath value rounded to float64.
    digits : int
        Significant decimal digits of the evaluation (``mp.dps``).
    steps : list of (dict or None)
        Per step, the unrounded mpmath values (``None`` where the step has no
        positions): ``"x"``, ``"xd"``, ``"xdd"`` (the derived coordinates, in the order
        of ``x_names``), ``"links"`` ``{name: {"rotation", "omega", "alpha"}}``,
        ``"joints"`` ``{name: {"position", "velocity", "acceleration"}}`` (pairs),
        ``"points"`` likewise, and with forces ``"reactions"`` ``{joint: (fx, fy)}``,
        ``"reaction_moments"``, ``"driving"``, ``"frame"`` ``(fx, fy, m)``, ``"springs"``
        ``{name: (length or angle, effort)}``.
    x_names : list of str
    """

    analysis: object
    digits: int
    steps: list = field(default_factory=list)
    x_names: list = field(default_factory=list)


_ROUNDED = (("joints", ("position", "velocity", "acceleration")),
            ("points", ("position", "velocity", "acceleration")),
            ("links", ("rotation", "origin", "omega", "alpha", "origin_velocity",
                       "origin_acceleration", "com", "com_velocity", "com_acceleration")))
"""The kinematics an Analysis holds per joint, traced point and link, by record section."""
_AT_POSITIONS = {"position", "rotation", "origin", "com"}
"""Those of :data:`_ROUNDED` that every step with positions has (the others need rates)."""


class PreciseMechanism(Evaluator):
    """A scene's derived equations in mpmath (see the module docstring): the mpmath
    backend of :class:`~linkage_sym.codegen.evaluator.Evaluator`, one step at a time.

    Attributes
    ----------
    cm : CompiledMechanism
        The float64 run of the same mechanism (statuses, messages, the roots the
        continuation reached, the accuracy estimate).
    context : linkage_sym.structure.recipes.Context
        The scene with its link frames in mpmath (:class:`MpNumbers`).
    """

    def __init__(self, scene: Scene, digits: int, compiled: CompiledMechanism | None = None):
        self.scene = scene
        self.digits = digits
        self.cm = cm = compiled if compiled is not None else compile_mechanism(scene)
        art = mp_artifact(scene)
        if art.x != cm.art.x or art.pattern != cm.art.pattern:
            raise RuntimeError(  # pragma: no cover - both are built from one derivation
                "mpmath and NumPy functions of one mechanism disagree in layout")
        with mp.workdps(digits):
            numbers = MpNumbers()
            self.context = Context(scene, cm.frames, numbers)
            for link in cm.frames:
                self.context.frame(link)  # the frames at this precision, made once
            params = [p.recipe.value(scene, cm.frames, numbers) for p in art.params]
            sig = cm.params[cm.n_params:cm.n_params + art.sigmas]
            # then each gear mesh's flank, +1 until a tooth load says otherwise (step)
            params += [mp.mpf(float(s)) for s in sig] + [mp.mpf(1)] * len(art.flanks)
        super().__init__(art, load_functions(art, "mpmath", mp_namespace()), params)
        self.scaled = [(i, ld) for i, ld in enumerate(scene.loads) if ld.driver is not None]
        self._steps_of: dict = {}  # a driver's float64 step values -> step (driver_values)

    # -- driver values --------------------------------------------------------------
    def _step_index(self, name: str) -> dict:
        """``{float64 value: step}`` of the scene's sweep of driver ``name`` (-1 where two
        steps round to one value and their exact values differ)."""
        got = self._steps_of.get(name)
        if got is None:
            driver = next(d for d in self.scene.drivers if d.joint == name)
            start, stop, _ = driver_numbers(driver)
            values = np.asarray(self.cm.sweep()[0][name], float)
            got = {}
            for i, v in enumerate(values.tolist()):
                if got.setdefault(v, i) != i and start != stop:
                    got[v] = -1
            self._steps_of[name] = got
        return got

    def driver_values(self, Q) -> tuple[list, np.ndarray]:
        """The driver values of each step in mpmath, and the rounding they still carry.

        ``Q`` (D, N): float64 driver values, rows in the order of ``artifact["q"]``.  A
        value that is the float64 value of a step of the scene's own sweep of that driver
        (every value of that sweep, and of any part of it: the command line solves it in
        chunks) stands for that step, and gets the step's exact value from the scene's
        numbers (:func:`driver_step_mp`); any other value is taken as the exact binary64
        number it is.  Call it at the working precision.

        Returns
        -------
        values : list of (list of mpf)
            Per column of ``Q``, the drivers' values.
        rounding : ndarray (N,)
            Per column, the largest relative error a value still carries: 0, unless two
            steps of the scene's sweep round to one float64 value (steps less than an ulp
            apart) whose exact values differ; there ``eps |q|`` (rad for an ``R`` driver,
            over the mechanism's size for a ``P`` driver), which the accuracy estimate
            amplifies as it does the arithmetic's rounding.
        """
        drivers = {d.joint: d for d in self.scene.drivers}
        index = [self._step_index(n) for n in self.art.q]
        scale = [1.0 if drivers[n].kind == "R" else self.cm.L for n in self.art.q]
        Q = np.asarray(Q, float)
        out, rounding = [], np.zeros(Q.shape[1])
        for k, col in enumerate(Q.T):
            vals = []
            for n, idx, sc, v in zip(self.art.q, index, scale, col.tolist()):
                i = idx.get(v)
                vals.append(mp.mpf(v) if i is None or i < 0 else driver_step_mp(drivers[n], i))
                if i is not None and i < 0:
                    rounding[k] = max(rounding[k], accuracy.EPS * abs(v) / sc)
            out.append(vals)
        return out, rounding

    # -- one step -------------------------------------------------------------------
    # -- one step: the hooks of the evaluator -----------------------------------------
    def coordinate(self, c, value, ctx):
        """A closed form's value: real (else :class:`NotReal`), an angle shifted by whole
        turns toward the float64 run's (the turn the continuation counted)."""
        v = real(value)
        if self.art.is_angle[c]:
            v = v + 2 * mp.pi * round(float((ctx.x_float[c] - v) / (2 * mp.pi)))
        return v

    def newton_step(self, step, X, ctx):
        """A group without a closed form: Newton's method on its loop equations in mpmath,
        from the float64 run's root (quadratic convergence: that root, to every digit)."""
        cols = step.x
        for c in cols:
            X[c] = mp.mpf(float(ctx.x_float[c]))
        n = len(cols)
        tol = mp.mpf(10) ** (-self.digits + 2)
        scale = [1 if self.art.is_angle[c] else self.cm.L for c in cols]
        for _ in range(NEWTON_ITER):
            out = self.call(step.function, ctx.P, X=X, Q=ctx.Q)
            r = mp.matrix(out[:n])
            J = mp.matrix(n, n)
            for a in range(n):
                for b in range(n):
                    J[a, b] = out[n + a * n + b]
            d = mp.lu_solve(J, r)
            for kk, c in enumerate(cols):
                X[c] -= d[kk]
            if max(abs(d[kk]) / scale[kk] for kk in range(n)) <= tol:
                return
        raise NotReal  # pragma: no cover - Newton from a float64 root converges

    def block_system(self, entries, shape):
        return MpBlocks(entries, self.art.blocks, self.m)

    def dense_solve(self, pattern, values, b):
        n = len(b)
        A = mp.matrix(n, n)
        for (i, j), v in zip(pattern, values):
            A[i, j] = v
        sol = mp.lu_solve(A, mp.matrix(b))
        return [sol[j] for j in range(n)]

    def force_zeros(self, like):
        return [mp.mpf(0)] * len(self.art.force_names)

    def friction_ops(self):
        return MpOps(self.digits)

    def positions(self, Q, x_float):
        """Coordinates (list of mpf) at driver values ``Q`` (mpf), near ``x_float``."""
        return self.walk([None] * self.m, _StepContext(self.params, Q, x_float))

    def _float_ratios(self, Xf, Qs, QDs, steps) -> np.ndarray:
        """The float64 runtime's indicator (the smallest Hadamard ratio of a group block) at
        ``steps``, at its own positions ``Xf`` (m, N) and driver values (inf: 1x1 blocks)."""
        A, _ = self.cm.rate_system(Xf[:, steps], list(Qs[:, steps]), list(QDs[:, steps]))
        out = np.full(len(steps), np.inf)
        for r in A.ratios():
            if r is not None:
                out = np.fmin(out, r)
        return out

    def step(self, q, qd, qdd, x_float, rates: bool, stages, q_float=None) -> dict:
        """Every value at one step (mpf), from driver values ``q`` (mpf, or floats taken as
        the exact binary64 numbers they are; ``q_float`` their float64 values, ``q`` itself
        unless given: see :meth:`driver_values`)."""
        Q = [v if isinstance(v, mp.mpf) else mp.mpf(float(v)) for v in q]
        if q_float is None:
            q_float = [float(v) for v in q]
        QD = [mp.mpf(float(v)) for v in qd]
        QDD = [mp.mpf(float(v)) for v in qdd]
        X = self.positions(Q, x_float)
        CS = ([mp.cos(v) for v in X], [mp.sin(v) for v in X])
        zero = [mp.mpf(0)] * self.m
        XD, XDD = zero, zero
        ratio = None
        if rates:  # the rate system: its blocks' indicator, and the rates if asked
            A, Bqd = self.rate_system(X, Q, QD, CS)
            ratio = min((r for r in A.ratios() if r is not None), default=None)
        if rates and "velocity" in stages:
            XD = A.solve(Bqd)
            if "acceleration" in stages:
                XDD = A.solve(self.accelerations_rhs(X, XD, Q, QD, QDD, CS))
        P = self.params
        if self.scaled and "forces" in stages:  # loads over the cycle: scaled at this step
            # every factor, so that a step outside a load's table is refused
            factors = {i: factor_mp(ld, Q[self.art.q.index(ld.driver)],
                                     float(q_float[self.art.q.index(ld.driver)]))
                       for i, ld in self.scaled}
            P = self.scaled_loads(P, factors) or P
        pts = self.call("points", P, X=X, XD=XD, XDD=XDD, Q=Q, QD=QD, QDD=QDD, CS=CS)
        rec = {"x": X, "xd": XD, "xdd": XDD, "pts": pts, "ratio": ratio}
        if rates and "forces" in stages:
            F, fric = self.forces_and_friction(pts)  # with the joints' friction where it acts
            # a gear mesh's tooth load must press: the other flank where it pulls, as the
            # float64 runtime does (CompiledMechanism._forces)
            at, n = self.art.flank_at, len(self.art.flanks)
            for _ in range(2 * n):
                pull = self.pulling(F)
                if not any(pull):
                    break
                P = self.with_flanks(P, [-f if p else f for f, p in zip(P[at:at + n], pull)])
                pts = self.call("points", P, X=X, XD=XD, XDD=XDD, Q=Q, QD=QD, QDD=QDD, CS=CS)
                F, fric = self.forces_and_friction(pts)
            rec["pts"], rec["F"] = pts, F
            if fric is not None:  # and the efforts with the friction left out
                rec["friction"], rec["ideal"] = fric, self.solve_forces(pts)
            rec["frame"] = self.call("frame", P, X=X, XD=XD, F=F, CS=CS)
        return rec

    # -- the sweep ------------------------------------------------------------------
    def run(self, q=None, qd=None, qdd=None) -> PreciseResult:
        """Every step of a sweep (the scene's unless given) in mpmath; see the module docstring
        and :func:`run_precise` (the driver values)."""
        cm, art = self.cm, self.art
        if q is None:
            q, qd, qdd = cm.sweep()
        base = cm.run(q, qd, qdd)
        base_accuracy = base.accuracy
        Qs, QDs, QDDs, Xf, _, _ = cm.step_positions(q, qd, qdd)
        status = base.status.copy()
        messages = list(base.messages)
        stages = art.stages
        steps: list = [None] * len(status)
        with mp.workdps(self.digits):
            Qmp, rounding = self.driver_values(Qs)

            def at(i, rates):  # step i, with rates or positions only
                return self.step(Qmp[i], QDs[:, i], QDDs[:, i], Xf[:, i], rates, stages,
                                 Qs[:, i])

            for i in range(len(status)):
                if status[i] == UNASSEMBLABLE:
                    continue
                try:
                    steps[i] = at(i, status[i] == OK)
                except NotReal:
                    status[i] = UNASSEMBLABLE
                    messages[i] = (f"no real position at {self.digits} digits (a closed form's "
                                   "square root is negative: the float64 run took a tangency)")
                except ZeroDivisionError:
                    status[i] = SINGULAR
                    messages[i] = (f"singular position: a group block is exactly singular at "
                                   f"{self.digits} digits; velocities and accelerations have no "
                                   "unique solution")
                    steps[i] = at(i, False)
            K = accuracy.condition_of(base_accuracy) * self._gain(steps, status, Xf, Qs, QDs)
            # a step whose exact driver value is a singular position (a dead centre the
            # float64 run, at the rounded value, found merely ill-conditioned)
            for i in np.flatnonzero((status == OK) & ~(K <= SINGULAR_COND)):
                status[i] = SINGULAR
                base.condition[i] = K[i]
                messages[i] = (f"singular position at {self.digits} digits: condition number "
                               f"about {K[i]:.3g} at the step's exact driver value (the float64 "
                               f"run's at its rounding, times the ratio of the group blocks' "
                               f"Hadamard ratios there and here), above {SINGULAR_COND:.0e}; "
                               "velocities and accelerations have no unique solution")
                steps[i] = at(i, False)
            records = [None if s is None else self._record(s, stages) for s in steps]
        base.status = status
        base.messages = messages
        analysis = self._round_into(base, records, stages)
        analysis.accuracy = self._accuracy(analysis, K, stages, rounding)
        return PreciseResult(analysis, self.digits, records, list(art.x))

    def _gain(self, steps, status, Xf, Qs, QDs) -> np.ndarray:
        """How much worse conditioned each ``ok`` step is at its exact driver value than the
        float64 run found it at the rounded one: the float64 runtime's indicator (the group
        blocks' smallest Hadamard ratio, to which the condition number is inversely
        proportional, :mod:`linkage_sym.numeric.results.accuracy`) there over this run's here, at
        least 1 (1 where there is no indicator).  Near a dead centre the two differ by the
        driver's rounding alone, a fraction of it; at a step that is exactly a dead centre,
        the float64 run's rounding kept it a tangency's width away (condition ~1e8, where
        here it is ~1e25).  Call it at the working precision."""
        gain = np.ones(len(status))
        idx = np.array([i for i, s in enumerate(steps) if status[i] == OK and s is not None
                        and s["ratio"] is not None], dtype=np.intp)
        if len(idx):
            for i, r in zip(idx, self._float_ratios(Xf, Qs, QDs, idx)):
                here = steps[i]["ratio"]
                if np.isfinite(r) and r > 0:
                    gain[i] = max(1.0, float(mp.mpf(float(r)) / here)) if here > 0 else math.inf
        return gain

    def _accuracy(self, res, K, stages, rounding) -> dict:
        """``K`` (the float64 run's, times :meth:`_gain`) with ``10^-digits`` for eps, plus
        the rounding to float64
        (positions: an ulp of the largest coordinate over the mechanism's size or of the
        largest rotation, :func:`accuracy.magnitude_floor`).

        The driver values are exact (:meth:`driver_values`): a scene's steps from its
        numbers, values a caller gives as the binary64 numbers they are.  Where a value
        still carries a rounding (``rounding`` (N,), relative), it is amplified as the
        arithmetic's is: ``eps`` is ``10^-digits`` plus that rounding at that step.
        """
        floor = {"position": accuracy.magnitude_floor(res, self.cm.L), "velocity": accuracy.EPS,
                 "acceleration": accuracy.EPS, "forces": accuracy.EPS}
        return accuracy.accuracy(K, res.status == OK, stages,
                                 unit=10.0 ** (-self.digits) + rounding, floor=floor)

    def _record(self, s, stages) -> dict:
        """The step's values by name (mpf), as in :attr:`PreciseResult.steps`."""
        scene, cm, art = self.scene, self.cm, self.art
        pts = s["pts"]
        levels = [0] + ([1] if "velocity" in stages else []) + ([2] if "acceleration" in stages else [])
        X, XD, XDD = s["x"], s["xd"], s["xdd"]
        rec: dict = {"x": X, "xd": XD, "xdd": XDD, "joints": {}, "links": {}, "points": {}}
        lev_names = {0: "position", 1: "velocity", 2: "acceleration"}
        for j in scene.joints:
            rec["joints"][j.name] = {lev_names[v]: tuple(art.rows(pts, f"joint:{j.name}:{v}"))
                                     for v in levels}
        motion = {}
        for link in scene.links:
            n = link.name
            c = cm.angle_of[n]
            origin, th0 = self.context.frame(n)
            rot = X[c] - th0
            motion[n] = m = frame_motion(
                mp.cos(rot), mp.sin(rot), origin, lambda v, n=n: art.rows(pts, f"origin:{n}:{v}"),
                XD[c] if 1 in levels else None, XDD[c] if 2 in levels else None)
            lk = {"rotation": rot, "origin": tuple(m[2:4])}
            if 1 in levels:
                lk["omega"], lk["origin_velocity"] = m[4], tuple(m[5:7])
            if 2 in levels:
                lk["alpha"], lk["origin_acceleration"] = m[7], tuple(m[8:10])
            if link.com is not None:
                for v in levels:
                    key = "com" if v == 0 else f"com_{lev_names[v]}"
                    lk[key] = tuple(art.rows(pts, f"com:{n}:{v}"))
            rec["links"][n] = lk
        for pt in scene.points:
            got = rigid_point(motion[pt.link], self.context.num.point(pt.at))
            rec["points"][pt.name] = {lev_names[v]: got[v] for v in levels}
        if "F" in s:
            reactions, driving = self.reactions(scene, s["F"], lambda key: art.rows(pts, key),
                                                mp.mpf(0))
            rec["reactions"] = {name: r[:2] for name, r in reactions.items()}
            rec["reaction_moments"] = {name: r[2] for name, r in reactions.items()}
            rec["driving"] = driving
            rec["frame"] = tuple(s["frame"])
            # each acting spring's length or angle and its effort (symbolic.springs)
            rec["springs"] = {k.name: tuple(art.rows(pts, f"spring:{k.name}"))
                              for k in scene.active_springs}
            if scene.effects.friction:
                rec.update(friction_record(self, s.get("friction"), s.get("ideal", s["F"]),
                                           driving))
        return rec

    def _round_into(self, res, records, stages):
        """``res`` (the float64 run's Analysis) with every value replaced by the mpmath one."""
        ok, has_pos = res.status == OK, res.status != UNASSEMBLABLE
        # (array, its value in a record, whether it needs rates)
        targets = [(getattr(kin, f), lambda r, s=section, n=name, f=f: r[s][n][f],
                    f not in _AT_POSITIONS)
                   for section, fields in _ROUNDED for name, kin in getattr(res, section).items()
                   for f in fields if getattr(kin, f) is not None]
        fo = res.forces
        if fo is not None:
            fo.method = "mpmath"
            fo.groups = [GroupForces(tuple(g.links), "mpmath") for g in fo.groups]
            for section in ("reactions", "reaction_moments", "driving"):
                targets += [(arr, lambda r, s=section, n=name: r[s][n], True)
                            for name, arr in getattr(fo, section).items()]
            targets += [(fo.frame_force, lambda r: r["frame"][:2], True),
                        (fo.frame_moment, lambda r: r["frame"][2], True)]
            targets += [(arr, lambda r, n=name, i=i: r["springs"][n][i], True)
                        for name, rec in fo.springs.items()
                        for i, arr in enumerate(rec.values())]
            targets += friction_targets(fo)
        for arr, get, rate in targets:
            if not arr.flags.writeable:
                continue  # pragma: no cover - results own their arrays
            mask = ok if rate else has_pos
            arr[~mask] = np.nan
            for i in np.flatnonzero(mask):
                rec = records[i]
                if rec is None or (rate and "velocity" not in stages and "reactions" not in rec):
                    continue
                value = get(rec)
                if arr.ndim == 1:
                    arr[i] = float(value)
                else:
                    arr[i, 0], arr[i, 1] = float(value[0]), float(value[1])
        return res


def run_precise(scene: Scene, digits, q=None, qd=None, qdd=None) -> PreciseResult:
    """Analyse ``scene`` with its derived equations in mpmath at ``digits`` digits.

    See the module docstring.

    Parameters
    ----------
    scene : Scene
    digits : int or str
        Significant decimal digits (:func:`parse_precision`).
    q, qd, qdd : dict of ndarray, optional
        Driver values as for ``Plan.run``; the scene's sweep unless given, each step at
        its exact value from the scene's numbers (:func:`driver_step_mp`).  Given values
        are taken as the exact binary64 numbers they are (the result is that input's, and
        the accuracy estimate counts no rounding of them), except a ``q`` value equal to
        the float64 value of a step of the scene's sweep of that driver, which stands for
        that step (:meth:`PreciseMechanism.driver_values`).
    """
    d = parse_precision(digits)
    if d is None:
        raise ValueError("precision: run_precise needs a number of digits, not 'double'")
    return PreciseMechanism(scene, d).run(q, qd, qdd)


def analyze_precise(scene: Scene, digits) -> object:
    """The :class:`~linkage_sym.numeric.results.result.Analysis` of :func:`run_precise`."""
    return run_precise(scene, digits).analysis


__all__ = ["DOUBLE", "PreciseMechanism", "PreciseResult", "analyze_precise", "parse_precision",
           "run_precise"]
