"""Revolute-only Newton groups in loop-closure coordinates (:mod:`linkage_sym.numeric.loop_closure`).

The class-III triad is solved in its four links' angles with four loop rows
(the pose formulation, :class:`~linkage_sym.numeric.newton.NewtonSolver`,
has twelve of each).  Checked against what shares no code with it:

* **the Jacobian** (``i E_k W[k, r]`` of the linear form) against central
  differences of the rows themselves (step ``1e-6``: truncation ``~1e-12``,
  rounding ``~1e-10``; ``1e-8`` of the Jacobian's scale);
* **the positions and rates** against the pose formulation (the group solved
  in poses, the constraint rows of :mod:`~linkage_sym.numeric.constraints`):
  the same status at every step and every value within ``1e-10`` of its
  family's scale (positions: the mechanism's size), on the shipped class-III
  six-bar and on random triads over a full turn, with limits and gaps; every
  ``ok`` step closes and keeps the assembly mode by the tests' own joint
  equations and finite-difference Jacobian (:mod:`reference_kinematics`);
* the rates against **finite differences of the positions** along a fine
  sweep (velocities ``1e-7``, accelerations ``1e-5`` of their scale: the
  central difference's truncation at 0.01 deg steps);
* **the indicator** (``1 / (|J|_F |J^-1|_F)``) against the SVD: between
  ``r / n`` and ``r`` for ``r = sigma_min / sigma_max``, on matrices
  conditioned from 1 to 1e15, ``0`` for singular ones and NaN for non-finite.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

sys.path.insert(0, os.path.dirname(__file__))

import reference_kinematics as ref  # noqa: E402
import scenes  # noqa: E402
from test_batched_continuation import _load, _triad_from, assert_same  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.numeric import continuation, loop_closure  # noqa: E402
from linkage_sym.numeric.loop_closure import LoopClosureSolver  # noqa: E402
from linkage_sym.numeric.newton import NewtonSolver  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.numeric.state import LinkState  # noqa: E402

SETTINGS = dict(max_examples=8, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
wide_jitter = st.tuples(*[st.floats(-0.06, 0.06, allow_nan=False)] * 12)


def _pose_plan(scene):
    """The plan with every Newton group in pose coordinates (the formulation before)."""
    applies = loop_closure.applies
    loop_closure.applies = lambda *a: False
    try:
        return compile_plan(scene)
    finally:
        loop_closure.applies = applies


def _group_problem(plan):
    """The loop-closure group's problem along the plan's own path (its inputs solved)."""
    q, _, _, path = plan._scene_sweep()
    S = {n: LinkState() for n in ["ground", *plan.scene.link_names]}
    for sv in plan.solvers:
        if isinstance(sv, LoopClosureSolver):
            return sv, sv._problem(S, path.q), len(next(iter(path.q.values())))
        sv.position(S, path.q)
    raise AssertionError("no loop-closure group")


def test_the_triads_take_the_loop_closure_and_the_others_stay_in_poses():
    plan = compile_plan(linkage_sym.load_example("sixbar_class3"))
    kinds = [type(sv) for sv in plan.solvers]
    assert LoopClosureSolver in kinds
    sv = next(sv for sv in plan.solvers if isinstance(sv, LoopClosureSolver))
    assert sv.nvar == 4 and len(sv.loops) == 2  # 4 angles, 2 loops: 4 rows
    # an actuator (a driven slide) and the printing mechanism's P joints: pose coordinates
    for name in ("hydraulic_boom", "printing_mechanism"):
        plan = compile_plan(linkage_sym.load_example(name))
        newton = [sv for sv in plan.solvers if isinstance(sv, NewtonSolver)]
        assert newton and not any(isinstance(sv, LoopClosureSolver) for sv in newton), name


@pytest.mark.parametrize("jitter", [None, (0.02, -0.01, 0.0, 0.015, -0.02, 0.01,
                                           0.01, 0.0, -0.015, 0.02, 0.0, -0.01)])
def test_jacobian_against_central_differences(jitter):
    scene = (linkage_sym.load_example("sixbar_class3") if jitter is None
             else linkage_sym.load_scene(_triad_from(jitter)))
    _, problem, n_points = _group_problem(compile_plan(scene))
    rng = np.random.default_rng(1)
    h = 1e-6
    for i in rng.integers(0, n_points, 6):
        ctx = problem.at(int(i))
        for _ in range(3):
            u = rng.uniform(-math.pi, math.pi, problem.sv.nvar)
            _, J = problem.evaluate(u, ctx)
            fd = np.array([(problem.evaluate(u + h * e, ctx)[0] - problem.evaluate(u - h * e, ctx)[0])
                           / (2 * h) for e in np.eye(len(u))]).T
            assert np.max(np.abs(J - fd)) <= 1e-8 * np.max(np.abs(J)), (i, J, fd)
            # the batched evaluation is the same function
            R1, J1 = problem.evaluate_points(u[None], np.array([i]))
            R0, J0 = problem.evaluate(u, ctx)
            assert np.allclose(R1[0], R0, rtol=0, atol=1e-15) and np.allclose(J1[0], J0, atol=1e-15)


def _against_poses(scene, what):
    a = linkage_sym.analyze(scene)  # the default plan: loop closure
    b = _pose_plan(scene).run()
    assert_same(b, a, what, scene.characteristic_length(), words=False)
    ok = np.flatnonzero(a.status == "ok")
    assert not ref.closure_failures(scene, a, 1e-12, 1e-9)
    _, s0, signs, _ = ref.determinant_signs(scene, a)
    assert np.all(signs[ok] == s0), "an ok step in another assembly mode"
    return a, b


def test_the_shipped_class3_sixbar_agrees_with_the_pose_formulation():
    a, _ = _against_poses(linkage_sym.load_example("sixbar_class3"), "sixbar_class3")
    assert (a.status == "ok").all()


@settings(**SETTINGS)
@given(j=wide_jitter)
def test_random_triads_agree_with_the_pose_formulation(j):
    """Random triads over a full turn (181 steps): continuous sweeps, limits, gaps."""
    scene = _load(_triad_from(j, steps=181))
    if scene is None:
        return
    _against_poses(scene, "random triad")


def test_a_triad_past_a_limit_agrees_with_the_pose_formulation():
    scene = linkage_sym.load_scene(scenes.triad_jump())
    a, b = _against_poses(scene, "triad jump")
    assert any("passes a limit" in w for w in a.warnings)


def test_rates_against_finite_differences_of_the_positions():
    """Velocities and accelerations of every link against central differences of the
    solved rotations and origins over 0.01 deg steps (the driver at constant speed 10
    rad/s plus an acceleration of 1 rad/s^2, as the scene has it)."""
    d = _triad_from((0.0,) * 12)
    h = math.radians(0.01)
    th0 = np.radians(np.arange(5.0, 355.0, 25.0))
    w, al = 10.0, 1.0
    q = np.stack([th0 - h, th0, th0 + h], axis=1).ravel()
    plan = compile_plan(linkage_sym.load_scene(d))
    res = plan.run({"A": q}, {"A": np.full(len(q), w)}, {"A": np.full(len(q), al)})
    assert (res.status == "ok").all()
    for name in ("link_BC", "lever", "rocker_DE", "rocker_FG"):
        lk = res.links[name]
        th = lk.rotation.reshape(-1, 3)
        xy = np.asarray(lk.origin).reshape(-1, 3, 2)
        dth = (th[:, 2] - th[:, 0]) / (2 * h)  # d/dq
        d2th = (th[:, 2] - 2 * th[:, 1] + th[:, 0]) / h**2
        om = np.asarray(lk.omega).reshape(-1, 3)[:, 1]
        alpha = np.asarray(lk.alpha).reshape(-1, 3)[:, 1]
        # chain rule along the sweep: dtheta/dt = theta' w, d2theta/dt2 = theta'' w^2 + theta' al
        scale_w, scale_a = np.max(np.abs(om)), np.max(np.abs(alpha))
        assert np.max(np.abs(om - dth * w)) <= 1e-7 * scale_w, name
        assert np.max(np.abs(alpha - (d2th * w * w + dth * al))) <= 1e-5 * scale_a, name
        dxy = (xy[:, 2] - xy[:, 0]) / (2 * h)
        v = np.asarray(lk.origin_velocity).reshape(-1, 3, 2)[:, 1]
        assert np.max(np.abs(v - dxy * w)) <= 1e-7 * np.max(np.abs(v)), name


def test_indicator_lies_between_r_over_n_and_r():
    rng = np.random.default_rng(3)
    for n in (2, 4, 9):
        mats = []
        for c in np.logspace(0, 15, 31):
            Q1, _ = np.linalg.qr(rng.normal(size=(n, n)))
            Q2, _ = np.linalg.qr(rng.normal(size=(n, n)))
            s = np.logspace(0, -math.log10(c), n) * rng.uniform(0.1, 10)
            mats.append(Q1 @ np.diag(s) @ Q2)
        J = np.array(mats)
        sv = np.linalg.svd(J, compute_uv=False)
        r = sv[:, -1] / sv[:, 0]
        got = continuation.indicator(J)
        # the inverse's rounding (about n eps kappa relative) allowed for
        slack = 1e-12 * (1.0 / r)
        assert np.all(got <= r * (1 + slack)), n
        assert np.all(got >= r / n * (1 - slack)), n
        # the Frobenius definition itself, from the singular values
        want = 1.0 / np.sqrt(np.sum(sv**2, axis=1) * np.sum(sv**-2.0, axis=1))
        good = r > 1e-8
        assert np.allclose(got[good], want[good], rtol=1e-7, atol=0), n
    singular = np.ones((2, 3, 3))
    assert np.all(continuation.indicator(singular) == 0.0)
    odd = np.array([np.eye(3), np.full((3, 3), np.nan), 2 * np.eye(3)])
    got = continuation.indicator(odd)
    assert got[0] == pytest.approx(1 / 3) and np.isnan(got[1]) and got[2] == pytest.approx(1 / 3)
