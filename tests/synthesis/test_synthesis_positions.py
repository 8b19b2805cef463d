"""Synthesis by two or three coupler positions (``linkage_sym.synthesis.positions``).

The positions come from four-bars built from dimensions (the builders), so the
three-position design must give back their fixed pivots; every design is driven
by the solver through its crank angles and must pass through each given
position to 1e-9 of the coupler's length (the solver shares no code with the
synthesis).
"""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.synthesis import builders
from linkage_sym.synthesis.common import SynthesisError
from linkage_sym.synthesis.positions import coupler_positions

TOL = 1e-9
"""Positions reproduced by the solver, relative to the coupler length."""


def positions_of(a, b, c, d, angles, branches=None):
    rows = []
    for k, phi in enumerate(angles):
        branch = "open" if branches is None else branches[k]
        j = builders.fourbar(a, b, c, d, crank_deg=phi, branch=branch).scene["joints"]
        rows.append([*j[1]["at"], *j[2]["at"]])
    return rows


def reproduced(design, rows):
    """Largest distance (relative to the coupler) between the solver's B, C and the positions,
    driving the crank along the sweep through the positions' crank angles."""
    scene = linkage_sym.load_scene(design.scene)
    plan = linkage_sym.compile_plan(scene)
    q = np.array(design.extra["crank_angles"])
    path = np.concatenate([np.linspace(q[0], q[-1], 181), q])
    n = len(path)
    res = plan.run(q={"A": path}, qd={"A": np.ones(n)}, qdd={"A": np.zeros(n)})
    assert (res.status == "ok").all(), set(res.status)
    got = np.hstack([res.joints["B"].position[-len(q):], res.joints["C"].position[-len(q):]])
    return float(np.abs(got - np.array(rows)).max()) / design.lengths["coupler"]


lengths = st.tuples(st.floats(0.2, 1.0), st.floats(2.0, 4.0), st.floats(2.0, 4.0), st.floats(2.0, 4.0))


@settings(max_examples=40, deadline=None)
@given(lengths, st.floats(0.0, 360.0), st.floats(10.0, 150.0), st.floats(10.0, 150.0),
       st.sampled_from(["open", "crossed"]))
def test_three_positions_give_back_the_pivots(lens, phi1, step1, step2, branch):
    a, b, c, d = lens
    assume(2 * max(lens) < sum(lens))
    try:
        rows = positions_of(a, b, c, d, [phi1, phi1 + step1, phi1 + step1 + step2], [branch] * 3)
    except SynthesisError:
        assume(False)
    try:
        design = coupler_positions(rows)
    except SynthesisError as err:
        # only a defect may refuse a four-bar's own positions: a dead centre between them
        assert "defect" in err.reason, err.reason
        return
    assert design.extra["pivots"] == pytest.approx([0.0, 0.0, d, 0.0], abs=TOL * b)
    assert reproduced(design, rows) <= TOL


@settings(max_examples=30, deadline=None)
@given(lengths, st.floats(0.0, 360.0), st.floats(10.0, 150.0))
def test_two_positions_with_the_pivots(lens, phi1, step):
    a, b, c, d = lens
    assume(2 * max(lens) < sum(lens))
    try:
        rows = positions_of(a, b, c, d, [phi1, phi1 + step])
    except SynthesisError:
        assume(False)
    try:
        design = coupler_positions(rows, pivots=[0.0, 0.0, d, 0.0])
    except SynthesisError as err:
        assert "dead centre" in err.reason, err.reason
        return
    assert reproduced(design, rows) <= TOL


@pytest.mark.slow
def test_two_positions_without_pivots():
    rows = positions_of(1.0, 3.0, 3.0, 3.5, [60.0, 100.0])
    design = coupler_positions(rows)
    assert reproduced(design, rows) <= TOL
    assert "perpendicular bisectors" in design.notes[0] and "give pivots" in design.notes[0]
    # the pivots are on the bisectors, to rounding
    A, D = np.array(design.extra["pivots"][:2]), np.array(design.extra["pivots"][2:])
    for P, k in ((A, 0), (D, 2)):
        r = [math.dist(P, row[k:k + 2]) for row in rows]
        assert r[0] == pytest.approx(r[1], rel=1e-12)


def test_minimum_transmission_angle_between_the_positions():
    """Against the solver's positions on a fine sweep between the positions (law of cosines-free:
    the angle between C->B and C->D from coordinates)."""
    rows = positions_of(1.0, 3.0, 3.0, 3.5, [60.0, 100.0, 140.0])
    design = coupler_positions(rows)
    q = np.array(design.extra["crank_angles"])
    path = np.linspace(q[0], q[-1], 8001)
    plan = linkage_sym.compile_plan(linkage_sym.load_scene(design.scene))
    res = plan.run(q={"A": path}, qd={"A": np.ones(8001)}, qdd={"A": np.zeros(8001)})
    u = res.joints["B"].position - res.joints["C"].position
    v = res.joints["D"].position - res.joints["C"].position
    g = np.arccos(np.sum(u * v, axis=1) / np.hypot(*u.T) / np.hypot(*v.T))
    assert np.min(np.minimum(g, np.pi - g)) == pytest.approx(design.gamma_min, rel=1e-9)


# ------------------------------------------------------------------ defects and refusals


def test_branch_defect_is_refused():
    rows = positions_of(1.0, 3.0, 3.0, 3.5, [60.0, 100.0, 140.0], ["open", "open", "crossed"])
    with pytest.raises(SynthesisError) as err:
        coupler_positions(rows)
    assert err.value.field == "positions"
    assert "branch defect: position 3 is in the other assembly mode" in err.value.reason


def test_order_defect_is_refused():
    """A Grashof double-rocker (the coupler shortest): its crank rocks between about 38.6 and
    78.6 deg; positions at 45, 70, 57 deg must be met in that order, so the crank would have to
    turn the other way round, through a dead centre."""
    a, b, c, d = 3.0, 1.0, 3.5, 4.0
    ok = coupler_positions(positions_of(a, b, c, d, [45.0, 57.0, 70.0]))
    assert ok.extra["pivots"] == pytest.approx([0.0, 0.0, d, 0.0], abs=1e-9)
    with pytest.raises(SynthesisError) as err:
        coupler_positions(positions_of(a, b, c, d, [45.0, 70.0, 57.0]))
    assert "order defect" in err.value.reason and "dead centre" in err.value.reason


def test_two_positions_with_a_dead_centre_either_way_are_refused():
    a, b, c, d = 3.0, 1.0, 3.5, 4.0
    rows = positions_of(a, b, c, d, [45.0, 70.0])
    rows[1] = positions_of(a, b, c, d, [-50.0])[0]  # on the mirror range of the crank
    with pytest.raises(SynthesisError) as err:
        coupler_positions(rows, pivots=[0.0, 0.0, d, 0.0])
    assert err.value.field == "pivots" and "dead centre" in err.value.reason


@pytest.mark.parametrize("kwargs, field, words", [
    ({"positions": [[0, 0, 1, 0]]}, "positions", "2 or 3 positions"),
    ({"positions": "x"}, "positions", "2 or 3 positions"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1]]}, "positions[1]", "four numbers"),
    ({"positions": [[0, 0, 1, 0], [0, 1, "a", 1]]}, "positions[1][2]", "a finite number"),
    ({"positions": [[0, 0, 0, 0], [0, 1, 1, 1]]}, "positions[0]", "the coupler has no length"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1, 1.5]]}, "positions[1]", "a rigid coupler keeps its length"),
    ({"positions": [[0, 0, 1, 0], [0, 0, 0, 1]]}, "positions[1]", "B is where it is in positions[0]"),
    ({"positions": [[0, 0, 1, 0], [1, 0, 2, 0], [2, 0, 3, 0]]}, "positions", "are in line"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1, 1], [1, 2, 1, 3]], "pivots": [0, 0, 1, 1]}, "pivots",
     "three positions fix the pivots"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1, 1]], "pivots": [0, 0, 1]}, "pivots", "four numbers"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1, 1]], "pivots": [0, 0, 1, 0.5]}, "pivots",
     "A = (0, 0) is not on the perpendicular bisector of B1B2"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1, 1]], "pivots": [0.5, 0.5, 0.5, 0.5]}, "pivots",
     "the fixed pivots A and D coincide"),
    ({"positions": [[0, 0, 1, 0], [0, 1, 1, 1]], "steps": 0}, "steps", "an integer >= 2"),
])
def test_refusals_name_the_field_and_the_reason(kwargs, field, words):
    with pytest.raises(SynthesisError) as err:
        coupler_positions(**kwargs)
    assert err.value.field == field
    assert words in err.value.reason, err.value.reason
