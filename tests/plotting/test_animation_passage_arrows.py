"""The animation's arrows at a joint's passage through infinity.

The guide-slider of :mod:`tests.support.parallel_slides` (10 steps from 30 to -30 degrees,
the guide turning at 1 rad/s; mechanism size ``L = 0.1 m``, drawn in millimetres): joint
``C = (H cot q, H)`` passes through infinity between steps 4 and 5, its speed ``H / sin² q``
(1.66 m/s at step 3, unbounded near the passage).  The guide's point ``A_slide``, which the
passage does not carry off, moves at ``0.02 m/s`` on its circle of radius 0.02 m.  Read back
from the frames' arrows:

* the velocity scale is set by the points not carried off: ``A_slide``'s arrow is the usual
  longest, ``ARROW_SHARE * L`` (35 mm) at every step, not a few hundredths of a millimetre
  (the old scale, set by ``C`` next to the passage);
* an arrow longer than ``CUT`` times that (70 mm) is drawn 70 mm long along its vector with
  a break mark across it (``C`` at step 3: 2.9 m long at this scale).

The reference speeds are the geometry's, written here.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

import linkage_sym
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.plotting.animation import animate
from tests.support.parallel_slides import H, guide_slider

L_MM = 100.0  # the guide-slider's characteristic length, mm
SHARE_MM = 0.35 * L_MM  # the usual longest arrow
TOL = 1e-9  # mm


@pytest.fixture(scope="module")
def run():
    scene = linkage_sym.load_scene(guide_slider(10))
    res = compile_plan(scene).run()
    assert res.passages and res.passages[0].before == 4
    return scene, res


def _arrows(ax, gid):
    """``[(x, y, u, v)]`` of the quiver ``gid`` of the axes, in millimetres."""
    q = next(c for c in ax.collections if c.get_gid() == gid)
    return [tuple(r) for r in np.column_stack([q.X, q.Y, q.U, q.V])]


def _at(rows, p):
    return next(r for r in rows if math.hypot(r[0] - p[0], r[1] - p[1]) < 1e-6)


def test_the_arrows_of_the_points_not_carried_off_keep_their_length(run):
    scene, res = run
    anim = animate(scene, res, velocity=True)
    for step in (0, 3, 4, 9):
        anim.draw(step)
        p = np.asarray(res.joints["A_slide"].position[step]) * 1000.0
        x, y, u, v = _at(_arrows(anim.ax, "velocity"), p)
        # speed 0.02 m/s at every step, the largest of the points not carried off
        assert math.hypot(u, v) == pytest.approx(SHARE_MM, abs=TOL)
    plt.close(anim.figure)


def test_an_arrow_far_longer_than_the_scale_is_cut_and_marked(run):
    scene, res = run
    anim = animate(scene, res, velocity=True)
    anim.draw(3)
    q = math.radians(10.0)
    c = np.array([H / math.tan(q) * 1000.0, H * 1000.0])
    speed = H / math.sin(q) ** 2  # m/s, along -x: the reference, 1.66 m/s
    assert speed * SHARE_MM / 0.02 > 2 * SHARE_MM  # longer than the cut
    x, y, u, v = _at(_arrows(anim.ax, "velocity"), c)
    assert (u, v) == pytest.approx((-2 * SHARE_MM, 0.0), abs=1e-6)
    marks = [line for line in anim.ax.get_lines() if line.get_gid() == "velocity cut"]
    assert any(np.allclose(m.get_xydata()[0], c + [-0.6 * 2 * SHARE_MM, 0.0], atol=1e-6)
               for m in marks)
    every = _arrows(anim.ax, "velocity")
    assert max(math.hypot(r[2], r[3]) for r in every) <= 2 * SHARE_MM + TOL
    labels = [t.get_text() for lg in anim.figure.legends for t in lg.get_texts()]
    assert any(t.startswith("arrow cut at 2×") for t in labels)
    plt.close(anim.figure)


def test_without_a_passage_nothing_is_cut_and_the_largest_sets_the_scale():
    scene = linkage_sym.load_scene(guide_slider(10, stop=5.0))
    res = compile_plan(scene).run()
    assert res.passages == ()
    anim = animate(scene, res, velocity=True)
    speeds = [float(np.max(np.hypot(*np.asarray(jk.velocity).T)))
              for name, jk in res.joints.items() if name not in ("A",)]
    assert anim.scales["velocity"] == pytest.approx(SHARE_MM / max(speeds), rel=1e-12)
    for step in range(10):
        anim.draw(step)
        assert not [ln for ln in anim.ax.get_lines() if (ln.get_gid() or "").endswith(" cut")]
    labels = [t.get_text() for lg in anim.figure.legends for t in lg.get_texts()]
    assert not any(t.startswith("arrow cut") for t in labels)
    plt.close(anim.figure)
