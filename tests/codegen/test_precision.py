"""The precision knob (``analyze(scene, precision=DIGITS)``, ``--precision DIGITS``).

The arbitrary-precision run evaluates the derived equations in mpmath.  It is checked
against the closed forms of the four-bar and the offset slider-crank in
``reference_kinematics`` (``fourbar_mp``, ``slider_crank_mp``: eqs. 3-9 to 3-17 of the
kinematics chapter re-derived by hand, evaluated here at 60 digits), with the lengths
computed in mpmath from the scene's binary64 joint coordinates (the scene's numbers *are*
the mechanism), and each step's driver value from the scene's ``start_deg``/``stop_deg``
(``_step_q``: the exact step, not its float64 rounding):

* at 50 digits, positions (link rotations in rad, joint coordinates relative to the
  mechanism's size) and rates (relative to the step's largest |omega|, |v|, |alpha|, |a|)
  agree to ``TOL = 1e-30`` -- also 1e-6 degrees from a dead centre, where the condition
  number is ~1e4 and float64 keeps only 11 to 13 digits;
* the rounded Analysis is the reference rounded: within 2 ulps of each value (4 eps
  relative to the value or to its scale);
* the other fields (statuses, forces against the numeric solver) and the refusals.
"""

from __future__ import annotations

import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.codegen.precision import parse_precision, run_precise  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402

TOL = mp.mpf("1e-30")
EPS = float(np.finfo(float).eps)
L_TRIPLE = (2.0, 3.0, 2.5, 4.0)  # triple rocker: limit (dead centre) at 129.838 deg
W1, A1 = 10.0, 3.0


def _mpt(p):
    return mp.mpf(p[0]), mp.mpf(p[1])


def _step_q(d, i):
    """Step ``i``'s exact driver value (rad, mpf) of the scene dict ``d``'s one R driver:
    ``start + i (stop - start) / (steps - 1)`` degrees, from the binary64 numbers it gives."""
    dr, = d["drivers"]
    a, b, n = mp.mpf(dr["start_deg"]), mp.mpf(dr["stop_deg"]), dr["steps"]
    return (a * (n - 1 - i) + b * i) / (n - 1) * mp.pi / 180


def _near(a, ref_angle):
    """``a`` shifted by whole turns to the value nearest ``ref_angle``."""
    return a + 2 * mp.pi * mp.nint((ref_angle - a) / (2 * mp.pi))


def _fourbar_reference(d, res):
    """Per step: mpf rotations, omegas, alphas of coupler/rocker and C's motion."""
    J = {j["name"]: _mpt(j["at"]) for j in d["joints"]}
    A, B, C, D = J["A"], J["B"], J["C"], J["D"]
    assert A == (0, 0) and D[1] == 0  # canonical frame of reference_kinematics
    l1, l2 = mp.hypot(B[0] - A[0], B[1] - A[1]), mp.hypot(C[0] - B[0], C[1] - B[1])
    l3, l4 = mp.hypot(C[0] - D[0], C[1] - D[1]), D[0]
    th2_0 = mp.atan2(C[1] - B[1], C[0] - B[0])
    th3_0 = mp.atan2(C[1] - D[1], C[0] - D[0])
    sigma = 1 if (B[0] - D[0]) * (C[1] - D[1]) - (B[1] - D[1]) * (C[0] - D[0]) > 0 else -1
    out = []
    for i in range(res.n_steps):
        q = res.drivers["A"]
        r = ref.fourbar_mp(l1, l2, l3, l4, _step_q(d, i), mp.mpf(float(q["qd"][i])),
                           mp.mpf(float(q["qdd"][i])), sigma)
        if r is None:
            out.append(None)
            continue
        out.append({
            "coupler": (r["th2"] - th2_0, r["w2"], r["a2"]),
            "rocker": (r["th3"] - th3_0, r["w3"], r["a3"]),
            "C": ((r["Cx"], r["Cy"]), (r["vCx"], r["vCy"]), (r["aCx"], r["aCy"])),
            "L": max(l1, l2, l3, l4, mp.hypot(C[0] - A[0], C[1] - A[1]),
                     mp.hypot(B[0] - D[0], B[1] - D[1])),
            "det": r["det"],
        })
    return out


def _check_against(pr, reference, links, joint, tol=TOL):
    """Worst relative errors (positions, rates) of the unrounded values; asserts ``tol``."""
    worst = [mp.mpf(0), mp.mpf(0)]
    for i, r in enumerate(reference):
        got = pr.steps[i]
        if r is None:
            assert got is None and pr.analysis.status[i] == "unassemblable", i
            continue
        assert pr.analysis.status[i] == "ok", (i, pr.analysis.messages[i])
        L = r["L"]
        w_scale = max(abs(r[n][1]) for n in links)
        a_scale = max(abs(r[n][2]) for n in links)
        (p, v, a) = r[joint]
        v_scale = max(abs(v[0]), abs(v[1]), w_scale * L)
        acc_scale = max(abs(a[0]), abs(a[1]), a_scale * L)
        for n in links:
            rot, w, al = r[n]
            g = got["links"][n]
            e_pos = abs(g["rotation"] - _near(rot, g["rotation"]))
            e_rate = max(abs(g["omega"] - w) / w_scale, abs(g["alpha"] - al) / a_scale)
            worst = [max(worst[0], e_pos), max(worst[1], e_rate)]
        gj = got["joints"][joint]
        for k in (0, 1):
            worst[0] = max(worst[0], abs(gj["position"][k] - p[k]) / L)
            worst[1] = max(worst[1], abs(gj["velocity"][k] - v[k]) / v_scale,
                           abs(gj["acceleration"][k] - a[k]) / acc_scale)
        assert worst[0] <= tol and worst[1] <= tol, (i, mp.nstr(worst[0], 5), mp.nstr(worst[1], 5))
    return worst


def _double_rate_error(res, reference, links):
    """Worst relative error of float64 omegas against the reference."""
    worst = 0.0
    for i, r in enumerate(reference):
        if r is None or res.status[i] != "ok":
            continue
        scale = max(abs(r[n][1]) for n in links)
        for n in links:
            worst = max(worst, float(abs(mp.mpf(float(res.links[n].omega[i])) - r[n][1]) / scale))
    return worst


@pytest.mark.parametrize("gap_deg", [None, 1e-6])
def test_fourbar_at_50_digits(gap_deg):
    """A crank-rocker over a turn, and a triple rocker whose last step is 1e-6 deg short of its
    limit position (condition number ~1e4): 1e-30 on positions and rates, where float64's
    rates there are off by more than 1e-13 (relative)."""
    if gap_deg is None:
        d, _ = scenes.fourbar(1.0, 3.2, 2.6, 3.0, start_deg=7.3, stop_deg=367.3, steps=25,
                              speed=W1, acceleration=A1, name="crank-rocker 50 digits")
    else:
        with mp.workdps(60):
            lim = float(mp.degrees(ref.fourbar_limits_mp(*L_TRIPLE)[0]))
        d, _ = scenes.fourbar(*L_TRIPLE, start_deg=lim - 20 - gap_deg, stop_deg=lim - gap_deg,
                              steps=21, speed=W1, acceleration=A1, name="near dead centre")
    scene = load_scene(d)
    pr = run_precise(scene, 50)
    with mp.workdps(60):
        reference = _fourbar_reference(d, pr.analysis)
        worst = _check_against(pr, reference, ("coupler", "rocker"), "C")
        if gap_deg is not None:
            assert 1 / abs(reference[-1]["det"]) > 5e3  # really near the dead centre
            double = linkage_sym.analyze(scene)
            assert _double_rate_error(double, reference, ("coupler", "rocker")) > 1e-13
    print(f"gap {gap_deg}: worst position {mp.nstr(worst[0], 3)}, rate {mp.nstr(worst[1], 3)}")


def test_rounded_analysis_is_the_reference_rounded():
    """The float64 Analysis of a 50-digit run is the reference rounded once: each value
    within ``EPS |value|`` (half an ulp is at most EPS/2 |value|; the unrounded values
    are good to 1e-30 of their scale, which adds ``1e-30 * scale``)."""
    d, _ = scenes.fourbar(1.0, 3.2, 2.6, 3.0, start_deg=0, stop_deg=360, steps=13,
                          speed=W1, acceleration=A1, name="rounded")
    scene = load_scene(d)
    res = run_precise(scene, 50).analysis
    with mp.workdps(60):
        reference = _fourbar_reference(d, res)

        def close(got, want, scale):
            return abs(mp.mpf(float(got)) - want) <= EPS * abs(want) + TOL * scale

        for i, r in enumerate(reference):
            for n in ("coupler", "rocker"):
                rot, w, al = r[n]
                lk = res.links[n]
                assert close(lk.rotation[i], _near(rot, lk.rotation[i]), 1), (i, n)
                assert close(lk.omega[i], w, abs(w)) and close(lk.alpha[i], al, abs(al)), (i, n)
            jk = res.joints["C"]
            for k, arr in enumerate((jk.position, jk.velocity, jk.acceleration)):
                for c in (0, 1):
                    want = r["C"][k][c]
                    assert close(arr[i, c], want, r["L"] if k == 0 else abs(want)), (i, k, c)


def _slider_reference(d, res):
    J = {j["name"]: _mpt(j["at"]) for j in d["joints"]}
    A, B, C = J["A"], J["B"], J["C"]
    assert A == (0, 0)
    l1, l2, e = mp.hypot(*B), mp.hypot(C[0] - B[0], C[1] - B[1]), C[1]
    th2_0 = mp.atan2(C[1] - B[1], C[0] - B[0])
    sigma = 1 if mp.cos(th2_0) > 0 else -1
    out = []
    for i in range(res.n_steps):
        q = res.drivers["A"]
        r = ref.slider_crank_mp(l1, l2, e, _step_q(d, i), mp.mpf(float(q["qd"][i])),
                                mp.mpf(float(q["qdd"][i])), sigma)
        if r is None:
            out.append(None)
            continue
        out.append({
            "rod": (r["th2"] - th2_0, r["w2"], r["a2"]),
            "C": ((r["x"], e), (r["v"], mp.mpf(0)), (r["a"], mp.mpf(0))),
            "L": max(l1, l2, mp.hypot(*C)),
            "det": r["det"],
        })
    return out


@pytest.mark.parametrize("near", [False, True])
def test_offset_slider_crank_at_50_digits(near):
    """The offset slider-crank over a turn, and one whose crank is too long for part of the
    turn (l1 = 1, l2 = 0.9, e = 0.3: the rod stands normal to the guide where
    sin th1 = -0.6), swept to 1e-6 deg of that limit: 1e-30 on positions and rates."""
    if not near:
        d, _ = scenes.slider_crank(0.05, 0.2, 0.02, start_deg=3.1, stop_deg=363.1, steps=25,
                                   speed=50.0, acceleration=A1, name="slider 50 digits")
    else:
        with mp.workdps(60):
            lim = float(mp.degrees(mp.asin(mp.mpf(-0.6))))  # -36.87 deg, rod normal to the guide
        d, _ = scenes.slider_crank(1.0, 0.9, 0.3, start_deg=lim + 30, stop_deg=lim + 1e-6,
                                   steps=16, speed=W1, acceleration=A1, name="slider near limit")
    scene = load_scene(d)
    pr = run_precise(scene, 50)
    with mp.workdps(60):
        reference = _slider_reference(d, pr.analysis)
        _check_against(pr, reference, ("rod",), "C")
        if near:
            assert 1 / abs(reference[-1]["det"]) > 5e3
            double = linkage_sym.analyze(scene)
            assert _double_rate_error(double, reference, ("rod",)) > 1e-13


@pytest.mark.slow
def test_statuses_and_forces_as_the_numeric_solver():
    """Shipped examples with forces at 30 digits: statuses as float64's; reactions, efforts
    and frame loads equal the numeric solver's to 1e-12 of each array's largest value (the
    numeric one carries ~1e-15; the tolerance leaves room for its conditioning)."""
    for name in ("crank_rocker", "slider_crank_offset", "sixbar_class3"):
        scene = linkage_sym.load_example(name)
        scene = dataclasses.replace(scene, drivers=tuple(
            dataclasses.replace(dr, steps=19) for dr in scene.drivers))
        got = linkage_sym.analyze(scene, precision=30)
        num = linkage_sym.analyze(scene)
        assert list(got.status) == list(num.status)
        assert got.forces.method == "mpmath"
        pairs = [(got.forces.driving[k], num.forces.driving[k]) for k in num.forces.driving]
        pairs += [(got.forces.reactions[k], num.forces.reactions[k]) for k in num.forces.reactions]
        pairs += [(got.forces.frame_force, num.forces.frame_force),
                  (got.forces.frame_moment, num.forces.frame_moment)]
        for a, b in pairs:
            scale = float(np.nanmax(np.abs(b))) or 1.0
            assert float(np.nanmax(np.abs(a - b))) <= 1e-12 * scale, name
        got.to_json()  # strict JSON


def test_exactly_singular_step_keeps_positions_only():
    """The change-point four-bar's exactly singular step: no rates, positions kept."""
    scene = load_scene(scenes.change_point_fourbar("precise change point", W1, A1))
    res = linkage_sym.analyze(scene, precision=40)
    assert res.status[18] == "singular"
    assert np.isnan(res.links["coupler"].omega[18])
    assert math.dist(res.joints["C"].position[18], (24.0, 0.0)) <= 1e-6 * 24


def test_precision_option_is_parsed_and_refused():
    assert parse_precision("double") is None and parse_precision(None) is None
    assert parse_precision("50") == 50 and parse_precision(30) == 30
    for bad in ("fifty", "3", 5000, True, "1e3"):
        with pytest.raises(ValueError, match="precision"):
            parse_precision(bad)
    scene = linkage_sym.load_example("crank_rocker")
    with pytest.raises(ValueError, match="precision"):
        linkage_sym.analyze(scene, method="global", precision=30)


def test_analyze_precision_option(tmp_path, capsys):
    """``analyze --precision 30`` writes the arbitrary-precision result (the API's, value for
    value) and says its accuracy is float64's rounding; bad values and combinations exit 2
    with the option named, nothing written."""
    import json

    from linkage_sym.cli import main

    d, _ = scenes.fourbar(1.0, 3.2, 2.6, 3.0, start_deg=0, stop_deg=360, steps=13,
                          speed=W1, acceleration=A1, name="cli precision")
    path = tmp_path / "s.json"
    path.write_text(json.dumps(d))
    out = tmp_path / "r.json"
    assert main(["analyze", str(path), "-o", str(out), "--precision", "30"]) == 0
    text = capsys.readouterr().out
    # float64's rounding of the positions: at the last step the crank has turned 2 pi, whose
    # own representation carries eps * 2 pi = 1.4e-15 rad (accuracy.magnitude_floor)
    assert "accuracy (estimated relative error, worst step): position 1.4e-15" in text
    got = json.loads(out.read_text())
    want = json.loads(linkage_sym.analyze(load_scene(d), precision=30).to_json())
    assert got == want
    for bad, name in ((["--precision", "fifty"], "--precision"),
                      (["--precision", "30", "--method", "global"], "--precision 30"),
                      (["--precision", "30", "--disconnection", "0"], "--precision 30")):
        target = tmp_path / "never.json"
        assert main(["analyze", str(path), "-o", str(target), *bad]) == 2
        assert name in capsys.readouterr().err and not target.exists()


# ------------------------------------------------------------------ exact driver values

# An offset slider-crank whose rod stands normal to the guide with the crank at exactly 180
# degrees (a dead centre and the sweep's limit): crank l1 = 1/2 about A = (0, 0), rod
# l2 = 5/4, slider C on y = e = 5/4.  Assembled at 90 degrees, B = (0, 1/2), C = (1, 5/4):
# every length exact in binary64.  At the crank angle q, h = e - l1 sin q and
# s = sqrt(l2^2 - h^2) (C is s ahead of B): s = 0 at 180 degrees, where d(x_C)/dq and the
# rod's d(phi)/dq are infinite, so float64's rounding of the step (float(pi) is 1.2e-16
# short of pi) moves the positions by sqrt(2 l1 l2 1.2e-16) = 1.2e-8.
L1, L2, E_GUIDE = mp.mpf(1) / 2, mp.mpf(5) / 4, mp.mpf(5) / 4
L_BELOW = mp.mpf(5) / 4  # below the mechanism's size |AC| = 1.6: errors over it are larger


def _dead_centre_scene(stop_deg, steps):
    return {
        "name": "slider to its dead centre",
        "links": [{"name": "crank"}, {"name": "rod"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0, 0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [0, 0.5]},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [1, 1.25]},
            {"name": "S", "type": "P", "links": ["ground", "slider"], "at": [1, 1.25],
             "axis_deg": 0},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 90, "stop_deg": stop_deg,
                     "steps": steps, "speed": W1, "acceleration": A1}],
        "outputs": ["kinematics"],
    }


def _dead_centre_reference(q, qd, qdd):
    """Positions and rates of the scene above at crank angle ``q`` (mpf), by its closed form:
    x_C = l1 cos q + s, rod angle phi = atan2(h, s), and their q-derivatives by hand
    (h' = -l1 cos q, s' = -h h'/s, s'' = -(h'^2 + h h'' + s'^2)/s, phi' = (h's - hs')/l2^2,
    phi'' = (h''s - hs'')/l2^2).  Rates are ``None`` at s = 0."""
    h = E_GUIDE - L1 * mp.sin(q)
    s = mp.sqrt(L2**2 - h**2)
    phi0 = mp.atan2(mp.mpf(3) / 4, 1)  # the rod in the assembly configuration
    out = {"x": L1 * mp.cos(q) + s, "rod": mp.atan2(h, s) - phi0, "crank": q - mp.pi / 2,
           "B": (L1 * mp.cos(q), L1 * mp.sin(q))}
    if s == 0:
        return out
    h1, h2 = -L1 * mp.cos(q), L1 * mp.sin(q)
    s1 = -h * h1 / s
    s2 = -(h1**2 + h * h2 + s1**2) / s
    x1, x2 = -L1 * mp.sin(q) + s1, -L1 * mp.cos(q) + s2
    p1, p2 = (h1 * s - h * s1) / L2**2, (h2 * s - h * s2) / L2**2
    out.update(v=x1 * qd, a=x2 * qd**2 + x1 * qdd, omega=p1 * qd, alpha=p2 * qd**2 + p1 * qdd)
    return out


def _dead_centre_errors(res, i, r):
    """Relative errors of step ``i``'s rounded values against ``r``, as the accuracy estimate
    measures them, over smaller scales (so larger errors) than its own: lengths over
    ``L_BELOW`` = 5/4 (the mechanism's size is |AC| = 1.6), speeds over
    max(|v_C|, |omega_rod| L_BELOW) (the estimate's V counts every joint), likewise
    accelerations."""
    L = L_BELOW
    f = mp.mpf
    e_pos = max(abs(f(float(res.joints["C"].position[i, 0])) - r["x"]) / L,
                abs(f(float(res.joints["C"].position[i, 1])) - E_GUIDE) / L,
                abs(f(float(res.joints["B"].position[i, 0])) - r["B"][0]) / L,
                abs(f(float(res.joints["B"].position[i, 1])) - r["B"][1]) / L,
                abs(f(float(res.links["rod"].rotation[i])) - r["rod"]),
                abs(f(float(res.links["crank"].rotation[i])) - r["crank"]))
    if "v" not in r:
        return e_pos, None, None
    V = max(abs(r["v"]), abs(r["omega"]) * L)
    A = max(abs(r["a"]), abs(r["alpha"]) * L)
    e_vel = max(abs(f(float(res.joints["C"].velocity[i, 0])) - r["v"]) / V,
                abs(f(float(res.links["rod"].omega[i])) - r["omega"]) * L / V)
    e_acc = max(abs(f(float(res.joints["C"].acceleration[i, 0])) - r["a"]) / A,
                abs(f(float(res.links["rod"].alpha[i])) - r["alpha"]) * L / A)
    return e_pos, e_vel, e_acc


@pytest.mark.parametrize("stop_deg", [180.0, 180 - 1e-7])
def test_driver_values_are_the_exact_steps_at_a_dead_centre(stop_deg):
    """Each step's driver value is the scene's step, start + i (stop - start)/(steps - 1)
    degrees, in the working precision, not its float64 rounding.  Swept to the dead centre
    at exactly 180 degrees (the float64 run finds that step singular: positions only) and to
    1e-7 degrees short of it (condition number ~6e4, rates ~1e4 times the crank's): every
    rounded value is the reference's rounding, to EPS relative (half an ulp, and the
    unrounded values' 1e-30 of their scale); the old float64 driver was off there by 1e-8
    (positions at 180) and 3e-8 (rates, relative, 1e-7 short).  The accuracy estimate of
    every ok step bounds the error measured."""
    steps = 10
    d = _dead_centre_scene(stop_deg, steps)
    res = run_precise(load_scene(d), 50).analysis
    with mp.workdps(70):
        last = _dead_centre_reference(_step_q(d, steps - 1), mp.mpf(W1), mp.mpf(A1))
        # the test's point: float64's driver at the last step is far from the step's value
        rounded = _dead_centre_reference(mp.mpf(float(res.drivers["A"]["q"][-1])), mp.mpf(W1),
                                         mp.mpf(A1))
        assert abs(rounded["x"] - last["x"]) > (1e-9 if stop_deg == 180 else 1e-13)
        if stop_deg != 180:
            assert abs(rounded["omega"] / last["omega"] - 1) > 1e-9

        def close(got, want, scale=1):
            return abs(mp.mpf(float(got)) - want) <= EPS * abs(want) + TOL * scale

        for i in range(steps):
            r = _dead_centre_reference(_step_q(d, i), mp.mpf(W1), mp.mpf(A1))
            want = "singular" if (stop_deg == 180 and i == steps - 1) else "ok"
            assert res.status[i] == want, (i, res.messages[i])
            assert close(res.joints["C"].position[i, 0], r["x"]), (i, "x")
            assert close(res.links["rod"].rotation[i], r["rod"]), (i, "rod")
            assert close(res.links["crank"].rotation[i], r["crank"]), (i, "crank")
            for k in (0, 1):
                assert close(res.joints["B"].position[i, k], r["B"][k]), (i, "B", k)
            e_pos, e_vel, e_acc = _dead_centre_errors(res, i, r)
            if want != "ok":
                continue
            V = max(abs(r["v"]), abs(r["omega"]) * L_BELOW)
            A = max(abs(r["a"]), abs(r["alpha"]) * L_BELOW)
            assert close(res.joints["C"].velocity[i, 0], r["v"], V), (i, "v")
            assert close(res.joints["C"].acceleration[i, 0], r["a"], A), (i, "a")
            assert close(res.links["rod"].omega[i], r["omega"], V), (i, "omega")
            assert close(res.links["rod"].alpha[i], r["alpha"], A), (i, "alpha")
            acc = res.accuracy
            assert e_pos <= acc["position"][i], (i, e_pos, acc["position"][i])
            assert e_vel <= acc["velocity"][i], (i, e_vel, acc["velocity"][i])
            assert e_acc <= acc["acceleration"][i], (i, e_acc, acc["acceleration"][i])


def test_command_line_chunks_take_the_exact_steps(tmp_path, capsys):
    """``analyze --precision 50`` solves the sweep in chunks of driver values; each is still
    its step's exact value: 1e-7 degrees short of the dead centre, x_C and the rod's omega
    written are the reference's rounding (EPS relative; float64's driver moved omega by 3e-8)."""
    import json

    from linkage_sym.cli import main

    d = _dead_centre_scene(180 - 1e-7, 4)
    path, out = tmp_path / "s.json", tmp_path / "r.json"
    path.write_text(json.dumps(d))
    assert main(["analyze", str(path), "-o", str(out), "--precision", "50"]) == 0
    capsys.readouterr()
    last = json.loads(out.read_text())["steps"][-1]
    with mp.workdps(70):
        r = _dead_centre_reference(_step_q(d, 3), mp.mpf(W1), mp.mpf(A1))
        for got, want in ((last["joints"]["C"]["position"][0], r["x"]),
                          (last["links"]["rod"]["omega"], r["omega"])):
            assert abs(mp.mpf(got) - want) <= EPS * abs(want), (got, want)


def test_given_driver_values_are_exact_floats():
    """Driver values given through the API are taken as the binary64 numbers they are (the
    result is the reference at that number), except values of the scene's own sweep, which
    stand for their steps (the reference at the step's exact value)."""
    d = _dead_centre_scene(180 - 1e-7, 10)
    scene = load_scene(d)
    mine = math.radians(180 - 3e-7)  # no step of the sweep
    q_sweep = linkage_sym.compile_mechanism(scene).sweep()[0]["A"]
    q = {"A": np.array([mine, q_sweep[9]])}
    rates = ({"A": np.full(2, W1)}, {"A": np.full(2, A1)})
    res = run_precise(scene, 50, q, *rates).analysis
    with mp.workdps(70):
        for i, at in enumerate((mp.mpf(mine), _step_q(d, 9))):
            r = _dead_centre_reference(at, mp.mpf(W1), mp.mpf(A1))
            assert res.status[i] == "ok"
            for got, want in ((res.joints["C"].position[i, 0], r["x"]),
                              (res.links["rod"].omega[i], r["omega"])):
                assert abs(mp.mpf(float(got)) - want) <= EPS * abs(want), (i, got, want)
            e_pos, e_vel, e_acc = _dead_centre_errors(res, i, r)
            assert e_pos <= res.accuracy["position"][i] and e_vel <= res.accuracy["velocity"][i]


def test_steps_closer_than_an_ulp_count_their_rounding():
    """A sweep whose steps are closer than an ulp of their radians (1e-7 degrees short of the
    dead centre, 12 steps over two ulps of the degrees): several steps round to one float64
    value, which stands for none of them, so the run takes it as it is; the estimate adds
    that rounding amplified by the step's condition (K eps |q|), and bounds the error
    against each step's exact value (about 3e-12 for positions, 8e-8 for rates)."""
    start = 180 - 1e-7
    stop = math.nextafter(math.nextafter(start, 1000.0), 1000.0)
    d = _dead_centre_scene(stop, 12)
    d["drivers"][0]["start_deg"] = start
    res = run_precise(load_scene(d), 50).analysis
    assert len(set(res.drivers["A"]["q"].tolist())) < 12
    worst = 0.0
    with mp.workdps(70):
        for i in range(12):
            r = _dead_centre_reference(_step_q(d, i), mp.mpf(W1), mp.mpf(A1))
            assert res.status[i] == "ok"
            for e, name in zip(_dead_centre_errors(res, i, r), ("position", "velocity",
                                                              "acceleration")):
                assert e <= res.accuracy[name][i], (i, name, e, res.accuracy[name][i])
                worst = max(worst, float(e / res.accuracy[name][i]))
    assert worst > 1e-3  # the rounding is there, and the estimate is not far above it


def test_load_range_end_at_an_exact_step():
    """A load active up to 180 degrees, at the step of exactly 180 degrees: the exact value
    pi lies beyond the range's float64 end float(pi), but the step is at the range's end in
    the scene's degrees and acts (as the float64 run decides); between the table's points the
    factor is interpolated at the exact value."""
    from linkage_sym.codegen.mp_numbers import factor_mp as _factor_mp
    from linkage_sym.model import Load, LoadTable

    load = Load("rod", torque=1.0, driver="A", period=2 * math.pi,
                table=LoadTable((0.0, math.pi), (0.0, 1.0)), active=(0.0, math.pi))
    with mp.workdps(50):
        # acts (the exact value interpolates on the table's next piece: 1 - 4e-17)
        assert abs(_factor_mp(load, +mp.pi, math.pi) - 1) < mp.mpf(10)**-15
        assert abs(_factor_mp(load, mp.pi / 3, math.pi / 3) - mp.mpf(1) / 3) < mp.mpf(10)**-15
        assert _factor_mp(load, mp.pi * 1.5, math.pi * 1.5) == 0


def test_scene_keeps_the_driver_degrees_it_was_given():
    """The degrees a scene gives are the step values' source, and written back unchanged:
    123.72814463424251 degrees converts to the same radians as 123.7281446342425 (one ulp
    apart), which the conversion back from radians picks."""
    from linkage_sym.codegen.precision import driver_step_mp
    from linkage_sym.scene import dump_scene

    given = 123.72814463424251
    d = _dead_centre_scene(given, 2)
    scene = load_scene(d)
    assert dump_scene(scene)["drivers"][0]["stop_deg"] == given
    with mp.workdps(40):
        assert driver_step_mp(scene.drivers[0], 1) == mp.mpf(given) * mp.pi / 180
        assert mp.mpf(float(scene.drivers[0].stop)) != mp.mpf(given) * mp.pi / 180


def test_a_step_exactly_at_a_dead_centre_is_singular():
    """Crank l1 = 1, rod l2 = 13/8, guide y = 13/8, assembled at 90 degrees (B = (0, 1),
    C = (3/2, 13/8)): the rod stands normal to the guide at exactly 180 degrees.  The compiled
    float64 run, at float(pi), finds that step a tangency's width away (condition 1.4e8: ok),
    and its rates at float(pi) are finite; at the exact value they are not.  The 50-digit run
    says singular (its block indicator is ~1e-26 there, against float64's 1e-8), keeps the
    position, the reference's (-1, 13/8) rounded, and gives no rates (before, the rod's omega
    was -1.2e52 with an accuracy of 2.2e-16)."""
    d = _dead_centre_scene(180.0, 4)
    for j, at in zip(d["joints"][1:], ([0, 1], [1.5, 1.625], [1.5, 1.625])):
        j["at"] = at
    scene = load_scene(d)
    assert linkage_sym.compile_mechanism(scene).run().status[-1] == "ok"
    res = run_precise(scene, 50).analysis
    assert list(res.status) == ["ok", "ok", "ok", "singular"], res.messages
    assert "singular position at 50 digits" in res.messages[-1]
    assert res.condition[-1] > 1e20
    assert tuple(res.joints["C"].position[-1]) == (-1.0, 1.625)
    assert np.isnan(res.links["rod"].omega[-1]) and np.isnan(res.accuracy["velocity"][-1])
    assert np.all(res.accuracy["velocity"][:3] < 1e-15)  # the other steps as they were
