"""A function of ``x`` written as text, evaluated without ``eval``.

The text is parsed by Python's :mod:`ast` and only these nodes are accepted:
numbers, the name ``x``, the constants ``pi`` and ``e``, the operators
``+ - * / **`` and unary ``+ -``, and calls of the NumPy functions in
:data:`FUNCTIONS` with one argument.  Anything else (attributes, other names,
subscripts, keywords, lambdas ...) is refused before anything is evaluated.

NumPy only (import contract in ``pyproject.toml``).

Examples
--------
>>> f = parse("log10(x) + 2*x**2")
>>> float(f(np.array([10.0]))[0])
201.0
>>> parse("__import__('os')")
Traceback (most recent call last):
...
linkage_sym.synthesis.common.SynthesisError: function: '__import__' is not one of the allowed functions (abs, arccos, arcsin, arctan, cos, cosh, exp, log, log10, log2, sin, sinh, sqrt, tan, tanh)
"""

from __future__ import annotations

import ast
import math
import operator

import numpy as np

from linkage_sym.synthesis.common import SynthesisError

FUNCTIONS = {n: getattr(np, n) for n in ("abs", "arccos", "arcsin", "arctan", "cos", "cosh", "exp",
                                         "log", "log10", "log2", "sin", "sinh", "sqrt", "tan",
                                         "tanh")}
"""The functions an expression may call (NumPy's, elementwise)."""

CONSTANTS = {"pi": math.pi, "e": math.e}

_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow}
_UNARY = {ast.UAdd: operator.pos, ast.USub: operator.neg}

MAX_TEXT = 1000
"""Longest expression accepted (characters)."""


def _check(node, field):
    """Refuse any node outside the small grammar (recursively)."""
    if isinstance(node, ast.Expression):
        return _check(node.body, field)
    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        return None
    if isinstance(node, ast.Name):
        if node.id != "x" and node.id not in CONSTANTS:
            raise SynthesisError(field, f"unknown name {node.id!r}: only x, pi and e")
        return None
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        _check(node.left, field)
        return _check(node.right, field)
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        return _check(node.operand, field)
    if isinstance(node, ast.Call):
        name = node.func.id if isinstance(node.func, ast.Name) else ast.unparse(node.func)
        if name not in FUNCTIONS:
            raise SynthesisError(field, f"{name!r} is not one of the allowed functions "
                                        f"({', '.join(sorted(FUNCTIONS))})")
        if len(node.args) != 1 or node.keywords:
            raise SynthesisError(field, f"{name}() takes one argument")
        return _check(node.args[0], field)
    raise SynthesisError(field, f"{ast.unparse(node)!r} is not allowed: numbers, x, pi, e, "
                                "+ - * / ** and the allowed functions only")


def _value(node, x):
    if isinstance(node, ast.Constant):
        return float(node.value)
    if isinstance(node, ast.Name):
        return x if node.id == "x" else CONSTANTS[node.id]
    if isinstance(node, ast.BinOp):
        return _BINARY[type(node.op)](_value(node.left, x), _value(node.right, x))
    if isinstance(node, ast.UnaryOp):
        return _UNARY[type(node.op)](_value(node.operand, x))
    return FUNCTIONS[node.func.id](_value(node.args[0], x))


def parse(text: str, field: str = "function"):
    """The function ``f(x)`` (an array in, an array out) of an expression.

    Parameters
    ----------
    text : str
        E.g. ``"log10(x)"``, ``"x**2"``, ``"sin(pi*x/2)"``.
    field : str
        The name a refusal gives.

    Returns
    -------
    callable
        ``f(x)`` on a float array; ``x`` broadcast when the expression
        does not depend on it.

    Raises
    ------
    SynthesisError
        Text that is too long, not an expression, or outside the grammar.
    """
    if not isinstance(text, str) or not text.strip():
        raise SynthesisError(field, f"an expression of x is expected, got {text!r}")
    if len(text) > MAX_TEXT:
        raise SynthesisError(field, f"at most {MAX_TEXT} characters, got {len(text)}")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as err:
        raise SynthesisError(field, f"{text!r} is not an expression: {err.msg}") from None
    _check(tree, field)

    def f(x):
        x = np.asarray(x, dtype=float)
        with np.errstate(all="ignore"):
            return np.broadcast_to(np.asarray(_value(tree.body, x), dtype=float), x.shape).copy()

    return f
