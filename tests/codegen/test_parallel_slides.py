"""Dyads of two slides (PRP, RPP) in the compiled mechanism and the page's evaluator.

The generated function ``parallels_<group>`` gives the cross product of the slides (the
closed form's denominator); the runtime (:mod:`linkage_sym.codegen.parallels`) fails a
path point where it is zero to rounding and notes a sign change between two solved path
points.  Against the numeric solver (which finds both by its own line intersection) and the
intersection of the two lines written in :mod:`tests.support.parallel_slides`:

* the step at the parallel position is ``unassemblable``, the others ``ok`` with ``C`` at
  the lines' intersection;
* the passage of ``C`` through infinity between two steps is the same warning, word for
  word, as the numeric solver's, at the same step, for several step counts;
* an RPP dyad whose slides are parallel to rounding (the closed form gives ~1e14 m, which
  was ``singular`` at some steps) is ``unassemblable`` at every step, in the page too.
"""

from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.artifact import Artifact
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.codegen.javascript import mechanism_script
from linkage_sym.examples import load_example
from tests.support.parallel_slides import H, guide_slider, joint_c, pinned_rod

NODE = shutil.which("node")
POS_TOL = 1e-12


@pytest.mark.parametrize("steps", [10, 11, 41])
def test_the_symbolic_runtime_words_the_passage_as_the_numeric_solver(steps):
    scene = linkage_sym.load_scene(guide_slider(steps))
    sym = compile_mechanism(scene).run()
    num = linkage_sym.analyze(scene)
    assert list(sym.status) == list(num.status)
    assert len(sym.warnings) == 1 and sym.warnings == num.warnings
    q = sym.drivers["A"]["q"]
    parallel = np.abs(q) < 1e-12
    assert np.all(sym.status[parallel] == "unassemblable") and np.all(sym.status[~parallel] == "ok")
    for k in np.flatnonzero(~parallel):
        x, y = joint_c(q[k])
        got = sym.joints["C"].position[k]
        assert abs(got[0] - x) <= POS_TOL * abs(x) and abs(got[1] - y) <= POS_TOL * H, k


def test_the_parallel_step_has_the_numeric_solvers_message():
    scene = linkage_sym.load_scene(guide_slider(11))
    sym = compile_mechanism(scene).run()
    assert sym.messages[5] == ("dyad PRP (rod, block): the slides of joints A_slide and "
                               "C_guide are parallel")
    assert sym.messages == linkage_sym.analyze(scene).messages
    assert "at step 6 (reached from step 5) it is on the far side" in sym.warnings[0]


def test_an_rpp_dyad_parallel_to_rounding_is_unassemblable_everywhere():
    sym = compile_mechanism(linkage_sym.load_scene(pinned_rod(20.0))).run()
    assert set(sym.status) == {"unassemblable"} and sym.warnings == []
    assert set(sym.messages) == {"dyad RPP (rod, block): the slides of joints B_rod and "
                                 "B_guide are parallel"}
    ok = compile_mechanism(linkage_sym.load_scene(pinned_rod(110.0))).run()
    assert set(ok.status) == {"ok"} and ok.warnings == []


def test_the_artifact_records_its_dyads_of_two_slides():
    cm = compile_mechanism(linkage_sym.load_scene(guide_slider(10)))
    assert cm.art.parallels == ((1, "A_slide", "C_guide", "C"),)
    assert "parallels_1" in cm.functions
    assert Artifact.from_dict(cm.art.to_dict()) == cm.art
    # a mechanism without one keeps its artifact's JSON as it was
    plain = compile_mechanism(load_example("crank_rocker")).art
    assert plain.parallels == () and "parallels" not in plain.to_dict()


@pytest.mark.skipif(NODE is None, reason="Node.js (node) is not installed")
@pytest.mark.parametrize("case", ["gs11", "gs10", "rpp parallel"])
def test_the_page_evaluator_fails_parallel_slides(case, tmp_path):
    d = {"gs11": lambda: guide_slider(11), "gs10": lambda: guide_slider(10),
         "rpp parallel": lambda: pinned_rod(20.0)}[case]()
    scene = linkage_sym.load_scene(d)
    Q = np.array([np.linspace(dr.start, dr.stop, dr.steps) for dr in scene.drivers])
    script = mechanism_script(scene) + f"""
const mech = new LinkageEvaluator.Mechanism(MODEL.artifact, GENERATED, MODEL);
const got = mech.solveSteps({json.dumps(Q.T.tolist())});
console.log(JSON.stringify(got.map((g) => ({{status: g.status, joints: g.joints}}))));
"""
    path = tmp_path / "run.js"
    path.write_text(script)
    p = subprocess.run([NODE, str(path)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr[-3000:]
    got = json.loads(p.stdout.strip().splitlines()[-1])
    res = compile_mechanism(scene).run()
    assert [g["status"] for g in got] == [str(s) for s in res.status]
    if case == "rpp parallel":
        assert {g["status"] for g in got} == {"unassemblable"}
        return
    for k, g in enumerate(got):
        if g["status"] == "ok":
            x, y = joint_c(Q[0, k])
            assert abs(g["joints"]["C"][0] - x) <= 1e-9 * abs(x)
            assert abs(g["joints"]["C"][1] - y) <= 1e-9 * H
