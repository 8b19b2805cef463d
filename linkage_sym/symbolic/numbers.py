"""How the derived equations print numbers: to a number of significant digits, or in full.

``derive(scene, symbolic=False)`` puts the scene's numbers in place of the parameter symbols
(``derive --numeric``); SymPy prints them with all 15 digits of a double, so a dyad's Heron row
(four such numbers under one square root) runs past a page's margin.  The printers of
:mod:`linkage_sym.symbolic.latex`, :mod:`~linkage_sym.symbolic.markdown` and
:mod:`~linkage_sym.symbolic.text` take ``digits``: each number correctly rounded to that many
significant digits (default :data:`DIGITS`, and the documents say so: :func:`rounding_note`),
or ``"full"`` (:data:`FULL`): the shortest decimal that reads back as the same double
(Python's ``repr``), the exact value of the scene's number.

Examples
--------
>>> import sympy as sp
>>> x = sp.Float(0.111539469379817)
>>> float_text(x, 3), float_text(x, FULL), float_text(sp.Float(3.33333333157881e-10), 3)
('0.112', '0.111539469379817', '3.33e-10')
>>> float_text(sp.Float(0.1), 17), float_text(sp.Float(0.1), FULL)
('0.10000000000000001', '0.1')
"""

from __future__ import annotations

from decimal import ROUND_HALF_EVEN, Context, Decimal

__all__ = ["DIGITS", "FULL", "MAX_DIGITS", "check_digits", "float_text", "rounding_note"]

DIGITS = 6
"""The significant digits of a printed number by default: a publication's precision, far
finer than a drawing or a machined part (a 1 m link to a micrometre)."""
FULL = "full"
"""``digits`` for the exact numbers: the shortest decimal that reads back as the same double."""
MAX_DIGITS = 17
"""The most significant digits asked for: 17 read back as the same double, every double."""


def check_digits(digits) -> int | str:
    """``digits`` if it is :data:`FULL` or a whole number from 1 to :data:`MAX_DIGITS`.

    Raises
    ------
    ValueError
        For anything else.
    """
    if digits == FULL:
        return FULL
    if isinstance(digits, bool) or not isinstance(digits, int) or not 1 <= digits <= MAX_DIGITS:
        raise ValueError(f"the significant digits of printed numbers must be a whole number from "
                         f"1 to {MAX_DIGITS}, or {FULL!r} for the exact numbers; got {digits!r}")
    return digits


def _digits(x, digits) -> tuple[str, str, int]:
    """``(sign, significant digits, decimal exponent of the first)`` of the ``Float`` ``x``,
    correctly rounded (half to even) to ``digits`` significant digits, or the shortest that
    read back as the same double (:data:`FULL`)."""
    if x._prec <= 53:  # a double: Python's own conversions, correctly rounded
        v = float(x)
        text = repr(v) if digits == FULL else f"{v:.{digits - 1}e}"
        d = Decimal(text)
    else:  # finer than a double: all its digits, or rounded from its exact value
        from mpmath.libmp import prec_to_dps

        sign, man, exp, _ = x._mpf_  # the value (-1)**sign * man * 2**exp, exactly
        p, q = (man << exp, 1) if exp >= 0 else (man, 1 << -exp)
        prec = prec_to_dps(x._prec) if digits == FULL else digits
        d = Context(prec=prec, rounding=ROUND_HALF_EVEN).divide(Decimal(-p if sign else p),
                                                                Decimal(q))
    sign, ds, exp = d.as_tuple()
    significant = "".join(map(str, ds)).lstrip("0")
    if not significant:
        return "", "0", 0
    return "-" if sign else "", significant.rstrip("0"), exp + len(significant) - 1


def float_text(x, digits) -> str:
    """The SymPy ``Float`` ``x`` as decimal text, correctly rounded to ``digits`` significant
    digits or in full (:data:`FULL`), trailing zeros dropped: fixed-point from 1e-4 up to
    ``10**digits`` (``10**16`` in full), ``3.5e-10`` beyond."""
    sign, ds, e = _digits(x, digits)
    if e < -4 or e >= (16 if digits == FULL else digits):
        return f"{sign}{ds[0]}{'.' + ds[1:] if len(ds) > 1 else ''}e{e}"
    if e < 0:
        return f"{sign}0.{'0' * (-e - 1)}{ds}"
    whole, frac = ds[:e + 1].ljust(e + 1, "0"), ds[e + 1:]
    return f"{sign}{whole}.{frac or '0'}"


def rounding_note(digits) -> str:
    """The sentence a document gives its numbers' rounding (in plain words, no markup)."""
    if digits == FULL:
        return ("Numbers are printed in full: each the shortest decimal that reads back as the "
                "scene's double.")
    return f"Numbers are rounded to {digits} significant digits."
