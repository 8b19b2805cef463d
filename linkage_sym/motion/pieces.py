"""The smooth pieces of the equation of motion, and the equation frozen on one piece.

The right-hand side ``qdd(q, qd)`` has kinks where the motor's table has a row (the speeds
of its rows: the effort's slope changes) and where a load varying over the cycle switches on
or off or its table has a row (the driver angles of its ``active`` ends and of its table's
rows, repeating with its period).  An integrator stepping across a kink sees a function that
is not smooth: its error estimate fails, it shrinks its steps and LSODA turns to its stiff
method, thousands of evaluations a turn.  Between two consecutive breakpoints the
right-hand side is smooth; :mod:`~linkage_sym.motion.integrate` integrates each such
**piece** on its own and restarts the solver where the motion leaves it.

On a piece the equation is evaluated **frozen**: the motor's effort is the line of the table's
segment the piece lies in, and each varying load's factor is the line it follows on the
piece (its active state and its table's segment), both extended beyond the piece's ends.  The
solver's steps and its Jacobian then see a smooth function even where a step reaches past
the piece's end (the part past it is thrown away: the step is cut at the crossing, found on
its dense output, and the solver restarts from there with the next piece).  Within the piece
the frozen equation is the scene's to rounding.

The frozen loads are the scene's loads with their factor a periodic table of two rows: linear
over the whole reduction period around the piece but for a ramp of :data:`RAMP` of the
period opposite it (where no step reaches: no piece is wider than 1/:data:`SPLIT` of the
period, so a step would have to reach more than three eighths of a period past a piece's end;
a step that does is taken again shorter).  Loads are frozen for an ``R`` driver whose
angle is reduced by whole periods (:meth:`MotionEquations.reduce`); for a ``P`` driver, or
an ``R`` driver whose loads do not repeat, only the motor's kinks are pieces' ends.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.model import LoadTable

__all__ = ["Piece", "Pieces"]

SPLIT = 4
"""No piece spans more than this fraction (its inverse) of the loads' period."""
RAMP = 1e-6
"""The fraction of the period over which a frozen load's table returns (opposite the piece)."""


@dataclass
class Piece:
    """One smooth piece: the driver's interval ``[lo, hi]`` (unwrapped; infinite without
    varying loads), the motor's segment ``s`` between the speeds ``[slo, shi]``, the effort
    plan of its frozen loads and the interval ``safe`` over which they are frozen."""

    plan: object
    j: int
    turn: int
    lo: float
    hi: float
    safe: tuple
    s: int
    slo: float
    shi: float
    base: tuple

    def motor(self, qd: float) -> float:
        """The frozen motor's effort: the line of segment ``s`` (its row's effort held
        beyond the table's ends), computed as :func:`numpy.interp` computes it."""
        s0, e0, slope = self.base
        return e0 + (qd - s0) * slope if slope else e0

    def switching(self, y) -> np.ndarray:
        """The four switching functions at ``y = (q, qd)``: all ``>= 0`` on the piece."""
        q, qd = y[0], y[1]
        return np.array([q - self.lo, self.hi - q, qd - self.slo, self.shi - qd])

    def inside_safe(self, q: float) -> bool:
        """Whether ``q`` is where the frozen loads are the piece's lines."""
        return self.safe[0] <= q <= self.safe[1]


class Pieces:
    """The breakpoints of a scene's equation of motion and its frozen pieces.

    Parameters
    ----------
    eq : MotionEquations
    """

    def __init__(self, eq):
        self.eq = eq
        self.speeds = np.asarray(eq.motor.speeds, float)
        self.efforts = np.asarray(eq.motor.efforts, float)
        self.varying = [i for i, load in enumerate(eq.scene.loads)
                        if load.driver == eq.joint and load.period is not None
                        and (load.table is not None or load.active is not None)]
        self.R = eq.period if (self.varying and eq.driver.kind == "R") else None
        self.B = None if self.R is None else self._breakpoints()
        self._plans: dict = {}

    def _breakpoints(self) -> np.ndarray:
        """The varying loads' switch points in ``[0, R)``, wide intervals split."""
        R = self.R
        pts = []
        for i in self.varying:
            load = self.eq.scene.loads[i]
            own = list(load.table.q) if load.table is not None else []
            own += list(load.active) if load.active is not None else []
            for k in range(int(round(R / load.period))):
                pts += [x + k * load.period for x in own]
        B = np.unique(np.mod(np.asarray(pts, float), R))
        out = []
        for a, b in zip(B, np.append(B[1:], B[0] + R)):
            n = max(1, math.ceil((b - a) * SPLIT / R - 1e-9))
            out += [a + (b - a) * k / n for k in range(n)]
        return np.unique(np.mod(np.asarray(out), R))

    # -- the piece at a state --------------------------------------------------
    def at(self, q: float, qd: float, up_q: bool, up_qd: bool) -> Piece:
        """The piece the motion at ``(q, qd)`` is in, or enters when it lies on a
        breakpoint (``up_q``, ``up_qd``: whether ``q``, ``qd`` increase)."""
        s = int(np.searchsorted(self.speeds, qd, side="right" if up_qd else "left"))
        if len(self.speeds) == 1:
            s = 0
        if self.B is None:
            return self._piece(None, 0, s)
        turn = math.floor(q / self.R)
        x = q - turn * self.R
        j = int(np.searchsorted(self.B, x, side="right" if up_q else "left")) - 1
        if j < 0:
            turn, j = turn - 1, len(self.B) - 1
        return self._piece(j, turn, s)

    def neighbour(self, piece: Piece, k: int) -> Piece:
        """The piece past the switching function ``k`` of ``piece``."""
        j, turn, s = (None if piece.j < 0 else piece.j), piece.turn, piece.s
        if k == 0:
            j -= 1
            if j < 0:
                turn, j = turn - 1, len(self.B) - 1
        elif k == 1:
            j += 1
            if j == len(self.B):
                turn, j = turn + 1, 0
        else:
            s += 1 if k == 3 else -1
        return self._piece(j, turn, s)

    def _piece(self, j, turn: int, s: int) -> Piece:
        sp, ef = self.speeds, self.efforts
        n = len(sp)
        slo = -math.inf if s == 0 or n == 1 else sp[s - 1]
        shi = math.inf if s >= n or n == 1 else sp[s]
        if n == 1 or s == 0:
            base = (sp[0], ef[0], 0.0)
        elif s >= n:
            base = (sp[-1], ef[-1], 0.0)
        else:
            base = (sp[s - 1], ef[s - 1], (ef[s] - ef[s - 1]) / (sp[s] - sp[s - 1]))
        if j is None:
            return Piece(self.eq.effort_plan, -1, 0, -math.inf, math.inf,
                         (-math.inf, math.inf), s, slo, shi, base)
        R, B = self.R, self.B
        lo = turn * R + B[j]
        hi = turn * R + (B[j + 1] if j + 1 < len(B) else B[0] + R)
        mid = 0.5 * (lo + hi)
        safe = (mid - R / 2 * (1 - 2 * RAMP), mid + R / 2 * (1 - 2 * RAMP))
        return Piece(self._plan(j), j, turn, lo, hi, safe, s, slo, shi, base)

    def _plan(self, j: int):
        """The effort plan with every varying load frozen on interval ``j``."""
        if j not in self._plans:
            from linkage_sym.numeric.forces.loads import load_factor
            from linkage_sym.numeric.plan import compile_plan

            R, B = self.R, self.B
            lo, hi = B[j], (B[j + 1] if j + 1 < len(B) else B[0] + R)
            x = np.array([0.75 * lo + 0.25 * hi, 0.25 * lo + 0.75 * hi])
            mid, half = 0.5 * (lo + hi), R / 2 * (1 - 2 * RAMP)
            scene = self.eq.effort_plan.scene
            loads = list(scene.loads)
            for i in self.varying:
                f = load_factor(loads[i], {self.eq.joint: x})
                slope = (f[1] - f[0]) / (x[1] - x[0])
                fm = 0.5 * (f[0] + f[1])
                table = LoadTable((mid - half, mid + half), (fm - slope * half, fm + slope * half))
                loads[i] = dataclasses.replace(loads[i], table=table, active=None, period=R)
            self._plans[j] = compile_plan(dataclasses.replace(scene, loads=tuple(loads)))
        return self._plans[j]
