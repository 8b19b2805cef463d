"""The precision knob (``analyze(scene, precision=DIGITS)``, ``--precision DIGITS``).

The arbitrary-precision run evaluates the derived equations in mpmath.  It is checked
against the closed forms of the four-bar and the offset slider-crank in
``reference_kinematics`` (``fourbar_mp``, ``slider_crank_mp``: eqs. 3-9 to 3-17 of the
kinematics chapter re-derived by hand, evaluated here at 60 digits), with the lengths
computed in mpmath from the scene's binary64 joint coordinates (the scene's numbers *are*
the mechanism):

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
import os
import sys

import mpmath as mp
import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

import reference_kinematics as ref  # noqa: E402
import scenes  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.codegen.precision import parse_precision, run_precise  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402

TOL = mp.mpf("1e-30")
EPS = float(np.finfo(float).eps)
L_TRIPLE = (2.0, 3.0, 2.5, 4.0)  # triple rocker: limit (dead centre) at 129.838 deg
W1, A1 = 10.0, 3.0


def _mpt(p):
    return mp.mpf(p[0]), mp.mpf(p[1])


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
        r = ref.fourbar_mp(l1, l2, l3, l4, mp.mpf(float(q["q"][i])), mp.mpf(float(q["qd"][i])),
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
        r = ref.slider_crank_mp(l1, l2, e, mp.mpf(float(q["q"][i])), mp.mpf(float(q["qd"][i])),
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
