"""Plots and animations at a joint's passage through infinity.

The guide-slider of :mod:`tests.support.parallel_slides` (a PRP dyad, rod and block, whose
joint ``C`` is at ``(H / tan q, H)``) with a traced point ``P`` on the rod: with 10 steps
from 30 to -30 degrees, ``C`` is at ``x = +0.858 m`` at step 4 and ``-0.858 m`` at step 5
(the slides parallel at 0 degrees, between them; both steps ``ok``).  Read back from the
Matplotlib figures:

* no line of the paths plot, the motion diagrams or an animation frame joins the two steps
  of a point on the rod or the block (``C``, ``C_guide``, ``P``, the centres of mass); the
  guide's point ``A_slide``, which the passage does not move, stays joined there;
* the paths plot frames the mechanism, not the far points, and says where the passage is;
* a step that is not ``ok`` (11 steps: step 5 at the parallel position) breaks every line;
* a scene without a passage draws exactly its result's arrays, as before.

The reference positions are the lines' intersection written in the support module, not
the solver's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.plotting.animation import animate
from linkage_sym.plotting.motion import motion_figure
from linkage_sym.plotting.paths import coupler_curves_figure
from linkage_sym.plotting.style import length_unit
from tests.support.parallel_slides import H, guide_slider, joint_c

MM = 1000.0  # the figures of this scene are in millimetres
TOL = 1e-9  # mm: a drawn point equals a step's position (rounding of the scaling only)


def _scene(steps):
    d = guide_slider(steps)
    d["points"] = [{"name": "P", "link": "rod", "at": [0.03, 0.03]}]
    return linkage_sym.load_scene(d)


@pytest.fixture(scope="module")
def passage():
    scene = _scene(10)
    return scene, compile_plan(scene).run()


def _segments(axes) -> list:
    """Every drawn segment ``(p, q)`` between consecutive finite points of every line of
    the axes."""
    return _line_segments([line for ax in axes for line in ax.get_lines()])


def _line_segments(lines) -> list:
    out = []
    for line in lines:
        xy = np.column_stack([np.asarray(line.get_xdata(), float),
                              np.asarray(line.get_ydata(), float)])
        good = np.all(np.isfinite(xy), axis=1)
        for k in np.flatnonzero(good[:-1] & good[1:]):
            out.append((xy[k], xy[k + 1]))
    return out


def _joined(segments, p, q) -> bool:
    return any((np.allclose(a, p, rtol=0, atol=TOL) and np.allclose(b, q, rtol=0, atol=TOL))
               or (np.allclose(a, q, rtol=0, atol=TOL) and np.allclose(b, p, rtol=0, atol=TOL))
               for a, b in segments)


def _far_series(res):
    return {"C": res.joints["C"].position, "P": res.points["P"].position,
            "rod com": res.links["rod"].com, "block com": res.links["block"].com}


def test_the_reference_passage_is_between_steps_4_and_5(passage):
    _, res = passage
    x = [joint_c(q)[0] for q in res.drivers["A"]["q"]]
    assert x[4] > 0.8 and x[5] < -0.8 and all(v > 0 for v in x[:5]) and all(v < 0 for v in x[5:])
    assert np.allclose(res.joints["C"].position[[4, 5]], [[x[4], H], [x[5], H]], rtol=1e-12)


def test_the_paths_plot_does_not_join_the_steps_of_the_passage(passage):
    scene, res = passage
    fig = coupler_curves_figure(scene, res)
    segs = _segments(fig.axes)
    for name, pos in _far_series(res).items():
        assert not _joined(segs, pos[4] * MM, pos[5] * MM), name
        assert _joined(segs, pos[3] * MM, pos[4] * MM), name  # the rest of the path is drawn
        assert _joined(segs, pos[5] * MM, pos[6] * MM), name
    a = res.joints["A_slide"].position * MM  # on the guide: not carried off
    assert _joined(segs, a[4], a[5])


def test_the_paths_plot_frames_the_mechanism_and_names_the_passage(passage):
    scene, res = passage
    fig = coupler_curves_figure(scene, res)
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    L = scene.characteristic_length() * MM
    # not the far points at +-858 mm: the near ones and two mechanism sizes around them
    assert x1 - x0 < 8 * L and y1 - y0 < 8 * L
    assert not (x0 <= res.joints["C"].position[4, 0] * MM <= x1)
    for j in scene.joints:  # the assembly configuration is in the drawing
        assert x0 <= j.at[0] * MM <= x1 and y0 <= j.at[1] * MM <= y1
    notes = [" ".join(t.get_text().split()) for t in ax.texts
             if t.get_gid() == "passages through infinity"]
    assert len(notes) == 1 and "joint C passes through infinity between steps 4 and 5" in notes[0]
    labels = [h.get_label() for h in ax.get_legend().legend_handles]
    assert "path of C, C_guide, through infinity after step 4" in labels
    assert "path of A_slide" in labels


def test_the_motion_diagrams_do_not_join_the_sliders_steps_of_the_passage(passage):
    scene, res = passage
    q = np.degrees(res.drivers["A"]["q"])
    block = res.joints["C_guide"]  # the block's point on the ground slide (axis 0 degrees)
    values = {"position": block.position[:, 0] - scene.joint("C_guide").at[0],
              "velocity": block.velocity[:, 0], "acceleration": block.acceleration[:, 0]}
    for quantity, v in values.items():
        fig = motion_figure(scene, res, quantity)
        segs = _segments(fig.axes)
        assert not _joined(segs, (q[4], v[4]), (q[5], v[5])), quantity
        assert _joined(segs, (q[3], v[3]), (q[4], v[4])), quantity
        marks = [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "_passage"]
        assert len(marks) == 1 and np.allclose(marks[0].get_xdata(), 0.0, atol=1e-9)


def test_the_animation_does_not_join_the_steps_of_the_passage(passage):
    scene, res = passage
    anim = animate(scene, res, dpi=30)
    for frame in (9, 5, 4):
        anim.draw(frame)
        traces = [ln for ln in anim.ax.get_lines() if str(ln.get_gid()).startswith("trace ")]
        segs = _line_segments(traces)
        for name, pos in _far_series(res).items():
            if name.endswith("com"):
                continue  # the animation traces joints and points only
            assert not _joined(segs, pos[4] * MM, pos[5] * MM), (frame, name)
        boxes = [t for t in anim.ax.texts if t.get_gid() == "passage through infinity"]
        assert len(boxes) == (frame in (4, 5)), frame
    (x0, x1) = anim.ax.get_xlim()
    assert x1 - x0 < 10 * scene.characteristic_length() * MM


def test_a_step_that_is_not_ok_breaks_every_line():
    scene = _scene(11)
    res = compile_plan(scene).run()
    assert list(res.status) == ["ok"] * 5 + ["unassemblable"] + ["ok"] * 5
    segs = _segments(coupler_curves_figure(scene, res).axes)
    a = res.joints["A_slide"].position * MM
    assert not _joined(segs, a[4], a[6])  # not joined over the step without a position
    for pos in _far_series(res).values():
        assert not _joined(segs, pos[4] * MM, pos[6] * MM)
    q = np.degrees(res.drivers["A"]["q"])
    s = res.joints["C_guide"].position[:, 0] - scene.joint("C_guide").at[0]
    segs = _segments(motion_figure(scene, res, "position").axes)
    assert not _joined(segs, (q[4], s[4]), (q[6], s[6]))


@pytest.mark.parametrize("name", ["crank_rocker", "slider_crank_offset"])
def test_without_a_passage_the_lines_are_the_results_arrays(name):
    scene = linkage_sym.load_example(name)
    res = compile_plan(scene).run()  # no passage (tests/numeric/test_infinity_passages.py)
    scale = length_unit(scene)[1]
    ax = coupler_curves_figure(scene, res).axes[0]
    drawn = [ln for ln in ax.get_lines() if ln.get_label().startswith("path of ")]
    assert drawn
    for line in drawn:
        joint = line.get_label()[len("path of "):].split(", ")[0]
        assert np.array_equal(line.get_xydata(), res.joints[joint].position * scale)


def test_a_guide_slider_short_of_the_parallel_position_has_no_passage_and_no_note():
    scene = linkage_sym.load_scene(guide_slider(9, 30.0, 5.0))
    res = compile_plan(scene).run()
    ax = coupler_curves_figure(scene, res).axes[0]
    assert [t for t in ax.texts if t.get_gid() == "passages through infinity"] == []
    xy = res.joints["C"].position
    line = next(ln for ln in ax.get_lines() if ln.get_label().startswith("path of C"))
    assert np.array_equal(line.get_xydata(), xy * MM)
    assert math.isclose(float(xy[0, 0]), joint_c(math.radians(30.0))[0], rel_tol=1e-12)
