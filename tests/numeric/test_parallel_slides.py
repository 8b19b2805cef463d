"""Dyads of two slides (PRP, RPP) whose slides become parallel: the joint at infinity.

* a step where the slides are parallel is ``unassemblable`` (never a step whose infinite
  positions reach the singularity test's SVD: a traceback before);
* a passage of the joint through infinity between two steps is a warning of the run at the
  first step past it, whatever the number of steps, instead of a silent jump from
  ``x = +0.858`` to ``x = -0.858``;
* the steps on both sides stay ``ok``: they are exact solutions of the constraints,
  checked against the intersection of the two lines written in the test
  (:mod:`tests.support.parallel_slides`);
* an RPP dyad's slides turn together (the angle between them never changes): it is never
  parallel along a sweep, or parallel everywhere (then every step is unassemblable).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.numeric.kinematics.loci import line_line
from linkage_sym.numeric.plan import compile_plan
from tests.support.parallel_slides import H, guide_slider, joint_c, pinned_rod

METHODS = ("dyad", "global")
POS_TOL = 1e-12
"""Relative tolerance of ``C`` against the lines' intersection (positions up to ~1 m)."""


def crossing_warning(before, after, step):
    return ("dyad PRP (rod, block): the slides of joints A_slide and C_guide become parallel "
            f"between A = {before}° and A = {after}°: joint C passes through infinity there; "
            f"at {step} it is on the far side of its slides")


def check_positions(res):
    q = res.drivers["A"]["q"]
    ok = res.status == "ok"
    for k in np.flatnonzero(ok):
        x, y = joint_c(q[k])
        got = res.joints["C"].position[k]
        assert abs(got[0] - x) <= POS_TOL * abs(x) and abs(got[1] - y) <= POS_TOL * H, k
    return ok


@pytest.mark.parametrize("method", METHODS)
def test_a_step_at_the_parallel_position_is_unassemblable(method):
    res = compile_plan(linkage_sym.load_scene(guide_slider(11))).run(method=method)
    q = np.degrees(res.drivers["A"]["q"])
    assert abs(q[5]) < 1e-12
    assert list(res.status) == ["ok"] * 5 + ["unassemblable"] + ["ok"] * 5
    assert res.messages[5] == ("dyad PRP (rod, block): the slides of joints A_slide and "
                               "C_guide are parallel")
    check_positions(res)
    # the joint is on the other side of the rod's slide past the parallel step
    assert res.joints["C"].position[4, 0] > 0 > res.joints["C"].position[6, 0]
    assert res.warnings == [crossing_warning("1.5", "-1.5", "step 6 (reached from step 5)")]
    json.dumps(res.to_dict(), allow_nan=False)  # a valid result file


@pytest.mark.parametrize("method", METHODS)
def test_a_passage_through_infinity_between_steps_is_a_warning(method):
    res = compile_plan(linkage_sym.load_scene(guide_slider(10))).run(method=method)
    assert set(res.status) == {"ok"}
    check_positions(res)
    x = res.joints["C"].position[:, 0]
    # the reference: the lines' intersection changes side between steps 4 and 5 only
    ref = np.array([joint_c(v)[0] for v in res.drivers["A"]["q"]])
    assert np.array_equal(np.sign(x), np.sign(ref)) and ref[4] > 0 > ref[5]
    assert res.warnings == [crossing_warning("1.66667", "-1.66667",
                                             "step 5 (reached from step 4)")]


@pytest.mark.parametrize("steps", [5, 9, 10, 11, 12, 41])
def test_the_side_of_infinity_does_not_depend_on_the_step_count(steps):
    """Whatever the steps, one warning, at the first step past 0 degrees."""
    res = linkage_sym.analyze(linkage_sym.load_scene(guide_slider(steps)))
    q = res.drivers["A"]["q"]
    past = int(np.flatnonzero(q < -1e-12)[0])
    assert len(res.warnings) == 1
    # the first point solved past it: the step itself when the steps are at most 2 degrees
    # apart (no path point between them), else a point of the path before it
    where = f"step {past}" if 60.0 / (steps - 1) <= 2.0 else (
        f"step {past} (reached from step {past - 1})")
    assert f"; at {where} it is on the far side" in res.warnings[0]
    assert np.all(res.status[np.abs(q) > 1e-12] == "ok")
    check_positions(res)


def test_a_prp_dyad_that_never_becomes_parallel_has_no_warning():
    res = linkage_sym.analyze(linkage_sym.load_scene(guide_slider(9, 30.0, 5.0)))
    assert set(res.status) == {"ok"} and res.warnings == []
    check_positions(res)


def test_parallel_lines_within_rounding_have_no_intersection():
    # exactly parallel, a rounding error off parallel, and anti-parallel: no point
    for u2 in ((1.0, 0.0), (1.0, 1e-17), (-1.0, 2e-16)):
        Yx, Yy, s = line_line(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, *u2)
        assert math.isnan(float(s)) and math.isnan(float(Yx)) and math.isnan(float(Yy))
    # a small angle far above rounding: the intersection, signed as cross(u1, u2)
    a = 1e-6
    Yx, Yy, s = line_line(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, math.cos(a), -math.sin(a))
    assert float(s) == pytest.approx(-math.sin(a), rel=1e-15)
    assert float(Yx) == pytest.approx(1.0 / math.tan(a), rel=1e-9) and float(Yy) == 0.0


def test_a_non_finite_jacobian_is_singular_not_a_traceback():
    scene = linkage_sym.load_scene(guide_slider(5, 30.0, 10.0))
    plan = compile_plan(scene)
    q, qd, qdd = plan.sweep()
    S, status = plan.link_states(q, qd, qdd)
    rod = S["rod"]
    th = np.array(rod.th, dtype=float)
    th[2] = np.nan  # a joint at infinity leaves no number in the Jacobian's rows
    rod.set_pose(th, rod.dx, rod.dy)
    cond = plan.condition_numbers(S, np.arange(5))
    assert np.isinf(cond[2]) and np.all(np.isfinite(cond[[0, 1, 3, 4]]))


def rpp_reference(q, axis_deg):
    """Joint B_rod of :func:`pinned_rod` at guide angle ``q``: the guide's line through the
    origin meets the rod's slide, which turns with the guide about E."""
    q0, E = math.radians(20.0), (0.3, 0.0)
    b = (0.2 * math.cos(q0), 0.2 * math.sin(q0))
    d = q - q0
    c, s = math.cos(d), math.sin(d)
    P = (E[0] + c * (b[0] - E[0]) - s * (b[1] - E[1]), E[1] + s * (b[0] - E[0]) + c * (b[1] - E[1]))
    w = math.radians(axis_deg) + d
    u, v = (math.cos(q), math.sin(q)), (math.cos(w), math.sin(w))
    # P + t v on the line t' u through the origin: cross(u, P + t v) = 0
    t = -(u[0] * P[1] - u[1] * P[0]) / (u[0] * v[1] - u[1] * v[0])
    return P[0] + t * v[0], P[1] + t * v[1]


@pytest.mark.parametrize("method", METHODS)
def test_an_rpp_dyad_is_never_parallel_along_a_sweep(method):
    res = compile_plan(linkage_sym.load_scene(pinned_rod(110.0))).run(method=method)
    assert set(res.status) == {"ok"} and res.warnings == []
    for k, q in enumerate(res.drivers["A"]["q"]):
        ref = rpp_reference(q, 110.0)
        assert np.max(np.abs(res.joints["B_rod"].position[k] - ref)) <= POS_TOL * 0.5


@pytest.mark.parametrize("method", METHODS)
def test_an_rpp_dyad_with_parallel_slides_is_unassemblable_everywhere(method):
    res = compile_plan(linkage_sym.load_scene(pinned_rod(20.0))).run(method=method)
    assert set(res.status) == {"unassemblable"}
    assert set(res.messages) == {"dyad RPP (rod, block): the slides of joints B_rod and "
                                 "B_guide are parallel"}


def test_the_command_line_reports_the_parallel_step(tmp_path, capsys):
    path = tmp_path / "gs11.json"
    path.write_text(json.dumps(guide_slider(11)))
    out = tmp_path / "out.json"
    assert main(["analyze", str(path), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "11 steps: 10 ok, 1 unassemblable" in text
    assert "warning: dyad PRP (rod, block): the slides of joints A_slide and C_guide" in text
    steps = json.loads(out.read_text())["steps"]
    assert steps[5]["status"] == "unassemblable"
