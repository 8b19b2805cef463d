"""Two links at rest relative to each other: a shared pin is still their centre (issue 27).

The crank-rocker's coupler and rocker turn alike (``w_coupler = w_rocker``) at a step
found here by a root search on a closed-form four-bar velocity analysis written in this
file (circle intersection for ``C``, the velocity loop solved by Cramer's rule): no code of
the package is used for it.  At that step their relative motion vanishes, so every point
has zero relative velocity, but the pin ``C`` has none at every step: it is reported as
their centre.  A pair without a shared pin at relative rest stays ``undefined``.

Tolerances: the root to ``xtol = 1e-15`` rad, so the links' relative angular velocity at
that step is about 1e-15 of the crank's, below the rest threshold (1e-12 of the
mechanism's speed); the pin's position to 1e-12 of the mechanism's size (rounding of a
circle intersection, observed about 1e-17 m).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

import linkage_sym
from linkage_sym.centres import instant_centres, velocity_centres
from linkage_sym.examples import example_dict


def _joints(scene):
    return {j["name"]: np.array(j["at"], float) for j in scene["joints"]}


def fourbar_state(scene, theta, omega2):
    """Closed form: ``(B, C, w_coupler, w_rocker)`` of the crank-rocker at crank angle
    ``theta`` (from +x, as the driver's ``toward B``), crank speed ``omega2``; ``C`` on
    the side of ``BD`` it has in the assembly configuration."""
    P = _joints(scene)
    A, B0, C0, D = P["A"], P["B"], P["C"], P["D"]
    a, b, c = np.linalg.norm(B0 - A), np.linalg.norm(C0 - B0), np.linalg.norm(C0 - D)
    e0, g0 = D - B0, C0 - B0
    side = np.sign(e0[0] * g0[1] - e0[1] * g0[0])
    B = A + a * np.array([math.cos(theta), math.sin(theta)])
    e = D - B
    f = np.linalg.norm(e)
    x = (b * b - c * c + f * f) / (2 * f)
    h = math.sqrt(b * b - x * x)
    u = e / f
    n = np.array([-u[1], u[0]])
    C = B + x * u + side * h * n
    # velocity loop: w3 J (C - B) - w4 J (C - D) = -w2 J (B - A), J the +90 degree turn
    r3, r4, r2 = C - B, C - D, B - A
    # J r = (-r_y, r_x): two equations in w3, w4
    m = np.array([[-r3[1], r4[1]], [r3[0], -r4[0]]])
    rhs = -omega2 * np.array([-r2[1], r2[0]])
    det = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
    w3 = (rhs[0] * m[1, 1] - m[0, 1] * rhs[1]) / det
    w4 = (m[0, 0] * rhs[1] - rhs[0] * m[1, 0]) / det
    return B, C, w3, w4


def crank_rocker_at(theta_deg, speed):
    scene = example_dict("crank_rocker")
    scene["drivers"][0].update(start_deg=theta_deg, stop_deg=theta_deg + 1.0, steps=2, speed=speed)
    scene["outputs"] = ["kinematics", "instant_centres"]
    return scene


def rest_angle(scene):
    """A crank angle (rad) where the coupler and rocker turn alike: a sign change of
    ``w_coupler - w_rocker`` bracketed on a grid, then Brent's method."""
    w2 = scene["drivers"][0]["speed"]
    g = lambda t: (lambda s: s[2] - s[3])(fourbar_state(scene, t, w2))  # noqa: E731
    grid = np.radians(np.arange(1.0, 361.0, 7.0))  # no grid point on a root
    vals = [g(t) for t in grid]
    for t0, t1, v0, v1 in zip(grid, grid[1:], vals, vals[1:]):
        if v0 * v1 < 0:
            return brentq(g, t0, t1, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    raise AssertionError("no step where the coupler and rocker turn alike")


def test_pinned_links_at_relative_rest_keep_their_pin_as_centre():
    base = example_dict("crank_rocker")
    theta = rest_angle(base)
    scene = crank_rocker_at(math.degrees(theta), base["drivers"][0]["speed"])
    s = linkage_sym.load_scene(scene)
    an = linkage_sym.analyze(s)
    assert an.status[0] == "ok"
    _, C, w3, w4 = fourbar_state(scene, theta, scene["drivers"][0]["speed"])
    assert abs(w3 - w4) <= 1e-13 * abs(scene["drivers"][0]["speed"])
    # the velocity fields agree the two links are at rest relative to each other there
    vc = velocity_centres(an)
    k = vc.pairs.index(("coupler", "rocker"))
    assert vc.undefined[0, k]
    ic = instant_centres(s, an)
    assert not ic.undefined[0, k]
    L = s.characteristic_length()
    assert np.linalg.norm(ic.position[0, k] - C) <= 1e-12 * L
    rec = ic.records(0)[k]
    assert rec["links"] == ["coupler", "rocker"] and "undefined" not in rec
    assert np.linalg.norm(np.array(rec["position"]) - C) <= 1e-12 * L


def test_a_pair_without_a_shared_pin_at_relative_rest_stays_undefined():
    """The crank standing still (speed 0): every pair is at rest relative to each other;
    the four pinned pairs report their pins, ground-coupler and crank-rocker none."""
    scene = crank_rocker_at(30.0, 0.0)
    s = linkage_sym.load_scene(scene)
    an = linkage_sym.analyze(s)
    ic = instant_centres(s, an)
    pins = {("ground", "crank"): "A", ("crank", "coupler"): "B", ("coupler", "rocker"): "C",
            ("ground", "rocker"): "D"}
    for k, pair in enumerate(ic.pairs):
        if pair in pins:
            assert not ic.undefined[0, k], pair
            want = an.joints[pins[pair]].position[0]
            assert np.array_equal(ic.position[0, k], want), pair
        else:
            assert ic.undefined[0, k], pair
            assert np.isnan(ic.position[0, k]).all(), pair
            assert ic.records(0)[k] == {"links": list(pair), "undefined": True}
