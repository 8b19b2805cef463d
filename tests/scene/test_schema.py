"""``docs/scene.schema.json`` against the validator (``linkage_sym.load_scene``).

Every shipped example passes both; every scene in ``INVALID`` is refused by both
(the schema with at least one error, ``load_scene`` with a ``SceneError`` naming
the field).  The validator refuses unknown keys at every level, so the schema
says ``additionalProperties: false`` everywhere and the test checks that too.

Rules only the validator checks (a JSON Schema cannot express them: they relate
one part of a scene to another, need arithmetic, or are not visible in a parsed
document) are in ``VALIDATOR_ONLY``: each such scene passes the schema and is
refused by ``load_scene``, so that the list stays true.
"""

import copy
import json
import math
from pathlib import Path

import pytest

from linkage_sym.scene.schedules import SCHEDULE_KEYS

jsonschema = pytest.importorskip("jsonschema")

from linkage_sym import load_scene  # noqa: E402
from linkage_sym.errors import SceneError  # noqa: E402
from linkage_sym.examples import example_names, example_path  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SCHEMA_PATH = ROOT / "docs" / "scene.schema.json"


@pytest.fixture(scope="module")
def validator():
    schema = json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def base():
    """A valid scene with every section: R and P joints, both driver forms' joints, loads, points."""
    return {
        "name": "slider-crank",
        "links": [
            {"name": "crank", "mass": 0.2, "com": [0.01, 0.0], "inertia": 1e-5},
            {"name": "rod", "mass": 0.4, "com": [0.05, 0.0]},
            {"name": "slider"},
        ],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [0.02, 0.0]},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [0.1, 0.0]},
            {"name": "G", "type": "P", "links": ["ground", "slider"], "at": [0.1, 0.0], "axis_deg": 0},
        ],
        "drivers": [
            {"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360, "steps": 37, "speed": 10.0}
        ],
        "loads": [
            {"link": "slider", "force": [-10.0, 0.0], "at": [0.1, 0.0]},
            {"link": "rod", "torque": 0.1},
        ],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
        "points": [{"name": "P", "link": "rod", "at": [0.06, 0.01]}],
    }


def p_driven():
    """A valid scene driven at a P joint (the other driver form)."""
    return {
        "name": "slider",
        "links": [{"name": "block", "mass": 1, "com": [0, 0]}],
        "joints": [{"name": "S", "type": "P", "links": ["ground", "block"], "at": [0, 0], "axis_deg": 90}],
        "drivers": [{"joint": "S", "start": 0, "stop": 0.1, "steps": 11, "speed": 1, "acceleration": 0.5}],
        "effects": {"gravity": False},
    }


def edit(change, make=base):
    """A scene from ``make()`` with ``change(scene)`` applied."""
    def build():
        scene = copy.deepcopy(make())
        change(scene)
        return scene

    return build


def delete(path):
    def change(scene):
        *head, last = path
        obj = scene
        for key in head:
            obj = obj[key]
        del obj[last]

    return change


def put(path, value):
    def change(scene):
        *head, last = path
        obj = scene
        for key in head:
            obj = obj[key]
        obj[last] = value

    return change


# (id, scene factory, the field path load_scene must name)
INVALID = [
    # missing required keys
    ("missing-name", edit(delete(["name"])), "name"),
    ("missing-links", edit(delete(["links"])), "links"),
    ("missing-joints", edit(delete(["joints"])), "joints"),
    ("missing-drivers", edit(delete(["drivers"])), "drivers"),
    ("missing-joint-at", edit(delete(["joints", 1, "at"])), "joints[1].at"),
    ("missing-joint-type", edit(delete(["joints", 0, "type"])), "joints[0].type"),
    ("missing-driver-speed", edit(delete(["drivers", 0, "speed"])), "drivers[0].speed"),
    ("missing-driver-steps", edit(delete(["drivers", 0, "steps"])), "drivers[0].steps"),
    ("missing-com-of-massive-link", edit(delete(["links", 1, "com"])), "links[1].com"),
    ("missing-axis-of-P-joint", edit(delete(["joints", 3, "axis_deg"])), "joints[3].axis_deg"),
    ("missing-point-at", edit(delete(["points", 0, "at"])), "points[0].at"),
    ("force-without-at", edit(delete(["loads", 0, "at"])), "loads[0].at"),
    ("at-without-force", edit(delete(["loads", 0, "force"])), "loads[0].force"),
    ("load-without-force-or-torque", edit(delete(["loads", 1, "torque"])), "loads[1]"),
    ("no-driver", edit(put(["drivers"], [])), "drivers"),
    # wrong types
    ("name-not-string", edit(put(["name"], 3)), "name"),
    ("name-empty", edit(put(["name"], "")), "name"),
    ("links-not-array", edit(put(["links"], {"crank": {}})), "links"),
    ("link-not-object", edit(put(["links", 0], "crank")), "links[0]"),
    ("mass-string", edit(put(["links", 0, "mass"], "0.2")), "links[0].mass"),
    ("mass-boolean", edit(put(["links", 0, "mass"], True)), "links[0].mass"),
    ("com-three-numbers", edit(put(["links", 0, "com"], [0.0, 0.0, 0.0])), "links[0].com"),
    ("at-string-coordinate", edit(put(["joints", 1, "at"], [0.02, "0"])), "joints[1].at[1]"),
    ("joint-links-one-name", edit(put(["joints", 1, "links"], ["crank"])), "joints[1].links"),
    ("joint-links-same-link", edit(put(["joints", 1, "links"], ["crank", "crank"])), "joints[1].links"),
    ("steps-zero", edit(put(["drivers", 0, "steps"], 0)), "drivers[0].steps"),
    ("steps-fraction", edit(put(["drivers", 0, "steps"], 36.5)), "drivers[0].steps"),
    ("speed-string", edit(put(["drivers", 0, "speed"], "fast")), "drivers[0].speed"),
    ("inertia-effect-not-boolean", edit(put(["effects", "inertia"], "yes")), "effects.inertia"),
    ("gravity-true", edit(put(["effects", "gravity"], True)), "effects.gravity"),
    ("effects-not-object", edit(put(["effects"], [True])), "effects"),
    ("outputs-unknown", edit(put(["outputs"], ["kinematics", "energy"])), "outputs[1]"),
    ("outputs-twice", edit(put(["outputs"], ["frame", "frame"])), "outputs[1]"),
    ("points-not-array", edit(put(["points"], {"P": [0, 0]})), "points"),
    # unknown joint type; the joint types' own keys
    ("joint-type-unknown", edit(put(["joints", 1, "type"], "H")), "joints[1].type"),
    ("joint-type-lowercase", edit(put(["joints", 1, "type"], "r")), "joints[1].type"),
    ("axis-on-R-joint", edit(put(["joints", 1, "axis_deg"], 0)), "joints[1].axis_deg"),
    # negative mass and inertia
    ("mass-negative", edit(put(["links", 0, "mass"], -0.2)), "links[0].mass"),
    ("inertia-negative", edit(put(["links", 0, "inertia"], -1e-5)), "links[0].inertia"),
    # ground is never a moving link
    ("link-named-ground", edit(put(["links", 2, "name"], "ground")), "links[2].name"),
    ("load-on-ground", edit(put(["loads", 1, "link"], "ground")), "loads[1].link"),
    ("point-on-ground", edit(put(["points", 0, "link"], "ground")), "points[0].link"),
    # unknown keys: the validator refuses them at every level
    ("unknown-top-level-key", edit(put(["units"], "SI")), "units"),
    ("unknown-link-key", edit(put(["links", 0, "mas"], 0.2)), "links[0].mas"),
    ("unknown-joint-key", edit(put(["joints", 0, "angle"], 0)), "joints[0].angle"),
    ("unknown-driver-key", edit(put(["drivers", 0, "spead"], 1.0)), "drivers[0].spead"),
    ("unknown-load-key", edit(put(["loads", 1, "moment"], 1.0)), "loads[1].moment"),
    ("unknown-effects-key", edit(put(["effects", "magnetism"], True)), "effects.magnetism"),
    ("unknown-point-key", edit(put(["points", 0, "colour"], "red")), "points[0].colour"),
    # the driver forms: an R joint's driver in degrees, a P joint's in metres
    ("R-driver-with-start", edit(put(["drivers", 0, "start"], 0.0)), "drivers[0].start"),
    ("R-driver-without-toward", edit(delete(["drivers", 0, "toward"])), "drivers[0].toward"),
    ("P-driver-with-start-deg", edit(put(["drivers", 0, "start_deg"], 0), p_driven), "drivers[0].start_deg"),
    ("P-driver-with-toward", edit(put(["drivers", 0, "toward"], "S"), p_driven), "drivers[0].toward"),
    ("P-driver-without-stop", edit(delete(["drivers", 0, "stop"]), p_driven), "drivers[0].stop"),
]

# Rules a JSON Schema cannot express: (id, scene factory, field path, why).
VALIDATOR_ONLY = [
    ("unknown-link-in-joint", edit(put(["joints", 2, "links", 0], "cuopler")), "joints[2].links[0]",
     "a name must refer to a link listed elsewhere in the document"),
    ("driver-on-missing-joint", edit(put(["drivers", 0, "joint"], "Z")), "drivers[0].joint",
     "a name must refer to a joint listed elsewhere"),
    ("toward-missing-joint", edit(put(["drivers", 0, "toward"], "Q")), "drivers[0].toward",
     "a name must refer to a joint listed elsewhere"),
    ("load-on-unknown-link", edit(put(["loads", 1, "link"], "rood")), "loads[1].link",
     "a name must refer to a link listed elsewhere"),
    ("point-on-unknown-link", edit(put(["points", 0, "link"], "rood")), "points[0].link",
     "a name must refer to a link listed elsewhere"),
    ("duplicate-link-name", edit(put(["links", 1, "name"], "crank")), "links[1].name",
     "uniqueness of one property across array items (uniqueItems compares whole items)"),
    ("duplicate-joint-name", edit(put(["joints", 1, "name"], "A")), "joints[1].name",
     "uniqueness of one property across array items"),
    ("point-named-as-joint", edit(put(["points", 0, "name"], "C")), "points[0].name",
     "uniqueness across two arrays"),
    ("P-driver-form-on-R-joint", edit(put(["drivers", 0], {"joint": "A", "start": 0, "stop": 1,
                                                           "steps": 37, "speed": 1.0})),
     "drivers[0].start", "the driver's form depends on the type of the joint it names"),
    ("toward-not-on-driven-link", edit(put(["drivers", 0, "toward"], "C")), "drivers[0].toward",
     "geometry of the linkage graph: toward must be on the driven joint's links[1]"),
    ("mobility-mismatch", edit(put(["drivers"], [
        {"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360, "steps": 37, "speed": 10.0},
        {"joint": "G", "start": 0, "stop": 0.01, "steps": 37, "speed": 0.1}])), "drivers",
     "arithmetic on counts (Gruebler-Kutzbach mobility = number of drivers)"),
    ("unequal-steps", edit(put(["drivers"], [
        {"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360, "steps": 37, "speed": 10.0},
        {"joint": "G", "start": 0, "stop": 0.01, "steps": 11, "speed": 0.1}])), "drivers[1].steps",
     "equality of a property across array items"),
    ("link-in-no-joint", edit(lambda s: s["links"].append({"name": "loose"})), "links[3]",
     "connectivity of the linkage graph"),
    ("steps-as-float", edit(put(["drivers", 0, "steps"], 37.0)), "drivers[0].steps",
     "JSON Schema counts 37.0 as an integer; the validator wants a JSON integer"),
    ("mass-not-finite", edit(put(["links", 0, "mass"], math.inf)), "links[0].mass",
     "Infinity and NaN are not JSON numbers, but Python's json reads them and the schema takes them as numbers"),
]


def schema_errors(validator, scene):
    return sorted(e.message for e in validator.iter_errors(scene))


@pytest.mark.parametrize("name", example_names())
def test_every_shipped_example_passes_schema_and_validator(validator, name):
    scene = json.loads(example_path(name).read_text(encoding="utf-8"))
    assert schema_errors(validator, scene) == []
    load_scene(example_path(name))


@pytest.mark.parametrize("make", [base, p_driven], ids=["base", "P-driven"])
def test_the_test_scenes_pass_both(validator, make):
    assert schema_errors(validator, make()) == []
    load_scene(make())


def test_optional_sections_may_be_left_out(validator):
    scene = base()
    for key in ("loads", "effects", "outputs", "points"):
        del scene[key]
    assert schema_errors(validator, scene) == []
    load_scene(scene)


@pytest.mark.parametrize("gravity", [None, False, [0.0, -9.81]])
def test_gravity_forms(validator, gravity):
    scene = edit(put(["effects", "gravity"], gravity))()
    assert schema_errors(validator, scene) == []
    load_scene(scene)


@pytest.mark.parametrize("make, field", [(m, f) for _, m, f in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_scene_refused_by_both(validator, make, field):
    scene = make()
    assert schema_errors(validator, scene), "the schema accepts it"
    with pytest.raises(SceneError) as err:
        load_scene(scene)
    assert any(p.startswith(f"{field}:") for p in err.value.problems), err.value.problems


@pytest.mark.parametrize("make, field", [(m, f) for _, m, f, _ in VALIDATOR_ONLY],
                         ids=[i for i, _, _, _ in VALIDATOR_ONLY])
def test_rules_only_the_validator_checks(validator, make, field):
    scene = make()
    assert schema_errors(validator, scene) == [], "the schema expresses it after all: move it to INVALID"
    with pytest.raises(SceneError) as err:
        load_scene(scene)
    assert any(p.startswith(f"{field}:") for p in err.value.problems), err.value.problems


def test_repeated_key_refused_by_the_loader_only(validator, tmp_path):
    """A key given twice: a parsed document no longer shows it, so only the file loader sees it."""
    text = json.dumps(base()).replace('"type": "R"', '"type": "P", "type": "R"', 1)
    parsed = json.loads(text)
    assert schema_errors(validator, parsed) == []
    path = tmp_path / "twice.json"
    path.write_text(text)
    with pytest.raises(SceneError) as err:
        load_scene(path)
    assert any("joints[0].type: given more than once" in p for p in err.value.problems)


def test_schema_lists_the_validators_keys():
    """The schema's keys are exactly those the validator accepts (contract + points)."""
    from linkage_sym.scene import validate as v

    schema = json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))
    defs = schema["$defs"]
    assert set(schema["properties"]) == set(v.TOP_KEYS)
    assert set(defs["link"]["properties"]) == set(v.LINK_KEYS)
    assert set(defs["joint"]["properties"]) == set(v.JOINT_KEYS)
    assert set(defs["load"]["properties"]) == set(v.LOAD_KEYS) | set(SCHEDULE_KEYS)
    assert set(defs["point"]["properties"]) == set(v.POINT_KEYS)
    assert set(defs["effects"]["properties"]) == set(v.EFFECTS_KEYS)
    driver_keys = set().union(*(set(d["properties"]) for d in defs["driver"]["oneOf"]))
    assert driver_keys == set(v.DRIVER_KEYS)
    assert defs["joint"]["properties"]["type"]["enum"] == list(v.JOINT_TYPES)
