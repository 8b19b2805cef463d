"""Hard cases of the compiled symbolic mechanism against 50-digit mpmath.

The reference evaluates the *same* nested closed forms
(``derive(scene).nested_closed_forms()``) and the same rate equations
(``A xd = B qd`` from ``derive(scene).A, .B``) with SymPy's mpmath printer at
``mp.dps = 50``, at the float64 inputs converted exactly (drivers, the
compiled parameter values ``cm.params`` including the assembly signs).  What
is left is the float64 error of the generated code, compared with what
evaluating the formula in floating point can do near a dead centre:

* positions (closed forms): ``C_POS * eps * kappa`` rad, with
  ``kappa = 1/|sin(theta_coupler - theta_rocker)|`` (the inverse of the
  dyad's dimensionless Jacobian determinant): the closed form takes a square
  root of a discriminant that vanishes like ``sin^2`` at the dead centre and
  is computed with an absolute error of a few eps (in units of L^4), so the
  angle moves by ~``eps/(2 sin)``.  ``C_POS = 8`` (observed: 1.8 at kappa = 59, 1.2 at
  kappa = 5.9e3; the margin is for other platforms' libm);
* rates: ``C_RATE * eps * kappa`` relative to ``max|xd|`` over the sweep: the
  compiled run solves the 2x2 block by Cramer's rule (forward error
  ~ eps * cond, cond ~ kappa) with entries evaluated at positions that carry
  their own ~eps error, which the mpmath solve at the float positions does
  not see (another eps * kappa |xd|).  ``C_RATE = 32`` (observed 1.7 and 2.1).
"""

from __future__ import annotations

import json
import math

import mpmath as mp
import numpy as np
import pytest
import sympy as sp

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402
from tests.symbolic.test_symbolic import compare_analyses  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.codegen.compile import compile_mechanism  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402
from linkage_sym.symbolic.mechanism import derive  # noqa: E402

EPS = float(np.finfo(float).eps)
C_POS = 8.0
C_RATE = 32.0
W1, A1 = 10.0, 3.0
L_TRIPLE = (2.0, 3.0, 2.5, 4.0)  # triple rocker, limit at 129.838 deg


def _mp_functions(eqs, cm):
    """mpmath functions of the nested closed forms and of A, B qd, with the
    symbols in the order (x, q, qd, P) -- P as cm.param_names then sigmas."""
    p_syms = list(eqs.parameters) + list(eqs.sigmas)
    assert [s.name for s in eqs.parameters] == cm.param_names
    args = list(eqs.x) + list(eqs.q) + list(eqs.qd) + p_syms
    nested = eqs.nested_closed_forms()
    closed = sp.lambdify(args, [nested[s] for s in eqs.x], modules="mpmath")
    Bqd = eqs.B * sp.Matrix(eqs.qd)
    rates = sp.lambdify(args, [eqs.A, Bqd], modules="mpmath")
    return closed, rates


@pytest.mark.parametrize("gap_deg", [0.01, 1e-6])
def test_closed_forms_and_rates_near_dead_centre(gap_deg):
    lim = float(mp.degrees(ref.fourbar_limits_mp(*L_TRIPLE)[0]))
    start = lim - 20.0 - gap_deg
    d, _ = scenes.fourbar(*L_TRIPLE, start_deg=start, stop_deg=start + 20, steps=21,
                          speed=W1, acceleration=A1, sigma=1, name="symbolic near dead centre")
    scene = load_scene(d)
    cm = compile_mechanism(scene)
    eqs = derive(scene, True)
    closed, rates = _mp_functions(eqs, cm)
    res = cm.run()
    assert np.all(res.status == "ok")
    num = linkage_sym.analyze(scene)
    q = np.asarray(res.drivers["A"]["q"], dtype=float)
    # float64: the generated closed forms, called with float64 arrays
    X = [np.asarray(v, dtype=float) for v in
         cm.functions["positions_0"](None, None, None, [q], None, None, None, cm.params)]
    assert len(X) == len(eqs.x) == 3
    names = [s.name for s in eqs.x]
    ic, ir = names.index("theta_coupler"), names.index("theta_rocker")
    pm = [mp.mpf(float(p)) for p in cm.params]  # exact conversions
    worst_pos = worst_rate = 0.0
    kappas = []
    with mp.workdps(50):
        xd_ref = []
        for i, qi in enumerate(q):
            xm = closed(*([0] * len(eqs.x) + [mp.mpf(float(qi)), mp.mpf(W1)] + pm))
            xm = [mp.mpf(v) for v in xm]
            kappa = float(1 / abs(mp.sin(xm[ic] - xm[ir])))
            kappas.append(kappa)
            for c in range(3):
                err = abs(float(mp.mpf(float(X[c][i])) - xm[c]))
                tol = C_POS * EPS * kappa * max(1.0, abs(float(xm[c])))
                assert err <= tol, (f"gap {gap_deg}: step {i} {names[c]}: float64 "
                                    f"{X[c][i]!r} vs mpmath {mp.nstr(xm[c], 20)}: {err:.3e} > {tol:.3e}")
                worst_pos = max(worst_pos, err / tol * C_POS)
            # the same A, B qd entries, at the float64 positions, solved in 50 digits
            xf = [mp.mpf(float(X[c][i])) for c in range(3)]
            Am, bm = rates(*(xf + [mp.mpf(float(qi)), mp.mpf(W1)] + pm))
            xd_ref.append(mp.lu_solve(mp.matrix(Am), mp.matrix(bm)))
        assert kappas[-1] > (50 if gap_deg == 0.01 else 1e3), kappas[-1]
        scale = max(abs(float(v)) for xd in xd_ref for v in xd)
        for i in range(len(q)):
            for c, link in enumerate(("crank", "coupler", "rocker")):
                got = float(res.links[link].omega[i])
                err = abs(float(mp.mpf(got) - xd_ref[i][c]))
                tol = C_RATE * EPS * kappas[i] * scale
                assert err <= tol, (f"gap {gap_deg}: step {i} omega {link}: {got!r} vs mpmath "
                                    f"{mp.nstr(xd_ref[i][c], 20)}: {err:.3e} > {tol:.3e}")
                worst_rate = max(worst_rate, err / tol * C_RATE)
    # against the numeric solver, the tolerance grows with the conditioning
    # (both carry ~eps*kappa): compare the well-conditioned steps at 1e-10
    good = [i for i, k in enumerate(kappas) if k <= 10]
    assert len(good) >= 15
    for lk in ("coupler", "rocker"):
        g = np.asarray(good)
        np.testing.assert_allclose(res.links[lk].rotation[g], num.links[lk].rotation[g],
                                   rtol=0, atol=1e-10)
    print(f"gap {gap_deg} deg: kappa {kappas[-1]:.3g}; worst pos err/(eps kappa) "
          f"{worst_pos:.2f}, worst rate err/(eps kappa |xd|max) {worst_rate:.2f}")


def _assert_json_clean(res):
    json.dumps(res.to_dict(), allow_nan=False)


def test_crank_too_long_flags_the_same_steps_unassemblable():
    """Triple rocker through a full turn: |BD| > l2 + l3 for th1 in
    (129.84, 230.16) deg; the symbolic run flags exactly the numeric solver's
    unassemblable steps (26..46), with a message and no positions, and
    equals it elsewhere (1e-10 of the family scales)."""
    d, _ = scenes.fourbar(*L_TRIPLE, start_deg=0, stop_deg=360, steps=73, speed=W1,
                          acceleration=A1, sigma=1, name="symbolic long crank")
    scene = load_scene(d)
    sym = compile_mechanism(scene).run()
    num = linkage_sym.analyze(scene)
    bad = [i for i in range(73) if sym.status[i] != "ok"]
    assert bad == list(range(26, 47))
    assert all(sym.status[i] == "unassemblable" for i in bad)
    compare_analyses(scene, sym, num, "long-crank four-bar")
    dd = sym.to_dict()["steps"]
    for i in bad:
        assert isinstance(dd[i].get("message"), str) and dd[i]["message"].strip()
        assert "joints" not in dd[i] and "links" not in dd[i]
    _assert_json_clean(sym)


def test_slider_crank_crank_too_long():
    """Offset slider-crank whose crank reaches beyond the rod over part of the
    turn (|l1 sin th - e| > l2): same unassemblable steps as numeric."""
    l1, l2, e = 1.0, 0.9, 0.3  # unassemblable where sin th > 1.2 or sin th < -0.6
    d, _ = scenes.slider_crank(l1, l2, e, start_deg=0, stop_deg=360, steps=73, speed=W1,
                               acceleration=A1, sigma=1, assembly_deg=0.0,
                               name="symbolic long crank slider")
    scene = load_scene(d)
    sym = compile_mechanism(scene).run()
    num = linkage_sym.analyze(scene)
    th = np.radians(np.linspace(0, 360, 73))
    expect_bad = np.flatnonzero(l1 * np.sin(th) - e < -l2)
    assert len(expect_bad) > 5
    bad = np.flatnonzero(num.status == "unassemblable")
    assert set(expect_bad) <= set(bad)
    assert list(sym.status) == list(num.status)
    compare_analyses(scene, sym, num, "long-crank slider-crank")
    _assert_json_clean(sym)


def test_exactly_singular_step_keeps_positions():
    """Change-point four-bar (7 + 17 = 10 + 14, integer assembly points): at
    th1 = 0 the joints are exactly in line (C = (24, 0)), so the step is
    ``singular``: positions kept (to 4 sqrt(eps) x size: a double root),
    no rates, a message, no NaN in to_dict(); the other steps as numeric."""
    d = scenes.change_point_fourbar("symbolic change point", W1, A1)
    scene = load_scene(d)
    sym = compile_mechanism(scene).run()
    num = linkage_sym.analyze(scene)
    i = 18
    assert num.status[i] == "singular"
    assert sym.status[i] == "singular", f"symbolic status {sym.status[i]!r} ({sym.messages[i]})"
    step = sym.to_dict()["steps"][i]
    assert isinstance(step.get("message"), str) and step["message"]
    size = scene.characteristic_length()
    tol = 4 * math.sqrt(EPS) * size
    assert math.dist(step["joints"]["C"]["position"], (24.0, 0.0)) <= tol
    assert math.dist(step["joints"]["B"]["position"], (7.0, 0.0)) <= tol
    for jn, rec in step["joints"].items():
        assert "position" in rec and "velocity" not in rec and "acceleration" not in rec, jn
    for ln, rec in step["links"].items():
        assert "rotation" in rec and "omega" not in rec and "alpha" not in rec, ln
    _assert_json_clean(sym)
    # the other steps: as the numeric solver (positions at the singular step
    # are only determined to O(sqrt(eps)), so compare it separately above)
    others = np.array([k for k in range(37) if k != i])
    assert list(sym.status[others]) == list(num.status[others])
    L = size
    for jn in num.joints:
        np.testing.assert_allclose(sym.joints[jn].position[others],
                                   num.joints[jn].position[others], rtol=0, atol=1e-10 * L)
        V = np.nanmax(np.abs(num.joints[jn].velocity[others])) + 1.0
        np.testing.assert_allclose(sym.joints[jn].velocity[others],
                                   num.joints[jn].velocity[others], rtol=0, atol=1e-10 * V)


def _limit_fourbar(l1, g, r1):
    """A four-bar whose dyad reaches its limit (coupler and rocker in line) exactly at the
    sweep's last step, crank angle 180 deg: ``|BD| = g + l1 = r1 + r2`` there."""
    r2 = (g + l1) - r1
    B, D = (0.0, l1), (g, 0.0)
    dx, dy = D[0] - B[0], D[1] - B[1]
    dd = math.hypot(dx, dy)
    a = (dd * dd + r1 * r1 - r2 * r2) / (2 * dd)
    h = math.sqrt(r1 * r1 - a * a)
    C = [B[0] + a * dx / dd - h * dy / dd, B[1] + a * dy / dd + h * dx / dd]
    return {"name": "limit", "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
            "joints": [{"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0, 0]},
                       {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": list(B)},
                       {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": C},
                       {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": list(D)}],
            "drivers": [{"joint": "A", "toward": "B", "start_deg": 90, "stop_deg": 180,
                         "steps": 31, "speed": 1.0}],
            "outputs": ["kinematics"]}


@pytest.mark.parametrize("l1,g,r1", [(0.3, 0.9, 0.3), (0.17, 0.9, 0.3), (0.3, 1.1, 0.77),
                                     (0.2, 0.7, 0.45), (0.2, 0.9, 0.77), (0.1, 1.1, 0.77),
                                     (0.7, 0.9, 0.6)])
def test_a_limit_missed_by_rounding_is_a_tangency_in_both_runtimes(l1, g, r1):
    """A step exactly at a limit position where rounding puts the Heron product a few ulps
    below zero (these dimensions, found by a search, do; the generated code once called
    the step unassemblable where the numeric solver, which takes a miss within 8 ulps of
    the coordinates as the tangency, calls it singular): both runtimes call it singular,
    with the joint in line to rounding (the closed form's own ``C = B + (|BC|/|BD|)(D - B)``
    at the tangency, written here)."""
    scene = load_scene(_limit_fourbar(l1, g, r1))
    num, sym = linkage_sym.analyze(scene), compile_mechanism(scene).run()
    assert str(num.status[-1]) == "singular" and str(sym.status[-1]) == "singular"
    B, D = (-l1, 0.0), (g, 0.0)
    C = np.array([B[0] + r1 / (g + l1) * (D[0] - B[0]), 0.0])
    for res in (num, sym):
        assert np.max(np.abs(res.joints["C"].position[-1] - C)) <= 1e-15 * 4, res.joints["C"].position[-1]


def test_generated_run_warns_like_the_numeric_one():
    """A triple rocker whose step 60 sits a rounding-level miss inside its limit position
    (condition ~1e8, see test_kinematics_hard_cases.L_LIMIT): the generated code's run
    names that step in its warnings, as the numeric plan does; the condition numbers
    themselves differ (each method's own rounding of a near-double root)."""
    lengths = (1.0, math.sqrt(3.0) - 0.8, 0.8, 2.0)
    d, _ = scenes.fourbar(*lengths, start_deg=0, stop_deg=120, steps=121, speed=10.0,
                          acceleration=3.0, assembly_deg=10.0)
    sym = compile_mechanism(load_scene(d)).run()
    num = linkage_sym.analyze(load_scene(d))
    for res in (sym, num):
        assert res.status[60] == "ok"
        assert len(res.warnings) == 1 and "step 60" in res.warnings[0], res.warnings
