"""Traced points (the scene format's ``points`` extension): validation, JSON, symbolic path.

Their motion against eq. 3-18 of the kinematics chapter [4] is checked in
``test_kinematics_reference.test_fourbar_matches_complex_vector_solution``.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict
from linkage_sym.plotting.paths import link_points
from linkage_sym.scene import dump_scene, parse_scene


def _with_points(points):
    d = example_dict("crank_rocker")
    d["points"] = points
    return d


def test_bad_points_are_refused_each_by_its_field():
    d = _with_points([
        {"name": "P", "link": "coupler", "at": [0.03, 0.06]},
        {"name": "B", "link": "ground", "at": [0, "x"]},
        {"name": "P", "link": "cuopler", "at": [0, 0], "size": 3},
        {"link": "rocker", "at": [0.0]},
    ])
    with pytest.raises(SceneError) as info:
        parse_scene(d)
    assert info.value.problems == [
        "points[1].name: 'B' already names joints[1]; a point needs its own name",
        "points[1].link: a point on 'ground' does not move; points trace moving links",
        "points[1].at[1]: must be a finite number, got \"x\"",
        "points[2].size: unknown key",
        "points[2].name: duplicate point name 'P' (first at points[0])",
        "points[2].link: unknown link 'cuopler' (did you mean 'coupler'?)",
        "points[3].name: required key is missing",
        "points[3].at: must be an array of 2 finite numbers [x, y], got [0.0]",
    ]
    with pytest.raises(SceneError, match="points: must be an array"):
        parse_scene(_with_points({"name": "P"}))


def test_points_round_trip_and_stay_out_when_absent():
    scene = linkage_sym.load_example("crank_rocker")
    assert [p.name for p in scene.points] == ["P"]
    assert parse_scene(dump_scene(scene)) == scene
    bare = example_dict("crank_rocker")
    del bare["points"]
    assert "points" not in dump_scene(parse_scene(bare))


def test_points_in_the_result_json_only_where_positions_are():
    """Every step with positions carries the point with the arrays' values; a scene
    without points has no ``points`` key; an unassemblable step has none."""
    d = _with_points([{"name": "P", "link": "coupler", "at": [0.03, 0.06]}])
    d["joints"][0]["at"] = [0.0, 0.0]
    res = linkage_sym.analyze(parse_scene(d))
    steps = res.to_dict()["steps"]
    for i in (0, 100, 300):
        rec = steps[i]["points"]["P"]
        assert rec["position"] == res.points["P"].position[i].tolist()
        assert rec["velocity"] == res.points["P"].velocity[i].tolist()
        assert rec["acceleration"] == res.points["P"].acceleration[i].tolist()
    del d["points"]
    assert all("points" not in s for s in linkage_sym.analyze(parse_scene(d)).to_dict()["steps"])
    # a crank too long over part of the turn: those steps have no point either
    d = _with_points([{"name": "P", "link": "coupler", "at": [0.03, 0.06]}])
    d["joints"][1]["at"] = [0.05, 0.0]  # crank 0.05: |BD| exceeds BC + CD over part of the turn
    res = linkage_sym.analyze(parse_scene(d))
    bad = np.flatnonzero(res.status == "unassemblable")
    assert len(bad) > 0
    steps = res.to_dict()["steps"]
    assert all("points" not in steps[i] for i in bad)
    assert np.all(np.isnan(res.points["P"].position[bad]))
    json.dumps(res.to_dict(), allow_nan=False)


def test_symbolic_run_gives_the_same_points():
    """The generated code's run computes points from its link motion (separate formulas
    in ``LinkKinematics.point*``): equal to the numeric plan's to 1e-12 of the sweep's
    largest value."""
    scene = linkage_sym.load_example("crank_rocker")
    num = linkage_sym.analyze(scene)
    sym = compile_mechanism(scene).run()
    for f in ("position", "velocity", "acceleration"):
        a, b = getattr(num.points["P"], f), getattr(sym.points["P"], f)
        assert np.max(np.abs(a - b)) <= 1e-12 * np.max(np.abs(a)), f


def test_a_traced_point_outlines_its_link():
    scene = linkage_sym.load_example("crank_rocker")
    assert (0.03, 0.06) in link_points(scene)["coupler"]
