"""Structural analysis: mobility, Assur groups in solving order, disconnection choices.

Expected decompositions are worked out by hand from the mechanisms' graphs
(textbook Assur-group rules), not produced by the code under test.
"""

import pytest

from linkage_sym import SceneError
from linkage_sym.model import Driver, Joint, Link, Scene
from linkage_sym.structure import decompose, disconnections, mobility, structure_report


def _scene(joints, links, drivers):
    return Scene(
        "t",
        tuple(Link(n) for n in links),
        tuple(Joint(*j) for j in joints),
        tuple(Driver(*d) for d in drivers),
    )


def fourbar():
    return _scene(
        [
            ("A", "R", ("ground", "crank"), (0, 0)),
            ("B", "R", ("crank", "coupler"), (1, 0)),
            ("C", "R", ("coupler", "rocker"), (2, 1)),
            ("D", "R", ("rocker", "ground"), (3, 0)),
        ],
        ["crank", "coupler", "rocker"],
        [("A", "R", 0.0, 1.0, 5, 1.0, 0.0, "B")],
    )


def triad():
    """Crank + class-III group: ternary t with binaries b1 (to crank), b2, b3 (to ground)."""
    return _scene(
        [
            ("A", "R", ("ground", "crank"), (0, 0)),
            ("B", "R", ("crank", "b1"), (1, 0)),
            ("C", "R", ("b1", "t"), (2, 1)),
            ("D", "R", ("t", "b2"), (3, 1)),
            ("E", "R", ("b2", "ground"), (3.2, -0.5)),
            ("F", "R", ("t", "b3"), (2.5, 2)),
            ("G", "R", ("b3", "ground"), (1.5, 3)),
        ],
        ["crank", "b1", "t", "b2", "b3"],
        [("A", "R", 0.0, 0.6, 5, 1.0, 0.0, "B")],
    )


def test_fourbar_is_input_plus_rrr():
    s = fourbar()
    assert mobility(s) == 1
    g = decompose(s).groups
    assert [x.kind for x in g] == ["input", "dyad"]
    assert g[1].dyad_type == "RRR" and set(g[1].links) == {"coupler", "rocker"}
    assert set(g[1].external) == {"B", "D"} and g[1].internal == ("C",)


@pytest.mark.parametrize(
    "types, expected",
    [
        # (type of B, type of C, type of D) -> canonical dyad type
        (("R", "R", "P"), "RRP"),  # slider-crank
        (("R", "P", "R"), "RPR"),  # guide-bar (inverted slider-crank)
        (("P", "R", "P"), "PRP"),
        (("R", "P", "P"), "RPP"),
        (("P", "R", "R"), "RRP"),  # written the other way round
        (("P", "P", "R"), "RPP"),
    ],
)
def test_dyad_types(types, expected):
    tb, tc, td = types
    joints = [
        Joint("A", "R", ("ground", "crank"), (0, 0)),
        Joint("B", tb, ("crank", "coupler"), (1, 0), None if tb == "R" else 0.3),
        Joint("C", tc, ("coupler", "rocker"), (2, 1), None if tc == "R" else 1.2),
        Joint("D", td, ("rocker", "ground"), (3, 0), None if td == "R" else 0.1),
    ]
    s = Scene(
        "t",
        (Link("crank"), Link("coupler"), Link("rocker")),
        tuple(joints),
        (Driver("A", "R", 0.0, 1.0, 5, 1.0, 0.0, "B"),),
    )
    (g,) = [x for x in decompose(s).groups if x.kind == "dyad"]
    assert g.dyad_type == expected
    # the links are ordered so the type reads first external, internal, last external
    jt = {j.name: j.type for j in joints}
    assert "".join(jt[n] for n in g.joints) == expected


def test_triad_is_class_three_with_its_disconnections():
    s = triad()
    dec = decompose(s)
    assert [g.kind for g in dec.groups] == ["input", "triad"]
    tri = dec.groups[1]
    assert tri.assur_class == 3
    assert set(tri.links) == {"b1", "t", "b2", "b3"}
    assert set(tri.external) == {"B", "E", "G"} and set(tri.internal) == {"C", "D", "F"}
    choices = disconnections(s, tri)
    # remove one of 3 binary links, then either of the 2 others drives: 6 choices;
    # cut one of the 3 internal joints, then 2 inputs among 3 binaries leaving a dyad: 2 each
    by_link = [c for c in choices if c.removed_links]
    by_joint = [c for c in choices if not c.removed_links]
    assert len(by_link) == 6 and len(by_joint) == 6
    for c in by_link:
        assert c.unknowns == 1 and len(c.dyads) == 1
        (inp, _), = c.inputs
        assert inp != c.removed_links[0] and inp != "t"
    for c in by_joint:
        assert c.unknowns == 2


def test_report_lists_groups_and_choices():
    s = triad()
    text = structure_report(s, decompose(s))
    assert "triad (class III): b1, t, b2, b3" in text
    assert "remove link 'b1' (joints B, C); input 'b2' turning about E -> dyad RRR" in text


def test_over_and_under_constrained_parts_are_refused():
    # a rigid triangle (over-constrained) plus a free two-link chain: Grübler says 1,
    # yet no group closes
    s = _scene(
        [
            ("A", "R", ("ground", "crank"), (0, 0)),
            ("B", "R", ("crank", "x"), (1, 0)),
            ("C", "R", ("x", "ground"), (1, 1)),
            ("D", "R", ("ground", "p"), (5, 0)),
            ("E", "R", ("p", "q"), (6, 0)),
        ],
        ["crank", "x", "p", "q"],
        [("A", "R", 0.0, 1.0, 5, 1.0, 0.0, "B")],
    )
    assert mobility(s) == 3 * 4 - 2 * 5 == 2
    s = _scene(
        [
            ("A", "R", ("ground", "crank"), (0, 0)),
            ("B", "R", ("crank", "x"), (1, 0)),
            ("C", "R", ("x", "ground"), (1, 1)),
            ("F", "R", ("x", "y"), (1, 0.5)),
            ("G", "R", ("y", "ground"), (0.5, 0.5)),
            ("D", "R", ("ground", "p"), (5, 0)),
            ("E", "R", ("p", "q"), (6, 0)),
        ],
        ["crank", "x", "y", "p", "q"],
        [("A", "R", 0.0, 1.0, 5, 1.0, 0.0, "B")],
    )
    assert mobility(s) == 1
    with pytest.raises(SceneError, match="structure: links .* over-constrained"):
        decompose(s)


def test_relative_driver_group():
    """Hydraulic boom: cylinder and piston with a P driver between them (an actuator)."""
    s = Scene(
        "boom",
        (Link("cyl"), Link("piston"), Link("boom")),
        (
            Joint("O", "R", ("ground", "cyl"), (0, 0)),
            Joint("S", "P", ("cyl", "piston"), (1, 0.5), 0.4636476),
            Joint("Q", "R", ("piston", "boom"), (2, 1)),
            Joint("H", "R", ("boom", "ground"), (-1, 1)),
        ),
        (Driver("S", "P", 0.0, 0.3, 5, 0.1),),
    )
    (g,) = decompose(s).groups
    assert g.kind == "driven" and set(g.links) == {"cyl", "piston", "boom"}
    assert g.drivers == ("S",)
