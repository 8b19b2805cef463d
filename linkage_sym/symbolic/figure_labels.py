"""Where the loop figures' labels go: clear of each other, of the joints' dots and of the lines.

:mod:`linkage_sym.symbolic.latex_figures` names each joint, vector and angle of a loop's
picture.  Placed by fixed rules (a joint's name away from the mechanism's centre, a vector's
name on one side of its middle, an angle's name in its arc) labels met where several vectors
start at one joint: the shaper's B and E had three labels over one another.  A
:class:`Placer` places them one after another, each at the first of its candidate places
(in the order of preference) whose box, estimated from its text (:func:`label_size`), overlaps
no label placed before it and no joint's dot, and crosses the fewest lines; a joint's
candidates look first along the bisector of the largest angle free of its lines
(:func:`free_directions`).  Coordinates are the picture's centimetres.

Examples
--------
>>> p = Placer()
>>> p.dot(0j)
>>> p.segment(0j, 2 + 0j)
>>> c = p.place((0.5, 0.3), around(0j, (0.5, 0.3), free_directions(0j, [0.0])))
>>> round(c.real, 2), round(c.imag, 2)
(-0.37, 0.0)
"""

from __future__ import annotations

import cmath
import math
import re
from dataclasses import dataclass

from linkage_sym.symbolic.latex_notation import typeset_width

__all__ = ["CHAR", "DOT", "Box", "Placer", "around", "free_directions", "label_size"]

CHAR = 0.17
"""The width (cm) of one character of ``typeset_width`` at the figures' ``\\footnotesize``
(8 pt: an italic letter about 4.5 pt wide; measured on the rendered shaper's labels), with a
little to spare."""
LINE = 0.34
"""A label's height (cm): 8 pt type with its ascenders and descenders."""
SCRIPTED = 0.42
"""... with sub- or superscripts."""
DOT = 0.1
"""The radius (cm) around a joint's point that no label covers: its pin is 4 pt across."""
GAP = 0.04
"""The least space (cm) between two labels' boxes."""


@dataclass(frozen=True)
class Box:
    """A label's box: its centre and half sizes (cm)."""

    centre: complex
    hw: float
    hh: float

    def overlaps(self, other: Box, gap: float = GAP) -> bool:
        """Whether the boxes come closer than ``gap``."""
        d = self.centre - other.centre
        return (abs(d.real) < self.hw + other.hw + gap) and (abs(d.imag) < self.hh + other.hh + gap)

    def covers(self, p: complex, r: float = DOT) -> bool:
        """Whether the box comes within ``r`` of the point ``p``."""
        dx = max(abs(p.real - self.centre.real) - self.hw, 0.0)
        dy = max(abs(p.imag - self.centre.imag) - self.hh, 0.0)
        return math.hypot(dx, dy) < r

    def crosses(self, a: complex, b: complex) -> bool:
        """Whether the segment ``a b`` passes through the box (Liang and Barsky's clipping)."""
        t0, t1 = 0.0, 1.0
        d = b - a
        for p, q in ((-d.real, a.real - (self.centre.real - self.hw)),
                     (d.real, (self.centre.real + self.hw) - a.real),
                     (-d.imag, a.imag - (self.centre.imag - self.hh)),
                     (d.imag, (self.centre.imag + self.hh) - a.imag)):
            if abs(p) < 1e-12:
                if q < 0:
                    return False
                continue
            t = q / p
            if p < 0:
                t0 = max(t0, t)
            else:
                t1 = min(t1, t)
            if t0 > t1:
                return False
        return True


def label_size(text: str, math_mode: bool = True) -> tuple[float, float]:
    """A label's estimated ``(width, height)`` in cm: math by :func:`typeset_width`, text by
    its characters (``\\_`` one)."""
    if math_mode:
        tex = text.replace(r"\_", "x")
        w = typeset_width(tex)
        scripted = "_" in tex or "^" in tex
    else:
        w = len(text.replace(r"\_", "_"))
        scripted = False
    return CHAR * w + 0.08, SCRIPTED if scripted else LINE


def free_directions(p: complex, angles: list[float], n: int = 16) -> list[complex]:
    """Unit directions from ``p``: the bisector of the largest angle between the lines at
    ``p`` (their directions ``angles``, radians) first, then ``n`` directions round, the
    farthest from any line first."""
    if not angles:
        return [cmath.exp(1j * (math.pi / 2 - 2 * math.pi * k / n)) for k in range(n)]
    a = sorted(x % (2 * math.pi) for x in angles)
    gaps = [((a[(i + 1) % len(a)] - a[i]) % (2 * math.pi) or 2 * math.pi, a[i])
            for i in range(len(a))]
    gap, start = max(gaps)
    first = start + gap / 2

    def clearance(t):
        return min(abs(math.remainder(t - x, 2 * math.pi)) for x in a)

    round_ = sorted((first + 2 * math.pi * k / n for k in range(1, n)), key=clearance, reverse=True)
    return [cmath.exp(1j * t) for t in [first, *round_]]


def around(p: complex, size: tuple[float, float], directions, dists=(0.12, 0.25, 0.45)) -> list[complex]:
    """Candidate centres of a ``size`` box beside the point ``p``: in each direction (in
    order), the box's near side ``dist`` from ``p``, the nearer distances first."""
    hw, hh = size[0] / 2, size[1] / 2
    out = []
    for dist in dists:
        for d in directions:
            out.append(p + d * (dist + abs(d.real) * hw + abs(d.imag) * hh))
    return out


class Placer:
    """The labels placed so far and what they keep clear of."""

    def __init__(self):
        self.boxes: list[Box] = []
        self.dots: list[complex] = []
        self.segments: list[tuple[complex, complex]] = []

    def block(self, box: Box) -> None:
        """A box no label may overlap (a fixed label, a slider's block)."""
        self.boxes.append(box)

    def dot(self, p: complex) -> None:
        """A joint's point, which no label covers."""
        self.dots.append(p)

    def segment(self, a: complex, b: complex) -> None:
        """A drawn line, which labels avoid crossing where they can."""
        if abs(b - a) > 1e-9:
            self.segments.append((a, b))

    def angles_at(self, p: complex) -> list[float]:
        """The directions of the lines that end at ``p``."""
        out = []
        for a, b in self.segments:
            for x, y in ((a, b), (b, a)):
                if abs(x - p) < 1e-6:
                    out.append(cmath.phase(y - x))
        return out

    def place(self, size: tuple[float, float], candidates: list[complex]) -> complex:
        """The first candidate centre whose box overlaps no label and covers no dot, crossing
        the fewest lines (the least trouble where every candidate has some); the box is kept."""
        best = None
        for k, c in enumerate(candidates):
            box = Box(c, size[0] / 2, size[1] / 2)
            hard = sum(box.overlaps(b) for b in self.boxes) + sum(box.covers(p) for p in self.dots)
            soft = sum(box.crosses(a, b) for a, b in self.segments)
            score = (hard, soft, k)
            if best is None or score < best[0]:
                best = (score, box)
            if score[:2] == (0, 0):
                break
        self.boxes.append(best[1])
        return best[1].centre

