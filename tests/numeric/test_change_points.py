"""An RRR dyad's change point between two steps: a warning of the run, whatever the steps.

The four-bar 3, 1, 1, 3 (:mod:`tests.support.change_points`) has its coupler end ``B`` on the
rocker's pivot ``D`` at the crank angle ``PHI``: there joint ``C`` can be anywhere on one
circle, and the coupler and rocker may go on in the same assembly mode (a half turn) or
change it.  The closed form keeps its mode; where the change point falls between two steps
every step is ``ok``, and before this warning nothing said that the other branch was there:
which way the half turn went was left to the solving path's points.  Checked against the
geometry written by hand:

* at every step count the warning comes once, its driver values bracketing ``PHI`` at most
  one path increment (2 degrees) apart, at the first step past it;
* the ``ok`` steps are the circles' intersection on the assembly configuration's side of
  the line from ``B`` to ``D`` (the mode kept), the coupler a half turn away across ``PHI``;
* a four-bar 3, 1, 1, 3.001, whose joints ``B`` and ``D`` stay 0.001 apart, has no warning,
  and its rotations follow the one continuous motion (the hand positions unwrapped on a
  grid 200 times finer than the steps);
* the shared screen and minimisation (:mod:`linkage_sym.numeric.continuation.change_points`)
  on curves whose distance from zero is known.

Tolerances: positions 1e-12 of the size (3) away from the change point, where the dyad's
condition is moderate; rotations 1e-9 rad (near 3, 1, 1, 3.001 the dyad's condition number
is about 1/0.001).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.numeric.continuation import change_points
from tests.support import change_points as hand

METHODS = ("dyad", "global")
STEP_COUNTS = (2, 7, 8, 13, 20, 41, 100)
"""Sweeps from PHI + 7 to PHI - 23 degrees whose solving path has no point at PHI."""
POS_TOL = 1e-12 * 3.0
ROT_TOL = 1e-9


def run(steps, gap=0.0, method="dyad", start=hand.PHI + 7.0, stop=hand.PHI - 23.0):
    scene = linkage_sym.load_scene(hand.scene(start, stop, steps, gap))
    return linkage_sym.analyze(scene, method=method)


def check_warning(res):
    """The one warning, its values bracketing PHI one path increment apart at most, at the
    first step past them (the sweep goes down, so at the first step below PHI)."""
    assert len(res.warnings) == 1, res.warnings
    m = hand.WARNING.match(res.warnings[0])
    assert m, res.warnings[0]
    before, after = float(m["before"]), float(m["after"])
    assert after < hand.PHI < before and before - after <= 2.0 + 1e-9, (before, after)
    q = np.degrees(res.drivers["A"]["q"])
    k = int(np.flatnonzero(q <= after + 1e-4)[0])  # the first step at or past ``after``
    assert q[k] < hand.PHI <= q[k - 1] + 1e-9
    expect = f"step {k}" if abs(q[k] - after) < 1e-4 else f"step {k} (reached from step {k - 1})"
    assert m["step"] == expect, (m["step"], expect)
    return k


def check_positions(res, gap=0.0):
    q = res.drivers["A"]["q"]
    _, B, C, _ = hand.points(q, gap)
    ok = res.status == "ok"
    for name, ref in (("B", B), ("C", C)):
        err = np.max(np.abs(res.joints[name].position[ok] - ref[ok]))
        assert err <= POS_TOL, (name, err)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("steps", STEP_COUNTS)
def test_a_change_point_between_steps_is_a_warning_at_every_step_count(steps, method):
    res = run(steps, method=method)
    assert set(res.status) == {"ok"}
    k = check_warning(res)
    check_positions(res)  # the assembly mode kept: C on the same side of BD throughout
    # and so the coupler and the rocker turn a half turn (either way) across PHI
    for link in ("coupler", "rocker"):
        th = res.links[link].rotation
        assert abs(abs(th[k] - th[k - 1]) - math.pi) < math.pi / 4, (link, th[k - 1], th[k])


@pytest.mark.parametrize("method", METHODS)
def test_a_step_at_the_change_point_is_unassemblable_and_the_passage_is_warned(method):
    """31 steps from 37 to 7 degrees: step 7 is at PHI (B on D to rounding)."""
    res = run(31, method=method)
    assert res.status[7] == "unassemblable" and "coincide" in res.messages[7]
    assert list(np.flatnonzero(res.status != "ok")) == [7]
    check_warning(res)
    check_positions(res)


@pytest.mark.parametrize("method", METHODS)
def test_a_change_point_before_the_first_step_is_warned_at_step_0(method):
    """Assembled at PHI + 25 degrees, swept from PHI - 5 down: the solving path from the
    assembly configuration to the first step passes the change point."""
    res = run(4, method=method, start=hand.PHI - 5.0, stop=hand.PHI - 20.0)
    assert set(res.status) == {"ok"} and len(res.warnings) == 1
    m = hand.WARNING.match(res.warnings[0])
    assert m and m["step"] == "step 0 (reached from the assembly configuration)"
    assert float(m["after"]) < hand.PHI < float(m["before"])
    check_positions(res)


def _hand_rotations(q_steps, gap, fine=200):
    """The coupler's and rocker's rotations from the assembly configuration at the steps,
    by unwrapping the hand positions along the path refined ``fine`` times."""
    a = math.radians(hand.ASSEMBLY)
    grid = np.concatenate([np.linspace(a, q_steps[0], 2000)[:-1],
                           np.concatenate([np.linspace(q_steps[i], q_steps[i + 1], fine + 1)[:-1]
                                           for i in range(len(q_steps) - 1)] + [q_steps[-1:]])])
    _, B, C, D = hand.points(grid, gap)
    out = {}
    for link, v in (("coupler", C - B), ("rocker", C - D)):
        th = np.unwrap(np.arctan2(v[:, 1], v[:, 0]))
        out[link] = (th - th[0])[1999::fine]
    return out


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("steps", (7, 13, 41, 3001))
def test_a_near_change_point_four_bar_has_no_warning_and_moves_continuously(steps, method):
    res = run(steps, gap=0.001, method=method)
    assert set(res.status) == {"ok"} and res.warnings == []
    check_positions(res, gap=0.001)
    ref = _hand_rotations(np.asarray(res.drivers["A"]["q"]), 0.001)
    for link, th in ref.items():
        err = np.max(np.abs(res.links[link].rotation - th))
        assert err <= ROT_TOL, (link, err)


def test_a_four_bar_far_from_a_change_point_is_not_screened():
    """Links of different lengths: the outer joints never meet, nothing is searched."""
    from linkage_sym.numeric.kinematics.closed_form import DyadSolver
    from linkage_sym.numeric.plan import compile_plan

    plan = compile_plan(linkage_sym.load_scene(hand.scene(37.0, 7.0, 7, gap=0.0)))
    assert [s.meets for s in plan.solvers if isinstance(s, DyadSolver)] == [True]
    crank_rocker = linkage_sym.load_example("crank_rocker")
    plan = compile_plan(crank_rocker)
    assert not any(s.meets for s in plan.solvers if isinstance(s, DyadSolver))


# -- the screen and the minimisation both runtimes share -----------------------------------

TOL = 1e-13


@pytest.mark.parametrize("t0", [0.0, 0.3141592653589793, 0.5, 0.77, 1.0 - 1e-9])
def test_a_line_through_zero_is_found_anywhere_in_the_interval(t0):
    """``e(t) = (t - t0, 0.3 (t - t0))``: zero at ``t0``, a grid point or not."""
    assert change_points.through_zero(lambda t: (t - t0, 0.3 * (t - t0)), TOL)


@pytest.mark.parametrize("miss, found", [(1e-3, False), (1e-9, False), (1e-12, False),
                                         (5e-14, True), (0.0, True)])
def test_a_line_missing_zero_is_found_within_rounding_only(miss, found):
    """``e(t) = (t - t0, miss)``: its distance from zero is ``miss``, against 1e-13."""
    t0 = 0.4142135623730951
    assert change_points.through_zero(lambda t: (t - t0, miss + 0 * t), TOL) is found


@pytest.mark.parametrize("miss, found", [(1e-6, False), (1e-12, False), (0.0, True)])
def test_a_circle_through_or_past_zero(miss, found):
    """``e`` on the circle of radius 3 about ``(3 + miss, 0)`` turned by 4 degrees over the
    interval (a crank's end about a pivot ``3 + miss`` from its own): its distance from
    zero is ``miss`` at the angle 0, inside the interval."""
    a0, a1 = math.radians(-1.3), math.radians(2.7)

    def e(t):
        a = a0 + t * (a1 - a0)
        return 3.0 * np.cos(a) - (3.0 + miss), 3.0 * np.sin(a)

    assert change_points.through_zero(e, TOL) is found


def test_the_screen_keeps_only_intervals_near_zero():
    """Far from zero (a chord farther than its length from the origin) nothing is kept;
    a run of coincident points between two solved ones is a passage at once."""
    x, no = np.array([10.0, 9.0, 8.0, 0.5, -0.5, -8.0]), np.zeros(6, bool)
    assert change_points.intervals(x, np.ones(6), ~no, no, TOL) == [
        (2, 3, False), (3, 4, False), (4, 5, False)]
    x = np.array([3.0, 2.0, 1.0, 0.0, 0.0, -1.0])
    own = np.array([False, False, False, True, True, False])
    assert change_points.intervals(x, np.zeros(6), ~own, own, TOL) == [
        (1, 2, False), (2, 5, True)]
    # not at one point where the dyad fails: screened (its chord passes through zero here)
    x[3:5] = np.nan
    assert change_points.intervals(x, np.zeros(6), ~own, own, TOL) == [
        (1, 2, False), (2, 5, False)]
    # points where an earlier group fails between: not this dyad's to say
    assert change_points.intervals(x, np.zeros(6), ~own, no, TOL) == [(1, 2, False)]
    assert change_points.intervals(x + 100.0, np.zeros(6), ~own, own, TOL) == []


def test_a_point_without_a_value_at_the_passage_is_spanned():
    """The closed form has no value exactly at the zero (a grid point, t = 0.5): the grid's
    brackets span it and find the zero all the same."""
    def e(t):
        x = np.where(t == 0.5, np.nan, t - 0.5)
        return x, 2.0 * x

    assert change_points.through_zero(e, TOL)
    assert not change_points.through_zero(lambda t: (np.where(t == 0.5, np.nan, t - 0.5),
                                                     1e-9 + 0 * t), TOL)
