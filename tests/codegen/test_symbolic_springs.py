"""Springs and dampers in the symbolic layer (the contract's ``springs``, issue 29).

The compiled symbolic run (its force blocks derived with the springs as known loads,
:mod:`linkage_sym.symbolic.springs`) is checked against references sharing no code
with it:

* the numeric dyad run (its springs from solved link states,
  :mod:`linkage_sym.numeric.forces.springs`): the same statuses, every reaction,
  effort, frame value and spring record within 1e-10 of its scale, on the shipped
  crank-rocker with a link spring and a joint spring (both damped) and on the class-III
  six-bar with springs inside and across its triad;
* each link's equilibrium and the power balance written from the springs' own
  variables (:mod:`tests.support.force_checks`), to 1e-9;
* a torsion spring at the crank's pivot over two turns: its torque is
  ``-k (q - theta_f)`` with ``q`` the driver's value, whole turns counted;
* ``--precision 50`` (mpmath) against float64, to 1e-12 of each value's scale;
* two scenes differing only in a spring never share a compiled artifact.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen import cache
from linkage_sym.codegen.precision import analyze_precise
from linkage_sym.examples import example_dict
from tests.support.force_checks import link_residuals, max_rel, power_residual, reaction_scale
from tests.support.spring_checks import class3_with_springs

TOL = 1e-10


def _crank_rocker():
    d = example_dict("crank_rocker_spring")
    d["springs"][1]["damping"] = 0.01  # the joint spring damped too
    return linkage_sym.load_scene(d)



def _same_forces(scene, a, b, tol):
    """``a`` and ``b``: the same statuses, and every force value within ``tol`` of its scale
    (``b``'s reactions' scale; a length for the torques; the springs' own)."""
    np.testing.assert_array_equal(a.status, b.status)
    scale = reaction_scale(scene, b.forces)
    L = scene.characteristic_length()
    for j, r in b.forces.reactions.items():
        assert max_rel(a.forces.reactions[j] - r, scale) <= tol, j
        assert max_rel((a.forces.reaction_moments[j] - b.forces.reaction_moments[j]) / L,
                       scale) <= tol, j
    for d, e in b.forces.driving.items():
        assert max_rel((a.forces.driving[d] - e) / L, scale) <= tol, d
    assert max_rel(a.forces.frame_force - b.forces.frame_force, scale) <= tol
    assert max_rel((a.forces.frame_moment - b.forces.frame_moment) / L, scale) <= tol
    assert set(a.forces.springs) == {k.name for k in scene.springs} == set(b.forces.springs)
    for name, rec in b.forces.springs.items():
        assert list(a.forces.springs[name]) == list(rec)
        for key, v in rec.items():
            got = a.forces.springs[name][key]
            np.testing.assert_array_equal(np.isnan(got), np.isnan(v))
            assert np.nanmax(np.abs(got - v)) <= tol * np.nanmax(np.abs(v)), (name, key)


@pytest.mark.parametrize("make", [_crank_rocker, class3_with_springs])
def test_the_compiled_symbolic_run_equals_the_dyad_run(make):
    scene = make()
    sym = linkage_sym.analyze(scene, method="symbolic")
    num = linkage_sym.analyze(scene, method="dyad")
    assert sym.forces.method == "symbolic" and sym.ok.all()
    _same_forces(scene, sym, num, TOL)
    # and against the equilibrium of each link and the power balance, written apart
    for link, (rf, rm, sf, sm) in link_residuals(scene, sym).items():
        assert max_rel(rf, sf) <= 1e-9 and max_rel(rm, sm) <= 1e-9, link
    r, s = power_residual(scene, sym)
    assert max_rel(r, s) <= 1e-9


def test_a_torsion_spring_at_the_crank_counts_whole_turns():
    d = example_dict("crank_rocker_spring")
    d["springs"] = [{"name": "t", "joint": "A", "stiffness": 1.5, "free_angle_deg": 30.0}]
    d["drivers"][0].update(stop_deg=720, steps=721)
    scene = linkage_sym.load_scene(d)
    sym = linkage_sym.analyze(scene, method="symbolic")
    q = np.radians(np.linspace(0.0, 720.0, 721))  # the crank's rotation from the assembly
    np.testing.assert_allclose(sym.forces.springs["t"]["angle"], q, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sym.forces.springs["t"]["torque"],
                               -1.5 * (q - math.radians(30.0)), rtol=0, atol=1e-12)
    _same_forces(scene, sym, linkage_sym.analyze(scene, method="dyad"), TOL)


def test_precision_50_equals_float64():
    d = example_dict("crank_rocker_spring")
    d["drivers"][0]["steps"] = 25  # mpmath is slow: every 15 degrees
    d["springs"][1]["damping"] = 0.01
    scene = linkage_sym.load_scene(d)
    mp50 = analyze_precise(scene, 50)
    f64 = linkage_sym.analyze(scene, method="symbolic")
    assert mp50.forces.method == "mpmath"
    _same_forces(scene, mp50, f64, 1e-12)


@pytest.mark.slow
def test_scenes_differing_only_in_a_spring_do_not_share_an_artifact():
    base = example_dict("crank_rocker_spring")
    variants = [copy.deepcopy(base) for _ in range(4)]
    variants[1]["springs"][0]["damping"] = 0.0  # no damper: no rates in its tension
    variants[2]["springs"][0]["links"] = ["ground", "coupler"]  # the other link
    variants[3]["springs"] = variants[3]["springs"][:1]  # one spring less
    scenes = [linkage_sym.load_scene(v) for v in variants]
    keys = {cache.key_of(cache.signature(s)) for s in scenes}
    assert len(keys) == len(scenes)
    # the same spring with other numbers: one artifact (the numbers are parameters)
    other = copy.deepcopy(base)
    other["springs"][0].update(stiffness=900.0, free_length=0.02, damping=5.0)
    assert cache.key_of(cache.signature(linkage_sym.load_scene(other))) == \
        cache.key_of(cache.signature(scenes[0]))
    # each run through the cache, one after the other, is its own scene's
    for s in scenes + [linkage_sym.load_scene(other)]:
        _same_forces(s, linkage_sym.analyze(s, method="symbolic"),
                     linkage_sym.analyze(s, method="dyad"), TOL)
