"""The derived springs and dampers (contract part two, issue 29) against the numeric solver,
which shares no code with them: each derived tension or torque, at the numeric run's
coordinates and rates, is the numeric spring's force, its length or angle the numeric one;
every link's derived equilibrium holds with the numeric reactions and efforts; ``derive``
prints the springs as text and LaTeX."""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from linkage_sym.symbolic.text import plain_text as _plain_text
from linkage_sym.examples import example_dict
from linkage_sym.structure.parameters import ident, link_frames
from linkage_sym.symbolic.latex import latex_document


@pytest.fixture(scope="module")
def machine():
    d = example_dict("crank_rocker_spring")
    d["springs"][1]["damping"] = 0.01  # both springs damped
    d["springs"][1]["free_angle_deg"] = 20.0
    scene = linkage_sym.load_scene(d)
    return scene, linkage_sym.derive(scene, symbolic=False, forces=True), linkage_sym.analyze(scene)


def _values(scene, res, i):
    """The coordinates (assembly angle plus rotation), rates, reactions and efforts at step
    ``i`` of the numeric result."""
    frames = link_frames(scene)
    v = {}
    for n, lk in res.links.items():
        k = ident(n)
        v[f"theta_{k}"] = frames[n].theta0 + float(lk.rotation[i])
        v[f"omega_{k}"], v[f"alpha_{k}"] = float(lk.omega[i]), float(lk.alpha[i])
    for j in scene.joints:
        v[f"R_{ident(j.name)}x"], v[f"R_{ident(j.name)}y"] = map(float, res.forces.reactions[j.name][i])
    v["tau_A"] = float(res.forces.driving["A"][i])
    return v


@pytest.mark.parametrize("i", [0, 77, 200, 333])
def test_derived_springs_give_the_numeric_springs(machine, i):
    scene, eqs, res = machine
    v = _values(scene, res, i)
    assert [(n, kind) for n, _, _, kind, _ in eqs.spring_efforts] == [("k1", "tension"),
                                                                      ("k2", "torque")]
    for name, _, effort, _, value in eqs.spring_efforts:
        rec = list(res.forces.springs[name].values())
        for expr, want in ((value, rec[0][i]), (effort, rec[1][i])):
            got = float(expr.xreplace({s: v[s.name] for s in expr.free_symbols}))
            assert got == pytest.approx(want, rel=1e-12, abs=1e-15), name
    # the link equilibrium, the springs substituted, with the numeric forces
    scale = np.nanmax(np.abs(res.forces.reactions["A"]))
    L = scene.characteristic_length()
    for link, row in eqs.link_equations.items():
        for k, e in enumerate(row):
            subs = {s: v[s.name] for s in e.free_symbols}
            assert abs(float(e.xreplace(subs))) <= 1e-10 * scale * (L if k == 2 else 1.0), (link, k)


@pytest.mark.slow  # over 10 s on a loaded machine: the fast lane stays under 2 min
def test_derive_prints_the_springs():
    eqs = linkage_sym.derive(linkage_sym.load_example("crank_rocker_spring"))
    text = _plain_text(eqs)
    assert "## springs and dampers" in text
    assert "\ntau_k2 = -k_k2*(theta0_rocker - theta_f_k2 - theta_rocker)\n" in text
    # the spring's length named once, as a dyad's d is, then used (issue 31)
    assert "\nL_k1 = sqrt(dx_k1**2 + dy_k1**2)\n" in text
    assert "\nT_k1 = k_k1*(-L0_k1 + L_k1) + c_k1*(" in text
    tex = latex_document(eqs, symbols=True)
    assert r"\tau_{\mathrm{k2}} &= - k_{k2} \left(\theta^{0}_{\mathrm{rocker}} - " in tex
    assert r"T_{\mathrm{k1}} &= " in tex
    assert tex.count(r"L_{\mathrm{k1}} &= \sqrt{\Delta x_{\mathrm{k1}}^{2} + \Delta y_{\mathrm{k1}}^{2}}") == 1
    assert tex.count(r"\sqrt") == 3  # the spring's length, the dyad's d and h: each once
    assert r"$k_{k1}$ & stiffness of spring k1" in tex
    assert tex.count(r"\begin{align}") == tex.count(r"\end{align}")
    names = [s.name for s in eqs.parameters]
    assert {"k_k1", "c_k1", "L0_k1", "k_k2", "theta_f_k2"} <= set(names)
    assert "c_k2" not in names  # the example's joint spring has no damper
