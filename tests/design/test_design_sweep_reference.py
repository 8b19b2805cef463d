"""The design sweep's ``K`` and ``min_transmission_deg`` on a grid of crank-rockers against a
four-bar sweep written by hand in NumPy from the textbook's formulas
(tests/support/fourbar_sweep_numpy.py, which imports nothing of the package): the yardstick
of benchmarks/bench_design_sweep.py, checked here on 12 x 12 designs so that the speed the
benchmark reports is that of the same numbers.

The shipped crank-rocker over a full turn in 361 steps, coupler ``l_BC`` 0.045..0.085 and
rocker ``l_CD`` 0.025..0.075 (crank 0.024, ground 0.078): 101 designs close at every step,
the others at some steps or none.

Tolerances (observed at most 1.3e-15 and 1.8e-13 degrees):

* ``K``: 1e-12 relative.  Both take the same toggle positions (the rocker's rate is 0
  where crank and coupler are in line); the package locates them by Newton between steps
  to 1e-12 of a step (1.7e-14 rad of crank), the reference in closed form, and ``K`` is a
  ratio of crank intervals of at least 2 rad here, so the two differ by at most about 2e-14
  relative plus the rounding of the closed forms (a few 1e-16).
* ``min_transmission_deg``: 1e-10 degrees, on the designs that close at every step.  Both
  take the smallest angle over the same 361 steps (no interpolation between steps), so
  only rounding separates them: the package's angle from the coordinates' cosines and
  sines (tangent of the half angle) and an arctangent of a ratio, the reference's from
  ``arctan2`` of the cross and dot products of its positions, the positions carrying the
  law of cosines' ``sqrt(1 - cos^2)`` amplification where a design barely closes.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

import linkage_sym
from tests.support.fourbar_sweep_numpy import sweep_fourbar

K_RTOL = 1e-12
MU_ATOL_DEG = 1e-10


def _scene():
    scene = linkage_sym.load_example("crank_rocker")
    drv = dataclasses.replace(scene.drivers[0], start=0.0, stop=2 * math.pi, steps=361)
    return dataclasses.replace(scene, drivers=(drv,))


def test_K_and_transmission_agree_with_a_hand_written_numpy_sweep():
    scene = _scene()
    coupler, rocker = np.linspace(0.045, 0.085, 12), np.linspace(0.025, 0.075, 12)
    res = linkage_sym.sweep(scene, {"l_BC": coupler, "l_CD": rocker},
                            ["assemblable", "K", "min_transmission_deg"])
    # the reference's inputs from the scene: A at the origin, the crank AB, the pivot D, and
    # the assembly mode (the side of B -> D on which C lies)
    at = {j.name: np.array(j.at) for j in scene.joints}
    assert not at["A"].any()
    u, v = at["D"] - at["B"], at["C"] - at["B"]
    sigma = 1 if u[0] * v[1] - u[1] * v[0] > 0 else -1
    B, C = np.meshgrid(coupler, rocker, indexing="ij")  # the grid's order: first slowest
    theta = np.linspace(0.0, 2 * math.pi, 361)
    closed, mu, K = sweep_fourbar(float(np.hypot(*at["B"])), B.ravel(), C.ravel(),
                                  float(at["D"][0]), float(at["D"][1]), theta, sigma)
    Kp = np.asarray(res["K"], float)
    mp = np.asarray(res["min_transmission_deg"], float)
    # the same designs close at every step (none of them singular), and have K
    assert closed.sum() == 101
    np.testing.assert_array_equal(np.asarray(res["assemblable"], float) == 1.0, closed)
    np.testing.assert_array_equal(np.isfinite(Kp), closed)
    np.testing.assert_array_equal(np.isfinite(K), closed)
    np.testing.assert_allclose(Kp[closed], K[closed], rtol=K_RTOL, atol=0)
    np.testing.assert_allclose(mp[closed], mu[closed], rtol=0, atol=MU_ATOL_DEG)
