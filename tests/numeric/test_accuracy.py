"""The accuracy estimate of every ok step (``Analysis.accuracy``, ``"accuracy"`` in the JSON).

Each estimate is checked against the error measured at that step against a 50-digit
reference, in the scales of ``accuracy_checks.measured`` (positions over the mechanism's
size and rotations in radians; rates over the step's largest speed or acceleration;
forces over the step's largest reaction or effort):

* **bound**: measured <= estimate, on every ok step of every shipped example (their own
  sweeps, 361 steps; reference: the arbitrary-precision run at 50 digits, which
  ``test_precision`` holds to the closed forms), of four-bars 0.1 to 1e-10 degrees from a
  dead centre with inertia, gravity and forces (condition numbers to 7e6), the
  change-point four-bar and a four-bar a rounding-level miss inside its limit (reference:
  ``mp_reference``, the format's own equations solved in mpmath, sharing no code with the
  solvers), and hypothesis-random crank-rockers, slider-cranks and class-III triads with
  masses (``mp_reference``); for the numeric solver (dyad and global forces), the
  compiled symbolic runtime and the arbitrary-precision run at 20 digits;
* **not too pessimistic**: estimate <= 1e4 x measured on well-conditioned steps
  (condition number at most 100), a measured error below one ulp counting as one ulp: a
  rounded float64 cannot be closer than half an ulp, and the scale it is measured in (the
  step's largest speed, reaction...) is rounded too, so below one ulp which steps come
  out exactly rounded is luck (the printing mechanism's force estimate at condition 80 is
  1.1e4 half-ulps: it passed with half an ulp only while no such step rounded exactly).
"""

from __future__ import annotations

import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402
from tests.support.accuracy_checks import measured  # noqa: E402
from tests.support.mp_reference import Reference  # noqa: E402
from tests.numeric.test_newton_groups import _triad_from  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.codegen.compile import compile_mechanism  # noqa: E402
from linkage_sym.codegen.precision import run_precise  # noqa: E402
from linkage_sym.errors import SceneError  # noqa: E402
from linkage_sym.examples import example_names, load_example  # noqa: E402
from tests.support.example_sets import symbolic_examples  # noqa: E402
from tests.support.marks import slow_cases  # noqa: E402
from linkage_sym.numeric.results import accuracy  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402

EPS = float(np.finfo(float).eps)
PESSIMISM = 1e4
WELL_CONDITIONED = 100.0
SETTINGS = dict(max_examples=12, derandomize=True, deadline=None, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


class Tally:
    """Worst ratios seen, for the message and the printout."""

    def __init__(self):
        self.bound = {}  # field -> (measured / estimate, where)
        self.pess = {}  # field -> (estimate / measured, where)

    def check(self, scene, res, i, rec, where, K=None):
        m = measured(scene, res, i, rec)
        for name, err in m.items():
            if err is None:
                continue
            est = float(res.accuracy[name][i])
            assert np.isfinite(est), (where, i, name)
            r = err / est
            if r > self.bound.get(name, (0.0,))[0]:
                self.bound[name] = (r, f"{where} step {i}")
            assert err <= est, (f"{where} step {i} {name}: measured {err:.3e} > estimate "
                                f"{est:.3e} (condition {K})")
            if K is not None and K <= WELL_CONDITIONED:
                p = est / max(err, EPS)  # one ulp: see the module docstring
                if p > self.pess.get(name, (0.0,))[0]:
                    self.pess[name] = (p, f"{where} step {i}")
                assert p <= PESSIMISM, (f"{where} step {i} {name}: estimate {est:.3e} is "
                                        f"{p:.3g} x the measured {err:.3e} (condition {K:.3g})")

    def __str__(self):
        b = ", ".join(f"{k} {v[0]:.2f} ({v[1]})" for k, v in self.bound.items())
        p = ", ".join(f"{k} {v[0]:.3g} ({v[1]})" for k, v in self.pess.items())
        return f"worst measured/estimate: {b}\nworst estimate/measured (K <= 100): {p}"


def _exact_step(scene, i):
    """Step ``i``'s driver values (mpf) from the scene's numbers, the steps an
    arbitrary-precision run solves: ``start + i (stop - start) / (steps - 1)``, in degrees
    converted with pi for an R driver read from a file."""
    out = {}
    for d in scene.drivers:
        deg = d.start_deg is not None
        a, b = (mp.mpf(d.start_deg), mp.mpf(d.stop_deg)) if deg else (mp.mpf(d.start), mp.mpf(d.stop))
        v = a + (b - a) * i / (d.steps - 1) if d.steps > 1 else a
        out[d.joint] = v * mp.pi / 180 if deg else v
    return out


def _check_mp(scene, res, where, tally, steps=None, exact_steps=False):
    """Every ok step of ``res`` against ``mp_reference`` (condition from the reference), at
    ``res``'s float64 driver values, or (``exact_steps``) at the scene's exact steps."""
    R = Reference(scene)
    n = 0
    for i in range(res.n_steps) if steps is None else steps:
        if res.status[i] != "ok":
            continue
        with mp.workdps(R.digits + 10):
            rec = R.solve(res, i, _exact_step(scene, i) if exact_steps else None)
        assert rec is not None, f"{where} step {i}: the reference's Newton did not converge"
        tally.check(scene, res, i, rec, where, rec["cond"])
        n += 1
    return n


def _with_steps(scene, steps):
    return dataclasses.replace(scene, drivers=tuple(
        dataclasses.replace(d, steps=steps) for d in scene.drivers))


@pytest.mark.slow
@pytest.mark.parametrize("name", symbolic_examples())  # the mpmath reference is symbolic
def test_bounds_every_step_of_the_shipped_examples(name):
    scene = load_example(name)
    res = linkage_sym.analyze(scene)
    precise = run_precise(scene, 50)
    tally = Tally()
    K = compile_plan(scene).run(exact_condition=True).condition  # which steps are well conditioned
    with mp.workdps(50):
        for i in range(res.n_steps):
            if res.status[i] == "ok":
                tally.check(scene, res, i, precise.steps[i], name, float(K[i]))
    assert np.all(np.isnan(res.accuracy["position"][res.status != "ok"]))
    print(f"{name}: {tally}")


def _toggle_scene(gap_deg, steps=6):
    """A triple rocker whose last step is ``gap_deg`` before its limit, with a coupler mass,
    inertia and gravity, and all four outputs."""
    lengths = (2.0, 3.0, 2.5, 4.0)
    with mp.workdps(30):
        lim = float(mp.degrees(ref.fourbar_limits_mp(*lengths)[0]))
    d, _ = scenes.fourbar(*lengths, start_deg=lim - 10 - gap_deg, stop_deg=lim - gap_deg,
                          steps=steps, speed=10.0, acceleration=3.0, coupler_com=(1.0, 0.3),
                          name=f"toggle {gap_deg}")
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    d["effects"] = {"inertia": True, "gravity": [0.0, -9.81]}
    return load_scene(d)


@pytest.mark.parametrize("gap_deg", slow_cases([1e-1, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10],
                                                {1e-1, 1e-4, 1e-6, 1e-8, 1e-10}, key=float))
def test_bounds_near_a_dead_centre(gap_deg):
    """Condition numbers from 22 to 7e6; the velocity error at 1e-10 deg is ~20 %, and the
    estimate says so: every method's estimate bounds it."""
    scene = _toggle_scene(gap_deg)
    tally = Tally()
    plan = compile_plan(scene)
    for label, res in (("dyad", plan.run()), ("global", plan.run(method="global")),
                       ("symbolic", compile_mechanism(scene).run())):
        _check_mp(scene, res, f"{label} gap {gap_deg}", tally)
    if gap_deg <= 1e-8:
        assert tally.bound["velocity"][0] > 0.01  # the last step's rates really lose digits
    print(tally)


@pytest.mark.slow
def test_bounds_change_point_and_limit_within_rounding():
    tally = Tally()
    scene = load_scene(scenes.change_point_fourbar("accuracy change point", 10.0, 3.0))
    res = linkage_sym.analyze(scene)
    assert res.status[18] == "singular" and np.isnan(res.accuracy["velocity"][18])
    assert _check_mp(scene, res, "change point", tally) == 36
    # step 60 sits at the limit to rounding (condition ~1e8): in exact arithmetic its
    # position is a double root or none, so there is nothing to measure against; the
    # estimate says its rates carry no digit, its neighbours are measured
    lengths = (1.0, math.sqrt(3.0) - 0.8, 0.8, 2.0)
    d, _ = scenes.fourbar(*lengths, start_deg=0, stop_deg=120, steps=121, speed=10.0,
                          acceleration=3.0, assembly_deg=10.0)
    scene = load_scene(d)
    res = linkage_sym.analyze(scene)
    assert res.status[60] == "ok" and res.condition[60] > 1e6
    assert res.accuracy["velocity"][60] > 1e-2
    _check_mp(scene, res, "near a limit within rounding", tally, steps=[0, 30, 55, 58, 59])
    print(tally)


def test_precision_runs_carry_their_own_estimate():
    """At 20 digits near a dead centre (condition 7e5) the estimate is 10^-20 K^2-sized
    plus the rounding to float64, and bounds the error against the 50-digit reference
    at 20 digits before rounding (checked on the unrounded values)."""
    scene = _toggle_scene(1e-8)
    p20 = run_precise(scene, 20)
    p50 = run_precise(scene, 50)
    res = p20.analysis
    K = accuracy.condition_of(linkage_sym.analyze(scene, method="symbolic").accuracy)
    with mp.workdps(50):
        for i in range(res.n_steps):
            a, b = p20.steps[i], p50.steps[i]
            for n in a["links"]:
                err_w = abs(a["links"][n]["omega"] - b["links"][n]["omega"])
                V = max(abs(b["links"][m]["omega"]) for m in b["links"])
                assert float(err_w / V) <= res.accuracy["velocity"][i]
            est = res.accuracy["velocity"][i]
            assert est <= EPS + accuracy.C_VELOCITY * 1e-20 * K[i] ** 2 * 1.0001
    tally = Tally()
    _check_mp(scene, res, "precision 20", tally, exact_steps=True)  # the rounded result too


def test_json_carries_the_estimate_on_ok_steps_only():
    scene = load_scene(scenes.change_point_fourbar("accuracy json", 10.0, 0.0))
    res = linkage_sym.analyze(scene)
    steps = res.to_dict()["steps"]
    assert "accuracy" not in steps[18]
    assert set(steps[0]["accuracy"]) == {"position", "velocity", "acceleration"}
    assert all(0 < v < 1e-10 for v in steps[0]["accuracy"].values())
    res.to_json()


def test_calibration_is_kept_for_the_own_sweep():
    """The indicator-to-condition ratio is calibrated once per plan, on its own sweep, and
    used by every run: the scene's sweep, the same sweep given explicitly, and a part of it
    give the same estimates."""
    plan = compile_plan(load_example("watt_sixbar"))
    a = plan.run()
    G = plan._calibration.G
    assert np.isfinite(G) and G > 1
    q, qd, qdd = plan.sweep()
    b = plan.run(q, qd, qdd)
    c = plan.run(*({k: v[100:150] for k, v in d.items()} for d in (q, qd, qdd)))
    assert plan._calibration.G == G
    np.testing.assert_array_equal(a.accuracy["forces"], b.accuracy["forces"])
    np.testing.assert_array_equal(a.accuracy["forces"][100:150], c.accuracy["forces"])


# -- random mechanisms ---------------------------------------------------------------------------

TALLY = Tally()


def _crank_rocker(l2, l3, l4, f):
    l1max = min(l4 - abs(l2 - l3), l2 + l3 - l4)
    return None if l1max <= 0.05 else f * l1max


def _forces(d, mass_links=()):
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    d["effects"] = {"inertia": True, "gravity": [0.0, -9.81]}
    return d


@pytest.mark.slow
@settings(**SETTINGS)
@given(l2=st.floats(1.0, 4.0), l3=st.floats(1.0, 4.0), l4=st.floats(1.0, 4.0),
       f=st.floats(0.1, 0.99), sg=st.sampled_from([1, -1]), start=st.floats(-180, 180),
       rot=st.floats(-180, 180), sc=st.sampled_from([1e-3, 1.0, 1e3]),
       com=st.tuples(st.floats(0.1, 0.9), st.floats(-0.5, 0.5)))
def test_bounds_random_crank_rockers(l2, l3, l4, f, sg, start, rot, sc, com):
    """Any Grashof crank-rocker (up to 0.99 of the longest crank: transmission angles near
    0), anywhere in the plane, at three scales, with a coupler mass."""
    l1 = _crank_rocker(l2, l3, l4, f)
    if l1 is None:
        return
    try:
        d, _ = scenes.fourbar(l1 * sc, l2 * sc, l3 * sc, l4 * sc, start_deg=start,
                              stop_deg=start + 360, steps=7, speed=10.0, acceleration=2.0,
                              sigma=sg, rotate_deg=rot, origin=(0.3 * sc, -0.7 * sc),
                              coupler_com=(com[0] * l2 * sc, com[1] * l2 * sc))
        scene = load_scene(_forces(d))
    except (SceneError, ValueError):
        return
    res = linkage_sym.analyze(scene)
    _check_mp(scene, res, "random crank-rocker", TALLY)


@pytest.mark.slow
@settings(**SETTINGS)
@given(l1=st.floats(0.5, 2.0), r=st.floats(1.1, 5.0), ef=st.floats(-0.95, 0.95),
       sg=st.sampled_from([1, -1]), start=st.floats(-180, 180), rot=st.floats(-180, 180),
       sc=st.sampled_from([1e-3, 1.0, 1e3]))
def test_bounds_random_slider_cranks(l1, r, ef, sg, start, rot, sc):
    l2 = r * l1
    e = ef * (l2 - l1)
    d, _ = scenes.slider_crank(l1 * sc, l2 * sc, e * sc, start_deg=start, stop_deg=start + 360,
                               steps=7, speed=10.0, acceleration=2.0, sigma=sg, rotate_deg=rot,
                               origin=(-1.1 * sc, 0.4 * sc))
    for link in d["links"]:  # masses at the links' first joints' midpoints
        link.update(mass=0.3, inertia=1e-3 * sc * sc, com=[0.0, 0.0])
    at = {j["name"]: j["at"] for j in d["joints"]}
    d["links"][0]["com"] = [(at["A"][0] + at["B"][0]) / 2, (at["A"][1] + at["B"][1]) / 2]
    d["links"][1]["com"] = [(at["B"][0] + at["C"][0]) / 2, (at["B"][1] + at["C"][1]) / 2]
    d["links"][2]["com"] = list(at["C"])
    try:
        scene = load_scene(_forces(d))
    except SceneError:
        return
    res = linkage_sym.analyze(scene)
    _check_mp(scene, res, "random slider-crank", TALLY)


@pytest.mark.slow
@settings(**{**SETTINGS, "max_examples": 6})
@given(j=st.tuples(*[st.floats(-0.03, 0.03, allow_nan=False)] * 12))
def test_bounds_random_class_three_triads(j):
    """Class-III triads (Newton positions, superposition forces) with masses."""
    try:
        scene = load_scene(_triad_from(j))
    except SceneError:
        return
    scene = _with_steps(scene, 5)
    for res in (linkage_sym.analyze(scene), linkage_sym.analyze(scene, method="symbolic")):
        _check_mp(scene, res, f"random triad ({res.forces.method})", TALLY)


def test_print_random_tally():
    print(TALLY)


def test_analyze_prints_the_worst_steps_accuracy(tmp_path, capsys):
    """The summary's accuracy line gives each field's largest estimate over the sweep (the
    step it is at), the same whether the sweep is written whole or streamed to stdout."""
    from linkage_sym.cli import main

    path = tmp_path / "s.json"
    scene_dict = scenes.change_point_fourbar("cli accuracy", 10.0, 3.0)
    path.write_text(__import__("json").dumps(scene_dict))
    res = linkage_sym.analyze(load_scene(scene_dict))
    assert main(["analyze", str(path)]) == 0
    out = capsys.readouterr().out
    (line,) = [ln for ln in out.splitlines() if ln.startswith("accuracy (estimated relative error")]
    for name in ("position", "velocity", "acceleration"):
        v = res.accuracy[name]
        i = int(np.nanargmax(v))
        assert f"{name} {v[i]:.2g} (step {i})" in line
    digits = int(-math.log10(np.nanmax(res.accuracy["acceleration"])))
    assert line.endswith(f"at least {digits} significant digits everywhere")
    assert main(["analyze", str(path), "-o", "-"]) == 0
    captured = capsys.readouterr()
    assert line in captured.err and "accuracy" in captured.out  # the JSON's steps carry it
