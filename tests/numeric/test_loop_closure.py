"""Newton groups of R and P joints in loop-closure coordinates (:mod:`linkage_sym.numeric.kinematics.loop_closure`).

The class-III triad is solved in its four links' angles with four loop rows
(the pose formulation, :class:`~linkage_sym.numeric.kinematics.newton.NewtonSolver`,
has twelve of each), the printing mechanism's triad (Dang and Zhang's
example) in its four angles and its slide.  Checked against what shares no
code with it:

* **the Jacobian** (``i E_k W[k, r]`` of the linear form) against central
  differences of the rows themselves (step ``1e-6``: truncation ``~1e-12``,
  rounding ``~1e-10``; ``1e-8`` of the Jacobian's scale);
* **the positions and rates** against the pose formulation (the group solved
  in poses, the constraint rows of :mod:`~linkage_sym.numeric.kinematics.constraints`),
  also for driven groups (the hydraulic boom's actuator, random knees):
  the same status at every step and every value within ``1e-10`` of its
  family's scale (positions: the mechanism's size), on the shipped class-III
  six-bar and printing mechanisms and on random triads and printing
  mechanisms (joints moved, guide turned) over a full turn, with limits and gaps; every
  ``ok`` step closes and keeps the assembly mode by the tests' own joint
  equations and finite-difference Jacobian (:mod:`reference_kinematics`);
* the rates against **finite differences of the positions** (Richardson's
  rule on central differences over 0.01 and 0.02 deg: velocities ``1e-7``,
  accelerations ``1e-5`` of their scale);
* **the indicator** (``1 / (|J|_F |J^-1|_F)``) against the SVD: between
  ``r / n`` and ``r`` for ``r = sigma_min / sigma_max``, on matrices
  conditioned from 1 to 1e15, ``0`` for singular ones and NaN for non-finite.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402
from tests.numeric.test_batched_continuation import _knee_from, _load, _triad_from, assert_same  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.examples import example_names, example_path  # noqa: E402
from linkage_sym.numeric import continuation  # noqa: E402
from linkage_sym.numeric.kinematics import loop_closure  # noqa: E402
from linkage_sym.numeric.kinematics.loop_closure import LoopClosureSolver  # noqa: E402
from linkage_sym.numeric.kinematics.newton import NewtonSolver  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.numeric.kinematics.state import LinkState  # noqa: E402

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


def test_every_newton_group_takes_the_loop_closure():
    plan = compile_plan(linkage_sym.load_example("sixbar_class3"))
    sv = next(sv for sv in plan.solvers if isinstance(sv, LoopClosureSolver))
    assert sv.nvar == 4 and len(sv.loops) == 2  # 4 angles, 2 loops: 4 rows
    plan = compile_plan(linkage_sym.load_example("printing_mechanism"))
    sv = next(sv for sv in plan.solvers if isinstance(sv, LoopClosureSolver))
    assert sv.nvar == 5 and len(sv.loops) == 2  # 4 angles and a slide; 2 loops, 1 angle row
    plan = compile_plan(linkage_sym.load_example("hydraulic_boom"))
    sv = next(sv for sv in plan.solvers if isinstance(sv, LoopClosureSolver))
    assert sv.nvar == 4 and len(sv.lin_driver) == 1  # 3 angles and the driven slide
    # gear groups of several links: their mesh rows and no loop
    plan = compile_plan(linkage_sym.load_example("gear_linkage"))
    sv = next(sv for sv in plan.solvers if isinstance(sv, LoopClosureSolver))
    assert sv.nvar == 2 and not sv.loops and sv.T.shape[1] == 2  # two mesh rows
    # every shipped Newton group takes it; the pose formulation stays for any other row
    for name in example_names():
        plan = compile_plan(linkage_sym.load_example(name))
        for sv in plan.solvers:
            assert not isinstance(sv, NewtonSolver) or isinstance(sv, LoopClosureSolver), name


def _triad_with_slide(axis_deg, steps=181):
    """The triad with its joint D a slide of rocker_DE along the lever (``axis_deg``): a
    guide that turns with the group (its slide's terms in the angle columns and the
    Coriolis term of the accelerations)."""
    d = _triad_from((0.0,) * 12, steps=steps)
    for joint in d["joints"]:
        if joint["name"] == "D":
            joint["type"], joint["axis_deg"] = "P", axis_deg
    return d


def _printing_from(j, steps=181, guide="ground"):
    """The printing mechanism (Dang and Zhang's example: a triad with a slider on a fixed
    guide) with its triad's joints moved by ``j`` and its guide turned by ``j[-1]`` rad;
    ``guide="crank"`` puts the slide on the crank instead (a known guide that turns)."""
    d = json.loads(example_path("printing_mechanism").read_text())
    for joint in d["joints"]:
        if joint["name"] == "F_guide":
            joint["links"] = [guide, "slider"]
    moved = {"C": j[0:2], "D": j[2:4], "E": j[4:6], "F": j[6:8]}
    for joint in d["joints"]:
        if joint["name"] in moved:
            joint["at"] = [joint["at"][0] + moved[joint["name"]][0],
                           joint["at"][1] + moved[joint["name"]][1]]
        if joint["name"] == "F_guide":
            joint["axis_deg"] = joint["axis_deg"] + math.degrees(j[8])
    d["drivers"][0]["steps"] = steps
    return d


@pytest.mark.parametrize("jitter", [None, (0.02, -0.01, 0.0, 0.015, -0.02, 0.01,
                                           0.01, 0.0, -0.015, 0.02, 0.0, -0.01), "printing",
                                     "printing turned", "slide on the lever",
                                     pytest.param("guide on the crank", marks=pytest.mark.slow),
                                     "hydraulic boom", pytest.param("knee", marks=pytest.mark.slow),
                                     "gear_linkage", "planetary_train"])
def test_jacobian_against_central_differences(jitter):
    if jitter is None:
        scene = linkage_sym.load_example("sixbar_class3")
    elif jitter == "printing":
        scene = linkage_sym.load_example("printing_mechanism")
    elif jitter == "printing turned":
        scene = linkage_sym.load_scene(_printing_from((0.02, 0.01, -0.01, 0.02, 0.0, 0.01,
                                                       0.01, -0.02, 0.3)))
    elif jitter == "slide on the lever":
        scene = linkage_sym.load_scene(_triad_with_slide(60.0))
    elif jitter == "guide on the crank":
        scene = linkage_sym.load_scene(_printing_from((0.0,) * 8 + (0.3,), guide="crank"))
    elif jitter == "hydraulic boom":
        scene = linkage_sym.load_example("hydraulic_boom")
    elif jitter == "knee":
        scene = linkage_sym.load_scene(_knee_from((0.02, -0.01, 0.03, 0.0, -0.02, 0.01)))
    elif jitter in ("gear_linkage", "planetary_train"):
        scene = linkage_sym.load_example(jitter)
    else:
        scene = linkage_sym.load_scene(_triad_from(jitter))
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


@pytest.mark.slow
def test_the_shipped_class3_sixbar_agrees_with_the_pose_formulation():
    a, _ = _against_poses(linkage_sym.load_example("sixbar_class3"), "sixbar_class3")
    assert (a.status == "ok").all()


@pytest.mark.slow
@settings(**SETTINGS)
@given(j=wide_jitter)
def test_random_triads_agree_with_the_pose_formulation(j):
    """Random triads over a full turn (181 steps): continuous sweeps, limits, gaps."""
    scene = _load(_triad_from(j, steps=181))
    if scene is None:
        return
    _against_poses(scene, "random triad")


@pytest.mark.slow
def test_the_printing_mechanism_agrees_with_the_pose_formulation():
    for name in ("printing_mechanism", "printing_mechanism_stroke"):
        a, _ = _against_poses(linkage_sym.load_example(name), name)
        assert (a.status == "ok").all()


@pytest.mark.slow
@settings(**SETTINGS)
@given(j=st.tuples(*[st.floats(-0.06, 0.06, allow_nan=False)] * 8,
                   st.floats(-0.5, 0.5, allow_nan=False)))
def test_random_printing_mechanisms_agree_with_the_pose_formulation(j):
    """The printing mechanism's triad moved and its slider's guide turned at random, over a
    full turn, the guide on the ground and on the crank: slides, limits, gaps."""
    for guide in ("ground", "crank"):
        scene = _load(_printing_from(j, guide=guide))
        if scene is not None:
            _against_poses(scene, f"random printing mechanism, guide on the {guide}")


@pytest.mark.parametrize("axis_deg", [pytest.param(0.0, marks=pytest.mark.slow), 60.0,
                                      pytest.param(120.0, marks=pytest.mark.slow),
                                      pytest.param(150.0, marks=pytest.mark.slow)])
def test_a_triad_sliding_on_its_lever_agrees_with_the_pose_formulation(axis_deg):
    """The guide turns with the group; at 0, 120 and 150 deg parts of the turn cannot be
    assembled (limits, gaps)."""
    _against_poses(linkage_sym.load_scene(_triad_with_slide(axis_deg, steps=361)),
                   f"triad sliding on its lever, {axis_deg} deg")


@pytest.mark.parametrize("name", ["gear_linkage", "planetary_train"])
def test_gear_groups_agree_with_the_pose_formulation(name):
    """Gear groups of several links: their mesh rows (linear in the angles), no loop."""
    scene = linkage_sym.load_example(name)
    a = linkage_sym.analyze(scene)
    b = _pose_plan(scene).run()
    assert_same(b, a, name, scene.characteristic_length(), words=False)
    assert (a.status == "ok").all()


def test_the_hydraulic_boom_agrees_with_the_pose_formulation():
    """A driven slide inside the group (the actuator): its driver row ``s - q``."""
    a, _ = _against_poses(linkage_sym.load_example("hydraulic_boom"), "hydraulic boom")
    assert (a.status == "ok").all()


@pytest.mark.slow
@settings(**{**SETTINGS, "max_examples": 4})
@given(j=st.tuples(*[st.floats(-0.12, 0.12, allow_nan=False)] * 6), long=st.booleans())
def test_random_knees_agree_with_the_pose_formulation(j, long):
    """Knee linkages driven at the knee (a driver row on two of the group's angles) over
    180 deg or two turns (6 deg steps; the pose formulation's re-entry searches make finer
    sweeps slow here, test_batched_continuation walks them at 1 deg): limits,
    unassemblable stretches, re-entries."""
    kw = dict(start_deg=-180, stop_deg=540, steps=121) if long else {}
    scene = _load(_knee_from(j, **kw))
    if scene is not None:
        _against_poses(scene, "random knee")


@pytest.mark.slow
def test_a_triad_past_a_limit_agrees_with_the_pose_formulation():
    scene = linkage_sym.load_scene(scenes.triad_jump())
    a, b = _against_poses(scene, "triad jump")
    assert any("passes a limit" in w for w in a.warnings)


@pytest.mark.parametrize("which", ["triad", "printing", "slide on the lever",
                                   pytest.param("guide on the crank", marks=pytest.mark.slow),
                                   "hydraulic boom", pytest.param("knee", marks=pytest.mark.slow),
                                   "planetary_train"])
def test_rates_against_finite_differences_of_the_positions(which):
    """Velocities and accelerations of every link against finite differences of the
    solved rotations and origins (the driver at constant speed plus an acceleration, the
    chain rule along the sweep): central differences over two steps combined by
    Richardson's rule, so the truncation is ``O(h^4)`` (a motion near a limit has a
    third derivative large enough to put a plain central difference 4e-6 off) and the
    rounding ``eps/h^2`` about 1e-8 for the second differences (the slide's steps:
    ``1e-4`` of the mechanism's size)."""
    triad = ("link_BC", "lever", "rocker_DE", "rocker_FG")
    driver, h, w, al = "A", math.radians(0.01), 10.0, 1.0
    if which in ("triad", "slide on the lever"):
        d = _triad_from((0.0,) * 12) if which == "triad" else _triad_with_slide(60.0)
        links, q0 = triad, np.radians(np.arange(5.0, 355.0, 25.0))
    elif which == "hydraulic boom":
        d = json.loads(example_path("hydraulic_boom").read_text())
        links, driver, h, w, al = ("boom", "cylinder", "rod"), "P", 1e-4, 0.05, 0.02
        q0 = np.linspace(-0.19, 0.29, 14)
    elif which == "planetary_train":
        d = json.loads(example_path("planetary_train").read_text())
        links, driver = ("arm", "planet"), "O_sun"
        q0 = np.radians(np.arange(5.0, 355.0, 25.0))
    elif which == "knee":
        d = _knee_from((0.02, -0.01, 0.03, 0.0, -0.02, 0.01))
        links, driver = ("thigh", "shin", "rocker"), "K"
        q0 = np.radians(np.arange(-95.0, 5.0, 7.5))  # an assemblable stretch
    else:
        d = _printing_from((0.0,) * 8 + (0.3,), guide="ground" if which == "printing" else "crank")
        links = ("coupler", "lever", "rocker", "slider")
        q0 = np.radians(np.arange(305.0, 655.0, 12.5))
    q = (q0[:, None] + h * np.arange(-2, 3)[None, :]).ravel()
    plan = compile_plan(linkage_sym.load_scene(d))
    res = plan.run({driver: q}, {driver: np.full(len(q), w)}, {driver: np.full(len(q), al)})
    ok = (res.status == "ok").reshape(-1, 5).all(axis=1)  # stencils solved whole
    assert ok.sum() >= 8, res.status

    def d1(f):  # d/dq, Richardson from steps h and 2 h
        return (4 * (f[:, 3] - f[:, 1]) / (2 * h) - (f[:, 4] - f[:, 0]) / (4 * h)) / 3

    def d2(f):  # d2/dq2, the same
        return (4 * (f[:, 3] - 2 * f[:, 2] + f[:, 1]) / h**2
                - (f[:, 4] - 2 * f[:, 2] + f[:, 0]) / (4 * h**2)) / 3

    for name in links:
        lk = res.links[name]
        th = lk.rotation.reshape(-1, 5)[ok]
        xy = np.asarray(lk.origin).reshape(-1, 5, 2)[ok]
        om = np.asarray(lk.omega).reshape(-1, 5)[ok, 2]
        alpha = np.asarray(lk.alpha).reshape(-1, 5)[ok, 2]
        v = np.asarray(lk.origin_velocity).reshape(-1, 5, 2)[ok, 2]
        a = np.asarray(lk.origin_acceleration).reshape(-1, 5, 2)[ok, 2]
        # chain rule along the sweep: dtheta/dt = theta' w, d2theta/dt2 = theta'' w^2 + theta' al
        scale_w, scale_a = max(np.max(np.abs(om)), 1.0), max(np.max(np.abs(alpha)), 1.0)
        assert np.max(np.abs(om - d1(th) * w)) <= 1e-7 * scale_w, name
        assert np.max(np.abs(alpha - (d2(th) * w * w + d1(th) * al))) <= 1e-5 * scale_a, name
        dxy, d2xy = d1(xy), d2(xy)
        assert np.max(np.abs(v - dxy * w)) <= 1e-7 * np.max(np.abs(v)), name
        assert np.max(np.abs(a - (d2xy * w * w + dxy * al))) <= 1e-5 * np.max(np.abs(a)), name


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
