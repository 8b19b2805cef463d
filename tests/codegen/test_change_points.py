"""An RRR dyad's change point in the compiled mechanism (:mod:`linkage_sym.codegen.change_points`).

The runtime finds the passage of the dyad's outer joints through one point with its own
positions (the dyad's two angles, the closed forms called again between path points) and
words it as the numeric solver does.  On the four-bar 3, 1, 1, 3 written by hand
(:mod:`tests.support.change_points`): the warning at every step count, its values
bracketing the analytic change point, word for word the numeric solver's; none for the
four-bar 3, 1, 1, 3.001; nothing searched for a four-bar whose links differ.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.runtime import load_compiled
from tests.support import change_points as hand

STEP_COUNTS = (2, 7, 8, 13, 20, 41, 100)
POS_TOL = 1e-12 * 3.0


def run(steps, gap=0.0, method="symbolic"):
    scene = linkage_sym.load_scene(hand.scene(hand.PHI + 7.0, hand.PHI - 23.0, steps, gap))
    return linkage_sym.analyze(scene, method=method)


@pytest.mark.parametrize("steps", STEP_COUNTS)
def test_the_symbolic_runtime_warns_of_the_change_point_at_every_step_count(steps):
    res = run(steps)
    assert set(res.status) == {"ok"}
    assert len(res.warnings) == 1
    m = hand.WARNING.match(res.warnings[0])
    assert m, res.warnings[0]
    assert float(m["after"]) < hand.PHI < float(m["before"])
    assert res.warnings == run(steps, method="dyad").warnings  # word for word
    _, B, C, _ = hand.points(res.drivers["A"]["q"])
    assert np.max(np.abs(res.joints["C"].position - C)) <= POS_TOL


def test_a_step_at_the_change_point_is_warned_as_by_the_numeric_solver():
    """Step 7 of 31 is at the change point: the passage is the interval around it."""
    scene = linkage_sym.load_scene(hand.scene(hand.PHI + 7.0, hand.PHI - 23.0, 31))
    sym, num = (linkage_sym.analyze(scene, method=m) for m in ("symbolic", "dyad"))
    assert len(sym.warnings) == 1 and sym.warnings == num.warnings


def test_a_change_point_before_the_first_step_is_warned_as_by_the_numeric_solver():
    scene = linkage_sym.load_scene(hand.scene(hand.PHI - 5.0, hand.PHI - 20.0, 4))
    sym, num = (linkage_sym.analyze(scene, method=m) for m in ("symbolic", "dyad"))
    assert len(sym.warnings) == 1 and sym.warnings == num.warnings
    assert "at step 0 (reached from the assembly configuration)" in sym.warnings[0]


@pytest.mark.parametrize("steps", (7, 41, 3001))
def test_a_near_change_point_four_bar_has_no_warning(steps):
    res = run(steps, gap=0.001)
    assert set(res.status) == {"ok"} and res.warnings == []
    _, B, C, _ = hand.points(res.drivers["A"]["q"], 0.001)
    assert np.max(np.abs(res.joints["C"].position - C)) <= POS_TOL
    num = run(steps, gap=0.001, method="dyad")
    for link in ("coupler", "rocker"):  # the one continuous motion, as the numeric solver's
        assert np.max(np.abs(res.links[link].rotation - num.links[link].rotation)) <= 1e-9


def test_only_dyads_whose_links_are_equal_are_searched():
    scene = linkage_sym.load_scene(hand.scene(37.0, 7.0, 7))
    linkage_sym.analyze(scene, method="symbolic")  # compiled and cached
    cm = load_compiled(scene)
    assert [d.names[0] for d in cm.meeting] == ["dyad RRR (coupler, rocker)"]
    assert cm.meeting[0].steps is not None  # every group before it has a closed form
    crank_rocker = linkage_sym.load_example("crank_rocker")
    linkage_sym.analyze(crank_rocker, method="symbolic")
    assert load_compiled(crank_rocker).meeting == []
