"""A chunk of designs solved at the steps of the scene's sweep: what the metrics read.

Filled by :meth:`linkage_sym.design.evaluate.Model.solve` (the compiled
mechanism's functions); :class:`linkage_sym.design.newton_groups.PlanSolution`
reads the same quantities from the numeric plan's result for designs with
groups without a closed form.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass
class Solution:
    """A chunk of ``n`` designs solved at the ``N`` steps of the scene's sweep.

    Per-step arrays are ``(n, N)`` (coordinates ``(m, n, N)``), NaN where a step
    has no value; per-design arrays ``(n,)``.
    """

    n: int
    N: int
    P: list  # parameters of the designs: floats (shared) or (n,) arrays
    assembled: np.ndarray  # (n,) bool
    X0: np.ndarray  # (m, n) the assembly configuration
    joints0: dict  # joint -> (2, n) positions in the assembly configuration
    L: np.ndarray  # (n,) size: largest distance between two joints at assembly
    X: np.ndarray  # (m, n, N) coordinates, angles continuous from the assembly
    pos_ok: np.ndarray  # (n, N)
    ok: np.ndarray  # (n, N)
    rate_t: np.ndarray | None = None  # (m, n, N) rates along the steps (dq/dt per step; NaN
    # for a coordinate the metrics do not read)
    XD: np.ndarray | None = None  # (m, n, N) at the scene's speeds
    XDD: np.ndarray | None = None
    points: list | None = None  # the points function's outputs, (n, N) each
    forces: np.ndarray | None = None  # (nF, n, N) reactions and efforts
    C: np.ndarray | None = None  # (m, n, N) cosines of the coordinates (NaN where no position)
    S: np.ndarray | None = None
    model: object = None  # the Model that solved it
    transmission: np.ndarray | None = None  # (dyads, n) each RRR dyad's smallest transmission
    # ratio |sin gamma| / |cos gamma| over the steps, when the solver computed it (numba)
    locked: np.ndarray | None = None  # (n, N) the self-locking steps (joint friction): ok
    # kinematically, but no finite driving effort moves the design there (forces NaN)
    brackets: tuple | None = None  # (design, step, rate there, rate at the next step) of each
    # sign change of the output's rate along the steps between ok steps, when the solver
    # found them (numba; else Limits finds them in rate_t)

    model_rates = True  # rate_at is the Model's (a subclass: another runtime's)

    # what the metrics read, (n, N) each; a subclass reads them from another runtime's result
    def reaction(self, joint) -> np.ndarray:
        """Magnitude of the reaction at ``joint`` (see :meth:`Model.reaction`)."""
        return self.model.reaction(self, joint)

    def effort(self, driver) -> np.ndarray:
        """The driving torque or force at ``driver``."""
        return self.model.effort(self, driver)

    def com(self, link):
        """``(x, y, ax, ay)``: the centre of mass of ``link`` and its acceleration."""
        a0, _ = self.model.point_rows(f"com:{link}:0")
        a2, _ = self.model.point_rows(f"com:{link}:2")
        return self.points[a0], self.points[a0 + 1], self.points[a2], self.points[a2 + 1]

    def alpha(self, link) -> np.ndarray:
        """The angular acceleration of ``link`` at the scene's speeds."""
        return self.XDD[self.model.angle_of[link]]

    def traced(self, point):
        """``(x, y)`` of the traced point ``point`` at every step with positions (``ok``
        or singular; NaN where unassemblable)."""
        model = self.model
        pt = next(q for q in model.scene.points if q.name == point)
        fr = model.frames[pt.link]
        c, s = math.cos(fr.theta0), math.sin(fr.theta0)
        dx, dy = pt.at[0] - fr.origin[0], pt.at[1] - fr.origin[1]
        lx, ly = c * dx + s * dy, -s * dx + c * dy  # in the link frame (u, u -> v)
        a, _ = model.point_rows(f"origin:{pt.link}:0")
        th = self.X[model.angle_of[pt.link]]
        x = self.points[a] + np.cos(th) * lx - np.sin(th) * ly
        y = self.points[a + 1] + np.sin(th) * lx + np.cos(th) * ly
        return np.where(self.pos_ok, x, np.nan), np.where(self.pos_ok, y, np.nan)

    def rate_at(self, d, t, col):
        """The rate along the steps of coordinate ``col`` of designs ``d`` at fractional
        steps ``t``, its own rate and the coordinate (:meth:`Model.rate_at`)."""
        return self.model.rate_at(self.P, d, t, col)
