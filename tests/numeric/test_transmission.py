"""Transmission angles of RRR dyads (``linkage_sym.numeric.results.transmission``, the result's
``transmission_angles`` extension, and its plot).

Checked against formulas written here that share no code with the function:
the law of cosines with the dyad's link lengths (from the scene's assembly
points) and the distance of its outer joints (solver positions), and for the
four-bar the closed form in the crank angle of the textbook section *Design of
four-bar mechanisms* (cos gamma = (b^2 + c^2 - a^2 - d^2 + 2 a d cos phi)/(2 b c)).
"""

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.examples import example_dict, example_path
from linkage_sym.numeric.results.transmission import rrr_dyads, transmission_angles
from linkage_sym.plotting.transmission import minimum, transmission_angles as plot_angles
from linkage_sym.synthesis import builders

TOL = 1e-12
"""cos(gamma) of the function against the formulas (absolute; cosines are O(1))."""


def law_of_cosines(scene, res, inner, e1, e2):
    J, P, Q = (np.array(scene.joint(n).at) for n in (inner, e1, e2))
    l1, l2 = math.dist(J, P), math.dist(J, Q)
    r = np.hypot(*(res.joints[e1].position - res.joints[e2].position).T)
    return (l1 * l1 + l2 * l2 - r * r) / (2 * l1 * l2)


@pytest.mark.parametrize("name", ["crank_rocker", "watt_sixbar", "stephenson_sixbar",
                                  "sixbar_class3", "fivebar", "song_wang_sixbar"])
def test_examples_against_the_law_of_cosines(name):
    scene = linkage_sym.load_example(name)
    res = linkage_sym.analyze(scene)
    dyads = rrr_dyads(scene)
    assert set(res.transmission_angles) == {d[0] for d in dyads}
    for inner, e1, e2 in dyads:
        g = res.transmission_angles[inner]
        ok = np.isfinite(g)
        assert ok.any()
        assert np.abs(np.cos(g[ok]) - law_of_cosines(scene, res, inner, e1, e2)[ok]).max() <= TOL
        assert ((g[ok] >= 0) & (g[ok] <= math.pi)).all()


@settings(max_examples=50, deadline=None)
@given(st.floats(0.2, 1.0), st.floats(2.0, 4.0), st.floats(2.0, 4.0), st.floats(2.0, 4.0),
       st.sampled_from(["open", "crossed"]))
def test_random_fourbars_against_the_closed_form(a, b, c, d, branch):
    try:
        design = builders.fourbar(a, b, c, d, crank_deg=90.0, branch=branch, steps=73)
    except linkage_sym.synthesis.SynthesisError:
        return
    scene = linkage_sym.load_scene(design.scene)
    res = linkage_sym.analyze(scene)
    phi = res.drivers["A"]["q"]
    closed = (b * b + c * c - a * a - d * d + 2 * a * d * np.cos(phi)) / (2 * b * c)
    g = res.transmission_angles["C"]
    ok = res.status != "unassemblable"
    assert np.isnan(g[~ok]).all()
    assert np.abs(np.cos(g[ok]) - closed[ok]).max() <= TOL * 8


def test_result_json_carries_them_with_the_kinematics(tmp_path):
    out = tmp_path / "r.json"
    assert main(["analyze", str(example_path("crank_rocker")), "-o", str(out)]) == 0
    steps = json.loads(out.read_text())["steps"]
    assert all(set(s["transmission_angles"]) == {"C"} for s in steps)
    res = linkage_sym.analyze(linkage_sym.load_example("crank_rocker"))
    assert [s["transmission_angles"]["C"] for s in steps] == res.transmission_angles["C"].tolist()


def test_not_written_without_kinematics_positions_or_rrr_dyads():
    d = example_dict("crank_rocker")
    d["outputs"] = ["driving"]
    r = linkage_sym.analyze(linkage_sym.load_scene(d)).to_dict()
    assert all("transmission_angles" not in s for s in r["steps"])
    r = linkage_sym.analyze(linkage_sym.load_example("slider_crank_offset"))
    assert r.transmission_angles == {}
    assert all("transmission_angles" not in s for s in r.to_dict()["steps"])
    # a step that cannot be assembled has none
    d = builders.fourbar(1.0, 1.0, 1.0, 1.5, crank_deg=0.0, steps=37).scene
    r = linkage_sym.analyze(linkage_sym.load_scene(d)).to_dict()
    bad = [s for s in r["steps"] if s["status"] == "unassemblable"]
    assert bad and all("transmission_angles" not in s for s in bad)


def test_symbolic_method_gives_the_same():
    scene = linkage_sym.load_example("watt_sixbar")
    num = linkage_sym.analyze(scene).transmission_angles
    sym = linkage_sym.analyze(scene, method="symbolic").transmission_angles
    assert set(num) == set(sym) == {"C", "E"}
    for k in num:
        assert np.abs(np.cos(num[k]) - np.cos(sym[k])).max() <= 1e-10


def test_function_on_an_analysis_and_scene():
    scene = linkage_sym.load_example("crank_rocker")
    res = linkage_sym.analyze(scene)
    g = transmission_angles(scene, res)
    assert np.array_equal(g["C"], res.transmission_angles["C"])


def test_plot_marks_the_minimum(tmp_path):
    scene = linkage_sym.load_example("watt_sixbar")
    res = linkage_sym.analyze(scene)
    path = plot_angles(scene, res, tmp_path / "t.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    k, v = minimum(res.transmission_angles["C"])
    g = res.transmission_angles["C"]
    assert v == pytest.approx(np.min(np.minimum(g, np.pi - g)), rel=0)
    with pytest.raises(ValueError, match="no transmission angles"):
        r2 = linkage_sym.analyze(linkage_sym.load_example("slider_crank_offset"))
        plot_angles(linkage_sym.load_example("slider_crank_offset"), r2, tmp_path / "x.png")


@pytest.mark.slow
def test_analyze_plots_include_it(tmp_path):
    pics = tmp_path / "pics"
    assert main(["analyze", str(example_path("crank_rocker")), "--plots", str(pics)]) == 0
    assert (pics / "crank-rocker_transmission.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
