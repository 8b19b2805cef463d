"""Slider-crank path generation: points taken from random known slider-cranks (offset and guide
direction random) are met by every reported design to 1e-9 of its coupler length, measured by
the solver on the scene as written (JSON), with no defect -- each checked here by the solver
(tests.support.slider_reference), not by the synthesis."""

import json
import math

import numpy as np
import pytest

from linkage_sym.synthesis.common import SynthesisError
from linkage_sym.synthesis.path_check import check
from linkage_sym.synthesis.path_gen import synthesize_path
from linkage_sym.synthesis.path_slider import scene_of
from tests.support.slider_reference import (
    coupler_points,
    random_slider_crank,
    slider_modes_and_gamma,
    solve_at,
)


def _targets(rng, n, span_deg):
    known = random_slider_crank(rng)
    th = np.radians(known["drivers"][0]["start_deg"] + np.linspace(0.0, span_deg, n))
    return coupler_points(known, th), th


def _coupler(scene):
    B, C = (np.array(j["at"]) for j in scene["joints"] if j["name"] in "BC")
    return float(np.hypot(*(C - B)))


def _verified(d, T, min_gamma):
    """The design as written (JSON) analysed by the solver: the largest distance from a
    target over the coupler's length; one mode, every step solved, order, transmission."""
    scene = json.loads(json.dumps(d.scene))
    assert [j["name"] for j in scene["joints"]] == ["A", "B", "C", "C_guide"]
    th = d.thetas
    q = np.linspace(th[0], th[-1], 401)
    solve_at(scene, q)  # asserts every step solved: no dead centre, none beyond reach
    modes, gamma = slider_modes_and_gamma(scene, q)
    assert len(set(modes.tolist())) == 1
    assert np.degrees(gamma).min() >= min_gamma - 1e-9
    steps = np.diff(th)
    assert ((steps > 0).all() or (steps < 0).all()) and abs(th[-1] - th[0]) < 2 * math.pi
    drv = scene["drivers"][0]
    assert math.radians(drv["start_deg"]) == pytest.approx(th[0], abs=1e-12)
    assert math.radians(drv["stop_deg"]) == pytest.approx(th[-1], abs=1e-12)
    return float(np.hypot(*(coupler_points(scene, th) - T).T).max()) / _coupler(scene)


@pytest.mark.parametrize("timing", [False, True])
def test_three_points_exact(timing):
    rng = np.random.default_rng(7)
    for _ in range(3):
        T, th = _targets(rng, 3, 150.0)
        ds = synthesize_path(T, np.degrees(th) if timing else None, keep=4,
                             linkage="slider-crank")
        assert ds, "no exact design"
        for d in ds:
            assert d.exact and _verified(d, T, 20.0) <= 1e-9
            if timing:
                assert np.allclose(np.diff(d.thetas), np.diff(th), rtol=0, atol=1e-12)


@pytest.mark.parametrize("n, timing", [(5, False), pytest.param(6, True, marks=pytest.mark.slow)])
def test_points_of_a_known_slider_crank_are_met_exactly(n, timing):
    rng = np.random.default_rng(20 + n)
    T, th = _targets(rng, n, 200.0)
    ds = synthesize_path(T, np.degrees(th) if timing else None, starts=1500, refine_best=10,
                         keep=3, min_transmission_deg=10.0, linkage="slider-crank")
    assert ds
    for d in ds:
        err = _verified(d, T, 10.0)
        assert d.exact and err <= 1e-9
        assert d.check.error / d.check.coupler == pytest.approx(err, rel=1e-6, abs=1e-15)


def test_check_names_the_slider_cranks_defects():
    z = np.array([0.0, 0.0, 0.5, 1.5, 0.3, 0.4, 0.6, 0.5])  # the crank turns fully
    th = np.radians([10.0, 60.0, 120.0])
    good = scene_of(z, 1.0, th)
    T = coupler_points(good, th)
    c = check(good, T, th)
    assert c.defects == "" and c.grashof == "slider-crank" and c.full_turn
    assert "order" in check(good, T[[0, 2, 1]], th[[0, 2, 1]]).defects
    # crank + offset = 1.3 > rod 1.0: the rod reaches the guide only for sin(theta) >= -0.7,
    # theta >= -44.4 deg
    rocker = np.array([0.0, 0.0, 1.0, 1.0, 0.3, 0.0, 0.3, 0.2])
    th2 = np.radians([0.0, -30.0, -60.0])
    c = check(scene_of(rocker, 1.0, th2), np.zeros((3, 2)), th2)
    assert "dead-centre" in c.defects and c.grashof == "slider-rocker" and not c.full_turn


def test_unknown_linkage_refused():
    with pytest.raises(SynthesisError, match="linkage"):
        synthesize_path([[0, 0], [1, 0], [1, 1]], linkage="six-bar")
