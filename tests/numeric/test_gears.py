"""Gear meshes (``G`` joints, issue 20): format, structure, kinematics, forces.

Independent checks, none sharing code with the solver:

* planetary ratios against the Willis formula, written here:
  ``(w_s - w_c) / (w_r - w_c) = -r_r / r_s`` (and the accelerations alike);
* a gear pair against its equivalent four-bar at an instant (the involute
  profiles' centres of curvature, the feet of the base circles on the line
  of action, as the coupler's pins), solved by the closed-form dyad;
* a gear pair's driving torque and tooth load against their closed forms,
  ``T_in = T_out r_1 / r_2``, ``Fn = T_out / (r_2 cos(phi))``;
* every shipped example (the planetary train, the gear-linkage of example
  3-3) through the contract test of ``test_kinetostatics.py``: the global
  solve extended by the mesh constraint, each link's equilibrium, the power
  balance and the mesh force on its line of action (``force_checks``).

Tolerances: 1e-12 relative for kinematics (closed forms and Newton to
1e-13 on well-conditioned groups), 1e-9 for forces as in the contract test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym import compile_plan, load_scene
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict
from linkage_sym.structure import decompose
from tests.support.force_checks import (dyad_and_global_checked, max_rel, mesh_residuals, power_residual,
                          reaction_scale)

TOL_KIN = 1e-12
TOL_F = 1e-9


def gear_pair(r1=0.03, r2=0.05, internal=False, torque=-2.0, phi=20.0, steps=73):
    """Pinion ``p`` driven about A, gear ``g`` about B on the ground, a torque on ``g``."""
    d = abs(r2 - r1) if internal else r1 + r2
    return {
        "name": "pair",
        "links": [
            {"name": "p", "mass": 0.2, "com": [0.0, 0.0], "inertia": 1e-4},
            {"name": "g", "mass": 0.5, "com": [d, 0.0], "inertia": 6e-4},
        ],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "p"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["ground", "g"], "at": [d, 0.0]},
            {"name": "M", "type": "G", "links": ["p", "g"], "radii": [r1, r2],
             "internal": internal, "pressure_angle_deg": phi},
        ],
        "drivers": [{"joint": "A", "toward": "M", "start_deg": 0, "stop_deg": 360,
                     "steps": steps, "speed": 12.0, "acceleration": 3.0}],
        "loads": [{"link": "g", "torque": torque}],
        "effects": {"inertia": False, "gravity": False, "loads": True},
    }


def planetary(driven="sun", ring_fixed=True):
    """Sun (r 0.03), planet (0.015) on an arm, ring (0.06): the shipped train, or variants."""
    d = example_dict("planetary_train")
    if driven == "arm":
        d["drivers"] = [{"joint": "O_arm", "toward": "C", "start_deg": 0, "stop_deg": 360,
                         "steps": 91, "speed": 7.0, "acceleration": -2.0}]
    if not ring_fixed:  # the ring a moving link of its own, driven too
        d["links"].append({"name": "ring", "mass": 1.0, "com": [0.0, 0.0], "inertia": 4e-3})
        d["joints"].append({"name": "O_ring", "type": "R", "links": ["ground", "ring"],
                            "at": [0.0, 0.0]})
        for j in d["joints"]:
            if j["name"] == "G_rp":
                j["links"] = ["ring", "planet"]
        d["drivers"].append({"joint": "O_ring", "toward": "G_rp", "start_deg": 0,
                             "stop_deg": -90, "steps": d["drivers"][0]["steps"],
                             "speed": -4.0, "acceleration": 1.5})
    return d


def refused(d):
    with pytest.raises(SceneError) as e:
        load_scene(d)
    return "\n".join(e.value.problems)


# -- format and validation ----------------------------------------------------

def test_pitch_point_is_computed_and_checked():
    s = load_scene(gear_pair())
    assert s.joint("M").at == pytest.approx((0.03, 0.0), abs=1e-15)
    assert s.joint("M").pivots == ("A", "B")
    s = load_scene(gear_pair(r1=0.02, r2=0.05, internal=True))  # the ring is g: P beyond A
    assert s.joint("M").at == pytest.approx((-0.02, 0.0), abs=1e-15)
    d = gear_pair()
    d["joints"][2]["at"] = [0.031, 0.0]
    assert "joints[2].at: [0.031, 0] is not the pitch point [0.03, 0]" in refused(d)


def test_pivot_distance_names_the_joint_and_both_numbers():
    d = gear_pair()
    d["joints"][2]["radii"] = [0.03, 0.06]
    msg = refused(d)
    assert "joints[2].radii: mesh 'M': the pivots A (p) and B (g) are 0.08 m apart" in msg
    assert "ra + rb = 0.03 + 0.06 = 0.09 m" in msg
    d = gear_pair(internal=True)
    d["joints"][2]["radii"] = [0.03, 0.06]
    assert "an internal mesh needs |ra - rb| = 0.03 - 0.06 = 0.03 m" in refused(d)


@pytest.mark.parametrize("change, expected", [
    (lambda d: d["joints"][2].update(carrier="pp"), "joints[2].carrier: unknown link 'pp' (did you mean 'p'?)"),
    (lambda d: d["joints"][2].update(carrier="p"), "joints[2].carrier: link 'p' is one of the mesh's gears"),
    (lambda d: d["joints"][2].update(radii=[0.03, 0]), "joints[2].radii[1]: a pitch radius must be > 0"),
    (lambda d: d["joints"][2].update(radii=[0.03]), "joints[2].radii: must be an array of 2 numbers"),
    (lambda d: d["joints"][2].pop("radii"), "joints[2].radii: required key is missing"),
    (lambda d: d["joints"][2].update(internal=True, radii=[0.04, 0.04]),
     "joints[2].radii: an internal mesh needs two different radii"),
    (lambda d: d["joints"][2].update(pressure_angle_deg=50), "joints[2].pressure_angle_deg: must be at most 45"),
    (lambda d: d["joints"][2].update(axis_deg=10), "joints[2].axis_deg: not allowed on a gear mesh"),
    (lambda d: d["joints"][0].update(radii=[1, 2]), "joints[0].radii: not allowed on a R joint"),
    (lambda d: d["joints"][1].update(links=["p", "g"], at=[0.08, 0.0]),
     "joints[2].links[1]: gear 'g' needs one R joint with the carrier 'ground' to turn on"),
    (lambda d: d["drivers"][0].update(joint="M"), "drivers[0].joint: joint 'M' is a gear mesh"),
])
def test_refusals_name_the_field(change, expected):
    d = gear_pair()
    change(d)
    assert expected in refused(d)


def test_toward_a_mesh_must_mesh_the_driven_gear():
    d = planetary()
    d["drivers"][0]["toward"] = "G_rp"
    assert "drivers[0].toward: gear mesh 'G_rp' does not mesh link 'sun'" in refused(d)


def test_mobility_counts_a_mesh_as_one_constraint():
    d = planetary()
    d["joints"] = [j for j in d["joints"] if j["name"] != "G_rp"]
    msg = refused(d)
    assert "M = 3*3 - 2*3 - 1 = 2" in msg and "1 gear meshes (higher pairs)" in msg


# -- structure ----------------------------------------------------------------

def test_decomposition_allows_higher_pairs():
    groups = decompose(load_scene(planetary())).groups
    assert [(g.label, g.links) for g in groups] == [
        ("input link", ("sun",)), ("gear group", ("planet", "arm"))]
    groups = decompose(load_scene(planetary("arm"))).groups
    assert [(g.label, g.links) for g in groups] == [
        ("input link", ("arm",)), ("gear", ("planet",)), ("gear", ("sun",))]
    assert decompose(load_scene(planetary())).mobility == 1
    assert decompose(load_scene(planetary(ring_fixed=False))).mobility == 2


# -- kinematics ---------------------------------------------------------------

def willis(a, rs=0.03, rr=0.06, rp=0.015, ring=None):
    """Residuals of the Willis formula for the sun-ring and sun-planet pairs, rates and accelerations."""
    out = []
    for f in ("omega", "alpha"):
        s, c, p = (getattr(a.links[n], f) for n in ("sun", "arm", "planet"))
        r = 0.0 if ring is None else getattr(a.links[ring], f)
        out.append(((s - c) * (-rs / rr) - (r - c), np.abs(s) + np.abs(c) + np.abs(r)))
        out.append(((s - c) * (-rs / rp) - (p - c), np.abs(s) + np.abs(c) + np.abs(p)))
    return out


@pytest.mark.parametrize("variant", ["sun", "arm", "two drivers"])
def test_planetary_ratios_follow_willis(variant):
    d = planetary("arm" if variant == "arm" else "sun", ring_fixed=variant != "two drivers")
    a = compile_plan(load_scene(d)).run()
    assert a.ok.all()
    for res, scale in willis(a, ring=None if variant != "two drivers" else "ring"):
        assert max_rel(res, scale) <= TOL_KIN
    # the rotations (from the assembly configuration) obey the same linear law
    s, c, p = (a.links[n].rotation for n in ("sun", "arm", "planet"))
    r = a.links["ring"].rotation if variant == "two drivers" else 0.0
    scale = np.abs(s) + np.abs(c) + np.abs(p) + np.abs(r)
    assert max_rel((s - c) * 0.03 + (p - c) * 0.015, 0.03 * scale) <= TOL_KIN
    assert max_rel((s - c) * 0.03 + (r - c) * 0.06, 0.06 * scale) <= TOL_KIN
    # the planet's centre stays on the arm at the centre distance
    C = a.joints["C"].position
    assert np.allclose(np.hypot(C[:, 0], C[:, 1]), 0.045, rtol=0, atol=1e-15)


def test_planet_with_ring_fixed_closed_form():
    """Sun driven, ring fixed: w_arm = w_sun r_s / (r_s + r_r), the planet's angle likewise."""
    a = compile_plan(load_scene(planetary())).run()
    s = a.links["sun"]
    assert max_rel(a.links["arm"].omega - s.omega / 3, np.abs(s.omega)) <= TOL_KIN
    assert max_rel(a.links["arm"].alpha - s.alpha / 3, np.abs(s.alpha)) <= TOL_KIN
    assert max_rel(a.links["arm"].rotation - s.rotation / 3, np.abs(s.rotation) + 1) <= TOL_KIN
    # the pitch point (the mesh joint's position) lies on the line of centres, r_s from O
    P = a.joints["G_sp"].position
    assert np.allclose(np.hypot(P[:, 0], P[:, 1]), 0.03, rtol=0, atol=1e-15)


@pytest.mark.parametrize("internal", [False, True])
def test_gear_pair_equals_its_equivalent_four_bar_at_an_instant(internal):
    r1, r2, phi = 0.03, 0.05, math.radians(20)
    a = compile_plan(load_scene(gear_pair(r1, r2, internal))).run()
    k = 17
    O1, O2 = np.zeros(2), np.array([abs(r2 - r1) if internal else r1 + r2, 0.0])
    # the line of action through the pitch point P: the common normal of the involutes; its
    # feet of the base circles (radius r cos(phi)) are the profiles' centres of curvature
    P = a.joints["M"].position[k]
    e = (O2 - O1) / np.linalg.norm(O2 - O1)
    t = np.array([-e[1], e[0]])
    u = math.cos(phi) * t + math.sin(phi) * e  # one flank's line of action
    A = P + np.dot(O1 - P, u) * u
    B = P + np.dot(O2 - P, u) * u
    assert abs(np.linalg.norm(A - O1) - r1 * math.cos(phi)) < 1e-15
    four_bar = {
        "name": "equivalent", "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [
            {"name": "O1", "type": "R", "links": ["ground", "crank"], "at": O1.tolist()},
            {"name": "A", "type": "R", "links": ["crank", "coupler"], "at": A.tolist()},
            {"name": "B", "type": "R", "links": ["coupler", "rocker"], "at": B.tolist()},
            {"name": "O2", "type": "R", "links": ["rocker", "ground"], "at": O2.tolist()},
        ],
        "drivers": [{"joint": "O1", "toward": "A", "start_deg": math.degrees(math.atan2(A[1], A[0])),
                     "stop_deg": math.degrees(math.atan2(A[1], A[0])), "steps": 1,
                     "speed": float(a.links["p"].omega[k]),
                     "acceleration": float(a.links["p"].alpha[k])}],
        "outputs": ["kinematics"],
    }
    b = compile_plan(load_scene(four_bar)).run()
    w2 = a.links["g"].omega[k]
    assert abs(b.links["rocker"].omega[0] - w2) <= TOL_KIN * abs(w2)
    assert abs(w2 - (1 if internal else -1) * a.links["p"].omega[k] * r1 / r2) <= TOL_KIN * abs(w2)
    # the involutes' centres of curvature stay put to second order: accelerations agree too
    al2 = a.links["g"].alpha[k]
    assert abs(b.links["rocker"].alpha[0] - al2) <= 1e-9 * (abs(al2) + w2 ** 2)


# -- forces -------------------------------------------------------------------

@pytest.mark.parametrize("internal", [False, True])
@pytest.mark.parametrize("torque", [-2.0, 3.0])
def test_gear_pair_forces_closed_form(internal, torque):
    r1, r2, phi = 0.03, 0.05, math.radians(20)
    scene = load_scene(gear_pair(r1, r2, internal, torque))
    plan = compile_plan(scene)
    a, g = plan.run(), plan.run(method="global")
    assert [x.method for x in a.forces.groups] == ["input", "gear"]
    # the pinion balances the load through the ratio (no inertia, no gravity)
    ratio = (1 if internal else -1) * r1 / r2  # w_g / w_p
    T_in = -torque * ratio
    for res in (a, g):
        assert max_rel(res.forces.driving["A"] - T_in, abs(T_in)) <= TOL_F
        Fn = np.hypot(*res.forces.reactions["M"].T)
        assert max_rel(Fn - abs(torque) / (r2 * math.cos(phi)), Fn) <= TOL_F
        for r, s, rn in mesh_residuals(scene, res).values():
            assert max_rel(r, s) <= TOL_F and (rn > 0).all()
        r, s = power_residual(scene, res)
        assert max_rel(r, s) <= TOL_F


@pytest.mark.parametrize("variant", ["arm", "two drivers"])
def test_planetary_variants_forces_checked(variant):
    d = planetary("arm" if variant == "arm" else "sun", ring_fixed=variant != "two drivers")
    scene = load_scene(d)
    for res in dyad_and_global_checked(scene, compile_plan(scene), TOL_F):
        for r, s, rn in mesh_residuals(scene, res).values():
            assert max_rel(r, s) <= TOL_F and (rn >= 0).all()


def test_the_flank_follows_the_tangential_force():
    """A load torque that changes sign over the cycle: the tooth load never pulls."""
    d = gear_pair(torque=0.0)
    d["loads"] = [{"link": "g", "torque": 2.0, "table": {"q_deg": [0, 180, 360], "scale": [1, -1, 1]}}]
    scene = load_scene(d)
    a = compile_plan(scene).run()
    ((r, s, rn),) = mesh_residuals(scene, a).values()
    assert max_rel(r, s) <= TOL_F and (rn >= -1e-12 * s).all()
    tangential = a.forces.reactions["M"][:, 1]  # the pitch point is on the x axis
    assert (tangential > 0).any() and (tangential < 0).any()


def test_result_json_has_the_mesh_force():
    a = linkage_sym.analyze(load_scene(gear_pair()))
    step = a.to_dict()["steps"][3]
    rec = step["joints"]["M"]
    assert set(rec) == {"position", "velocity", "acceleration", "reaction"}
    assert rec["position"] == pytest.approx([0.03, 0.0], abs=1e-15)  # the pitch point, on the carrier
    assert rec["velocity"] == pytest.approx([0.0, 0.0], abs=1e-15)


def test_scenes_without_meshes_are_unchanged():
    """R/P scenes take none of the new paths: no mesh, no flank iteration, no early unwrap."""
    scene = linkage_sym.load_example("crank_rocker")
    assert scene.meshes == () and not compile_plan(scene).unwrap_early
    assert all(j.carrier is None and j.radii is None for j in scene.joints)


# -- instant centres ------------------------------------------------------------

def test_kennedy_takes_a_mesh_s_pitch_point_as_its_centre():
    """Example 3-3 of the textbook chapter: E (gears 1, 3) is P13, K (gears 2, 3) is P23;
    the centre of link 6 follows by three-centre lines through them, and agrees with
    the velocity method (``test_centres`` checks every example that way)."""
    from linkage_sym.centres.kennedy import kennedy_centres
    from linkage_sym.centres.velocity import velocity_centres

    scene = linkage_sym.load_example("gear_linkage")
    res = linkage_sym.analyze(scene)
    k = kennedy_centres(scene, res)
    assert k.reached.all()
    for mesh, pair in (("E", ("ground", "gear3")), ("K", ("gear2", "gear3"))):
        i = k.pairs.index(pair)
        assert k.source[i] == f"pitch point of mesh {mesh}"
        assert np.array_equal(k.position[:, i], res.joints[mesh].position)
    v = velocity_centres(res)
    i = k.pairs.index(("ground", "link6"))
    assert max_rel(k.position[:, i] - v.position[:, i], np.hypot(*v.position[:, i].T) + 0.3) <= 1e-9


def test_a_flank_that_never_settles_is_a_warning(monkeypatch):
    """Were the tooth load to pull with either flank (a solve that does not settle), the run
    says so at those steps instead of reporting the force as if the teeth carried it."""
    from linkage_sym.numeric.forces import kinetostatics

    scene = load_scene(example_dict("planetary_train"))
    plan = compile_plan(scene)
    mesh = scene.meshes[0].name
    solve = kinetostatics.ForcePlan._solve

    def pulling(self, Sk, geo, *args):
        reactions, efforts, frame, groups, fric = solve(self, Sk, geo, *args)
        ux, uy = geo.line_of_action(mesh)
        fx, fy, m = reactions[mesh]
        along = fx * ux + fy * uy
        reactions[mesh] = (fx - 2 * np.abs(along) * ux, fy - 2 * np.abs(along) * uy, m)  # pulls
        return reactions, efforts, frame, groups, fric

    monkeypatch.setattr(kinetostatics.ForcePlan, "_solve", pulling)
    res = plan.run()
    assert any(w.startswith(f"gear mesh {mesh}: the tooth load still pulls at {res.n_steps} step")
               for w in res.warnings), res.warnings


# -- the symbolic layer ---------------------------------------------------------

def _compare(d, what):
    """The compiled symbolic run against the numeric solver (test_symbolic's contract check:
    statuses, warnings, and every array within 1e-9 of its family's scale)."""
    from tests.symbolic.test_symbolic import compare_analyses, compare_dicts

    scene = load_scene(d)
    sym = linkage_sym.analyze(scene, method="symbolic")
    num = linkage_sym.analyze(scene)
    assert sym.warnings == num.warnings, what
    compare_analyses(scene, sym, num, what)
    compare_dicts(scene, sym.to_dict(), num.to_dict(), what)
    return scene, sym


@pytest.mark.parametrize("internal", [False, True])
def test_symbolic_gear_pair_closed_form_equals_numeric(internal):
    """A gear on its pivot: the symbolic closed form of its angle (from the mesh equation)
    and its tooth load against the numeric solver and the closed-form torques."""
    from linkage_sym.symbolic.mechanism import derive

    d = gear_pair(internal=internal)
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    scene, sym = _compare(d, f"gear pair internal={internal}")
    eqs = derive(scene)
    assert [ge.closed for ge in eqs.groups] == [True, True]
    ratio = (1 if internal else -1) * 0.03 / 0.05
    assert max_rel(sym.links["g"].omega - ratio * sym.links["p"].omega,
                   np.abs(sym.links["p"].omega)) <= TOL_KIN
    assert max_rel(sym.forces.driving["A"] - 2.0 * ratio, 2.0 * abs(ratio)) <= TOL_F


def test_symbolic_mesh_equation_is_the_rolling_law():
    """The derived mesh row of the planetary train is ``ra (da - dc) + rb (db - dc)`` (an
    external mesh; ``d`` the rotations from the assembly configuration), written here."""
    from linkage_sym.symbolic.mechanism import derive
    import sympy as sp

    eqs = derive(load_scene(planetary()), forces=False)
    row = eqs.Phi[eqs.groups[1].rows][0]
    th = {n: sp.Symbol(f"theta_{n}", real=True) for n in ("sun", "planet", "arm")}
    th0 = {n: sp.Symbol(f"theta0_{n}", real=True) for n in ("sun", "planet", "arm")}
    ra, rb = sp.Symbol("r_G_sp_sun", real=True), sp.Symbol("r_G_sp_planet", real=True)
    d = {n: th[n] - th0[n] for n in th}
    assert sp.expand(row - (ra * (d["sun"] - d["arm"]) + rb * (d["planet"] - d["arm"]))) == 0


def test_symbolic_flank_follows_the_tangential_force():
    """The load torque changing sign over the cycle: the symbolic runtime settles the flanks
    as the numeric solver does (the same mesh forces, whose tangential part changes sign)."""
    d = gear_pair(torque=0.0)
    d["loads"] = [{"link": "g", "torque": 2.0, "table": {"q_deg": [0, 180, 360], "scale": [1, -1, 1]}}]
    scene, sym = _compare(d, "gear pair, load changing sign")
    tangential = sym.forces.reactions["M"][:, 1]
    assert (tangential > 0).any() and (tangential < 0).any()
    ((r, s, rn),) = mesh_residuals(scene, sym).values()
    assert max_rel(r, s) <= TOL_F and (rn >= -1e-12 * s).all()


@pytest.mark.parametrize("variant", ["arm", "two drivers"])
def test_symbolic_planetary_variants_equal_numeric(variant):
    _compare(planetary("arm" if variant == "arm" else "sun", ring_fixed=variant != "two drivers"),
             f"planetary ({variant})")


def test_symbolic_flank_that_never_settles_is_the_same_warning(monkeypatch):
    """Were the tooth load to pull with either flank, the symbolic runtime says so with the
    numeric solver's words."""
    from linkage_sym.codegen import runtime

    scene = load_scene(example_dict("planetary_train"))
    cm = linkage_sym.compile_mechanism(scene)
    name = scene.meshes[0].name
    row = cm.art.force_names.index(f"Fn_{name}")
    solve = runtime.CompiledMechanism.solve_forces

    def pulling(self, pts, take=lambda v: v):
        Fv = solve(self, pts, take)
        Fv[row] = -np.abs(Fv[row]) - 1.0
        return Fv

    monkeypatch.setattr(runtime.CompiledMechanism, "solve_forces", pulling)
    res = cm.run()
    assert any(w.startswith(f"gear mesh {name}: the tooth load still pulls at {res.n_steps} step")
               and "after 5 force solves" in w for w in res.warnings), res.warnings


@pytest.mark.slow
def test_symbolic_precision_of_a_gear_train_equals_float():
    """``--precision 50`` (mpmath, its own flank choice per step) against the float64 run."""
    from linkage_sym.codegen.precision import analyze_precise

    d = example_dict("gear_linkage")
    d["drivers"][0]["steps"] = 13
    scene = load_scene(d)
    hi = analyze_precise(scene, 50)
    lo = linkage_sym.analyze(scene, method="symbolic")
    assert list(hi.status) == list(lo.status)
    scale = reaction_scale(scene, lo.forces)
    for j in lo.forces.reactions:
        assert max_rel(hi.forces.reactions[j] - lo.forces.reactions[j], scale) <= 1e-12, j
    assert max_rel(hi.forces.driving["O"] - lo.forces.driving["O"], scale) <= 1e-12


def test_latex_names_the_flanks_and_tooth_loads():
    from linkage_sym.symbolic.latex import latex_document
    from linkage_sym.symbolic.mechanism import derive

    tex = latex_document(derive(load_scene(example_dict("planetary_train"))), symbols=True)
    # a long meaning wraps in a \parbox (the symbol table's column stays within the page)
    assert r"\kappa_{\mathrm{G\_sp}}$ & \parbox[t]{0.6\linewidth}{\raggedright flank of gear mesh G\_sp" in tex
    assert r"F_{\mathrm{G\_rp},n}$ & \parbox[t]{0.6\linewidth}{\raggedright tooth load of gear " \
           r"mesh G\_rp on its line of action (gear ground on gear planet)" in tex
    assert r"\paragraph{Gear meshes.}" in tex and r"\label{eq:planetary-train:mesh-G-rp}" in tex
    assert "from its loop and mesh equations above" in tex


def test_derive_prints_the_mesh_equations(tmp_path):
    from linkage_sym.cli import main

    out = tmp_path / "eqs.txt"
    assert main(["derive", str(linkage_sym.examples.example_path("planetary_train")),
                 "-o", str(out)]) == 0
    text = out.read_text()
    assert "## gear meshes (rolling without slip = 0)" in text
    assert "G_sp: r_G_sp_planet*(theta0_arm - theta0_planet - theta_arm + theta_planet)" in text


def test_an_internal_and_an_external_mesh_are_compiled_apart():
    """The rolling law's sign and carrier shape the generated code: they are in the cache key
    (the same topology with an internal mesh once ran the external mesh's functions)."""
    from linkage_sym.codegen import cache

    key = lambda d: cache.key_of(cache.signature(load_scene(d)))  # noqa: E731
    assert key(gear_pair(internal=False)) != key(gear_pair(internal=True))


def test_balancing_refuses_meshes_by_name():
    """The derived balancing conditions (Song and Wang 1992) cover hinged linkages: a scene
    with meshes is refused naming each mesh as a gear mesh (not as a prismatic joint)."""
    from linkage_sym.balancing import BalanceModel

    with pytest.raises(SceneError) as e:
        BalanceModel(load_scene(example_dict("gear_linkage")))
    assert "joints[3] 'K': a gear mesh;" in str(e.value) and "prismatic" not in str(e.value)


def test_design_sweeps_refuse_meshes_by_name():
    from linkage_sym.design.parameters import SweepError

    with pytest.raises(SweepError, match=r"gear meshes \(K, E\): design sweeps do not take them"):
        linkage_sym.sweep(load_scene(example_dict("gear_linkage")), {"l_BC": [0.3, 0.31]})
    with pytest.raises(SweepError, match=r"cam contacts \(K\): design sweeps do not take them"):
        linkage_sym.sweep(load_scene(example_dict("cam_cycloidal_roller")), {"l_AB": [0.01, 0.02]})
