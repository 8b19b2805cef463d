"""A reader of the LaTeX that ``linkage-sym derive --latex`` prints, evaluating it with numbers.

It shares no code with the printer (neither SymPy nor :mod:`linkage_sym.symbolic`): it reads
the math that the derived equations use -- sums, implicit and ``\\cdot`` products,
``\\frac``, ``\\sqrt``, powers, ``\\left( \\right)``, ``\\sin``, ``\\cos``, ``\\tan``,
``\\operatorname{atan2}`` (with a power such as ``\\cos^{2}{\\left(x \\right)}``),
``\\pi`` and numbers -- and looks every other name up, the longest first, in the values it
is given (``{"x_{B}": 0.01, "\\\\theta_{\\\\mathrm{crank}}": 0.3, ...}``), so that a name the
reader does not know is an error, never a silent zero.

:func:`value` evaluates one expression; :func:`rows` splits an ``align`` block into its
``lhs &= rhs`` rows (continuation rows ``&\\quad + ...`` joined); :func:`matrix` reads a
``pmatrix``'s entries.

Examples
--------
>>> value(r"\\frac{- x_{B} + x_{D}}{2} + \\sqrt{4}", {"x_{B}": 1.0, "x_{D}": 3.0})
3.0
>>> value(r"\\cos^{2}{\\left(\\theta \\right)} + \\sin^{2}{\\left(\\theta \\right)}", {r"\\theta": 0.7})
1.0
>>> matrix(r"\\begin{pmatrix} 1 & - a \\\\ 0 & a b \\end{pmatrix}")
[['1', '- a'], ['0', 'a b']]
"""

from __future__ import annotations

import math
import re

__all__ = ["LatexReadError", "value", "rows", "matrix", "sections"]

FUNCTIONS = {r"\sin": math.sin, r"\cos": math.cos, r"\tan": math.tan,
             r"\operatorname{atan2}": math.atan2, r"\operatorname{atan}": math.atan}
_SKIP = (r"\qquad", r"\quad", r"\,", r"\;", r"\!", r"\left.", r"\right.")


class LatexReadError(ValueError):
    """Text the reader cannot read, with the place."""


class _Reader:
    """Recursive descent over one expression; every rule returns a float."""

    def __init__(self, tex: str, values: dict):
        self.s = tex
        self.i = 0
        self.values = values
        self.names = sorted(values, key=len, reverse=True)

    # -- characters -----------------------------------------------------------------
    def _blank(self) -> None:
        while True:
            while self.i < len(self.s) and self.s[self.i].isspace():
                self.i += 1
            for k in _SKIP:
                if self.s.startswith(k, self.i) and not self.s[self.i + len(k):][:1].isalpha():
                    self.i += len(k)
                    break
            else:
                return

    def peek(self, text: str) -> bool:
        self._blank()
        return self.s.startswith(text, self.i)

    def take(self, text: str) -> None:
        if not self.peek(text):
            self.fail(f"{text!r} expected")
        self.i += len(text)

    def fail(self, why: str):
        raise LatexReadError(f"{why} at {self.i}: ...{self.s[max(0, self.i - 40):self.i]}"
                             f"<HERE>{self.s[self.i:self.i + 40]}...")

    # -- grammar --------------------------------------------------------------------
    def sum(self) -> float:
        sign = 1.0
        if self.peek("-"):
            self.take("-")
            sign = -1.0
        elif self.peek("+"):
            self.take("+")
        total = sign * self.product()
        while True:
            if self.peek("+"):
                self.take("+")
                total += self.product()
            elif self.peek("-"):
                self.take("-")
                total -= self.product()
            else:
                return total

    def product(self) -> float:
        out = self.power()
        while True:
            if self.peek(r"\cdot"):
                self.take(r"\cdot")
                out *= self.power()
            elif self._starts_factor():
                out *= self.power()
            else:
                return out

    def _starts_factor(self) -> bool:
        self._blank()
        if self.i >= len(self.s):
            return False
        c = self.s[self.i]
        if c in "+-)},&=^_" or self.s.startswith(r"\right", self.i) or self.s.startswith("\\\\", self.i):
            return False
        return not self.s.startswith(r"\end", self.i)

    def power(self) -> float:
        base = self.atom()
        if self.peek("^"):
            self.take("^")
            return base ** self.group_or_atom()
        return base

    def group_or_atom(self) -> float:
        if self.peek("{"):
            self.take("{")
            v = self.sum()
            self.take("}")
            return v
        return self.atom()

    def atom(self) -> float:
        self._blank()
        for name in self.names:  # a given name before any rule: x^{G}_{...} is one name
            if self.s.startswith(name, self.i) and not self._continues_name(self.i + len(name)):
                self.i += len(name)
                return float(self.values[name])
        m = re.compile(r"\d+(\.\d+)?").match(self.s, self.i)
        if m:
            self.i = m.end()
            return float(m.group())
        if self.peek("{"):
            return self.group_or_atom()
        if self.peek(r"\left("):
            self.take(r"\left(")
            v = self.sum()
            self.take(r"\right)")
            return v
        if self.peek(r"\left|"):
            self.take(r"\left|")
            v = self.sum()
            self.take(r"\right|")
            return abs(v)
        if self.peek(r"\frac"):
            self.take(r"\frac")
            num = self.group_or_atom()
            return num / self.group_or_atom()
        if self.peek(r"\sqrt"):
            self.take(r"\sqrt")
            v = self.group_or_atom()
            return math.sqrt(v) if v >= 0 else math.nan
        if self.peek(r"\pi"):
            self.take(r"\pi")
            return math.pi
        for name, f in FUNCTIONS.items():
            if self.peek(name) and not self._continues_name(self.i + len(name)):
                return self._call(name, f)
        self.fail("unknown name")

    def _continues_name(self, j: int) -> bool:
        """Whether the text at ``j`` still belongs to a longer name (``_{...}``, ``^{...}``
        of a name, or more letters of a command)."""
        return j < len(self.s) and (self.s[j].isalpha() and self.s[j - 1].isalpha()
                                    or self.s[j] == "_")

    def _call(self, name: str, f) -> float:
        self.take(name)
        exponent = None
        if self.peek("^"):
            self.take("^")
            exponent = self.group_or_atom()
        braced = self.peek("{")
        if braced:
            self.take("{")
        self.take(r"\left(")
        args = [self.sum()]
        while self.peek(","):
            self.take(",")
            args.append(self.sum())
        self.take(r"\right)")
        if braced:
            self.take("}")
        v = f(*args)
        return v if exponent is None else v ** exponent


def value(tex: str, values: dict) -> float:
    """The value of the expression ``tex`` with the names of ``values`` (LaTeX -> number)."""
    r = _Reader(tex, values)
    v = r.sum()
    r._blank()
    if r.i != len(r.s):
        r.fail("end of the expression expected")
    return v


def rows(block: str) -> list[tuple[str, str]]:
    """``[(lhs, rhs), ...]`` of an ``align`` block's rows ``lhs &= rhs``, labels and
    ``\\nonumber`` dropped, a continuation row (``&\\quad + ...``) joined to its row."""
    out: list = []
    depth, cur, parts = 0, "", []
    for tok in re.split(r"(\\begin\{\w+\}|\\end\{\w+\}|\\\\)", block):
        if tok.startswith(r"\begin"):
            depth += 1
        elif tok.startswith(r"\end"):
            depth -= 1
        elif tok == "\\\\" and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        cur += tok
    parts.append(cur)
    for p in parts:
        p = re.sub(r"\\label\{[^}]*\}|\\nonumber|\\notag", "", p).strip()
        if not p:
            continue
        lhs, sep, rhs = p.partition("&=")
        if sep:
            out.append((lhs.strip(), rhs.strip()))
        elif p.startswith("&") and out:
            out[-1] = (out[-1][0], out[-1][1] + " " + p[1:].strip())
        else:
            raise LatexReadError(f"a row without '&=': {p[:80]}")
    return out


def matrix(tex: str) -> list[list[str]]:
    """The entries (LaTeX) of the ``pmatrix`` ``tex``, row by row."""
    m = re.fullmatch(r"\s*\\begin\{pmatrix\}(.*)\\end\{pmatrix\}\s*", tex, re.S)
    if not m:
        raise LatexReadError(f"not a pmatrix: {tex[:80]}")
    return [[e.strip() for e in r.split("&")] for r in m.group(1).split("\\\\")]


def sections(doc: str) -> dict[str, str]:
    """The text of each ``\\paragraph{Name.}`` of the document, by name."""
    parts = re.split(r"\\paragraph\{([^}]*)\.\}", doc)
    return {parts[k]: parts[k + 1] for k in range(1, len(parts) - 1, 2)}
