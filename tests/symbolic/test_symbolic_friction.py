"""The derived force equations with joint friction (contract part two, issue 29) against the
numeric solver, which shares no code with them: at steps of the press, every link's derived
equilibrium (SymPy, the scene's numbers) is satisfied by the numeric reactions, efforts and
frictions, and each derived friction law gives the numeric friction; ``derive --latex``
prints the laws."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import linkage_sym
from linkage_sym.structure.parameters import ident

PRESS = "slider_crank_press_friction"


@pytest.fixture(scope="module")
def press():
    scene = linkage_sym.load_example(PRESS)
    return scene, linkage_sym.derive(scene, symbolic=False, forces=True), linkage_sym.analyze(scene)


def _values(scene, res, i):
    """Every symbol of the derived force equations at step ``i`` of the numeric result."""
    v = {}
    for n, lk in res.links.items():
        k = ident(n)
        v[f"theta_{k}"], v[f"omega_{k}"], v[f"alpha_{k}"] = (
            float(lk.rotation[i]), float(lk.omega[i]), float(lk.alpha[i]))
    f = res.forces
    for j in scene.joints:
        k = ident(j.name)
        R = f.reactions[j.name][i]
        if j.type == "R":
            v[f"R_{k}x"], v[f"R_{k}y"] = float(R[0]), float(R[1])
            v[f"Mf_{k}"] = float(f.friction[j.name][i])
        else:
            n = np.array([-np.sin(j.axis), np.cos(j.axis)])  # a guide on the ground
            v[f"N_{k}"] = float(R @ n)
            v[f"M_{k}"] = float(f.reaction_moments[j.name][i])
            v[f"Ff_{k}"] = float(f.friction[j.name][i])
    v["tau_A"] = float(f.driving["A"][i])
    return v


@pytest.mark.parametrize("i", [45, 90, 130])  # the pressing force acts (30 to 150 deg)
def test_derived_equilibrium_holds_with_the_numeric_frictions(press, i):
    scene, eqs, res = press
    v = _values(scene, res, i)
    scale = np.nanmax(np.abs(res.forces.reactions["A"]))
    L = scene.characteristic_length()
    for link, row in eqs.link_equations.items():
        for k, e in enumerate(row):
            subs = {s: v[s.name] for s in e.free_symbols}
            r = float(e.xreplace(subs))
            assert abs(r) <= 1e-10 * scale * (L if k == 2 else 1.0), (link, k, r)


@pytest.mark.parametrize("i", [10, 100, 200, 300])  # no joint at rest relative to its link
def test_derived_friction_laws_give_the_numeric_friction(press, i):
    scene, eqs, res = press
    v = _values(scene, res, i)
    assert [law.joint for law in eqs.friction_laws] == ["A", "B", "C", "C_guide"]
    for law in eqs.friction_laws:
        j = scene.joint(law.joint)
        w = {n: 0.0 if n == "ground" else res.links[n].omega[i] for n in j.links}
        rel = (w[j.links[1]] - w[j.links[0]] if j.type == "R"
               else res.joints[j.name].velocity[i] @ [np.cos(j.axis), np.sin(j.axis)])
        subs = {s: v[s.name] for s in law.law.free_symbols if s != law.sign}
        subs[law.sign] = float(np.sign(rel))
        want = res.forces.friction[law.joint][i]
        assert float(law.law.xreplace(subs)) == pytest.approx(want, rel=1e-12, abs=0)


def test_latex_prints_the_friction_laws():
    from linkage_sym.symbolic.latex import latex_document

    tex = latex_document(linkage_sym.derive(linkage_sym.load_example(PRESS)), symbols=True)
    assert r"\paragraph{Joint friction.}" in tex
    assert r"M^{f}_{B} &= - \nu_{B} \rho_{B} \sqrt{R_{B,x}^{2} + R_{B,y}^{2}}" in tex
    assert r"\label{eq:slider-crank-press-friction:friction-C-guide}" in tex
    assert r"$\rho_{A}$ & friction circle's radius of joint A & m \\" in tex
    assert tex.count(r"\begin{align}") == tex.count(r"\end{align}")
    # without friction acting: no such section, the equations as before
    off = linkage_sym.derive(linkage_sym.load_example("slider_crank_offset"))
    assert off.friction_laws == [] and "Joint friction" not in latex_document(off)


def test_the_frame_carries_the_ground_joints_friction(press):
    scene, eqs, res = press
    v = _values(scene, res, 90)
    got = [float(e.xreplace({s: v[s.name] for s in e.free_symbols})) for e in eqs.frame]
    assert got[0] == pytest.approx(res.forces.frame_force[90, 0], rel=1e-10)
    assert got[1] == pytest.approx(res.forces.frame_force[90, 1], rel=1e-10)
    assert got[2] == pytest.approx(res.forces.frame_moment[90], rel=1e-9)
    assert sp.Symbol("Mf_A", real=True) in eqs.frame[2].free_symbols
