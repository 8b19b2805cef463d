"""A scene's sweep to be solved in chunks: which runtime solves it, and the route a chunk's
solving path takes (no SymPy, no plots).

:func:`plan_sweep` (the numeric plan, a force method) and :func:`compiled_sweep` (the
compiled mechanism) make a :class:`Sweep`; :func:`linkage_sym.output.write_sweep` solves it
chunk by chunk.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from linkage_sym.numeric.results.result import Analysis

__all__ = ["Sweep", "compiled_sweep", "path_limits", "plan_sweep"]


@dataclass
class Sweep:
    """A sweep to solve in chunks: ``run(q, qd, qdd)`` solves any of its steps.

    ``heads`` are the Newton groups' names as their warnings begin
    (``"triad (b1, t, b2, b3)"``), in the order a run lists their warnings.
    ``q0`` is each driver's value in the assembly configuration and
    ``limits`` its largest increment along a solving path (see
    :func:`linkage_sym.numeric.engine.run.solving_path`): with them,
    :meth:`waypoints` lets a chunk's path take the whole sweep's route.
    """

    run: Callable[..., Analysis]
    q: dict
    qd: dict
    qdd: dict
    method: str = "dyad"
    heads: list = field(default_factory=list)
    q0: dict = field(default_factory=dict)
    limits: dict = field(default_factory=dict)

    @property
    def n_steps(self) -> int:
        return len(next(iter(self.q.values())))

    def solve(self, a: int, b: int, waypoints=()) -> Analysis:
        """Steps ``a`` to ``b`` of the sweep, after the steps ``waypoints`` (indices)."""
        idx = np.concatenate([np.asarray(waypoints, dtype=np.intp), np.arange(a, b)])
        part = [{k: np.asarray(v)[idx] for k, v in d.items()} for d in (self.q, self.qd, self.qdd)]
        return self.run(*part)

    def waypoints(self, a: int) -> np.ndarray:
        """Steps of the sweep a chunk starting at step ``a`` solves first, so that its path
        takes the whole sweep's route: from the assembly configuration to the sweep's first
        step, then along the sweep.

        A run's path goes from the assembly configuration straight to its
        first step.  Where the sweep does not start at the assembly
        configuration, the whole sweep's path first goes back to its start;
        a Newton group may pass a limit position on the way and go on in
        another configuration of its assembly mode (a jump, warned), which
        the straight path to a later step would not.  So such a chunk also
        solves every ``m``-th step before it, ``m`` the most steps whose
        driver increments stay within the path's limits (so the path's
        refinement is the sweep's).  Closed-form groups have no such memory
        (their rotations are joined across chunks by whole turns): no
        waypoints for them, nor where the sweep starts at the assembly
        configuration.
        """
        if a <= 0 or not self.heads or self._straight(a):
            return np.zeros(0, dtype=np.intp)
        m = math.inf
        for k, v in self.q.items():
            h = abs(float(v[1]) - float(v[0])) if len(v) > 1 else 0.0
            if h > 0:
                m = min(m, self.limits[k] / h)
        m = 1 if not math.isfinite(m) else max(1, int(m))
        return np.arange(0, a, m, dtype=np.intp)

    def _straight(self, a: int) -> bool:
        """Whether the straight path from the assembly configuration to step ``a`` is the
        sweep's route: the sweep starts at the assembly configuration (to a millionth of a
        path increment), or its one driver starts between the assembly value and step ``a``."""
        if all(abs(float(self.q[k][0]) - v) <= 1e-6 * self.limits[k] for k, v in self.q0.items()):
            return True
        if len(self.q) == 1:
            (k, v), = self.q.items()
            return (float(v[0]) - self.q0[k]) * (float(v[a]) - float(v[0])) >= 0
        return False

    def most_waypoints(self) -> int:
        """The most waypoints of any chunk (the last)."""
        return len(self.waypoints(self.n_steps - 1))


def path_limits(scene, L) -> dict:
    from linkage_sym.numeric.engine.run import MAX_ANGLE_STEP, MAX_SLIDE_STEP

    return {d.joint: MAX_ANGLE_STEP if scene.joint(d.joint).type == "R" else MAX_SLIDE_STEP * L
            for d in scene.drivers}


def plan_sweep(plan, method: str = "dyad") -> Sweep:
    """The scene's sweep solved by a numeric plan (``compile_plan``) with a force method."""
    from linkage_sym.numeric.kinematics.newton import NewtonSolver

    q, qd, qdd = plan.sweep()
    heads = [f"{sv.group.label} ({', '.join(sv.links)})" for sv in plan.solvers
             if isinstance(sv, NewtonSolver)]
    return Sweep(lambda q, qd, qdd: plan.run(q, qd, qdd, method=method), q, qd, qdd, method, heads,
                 dict(plan.q0), path_limits(plan.scene, plan.L))


def compiled_sweep(mechanism) -> Sweep:
    """The scene's sweep evaluated by a compiled mechanism (``compile_mechanism``)."""
    art = mechanism.art
    heads = [art.group(st.group).title for st in art.newton_steps]
    q, qd, qdd = mechanism.sweep()
    return Sweep(lambda q, qd, qdd: mechanism.run(q, qd, qdd), q, qd, qdd, "symbolic", heads,
                 dict(mechanism.q0), path_limits(mechanism.scene, mechanism.L))
