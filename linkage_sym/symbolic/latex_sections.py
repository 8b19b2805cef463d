"""LaTeX rendering of a mechanism's derived equations, in the notation of the
textbook chapter "Kinematic analysis of planar mechanisms".

:func:`latex_document` writes a document *fragment* (no preamble; ``\\input``
it in a document that loads ``amsmath``) with the symbols, loop equations
(eq. 3-8 and its projections 3-9), closed-form positions, the velocity and
acceleration equations (3-28, 3-29) and, when derived, each group's force
equations and the frame loads.  Link angles are ``\\theta``, rates
``\\omega``, accelerations ``\\alpha`` and lengths ``l``.

Size: about 600 lines: one typesetting convention (names, named
intermediates, line breaking) shared by every section of the document.
"""

from __future__ import annotations

import re

import sympy as sp

from linkage_sym.symbolic.mechanism import MechanismEquations

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
    "xQ": r"x^{Q}",
    "yQ": r"y^{Q}",
}
_LINK_PREFIXES = {"theta0", "theta", "omega", "alpha", "m", "I", "p", "q"}
"""Parameter prefixes followed by a link name (always upright)."""

MAX_MATRIX = 8
"""Matrices with more rows or columns than this are written entry by entry."""
MAX_ENTRY = 70
MAX_MATRIX_CHARS = 900
LINE = 150
"""Sums longer than this (LaTeX characters) are broken over several rows."""
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
}


def escape_text(s: str) -> str:
    """``s`` safe in LaTeX text mode (and inside ``\\mathrm``)."""
    return "".join(_TEXT_ESCAPES.get(c, c) for c in s)


def _sub(name: str, upright: bool = False) -> str:
    """A subscript: short alphanumeric names as they are, others upright."""
    if not upright and re.fullmatch(r"[A-Za-z0-9]{1,3}", name):
        return name
    return r"\mathrm{" + escape_text(name) + "}"


def _label(s: str) -> str:
    return re.sub(r"[^A-Za-z0-9:.-]", "-", s)


class _Namer:
    """``symbol_names`` for :func:`sympy.latex`, from the equations' structure."""

    def __init__(self, eqs: MechanismEquations):
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
        for s in eqs.parameters:
            names.setdefault(s, self.param(s.name))
        for s, _, _ in getattr(eqs, "force_intermediates", ()):
            comp, link = s.name[2], s.name[4:]
            names[s] = rf"a^{{G}}_{{{_sub(link, upright=True)},{comp}}}"
        for s, _ in eqs.intermediates:
            base = s.name.rstrip("'")
            names[s] = self.param(base) + "'" * (len(s.name) - len(base))
        self.names = names

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
        return sp.latex(expr, symbol_names=self.names).replace(
            r"\operatorname{atan}_{2}", r"\operatorname{atan2}")

    def sum_rows(self, lhs: str, expr, width: int = LINE) -> list[str]:
        """``lhs &= expr`` as align rows, a long sum broken between its terms."""
        expr = sp.sympify(expr)
        whole = self(expr)
        if len(whole) <= width:
            return [f"{lhs} &= {whole}"]
        # a term too long for a row is expanded into terms of its own, where that helps
        terms = []
        for t in (expr.as_ordered_terms() if isinstance(expr, sp.Add) else [expr]):
            te = sp.expand(t) if len(self(t)) > width else t
            terms += te.as_ordered_terms() if isinstance(te, sp.Add) else [t]
        if len(terms) == 1:
            return [f"{lhs} &= {whole}"]
        rows, cur = [], ""
        for i, t in enumerate(terms):
            neg = t.could_extract_minus_sign()
            body = self(-t if neg else t)
            if isinstance(-t if neg else t, sp.Add):
                body = rf"\left({body}\right)"
            piece = ("- " if neg else ("" if i == 0 else "+ ")) + body
            if cur and len(cur) + len(piece) > width:
                rows.append(cur)
                cur = ""
            cur = (cur + " " + piece).strip()
        rows.append(cur)
        out = [f"{lhs} &= {rows[0]}"]
        out += [rf"&\quad {r}" for r in rows[1:]]
        return out


def _pmatrix(namer: _Namer, M: sp.Matrix, force: bool = False) -> str | None:
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


def _rows_of(namer: _Namer, lhs: str, syms, per_row: int = 8) -> list[str]:
    """``lhs &= (a, b, c, ...)^T`` as align rows of at most ``per_row`` entries."""
    names = [namer(s) for s in syms]
    chunks = [names[i:i + per_row] for i in range(0, len(names), per_row)]
    rows = []
    for k, chunk in enumerate(chunks):
        text = ", ".join(chunk) + ("," if k < len(chunks) - 1 else r")^{\mathsf{T}}")
        rows.append(f"{lhs} &= ({text}" if k == 0 else rf"&\qquad {text}")
    return rows


def _column(namer: _Namer, syms) -> str:
    return r"\begin{pmatrix} " + r" \\ ".join(namer(s) for s in syms) + r" \end{pmatrix}"


class _Doc:
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

    def entries(self, namer: _Namer, name: str, M: sp.Matrix, what: str, entry: str):
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


BIBLIOGRAPHY = {
    "linkagesym-kinematics": (
        r"\emph{Kinematic analysis of planar mechanisms} (Chinese: Pingmian jigou de yundong "
        r"fenxi), chapter~3 of a textbook on the theory of machines and mechanisms; author, "
        r"publisher and year not shown in the text available to linkage\_sym (not before 2008)."
    ),
}
"""The works the derived equations cite, as ``\\bibitem`` texts (author, title; README, Sources)."""

UNITS = {
    "length": "m", "coordinate": "m", "angle": "rad", "mass": "kg",
    "inertia": r"kg\,m$^2$", "gravity": r"m/s$^2$",
}


def _unit_of_parameter(p) -> str:
    if p.kind == "load":
        return r"N\,m" if p.name.startswith("T_") else "N"
    return UNITS.get(p.kind, "")


def _unit_of_intermediate(sym) -> str:
    pre = sym.name.split("_", 1)[0]
    if pre in ("cphi", "sphi"):
        return "1"
    if pre in ("aGx", "aGy"):
        return r"m/s$^2$"
    return "m"


def bibliography() -> str:
    """A ``thebibliography`` environment with every work the documents cite."""
    items = [rf"\bibitem{{{k}}} {v}" for k, v in BIBLIOGRAPHY.items()]
    return "\n".join([r"\begin{thebibliography}{9}", *items, r"\end{thebibliography}"])


def standalone(body: str, title: str = "Equations") -> str:
    """``body`` (fragments of :func:`latex_document`) as a complete document with its bibliography."""
    return "\n".join([
        r"\documentclass{article}",
        r"\usepackage{amsmath,amssymb}",
        r"\usepackage{longtable}",
        r"\usepackage[margin=2cm]{geometry}",
        r"\setcounter{MaxMatrixCols}{20}",
        rf"\title{{{escape_text(title)}}}",
        r"\author{generated by linkage\_sym}",
        r"\begin{document}",
        r"\maketitle",
        body,
        bibliography(),
        r"\end{document}",
        "",
    ])


def _nomenclature(doc, nm, eqs) -> None:
    """Every symbol with its meaning and unit, as a ``longtable``."""
    rows = []
    for s, sd, sdd in zip(eqs.x, eqs.xd, eqs.xdd):
        if s.name.startswith("theta_"):
            link = escape_text(s.name[6:])
            rows += [(nm(s), f"angle of link {link}", "rad"),
                     (nm(sd), f"angular velocity of link {link}", "rad/s"),
                     (nm(sdd), f"angular acceleration of link {link}", r"rad/s$^2$")]
        else:
            j = escape_text(s.name[2:])
            rows += [(nm(s), f"slide of prismatic joint {j}", "m"),
                     (nm(sd), f"slide velocity of joint {j}", "m/s"),
                     (nm(sdd), f"slide acceleration of joint {j}", r"m/s$^2$")]
    for q, qd, qdd, d in zip(eqs.q, eqs.qd, eqs.qdd, eqs.scene.drivers):
        j = escape_text(d.joint)
        u = "rad" if d.kind == "R" else "m"
        rows += [(nm(q), f"driver coordinate of joint {j}", u),
                 (nm(qd), "its velocity", u + "/s"), (nm(qdd), "its acceleration", u + r"/s$^2$")]
    for ge in eqs.groups:
        if ge.sigma is not None:
            rows.append((nm(ge.sigma), f"assembly mode of group {ge.index + 1} ($\\pm 1$)", "1"))
    for j, k in zip(eqs.scene.meshes, eqs.flanks):
        rows.append((nm(k), f"flank of gear mesh {escape_text(j.name)}: sign of its tangential "
                            "force ($\\pm 1$)", "1"))
    for s in eqs.parameters:
        p = eqs.table.params[s.name]
        rows.append((nm(s), escape_text(p.meaning), _unit_of_parameter(p)))
    for s, meaning in eqs.intermediates:
        rows.append((nm(s), escape_text(meaning), _unit_of_intermediate(s)))
    if eqs.has_forces:
        for s, _, meaning in eqs.force_intermediates:
            rows.append((nm(s), escape_text(meaning), _unit_of_intermediate(s)))
        for j in eqs.scene.joints:
            jn = escape_text(j.name)
            if j.type == "G":
                a, b = (escape_text(n) for n in j.links)
                rows.append((nm(eqs.F[j.name][0]), f"tooth load of gear mesh {jn} on its line of "
                                                   f"action (gear {a} on gear {b})", "N"))
                continue
            f1, f2 = eqs.F[j.name]
            if j.type == "R":
                rows += [(nm(f1), f"force of joint {jn}'s first link on its second, x", "N"),
                         (nm(f2), "the same, y", "N")]
            else:
                rows += [(nm(f1), f"normal force of prismatic joint {jn}", "N"),
                         (nm(f2), f"couple of prismatic joint {jn}", r"N\,m")]
        for d in eqs.scene.drivers:
            rows.append((nm(eqs.E[d.joint]), f"driving effort at joint {escape_text(d.joint)}",
                         r"N\,m" if d.kind == "R" else "N"))
    doc.text(r"\begin{longtable}{lll}")
    doc.text(r"symbol & meaning & unit \\ \hline \endhead")
    for sym, meaning, unit in rows:
        doc.text(rf"${sym}$ & {meaning} & {unit} \\")
    doc.text(r"\end{longtable}")


def latex_document(eqs: MechanismEquations, symbols: bool = False) -> str:
    r"""A LaTeX fragment with a mechanism's equations in the kinematics chapter's notation.

    Sections: the symbols and their meanings; every closed vector loop in
    complex form (eq. 3-8) and its projections (eq. 3-9); the explicit
    positions of input links and dyads; the velocity equation
    ``A xd = B qd`` (3-28) and the acceleration equation (3-29) as
    matrices; and, when ``eqs.has_forces``, each group's force equations
    ``A_g F_g = b_g - C_g F_later`` and the frame force and moment.

    Parameters
    ----------
    eqs : MechanismEquations
        The result of :func:`linkage_sym.symbolic.derive`.
    symbols : bool
        A nomenclature table (``longtable``) of every symbol with its meaning
        and unit instead of the list of symbols.

    Returns
    -------
    str
        A fragment without ``\documentclass``, for ``\input`` in a
        document that loads ``amsmath``.  Every equation carries a
        ``\label`` starting with ``eq:<scene name>:``.  Matrices larger than
        :data:`MAX_MATRIX` or with long entries are listed entry by entry.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> from linkage_sym.symbolic import derive
    >>> tex = latex_document(derive(load_example("crank_rocker")))
    >>> r"\theta_{\mathrm{crank}}" in tex and r"\label{eq:crank-rocker:loop-D}" in tex
    True
    >>> tex.count(r"\begin{equation}") == tex.count(r"\end{equation}")
    True
    """
    nm = _Namer(eqs)
    scene = eqs.scene
    doc = _Doc("eq:" + scene.name)
    title = escape_text(scene.name)
    doc.text(f"% Equations of mechanism '{scene.name}', generated by linkage_sym.")
    doc.text(r"% Needs amsmath (and longtable with a symbol table); for matrices with more")
    doc.text(r"% than 10 columns add \setcounter{MaxMatrixCols}{20} to the preamble.")
    doc.text(r"% Cites the keys below; add these entries to your bibliography:")
    for key, text in BIBLIOGRAPHY.items():
        doc.text(rf"%   \bibitem{{{key}}} {text}")
    doc.text(rf"\subsection*{{Equations of the mechanism \texttt{{{title}}}}}")

    # (a) symbols
    doc.text(r"\paragraph{Symbols.}")
    doc.text(
        r"Link angles $\theta$ are measured from the $x$-axis to each link's axis, "
        r"$\omega = \dot\theta$, $\alpha = \ddot\theta$; $s$ is the slide of a prismatic "
        r"joint (0 in the assembly configuration), $q$ a driver coordinate."
    )
    if symbols:
        _nomenclature(doc, nm, eqs)
    else:
        _symbol_list(doc, nm, eqs)
    if not eqs.parameters:
        doc.text("The dimensions are the scene's numbers (derived with symbolic=False).")
    _rest(doc, nm, eqs)
    return "\n".join(doc.out) + "\n"


def _symbol_list(doc, nm, eqs) -> None:
    doc.text(r"\begin{itemize}")
    for s, sd, sdd in zip(eqs.x, eqs.xd, eqs.xdd):
        if s.name.startswith("theta_"):
            what = f"angle, angular velocity and acceleration of link {s.name[6:]}"
        else:
            what = f"slide of prismatic joint {s.name[2:]} and its rates"
        doc.text(rf"\item ${nm(s)}, {nm(sd)}, {nm(sdd)}$: {escape_text(what)}")
    for q, qd, qdd in zip(eqs.q, eqs.qd, eqs.qdd):
        doc.text(rf"\item ${nm(q)}, {nm(qd)}, {nm(qdd)}$: driver coordinate of joint "
                 f"{escape_text(q.name[2:])} and its rates")
    for ge in eqs.groups:
        if ge.sigma is not None:
            doc.text(rf"\item ${nm(ge.sigma)} = \pm 1$: assembly mode of group {ge.index + 1}")
    for s in eqs.parameters:
        p = eqs.table.params[s.name]
        doc.text(rf"\item ${nm(s)}$: {escape_text(p.meaning)} ({p.kind})")
    for s, meaning in eqs.intermediates:
        doc.text(rf"\item ${nm(s)}$: {escape_text(meaning)} (intermediate)")
    for s, _, meaning in getattr(eqs, "force_intermediates", ()):
        doc.text(rf"\item ${nm(s)}$: {escape_text(meaning)} (intermediate)")
    if eqs.has_forces:
        doc.text(
            r"\item $R_{J,x}, R_{J,y}$: force of the joint's first link on its second at "
            r"revolute joint $J$; $N_{J}$, $M_{J}$: normal force and couple of prismatic joint "
            r"$J$; $\tau_{J}$, $f_{J}$: driving torque or force at joint $J$"
        )
    doc.text(r"\end{itemize}")


def scene_joint_type(eqs, name: str) -> str:
    return eqs.scene.joint(name).type


def _rest(doc, nm, eqs) -> None:

    # (b) loops
    doc.text(r"\paragraph{Loop equations.}")
    if eqs.loops:
        doc.text(
            "Each joint that closes a loop gives a closed vector loop "
            r"\cite[eq.~3-8]{linkagesym-kinematics} and its projections on the "
            "axes (its eq.~3-9):"
        )
    else:
        doc.text("The mechanism has no closed vector loop: every link is placed along a tree"
                 + (" (its gear meshes close it below)." if eqs.meshes else "."))
    for jname, v in eqs.loops:
        key = f"loop-{jname}"
        rows = [r.replace("&=", "&=", 1) for r in nm.sum_rows("0", v.complex())]
        doc.align(rows, [key] + [None] * (len(rows) - 1))
        rx, ry = nm.sum_rows("0", v.x), nm.sum_rows("0", v.y)
        doc.align(rx + ry, [key + "-x"] + [None] * (len(rx) - 1) + [key + "-y"] + [None] * (len(ry) - 1))

    if eqs.meshes:
        doc.text(r"\paragraph{Gear meshes.}")
        doc.text(
            "Each mesh rolls without slip: its pitch radii times the rotations of its gears "
            "relative to its carrier, from the assembly configuration, cancel (an external "
            "mesh) or agree (an internal one):"
        )
        rows, keys = [], []
        for jname, e in eqs.meshes:
            r = nm.sum_rows("0", e)
            rows += r
            keys += [f"mesh-{jname}"] + [None] * (len(r) - 1)
        doc.align(rows, keys)

    # (c) positions
    doc.text(r"\paragraph{Positions.}")
    if eqs.closed_forms:
        doc.text(
            "Explicit positions of the input links and dyads, in solving order "
            r"(each may use those above it; $\sigma = \pm 1$ selects the assembly mode). "
            "Each dyad first names its outer joints, the distance $d$ between them, the "
            "projection $a$ and the half-chord $h$ of its inner joint (Heron's form, accurate "
            "near a dead centre), then its inner joint and its angles:"
        )
        rows, keys = [], []
        for s, e in eqs.position_steps:
            r = nm.sum_rows(nm(s), e)
            rows += r
            keys += [f"pos-{s.name}"] + [None] * (len(r) - 1)
        doc.align(rows, keys)
    for ge in eqs.groups:
        if not ge.closed:
            coords = ", ".join(f"${nm(s)}$" for s in ge.x)
            links = escape_text(", ".join(ge.group.links))
            doc.text(
                f"Group {ge.index + 1} ({escape_text(ge.group.kind)}: links {links}) has no "
                f"explicit closed form: its coordinates {coords} are found numerically "
                "(Newton's method) from its loop "
                + ("and mesh " if any(scene_joint_type(eqs, j) == "G" for j in ge.group.joints) else "")
                + "equations above."
            )

    # (d) velocities
    doc.text(r"\paragraph{Velocities.}")
    doc.text(
        r"Differentiating the position equations $\Phi$ with respect to time gives "
        r"$\mathbf{A}\,\dot{\mathbf{x}} = \mathbf{B}\,\dot{\mathbf{q}}$ "
        r"\cite[eq.~3-28]{linkagesym-kinematics}, "
        r"$\mathbf{A} = \partial\Phi/\partial\mathbf{x}$, "
        r"$\mathbf{B} = -\partial\Phi/\partial\mathbf{q}$:"
    )
    A, B = _pmatrix(nm, eqs.A), _pmatrix(nm, eqs.B)
    col_xd, col_qd = _column(nm, eqs.xd), _column(nm, eqs.qd)
    whole = f"{A} {col_xd} = {B} {col_qd}"
    if A is not None and B is not None and len(whole) <= MAX_EQUATION:
        doc.equation(whole, "velocity")
    else:
        doc.equation(r"\mathbf{A}\,\dot{\mathbf{x}} = \mathbf{B}\,\dot{\mathbf{q}}", "velocity")
        doc.align([rf"\dot{{\mathbf{{x}}}} &= {col_xd}", rf"\dot{{\mathbf{{q}}}} &= {col_qd}"],
                  numbered=False)
        if A is None:
            doc.entries(nm, r"\mathbf{A}", eqs.A, "the matrix", "A")
        else:
            doc.align([rf"\mathbf{{A}} &= {A}"], numbered=False)
        if B is None:
            doc.entries(nm, r"\mathbf{B}", eqs.B, "the matrix", "B")
        else:
            doc.align([rf"\mathbf{{B}} &= {B}"], numbered=False)

    # (e) accelerations
    doc.text(r"\paragraph{Accelerations.}")
    doc.text(
        r"Differentiating once more \cite[eq.~3-29]{linkagesym-kinematics}, "
        r"$\mathbf{A}\,\ddot{\mathbf{x}} = -\dot{\mathbf{A}}\,\dot{\mathbf{x}} + "
        r"\dot{\mathbf{B}}\,\dot{\mathbf{q}} + \mathbf{B}\,\ddot{\mathbf{q}}$, with the same "
        r"$\mathbf{A}$; the right-hand side is printed as one column $\mathbf{r}$:"
    )
    doc.equation(
        r"\mathbf{A}\,\ddot{\mathbf{x}} = \mathbf{r} = -\dot{\mathbf{A}}\,\dot{\mathbf{x}} "
        r"+ \dot{\mathbf{B}}\,\dot{\mathbf{q}} + \mathbf{B}\,\ddot{\mathbf{q}}",
        "acceleration",
    )
    doc.align([rf"\ddot{{\mathbf{{x}}}} &= {_column(nm, eqs.xdd)}"], numbered=False)
    rhs = _pmatrix(nm, eqs.acc_rhs)
    if rhs is not None and eqs.acc_rhs.rows <= MAX_MATRIX:
        doc.align([rf"\mathbf{{r}} &= {rhs}"], numbered=False)
    else:
        doc.entries(nm, r"\mathbf{r}", eqs.acc_rhs, "the right-hand side", "r")

    # (f) forces
    if eqs.has_forces:
        doc.text(r"\paragraph{Forces.}")
        doc.text(
            "Each group's links in equilibrium with their loads and d'Alembert inertia "
            r"forces give $\mathbf{A}_g \mathbf{F}_g = \mathbf{b}_g - \mathbf{C}_g "
            r"\mathbf{F}_{\mathrm{later}}$, solved from the last group back "
            r"($\mathbf{F}_{\mathrm{later}}$: the reactions and efforts of the groups solved after it)."
        )
        if eqs.force_intermediates:
            doc.text(
                r"The d'Alembert forces use the accelerations $a^{G}$ of the centres of mass, "
                "from the positions and rates above:"
            )
            rows, keys = [], []
            for sym, e, _ in eqs.force_intermediates:
                r = nm.sum_rows(nm(sym), e)
                rows += r
                keys += [f"acc-{sym.name}"] + [None] * (len(r) - 1)
            doc.align(rows, keys)
        for ge, (Ag, bg, Cg, later) in zip(eqs.groups, eqs.readable_force_blocks):
            g = ge.index + 1
            links = escape_text(", ".join(ge.group.links))
            doc.text(rf"\subparagraph{{Group {g}}} ({escape_text(ge.group.kind)}: links {links}).")
            a = _pmatrix(nm, Ag)
            b = _pmatrix(nm, bg)
            c = _pmatrix(nm, Cg) if later else None
            F = _column(nm, ge.forces)
            Fl = _column(nm, later) if later else None
            small = a is not None and b is not None and (not later or c is not None)
            rhs = None if not small else b + (f" - {c} {Fl}" if later else "")
            if small and len(f"{a} {F} = {rhs}") <= MAX_EQUATION:
                doc.equation(f"{a} {F} = {rhs}", f"forces-{g}")
            else:
                rhs = rf"\mathbf{{b}}_{{{g}}}" + (
                    rf" - \mathbf{{C}}_{{{g}}} \mathbf{{F}}_{{>{g}}}" if later else "")
                doc.equation(rf"\mathbf{{A}}_{{{g}}} \mathbf{{F}}_{{{g}}} = {rhs}", f"forces-{g}")
                rows = _rows_of(nm, rf"\mathbf{{F}}_{{{g}}}", ge.forces)
                if later:
                    rows += _rows_of(nm, rf"\mathbf{{F}}_{{>{g}}}", later)
                doc.align(rows, numbered=False)
                for name, M, m_tex, what, entry in (
                    (rf"\mathbf{{A}}_{{{g}}}", Ag, a, "the matrix", f"A^{{({g})}}"),
                    (rf"\mathbf{{b}}_{{{g}}}", bg, b, "the column", f"b^{{({g})}}"),
                    (rf"\mathbf{{C}}_{{{g}}}", Cg, c, "the matrix", f"C^{{({g})}}"),
                ):
                    if name.startswith(r"\mathbf{C}") and not later:
                        continue
                    if m_tex is not None:
                        doc.align([f"{name} &= {m_tex}"], numbered=False)
                    elif M.is_zero_matrix:
                        doc.text(f"${name} = 0$.")
                    else:
                        doc.entries(nm, name, M, what, entry)
        doc.text(
            "The frame (ground) carries the force and the moment about the origin "
            "that the moving links put on it:"
        )
        rows, keys = [], []
        for lhs, e, k in zip(
            (r"F^{\mathrm{fr}}_{x}", r"F^{\mathrm{fr}}_{y}", r"M^{\mathrm{fr}}"),
            eqs.frame,
            ("frame-x", "frame-y", "frame-moment"),
        ):
            r = nm.sum_rows(lhs, e)
            rows += r
            keys += [k] + [None] * (len(r) - 1)
        doc.align(rows, keys)
