"""Warnings of Newton groups: where something happens, once per event (issue 27).

A knee linkage driven at the knee (``scenes.knee_scene``) has a driver row on the shin's
angle relative to the thigh's.  After a re-entry (a root search past a gap) the group's
angles were shifted by whole turns to those nearest the last configuration, which that row
does not allow; every later continuation then converged to the same configuration a turn
away, was refused, and the search that followed was worded "passes a limit or singular
position": a warning every path point (2 degrees), with no limit there.

The reference is the knee's closed form (``test_newton_groups.knee_truth``: with the knee
angle given, hip-ankle is a rigid distance ``d(q)``; the group is assemblable iff
``|d - l_rocker| <= |HG| <= d + l_rocker``, its limits where equality holds), evaluated
on a fine grid (0.01 degree) between the steps: a knee's limit is the edge of a stretch
that cannot be assembled, so its events are the re-entries after those stretches, one
warning each, and no "passes a limit" warning.  A class-III triad that really jumps past
its limits (``scenes.triad_jump``) keeps one warning per limit.
"""

from __future__ import annotations

import math
import os
import re
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

import scenes  # noqa: E402
from test_newton_groups import knee_truth  # noqa: E402

import linkage_sym  # noqa: E402

# a knee of the random family of test_newton_groups; before the fix its sweep over two
# turns gave 304 "passes a limit" warnings, the 6 steps from -180 to -170 degrees 23
JITTER = (-0.0749, -0.1068, -0.054, 0.0378, 0.0149, -0.084)
PASSES = "passes a limit or singular position"
REENTERS = "re-enters after steps that cannot be assembled"


def knee(start_deg, stop_deg, steps):
    j = JITTER
    K = (0.3 + j[0], 0.5 + j[1])
    A = (K[0] + 0.4 + j[2], K[1] - 0.3 + j[3])
    G = (0.6 + j[4], -0.2 + j[5])
    return scenes.knee_scene(K, A, G, start_deg=start_deg, stop_deg=stop_deg, steps=steps)


def assemblable(d, q_deg):
    """The closed form's assemblability at knee angles ``q_deg`` (degrees)."""
    e = {**d, "drivers": [{**d["drivers"][0], "start_deg": float(q_deg[0]),
                           "stop_deg": float(q_deg[-1]), "steps": len(q_deg)}]}
    return knee_truth(e)[0]


def expected_reentries(d):
    """Steps reached past a stretch the closed form cannot assemble: from the assembly
    configuration (its knee angle, the representative nearest the start) to step 0, and
    between consecutive steps."""
    J = {j["name"]: np.array(j["at"], float) for j in d["joints"]}
    dr = d["drivers"][0]
    q = np.linspace(dr["start_deg"], dr["stop_deg"], dr["steps"])
    qa = math.degrees(math.atan2(*(J["A"] - J["K"])[::-1]))
    qa += 360.0 * round((q[0] - qa) / 360.0)
    out = []
    prev = qa
    for k, qk in enumerate(q):
        n = max(3, int(abs(qk - prev) / 0.01) + 1)
        path = assemblable(d, np.linspace(prev, qk, n))
        if path[-1] and not path.all():
            out.append(k)
        prev = qk
    return out


def warned_steps(res, kind):
    return [int(re.search(r"at step (\d+)", w).group(1)) for w in res.warnings if kind in w]


@pytest.mark.parametrize("method", ["dyad", "symbolic"])
@pytest.mark.parametrize("sweep", [(-180.0, -170.0, 6), (-180.0, 540.0, 721)])
def test_a_knee_warns_once_per_gap_and_never_of_a_limit_it_does_not_pass(method, sweep):
    d = knee(*sweep)
    res = linkage_sym.analyze(linkage_sym.load_scene(d), method=method)
    ok = knee_truth(d)[0]
    assert np.array_equal(res.status == "ok", ok)
    assert warned_steps(res, PASSES) == []  # was 23 and 304
    want = expected_reentries(d)
    assert want and want[0] == 0  # the path from the assembly configuration crosses a gap
    assert warned_steps(res, REENTERS) == want


def test_a_triad_that_really_passes_its_limits_warns_once_per_limit():
    """``scenes.triad_jump``: three limits passed, each followed by a jump to another root
    of the assembly mode's determinant sign (test_batched_continuation), one warning each,
    at three different steps."""
    res = linkage_sym.analyze(linkage_sym.load_scene(scenes.triad_jump()))
    steps = warned_steps(res, PASSES)
    assert steps == [0, 14, 70]
