"""``derive --markdown``: the derived equations as Markdown with MathJax math.

Every derivable shipped example's page parses as CommonMark with dollar math (markdown-it-py
and the ``dollarmath`` plugin MyST uses), each of its math blocks converts to MathML
(latex2mathml, an independent reader of the LaTeX), no LaTeX text markup is left outside
math, and each section holds the same equations as the LaTeX output's (the same displays and
the same rows).
"""

from __future__ import annotations

import re

import pytest
from latex2mathml.converter import convert
from markdown_it import MarkdownIt
from mdit_py_plugins.dollarmath import dollarmath_plugin

from linkage_sym.cli import main
from linkage_sym.examples import example_path, load_example
from linkage_sym.symbolic import derive
from linkage_sym.symbolic.latex import latex_document
from linkage_sym.symbolic.markdown import markdown_document, markdown_text
from tests.support.example_sets import symbolic_examples
from tests.support.marks import fast_cases

PARSER = MarkdownIt("commonmark").enable("table").use(dollarmath_plugin)


def latex_sections(tex: str) -> dict[str, str]:
    """The LaTeX text of each ``\\paragraph`` section, by its title (without the period)."""
    parts = re.split(r"^\\paragraph\{(.+?)\.?\}", tex, flags=re.M)
    return dict(zip(parts[1::2], parts[2::2]))


def markdown_sections(md: str) -> dict[str, str]:
    """The Markdown text of each ``##`` section, by its title (the references left out)."""
    parts = re.split(r"^## (.+)$", md, flags=re.M)
    out = dict(zip(parts[1::2], parts[2::2]))
    out.pop("References")
    return out


def latex_counts(tex: str) -> tuple[int, int]:
    """Displays and equation rows (a row: an ``&=``, or a one-line ``equation``)."""
    displays = len(re.findall(r"\\begin\{(?:align\*?|equation)\}", tex))
    return displays, tex.count("&=") + tex.count(r"\begin{equation}")


def markdown_counts(md: str) -> tuple[int, int]:
    blocks = re.findall(r"^\$\$\n(.*?)\n\$\$$", md, flags=re.M | re.S)
    return len(blocks), md.count("&=") + sum(r"\begin{aligned}" not in b for b in blocks)


@pytest.mark.parametrize("name", fast_cases(symbolic_examples(), {"crank_rocker", "sixbar_class3"}))
def test_the_markdown_parses_converts_and_holds_the_latex_equations(name):
    eqs = derive(load_example(name))
    md, tex = markdown_document(eqs, symbols=True), latex_document(eqs, symbols=True)
    tokens = PARSER.parse(md)
    blocks = [t.content for t in tokens if t.type == "math_block"]
    assert len(blocks) == md.count("$$") // 2 > 0
    for block in blocks:
        convert(block)  # raises on LaTeX it cannot read
    for t in tokens:
        for child in t.children or []:
            if child.type == "math_inline":
                convert(child.content)
    text = re.sub(r"\$\$.*?\$\$", "", md, flags=re.S)
    text = re.sub(r"(?<!\\)\$.*?(?<!\\)\$", "", text)
    assert not re.findall(r"\\[A-Za-z]+", text), "LaTeX markup outside math"
    ltx, mds = latex_sections(tex), markdown_sections(md)
    assert list(ltx) == list(mds)
    for section in ltx:
        assert latex_counts(ltx[section]) == markdown_counts(mds[section]), section
    assert md.startswith(f"# Equations of the mechanism `{eqs.scene.name}`\n")


def test_the_running_text_becomes_commonmark():
    assert markdown_text(r"\emph{Kinematic} chapter~3, linkage\_sym, \texttt{a\_b}, "
                         r"N\,m, 100\% $x~y$") == r"*Kinematic* chapter 3, linkage\_sym, `a_b`, N m, 100% $x~y$"


def test_cli_derive_markdown_and_its_refusals(tmp_path, capsys):
    scene = str(example_path("crank_rocker"))
    out = tmp_path / "eqs.md"
    assert main(["derive", scene, "--markdown", "--symbols", "-o", str(out)]) == 0
    assert out.read_text() == markdown_document(derive(load_example("crank_rocker")), symbols=True)
    capsys.readouterr()
    assert main(["derive", scene, "--latex", "--markdown"]) == 2
    err = capsys.readouterr().err
    assert "--latex and --markdown" in err and "give one of them" in err
    assert main(["derive", scene, "--markdown", "--standalone"]) == 2
    assert "--standalone" in capsys.readouterr().err


def test_an_arrow_in_the_symbol_table_is_an_arrow():
    """The LaTeX prints ``->`` of a parameter's meaning as math (its text font has no
    ``>``); the Markdown as the character, with no LaTeX command left in its text."""
    md = markdown_document(derive(load_example("shaper")), symbols=True)
    assert "B\\_slide\u2192D" in md
    assert "ensuremath" not in md
