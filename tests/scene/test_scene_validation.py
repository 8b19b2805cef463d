"""Loading and validating scenes (``shared/spec/scene-format.md``).

Every refusal is checked to produce exactly the expected problem (field path
and reason) and no cascade of follow-up noise.
"""

from __future__ import annotations

import copy
import json
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from linkage_sym.errors import SceneError
from linkage_sym.model.scene import OUTPUTS, Driver, Effects, Joint, Link, Load, Scene
from linkage_sym.examples import example_names, load_example
from linkage_sym.scene import dump_scene, load_scene, parse_scene

# The example of the spec, verbatim.
CRANK_ROCKER = {
    "name": "crank-rocker",
    "links": [
        {"name": "crank", "mass": 0.2, "com": [0.012, 0.0], "inertia": 1.0e-5},
        {"name": "coupler", "mass": 0.5, "com": [0.045, 0.02], "inertia": 2.0e-4},
        {"name": "rocker", "mass": 0.3, "com": [0.07, 0.024], "inertia": 6.0e-5},
    ],
    "joints": [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [0.024, 0.0]},
        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [0.066, 0.047]},
        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [0.078, 0.0]},
    ],
    "drivers": [
        {"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360, "steps": 361,
         "speed": 10.0, "acceleration": 0.0}
    ],
    "loads": [
        {"link": "rocker", "torque": -0.5},
        {"link": "coupler", "force": [0.0, -5.0], "at": [0.05, 0.03]},
    ],
    "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
    "outputs": ["kinematics", "reactions", "driving", "frame"],
}

# A slider-crank driven by its slider: a P joint and a P driver.
SLIDER_CRANK = {
    "name": "slider-crank",
    "links": [
        {"name": "crank", "mass": 0.2, "com": [0.01, 0.0]},
        {"name": "rod"},
        {"name": "slider", "mass": 0.4, "com": [0.08, 0.0]},
    ],
    "joints": [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [0.02, 0.0]},
        {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [0.08, 0.0]},
        {"name": "D", "type": "P", "links": ["ground", "slider"], "at": [0.08, 0.0], "axis_deg": 180},
    ],
    "drivers": [{"joint": "D", "start": -0.01, "stop": 0.01, "steps": 5, "speed": 0.2}],
}

# A five-bar: mobility 2, two drivers.
FIVE_BAR = {
    "name": "five-bar",
    "links": [{"name": "l1"}, {"name": "l2"}, {"name": "l3"}, {"name": "l4"}],
    "joints": [
        {"name": "A", "type": "R", "links": ["ground", "l1"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["l1", "l2"], "at": [0.01, 0.03]},
        {"name": "C", "type": "R", "links": ["l2", "l3"], "at": [0.04, 0.06]},
        {"name": "D", "type": "R", "links": ["ground", "l4"], "at": [0.06, 0.0]},
        {"name": "E", "type": "R", "links": ["l4", "l3"], "at": [0.07, 0.03]},
    ],
    "drivers": [
        {"joint": "A", "toward": "B", "start_deg": 60, "stop_deg": 120, "steps": 11, "speed": 1.0},
        {"joint": "D", "toward": "E", "start_deg": 70, "stop_deg": 30, "steps": 11, "speed": -2.0},
    ],
}

BASES = {"crank_rocker": CRANK_ROCKER, "slider_crank": SLIDER_CRANK, "five_bar": FIVE_BAR}


def refused(data) -> SceneError:
    """The SceneError that parsing ``data`` raises."""
    with pytest.raises(SceneError) as info:
        parse_scene(data)
    return info.value


# -- accepted scenes -------------------------------------------------------------


def test_spec_example_parses_to_the_expected_dataclasses():
    expected = Scene(
        name="crank-rocker",
        links=(
            Link("crank", 0.2, (0.012, 0.0), 1.0e-5),
            Link("coupler", 0.5, (0.045, 0.02), 2.0e-4),
            Link("rocker", 0.3, (0.07, 0.024), 6.0e-5),
        ),
        joints=(
            Joint("A", "R", ("ground", "crank"), (0.0, 0.0)),
            Joint("B", "R", ("crank", "coupler"), (0.024, 0.0)),
            Joint("C", "R", ("coupler", "rocker"), (0.066, 0.047)),
            Joint("D", "R", ("rocker", "ground"), (0.078, 0.0)),
        ),
        drivers=(Driver("A", "R", 0.0, math.radians(360), 361, 10.0, 0.0, toward="B"),),
        loads=(
            Load("rocker", torque=-0.5),
            Load("coupler", force=(0.0, -5.0), at=(0.05, 0.03)),
        ),
        effects=Effects(inertia=True, gravity=(0.0, -9.81), loads=True),
        outputs=OUTPUTS,
    )
    scene = parse_scene(CRANK_ROCKER)
    assert scene == expected
    assert scene.drivers[0].stop == pytest.approx(2 * math.pi)
    assert type(scene.drivers[0].start) is float  # the file's integer 0 became a float


def test_defaults_are_applied():
    data = copy.deepcopy(CRANK_ROCKER)
    for key in ("loads", "effects", "outputs"):
        del data[key]
    data["links"][1] = {"name": "coupler"}
    del data["drivers"][0]["acceleration"]
    scene = parse_scene(data)
    assert scene.link("coupler") == Link("coupler", mass=0.0, com=None, inertia=0.0)
    assert scene.drivers[0].acceleration == 0.0
    assert scene.loads == ()
    assert scene.effects == Effects(inertia=False, gravity=None, loads=True)
    assert scene.outputs == ("kinematics", "reactions", "driving", "frame")


@pytest.mark.parametrize("gravity", [None, False])
def test_gravity_null_or_false_means_none(gravity):
    data = copy.deepcopy(CRANK_ROCKER)
    data["effects"]["gravity"] = gravity
    assert parse_scene(data).effects.gravity is None


def test_outputs_keep_the_users_order():
    data = dict(CRANK_ROCKER, outputs=["frame", "kinematics"])
    assert parse_scene(data).outputs == ("frame", "kinematics")


def test_p_joint_and_p_driver():
    scene = parse_scene(SLIDER_CRANK)
    assert scene.joint("D") == Joint("D", "P", ("ground", "slider"), (0.08, 0.0), axis=math.pi)
    assert scene.joint("A").axis is None
    assert scene.drivers == (Driver("D", "P", -0.01, 0.01, 5, 0.2, 0.0, toward=None),)


def test_five_bar_with_two_drivers_is_accepted():
    scene = parse_scene(FIVE_BAR)
    assert [(d.joint, d.kind, d.toward) for d in scene.drivers] == [("A", "R", "B"), ("D", "R", "E")]
    assert scene.drivers[1].start == math.radians(70)
    assert scene.steps == 11


def test_driver_may_point_toward_a_ground_joint():
    # D's links[1] is ground, and A is on the ground.
    data = copy.deepcopy(CRANK_ROCKER)
    data["drivers"][0].update(joint="D", toward="A")
    assert parse_scene(data).drivers[0].toward == "A"


def test_load_scene_from_a_file(tmp_path):
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(CRANK_ROCKER, indent=2), encoding="utf-8")
    assert load_scene(path) == parse_scene(CRANK_ROCKER)
    assert load_scene(str(path)) == parse_scene(CRANK_ROCKER)


def test_load_scene_takes_a_mapping():
    assert load_scene(CRANK_ROCKER) == parse_scene(CRANK_ROCKER)


def test_load_scene_rejects_other_sources():
    with pytest.raises(TypeError):
        load_scene(42)


# -- files -------------------------------------------------------------------------


def test_json_syntax_error_names_the_file_and_line(tmp_path):
    path = tmp_path / "broken.json"
    lines = json.dumps(CRANK_ROCKER, indent=2).splitlines()
    assert lines[1] == '  "name": "crank-rocker",'
    lines[1] = lines[1].rstrip(",")  # the parser stumbles on the next key, line 3
    path.write_text("\n".join(lines), encoding="utf-8")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    message = str(info.value)
    assert "broken.json" in message
    assert "line 3" in message
    assert "invalid JSON" in message


def test_json_syntax_error_reports_the_exact_position(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{\n  "name": "x",\n  "links": [,]\n}\n', encoding="utf-8")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert info.value.problems == [f"{path}: line 3, column 13: invalid JSON: Expecting value"]


def test_repeated_keys_are_refused_with_their_fields(tmp_path):
    """json.loads keeps the last of repeated keys; a scene file must not mean that silently.
    Every repeated key is reported, by its field path."""
    text = json.dumps(CRANK_ROCKER, indent=2)
    text = text.replace('"name": "crank-rocker",', '"name": "crank-rocker",\n  "name": "other",', 1)
    text = text.replace('"type": "R",', '"type": "R", "type": "P",', 2)
    path = tmp_path / "twice.json"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert info.value.problems == [
        f"{path}: name: given more than once",
        f"{path}: joints[0].type: given more than once",
        f"{path}: joints[1].type: given more than once",
    ]


def test_missing_file(tmp_path):
    path = tmp_path / "nowhere.json"
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert info.value.problems == [f"{path}: no such file"]


def test_file_whose_top_level_is_not_an_object(tmp_path):
    path = tmp_path / "list.json"
    path.write_text("[1, 2]", encoding="utf-8")
    with pytest.raises(SceneError, match="scene: must be an object, got an array"):
        load_scene(path)


# -- refusals ------------------------------------------------------------------------


SECOND_DRIVER = {"joint": "D", "toward": "A", "start_deg": 0, "stop_deg": 1, "steps": 361, "speed": 0.0}


def _link(name):
    return lambda s: s["links"].append({"name": name})


REFUSALS = [
    # top level
    pytest.param("crank_rocker", lambda s: s.update(name=""),
        "name", "must be a non-empty string", id="name-empty"),
    pytest.param("crank_rocker", lambda s: s.update(name=7),
        "name", "must be a non-empty string, got 7", id="name-not-string"),
    pytest.param("crank_rocker", lambda s: s.pop("name"),
        "name", "required key is missing", id="name-missing"),
    pytest.param("crank_rocker", lambda s: s.update(spead=1),
        "spead", "unknown key", id="top-unknown-key"),
    pytest.param("crank_rocker", lambda s: s.pop("joints"),
        "joints", "required key is missing", id="joints-missing"),
    pytest.param("crank_rocker", lambda s: s.update(links={"crank": {}}),
        "links", "must be an array, got an object", id="links-not-array"),
    # links
    pytest.param("crank_rocker", lambda s: s["links"][0].update(mas=1),
        "links[0].mas", "unknown key (did you mean 'mass'?)", id="link-unknown-key"),
    pytest.param("crank_rocker", _link("crank"),
        "links[3].name", "duplicate link name 'crank' (first at links[0])", id="link-duplicate"),
    pytest.param("crank_rocker", _link(""),
        "links[3].name", "must be a non-empty string", id="link-name-empty"),
    pytest.param("crank_rocker", lambda s: s["links"].append({"mass": 1.0, "com": [0, 0]}),
        "links[3].name", "required key is missing", id="link-name-missing"),
    pytest.param("crank_rocker", _link("ground"),
        "links[3].name", "'ground' is the fixed link", id="link-called-ground"),
    pytest.param("crank_rocker", lambda s: s["links"].append("rod"),
        "links[3]", "must be an object, got a string", id="link-not-object"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(mass=-1.0),
        "links[0].mass", "must be a finite number >= 0, got -1.0", id="mass-negative"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(mass=math.nan),
        "links[0].mass", "must be a finite number >= 0, got NaN", id="mass-nan"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(mass=True),
        "links[0].mass", "must be a finite number >= 0, got true", id="mass-bool"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(mass="0.2"),
        "links[0].mass", 'must be a finite number >= 0, got "0.2"', id="mass-string"),
    pytest.param("crank_rocker", lambda s: s["links"][0].pop("com"),
        "links[0].com", "required key is missing (a link with mass > 0", id="com-missing"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(com=[0.0]),
        "links[0].com", "must be an array of 2 finite numbers [x, y], got [0.0]", id="com-short"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(com=[0.0, "a"]),
        "links[0].com[1]", 'must be a finite number, got "a"', id="com-not-number"),
    pytest.param("crank_rocker", lambda s: s["links"][0].update(inertia=-1e-5),
        "links[0].inertia", "must be a finite number >= 0", id="inertia-negative"),
    # joints
    pytest.param("crank_rocker", lambda s: s["joints"][0].update(pos=[0, 0]),
        "joints[0].pos", "unknown key", id="joint-unknown-key"),
    pytest.param("crank_rocker", lambda s: s["joints"][3].update(name="A"),
        "joints[3].name", "duplicate joint name 'A' (first at joints[0])", id="joint-duplicate"),
    pytest.param("crank_rocker", lambda s: s["joints"][1].update(type="r"),
        "joints[1].type", 'must be "R" (revolute), "P" (prismatic), "G" (gear mesh) or "cam" '
        '(cam contact), got "r" (did you mean "R"?)', id="joint-type"),
    pytest.param("crank_rocker", lambda s: s["joints"][1].pop("type"),
        "joints[1].type", "required key is missing", id="joint-type-missing"),
    pytest.param(
        "crank_rocker",
        lambda s: s["joints"][2].update(links=["coupler", "rocekr"]),
        "joints[2].links[1]",
        "unknown link 'rocekr' (did you mean 'rocker'?)",
        id="joint-unknown-link",
    ),
    pytest.param("crank_rocker", lambda s: s["joints"][2].update(links=["coupler"]),
        "joints[2].links", "must be an array of 2 link names", id="joint-one-link"),
    pytest.param("crank_rocker", lambda s: s["joints"][2].update(links=["coupler", "rocker", "crank"]),
        "joints[2].links", "must be an array of 2 link names", id="joint-three-links"),
    pytest.param("crank_rocker", lambda s: s["joints"][2].update(links=["coupler", 3]),
        "joints[2].links[1]", "must be a non-empty link name, got 3", id="joint-link-not-string"),
    pytest.param("crank_rocker", lambda s: s["joints"][2].update(links=["rocker", "rocker"]),
        "joints[2].links", "both ends are link 'rocker'", id="joint-same-link"),
    pytest.param("crank_rocker", lambda s: s["joints"][3].update(at=[0.078, math.inf]),
        "joints[3].at[1]", "must be a finite number, got Infinity", id="joint-at-infinite"),
    pytest.param("crank_rocker", lambda s: s["joints"][3].pop("at"),
        "joints[3].at", "required key is missing", id="joint-at-missing"),
    pytest.param("crank_rocker", lambda s: s["joints"][3].update(axis_deg=0),
        "joints[3].axis_deg", "not allowed on an R joint", id="r-joint-axis"),
    pytest.param("slider_crank", lambda s: s["joints"][3].pop("axis_deg"),
        "joints[3].axis_deg", "required key is missing (a P joint", id="p-joint-no-axis"),
    pytest.param("slider_crank", lambda s: s["joints"][3].update(axis_deg=None),
        "joints[3].axis_deg", "must be a finite number, got null", id="p-joint-axis-null"),
    # drivers
    pytest.param("crank_rocker", lambda s: s.update(drivers=[]),
        "drivers", "must list at least one driver", id="no-driver"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(spead=1.0),
        "drivers[0].spead", "unknown key (did you mean 'speed'?)", id="driver-unknown-key"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(joint="Z"),
        "drivers[0].joint", "unknown joint 'Z'", id="driver-unknown-joint"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].pop("joint"),
        "drivers[0].joint", "required key is missing", id="driver-no-joint"),
    pytest.param(
        "five_bar",
        lambda s: s["drivers"][1].update(joint="A", toward="B"),
        "drivers[1].joint",
        "joint 'A' already has a driver (drivers[0])",
        id="two-drivers-one-joint",
    ),
    pytest.param(
        "crank_rocker",
        lambda s: s["drivers"][0].pop("toward"),
        "drivers[0].toward",
        "required key is missing (a driver of R joint 'A'",
        id="r-driver-no-toward",
    ),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(toward="Q"),
        "drivers[0].toward", "unknown joint 'Q'", id="toward-unknown"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(toward="A"),
        "drivers[0].toward", "must name a joint other than the driven joint 'A'", id="toward-itself"),
    pytest.param(
        "crank_rocker",
        lambda s: s["drivers"][0].update(toward="C"),
        "drivers[0].toward",
        "joint 'C' is not on link 'crank' (links[1] of the driven joint 'A')",
        id="toward-off-link",
    ),
    pytest.param(
        "crank_rocker",
        lambda s: s["joints"][1].update(at=[0.0, 0.0]),
        "drivers[0].toward",
        "joint 'B' is at the same point as the driven joint 'A'",
        id="toward-same-point",
    ),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].pop("start_deg"),
        "drivers[0].start_deg", "required key is missing", id="r-driver-no-start"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].pop("stop_deg"),
        "drivers[0].stop_deg", "required key is missing", id="r-driver-no-stop"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(start=0.0),
        "drivers[0].start", "not allowed on a driver of R joint 'A'", id="r-driver-start-metres"),
    pytest.param("slider_crank", lambda s: s["drivers"][0].update(start_deg=0.0),
        "drivers[0].start_deg", "not allowed on a driver of P joint 'D'", id="p-driver-start-deg"),
    pytest.param("slider_crank", lambda s: s["drivers"][0].update(toward="C"),
        "drivers[0].toward", "not allowed on a driver of P joint 'D'", id="p-driver-toward"),
    pytest.param("slider_crank", lambda s: s["drivers"][0].pop("stop"),
        "drivers[0].stop", "required key is missing (a driver of P joint 'D'", id="p-driver-no-stop"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(steps=0),
        "drivers[0].steps", "must be an integer >= 1, got 0", id="steps-zero"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(steps=36.5),
        "drivers[0].steps", "must be an integer >= 1, got 36.5", id="steps-float"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(steps=True),
        "drivers[0].steps", "must be an integer >= 1, got true", id="steps-bool"),
    pytest.param(
        "five_bar",
        lambda s: s["drivers"][1].update(steps=12),
        "drivers[1].steps",
        "every driver must have the same steps: drivers[0] has 11, got 12",
        id="steps-not-shared",
    ),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].pop("speed"),
        "drivers[0].speed", "required key is missing", id="speed-missing"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(speed="fast"),
        "drivers[0].speed", 'must be a finite number, got "fast"', id="speed-not-number"),
    pytest.param("crank_rocker", lambda s: s["drivers"][0].update(acceleration=-math.inf),
        "drivers[0].acceleration", "must be a finite number", id="acceleration-infinite"),
    # loads
    pytest.param("crank_rocker", lambda s: s["loads"][0].update(link="ground"),
        "loads[0].link", "loads act on moving links, not on 'ground'", id="load-on-ground"),
    pytest.param("crank_rocker", lambda s: s["loads"][0].update(link="roker"),
        "loads[0].link", "unknown link 'roker' (did you mean 'rocker'?)", id="load-unknown-link"),
    pytest.param("crank_rocker", lambda s: s["loads"][1].pop("at"),
        "loads[1].at", "required key is missing (a force needs the point", id="force-without-at"),
    pytest.param("crank_rocker", lambda s: s["loads"][1].pop("force"),
        "loads[1].force", "required key is missing (an 'at' point is given)", id="at-without-force"),
    pytest.param("crank_rocker", lambda s: s["loads"][0].pop("torque"),
        "loads[0]", "a load needs a 'force' (with 'at') or a 'torque'", id="load-empty"),
    pytest.param("crank_rocker", lambda s: s["loads"][0].update(torque=[1.0]),
        "loads[0].torque", "must be a finite number, got [1.0]", id="torque-not-number"),
    pytest.param("crank_rocker", lambda s: s["loads"][1].update(force=[1, 2, 3]),
        "loads[1].force", "must be an array of 2 finite numbers", id="force-three-numbers"),
    pytest.param("crank_rocker", lambda s: s.update(loads={"link": "crank"}),
        "loads", "must be an array, got an object", id="loads-not-array"),
    # effects
    pytest.param("crank_rocker", lambda s: s.update(effects=[]),
        "effects", "must be an object, got an array", id="effects-not-object"),
    pytest.param("crank_rocker", lambda s: s["effects"].update(inertia="yes"),
        "effects.inertia", 'must be true or false, got "yes"', id="inertia-not-bool"),
    pytest.param("crank_rocker", lambda s: s["effects"].update(loads=1),
        "effects.loads", "must be true or false, got 1", id="effects-loads-not-bool"),
    pytest.param("crank_rocker", lambda s: s["effects"].update(gravity=True),
        "effects.gravity", "must be false, null or an array of 2 finite numbers", id="gravity-true"),
    pytest.param("crank_rocker", lambda s: s["effects"].update(gravity=[0, "g"]),
        "effects.gravity[1]", "must be a finite number", id="gravity-not-number"),
    pytest.param("crank_rocker", lambda s: s["effects"].update(gravitation=[0, -9.81]),
        "effects.gravitation", "unknown key (did you mean 'gravity'?)", id="effects-unknown-key"),
    # outputs
    pytest.param("crank_rocker", lambda s: s.update(outputs=["kinematic"]),
        "outputs[0]", "unknown output 'kinematic' (did you mean 'kinematics'?)", id="output-unknown"),
    pytest.param("crank_rocker", lambda s: s.update(outputs=["frame", "driving", "frame"]),
        "outputs[2]", "output 'frame' is listed twice (also outputs[0])", id="output-twice"),
    pytest.param("crank_rocker", lambda s: s.update(outputs="frame"),
        "outputs", "must be an array, got a string", id="outputs-not-array"),
    pytest.param(
        "crank_rocker",
        lambda s: s.update(outputs=[None]),
        "outputs[0]",
        "must be one of kinematics, reactions, driving, frame, instant_centres, got null",
        id="output-not-string",
    ),
    # structure
    pytest.param("crank_rocker", _link("spare"),
        "links[3]", "link 'spare' appears in no joint", id="link-in-no-joint"),
    pytest.param("crank_rocker", lambda s: s["joints"].pop(3),
        "drivers", "1 driver given but the mobility is M = 3*3 - 2*3 = 3", id="mobility-too-high"),
    pytest.param("crank_rocker", lambda s: s["drivers"].append(SECOND_DRIVER),
        "drivers", "2 drivers given but the mobility is M = 3*3 - 2*4 = 1", id="mobility-too-low"),
]


@pytest.mark.parametrize(("word", "meant"), [
    ("revolute", "R"), ("Revolute", "R"), ("pin", "R"), ("hinge", "R"), ("prismatic", "P"),
    ("slider", "P"), (" Sliding ", "P"), ("gear", "G"), ("gear-mesh", "G"), ("CAM", "cam"),
    ("cam contact", "cam"), ("spherical", None), ("", None)])
def test_joint_type_names_every_type_and_the_one_a_synonym_means(word, meant):
    """A refused joint type lists every type the format and its extensions accept (R, P, G,
    cam: validate.JOINT_TYPES) with what each is, and where the word is a synonym, the type."""
    data = copy.deepcopy(BASES["crank_rocker"])
    data["joints"][1]["type"] = word
    error = refused(data)
    assert error.problems == [
        'joints[1].type: must be "R" (revolute), "P" (prismatic), "G" (gear mesh) or "cam" '
        f'(cam contact), got "{word}"' + (f' (did you mean "{meant}"?)' if meant else "")]


@pytest.mark.parametrize(("base", "mutate", "path", "reason"), REFUSALS)
def test_refusal(base, mutate, path, reason):
    data = copy.deepcopy(BASES[base])
    mutate(data)
    error = refused(data)
    assert isinstance(error, SceneError)
    assert f"{path}: {reason}" in str(error)
    assert len(error.problems) == 1, error.problems  # no cascade of follow-up problems
    assert error.problems[0].startswith(f"{path}: ")


# -- numbers the solver cannot carry ---------------------------------------------------


def _scaled(factor):
    """Every joint and every point fixed on a link scaled by ``factor`` (about the origin)."""

    def mutate(s):
        for entry in [*s["joints"], *s.get("points", []), *s["links"], *s.get("loads", [])]:
            for key in ("at", "com"):
                if key in entry:
                    entry[key] = [c * factor for c in entry[key]]

    return mutate


MAGNITUDE = "must be within +-1e+30 (SI units): the solver multiplies up to ten such quantities"
NUMERIC_REFUSALS = [
    pytest.param(lambda s: s["joints"][1].update(at=[1e308, 0.0]),
        "joints[1].at[0]", MAGNITUDE, id="coordinate-1e308"),
    pytest.param(lambda s: s["links"][1].update(com=[0.045, -1e31]),
        "links[1].com[1]", MAGNITUDE, id="com-1e31"),
    pytest.param(lambda s: s["links"][0].update(mass=1e308),
        "links[0].mass", MAGNITUDE, id="mass-1e308"),
    pytest.param(lambda s: s["links"][0].update(inertia=1e300),
        "links[0].inertia", MAGNITUDE, id="inertia-1e300"),
    pytest.param(lambda s: s["loads"][0].update(torque=-1e308),
        "loads[0].torque", MAGNITUDE, id="torque-1e308"),
    pytest.param(lambda s: s["loads"][1].update(force=[0.0, 1e308]),
        "loads[1].force[1]", MAGNITUDE, id="force-1e308"),
    pytest.param(lambda s: s["loads"][1].update(at=[1e308, 0.03]),
        "loads[1].at[0]", MAGNITUDE, id="load-point-1e308"),
    pytest.param(lambda s: s["effects"].update(gravity=[0.0, -1e308]),
        "effects.gravity[1]", MAGNITUDE, id="gravity-1e308"),
    pytest.param(lambda s: s["drivers"][0].update(speed=1e308),
        "drivers[0].speed", MAGNITUDE, id="speed-1e308"),
    pytest.param(lambda s: s["drivers"][0].update(acceleration=-1e308),
        "drivers[0].acceleration", MAGNITUDE, id="acceleration-1e308"),
    pytest.param(lambda s: s["drivers"][0].update(stop_deg=1e308),
        "drivers[0].stop_deg", "an angle must be within +-1e+06 degrees", id="angle-1e308"),
    pytest.param(lambda s: s["drivers"][0].update(stop_deg=360_001),
        "drivers[0].stop_deg",
        "the sweep from start_deg 0 to stop_deg 360001 covers 1000 turns; at most 1000",
        id="sweep-over-1000-turns"),
    pytest.param(_scaled(1e-300),
        "joints", "the mechanism's size (the largest distance between two joints) is 8.1e-302 m, "
        "below 1e-30 m", id="lengths-1e-300"),
    pytest.param(lambda s: s["links"][1].update(com=[0.045, 1e8]),
        "links[1].com", "is 1e+08 m from the origin, more than 1e+09 times the mechanism's size "
        "(0.081 m", id="point-far-from-a-small-mechanism"),
    pytest.param(lambda s: [j.update(at=[0.5, 0.5]) for j in s["joints"]],
        "joints", "all 4 joints are at the same point [0.5, 0.5]: the mechanism has no size",
        id="joints-all-at-one-point"),
]


@pytest.mark.parametrize(("mutate", "path", "reason"), NUMERIC_REFUSALS)
def test_numbers_beyond_what_the_solver_carries_are_refused(mutate, path, reason):
    data = copy.deepcopy(CRANK_ROCKER)
    mutate(data)
    error = refused(data)
    assert len(error.problems) == 1, error.problems
    assert error.problems[0].startswith(f"{path}: {reason}"), error.problems


def test_a_slide_beyond_a_thousand_sizes_is_refused():
    data = copy.deepcopy(SLIDER_CRANK)
    data["drivers"][0]["stop"] = 1e3  # the mechanism is 0.08 m
    error = refused(data)
    assert error.problems == [
        "drivers[0].stop: must be within +-80 m, 1000 times the mechanism's size (0.08 m): "
        "the solver follows a slide in increments of 2% of the size, got 1000"
    ]


@pytest.mark.parametrize("factor", [1e-25, 1e25])
def test_tiny_and_huge_but_representable_mechanisms_are_accepted(factor):
    data = copy.deepcopy(CRANK_ROCKER)
    _scaled(factor)(data)
    scene = parse_scene(data)
    assert scene.joints[1].at == (0.024 * factor, 0.0)


def test_a_single_joint_needs_no_size():
    data = {
        "name": "slider",
        "links": [{"name": "block", "mass": 1, "com": [0, 0]}],
        "joints": [{"name": "S", "type": "P", "links": ["ground", "block"], "at": [3, 4],
                    "axis_deg": 90}],
        "drivers": [{"joint": "S", "start": 0, "stop": 0.1, "steps": 11, "speed": 1}],
    }
    assert parse_scene(data).joints[0].at == (3.0, 4.0)
    data["drivers"][0]["stop"] = 1001.0  # a slide is measured against 1 m when there is no size
    assert refused(data).problems[0].startswith("drivers[0].stop: must be within +-1e+03 m")


# -- over-constrained in one part, under-constrained in another -------------------------


def test_over_and_under_constrained_parts_are_both_named():
    """Gruebler's count matches (M = 3*3 - 2*4 = 1, one driver), the mechanism does not.

    Link 'beam' is pinned to the ground twice (4 equations for 3 unknowns); the
    two-link arm 'upper', 'fore' has one driver for its two degrees of freedom.
    """
    import linkage_sym

    data = {
        "name": "over-and-under",
        "links": [{"name": "beam"}, {"name": "upper"}, {"name": "fore"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "beam"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["beam", "ground"], "at": [0.1, 0.0]},
            {"name": "C", "type": "R", "links": ["ground", "upper"], "at": [0.3, 0.0]},
            {"name": "D", "type": "R", "links": ["upper", "fore"], "at": [0.4, 0.0]},
        ],
        "drivers": [{"joint": "C", "toward": "D", "start_deg": 0, "stop_deg": 90, "steps": 3,
                     "speed": 1.0}],
    }
    scene = parse_scene(data)  # the count alone cannot tell
    with pytest.raises(SceneError) as info:
        linkage_sym.analyze(scene)
    assert info.value.problems == [
        "structure: link beam is over-constrained (4 constraint equations for 3 unknowns)",
        "structure: link fore is under-constrained (2 constraint equations for 3 unknowns): the "
        "drivers do not determine their positions (the mechanism is over-constrained in one part "
        "and under-constrained in another, which the Gruebler-Kutzbach count cannot see)",
    ]


def test_a_rigid_triangle_and_a_free_chain_are_both_named():
    import linkage_sym

    data = copy.deepcopy(CRANK_ROCKER)
    # the rocker also pinned to the crank: coupler and rocker form a rigid triangle with it
    data["joints"].append({"name": "E", "type": "R", "links": ["crank", "rocker"],
                           "at": [0.05, -0.02]})
    # and a free two-link arm on the ground (mobility 2, no driver): Gruebler still says 1
    data["links"] += [{"name": "upper"}, {"name": "fore"}]
    data["joints"] += [
        {"name": "F", "type": "R", "links": ["ground", "upper"], "at": [0.3, 0.0]},
        {"name": "G", "type": "R", "links": ["upper", "fore"], "at": [0.4, 0.0]},
    ]
    data["loads"] = []
    with pytest.raises(SceneError) as info:
        linkage_sym.analyze(parse_scene(data))
    over, under = info.value.problems
    assert over.startswith("structure: links coupler, rocker are over-constrained (")
    assert under.startswith("structure: links upper, fore are under-constrained (4 constraint "
                            "equations for 6 unknowns)")


def test_top_level_must_be_an_object():
    error = refused(["not", "a", "scene"])
    assert error.problems == ["scene: must be an object, got an array"]


def test_links_not_connected_to_the_ground():
    data = copy.deepcopy(CRANK_ROCKER)
    data["links"] += [{"name": "f1"}, {"name": "f2"}]
    data["joints"].append({"name": "F", "type": "R", "links": ["f1", "f2"], "at": [1.0, 1.0]})
    error = refused(data)
    assert error.problems == [
        "links[3]: link 'f1' is not connected to the ground",
        "links[4]: link 'f2' is not connected to the ground",
    ]


def test_toward_a_p_joint_sliding_along_the_driven_link():
    # The slider's reference point is fixed on the slider, not on the crank it slides along.
    data = copy.deepcopy(SLIDER_CRANK)
    data["joints"][2].update(links=["crank", "slider"], type="P", axis_deg=0)
    data["joints"][1]["links"] = ["rod", "slider"]
    data["joints"][2]["at"] = [0.05, 0.0]
    data["drivers"] = [
        {"joint": "A", "toward": "C", "start_deg": 0, "stop_deg": 10, "steps": 3, "speed": 1.0}
    ]
    assert refused(data).problems == [
        "drivers[0].toward: P joint 'C' slides along link 'crank': "
        "its point is fixed on 'slider', not on 'crank'"
    ]


def test_three_unrelated_mistakes_are_all_reported():
    data = copy.deepcopy(CRANK_ROCKER)
    data["links"][1]["mass"] = -0.5
    data["joints"][3]["links"] = ["rocker", "grund"]
    data["drivers"][0]["spead"] = data["drivers"][0].pop("speed")
    error = refused(data)
    message = str(error)
    assert "links[1].mass: must be a finite number >= 0, got -0.5" in message
    assert "joints[3].links[1]: unknown link 'grund' (did you mean 'ground'?)" in message
    assert "drivers[0].spead: unknown key (did you mean 'speed'?)" in message
    assert "drivers[0].speed: required key is missing" in message
    assert len(error.problems) == 4
    assert message.startswith("invalid scene (4 problems):")


def test_structural_checks_wait_for_valid_names():
    # An unknown link in a joint would also leave 'rocker' unconnected and the
    # mobility wrong; only the name is reported.
    data = copy.deepcopy(CRANK_ROCKER)
    data["joints"][2]["links"] = ["coupler", "rokcer"]
    data["joints"].pop(3)
    assert refused(data).problems == ["joints[2].links[1]: unknown link 'rokcer' (did you mean 'rocker'?)"]


# -- round trip ------------------------------------------------------------------------


@pytest.mark.parametrize("base", sorted(BASES))
def test_dump_then_parse_is_the_identity(base):
    scene = parse_scene(BASES[base])
    dumped = dump_scene(scene)
    assert parse_scene(dumped) == scene
    assert parse_scene(json.loads(json.dumps(dumped))) == scene


def test_dump_writes_the_file_layout():
    dumped = dump_scene(parse_scene(CRANK_ROCKER))
    assert dumped["drivers"] == [
        {"joint": "A", "toward": "B", "start_deg": 0.0, "stop_deg": 360.0, "steps": 361,
         "speed": 10.0, "acceleration": 0.0}
    ]
    assert dumped["loads"] == [
        {"link": "rocker", "torque": -0.5},
        {"link": "coupler", "force": [0.0, -5.0], "at": [0.05, 0.03]},
    ]
    assert dumped["effects"] == CRANK_ROCKER["effects"]
    slider = dump_scene(parse_scene(SLIDER_CRANK))
    assert slider["joints"][3]["axis_deg"] == 180.0
    assert slider["drivers"][0]["start"] == -0.01 and "start_deg" not in slider["drivers"][0]


def test_dump_of_a_scene_without_gravity_or_loads_reloads():
    data = {k: v for k, v in CRANK_ROCKER.items() if k not in ("effects", "loads")}
    scene = parse_scene(data)
    assert "gravity" not in dump_scene(scene)["effects"]
    assert parse_scene(dump_scene(scene)) == scene


angles = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)
sweeps = st.floats(min_value=-359_999, max_value=359_999, allow_nan=False, allow_infinity=False)


@given(start=angles, sweep=sweeps, axis=angles)
def test_round_trip_is_exact_for_any_angle(start, sweep, axis):
    # every angle the validator accepts: within 1e6 degrees, a sweep of at most 1000 turns
    stop = min(max(start + sweep, -1e6), 1e6)
    data = copy.deepcopy(SLIDER_CRANK)
    data["joints"][3]["axis_deg"] = axis
    data["drivers"] = [{"joint": "A", "toward": "B", "start_deg": start, "stop_deg": stop,
                        "steps": 2, "speed": 1.0}]
    scene = parse_scene(data)
    assert parse_scene(dump_scene(scene)) == scene


# -- robustness -------------------------------------------------------------------------

json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
    max_leaves=12,
)


def _leaf_paths(value, prefix=()):
    """Paths to every value nested in ``value``, containers included."""
    yield prefix
    if isinstance(value, dict):
        for key, item in value.items():
            yield from _leaf_paths(item, (*prefix, key))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            yield from _leaf_paths(item, (*prefix, i))


@pytest.mark.slow
@given(base=st.sampled_from(sorted(BASES)), where=st.integers(0, 10_000), value=json_values)
def test_any_corruption_is_a_scene_error_or_a_scene(base, where, value):
    data = copy.deepcopy(BASES[base])
    paths = [p for p in _leaf_paths(data) if p]
    *parents, last = paths[where % len(paths)]
    target = data
    for key in parents:
        target = target[key]
    target[last] = value
    try:
        scene = parse_scene(data)
    except SceneError as error:
        assert error.problems and all(": " in p for p in error.problems)
    else:
        assert parse_scene(dump_scene(scene)) == scene


@pytest.mark.parametrize("name", example_names())
def test_every_shipped_example_dumps_and_reloads_unchanged(name):
    """Round trip of each shipped scene, extensions included (gear meshes, cam contacts, loads
    over the cycle, traced points): ``load_scene(dump_scene(s)) == s``."""
    scene = load_example(name)
    assert load_scene(json.loads(json.dumps(dump_scene(scene)))) == scene
