"""Exact extremes (``analyze --extremes``, ``linkage_sym.numeric.extremes``).

Checked against the closed forms of ``reference_kinematics`` (``fourbar_mp``,
``slider_crank_mp``, ``fourbar_limits_mp``) at 40 digits, whose rate roots this test
finds itself with ``mpmath.findroot`` (a bracketing solver, ``anderson``):

* a crank-rocker loaded only by a torque ``T`` on its rocker (no masses): the rocker's
  and the coupler's rotation extremes are where ``omega_3`` / ``omega_2`` vanish; C's
  coordinates where its velocity components vanish; the crank torque is ``-T dth3/dth1``
  (virtual work), extreme where ``alpha_3`` (at ``omega_1 = 1``, ``alpha_1 = 0``)
  vanishes; the coupler is a two-force member, so every reaction has the magnitude
  ``|T| / (l3 |sin(th3 - th2)|)``, extreme where ``d sin(th3 - th2) / dth1 = 0``;
* the offset slider-crank's dead centres: the slide's extremes where the slider's
  velocity vanishes;
* a triple rocker swept past its limit: the assembly limit at the crank angle where
  ``|BD| = l2 + l3``.

Tolerances: values 1e-10 (radians; metres over the size; newtons and newton-metres
relative to the largest value); locations 1e-8 rad (a location is only determined to
about ``sqrt(eps)`` relative by the flat value around it; Brent stops at 1e-11 steps).
And the sampled extremes of ``N`` steps approach the exact one as ``1/N^2``.
"""

from __future__ import annotations

import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

from linkage_sym.numeric.extremes import brent, find_extremes, summary_lines  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402

LENGTHS = (1.0, 3.2, 2.6, 3.0)  # crank-rocker
T_ROCKER = -0.5
START = 7.3  # deg: no extreme falls on a sample


def _fourbar_scene(steps, start=START, torque=True):
    d, _ = scenes.fourbar(*LENGTHS, start_deg=start, stop_deg=start + 360, steps=steps,
                          speed=10.0, assembly_deg=START, name="extremes four-bar")
    if torque:
        d["loads"] = [{"link": "rocker", "torque": T_ROCKER}]
        d["effects"] = {"inertia": False, "loads": True}
        d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    return d


class _Fourbar:
    """The scene's four-bar in mpmath (lengths from its binary64 joints)."""

    def __init__(self, d):
        J = {j["name"]: (mp.mpf(j["at"][0]), mp.mpf(j["at"][1])) for j in d["joints"]}
        B, C, D = J["B"], J["C"], J["D"]
        self.l = (mp.hypot(*B), mp.hypot(C[0] - B[0], C[1] - B[1]),
                  mp.hypot(C[0] - D[0], C[1] - D[1]), D[0])
        self.th2_0 = mp.atan2(C[1] - B[1], C[0] - B[0])
        self.th3_0 = mp.atan2(C[1] - D[1], C[0] - D[0])

    def at(self, th1):
        return ref.fourbar_mp(*self.l, th1, 1, 0, 1)

    def quantities(self):
        """name -> (value(th1), rate(th1)) of the quantities checked."""
        l1, l2, l3, l4 = self.l
        T = mp.mpf(T_ROCKER)
        return {
            # rocker and coupler oscillate: their rotations stay within half a turn
            ("links", "rocker", "rotation"): (lambda t: _wrap(self.at(t)["th3"] - self.th3_0),
                                             lambda t: self.at(t)["w3"]),
            ("links", "coupler", "rotation"): (lambda t: _wrap(self.at(t)["th2"] - self.th2_0),
                                              lambda t: self.at(t)["w2"]),
            ("joints", "C", "x"): (lambda t: self.at(t)["Cx"], lambda t: self.at(t)["vCx"]),
            ("joints", "C", "y"): (lambda t: self.at(t)["Cy"], lambda t: self.at(t)["vCy"]),
            ("driving", "A", "effort"): (lambda t: -T * self.at(t)["w3"],
                                        lambda t: -T * self.at(t)["a3"]),
            ("reactions", "C", "magnitude"): (
                lambda t: abs(T) / (l3 * abs(mp.sin(self.at(t)["th3"] - self.at(t)["th2"]))),
                lambda t: (self.at(t)["w3"] - self.at(t)["w2"])
                * mp.cos(self.at(t)["th3"] - self.at(t)["th2"])),
        }


def _wrap(a):
    return mp.atan2(mp.sin(a), mp.cos(a))


def _exact_extremes(value, rate, th, with_all=False):
    """Max and min of ``value`` over the sampled crank angles ``th`` (mpf list): the
    samples and every rate root between two samples (findroot on the closed form);
    with ``with_all`` also every candidate ``(value, angle)``."""
    vals = [(value(t), t) for t in th]
    rates = [rate(t) for t in th]
    for a, b, ra, rb in zip(th, th[1:], rates, rates[1:]):
        if (ra < 0) != (rb < 0):
            root = mp.findroot(rate, (a, b), solver="anderson")
            vals.append((value(root), root))
    hi, lo = max(vals, key=lambda v: v[0]), min(vals, key=lambda v: v[0])
    return (hi, lo, vals) if with_all else (hi, lo)


@pytest.mark.slow
def test_fourbar_extremes_match_the_closed_form_rate_roots():
    d = _fourbar_scene(73)
    scene = load_scene(d)
    plan = compile_plan(scene)
    res = plan.run()
    ext = find_extremes(scene, plan, res)
    with mp.workdps(40):
        fb = _Fourbar(d)
        th = [mp.mpf(float(v)) for v in res.drivers["A"]["q"]]
        # the closed-form effort is the solver's (sign convention included), sampled
        for i in (0, 20, 50):
            assert abs(float(-mp.mpf(T_ROCKER) * fb.at(th[i])["w3"]) - res.forces.driving["A"][i]) \
                <= 1e-12 * abs(res.forces.driving["A"][i])
        L = scene.characteristic_length()
        for key, (value, rate) in fb.quantities().items():
            hi, lo, cands = _exact_extremes(value, rate, th, with_all=True)
            got = ext.values[key]
            scale = {"links": 1.0, "joints": L}.get(key[0], float(abs(hi[0])))
            for kind, (v, t) in (("max", hi), ("min", lo)):
                e = got[kind]
                unwrap = 0.0
                if key[2] == "rotation":
                    unwrap = 2 * mp.pi * mp.nint((e.value - v) / (2 * mp.pi))
                assert abs(e.value - float(v + unwrap)) <= 1e-10 * scale, (key, kind, e.value, v)
                # where: one of the closed form's candidates with the extreme value (C's y
                # has its minimum twice, where the rocker passes -90 degrees each way)
                assert any(abs(e.drivers["A"] - float(tc)) <= 1e-8
                           and abs(float(vc - v)) <= 1e-10 * scale for vc, tc in cands), (key, kind)
                assert (e.value >= e.sampled) if kind == "max" else (e.value <= e.sampled)
    # every reaction of the two-force coupler has the same magnitude: one check covers them
    mags = [ext.values["reactions", j, "magnitude"]["max"].value for j in "ABCD"]
    assert max(mags) - min(mags) <= 1e-10 * max(mags)
    lines = summary_lines(scene, ext)
    assert any(line.startswith("limit position of the dyad RRR") for line in lines)
    assert any("driving effort at A max" in line for line in lines)


def test_slider_dead_centres_match_the_closed_form():
    """The slide's extremes (dead centres) where the slider's velocity vanishes."""
    d, _ = scenes.slider_crank(0.05, 0.2, 0.02, start_deg=3.1, stop_deg=363.1, steps=37,
                               speed=50.0, name="dead centres")
    scene = load_scene(d)
    plan = compile_plan(scene)
    ext = find_extremes(scene, plan, plan.run())
    (group,) = ext.limits
    (item,) = [it for it in group["limits"] if it["coordinate"] == "slide of S"]
    with mp.workdps(40):
        J = {j["name"]: (mp.mpf(j["at"][0]), mp.mpf(j["at"][1])) for j in d["joints"]}
        B, C = J["B"], J["C"]
        l1, l2, e = mp.hypot(*B), mp.hypot(C[0] - B[0], C[1] - B[1]), C[1]
        x0 = C[0]

        def x(t):
            return ref.slider_crank_mp(l1, l2, e, t, 1)["x"]

        def v(t):
            return ref.slider_crank_mp(l1, l2, e, t, 1)["v"]

        th = [mp.mpf(float(a)) for a in np.radians(np.linspace(3.1, 363.1, 37))]
        hi, lo = _exact_extremes(x, v, th)
        for kind, (val, t) in (("max", hi), ("min", lo)):
            got = item[kind]
            assert got["located"] == "rate root"
            assert abs(got["value"] - float(val - x0)) <= 1e-10 * 0.25
            assert abs(got["drivers"]["A"] - float(t)) <= 1e-8
        # outer dead centre: crank and rod in line, x = sqrt((l1 + l2)^2 - e^2)
        assert abs(float(hi[0]) - float(mp.sqrt((l1 + l2) ** 2 - e ** 2))) <= 1e-30


def test_assembly_limit_of_a_triple_rocker():
    """Swept past its limit, the sweep leaves the assemblable range at the closed form's
    crank angle (|BD| = l2 + l3) to 1e-9 rad."""
    lengths = (2.0, 3.0, 2.5, 4.0)
    d, _ = scenes.fourbar(*lengths, start_deg=100.0, stop_deg=160.0, steps=13, speed=10.0)
    scene = load_scene(d)
    plan = compile_plan(scene)
    ext = find_extremes(scene, plan, plan.run())
    (limit,) = ext.assembly
    assert limit.get("leaves")
    with mp.workdps(40):
        J = {j["name"]: (mp.mpf(j["at"][0]), mp.mpf(j["at"][1])) for j in d["joints"]}
        B, C, D = J["B"], J["C"], J["D"]
        ls = (mp.hypot(*B), mp.hypot(C[0] - B[0], C[1] - B[1]),
              mp.hypot(C[0] - D[0], C[1] - D[1]), D[0])
        th_lim = ref.fourbar_limits_mp(*ls)[0]
    assert abs(limit["drivers"]["A"] - float(th_lim)) <= 1e-9


@pytest.mark.parametrize("steps", [37, 361, pytest.param(3601, marks=pytest.mark.slow)])
def test_sampled_extremes_converge_as_one_over_n_squared(steps):
    """The largest sample of N steps misses the rocker's exact maximum by at most
    ``|f''| Delta^2 / 8`` (``f''``: the rocker's angular acceleration per crank angle
    squared at the maximum, from the closed form; ``Delta`` the step), and by nearly that
    where the maximum falls midway between two samples.  Over 16 phases of the samples
    (starts shifted by Delta/16) the worst miss is within [(15/16)^2, 1] of that bound
    (0.02 either side for the Delta^3 terms at N = 37).  So a sampled extreme is off by
    O(1/N^2); ``find_extremes`` is exact (1e-10, the other tests)."""
    delta_deg = 360.0 / (steps - 1)
    delta = math.radians(delta_deg)
    misses, exact = [], None
    for k in range(16):
        d = _fourbar_scene(steps, start=START + k * delta_deg / 16, torque=False)
        scene = load_scene(d)
        plan = compile_plan(scene)
        res = plan.run()
        if exact is None:  # the mechanism's maximum does not depend on the sampling
            exact = find_extremes(scene, plan, res).values["links", "rocker", "rotation"]["max"]
        misses.append(exact.value - float(np.max(res.links["rocker"].rotation)))
    with mp.workdps(40):
        fb = _Fourbar(d)
        th_max = mp.mpf(exact.drivers["A"])
        assert abs(fb.at(th_max)["w3"]) <= 1e-9  # the located maximum is a rate root
        bound = float(abs(fb.at(th_max)["a3"])) * delta ** 2 / 8
    assert min(misses) >= -1e-15
    worst = max(misses) / bound
    assert (15 / 16) ** 2 - 0.02 <= worst <= 1.02, (steps, worst)
    print(f"N = {steps}: worst sampled miss {max(misses):.3e} rad = {worst:.4f} x f'' Delta^2/8")


def test_brent_generator_finds_roots_as_scipy():
    from scipy.optimize import brentq

    for f, a, b in ((lambda x: x ** 3 - 2 * x - 5, 2.0, 3.0), (math.cos, 0.0, 3.0),
                    (lambda x: math.exp(x) - 10.0, 0.0, 5.0)):
        gen = brent(a, b, f(a), f(b), 1e-14)
        x = next(gen)
        try:
            while True:
                x = gen.send(f(x))
        except StopIteration as stop:
            root = stop.value
        assert abs(root - brentq(f, a, b, xtol=1e-14)) <= 4e-14


@pytest.mark.slow
def test_class_three_group_extremes_are_stationary():
    """A class-III six-bar (Newton positions, superposition forces): every extreme located
    between samples is at least as extreme as the samples and a local extreme of the
    quantity itself (the plan run at 1e-3 steps either side gives no larger maximum or
    smaller minimum, to 1e-12 of the value's scale)."""
    from linkage_sym.examples import load_example
    from linkage_sym.numeric.extremes import FractionalSweep, quantities

    scene = load_example("sixbar_class3")
    scene = dataclasses.replace(scene, drivers=tuple(
        dataclasses.replace(dr, steps=37) for dr in scene.drivers))
    plan = compile_plan(scene)
    res = plan.run()
    ext = find_extremes(scene, plan, res)
    assert ext.limits and ext.limits[-1]["group"].startswith("triad")
    q, qd, qdd = plan.sweep()
    sw = FractionalSweep(scene, plan, q, qd, qdd, None)
    qs = {(qu.group, qu.name, qu.field): qu for qu in quantities(scene, True)}
    checks = []
    for key, mm in ext.values.items():
        for kind in ("max", "min"):
            e = mm[kind]
            better = (e.value >= e.sampled) if kind == "max" else (e.value <= e.sampled)
            assert better, (key, kind)
            if e.located == "rate root":
                checks.append((key, kind, e))
    ts = sorted({x for _, _, e in checks for x in (e.t - 1e-3, e.t + 1e-3)})
    kin, force = sw.kinematics(np.array(ts)), sw.forces(np.array(ts))
    for key, kind, e in checks:
        qu = qs[key]
        vals = np.asarray(qu.value(kin if qu.kinematic else force), float)
        side = vals[[ts.index(e.t - 1e-3), ts.index(e.t + 1e-3)]]
        scale = 1e-12 * (float(np.nanmax(np.abs(qu.value(res)))) + 1e-300)
        if kind == "max":
            assert np.all(side <= e.value + scale), (key, kind, e.value, side)
        else:
            assert np.all(side >= e.value - scale), (key, kind, e.value, side)
    assert len(checks) >= 20


def test_analyze_extremes_option(tmp_path, capsys):
    """``analyze --extremes`` prints the limit positions and effort extremes and writes the
    extremes into the result (whole JSON and the one streamed to standard output alike)."""
    import json

    from linkage_sym.cli import main

    d, _ = scenes.slider_crank(0.05, 0.2, 0.02, start_deg=3.1, stop_deg=363.1, steps=37,
                               speed=50.0, name="cli extremes")
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    d["effects"] = {"inertia": True, "gravity": [0.0, -9.81]}
    for link in d["links"]:
        link.update(mass=0.5, inertia=1e-3, com=[0.0, 0.0])
    path = tmp_path / "s.json"
    path.write_text(json.dumps(d))
    out = tmp_path / "r.json"
    assert main(["analyze", str(path), "-o", str(out), "--extremes"]) == 0
    text = capsys.readouterr().out
    assert "limit position of the dyad RRP (rod, slider): slide of S max" in text
    assert "driving effort at A max" in text
    result = json.loads(out.read_text())
    scene = load_scene(d)
    plan = compile_plan(scene)
    ext = find_extremes(scene, plan, plan.run()).to_dict()
    assert result["extremes"] == json.loads(json.dumps(ext))
    assert result["extremes"]["slides"]["S"]["slide"]["max"]["located"] == "rate root"
    assert main(["analyze", str(path), "-o", "-", "--extremes"]) == 0
    assert json.loads(capsys.readouterr().out)["extremes"] == result["extremes"]


def test_a_fully_turning_link_has_no_limit_position(tmp_path, capsys):
    """A rotating guide-bar (crank 0.05 > frame 0.02: the guide turns fully): its guide's
    extremes are the sweep's ends, printed as such, not as limit positions; the JSON item says
    ``turns_fully``; the start's rounding noise prints as 0, never -0."""
    import json

    from linkage_sym.cli import main

    scene_path = tmp_path / "gb.json"
    assert main(["new", "guide-bar", "--crank", "0.05", "--ground", "0.02",
                 "-o", str(scene_path)]) == 0
    out = tmp_path / "r.json"
    capsys.readouterr()
    assert main(["analyze", str(scene_path), "--extremes", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "limit position of" not in text and "-0.0" not in text
    assert ("dyad RPR (slider, rocker): rotation of rocker about D turns fully, no limit "
            "position: 0.000000° at A = 0.000000° and 360.000000° at A = 360.000000°, the ends "
            "of the sweep") in text
    (item,) = json.loads(out.read_text())["extremes"]["limits"][0]["limits"]
    assert item["turns_fully"] is True
    # a rocker's item says it does not turn fully
    d, _ = scenes.fourbar(*LENGTHS, start_deg=START, stop_deg=START + 360, steps=37, speed=1.0)
    scene = load_scene(d)
    plan = compile_plan(scene)
    (group,) = find_extremes(scene, plan, plan.run()).limits
    assert group["limits"][0]["turns_fully"] is False


def test_rounding_noise_prints_as_zero():
    """Values within 1e-12 of the characteristic length (lengths, slides), of 1 rad (angles) or
    of the quantity's largest magnitude (efforts) print as 0, never -0; larger ones as they
    are."""
    from linkage_sym.numeric.extremes import Extreme, Extremes

    d, _ = scenes.slider_crank(0.05, 0.2, 0.0, start_deg=0.0, stop_deg=360.0, steps=37,
                               speed=1.0, name="noise")
    scene = load_scene(d)
    L = scene.characteristic_length()

    def e(value, t, a, sampled=None):
        return {"value": value, "step": t, "drivers": {"A": a}, "located": "sample",
                "sampled": value if sampled is None else sampled}

    ext = Extremes()
    ext.n_steps = 37
    ext.limits = [{"group": "dyad RRP", "links": ["rod", "slider"], "limits": [
        {"coordinate": "slide of S", "max": e(-2.77556e-17, 0.0, -1e-17),
         "min": e(-0.1, 18.0, math.pi)},
        {"coordinate": "slide of S", "max": e(0.9e-12 * L, 0.0, 0.9e-12),
         "min": e(-1.1e-12 * L, 18.0, -1.1e-12)}]}]
    ext.values[("driving", "A", "effort")] = {
        "max": Extreme(2.0, 3.0, {"A": 0.5}, "rate root", 1.9),
        "min": Extreme(-1e-13, 9.0, {"A": 1.0}, "rate root", -1e-13)}
    lines = summary_lines(scene, ext)
    assert lines[1].endswith("slide of S max 0 m at A = 0.000000°")
    # above the noise: as it is, but an angle that rounds to 0 at six decimals shows no sign
    assert lines[2].endswith(f"slide of S min {-1.1e-12 * L:.6g} m at A = 0.000000°")
    assert lines[3].endswith("slide of S max 0 m at A = 0.000000°")
    assert lines[5] == "driving effort at A min: 0 N·m at A = 57.295780° (rate root; smallest sample 0)"
    assert not any("-0 " in ln or "-0.000000" in ln for ln in lines)
