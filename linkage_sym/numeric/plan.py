"""Compile once, evaluate many: a scene analysed into a solving plan.

:func:`compile_plan` does everything that depends only on the mechanism: the
structural decomposition, each group's solver with its assembly mode, the
driver offsets, the stages a scene needs.  :meth:`Plan.run` then evaluates
the plan over a sweep, every group vectorised over the steps (Newton groups
step by step).

Path and steps
--------------
Positions are solved along a *path*: the assembly configuration, then
intermediate driver values up to the first step (the mechanism moves
continuously from the assembly configuration to the first step), then the
steps, refined where consecutive steps are far apart.  Rotations are
unwrapped along that path, so they are continuous and measured from the
assembly configuration.  Velocities and accelerations are solved at the
steps only.  The path, the singularity threshold and its message and the run's
warnings are shared with the compiled symbolic mechanism
(:mod:`linkage_sym.numeric.engine.run`), as is the Newton continuation policy
(:mod:`linkage_sym.numeric.continuation`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results import accuracy
from linkage_sym.numeric.kinematics import loop_closure
from linkage_sym.numeric.engine.block import ResultLayout
from linkage_sym.numeric.kinematics.closed_form import DyadSolver, InputSolver
from linkage_sym.numeric.kinematics.constraints import jacobian
from linkage_sym.numeric.kinematics.joint_rows import scene_constraints
from linkage_sym.numeric.forces.policy import check_method
from linkage_sym.numeric.kinematics.loop_closure import LoopClosureSolver
from linkage_sym.numeric.kinematics.newton import NewtonSolver
from linkage_sym.numeric.results.result import Analysis
from linkage_sym.numeric.kinematics.solver import GroupSolver
from linkage_sym.numeric.kinematics.state import LinkState
from linkage_sym.numeric.engine.run import (
    SCREEN,
    Calibration,
    ground_driven,
    interrupted,
    nearest_across_gaps,
    finish,
    mark_singular,
    needed_stages,
    new_analysis,
    scene_sweep,
    solving_path,
    step_status,
    unwrap_angles,
)
from linkage_sym.structure import Decomposition, decompose
from linkage_sym.structure.parameters import driver_q0

@dataclass
class _Path:
    q: dict  # driver -> values along the path
    out: slice | np.ndarray  # where the steps are in the path


class Plan:
    """A compiled solving plan; see :func:`compile_plan`."""

    def __init__(self, scene: Scene, decomposition: Decomposition, disconnection=None):
        self.scene = scene
        self.decomposition = decomposition
        L = scene.characteristic_length()
        self.L = L if L > 0 else 1.0
        self.q0 = driver_q0(scene)
        self.constraints = scene_constraints(scene, self.q0)
        self.solvers: list[GroupSolver] = []
        for g in decomposition.groups:
            if g.kind == "input":
                self.solvers.append(InputSolver(scene, g, self.q0))
            elif g.kind == "dyad":
                self.solvers.append(DyadSolver(scene, g))
            elif g.kind == "gear" and len(g.links) == 1:
                from linkage_sym.numeric.kinematics.gears import GearSolver  # a scene with gears

                self.solvers.append(GearSolver(scene, g))
            elif g.kind == "cam":  # a follower on its pivot or slide (others refused by name)
                from linkage_sym.numeric.kinematics.cams import CamSolver  # a scene with cams

                self.solvers.append(CamSolver(scene, g, self.L))
            elif loop_closure.applies(scene, g, self.constraints):
                self.solvers.append(LoopClosureSolver(scene, g, self.constraints, self.L))
            else:
                self.solvers.append(NewtonSolver(scene, g, self.constraints, self.L))
        self.stages = needed_stages(scene)
        self.layout = ResultLayout(scene, self.stages)
        self._own_sweep = None
        self._calibration = Calibration()  # accuracy: the indicator-to-condition ratio
        # links whose rotation may come wrapped to one turn (atan2 in a dyad, or
        # copied or offset from such a link): unwrapped as soon as they are solved when
        # a mesh reads them (below); Newton groups move continuously from the assembly
        # configuration, and an input link on the ground takes the driver value itself
        self.wrapped = [n for g, sv in zip(decomposition.groups, self.solvers) if sv.wraps
                        for n in g.links]
        # every link's rotation is made continuous along the path, its jumps of more than
        # half a turn between consecutive solved points taken as whole turns: an atan2's
        # wrap, or a Newton group that re-entered past a limit nearest its stop; a link
        # turned by a driver on the ground has the driver's value and is left as it is
        driven = ground_driven(scene)
        self.unwrapped = [n for n in scene.link_names if n not in driven]
        # a mesh's row is linear in rotations from the assembly configuration, so the
        # rotations it reads must be unwrapped before a later group uses them
        self.unwrap_early = bool(scene.meshes)
        self.all_constraints = [c for rows in self.constraints.values() for c in rows.rows]
        self.force_plan = None
        if "forces" in self.stages:  # the force layer loads only for a scene that asks for forces
            from linkage_sym.numeric.forces.kinetostatics import ForcePlan

            self.force_plan = ForcePlan(scene, decomposition, self.L, disconnection)
        # the scene's own sweep, its solving path and the accuracy calibration belong to the
        # scene, not to a call: made here, once (compile once, run many), so that every run,
        # the first one too, only solves
        self._scene_sweep()
        self._calibration.ratio(self._sweep_values, lambda *d: self.run(*d, exact_condition=True))
        # and the memory a run of the scene's sweep takes, touched once here, so that the
        # first run does not pay the first touch of fresh pages (numeric.engine.block.warm)
        self.layout.warm(len(next(iter(self._own_sweep[0].values()))), "numeric")

    # -- the sweep ---------------------------------------------------------
    def sweep(self):
        """Driver values ``(q, qd, qdd)`` of the scene's sweep: dicts of (N,) arrays."""
        return scene_sweep(self.scene)

    def _scene_sweep(self):
        """The scene's sweep and its solving path, made once (read-only arrays, shared by runs)."""
        if self._own_sweep is None:
            q, qd, qdd = self.sweep()
            path = self._path(q)
            for arrays in (q, qd, qdd, path.q):
                for a in arrays.values():
                    a.flags.writeable = False
            self._own_sweep = (q, qd, qdd, path)
        return self._own_sweep

    def _path(self, q) -> _Path:
        names = list(q)
        Q = np.stack([np.asarray(q[n], dtype=float) for n in names])  # (nd, N)
        P, out, n_ref = solving_path(self.scene, names, self.q0, self.L, Q)
        # the steps as a slice when they are contiguous: views, no copies
        sel = slice(int(out[0]), int(out[0]) + len(out)) if n_ref == 1 else out
        return _Path({n: P[i] for i, n in enumerate(names)}, sel)

    # -- running -----------------------------------------------------------
    def run(self, q=None, qd=None, qdd=None, exact_condition=False, method="dyad") -> Analysis:
        """Solve the plan over a sweep (the scene's, unless ``q, qd, qdd`` are given).

        Parameters
        ----------
        q, qd, qdd : dict of array_like, optional
            Driver coordinate, velocity and acceleration per driven joint,
            each of shape (N,).  Default: the scene's sweep.
        exact_condition : bool
            Compute the exact dimensionless condition number at every step,
            not only where a group's indicator flags a near-singular step.
        method : {"dyad", "global"}
            Force method (see :mod:`linkage_sym.numeric.forces.kinetostatics`).
        """
        check_method(method)  # before the kinematics, not after
        if q is None:
            q, qd, qdd, path = self._scene_sweep()
        else:
            q = {k: np.asarray(v, dtype=float) for k, v in q.items()}
            path = self._path(q)
        qd = {k: np.asarray(v, dtype=float) for k, v in qd.items()}
        qdd = {k: np.asarray(v, dtype=float) for k, v in qdd.items()}
        S, block, status, messages, condition, forces, ok, ind_min, path_index = self._solve(
            q, qd, qdd, path, exact_condition, method)
        res = self._analysis(S, block, q, qd, qdd, status, messages, condition, forces)
        if self.scene.cams:  # each contact's point and pressure angle, in its joint's record
            from linkage_sym.numeric.kinematics.cams import cam_records

            cam_records(self.solvers, S, res.joints, status)
        finish(res, self.scene, [n for sv in self.solvers for n in sv.notes], path_index,
               self.decomposition)
        self._set_accuracy(res, ok, ind_min)
        return res

    def driving(self, q, qd, qdd, method="dyad") -> tuple:
        """The drivers' efforts alone at the states ``(q, qd, qdd)`` (dicts of ``(N,)``
        arrays, as :meth:`run` takes them): what :meth:`run` solves, without the result's
        records (points, warnings, transmission angles, accuracies).

        Returns
        -------
        driving : dict
            Each driven joint's effort, ``(N,)`` (meaningful where the step is ``ok``).
        status, messages : ndarray, dict
            Each step's status and the messages of those not ``ok``, as :meth:`run` gives them.
        """
        driving, _, status, messages = self.driving_states(q, qd, qdd, method)
        return driving, status, messages

    def driving_states(self, q, qd, qdd, method="dyad") -> tuple:
        """:meth:`driving` and the links' states of the same solve (what
        :meth:`link_states` gives): one solve where both are wanted.

        Returns
        -------
        driving, states, status, messages
            As :meth:`driving` and :meth:`link_states` give them.
        """
        check_method(method)
        q = {k: np.asarray(v, dtype=float) for k, v in q.items()}
        qd = {k: np.asarray(v, dtype=float) for k, v in qd.items()}
        qdd = {k: np.asarray(v, dtype=float) for k, v in qdd.items()}
        got = self._solve(q, qd, qdd, self._path(q), False, method)
        return got[5].driving, got[0], got[2], got[3]

    def link_states(self, q, qd, qdd) -> tuple:
        """The links' positions, velocities and accelerations alone at the states
        ``(q, qd, qdd)`` (dicts of ``(N,)`` arrays, as :meth:`run` takes them): what
        :meth:`run` solves before its records, forces included where the plan has them.

        Returns
        -------
        states : dict of LinkState
            Each link's state over the steps (component arrays).
        status : ndarray
            Each step's status, as :meth:`run` gives it.
        """
        q = {k: np.asarray(v, dtype=float) for k, v in q.items()}
        qd = {k: np.asarray(v, dtype=float) for k, v in qd.items()}
        qdd = {k: np.asarray(v, dtype=float) for k, v in qdd.items()}
        got = self._solve(q, qd, qdd, self._path(q), False, "dyad")
        return got[0], got[2]

    def _solve(self, q, qd, qdd, path, exact_condition, method) -> tuple:
        """Positions, rates and forces along ``path``: ``(S, block, status, messages,
        condition, forces, ok, ind_min, path_index)``."""
        N = len(next(iter(q.values())))
        S = {GROUND: LinkState()}
        for n in self.scene.link_names:
            S[n] = LinkState()
        inds, failed_at = self._solve_positions(S, path)
        valid = failed_at < 0
        all_valid = bool(valid.all())
        self._unwrap_rotations(S, valid, all_valid, len(failed_at))
        out = path.out
        failed = failed_at[out]
        path_index = np.arange(len(failed_at))[out]
        status, messages = step_status(
            failed, lambda i: self.solvers[failed[i]].failure(S, int(path_index[i])))
        S = {n: (st.take(out) if n != GROUND else st) for n, st in S.items()}
        if not all_valid:  # the scene format's rule for rotations across a gap
            self._across_gaps(S, valid, out, failed < 0)
        # --- singularity: exact condition number where an indicator is small
        ind_min, condition, ok = self._find_singular(S, inds, out, failed, status, messages,
                                                     exact_condition)
        block = self._solve_rates(S, q, qd, qdd, N)
        forces = None
        if self.force_plan is not None:
            from linkage_sym.numeric.forces.kinetostatics import mark_self_locking

            forces = self.force_plan.run(S, ok, method, q)
            mark_self_locking(status, messages, ok, forces)  # friction (contract part two)
        return S, block, status, messages, condition, forces, ok, ind_min, path_index

    def _solve_positions(self, S, path) -> tuple:
        """Every group's positions along the path (rotations unwrapped early where the plan
        says so); ``(indicators, failed_at)``: each group's singularity indicator and the
        first group that failed at each path point (-1: none)."""
        inds = []
        npath = len(path.q[next(iter(path.q))])
        wrapped = set(self.wrapped)
        for solver in self.solvers:
            ind = solver.position(S, path.q)
            if self.unwrap_early:
                for n in wrapped.intersection(solver.group.links):
                    th = np.array(np.broadcast_to(S[n].th, (len(next(iter(path.q.values()))),)))
                    ok = np.isfinite(th)
                    th[ok] = unwrap_angles(th[ok])
                    S[n].th = th
            # a group whose geometry does not change (two fixed slide directions) gives a scalar
            inds.append(None if ind is None else np.broadcast_to(ind, (npath,)))
        for gi, solver in enumerate(self.solvers):  # an RRR dyad's change points on the path
            if isinstance(solver, DyadSolver) and solver.meets:
                solver.notes = solver.change_points(path.q, inds[gi], self._upstream(gi))
        failed_at = np.full(npath, -1)
        for gi, ind in enumerate(inds):
            if ind is None:
                continue
            bad = ~np.isfinite(ind) & (failed_at < 0)
            failed_at[bad] = gi
        return inds, failed_at

    def _upstream(self, gi: int):
        """``solve(qs)``: the states of the groups solved before group ``gi`` at the driver
        values ``qs`` (dict of arrays), in a new state, when each of them has a closed form
        (input links and dyads); ``None`` otherwise (a group by continuation needs the path
        from the assembly configuration)."""
        before = self.solvers[:gi]
        if not all(isinstance(sv, (InputSolver, DyadSolver)) for sv in before):
            return None

        def solve(qs):
            S = {GROUND: LinkState()}
            for n in self.scene.link_names:
                S[n] = LinkState()
            for sv in before:
                # what a position call leaves for the run (notes, an RRR's outer joints)
                # belongs to the run's path, not to these driver values
                kept = {k: vars(sv)[k] for k in ("notes", "outer") if k in vars(sv)}
                sv.position(S, qs)
                vars(sv).update(kept)
            return S

        return solve

    def _unwrap_rotations(self, S, valid, all_valid: bool, npath: int) -> None:
        """The rotations of the links not driven from the ground, unwrapped over the valid
        path points."""
        for n in self.unwrapped:
            st = S[n]
            if np.ndim(st.th) == 0:
                continue  # a link that never turns
            if all_valid and np.shape(st.th) == (npath,):
                st.th = unwrap_angles(st.th)  # a new array only where it changes
                continue
            th = np.array(np.broadcast_to(st.th, (npath,)), dtype=float)
            if all_valid:
                th = unwrap_angles(th)
            else:
                th[valid] = unwrap_angles(th[valid])
            st.th = th

    def _find_singular(self, S, inds, out, failed, status, messages, exact_condition) -> tuple:
        """``(ind_min, condition, ok)``: the smallest indicator per step, the exact condition
        number where it is small (or everywhere, ``exact_condition``), and the steps still
        ``ok`` once the singular ones are marked (in ``status`` and ``messages``)."""
        N = len(status)
        ind_min = np.full(N, np.inf)
        for ind in inds:
            if ind is not None:
                ind_min = np.fmin(ind_min, ind[out])
        condition = np.full(N, np.nan)
        ok = failed < 0  # status == OK, kept as a mask (comparing strings costs)
        check = (failed < 0) & (np.ones(N, bool) if exact_condition else ind_min < SCREEN)
        if check.any():
            idx = np.flatnonzero(check)
            sing = mark_singular(status, messages, condition, idx, self.condition_numbers(S, idx))
            ok[sing] = False
        return ind_min, condition, ok

    def _solve_rates(self, S, q, qd, qdd, N) -> np.ndarray:
        """Velocities and accelerations, written by the solvers straight into one block that
        holds every result array; the block."""
        block = np.empty((self.layout.n_rows, N))
        for link in self.scene.links:
            rows = self.layout.rate_rows(block, link.name)
            if rows:
                S[link.name].bind_rates(rows)
        if "velocity" in self.stages:
            for solver in self.solvers:
                solver.velocity(S, q, qd)
        if "acceleration" in self.stages:
            for solver in self.solvers:
                solver.acceleration(S, q, qd, qdd)
        for link in self.scene.links:
            S[link.name].fill_rates()
        return block

    def _set_accuracy(self, res, ok, ind_min) -> None:
        """Record the calibration run's conditions, or set each ok step's relative
        accuracies (:mod:`~linkage_sym.numeric.results.accuracy`)."""
        if self._calibration.active:
            self._calibration.record(res.condition, ok, ind_min)
        else:
            # each ok step's relative accuracies (numeric.results.accuracy): K exact where computed,
            # else from the indicators with the calibration ratio G
            G = self._calibration.ratio(
                self._sweep_values, lambda *d: self.run(*d, exact_condition=True))
            K = accuracy.condition_estimate(res.condition, ok, ind_min, G)
            res.accuracy = accuracy.accuracy(
                K, ok, self.stages, accuracy.amplification_of(res.forces),
                floor={"position": accuracy.magnitude_floor(res, self.L)})

    def _sweep_values(self):
        return self._scene_sweep()[:3]

    def _across_gaps(self, S, valid, out, solved) -> None:
        """Each link's rotation after an interruption of the path: the value nearest the
        last solved step (:func:`~linkage_sym.numeric.engine.run.nearest_across_gaps`), except
        a link turned by a driver on the ground, whose rotation is the driver's value."""
        broken = interrupted(valid, out, solved)
        if not broken.any():
            return
        for n in self.unwrapped:  # every link but those turned by a driver on the ground
            st = S[n]
            if np.shape(st.th) == solved.shape:
                st.th = nearest_across_gaps(st.th, solved, broken)

    def condition_numbers(self, S, idx) -> np.ndarray:
        """Exact dimensionless condition number of the full constraint Jacobian at steps ``idx``
        (infinite where the Jacobian is not finite)."""
        Si = {n: st.take(idx) if n != GROUND else st for n, st in S.items()}
        J = jacobian(self.all_constraints, Si, list(self.scene.link_names), len(idx), self.L)
        # a step whose Jacobian is not finite (a joint at infinity) has no condition number:
        # infinite, so the step is singular, and never handed to the SVD
        good = np.isfinite(J).all(axis=(1, 2))
        every = bool(good.all())
        cond = np.full(len(J), np.inf)
        if good.any():
            sv = np.linalg.svd(J if every else J[good], compute_uv=False)
            with np.errstate(divide="ignore"):
                cond[good] = sv[:, 0] / sv[:, -1]
        return cond

    def _analysis(self, S, block, q, qd, qdd, status, messages, condition, forces) -> Analysis:
        """Assemble the result arrays in ``block`` (see :class:`ResultLayout`).

        The rates of the links are there already (the solvers wrote them);
        positions are copied in, points of links are written in place.
        """
        N = len(status)
        lay = self.layout
        has_v = "velocity" in self.stages
        has_a = "acceleration" in self.stages
        tmp = np.empty(N) if has_a else None
        links, joints, points = lay.records(self.scene, block, self.stages)
        for link in self.scene.links:
            n, st, lk = link.name, S[link.name], links[link.name]
            lk.rotation[...] = st.th
            o = lk.origin.T
            o[0] = st.dx
            o[1] = st.dy
            if link.com is not None:
                out = lk.com.T
                st.point_into(link.com, out[0], out[1])
                if has_v:
                    out = lk.com_velocity.T
                    st.point_velocity_into(link.com, out[0], out[1])
        # joints (their point on links[1]) and traced points: (link, point, record)
        tracked = [(j.moves_with, j.at, joints[j.name]) for j in self.scene.joints]
        tracked += [(pt.link, pt.at, points[pt.name]) for pt in self.scene.points]
        for k, X, rec in tracked:
            out = rec.position.T
            S[k].point_into(X, out[0], out[1])
            if has_v:
                out = rec.velocity.T
                S[k].point_velocity_into(X, out[0], out[1])
        if has_a:
            w2 = {n: np.multiply(st.w, st.w) for n, st in S.items()}
            for link in self.scene.links:
                if link.com is not None:
                    n = link.name
                    out = links[n].com_acceleration.T
                    S[n].point_acceleration_into(link.com, out[0], out[1], w2[n], tmp)
            for k, X, rec in tracked:
                out = rec.acceleration.T
                S[k].point_acceleration_into(X, out[0], out[1], w2[k], tmp)
        lay.invalidate(block, status)
        return new_analysis(self.scene, self.stages, status, messages, q, qd, qdd, joints,
                            links, points, condition, forces)


def compile_plan(scene: Scene, disconnection=None) -> Plan:
    """Analyse ``scene`` once into a :class:`Plan` whose ``run`` solves every step.

    Raises
    ------
    SceneError
        If the mechanism cannot be decomposed into solvable groups, or its
        assembly configuration is a singular position of a group.
    """
    return Plan(scene, decompose(scene), disconnection)
