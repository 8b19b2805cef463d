"""Groups solved by Newton's method: one continuation policy for both runtimes.

Class-III triads and driven (actuator) groups have no closed form; both the
numeric plan and the compiled symbolic mechanism solve them by the policy of
:mod:`linkage_sym.numeric.continuation`.  Checked here, on random geometries:

* **a knee linkage** (thigh on a hip pivot, shin driven at the knee relative
  to the thigh, a rocker from the ankle to the ground): with the knee angle
  given, hip--ankle is a rigid distance ``d(q)``, so the ankle is the
  intersection of two circles -- a closed form written in this file, sharing
  no code with either runtime: assemblable iff ``|d - l_r| <= |HG| <= d + l_r``,
  the ankle on the assembly configuration's side of line ``HG``, the limit
  positions where ``|HG| = |d - l_r|`` or ``d + l_r``;
* **a class-III triad** (the shipped six-bar's topology, joints jittered):
  every ``ok`` step closes (the tests' own joint equations) with the assembly
  configuration's determinant sign of every group (the tests' own finite-
  difference Jacobian), and the two runtimes agree;
* **resolution**: a sweep of ``N`` steps and one of ``20 N`` agree at their
  shared driver values, status and values (``1e-9``), on every shipped example
  and on random Newton-group mechanisms;
* **rotation across a gap**: every link's rotation comes back with the value
  nearest the last solved step (within half a turn).

Tolerance ``1e-9`` of the mechanism's size (positions) and of each quantity's
scale over the sweep (rates, forces): both sides converge Newton to a scaled
residual of 1e-13; what is left is the conditioning of steps near a limit.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

import linkage_sym  # noqa: E402
from tests.support.example_sets import symbolic_examples  # noqa: E402
from linkage_sym.errors import SceneError  # noqa: E402
from linkage_sym.examples import example_names  # noqa: E402

TOL = 1e-9
SETTINGS = dict(max_examples=12, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


# -- scenes ----------------------------------------------------------------------------------

def knee_truth(d):
    """Closed form of the knee linkage at its steps: (assemblable, ankle position, hip-ankle
    distance, the distances at which the group is at a limit)."""
    J = {j["name"]: np.array(j["at"], float) for j in d["joints"]}
    H, K, A, G = J["H"], J["K"], J["A"], J["G"]
    dr = d["drivers"][0]
    q = np.radians(np.linspace(dr["start_deg"], dr["stop_deg"], dr["steps"]))
    lt, ls, lr = np.linalg.norm(K - H), np.linalg.norm(A - K), np.linalg.norm(G - A)
    th_t = math.atan2(K[1] - H[1], K[0] - H[0])
    # the knee angle q is the direction of K->A measured in the thigh's assembly frame
    dHA = np.abs(lt * np.exp(1j * th_t) + ls * np.exp(1j * q))
    HG = np.linalg.norm(G - H)
    ok = (np.abs(dHA - lr) <= HG) & (HG <= dHA + lr)
    side = np.sign((G - H)[0] * (A - H)[1] - (G - H)[1] * (A - H)[0])
    a = (dHA ** 2 - lr ** 2 + HG ** 2) / (2 * HG)
    h = np.sqrt(np.maximum(dHA ** 2 - a ** 2, 0.0))
    u = (G - H) / HG
    n = np.array([-u[1], u[0]])
    ankle = H + a[:, None] * u + side * h[:, None] * n
    return ok, ankle, dHA, (abs(HG - lr), HG + lr), (lt, ls, th_t)



knee_scene, triad_scene, TRIAD_BASE = scenes.knee_scene, scenes.triad_scene, scenes.TRIAD_BASE

jitter = st.floats(-0.03, 0.03, allow_nan=False)
knee_points = st.tuples(*[st.floats(-0.12, 0.12, allow_nan=False)] * 6)


def _knee_from(j):
    K = (0.3 + j[0], 0.5 + j[1])
    A = (K[0] + 0.4 + j[2], K[1] - 0.3 + j[3])
    G = (0.6 + j[4], -0.2 + j[5])
    return knee_scene(K, A, G)


def _triad_from(j):
    return triad_scene({k: (v[0] + j[2 * i], v[1] + j[2 * i + 1])
                        for i, (k, v) in enumerate(TRIAD_BASE.items())})


def _load(d):
    try:
        return linkage_sym.load_scene(d)
    except SceneError:
        return None  # an assembly configuration at a singular position: refused, fine


# -- comparisons -----------------------------------------------------------------------------

def _scales(res):
    """Scale of each compared family over the sweep (largest magnitude, or 1)."""
    out = {}
    for fam, arrs in _families(res).items():
        vals = [np.abs(a[np.isfinite(a)]) for a in arrs if a is not None]
        m = max((float(v.max()) for v in vals if v.size), default=0.0)
        out[fam] = m if m > 0 else 1.0
    return out


def _families(res):
    fam = {"position": [], "rotation": [], "velocity": [], "acceleration": [], "force": []}
    for j in res.joints.values():
        fam["position"].append(j.position)
        fam["velocity"].append(j.velocity)
        fam["acceleration"].append(j.acceleration)
    for lk in res.links.values():
        fam["rotation"].append(lk.rotation)
        fam["velocity"].append(None if lk.omega is None else lk.omega)
        fam["acceleration"].append(None if lk.alpha is None else lk.alpha)
    if res.forces is not None:
        fam["force"] += list(res.forces.reactions.values()) + list(res.forces.driving.values())
    return fam


def assert_same(a, b, what, rows_a=slice(None), rows_b=slice(None), size=None):
    """Statuses equal and every value within TOL of its family's scale (positions: ``size``)."""
    sa, sb = a.status[rows_a], b.status[rows_b]
    diff = np.flatnonzero(sa != sb)
    assert not len(diff), (
        f"{what}: statuses differ at {len(diff)} step(s), first {diff[0]}: "
        f"{sa[diff[0]]} / {sb[diff[0]]} ({a.messages[np.arange(len(a.status))[rows_a][diff[0]]]} / "
        f"{b.messages[np.arange(len(b.status))[rows_b][diff[0]]]})")
    scale = _scales(a)
    if size is not None:
        scale["position"] = size
    for fam, (xa, xb) in {k: (_families(a)[k], _families(b)[k]) for k in scale}.items():
        for k, (u, v) in enumerate(zip(xa, xb)):
            if u is None or v is None:
                continue
            u, v = np.asarray(u)[rows_a], np.asarray(v)[rows_b]
            assert np.array_equal(np.isnan(u), np.isnan(v)), f"{what}: {fam}[{k}] NaN pattern"
            err = np.nanmax(np.abs(u - v), initial=0.0)
            assert err <= TOL * scale[fam], f"{what}: {fam}[{k}] differs by {err:.3g}"


def _steps_of(d, steps):
    e = json.loads(json.dumps(d))
    for dr in e["drivers"]:
        dr["steps"] = steps
    return e


# -- the knee linkage against its closed form --------------------------------------------------

@pytest.mark.slow
@settings(**SETTINGS)
@given(j=knee_points)
def test_knee_linkage_both_methods_match_the_closed_form(j):
    d = _knee_from(j)
    scene = _load(d)
    if scene is None:
        return
    ok, ankle, dHA, limits, _ = knee_truth(d)
    L = scene.characteristic_length()
    # steps within 1e-9 of a limit distance may go either way (tangency): not judged
    HG = math.hypot(*d["joints"][3]["at"])
    lr = math.dist(d["joints"][2]["at"], d["joints"][3]["at"])
    near = np.minimum(np.abs(np.abs(dHA - lr) - HG), np.abs(dHA + lr - HG)) <= 1e-9 * L
    results = {m: linkage_sym.analyze(scene, method=m) for m in ("dyad", "symbolic")}
    for m, res in results.items():
        solved = res.status == "ok"
        judged = ~near & (res.status != "singular")
        bad = np.flatnonzero(judged & (solved != ok))
        assert not len(bad), (m, bad, res.status[bad[:3]], ok[bad[:3]], res.messages[bad[0]])
        err = np.linalg.norm(res.joints["A"].position[solved] - ankle[solved], axis=1)
        assert err.max(initial=0.0) <= TOL * L, (m, err.max())
    assert_same(results["dyad"], results["symbolic"], "dyad vs symbolic", size=L)


@pytest.mark.slow
@settings(**SETTINGS)
@given(j=knee_points)
def test_knee_linkage_rotation_across_a_gap_is_the_nearest_value(j):
    """Scene format: across unassemblable steps a rotation continues with the value nearest
    the last solved step; and a step's values do not depend on the sweep's step count."""
    d = _knee_from(j)
    scene = _load(d)
    if scene is None:
        return
    res = linkage_sym.analyze(scene)
    good = np.flatnonzero(res.status == "ok")
    for name, lk in res.links.items():
        jumps = np.abs(np.diff(lk.rotation[good]))
        assert jumps.max(initial=0.0) <= math.pi, (name, jumps.max())


def test_knee_limit_is_reported_at_its_driver_value():
    """The first step past a limit names the knee angle of the limit: the closed form's
    (where hip-ankle equals |HG| + l_rocker or |HG - l_rocker|), to 1e-6 rad.  The
    continuation bisects the path interval (at most 2 degrees) to 1/4096 of it."""
    d = knee_scene((0.3, 0.5), (0.7, 0.2), (0.6, -0.2), start_deg=-60, stop_deg=120, steps=19)
    ok, _, dHA, limits, (lt, ls, th_t) = knee_truth(d)
    res = linkage_sym.analyze(linkage_sym.load_scene(d))
    first = int(np.flatnonzero(~ok)[0])
    assert ok[first - 1] and res.status[first - 1] == "ok" and res.status[first] == "unassemblable"
    msg = res.messages[first]
    got = math.radians(float(re.search(r"K = ([-0-9.e]+)°", msg).group(1)))
    # the limit angle: |lt e^{i th_t} + ls e^{i q}| = the limit distance, between the steps
    q = np.radians(np.linspace(-60, 120, 19))
    lo, hi = q[first - 1], q[first]
    target = min(limits, key=lambda x: abs(x - dHA[first]))
    f = lambda x: abs(lt * np.exp(1j * th_t) + ls * np.exp(1j * x)) - target  # noqa: E731
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sign(f(mid)) == np.sign(f(lo)) else (lo, mid)
    assert abs(got - lo) <= 1e-6, (msg, math.degrees(lo))


# -- class-III triads: both methods, closure and determinant signs ------------------------------

@pytest.mark.slow
@settings(**SETTINGS)
@given(j=st.tuples(*[jitter] * 12))
def test_random_triads_both_methods_agree_and_close_in_the_assembly_mode(j):
    d = _triad_from(j)
    scene = _load(d)
    if scene is None:
        return
    num = linkage_sym.analyze(scene)
    sym = linkage_sym.analyze(scene, method="symbolic")
    assert_same(num, sym, "dyad vs symbolic", size=scene.characteristic_length())
    for res in (num, sym):
        assert not ref.closure_failures(scene, res, 1e-12, 1e-9)
        _, s0, signs, _ = ref.determinant_signs(scene, res)
        okr = np.flatnonzero(res.status == "ok")
        assert np.all(signs[okr] == s0), "an ok step in another assembly mode"


# -- resolution independence ---------------------------------------------------------------------

def _resolution_pair(d, n):
    """Analyses of ``d`` with n and 20 (n - 1) + 1 steps (every 20th step shared)."""
    coarse = linkage_sym.load_scene(_steps_of(d, n))
    fine = linkage_sym.load_scene(_steps_of(d, 20 * (n - 1) + 1))
    return coarse, fine


@pytest.mark.slow
@pytest.mark.parametrize("name", example_names())
def test_shipped_examples_do_not_depend_on_the_step_count(name):
    d = json.loads(linkage_sym.examples.example_path(name).read_text())
    coarse, fine = _resolution_pair(d, 19)
    # the symbolic layer refuses gear meshes (test_gears.py): the numeric method only there
    for m in ("dyad", "symbolic") if name in symbolic_examples() else ("dyad",):
        a = linkage_sym.analyze(coarse, method=m)
        b = linkage_sym.analyze(fine, method=m)
        assert_same(a, b, f"{name} ({m}) 19 vs 361 steps", rows_b=slice(None, None, 20),
                    size=coarse.characteristic_length())


@pytest.mark.slow
@settings(**{**SETTINGS, "max_examples": 6})
@given(j=knee_points, kind=st.sampled_from(["knee", "triad"]), jt=st.tuples(*[jitter] * 12))
def test_random_newton_groups_do_not_depend_on_the_step_count(j, kind, jt):
    d = _knee_from(j) if kind == "knee" else _triad_from(jt)
    if _load(d) is None:
        return
    coarse, fine = _resolution_pair(d, 13)
    for m in ("dyad", "symbolic"):
        a = linkage_sym.analyze(coarse, method=m)
        b = linkage_sym.analyze(fine, method=m)
        assert_same(a, b, f"{kind} ({m}) 13 vs 241 steps", rows_b=slice(None, None, 20),
                    size=coarse.characteristic_length())


# -- jumps are never silent ----------------------------------------------------------------------

@pytest.mark.slow
def test_a_triad_that_jumps_past_a_limit_says_so_and_names_an_ambiguous_mode():
    """A random triad whose branch ends at a limit position and which goes on in another
    configuration of the same determinant sign: both runtimes warn, naming the limit's
    driver value and the number of solutions of that sign (the mode is ambiguous)."""
    scene = linkage_sym.load_scene(scenes.triad_jump())  # the jump is at step 14
    for m in ("dyad", "symbolic"):
        res = linkage_sym.analyze(scene, method=m)
        w = [x for x in res.warnings if "ambiguous" in x]
        assert w and re.search(r"A = [-0-9.]+°", w[0]) and "2 solutions" in w[0], res.warnings
        assert "at step 14 (reached from step 13)" in w[0], w[0]
