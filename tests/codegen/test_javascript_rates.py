"""The JavaScript evaluator's rate and force hooks (``evaluator_rates.js``) run in Node.

No browser.  For every shipped example the symbolic layer derives, the page's artifact
(:func:`linkage_sym.codegen.javascript.page_artifact`) walked by the JavaScript evaluator at
12 steps of the scene's sweep (the drivers at the scene's speeds and accelerations; every
step of three hard sweeps: a singular step, unassemblable steps, a Newton group's
re-entry) against
the NumPy backend of the one evaluator (:class:`~linkage_sym.codegen.runtime.CompiledMechanism`
on a NumPy artifact of the same scene: the same derivation, another printer and the Python
walk, block solves and force blocks): statuses equal; joints' and traced points' velocities
and accelerations, joint reactions (with a ``P`` joint's moment) and driving efforts each to
``1e-9`` of the largest magnitude of that quantity over the 12 steps.  And the page's
``position_points`` gives the first rows of ``points`` (the layout the page reads) to
``1e-12`` of their size.
"""

from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.compile import build_artifact
from linkage_sym.codegen.javascript import mechanism_script, page_artifact, page_scene
from linkage_sym.codegen.runtime import CompiledMechanism
from linkage_sym.examples import load_example
from tests.support import scenes
from tests.support.example_sets import symbolic_examples
from tests.support.marks import fast_cases

NODE = shutil.which("node")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node.js (node) is not installed")

TOL = 1e-9


def node(script: str, tmp_path):
    path = tmp_path / "run.js"
    path.write_text(script)
    p = subprocess.run([NODE, str(path)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


SCRIPT = """
const mech = new LinkageEvaluator.Mechanism(MODEL.artifact, GENERATED, MODEL);
const QD = MODEL.drivers.map((d) => d.speed), QDD = MODEL.drivers.map((d) => d.acceleration);
const steps = mech.solveSteps(%s);
console.log(JSON.stringify(steps.map((s) => {
  if (s.status !== "ok") return { status: s.status };
  const st = mech.motion(s.X, s.Q, QD, QDD);
  const first = mech.f.points(s.X, st.XD, st.XDD, s.Q, QD, QDD, null, mech.P, st.CX, st.SX);
  const pp = mech.f.position_points(s.X, null, null, s.Q, null, null, null, mech.P, st.CX, st.SX);
  return { status: s.status, kin: mech.kinematics(st), forces: mech.reactions(st),
           position_points: pp, points_head: first.slice(0, pp.length) };
})));
"""


def biggest(arrays) -> float:
    return max(float(np.max(np.abs(np.asarray(a, float)))) for a in arrays)


def _long_crank():
    from linkage_sym.examples import example_dict

    d = example_dict("crank_rocker")
    next(j for j in d["joints"] if j["name"] == "B")["at"] = [0.03, 0.0]  # no longer Grashof
    return linkage_sym.load_scene(d)


HARD = {  # as tests/codegen/test_javascript.py's: their rates at every step
    "change point": lambda: linkage_sym.load_scene(scenes.change_point_fourbar()),
    "long crank": _long_crank,
    "triad jump": lambda: linkage_sym.load_scene(scenes.triad_jump()),
}


@pytest.mark.parametrize("name", fast_cases(symbolic_examples() + sorted(HARD),
                                             {"crank_rocker", "sixbar_class3"}))
def test_the_javascript_rates_and_forces_equal_the_numpy_evaluator(name, tmp_path):
    """At 12 steps of a shipped example; at every step of a sweep with a singular step, a
    run of unassemblable steps, or a Newton group's re-entry."""
    scene = page_scene(HARD[name]() if name in HARD else load_example(name))
    idx = (np.arange(scene.steps) if name in HARD
           else np.round(np.linspace(0, scene.steps - 1, 12)).astype(int))
    Q = np.array([np.linspace(d.start, d.stop, d.steps)[idx] for d in scene.drivers])
    got = node(mechanism_script(scene, page_artifact(scene)) + SCRIPT % json.dumps(Q.T.tolist()),
               tmp_path)
    res = CompiledMechanism(build_artifact(scene), scene).run()
    assert [g["status"] for g in got] == [str(res.status[k]) for k in idx]
    ok = [(g, k) for g, k in zip(got, idx) if g["status"] == "ok"]
    ks = [k for _, k in ok]
    for level, attr in ((1, "velocity"), (2, "acceleration")):
        recs = [("joints", j.name, res.joints[j.name]) for j in scene.joints]
        recs += [("points", p.name, res.points[p.name]) for p in scene.points]
        scale = biggest(getattr(r, attr)[ks] for _, _, r in recs)
        for g, k in ok:
            for kind, n, r in recs:
                err = np.max(np.abs(np.array(g["kin"][kind][n][level]) - getattr(r, attr)[k]))
                assert err <= TOL * scale, (name, attr, k, n, err / scale)
    f = res.forces
    if f is None:
        assert all(g["forces"] is None for g, _ in ok)
        return
    r_scale = biggest(r[ks] for r in f.reactions.values())
    m_scale = max(biggest(m[ks] for m in f.reaction_moments.values()), r_scale * scene.characteristic_length())
    d_scale = biggest(v[ks] for v in f.driving.values())
    for g, k in ok:
        for n, r in f.reactions.items():
            fx, fy, mz = g["forces"]["reactions"][n]
            assert np.max(np.abs(np.array([fx, fy]) - r[k])) <= TOL * r_scale, (name, k, n)
            assert abs(mz - f.reaction_moments[n][k]) <= TOL * m_scale, (name, k, n)
        for n, v in f.driving.items():
            assert abs(g["forces"]["driving"][n] - v[k]) <= TOL * d_scale, (name, k, n)
        head = np.array(g["points_head"])
        assert np.max(np.abs(np.array(g["position_points"]) - head)) <= 1e-12 * max(1.0, np.abs(head).max())
