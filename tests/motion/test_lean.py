"""The equation of motion at one state (``motion.lean``) against the full runs.

The lean path calls the same solves without a result's bookkeeping; its ``qdd`` must be the
one the whole :class:`~linkage_sym.numeric.results.result.Analysis` of the numeric plan and of
the compiled mechanism give (``(M - E0) / J`` from ``MotionEquations.effort`` and
``MotionEquations.inertia``), to 1e-12 relative, over a turn of the crank-rocker and of the
shaper at several speeds.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.motion.equations import MotionEquations, motor_effort


@pytest.mark.parametrize("name", ["crank_rocker_motor", "shaper_flywheel"])
def test_one_state_acceleration_is_the_full_runs(name):
    eq = MotionEquations(linkage_sym.load_scene(example_dict(name)), require_simulate=False)
    q = np.linspace(-7.0, 7.0, 37)
    qd = np.linspace(2.0, 30.0, 37)
    e0 = eq.effort(q, qd)[0]
    J = eq.inertia(q)[0]
    want = (motor_effort(eq.motor, qd) - e0) / J
    got = np.array([eq.acceleration(a, b) for a, b in zip(q, qd)])
    scale = np.abs(motor_effort(eq.motor, qd)) / J + np.abs(e0) / J
    np.testing.assert_array_less(np.abs(got - want), 1e-12 * scale)
