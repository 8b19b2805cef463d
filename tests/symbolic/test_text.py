"""``linkage-sym derive`` without ``--latex``: the named positions, wrapped to the terminal.

Issue 31: the coupler angle printed as one line of about 3000 characters with the same
square root about ten times.  The text now names the intermediates the LaTeX names (the
outer joints, ``d``, ``a``, ``h``, the inner joint, then the angles) and keeps every line
within the terminal's width (``COLUMNS``).
"""

from __future__ import annotations

import pytest
import sympy as sp

from linkage_sym.cli import main
from linkage_sym.examples import example_path

NAMED = (  # the four-bar's dyad, step by step, as a reader writes it (SymPy's text)
    "dx_2 = -x_B + x_D",
    "d_2 = sqrt(dx_2**2 + dy_2**2)",
    "a_2 = (d_2**2 + l_BC**2 - l_CD**2)/(2*d_2)",
    "x_C = x_B + (a_2*dx_2 - dy_2*h_2*sigma_2)/d_2",
    "theta_coupler = atan2(-y_B + y_C, -x_B + x_C)",
)


def _derive(capsys, name, *extra) -> str:
    assert main(["derive", str(example_path(name)), *extra]) == 0
    return capsys.readouterr().out


@pytest.mark.parametrize("columns", [60, 80, 132])
def test_no_line_is_wider_than_the_terminal(monkeypatch, capsys, columns):
    monkeypatch.setenv("COLUMNS", str(columns))
    text = _derive(capsys, "crank_rocker")
    lines = text.splitlines()
    assert max(len(ln) for ln in lines) <= columns, max(lines, key=len)
    assert len(lines) < 300  # the named steps, not the nested closed forms, wrapped


def test_the_positions_are_the_named_steps(monkeypatch, capsys):
    monkeypatch.setenv("COLUMNS", "200")
    text = _derive(capsys, "crank_rocker")
    for line in NAMED:
        assert line in text.splitlines(), line
    # the half-chord's square root is written once, in h_2, not in every angle
    assert text.count("sqrt((-d_2") == 1
    assert "A = [" in text and "B = [" in text


def test_a_wrapped_equation_reads_back_as_the_same_expression(monkeypatch, capsys):
    """Joining a wrapped row's continuation lines gives SymPy's text of the expression back."""
    monkeypatch.setenv("COLUMNS", "50")
    lines = _derive(capsys, "crank_rocker").splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith("h_2 = "))
    joined = lines[i]
    for ln in lines[i + 1:]:
        if not ln.startswith("    "):
            break
        joined += " " + ln.strip()
    lhs, rhs = joined.split(" = ", 1)
    d, l1, l2 = sp.symbols("d_2 l_BC l_CD", real=True)
    want = sp.sqrt((-d + l1 + l2) * (d - l1 + l2) * (d + l1 - l2) * (d + l1 + l2)) / (2 * d)
    got = sp.sympify(rhs, locals={"d_2": d, "l_BC": l1, "l_CD": l2})
    assert lhs == "h_2" and sp.simplify(got - want) == 0
