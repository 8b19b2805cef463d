"""Position rows that keep to the page: a square root too wide for a row gets its radicand named.

A dyad's half-chord ``h`` is one square root of a product of four factors (Heron's form,
:mod:`linkage_sym.symbolic.closed_forms`); the line breaking of
:meth:`~linkage_sym.symbolic.latex_notation.Namer.sum_rows` breaks sums between their terms,
never inside a root.  With the scene's numbers in full (``derive --numeric --digits full``:
four 17-digit numbers under the root) that row runs past the margin.  :func:`position_rows`
then names the radicand as a row of its own (``H_{2}`` for ``h_{2}``), the way the positions
already name a dyad's distance ``d``, and breaks that product between its factors
(:func:`product_rows`); the row of ``h`` reads ``\\sqrt{H_{2}}``.  A row that fits is written as
before, so the symbolic equations (whose rows fit) print unchanged.
"""

from __future__ import annotations

import re

import sympy as sp

from linkage_sym.symbolic.latex_notation import TYPESET, Namer, typeset_width
from linkage_sym.symbolic.tangent import tangent_sqrt

__all__ = ["position_rows", "product_rows"]


def _too_wide(rows: list[str], width: float) -> bool:
    return any(typeset_width(r.split("&", 1)[-1].lstrip("=")) > width for r in rows)


def product_rows(nm: Namer, lhs: str, factors, width: float = TYPESET) -> list[str]:
    r"""``lhs &= f_1 f_2 ...`` as align rows, broken between the factors where the product is
    too wide for a row, each row after the first continued with ``\cdot``.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> from linkage_sym.symbolic import derive
    >>> nm = Namer(derive(load_example("crank_rocker")))
    >>> a, b, c = sp.symbols("a b c")
    >>> product_rows(nm, "H", [a + b, b + c, a - c], width=12)
    ['H &= \\left(a + b\\right) \\left(b + c\\right)', '&\\quad \\cdot \\left(a - c\\right)']
    """
    factors = list(factors)
    sign = ""
    if factors and factors[0] == -1:
        sign, factors = "- ", factors[1:]
    pieces = [rf"\left({nm(f)}\right)" if isinstance(f, sp.Add) else nm(f) for f in factors]
    rows, cur = [], sign
    for p in pieces:
        if cur.strip("- ") and typeset_width(cur + " " + p) > width:
            rows.append(cur)
            cur = r"\cdot " + p
        else:
            cur = (cur + " " + p).strip()
    rows.append(cur)
    return [f"{lhs} &= {rows[0]}"] + [rf"&\quad {r}" for r in rows[1:]]


def _radicand_name(nm: Namer, s) -> str | None:
    """``H_{2}`` for ``h_{2}`` (the row's letter in capitals), primed until no symbol has it;
    None for a symbol not written as a letter with a subscript."""
    m = re.fullmatch(r"([a-z])(_\{.+\})", nm(s))
    if m is None:
        return None
    name = m.group(1).upper() + m.group(2)
    taken = set(nm.names.values())
    while name in taken:
        name += "'"
    return name


def _roots(e) -> dict:
    """``{square root: its radicand's factors}`` of ``e``'s square roots of more than a symbol
    (``sqrt``, and :class:`~linkage_sym.symbolic.tangent.tangent_sqrt` with its factors in
    the order of the derivation)."""
    e = sp.sympify(e)
    out = {a: sp.Mul.make_args(a.base) for a in e.atoms(sp.Pow)
           if a.exp == sp.S.Half and not a.base.is_Atom}
    out.update({a: a.args[1:] for a in e.atoms(tangent_sqrt)})
    return out


def position_rows(nm: Namer, steps) -> tuple[list[str], list, list[tuple[str, str]]]:
    """The align rows of the position steps ``[(symbol, expr), ...]``, their equation keys,
    and each radicand named (``[(radicand's name, row's symbol), ...]``) where a row with a
    square root is too wide for the page."""
    rows, keys, named = [], [], []
    for s, e in steps:
        r = nm.sum_rows(nm(s), e)
        roots = _roots(e)
        name = _radicand_name(nm, s) if roots and _too_wide(r, TYPESET) else None
        if name is not None:
            root, radicand = max(roots.items(), key=lambda a: typeset_width(nm(sp.Mul(*a[1]))))
            sym = sp.Symbol(f"radicand_{s.name}", positive=True)
            nm.names[sym] = name
            base = product_rows(nm, name, radicand)
            rows += base
            keys += [f"pos-{sym.name}"] + [None] * (len(base) - 1)
            named.append((name, nm(s)))
            r = nm.sum_rows(nm(s), sp.sympify(e).xreplace({root: sp.sqrt(sym)}))
        rows += r
        keys += [f"pos-{s.name}"] + [None] * (len(r) - 1)
    return rows, keys, named
