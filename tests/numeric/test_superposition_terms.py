"""Dang and Zhang's intermediates (superposition_terms) are those the solver combines.

For every disconnection of every complex group of the shipped examples that have one, at a
few steps: X = -K^-1 M_bar (eqs. 6, 10) and R' + R'' X (eqs. 7, 11) is the solver's reaction
at every joint of the group.  Tolerance 1e-9 of the largest reaction: the same arithmetic in
another order (the solver combines the same runs), so only rounding separates them.
"""

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.numeric.forces.superposition import superposition_terms
from linkage_sym.structure.disconnection import usable_disconnections

REL = 1e-9


def scene(name, steps=7):
    d = example_dict(name)
    drv = d["drivers"][0]
    drv.update(stop_deg=drv["start_deg"] + 300.0, steps=steps)
    return linkage_sym.load_scene(d)


@pytest.mark.parametrize("name", [pytest.param("printing_mechanism", marks=pytest.mark.slow),
                                  "sixbar_class3"])
def test_terms_recombine_into_the_solvers_reactions(name):
    s = scene(name)
    plan = compile_plan(s)
    (gi, g), = [(i, x) for i, x in enumerate(plan.decomposition.groups) if x.kind not in ("input", "dyad")]
    for k in range(len(usable_disconnections(s, g))):
        p = compile_plan(s, disconnection=k)
        a = p.run()
        t = superposition_terms(p, a, k)
        n = len(t.unknowns)
        assert t.residual.shape[0] == n and t.coefficients.shape[:2] == (n, n)
        ok = a.status == "ok"
        scale = max(float(np.nanmax(np.linalg.norm(a.forces.reactions[j], axis=1))) for j in g.joints)
        for step in range(t.X.shape[1]):
            X = np.linalg.solve(t.coefficients[:, :, step], -t.residual[:, step])
            np.testing.assert_allclose(X, t.X[:, step], rtol=1e-9, atol=REL * scale)
        for j in g.joints:
            got = np.array(t.particular[j][:2]) + sum(t.X[i] * np.array(t.units[i][j][:2]) for i in range(n))
            np.testing.assert_allclose(got.T, a.forces.reactions[j][ok], rtol=0, atol=REL * scale, err_msg=(k, j))


def test_bad_choice_is_refused_with_the_count():
    s = scene("printing_mechanism", 1)
    p = compile_plan(s)
    with pytest.raises(ValueError, match="12 disconnections"):
        superposition_terms(p, p.run(), 12)
