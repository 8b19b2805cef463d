"""The drawing of the instant centres (``centres --plots``): labels clear of each other, the
mechanism filling the axes.  The figures are read back from Matplotlib's objects and the
renderer's extents of the texts."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import linkage_sym
from linkage_sym.centres import instant_centres
from linkage_sym.plotting import centres as pc
from tests.support.marks import slow_cases


@pytest.fixture(scope="module")
def solved():
    out = {}
    for name in ("crank_rocker", "shaper"):
        scene = linkage_sym.load_example(name)
        res = linkage_sym.analyze(scene)
        out[name] = scene, res, instant_centres(scene, res)
    return out


def _figure(monkeypatch, solved, name, step):
    made = []
    monkeypatch.setattr(pc.style, "save", lambda fig, path: made.append(fig) or path)
    scene, res, ic = solved[name]
    pc.centres_figure(scene, res, ic, step, "unused.png")
    (fig,) = made
    return scene, res, fig


def _texts(fig):
    """``(text, pixel box)`` of every label in the drawing (renderer extents)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    ax = fig.axes[0]
    return [(t.get_text(), t.get_window_extent(renderer)) for t in ax.texts
            if t.get_text().strip() and t.get_gid() != "numbering"]


CASES = [("crank_rocker", k) for k in range(0, 361, 10)] + [
    ("shaper", k) for k in (0, 135, 180, 360)]
# over 3 s each on a loaded 2-core machine, and all but three of the rest (about 1 s each): the
# default run only (-m "not slow" leaves them out)
SLOW_CASES = {("crank_rocker", k) for k in (0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120,
                                           130, 140, 150, 160, 180, 190, 200, 220, 230, 240, 250,
                                           260, 280, 290, 300, 310, 320, 330, 340, 350, 360)} | {
    ("shaper", k) for k in (0, 135, 180, 360)}


@pytest.mark.parametrize("name,step", slow_cases(CASES, SLOW_CASES, key=lambda c: c))
def test_no_label_covers_another(monkeypatch, solved, name, step):
    """At step 30 of the crank-rocker P24 (by Kennedy, 4 mm from A) was written over P12,
    at step 40 P13 over the joint name C; in the shaper joint names covered each other.
    Each label is now placed where its box (the renderer's extent) meets no other."""
    _, _, fig = _figure(monkeypatch, solved, name, step)
    boxes = _texts(fig)
    assert len(boxes) >= 6
    clash = [(a, b) for (a, ba), (b, bb) in itertools.combinations(boxes, 2) if ba.overlaps(bb)]
    assert clash == []


@pytest.mark.parametrize("step", slow_cases([0, 30, 120, 220], {"30", "120"}))
def test_the_mechanism_fills_the_drawing(monkeypatch, solved, step):
    """The axes were a square 1.8 mechanism sizes wide about the joints' middle, so the
    crank-rocker (78 mm by 60 mm) left a third of the canvas empty.  Now what is drawn --
    the joints, the traced point, the centres drawn -- spans at least 60 % of the axes' width
    and of their height (the rest: room for the ground symbols and the labels) and covers at
    least 45 % of their area (it was 17 % at step 0), and the axes take at least 45 % of the
    figure."""
    scene, res, fig = _figure(monkeypatch, solved, "crank_rocker", step)
    ax = fig.axes[0]
    pts = [res.joints[j.name].position[step] * 1000 for j in scene.joints]
    pts += [pk.position[step] * 1000 for pk in res.points.values()]
    pts += [np.column_stack(ln.get_data())[0] for ln in ax.get_lines()
            if ln.get_marker() == "o" and len(ln.get_xdata()) == 1]
    pts = np.array(pts)
    span = pts.max(axis=0) - pts.min(axis=0)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    fill = span / np.array([x1 - x0, y1 - y0])
    assert fill.min() >= 0.6 and fill.prod() >= 0.45, fill
    box = ax.get_position()
    assert box.width * box.height >= 0.45
