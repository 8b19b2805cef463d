"""A Newton group's assembly-mode jump between two ``ok`` steps in the plots.

``scenes.triad_jump`` (a class-III triad on a crank, 73 steps over a turn): the triad's
branch ends at a limit between steps 13 and 14 and between steps 69 and 70, and goes on in
another configuration of its assembly mode (both steps ``ok``, the run warns).  The reference
is the geometry of the solved positions, not the solver's notes: joint ``C`` (on the
triad's ``link_BC`` and ``lever``) moves between steps 13 and 14 (and 69 and 70) over five times farther than
between any two neighbouring steps of its continuous stretches; joint ``B``, a pin of the
crank, moves as the crank does.  (The run's record: tests/numeric/test_assembly_jumps.py.)

* read back from the Matplotlib figures, no line of the paths plot, of the rotation
  diagram, of the driving effort or of an animation frame joins step 13 to step 14 of a
  point or a link of the triad, each figure says so; ``B``'s path stays joined.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

import linkage_sym
from linkage_sym.plotting.animation import animate
from linkage_sym.plotting.forces import driving_effort_figure
from linkage_sym.plotting.motion import motion_figure
from linkage_sym.plotting.paths import coupler_curves_figure
from tests.support import scenes

TRIAD = ("link_BC", "lever", "rocker_DE", "rocker_FG")
MM = 1000.0
TOL = 1e-9  # relative: a drawn point is a step's value (unit scaling only)


@pytest.fixture(scope="module")
def run():
    scene = linkage_sym.load_scene(scenes.triad_jump())
    return scene, linkage_sym.analyze(scene)


def _xy(line):
    return np.column_stack([np.asarray(line.get_xdata(), float),
                            np.asarray(line.get_ydata(), float)])


def _same(a, b) -> bool:
    b = np.asarray(b, dtype=float)
    return np.allclose(a, b, rtol=TOL, atol=TOL * max(float(np.max(np.abs(b))), 1.0))


def _joined(lines, p, q) -> bool:
    for line in lines:
        xy = _xy(line)
        for k in range(len(xy) - 1):
            if ((_same(xy[k], p) and _same(xy[k + 1], q))
                    or (_same(xy[k], q) and _same(xy[k + 1], p))):
                return True
    return False


def test_the_paths_are_not_joined_across_the_jump(run):
    scene, res = run
    fig = coupler_curves_figure(scene, res)
    ax = fig.axes[0]
    C, B = res.joints["C"].position * MM, res.joints["B"].position * MM
    lines = ax.get_lines()
    assert not _joined(lines, C[13], C[14]) and not _joined(lines, C[69], C[70])
    assert _joined(lines, C[12], C[13]) and _joined(lines, B[13], B[14])
    labels = ax.get_legend_handles_labels()[1]
    assert "path of C, assembly-mode jump after steps 13, 69" in labels
    assert "path of B" in labels
    notes = [t.get_text() for t in ax.texts if t.get_gid() == "assembly-mode jumps"]
    assert notes and "between steps 13 and 14" in notes[0].replace("\n", " ")
    plt.close(fig)


def test_the_rotations_and_the_driving_effort_are_not_joined_across_the_jump(run):
    scene, res = run
    x = np.degrees(res.drivers["A"]["q"])
    fig = motion_figure(scene, res, "position")
    lines = fig.axes[0].get_lines()
    for link in TRIAD:
        r = np.degrees(res.links[link].rotation)
        drawn = [ln for ln in lines if ln.get_label().split(",")[0] == f"rotation {link}"]
        assert drawn, link
        assert not _joined(drawn, (x[13], r[13]), (x[14], r[14]))
    plt.close(fig)
    fig = driving_effort_figure(scene, res)
    T = res.forces.driving["A"]
    lines = fig.axes[0].get_lines()
    assert not _joined(lines, (x[13], T[13]), (x[14], T[14]))
    assert _joined(lines, (x[12], T[12]), (x[13], T[13]))
    plt.close(fig)


def test_an_animation_frame_breaks_the_path_and_says_so(run):
    scene, res = run
    anim = animate(scene, res)
    anim.draw(14)
    C = res.joints["C"].position * MM
    assert not _joined(anim.ax.get_lines(), C[13], C[14])
    assert _joined(anim.ax.get_lines(), C[12], C[13])
    notes = [t.get_text() for t in anim.ax.texts if t.get_gid() == "passage through infinity"]
    assert notes and "assembly mode" in notes[0]
    plt.close(anim.figure)
