"""The derived equations as plain text, wrapped to a width: ``linkage-sym derive``'s output.

The positions are the named steps the LaTeX prints (each dyad's outer joints,
the distance ``d``, the projection ``a`` and half-chord ``h`` of its inner
joint, the inner joint, then the angles), not the nested closed forms, and
matrices print row by row: no line is longer than the width asked for.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.symbolic import derive
>>> text = plain_text(derive(load_example("crank_rocker")), width=60)
>>> max(len(line) for line in text.splitlines()) <= 60
True
>>> "d_2 = sqrt(dx_2**2 + dy_2**2)" in text
True
"""

from __future__ import annotations

import textwrap

from sympy.printing.str import StrPrinter

from linkage_sym.symbolic.mechanism import MechanismEquations
from linkage_sym.symbolic.numbers import DIGITS, check_digits, float_text, rounding_note

__all__ = ["MIN_WIDTH", "RoundedStr", "plain_text", "wrap"]

MIN_WIDTH = 40
"""The narrowest width :func:`plain_text` wraps to (a narrower one is taken as this)."""


class RoundedStr(StrPrinter):
    """SymPy's text with every ``Float`` as :func:`float_text` prints it.

    Examples
    --------
    >>> import sympy as sp
    >>> RoundedStr(4).doprint(sp.Float(0.123456) * sp.Symbol("d") + 2)
    '0.1235*d + 2'
    """

    def __init__(self, digits, settings=None):
        super().__init__(settings)
        self.digits = check_digits(digits)

    def _print_Float(self, expr):
        return float_text(expr, self.digits)


def wrap(head: str, body: str, width: int, indent: str = "    ") -> list[str]:
    """``head + body`` as lines of at most ``width`` characters, continued with ``indent``.

    Lines break at spaces (SymPy's text puts them around ``+``, ``-`` and after
    commas); a piece longer than a line is cut where it must be.

    Examples
    --------
    >>> wrap("x = ", "a + b + c", 9)
    ['x = a + b', '    + c']
    """
    return textwrap.wrap(head + body, width=width, subsequent_indent=indent,
                         break_on_hyphens=False, break_long_words=True) or [head.rstrip()]


def _matrix(name: str, M, width: int, p=str) -> list[str]:
    """Matrix ``M`` as ``name = [`` and one wrapped line per row (``[a, b, c],``), then ``]``."""
    if M.rows == 0 or M.cols == 0:
        return [f"{name} = []  ({M.rows} x {M.cols})"]
    out = [f"{name} = [  ({M.rows} x {M.cols})"]
    for i in range(M.rows):
        cells = ", ".join(p(M[i, j]) for j in range(M.cols))
        out += wrap("  ", f"[{cells}],", width, "     ")
    return out + ["]"]


def plain_text(eqs: MechanismEquations, width: int = 100, digits=DIGITS) -> str:
    """The derived equations as SymPy text, section by section, wrapped to ``width``.

    Parameters
    ----------
    eqs : MechanismEquations
        The result of :func:`linkage_sym.symbolic.derive`.
    width : int
        The longest line, in characters (at least :data:`MIN_WIDTH`).
    digits : int or str
        The numbers' significant digits, or ``"full"``: as
        :func:`linkage_sym.symbolic.latex.latex_document`'s (said in a line after the title
        where the equations hold the scene's numbers).

    Returns
    -------
    str
        The text, ending with a newline.
    """
    w = max(int(width), MIN_WIDTH)
    p = RoundedStr(digits).doprint
    out = [f"# mechanism {eqs.scene.name}"]
    if eqs.substituted:
        out += wrap("", rounding_note(digits), w)
    out += ["", "## coordinates"]
    out += wrap("x = ", str(eqs.x), w) + wrap("q = ", str(eqs.q), w)
    out += ["", "## loop equations (complex form = 0)"]
    for j, v in eqs.loops:
        out += wrap(f"{j}: ", f"{p(v.complex())} = 0", w)
    if eqs.meshes:
        out += ["", "## gear meshes (rolling without slip = 0)"]
        for j, e in eqs.meshes:
            out += wrap(f"{j}: ", f"{p(e)} = 0", w)
    out += ["", "## position equations Phi = 0"]
    for e in eqs.Phi:
        out += wrap("", f"{p(e)} = 0", w)
    out += ["", "## positions, in solving order (each may use those above it)"]
    for s, e in eqs.position_steps:
        out += wrap(f"{s} = ", p(e), w)
    for g in eqs.groups:
        if not g.closed:
            out += wrap("", f"group {g.index + 1} ({g.group.kind}): solved numerically for {g.x}", w)
    out += ["", "## velocity: A xd = B qd"] + wrap("xd = ", str(eqs.xd), w)
    out += _matrix("A", eqs.A, w, p) + _matrix("B", eqs.B, w, p)
    out += ["", "## acceleration: A xdd = acc_rhs"] + wrap("xdd = ", str(eqs.xdd), w)
    out += _matrix("acc_rhs", eqs.acc_rhs, w, p)
    if eqs.has_forces:
        out += _forces(eqs, w, p)
    if eqs.parameters or eqs.intermediates:
        out += ["", "## parameters"]
        for s in eqs.parameters:
            out += wrap(f"{s}: ", eqs.table.params[s.name].meaning, w)
        for s, meaning in eqs.intermediates:
            out += wrap(f"{s}: ", f"{meaning} (intermediate)", w)
    return "\n".join(out) + "\n"


def _forces(eqs, w: int, p) -> list[str]:
    """The centres of mass's accelerations, each group's force equations, friction, frame."""
    out = ["", "## forces: A_g F_g = b_g - C_g F_later"]
    for s, e, _ in eqs.force_intermediates:
        out += wrap(f"{s} = ", p(e), w)
    for g, (A, b, C, later) in zip(eqs.groups, eqs.readable_force_blocks):
        out += wrap(f"group {g.index + 1}: F_g = ", str(g.forces), w)
        out += _matrix(f"A_{g.index + 1}", A, w, p) + _matrix(f"b_{g.index + 1}", b, w, p)
        if later:
            out += _matrix(f"C_{g.index + 1}", C, w, p) + wrap("F_later = ", str(later), w)
    if eqs.friction_laws:  # contract part two: the laws that close the force equations
        out += [""] + wrap("## joint friction ", "(rho_J = f r: the friction circle's radius; "
                           "mu_J: the coefficient; nu_J: the sign of the joint's relative motion)",
                           w)
        for law in eqs.friction_laws:
            out += wrap(f"{law.friction} = ", p(law.law), w)
    if getattr(eqs, "spring_efforts", None):  # contract part two: known loads of the rates
        out += [""] + wrap("## springs and dampers ", "(T_k: a spring's tension; tau_k: a joint "
                           "spring's torque on its joint's links[1])", w)
        for sym, e, _ in eqs.spring_steps:  # a spring's length named, as a dyad's d is
            out += wrap(f"{sym} = ", p(e), w)
    out += ["", "## frame force x, y and moment about the origin"]
    for name, e in zip(("F_frame_x", "F_frame_y", "M_frame"), eqs.readable_frame):
        out += wrap(f"{name} = ", p(e), w)
    return out
