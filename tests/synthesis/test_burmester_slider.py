"""Slider dyads in Burmester motion generation: poses of random known slider-cranks (offset
and guide direction random) give that slider-crank among the solutions to 1e-9 of its size,
and every defect-free design passes through every pose -- measured here by the solver on the
scene as written (tests.support.slider_reference), not by the synthesis."""

import json
import math

import numpy as np
import pytest

from linkage_sym.synthesis.burmester_slider import slider_points
from linkage_sym.synthesis.motion import motion_synthesis, table
from tests.support.slider_reference import random_slider_crank, solve_at

POSES = [[0.0, 0.0, 0.0], [1.0, 0.2, 10.0], [1.8, 0.7, 25.0], [2.3, 1.5, 45.0], [2.5, 2.4, 70.0]]


def _known(seed, n):
    """A random slider-crank, its poses (the coupler frame: origin P, the coupler's angle) at
    n crank angles spread over 210 degrees, its joints at pose 1 and its size."""
    known = random_slider_crank(np.random.default_rng(seed))
    th = np.radians(known["drivers"][0]["start_deg"] + np.linspace(0.0, 210.0, n))
    res = solve_at(known, th)
    P, rot = res.points["P"].position, res.links["coupler"].rotation
    poses = [[float(P[j, 0]), float(P[j, 1]), math.degrees(rot[j])] for j in range(n)]
    joints = {j["name"]: j for j in known["joints"]}
    size = max(math.dist(joints[a]["at"], joints[b]["at"]) for a, b in ("AB", "BC", "AC"))
    return poses, joints, size


def _through_poses(scene, crank_angles, poses):
    """The largest distance of the solver's coupler frame from a pose (m, rotation error times
    the coupler's length added), the scene read back from JSON."""
    scene = json.loads(json.dumps(scene))
    res = solve_at(scene, np.asarray(crank_angles))
    at = {j["name"]: j["at"] for j in scene["joints"]}
    b = math.dist(at["B"], at["C"])
    P, rot = res.points["P"].position, res.links["coupler"].rotation
    err = [math.dist(P[k], p[:2]) + b * abs(math.remainder(rot[k] - math.radians(p[2] - poses[0][2]),
                                                            2 * math.pi))
           for k, p in enumerate(poses)]
    return max(err) / b


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_five_poses_of_a_slider_crank_give_it_back(seed):
    poses, j, size = _known(seed, 5)
    result = motion_synthesis(poses)
    sliders = [d for d in result.designs if d.kind == "slider-crank"]
    assert sliders
    found = 0
    for d in sliders:
        at = {x["name"]: x for x in d.scene["joints"]}
        off = sum(math.dist(at[n]["at"], j[n]["at"]) for n in "ABC")
        turn = abs(math.remainder(math.radians(at["C_guide"]["axis_deg"] - j["C_guide"]["axis_deg"]),
                                  math.pi))
        found += off <= 1e-9 * size and turn <= 1e-9
    assert found == 1
    for d in result.designs:
        if d.check.defect_free:
            assert _through_poses(d.scene, d.check.crank_angles, poses) <= 1e-9
    rows = table(result)
    assert {r["linkage"] for r in rows} >= {"slider-crank"}
    assert all(math.isnan(r["guide_deg"]) == (r["linkage"] == "four-bar") for r in rows)


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
@pytest.mark.parametrize("seed", [5, 6])
def test_four_poses_slider_pin_and_designs_through_them(seed):
    poses, j, size = _known(seed, 4)
    pins = slider_points(poses)
    assert 1 <= len(pins) <= 3
    assert min(math.dist(s.circle, j["C"]["at"]) for s in pins) <= 1e-9 * size
    result = motion_synthesis(poses)
    free = [d for d in result.designs if d.kind == "slider-crank" and d.check.defect_free]
    assert free
    for d in free:
        assert _through_poses(d.scene, d.check.crank_angles, poses) <= 1e-9


def test_five_general_poses_have_no_slider_dyad():
    # a random-start Newton search on the collinearity of the five positions finds none either
    from scipy.optimize import least_squares

    P = np.array(POSES)
    Z, R = P[:, 0] + 1j * P[:, 1], np.exp(1j * np.radians(P[:, 2]))
    rng = np.random.default_rng(0)

    def f(x):
        w = np.exp(-1j * x[2])
        M = Z + R * complex(x[0], x[1])
        return ((M[1:] - M[0]) * w).imag

    best = min(np.max(np.abs(least_squares(f, np.append(rng.uniform(-5, 5, 2),
                                                         rng.uniform(-2, 2)), xtol=1e-15,
                                           ftol=1e-15, gtol=1e-15).fun)) for _ in range(40))
    assert best > 1e-6
    assert slider_points(POSES) == []
