"""The LaTeX notation of the derived equations: names, line breaking, matrices.

One typesetting convention shared by every section of
:func:`linkage_sym.symbolic.latex.latex_document`: how a symbol prints
(:class:`Namer`, after the textbook's notation: link angles ``\\theta``, rates
``\\omega``, accelerations ``\\alpha``, lengths ``l``), how a long sum breaks
over rows (:meth:`Namer.sum_rows`), when a matrix prints whole
(:func:`pmatrix`) or entry by entry (:meth:`Doc.entries`), and the document
being written with its equations' labels (:class:`Doc`).

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.symbolic import derive
>>> eqs = derive(load_example("crank_rocker"))
>>> print(Namer(eqs)(eqs.x[0] + eqs.xd[0]))
\\omega_{\\mathrm{crank}} + \\theta_{\\mathrm{crank}}
>>> print(escape_text("a_b & c"))
a\\_b \\& c
>>> print(escape_text("angle of B->D, x > 0"))
angle of B\\ensuremath{\\to}D, x \\ensuremath{>} 0
"""

from __future__ import annotations

import re

import sympy as sp
from sympy.printing.latex import LatexPrinter

from linkage_sym.symbolic.mechanism import MechanismEquations
from linkage_sym.symbolic.numbers import DIGITS, check_digits, float_text
from linkage_sym.structure.parameters import ident

__all__ = [
    "LINE", "ROW_SOURCE", "TYPESET", "MAX_ENTRY", "MAX_EQUATION", "MAX_MATRIX", "MAX_MATRIX_CHARS",
    "Doc", "Namer", "column", "escape_text", "pmatrix", "rows_of", "typeset_width",
]

# prefixes of parameter names, and how they print
_GREEK = {
    "theta0": r"\theta^{0}",
    "theta": r"\theta",
    "omega": r"\omega",
    "alpha": r"\alpha",
    "beta": r"\beta",
    "gamma": r"\gamma",
    "delta": r"\delta",
    "sigma": r"\sigma",
    "kappa": r"\kappa",
    "phi": r"\varphi",
    "epsilon": r"\epsilon",
    "tau": r"\tau",
    "xi": r"\xi",
    "eta": r"\eta",
    "sdot": r"\dot{s}",
    "sddot": r"\ddot{s}",
    "qdot": r"\dot{q}",
    "qddot": r"\ddot{q}",
    "dx": r"\Delta x",
    "dy": r"\Delta y",
    "cphi": r"\cos\varphi",
    "sphi": r"\sin\varphi",
    # a link's centre of mass in its frame: the parameters xG_<link>, yG_<link> print as
    # x^G, y^G, so that q means only a driver coordinate (q_A) in the equations
    "xG": r"x^{G}",
    "yG": r"y^{G}",
    "xQ": r"x^{Q}",
    "yQ": r"y^{Q}",
}
_LINK_PREFIXES = {"theta0", "theta", "omega", "alpha", "m", "I", "xG", "yG"}
"""Parameter prefixes followed by a link name (always upright)."""

MAX_MATRIX = 8
"""Matrices with more rows or columns than this are written entry by entry."""
MAX_ENTRY = 70
MAX_MATRIX_CHARS = 900
LINE = 150
"""The longest row of a matrix block written whole (LaTeX characters, less 30)."""
TYPESET = 80
"""A sum wider than this when typeset (:func:`typeset_width`, in characters) is broken over
several rows, as is one longer than :data:`ROW_SOURCE` LaTeX characters."""
ROW_SOURCE = 200
MAX_EQUATION = 250
"""A matrix equation longer than this is written with named matrices and their entries."""

_TEXT_ESCAPES = {
    "\\": r"\textbackslash{}",
    "&": r"\&",
    "%": r"\%",
    "$": r"\$",
    "#": r"\#",
    "_": r"\_",
    "{": r"\{",
    "}": r"\}",
    "~": r"\textasciitilde{}",
    "^": r"\textasciicircum{}",
    # in the default (OT1) text font these two characters print as inverted marks
    "<": r"\ensuremath{<}",
    ">": r"\ensuremath{>}",
}


def escape_text(s: str) -> str:
    """``s`` safe in LaTeX text mode (and inside ``\\mathrm``)."""
    parts = s.split("->")  # an arrow as an arrow, in text and in math alike
    return r"\ensuremath{\to}".join("".join(_TEXT_ESCAPES.get(c, c) for c in p) for p in parts)


def typeset_width(tex: str) -> float:
    """An estimate of the typeset width of math ``tex``, in characters of the body font:
    a command (``\\alpha``, ``\\sin``) as its printed letters, sub- and superscripts at
    0.7, ``\\left``, ``\\right``, ``\\mathrm`` and braces as nothing, an operator with
    its spaces as 2.

    Examples
    --------
    >>> typeset_width(r"x_{D} - x_{B}")
    5.4
    """
    t = re.sub(r"\\(left|right|mathrm|operatorname|quad)\b", "", tex)
    t = re.sub(r"\\(sin|cos|tan|sqrt|atan2)\b", lambda m: m.group(1)[:3], t)
    t = re.sub(r"\\[A-Za-z]+", "a", t)
    width, depth = 0.0, 0
    script = []  # brace depths at which a sub- or superscript started
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
        w = 2.0 if c in "+-=" else 1.0
        width += 0.7 * w if (script or pending) else w
        pending = False
    return round(width, 6)


def _sub(name: str, upright: bool = False) -> str:
    """A subscript: short alphanumeric names as they are, others upright."""
    if not upright and re.fullmatch(r"[A-Za-z0-9]{1,3}", name):
        return name
    return r"\mathrm{" + escape_text(name) + "}"


def _label(s: str) -> str:
    return re.sub(r"[^A-Za-z0-9:.-]", "-", s)


class _WrittenOrder(LatexPrinter):
    """SymPy's LaTeX with every sum, also inside a product, a fraction or a function, written
    positive terms first, as a person writes it (``x_D - x_B``, not ``-x_B + x_D``); the
    terms keep SymPy's order otherwise.

    Examples
    --------
    >>> xb, xd, y = sp.symbols("x_B x_D y")
    >>> print(_WrittenOrder().doprint(sp.atan2(y, xd - xb) * (xd - xb - y)))
    \\left(x_{D} - x_{B} - y\\right) \\operatorname{atan}_{2}{\\left(y,x_{D} - x_{B} \\right)}
    """

    def __init__(self, settings=None, digits=None):
        super().__init__(settings)
        self.digits = digits

    def _print_Float(self, expr):
        """A number to :attr:`digits` significant digits (SymPy's own: None), ``a \\cdot
        10^{e}`` beyond the fixed-point range (:func:`~linkage_sym.symbolic.numbers.float_text`)."""
        if self.digits is None:
            return super()._print_Float(expr)
        text = float_text(expr, self.digits)
        mant, _, exp = text.partition("e")
        return rf"{mant} \cdot 10^{{{exp}}}" if exp else text

    def _as_ordered_terms(self, expr, order=None):
        terms = super()._as_ordered_terms(expr, order=order)
        if not isinstance(expr, sp.Add):
            return terms
        return sorted(terms, key=lambda t: t.could_extract_minus_sign())  # stable


class Namer:
    """``symbol_names`` for :func:`sympy.latex`, from the equations' structure, and the
    numbers' significant digits.

    Parameters
    ----------
    eqs : MechanismEquations
        The derived equations.
    digits : int or str
        Each number (the scene's, where ``derive(..., symbolic=False)`` put them in place of
        the parameters) correctly rounded to this many significant digits, or ``"full"``
        (:func:`linkage_sym.symbolic.numbers.float_text`).
    """

    def __init__(self, eqs: MechanismEquations, digits=DIGITS):
        self.digits = check_digits(digits)
        names: dict = {}
        links = {f"theta_{s.name[6:]}" for s in eqs.x if s.name.startswith("theta_")}
        for s, sd, sdd in zip(eqs.x, eqs.xd, eqs.xdd):
            if s.name in links:
                n = _sub(s.name[6:], upright=True)
                names[s] = rf"\theta_{{{n}}}"
                names[sd] = rf"\omega_{{{n}}}"
                names[sdd] = rf"\alpha_{{{n}}}"
            else:
                n = _sub(s.name[2:])
                names[s] = f"s_{{{n}}}"
                names[sd] = rf"\dot{{s}}_{{{n}}}"
                names[sdd] = rf"\ddot{{s}}_{{{n}}}"
        for q, qd, qdd in zip(eqs.q, eqs.qd, eqs.qdd):
            n = _sub(q.name[2:])
            names[q] = f"q_{{{n}}}"
            names[qd] = rf"\dot{{q}}_{{{n}}}"
            names[qdd] = rf"\ddot{{q}}_{{{n}}}"
        for s in eqs.sigmas:
            names[s] = rf"\sigma_{{{_sub(s.name[6:])}}}"
        for s in eqs.flanks:
            names[s] = rf"\kappa_{{{_sub(s.name[6:])}}}"
        if eqs.has_forces:
            for jname, fs in eqs.F.items():
                if len(fs) == 1:  # a gear mesh's tooth load
                    names[fs[0]] = rf"F_{{{_sub(fs[0].name[3:])},n}}"
                    continue
                f1, f2 = fs
                n = _sub(f1.name[2:-1] if f1.name.startswith("R_") else f1.name[2:])
                if f1.name.startswith("R_"):
                    names[f1], names[f2] = f"R_{{{n},x}}", f"R_{{{n},y}}"
                else:
                    names[f1], names[f2] = f"N_{{{n}}}", f"M_{{{n}}}"
            for e in eqs.E.values():
                pre, n = e.name.split("_", 1)
                names[e] = (r"\tau" if pre == "tau" else "f") + f"_{{{_sub(n)}}}"
        for law in getattr(eqs, "friction_laws", ()):  # joint friction (contract part two)
            n = _sub(law.friction.name[3:])
            names[law.friction] = rf"M^{{f}}_{{{n}}}" if law.kind == "R" else rf"F^{{f}}_{{{n}}}"
            names[law.sign] = rf"\nu_{{{n}}}"
            if isinstance(law.arm, sp.Symbol):
                names[law.arm] = (r"\rho" if law.kind == "R" else r"\mu") + f"_{{{n}}}"
        for s in eqs.parameters:
            names.setdefault(s, self.param(s.name))
        springs = {sym: name for name, sym, _, _, _ in getattr(eqs, "spring_efforts", ())}
        for s, _, _ in getattr(eqs, "force_intermediates", ()):
            if s in springs:  # a spring's tension T or torque tau (contract part two)
                head = r"\tau" if s.name.startswith("tau_") else "T"
                names[s] = rf"{head}_{{{_sub(ident(springs[s]), upright=True)}}}"
            elif s.name.startswith(("aGx_", "aGy_")):
                comp, link = s.name[2], s.name[4:]
                names[s] = rf"a^{{G}}_{{{_sub(link, upright=True)},{comp}}}"
            else:  # a spring's named length L_k and its components dx_k, dy_k
                pre, _, spring = s.name.partition("_")
                names[s] = rf"{_GREEK.get(pre, pre)}_{{{_sub(spring, upright=True)}}}"
        for s, _ in eqs.intermediates:
            base = s.name.rstrip("'")
            names[s] = self.param(base) + "'" * (len(s.name) - len(base))
        self.names = names
        # each coordinate, rate and acceleration ranks as its link (or slide) in solving order
        self.rank = {s: i for i, trio in enumerate(zip(eqs.x, eqs.xd, eqs.xdd)) for s in trio}

    @staticmethod
    def param(name: str) -> str:
        pre, _, rest = name.partition("_")
        if not rest:
            return name if len(name) == 1 else r"\mathrm{" + escape_text(name) + "}"
        head = _GREEK.get(pre, pre if len(pre) == 1 else r"\mathrm{" + escape_text(pre) + "}")
        if pre == "F" and re.fullmatch(r"\d+[xy]", rest):
            return f"F_{{{rest[:-1]},{rest[-1]}}}"
        return f"{head}_{{{_sub(rest, upright=pre in _LINK_PREFIXES)}}}"

    def __call__(self, expr) -> str:
        for s in getattr(expr, "free_symbols", ()):
            if s not in self.names:  # pragma: no cover - every symbol is named above
                self.names[s] = self.param(s.name)
        return _WrittenOrder({"symbol_names": self.names}, self.digits).doprint(expr).replace(
            r"\operatorname{atan}_{2}", r"\operatorname{atan2}")

    def terms(self, expr) -> list:
        """A sum's terms in the order a person writes them: by the link whose coordinate,
        rate or acceleration they hold, in solving order (terms of the dimensions alone
        last), and within each the positive terms before the negative ones (``x_D - x_B``,
        not SymPy's ``-x_B + x_D``)."""
        if not isinstance(expr, sp.Add):
            return [expr]

        def key(t):
            ranks = [self.rank[s] for s in t.free_symbols if s in self.rank]
            return (min(ranks) if ranks else len(self.rank), t.could_extract_minus_sign())

        return sorted(expr.as_ordered_terms(), key=key)

    def _join(self, terms, first: bool = True) -> list[str]:
        """Each term as ``+ t`` or ``- t`` (the very first without its ``+``)."""
        out = []
        for i, t in enumerate(terms):
            neg = t.could_extract_minus_sign()
            body = self(-t if neg else t)
            if isinstance(-t if neg else t, sp.Add):
                body = rf"\left({body}\right)"
            out.append(("- " if neg else ("" if first and i == 0 else "+ ")) + body)
        return out

    def sum_rows(self, lhs: str, expr, width: float = TYPESET) -> list[str]:
        """``lhs &= expr`` as align rows, a long sum broken between its terms (in the
        order of :meth:`terms`): no row wider than ``width`` typeset characters
        (:func:`typeset_width`) or longer than :data:`ROW_SOURCE` LaTeX characters, but
        where a single term is."""
        expr = sp.sympify(expr)

        def fits(tex):
            return typeset_width(tex) <= width and len(tex) <= ROW_SOURCE

        whole = " ".join(self._join(self.terms(expr)))
        if fits(whole):
            return [f"{lhs} &= {whole}"]
        # a term too long for a row is expanded into terms of its own, where that helps
        terms = []
        for t in self.terms(expr):
            te = sp.expand(t) if not fits(self(t)) else t
            terms += self.terms(te) if isinstance(te, sp.Add) else [t]
        if len(terms) == 1:
            return [f"{lhs} &= {whole}"]
        rows, cur = [], ""
        for piece in self._join(terms):
            if cur and not fits(cur + " " + piece):
                rows.append(cur)
                cur = ""
            cur = (cur + " " + piece).strip()
        rows.append(cur)
        out = [f"{lhs} &= {rows[0]}"]
        out += [rf"&\quad {r}" for r in rows[1:]]
        return out


def pmatrix(namer: Namer, M: sp.Matrix, force: bool = False) -> str | None:
    """``M`` as a ``pmatrix``, or None when it is too big to read that way."""
    if M.rows == 0 or M.cols == 0:
        return None
    cells = [[namer(M[i, j]) for j in range(M.cols)] for i in range(M.rows)]
    if not force:
        if max(M.rows, M.cols) > MAX_MATRIX:
            return None
        if max(len(c) for r in cells for c in r) > MAX_ENTRY:
            return None
        if sum(len(c) for r in cells for c in r) > MAX_MATRIX_CHARS:
            return None
    body = r" \\ ".join(" & ".join(r) for r in cells)
    out = r"\begin{pmatrix} " + body + r" \end{pmatrix}"
    return None if not force and len(out) > MAX_EQUATION else out


def rows_of(namer: Namer, lhs: str, syms, per_row: int = 8) -> list[str]:
    """``lhs &= (a, b, c, ...)^T`` as align rows of at most ``per_row`` entries."""
    names = [namer(s) for s in syms]
    chunks = [names[i:i + per_row] for i in range(0, len(names), per_row)]
    rows = []
    for k, chunk in enumerate(chunks):
        text = ", ".join(chunk) + ("," if k < len(chunks) - 1 else r")^{\mathsf{T}}")
        rows.append(f"{lhs} &= ({text}" if k == 0 else rf"&\qquad {text}")
    return rows


def column(namer: Namer, syms) -> str:
    """The symbols ``syms`` as a column vector (``pmatrix``)."""
    return r"\begin{pmatrix} " + r" \\ ".join(namer(s) for s in syms) + r" \end{pmatrix}"


class Doc:
    """A LaTeX fragment being written: its lines (``out``) and its equations' labels.

    Parameters
    ----------
    prefix : str
        The start of every ``\\label`` (``eq:<scene name>``).
    """

    def __init__(self, prefix: str):
        self.out: list[str] = []
        self.prefix = prefix
        self.labels: list[str] = []

    def label(self, key: str) -> str:
        lab = _label(f"{self.prefix}:{key}")
        self.labels.append(lab)
        return rf"\label{{{lab}}}"

    def text(self, s: str = ""):
        self.out.append(s)

    def equation(self, body: str, key: str):
        self.out += [r"\begin{equation}", body + " " + self.label(key), r"\end{equation}"]

    def align(self, rows: list[str], keys: list | None = None, numbered: bool = True):
        """Rows of an ``align`` (``keys[i]``: label of row i, None: unnumbered)."""
        env = "align" if numbered else "align*"
        self.out.append(rf"\begin{{{env}}}")
        for i, r in enumerate(rows):
            tail = r" \\" if i < len(rows) - 1 else ""
            if numbered:
                k = keys[i] if keys else None
                r = r + (" " + self.label(k) if k is not None else r" \nonumber")
            self.out.append(r + tail)
        self.out.append(rf"\end{{{env}}}")

    def entries(self, namer: Namer, name: str, M: sp.Matrix, what: str, entry: str):
        """The nonzero entries of a matrix too big to print whole (``entry``: the
        entries' letter, with any superscript; the row/column index is appended)."""
        rows = []
        for i in range(M.rows):
            for j in range(M.cols):
                if M[i, j] != 0:
                    idx = f"{i + 1}" if M.cols == 1 else f"{i + 1},{j + 1}"
                    rows += namer.sum_rows(f"{entry}_{{{idx}}}", M[i, j])
        shape = f"{M.rows}" if M.cols == 1 else rf"{M.rows} \times {M.cols}"
        self.text(
            f"The nonzero entries ${entry}_{{{'i' if M.cols == 1 else 'ij'}}}$ of {what} ${name}$ (${shape}$; "
            "every entry not listed is zero):"
        )
        if rows:
            self.align(rows, numbered=False)
