"""Mutated example scenes are analysed into strict JSON or refused with a SceneError.

Each case takes one of the shipped examples (``linkage_sym/examples/*.json``),
mutates it the way a hand-edited file goes wrong -- a key deleted, a value of
the wrong type, NaN, an infinity, 1e308, 1e-300, an empty list, a duplicate
name, the two links of a joint swapped, a joint moved -- and checks that
:func:`linkage_sym.analyze` either refuses it with :class:`SceneError` or gives
a result whose JSON is strict (no ``NaN``, no ``Infinity``).  Any other
exception fails the test.

The cases are drawn reproducibly (``derandomize=True``, no example database)
and few enough to run in seconds.
"""

from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict, example_names
from linkage_sym.scene import parse_scene

STEPS = 5
"""Steps of every driver of a mutated scene: enough for a sweep, few for speed."""

BAD_NUMBERS = (math.nan, math.inf, -math.inf, 1e308, -1e308, 1e-300, -1e-300)
WRONG_TYPES = (None, True, "x", "", [], {}, [1.0], {"x": 1.0}, 0, -1)

MUTATIONS = (
    "delete a key",
    "wrong type",
    "bad number",
    "empty list",
    "duplicate name",
    "swap links",
    "move a joint",
)


def _base(name: str) -> dict:
    """The example as parsed JSON, with a short sweep."""
    data = example_dict(name)
    for driver in data["drivers"]:
        driver["steps"] = STEPS
    return data


BASES = {name: _base(name) for name in example_names()}


def _paths(value, prefix=()):
    """Paths of every value nested in ``value`` (not the root), in document order."""
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list):
        items = enumerate(value)
    else:
        return
    for key, item in items:
        yield (*prefix, key)
        yield from _paths(item, (*prefix, key))


def _parent(data, path):
    for key in path[:-1]:
        data = data[key]
    return data


def _mutate(data: dict, kind: str, draw) -> str:
    """Apply one mutation of ``kind`` to ``data`` in place; returns what it did."""
    paths = list(_paths(data))
    if kind == "delete a key":
        path = draw(st.sampled_from([p for p in paths if isinstance(p[-1], str)]))
        del _parent(data, path)[path[-1]]
        return f"deleted {path}"
    if kind == "wrong type":
        path = draw(st.sampled_from(paths))
        value = draw(st.sampled_from(WRONG_TYPES))
        _parent(data, path)[path[-1]] = copy.deepcopy(value)
        return f"{path} = {value!r}"
    if kind == "bad number":
        numeric = [p for p in paths if isinstance(_parent(data, p)[p[-1]], (int, float))
                   and not isinstance(_parent(data, p)[p[-1]], bool)]
        path = draw(st.sampled_from(numeric))
        value = draw(st.sampled_from(BAD_NUMBERS))
        _parent(data, path)[path[-1]] = value
        return f"{path} = {value!r}"
    if kind == "empty list":
        path = draw(st.sampled_from([p for p in paths if isinstance(_parent(data, p)[p[-1]], list)]))
        _parent(data, path)[path[-1]] = []
        return f"{path} = []"
    if kind == "duplicate name":
        section = draw(st.sampled_from([s for s in ("links", "joints", "points")
                                        if len(data.get(s, [])) >= 2]))
        i, j = draw(st.lists(st.integers(0, len(data[section]) - 1), min_size=2, max_size=2,
                             unique=True))
        data[section][j]["name"] = data[section][i]["name"]
        return f"{section}[{j}].name = {section}[{i}].name"
    if kind == "swap links":
        i = draw(st.integers(0, len(data["joints"]) - 1))
        other = draw(st.integers(0, len(data["joints"]) - 1))
        if other == i:  # the two ends of one joint
            data["joints"][i]["links"].reverse()
            return f"joints[{i}].links reversed"
        a, b = data["joints"][i], data["joints"][other]
        a["links"], b["links"] = b["links"], a["links"]
        return f"joints[{i}].links <-> joints[{other}].links"
    if kind == "move a joint":
        i = draw(st.integers(0, len(data["joints"]) - 1))
        joint = data["joints"][i]
        if draw(st.booleans()):  # onto another joint
            j = draw(st.integers(0, len(data["joints"]) - 1))
            joint["at"] = list(data["joints"][j]["at"])
        else:
            dx, dy = draw(st.tuples(*[st.floats(-0.5, 0.5, allow_nan=False)] * 2))
            joint["at"] = [joint["at"][0] + dx, joint["at"][1] + dy]
        return f"joints[{i}].at = {joint['at']}"
    raise AssertionError(kind)


def _refuse_constant(name):
    raise ValueError(f"non-finite number {name} in the result JSON")


def assert_strict_json(analysis) -> dict:
    """The result's JSON, checked strict both ways: written and parsed."""
    text = analysis.to_json()
    parsed = json.loads(text, parse_constant=_refuse_constant)
    # and the plain to_dict() that the command line dumps is strict as well
    assert json.loads(json.dumps(analysis.to_dict(), allow_nan=False)) == parsed
    return parsed


@pytest.mark.slow
@settings(
    max_examples=100,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(name=st.sampled_from(sorted(BASES)), kind=st.sampled_from(MUTATIONS), data=st.data())
def test_a_mutated_example_is_analysed_or_refused(name, kind, data):
    scene_data = copy.deepcopy(BASES[name])
    what = _mutate(scene_data, kind, data.draw)
    note = f"{name}: {kind}: {what}"
    try:
        scene = parse_scene(scene_data)
        analysis = linkage_sym.analyze(scene)
    except SceneError as error:
        assert error.problems and all(": " in p for p in error.problems), note
        event(f"{kind}: refused")
        return
    event(f"{kind}: analysed")
    result = assert_strict_json(analysis)
    assert len(result["steps"]) == STEPS, note


@pytest.mark.parametrize("name", sorted(BASES))
def test_every_unmutated_example_gives_strict_json(name):
    assert_strict_json(linkage_sym.analyze(parse_scene(copy.deepcopy(BASES[name]))))


# -- the JSON writer is strict whatever the arrays hold ----------------------------------


def _analysis_with_non_finite_values():
    analysis = linkage_sym.analyze(parse_scene(copy.deepcopy(BASES["crank_rocker"])))
    joint = analysis.joints["C"]
    joint.velocity = joint.velocity.copy()
    joint.velocity[1, 0] = math.inf
    link = analysis.links["coupler"]
    link.omega = link.omega.copy()
    link.omega[2] = math.nan
    forces = analysis.forces
    forces.driving = {k: v.copy() for k, v in forces.driving.items()}
    forces.driving["A"][3] = -math.inf
    forces.frame_moment = forces.frame_moment.copy()
    forces.frame_moment[3] = math.nan
    return analysis


def test_non_finite_values_are_left_out_and_named():
    analysis = _analysis_with_non_finite_values()
    result = assert_strict_json(analysis)
    steps = result["steps"]
    assert "velocity" not in steps[1]["joints"]["C"]
    assert steps[1]["joints"]["C"]["position"] == analysis.joints["C"].position[1].tolist()
    assert "omega" not in steps[2]["links"]["coupler"] and "alpha" in steps[2]["links"]["coupler"]
    assert "A" not in steps[3]["driving"]
    assert steps[3]["frame"] == {"force": analysis.forces.frame_force[3].tolist()}
    assert [s["status"] for s in steps] == ["ok"] * STEPS  # the other values are still results
    assert "velocity" in steps[0]["joints"]["C"] and "A" in steps[0]["driving"]
    assert result["warnings"][-1] == (
        "4 computed values are not finite (NaN or infinite) and left out of the result: "
        "steps[1].joints.C.velocity, steps[2].links.coupler.omega, steps[3].driving.A and 1 more"
    )


def test_to_json_never_writes_nan_or_infinity():
    analysis = _analysis_with_non_finite_values()
    text = analysis.to_json(indent=1)
    json.loads(text, parse_constant=_refuse_constant)
    with pytest.raises(ValueError, match="non-finite number NaN"):
        json.loads('{"x": NaN}', parse_constant=_refuse_constant)  # the check itself bites


def test_a_finite_result_has_no_extra_warning():
    analysis = linkage_sym.analyze(parse_scene(copy.deepcopy(BASES["crank_rocker"])))
    assert analysis.to_dict().get("warnings", []) == analysis.warnings
    assert np.isfinite(analysis.forces.frame_moment).all()
