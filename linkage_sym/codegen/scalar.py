"""The generated functions printed as scalar code: one entry per call, for a compiled loop.

The generated functions (:mod:`linkage_sym.codegen.compile`) take lists of arrays and
return a list (:mod:`linkage_sym.codegen.evaluator`).  A compiled loop over designs x
steps (:mod:`linkage_sym.design.numba_sweep`) calls them once per entry with numbers,
so :func:`scalar_function` rewrites a function's syntax tree (no SymPy: the artifact's
text is all there is):

- the unpacking of an argument, ``[l_AB, l_BC] = P``, becomes an indexing, ``l_AB =
  P[0]`` (every argument a one-dimensional array of numbers);
- the returned list is written into an output array ``out`` (one more argument);
- the derivation's helpers, ``_tangent_sqrt(size, f1, ..., fk)`` and
  ``_coordinate_size(v1, ..., vk)``, become calls of scalar helpers of that many
  arguments (:func:`scalar_helpers`: the numeric solver's rule for a rounding-level
  miss of a tangency, entry by entry);
- the terms that depend on the driver values only (``sin(q_A)``: no design parameter,
  no coordinate) and call a function are *hoisted*: read from an argument ``H`` (the
  step's row of a table), which a second function, ``pre_<name>``, fills once per step.
  The loop then computes a crank's sine once per step, as the NumPy backend's
  broadcasting does, and not once per design.

Examples
--------
>>> src = '''def f(X, XD, XDD, Q, QD, QDD, FORCES, P, CX=None, SX=None):
...     [q_A] = Q
...     [l_AB, y_A] = P
...     x0 = l_AB*sin(q_A) + y_A
...     return [q_A, x0]
... '''
>>> s = scalar_function(src, "f")
>>> print(s.source)
def f(X, XD, XDD, Q, QD, QDD, FORCES, P, CX, SX, H, out):
    q_A = Q[0]
    l_AB = P[0]
    y_A = P[1]
    x0 = l_AB * H[0] + y_A
    out[0] = q_A
    out[1] = x0
>>> print(s.pre_source)
def pre_f(Q, QD, QDD, H):
    q_A = Q[0]
    H[0] = sin(q_A)
>>> s.outputs, s.hoisted
(2, 1)
"""

from __future__ import annotations

import ast
from dataclasses import dataclass

__all__ = ["ScalarFunction", "scalar_function", "scalar_helpers", "ScalarPrintError"]

ARGS = ("X", "XD", "XDD", "Q", "QD", "QDD", "FORCES", "P", "CX", "SX")
"""The generated functions' arguments, in order (:mod:`linkage_sym.codegen.evaluator`)."""
STEP_ARGS = ("Q", "QD", "QDD")
"""The arguments that are the same for every design at a step (the drivers')."""
HELPERS = {"_tangent_sqrt": "_tangent_sqrt_{}", "_coordinate_size": "_coordinate_size_{}"}


class ScalarPrintError(ValueError):
    """A generated function this printer cannot write as scalar code (its text is not of
    the form the derivation prints)."""


@dataclass(frozen=True)
class ScalarFunction:
    """A generated function as scalar code.

    Attributes
    ----------
    name : str
    source : str
        ``name(X, XD, XDD, Q, QD, QDD, FORCES, P, CX, SX, H, out)``: every argument a
        one-dimensional array, the outputs written into ``out``.
    pre_source : str
        ``pre_<name>(Q, QD, QDD, H)``: fills ``H`` with the hoisted terms at a step.
    outputs : int
        How many values it writes.
    hoisted : int
        How many terms ``H`` holds.
    arities : dict
        ``{helper: set of argument counts}`` of the derivation's helpers it calls.
    """

    name: str
    source: str
    pre_source: str
    outputs: int
    hoisted: int
    arities: dict


def _names(node) -> set:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)}


def _has_call(node) -> bool:
    return any(isinstance(n, ast.Call) for n in ast.walk(node))


def _index(name, k):
    return ast.Subscript(value=ast.Name(name, ast.Load()), slice=ast.Constant(k), ctx=ast.Load())


class _Hoist(ast.NodeTransformer):
    """Replace the largest terms reading only step names (and globals) that call a
    function by ``H[k]``; remember them in order."""

    def __init__(self, local: set, step: set):
        self.local, self.step, self.terms = local, step, []

    def _step_only(self, node) -> bool:
        return all(n in self.step or n not in self.local for n in _names(node))

    def visit(self, node):
        if isinstance(node, ast.expr) and not isinstance(node, ast.Name) and _has_call(node) \
                and self._step_only(node) and not _is_helper_call(node):
            self.terms.append(node)
            return _index("H", len(self.terms) - 1)
        return self.generic_visit(node)


def _is_helper_call(node) -> bool:
    return isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in HELPERS


class _Helpers(ast.NodeTransformer):
    """``_tangent_sqrt(...)`` -> ``_tangent_sqrt_<k>(...)`` (``k`` arguments)."""

    def __init__(self):
        self.arities: dict = {}

    def visit_Call(self, node):
        self.generic_visit(node)
        if isinstance(node.func, ast.Name) and node.func.id in HELPERS:
            k = len(node.args)
            self.arities.setdefault(node.func.id, set()).add(k)
            node.func = ast.Name(HELPERS[node.func.id].format(k), ast.Load())
        return node


def _function(source: str, name: str) -> ast.FunctionDef:
    tree = ast.parse(source)
    fn = next((s for s in tree.body if isinstance(s, ast.FunctionDef) and s.name == name), None)
    if fn is None:
        raise ScalarPrintError(f"the generated source defines no function {name!r}")
    return fn


def _unpack(stmt):
    """``(targets, argument)`` of ``[a, b] = ARG``, else None."""
    if (isinstance(stmt, ast.Assign) and len(stmt.targets) == 1
            and isinstance(stmt.targets[0], (ast.List, ast.Tuple))
            and isinstance(stmt.value, ast.Name) and stmt.value.id in ARGS
            and all(isinstance(t, ast.Name) for t in stmt.targets[0].elts)):
        return [t.id for t in stmt.targets[0].elts], stmt.value.id
    return None


def scalar_function(source: str, name: str) -> ScalarFunction:
    """The generated function ``name`` of ``source`` as scalar code (see the module
    docstring).

    Raises
    ------
    ScalarPrintError
        A statement the derivation does not print (anything but argument unpackings,
        assignments of one name, and one returned list at the end).
    """
    fn = _function(source, name)
    body = [s for s in fn.body if not (isinstance(s, ast.Expr) and isinstance(s.value, ast.Constant))]
    local = set()
    for s in body:
        got = _unpack(s)
        if got is not None:
            local.update(got[0])
        elif isinstance(s, ast.Assign) and len(s.targets) == 1 and isinstance(s.targets[0], ast.Name):
            local.add(s.targets[0].id)
    step: set = set()
    hoist = _Hoist(local, step)
    helpers = _Helpers()
    main, pre = [], []
    outputs = None
    for s in body:
        got = _unpack(s)
        if got is not None:
            targets, arg = got
            lines = [ast.Assign([ast.Name(t, ast.Store())], _index(arg, k)) for k, t in enumerate(targets)]
            main += lines
            if arg in STEP_ARGS:
                step.update(targets)
                pre += lines
            continue
        if isinstance(s, ast.Assign) and len(s.targets) == 1 and isinstance(s.targets[0], ast.Name):
            first = len(hoist.terms)
            value = hoist.visit(s.value)
            pre += _stores(hoist.terms, first)
            if hoist._step_only(s.value):
                step.add(s.targets[0].id)
                pre.append(ast.Assign([ast.Name(s.targets[0].id, ast.Store())], s.value))
            main.append(ast.Assign([ast.Name(s.targets[0].id, ast.Store())], helpers.visit(value)))
            continue
        if isinstance(s, ast.Return) and isinstance(s.value, (ast.List, ast.Tuple)) and s is body[-1]:
            outputs = len(s.value.elts)
            for k, e in enumerate(s.value.elts):
                first = len(hoist.terms)
                value = hoist.visit(e)
                pre += _stores(hoist.terms, first)
                target = ast.Subscript(ast.Name("out", ast.Load()), ast.Constant(k), ast.Store())
                main.append(ast.Assign([target], helpers.visit(value)))
            continue
        raise ScalarPrintError(f"{name}: a statement the derivation does not print: "
                               f"{ast.unparse(s)[:80]!r}")
    if outputs is None:
        raise ScalarPrintError(f"{name}: no returned list of outputs")
    args = ", ".join(ARGS + ("H", "out"))
    text = f"def {name}({args}):\n" + "".join(f"    {_text(s)}\n" for s in main)
    pre_text = (f"def pre_{name}(Q, QD, QDD, H):\n"
                + ("".join(f"    {_text(s)}\n" for s in pre) if pre else "    pass\n"))
    return ScalarFunction(name, text.rstrip("\n"), pre_text.rstrip("\n"), outputs,
                          len(hoist.terms), helpers.arities)


def _text(stmt) -> str:
    return ast.unparse(ast.fix_missing_locations(ast.Module([stmt], [])))


def _stores(terms, first) -> list:
    """``H[k] = term`` for the terms hoisted from ``first`` on (the helpers' calls inside
    them renamed as in the main function)."""
    helpers = _Helpers()
    return [ast.Assign([ast.Subscript(ast.Name("H", ast.Load()), ast.Constant(k), ast.Store())],
                       helpers.visit(ast.fix_missing_locations(t)))
            for k, t in enumerate(terms) if k >= first]


def scalar_helpers(arities: dict) -> str:
    """Source of the scalar helpers of ``arities`` (``{helper: argument counts}``):
    ``_coordinate_size_<k>``, the largest magnitude of its arguments, and
    ``_tangent_sqrt_<k>(size, f1, ...)``, the square root of the product of the factors
    with a product below zero taken as a tangency (0) when its smallest factor is above
    ``-TANGENT_ULPS * eps * size``, else NaN
    (:func:`~linkage_sym.numeric.kinematics.loci.clamp_tangent`, entry by entry; NaN
    propagates through the largest and the smallest, as NumPy's ``maximum`` and
    ``minimum``).
    The module's namespace must define ``TANGENT_ULPS``, ``EPS``, ``sqrt`` and ``nan``."""
    out = []
    for k in sorted(arities.get("_coordinate_size", ())):
        args = ", ".join(f"v{i}" for i in range(k))
        body = "    m = 0.0\n" + "".join(f"    a = abs(v{i})\n    if a > m or a != a:\n"
                                         "        m = a\n" for i in range(k))
        out.append(f"def _coordinate_size_{k}({args}):\n{body}    return m\n")
    for k in sorted(arities.get("_tangent_sqrt", ())):
        f = [f"f{i}" for i in range(k - 1)]
        worst = "".join(f"        if {v} < w or {v} != {v}:\n            w = {v}\n" for v in f[1:])
        out.append(f"def _tangent_sqrt_{k}(size, {', '.join(f)}):\n"
                   f"    p = {' * '.join(f)}\n"
                   "    if p < 0.0:\n"
                   f"        w = {f[0]}\n{worst}"
                   "        p = 0.0 if w >= -(TANGENT_ULPS * EPS * size) else nan\n"
                   "    return sqrt(p)\n")
    return "\n".join(out)
