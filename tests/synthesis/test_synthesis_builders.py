"""Scenes from dimensions (``linkage_sym.synthesis.builders``).

Each written scene is read back by ``linkage_sym.load_scene`` (the validator)
and its lengths -- distances of the joints' assembly points -- must equal the
requested ones to 1e-12 relative (the coordinates are computed, so they round:
a few ulps).  The builders' K, theta, swing, stroke and minimum transmission
angle are checked against the solver (extremes as roots of the output's
velocity, tests/support/synthesis_checks.py) and the transmission angle against the
solver's joint positions.
"""

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.synthesis import builders
from linkage_sym.synthesis.common import SynthesisError

from tests.support.synthesis_checks import rocker_swing_and_K, slider_stroke_and_K

REL = 1e-12
"""Lengths of a written scene against the requested ones (relative)."""


def at(scene, name):
    return np.array(scene.joint(name).at)


def dist(scene, p, q):
    return float(np.hypot(*(at(scene, p) - at(scene, q))))


length = st.floats(0.01, 10.0)
angle = st.floats(-720.0, 720.0)


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(length, length, length, length, angle, st.sampled_from(["open", "crossed"]),
       st.floats(-5, 5), st.floats(-5, 5))
# the crank pin B within 2e-159 m of D (found by hypothesis): it gave a coupler 6e-8 too long
@example(a=1.0, b=1.0, c=1.0, d=1.0, phi=1.24e-157, branch="open", u=0.0, v=0.0)
def test_fourbar_lengths_branch_and_point(a, b, c, d, phi, branch, u, v):
    try:
        design = builders.fourbar(a, b, c, d, crank_deg=phi, branch=branch, coupler_point=(u, v))
    except SynthesisError as err:
        assume(False)  # not assemblable there: refusals are tested below
        raise AssertionError from err
    s = linkage_sym.load_scene(design.scene)
    for (p, q), want in ((("A", "B"), a), (("B", "C"), b), (("C", "D"), c), (("A", "D"), d)):
        assert dist(s, p, q) == pytest.approx(want, rel=REL, abs=0)
    B, C, D = at(s, "B"), at(s, "C"), at(s, "D")
    side = (D - B)[0] * (C - B)[1] - (D - B)[1] * (C - B)[0]
    assert (side > 0) == (branch == "open")
    assert at(s, "A").tolist() == [0.0, 0.0] and D[1] == 0.0
    assert math.atan2(B[1], B[0]) == pytest.approx(math.remainder(math.radians(phi), 2 * math.pi),
                                                   abs=1e-12)
    P = np.array(s.points[0].at)
    e = (C - B) / b
    assert (P - B) @ e == pytest.approx(u, abs=1e-12 * (b + abs(u) + abs(v)))
    assert (e[0] * (P - B)[1] - e[1] * (P - B)[0]) == pytest.approx(v, abs=1e-12 * (b + abs(u) + abs(v)))


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(length, length, st.floats(-10, 10), angle, st.sampled_from(["right", "left"]))
def test_slider_crank_lengths_and_line(a, b, e, phi, branch):
    try:
        design = builders.slider_crank(a, b, e, crank_deg=phi, branch=branch)
    except SynthesisError:
        assume(False)
    s = linkage_sym.load_scene(design.scene)
    assert dist(s, "A", "B") == pytest.approx(a, rel=REL, abs=0)
    assert dist(s, "B", "C") == pytest.approx(b, rel=REL, abs=0)
    assert at(s, "C")[1] == e and s.joint("C_guide").axis == 0.0
    assert (at(s, "C")[0] > at(s, "B")[0]) == (branch == "right")


@settings(max_examples=100, deadline=None)
@given(length, length, angle)
def test_guide_bar_lengths_and_guide(a, d, phi):
    assume(abs(a - d) > 1e-6 * d)
    s = linkage_sym.load_scene(builders.guide_bar(a, d, crank_deg=phi).scene)
    assert dist(s, "A", "B") == pytest.approx(a, rel=REL, abs=0)
    assert dist(s, "A", "D") == pytest.approx(d, rel=REL, abs=0)
    B, D = at(s, "B"), at(s, "D")
    axis = s.joint("B_slide").axis
    # the guide passes through D and B
    assert abs(math.sin(math.atan2(*(B - D)[::-1]) - axis)) <= 1e-12


def test_fourbar_K_swing_and_transmission_against_the_solver():
    """The builder's K, theta, swing (closed forms) against the solver's rocker extremes; its
    minimum transmission angle against the solver's positions over a fine sweep."""
    design = builders.fourbar(0.024, 0.06, 0.05, 0.078, crank_deg=30.0)
    psi, K = rocker_swing_and_K(design.scene)
    assert psi == pytest.approx(design.extra["swing"], rel=1e-9)
    assert K == pytest.approx(design.K, rel=1e-9)
    scene = dict(design.scene, drivers=[dict(design.scene["drivers"][0], start_deg=0.0,
                                             stop_deg=360.0, steps=3601)])
    res = linkage_sym.analyze(linkage_sym.load_scene(scene))
    u = res.joints["B"].position - res.joints["C"].position
    v = res.joints["D"].position - res.joints["C"].position
    g = np.arccos(np.sum(u * v, axis=1) / np.hypot(*u.T) / np.hypot(*v.T))
    k = int(np.argmin(np.minimum(g, np.pi - g)))
    # the minimum is at a step of this sweep (0 or 180 deg): equal to rounding
    assert min(g[k], np.pi - g[k]) == pytest.approx(design.gamma_min, rel=1e-12)
    assert k * 0.1 == pytest.approx(180.0)  # crank in line with the frame, away from D
    assert design.gamma_min_where.startswith("crank angle 180°")


def test_slider_crank_stroke_and_K_against_the_solver():
    design = builders.slider_crank(0.05, 0.2, 0.02, crank_deg=90.0)
    H, K = slider_stroke_and_K(design.scene)
    assert H == pytest.approx(design.extra["stroke"], rel=1e-9)
    assert K == pytest.approx(design.K, rel=1e-9)


def test_guide_bar_swing_and_K_against_the_solver():
    design = builders.guide_bar(0.03, 0.06, crank_deg=10.0)
    psi, K = rocker_swing_and_K(design.scene)
    assert psi == pytest.approx(math.radians(60.0), rel=1e-9)
    assert K == pytest.approx(2.0, rel=1e-9)


def test_guide_bar_transmission_angle_is_90_degrees():
    """The guide's force on the block is normal to the guide, and so is the velocity of the guide's
    point under the block: their angle is 0, the transmission angle 90 deg (solver's values)."""
    design = builders.guide_bar(0.03, 0.06, crank_deg=10.0)
    d = dict(design.scene, links=[{"name": n, "mass": 1.0, "com": [0.0, 0.0], "inertia": 1e-3}
                                  for n in ("crank", "slider", "rocker")],
             effects={"inertia": True}, outputs=["kinematics", "reactions"])
    d["links"][1]["com"] = d["joints"][1]["at"]
    res = linkage_sym.analyze(linkage_sym.load_scene(d))
    axis = res.links["rocker"].rotation + math.radians(d["joints"][2]["axis_deg"])
    t = np.stack([np.cos(axis), np.sin(axis)], axis=1)
    force = res.forces.reactions["B_slide"]
    B = res.joints["B"].position
    w = res.links["rocker"].omega
    D = np.array(d["joints"][3]["at"])
    vel = np.stack([-w * (B - D)[:, 1], w * (B - D)[:, 0]], axis=1)
    f_along = np.abs(np.sum(force * t, axis=1)) / np.hypot(*force.T)
    v_along = np.abs(np.sum(vel * t, axis=1)) / np.hypot(*vel.T)
    assert f_along.max() <= 1e-12 and v_along.max() <= 1e-12
    assert design.gamma_min == math.pi / 2


def test_solver_starts_where_the_builder_put_the_joints():
    design = builders.fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=57.0, branch="crossed")
    res = linkage_sym.analyze(linkage_sym.load_scene(design.scene))
    assert (res.status == "ok").all()
    assert res.joints["C"].position[0] == pytest.approx(design.scene["joints"][2]["at"], abs=1e-15)


# ------------------------------------------------------------------ refusals, each with its reason


@pytest.mark.parametrize("call, field, words", [
    (lambda: builders.fourbar(0, 3, 3, 3.5), "crank", "a length > 0 is expected"),
    (lambda: builders.fourbar(1, -3, 3, 3.5), "coupler", "a length > 0 is expected"),
    (lambda: builders.fourbar(1, 3, float("nan"), 3.5), "rocker", "a finite number"),
    (lambda: builders.fourbar(1, 3, 3, "x"), "ground", "a finite number"),
    (lambda: builders.fourbar(1, 1, 1, 5), "crank", "no four-bar has these lengths"),
    (lambda: builders.fourbar(1, 1, 1, 2.5, crank_deg=180), "crank_deg", "is more than coupler + rocker"),
    (lambda: builders.fourbar(1, 4, 1, 3.5, crank_deg=0), "crank_deg", "is less than |coupler - rocker|"),
    (lambda: builders.fourbar(1, 2.5, 2, 3.5, crank_deg=180), "crank_deg", "dead-centre position"),
    (lambda: builders.fourbar(1, 3, 3, 3.5, branch="up"), "branch", "one of open, crossed"),
    (lambda: builders.fourbar(1, 3, 3, 3.5, coupler_point=(1,)), "coupler_point", "two numbers"),
    (lambda: builders.fourbar(1, 3, 3, 3.5, steps=1), "steps", "an integer >= 2"),
    (lambda: builders.fourbar(1, 3, 3, 3.5, speed=float("inf")), "speed", "a finite number"),
    (lambda: builders.fourbar(1, 3, 3, 3.5, name=""), "name", "a non-empty name"),
    (lambda: builders.slider_crank(0.05, 0.1, 0.2, crank_deg=-90), "crank_deg", "cannot reach the slider's line"),
    (lambda: builders.slider_crank(0.05, 0.1, 0.05, crank_deg=-90), "crank_deg", "perpendicular to the slider's line"),
    (lambda: builders.slider_crank(0.05, 0.1, branch="up"), "branch", "one of right, left"),
    (lambda: builders.guide_bar(0.05, 0.05), "crank", "the block would pass through the guide's pivot D"),
    (lambda: builders.guide_bar(0.05, 0.0), "ground", "a length > 0"),
])
def test_refusals_name_the_field_and_the_reason(call, field, words):
    with pytest.raises(SynthesisError) as err:
        call()
    assert err.value.field == field
    assert words in err.value.reason


def test_fourbar_crank_pin_on_the_rocker_pivot_is_refused():
    """Crank = ground and coupler = rocker: at a crank angle of 1.24e-157 deg the pin B is 2.2e-159 m
    from D; the direction B -> D, which places C, is rounding (the old code wrote a coupler 6e-8 too
    long): refused, naming the crank angle and the lengths that bring B onto D."""
    with pytest.raises(SynthesisError) as err:
        builders.fourbar(1, 1, 1, 1, crank_deg=1.24e-157)
    assert err.value.field == "crank_deg"
    assert "the crank pin B is 2.16421e-159 m from the rocker pivot D" in err.value.reason
    assert "crank 1 m and ground 1 m bring B onto D" in err.value.reason


def _exact_length(p, q) -> float:
    """|pq| of two written points: the squared distance exact in rationals, one rounding."""
    return math.sqrt(float((Fraction(p[0]) - Fraction(q[0])) ** 2 + (Fraction(p[1]) - Fraction(q[1])) ** 2))


@pytest.mark.parametrize("scale", [1e-3, 1.0, 7.5])
@pytest.mark.parametrize("mismatch", [0.0, 2.0 ** -40, -(2.0 ** -40), 2.0 ** -30])
def test_fourbar_near_the_rocker_pivot_builds_exact_or_is_refused(scale, mismatch):
    """B approaching D (crank = ground, rocker = coupler (1 + mismatch)): |BD| from 1e-3 to 1e-15 of
    the size.  Each build is refused (``crank_deg``) exactly when |BD| <= 1e-9 of the largest length,
    or the written lengths are the requested ones to 1e-12 relative: distances of the written
    coordinates in exact rational arithmetic against the request.  (The old code wrote a rocker
    4e-12 too long at mismatch 2**-30, |BD| = 1e-8 (b*b - c*c over a small |BD|), and 6e-8 at
    |BD| = 2e-159.)"""
    a = d = 1.3 * scale
    b, c = 0.9 * scale, 0.9 * scale * (1.0 + mismatch)
    for k in range(3, 16):
        phi = 2.0 * math.asin(10.0 ** -k / 2.0)  # |BD| = 1e-k a (to B's rounding, 2e-16 a)
        for branch in ("open", "crossed"):
            bd = 10.0 ** -k * a
            try:
                design = builders.fourbar(a, b, c, d, crank_deg=math.degrees(phi), branch=branch)
            except SynthesisError as err:
                assert err.field == "crank_deg"
                assert bd <= 1.01e-9 * a or bd < abs(b - c) * 1.01  # not assemblable there
                continue
            assert bd > 0.99e-9 * a
            j = {x["name"]: x["at"] for x in design.scene["joints"]}
            for (p, q), want in ((("A", "B"), a), (("B", "C"), b), (("C", "D"), c)):
                assert _exact_length(j[p], j[q]) == pytest.approx(want, rel=REL, abs=0)


def test_dead_centre_refusal_is_the_solver_s_singular_assembly():
    """The tangency the builder refuses (|BD| = b + c exactly: 1 + 3.5 = 2.5 + 2 at 180 deg) is one
    the solver cannot start from either."""
    a, b, c, d = 1.0, 2.5, 2.0, 3.5
    scene = {"name": "t", "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
             "joints": [{"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
                        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [-a, 0.0]},
                        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [-a + b, 0.0]},
                        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [d, 0.0]}],
             "drivers": [{"joint": "A", "toward": "B", "start_deg": 180, "stop_deg": 540,
                          "steps": 5, "speed": 1.0}], "outputs": ["kinematics"]}
    with pytest.raises(linkage_sym.SceneError):
        linkage_sym.compile_plan(linkage_sym.load_scene(scene))


def test_notes_say_when_the_crank_does_not_turn_fully():
    d = builders.fourbar(3.0, 1.0, 3.5, 4.0, crank_deg=60)  # Grashof double-rocker
    assert d.notes[0].startswith("Grashof class: double-rocker") and d.K is None
    assert "cannot make the full turn" in d.notes[1]
    s = builders.slider_crank(0.05, 0.06, 0.02, crank_deg=90)
    assert s.K is None and "cannot make a full turn" in s.notes[0]
    g = builders.guide_bar(0.08, 0.06)
    assert g.K is None and "turns fully" in g.notes[0]
    r = builders.fourbar(2.375, 2.125, 1.9375, 2.5, crank_deg=4.0)  # the rocker is the shortest
    assert r.notes[0].startswith("Grashof class: crank-rocker") and r.K is None
    assert "the rocker CD is this loop's crank" in r.notes[1]
