"""The numbers of ``derive --numeric`` (:mod:`linkage_sym.symbolic.numbers`): correctly rounded
to the significant digits asked for, or in full, and every output says which (issue 31).

The reference of the rounding is :mod:`decimal`: a double's exact value (``Decimal(x)`` holds
every binary digit) rounded half to even in a context of ``digits`` digits; it shares no code
with :func:`float_text`, which takes Python's shortest ``repr`` and ``format``.
"""

from __future__ import annotations

import decimal
import re

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.examples import example_path, load_example
from linkage_sym.symbolic.latex import latex_document
from linkage_sym.symbolic.markdown import markdown_document
from linkage_sym.symbolic.numbers import DIGITS, FULL, MAX_DIGITS, check_digits, float_text
from linkage_sym.symbolic.text import plain_text

DOUBLES = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e300, max_value=1e300)


def _exact_rounded(x: float, digits: int) -> decimal.Decimal:
    return decimal.Context(prec=digits, rounding=decimal.ROUND_HALF_EVEN).plus(decimal.Decimal(x))


@settings(max_examples=400, deadline=None)
@given(x=DOUBLES, digits=st.integers(1, 17))
def test_a_number_is_its_exact_value_correctly_rounded(x, digits):
    text = float_text(sp.Float(x), digits)
    assert decimal.Decimal(text) == _exact_rounded(x, digits), (x, digits, text)
    mant = re.sub(r"e-?\d+$", "", text).lstrip("-").replace(".", "").lstrip("0").rstrip("0")
    assert len(mant) <= digits


@pytest.mark.parametrize("x", [-17.35, 9.515, 222.5, 0.55, 2.5, 0.125, -4618.515])
def test_near_ties_round_to_the_nearest(x):
    """Decimal ties that the double misses (``-17.35`` is ``-17.350000000000001...``) and exact
    binary ties (``2.5``: to even); an intermediate binary rounding (mpmath's ``to_str``)
    got the first kind wrong."""
    for digits in (1, 2, 3, 6):
        assert decimal.Decimal(float_text(sp.Float(x), digits)) == _exact_rounded(x, digits)


@settings(max_examples=300, deadline=None)
@given(x=DOUBLES)
def test_in_full_a_number_reads_back_as_the_same_double(x):
    text = float_text(sp.Float(x), FULL)
    assert float(text) == x
    assert decimal.Decimal(text) == decimal.Decimal(repr(x))  # and as short as Python's repr


def test_the_digits_asked_for_are_checked():
    assert check_digits(1) == 1 and check_digits(17) == 17 and check_digits(FULL) == FULL
    for bad in (0, 18, -3, 2.5, True, "6", None):
        with pytest.raises(ValueError, match="significant digits") as err:
            check_digits(bad)
        assert "--" not in str(err.value)  # a library message: no option names


def test_every_output_says_how_its_numbers_are_printed():
    scene = load_example("crank_rocker")
    numeric = linkage_sym.derive(scene, symbolic=False)
    symbolic = linkage_sym.derive(scene)
    for digits, note in ((DIGITS, f"Numbers are rounded to {DIGITS} significant digits."),
                         (3, "Numbers are rounded to 3 significant digits."),
                         (FULL, "Numbers are printed in full")):
        for doc in (latex_document(numeric, digits=digits), markdown_document(numeric, digits=digits),
                    plain_text(numeric, digits=digits)):
            assert note in doc
    for doc in (latex_document(symbolic), markdown_document(symbolic), plain_text(symbolic)):
        assert "Numbers are" not in doc  # no number to round


def test_the_text_rounds_its_numbers():
    eqs = linkage_sym.derive(load_example("fivebar"), symbolic=False)
    full, three = plain_text(eqs, digits=FULL), plain_text(eqs, digits=3)
    assert "0.24000000003338678" in full and "0.24000000003338678" not in three
    assert "3.33e-10" in three and "3.333333331578814e-10" in full


def test_a_root_too_wide_for_a_row_has_its_radicand_named():
    """In full digits the five-bar's Heron root holds four 17-digit numbers: its radicand
    ``H_{3}`` is a row of its own, broken between its factors; rounded, it fits a row."""
    eqs = linkage_sym.derive(load_example("fivebar"), symbolic=False)
    full, rounded = latex_document(eqs, digits=FULL), latex_document(eqs, digits=DIGITS)
    assert "its angles. A square root too wide for a row has its radicand named as a row of its " \
           "own ($H_{3}$ of $h_{3}$):" in full
    assert re.search(r"^H_\{3\} &= .*\n&\\quad \\cdot ", full, re.M)
    assert r"h_{3} &= \frac{\sqrt{H_{3}}}{2 d_{3}}" in full
    assert "H_{3}" not in rounded and r"h_{3} &= \frac{\sqrt{\left(0.24 - d_{3}\right)" in rounded


def test_the_command_line_takes_digits(tmp_path, capsys):
    scene = str(example_path("fivebar"))
    out = tmp_path / "eqs.md"
    assert main(["derive", scene, "--markdown", "--numeric", "--digits", "full", "-o", str(out)]) == 0
    assert "0.24000000003338678" in out.read_text() and "printed in full" in out.read_text()
    assert main(["derive", scene, "--numeric", "--digits", "2", "-o", str(out)]) == 0
    assert "rounded to 2 significant digits" in out.read_text()
    capsys.readouterr()
    assert main(["derive", scene, "--digits", "4"]) == 2
    assert "--digits rounds the numbers that --numeric puts in" in capsys.readouterr().err
    for bad in ("0", "18", "six"):
        with pytest.raises(SystemExit) as err:
            main(["derive", scene, "--numeric", "--digits", bad])
        assert err.value.code == 2
        assert "argument --digits: a whole number from 1 to 17, or 'full'" in capsys.readouterr().err


def test_the_help_states_the_library_numbers(capsys):
    """The command line writes them out (importing them would load SymPy at start-up)."""
    with pytest.raises(SystemExit):
        main(["derive", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert f"(1 to {MAX_DIGITS}; default {DIGITS}, and the output says so), or '{FULL}'" in text
