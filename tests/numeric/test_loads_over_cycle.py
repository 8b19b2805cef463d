"""Loads that vary over the cycle (an extension of the format): ``table``, ``active``.

Checked against what shares no code with the solvers:

* the work over a cycle: at constant crank speed the kinetic and potential
  energies come back after a cycle, so the driving effort's work over one
  equals minus the work of the tabulated load, integrated here from the
  table (written out segment by segment) and the slider-crank's closed-form
  piston position;
* a load outside its ``active`` range contributes nothing: those steps equal
  the same scene without the load, the steps inside equal the scene with a
  constant load;
* the three methods (dyad, global, symbolic) and the mpmath evaluation agree;
  the float64 factor (:func:`load_factor`) against the mpmath one.
"""

from __future__ import annotations

import copy
import math

import mpmath as mp
import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.codegen.mp_numbers import factor_mp as _factor_mp
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict, load_example
from linkage_sym.model import Load, LoadTable
from linkage_sym.numeric.forces.loads import load_factor
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.scene import dump_scene, load_scene

STEP_DEG = 0.25
"""The work check's sweep: 2881 steps over the engine's 720 degree cycle."""


def _engine_sweep(scene, step_deg=STEP_DEG):
    th = np.radians(np.arange(0.0, 720.0 + step_deg / 2, step_deg))
    d = scene.drivers[0]
    return {"A": th}, {"A": np.full(th.shape, d.speed)}, {"A": np.zeros(th.shape)}


# -- the engine: work over a cycle ---------------------------------------------------------------


def _gas_work(d: dict) -> float:
    """Work of the gas force on the piston over the cycle, from the scene's numbers.

    ``x(θ) = r cos θ + sqrt(l² − (r sin θ)²)`` (the slider-crank with its guide
    through the crank pivot), the force ``−F0 s(θ)`` along x with ``s`` linear
    between the tabulated angles: Gauss–Legendre on each table interval
    (exact for the linear factor times a smooth ``x'``, to rounding).
    """
    A = np.array(d["joints"][0]["at"])
    B = np.array(d["joints"][1]["at"])
    C = np.array(d["joints"][2]["at"])
    r, l = np.hypot(*(B - A)), np.hypot(*(C - B))
    load = d["loads"][0]
    F0 = load["force"][0]
    q = np.radians(load["table"]["q_deg"])
    s = np.array(load["table"]["scale"])
    xg, wg = np.polynomial.legendre.leggauss(30)
    total = 0.0
    for k in range(len(q) - 1):
        a, b = q[k], q[k + 1]
        th = 0.5 * (b - a) * xg + 0.5 * (a + b)
        sk = s[k] + (s[k + 1] - s[k]) * (th - a) / (b - a)
        dx = -r * np.sin(th) - r * r * np.sin(th) * np.cos(th) / np.sqrt(l * l - (r * np.sin(th)) ** 2)
        total += 0.5 * (b - a) * np.sum(wg * F0 * sk * dx)
    return total


def _simpson_by_segment(y, per_segment):
    """Simpson's rule on each run of ``per_segment`` intervals (the table's intervals),
    so no rule straddles a kink of the piecewise-linear factor."""
    h = math.radians(STEP_DEG)
    total = 0.0
    for a in range(0, len(y) - 1, per_segment):
        seg = y[a : a + per_segment + 1]
        total += h / 3 * (seg[0] + seg[-1] + 4 * seg[1:-1:2].sum() + 2 * seg[2:-1:2].sum())
    return total


@pytest.mark.parametrize("method", ["dyad", "global", "symbolic"])
def test_engine_driving_work_over_a_cycle_equals_minus_the_gas_work(method):
    d = example_dict("engine_four_stroke")
    scene = load_example("engine_four_stroke")
    q, qd, qdd = _engine_sweep(scene)
    if method == "symbolic":
        res = compile_mechanism(scene).run(q, qd, qdd)
    else:
        res = compile_plan(scene).run(q, qd, qdd, method=method)
    assert res.ok.all()
    tau = res.forces.driving["A"]
    per = round(15.0 / STEP_DEG)  # the table's angles are 15 degrees apart
    assert np.allclose(np.diff(d["loads"][0]["table"]["q_deg"]), 15.0)
    w_drive = _simpson_by_segment(tau, per)
    w_gas = _gas_work(d)
    assert w_gas > 100.0  # a cycle that does work: about 0.4 kJ
    # Simpson's rule with h = 0.25 deg on each smooth piece (between table angles): its error,
    # ~h^4 times tau's fourth derivative, is about 1e-11 of the work here; 1e-9 leaves room
    assert abs(w_drive + w_gas) <= 1e-9 * abs(w_gas), (w_drive, w_gas)


def test_engine_methods_agree():
    scene = load_example("engine_four_stroke")
    a = compile_plan(scene).run()
    g = compile_plan(scene).run(method="global")
    s = compile_mechanism(scene).run()
    peak = np.max(np.abs(a.forces.driving["A"]))
    for other in (g, s):
        np.testing.assert_allclose(other.forces.driving["A"], a.forces.driving["A"], rtol=0, atol=1e-9 * peak)
        for j in a.forces.reactions:
            np.testing.assert_allclose(other.forces.reactions[j], a.forces.reactions[j], rtol=0,
                                       atol=1e-9 * np.max(np.abs(a.forces.reactions[j])))


def test_engine_factor_follows_the_table_at_the_tabulated_angles():
    """At the tabulated angles the load is the tabulated fraction of the full force: the
    piston's reaction along the guide minus its inertia is that force (checked through the
    difference of two runs, with and without the load, which shares only the kinematics)."""
    d = example_dict("engine_four_stroke")
    scene = load_scene(d)
    bare = copy.deepcopy(d)
    bare["loads"] = []
    tab = d["loads"][0]["table"]
    q = {"A": np.radians(np.array(tab["q_deg"][:-1]))}
    qd = {"A": np.full(q["A"].shape, scene.drivers[0].speed)}
    qdd = {"A": np.zeros(q["A"].shape)}
    with_load = compile_plan(scene).run(q, qd, qdd)
    without = compile_plan(load_scene(bare)).run(q, qd, qdd)
    # the load's share of the crank torque is linear in the load: factor x (torque of the full force)
    full = copy.deepcopy(d)
    del full["loads"][0]["table"], full["loads"][0]["period_deg"]
    constant = compile_plan(load_scene(full)).run(q, qd, qdd)
    share = with_load.forces.driving["A"] - without.forces.driving["A"]
    unit = constant.forces.driving["A"] - without.forces.driving["A"]
    scale = np.array(tab["scale"][:-1])
    np.testing.assert_allclose(share, scale * unit, rtol=0, atol=1e-9 * np.max(np.abs(unit)))


# -- the printing mechanism: a force over the printing stroke only --------------------------------


def test_printing_force_acts_only_over_its_range():
    d = example_dict("printing_mechanism_stroke")
    scene = load_scene(d)
    lo, hi = d["loads"][0]["active_deg"]
    bare = copy.deepcopy(d)
    bare["loads"] = []
    const = copy.deepcopy(d)
    del const["loads"][0]["active_deg"]
    res = compile_plan(scene).run()
    res0 = compile_plan(load_scene(bare)).run()
    res1 = compile_plan(load_scene(const)).run()
    deg = np.degrees(res.drivers["A"]["q"])
    # ends included (the format's rule): a step on an end up to rounding (1e-9°) is inside; the
    # steps at 330° and 630° are ends, which rounding had put outside (the code too, before)
    inside = np.mod(deg - lo + 1e-9, 360.0) <= hi - lo + 2e-9
    assert inside.any() and (~inside).any()
    assert np.isclose(deg, hi).any() and np.isclose(deg, lo + 360.0).any()
    assert res.ok.all()
    tau, tau0, tau1 = (r.forces.driving["A"] for r in (res, res0, res1))
    scale = np.max(np.abs(tau1))
    np.testing.assert_allclose(tau[~inside], tau0[~inside], rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(tau[inside], tau1[inside], rtol=0, atol=1e-12 * scale)
    assert np.max(np.abs(tau1[~inside] - tau0[~inside])) > 1e-3 * scale  # the force matters there
    sym = compile_mechanism(scene).run()
    np.testing.assert_allclose(sym.forces.driving["A"], tau, rtol=0, atol=1e-9 * scale)


# -- the factor: float64 against mpmath, and the P-driver table ----------------------------------


def test_factor_float64_against_mpmath():
    rng = np.random.default_rng(7)
    for period in (2 * math.pi, 4 * math.pi):
        q = np.sort(rng.uniform(0.0, period * 0.95, 9))
        q = q - q[0] + rng.uniform(-10, 10)
        load = Load("l", torque=1.0, driver="A", period=period,
                    table=LoadTable(tuple(q), tuple(rng.uniform(-2, 2, 9))),
                    active=(q[2], q[2] + 0.7 * period))
        x = rng.uniform(-30, 30, 200)
        got = load_factor(load, {"A": x})
        mp.mp.dps = 40
        want = np.array([float(_factor_mp(load, mp.mpf(float(v)))) for v in x])
        np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-13)


def _boom_with_table():
    d = example_dict("hydraulic_boom")
    drv = d["drivers"][0]
    lo, hi = sorted((drv["start"], drv["stop"]))
    d["loads"][0]["table"] = {"q": [lo, 0.5 * (lo + hi), hi], "scale": [1.0, 0.2, 1.5]}
    return d


def test_p_driver_table_methods_agree_and_out_of_table_is_refused():
    d = _boom_with_table()
    scene = load_scene(d)
    assert scene.drivers[0].kind == "P"
    a = compile_plan(scene).run()
    s = compile_mechanism(scene).run()
    j = scene.drivers[0].joint
    peak = np.max(np.abs(a.forces.driving[j]))
    np.testing.assert_allclose(s.forces.driving[j], a.forces.driving[j], rtol=0, atol=1e-9 * peak)
    q, qd, qdd = compile_plan(scene).sweep()
    lo, hi = np.min(q[j]), np.max(q[j])
    beyond = {j: hi + np.array([0.0, 0.01, 0.02]) * (hi - lo)}  # assemblable, past the table
    three = lambda d: {k: v[:3] for k, v in d.items()}  # noqa: E731
    with pytest.raises(ValueError, match="outside its table"):
        compile_plan(scene).run(beyond, three(qd), three(qdd))


def test_precision_run_scales_loads_as_float64():
    d = example_dict("engine_four_stroke")
    d["drivers"][0]["steps"] = 13  # every 60 degrees: mpmath is slow
    scene = load_scene(d)
    precise = linkage_sym.analyze(scene, precision=30)
    double = compile_plan(scene).run()
    peak = np.max(np.abs(double.forces.driving["A"]))
    np.testing.assert_allclose(precise.forces.driving["A"], double.forces.driving["A"], rtol=0,
                               atol=1e-11 * peak)


# -- the format: dumping and every refusal ------------------------------------------------------


def _same_load(a: Load, b: Load):
    """Equal, angles to the rounding of a radians -> degrees -> radians round trip."""
    assert (a.link, a.force, a.at, a.torque, a.driver) == (b.link, b.force, b.at, b.torque, b.driver)
    for x, y in ((a.period, b.period), (a.active, b.active)):
        assert (x is None) == (y is None)
        if x is not None:
            np.testing.assert_allclose(x, y, rtol=1e-15)
    assert (a.table is None) == (b.table is None)
    if a.table is not None:
        np.testing.assert_allclose(a.table.q, b.table.q, rtol=1e-15, atol=1e-15)
        assert a.table.scale == b.table.scale


def test_dump_and_load_keep_the_schedule():
    scenes = [load_example(n) for n in ("engine_four_stroke", "printing_mechanism_stroke")]
    scenes.append(load_scene(_boom_with_table()))
    for scene in scenes:
        again = load_scene(dump_scene(scene))
        assert any(ld.driver for ld in scene.loads)
        for a, b in zip(again.loads, scene.loads, strict=True):
            _same_load(a, b)


def _problems(d) -> list[str]:
    with pytest.raises(SceneError) as err:
        load_scene(d)
    return err.value.problems


@pytest.mark.parametrize("change, field, words", [
    (lambda ld: ld.update(table={"q": [0, 90], "scale": [1, 2]}), "loads[0].table.q", "'q_deg'"),
    (lambda ld: ld.update(table={"q_deg": [0, 90, 90], "scale": [1, 2, 3]}), "loads[0].table.q_deg",
     "strictly increasing"),
    (lambda ld: ld.update(table={"q_deg": [0, 90], "scale": [1, 2, 3]}), "loads[0].table.scale",
     "as many numbers"),
    (lambda ld: ld.update(table={"q_deg": [0, 400], "scale": [1, 2]}), "loads[0].table.q_deg",
     "more than the period"),
    (lambda ld: ld.update(table={"q_deg": [0, 180, 360], "scale": [1, 2, 3]}), "loads[0].table.scale",
     "one angle"),
    (lambda ld: ld.update(table={"q_deg": [0], "scale": [1]}), "loads[0].table.q_deg", "at least 2"),
    (lambda ld: ld.update(table={"q_deg": [0, "x"], "scale": [1, 2]}), "loads[0].table.q_deg[1]",
     "finite number"),
    (lambda ld: ld.update(active_deg=[90, 30]), "loads[0].active_deg", "to >= from"),
    (lambda ld: ld.update(active=[0.1, 0.2]), "loads[0].active", "'active_deg'"),
    (lambda ld: ld.update(active_deg=[0, 400]), "loads[0].active_deg", "more than the period"),
    (lambda ld: ld.update(driver="B"), "loads[0].driver", "with a 'table' or an 'active'"),
    (lambda ld: ld.update(active_deg=[0, 90], driver="B"), "loads[0].driver", "not a driven joint"),
    (lambda ld: ld.update(active_deg=[0, 90], period_deg=0), "loads[0].period_deg", "positive"),
])
def test_bad_schedules_are_refused_naming_the_field(change, field, words):
    d = example_dict("crank_rocker")
    change(d["loads"][0])
    problems = _problems(d)
    assert any(p.startswith(field + ":") and words in p for p in problems), problems


def test_p_driver_schedule_refusals():
    d = _boom_with_table()
    d["loads"][0]["table"] = {"q": [0.0, 1e-3], "scale": [1, 2]}
    assert any(p.startswith("loads[0].table.q:") and "cover the sweep" in p for p in _problems(d))
    d = _boom_with_table()
    d["loads"][0]["period_deg"] = 360
    assert any(p.startswith("loads[0].period_deg:") for p in _problems(d))
    d = _boom_with_table()
    d["loads"][0]["table"] = {"q_deg": [0, 1], "scale": [1, 2]}
    assert any(p.startswith("loads[0].table.q_deg:") and "'q'" in p for p in _problems(d))


def test_several_drivers_need_the_driver_named():
    d = example_dict("fivebar")
    assert len(d["drivers"]) == 2
    d.setdefault("loads", []).append({"link": d["links"][0]["name"], "torque": 1.0,
                                      "active_deg": [0, 90]})
    i = len(d["loads"]) - 1
    assert any(p.startswith(f"loads[{i}].driver:") and "several drivers" in p for p in _problems(d))
    d["loads"][i]["driver"] = d["drivers"][1]["joint"]
    scene = load_scene(d)
    assert scene.loads[i].driver == d["drivers"][1]["joint"]


def test_an_active_range_includes_both_ends_whatever_the_rounding():
    """A range across 0° written past the period, [340°, 560°], over a 361-step turn: the steps
    at 340°..360° and 0°..200° act, 222 of them, counted here from the step numbers (the
    step at exactly 200° was left out by rounding: 221)."""
    from linkage_sym.numeric.forces.loads import load_factor

    ld = Load("ram", force=(1.0, 0.0), driver="A", period=2 * math.pi,
              active=(math.radians(340.0), math.radians(560.0)))
    q = np.linspace(0.0, 2 * math.pi, 361)
    f = load_factor(ld, {"A": q})
    k = np.arange(361)
    assert np.array_equal(f > 0, (k <= 200) | (k >= 340))
