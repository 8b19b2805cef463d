"""Force plots at a joint's passage through infinity.

The guide-slider of :mod:`tests.support.parallel_slides` with its masses' inertia and
gravity (its driver turning at 1 rad/s): with 10 steps from 30 to -30 degrees the rod's line
is parallel to the block's slide between steps 4 and 5 (guide angles 3.33 and -3.33
degrees, the reference below), where joint ``C`` passes through infinity.  The driving
effort, every reaction and the frame loads are large there and of opposite signs on the two
sides (the links carried off move unboundedly fast near the passage): read back from the
Matplotlib figures, no line of the driving effort, of a reaction's hodograph or of the frame
force and moment joins step 4 to step 5, while every step's value is still drawn.  A sweep
without a passage (30 to 5 degrees) draws its arrays exactly as they are.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

import linkage_sym
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.plotting.forces import (driving_effort_figure, frame_loads_figure,
                                         reaction_hodographs_figure)
from tests.support.parallel_slides import guide_slider

TOL = 1e-9  # relative: a drawn point is a step's value (degrees or polar conversion only)


def _run(steps, stop=-30.0):
    d = guide_slider(steps, stop=stop)
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    d["effects"] = {"inertia": True, "gravity": [0.0, -9.81]}
    scene = linkage_sym.load_scene(d)
    return scene, compile_plan(scene).run()


@pytest.fixture(scope="module")
def passage():
    return _run(10)


def _xy(line):
    return np.column_stack([np.asarray(line.get_xdata(), float),
                            np.asarray(line.get_ydata(), float)])


def _same(a, b) -> bool:
    return np.allclose(a, b, rtol=TOL, atol=TOL * max(float(np.max(np.abs(b))), 1.0))


def _joined(lines, p, q) -> bool:
    """Whether a segment of one of ``lines`` joins the points ``p`` and ``q``."""
    for line in lines:
        xy = _xy(line)
        for k in range(len(xy) - 1):
            if ((_same(xy[k], p) and _same(xy[k + 1], q))
                    or (_same(xy[k], q) and _same(xy[k + 1], p))):
                return True
    return False


def _drawn(lines, p) -> bool:
    return any(_same(row, p) for line in lines for row in _xy(line))


def _polar(v):
    return np.array([math.atan2(v[1], v[0]), math.hypot(v[0], v[1])])


def _guide_angles(res):
    return np.degrees(np.asarray(res.drivers["A"]["q"], dtype=float))


def test_the_reference_passage_is_between_steps_4_and_5(passage):
    _, res = passage
    q = _guide_angles(res)
    # the rod's line through the origin at the guide's angle is parallel to y = H at 0 deg
    assert q[4] > 0 > q[5] and list(res.status) == ["ok"] * 10
    T = np.asarray(res.forces.driving["A"])
    # the efforts are not zero: large and of opposite signs across the passage
    assert abs(T[4]) > 100 * abs(T[0]) and np.sign(T[4]) == -np.sign(T[5])


def test_the_driving_effort_is_not_joined_across_the_passage(passage):
    scene, res = passage
    fig = driving_effort_figure(scene, res)
    q, T = _guide_angles(res), np.asarray(res.forces.driving["A"])
    lines = [line for line in fig.axes[0].get_lines() if len(line.get_xdata()) > 2]
    assert not _joined(lines, (q[4], T[4]), (q[5], T[5]))
    assert all(_drawn(lines, (q[k], T[k])) for k in range(10))
    assert _joined(lines, (q[3], T[3]), (q[4], T[4]))
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert any("through infinity after step 4" in t for t in legend)
    plt.close(fig)


@pytest.mark.parametrize("joint", ["A", "A_slide", "C"])
def test_no_reaction_hodograph_is_joined_across_the_passage(passage, joint):
    scene, res = passage
    fig = reaction_hodographs_figure(scene, res, [joint])
    R = np.asarray(res.forces.reactions[joint])
    lines = fig.axes[0].get_lines()
    assert abs(R[4, 1]) > 100 * abs(R[0, 1])  # a force that matters
    assert not _joined(lines, _polar(R[4]), _polar(R[5]))
    assert all(_drawn(lines, _polar(R[k])) for k in range(10))
    assert _joined(lines, _polar(R[5]), _polar(R[6]))
    assert "through infinity after step 4" in fig.axes[0].get_title()
    plt.close(fig)


def test_the_frame_loads_are_not_joined_across_the_passage(passage):
    scene, res = passage
    fig = frame_loads_figure(scene, res)
    polar, ax = fig.axes[0], fig.axes[1]
    F, M, q = res.forces.frame_force, res.forces.frame_moment, _guide_angles(res)
    assert abs(M[4]) > 20 * abs(M[0]) and np.sign(M[4]) == -np.sign(M[5])
    assert not _joined(polar.get_lines(), _polar(F[4]), _polar(F[5]))
    assert not _joined(ax.get_lines(), (q[4], M[4]), (q[5], M[5]))
    assert all(_drawn(ax.get_lines(), (q[k], M[k])) for k in range(10))
    assert all(_drawn(polar.get_lines(), _polar(F[k])) for k in range(10))
    plt.close(fig)


def test_without_a_passage_the_force_curves_are_the_arrays():
    scene, res = _run(10, stop=5.0)
    assert res.passages == ()
    q, T = _guide_angles(res), np.asarray(res.forces.driving["A"])
    fig = driving_effort_figure(scene, res)
    line = fig.axes[0].get_lines()[1]  # after the zero line
    assert np.array_equal(line.get_xdata(), q) and np.array_equal(line.get_ydata(), T)
    plt.close(fig)
    fig = frame_loads_figure(scene, res)
    moment = next(ln for ln in fig.axes[1].get_lines() if len(ln.get_xdata()) == 10)
    assert np.array_equal(moment.get_ydata(), res.forces.frame_moment)
    F = res.forces.frame_force
    force = next(ln for ln in fig.axes[0].get_lines() if len(ln.get_xdata()) == 10)
    assert np.array_equal(force.get_ydata(), np.hypot(F[:, 0], F[:, 1]))
    plt.close(fig)
