"""Counterweights and partial balancing (linkage_sym.balancing: counterweight, cycle, options, search).

Every check compares with something that shares no code with the thing
tested:

* :class:`CycleModel` (one kinematic run, then linear maps) against the
  numeric force solver run afresh on the scene that
  :func:`with_counterweights` writes;
* :func:`with_counterweights` against mass, first and second moments summed
  here from the scene's own numbers (the link frame is rebuilt here from the
  joints, the inertia is summed about the origin rather than by the parallel
  axis theorem about the new centre);
* the optimiser against the start (never worse), its bounds, the force
  solver on the scene it returns, and for full force balance of a four-bar
  against the Berkof–Lowen conditions derived in :func:`berkof_lowen` and a
  linear least-squares fit over the cycle.
"""

from __future__ import annotations

import copy
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import linkage_sym
from linkage_sym.balancing import (
    Counterweight,
    CycleModel,
    OptionsError,
    default_bounds,
    optimize_counterweights,
    search_options,
    with_counterweights,
)
from linkage_sym.examples import example_dict

EVAL_TOL = 1e-9  # relative to the peak of each series: CycleModel is exact up to rounding


# -- helpers (independent of the module under test) -------------------------------
def frame_of(scene: dict, link: str):
    """Origin (first joint of the link in scene order) and unit x (toward the next
    joint at a different point) of a link frame, read off the scene dict."""
    js = [j for j in scene["joints"] if link in j["links"]]
    u = np.array(js[0]["at"], float)
    for j in js[1:]:
        d = np.array(j["at"], float) - u
        if np.hypot(*d) > 1e-12:
            return u, d / np.hypot(*d)
    return u, np.array([1.0, 0.0])


def to_global(scene: dict, cw: Counterweight) -> np.ndarray:
    u, ex = frame_of(scene, cw.link)
    ey = np.array([-ex[1], ex[0]])
    return u + cw.at[0] * ex + cw.at[1] * ey


def with_effects(scene: dict, **effects) -> dict:
    s = copy.deepcopy(scene)
    s["effects"] = effects
    s["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    return s


def solver_series(scene: dict):
    """Shaking force and moment (inertia only) and driver efforts (scene's effects)
    of a scene dict, from the numeric force solver."""
    shaking = linkage_sym.analyze(linkage_sym.load_scene(with_effects(scene, inertia=True, loads=False)))
    own = copy.deepcopy(scene)
    own["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    efforts = linkage_sym.analyze(linkage_sym.load_scene(own))
    return shaking, efforts


def repeats_first_step(scene: dict) -> bool:
    """A sweep over whole turns of every R driver (P drivers still, no gears): its last
    step is its first again, and a cycle average counts it once."""
    if any(j["type"] == "G" for j in scene["joints"]):
        return False
    turns = [(d["stop_deg"] - d["start_deg"]) / 360.0 if "start_deg" in d
             else float(d["stop"] != d["start"]) * 0.5 for d in scene["drivers"]]
    return all(t == round(t) for t in turns) and any(t != 0 for t in turns)


def rms_of(shaking, efforts, scene: dict) -> dict:
    ok = shaking.ok & efforts.ok
    if repeats_first_step(scene) and ok[0]:
        ok[-1] = False
    F = shaking.forces.frame_force[ok]
    M = shaking.forces.frame_moment[ok]
    T = np.stack([v[ok] for v in efforts.forces.driving.values()], axis=1)
    return {
        "force": math.sqrt(np.mean(np.sum(F ** 2, axis=1))),
        "moment": math.sqrt(np.mean(M ** 2)),
        "driving": math.sqrt(np.mean(np.sum(T ** 2, axis=1))),
    }


def random_counterweights(scene: dict, rng) -> list[Counterweight]:
    L = max(
        math.dist(a["at"], b["at"]) for a in scene["joints"] for b in scene["joints"]
    )
    cws = [
        Counterweight(link["name"], rng.uniform(0.05, 0.5), tuple(rng.uniform(-L, L, 2)))
        for link in scene["links"]
    ]
    first = scene["links"][0]["name"]  # two on one link: both must count
    cws.append(Counterweight(first, rng.uniform(0.05, 0.3), tuple(rng.uniform(-L, L, 2))))
    return cws


def assert_series_close(got, want, what):
    got, want = np.asarray(got), np.asarray(want)
    assert np.array_equal(np.isnan(got), np.isnan(want)), what
    ok = ~np.isnan(want)
    peak = np.max(np.abs(want[ok]))
    err = np.max(np.abs(got[ok] - want[ok]))
    assert err <= EVAL_TOL * peak, f"{what}: error {err:.3g} vs peak {peak:.3g}"


def check_model_against_solver(scene: dict, cws):
    model = CycleModel(linkage_sym.load_scene(scene))
    ev = model.evaluate(cws)
    shaking, efforts = solver_series(with_counterweights(scene, cws))
    assert_series_close(ev["force"], shaking.forces.frame_force, "shaking force")
    assert_series_close(ev["moment"], shaking.forces.frame_moment, "shaking moment")
    assert set(ev["driving"]) == set(efforts.forces.driving)
    for k, v in efforts.forces.driving.items():
        assert_series_close(ev["driving"][k], v, f"effort of driver {k}")
    got, want = model.rms(cws), rms_of(shaking, efforts, scene)
    for k in want:
        assert got[k] == pytest.approx(want[k], rel=EVAL_TOL)
    return model, shaking


# -- CycleModel == the force solver ------------------------------------------------
@pytest.mark.parametrize("name", ["crank_rocker", "watt_sixbar", "stephenson_sixbar", "fivebar"])
def test_cycle_model_matches_force_solver(name):
    """Random counterweights on every link (two on the first): force and moment
    with inertia only, efforts with the scene's effects (inertia, gravity and
    loads in these examples), all to 1e-9 of the series' peak."""
    scene = example_dict(name)
    rng = np.random.default_rng(sum(map(ord, name)))
    for _ in range(2):
        check_model_against_solver(scene, random_counterweights(scene, rng))


@pytest.mark.parametrize(
    "effects",
    [
        {"inertia": False, "gravity": [0.0, -9.81], "loads": True},  # weight only: (a - g) -> -g
        {"inertia": True, "loads": False},  # no gravity
        {"inertia": False, "gravity": [3.0, -9.81], "loads": False},
    ],
)
def test_driver_efforts_follow_the_scene_effects(effects):
    scene = example_dict("crank_rocker")
    scene["effects"] = effects
    check_model_against_solver(scene, random_counterweights(scene, np.random.default_rng(7)))


def test_prismatic_joints_and_two_drivers_of_other_kinds():
    """A slider-crank (P joint, a link whose joints coincide) and a P-driven boom."""
    for name in ("slider_crank_offset", "hydraulic_boom"):
        scene = example_dict(name)
        check_model_against_solver(scene, random_counterweights(scene, np.random.default_rng(3)))


def non_grashof_scene() -> dict:
    """The crank-rocker with a longer crank (B moved): non-Grashof, so the crank
    cannot turn fully and part of the sweep cannot be assembled."""
    scene = example_dict("crank_rocker")
    for j in scene["joints"]:
        if j["name"] == "B":
            j["at"] = [0.04, 0.0]
    return scene


def test_steps_that_are_not_ok_are_left_out():
    scene = non_grashof_scene()
    model, shaking = check_model_against_solver(
        scene, random_counterweights(scene, np.random.default_rng(11))
    )
    assert 0 < model.n_excluded < model.n_steps
    assert model.n_excluded == int((~shaking.ok).sum())
    assert np.array_equal(model.ok, shaking.ok)
    ev = model.evaluate([])
    assert np.all(np.isnan(ev["moment"][~model.ok])) and np.all(np.isfinite(ev["moment"][model.ok]))
    res = optimize_counterweights(scene, weights=(1, 1, 0))
    assert res.n_excluded == model.n_excluded
    assert res.objective <= res.objective_start


# -- with_counterweights -----------------------------------------------------------
def test_with_counterweights_preserves_mass_and_first_moment_and_adds_inertia():
    scene = example_dict("watt_sixbar")
    scene["links"][0] = {"name": "crank", "mass": 0.0, "inertia": 0.0}  # a massless link
    rng = np.random.default_rng(5)
    cws = random_counterweights(scene, rng)
    out = with_counterweights(scene, cws, name="cw")
    assert out["name"] == "cw"
    linkage_sym.load_scene(out)  # loads back
    assert out["joints"] == scene["joints"] and out["drivers"] == scene["drivers"]
    before = {l["name"]: l for l in scene["links"]}
    total_mass = total_first = 0.0
    for link in out["links"]:
        old = before[link["name"]]
        mine = [(cw.mass, to_global(scene, cw)) for cw in cws if cw.link == link["name"]]
        m_old = old.get("mass", 0.0)
        c_old = np.array(old.get("com", [0.0, 0.0]), float)
        m = m_old + sum(mu for mu, _ in mine)
        first = m_old * c_old + sum(mu * p for mu, p in mine)
        # polar moment about the global origin is additive; the new inertia is that
        # minus the total mass at the new centre (Steiner, used backwards)
        polar = old.get("inertia", 0.0) + m_old * c_old @ c_old + sum(mu * p @ p for mu, p in mine)
        assert link["mass"] == pytest.approx(m, rel=1e-14)
        np.testing.assert_allclose(link["mass"] * np.array(link["com"]), first, rtol=1e-13, atol=1e-16)
        c_new = np.array(link["com"])
        assert link["inertia"] == pytest.approx(polar - m * c_new @ c_new, rel=1e-9)
        total_mass += link["mass"]
        total_first = total_first + link["mass"] * c_new
    assert total_mass == pytest.approx(
        sum(l.get("mass", 0.0) for l in scene["links"]) + sum(cw.mass for cw in cws), rel=1e-14
    )
    want = sum(l["mass"] * np.array(l["com"]) for l in scene["links"] if l.get("mass", 0.0) > 0)
    want = want + sum(cw.mass * to_global(scene, cw) for cw in cws)
    np.testing.assert_allclose(total_first, want, rtol=1e-13)


def test_with_counterweights_single_point_mass_by_hand():
    """A 0.2 kg mass at (-0.012, 0) on the crank (A at the origin, B on +x) puts the
    crank's centre at A; inertia 1e-5 + 0.2*0.012^2 + 0.2*0.012^2."""
    out = with_counterweights(example_dict("crank_rocker"), [Counterweight("crank", 0.2, (-0.012, 0.0))])
    crank = out["links"][0]
    assert crank["mass"] == pytest.approx(0.4)
    np.testing.assert_allclose(crank["com"], [0.0, 0.0], atol=1e-17)
    assert crank["inertia"] == pytest.approx(1e-5 + 2 * 0.2 * 0.012 ** 2, rel=1e-12)
    assert out["links"][1:] == example_dict("crank_rocker")["links"][1:]
    assert out["name"] == "crank-rocker with counterweights"


def test_invalid_counterweights_are_refused():
    with pytest.raises(ValueError, match="mass"):
        Counterweight("crank", -0.1, (0, 0))
    with pytest.raises(ValueError, match="no such moving link"):
        with_counterweights(example_dict("crank_rocker"), [Counterweight("ground", 0.1, (0, 0))])
    with pytest.raises(ValueError, match="outside the bounds"):
        optimize_counterweights(
            example_dict("crank_rocker"), links=["crank"], start=[Counterweight("crank", 5.0, (0, 0))]
        )
    with pytest.raises(ValueError, match="weights"):
        optimize_counterweights(example_dict("crank_rocker"), weights=(0, 0, 0))


# -- the optimiser ----------------------------------------------------------------
def assert_within_bounds(res, links):
    assert [cw.link for cw in res.counterweights] == list(links)
    for cw in res.counterweights:
        assert 0.0 <= cw.mass <= res.max_mass[cw.link] * (1 + 1e-12)
        assert max(abs(cw.at[0]), abs(cw.at[1])) <= res.max_radius[cw.link] * (1 + 1e-12)


@pytest.mark.parametrize("name", ["crank_rocker",
                                  pytest.param("watt_sixbar", marks=pytest.mark.slow)])
@pytest.mark.parametrize("weights", [(1, 1, 1), (0, 1, 0), (0.2, 0, 1)])
def test_optimiser_is_never_worse_than_the_start_and_respects_bounds(name, weights):
    scene = example_dict(name)
    links = [l["name"] for l in scene["links"]]
    res = optimize_counterweights(scene, weights=weights)
    assert res.objective <= res.objective_start
    assert res.objective_start == pytest.approx(sum(weights))  # normalised by the start
    assert_within_bounds(res, links)
    # the reported RMS values are those of the force solver on the scene returned
    got = rms_of(*solver_series(res.scene), res.scene)
    for k in got:
        assert res.rms_final[k] == pytest.approx(got[k], rel=1e-9)
    J = sum(w * res.rms_final[k] / res.scales[k] for w, k in zip(weights, ("force", "moment", "driving")))
    assert J == pytest.approx(res.objective, rel=1e-12)
    if res.objective_bound is not None:  # the convex relaxation is a lower bound
        assert res.objective_bound <= res.objective * (1 + 1e-6) + 1e-12


def test_optimiser_from_a_given_start_with_tight_bounds():
    scene = example_dict("watt_sixbar")
    links = ["crank", "rocker"]
    start = [Counterweight("crank", 0.05, (0.01, -0.02)), Counterweight("rocker", 0.02, (0.0, 0.03))]
    res = optimize_counterweights(
        scene, links=links, weights=(1, 0.5, 0.5), max_mass=0.06, max_radius={"crank": 0.03}, start=start
    )
    assert res.max_mass == {"crank": 0.06, "rocker": 0.06}
    assert res.max_radius["crank"] == 0.03
    assert res.max_radius["rocker"] == pytest.approx(default_bounds(linkage_sym.load_scene(scene))[1]["rocker"])
    assert_within_bounds(res, links)
    model = CycleModel(linkage_sym.load_scene(scene))
    start_rms = model.rms(start)
    assert res.rms_start == pytest.approx(start_rms, rel=1e-12)
    assert res.objective <= res.objective_start
    # restarting from the optimum cannot make it worse
    again = optimize_counterweights(
        scene, links=links, weights=(1, 0.5, 0.5), max_mass=0.06, max_radius={"crank": 0.03},
        start=list(res.counterweights), model=model,
    )
    assert again.objective <= again.objective_start
    assert again.objective_start == pytest.approx(sum((1, 0.5, 0.5)))


@pytest.mark.slow
def test_a_start_value_of_zero_is_normalised_by_the_gross_scale():
    """Start from a force-balanced design: rms_F0 ~ 1e-16, so the force term is
    normalised by the gross scale instead (else it would dominate by 1e16)."""
    scene = example_dict("crank_rocker")
    links = ["crank", "rocker"]
    # full force balance needs 0.37 kg on the 0.2 kg crank: the mechanism's mass as the bound
    balanced = optimize_counterweights(scene, links=links, weights=(1, 0, 0), max_mass=1.0)
    res = optimize_counterweights(scene, links=links, weights=(1, 1, 0), max_mass=1.0,
                                  start=list(balanced.counterweights))
    assert res.rms_start["force"] < 1e-12 * res.scales["force"]
    assert res.scales["force"] == pytest.approx(CycleModel(linkage_sym.load_scene(scene)).gross["force"])
    assert np.isfinite(res.objective_start) and res.objective <= res.objective_start


# -- full force balance of the four-bar (Berkof & Lowen 1969) -----------------------------
def berkof_lowen(scene: dict):
    """Counterweight first moments that force-balance a four-bar, by Berkof & Lowen.

    With the crank A->B (length a1, angle t1), coupler B->C (a2, t2), rocker
    D->C (a3, t3), each link's centre of mass written as a complex number in its
    own frame (crank z1 from A, coupler z2 from B, rocker z3 from D), the total
    first moment of mass is

        m1 (A + z1 e^{i t1}) + m2 (A + a1 e^{i t1} + z2 e^{i t2}) + m3 (D + z3 e^{i t3}).

    The loop closure a1 e^{i t1} + a2 e^{i t2} = (D - A) + a3 e^{i t3} eliminates
    e^{i t2} = ((D - A) + a3 e^{i t3} - a1 e^{i t1}) / a2, leaving

        const + e^{i t1} [m1 z1 + m2 a1 (1 - z2/a2)] + e^{i t3} [m3 z3 + m2 z2 a3/a2].

    t1 and t3 vary independently over the cycle (the rocker is not a function
    of the crank angle alone by a rigid rotation), so the total mass centre is
    stationary, and the shaking force -m_tot a_G zero, iff both brackets vanish:

        m1 z1 = m2 (a1/a2) (z2 - a2)   (z2 - a2: coupler centre measured from C, B->C frame)
        m3 z3 = -m2 (a3/a2) z2         (z2 measured from B)

    The counterweights supply the difference to the links' own first moments.
    Returns ``(crank cw first moment about A in the A->B frame, rocker cw first
    moment about D in the D->C frame)`` as complex numbers.
    """
    at = {j["name"]: complex(*j["at"]) for j in scene["joints"]}
    link = {l["name"]: l for l in scene["links"]}
    A, B, C, D = at["A"], at["B"], at["C"], at["D"]
    a1, a2, a3 = abs(B - A), abs(C - B), abs(C - D)
    e1, e2, e3 = (B - A) / a1, (C - B) / a2, (C - D) / a3  # unit x of each frame

    def com(name, origin, e):  # centre of mass in the frame (origin, x along e)
        return (complex(*link[name]["com"]) - origin) / e

    m1, m2, m3 = (link[n]["mass"] for n in ("crank", "coupler", "rocker"))
    z1, z2, z3 = com("crank", A, e1), com("coupler", B, e2), com("rocker", D, e3)
    crank_cw = m2 * (a1 / a2) * (z2 - a2) - m1 * z1
    rocker_cw = -m2 * (a3 / a2) * z2 - m3 * z3
    return crank_cw, rocker_cw


def least_squares_balance(scene: dict):
    """The same first moments by a linear least-squares fit over the cycle.

    A first moment c (link frame, about a fixed pivot) adds -(alpha k x - omega^2)(R c)
    to the shaking force; the four unknowns (crank about A, rocker about D, each in
    its A->B or D->C frame) are fitted so that the force solver's shaking force
    plus these terms vanishes at every step.
    """
    an = linkage_sym.analyze(linkage_sym.load_scene(with_effects(scene, inertia=True, loads=False)))
    at = {j["name"]: np.array(j["at"], float) for j in scene["joints"]}
    cols = []
    for name, u, v in (("crank", "A", "B"), ("rocker", "D", "C")):
        d = at[v] - at[u]
        lk = an.links[name]
        th = math.atan2(d[1], d[0]) + lk.rotation
        w, al = lk.omega, lk.alpha
        e1 = np.stack([np.cos(th), np.sin(th)], axis=1)
        e2 = np.stack([-np.sin(th), np.cos(th)], axis=1)
        f1 = al[:, None] * e2 - (w * w)[:, None] * e1  # acceleration per unit x
        f2 = -al[:, None] * e1 - (w * w)[:, None] * e2
        cols += [-f1, -f2]
    A = np.stack([c.ravel() for c in cols], axis=1)
    x, *_ = np.linalg.lstsq(A, -an.forces.frame_force.ravel(), rcond=None)
    residual = an.forces.frame_force.ravel() + A @ x
    return complex(x[0], x[1]), complex(x[2], x[3]), np.max(np.abs(residual))


def test_full_force_balance_of_the_crank_rocker_is_berkof_lowen():
    """Counterweights on the crank and the rocker, weights (1, 0, 0).

    The optimised RMS shaking force is <= 1e-6 of the start, and the counterweights'
    first moments about the fixed pivots equal the Berkof–Lowen values to 1e-6
    relative (the optimiser's tolerance; the least-squares polish in fact reaches
    rounding level).  The least-squares fit over the cycle gives the same values
    to 1e-9 and leaves a residual force at rounding level.
    """
    scene = example_dict("crank_rocker")
    crank_bl, rocker_bl = berkof_lowen(scene)
    crank_ls, rocker_ls, resid = least_squares_balance(scene)
    assert abs(crank_ls - crank_bl) <= 1e-9 * abs(crank_bl)
    assert abs(rocker_ls - rocker_bl) <= 1e-9 * abs(rocker_bl)
    assert resid <= 1e-12

    # full balance needs 0.37 kg on the 0.2 kg crank: the mechanism's mass as the bound
    res = optimize_counterweights(scene, links=["crank", "rocker"], weights=(1, 0, 0), max_mass=1.0)
    assert res.success
    assert res.rms_final["force"] <= 1e-6 * res.rms_start["force"]
    # the force solver agrees on the scene returned
    shaking, _ = solver_series(res.scene)
    F = shaking.forces.frame_force
    assert math.sqrt(np.mean(np.sum(F ** 2, axis=1))) <= 1e-6 * res.rms_start["force"]

    cw = {c.link: c for c in res.counterweights}
    # crank: link frame = A->B frame, origin at the pivot A
    crank = cw["crank"].mass * complex(*cw["crank"].at)
    # rocker: link frame has origin C and x toward D; D is at (|CD|, 0) there, and the
    # D->C frame is this one turned by half a turn (a vector z there is -z here)
    CD = math.dist(*(j["at"] for j in scene["joints"] if j["name"] in ("C", "D")))
    rocker_here = cw["rocker"].mass * (complex(*cw["rocker"].at) - CD)
    rocker = -rocker_here
    assert abs(crank - crank_bl) <= 1e-6 * abs(crank_bl)
    assert abs(rocker - rocker_bl) <= 1e-6 * abs(rocker_bl)


# -- the package's layout ------------------------------------------------------------
def test_the_former_optimize_module_re_exports_the_same_objects():
    import linkage_sym.balancing as balancing
    from linkage_sym.balancing import optimize

    for name in optimize.__all__:
        assert getattr(optimize, name) is getattr(balancing, name), name


def test_the_optimiser_runs_without_loading_sympy():
    """The package's names load their modules lazily: the NumPy/SciPy layer never pulls SymPy in."""
    code = (
        "import sys\n"
        "from linkage_sym.balancing import Counterweight, CycleModel, search_options\n"
        "from linkage_sym.examples import load_example\n"
        "scene = load_example('crank_rocker')\n"
        "search_options(scene)\n"
        "CycleModel(scene).rms([Counterweight('crank', 0.1, (-0.01, 0.0))])\n"
        "print('sympy' in sys.modules)\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       cwd=Path(__file__).resolve().parents[2])
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == ["False"]


def test_mean_square_factors_give_the_rms_of_the_cycle():
    scene = linkage_sym.load_scene(example_dict("watt_sixbar"))
    model = CycleModel(scene)
    links = ["rocker", "crank"]
    cws = [Counterweight("crank", 0.05, (0.01, -0.02)), Counterweight("rocker", 0.02, (0.0, 0.03))]
    p = model.parameters(cws).reshape(-1, 4)
    x = np.append(np.concatenate([p[model.links.index(n)] for n in links]), 1.0)
    factors = model.mean_square_factors(links)
    rms = model.rms(cws)
    for term, R in factors.items():
        assert np.linalg.norm(R @ x) == pytest.approx(rms[term], rel=1e-12)


def test_options_are_checked_in_one_place_with_every_problem_at_once():
    scene = example_dict("crank_rocker")
    with pytest.raises(OptionsError) as err:
        optimize_counterweights(scene, links=["crank", "crank"], weights=(1, -1, 0), max_mass={"rocker": 1.0},
                                max_radius=float("inf"))
    assert [o for o, _ in err.value.problems] == ["weights", "links", "max_mass", "max_radius"]
    with pytest.raises(OptionsError) as again:
        search_options(scene, links=["crank", "crank"], weights=(1, -1, 0), max_mass={"rocker": 1.0},
                       max_radius=float("inf"))
    assert again.value.problems == err.value.problems
    ok = search_options(scene, links=["rocker"], weights=("1", "0", "0.5"), max_mass={"rocker": 0.2})
    assert ok.links == ("rocker",) and ok.weights == (1.0, 0.0, 0.5) and ok.max_mass == {"rocker": 0.2}
    assert ok.max_radius == {"rocker": default_bounds(linkage_sym.load_scene(scene))[1]["rocker"]}


# -- default bounds relative to the links' own masses ---------------------------------
def test_default_mass_bounds_are_the_links_own_masses_and_scale_with_them():
    """The default bound of every counterweight was the mechanism's total moving mass, so
    the optimiser put up to three times the mechanism's mass on a guide-bar quick-return
    (0.516, 0.57 and 0.57 kg on its 0.57 kg).  Now each link's own mass, read here from
    the scene dict; a massless link gets the mean moving-link mass; ten times every mass
    gives ten times every bound (1e-15 relative: one product)."""
    d = example_dict("guide_bar_quick_return")
    mm, _ = default_bounds(linkage_sym.load_scene(copy.deepcopy(d)))
    assert mm == {link["name"]: link["mass"] for link in d["links"]}
    heavy = copy.deepcopy(d)
    for link in heavy["links"]:
        link["mass"] *= 10
        link["inertia"] = link.get("inertia", 0.0) * 10
    mm10, _ = default_bounds(linkage_sym.load_scene(heavy))
    for n in mm:
        assert mm10[n] == pytest.approx(10 * mm[n], rel=1e-15)
    massless = copy.deepcopy(d)
    massless["links"][1]["mass"] = 0.0
    massless["links"][1]["inertia"] = 0.0
    mm0, _ = default_bounds(linkage_sym.load_scene(massless))
    rest = [link["mass"] for link in massless["links"]]
    assert mm0[d["links"][1]["name"]] == pytest.approx(sum(rest) / len(rest), rel=1e-15)
    res = search_options(linkage_sym.load_scene(copy.deepcopy(d)))
    assert res.max_mass == mm


@pytest.mark.slow
def test_an_optimisation_that_did_not_converge_is_reported(tmp_path, capsys):
    """'the convex relaxation did not converge' appeared only inside the JSON's message:
    it is now in the result's notes and printed as a warning line (in the summary, or on
    standard error when the JSON goes to standard output).  A massless guide-bar has
    nothing to balance (J = 0 everywhere): the relaxation's solver stops without
    converging."""
    from linkage_sym.cli import main

    scene, opt = tmp_path / "g.json", tmp_path / "opt.json"
    assert main(["new", "guide-bar", "--crank", "0.03", "--ground", "0.06", "--steps", "13",
                 "-o", str(scene)]) == 0
    res = optimize_counterweights(linkage_sym.load_scene(scene))
    assert res.notes == ("the convex relaxation did not converge",) and res.objective_bound is None
    capsys.readouterr()
    assert main(["balance", str(scene), "--optimize", str(opt)]) == 0
    out = capsys.readouterr().out
    assert "warning: optimisation: the convex relaxation did not converge" in out.splitlines()
    assert main(["balance", str(scene), "--optimize", str(opt), "-o", "-"]) == 0
    got = capsys.readouterr()
    assert "warning: optimisation: the convex relaxation did not converge" in got.err.splitlines()
    assert json.loads(got.out)["optimized"]["notes"] == ["the convex relaxation did not converge"]
