"""A mechanism's derived equations as Markdown with MathJax math, for notebooks and the docs.

The same sections, equations and named intermediates as
:func:`linkage_sym.symbolic.latex.latex_document` (written by the same section
writers, :func:`linkage_sym.symbolic.latex.write_document`), into a
:class:`MarkdownDoc`: headings for the sections (``##``) and force groups
(``###``), running text in CommonMark, the symbols as a list or a table, and
every display as a ``$$ ... $$`` block (rows of an ``aligned`` environment),
which Jupyter's MathJax and MyST's ``dollarmath`` render.  Equations are not
numbered (a notebook has no ``\\label``), and the vector loops' figures are
left out (TikZ is LaTeX's).
"""

from __future__ import annotations

import re

from linkage_sym.symbolic.latex import BIBLIOGRAPHY, write_document
from linkage_sym.symbolic.latex_notation import Doc
from linkage_sym.symbolic.mechanism import MechanismEquations
from linkage_sym.symbolic.numbers import DIGITS

__all__ = ["MarkdownDoc", "markdown_document", "markdown_text"]

_MATH = re.compile(r"(?<!\\)\$(.*?)(?<!\\)\$")
_CITE = re.compile(r"\\cite(?:\[([^\]]*)\])?\{([^}]*)\}")
_TEXT = [  # LaTeX text-mode markup the section writers use, and its Markdown
    (re.compile(r"\\emph\{([^}]*)\}"), r"*\1*"),
    (re.compile(r"\\ensuremath\{\\to\}"), "\u2192"),
    (re.compile(r"\\ensuremath\{<\}"), "&lt;"),
    (re.compile(r"\\ensuremath\{>\}"), "&gt;"),
    (re.compile(r"\\textbackslash\{\}"), r"\\\\"),
    (re.compile(r"\\textasciitilde\{\}"), r"\\~"),
    (re.compile(r"\\textasciicircum\{\}"), r"\\^"),
    (re.compile(r"\\([%{}])"), r"\1"),
    (re.compile(r"\\,"), " "),
    (re.compile(r"(?<!\\)~"), " "),
]
_PARBOX = re.compile(r"^\\parbox\[t\]\{[^}]*\}\{\\raggedright (.*)\}$")
"""A long meaning in the symbol table, set as a paragraph in LaTeX: a plain cell here."""
_REFERENCES = {key: i + 1 for i, key in enumerate(BIBLIOGRAPHY)}


def _code(m: re.Match) -> str:
    return "`" + m.group(1).replace("\\_", "_").replace("\\&", "&") + "`"


def _braced(s: str, start: int) -> tuple[str, str]:
    """The text of ``s`` from ``start`` to its matching closing brace, and what follows it."""
    depth = 1
    for i in range(start, len(s)):
        if s[i] == "{" and s[i - 1] != "\\":
            depth += 1
        elif s[i] == "}" and s[i - 1] != "\\":
            depth -= 1
            if depth == 0:
                return s[start:i], s[i + 1:]
    raise ValueError(f"unbalanced braces in {s!r}")


def markdown_text(s: str) -> str:
    r"""LaTeX running text (as the section writers write it) as CommonMark: inline math
    ``$...$`` kept, citations as ``[n, where]``, ``\emph`` and ``\texttt`` as Markdown.

    Examples
    --------
    >>> markdown_text(r"A loop \cite[eq.~3-8]{linkagesym-kinematics} of $l_{AB}$, kg\,m$^2$")
    'A loop [1, eq. 3-8] of $l_{AB}$, kg m$^2$'
    """
    parts = _MATH.split(s)
    out = []
    for i, part in enumerate(parts):
        if i % 2:  # math, as it is
            out.append(f"${part}$")
            continue
        part = _CITE.sub(lambda m: f"[{_REFERENCES[m.group(2)]}"
                         + (f", {m.group(1)}" if m.group(1) else "") + "]", part)
        part = re.sub(r"\\texttt\{((?:[^}\\]|\\.)*)\}", _code, part)
        for pattern, repl in _TEXT:
            part = pattern.sub(repl, part)
        out.append(part)
    return "".join(out)


class MarkdownDoc(Doc):
    """A Markdown document that reads a :class:`~linkage_sym.symbolic.latex_notation.Doc`'s
    calls: LaTeX comments dropped, headings, lists and tables as Markdown, displays as
    ``$$`` blocks.

    Parameters
    ----------
    prefix : str
        The start of every equation's key (kept for :attr:`labels`, not printed).
    """

    def __init__(self, prefix: str):
        super().__init__(prefix)
        self._table = False

    def text(self, s: str = ""):
        if s.startswith("%"):
            return
        heading = re.match(r"\\(subsection\*|paragraph|subparagraph)\{", s)
        if heading:
            level = {"subsection*": "#", "paragraph": "##", "subparagraph": "###"}[heading[1]]
            title, rest = _braced(s, heading.end())
            if level == "###":  # a force group: "Group 1 (dyad: links ...)" as its heading
                title, rest = f"{title} {rest.strip().rstrip('.')}", ""
            self.out += [f"{level} {markdown_text(title.rstrip('.'))}", ""]
            if rest.strip():
                self.out += [markdown_text(rest.strip()), ""]
        elif s.startswith(r"\begin{itemize}") or s.startswith(r"\end{itemize}"):
            self.out.append("")
        elif s.startswith(r"\item "):
            self.out.append("- " + markdown_text(s[6:]))
        elif s.startswith(r"\begin{longtable}"):
            self._table = True
        elif s.startswith(r"\end{longtable}"):
            self._table = False
            self.out.append("")
        elif self._table:
            cells = [c.strip() for c in re.split(r"(?<!\\)&", s.split(r"\\")[0])]
            cells = [markdown_text(_PARBOX.sub(r"\1", c)).replace("|", r"\|") for c in cells]
            row = "| " + " | ".join(cells) + " |"
            self.out += [row, "| --- | --- | --- |"] if r"\endhead" in s else [row]
        else:
            self.out += [markdown_text(s), ""]

    def equation(self, body: str, key: str):
        self.label(key)
        self.out += ["$$", body, "$$", ""]

    def align(self, rows: list[str], keys: list | None = None, numbered: bool = True):
        for k in (keys or []) if numbered else []:
            if k is not None:
                self.label(k)
        self.out += ["$$", r"\begin{aligned}", " \\\\\n".join(rows), r"\end{aligned}", "$$", ""]


def markdown_document(eqs: MechanismEquations, symbols: bool = False, digits=DIGITS) -> str:
    r"""A mechanism's equations as Markdown with MathJax math (``$$`` blocks).

    Parameters
    ----------
    eqs : MechanismEquations
        The result of :func:`linkage_sym.symbolic.derive`.
    symbols : bool
        A table of every symbol with its meaning and unit instead of the list of symbols.
    digits : int or str
        The numbers' significant digits, or ``"full"``: as
        :func:`linkage_sym.symbolic.latex.latex_document`'s.

    Returns
    -------
    str
        The page: a ``#`` title, a ``##`` heading a section (symbols, loop equations,
        positions, velocities, accelerations, forces), the same equations as
        :func:`linkage_sym.symbolic.latex.latex_document` and its references.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> from linkage_sym.symbolic import derive
    >>> md = markdown_document(derive(load_example("crank_rocker")))
    >>> md.splitlines()[0]
    '# Equations of the mechanism `crank-rocker`'
    >>> "## Loop equations" in md and md.count("$$") % 2 == 0
    True
    """
    doc = MarkdownDoc("eq:" + eqs.scene.name)
    write_document(doc, eqs, symbols=symbols, figures=False, digits=digits)
    doc.out += ["## References", ""]
    doc.out += [f"{n}. {markdown_text(BIBLIOGRAPHY[key])}" for key, n in _REFERENCES.items()]
    return "\n".join(doc.out) + "\n"
