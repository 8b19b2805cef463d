"""Reading ``springs`` and ``effects.springs`` (the contract's second part).

Every bad input is refused with its field named and the reason, every problem
at once; the JSON Schema refuses what it can express; a scene read and written
back (``dump_scene``) is the same scene; on the command line nothing is written.
"""

from __future__ import annotations

import copy
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict
from linkage_sym.model import Spring
from linkage_sym.scene import dump_scene, parse_scene

ROOT = Path(__file__).resolve().parents[2]
LINK = {"name": "k1", "links": ["ground", "rocker"], "at": [[0.10, 0.05], [0.07, 0.02]],
        "stiffness": 500.0, "free_length": 0.03, "damping": 2.0}
JOINT = {"name": "k2", "joint": "D", "stiffness": 1.5, "free_angle_deg": 0.0, "damping": 0.0}


def scene_with(*springs, effects=None):
    d = example_dict("crank_rocker")
    d["springs"] = [copy.deepcopy(s) for s in springs]
    if effects is not None:
        d["effects"].update(effects)
    return d


def problems(d) -> list[str]:
    with pytest.raises(SceneError) as err:
        parse_scene(d)
    return err.value.problems


def test_the_contracts_springs_are_read():
    scene = parse_scene(scene_with(LINK, JOINT))
    assert scene.springs == (
        Spring("k1", 500.0, 2.0, ("ground", "rocker"), ((0.10, 0.05), (0.07, 0.02)), 0.03),
        Spring("k2", 1.5, 0.0, joint="D", free_angle_deg=0.0))
    assert scene.effects.springs and scene.active_springs == scene.springs


def test_defaults():
    link = {"name": "k", "links": ["crank", "rocker"], "at": [[0.0, 0.01], [0.07, 0.02]],
            "stiffness": 10}
    scene = parse_scene(scene_with(link, {"name": "t", "joint": "B", "stiffness": 2}))
    k, t = scene.springs
    assert k.free_length == math.hypot(0.07, 0.01) and k.damping == 0.0
    assert t.free_angle == 0.0 and t.damping == 0.0
    # effects.springs: true by default with springs, as given otherwise
    assert parse_scene(scene_with(LINK)).effects.springs is True
    off = parse_scene(scene_with(LINK, effects={"springs": False}))
    assert off.effects.springs is False and off.active_springs == ()
    d = scene_with(LINK)
    del d["effects"]
    assert parse_scene(d).effects.springs is True
    assert parse_scene(example_dict("crank_rocker")).effects.springs is False


def test_free_angle_in_degrees():
    scene = parse_scene(scene_with(dict(JOINT, free_angle_deg=30.0)))
    assert scene.springs[0].free_angle == math.radians(30.0)


def _with(base, **change):
    out = copy.deepcopy(base)
    for key, value in change.items():
        if value is None:
            out.pop(key, None)
        else:
            out[key] = value
    return out


BAD = [
    # (id, springs, the problem: field and a piece of its reason)
    ("negative-stiffness", [_with(LINK, stiffness=-1.0)],
     "springs[0].stiffness: must be a finite number >= 0, got -1.0"),
    ("negative-damping", [_with(JOINT, damping=-0.5)],
     "springs[0].damping: must be a finite number >= 0, got -0.5"),
    ("negative-free-length", [_with(LINK, free_length=-0.01)],
     "springs[0].free_length: must be a finite number >= 0, got -0.01"),
    ("stiffness-missing", [_with(LINK, stiffness=None)],
     "springs[0].stiffness: required key is missing"),
    ("stiffness-string", [_with(LINK, stiffness="500")],
     "springs[0].stiffness: must be a finite number >= 0, got \"500\""),
    ("link-and-itself", [_with(LINK, links=["rocker", "rocker"])],
     "springs[0].links: a spring between link 'rocker' and itself (it needs two different links)"),
    ("ground-and-itself", [_with(LINK, links=["ground", "ground"])],
     "springs[0].links: a spring between link 'ground' and itself"),
    ("unknown-link", [_with(LINK, links=["ground", "rocket"])],
     "springs[0].links[1]: unknown link 'rocket' (did you mean 'rocker'?)"),
    ("links-one-name", [_with(LINK, links=["rocker"])],
     "springs[0].links: must be an array of 2 link names, got [\"rocker\"]"),
    ("at-one-point", [_with(LINK, at=[[0.1, 0.05]])],
     "springs[0].at: must be two points [[x, y], [x, y]] (one on each link), got 1 items"),
    ("at-bad-coordinate", [_with(LINK, at=[[0.1, 0.05], [0.07, "x"]])],
     "springs[0].at[1][1]: must be a finite number, got \"x\""),
    ("at-missing", [_with(LINK, at=None)], "springs[0].at: required key is missing"),
    ("at-coincide", [_with(LINK, at=[[0.07, 0.02], [0.07, 0.02]])],
     "springs[0].at: the two points coincide in the assembly configuration"),
    ("unknown-joint", [_with(JOINT, joint="Q")], "springs[0].joint: unknown joint 'Q'"),
    ("joint-not-R", None, "springs[0].joint: a joint spring acts at an R joint; joint 'S' is of type P"),
    ("joint-and-links", [_with(LINK, joint="D")],
     "springs[0]: give either 'joint' (a spring at an R joint) or 'links' and 'at'"),
    ("neither", [{"name": "k", "stiffness": 1.0}],
     "springs[0].links: required key is missing (a spring joins two links"),
    ("free-length-at-joint", [_with(JOINT, free_length=0.1)],
     "springs[0].free_length: not allowed on a joint spring (only between two links)"),
    ("free-angle-between-links", [_with(LINK, free_angle_deg=5.0)],
     "springs[0].free_angle_deg: not allowed on a spring between two links (only at a joint)"),
    ("duplicate-name", [LINK, _with(JOINT, name="k1")],
     "springs[1].name: duplicate spring name 'k1' (first at springs[0])"),
    ("name-missing", [_with(LINK, name=None)], "springs[0].name: required key is missing"),
    ("unknown-key", [_with(LINK, stifness=3.0)],
     "springs[0].stifness: unknown key (did you mean 'stiffness'?)"),
    ("not-an-object", ["k1"], "springs[0]: must be an object, got a string"),
    ("point-far-away", [_with(LINK, at=[[0.1, 0.05], [1e12, 0.0]])], "springs[0].at[1]"),
]


def _scene_of(case_id, springs):
    if case_id == "joint-not-R":
        d = example_dict("slider_crank_offset")
        (slide,) = [j["name"] for j in d["joints"] if j["type"] == "P"]
        assert slide == "C_guide"
        d["joints"] = [dict(j, name="S") if j["name"] == slide else j for j in d["joints"]]
        d["springs"] = [{"name": "k", "joint": "S", "stiffness": 1.0}]
        return d
    return scene_with(*springs)


@pytest.mark.parametrize("case_id, springs, problem", BAD, ids=[b[0] for b in BAD])
def test_bad_springs_are_refused_naming_the_field(case_id, springs, problem):
    got = problems(_scene_of(case_id, springs))
    assert any(p.startswith(problem) for p in got), got


def test_every_problem_at_once_with_the_rest_of_the_scene():
    d = scene_with(_with(LINK, stiffness=-1.0, links=["rocker", "rocker"]),
                   _with(JOINT, joint="Q", damping=-1.0), effects={"springs": "yes"})
    d["links"][0]["mass"] = -1.0
    got = problems(d)
    assert got == [
        "links[0].mass: must be a finite number >= 0, got -1.0",
        "effects.springs: must be true or false, got \"yes\"",
        "springs[0].stiffness: must be a finite number >= 0, got -1.0",
        "springs[0].links: a spring between link 'rocker' and itself (it needs two different links)",
        "springs[1].damping: must be a finite number >= 0, got -1.0",
        "springs[1].joint: unknown joint 'Q'",
    ]


def test_springs_not_an_array():
    assert problems(dict(scene_with(), springs={"k1": LINK})) == [
        "springs: must be an array, got an object"]


def test_dump_and_read_back_is_the_same_scene():
    for effects in (None, {"springs": False}):
        scene = parse_scene(scene_with(LINK, _with(JOINT, free_angle_deg=12.3), effects=effects))
        assert parse_scene(json.loads(json.dumps(dump_scene(scene)))) == scene
    plain = parse_scene(example_dict("crank_rocker"))
    assert "springs" not in dump_scene(plain) and "springs" not in dump_scene(plain)["effects"]


def test_schema_takes_the_example_and_refuses_what_it_can_express():
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((ROOT / "docs" / "scene.schema.json").read_text(encoding="utf-8"))
    v = jsonschema.Draft202012Validator(schema)
    assert list(v.iter_errors(example_dict("crank_rocker_spring"))) == []
    assert list(v.iter_errors(scene_with(LINK, JOINT))) == []
    for case_id, springs, _ in BAD:
        if case_id in {"negative-stiffness", "negative-damping", "negative-free-length",
                       "stiffness-missing", "stiffness-string", "links-one-name", "at-one-point",
                       "at-bad-coordinate", "at-missing", "joint-and-links", "neither",
                       "free-length-at-joint", "free-angle-between-links", "name-missing",
                       "unknown-key", "not-an-object"}:
            assert list(v.iter_errors(_scene_of(case_id, springs))), case_id


def test_the_command_line_refuses_and_writes_nothing(tmp_path):
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(scene_with(_with(LINK, links=["rocker", "rocker"]))))
    out = tmp_path / "r.json"
    run = subprocess.run([sys.executable, "-m", "linkage_sym", "analyze", str(scene), "-o", str(out)],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 2
    assert "springs[0].links: a spring between link 'rocker' and itself" in run.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.json"]
