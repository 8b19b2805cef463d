"""The loop figures' labels (``derive --latex``) do not collide (issue 31).

Read back from the TikZ source of every derivable shipped example's figures: each label's
place (a node ``at`` a point, or ``pos`` along a vector shifted by ``xshift``/``yshift``,
always ``anchor=center``) and its box, estimated here from its text with this test's own rule
(a character 0.14 cm at ``\\footnotesize``, 0.7 of that in a sub- or superscript, a line
0.30 cm high: smaller than :mod:`linkage_sym.symbolic.figure_labels`' estimate, so the test
does not lean on its margins).  No two boxes overlap, and no box covers a joint's pin (4 pt
across: 0.07 cm about its point).  The old figures had labels on top of each other at the
shaper's joints B and E.
"""

from __future__ import annotations

import itertools
import re

import pytest

from linkage_sym.examples import load_example
from linkage_sym.symbolic import derive
from linkage_sym.symbolic.figure_labels import free_directions
from linkage_sym.symbolic.latex import latex_document
from tests.support.example_sets import symbolic_examples
from tests.support.marks import fast_cases

CHAR, SCRIPT, HEIGHT, PIN = 0.14, 0.7, 0.30, 0.07
NUM = r"(-?[0-9.]+)"
PT = rf"\({NUM}, {NUM}\)"
NODE = re.compile(rf"\\node\[anchor=center\] at {PT} \{{(.*?)\}};(?: |$)", re.M)
ON_VECTOR = re.compile(rf"\\draw\[(?:ground )?vec\] {PT} -- {PT} node\[pos={NUM}, anchor=center, "
                       rf"xshift={NUM}cm, yshift={NUM}cm\] \{{(.*?)\}};$", re.M)
PIN_AT = re.compile(rf"\\node\[pin\] at {PT} \{{\}};")


def text_width(text: str) -> float:
    """The test's estimate of a label's width (cm)."""
    if not text.startswith("$"):  # a joint's names, in text
        return CHAR * len(text.replace(r"\_", "_"))
    t = text.strip("$").replace(r"\_", "x").replace(r"\mathrm", "")
    t = re.sub(r"\\(left|right)\b", "", t)
    t = re.sub(r"\\[A-Za-z]+", "a", t)
    width, depth, script = 0.0, 0, []
    pending = False
    for c in t:
        if c in "_^":
            pending = True
            continue
        if c == "{":
            depth += 1
            if pending:
                script.append(depth)
                pending = False
            continue
        if c == "}":
            if script and script[-1] == depth:
                script.pop()
            depth -= 1
            continue
        if c == " ":
            continue
        width += CHAR * (SCRIPT if (script or pending) else 1.0) * (2 if c in "+-" else 1)
        pending = False
    return width


def label_boxes(fig: str) -> list[tuple[str, tuple[float, float, float, float]]]:
    """Every label of a figure with its box ``(left, bottom, right, top)`` (cm)."""
    out = []

    def box(x, y, text):
        w = text_width(text) / 2
        return text, (x - w, y - HEIGHT / 2, x + w, y + HEIGHT / 2)

    for x, y, text in NODE.findall(fig):
        out.append(box(float(x), float(y), text))
    for x1, y1, x2, y2, pos, dx, dy, text in ON_VECTOR.findall(fig):
        t = float(pos)
        out.append(box(float(x1) + t * (float(x2) - float(x1)) + float(dx),
                       float(y1) + t * (float(y2) - float(y1)) + float(dy), text))
    return out


def overlap(a, b) -> bool:
    """Whether two boxes share an area."""
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def covers(box, x: float, y: float, r: float) -> bool:
    """Whether the box comes within ``r`` of the point."""
    dx = max(box[0] - x, 0.0, x - box[2])
    dy = max(box[1] - y, 0.0, y - box[3])
    return dx * dx + dy * dy < r * r


def test_the_estimate_reads_a_label():
    assert text_width("$l_{AB}$") == pytest.approx(CHAR * (1 + 2 * SCRIPT))
    assert text_width("A, B") == pytest.approx(CHAR * 4)
    assert label_boxes(r"\node[anchor=center] at (1, -2) {$O$};")[0][1] == pytest.approx(
        (1 - CHAR / 2, -2 - HEIGHT / 2, 1 + CHAR / 2, -2 + HEIGHT / 2))
    assert overlap((0, 0, 1, 1), (0.9, 0.9, 2, 2)) and not overlap((0, 0, 1, 1), (1, 0, 2, 1))
    assert covers((0, 0, 1, 1), 1.05, 0.5, 0.07) and not covers((0, 0, 1, 1), 1.1, 0.5, 0.07)


def test_the_largest_free_angle_is_looked_along_first():
    d = free_directions(0j, [0.0, 1.5707963267948966])  # lines along +x and +y
    assert abs(d[0] - complex(-0.7071067811865476, -0.7071067811865476)) < 1e-12


@pytest.mark.parametrize("name", fast_cases(symbolic_examples(), {"shaper", "gear_linkage"}))
def test_no_two_labels_overlap_and_none_covers_a_joint(name):
    eqs = derive(load_example(name))
    figs = re.findall(r"\\begin\{figure\}.*?\\end\{figure\}", latex_document(eqs, figures=True),
                      re.S)
    assert len(figs) == len(eqs.loops)
    for fig in figs:
        boxes = label_boxes(fig)
        # every label read: the joints' names, the vectors', the arcs' and the axes'
        assert len(boxes) == fig.count(r"\node[anchor=center]") + len(ON_VECTOR.findall(fig))
        assert len(boxes) >= len(ON_VECTOR.findall(fig)) > 0
        for (ta, a), (tb, b) in itertools.combinations(boxes, 2):
            assert not overlap(a, b), (name, ta, tb, a, b)
        pins = [(float(x), float(y)) for x, y in PIN_AT.findall(fig)]
        for (t, box), (x, y) in itertools.product(boxes, pins):
            assert not covers(box, x, y, PIN), (name, t, (x, y))
