"""Grashof class of four-bar loops (``linkage_sym.structure.grashof``).

Checked against a second criterion sharing no code with the length inequality:
a link next to the frame turns fully exactly when the dyad it drives can be
assembled at every angle, i.e. when the distance from its moving pivot to the
other fixed pivot, which ranges over ``[|d - a|, d + a]``, stays within the
dyad's reach ``[|b - c|, b + c]``; and on a few four-bars the solver itself
(every step of a full turn assembled, or not).
"""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.examples import example_path
from linkage_sym.structure.grashof import CHANGE_POINT_TOL, classify, four_bar_loops

from tests.support import scenes


def turns_fully(a, d, b, c):
    """Link ``a`` (next to the frame ``d``) turns fully: its dyad (b, c) reaches at every angle."""
    return d + a <= b + c and abs(d - a) >= abs(b - c)


length = st.floats(0.05, 20.0)


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(length, length, length, length)
def test_class_against_the_reach_of_the_dyads(d, a, b, c):
    """Random four-bars (frame d, crank a, coupler b, rocker c): the class names what turns."""
    margin = abs(min(a, b, c, d) + max(a, b, c, d) - (a + b + c + d - min(a, b, c, d) - max(a, b, c, d)))
    assume(margin > 1e-6 * (a + b + c + d))  # away from the change point, where both say "just"
    assume(2 * max(a, b, c, d) < a + b + c + d)  # a loop that closes
    g = classify([d, a, b, c], fixed=0)
    crank, rocker = turns_fully(a, d, b, c), turns_fully(c, d, b, a)
    expected = {(True, False): "crank-rocker", (False, True): "crank-rocker",
                (True, True): "double-crank", (False, False): "rockers"}[crank, rocker]
    if expected == "rockers":
        # neither link on the frame turns: a double-rocker when the coupler turns fully
        # relative to both (the same reach test with the crank, then the rocker, held
        # fixed), a triple-rocker when it does not
        coupler = turns_fully(b, a, c, d) and turns_fully(b, c, a, d)
        expected = "double-rocker" if coupler else "triple-rocker"
    assert g.name == expected, (d, a, b, c, g.detail)
    if g.name == "crank-rocker":
        assert g.shortest == (1 if crank else 3)


@pytest.mark.parametrize("lengths, turns", [
    ((0.078, 0.024, 0.06, 0.05), True),    # crank-rocker
    ((1.0, 3.0, 3.5, 4.0), True),          # double-crank (the frame shortest)
    ((4.0, 3.0, 1.0, 3.5), False),         # Grashof double-rocker
    ((3.0, 1.0, 1.2, 2.5), False),         # not Grashof
])
def test_class_against_the_solver(lengths, turns):
    """The crank's full turn: every step assembled exactly when the class says it turns."""
    d, a, b, c = lengths
    g = classify([d, a, b, c], fixed=0)
    assert (g.name in ("crank-rocker", "double-crank")) == turns
    # assemble where the dyad reaches: crank angle at the middle of the crank's range
    phi = next(p for p in np.linspace(0, math.pi, 181)
               if abs(b - c) < math.hypot(d - a * math.cos(p), a * math.sin(p)) < b + c)
    A, B, C, D = scenes.fourbar_points(a, b, c, d, phi)
    scene = {"name": "g", "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
             "joints": [{"name": "A", "type": "R", "links": ["ground", "crank"], "at": list(A)},
                        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": list(B)},
                        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": list(C)},
                        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": list(D)}],
             "drivers": [{"joint": "A", "toward": "B", "start_deg": math.degrees(phi),
                          "stop_deg": math.degrees(phi) + 360, "steps": 721, "speed": 1.0}],
             "outputs": ["kinematics"]}
    res = linkage_sym.analyze(linkage_sym.load_scene(scene))
    assert bool((res.status != "unassemblable").all()) == turns


def test_change_point_within_its_tolerance():
    """7 + 17 = 10 + 14 (tests/scenes.change_point_fourbar) is a change point; moved by twice
    the tolerance it is Grashof or not, by the sign."""
    loops = four_bar_loops(linkage_sym.load_scene(scenes.change_point_fourbar()))
    assert len(loops) == 1 and loops[0].grashof().name == "change point"
    p = 48.0
    assert classify([14.0, 7.0, 17.0, 10.0 + 2 * CHANGE_POINT_TOL * p]).grashof is True
    assert classify([14.0, 7.0, 17.0, 10.0 - 2 * CHANGE_POINT_TOL * p]).grashof is False
    assert classify([14.0, 7.0, 17.0, 10.0 + 0.5 * CHANGE_POINT_TOL * p]).name == "change point"


def test_loops_of_the_examples():
    """One loop in the crank-rocker, two in the Watt six-bar (one without the ground), none in a
    linkage whose loops hold a prismatic joint."""
    cr = four_bar_loops(linkage_sym.load_example("crank_rocker"))
    assert [(lp.links, lp.joints) for lp in cr] == [(("ground", "crank", "coupler", "rocker"),
                                                     ("A", "B", "C", "D"))]
    # lengths: distances of the assembly points (crank_rocker.json)
    assert cr[0].lengths == pytest.approx([0.078, 0.024, math.hypot(0.042, 0.047),
                                           math.hypot(0.012, 0.047)], rel=1e-15)
    watt = four_bar_loops(linkage_sym.load_example("watt_sixbar"))
    assert len(watt) == 2 and watt[0].links[0] == "ground" and "ground" not in watt[1].links
    assert watt[1].grashof().name in ("Grashof", "not Grashof", "change point")
    assert four_bar_loops(linkage_sym.load_example("slider_crank_offset")) == []


def test_structure_command_names_the_class(capsys):
    assert main(["structure", str(example_path("crank_rocker"))]) == 0
    out = capsys.readouterr().out
    assert "Four-bar loops (Grashof class" in out
    assert "ground D-A 0.078, crank A-B 0.024" in out and "): crank-rocker" in out


def test_not_grashof_is_a_triple_rocker_everywhere(capsys, tmp_path):
    """A four-bar that is not Grashof is named triple-rocker, never double-rocker: by
    ``classify``, in ``new fourbar``'s note, in the structure report and in a sweep's column;
    a Grashof four-bar with the coupler shortest stays a double-rocker."""
    from linkage_sym.structure.grashof import CLASS_NAMES

    lengths = [0.078, 0.05, 0.06, 0.05]  # ground, crank, coupler, rocker: 0.128 > 0.11
    assert classify(lengths, fixed=0).name == "triple-rocker"
    assert classify([4.0, 3.0, 1.0, 3.5], fixed=0).name == "double-rocker"
    assert set(CLASS_NAMES) == {"crank-rocker", "double-crank", "double-rocker",
                                "triple-rocker", "change point"}
    path = tmp_path / "tr.json"
    assert main(["new", "fourbar", "--crank", "0.05", "--coupler", "0.06", "--rocker", "0.05",
                 "--ground", "0.078", "-o", str(path)]) == 0
    out = capsys.readouterr().out
    assert "Grashof class: triple-rocker (not Grashof" in out and "double-rocker" not in out
    assert main(["structure", str(path)]) == 0
    out = capsys.readouterr().out
    assert "(m): triple-rocker" in out and "double-rocker" not in out
    res = linkage_sym.sweep(linkage_sym.load_scene(path), {"l_AB": [0.02, 0.05]}, ["grashof"])
    assert res["grashof"].tolist() == ["crank-rocker", "triple-rocker"]
