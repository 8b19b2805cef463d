"""Reading a joint's ``friction`` and ``effects.friction`` (contract part two, issue 29):
every refusal names its field, a scene with friction reads back from its dump, and the
symbolic layer refuses a scene whose friction acts, naming ``joints[i].friction``."""

from __future__ import annotations

import copy

import pytest

import linkage_sym
from linkage_sym.errors import SceneError, SymbolicUnsupportedError
from linkage_sym.examples import example_dict
from linkage_sym.model import JointFriction
from linkage_sym.scene import dump_scene, parse_scene

PRESS = "slider_crank_press_friction"


def _press(edit):
    d = copy.deepcopy(example_dict(PRESS))
    edit(d)
    return d


def _problems(d):
    with pytest.raises(SceneError) as err:
        parse_scene(d)
    return err.value.problems


def _set(i, value):
    def edit(d):
        d["joints"][i]["friction"] = value
    return edit


@pytest.mark.parametrize("edit, field, words", [
    (_set(1, {"coefficient": -0.1, "radius": 0.01}), "joints[1].friction.coefficient", ">= 0"),
    (_set(1, {"coefficient": 0.1, "radius": 0.0}), "joints[1].friction.radius", "> 0"),
    (_set(1, {"coefficient": 0.1, "radius": -0.01}), "joints[1].friction.radius", "> 0"),
    (_set(1, {"coefficient": 0.1}), "joints[1].friction.radius", "required"),
    (_set(3, {"coefficient": 0.1, "radius": 0.01}), "joints[3].friction.radius", "P joint"),
    (_set(3, {"coefficient": 0.1, "mu": 0.2}), "joints[3].friction.mu", "unknown key"),
    (_set(3, {}), "joints[3].friction.coefficient", "required"),
    (_set(0, 0.15), "joints[0].friction", "object"),
    (_set(0, {"coefficient": "high", "radius": 0.01}), "joints[0].friction.coefficient", "number"),
    (lambda d: d["effects"].update(friction="yes"), "effects.friction", "true or false"),
])
def test_refused_naming_the_field(edit, field, words):
    problems = _problems(_press(edit))
    hits = [p for p in problems if p.startswith(field + ":")]
    assert hits, problems
    assert words in hits[0], hits[0]


def test_friction_on_a_gear_mesh_is_refused():
    d = copy.deepcopy(example_dict("planetary_train"))
    i = next(k for k, j in enumerate(d["joints"]) if j.get("type") == "G")
    d["joints"][i]["friction"] = {"coefficient": 0.05}
    (hit,) = [p for p in _problems(d) if p.startswith(f"joints[{i}].friction:")]
    assert "gear mesh" in hit


def test_friction_on_a_cam_contact_is_refused():
    d = copy.deepcopy(example_dict("cam_eccentric_rocker"))
    i = next(k for k, j in enumerate(d["joints"]) if j.get("type") == "cam")
    d["joints"][i]["friction"] = {"coefficient": 0.05}
    (hit,) = [p for p in _problems(d) if p.startswith(f"joints[{i}].friction:")]
    assert "cam contact" in hit


def test_read_and_dumped_back():
    scene = linkage_sym.load_example(PRESS)
    assert scene.effects.friction is True
    assert scene.joint("B").friction == JointFriction(0.15, 0.015)
    assert scene.joint("C_guide").friction == JointFriction(0.1, None)
    assert parse_scene(dump_scene(scene)) == scene
    plain = parse_scene(_press(lambda d: d["effects"].pop("friction")))
    assert plain.effects.friction is False
    assert "friction" not in dump_scene(plain)["effects"]


def test_the_compiled_symbolic_runtime_solves_friction_and_refuses_cams_still():
    """The compiled runtime solves the friction's laws (tests/codegen/test_symbolic_friction.py
    checks its values); it refused a scene whose friction acts before (issue 29).  The
    refusal that remains (cam contacts) still names its joints; friction that does not act
    is no obstacle either."""
    scene = linkage_sym.load_example(PRESS)
    assert linkage_sym.compile_mechanism(scene).art.friction
    assert linkage_sym.analyze(scene, method="symbolic").forces.method == "symbolic"
    with pytest.raises(SymbolicUnsupportedError) as err:
        linkage_sym.compile_mechanism(linkage_sym.load_example("cam_eccentric_rocker"))
    assert "method 'dyad' or 'global'" in err.value.problems[0]
    off = parse_scene(_press(lambda d: d["effects"].update(friction=False)))
    assert linkage_sym.compile_mechanism(off, use_cache=False) is not None


@pytest.mark.parametrize("edit", [
    _set(1, {"coefficient": -0.1, "radius": 0.01}),
    _set(1, {"coefficient": 0.1, "radius": 0.0}),
    _set(1, {"coefficient": 0.1}),
    _set(3, {"coefficient": 0.1, "radius": 0.01}),
    _set(3, {"coefficient": 0.1, "mu": 0.2}),
    lambda d: d["effects"].update(friction="yes"),
])
def test_the_schema_refuses_them_too(edit):
    import json
    from pathlib import Path

    import jsonschema

    schema = json.loads((Path(__file__).parents[2] / "docs" / "scene.schema.json").read_text())
    v = jsonschema.Draft202012Validator(schema)
    assert v.is_valid(example_dict(PRESS))
    assert not v.is_valid(_press(edit))
