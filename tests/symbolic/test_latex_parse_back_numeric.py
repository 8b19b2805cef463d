"""``derive --latex --numeric`` read back: its printed numbers are the scene's, rounded as the
document says (issue 31).

The numeric mode prints the scene's numbers in place of the parameters, each rounded to
``digits`` significant digits (:mod:`linkage_sym.symbolic.numbers`).  As in
``test_latex_parse_back.py`` (whose readers this module uses: the tests' own LaTeX reader, no
SymPy, no code of the printer), each printed position, rate-matrix entry and force equation is
read back, given the numeric solver's coordinates and rates at three steps through the
document's symbol table, and compared with the numeric solver (:func:`linkage_sym.analyze`):

* **in full** (``digits="full"``: the shortest decimal that reads back as the same double)
  within ``1e-12`` of each family's scale: the numbers are the scene's exact doubles;
* **rounded to 6 and to 4 digits** within ``ROUNDING * 10**-digits`` of the scale: each
  number is off by at most half a unit in its last digit (``0.5 * 10**(1 - digits)`` of
  itself), and the equations carry that to their values with a gain of a few units (a dyad's
  root near a dead centre most).  The error is also seen (above ``1e-12``): the numbers
  are rounded, not printed in full;
* every printed number has at most ``digits`` significant digits, and each document says so;
* each number printed rounded is the number printed in full rounded by :mod:`decimal` (its
  exact value correctly rounded, half to even): expression by expression, the two prints have
  the same numbers in the same places.
"""

from __future__ import annotations

import decimal
import re

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import load_example
from linkage_sym.symbolic.latex import latex_document
from linkage_sym.symbolic.latex_notation import Namer
from tests.symbolic.test_latex_parse_back import (Case, _matrix, _numbers, _phi_jacobians,
                                                  _positions, _read_forces, _rows, _vector)

EXAMPLES = ["crank_rocker", "fivebar", "watt_sixbar", "sixbar_class3"]
"""Four-bar, five-bar (its Heron radicand named in full digits), six-bar and a class-III triad;
the slider-crank of ``test_latex_parse_back.py`` is left out: its slide's direction is read
there from the angle parameter that the numeric mode replaces by a number."""
FULL_TOL = 1e-12
ROUNDING = 30.0
"""The largest error of a value read back, over ``10**-digits`` of its scale: each number is
off by at most ``5 * 10**-digits`` of itself (half a unit in its last digit), and the worst
value read moves by less than ``11 * 10**-digits`` (measured at 4 and 6 digits: the four-bar's
positions, its rocker near a dead centre)."""
DIGITS = ("full", 6, 4)


class NumericCase(Case):
    """One example in the numeric mode: the attributes ``test_latex_parse_back``'s readers use."""

    def __init__(self, name, digits):
        self.digits = digits
        super().__init__(name, derive={"symbolic": False}, document={"digits": digits})


_CASES: dict = {}


@pytest.fixture(scope="module", params=[(n, d) for n in EXAMPLES for d in DIGITS],
                ids=lambda p: f"{p[0]}-{p[1]}")
def case(request):
    if request.param not in _CASES:
        _CASES[request.param] = NumericCase(*request.param)
    return _CASES[request.param]


def _tolerance(digits) -> float:
    return FULL_TOL if digits == "full" else ROUNDING * 10.0 ** -digits


def _worst(case) -> dict:
    """The worst difference of each family (positions, rates, forces) from the numeric solver,
    over its scale, at the case's steps."""
    rows = _rows(case.parts["Positions"])
    sigmas = [sym for sym, meaning in case.table if meaning.startswith("assembly mode of group")]
    vel, acc = case.parts["Velocities"], case.parts["Accelerations"]
    dv, da = dict(_rows(vel)), dict(_rows(acc))
    worst = {"positions": 0.0, "rates": 0.0, "forces": 0.0}
    for i in case.steps:
        case.step = i
        values, forces = _numbers(case, i)
        best = min((_positions(case, values, rows, dict(zip(sigmas, signs)))
                    for signs in np.ndindex(*(2,) * len(sigmas))
                    for signs in [[1.0 - 2 * s for s in signs]]), key=lambda t: t[0])
        worst["positions"] = max(worst["positions"], best[0])
        values = best[1]
        _, A_ref, B_ref = _phi_jacobians(case, i)
        A = _matrix(vel, dv, r"\mathbf{A}", values)
        B = _matrix(vel, dv, r"\mathbf{B}", values)
        scale = np.maximum(np.abs(A_ref).max(axis=1, keepdims=True), 1e-300)
        worst["rates"] = max(worst["rates"], float(np.max(np.abs(A - A_ref) / scale)),
                             float(np.max(np.abs(B - B_ref) / np.maximum(scale, 1))))
        xdd = _vector(da, r"\ddot{\mathbf{x}}", values)
        xd = _vector(dv, r"\dot{\mathbf{x}}", values)
        r = _matrix(acc, da, r"\mathbf{r}", values)[:, 0]
        family = np.abs(A).sum(axis=1) * (np.abs(xdd).max() + np.abs(xd).max() ** 2)
        worst["rates"] = max(worst["rates"], float(np.max(np.abs(A @ xdd - r)) / family.max()))
        solved, w, _ = _read_forces(case, i, values, forces)
        assert set(solved) == set(forces)
        worst["forces"] = max(worst["forces"], w)
    return worst


@pytest.mark.slow
def test_the_numeric_document_reads_back_as_the_numeric_solver(case):
    digits = case.digits
    worst = _worst(case)
    tol = _tolerance(digits)
    assert all(w <= tol for w in worst.values()), (case.scene.name, digits, worst, tol)
    if digits != "full":  # the numbers are rounded: the document is not exact
        assert max(worst.values()) > FULL_TOL, (case.scene.name, digits, worst)


SCIENTIFIC = re.compile(r"(\d+(?:\.\d+)?) \\cdot 10\^\{-?\d+\}")


def _significant(doc: str) -> list[str]:
    """The significant digits of every number in the document's equations (``align`` and
    ``equation`` blocks; subscripts and labels, whose digits are names, dropped)."""
    blocks = re.findall(r"\\begin\{(align\*?|equation)\}(.*?)\\end\{\1\}", doc, re.S)
    text = re.sub(r"\\label\{[^}]*\}|_\{[^{}]*\}", "", "\n".join(b for _, b in blocks))
    found = SCIENTIFIC.findall(text) + re.findall(r"(?<![\w.])\d+\.\d+", SCIENTIFIC.sub(" ", text))
    return [f.replace(".", "").lstrip("0").rstrip("0") for f in found]


@pytest.mark.parametrize("digits", [6, 4, 2])
def test_every_printed_number_has_the_digits_the_document_states(digits):
    eqs = linkage_sym.derive(load_example("fivebar"), symbolic=False, forces=True)
    doc = latex_document(eqs, digits=digits)
    assert f"Numbers are rounded to {digits} significant digits." in doc
    found = _significant(doc)
    assert found and max(len(f) for f in found) == digits, sorted(found, key=len)[-3:]


_NUMBERS = re.compile(r"(\d+(?:\.\d+)?) \\cdot 10\^\{(-?\d+)\}|(?<![\w.])(\d+\.\d+)")


def _printed_numbers(tex_text: str) -> list[str]:
    """The numbers of one printed expression, as decimal text (``3.5e-10``)."""
    return [f"{m[0]}e{m[1]}" if m[0] else m[2] for m in _NUMBERS.findall(tex_text)]


def _rounded(text: str, digits: int) -> decimal.Decimal:
    """``text``'s exact value correctly rounded (half to even) to ``digits`` significant digits."""
    ctx = decimal.Context(prec=digits, rounding=decimal.ROUND_HALF_EVEN)
    return ctx.plus(decimal.Decimal(float(text)))


@pytest.mark.parametrize("name", EXAMPLES)
def test_each_rounded_number_is_the_full_number_rounded(name):
    eqs = linkage_sym.derive(load_example(name), symbolic=False, forces=True)
    full = Namer(eqs, "full")
    exprs = [e for _, e in eqs.position_steps] + list(eqs.A) + list(eqs.B) + list(eqs.acc_rhs)
    exprs += [e for block in eqs.readable_force_blocks for M in block[:3] for e in M]
    seen = 0
    for digits in (6, 3):
        nm = Namer(eqs, digits)
        for e in exprs:
            exact, got = _printed_numbers(full(e)), _printed_numbers(nm(e))
            assert len(got) == len(exact), (nm(e), full(e))
            for g, x in zip(got, exact):
                assert decimal.Decimal(x) == decimal.Decimal(repr(float(x)))  # in full: repr
                assert decimal.Decimal(g) == _rounded(x, digits), (g, x, digits)
                seen += 1
    assert seen > 100
