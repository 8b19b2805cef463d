"""The JavaScript backend (printer ``"javascript"``, ``evaluator.js``) run in Node.

No browser: Node (``node -e``) evaluates the page's script.  For every shipped example the
symbolic layer derives:

* every generated function of the JavaScript artifact (positions, Newton residuals and
  Jacobians, rates, accelerations, frame, points) at the same inputs as the NumPy artifact's
  function: equal to ``1e-12`` relative to the largest output's magnitude (the same
  expressions after the same ``cse``, printed twice);
* the page's evaluator (closed steps with the chosen assembly modes, Newton continuation
  from the assembly configuration, statuses) at 12 driver values across the sweep against
  the numeric solver (:func:`linkage_sym.numeric.plan.compile_plan`, which shares no code
  with the generated functions): joint positions to ``1e-9`` of the mechanism's size,
  statuses equal;
* the same over whole sweeps with a singular step, a run of unassemblable steps and a
  Newton group that passes a limit and re-enters (the re-entry search), against both
  Python runtimes.
"""

from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np
import pytest

from tests.support import scenes
from tests.support.example_sets import symbolic_examples

import linkage_sym

from linkage_sym.codegen.compile import build_artifact
from linkage_sym.codegen.javascript import mechanism_script
from linkage_sym.codegen.runtime import CompiledMechanism
from linkage_sym.examples import load_example
from linkage_sym.numeric.plan import compile_plan
from tests.support.marks import fast_cases

NODE = shutil.which("node")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node.js (node) is not installed")

FUNCTION_TOL = 1e-12
POSITION_TOL = 1e-9
ARTIFACTS: dict = {}


def js_artifact(name):
    if name not in ARTIFACTS:
        ARTIFACTS[name] = build_artifact(load_example(name), printer="javascript")
    return ARTIFACTS[name]


def node(script: str, tmp_path):
    path = tmp_path / "run.js"
    path.write_text(script)
    p = subprocess.run([NODE, str(path)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


def inputs(cm, rng):
    """Every argument of the generated functions near the assembly configuration."""
    m, D, F = cm.m, len(cm.art.q), len(cm.art.force_names)
    X = list(cm.x0 + 0.05 * rng.standard_normal(m))
    return {"X": X, "XD": list(rng.standard_normal(m)), "XDD": list(rng.standard_normal(m)),
            "Q": [cm.q0[n] + 0.1 for n in cm.art.q], "QD": list(rng.standard_normal(D)),
            "QDD": list(rng.standard_normal(D)), "FORCES": list(rng.standard_normal(F)),
            "P": list(cm.params), "CX": list(np.cos(X)), "SX": list(np.sin(X))}


@pytest.mark.parametrize("name", fast_cases(symbolic_examples(), {"crank_rocker", "sixbar_class3"}))
def test_every_generated_function_in_javascript_equals_numpy(name, tmp_path):
    scene = load_example(name)
    art = js_artifact(name)
    cm = CompiledMechanism(build_artifact(scene), scene)
    assert list(art.functions) == list(cm.functions)
    args = inputs(cm, np.random.default_rng(7))
    order = ["X", "XD", "XDD", "Q", "QD", "QDD", "FORCES", "P", "CX", "SX"]
    script = mechanism_script(scene, art).split("// the functions generated")[0]  # helpers
    script += "\n".join(art.functions.values())
    script += f"\nconst A = {json.dumps(args)};\n"
    script += "console.log(JSON.stringify({" + ", ".join(
        f"{n}: {n}({', '.join('A.' + k for k in order)})" for n in art.functions) + "}));"
    got = node(script, tmp_path)
    for fname, f in cm.functions.items():
        want = np.array([np.asarray(v, float) for v in f(*[args[k] for k in order])], float)
        js = np.array(got[fname], float)
        scale = max(1.0, float(np.max(np.abs(want))))
        assert js.shape == want.shape
        assert np.max(np.abs(js - want)) <= FUNCTION_TOL * scale, (name, fname)


@pytest.mark.parametrize("name", fast_cases(symbolic_examples(), {"crank_rocker", "sixbar_class3"}))
def test_the_page_evaluator_solves_as_the_numeric_solver(name, tmp_path):
    scene = load_example(name)
    Q = np.array([np.linspace(d.start, d.stop, 12) for d in scene.drivers])
    script = mechanism_script(scene, js_artifact(name)) + f"""
const mech = new LinkageEvaluator.Mechanism(MODEL.artifact, GENERATED, MODEL);
const got = mech.solveSteps({json.dumps(Q.T.tolist())});
console.log(JSON.stringify(got.map((g) => ({{status: g.status, joints: g.joints}}))));
"""
    got = node(script, tmp_path)
    zeros = {d.joint: np.zeros(12) for d in scene.drivers}
    res = compile_plan(scene).run({d.joint: Q[i] for i, d in enumerate(scene.drivers)},
                                  zeros, zeros)
    L = scene.characteristic_length()
    assert [g["status"] for g in got] == [str(s) for s in res.status]
    for k, g in enumerate(got):
        for j in scene.joints:
            err = np.max(np.abs(np.array(g["joints"][j.name]) - res.joints[j.name].position[k]))
            assert err <= POSITION_TOL * L, (name, k, j.name)


def _long_crank():
    from linkage_sym.examples import example_dict

    d = example_dict("crank_rocker")
    next(j for j in d["joints"] if j["name"] == "B")["at"] = [0.03, 0.0]  # no longer Grashof
    return d


HARD = {
    # a step exactly at the change point: singular (screened, then the condition number)
    "change point": lambda: scenes.change_point_fourbar(),
    # a crank too long for its coupler and rocker: a run of unassemblable steps
    "long crank": _long_crank,
    # a class-III triad whose branch ends at a limit and re-enters in another configuration
    # of the assembly's determinant sign (the re-entry search)
    "triad jump": lambda: scenes.triad_jump(),
}


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
@pytest.mark.parametrize("case", sorted(HARD))
def test_the_page_evaluator_statuses_at_singular_unassemblable_and_jumping_steps(case, tmp_path):
    """Every step of the sweep: statuses as both Python runtimes give them (the NumPy
    runtime and the numeric solver), positions of the solved steps to 1e-9 of the size."""
    from linkage_sym.codegen.compile import compile_mechanism

    scene = linkage_sym.load_scene(HARD[case]())
    Q = np.array([np.linspace(d.start, d.stop, d.steps) for d in scene.drivers])
    script = mechanism_script(scene) + f"""
const mech = new LinkageEvaluator.Mechanism(MODEL.artifact, GENERATED, MODEL);
const got = mech.solveSteps({json.dumps(Q.T.tolist())});
console.log(JSON.stringify(got.map((g) => ({{status: g.status, joints: g.joints}}))));
"""
    got = node(script, tmp_path)
    L = scene.characteristic_length()
    if case != "triad jump":  # the jump is ok everywhere; the others are there for their statuses
        assert {g["status"] for g in got} != {"ok"}
    for res in (linkage_sym.analyze(scene), compile_mechanism(scene).run()):
        assert [g["status"] for g in got] == [str(s) for s in res.status], case
        for k, g in enumerate(got):
            if g["status"] == "unassemblable":
                continue
            for j in scene.joints:
                err = np.max(np.abs(np.array(g["joints"][j.name]) - res.joints[j.name].position[k]))
                assert err <= POSITION_TOL * L, (case, k, j.name)


def test_a_page_of_springs_derives_its_forces():
    """The symbolic layer derives springs and dampers: the page of a scene with springs has
    its forces (checked against the numeric solver by ``tests/page/test_page_layers.py``)."""
    from linkage_sym.codegen.javascript import forces_left_out, mechanism_model, page_artifact
    from linkage_sym.examples import load_example
    scene = load_example("crank_rocker_spring")
    assert forces_left_out(scene) is None
    art = page_artifact(scene)
    assert "forces" in art.stages
    assert mechanism_model(scene, art)["scene"]["springs"]


@pytest.mark.parametrize("name, word", [("slider_crank_press_friction", "friction")])
def test_a_page_of_friction_derives_kinematics_and_says_why_forces_are_off(name, word):
    """The compiled symbolic layer does not solve joint friction: the page derives the
    kinematics alone (no force stage), its model says why its force layer is off, and the
    downloadable scene keeps the friction."""
    from linkage_sym.codegen.javascript import mechanism_model, page_artifact
    from linkage_sym.examples import load_example
    scene = load_example(name)
    art = page_artifact(scene)
    assert "forces" not in art.stages and "velocity" in art.stages
    model = mechanism_model(scene, art)
    assert word in model["forces_left_out"]
    dumped = model["scene"]
    assert dumped.get("springs") or any("friction" in j for j in dumped["joints"])
