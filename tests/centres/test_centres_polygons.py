"""Polygon quantities (:func:`linkage_sym.centres.polygon_quantities`) against closed forms.

Second methods, sharing no code with the package (``tests/support/reference_kinematics.py``
imports nothing of linkage_sym):

* sliding pairs between moving links: the slip velocity and slip acceleration
  of the guide-bar of the textbook chapter *Kinematic analysis of planar
  mechanisms* (examples 3-1/3-6) are the first and second time derivatives of
  the slide coordinate ``s2`` of its closed loop (``ds2``, ``dds2``), and the
  Coriolis term is ``2 w3 ds2`` normal to the slide; the same for the block of
  the shaper of example 3-7 (``ds3``, ``dds3`` of its matrix method) -- to
  1e-9 of the largest value over the sweep;
* normal and tangential accelerations: a four-bar's coupler point C about B is
  ``-w2^2 (C - B)`` and ``a2 J (C - B)`` with the closed-form ``w2``, ``a2``
  (eqs. 3-13 to 3-17), and ``a_B + a_n + a_t`` is the closed-form ``a_C``;
* example 3-1 itself at phi1 = 60 deg: the book measures, on its polygons,
  ``v_B3B2 = 0.32`` m/s, ``a_k = 2.5`` m/s^2, ``a_B3D^n = 1.05`` m/s^2 and
  ``a_B3D^t = 4.3`` m/s^2 (``0.1 x 43`` mm), each to its drawing's precision
  (half a millimetre of the drawing: 0.005 m/s, 0.05 m/s^2), with
  ``BD = 69`` mm measured there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.centres import polygon_quantities

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

REL = 1e-9


def _sliding(scene, res, joint):
    out = []
    for i in range(res.n_steps):
        pq = polygon_quantities(scene, res, i)
        out.append(next(s for s in pq.sliding if s.joint == joint))
    return out


@pytest.mark.parametrize("l1, l3, l4, gamma, sigma, rot", [
    (0.024, 0.048, 0.078, 100.0, 1, 0.0),     # example 3-1's proportions
    (0.5, 0.8, 1.7, 60.0, -1, 35.0),
    (1.0, 0.4, 2.5, 140.0, 1, -120.0),
])
def test_guide_bar_slip_and_coriolis(l1, l3, l4, gamma, sigma, rot):
    d, pl, _ = scenes.guide_bar(l1, l3, l4, gamma, steps=37, speed=7.0, acceleration=3.0,
                                sigma=sigma, rotate_deg=rot, origin=(0.1, -0.2))
    scene, res = scenes.run(d)
    assert np.all(res.status == "ok")
    th1 = np.radians(np.linspace(0.0, 360.0, 37))
    r = ref.guide_bar(l1, l3, l4, math.radians(gamma), th1, 7.0, 3.0, sigma)
    sl = _sliding(scene, res, "S")
    speed = np.array([s.speed for s in sl])
    rate = np.array([s.rate for s in sl])
    cor = np.array([s.coriolis for s in sl])
    scenes.assert_close(speed, r["ds2"], REL, "slip speed")
    scenes.assert_close(rate, r["dds2"], REL, "slip acceleration")
    # Coriolis: 2 w3 ds2 along the slide's normal, i.e. J applied to the slide direction
    th2 = pl.angle(r["th2"])
    n = np.stack([-np.sin(th2), np.cos(th2)], -1)
    expected = 2.0 * (r["w3"] * r["ds2"])[:, None] * n
    scenes.assert_close(cor, expected, REL, "Coriolis term")
    # the vectors are along the slide
    for s in sl:
        assert abs(s.velocity @ np.array([-s.axis[1], s.axis[0]])) <= 1e-12 * max(abs(s.speed), 1e-300) + 1e-15
        assert abs(s.acceleration @ np.array([-s.axis[1], s.axis[0]])) <= 1e-9 * np.max(np.abs(rate))


def test_shaper_block_slip():
    scene = linkage_sym.load_example("shaper")
    res = linkage_sym.analyze(scene)
    th1 = res.drivers["A"]["q"]
    r = ref.shaper(0.125, 0.600, 0.150, 0.275, 0.575, th1, 1.0)
    sl = _sliding(scene, res, "B_slide")
    # the slide's axis points from C to B or back: the sign of ds3 along it
    C = res.joints["C"].position
    B = res.joints["B"].position
    sign = np.sign(np.sum(np.array([s.axis for s in sl]) * (B - C), -1))
    scenes.assert_close(sign * np.array([s.speed for s in sl]), r["ds3"], REL, "shaper slip speed")
    scenes.assert_close(sign * np.array([s.rate for s in sl]), r["dds3"], REL, "shaper slip acceleration")
    cor = np.hypot(*np.array([s.coriolis for s in sl]).T)
    scenes.assert_close(cor, 2 * np.abs(r["w3"] * r["ds3"]), REL, "shaper Coriolis magnitude")


def test_fourbar_normal_and_tangential():
    l1, l2, l3, l4 = 0.03, 0.09, 0.07, 0.1
    d, pl = scenes.fourbar(l1, l2, l3, l4, steps=37, speed=6.0, acceleration=-4.0,
                           rotate_deg=25.0, origin=(0.4, 0.1))
    scene, res = scenes.run(d)
    th1 = np.radians(np.linspace(0.0, 360.0, 37))
    r = ref.fourbar(l1, l2, l3, l4, th1, 6.0, -4.0)
    BC = pl.vector(r["C"] - r["B"])
    J = np.stack([-BC[:, 1], BC[:, 0]], -1)
    normal, tangential, aB = [], [], []
    for i in range(res.n_steps):
        pq = polygon_quantities(scene, res, i)
        rel = next(x for x in pq.relative if x.link == "coupler" and x.point == "C" and x.about == "B")
        normal.append(rel.normal)
        tangential.append(rel.tangential)
        aB.append(pq.point("B3").acceleration)  # B on the coupler (link 3; the ground is 1)
    normal, tangential, aB = np.array(normal), np.array(tangential), np.array(aB)
    scenes.assert_close(normal, -(r["w2"] ** 2)[:, None] * BC, REL, "a_CB^n")
    scenes.assert_close(tangential, r["a2"][:, None] * J, REL, "a_CB^t")
    scenes.assert_close(aB + normal + tangential, pl.vector(r["aC"]), REL, "a_C = a_B + a^n + a^t")


def test_example_3_1_against_the_book():
    """The textbook chapter's example 3-1 (phi1 = 60 deg, w1 = 10 rad/s), read off its drawings."""
    scene = linkage_sym.load_example("guide_bar_quick_return")
    res = linkage_sym.analyze(scene)
    pq = polygon_quantities(scene, res, 0)
    s = pq.sliding[0]
    assert abs(s.speed) == pytest.approx(0.32, abs=0.005)               # mu_v * b2b3 = 0.01 * 32
    assert float(np.hypot(*s.coriolis)) == pytest.approx(2.5, abs=0.05)  # 2 * 3.91 * 0.32
    rel = next(x for x in pq.relative if x.link == "guide_bar" and x.point == "B" and x.about == "D")
    assert float(np.hypot(*rel.normal)) == pytest.approx(1.05, abs=0.05)     # 3.91^2 * 0.069
    assert float(np.hypot(*rel.tangential)) == pytest.approx(4.3, abs=0.05)  # 0.1 * 43
    assert pq.omega["guide_bar"] == pytest.approx(-3.91, abs=0.01)        # clockwise
    assert pq.alpha["guide_bar"] == pytest.approx(62.3, abs=0.5)


def test_no_accelerations_refused():
    scene = linkage_sym.load_example("crank_rocker")
    import dataclasses

    res = linkage_sym.analyze(dataclasses.replace(scene, outputs=("driving",), effects=dataclasses.replace(
        scene.effects, inertia=False)))
    with pytest.raises(ValueError, match="no accelerations"):
        polygon_quantities(scene, res, 0)
