"""The notation of the derived equations as a reader writes them (issue 31): sums in a
person's order and collected by the quantity they multiply, one meaning per symbol."""

from __future__ import annotations

import re

import pytest

from linkage_sym.examples import load_example
from linkage_sym.symbolic import derive
from linkage_sym.symbolic.latex import latex_document


@pytest.fixture(scope="module")
def crank_rocker():
    eqs = derive(load_example("crank_rocker"), forces=True)
    return eqs, latex_document(eqs, symbols=True)


def _row(doc: str, lhs: str) -> list[str]:
    """The align rows of the equation ``lhs &= ...`` (its continuation rows too)."""
    lines = doc.splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith(lhs + " &= "))
    out = [lines[i]]
    for ln in lines[i + 1:]:
        if not ln.startswith(r"&\quad"):
            break
        out.append(ln)
    return out


def test_a_difference_is_written_positive_term_first(crank_rocker):
    _, doc = crank_rocker
    assert r"\Delta x_{2} &= x_{D} - x_{B}" in doc
    assert r"\Delta y_{2} &= y_{D} - y_{B}" in doc


def test_an_acceleration_is_collected_by_link_and_by_the_rate_it_multiplies(crank_rocker):
    """a^G of the coupler: the crank's terms (B's acceleration) first, then the coupler's,
    each of its angular acceleration and its rate squared once, as the factor of a sum."""
    _, doc = crank_rocker
    rows = _row(doc, r"a^{G}_{\mathrm{coupler},x}")
    text = " ".join(rows)
    assert text.index(r"\alpha_{\mathrm{crank}}") < text.index(r"\alpha_{\mathrm{coupler}}")
    assert text.count(r"\alpha_{\mathrm{coupler}}") == 1
    assert text.count(r"\omega_{\mathrm{coupler}}^{2}") == 1
    assert r"\alpha_{\mathrm{coupler}} \left(" in text
    assert len(rows) <= 3


def test_q_is_only_a_driver_coordinate(crank_rocker):
    """The symbol table gives every symbol printed as ``q_{...}`` one meaning: a driver
    coordinate; the centre of mass in a link's frame is (x^G, y^G)."""
    eqs, doc = crank_rocker
    table = re.search(r"\\begin\{longtable\}\{lll\}\n(.*?)\\end\{longtable\}", doc, re.S).group(1)
    meanings = {}
    for r in table.splitlines()[1:]:
        sym, meaning, _ = (c.strip() for c in r.rstrip("\\ ").split(" & "))
        meanings[sym] = meaning
    qs = {s: m for s, m in meanings.items() if s.startswith("$q_")}
    assert qs and all(m.startswith("driver coordinate") for m in qs.values()), qs
    assert not any(s.startswith("$p_") for s in meanings), meanings
    assert meanings[r"$x^{G}_{\mathrm{coupler}}$"].startswith("centre of mass of link coupler")
    assert len(set(meanings)) == len(table.splitlines()[1:])  # no symbol printed twice
    assert {"xG_coupler", "yG_coupler"} <= {s.name for s in eqs.parameters}  # the text's names


def _groups(tex: str):
    """The text inside every ``{...}`` and ``\\left( ... \\right)`` of ``tex``."""
    opens = []
    i = 0
    while i < len(tex):
        if tex.startswith(r"\left(", i):
            opens.append(i + len(r"\left("))
            i += len(r"\left(")
        elif tex.startswith(r"\right)", i):
            yield tex[opens.pop():i]
            i += len(r"\right)")
        elif tex[i] == "{" and tex[i - 1] != "\\":
            opens.append(i + 1)
            i += 1
        elif tex[i] == "}" and tex[i - 1] != "\\":
            yield tex[opens.pop():i]
            i += 1
        else:
            i += 1


def _top_level_terms(group: str) -> list[list[str]]:
    """Each comma-separated argument of ``group`` split at its top-level ``+`` and ``-``."""
    args, terms, depth, cur = [], [], 0, ""
    for tok in re.split(r"(\\left\(|\\right\)|[{}]| [+-] |,)", group):
        if tok in (r"\left(", "{"):
            depth += 1
        elif tok in (r"\right)", "}"):
            depth -= 1
        elif depth == 0 and tok in (" + ", " - "):
            terms.append(cur)
            cur = tok.strip()
            continue
        elif depth == 0 and tok == ",":
            args.append(terms + [cur])
            terms, cur = [], ""
            continue
        cur += tok
    return args + [terms + [cur]]


@pytest.mark.parametrize("name", ["crank_rocker", "slider_crank_offset", "watt_sixbar"])
def test_an_inner_sum_is_written_positive_terms_first(name):
    """Inside a product, a fraction, a root or a function too: ``x_C - x_B``, not
    ``-x_B + x_C`` (no sum at any depth starts with a minus and goes on with a plus)."""
    doc = latex_document(derive(load_example(name), forces=True))
    assert r"\operatorname{atan2}{\left(y_{C} - y_{B},x_{C} - x_{B} \right)}" in doc or name != "crank_rocker"
    wrong = []
    for block in re.findall(r"\\begin\{(?:align\*?|equation)\}(.*?)\\end\{", doc, re.S):
        for group in _groups(block):
            for terms in _top_level_terms(group):
                first = terms[0].strip()
                if first.startswith("-") and any(t.startswith("+") for t in terms[1:]):
                    wrong.append(group[:120])
    assert not wrong, wrong[:5]


def test_a_block_of_numbers_wide_on_the_page_is_written_entry_by_entry():
    """``derive --numeric``: a row of a force block such as ``0.0630317380372777 sin(theta)``
    twice is short in source characters but ran 180 pt past the margin typeset; such a block
    is now written entry by entry, as a block of long source rows is."""
    import sympy as sp

    from linkage_sym.symbolic.latex_blocks import block_matrix

    th = sp.Symbol("theta_coupler")
    k = sp.Float("0.0630317380372777")
    wide = sp.Matrix([[0, 0, k * sp.sin(th), -k * sp.cos(th), 0, 0]])
    narrow = sp.Matrix([[0, 0, sp.Symbol("l") * sp.sin(th), -sp.Symbol("l") * sp.cos(th), 0, 0]])

    def namer(e):
        return sp.latex(e)

    assert block_matrix(namer, wide) is None
    assert block_matrix(namer, wide, force=True) is not None
    assert block_matrix(namer, narrow) is not None


def test_the_symbol_table_prints_arrows_and_comparisons_as_math():
    """In LaTeX's default text font ``<`` and ``>`` print as inverted marks (the shaper's
    ``angle of B_slide->D`` read ``B_slide¿D`` in the compiled symbol table): outside
    math, no such character is left in the table's text."""
    doc = latex_document(derive(load_example("shaper")), symbols=True)
    table = doc[doc.index(r"\begin{longtable}"):doc.index(r"\end{longtable}")]
    text = re.sub(r"\$[^$]*\$|\\ensuremath\{[^{}]*\}", "", table)
    assert "<" not in text and ">" not in text
    assert r"B\_slide\ensuremath{\to}D" in table
