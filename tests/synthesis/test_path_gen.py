"""Path generation: every design reported passes through its points (to 1e-9 of the coupler
when exact), its reported error is the solver's, a known four-bar is recovered from its own
points, and no design has a defect -- each measured here by the solver on the written scene."""

import math

import numpy as np
import pytest

from linkage_sym.synthesis.common import SynthesisError
from linkage_sym.synthesis.path_check import check, scene_of
from linkage_sym.synthesis.path_gen import read_targets, resample, synthesize_path
from tests.support.funcpath_reference import (
    branch_modes,
    coupler_points,
    random_crank_rocker,
    solve_at,
)


def _targets(known, thetas):
    return coupler_points(known.scene, thetas)


def _no_defect(d, T, min_gamma):
    """The design checked independently: points, one branch, no dead centre, order, transmission."""
    th = d.thetas
    q = np.linspace(th[0], th[-1], 401)
    res = solve_at(d.scene, q)  # asserts every step solved: no dead centre, none beyond reach
    assert len(set(branch_modes(d.scene, q).tolist())) == 1
    steps = np.diff(th)
    assert (steps > 0).all() or (steps < 0).all()
    assert abs(th[-1] - th[0]) < 2 * math.pi
    g = np.asarray(res.transmission_angles["C"])
    assert np.degrees(np.minimum(g, np.pi - g)).min() >= min_gamma - 1e-9
    P = coupler_points(d.scene, th)
    return np.hypot(*(P - T).T).max()


def _coupler(d):
    B, C = (np.array(j["at"]) for j in d.scene["joints"][1:3])
    return float(np.hypot(*(C - B)))


@pytest.mark.slow  # over 10 s on a loaded machine: the fast lane stays under 2 min
@pytest.mark.parametrize("timing", [False, True])
def test_three_points_exact(timing):
    rng = np.random.default_rng(3)
    for _ in range(3):
        known = random_crank_rocker(rng, coupler_point=True)
        th = known.scene["drivers"][0]["start_deg"] + np.array([0.0, 70.0, 150.0])
        T = _targets(known, np.radians(th))
        ds = synthesize_path(T, th if timing else None, keep=4)
        assert ds, "no exact design"
        for d in ds:
            err = _no_defect(d, T, 20.0)
            assert err <= 1e-9 * _coupler(d)
            assert d.exact and d.check.error == pytest.approx(err, abs=1e-15)
            if timing:
                assert np.allclose(np.diff(d.thetas), np.radians(np.diff(th)), atol=1e-12)


@pytest.mark.slow
def test_known_design_recovered_and_errors_are_the_solvers():
    rng = np.random.default_rng(11)
    known = random_crank_rocker(rng, coupler_point=True)
    th = known.scene["drivers"][0]["start_deg"] + np.linspace(0.0, 200.0, 6)
    T = _targets(known, np.radians(th))
    size = float(np.max(np.hypot(*(T[:, None] - T[None]).transpose(2, 0, 1))))
    for timing in (th, None):
        ds = synthesize_path(T, timing, starts=4000, keep=3, min_transmission_deg=10.0)
        assert ds
        assert ds[0].check.error <= 1e-6 * size
        for d in ds:
            err = _no_defect(d, T, 10.0)
            assert d.check.error == pytest.approx(err, rel=1e-9, abs=1e-15)


def test_check_names_each_defect():
    z = np.array([0.0, 0.0, 1.5, 0.0, 0.5, 1.2, 1.1, 0.5, 0.4])
    th = np.radians([10.0, 60.0, 120.0])
    good = scene_of(z, 1.0, th)
    T = coupler_points(good, th)
    assert check(good, T, th).defects == ""
    assert "order" in check(good, T[[0, 2, 1]], th[[0, 2, 1]]).defects
    # a triple-rocker (1, 1, 1, frame 2.5) driven past the crank's reach (49.46 deg)
    rocker = np.array([0.0, 0.0, 2.5, 0.0, 1.0, 1.0, 1.0, 0.3, 0.2])
    th2 = np.radians([0.0, 30.0, 55.0])
    assert "dead-centre" in check(scene_of(rocker, 1.0, th2), np.zeros((3, 2)), th2).defects


def test_resample_and_refusals():
    pts = resample([[0, 0], [2, 0], [2, 2]], 5)
    assert np.allclose(pts, [[0, 0], [1, 0], [2, 0], [2, 1], [2, 2]], rtol=0, atol=1e-15)
    with pytest.raises(SynthesisError, match="points"):
        read_targets([[0, 0], [1, 1]])
    with pytest.raises(SynthesisError, match="coincide"):
        read_targets([[0, 0], [1, 1], [1, 1]])
    with pytest.raises(SynthesisError, match="crank_deg"):
        synthesize_path([[0, 0], [1, 0], [1, 1]], [0, 10])
