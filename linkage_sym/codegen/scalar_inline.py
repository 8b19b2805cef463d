"""A scalar function's body as statements to paste into a compiled loop (no call, no array).

:func:`inline_lines` takes a function printed by :func:`~linkage_sym.codegen.scalar.scalar_function`
and gives its statements with every local renamed under a prefix, every read of an
argument's entry (``P[3]``, ``H[0]``, ``CX[1]``) replaced by the expression the caller
names for it, and every output ``out[k] = e`` an assignment of a local ``<prefix>out<k>``.
A loop over designs that pastes them evaluates the function in locals only -- no array
written per entry, nothing the compiler must keep in memory -- so that it can vectorise
the loop over designs.

Examples
--------
>>> from linkage_sym.codegen.scalar import scalar_function
>>> src = '''def f(X, XD, XDD, Q, QD, QDD, FORCES, P, CX=None, SX=None):
...     [q_A] = Q
...     [l_AB, y_A] = P
...     x0 = l_AB*sin(q_A) + y_A
...     return [x0, 1]
... '''
>>> s = scalar_function(src, "f")
>>> lines, outs = inline_lines(s, "f_", lambda arg, k: f"{arg}{k}[d]")
>>> print("\\n".join(lines[1:]))
f_l_AB = P0[d]
f_y_A = P1[d]
f_x0 = f_l_AB * H0[d] + f_y_A
f_out0 = f_x0
f_out1 = 1.0
>>> outs
['f_out0', 'f_out1']
"""

from __future__ import annotations

import ast

from linkage_sym.codegen.scalar import ARGS, ScalarFunction, ScalarPrintError

__all__ = ["inline_lines"]

_READ = set(ARGS) | {"H"}


class _Rename(ast.NodeTransformer):
    """Locals under ``prefix``; ``ARG[k]`` by ``reads(ARG, k)``; globals (``sqrt``, the
    helpers, ``nan``) as they are."""

    def __init__(self, local: set, prefix: str, reads):
        self.local, self.prefix, self.reads = local, prefix, reads

    def visit_Name(self, node):
        if node.id in self.local:
            return ast.copy_location(ast.Name(self.prefix + node.id, node.ctx), node)
        return node

    def visit_Subscript(self, node):
        if (isinstance(node.value, ast.Name) and node.value.id in _READ
                and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, int)):
            return ast.parse(f"({self.reads(node.value.id, node.slice.value)})", mode="eval").body
        return self.generic_visit(node)


def _number(value) -> str:
    """The text of ``value``; an integer the derivation prints (``1``, ``-1``) as a float,
    so that every output is a number of one type."""
    try:
        v = ast.literal_eval(value)
    except ValueError:
        return ast.unparse(value)
    return repr(float(v)) if isinstance(v, int) else ast.unparse(value)


def inline_lines(fn: ScalarFunction, prefix: str, reads) -> tuple[list, list]:
    """``(statements, output names)`` of ``fn``'s body pasted into a loop.

    Parameters
    ----------
    fn : ScalarFunction
    prefix : str
        Put before every local's name (and the outputs' ``out<k>``).
    reads : callable
        ``reads(argument, k)``: the expression (text) that stands for ``argument[k]``
        (``argument`` one of the generated functions' arguments, or ``H``, the hoisted
        terms).

    Raises
    ------
    ScalarPrintError
        A statement other than an assignment of one name or of ``out[k]``.
    """
    body = ast.parse(fn.source).body[0].body
    local = {s.targets[0].id for s in body
             if isinstance(s, ast.Assign) and isinstance(s.targets[0], ast.Name)}
    rename = _Rename(local, prefix, reads)
    lines, outs = [], [f"{prefix}out{k}" for k in range(fn.outputs)]
    for s in body:
        if not isinstance(s, ast.Assign) or len(s.targets) != 1:
            raise ScalarPrintError(f"{fn.name}: not an assignment: {ast.unparse(s)[:80]!r}")
        target, value = s.targets[0], rename.visit(s.value)
        if isinstance(target, ast.Name):
            lines.append(f"{prefix}{target.id} = {ast.unparse(value)}")
        elif (isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name)
              and target.value.id == "out" and isinstance(target.slice, ast.Constant)):
            lines.append(f"{outs[target.slice.value]} = {_number(value)}")
        else:
            raise ScalarPrintError(f"{fn.name}: an assignment of {ast.unparse(target)!r}")
    return lines, outs
