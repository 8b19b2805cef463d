"""Run a compiled mechanism over a sweep (NumPy only: no SymPy here).

A :class:`CompiledMechanism` holds the generated functions of one topology
(:mod:`linkage_sym.codegen.compile`) and the parameter values of one scene.
:meth:`CompiledMechanism.run` evaluates the stages a scene needs:

1. positions: the closed forms, vectorised over a path from the assembly
   configuration through the steps; groups without a closed form by Newton
   on their loop equations, step by step (sub-stepped where a step fails);
2. ``A xd = B qd`` and ``A xdd = rhs``: the generated entries, solved group
   block by group block (Cramer for blocks up to 3x3, LU otherwise;
   :class:`~linkage_sym.codegen.blocks.BlockSystem`);
3. points and the force blocks ``A_g F_g = b_g - C_g F_later``, solved from
   the last group back; the frame loads from the ground's reactions.

The result is the same :class:`~linkage_sym.numeric.results.result.Analysis` the
numeric solver returns, with ``forces.method == "symbolic"``.

Made once, when the mechanism is bound to a scene (as ``compile_plan`` does
for the numeric plan): the assembly modes, the accuracy calibration on the
scene's own sweep, and the memory a run of that sweep takes, warmed
(:mod:`linkage_sym.numeric.engine.heap`); every run, the first one too, only solves.

It is the NumPy backend of the one evaluator of generated code
(:class:`~linkage_sym.codegen.evaluator.NumpyEvaluator`: the calls, the block solves, the
forces, the loads) with what a run of one scene adds: the solving path and its
continuation, the singularity screen, the result's bookkeeping (shared with the numeric
plan: :mod:`linkage_sym.numeric.engine.run`, :mod:`linkage_sym.numeric.engine.block`).
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.codegen import cache, change_points
from linkage_sym.codegen.artifact import Artifact, ClosedStep
from linkage_sym.codegen.blocks import full
from linkage_sym.codegen.evaluator import NumpyEvaluator, frame_motion, load_functions, rigid_point
from linkage_sym.codegen.force_records import force_records
from linkage_sym.codegen.friction import mark_locked
from linkage_sym.codegen.parallels import two_slides
from linkage_sym.codegen.path import GroupPathProblem, PathContext
from linkage_sym.errors import SceneError
from linkage_sym.numeric.results import accuracy
from linkage_sym.numeric import continuation
from linkage_sym.numeric.continuation import messages as continuation_messages
from linkage_sym.numeric.engine.block import ResultLayout
from linkage_sym.numeric.kinematics.constraints import jacobian
from linkage_sym.numeric.kinematics.joint_rows import scene_constraints
from linkage_sym.numeric.kinematics.gears import pulling_note
from linkage_sym.numeric.kinematics.state import LinkState
from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results.jumps import JumpNote
from linkage_sym.numeric.results.result import OK, Analysis
from linkage_sym.numeric.engine.run import (
    unwrap_angles,
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
from linkage_sym.structure.parameters import driver_q0, ident, link_frames

SCREEN = 1e-3
"""A group block whose Hadamard ratio (by rows or by columns) is below this gets the
exact condition number."""
ASSEMBLY_MATCH = 1e-6
"""Closed forms must reproduce the assembly configuration to this (rad, or fraction of size)."""


def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


class CompiledMechanism(NumpyEvaluator):
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

    def __init__(self, artifact: Artifact | dict, scene: Scene):
        art = artifact if isinstance(artifact, Artifact) else Artifact.from_dict(artifact)
        self.scene = scene
        frames = link_frames(scene)
        self.frames = frames
        self.param_names = [p.name for p in art.params]
        params = [p.recipe.value(scene, frames) for p in art.params]
        self.n_params = len(params)  # then the assembly-mode signs, then the flanks
        params += [1.0] * art.sigmas
        self.flanks = list(art.flanks)
        params += [1.0] * len(self.flanks)
        super().__init__(art, load_functions(art, scene.name), params)
        self.L = scene.characteristic_length() or 1.0
        self.x_names = list(art.x)
        self.q0 = driver_q0(scene)
        xi = {n: i for i, n in enumerate(self.x_names)}
        self.angle_of = {n: xi["theta_" + ident(n)] for n in scene.link_names}
        self.x0 = np.zeros(self.m)
        for n, c in self.angle_of.items():
            self.x0[c] = frames[n].theta0
        self.is_angle = art.is_angle
        # the angles unwrapped along the path: all but those of links turned by a driver on
        # the ground, whose closed form is the driver's value itself (never wrapped)
        self._driven = [self.angle_of[n] for n in ground_driven(scene)]
        self._wrapped = [c for c in np.flatnonzero(self.is_angle) if c not in self._driven]
        self.blocks = art.blocks
        self._choose_branches()
        self._pose_constraints = None
        self._calibration = Calibration()  # accuracy: the indicator-to-condition ratio
        self._layout = ResultLayout(scene, art.stages)  # where a run writes its results
        self._own = None  # the scene's own sweep: driver arrays and solving path, made once
        self._decomposition = decompose(scene)  # the transmission angles' groups
        # the RRR dyads whose outer joints can meet (a change point), searched along the path
        self.meeting = change_points.meeting_dyads(self, self._decomposition)
        # the scene's own sweep and solving path, the accuracy calibration and the memory of
        # a run belong to the scene: made here, once, so that every run, the first one too,
        # only solves (as the numeric plan does)
        n_steps = self._drivers(None, None, None)[3].shape[1]
        self._calibration.ratio(self.sweep, self.run)
        self._layout.warm(n_steps, "symbolic")

    # -- positions -----------------------------------------------------------------
    def _choose_branches(self):
        """Assembly-mode signs: the ones whose closed forms give the assembly configuration."""
        art = self.art
        k = art.sigmas
        if k == 0:
            return
        combos = np.array(np.meshgrid(*[[1.0, -1.0]] * k, indexing="ij")).reshape(k, -1)
        n = self.n_params
        P = self.params[:n] + list(combos) + self.params[n + k:]
        Q = [self.q0[n] for n in art.q]
        X = list(self.x0)
        err = np.zeros(combos.shape[1])
        with np.errstate(invalid="ignore", divide="ignore"):
            for step in art.steps:
                if not isinstance(step, ClosedStep):
                    continue
                out = self.call(step.function, P, X=X, Q=Q)
                for c, v in zip(step.x, out):
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
                g = next(g for g in art.groups if g.sigma == n + i)
                raise SceneError(
                    [
                        f"joints: the assembly configuration is a singular position of the "
                        f"{g.title}: its assembly mode is undefined; "
                        "move the joints' `at` points off the dead-centre position"
                    ]
                )
        for i in range(k):
            self.params[n + i] = float(combos[i, best])

    def _path(self, Q: np.ndarray):
        """Driver values from the assembly configuration through the steps (refined),
        and the path index of each step."""
        P, out, _ = solving_path(self.scene, self.art.q, self.q0, self.L, Q)
        return P, out

    def _drivers(self, q, qd, qdd):
        """The driver arrays (D, N) in the order of ``artifact["q"]``, the solving path and
        the steps' path indices; for the scene's own sweep (``q`` None) made once."""
        if q is None and self._own is not None:
            return self._own
        own = q is None
        if own:
            q, qd, qdd = self.sweep()
        names = self.art.q
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
        K = Qpath.shape[1]
        failed = np.full(K, -1)
        self.newton_messages, self.path_notes, self.parallel_messages = {}, [], {}
        ctx = PathContext(self.params, list(Qpath), Qpath, K, failed)
        with np.errstate(invalid="ignore", divide="ignore"):
            X = self.walk([None] * self.m, ctx)
            if self.meeting:  # RRR dyads whose outer joints can meet: their change points
                self.path_notes += change_points.notes(self, X, Qpath, failed)
        return np.array(X), failed

    def closed_step(self, step, X, ctx):
        """A run of closed forms along the path; then its dyads of two slides (parallel slides
        fail, a passage of a joint through infinity is noted: :mod:`.parallels`)."""
        super().closed_step(step, X, ctx)
        if self.art.parallels and ctx.failed is not None:
            self.path_notes += two_slides(self, step, X, ctx.Qpath, ctx.failed,
                                          self.parallel_messages)

    def coordinate(self, c, value, ctx):
        """A closed form's values along the path; where it has none (NaN), the step's
        first failing group is the coordinate's."""
        x = np.array(full(value, ctx.K))
        bad = ~np.isfinite(x) & (ctx.failed < 0)
        ctx.failed[bad] = self.art.group_of_column()[c]
        return x

    def newton_step(self, step, X, ctx):
        """One group without a closed form at every path point: the continuation policy
        both runtimes share (:mod:`linkage_sym.numeric.continuation`)."""
        Qpath, failed = ctx.Qpath, ctx.failed
        g = step.group
        group = self.art.group(g)
        problem = GroupPathProblem(self, step, X, Qpath, failed)
        sol = continuation.solve_path(problem, Qpath.shape[1], self.x0[list(step.x)] / problem.scale)
        x = (sol.u * problem.scale).T
        for k, c in enumerate(step.x):
            X[c] = x[k]
        kinds = {n: self.scene.joint(n).type for n in self.art.q}
        qpath = dict(zip(self.art.q, Qpath))

        def where(i):
            return lambda t: continuation_messages.driver_values_text(qpath, kinds, i, t)

        for i, f in sol.failures.items():
            failed[i] = g
            self.newton_messages[i] = continuation_messages.failure_message(
                group.label, group.links, f, where(i))
        self.path_notes += [
            JumpNote(n[0], lambda step_text, n=n: continuation_messages.note_message(
                group.label, group.links, n, step_text, where(n[0])),
                group.label, tuple(group.links), n[1] is not None)
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
        if art.newton_steps:
            raise ValueError(
                "evaluate: a group of this mechanism has no closed form (Newton needs the "
                "path from the assembly configuration); use run()"
            )
        Q = [np.asarray(q[n], float) for n in art.q]
        QD = [np.asarray(qd[n], float) for n in art.q]
        QDD = [np.asarray(qdd[n], float) for n in art.q]
        N = len(Q[0])
        with np.errstate(invalid="ignore", divide="ignore"):
            X = np.array([np.broadcast_to(v, (N,)) for v in self.walk([None] * self.m,
                                                                     PathContext(self.params, Q, None, N, None))])
            CS = (list(np.cos(X)), list(np.sin(X)))
            A, Bqd = self.rate_system(X, Q, QD, CS)
            XD = A.solve(Bqd)
            XDD = A.solve(self.accelerations_rhs(list(X), list(XD), Q, QD, QDD, CS, shape=N))
            pts = self.call(
                "points", X=list(X), XD=list(XD), XDD=list(XDD), Q=Q, QD=QD, QDD=QDD, CS=CS
            )
        return {"x": X, "xd": XD, "xdd": XDD, "points": pts}

    def rate_system(self, X, Q, QD, CS=None, P=None, shape=None):
        """``A`` (a :class:`~linkage_sym.codegen.blocks.BlockSystem`) and ``B qd`` (a list
        of ``m`` arrays over the steps) at coordinates ``X`` (m, K)."""
        K = X.shape[1]
        if CS is None:
            CS = (list(np.cos(X)), list(np.sin(X)))
        return super().rate_system(list(X), Q, QD, CS, P, K)

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
        once on the scene's own sweep (:class:`~linkage_sym.numeric.engine.run.Calibration`)."""
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
        return accuracy.accuracy(K, ok, self.art.stages, accuracy.amplification_of(res.forces),
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
        # (no point solved: a mechanism that cannot be assembled even at its assembly)
        for c in self._wrapped if valid.any() else ():
            th = unwrap_angles(Xp[c] if every else Xp[c, valid])
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

        def message_of(i):
            g = art.group(int(failed[i]))
            if int(out[i]) in self.parallel_messages:  # a dyad of two slides, parallel
                return self.parallel_messages[int(out[i])]
            if g.closed:
                return f"{g.title} cannot be assembled: its closed form has no real solution"
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
                          self.condition_numbers(A.dense(steps), self.L))
        ok = status == OK
        rate_ok = ok[idx]
        stages = art.stages
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
            XDD[:, sel] = As.solve(self.accelerations_rhs(
                list(Xk[:, sel]), list(XD[:, sel]), [v[sel] for v in Qk], [v[sel] for v in QDk],
                [v[sel] for v in QDDk], (list(CS[0][:, sel]), list(CS[1][:, sel])), shape=n_sel))
        P0 = self._load_params(dict(zip(art.q, Qk)))

        def points(flanks=None, arrays=True):
            """The points function's outputs at the K steps; ``flanks``: each mesh's flank
            at every step (the parameters' +1 otherwise); ``arrays`` false: a constant
            output stays a scalar (the result block's rows broadcast it)."""
            P = P0 if flanks is None else self.with_flanks(P0, flanks)
            with np.errstate(invalid="ignore"):
                got = self.call("points", P, X=list(Xk), XD=list(XD), XDD=list(XDD), Q=Qk,
                                QD=QDk, QDD=QDDk, CS=(list(CS[0]), list(CS[1])))
            return [full(v, K) for v in got] if arrays else got

        pts = points(arrays="forces" in stages)  # the force solve indexes every output
        forces = None
        if "forces" in stages:
            forces = self._forces(pts, points, Xk, XD, CS, rate_ok, idx, N)
            mark_locked(status, messages, forces)  # joint friction: self-locking steps
        res = self._analysis(X, XD, XDD, CS, pts, idx, status, messages, condition, forces,
                             q, qd, qdd)
        finish(res, self.scene, self.path_notes, out, self._decomposition)
        # accuracy (numeric.results.accuracy): K of the pose Jacobian (the numeric solver's), exact
        # where a block was screened, else from the blocks' ratios calibrated on it
        indicator = np.full(N, np.inf)
        indicator[idx] = ratio_min
        res.accuracy = self._accuracy(res, indicator)
        return res

    def _load_params(self, q) -> list | None:
        """The parameters with the forces and torques of loads that vary over the cycle
        scaled by their factors at the driver values ``q`` (``None``: no such load)."""
        if "forces" not in self.art.stages:
            return None
        return self.loads_at(self.scene, q)

    def _forces(self, pts, points, Xk, XD, CS, rate_ok, idx, N):
        """Forces at the steps with rates.  A gear mesh's tooth load must press: solved with
        every flank +1, then again with the flanks the tooth loads show (as the numeric
        solver does, :mod:`linkage_sym.numeric.forces.kinetostatics`)."""
        sel = rate_ok
        ok_idx = idx[sel]
        flank = np.ones((len(self.flanks), len(sel)))
        solves = 1 + 2 * len(self.flanks)
        for _ in range(solves):  # with the joints' friction where it acts (codegen.friction)
            Fv, fric = self.forces_and_friction(pts, lambda v: v[sel])
            pulling = {}
            for m, (name, neg) in enumerate(zip(self.flanks, self.pulling(Fv))):
                if neg.any():
                    flank[m, np.flatnonzero(sel)[neg]] *= -1.0
                    pulling[name] = np.flatnonzero(neg)
            if not pulling:
                break
            pts = points(flank)
        notes = [pulling_note(name, ok_idx[bad], solves) for name, bad in pulling.items()]
        P = None
        if len(self.flanks):  # the frame's mesh forces on the flanks settled on
            P = self.with_flanks(None, [f[sel] for f in flank])
        ideal = self.solve_forces(pts, lambda v: v[sel]) if fric is not None else None
        return force_records(self, pts, (Fv, fric, ideal), (Xk, XD), CS, sel, ok_idx, N, notes, P)

    def _analysis(self, X, XD, XDD, CS, pts, idx, status, messages, condition, forces, q, qd, qdd):
        """Write the results into a result block (:class:`ResultLayout`, as the numeric
        plan does): the values at the steps ``idx`` where positions were solved; the
        layout blanks the steps without a solution."""
        scene, art = self.scene, self.art
        N = len(status)
        stages = art.stages
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
            put(rec.position.T, self.art.rows(pts, f"joint:{j.name}:0"))
            if has_v:
                put(rec.velocity.T, self.art.rows(pts, f"joint:{j.name}:1"))
            if has_a:
                put(rec.acceleration.T, self.art.rows(pts, f"joint:{j.name}:2"))
        for link in scene.links:
            n, lk = link.name, links[link.name]
            c = self.angle_of[n]
            fr = self.frames[n]
            lk.rotation[...] = X[c] - fr.theta0
            # the rotation's cosine and sine from those of the coordinate (no new cos/sin)
            ct, st = math.cos(fr.theta0), math.sin(fr.theta0)
            cr, sr = CS[0][c] * ct + CS[1][c] * st, CS[1][c] * ct - CS[0][c] * st
            # the link point at the global origin in the assembly configuration
            motion[n] = m = frame_motion(
                cr, sr, fr.origin, lambda lev, n=n: self.art.rows(pts, f"origin:{n}:{lev}"),
                XD[c] if has_v else None, XDD[c] if has_a else None)
            put(lk.origin.T, m[2:4])
            if has_v:
                put(lk.omega, m[4])
                put(lk.origin_velocity.T, m[5:7])
            if has_a:
                put(lk.alpha, m[7])
                put(lk.origin_acceleration.T, m[8:10])
            if link.com is not None:
                put(lk.com.T, self.art.rows(pts, f"com:{n}:0"))
                if has_v:
                    put(lk.com_velocity.T, self.art.rows(pts, f"com:{n}:1"))
                if has_a:
                    put(lk.com_acceleration.T, self.art.rows(pts, f"com:{n}:2"))
        # traced points (the format's ``points`` extension): rigid with their link, from its
        # rotation and origin motion at the solved steps (not part of the generated code)
        for pt in scene.points:
            rec = points[pt.name]
            got = rigid_point(motion[pt.link], pt.at)
            put(rec.position.T, got[0])
            if has_v:
                put(rec.velocity.T, got[1])
            if has_a:
                put(rec.acceleration.T, got[2])
        lay.invalidate(block, status)
        return new_analysis(scene, stages, status, messages, {k: q[k] for k in art.q}, qd, qdd,
                            joints, links, points, condition, forces)


def load_compiled(scene: Scene) -> CompiledMechanism | None:
    """The compiled mechanism of ``scene``'s topology from the cache, or ``None``.

    Needs neither SymPy nor a derivation: the cached functions are bound to
    this scene's parameter values.
    """
    art = cache.load_artifact(cache.key_of(cache.signature(scene)))
    return None if art is None else CompiledMechanism(art, scene)
