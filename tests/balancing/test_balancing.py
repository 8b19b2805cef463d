"""Balancing (issue 5): Song and Wang's [3] module, its assembly, and the force and moment conditions.

Every derived result is checked against something that shares no code with it:

* the link module against its defining identity (proved symbolically) and
  against Song and Wang's [3] printed eq. 6 (lines 2-4 as printed; line 1 with the
  OCR's ``-`` read as the product it must be);
* the assembled shaking moment and force (lambdified modules fed with the
  numeric kinematics) against the kinetostatic solver's frame moment and
  force with inertia as the only effect, on every shipped hinged example;
* the force conditions against Berkof and Lowen's four-bar conditions and
  Song and Wang's [3] eq. 14 (same solution set), and against the force solver: a
  design built from them has no shaking force, and breaking one condition
  brings it back.
"""

from __future__ import annotations

import dataclasses
import json
import random
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

import linkage_sym
from linkage_sym.balancing import Counterweight, optimize_counterweights, with_counterweights
from linkage_sym.balancing.assembly import shaking_moment
from linkage_sym.balancing.conditions import derive_balance
from linkage_sym.balancing.force import force_balance
from linkage_sym.balancing.force_counterweights import force_balancing_counterweights, solve_counterweights
from linkage_sym.balancing.module import check_identity, link_module
from linkage_sym.balancing.pins import BalanceModel
from linkage_sym.balancing.series import module_series
from linkage_sym.errors import BalanceError, SceneError
from linkage_sym.examples import example_dict, example_names, load_example
from linkage_sym.model import Effects
from linkage_sym.scene import load_scene
from tests.support.marks import slow_cases

HINGED = [n for n in example_names() if all(j["type"] == "R" for j in example_dict(n)["joints"])]
INERTIA_ONLY = Effects(inertia=True, gravity=None, loads=False)


def frame_loads(scene):
    """Shaking force and moment from the kinetostatic (dyad) solver."""
    res = linkage_sym.analyze(dataclasses.replace(scene, effects=INERTIA_ONLY))
    return res.forces.frame_force, res.forces.frame_moment


def peak(x):
    return float(np.nanmax(np.abs(x)))


# -- the module of one link ------------------------------------------------------
def test_module_identity_holds_symbolically():
    assert check_identity(link_module())


def test_module_matches_printed_eq6_up_to_its_ocr_error():
    """Song and Wang [3], eq. 6. Lines 2-4 are printed correctly; line 1 prints
    ``m/a^2 - [(a-p)^2 + q^2 + k^2]``, where dimensions demand the product."""
    mod = link_module()
    m, a, p, q, k = mod.m, mod.a, mod.p, mod.q, mod.k
    printed = (
        m / a**2 * ((a - p) ** 2 + q**2 + k**2),  # line 1, OCR '-' read as product
        m / a**2 * (a * p - (p**2 + q**2 + k**2)),
        m * q / a,
        m / a**2 * (p**2 + q**2 + k**2),
    )
    for derived, ref in zip(mod.mass_parameters, printed):
        assert sp.simplify(derived - ref) == 0
    # the OCR line as printed is wrong: it is not even of the right dimension
    assert sp.simplify(mod.mass_parameters[0] - (m / a**2 - ((a - p) ** 2 + q**2 + k**2))) != 0


def test_module_moment_of_a_rigid_body_in_plane_motion():
    """M_0 against -d/dt of the angular momentum by finite differences of a
    rigid body's motion (no module code involved in the reference)."""
    mod = link_module()
    f = sp.lambdify([mod.m, mod.a, mod.p, mod.q, mod.k, *mod.u, *mod.v], mod.M0)
    m, a, p, q, k = 1.3, 0.7, 0.2, -0.15, 0.25

    def motion(t):
        th = 0.4 + 1.1 * t + 0.3 * t**2
        xu, yu = 0.5 * np.cos(2 * t), 0.2 + 0.3 * t**2
        c, s = np.cos(th), np.sin(th)
        return th, np.array([xu, yu]), np.array([xu + a * c, yu + a * s]), np.array(
            [xu + p * c - q * s, yu + p * s + q * c])

    def H(t):  # angular momentum about the origin, by central differences of the motion
        h = 1e-5
        th0, _, _, s0 = motion(t)
        th1, _, _, s1 = motion(t + h)
        thm, _, _, sm = motion(t - h)
        v = (s1 - sm) / (2 * h)
        w = (th1 - thm) / (2 * h)
        return m * (s0[0] * v[1] - s0[1] * v[0]) + m * k**2 * w

    t, h = 0.37, 1e-3
    ref = -(H(t + h) - H(t - h)) / (2 * h)
    _, u, v, _ = motion(t)
    hh = 1e-4

    def acc(i):
        return (motion(t + hh)[i] - 2 * motion(t)[i] + motion(t - hh)[i]) / hh**2

    got = f(m, a, p, q, k, *u, *acc(1), *v, *acc(2))
    # finite differences of finite differences: about 1e-6 relative is all they give
    assert got == pytest.approx(ref, rel=1e-5)


# -- the assembled moment and force ----------------------------------------------
@pytest.mark.parametrize("name", slow_cases(HINGED, {"watt_sixbar", "song_wang_sixbar",
                                                     "sixbar_class3", "stephenson_sixbar"}))
def test_assembled_identities(name):
    sm = shaking_moment(load_example(name))
    msub = {sp.Symbol(n, real=True): e for n, e in sm.mass_parameters.items()}
    dsub = {D.symbol: D.expr for _, D in sm.terms}
    assert sp.expand(sm.expression.xreplace(msub).xreplace(dsub) - sm.explicit) == 0
    m = sm.model
    reg = sm.regrouped_expression().xreplace({m.phidd(l): sm.phidd_in_D(l) for l in m.links})
    assert sp.expand(reg.xreplace(dsub).xreplace(msub) - sm.explicit) == 0


@pytest.mark.parametrize("name", slow_cases(HINGED, {"sixbar_class3", "song_wang_sixbar",
                                                     "watt_sixbar"}))
def test_module_series_equal_frame_loads(name):
    """The issue's check: the modules' moment equals the kinetostatic frame
    moment (inertia only) at every step, <= 1e-9 of its peak; force likewise."""
    scene = load_example(name)
    s = module_series(scene)
    F, M = frame_loads(scene)
    assert np.array_equal(s.status, np.asarray(linkage_sym.analyze(scene).status))
    assert peak(s.moment - M) <= 1e-9 * peak(M)
    assert peak(s.force - F) <= 1e-9 * peak(F)


def test_prismatic_joint_is_refused_by_name():
    with pytest.raises(SceneError, match=r"joints\[2\] 'B_slide': a prismatic joint"):
        shaking_moment(load_example("shaper"))


# -- force balance conditions ----------------------------------------------------
def _linear_rows(conditions, links, values):
    """Coefficient rows of conditions that are linear in (m_j, m_j p_j, m_j q_j)."""
    subs, unknowns = {}, []
    for l in links:
        m, p, q = sp.symbols(f"m_{l} xG_{l} yG_{l}", real=True)
        S, T = sp.symbols(f"S_{l} T_{l}")
        mm = sp.Symbol(f"m_{l}", positive=True)
        subs.update({p: S / m, q: T / m, sp.Symbol(f"xG_{l}", real=True): S / mm,
                     sp.Symbol(f"yG_{l}", real=True): T / mm})
        unknowns += [mm, S, T]
    rows = []
    for c in conditions:
        e = sp.expand(sp.sympify(c).xreplace(subs))
        e = e.xreplace({sp.Symbol(f"m_{l}", real=True): sp.Symbol(f"m_{l}", positive=True) for l in links})
        e = e.xreplace(values)
        rows.append([sp.nsimplify(sp.diff(e, u)) for u in unknowns])
        assert sp.expand(e - sum(r * u for r, u in zip(rows[-1], unknowns))) == 0  # linear, no constant
    return sp.Matrix(rows)


def _same_solution_set(ours, theirs):
    r1, r2 = ours.rank(), theirs.rank()
    return r1 == r2 == ours.col_join(theirs).rank()


FOURBAR = {  # rocker listed D then C, so its frame runs D -> C as Berkof and Lowen's does
    "name": "fourbar-BL",
    "links": [{"name": "1", "mass": 0.2, "com": [0.01, 0.002], "inertia": 1e-5},
              {"name": "2", "mass": 0.5, "com": [0.05, 0.03], "inertia": 2e-4},
              {"name": "3", "mass": 0.3, "com": [0.08, 0.02], "inertia": 6e-5}],
    "joints": [{"name": "A", "type": "R", "links": ["ground", "1"], "at": [0, 0]},
               {"name": "B", "type": "R", "links": ["1", "2"], "at": [0.024, 0]},
               {"name": "D", "type": "R", "links": ["3", "ground"], "at": [0.078, 0]},
               {"name": "C", "type": "R", "links": ["2", "3"], "at": [0.066, 0.047]}],
    "drivers": [{"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360, "steps": 73, "speed": 10.0}],
    "effects": {"inertia": True},
}


def test_fourbar_conditions_are_berkof_lowen():
    """Berkof & Lowen (1969), J. Eng. Ind. 91(1): a four-bar's mass centre is
    stationary iff, in the frames A->B, B->C, D->C,
    m1 (p1, q1) = m2 (a1/a2) (p2 - a2, q2)   (crank CoM against the coupler's from C)
    m3 (p3, q3) = -m2 (a3/a2) (p2, q2)       (rocker CoM against the coupler's from B)."""
    fb = force_balance(load_scene(FOURBAR))
    a1, a2, a3 = sp.symbols("a_1 a_2 a_3", positive=True)
    m1, m2, m3 = sp.symbols("m_1 m_2 m_3", positive=True)
    p1, q1, p2, q2, p3, q3 = sp.symbols("xG_1 yG_1 xG_2 yG_2 xG_3 yG_3", real=True)
    bl = [m1 * p1 - m2 * a1 / a2 * (p2 - a2), m1 * q1 - m2 * a1 / a2 * q2,
          m3 * p3 + m2 * a3 / a2 * p2, m3 * q3 + m2 * a3 / a2 * q2]
    vals = {a1: sp.Rational(3, 7), a2: sp.Rational(11, 5), a3: sp.Rational(13, 9)}
    ours = _linear_rows([c.expr for c in fb.conditions], "123", vals)
    theirs = _linear_rows(bl, "123", vals)
    assert ours.shape[0] == 4 and _same_solution_set(ours, theirs)


def test_song_wang_sixbar_conditions_are_its_eq14():
    """Song and Wang [3], eq. 14 (from its ref. [1]), for the six-bar of its Fig. 2."""
    fb = force_balance(load_example("song_wang_sixbar"))
    m = {i: sp.Symbol(f"m_{i}", positive=True) for i in range(1, 6)}
    a = {i: sp.Symbol(f"a_{i}", positive=True) for i in range(1, 6)}
    p = {i: sp.Symbol(f"xG_{i}", real=True) for i in range(1, 6)}  # the paper's p_i, q_i
    q = {i: sp.Symbol(f"yG_{i}", real=True) for i in range(1, 6)}
    eq14 = [
        m[1] * q[1] / a[1] - m[2] * q[2] / a[2],
        m[4] * q[4] / a[4] + m[5] * q[5] / a[5],
        m[2] * q[2] / a[2] + m[3] * q[3] / a[3] - m[4] * q[4] / a[4],
        m[1] * p[1] / a[1] + m[2] * (a[2] - p[2]) / a[2],
        m[2] * p[2] / a[2] + m[3] * p[3] / a[3] + m[4] * (a[4] - p[4]) / a[4],
        m[4] * p[4] / a[4] + m[5] * p[5] / a[5],
    ]
    vals = {a[i]: sp.Rational(random.Random(i).randint(20, 90), 7) for i in range(1, 6)}
    ours = _linear_rows([c.expr for c in fb.conditions], "12345", vals)
    theirs = _linear_rows(eq14, "12345", vals)
    assert ours.shape[0] == 6 and _same_solution_set(ours, theirs)


@pytest.mark.slow
@pytest.mark.parametrize("name", HINGED)
def test_force_balanced_design_has_no_shaking_force(name):
    """Counterweights from the derived conditions: the force solver's shaking
    force <= 1e-9 of the unbalanced peak; 1 % more mass on one of them
    brings back a shaking force above 1e-4 of it."""
    scene = load_example(name)
    cws = force_balancing_counterweights(scene)
    F0, _ = frame_loads(scene)
    F1, _ = frame_loads(load_scene(with_counterweights(scene, cws)))
    assert peak(F1) <= 1e-9 * peak(F0)
    c = cws[0]
    broken = [Counterweight(c.link, 1.01 * c.mass, c.at)] + cws[1:]
    F2, _ = frame_loads(load_scene(with_counterweights(scene, broken)))
    assert peak(F2) >= 1e-4 * peak(F0)


@pytest.mark.slow
def test_counterweights_on_too_few_links_are_refused():
    with pytest.raises(BalanceError, match="cannot all hold with counterweights on crank, rocker only"):
        solve_counterweights(load_example("watt_sixbar"), derive_balance(load_example("watt_sixbar")),
                             ["crank", "rocker"])


# -- moment ----------------------------------------------------------------------
def test_fourbar_remaining_moment_is_eq18():
    """With the force balanced by the derived counterweights and q = 0 on every
    link, the force solver's shaking moment is eq. 18's -sum X_j phi''_j
    with phi''_j from the numeric kinematics (<= 1e-9 of its peak)."""
    data = json.loads(json.dumps(FOURBAR))
    # put every CoM on its link line (q = 0): then the force design needs q = 0 too
    data["links"][0]["com"] = [0.012, 0.0]
    B, C = np.array([0.024, 0.0]), np.array([0.066, 0.047])
    data["links"][1]["com"] = list(B + 0.4 * (C - B))
    Dp = np.array([0.078, 0.0])
    data["links"][2]["com"] = list(Dp + 0.5 * (C - Dp))
    scene = load_scene(data)
    b = derive_balance(scene)
    cws = force_balancing_counterweights(scene, b)
    new = load_scene(with_counterweights(scene, cws))
    F, M = frame_loads(new)
    assert peak(F) <= 1e-9 * peak(frame_loads(scene)[0])
    res = linkage_sym.analyze(dataclasses.replace(new, effects=INERTIA_ONLY))
    vals = BalanceModel(new).values()
    X = {l: float(b.moment.X[l].xreplace({s: vals[s.name] for s in b.moment.X[l].free_symbols})) for l in "123"}
    eq18 = -sum(X[l] * res.links[l].alpha for l in "123")
    assert peak(M - eq18) <= 1e-9 * peak(M)
    assert b.remaining.has(sp.Symbol("phidd_2", real=True))


def test_song_wang_conditions_reproduce_eq13_15_18():
    b = derive_balance(load_example("song_wang_sixbar"))
    # eqs. 10-11: the vanishing and the merged acceleration parameters
    assert set(b.moment.vanishing) == {"D_AB_1", "D_AB_2", "D_AB_3", "D_DC_1", "D_FE_1"}
    assert dict(b.moment.merged) == {"D_AB_4": ("D_BC_1",), "D_BC_4": ("D_DC_4", "D_CE_1"),
                                     "D_CE_4": ("D_FE_4",)}
    names = [c.name for c in b.moment_conditions]
    assert {"yG_2", "yG_4"} <= set(names)  # eq. 13 (the paper's q_2 = q_4 = 0)
    assert not b.pin_residuals  # force balance cancels every pin share: eq. 18 holds
    X = {i: sp.Symbol(f"m_{i}", positive=True) * (sp.Symbol(f"xG_{i}", real=True) ** 2
         + sp.Symbol(f"k_{i}", nonnegative=True) ** 2
         - sp.Symbol(f"a_{i}", positive=True) * sp.Symbol(f"xG_{i}", real=True)) for i in range(1, 6)}
    eq18 = -sum(X[i] * sp.Symbol(f"phidd_{i}", real=True) for i in range(1, 6))
    assert sp.expand(b.remaining - eq18) == 0
    # eq. 15: with q2 = q4 = 0 the force conditions give q1 = q3 = q5 = 0
    for i in (1, 3, 5):
        assert b.force_solution[sp.Symbol(f"yG_{i}", real=True)] == 0
    # the input crank turns at constant speed: no X condition for it
    assert "X_1" not in names and {"X_2", "X_3", "X_4", "X_5"} <= set(names)


# -- optimiser against the exact solution --------------------------------------------
@pytest.mark.slow
def test_optimiser_matches_exact_counterweights():
    """Where full force balance is possible, the optimiser (force weight only,
    counterweights on the pivoted links) reaches the exact solution: same
    first moments about the pivots (1e-6 relative: the optimiser's tolerance)."""
    scene = load_example("crank_rocker")
    exact = force_balancing_counterweights(scene)
    # 0.37 kg on the 0.2 kg crank: the mechanism's mass as the bound (default: the link's own)
    res = optimize_counterweights(scene, links=["crank", "rocker"], weights=(1.0, 0.0, 0.0),
                                  max_mass=1.0)
    frames = {"crank": (0.0, 0.0)}
    a_r = derive_balance(scene).model.values()["a_rocker"]
    frames["rocker"] = (a_r, 0.0)  # the rocker turns about D, its frame's v
    for link, pivot in frames.items():
        e = next(c for c in exact if c.link == link)
        o = next(c for c in res.counterweights if c.link == link)
        me = e.mass * (np.array(e.at) - pivot)
        mo = o.mass * (np.array(o.at) - pivot)
        assert np.allclose(mo, me, rtol=1e-6, atol=1e-6 * np.abs(me).max())
    assert res.objective <= res.objective_start


# -- command line ------------------------------------------------------------------
@pytest.mark.slow
def test_cli_balance_json(tmp_path):
    out = tmp_path / "b.json"
    r = subprocess.run([sys.executable, "-m", "linkage_sym", "balance",
                        str(linkage_sym.examples.example_path("song_wang_sixbar")), "-o", str(out), "--latex"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    d = json.loads(out.read_text())
    for key in ("symbols", "link_frames", "mass_parameters", "shaking_moment",
                "force_balance_conditions", "moment_balance_conditions", "series", "latex"):
        assert key in d
    assert d["link_frames"]["3"] == {"u": "D", "v": "C"} and d["link_frames"]["4"]["u"] == "C2"
    for s in ("m_1", "xG_1", "yG_1", "k_1", "a_1"):
        assert s in d["symbols"]
    exprs = (d["force_balance_conditions"] + d["moment_balance_conditions"]
             + list(d["mass_parameters"].values()) + [d["shaking_moment"]["assembled"],
                                                     d["shaking_moment"]["force_balanced"]])
    for e in exprs:
        assert isinstance(sp.sympify(e), sp.Expr)
    scene = load_example("song_wang_sixbar")
    _, M = frame_loads(scene)
    got = np.array([np.nan if v is None else v for v in d["series"]["shaking_moment"]])
    assert peak(got - M) <= 1e-9 * peak(M)


@pytest.mark.slow
def test_cli_balance_refuses_prismatic_and_writes_nothing(tmp_path):
    out = tmp_path / "b.json"
    r = subprocess.run([sys.executable, "-m", "linkage_sym", "balance",
                        str(linkage_sym.examples.example_path("slider_crank_offset")), "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "prismatic" in r.stderr and not out.exists()


@pytest.mark.slow
def test_cli_balance_writes_balanced_and_optimised_scenes(tmp_path):
    out, bal, opt = tmp_path / "b.json", tmp_path / "bal.json", tmp_path / "opt.json"
    r = subprocess.run([sys.executable, "-m", "linkage_sym", "balance",
                        str(linkage_sym.examples.example_path("crank_rocker")), "-o", str(out),
                        "--balanced-scene", str(bal), "--optimize", str(opt), "--max-mass", "0.3"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    F, _ = frame_loads(load_scene(str(bal)))
    assert peak(F) <= 1e-9 * peak(frame_loads(load_example("crank_rocker"))[0])
    d = json.loads(out.read_text())["optimized"]
    assert d["objective"] <= d["objective_start"]
    assert all(c["mass"] <= 0.3 for c in d["counterweights"])
    load_scene(str(opt))  # a valid scene


def _momentum_force(scene):
    """-sum m a_G over the moving links, from the kinematics (no force solver)."""
    res = linkage_sym.analyze(dataclasses.replace(scene, outputs=("kinematics",)))
    return -sum(link.mass * res.links[link.name].com_acceleration
                for link in scene.links if link.mass > 0)


@pytest.mark.slow
def test_cli_balance_optimises_a_slider_crank(tmp_path):
    """Prismatic joints: no module, so no derived conditions (the JSON says why), but
    --optimize runs.  With the force weight only, full force balance is possible (rod and
    crank counterweights): the optimised scene's shaking force, as -sum m a_G from its
    kinematics, is <= 1e-9 of the original's peak; the JSON's series come from the force
    solver and equal -sum m a_G to 1e-9 of the peak."""
    out, opt, pics = tmp_path / "b.json", tmp_path / "opt.json", tmp_path / "pics"
    src = linkage_sym.examples.example_path("slider_crank_offset")
    r = subprocess.run([sys.executable, "-m", "linkage_sym", "balance", str(src), "-o", str(out),
                        "--optimize", str(opt), "--weights", "1,0,0", "--plots", str(pics),
                        "--links", "crank,connecting_rod", "--max-mass", "3"],  # the mechanism's mass
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    d = json.loads(out.read_text())
    assert d["conditions_derived"] is False and "prismatic" in d["reasons"]["conditions"]
    assert {c["link"] for c in d["optimized"]["counterweights"]} <= {"crank", "connecting_rod"}
    before = _momentum_force(load_example("slider_crank_offset"))
    after = _momentum_force(load_scene(str(opt)))
    assert peak(after) <= 1e-9 * peak(before)
    got = np.array([[np.nan, np.nan] if v is None else v for v in d["series"]["shaking_force"]])
    assert peak(got - before) <= 1e-9 * peak(before)
    assert d["optimized"]["objective"] <= d["optimized"]["objective_start"]
    assert sorted(p.name for p in pics.iterdir()) == [
        "slider-crank-offset_shaking_force_polar.png", "slider-crank-offset_shaking_moment.png"]


@pytest.mark.slow
def test_cli_balance_refuses_latex_for_a_slider_crank(tmp_path):
    out, opt = tmp_path / "b.json", tmp_path / "opt.json"
    src = linkage_sym.examples.example_path("slider_crank_offset")
    r = subprocess.run([sys.executable, "-m", "linkage_sym", "balance", str(src), "-o", str(out),
                        "--optimize", str(opt), "--latex"], capture_output=True, text=True)
    assert r.returncode == 2 and "--latex" in r.stderr and "hinged" in r.stderr
    assert not out.exists() and not opt.exists()


# a command line each: the --weights and --max-mass refusals also run in the fast lane in
# tests/cli/test_cli_robustness.py, here in the default run
@pytest.mark.parametrize("args, message", [
    pytest.param(["--weights", "1,0"], "--weights", marks=pytest.mark.slow),
    pytest.param(["--weights", "0,0,0"], "--weights", marks=pytest.mark.slow),
    (["--links", "crank,cuopler"], "--links: 'cuopler' not among"),
    (["--links", "crank,crank"], "listed twice"),
    pytest.param(["--max-mass", "-1"], "--max-mass", marks=pytest.mark.slow),
])
def test_cli_balance_refuses_bad_optimise_options_and_writes_nothing(tmp_path, args, message):
    out, bal, opt = tmp_path / "b.json", tmp_path / "bal.json", tmp_path / "opt.json"
    r = subprocess.run([sys.executable, "-m", "linkage_sym", "balance",
                        str(linkage_sym.examples.example_path("crank_rocker")), "-o", str(out),
                        "--balanced-scene", str(bal), "--optimize", str(opt), *args],
                       capture_output=True, text=True)
    assert r.returncode == 2 and message in r.stderr, r.stderr
    assert not any(p.exists() for p in (out, bal, opt))
