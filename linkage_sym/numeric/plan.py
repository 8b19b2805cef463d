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
steps only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.closed_form import DyadSolver, InputSolver
from linkage_sym.numeric.constraints import jacobian, scene_constraints
from linkage_sym.numeric.kinetostatics import ForcePlan, check_method
from linkage_sym.numeric.newton import NewtonSolver
from linkage_sym.numeric.result import (
    OK,
    SINGULAR,
    UNASSEMBLABLE,
    Analysis,
    JointKinematics,
    LinkKinematics,
)
from linkage_sym.numeric.state import LinkState
from linkage_sym.structure import Decomposition, decompose
from linkage_sym.structure.parameters import driver_q0

SINGULAR_COND = 1e10
"""Spec: a step is singular when the dimensionless condition number exceeds this."""
SCREEN = 1e-3
"""A group indicator below this triggers the exact condition number at that step."""
MAX_ANGLE_STEP = math.radians(2.0)
"""Largest driver increment (R drivers) between two points of the solving path."""
MAX_SLIDE_STEP = 0.02
"""Largest driver increment (P drivers) along the path, as a fraction of the mechanism size."""


@dataclass
class _Path:
    q: dict  # driver -> values along the path
    out: slice | np.ndarray  # where the steps are in the path


def _unwrap(th: np.ndarray) -> np.ndarray:
    """Remove the 2 pi jumps of an angle sequence (as ``np.unwrap``, with a fast exit).

    Consecutive path points are at most a few degrees apart, so a jump of more
    than half a turn can only be a wrap of ``atan2``.
    """
    d = np.diff(th)
    jump = np.abs(d) > math.pi
    if not jump.any():
        return th
    k = np.zeros_like(th)
    k[1:] = np.cumsum(np.where(jump, np.round(d / (2 * math.pi)), 0.0))
    return th - 2 * math.pi * k


def solving_path(scene: Scene, names, q0: dict, L: float, Q: np.ndarray):
    """Driver values along the solving path (see the module docstring).

    Parameters
    ----------
    names : list of str
        The driven joints, in the order of the rows of ``Q``.
    q0 : dict
        Each driver's value in the assembly configuration.
    L : float
        Size of the mechanism (a slide's largest increment is a fraction of it).
    Q : ndarray (D, N)
        The steps' driver values.

    Returns
    -------
    P : ndarray (D, K)
        The assembly configuration, intermediate points up to the first step,
        then the steps, refined where consecutive steps are far apart.
    out : ndarray (N,)
        The path index of each step.
    n_ref : int
        Path intervals between consecutive steps (1: the steps are contiguous).
    """
    q0 = np.array([q0[n] for n in names])
    lim = np.array(
        [MAX_ANGLE_STEP if scene.joint(n).type == "R" else MAX_SLIDE_STEP * L for n in names]
    )
    n_pre = max(1, int(math.ceil(np.max(np.abs(Q[:, 0] - q0) / lim))))
    pre = q0[:, None] + (Q[:, :1] - q0[:, None]) * (np.arange(n_pre) / n_pre)[None, :]
    N = Q.shape[1]
    n_ref = max(1, int(math.ceil(np.max(np.abs(np.diff(Q, axis=1)) / lim[:, None])))) if N > 1 else 1
    if n_ref > 1:
        f = np.arange(n_ref) / n_ref
        seg = Q[:, :-1, None] + np.diff(Q, axis=1)[:, :, None] * f
        body = np.concatenate([seg.reshape(len(names), -1), Q[:, -1:]], axis=1)
    else:
        body = Q
    return np.concatenate([pre, body], axis=1), n_pre + np.arange(N) * n_ref, n_ref


def scene_sweep(scene: Scene):
    """Driver values ``(q, qd, qdd)`` of a scene's sweep: dicts of (N,) arrays."""
    q, qd, qdd = {}, {}, {}
    for d in scene.drivers:
        q[d.joint] = np.linspace(d.start, d.stop, d.steps)
        qd[d.joint] = np.full(d.steps, float(d.speed))
        qdd[d.joint] = np.full(d.steps, float(d.acceleration))
    return q, qd, qdd


def needed_stages(scene: Scene) -> tuple[str, ...]:
    """The stages a scene's outputs and effects call for, in order.

    Kinematics output needs positions, velocities and accelerations; forces
    need velocities and accelerations only when inertia acts on a link with
    mass.
    """
    outs = set(scene.outputs)
    forces = bool(outs & {"reactions", "driving", "frame"})
    inertia = scene.effects.inertia and any(
        link.mass > 0 or link.inertia > 0 for link in scene.links
    )
    stages = ["position"]
    if "kinematics" in outs or (forces and inertia):
        stages += ["velocity", "acceleration"]
    if forces:
        stages.append("forces")
    return tuple(stages)


class Plan:
    """A compiled solving plan; see :func:`compile_plan`."""

    def __init__(self, scene: Scene, decomposition: Decomposition, disconnection=None):
        self.scene = scene
        self.decomposition = decomposition
        L = scene.characteristic_length()
        self.L = L if L > 0 else 1.0
        self.q0 = driver_q0(scene)
        self.constraints = scene_constraints(scene, self.q0)
        self.solvers = []
        for g in decomposition.groups:
            if g.kind == "input":
                self.solvers.append(InputSolver(scene, g, self.q0))
            elif g.kind == "dyad":
                self.solvers.append(DyadSolver(scene, g))
            else:
                self.solvers.append(NewtonSolver(scene, g, self.constraints, self.L))
        self.stages = needed_stages(scene)
        # links whose rotation may come wrapped to one turn (atan2 in a dyad, or
        # copied or offset from such a link) and is unwrapped along the path;
        # Newton groups move continuously from the assembly configuration, and an
        # input link on the ground takes the (never wrapped) driver value itself
        self.wrapped = [
            n for g, sv in zip(decomposition.groups, self.solvers)
            if not isinstance(sv, NewtonSolver)
            and not (isinstance(sv, InputSolver) and sv.known == GROUND)
            for n in g.links
        ]
        self.all_constraints = [c for rows in self.constraints.values() for c in rows]
        self.force_plan = (
            ForcePlan(scene, decomposition, self.L, disconnection) if "forces" in self.stages else None
        )

    # -- the sweep ---------------------------------------------------------
    def sweep(self):
        """Driver values ``(q, qd, qdd)`` of the scene's sweep: dicts of (N,) arrays."""
        return scene_sweep(self.scene)

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
            Force method (see :mod:`linkage_sym.numeric.kinetostatics`).
        """
        check_method(method)  # before the kinematics, not after
        if q is None:
            q, qd, qdd = self.sweep()
        q = {k: np.asarray(v, dtype=float) for k, v in q.items()}
        N = len(next(iter(q.values())))
        path = self._path(q)
        S = {GROUND: LinkState()}
        for n in self.scene.link_names:
            S[n] = LinkState()
        inds = []
        npath = len(path.q[next(iter(path.q))])
        for solver in self.solvers:
            ind = solver.position(S, path.q)
            # a group whose geometry does not change (two fixed slide directions) gives a scalar
            inds.append(None if ind is None else np.broadcast_to(ind, (npath,)))
        # first group that failed at each path point
        failed_at = np.full(npath, -1)
        for gi, ind in enumerate(inds):
            if ind is None:
                continue
            bad = ~np.isfinite(ind) & (failed_at < 0)
            failed_at[bad] = gi
        valid = failed_at < 0
        all_valid = bool(valid.all())
        for n in self.wrapped:
            st = S[n]
            th = np.array(np.broadcast_to(st.th, (npath,)), dtype=float)
            if all_valid:
                th = _unwrap(th)
            else:
                th[valid] = _unwrap(th[valid])
            st.th = th
        out = path.out
        failed = failed_at[out]
        messages = [None] * N
        path_index = np.arange(npath)[out]
        for i in np.flatnonzero(failed >= 0):
            messages[i] = self.solvers[failed[i]].failure(S, int(path_index[i]))
        S = {n: (st.take(out) if n != GROUND else st) for n, st in S.items()}
        status = np.full(N, OK, dtype="<U13")
        status[failed >= 0] = UNASSEMBLABLE
        # --- singularity: exact condition number where an indicator is small
        ind_min = np.full(N, np.inf)
        for ind in inds:
            if ind is not None:
                ind_min = np.fmin(ind_min, ind[out])
        condition = np.full(N, np.nan)
        check = (failed < 0) & (np.ones(N, bool) if exact_condition else ind_min < SCREEN)
        if check.any():
            idx = np.flatnonzero(check)
            condition[idx] = self.condition_numbers(S, idx)
            sing = idx[~(condition[idx] <= SINGULAR_COND)]
            status[sing] = SINGULAR
            for i in sing:
                messages[i] = (
                    f"singular position: condition number {condition[i]:.3g} of the "
                    f"dimensionless constraint Jacobian exceeds {SINGULAR_COND:.0e}; "
                    "velocities and accelerations have no unique solution"
                )
        qd = {k: np.asarray(v, dtype=float) for k, v in qd.items()}
        qdd = {k: np.asarray(v, dtype=float) for k, v in qdd.items()}
        if "velocity" in self.stages:
            for solver in self.solvers:
                solver.velocity(S, q, qd)
        if "acceleration" in self.stages:
            for solver in self.solvers:
                solver.acceleration(S, q, qd, qdd)
        forces = None
        if self.force_plan is not None:
            forces = self.force_plan.run(S, status == OK, method)
        return self._analysis(S, q, qd, qdd, status, messages, condition, forces)

    def condition_numbers(self, S, idx) -> np.ndarray:
        """Exact dimensionless condition number of the full constraint Jacobian at steps ``idx``."""
        Si = {n: st.take(idx) if n != GROUND else st for n, st in S.items()}
        J = jacobian(self.all_constraints, Si, list(self.scene.link_names), len(idx), self.L)
        sv = np.linalg.svd(J, compute_uv=False)
        with np.errstate(divide="ignore"):
            return sv[:, 0] / sv[:, -1]

    def _analysis(self, S, q, qd, qdd, status, messages, condition, forces) -> Analysis:
        N = len(status)
        bad = status != OK
        sing = status == SINGULAR
        has_v = "velocity" in self.stages
        has_a = "acceleration" in self.stages

        def clean(arr, mask):
            out = np.empty(N)
            out[:] = arr
            if any_bad:
                out[mask] = np.nan
            return out

        any_bad = bool(bad.any())

        def vec(pair, mask):
            # filled as (2, N) rows (contiguous writes), returned as its (N, 2) view
            out = np.empty((2, N))
            out[0] = pair[0]
            out[1] = pair[1]
            out = out.T
            if any_bad:
                out[mask] = np.nan
            return out

        pos_bad = bad & ~sing
        links = {}
        for link in self.scene.links:
            st = S[link.name]
            lk = LinkKinematics(
                rotation=clean(st.th, pos_bad),
                origin=vec((st.dx, st.dy), pos_bad),
            )
            if has_v:
                lk.omega = clean(st.w, bad)
                lk.origin_velocity = vec((st.vx, st.vy), bad)
            if has_a:
                lk.alpha = clean(st.al, bad)
                lk.origin_acceleration = vec((st.ax, st.ay), bad)
            if link.com is not None:
                lk.com = vec(st.point(link.com), pos_bad)
                if has_v:
                    lk.com_velocity = vec(st.point_velocity(link.com), bad)
                if has_a:
                    lk.com_acceleration = vec(st.point_acceleration(link.com), bad)
            links[link.name] = lk
        joints = {}
        for j in self.scene.joints:
            st = S[j.links[1]]
            jk = JointKinematics(position=vec(st.point(j.at), pos_bad))
            if has_v:
                jk.velocity = vec(st.point_velocity(j.at), bad)
            if has_a:
                jk.acceleration = vec(st.point_acceleration(j.at), bad)
            joints[j.name] = jk
        drivers = {
            k: {"q": np.asarray(q[k], float), "qd": np.asarray(qd[k], float), "qdd": np.asarray(qdd[k], float)}
            for k in q
        }
        return Analysis(
            scene=self.scene.name,
            stages=self.stages,
            status=status,
            messages=messages,
            drivers=drivers,
            joints=joints,
            links=links,
            condition=condition,
            outputs=tuple(self.scene.outputs),
            forces=forces,
            p_joints=tuple(j.name for j in self.scene.joints if j.type == "P"),
        )


def compile_plan(scene: Scene, disconnection=None) -> Plan:
    """Analyse ``scene`` once into a :class:`Plan` whose ``run`` solves every step.

    Raises
    ------
    SceneError
        If the mechanism cannot be decomposed into solvable groups, or its
        assembly configuration is a singular position of a group.
    """
    return Plan(scene, decompose(scene), disconnection)
