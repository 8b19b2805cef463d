"""The code printers behind :func:`linkage_sym.codegen.compile.generate`.

Run also under the oldest supported SymPy (``.ci/run``): the printers' settings differ
between SymPy versions, and a setting one version lacks is an error at construction.
"""

from __future__ import annotations

import pytest
import sympy as sp

from linkage_sym.codegen.compile import ARGS, generate


def _args(*symbols):
    return [list(symbols)] + [[] for _ in ARGS[1:]]


def test_javascript_refuses_a_function_it_has_no_form_for():
    x = sp.Symbol("x")
    with pytest.raises(ValueError, match="no JavaScript form for"):
        generate("f", _args(x), [sp.Function("mystery")(x)], "doc", printer="javascript")


def test_javascript_prints_what_it_has_a_form_for():
    x = sp.Symbol("x")
    src = generate("f", _args(x), [sp.atan2(sp.sin(x), sp.cos(x)) + sp.sqrt(x)], "doc",
                   printer="javascript")
    assert "Math.atan2" in src and "Math.sqrt" in src
    assert "Not supported" not in src
