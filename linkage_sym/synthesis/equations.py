"""The design equations of the synthesis by ``K``, derived with SymPy and printable as LaTeX.

The numeric synthesis (:mod:`linkage_sym.synthesis.kratio`, NumPy only, never
importing this module: import contract in ``pyproject.toml``) uses these
relations; here each one is *derived* from what the textbook section *Design
of four-bar mechanisms* (Sources [2] of the README) states in words or draws
-- the crank's two strokes, the extreme positions with crank and coupler in
line, the auxiliary circle's inscribed angle -- with the law of cosines and
the law of sines, and each derivation is checked by SymPy (a difference that
simplifies to 0), so a printed formula is a proved one.  The OCR text's eq.
2-2 is only a claim to check: :func:`design_equations` derives it from the
strokes' angles.

:func:`latex_document` writes a fragment for a textbook (``\\input`` it in a
document that loads ``amsmath``), :func:`plain_text` the same as SymPy text.

Examples
--------
>>> eqs = design_equations()
>>> eqs[0].label, sp.sstr(eqs[0].rhs)
('theta_K', 'pi*(K - 1)/(K + 1)')
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

K, theta, psi, alpha, phi = sp.symbols("K theta psi alpha phi", positive=True)
a, b, c, d, e, H, R = sp.symbols("a b c d e H R", positive=True)
l1, l2, chord, gamma = sp.symbols("l_1 l_2 l_12 gamma", positive=True)

SYMBOLS = {
    K: "stroke-time ratio: the slower stroke's time over the faster's",
    theta: "extreme-position angle: the angle C1 A C2 at the crank pivot",
    psi: "swing angle of the rocker (or guide) between its extreme positions",
    a: "crank length AB", b: "coupler (connecting rod) length BC", c: "rocker length CD",
    d: "frame length AD", e: "offset of the slider's line from A", H: "stroke of the slider",
    l1: "AC1 = b + a (crank and coupler extended)", l2: "AC2 = b - a (overlapping)",
    chord: "the chord C1C2", R: "radius of the auxiliary circle",
    alpha: "the angle A C1 C2 (where A sits on the auxiliary circle)",
    phi: "crank angle from the frame line AD", gamma: "transmission angle at C",
}
"""Every symbol and what it stands for."""


@dataclass(frozen=True)
class DesignEquation:
    """One derived relation ``lhs = rhs``.

    ``label`` names it (also the LaTeX label), ``text`` says what it is and
    how it was derived, ``check`` is the expression SymPy reduced to 0 to
    prove it (``None`` where the equation is a definition).
    """

    label: str
    text: str
    lhs: sp.Expr
    rhs: sp.Expr
    check: sp.Expr | None = None


def _zero(expr) -> bool:
    """Whether ``expr`` simplifies to 0 (trigonometric identities expanded, or in exponentials)."""
    if sp.simplify(sp.expand_trig(sp.expand(expr))) == 0:
        return True
    return sp.simplify(sp.expand(expr.rewrite(sp.exp))) == 0


def design_equations() -> list[DesignEquation]:
    """Derive the design relations of the synthesis by ``K``; each is proved on the way.

    Returns
    -------
    list of DesignEquation
        In the order of the design procedure: ``theta`` from ``K``; crank
        and coupler from ``AC1``, ``AC2``; the chord and the auxiliary
        circle; ``AC1``, ``AC2``, crank and coupler on the circle; the
        transmission angle and its extremes; the slider-crank's stroke,
        offset, largest offset and minimum transmission angle; the
        guide-bar's crank and swing.

    Raises
    ------
    AssertionError
        If a derivation does not reduce to 0 (a SymPy regression).
    """
    out = []

    l1_expr = _crank_rocker_relations(out)
    _transmission_relations(out)
    _slider_and_guide_relations(out, l1_expr)
    for eq in out:
        if eq.check is not None:
            assert _zero(eq.check), f"derivation of {eq.label} does not reduce to 0: {eq.check}"
    return out


def _crank_rocker_relations(out: list):
    """Append steps 1 to 5 of :func:`design_equations` (``theta`` from ``K``, crank and coupler
    from the extreme positions, the chord, the auxiliary circle, the pivot on it); returns
    ``AC1`` on the circle, which the slider-crank's offset uses."""
    # 1. K from the strokes: the crank turns pi + theta, then pi - theta, at constant speed
    t_sol = sp.solve(sp.Eq(K, (sp.pi + theta) / (sp.pi - theta)), theta)
    assert len(t_sol) == 1
    t_K = sp.factor(t_sol[0])
    out.append(DesignEquation(
        "theta_K", "extreme-position angle from K (eq. 2-2): the crank turns through pi + theta in "
        "the slow stroke and pi - theta in the fast one, at constant speed, and K is the ratio of "
        "the two times", theta, t_K,
        (sp.pi + t_K) / (sp.pi - t_K) - K))

    # 2. crank and coupler from the extreme positions
    sol = sp.solve([sp.Eq(l1, b + a), sp.Eq(l2, b - a)], [a, b], dict=True)[0]
    out.append(DesignEquation("crank", "crank from the extreme positions: AC1 = b + a, AC2 = b - a",
                              a, sol[a], sol[a] - (l1 - l2) / 2))
    out.append(DesignEquation("coupler", "coupler from the extreme positions", b, sol[b],
                              sol[b] - (l1 + l2) / 2))

    # 3. the chord C1C2: isosceles triangle C1 D C2 with legs c and apex angle psi
    chord_sq = 2 * c**2 - 2 * c**2 * sp.cos(psi)  # law of cosines
    chord_expr = 2 * c * sp.sin(psi / 2)
    out.append(DesignEquation("chord", "the chord C1C2 of the rocker's extreme positions (law of "
                              "cosines in C1 D C2)", chord, chord_expr, chord_expr**2 - chord_sq))

    # 4. auxiliary circle: the chord subtends 2 theta at its centre O, theta at A on the arc
    R_expr = sp.solve(sp.Eq(chord, 2 * R * sp.sin(theta)), R)[0]
    out.append(DesignEquation("radius", "radius of the auxiliary circle: the central angle C1 O C2 "
                              "is 2 theta (the inscribed angle at A is theta)", R, R_expr,
                              2 * R_expr * sp.sin(theta) - chord))

    # 5. A on the circle: the law of sines in triangle A C1 C2 (angles theta at A, alpha at C1)
    l1_expr = 2 * R * sp.sin(theta + alpha)
    l2_expr = 2 * R * sp.sin(alpha)
    law = l1_expr / sp.sin(sp.pi - theta - alpha) - 2 * R  # a/sin(A) = 2R for every side
    out.append(DesignEquation("AC1", "AC1 by the law of sines in A C1 C2 (angle pi - theta - alpha "
                              "at C2)", l1, l1_expr, law))
    out.append(DesignEquation("AC2", "AC2 by the law of sines (angle alpha at C1)", l2, l2_expr,
                              l2_expr / sp.sin(alpha) - 2 * R))
    a_circle = 2 * R * sp.sin(theta / 2) * sp.cos(alpha + theta / 2)
    b_circle = 2 * R * sp.cos(theta / 2) * sp.sin(alpha + theta / 2)
    out.append(DesignEquation("crank_circle", "crank of the pivot at alpha: (AC1 - AC2)/2",
                              a, a_circle, sol[a].subs({l1: l1_expr, l2: l2_expr}) - a_circle))
    out.append(DesignEquation("coupler_circle", "coupler of the pivot at alpha: (AC1 + AC2)/2",
                              b, b_circle, sol[b].subs({l1: l1_expr, l2: l2_expr}) - b_circle))
    # the frame length: A = C1 + AC1 (cos alpha, sin alpha), C1 = (-l_12/2, 0), D = (0, -c cos(psi/2))
    Ax = -c * sp.sin(psi / 2) + l1_expr * sp.cos(alpha)
    Ay = l1_expr * sp.sin(alpha)
    d_coords = Ax**2 + (Ay + c * sp.cos(psi / 2))**2
    d_sq = l1**2 + c**2 + 2 * l1 * c * sp.sin(alpha - psi / 2)  # law of cosines in A C1 D
    out.append(DesignEquation("frame", "frame length AD of the pivot at alpha on the arc away from "
                              "D: the law of cosines in A C1 D (angle alpha + pi/2 - psi/2 at C1), "
                              "checked against the coordinates (chord on the x-axis, D below it)",
                              d**2, d_sq, d_sq.subs(l1, l1_expr) - d_coords))
    return l1_expr


def _transmission_relations(out: list) -> None:
    """Append step 6 of :func:`design_equations`: the transmission angle and its extremes."""
    # 6. transmission angle: |BD|^2 by the law of cosines in A B D and in B C D
    BD_sq = a**2 + d**2 - 2 * a * d * sp.cos(phi)
    cos_g = sp.solve(sp.Eq(BD_sq, b**2 + c**2 - 2 * b * c * sp.Symbol("x")), sp.Symbol("x"))[0]
    out.append(DesignEquation("transmission", "transmission angle at C (law of cosines in A B D "
                              "and B C D)", sp.cos(gamma), cos_g,
                              (b**2 + c**2 - BD_sq) / (2 * b * c) - cos_g))
    for label, at, words in (("transmission_0", 0, "crank over the frame (phi = 0)"),
                             ("transmission_pi", sp.pi, "crank in line with the frame (phi = pi)")):
        out.append(DesignEquation(label, f"its extremes: {words}", sp.cos(gamma),
                                  sp.factor(cos_g.subs(phi, at)), None))


def _slider_and_guide_relations(out: list, l1_expr) -> None:
    """Append steps 7 and 8 of :func:`design_equations`: the slider-crank's stroke, offset,
    largest offset and minimum transmission angle; the guide-bar's swing and crank."""
    # 7. slider-crank: the chord is the stroke; A at the offset e from the slider's line
    H_lengths = sp.sqrt((b + a)**2 - e**2) - sp.sqrt((b - a)**2 - e**2)
    out.append(DesignEquation("stroke", "stroke of an offset slider-crank from its lengths: the "
                              "extremes are at b + a and b - a from A", H, H_lengths, None))
    H_circle = 2 * R * sp.sin(theta)
    out.append(DesignEquation("stroke_circle", "the stroke is the chord of the auxiliary circle", H,
                              H_circle, None))
    e_alpha = l1_expr * sp.sin(alpha)
    out.append(DesignEquation("offset", "offset of the pivot at alpha (the height of A over the "
                              "stroke)", e, e_alpha, None))
    e_max = e_alpha.subs(alpha, sp.pi / 2 - theta)
    e_max_H = H / sp.tan(theta)
    out.append(DesignEquation("offset_max", "largest offset: the foot of A at an end of the stroke "
                              "(alpha = pi/2 - theta)", e, e_max_H,
                              e_max - e_max_H.subs(H, H_circle)))
    out.append(DesignEquation("slider_transmission", "minimum transmission angle of the slider-crank: "
                              "crank perpendicular to the slider's line, away from it",
                              sp.cos(gamma), (a + e) / b, None))

    # 8. guide-bar: at the extremes the guide is tangent to the crank circle (right angle at B)
    out.append(DesignEquation("guide_swing", "guide-bar: at the extremes the crank is perpendicular "
                              "to the guide, so it turns through pi + psi and pi - psi: theta equals "
                              "the guide's swing", psi, theta, None))
    a_guide = d * sp.sin(theta / 2)
    a_right = sp.solve(sp.Eq(sp.sin(psi / 2), a / d), a)[0].subs(psi, theta)  # angle ADB = psi/2
    out.append(DesignEquation("guide_crank", "guide-bar crank: the right triangle A B D at an "
                              "extreme (angle psi/2 at D)", a, a_guide, a_right - a_guide))


_SOURCE = ("textbook section \\emph{Design of four-bar mechanisms} (Chinese: Siganjigou de "
           "sheji), Figs.~2-65 and 2-66; title, author, publisher and year of the book not shown "
           "in the text available to linkage\\_sym")


def latex_document(equations: list[DesignEquation] | None = None) -> str:
    """The design equations as a LaTeX fragment (needs ``amsmath``).

    Examples
    --------
    >>> text = latex_document()
    >>> r"\\theta = \\frac{\\pi \\left(K - 1\\right)}{K + 1}" in text
    True
    """
    eqs = design_equations() if equations is None else equations
    names = {l1: "l_{AC_1}", l2: "l_{AC_2}", chord: "l_{C_1C_2}"}
    lines = [
        "% Design equations of the synthesis by the stroke-time ratio K, generated by linkage_sym.",
        "% Needs amsmath.  Cites the key below; add this entry to your bibliography:",
        f"%   \\bibitem{{linkagesym-fourbar-design}} {_SOURCE}.",
        "\\subsection*{Design by the stroke-time ratio $K$ "
        "\\cite{linkagesym-fourbar-design}}",
        "\\paragraph{Symbols.}",
        "\\begin{itemize}",
    ]
    for sym, words in SYMBOLS.items():
        lines.append(f"\\item ${sp.latex(sym, symbol_names=names)}$: {_escape(words)}")
    lines.append("\\end{itemize}")
    for eq in eqs:
        lines.append(f"\\paragraph{{{_escape(eq.text[0].upper() + eq.text[1:])}.}}")
        lines.append("\\begin{equation}")
        lines.append(f"  {sp.latex(eq.lhs, symbol_names=names)} = "
                     f"{sp.latex(eq.rhs, symbol_names=names)}")
        lines.append(f"  \\label{{eq:design-{eq.label.replace('_', '-')}}}")
        lines.append("\\end{equation}")
    return "\n".join(lines) + "\n"


def _escape(s: str) -> str:
    return s.replace("_", "\\_").replace("&", "\\&").replace("%", "\\%")


def plain_text(equations: list[DesignEquation] | None = None) -> str:
    """The design equations as SymPy text, one per line with its description.

    Examples
    --------
    >>> print(plain_text().splitlines()[2])
    a = l_1/2 - l_2/2    # crank from the extreme positions: AC1 = b + a, AC2 = b - a
    """
    eqs = design_equations() if equations is None else equations
    out = ["# design equations of the synthesis by the stroke-time ratio K"]
    for eq in eqs:
        out.append(f"{sp.sstr(eq.lhs)} = {sp.sstr(eq.rhs)}    # {eq.text}")
    return "\n".join(out) + "\n"


__all__ = ["DesignEquation", "SYMBOLS", "design_equations", "latex_document", "plain_text"]
