"""The ``instant_centres`` output (an extension of the scene format) in scenes and results.

* The validator and the JSON Schema accept it in ``outputs``, suggest it for a
  typo and refuse it twice; it is never a default, so a scene without it
  produces exactly the contract's layout.
* It asks for the velocity stage (and the acceleration stage, which the
  polygon quantities read): every ``ok`` step of the result has one record per
  unordered pair of links, ``N (N - 1) / 2`` of them, ground first, in scene
  order, the layout of the issue: ``{"links": [a, b], "position": [x, y]}``,
  ``{"links": [a, b], "at_infinity": true, "direction": [ux, uy]}`` or
  ``{"links": [a, b], "undefined": true}``, ``"method": "velocity"`` where
  Kennedy's construction does not reach; steps that are not ``ok`` have none.
* The records are those of :func:`linkage_sym.centres.instant_centres` (whose
  two methods ``tests/centres/test_centres.py`` checks against each other); the
  symbolic method's result carries the same centres as the numeric one, to
  1e-9 of the mechanism's size.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import linkage_sym
from linkage_sym.centres import instant_centres
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_path
from linkage_sym.model.scene import OUTPUTS

ROOT = Path(__file__).resolve().parents[2]


def example(name, outputs):
    d = json.loads(example_path(name).read_text())
    d["outputs"] = outputs
    return d


def test_validator_accepts_the_extension_and_keeps_the_default():
    scene = linkage_sym.load_scene(example("crank_rocker", ["kinematics", "instant_centres"]))
    assert scene.outputs == ("kinematics", "instant_centres")
    d = example("crank_rocker", None)
    del d["outputs"]
    assert linkage_sym.load_scene(d).outputs == OUTPUTS  # the contract's four, not the extension


@pytest.mark.parametrize("outputs, message", [
    (["instant_centers"], "outputs[0]: unknown output 'instant_centers' (did you mean 'instant_centres'?)"),
    (["instant_centres", "instant_centres"], "outputs[1]: output 'instant_centres' is listed twice"),
])
def test_validator_refusals(outputs, message):
    with pytest.raises(SceneError) as err:
        linkage_sym.load_scene(example("crank_rocker", outputs))
    assert any(p.startswith(message) for p in err.value.problems), err.value.problems


def test_schema_accepts_the_extension():
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((ROOT / "docs" / "scene.schema.json").read_text(encoding="utf-8"))
    v = jsonschema.Draft202012Validator(schema)
    assert not list(v.iter_errors(example("crank_rocker", ["instant_centres"])))
    assert list(v.iter_errors(example("crank_rocker", ["instant_centers"])))


def test_result_layout():
    scene = linkage_sym.load_scene(example("slider_crank_offset", ["instant_centres"]))
    res = linkage_sym.analyze(scene)
    assert res.stages == ("position", "velocity", "acceleration")
    out = json.loads(res.to_json())
    names = ["ground", *scene.link_names]
    pairs = [[a, b] for i, a in enumerate(names) for b in names[i + 1:]]
    for step in out["steps"]:
        assert "joints" not in step  # only what was asked for
        recs = step["instant_centres"]
        assert [r["links"] for r in recs] == pairs
        for r in recs:
            kind = set(r) - {"links", "method"}
            assert kind in ({"position"}, {"at_infinity", "direction"}, {"undefined"}), r
            if "direction" in r:
                assert r["at_infinity"] is True
                assert abs(np.hypot(*r["direction"]) - 1.0) <= 1e-15
    ground_slider = out["steps"][5]["instant_centres"][2]
    assert ground_slider == {"links": ["ground", "slider"], "at_infinity": True, "direction": [0.0, 1.0]}


def test_contract_layout_unchanged_without_the_extension():
    scene = linkage_sym.load_example("crank_rocker")
    out = linkage_sym.analyze(scene).to_dict()
    assert all("instant_centres" not in step for step in out["steps"])


def test_only_ok_steps_and_filled_pairs():
    """The five-bar's centres not at a joint are marked as filled from the velocities;
    a sweep that runs past the assembly limit has no centres at unassemblable steps."""
    out = linkage_sym.analyze(linkage_sym.load_scene(example("fivebar", ["instant_centres"]))).to_dict()
    recs = out["steps"][50]["instant_centres"]
    assert len(recs) == 10
    assert sum(r.get("method") == "velocity" for r in recs) == 5
    scene = linkage_sym.load_scene(_long_crank(example("crank_rocker", ["kinematics", "instant_centres"])))
    res = linkage_sym.analyze(scene)
    out = res.to_dict()
    assert (res.status == "unassemblable").any() and (res.status == "ok").any()
    for st, step in zip(res.status, out["steps"]):
        assert ("instant_centres" in step) == (st == "ok")


def _long_crank(d):
    """The crank-rocker with a crank too long to turn fully: some steps cannot be assembled."""
    d = copy.deepcopy(d)
    d["joints"][1]["at"] = [0.05, 0.0]  # crank 50 mm: |BD| reaches 128 mm > BC + CD
    c = np.array(d["joints"][2]["at"])
    b = np.array(d["joints"][1]["at"])
    d_ = np.array(d["joints"][3]["at"])
    # keep the assembly: put C where |BC| = 63 mm and |CD| = 48.5 mm from the new B
    dist = np.hypot(*(d_ - b))
    x = (0.063**2 - 0.0485**2 + dist**2) / (2 * dist)
    h = np.sqrt(0.063**2 - x**2)
    ex = (d_ - b) / dist
    c = b + x * ex + h * np.array([-ex[1], ex[0]])
    d["joints"][2]["at"] = [float(c[0]), float(c[1])]
    d["links"][1].pop("com", None)
    d["links"][1]["mass"] = 0.0
    d["points"] = []
    d["loads"] = []
    return d


def test_symbolic_method_carries_the_same_centres():
    scene = linkage_sym.load_scene(example("slider_crank_offset", ["instant_centres"]))
    num = linkage_sym.analyze(scene)
    sym = linkage_sym.analyze(scene, method="symbolic")
    a, b = num.instant_centres, sym.instant_centres
    assert a is not None and b is not None
    L = scene.characteristic_length()
    assert np.array_equal(a.at_infinity, b.at_infinity) and np.array_equal(a.undefined, b.undefined)
    fin = np.isfinite(a.position)
    assert np.array_equal(fin, np.isfinite(b.position))
    d = np.abs(a.position - b.position)[fin]
    assert np.all(d <= 1e-9 * np.maximum(L, np.abs(a.position[fin])))


def test_analyze_command_writes_them(tmp_path):
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(example("crank_rocker", ["instant_centres"])))
    p = subprocess.run([sys.executable, "-m", "linkage_sym", "analyze", str(path), "-o", "-"],
                       capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    scene = linkage_sym.load_scene(path)
    ic = instant_centres(scene, linkage_sym.analyze(scene))
    assert out["steps"][100]["instant_centres"] == json.loads(json.dumps(ic.records(100)))
