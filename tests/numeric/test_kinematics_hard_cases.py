"""Hard cases of the numeric kinematics against 50-digit mpmath references.

The references (reference_kinematics.fourbar_mp / slider_crank_mp) take the
link lengths *as the solver sees them*: read in 50 digits off the scene's
(double) assembly points, and the driver values the solver reports.  What is
left is the solver's own error, to be compared with what a backward-stable
method can do:

* positions and angles: ``C_POS * eps * kappa`` (x the mechanism's size for
  positions), with ``kappa = 1/|det|`` the inverse of the dyad's dimensionless
  Jacobian determinant (four-bar: ``1/|sin(th2 - th3)|``; slider-crank:
  ``1/|cos th2|``) -- a residual of a few ulp moves the solution by that much;
* rates: ``C_RATE * eps * kappa^2`` relative to ``max(|value|, S)``, ``S`` the
  largest magnitude over the sweep's well-conditioned steps (kappa <= 10):
  the rates solve a linear system with the Jacobian (one factor kappa) whose
  entries carry the position error (another factor kappa).

``C_POS = 8`` and ``C_RATE = 32``: observed worst cases are ~1.4 and ~5
(near a dead centre at kappa = 1.9e4); the constants leave a margin for other
platforms' libm, not for a less accurate method.
"""

from __future__ import annotations

import json
import math

import mpmath as mp
import numpy as np
import pytest

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

EPS = np.finfo(float).eps
C_POS = 8.0
C_RATE = 32.0
W1, A1 = 10.0, 3.0


@pytest.fixture(autouse=True)
def _digits():
    with mp.workdps(50):
        yield


def _mp_at(d):
    return {j["name"]: (mp.mpf(j["at"][0]), mp.mpf(j["at"][1])) for j in d["joints"]}


def _wrap(x):
    return x - 2 * mp.pi * mp.nint(x / (2 * mp.pi))


def fourbar_mp_sweep(d, res, sigma):
    """mpmath reference of every step of a four-bar scene built by
    scenes.fourbar (canonical frame: A at the origin, D on the x axis).
    Returns a list (None where the loop cannot close) of dicts of floats:
    rotations (from the assembly angles in 50 digits), omegas, alphas, B, C
    and kappa."""
    J = _mp_at(d)
    assert J["A"] == (0, 0) and J["D"][1] == 0
    dist = lambda a, b: mp.hypot(J[a][0] - J[b][0], J[a][1] - J[b][1])  # noqa: E731
    L = (dist("A", "B"), dist("B", "C"), dist("C", "D"), J["D"][0])
    th2a = mp.atan2(J["C"][1] - J["B"][1], J["C"][0] - J["B"][0])
    th3a = mp.atan2(J["C"][1] - J["D"][1], J["C"][0] - J["D"][0])
    q = np.asarray(res.drivers["A"]["q"], dtype=float)
    out = []
    for i, qi in enumerate(q):
        m = ref.fourbar_mp(*L, qi, W1, A1, sigma)
        if m is None:
            out.append(None)
            continue
        out.append(dict(
            rot2=m["th2"] - th2a, rot3=m["th3"] - th3a,
            w2=float(m["w2"]), w3=float(m["w3"]), a2=float(m["a2"]), a3=float(m["a3"]),
            B=(float(L[0] * mp.cos(qi)), float(L[0] * mp.sin(qi))),
            C=(float(m["Cx"]), float(m["Cy"])),
            vC=(float(m["vCx"]), float(m["vCy"])), aC=(float(m["aCx"]), float(m["aCy"])),
            kappa=float(1 / abs(m["det"])) if m["det"] != 0 else math.inf,
        ))
    return out


def _rate_scales(refs, keys):
    reg = [r for r in refs if r is not None and r["kappa"] <= 10]
    return {k: max(np.max(np.abs(np.asarray(r[k], dtype=float))) for r in reg) for k in keys}


def check_fourbar_steps(d, res, refs, steps, size, what):
    """Every step in ``steps`` against its mpmath reference (tolerances in the
    module docstring); returns the worst error / tolerance ratio."""
    S = _rate_scales(refs, ("w2", "w3", "a2", "a3", "vC", "aC"))
    worst = 0.0
    fails = []

    def chk(name, got, exp, tol, i):
        nonlocal worst
        err = float(np.max(np.abs(np.asarray(got, dtype=float) - np.asarray(exp, dtype=float))))
        if not err <= tol:  # NaN fails
            fails.append(f"step {i} {name}: got {got}, mpmath {exp}, |err| {err:.3e} > {tol:.3e}")
        else:
            worst = max(worst, err / tol)

    cl, rk = res.links["coupler"], res.links["rocker"]
    for i in steps:
        r = refs[i]
        k = r["kappa"]
        tp = C_POS * EPS * k
        for name, got, exp in (("coupler rotation", cl.rotation[i], r["rot2"]),
                               ("rocker rotation", rk.rotation[i], r["rot3"])):
            diff = _wrap(mp.mpf(float(got)) - exp)  # compared modulo 2 pi
            chk(name, float(diff), 0.0, tp * max(1.0, abs(float(got))), i)
        chk("joint B position", res.joints["B"].position[i], r["B"], tp * size, i)
        chk("joint C position", res.joints["C"].position[i], r["C"], tp * size, i)
        tr = C_RATE * EPS * k * k
        for name, got, key in (("coupler omega", cl.omega[i], "w2"),
                               ("rocker omega", rk.omega[i], "w3"),
                               ("coupler alpha", cl.alpha[i], "a2"),
                               ("rocker alpha", rk.alpha[i], "a3"),
                               ("joint C velocity", res.joints["C"].velocity[i], "vC"),
                               ("joint C acceleration", res.joints["C"].acceleration[i], "aC")):
            mag = max(float(np.max(np.abs(r[key]))), S[key])
            chk(name, got, r[key], tr * mag, i)
    assert not fails, f"{what} (reference: mpmath 50 digits): " + "; ".join(fails[:6])
    return worst


def _assert_json_clean(res):
    """to_dict() is valid strict JSON: no NaN or infinity anywhere."""
    json.dumps(res.to_dict(), allow_nan=False)


def _check_unassemblable(res, idx):
    dd = res.to_dict()["steps"]
    for i in idx:
        assert res.status[i] == "unassemblable", f"step {i}: status {res.status[i]}"
        step = dd[i]
        assert step["status"] == "unassemblable"
        assert isinstance(step.get("message"), str) and step["message"].strip(), \
            f"step {i}: no message"
        assert "joints" not in step and "links" not in step, f"step {i}: carries positions"


def _check_ok_finite(res, idx):
    for i in idx:
        assert res.status[i] == "ok", f"step {i}: {res.status[i]} ({res.messages[i]})"
        assert res.messages[i] is None
        for jk in res.joints.values():
            for arr in (jk.position, jk.velocity, jk.acceleration):
                assert np.all(np.isfinite(arr[i]))
        for lk in res.links.values():
            for arr in (lk.rotation, lk.omega, lk.alpha):
                assert np.isfinite(arr[i])


# ---------------------------------------------------------------------------
# (1) a sweep that passes within 0.01 deg (and 1e-7 deg) of a dead centre
# ---------------------------------------------------------------------------

# Non-Grashof triple rocker: l1 + l4 = 6 > l2 + l3 = 5.5; the input reaches its
# limit where coupler and rocker are stretched in line (|BD| = l2 + l3), at
# th1* = acos((l1^2 + l4^2 - (l2 + l3)^2) / (2 l1 l4)) = 129.838 deg.
L_TRIPLE = (2.0, 3.0, 2.5, 4.0)


@pytest.mark.parametrize("gap_deg,beyond", [(0.01, 10), (1e-7, 5)])
def test_sweep_through_dead_centre(gap_deg, beyond):
    """One step lands ``gap_deg`` before the input's limit angle; the sweep
    then continues ``beyond`` 1-deg steps past it."""
    lim = float(mp.degrees(ref.fourbar_limits_mp(*L_TRIPLE)[0]))
    start = lim - 20.0 - gap_deg
    d, _ = scenes.fourbar(*L_TRIPLE, start_deg=start, stop_deg=start + 20 + beyond,
                          steps=21 + beyond, speed=W1, acceleration=A1, sigma=1)
    scene, res = scenes.run(d)
    refs = fourbar_mp_sweep(d, res, 1)
    ok_idx = [i for i, r in enumerate(refs) if r is not None]
    bad_idx = [i for i, r in enumerate(refs) if r is None]
    assert ok_idx == list(range(21)) and bad_idx == list(range(21, 21 + beyond))
    assert refs[20]["kappa"] > (50 if gap_deg == 0.01 else 1e4)  # really near the limit
    _check_ok_finite(res, ok_idx)
    _check_unassemblable(res, bad_idx)
    check_fourbar_steps(d, res, refs, ok_idx, scene.characteristic_length(),
                        f"four-bar {gap_deg} deg before its dead centre")
    _assert_json_clean(res)


# ---------------------------------------------------------------------------
# (2) change point: Grashof equality l_s + l_l = p + q
# ---------------------------------------------------------------------------

# 7 + 17 = 10 + 14 with integer assembly points (Pythagorean: BC = (15, 8),
# DC = (-6, 8)), so that the scene's doubles *are* the mechanism: at th1 = 0,
# B = (7, 0), |BD| = 7 = l2 - l3 exactly, all four joints in line with
# C = (24, 0), and both assembly modes meet there.  (With assembly points
# rounded to doubles the change point may be missed by an ulp either way;
# such a miss, within rounding of the coordinates, is taken as a tangency:
# see test_limit_position_within_rounding_is_singular.)
def _change_point_run():
    d = scenes.change_point_fourbar("change point", W1, A1)
    scene, res = scenes.run(d)
    return d, scene, res


CHANGE_SIGMA = -1  # sign cross(B - D, C - D) in the assembly configuration


def test_change_point_fourbar_keeps_its_assembly_mode():
    """Every step but the change point (th1 = 0, step 18) is ok and equals the
    mpmath reference in the assembly configuration's mode (the sign of the
    dyad determinant, spec: resuming rule; the analytic branch would switch
    modes at the change point)."""
    d, scene, res = _change_point_run()
    refs = fourbar_mp_sweep(d, res, CHANGE_SIGMA)
    assert refs[18] is not None and refs[18]["kappa"] == math.inf  # exactly singular
    others = [i for i in range(37) if i != 18]
    _check_ok_finite(res, others)
    check_fourbar_steps(d, res, refs, others, scene.characteristic_length(),
                        "change-point four-bar")
    _assert_json_clean(res)


def test_exactly_singular_step_keeps_positions_only():
    """The change point itself: the velocity problem has no unique solution
    (cond = inf > 1e10), so the status is ``singular``, with a message; the
    position exists (C = (24, 0)) and is reported, velocities and accelerations
    are not (spec: scene-format.md, Result).  At a double root the position is
    determined to O(sqrt(eps)) only: tolerance 4 sqrt(eps) x size."""
    d, scene, res = _change_point_run()
    i = 18
    assert float(res.drivers["A"]["q"][i]) == pytest.approx(0.0, abs=1e-15)
    assert res.status[i] == "singular", (
        f"change point th1 = 0: status {res.status[i]!r} ({res.messages[i]}); expected "
        "'singular' (the loop closes, as a double root)")
    step = res.to_dict()["steps"][i]
    assert isinstance(step.get("message"), str) and step["message"]
    size = scene.characteristic_length()
    C = step["joints"]["C"]["position"]
    assert math.dist(C, (24.0, 0.0)) <= 4 * math.sqrt(EPS) * size
    assert math.dist(step["joints"]["B"]["position"], (7.0, 0.0)) <= 4 * math.sqrt(EPS) * size
    for jn, rec in step["joints"].items():
        assert "position" in rec and "velocity" not in rec and "acceleration" not in rec, jn
    for ln, rec in step["links"].items():
        assert "rotation" in rec and "omega" not in rec and "alpha" not in rec, ln
    _assert_json_clean(res)


# Limit position of a triple rocker hit by a step in exact arithmetic only: A at
# the origin, D = (2, 0), crank 1, l2 + l3 = sqrt(3) = |BD| at th1 = 60 deg.  The
# doubles miss the tangency by a few ulps one way or the other (which way depends
# on the placement); loci.TANGENT_ULPS takes a miss within 8 ulps of the
# coordinates as the tangency it is.
L_LIMIT = (1.0, math.sqrt(3.0) - 0.8, 0.8, 2.0)


@pytest.mark.parametrize("rotate_deg, origin", [
    (0.0, (0.0, 0.0)), (30.0, (0.0, 0.0)), (77.0, (0.0, 0.0)),
    (0.0, (100.0, -50.0)), (-123.0, (1e3, 1e3)), (200.0, (-3.0, 7.0)),
])
def test_limit_position_within_rounding_is_singular(rotate_deg, origin):
    """The step at the limit angle is never ``unassemblable``: missed outward
    it is the tangency, ``singular`` (condition number infinite); missed
    inward by an ulp the half-chord is ~sqrt(eps) and the spec's condition
    number ~1e8 < 1e10 makes it ``ok``, its condition number reported.
    Either way its position is the tangent one (C on the line BD at l2 from
    B, to the double root's 4 sqrt(eps) x size).  The steps before it are
    ok, the steps after it unassemblable (|BD| > l2 + l3 by far more than
    rounding)."""
    d, _ = scenes.fourbar(*L_LIMIT, start_deg=0, stop_deg=120, steps=121, speed=W1,
                          acceleration=A1, assembly_deg=10.0, rotate_deg=rotate_deg,
                          origin=origin)
    scene, res = scenes.run(d)
    i = 60
    assert res.status[i] in ("singular", "ok"), f"limit step: {res.status[i]} ({res.messages[i]})"
    assert res.condition[i] > 1e6, "the screen must flag the limit step"
    _check_ok_finite(res, range(i))
    _check_unassemblable(res, range(i + 1, 121))
    B, C = res.joints["B"].position[i], res.joints["C"].position[i]
    D = np.array(d["joints"][3]["at"])
    expect = B + L_LIMIT[1] * (D - B) / np.linalg.norm(D - B)
    size = scene.characteristic_length()
    assert np.linalg.norm(C - expect) <= 4 * math.sqrt(EPS) * size
    _assert_json_clean(res)


def test_ill_conditioned_ok_step_is_warned():
    """An ok step near the limit (condition ~4e8, measured by SVD: a rounding-level
    tangency missed inward) is named in ``warnings``, in the JSON too, with the
    digits it loses; a sweep that stays away from the limit has no warning."""
    d, _ = scenes.fourbar(*L_LIMIT, start_deg=0, stop_deg=120, steps=121, speed=W1,
                          acceleration=A1, assembly_deg=10.0)
    scene, res = scenes.run(d)
    assert res.status[60] == "ok" and res.condition[60] > 1e8  # this placement misses inward
    assert len(res.warnings) == 1
    w = res.warnings[0]
    assert "1 ok step(s)" in w and "step 60" in w and "fewer significant digits" in w
    assert res.to_dict()["warnings"] == res.warnings
    d, _ = scenes.fourbar(*L_LIMIT, start_deg=0, stop_deg=50, steps=51, speed=W1,
                          acceleration=A1, assembly_deg=10.0)
    assert scenes.run(d)[1].warnings == []


def test_tangency_tolerance_is_rounding_only():
    """circle_circle: centres one ulp beyond the reach give the tangent point;
    1e-12 relative beyond it (far above rounding) give NaN."""
    from linkage_sym.numeric.kinematics.loci import circle_circle

    r1, r2 = 0.1, 0.2
    reach = r1 + r2
    Yx, Yy, h, _ = circle_circle((0.0, 0.0), r1, (np.nextafter(reach, 1.0), 0.0), r2, 1.0)
    assert float(h) == 0.0 and float(Yx) == pytest.approx(r1, rel=1e-15) and float(Yy) == 0.0
    Yx, Yy, h, _ = circle_circle((0.0, 0.0), r1, (reach * (1 + 1e-12), 0.0), r2, 1.0)
    assert np.isnan(h) and np.isnan(Yx)


# ---------------------------------------------------------------------------
# (3) link-length ratios 1e-3 and 1e3, absolute scales 1e-3 and 1e3
# ---------------------------------------------------------------------------

# the dimensions of example 3-1 of the kinematics chapter [4]
L_EXAMPLE_3_1 = (0.024, math.hypot(0.042, 0.047), 0.048, 0.078)


@pytest.mark.parametrize("lengths", [
    pytest.param((1e-3, 1.0, 0.8, 0.9), id="crank-1e-3-of-the-others"),
    pytest.param((1.0, 1e3, 800.0, 900.0), id="others-1e3-times-crank"),
    pytest.param(tuple(x * 1e-3 for x in L_EXAMPLE_3_1), id="example-3-1-scaled-1e-3"),
    pytest.param(tuple(x * 1e3 for x in L_EXAMPLE_3_1), id="example-3-1-scaled-1e3"),
])
def test_fourbar_extreme_ratios(lengths):
    d, _ = scenes.fourbar(*lengths, steps=25, speed=W1, acceleration=A1, sigma=1)
    scene, res = scenes.run(d)
    refs = fourbar_mp_sweep(d, res, 1)
    assert all(r is not None for r in refs)
    _check_ok_finite(res, range(25))
    check_fourbar_steps(d, res, refs, range(25), scene.characteristic_length(),
                        f"four-bar {lengths}")


@pytest.mark.parametrize("l1,l2,e", [(1.0, 1e3, 0.5), (1e-3, 1.0, 0.2), (1e3, 2.5e3, -700.0)])
def test_slider_crank_extreme_ratios(l1, l2, e):
    """Offset slider-crank vs slider_crank_mp (kappa = 1/|cos th2|)."""
    d, _ = scenes.slider_crank(l1, l2, e, steps=25, speed=W1, acceleration=A1, sigma=1)
    scene, res = scenes.run(d)
    J = _mp_at(d)
    L1 = mp.hypot(*J["B"])
    L2 = mp.hypot(J["C"][0] - J["B"][0], J["C"][1] - J["B"][1])
    E = J["C"][1]
    th2a = mp.atan2(J["C"][1] - J["B"][1], J["C"][0] - J["B"][0])
    size = scene.characteristic_length()
    q = np.asarray(res.drivers["A"]["q"], dtype=float)
    refs = [ref.slider_crank_mp(L1, L2, E, qi, W1, A1, 1) for qi in q]
    S = {k: max(abs(float(r[k])) for r in refs) for k in ("w2", "a2", "v", "a")}
    _check_ok_finite(res, range(25))
    rod, C = res.links["rod"], res.joints["C"]
    for i, r in enumerate(refs):
        k = float(1 / abs(r["det"]))
        tp, tr = C_POS * EPS * k, C_RATE * EPS * k * k
        src = f"slider-crank {l1, l2, e} step {i} (mpmath 50 digits)"
        assert abs(float(_wrap(mp.mpf(float(rod.rotation[i])) - (r["th2"] - th2a)))) <= tp, src
        assert abs(C.position[i][0] - float(r["x"])) <= tp * size, src
        assert abs(C.position[i][1] - float(E)) <= tp * size, src
        for got, key in ((rod.omega[i], "w2"), (rod.alpha[i], "a2"), (C.velocity[i][0], "v"),
                         (C.acceleration[i][0], "a")):
            assert abs(got - float(r[key])) <= tr * max(abs(float(r[key])), S[key]), \
                f"{src}: {key} {got} vs {float(r[key])}"


# ---------------------------------------------------------------------------
# (4) a crank too long to assemble over part of the turn
# ---------------------------------------------------------------------------


def test_crank_too_long_for_part_of_the_turn():
    """Triple rocker driven through a full turn: |BD| > l2 + l3 for th1 in
    (129.84, 230.16) deg.  Those steps are ``unassemblable`` with a message and
    no positions in to_dict(); the others match the closed form (eqs.
    3-9..3-17 of [4]) to 1e-10 and mpmath to the conditioned tolerance; after the
    gap the solution resumes in the assembly mode (sign of the dyad's
    determinant) and the rotations continue with the value nearest the last
    solved step; no NaN anywhere in to_dict()."""
    d, _ = scenes.fourbar(*L_TRIPLE, start_deg=0, stop_deg=360, steps=73, speed=W1,
                          acceleration=A1, sigma=1)
    scene, res = scenes.run(d)
    refs = fourbar_mp_sweep(d, res, 1)
    bad = [i for i, r in enumerate(refs) if r is None]
    good = [i for i, r in enumerate(refs) if r is not None]
    assert bad == list(range(26, 47))  # 130 .. 230 deg
    _check_unassemblable(res, bad)
    _check_ok_finite(res, good)
    size = scene.characteristic_length()
    check_fourbar_steps(d, res, refs, good, size, "long-crank four-bar")
    # closed form, 1e-10 relative to the sweep's largest magnitude
    q = np.asarray(res.drivers["A"]["q"], dtype=float)[good]
    r = ref.fourbar(*L_TRIPLE, q, W1, A1, 1)
    g = np.asarray(good)
    for ln, key in (("coupler", "2"), ("rocker", "3")):
        lk = res.links[ln]
        scenes.assert_close(lk.omega[g], r["w" + key], 1e-10, f"{ln} omega (eq. 3-13/3-14)")
        scenes.assert_close(lk.alpha[g], r["a" + key], 1e-10, f"{ln} alpha (eq. 3-16/3-17)")
    scenes.assert_close(res.joints["C"].position[g], r["C"], 1e-10, "C (eqs. 3-9/3-10)",
                        scale=size)
    # same assembly mode after the gap: sign cross(B - D, C - D) = sigma = +1
    B, C = res.joints["B"].position[g], res.joints["C"].position[g]
    D = np.array(d["joints"][3]["at"])
    assert np.all(np.sign(ref._cross(B - D, C - D)) == 1)
    # rotation continues with the value nearest the last solved step
    for ln in ("coupler", "rocker"):
        rot = res.links[ln].rotation
        assert abs(rot[47] - rot[25]) <= math.pi, f"{ln}: rotation jumps across the gap"
        assert np.all(np.abs(np.diff(rot[:26])) < 1.0) and np.all(np.abs(np.diff(rot[47:])) < 1.0)
    _assert_json_clean(res)
