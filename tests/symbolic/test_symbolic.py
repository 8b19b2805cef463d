"""The symbolic layer (SymPy derivation, lambdified and cached functions)
against references that share no code with it.

References and tolerances
-------------------------
* **Numeric solver** (``linkage_sym.analyze``: dyad closed forms, Newton,
  Dang and Zhang's [1] superposition -- none of it in ``linkage_sym.symbolic`` or
  ``linkage_sym.codegen``).  Issue requirement: every quantity within
  ``1e-10`` *relative to its family's scale* (``RTOL``), because quantities
  that are exactly zero or tiny in the reference (a ground pivot's
  acceleration, a P joint's couple) carry the round-off of their family:

  - positions (joints, link origins, centres of mass): ``L`` = the largest of
    ``scene.characteristic_length()`` and the largest coordinate of any
    reported point (a point far from the mechanism carries round-off of its
    own size);
  - rotations: ``max(1, max |rotation|)`` rad;
  - velocities (and accelerations): the largest magnitude over all joint,
    origin and centre-of-mass velocities (accelerations) of the sweep;
    omega (alpha): that scale / ``L``;
  - reactions, P-driver forces and the frame force: the largest reaction
    magnitude ``Fs``; reaction moments, R-driver torques and the frame
    moment: ``Fs * L``.

  The mechanisms stay away from singular positions (statuses are compared
  first; random four-bars are filtered for transmission angles), so both
  methods carry ~1e-14 of their family: 1e-10 leaves four digits of margin
  and still catches any wrong term (O(1)).
* **The numeric derivation** ``derive(scene, False)`` for the symbolic one
  with the scene's values substituted: evaluated in 40-digit mpmath at random
  points; equal to ``1e-25`` relative to the largest entry of the same block
  (both hold the *same* doubles, so any difference beyond 40-digit round-off
  is a structural error).
* **50-digit mpmath** evaluation of the same closed forms / rate equations,
  near a dead centre (``test_symbolic_hard_cases`` section below), with the
  conditioned tolerances stated there.
"""

from __future__ import annotations

import inspect
import json
import math
import os
import random

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from tests.support import scenes  # noqa: E402

import linkage_sym  # noqa: E402
import linkage_sym.codegen.compile as cg_compile  # noqa: E402
from linkage_sym.codegen.compile import compile_mechanism  # noqa: E402
from linkage_sym.examples import example_names
from tests.support.example_sets import symbolic_examples  # noqa: E402
from tests.support.marks import slow_cases  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402
from linkage_sym.symbolic.mechanism import derive  # noqa: E402

RTOL = 1e-10
EPS = float(np.finfo(float).eps)
EXAMPLES = symbolic_examples()  # the symbolic layer refuses cam contacts
HYP = settings(max_examples=15, deadline=None, derandomize=True,
               suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


# =========================================================================== comparison
def _mag(v):
    v = np.asarray(v, dtype=float)
    return np.hypot(v[..., 0], v[..., 1]) if v.ndim == 2 else np.abs(v)


def _nanmax(arrs, floor=0.0):
    m = floor
    for a in arrs:
        if a is None:
            continue
        a = _mag(a)
        if np.any(np.isfinite(a)):
            m = max(m, float(np.nanmax(a)))
    return m


def family_scales(scene, ref):
    """Scales of every family (module docstring), from the reference result."""
    pos = [j.position for j in ref.joints.values()]
    pos += [lk.origin for lk in ref.links.values()] + [lk.com for lk in ref.links.values()]
    L = max(scene.characteristic_length(), _nanmax(pos))
    vel = [j.velocity for j in ref.joints.values()]
    vel += [lk.origin_velocity for lk in ref.links.values()]
    vel += [lk.com_velocity for lk in ref.links.values()]
    acc = [j.acceleration for j in ref.joints.values()]
    acc += [lk.origin_acceleration for lk in ref.links.values()]
    acc += [lk.com_acceleration for lk in ref.links.values()]
    s = dict(L=L, rot=_nanmax([lk.rotation for lk in ref.links.values()], 1.0),
             V=_nanmax(vel, 1e-300), A=_nanmax(acc, 1e-300))
    if ref.forces is not None:
        s["F"] = _nanmax(ref.forces.reactions.values(), 1e-300)
    return s


def _check(got, exp, scale, what, rtol, fails):
    g = np.asarray(got, dtype=float)
    e = np.asarray(exp, dtype=float)
    if g.shape != e.shape:
        fails.append(f"{what}: shape {g.shape} != {e.shape}")
        return 0.0
    if not np.array_equal(np.isnan(g), np.isnan(e)):
        fails.append(f"{what}: NaN pattern differs at steps "
                     f"{np.flatnonzero((np.isnan(g) != np.isnan(e)).reshape(len(g), -1).any(1))[:5]}")
        return 0.0
    err = np.where(np.isnan(e), 0.0, np.abs(g - e))
    worst = float(np.max(err)) / scale if err.size else 0.0
    if not worst <= rtol:
        i = np.unravel_index(np.argmax(err), err.shape)
        fails.append(f"{what}: worst at {i}: got {g[i]!r}, numeric {e[i]!r}, |err|/scale = "
                     f"{worst:.2e} > {rtol:.0e} (scale {scale:.3g})")
    return worst


def compare_analyses(scene, sym, num, what, rtol=RTOL):
    """Every array of the two results within ``rtol`` of its family scale.
    Returns the worst ratio |err|/scale observed."""
    assert list(sym.status) == list(num.status), (
        f"{what}: statuses differ at steps "
        f"{[i for i, (a, b) in enumerate(zip(sym.status, num.status)) if a != b][:10]}: "
        f"symbolic {[str(sym.status[i]) for i in range(len(sym.status)) if sym.status[i] != num.status[i]][:5]}"
        f" numeric {[str(num.status[i]) for i in range(len(num.status)) if sym.status[i] != num.status[i]][:5]}")
    assert tuple(sym.stages) == tuple(num.stages), what
    s = family_scales(scene, num)
    L, V, A = s["L"], s["V"], s["A"]
    fails: list = []
    worst = 0.0

    def chk(g, e, scale, name):
        nonlocal worst
        if e is None:
            if g is not None:
                fails.append(f"{name}: numeric has none, symbolic has one")
            return
        if g is None:
            fails.append(f"{name}: missing in the symbolic result")
            return
        worst = max(worst, _check(g, e, scale, f"{what} {name}", rtol, fails))

    for k in num.drivers:
        for key in ("q", "qd", "qdd"):
            chk(sym.drivers[k][key], num.drivers[k][key],
                max(1.0, float(np.max(np.abs(num.drivers[k][key])))), f"driver {k} {key}")
    assert set(sym.joints) == set(num.joints) and set(sym.links) == set(num.links), what
    for n, jn in num.joints.items():
        js = sym.joints[n]
        chk(js.position, jn.position, L, f"joint {n} position")
        chk(js.velocity, jn.velocity, V, f"joint {n} velocity")
        chk(js.acceleration, jn.acceleration, A, f"joint {n} acceleration")
    for n, ln in num.links.items():
        ls = sym.links[n]
        chk(ls.rotation, ln.rotation, s["rot"], f"link {n} rotation")
        chk(ls.omega, ln.omega, V / L, f"link {n} omega")
        chk(ls.alpha, ln.alpha, A / L, f"link {n} alpha")
        chk(ls.origin, ln.origin, L, f"link {n} origin")
        chk(ls.origin_velocity, ln.origin_velocity, V, f"link {n} origin velocity")
        chk(ls.origin_acceleration, ln.origin_acceleration, A, f"link {n} origin acceleration")
        chk(ls.com, ln.com, L, f"link {n} com")
        chk(ls.com_velocity, ln.com_velocity, V, f"link {n} com velocity")
        chk(ls.com_acceleration, ln.com_acceleration, A, f"link {n} com acceleration")
    assert (sym.forces is None) == (num.forces is None), what
    if num.forces is not None:
        fs, fn = sym.forces, num.forces
        assert fs.method == "symbolic"
        F = s["F"]
        assert set(fs.reactions) == set(fn.reactions) and set(fs.driving) == set(fn.driving)
        for n in fn.reactions:
            chk(fs.reactions[n], fn.reactions[n], F, f"reaction {n}")
            chk(fs.reaction_moments[n], fn.reaction_moments[n], F * L, f"reaction moment {n}")
        for n in fn.driving:
            kind = scene.joint(n).type
            chk(fs.driving[n], fn.driving[n], F * L if kind == "R" else F, f"driving {n}")
        chk(fs.frame_force, fn.frame_force, F, "frame force")
        chk(fs.frame_moment, fn.frame_moment, F * L, "frame moment")
    assert not fails, f"{len(fails)} quantity(ies) off: " + "; ".join(fails[:8])
    return worst


def _structure(d, path="", ignore=("force_method", "groups")):
    """Set of key paths of a to_dict() tree (list items by index)."""
    out = set()
    if isinstance(d, dict):
        for k, v in d.items():
            if path == "" and k in ignore:
                continue
            out.add(f"{path}/{k}")
            out |= _structure(v, f"{path}/{k}", ignore)
    elif isinstance(d, list) and d and isinstance(d[0], (dict, list)):
        for i, v in enumerate(d):
            out |= _structure(v, f"{path}[{i}]", ignore)
    return out


def compare_dicts(scene, ds, dn, what, rtol=RTOL):
    """Two to_dict() trees (the JSON contract): the same key structure
    (except the force method and how each group was solved, which name the
    method), the same statuses and messages' presence, and every number
    within ``rtol`` of its family scale (scales from the numeric tree)."""
    ss, sn = _structure(ds), _structure(dn)
    assert ss == sn, (f"{what}: to_dict keys differ; only symbolic: {sorted(ss - sn)[:6]}, "
                      f"only numeric: {sorted(sn - ss)[:6]}")
    assert ds["scene"] == dn["scene"] and ds["stages"] == dn["stages"]
    if "groups" in dn:
        assert [g["links"] for g in ds["groups"]] == [g["links"] for g in dn["groups"]]
    steps_s, steps_n = ds["steps"], dn["steps"]
    assert len(steps_s) == len(steps_n)

    def vals(key, sub=None):
        out = []
        for st_ in steps_n:
            for rec in (st_.get("joints", {}).values() if sub == "joints" else
                        st_.get("links", {}).values()):
                if key in rec:
                    out.append(np.hypot(*rec[key]) if isinstance(rec[key], list) else abs(rec[key]))
        return max(out, default=1e-300)

    L = max(scene.characteristic_length(), vals("position", "joints"), vals("com", "links"))
    # a point's speeds, or the links' turning at the mechanism's size (gears on fixed pivots:
    # every joint and centre of mass may stand still)
    V = max(vals("velocity", "joints"), vals("com_velocity", "links"), L * vals("omega", "links"))
    A = max(vals("acceleration", "joints"), vals("com_acceleration", "links"),
            L * vals("alpha", "links"), L * vals("omega", "links") ** 2)
    F = vals("reaction", "joints")
    scale = {"position": L, "com": L, "velocity": V, "com_velocity": V, "acceleration": A,
             "com_acceleration": A, "omega": V / L, "alpha": A / L, "reaction": F,
             "reaction_moment": F * L, "force": F, "moment": F * L,
             "rotation": max(1.0, vals("rotation", "links"))}
    worst = 0.0
    for i, (a, b) in enumerate(zip(steps_s, steps_n)):
        assert a["status"] == b["status"], f"{what} step {i}: {a['status']} vs {b['status']}"
        assert ("message" in a) == ("message" in b), f"{what} step {i}: message"
        for k, dv in b["drivers"].items():
            for kk, v in dv.items():
                assert abs(a["drivers"][k][kk] - v) <= rtol * max(1.0, abs(v)), (what, i, k, kk)
        for sec in ("joints", "links"):
            for name, rec in b.get(sec, {}).items():
                for key, v in rec.items():
                    err = float(np.max(np.abs(np.subtract(a[sec][name][key], v))))
                    r = err / scale[key]
                    assert r <= rtol, f"{what} step {i} {sec} {name} {key}: {a[sec][name][key]} vs {v}"
                    worst = max(worst, r)
        for name, v in b.get("driving", {}).items():
            sc = F * L if scene.joint(name).type == "R" else F
            assert abs(a["driving"][name] - v) <= rtol * sc, f"{what} step {i} driving {name}"
        if "frame" in b:
            for key, v in b["frame"].items():
                err = float(np.max(np.abs(np.subtract(a["frame"][key], v))))
                assert err <= rtol * scale[key], f"{what} step {i} frame {key}"
    return worst


def _json_clean(res):
    json.dumps(res.to_dict(), allow_nan=False)


# =========================================================================== 1. examples
@pytest.mark.parametrize("name", slow_cases(EXAMPLES, {
    "stephenson_sixbar", "song_wang_sixbar", "shaper", "fivebar", "engine_four_stroke",
    "sixbar_class3", "printing_mechanism", "guide_bar_quick_return", "printing_mechanism_stroke",
    "crank_rocker", "watt_sixbar", "shaper_flywheel", "fivebar_motors", "gear_linkage"}))
def test_examples_match_numeric(name):
    """Contract: the compiled symbolic run equals the numeric solver on every
    shipped example (arrays and JSON)."""
    scene = linkage_sym.load_example(name)
    sym = compile_mechanism(scene).run()
    num = linkage_sym.analyze(scene)
    assert sym.forces is not None and num.forces is not None
    compare_analyses(scene, sym, num, name)
    compare_dicts(scene, sym.to_dict(), num.to_dict(), name)
    _json_clean(sym)


def test_analyze_method_symbolic_is_the_compiled_run():
    scene = linkage_sym.load_example("crank_rocker")
    a = linkage_sym.analyze(scene, method="symbolic")
    assert a.forces.method == "symbolic"
    compare_analyses(scene, a, linkage_sym.analyze(scene), "analyze(method='symbolic')")


# =========================================================================== 2. random
def _with_dynamics(d, rng, gravity=True, loads=True):
    """Random masses, centres, inertias, loads and gravity on a scene dict."""
    pts = np.array([j["at"] for j in d["joints"]])
    lo, hi = pts.min(0), pts.max(0)
    size = float(np.max(hi - lo)) or 1.0
    for link in d["links"]:
        link["mass"] = float(rng.uniform(0.1, 3.0))
        link["com"] = [float(c) for c in rng.uniform(lo - 0.2 * size, hi + 0.2 * size)]
        link["inertia"] = float(rng.uniform(0.01, 0.2) * link["mass"] * size ** 2)
    if loads:
        names = [ln["name"] for ln in d["links"]]
        d["loads"] = [
            {"link": str(rng.choice(names)),
             "force": [float(f) for f in rng.uniform(-50, 50, 2)],
             "at": [float(c) for c in rng.uniform(lo, hi)]},
            {"link": str(rng.choice(names)), "torque": float(rng.uniform(-5, 5) * size)},
        ]
    d["effects"] = {"inertia": True, "gravity": [0.0, -9.81] if gravity else [0.0, 0.0],
                    "loads": bool(loads)}
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    return d


def _compare_scene_dict(d, what):
    scene = load_scene(d)
    num = linkage_sym.analyze(scene)
    sym = compile_mechanism(scene).run()
    compare_analyses(scene, sym, num, what)
    return num


def _fourbar_ok(l1, l2, l3, l4, sigma):
    """Crank-rocker (Grashof, crank shortest) whose transmission angle stays
    at least 20 deg from 0 and 180 deg over the turn (kappa <= 3)."""
    th = np.linspace(0, 2 * np.pi, 721)
    bd2 = l1 ** 2 + l4 ** 2 - 2 * l1 * l4 * np.cos(th)
    cmu = (l2 ** 2 + l3 ** 2 - bd2) / (2 * l2 * l3)
    return np.all(np.abs(cmu) <= math.cos(math.radians(20)))


@pytest.mark.slow
@HYP
@given(l1=st.floats(0.2, 1.0), l2=st.floats(1.0, 4.0), l3=st.floats(1.0, 4.0),
       l4=st.floats(1.0, 4.0), sigma=st.sampled_from([1, -1]),
       rot=st.floats(-180, 180), seed=st.integers(0, 2 ** 32 - 1),
       accel=st.floats(-50, 50))
def test_random_fourbars(l1, l2, l3, l4, sigma, rot, seed, accel):
    assume(_fourbar_ok(l1, l2, l3, l4, sigma))
    d, _ = scenes.fourbar(l1, l2, l3, l4, steps=37, sigma=sigma, rotate_deg=rot,
                          origin=(0.3, -0.2), acceleration=accel)
    _with_dynamics(d, np.random.default_rng(seed))
    num = _compare_scene_dict(d, f"four-bar {(l1, l2, l3, l4, sigma)}")
    assert np.all(num.status == "ok")


@pytest.mark.slow
@HYP
@given(l1=st.floats(0.2, 1.0), ratio=st.floats(2.5, 6.0), e=st.floats(-0.9, 0.9),
       sigma=st.sampled_from([1, -1]), rot=st.floats(-180, 180),
       seed=st.integers(0, 2 ** 32 - 1))
def test_random_offset_slider_cranks(l1, ratio, e, sigma, rot, seed):
    """|e| < l1 < l2 / 2.5: assemblable over the whole turn, rod angle <= ~48 deg."""
    e = e * l1
    d, _ = scenes.slider_crank(l1, ratio * l1, e, steps=37, sigma=sigma, rotate_deg=rot)
    _with_dynamics(d, np.random.default_rng(seed))
    num = _compare_scene_dict(d, f"slider-crank {(l1, ratio * l1, e, sigma)}")
    assert np.all(num.status == "ok")


@pytest.mark.slow
@HYP
@given(l1=st.floats(0.3, 0.8), l2=st.floats(2.0, 3.0), l3=st.floats(1.5, 2.5),
       e_len=st.floats(0.5, 2.0), e_ang=st.floats(-150, 150),
       gx=st.floats(-3.0, 6.0), gy=st.floats(-4.0, 4.0), seed=st.integers(0, 2 ** 32 - 1),
       sigma2=st.sampled_from([1, -1]))
def test_random_watt_sixbars(l1, l2, l3, e_len, e_ang, gx, gy, seed, sigma2):
    l4 = 2.5
    assume(_fourbar_ok(l1, l2, l3, l4, 1))
    G = (gx, gy)
    try:
        d, _ = scenes.watt_sixbar(l1, l2, l3, l4, e_len=e_len, e_ang_deg=e_ang, G=G,
                                  sigma2=sigma2, steps=37)
    except ValueError:
        assume(False)
    _with_dynamics(d, np.random.default_rng(seed))
    num = _compare_scene_dict(d, f"Watt six-bar {(l1, l2, l3, e_len, e_ang, G, sigma2)}")
    assert np.all(num.status == "ok")


# =========================================================================== 3. substitution
EXACT_TOL = mp.mpf("1e-25")
B_TOL = 8 * EPS
CLOSED_TOL = (mp.mpf("1e-25") if tuple(map(int, sp.__version__.split(".")[:2])) >= (1, 14)
              else mp.mpf(8 * EPS))
"""Closed forms of the two derivations: the same expression (1e-25 at 40 digits) with SymPy
1.14 and later; older SymPy (1.12, 1.13) folds the scene's Float constants of the numeric
derivation in double precision, which rounds them like the force right-hand sides (8 eps)."""
SUBST = ["crank_rocker", "slider_crank_offset", "guide_bar_quick_return", "watt_sixbar"]


def _mp_fn(syms, exprs):
    return sp.lambdify(syms, exprs, modules="mpmath")


@pytest.mark.slow
@pytest.mark.parametrize("name", SUBST)
def test_symbolic_dimensions_substituted_equal_numeric_derivation(name):
    """``derive(scene, True)`` with the scene's values substituted equals
    ``derive(scene, False)`` block by block, in 40-digit mpmath at random
    points (x, rates, drivers, forces, assembly signs +-1), relative to the
    block's largest entry at that point:

    * Phi, A, B, acc_rhs, frame, the force blocks' A_g, C_g and the nested
      closed forms hold the *same* doubles in both: equal to 1e-25
      (observed: 0 or ~1e-45);
    * the right-hand sides b_g (weights, inertia forces, loads) are not:
      ``derive(scene, False)`` folds products of parameters (m*p, m*g, I ...)
      as SymPy Floats of the doubles' 53-bit precision when it builds them,
      while the substituted symbolic form multiplies them at 40 digits; the
      coefficients then differ by the rounding of those products
      (<= eps/2 each, a few per coefficient; observed <= 1.7e-19 of the
      block scale -- the expanded difference is exactly such coefficient
      round-off, no term differs).  Tolerance ``B_TOL = 8 eps``: any real
      structural difference (a missing or wrong term) is O(1)."""
    scene = linkage_sym.load_example(name)
    es = derive(scene, True, forces=True)
    en = derive(scene, False, forces=True)
    vals = es.parameter_values()
    assert vals and set(vals) == set(es.parameters)
    assert not en.parameters
    assert [s.name for s in es.x] == [s.name for s in en.x]
    sub = {k: sp.Float(v) for k, v in vals.items()}

    def blocks(e, substitute):
        f = (lambda m: m.xreplace(sub)) if substitute else (lambda m: m)
        out = {"Phi": f(e.Phi), "A": f(e.A), "B": f(e.B), "acc_rhs": f(e.acc_rhs),
               "frame": f(sp.Matrix(e.frame))}
        for k, (Ag, bg, Cg, later) in enumerate(e.force_blocks):
            out[f"A_{k}"], out[f"b_{k}"], out[f"C_{k}"] = f(Ag), f(bg), f(Cg)
        return out

    bs, bn = blocks(es, True), blocks(en, False)
    assert set(bs) == set(bn)
    for k in bs:
        assert bs[k].shape == bn[k].shape, k
    assert [[s.name for s in blk[3]] for blk in es.force_blocks] == \
        [[s.name for s in blk[3]] for blk in en.force_blocks]
    free = (es.x + es.xd + es.xdd + es.q + es.qd + es.qdd + list(es.all_forces) + es.sigmas)
    for k in bs:
        extra = (bs[k].free_symbols | bn[k].free_symbols) - set(free)
        assert not extra, f"{name} {k}: unexpected free symbols {extra}"
    keys = sorted(bs)
    fs = _mp_fn(free, [bs[k] for k in keys])
    fn = _mp_fn(free, [bn[k] for k in keys])
    # closed forms: at drivers the numeric solver assembles, in the scene's modes
    num = linkage_sym.analyze(scene)
    cs, cn = es.nested_closed_forms(), en.nested_closed_forms()
    assert [s.name for s in cs] == [s.name for s in cn]
    csyms = list(cs)
    cfs = _mp_fn(free, [cs[s].xreplace(sub) for s in csyms])
    cfn = _mp_fn(free, [cn[s] for s in csyms])
    rng = random.Random(name)
    ok_steps = [i for i in range(num.n_steps) if num.status[i] == "ok"]
    worst = 0.0
    with mp.workdps(40):
        for trial in range(3):
            point = [mp.mpf(rng.uniform(-3, 3)) for _ in free]
            for i, s in enumerate(free):
                if s in es.sigmas:
                    point[i] = mp.mpf(rng.choice([1, -1]))
            for k, a, b in zip(keys, fs(*point), fn(*point)):
                a, b = mp.matrix(a), mp.matrix(b)
                scale = max([abs(v) for v in b] + [mp.mpf(1e-30)])
                diff = max([abs(x - y) for x, y in zip(a, b)] + [mp.mpf(0)])
                tol = B_TOL if k.startswith("b_") else EXACT_TOL
                assert diff <= tol * scale, \
                    f"{name} {k}: |diff| {mp.nstr(diff, 3)} vs scale {mp.nstr(scale, 3)}"
                if not k.startswith("b_"):
                    worst = max(worst, float(diff / scale))
            # closed forms at a driver value the scene assembles, modes as compiled
            step = rng.choice(ok_steps)
            for i, s in enumerate(free):
                if s in es.q:
                    d = scene.drivers[es.q.index(s)]
                    point[i] = mp.mpf(float(num.drivers[d.joint]["q"][step]))
                if s in es.sigmas:
                    point[i] = mp.mpf(rng.choice([1, -1]))
            for s, a, b in zip(csyms, cfs(*point), cfn(*point)):
                if isinstance(a, mp.mpc) or isinstance(b, mp.mpc):  # other mode unassemblable
                    assert mp.almosteq(a, b, rel_eps=mp.mpf("1e-25"), abs_eps=mp.mpf("1e-25"))
                    continue
                assert abs(a - b) <= CLOSED_TOL * max(1, abs(b)), f"{name} closed form {s}"
    assert worst <= EXACT_TOL


def test_substitution_simplifies_to_zero():
    """A few small entries: ``simplify(symbolic.xreplace(values) - numeric) == 0``."""
    scene = linkage_sym.load_example("crank_rocker")
    es = derive(scene, True, forces=True)
    en = derive(scene, False, forces=True)
    sub = es.parameter_values()
    for i in range(es.Phi.rows):
        assert sp.simplify(es.Phi[i].xreplace(sub) - en.Phi[i]) == 0, i
    for i, j in [(0, 0), (1, 1), (2, 2)]:
        assert sp.simplify(es.A[i, j].xreplace(sub) - en.A[i, j]) == 0, (i, j)
    for a, b in zip(es.frame, en.frame):
        assert sp.simplify(a.xreplace(sub) - b) == 0


# =========================================================================== 5. cache
def _fourbar_scene(l, **kw):
    d, _ = scenes.fourbar(*l, steps=25, speed=7.0, acceleration=2.0, **kw)
    _with_dynamics(d, np.random.default_rng(7))
    return load_scene(d)


def test_cache_reuses_topology_without_deriving(monkeypatch):
    s1 = _fourbar_scene((0.5, 2.0, 1.6, 2.2), name="cache-topology-1")
    s2 = _fourbar_scene((0.3, 1.3, 1.9, 1.7), rotate_deg=33.0, name="cache-topology-2")
    cm1 = compile_mechanism(s1)
    compare_analyses(s1, cm1.run(), linkage_sym.analyze(s1), "cache: first scene")

    def refuse(scene):
        raise AssertionError("build_artifact called: the cache was not used")

    monkeypatch.setattr(cg_compile, "build_artifact", refuse)
    cm2 = compile_mechanism(s2)
    assert cm2.params != cm1.params
    compare_analyses(s2, cm2.run(), linkage_sym.analyze(s2), "cache: second scene")
    # use_cache=False derives anew
    calls = []
    monkeypatch.undo()
    real = cg_compile.build_artifact

    def counting(scene, **kw):
        calls.append(scene.name)
        return real(scene, **kw)

    monkeypatch.setattr(cg_compile, "build_artifact", counting)
    cm3 = compile_mechanism(s2, use_cache=False)
    assert calls == [s2.name]
    compare_analyses(s2, cm3.run(), linkage_sym.analyze(s2), "cache: use_cache=False")


def test_generated_functions_document_their_arguments():
    scene = linkage_sym.load_example("watt_sixbar")
    cm = compile_mechanism(scene)
    eqs = derive(scene, True, forces=True)
    assert cm.param_names == [s.name for s in eqs.parameters]
    assert len(cm.params) == len(cm.param_names) + len(eqs.sigmas)
    lists = {
        "X": eqs.x, "XD": eqs.xd, "XDD": eqs.xdd, "Q": eqs.q, "QD": eqs.qd, "QDD": eqs.qdd,
        "FORCES": eqs.all_forces,
    }
    p_line = "P = [" + ", ".join(cm.param_names + [s.name for s in eqs.sigmas]) + "]"
    assert {"rates", "points", "positions_0"} <= set(cm.functions)
    for fname, f in cm.functions.items():
        doc = inspect.getdoc(f)
        assert doc, fname
        pos = -1
        for label, syms in lists.items():
            line = f"{label} = [" + ", ".join(s.name for s in syms) + "]"
            at = doc.find(line)
            assert at > pos, f"{fname}: docstring lacks {line!r} (in order)"
            pos = at
        assert doc.find(p_line) > pos, f"{fname}: docstring lacks {p_line[:60]!r}..."
        params = list(inspect.signature(f).parameters)
        assert params[:8] == ["X", "XD", "XDD", "Q", "QD", "QDD", "FORCES", "P"], fname
    assert "X = [theta_crank, " in inspect.getdoc(cm.functions["rates"])
    src = inspect.getsource(cm.functions["rates"])
    assert src.startswith("def rates(") and "return" in src


# =========================================================================== 6. CLI
@pytest.mark.parametrize("name", ["slider_crank_offset",
                                  pytest.param("sixbar_class3", marks=pytest.mark.slow)])
def test_cli_symbolic_matches_dyad(name, tmp_path):
    from linkage_sym import cli
    from linkage_sym.examples import __file__ as ex_init

    path = os.path.join(os.path.dirname(ex_init), f"{name}.json")
    out_s, out_d = tmp_path / "sym.json", tmp_path / "dyad.json"
    assert cli.main(["analyze", path, "-o", str(out_s), "--method", "symbolic"]) in (0, None)
    assert cli.main(["analyze", path, "-o", str(out_d), "--method", "dyad"]) in (0, None)
    ds = json.loads(out_s.read_text())
    dd = json.loads(out_d.read_text())
    assert ds["force_method"] == "symbolic"
    scene = linkage_sym.load_example(name)
    compare_dicts(scene, ds, dd, f"CLI {name}")


