"""The run's record of a Newton group's assembly-mode jumps (``Analysis.jumps``).

``scenes.triad_jump`` (a class-III triad on a crank, 73 steps over a turn) passes a limit
between the assembly configuration and step 0, between steps 13 and 14 and between steps 69
and 70, and goes on in another configuration of its assembly mode each time.  The
reference is the geometry of the solved positions, not the solver's notes: joint ``C`` moves
between steps 13 and 14 (and 69 and 70) over five times farther than between any two other
neighbouring steps.  Both runtimes record the three jumps with the triad's four links; the
JSON of a run is unchanged (the record is not written; the warning is).
"""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from tests.support import scenes

TRIAD = ("link_BC", "lever", "rocker_DE", "rocker_FG")


@pytest.fixture(scope="module")
def run():
    scene = linkage_sym.load_scene(scenes.triad_jump())
    return scene, linkage_sym.analyze(scene)


def test_the_reference_jumps_are_between_steps_13_14_and_69_70(run):
    _, res = run
    C = res.joints["C"].position
    moves = np.hypot(*np.diff(C, axis=0).T)
    smooth = np.delete(moves, [13, 69])
    assert moves[13] > 5 * smooth.max() and moves[69] > 5 * smooth.max()
    assert res.status[13] == res.status[14] == res.status[69] == res.status[70] == "ok"


@pytest.mark.parametrize("method", ["dyad", "symbolic"])
def test_the_run_records_the_jumps(run, method):
    scene, res = run
    if method != "dyad":
        res = linkage_sym.analyze(scene, method=method)
    got = [(j.before, j.after, j.links, j.limit) for j in res.jumps]
    assert got == [(None, 0, TRIAD, True), (13, 14, TRIAD, True), (69, 70, TRIAD, True)]
    assert all(j.group == f"triad (class III) ({', '.join(TRIAD)})" for j in res.jumps)




def test_the_record_is_not_written_to_the_json(run):
    _, res = run
    assert "jumps" not in res.to_json() and res.jumps
