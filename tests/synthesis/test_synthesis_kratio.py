"""Synthesis by the stroke-time ratio K (``linkage_sym.synthesis.kratio``).

Every synthesized scene is analysed by the solver, which shares no code with
the synthesis: the output's extreme positions are the roots of its velocity
(tests/support/synthesis_checks.py, brentq on single-step solver runs), and the
swing or stroke and K they give must equal the request to 1e-9 (relative).

Admissible and forbidden requests are generated here from an independent
construction of the auxiliary circle: a chord C1C2 of the rocker circle, the
two circles through C1, C2 with the central angle 2 theta, points of them
sampled and kept where the angle C1 A C2 (atan2) is theta, and the side-of-line
criterion (C1 and C2 on one side of AD) evaluated here.
"""

import math
import re

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.synthesis import kratio, kratio_check
from linkage_sym.synthesis.common import SynthesisError

from tests.support.synthesis_checks import rocker_swing_and_K, slider_stroke_and_K

TOL = 1e-9
"""Swing, stroke and K from the solver's extremes against the request (relative)."""


# ------------------------------------------------------------------ independent construction


def any_admissible(theta, psi, c=1.0, n=20001) -> bool:
    """Whether any sampled point of the two arcs is an admissible crank pivot, the samples
    near the bisector and the arcs' ends included (:func:`rocker_arcs` leaves those out of
    its lists, so an empty list there does not mean that K leaves no pivot at all).

    Just below the largest K a swing allows, the admissible pivots are an arc next to C1 or
    C2 whose length goes to 0 with the margin (1.7e-5 rad at K = 3.2352466, psi = 10 deg,
    found by hypothesis): the arcs are also sampled at 1e-2 ... 1e-12 rad from each end."""
    return any(ok.any() for _, ok, _, _ in rocker_arcs(theta, psi, c, n, margins=False))


def rocker_arcs(theta, psi, c=1.0, n=20001, margins=True):
    """Points A seeing C1C2 under theta (both arcs), with their admissibility; D at the origin."""
    C1 = c * np.array([-math.sin(psi / 2), math.cos(psi / 2)])
    C2 = c * np.array([math.sin(psi / 2), math.cos(psi / 2)])
    M, half = (C1 + C2) / 2, math.dist(C1, C2) / 2
    R = half / math.sin(theta)
    out = []
    for side in (1, -1):
        O = M + side * np.array([0.0, R * math.cos(theta)])
        t = np.linspace(0, 2 * math.pi, n, endpoint=False)
        if not margins:  # geometric samples next to the ends C1 and C2
            ends = [math.atan2(*(C - O)[::-1]) for C in (C1, C2)]
            near = np.geomspace(1e-12, 1e-2, 41)
            t = np.concatenate([t, *(e + sg * near for e in ends for sg in (1, -1))])
        A = O + R * np.stack([np.cos(t), np.sin(t)], axis=1)
        u, v = C1 - A, C2 - A
        seen = np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]), np.sum(u * v, axis=1))
        keep = np.abs(seen - theta) < 1e-6
        A = A[keep]
        s1 = A[:, 0] * C1[1] - A[:, 1] * C1[0]  # (A - D) x (C1 - D), D = 0
        s2 = A[:, 0] * C2[1] - A[:, 1] * C2[0]
        l1, l2 = np.hypot(*(C1 - A).T), np.hypot(*(C2 - A).T)
        far = np.abs(l1 - l2) > (1e-3 * c if margins else -1.0)  # away from the bisector (a -> 0)
        near_ends = np.minimum(l1, l2) > (1e-3 * c if margins else -1.0)
        out.append((A[far & near_ends], (s1 * s2 > 0)[far & near_ends],
                    (np.abs(l1 - l2) / 2)[far & near_ends], np.hypot(*A.T)[far & near_ends]))
    return out


def gamma_min_of(a, b, c, d):
    """Minimum transmission angle of a crank-rocker: law of cosines at crank angles 0 and pi."""
    g = [math.acos((b * b + c * c - r * r) / (2 * b * c)) for r in (d - a, d + a)]
    return min(min(x, math.pi - x) for x in g)


Ks = st.floats(1.05, 4.0)
psis = st.floats(10.0, 170.0)


# ------------------------------------------------------------------ crank-rocker


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(Ks, psis, st.floats(0.01, 10.0))
def test_crank_rocker_without_condition_meets_K_and_psi(K, psi, c):
    theta = math.pi * (K - 1) / (K + 1)
    assume(math.degrees(theta) < 90 + psi / 2 - 1.0)
    d = kratio.crank_rocker(K, c, psi)
    got_psi, got_K = rocker_swing_and_K(d.scene)
    assert got_psi == pytest.approx(math.radians(psi), rel=TOL)
    assert got_K == pytest.approx(K, rel=TOL)
    assert d.lengths["rocker"] == c


def grashof_margin(a, b, c, d):
    """``|s + l - (p + q)|`` over the perimeter: 0 at Grashof's change point."""
    s = sorted((a, b, c, d))
    return abs(s[0] + s[3] - s[1] - s[2]) / sum(s)


CHANGE_POINT_MARGIN = 1e-8
"""Admissible pivots whose four-bar is this close to Grashof's change point (fraction of the
perimeter) may be refused: next to an arc's end the linkage tends to the change point, and
the library refuses it within 1e-9 (``CHANGE_POINT_TOL``); the margin is ten times that, for the
rounding of this construction's lengths (1e-15) and of the library's."""


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(Ks, psis, st.floats(0.0, 1.0), st.sampled_from(["ground", "crank"]))
# the pivot 1.3e-13 (of the perimeter) from the change point: the joint coordinates missed K by
# 3.1e-9, the refusal said only that; now the refusal says it is no crank-rocker there
@example(K=2.7734375, psi=10.0, pick=0.0, which="ground")
def test_crank_rocker_at_random_admissible_pivots(K, psi, pick, which):
    """A random admissible pivot of the independent construction: its ground (or crank) length
    as the condition gives a crank-rocker with the request's K and psi, and the length as given;
    within :data:`CHANGE_POINT_MARGIN` of the change point it may be refused as one (the library
    takes the pivot with the larger transmission angle where one on each arc meets the length, so
    a pivot this close need not be its choice; the example's must, a test below)."""
    theta = math.pi * (K - 1) / (K + 1)
    pts = [(A, ok, a, dd) for A, ok, a, dd in rocker_arcs(theta, math.radians(psi))]
    cand = [(A[i], a[i], dd[i]) for A, ok, a, dd in pts for i in np.flatnonzero(ok)]
    assume(cand)
    A, a, dd = cand[int(pick * (len(cand) - 1))]
    h = math.radians(psi) / 2  # the rocker's extreme positions, D at the origin (rocker_arcs)
    l1, l2 = math.dist((-math.sin(h), math.cos(h)), A), math.dist((math.sin(h), math.cos(h)), A)
    margin = grashof_margin(a, (l1 + l2) / 2, 1.0, dd)
    kw = {"ground": float(dd)} if which == "ground" else {"crank": float(a)}
    try:
        design = kratio.crank_rocker(K, 1.0, psi, **kw)
    except SynthesisError as err:
        assert margin <= CHANGE_POINT_MARGIN, err
        assert err.field == which and "no crank-rocker: Grashof class: change point" in err.reason
        return
    assert design.lengths[which] == kw[which]
    L = design.lengths
    # a pivot next to an arc's end can give a transmission angle of 1e-4 degree: the limit
    # positions are then ill-conditioned (the rate's rounding over the sine of that angle),
    # and K located from the rates carries it (3e-9 at 1e-4 degree); the 1e-9 check is made
    # where the design transmits at least 1 degree
    assume(gamma_min_of(L["crank"], L["coupler"], L["rocker"], L["ground"]) > math.radians(1.0))
    got_psi, got_K = rocker_swing_and_K(design.scene)
    assert got_psi == pytest.approx(math.radians(psi), rel=TOL)
    assert got_K == pytest.approx(K, rel=TOL)


def test_crank_rocker_next_to_an_arc_s_end_is_refused_as_a_change_point():
    """K = 2.7734375, psi = 10 deg, the ground 1.0012299194512315 (hypothesis): the pivot is 1.3e-13
    of the perimeter from Grashof's change point, the four-bar is no crank-rocker there (its
    limit positions missed K by 3.1e-9): refused, the reason given."""
    a, b, c, d = 0.08659654534158585, 0.08782646479310896, 1.0, 1.0012299194512315  # 50 digits
    assert grashof_margin(a, b, c, d) < 1e-12
    with pytest.raises(SynthesisError) as err:
        kratio.crank_rocker(2.7734375, 1.0, 10.0, ground=d)
    assert err.value.field == "ground"
    assert "is next to an end of an admissible arc" in err.value.reason
    assert "no crank-rocker: Grashof class: change point" in err.value.reason


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(Ks, psis, st.floats(0.0, 1.0))
@example(K=3.234375, psi=10.0, pick=0.0)  # admissible pivots only next to the bisector
@example(K=3.2352465856939743, psi=10.0, pick=0.0)  # 4.7e-5 below the largest K: next to C2
def test_crank_rocker_crank_only_on_the_forbidden_arcs_is_refused(K, psi, pick):
    """A crank length that only pivots on the forbidden arcs give (same crank on both arcs at the
    same angle alpha; here: no admissible sample within 1e-3 of it) is refused, reason given."""
    theta = math.pi * (K - 1) / (K + 1)
    arcs = rocker_arcs(theta, math.radians(psi))
    good = np.concatenate([a[ok] for A, ok, a, dd in arcs])
    bad = np.concatenate([a[~ok] for A, ok, a, dd in arcs])
    if good.size:
        bad = np.array([x for x in bad if np.min(np.abs(good - x)) > 1e-3])
    assume(bad.size)
    a = float(bad[int(pick * (bad.size - 1))])
    with pytest.raises(SynthesisError) as err:
        kratio.crank_rocker(K, 1.0, psi, crank=a)
    if good.size or any_admissible(theta, math.radians(psi)):
        assert err.value.field == "crank" and "no admissible crank pivot" in err.value.reason
    else:  # no admissible pivot at all: K is refused first
        assert err.value.field == "K" and "leaves no admissible crank pivot" in err.value.reason


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(Ks, psis, st.floats(0.0, 1.0))
def test_crank_rocker_ground_only_on_the_forbidden_arcs_is_refused(K, psi, pick):
    theta = math.pi * (K - 1) / (K + 1)
    arcs = rocker_arcs(theta, math.radians(psi))
    good = np.concatenate([dd[ok] for A, ok, a, dd in arcs])
    bad = np.concatenate([dd[~ok] for A, ok, a, dd in arcs])
    if good.size:
        bad = np.array([x for x in bad if np.min(np.abs(good - x)) > 1e-3])
    assume(bad.size)
    d = float(bad[int(pick * (bad.size - 1))])
    with pytest.raises(SynthesisError) as err:
        kratio.crank_rocker(K, 1.0, psi, ground=d)
    if good.size or any_admissible(theta, math.radians(psi)):
        assert err.value.field == "ground"
        assert "lie on the forbidden arc between the lines D-C1 and D-C2" in err.value.reason
    else:  # no admissible pivot at all: K is refused first
        assert err.value.field == "K" and "leaves no admissible crank pivot" in err.value.reason


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(st.floats(1.01, 30.0), psis)
def test_which_K_have_a_crank_rocker(K, psi):
    """theta < 90 + psi/2 (deg) exactly when the independent construction has an admissible
    point; the synthesis refuses exactly the others."""
    theta = math.pi * (K - 1) / (K + 1)
    margin = math.degrees(theta) - (90 + psi / 2)
    assume(abs(margin) > 0.5)
    has = any(ok.any() for A, ok, a, dd in rocker_arcs(theta, math.radians(psi)))
    assert has == (margin < 0)
    if has:
        kratio.crank_rocker(K, 1.0, psi)
    else:
        with pytest.raises(SynthesisError) as err:
            kratio.crank_rocker(K, 1.0, psi)
        assert err.value.field == "K" and "θ < 90° + ψ/2" in err.value.reason


@pytest.mark.parametrize("K, psi", [pytest.param(1.5, 45.0, marks=pytest.mark.slow),
                                    pytest.param(1.2, 100.0, marks=pytest.mark.slow),
                                    (2.5, 30.0), (4.0, 150.0)])
def test_crank_rocker_best_transmission_angle(K, psi):
    """Without a condition, no admissible pivot of the independent construction gives a larger
    minimum transmission angle (law of cosines here) than the chosen one, beyond 1e-9; and the
    chosen one's is the solver's (transmission angles of a fine sweep, the extremes hit)."""
    theta = math.pi * (K - 1) / (K + 1)
    design = kratio.crank_rocker(K, 1.0, psi)
    best = 0.0
    for A, ok, a, dd in rocker_arcs(theta, math.radians(psi), n=200001):
        # crank (l1 - l2)/2 and coupler (l1 + l2)/2 of each admissible pivot
        C1 = np.array([-math.sin(math.radians(psi) / 2), math.cos(math.radians(psi) / 2)])
        C2 = C1 * np.array([-1.0, 1.0])
        l1, l2 = np.hypot(*(C1 - A[ok]).T), np.hypot(*(C2 - A[ok]).T)
        for ai, bi, di in zip(np.abs(l1 - l2) / 2, (l1 + l2) / 2, dd[ok]):
            best = max(best, gamma_min_of(ai, bi, 1.0, di))
    assert design.gamma_min >= best - 1e-9
    assert design.gamma_min <= best + 1e-4  # the sampling is fine enough to come this close
    L = design.lengths
    assert design.gamma_min == pytest.approx(gamma_min_of(L["crank"], L["coupler"], 1.0,
                                                          L["ground"]), rel=1e-12)
    sweep = dict(design.scene["drivers"][0], start_deg=0.0, stop_deg=360.0, steps=721)
    res = linkage_sym.analyze(linkage_sym.load_scene(dict(design.scene, drivers=[sweep])))
    g = res.transmission_angles["C"]
    assert np.min(np.minimum(g, np.pi - g)) == pytest.approx(design.gamma_min, rel=1e-12)
    assert "largest minimum transmission angle" in design.notes[-1]


def test_crank_rocker_worked_example():
    """K = 1.5, rocker 75 mm, swing 45 deg, frame 100 mm (numbers of our own: the textbook
    section gives the procedure only)."""
    d = kratio.crank_rocker(1.5, 0.075, 45.0, ground=0.1)
    assert math.degrees(d.theta) == pytest.approx(36.0, rel=1e-15)
    psi, K = rocker_swing_and_K(d.scene)
    assert math.degrees(psi) == pytest.approx(45.0, rel=TOL) and K == pytest.approx(1.5, rel=TOL)
    assert d.extra["arc"] == "far"


# ------------------------------------------------------------------ slider-crank


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(st.floats(1.05, 2.9), st.floats(0.01, 10.0), st.floats(0.02, 0.98), st.integers(0, 2),
       st.booleans())
def test_slider_crank_meets_K_and_stroke(K, H, frac, which, negative):
    theta = math.pi * (K - 1) / (K + 1)
    if which == 0:
        e = frac * H / math.tan(theta) * (-1 if negative else 1)
        d = kratio.slider_crank(K, H, offset=e)
        assert d.lengths["offset"] == e
    elif which == 1:
        lo, hi = H * math.tan(theta / 2) / 2, H / 2
        a = lo + frac * (hi - lo)
        d = kratio.slider_crank(K, H, crank=a)
        assert d.lengths["crank"] == a
    else:
        d = kratio.slider_crank(K, H)
    got_H, got_K = slider_stroke_and_K(d.scene)
    assert got_H == pytest.approx(H, rel=TOL)
    assert got_K == pytest.approx(K, rel=TOL)


@settings(max_examples=40, deadline=None)
@given(st.floats(1.05, 2.9), st.floats(1.0 + 1e-6, 3.0))
def test_slider_crank_offset_beyond_H_cot_theta_is_refused(K, factor):
    """Above H cot(theta) no point of the auxiliary arc at that height has its foot outside the
    stroke (sampled here); the synthesis refuses, naming the bound."""
    H = 1.0
    theta = math.pi * (K - 1) / (K + 1)
    e = factor * H / math.tan(theta)
    R = H / (2 * math.sin(theta))
    t = np.linspace(0, 2 * math.pi, 200001)
    A = np.stack([R * np.cos(t), R * math.cos(theta) + R * np.sin(t)], axis=1)
    outside = A[np.abs(A[:, 0]) > H / 2]
    assert outside[:, 1].max() <= H / math.tan(theta) * (1 + 1e-9)
    with pytest.raises(SynthesisError) as err:
        kratio.slider_crank(K, H, offset=e)
    assert err.value.field == "offset" and "too large for the stroke" in err.value.reason


@pytest.mark.parametrize("K, e", [(1 + 1e-6, 1e-10), (1 + 1e-4, 1e-12), (1 + 1e-9, 1e-10)])
def test_slider_crank_with_small_theta_and_offset_meets_K(K, e):
    """The pivot's angle alpha from cos(2 alpha + theta) = cos(theta) - e/R: taken as
    acos(cos(theta) - e/R) it lost every digit of a small theta or e/R (K = 1 + 1e-6 with
    e = 1e-10 gave K - 1 = 1.017e-6; K = 1 + 1e-9 a negative alpha, refused as a connecting
    rod of 0 m)."""
    d = kratio.slider_crank(K, 0.1, offset=e)
    assert d.lengths["offset"] == e and d.extra["alpha"] > 0
    got_H, got_K = slider_stroke_and_K(d.scene)
    assert got_H == pytest.approx(0.1, rel=TOL)
    assert got_K == pytest.approx(K, rel=TOL)


def test_slider_crank_best_transmission_angle():
    """Without a condition: no offset on a fine grid gives a larger minimum transmission angle
    (acos((a + e)/b), lengths from the stroke's extremes written here) than the chosen design."""
    K, H = 1.4, 0.1
    theta = math.pi * (K - 1) / (K + 1)
    d = kratio.slider_crank(K, H)
    best = 0.0
    for e in np.linspace(1e-6, H / math.tan(theta) * (1 - 1e-6), 20001):
        # AC1 - AC2 and the extremes on the line: sqrt(l1^2 - e^2) - sqrt(l2^2 - e^2) = H
        # with the inscribed angle theta: l1 l2 sin(theta) = e H (twice the triangle's area)
        # and H^2 = l1^2 + l2^2 - 2 l1 l2 cos(theta)
        p = e * H / math.sin(theta)                       # l1 l2
        s = math.sqrt(H * H + 2 * p * (1 + math.cos(theta)))  # l1 + l2
        q = math.sqrt(max(s * s - 4 * p, 0.0))            # l1 - l2
        a, b = q / 2, s / 2
        best = max(best, math.acos(min(1.0, (a + e) / b)))
    assert d.gamma_min >= best - 1e-9
    assert d.gamma_min <= best + 1e-6


# ------------------------------------------------------------------ guide-bar


@pytest.mark.slow
@settings(max_examples=30, deadline=None)
@given(st.floats(1.01, 20.0), st.floats(0.01, 10.0))
def test_guide_bar_meets_K(K, d):
    design = kratio.guide_bar(K, d)
    theta = math.pi * (K - 1) / (K + 1)
    psi, got_K = rocker_swing_and_K(design.scene)
    assert psi == pytest.approx(theta, rel=TOL)
    assert got_K == pytest.approx(K, rel=TOL)


# ------------------------------------------------------------------ refusals


@pytest.mark.parametrize("call, field, words", [
    (lambda: kratio.crank_rocker(0.8, 1.0, 40.0), "K", "K >= 1; got 0.8"),
    (lambda: kratio.crank_rocker(1.0, 1.0, 40.0), "K", "K = 1 means no quick return"),
    (lambda: kratio.crank_rocker(float("nan"), 1.0, 40.0), "K", "a finite number"),
    (lambda: kratio.crank_rocker(20.0, 1.0, 40.0), "K", "θ < 90° + ψ/2"),
    (lambda: kratio.crank_rocker(1.5, 0.0, 40.0), "rocker", "a length > 0"),
    (lambda: kratio.crank_rocker(1.5, 1.0, 180.0), "swing_deg", "less than 180°"),
    (lambda: kratio.crank_rocker(1.5, 1.0, 0.0), "swing_deg", "more than 0°"),
    (lambda: kratio.crank_rocker(1.5, 1.0, 40.0, ground=1.0, crank=0.2), "ground", "not both"),
    (lambda: kratio.crank_rocker(1.5, 0.075, 45.0, ground=0.3), "ground",
     "no point of the auxiliary arcs is at that distance"),
    (lambda: kratio.crank_rocker(1.5, 0.075, 45.0, ground=0.13), "ground",
     "lie on the forbidden arc between the lines D-C1 and D-C2"),
    (lambda: kratio.crank_rocker(1.5, 0.075, 45.0, crank=0.05), "crank", "at most half the chord"),
    (lambda: kratio.slider_crank(3.0, 0.1), "K", "below 90° (K < 3)"),
    (lambda: kratio.slider_crank(1.4, 0.0), "stroke", "a length > 0"),
    (lambda: kratio.slider_crank(1.4, 0.1, offset=0.0), "offset", "no quick return"),
    (lambda: kratio.slider_crank(1.4, 0.1, offset=0.2), "offset", "too large for the stroke"),
    (lambda: kratio.slider_crank(1.4, 0.1, offset=0.01, crank=0.03), "offset", "not both"),
    (lambda: kratio.slider_crank(1.4, 0.1, crank=0.06), "crank", "the crank must lie between"),
    (lambda: kratio.slider_crank(1.4, 0.1, crank=0.01), "crank", "the crank must lie between"),
    (lambda: kratio.guide_bar(2.0, -1.0), "ground", "a length > 0"),
    (lambda: kratio.guide_bar(0.9, 1.0), "K", "K >= 1"),
])
def test_refusals_name_the_field_and_the_reason(call, field, words):
    with pytest.raises(SynthesisError) as err:
        call()
    assert err.value.field == field
    assert words in err.value.reason, err.value.reason


# ------------------------------------------------------------------ the scene holds K (issue 27)


def mp_scene_K(scene):
    """``K`` of a scene's coordinates as written, in 50-digit arithmetic: the textbook's
    extreme-position angle ``theta`` from the limit positions (crank and coupler in line),
    ``K = (pi + theta) / (pi - theta)``; for a guide-bar the guide's swing
    ``theta = 2 asin(a / d)``."""
    import mpmath as mp

    with mp.workdps(50):
        P = {j["name"]: (mp.mpf(j["at"][0]), mp.mpf(j["at"][1])) for j in scene["joints"]}
        dist = lambda p, q: mp.sqrt((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2)  # noqa: E731
        a = dist(P["A"], P["B"])
        if "D" in P and "C" not in P:  # guide-bar
            theta = 2 * mp.asin(a / dist(P["A"], P["D"]))
        elif "D" not in P:  # slider-crank, slide along x
            b, e = dist(P["B"], P["C"]), P["C"][1] - P["A"][1]
            theta = abs(mp.asin(e / (b - a)) - mp.asin(e / (b + a)))
        else:  # crank-rocker: the angles C1 A D and C2 A D by the law of cosines
            b, c, d = dist(P["B"], P["C"]), dist(P["C"], P["D"]), dist(P["A"], P["D"])
            g = [mp.acos((d ** 2 + r ** 2 - c ** 2) / (2 * d * r)) for r in (b + a, b - a)]
            theta = abs(g[0] - g[1])
        return float((mp.pi + theta) / (mp.pi - theta))


REQUESTS_MET = [
    lambda: kratio.guide_bar(2.0, 0.4), lambda: kratio.guide_bar(1000.0, 0.0307),
    lambda: kratio.slider_crank(1.4, 0.1, offset=0.02), lambda: kratio.slider_crank(2.2892, 0.238),
    lambda: kratio.slider_crank(2.2892, 0.238, offset=-0.01),
    lambda: kratio.crank_rocker(1.4, 0.05, 40.0), lambda: kratio.crank_rocker(1.2, 0.05, 40.0, ground=0.09),
]


@pytest.mark.parametrize("call", REQUESTS_MET)
def test_scene_K_is_the_coordinates_K(call):
    """:func:`kratio.scene_K` against the 50-digit closed form of the same coordinates
    (1e-12: float64 rounding of a well-conditioned evaluation), and both against the
    request (``K_RTOL``)."""
    design = call()
    ref = mp_scene_K(design.scene)
    assert abs(kratio.scene_K(design) - ref) <= 1e-12 * ref
    assert abs(ref - design.K) <= kratio.K_RTOL * design.K


@pytest.mark.parametrize("call, field, K", [
    # the guide-bar's crank within a few ulp of the frame distance
    (lambda: kratio.guide_bar(2200000, 0.0307), "K", 2.2e6),
    # a tiny offset: crank and connecting rod equal to 1e-12, K rests on their difference
    (lambda: kratio.slider_crank(2.2892, 0.238, offset=-2.4e-13), "offset", 2.2892),
    # theta within 1e-10 of 90 degrees: asin(e / (b - a)) at 1
    (lambda: kratio.slider_crank(2.9999999999, 1e-29), "K", 2.9999999999),
])
def test_a_request_the_scene_cannot_hold_is_refused_with_the_K_it_would_have(monkeypatch, call,
                                                                               field, K):
    with pytest.raises(SynthesisError) as err:
        call()
    assert err.value.field == field
    got = float(re.search(r"limit positions give K = ([0-9.e+-]+)", err.value.reason).group(1))
    # the scene it would have written (the check switched off), by the 50-digit closed form
    monkeypatch.setattr(kratio_check, "K_RTOL", math.inf)
    ref = mp_scene_K(call().scene)
    assert abs(ref - K) > 1e-9 * K  # the request really is not met
    assert abs(got - ref) <= 1e-9 * ref  # the message's K is the scene's (10 digits printed)
