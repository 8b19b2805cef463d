"""A TikZ figure of each vector loop, drawn from the scene's geometry.

The figure a textbook places beside a vector-loop equation (the kinematics
chapter's eq. 3-8): the mechanism's links (grey; a link with three or more
joints as a plate, a gear as its pitch circle), its joints (ground pivots
hatched, a slider as a block), the loop's vectors (blue arrows, each named as
the printed loop equation names it: ``l_{AB}``, ``s_{B}``, ``x_{D} + i y_{D}``
from the origin) and the angles of its link vectors (arcs from the
``x``-direction, named ``\\theta`` as in the equation).

Every point is computed from the loop equation's own terms, evaluated in the
scene's assembly configuration (the joints' ``at``: link angles ``theta0``,
slides 0): a chain of vectors from a ground point to the joint that closes
the loop, both ways round, as :meth:`MechanismEquations.pos` places the
links.  Coordinates are centimetres on the page, ``scale`` times the scene's
(a comment in the picture states it), so that the picture fits
:data:`WIDTH` by :data:`HEIGHT`.  The picture needs only ``\\usepackage{tikz}``.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import sympy as sp

from linkage_sym.model import GROUND
from linkage_sym.structure.parameters import COINCIDENT, driver_q0
from linkage_sym.symbolic.closed_forms import other_link
from linkage_sym.symbolic.figure_labels import Box, Placer, around, free_directions, label_size
from linkage_sym.symbolic.latex_notation import escape_text
from linkage_sym.symbolic.vectors import Vec

__all__ = ["HEIGHT", "TIKZ_PREAMBLE", "WIDTH", "LoopTerm", "assembly_values", "loop_chains",
           "loop_figure"]

WIDTH = 11.0
"""The widest a figure's mechanism is drawn (cm): within the text of an A4 or letter page."""
HEIGHT = 10.0
"""The tallest a figure's mechanism is drawn (cm)."""
TIKZ_PREAMBLE = r"\usepackage{tikz}"
"""What a document needs in its preamble for the figures."""

_STYLES = (
    "link/.style={line width=2.2pt, draw=black!35, line cap=round, line join=round}, "
    "plate/.style={line width=1.2pt, draw=black!35, fill=black!8, line join=round}, "
    "gear/.style={line width=0.8pt, draw=black!35, dash pattern=on 3pt off 1.5pt}, "
    "vec/.style={->, >=stealth, line width=1pt, draw=blue!70!black}, "
    "ground vec/.style={vec, dashed}, "
    "angle/.style={->, >=stealth, line width=0.5pt, draw=red!60!black}, "
    "ref/.style={line width=0.4pt, draw=black!50, dash pattern=on 1.5pt off 1pt}, "
    "axis/.style={->, >=stealth, line width=0.5pt, draw=black!60}, "
    "pin/.style={circle, draw=black, fill=white, line width=0.6pt, inner sep=0pt, "
    "minimum size=4pt}, "
    "font=\\footnotesize"
)


@dataclass(frozen=True)
class LoopTerm:
    """One term of a half of a vector loop: ``coef e^{i angle}`` (a link vector or a
    slide) or a ground point ``x + i y`` (``angle`` None), ending at joint ``end``.

    Attributes
    ----------
    coef : Expr
        The length (signed as the chain walks it) or, for a ground point, ``x``.
    angle : Expr or None
        The angle of the unit vector; None for a ground point.
    y : Expr or None
        A ground point's ``y`` (None for a link vector).
    end : str
        The joint the chain reaches with this term.
    """

    coef: sp.Expr
    angle: sp.Expr | None
    y: sp.Expr | None
    end: str

    def vec(self) -> Vec:
        """The term as a :class:`Vec`."""
        return Vec.xy(self.coef, self.y) if self.angle is None else Vec.of(self.coef, self.angle)


def _chain(eqs, link: str, point: str) -> list[LoopTerm]:
    """The terms of ``eqs.pos(link, point)`` in the order a walk from the ground takes them."""
    if link == GROUND:
        x, y = (eqs.sym(n) for n in eqs.table.ground_point(point))
        return [LoopTerm(x, None, y, point)]
    J = eqs.scene.joint(eqs.anchor[link])
    out = _chain(eqs, other_link(J, link), J.name)
    if J.type == "P":  # the slide along the axis fixed on links[0]
        s = eqs.slide[J.name]
        angle = eqs.theta(J.links[0]) + eqs.sym(eqs.table.gamma(J.name))
        out.append(LoopTerm(s if link == J.links[1] else -s, angle, None, J.name))
    u = eqs.table.frames[link].u
    for start, end, sign in ((J.name, u, -1), (u, point, 1)):  # J to the origin u, u to point
        pl = eqs.table.point(link, start if sign < 0 else end)
        if start != end and pl is not None:
            l, b = pl
            th = eqs.theta(link) + (0 if b is None else eqs.sym(b))
            out.append(LoopTerm(sign * eqs.sym(l), th, None, end))
    return out


def loop_chains(eqs, jname: str) -> tuple[str | None, list[LoopTerm], list[LoopTerm]]:
    """The two halves of the loop closed at joint ``jname``: chains of terms from a common
    start to the joint, their shared beginning left out, so that the first half less the
    second is the printed loop (``eqs.loops``).

    Returns
    -------
    start : str or None
        The joint both halves start from (None: the origin, each half then starting
        with its ground point ``x + i y``).
    first, second : list of LoopTerm
        The halves, in walking order.

    Raises
    ------
    ValueError
        When the halves do not add up to the loop the equations hold (a bug).
    """
    J = eqs.scene.joint(jname)
    a, b = J.links
    if J.type == "R":
        h1, h2 = _chain(eqs, a, jname), _chain(eqs, b, jname)
    else:
        s = eqs.slide[jname]
        angle = eqs.theta(a) + eqs.sym(eqs.table.gamma(jname))
        h1, h2 = _chain(eqs, b, jname), _chain(eqs, a, jname) + [LoopTerm(s, angle, None, jname)]
    n = 0
    while n < min(len(h1), len(h2)) - 1 and h1[n] == h2[n]:
        n += 1
    start = h1[n - 1].end if n else None
    h1, h2 = h1[n:], h2[n:]
    total = sum((t.vec() for t in h1), Vec()) - sum((t.vec() for t in h2), Vec())
    loop = dict(eqs.loops)[jname]
    if sp.expand(total.complex() - loop.complex()) != 0:
        raise ValueError(f"the chains of loop {jname} do not add up to its equation")
    return start, h1, h2


def assembly_values(eqs) -> dict:
    """``{symbol: value}`` in the scene's assembly configuration: the parameters, the link
    angles ``theta0``, the slides 0 and the driver coordinates."""
    values = dict(eqs.parameter_values())
    values.update({eqs.th[n]: fr.theta0 for n, fr in eqs.table.frames.items()})
    values.update({s: 0.0 for s in eqs.slide.values()})
    q0 = driver_q0(eqs.scene)
    values.update({eqs.q_of[j]: v for j, v in q0.items()})
    return values


def _num(expr, values) -> float:
    return float(sp.sympify(expr).xreplace(values))


def _f(v: float) -> str:
    """A coordinate (cm) to 1e-10 cm, without a negative zero."""
    s = f"{v:.10f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _pt(z: complex) -> str:
    return f"({_f(z.real)}, {_f(z.imag)})"


class _Figure:
    """The picture of one loop: points, scale and the TikZ lines."""

    def __init__(self, eqs, nm, jname: str):
        self.eqs, self.nm, self.jname = eqs, nm, jname
        self.values = assembly_values(eqs)
        self.start, self.h1, self.h2 = loop_chains(eqs, jname)
        scene = eqs.scene
        # every joint where the derived position equations put it
        self.at = {n: complex(_num(k[0][0], self.values), _num(k[0][1], self.values))
                   for n, k in eqs.joint_kin.items()}
        pts = list(self.at.values()) + ([0j] if self.start is None else [])
        for j in scene.meshes:  # a gear's pitch circle
            pts += [self.at[p] + r * d for p, r in zip(j.pivots, j.radii) for d in (1, -1, 1j, -1j)]
        xs, ys = [p.real for p in pts], [p.imag for p in pts]
        size = scene.characteristic_length() or 1.0
        w, h = max(max(xs) - min(xs), size * 0.2), max(max(ys) - min(ys), size * 0.2)
        self.scale = min(WIDTH / w, HEIGHT / h)
        self.lines: list[str] = []
        self.arcs: dict[complex, int] = {}  # arcs drawn at each point
        self.placer = Placer()
        # labels placed once every line is known: (line index, size, candidates(), line(centre))
        self.pending: list[list] = [[], [], []]  # joints, vectors, angles: placed in this order

    def _label(self, rank: int, size, candidates, line) -> None:
        """A line to write once its label is placed (:meth:`place_labels`)."""
        self.pending[rank].append((len(self.lines), size, candidates, line))
        self.lines.append("")

    def place_labels(self) -> None:
        """Place every label (joints', then vectors', then angles') clear of the others, of
        the joints' dots and, where it can, of the lines
        (:class:`~linkage_sym.symbolic.figure_labels.Placer`), and write its line."""
        for rank in self.pending:
            for index, size, candidates, line in rank:
                self.lines[index] = line(self.placer.place(size, candidates()))

    def z(self, scene_point: complex) -> complex:
        return scene_point * self.scale

    def links(self) -> None:
        """Every moving link in grey: a bar, a plate or a gear's pitch circle."""
        scene = self.eqs.scene
        for link in scene.link_names:
            pts = []
            for j in scene.joints:
                if link in j.links and j.type in ("R", "P"):
                    p = self.z(self.at[j.name])
                    if all(abs(p - q) > 1e-6 for q in pts):
                        pts.append(p)
            if len(pts) == 2:
                self.lines.append(rf"\draw[link] {_pt(pts[0])} -- {_pt(pts[1])}; % link {link}")
                self.placer.segment(*pts)
            elif len(pts) > 2:
                c = sum(pts) / len(pts)
                pts.sort(key=lambda p: cmath.phase(p - c))
                for a, b in zip(pts, pts[1:] + pts[:1]):
                    self.placer.segment(a, b)
                path = " -- ".join(_pt(p) for p in pts)
                self.lines.append(rf"\draw[plate] {path} -- cycle; % link {link}")
        for j in scene.meshes:
            for gear, pivot, r in zip(j.links, j.pivots, j.radii):
                c = self.z(self.at[pivot])
                self.lines.append(rf"\draw[gear] {_pt(c)} circle[radius={_f(r * self.scale)}]; "
                                  f"% gear {gear}")

    def joints(self) -> None:
        """Ground pivots hatched, sliders as blocks, every joint a pin, named once (on the
        side free of its lines)."""
        scene = self.eqs.scene
        named: dict[complex, list[str]] = {}
        for j in scene.joints:
            p = self.z(self.at[j.name])
            self.lines.append(rf"\coordinate (J{len(self.lines)}) at {_pt(p)}; % joint {j.name}")
            key = next((k for k in named if abs(k - p) < 1e-6), p)
            named.setdefault(key, []).append(j.name)
            if j.type == "R" and GROUND in j.links:
                self.lines.append(rf"\begin{{scope}}[shift={{{_pt(p)}}}] \draw (0,0) -- (-0.16,-0.3) "
                                  r"-- (0.16,-0.3) -- cycle; \draw (-0.3,-0.3) -- (0.3,-0.3); "
                                  r"\foreach \k in {-0.24,-0.12,...,0.3} \draw (\k,-0.3) -- "
                                  r"(\k-0.12,-0.42); \end{scope}")
                self.placer.block(Box(p - 0.23j, 0.34, 0.2))  # the hatched base
            elif j.type == "P":
                axis = math.degrees(j.axis + _num(self.eqs.theta(j.links[0]), self.values))
                self._slider(p, math.radians(axis), GROUND in j.links)
                hatch = (r" \draw (-0.9,-0.13) -- (0.9,-0.13); \foreach \k in {-0.84,-0.66,...,0.9}"
                         r" \draw (\k,-0.13) -- (\k-0.12,-0.25);") if GROUND in j.links else ""
                self.lines.append(rf"\begin{{scope}}[shift={{{_pt(p)}}}, rotate={_f(axis)}]"
                                  r" \draw[fill=white] (-0.22,-0.13) rectangle (0.22,0.13);"
                                  + hatch + r" \end{scope}")
            if j.type in ("R", "P"):
                self.lines.append(rf"\node[pin] at {_pt(p)} {{}};")
                self.placer.dot(p)
        for p, names in named.items():
            self._point_label(p, ", ".join(escape_text(n) for n in names), math_mode=False)

    def _point_label(self, p: complex, text: str, math_mode: bool) -> None:
        """A point's name, first along the bisector of the largest angle free of its lines."""
        size = label_size(text, math_mode)

        def candidates():
            return around(p, size, free_directions(p, self.placer.angles_at(p)))

        body = f"${text}$" if math_mode else text
        self._label(0, size, candidates, lambda c: rf"\node[anchor=center] at {_pt(c)} {{{body}}};")

    def _slider(self, p: complex, axis: float, grounded: bool) -> None:
        """A slider's block (and a ground guide's hatched line) kept clear of the labels."""
        u, n = cmath.exp(1j * axis), cmath.exp(1j * axis) * 1j
        corners = [p + a * u + b * n for a in (-0.22, 0.22) for b in (-0.13, 0.13)]
        xs, ys = [c.real for c in corners], [c.imag for c in corners]
        self.placer.block(Box(p, (max(xs) - min(xs)) / 2, (max(ys) - min(ys)) / 2))
        if grounded:
            self.placer.segment(p - 0.9 * u - 0.13 * n, p + 0.9 * u - 0.13 * n)
            self.placer.segment(p - 0.9 * u - 0.25 * n, p + 0.9 * u - 0.25 * n)

    def origin(self) -> None:
        """The origin and the axes, where the ground points' vectors start there."""
        if self.start is None:
            self.lines.append(r"\draw[axis] (0,0) -- (0.8,0); \draw[axis] (0,0) -- (0,0.8);")
            for end, name in ((0.8 + 0j, "x"), (0.8j, "y")):
                self.placer.segment(0j, end)
                self._axis_label(end, name)
            self._point_label(0j, "O", math_mode=True)

    def _axis_label(self, end: complex, name: str) -> None:
        """An axis's name past its arrow's tip (or beside it, where lines cross there)."""
        size = label_size(name)
        u = end / abs(end)
        directions = [u, u * 1j, -u * 1j, u * cmath.exp(0.6j), u * cmath.exp(-0.6j)]
        self._label(0, size, lambda: around(end, size, directions, (0.04, 0.2, 0.4)),
                    lambda c: rf"\node[anchor=center] at {_pt(c)} {{${name}$}};")

    def _value(self, t: LoopTerm) -> complex:
        if t.angle is None:
            return complex(_num(t.coef, self.values), _num(t.y, self.values))
        return _num(t.coef, self.values) * cmath.exp(1j * _num(t.angle, self.values))

    def vectors(self) -> None:
        """Each term of the loop as an arrow from where the terms before it end (or a
        slide's axis where the slide is 0), named as the equation names it, with its
        angle's arc."""
        first = 0j if self.start is None else self.at[self.start]
        walks = []
        for half in (self.h1, self.h2):
            p, walk = first, []
            for t in half:
                walk.append((t, p, p + self._value(t)))
                p = walk[-1][2]
            walks += walk
        centre = sum(self.z(b) for _, _, b in walks) / len(walks)
        for t, a, b in walks:
            self._vector(t, self.z(a), self.z(b), centre)

    def _vector(self, t: LoopTerm, a: complex, b: complex, centre: complex) -> None:
        nm = self.nm
        if t.angle is None:
            if abs(b - a) < 1e-6:
                return
            self._vector_label("ground vec", a, b, 0.5, nm(t.coef + sp.I * t.y), centre)
            return
        neg = sp.sympify(t.coef).could_extract_minus_sign()
        mag = -t.coef if neg else t.coef
        tail, head = (b, a) if neg else (a, b)
        phi = _num(t.angle, self.values)
        u = cmath.exp(1j * phi)
        pos = 0.55
        if abs(head - tail) < 1e-6:  # a slide at 0: its axis, the direction it counts
            self.lines.append(rf"\draw[ref] {_pt(a - 0.5 * u)} -- {_pt(a + 0.9 * u)};")
            self.placer.segment(a - 0.5 * u, a + 0.9 * u)
            tail, head, pos = a, a + 0.9 * u, 1.0
        self._vector_label("vec", tail, head, pos, nm(mag), centre)
        self._arc(tail, phi, abs(head - tail), nm(t.angle))

    def _vector_label(self, style: str, tail: complex, head: complex, pos: float, label: str,
                      centre: complex) -> None:
        """The arrow from ``tail`` to ``head`` and its name: beside it, on the side away from
        the loop's centre first, near the point ``pos`` along it (its head: at ``pos`` 1)."""
        self.placer.segment(tail, head)
        size = label_size(label)
        u = (head - tail) / abs(head - tail)
        base = tail + pos * (head - tail)
        n = u * 1j if abs(base + u * 1j - centre) > abs(base - u * 1j - centre) else -u * 1j

        def candidates():
            if pos == 1.0:  # a slide at 0: round its axis's end
                return around(base, size, free_directions(base, self.placer.angles_at(base)))
            out = []
            for dist in (0.08, 0.22, 0.4):
                for t in (pos, 0.4, 0.7, 0.25, 0.85):
                    out += around(tail + t * (head - tail), size, [n, -n], (dist,))
            # a short vector among others: round its middle, farther out
            return out + around(base, size, free_directions(base, []), (0.3, 0.55, 0.8, 1.1))

        def line(c):
            shift = c - base
            return (rf"\draw[{style}] {_pt(tail)} -- {_pt(head)} node[pos={pos}, anchor=center, "
                    rf"xshift={_f(shift.real)}cm, yshift={_f(shift.imag)}cm] {{${label}$}};")

        self._label(1, size, candidates, line)

    def _arc(self, tail: complex, phi: float, length: float, name: str) -> None:
        """The arc of angle ``phi`` at ``tail`` from the ``x``-direction, named ``name``;
        arcs at one point drawn at growing radii."""
        key = next((k for k in self.arcs if abs(k - tail) < 1e-6), tail)
        self.arcs[key] = k = self.arcs.get(key, -1) + 1
        deg = math.degrees(math.remainder(phi, 2 * math.pi))
        r = min(0.5, 0.35 * length) + 0.32 * k
        self.placer.segment(tail, tail + r + 0.2)
        steps = [math.radians(deg) * i / 8 for i in range(9)]
        for x, y in zip(steps, steps[1:]):
            self.placer.segment(tail + r * cmath.exp(1j * x), tail + r * cmath.exp(1j * y))
        size = label_size(name)

        def candidates():
            out = []
            for extra in (0.08, 0.25, 0.45):
                for f in (0.5, 0.3, 0.7, 1.15, -0.2, 0.1, 0.9):
                    d = cmath.exp(1j * math.radians(f * deg))
                    out += around(tail + r * d, size, [d], (extra,))
            mid = tail + r * cmath.exp(1j * math.radians(deg / 2))  # a small arc: round it
            return out + around(mid, size, free_directions(mid, []), (0.08, 0.25, 0.45, 0.7))

        def line(c):
            return (rf"\draw[ref] {_pt(tail)} -- {_pt(tail + r + 0.2)}; "
                    rf"\draw[angle] {_pt(tail + r)} arc[start angle=0, end angle={_f(deg)}, "
                    rf"radius={_f(r)}]; \node[anchor=center] at {_pt(c)} {{${name}$}};")

        self._label(2, size, candidates, line)


def loop_figure(eqs, nm, jname: str, label: str, equation_label: str) -> str:
    r"""A ``figure`` with the TikZ picture of the vector loop closed at joint ``jname``.

    Parameters
    ----------
    eqs : MechanismEquations
        The derived equations (:func:`linkage_sym.symbolic.derive`).
    nm : Namer
        The symbols' names, as the printed equations use them.
    jname : str
        The joint that closes the loop (a key of ``eqs.loops``).
    label : str
        The figure's ``\label``.
    equation_label : str
        The ``\label`` of the loop's equation, which the caption cites.

    Returns
    -------
    str
        The ``figure`` environment (needs ``\usepackage{tikz}`` and amsmath's ``\eqref``).

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> from linkage_sym.symbolic import derive
    >>> from linkage_sym.symbolic.latex_notation import Namer
    >>> eqs = derive(load_example("crank_rocker"))
    >>> tex = loop_figure(eqs, Namer(eqs), "D", "fig:loop-D", "eq:loop-D")
    >>> r"{$l_{AB}$}" in tex and r"{$\theta_{\mathrm{crank}}$}" in tex
    True
    """
    fig = _Figure(eqs, nm, jname)
    fig.links()
    fig.joints()
    fig.origin()
    fig.vectors()
    fig.place_labels()
    caption = (
        rf"The vector loop closed at joint {escape_text(jname)}, "
        rf"equation~\eqref{{{equation_label}}}, in the scene's assembly configuration: its "
        r"vectors (blue) named as in the equation, their angles from the $x$-direction "
        r"(red arcs), the links (grey) and the ground pivots (hatched)."
    )
    return "\n".join([
        r"\begin{figure}[htbp]",
        r"\centering",
        rf"\begin{{tikzpicture}}[{_STYLES}]",
        f"% coordinates in cm: figure = {fig.scale!r} * scene (scene units), origin at the "
        "scene's origin",
        *fig.lines,
        r"\end{tikzpicture}",
        rf"\caption{{{caption}}}",
        rf"\label{{{label}}}",
        r"\end{figure}",
    ])
