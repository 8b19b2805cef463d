"""One design at one step as the NumPy backend evaluates it, and the pieces of the numba
backend's loops, printed per artifact.

:func:`entry_source` writes, for one artifact and one set of metrics, the function that
evaluates one entry (design, step) as :meth:`linkage_sym.design.evaluate.Model.solve` and
the metrics do with arrays -- the angles' cosines and sines from the closed step's
directions (:func:`unit_direction`, the NumPy backend's
:func:`~linkage_sym.codegen.evaluator.unit_direction` entry by entry), the rate matrix
``A`` and ``B qd`` (the generated ``rates``), the singularity screen (each group block's
Hadamard ratio against the screen, :meth:`~linkage_sym.codegen.blocks.BlockSystem.below`,
then the dimensionless condition number where it flags, :func:`singular`), the block
lower-triangular solve of the output's rate along the steps (Cramer's rule, as
:meth:`~linkage_sym.codegen.blocks.BlockSystem.solve`) and each RRR dyad's transmission
ratio (:meth:`~linkage_sym.design.metrics.MetricPlan._transmission`), in the same
formulas and order of operations.  The block loop (:mod:`linkage_sym.design.numba_block`)
calls it for the entries its own branch-free arithmetic does not decide, and prints its
screen and solve by :func:`screen_lines` and :func:`solve_lines`.  The artifact's layout
(the forms of the directions, the blocks, the pattern of ``A``, the dyads' coordinates)
is written into the code as constants, so that it has no loop over the layout and no
branch on it.

This module's own helpers are compiled when it is imported: it imports numba.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["entry_source", "fmax", "fmax_select", "position_lines", "screen_lines", "singular", "solve_lines", "unit_direction"]

_JIT = numba.njit(error_model="numpy")


@_JIT
def unit_direction(Y, X, cr, sr):
    """Cosine and sine of ``atan2(Y, X) + r`` from ``Y``, ``X``, ``cos r``, ``sin r``."""
    half = sr == 0.0 and abs(cr) == 1.0
    sign = cr if half else 1.0
    h = X * X + Y * Y
    if h == 0.0 or h == math.inf:
        a = math.atan2(Y, X)
        c, s = sign * math.cos(a), sign * math.sin(a)
    else:
        h = sign / math.sqrt(h)
        c, s = X * h, Y * h
    if not half:
        c, s = c * cr - s * sr, s * cr + c * sr
    return c, s


@_JIT
def fmax(a, b):
    """NumPy's ``fmax`` of two numbers (a NaN loses)."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a >= b else b


@numba.njit(error_model="numpy", inline="always")
def fmax_select(a, b):
    """NumPy's ``fmax`` of two numbers (a NaN loses) as selections, no branch."""
    return b if a != a else (a if (b != b) | (a >= b) else b)


@_JIT
def singular(rout, pattern, m, L, rows_length, cols_length, cond_max):
    """Whether the dimensionless condition number of ``A`` (the entries ``rout`` at
    ``pattern``; size ``L``) is above ``cond_max`` or not a number."""
    As = np.zeros((m, m))
    for p in range(pattern.shape[0]):
        i, j = pattern[p, 0], pattern[p, 1]
        v = rout[p]
        if rows_length[i]:
            v = v * (1.0 / L)
        if cols_length[j]:
            v = v * L
        As[i, j] = v
    for i in range(m):
        for j in range(m):
            if not np.isfinite(As[i, j]):
                return True
    _, s, _ = np.linalg.svd(As)
    return not s[0] / s[m - 1] <= cond_max


def _entry(pattern, i, j):
    """The expression of ``A[i, j]``: a local of the rates' outputs, or a structural 0."""
    return f"a{i}_{j}" if (i, j) in pattern else "0.0"


def screen_lines(blocks, pattern, fmax) -> list:
    """``flag = ...`` of every block of 2 or 3 coordinates (``BlockSystem.below``), the
    larger of two numbers by the function named ``fmax``."""
    out = ["flag = False"]
    for r0, _, c0, c1 in blocks:
        k = c1 - c0
        g = [[_entry(pattern, r0 + i, c0 + j) for j in range(k)] for i in range(k)]
        if k == 2:
            (a, b), (c, d) = g
            out += [f"det = {a} * {d} - {b} * {c}",
                    f"q0, q1, q2, q3 = {a} * {a}, {b} * {b}, {c} * {c}, {d} * {d}",
                    f"norms = {fmax}((q0 + q1) * (q2 + q3), (q0 + q2) * (q1 + q3))"]
        elif k == 3:
            (a, b, c), (d, e, f), (gg, h, kk) = g
            out += [f"det = {a} * ({e} * {kk} - {f} * {h}) + {b} * ({f} * {gg} - {d} * {kk})"
                    f" + {c} * ({d} * {h} - {e} * {gg})",
                    f"rows = (({a} * {a} + {b} * {b} + {c} * {c}) * ({d} * {d} + {e} * {e} + "
                    f"{f} * {f}) * ({gg} * {gg} + {h} * {h} + {kk} * {kk}))",
                    f"cols = (({a} * {a} + {d} * {d} + {gg} * {gg}) * ({b} * {b} + {e} * {e} + "
                    f"{h} * {h}) * ({c} * {c} + {f} * {f} + {kk} * {kk}))",
                    f"norms = {fmax}(rows, cols)"]
        else:
            continue
        out.append("flag = flag | (det * det < t2 * norms)")
    return out


def solve_lines(blocks, pattern, rhs, x="x") -> list:
    """``<x><c> = ...`` of every coordinate, block by block (``BlockSystem.solve``);
    ``rhs(i)``: the expression of row ``i`` of the right-hand side (``B qd``)."""
    out = []
    for r0, r1, c0, c1 in blocks:
        b = [rhs(r0 + i) for i in range(r1 - r0)]
        for (i, j) in pattern:
            if r0 <= i < r1 and j < c0:
                b[i - r0] = f"({b[i - r0]} - a{i}_{j} * {x}{j})"
        for i, e in enumerate(b):
            out.append(f"b{i} = {e}")
        k = c1 - c0
        g = [[_entry(pattern, r0 + i, c0 + j) for j in range(k)] for i in range(k)]
        if k == 1:
            out.append(f"{x}{c0} = b0 / {g[0][0]}")
        elif k == 2:
            (a, bb), (c, d) = g
            out += [f"det = {a} * {d} - {bb} * {c}",
                    f"{x}{c0} = (b0 * {d} - b1 * {bb}) / det",
                    f"{x}{c0 + 1} = ({a} * b1 - {c} * b0) / det"]
        else:
            (a, bb, c), (d, e, f), (gg, h, kk) = g
            out += [f"co0, co1, co2 = {e} * {kk} - {f} * {h}, {f} * {gg} - {d} * {kk}, "
                    f"{d} * {h} - {e} * {gg}",
                    f"det = {a} * co0 + {bb} * co1 + {c} * co2",
                    f"{x}{c0} = (co0 * b0 + ({c} * {h} - {bb} * {kk}) * b1 + ({bb} * {f} - {c} * {e})"
                    " * b2) / det",
                    f"{x}{c0 + 1} = (co1 * b0 + ({a} * {kk} - {c} * {gg}) * b1 + ({c} * {d} - {a} * "
                    f"{f}) * b2) / det",
                    f"{x}{c0 + 2} = (co2 * b0 + ({bb} * {gg} - {a} * {h}) * b1 + ({a} * {e} - {bb} * "
                    f"{d}) * b2) / det"]
    return out


def position_lines(x, forms, m) -> list:
    """The cosines and sines ``C``, ``S`` from the directions' outputs, and ``valid``
    (``Model._directions_at_steps``)."""
    out, finite, at = [], [], 0
    given = set()
    for c, form in zip(x, forms):
        given.add(c)
        if form == "unit":
            out.append(f"C[{c}], S[{c}] = dout[{at}], dout[{at + 1}]")
            finite.append(f"C[{c}]")
            at += 2
        elif form == "atan2":
            out.append(f"C[{c}], S[{c}] = unit_direction(dout[{at}], dout[{at + 1}], "
                       f"dout[{at + 2}], dout[{at + 3}])")
            finite.append(f"C[{c}]")
            at += 4
        else:
            out.append(f"C[{c}], S[{c}] = nan, nan")
            finite.append(f"dout[{at}]")
            at += 1
    out += [f"C[{c}], S[{c}] = nan, nan" for c in range(m) if c not in given]
    out.append("valid = " + (" and ".join(f"np.isfinite({v})" for v in finite) or "True"))
    return out


def entry_source(directions, rates, x, forms, blocks, pattern, m, dyads, col) -> str:
    """Source of ``entry(P, Qt, QD, QDD, Hdt, Hrt, cc, sc, d, Ld, screen, rows_length,
    cols_length, pattern, tr, dout, rout, C, S, nowhere) -> (status, rate)``: one design
    (parameters ``P``) at one step, as the NumPy backend evaluates it.

    ``directions``, ``rates``: the compiled scalar functions' names; ``x``, ``forms``:
    the closed step's coordinates and forms; ``blocks``, ``pattern``: the artifact's;
    ``dyads``: ``(ia, ib)`` of each RRR dyad whose transmission is measured; ``col``:
    the coordinate whose rate along the steps is returned (None: no rate solved).
    ``status``: 0 no positions, 1 positions but singular, 3 ok; with positions, ``tr``
    holds each dyad's transmission ratio; ``rate``: the rate of ``col`` when ok.  The
    block loop (:mod:`linkage_sym.design.numba_block`) calls it where its own arithmetic
    does not decide: a direction of length 0 or infinite, a step the screen flags."""
    pattern = [tuple(p) for p in pattern]
    lines = [f"{directions}(nowhere, nowhere, nowhere, Qt, QD, QDD, nowhere, P, nowhere, "
             "nowhere, Hdt, dout)"]
    lines += position_lines(x, forms, m)
    lines += ["if not valid:", "    return 0, 0.0"]
    for k, (ia, ib) in enumerate(dyads):
        lines += [f"cd = C[{ib}] * C[{ia}] + S[{ib}] * S[{ia}]",
                  f"sd = S[{ib}] * C[{ia}] - C[{ib}] * S[{ia}]",
                  f"tr[{k}] = abs((sd * cc[{k}, d] + cd * sc[{k}, d]) / (cd * cc[{k}, d] - sd * sc[{k}, d]))"]
    lines.append(f"{rates}(nowhere, nowhere, nowhere, Qt, QD, QDD, nowhere, P, C, S, Hrt, rout)")
    lines += [f"a{i}_{j} = rout[{p}]" for p, (i, j) in enumerate(pattern)]
    lines += screen_lines(blocks, pattern, "fmax")
    lines += [f"if flag and singular(rout, pattern, {m}, Ld, rows_length, cols_length, cond_max):",
              "    return 1, 0.0"]
    if col is None:
        lines.append("return 3, 0.0")
    else:
        lines += solve_lines(blocks, pattern, lambda i: f"rout[{len(pattern) + i}]")
        lines.append(f"return 3, x{col}")
    head = ["def entry(P, Qt, QD, QDD, Hdt, Hrt, cc, sc, d, Ld, screen, rows_length, cols_length,",
            "          pattern, tr, dout, rout, C, S, nowhere):",
            "    t2, cond_max = screen[0], screen[1]"]
    return "\n".join(head + [f"    {s}" for s in lines]) + "\n"
