"""Design sweeps of a dyad of two slides (PRP): the passages of its joint through infinity.

The guide-slider of :mod:`tests.support.parallel_slides` with its block's slide turned by
``gamma_C_guide``: the rod's line (through the origin at the guide's angle, 30 to -30
degrees) is parallel to the block's slide where the guide's angle equals that direction, so
a design crosses infinity exactly when ``gamma_C_guide`` (mod 180 degrees) lies between the
first and the last step's angles -- the reference, from the geometry, not from the sweep.
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.design import sweep
from tests.support.parallel_slides import guide_slider


def test_a_design_through_infinity_is_flagged():
    gammas = [0.0, 0.3, -0.45, 0.6, 1.2, -1.2, math.pi - 0.2]
    res = sweep(guide_slider(10), {"gamma_C_guide": gammas})
    q = np.radians(np.linspace(30.0, -30.0, 10))
    ref = []
    for g in gammas:
        # the slides are parallel where sin(q - g) = 0: between two steps, never at one here
        d = np.sign(np.sin(q - g))
        ref.append(int(np.count_nonzero(d[1:] != d[:-1])))
    assert res["through_infinity"].tolist() == ref
    assert ref == [1, 1, 1, 0, 0, 0, 1]
    assert "through_infinity" in res.metrics


def test_a_scene_without_two_slides_has_no_such_column():
    from linkage_sym.examples import load_example

    res = sweep(load_example("crank_rocker"), {"l_AB": [0.02, 0.025]})
    assert "through_infinity" not in res.columns


def test_designs_solved_one_at_a_time_count_the_passages_alike(monkeypatch):
    """Forced onto the numeric plan one design at a time (the route of designs with a group
    without a closed form), the count is the geometry's as well (the plan's angles give the
    slides' directions there)."""
    from linkage_sym.design.evaluate import Model

    init = Model.__init__

    def one_at_a_time(self, *args, **kwargs):
        init(self, *args, **kwargs)
        self.one_at_a_time = True

    monkeypatch.setattr(Model, "__init__", one_at_a_time)
    gammas = [0.0, 0.3, 0.6, math.pi - 0.2]
    res = sweep(guide_slider(10), {"gamma_C_guide": gammas})
    assert res["through_infinity"].tolist() == [1, 1, 0, 1]
