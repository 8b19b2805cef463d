"""What the solving plan asks of each group's solver (NumPy only).

:class:`GroupSolver` is the contract of the position and rate solvers of the
groups -- input links and dyads in closed form
(:mod:`~linkage_sym.numeric.kinematics.closed_form`), gears on their pivots
(:mod:`~linkage_sym.numeric.kinematics.gears`), every other group by Newton's method
(:mod:`~linkage_sym.numeric.kinematics.newton`) -- so a new kind of group adds a class
that meets it, not a branch in :class:`~linkage_sym.numeric.plan.Plan`.
The force routines have theirs in :mod:`~linkage_sym.numeric.forces.kinetostatics`
(``ForceRoutine``).
"""

from __future__ import annotations

from typing import Any, Protocol, Sequence

import numpy as np


class GroupSolver(Protocol):
    """The position and rate solver of one group, as :meth:`Plan.run` calls it."""

    wraps: bool
    """Whether the rotations it gives may come wrapped to one turn (an ``atan2``), so the
    plan unwraps them along the solving path; a group followed continuously from the
    assembly configuration (Newton, gears) or an input turning on the ground does not."""
    notes: Sequence[Any]
    """Assembly-mode jumps and ambiguous re-entries of the last ``position`` call, for the
    run's warnings (:func:`~linkage_sym.numeric.continuation.messages.step_warnings`)."""

    def position(self, S: dict, q: dict) -> np.ndarray | None:
        """Poses of the group's links at every path point, written into ``S``; returns the
        conditioning indicator (NaN where the group cannot be assembled), or ``None`` for a
        group whose geometry does not change."""

    def failure(self, S: dict, i: int) -> str:
        """Why the group cannot be assembled at path point ``i``."""

    def velocity(self, S: dict, q: dict, qd: dict) -> None:
        """Rates of the group's links at the steps, written into ``S``."""

    def acceleration(self, S: dict, q: dict, qd: dict, qdd: dict) -> None:
        """Accelerations of the group's links at the steps, written into ``S``."""
