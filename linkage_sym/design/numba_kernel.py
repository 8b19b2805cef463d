"""The compiled loop of the numba backend over a chunk's designs x steps, printed per artifact.

:func:`kernel_source` writes, for one artifact and one set of metrics, the loop that
:mod:`linkage_sym.design.numba_sweep` compiles with numba: at every entry it does what
:meth:`linkage_sym.design.evaluate.Model.solve` and the metrics do with arrays -- the
angles' cosines and sines from the closed step's directions (:func:`unit_direction`,
the NumPy backend's :func:`~linkage_sym.codegen.evaluator.unit_direction` entry by
entry), the rate matrix ``A`` and ``B qd`` (the generated ``rates``), the singularity
screen (each group block's Hadamard ratio against the screen,
:meth:`~linkage_sym.codegen.blocks.BlockSystem.below`, then the dimensionless condition
number where it flags, :func:`singular`), the block lower-triangular solve of the
output's rate along the steps (Cramer's rule, as
:meth:`~linkage_sym.codegen.blocks.BlockSystem.solve`), the brackets of its sign changes
(:class:`~linkage_sym.design.limits.Limits`) and each RRR dyad's smallest transmission
ratio (:meth:`~linkage_sym.design.metrics.MetricPlan._transmission`), in the same
formulas and order of operations.  The artifact's layout (the forms of the directions,
the blocks, the pattern of ``A``, the dyads' coordinates) is written into the loop as
constants, so that it has no loop over the layout and no branch on it.

This module's own helpers are compiled when it is imported: it imports numba.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["kernel_source", "singular", "unit_direction"]

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


def _screen_lines(blocks, pattern) -> list:
    """``flag = ...`` of every block of 2 or 3 coordinates (``BlockSystem.below``)."""
    out = ["flag = False"]
    for r0, _, c0, c1 in blocks:
        k = c1 - c0
        g = [[_entry(pattern, r0 + i, c0 + j) for j in range(k)] for i in range(k)]
        if k == 2:
            (a, b), (c, d) = g
            out += [f"det = {a} * {d} - {b} * {c}",
                    f"q0, q1, q2, q3 = {a} * {a}, {b} * {b}, {c} * {c}, {d} * {d}",
                    "norms = fmax((q0 + q1) * (q2 + q3), (q0 + q2) * (q1 + q3))"]
        elif k == 3:
            (a, b, c), (d, e, f), (gg, h, kk) = g
            out += [f"det = {a} * ({e} * {kk} - {f} * {h}) + {b} * ({f} * {gg} - {d} * {kk})"
                    f" + {c} * ({d} * {h} - {e} * {gg})",
                    f"rows = (({a} * {a} + {b} * {b} + {c} * {c}) * ({d} * {d} + {e} * {e} + "
                    f"{f} * {f}) * ({gg} * {gg} + {h} * {h} + {kk} * {kk}))",
                    f"cols = (({a} * {a} + {d} * {d} + {gg} * {gg}) * ({b} * {b} + {e} * {e} + "
                    f"{h} * {h}) * ({c} * {c} + {f} * {f} + {kk} * {kk}))",
                    "norms = fmax(rows, cols)"]
        else:
            continue
        out.append("flag = flag or det * det < t2 * norms")
    return out


def _solve_lines(blocks, pattern, m) -> list:
    """``x<c> = ...`` of every coordinate, block by block (``BlockSystem.solve``)."""
    out = []
    for r0, r1, c0, c1 in blocks:
        b = [f"rout[{len(pattern) + r0 + i}]" for i in range(r1 - r0)]
        for (i, j) in pattern:
            if r0 <= i < r1 and j < c0:
                b[i - r0] = f"({b[i - r0]} - a{i}_{j} * x{j})"
        for i, e in enumerate(b):
            out.append(f"b{i} = {e}")
        k = c1 - c0
        g = [[_entry(pattern, r0 + i, c0 + j) for j in range(k)] for i in range(k)]
        if k == 1:
            out.append(f"x{c0} = b0 / {g[0][0]}")
        elif k == 2:
            (a, bb), (c, d) = g
            out += [f"det = {a} * {d} - {bb} * {c}",
                    f"x{c0} = (b0 * {d} - b1 * {bb}) / det",
                    f"x{c0 + 1} = ({a} * b1 - {c} * b0) / det"]
        else:
            (a, bb, c), (d, e, f), (gg, h, kk) = g
            out += [f"co0, co1, co2 = {e} * {kk} - {f} * {h}, {f} * {gg} - {d} * {kk}, "
                    f"{d} * {h} - {e} * {gg}",
                    f"det = {a} * co0 + {bb} * co1 + {c} * co2",
                    f"x{c0} = (co0 * b0 + ({c} * {h} - {bb} * {kk}) * b1 + ({bb} * {f} - {c} * {e})"
                    " * b2) / det",
                    f"x{c0 + 1} = (co1 * b0 + ({a} * {kk} - {c} * {gg}) * b1 + ({c} * {d} - {a} * "
                    f"{f}) * b2) / det",
                    f"x{c0 + 2} = (co2 * b0 + ({bb} * {gg} - {a} * {h}) * b1 + ({a} * {e} - {bb} * "
                    f"{d}) * b2) / det"]
    return out


def _position_lines(x, forms, m) -> list:
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


def kernel_source(directions, rates, x, forms, blocks, pattern, m, dyads, col) -> str:
    """Source of ``kernel(Pd, Hd, Hr, Q, QD, QDD, assembled, L, cc, sc, screen,
    rows_length, cols_length, pos_ok, ok, tmin, bd, bi, bfa, bfb) -> brackets``.

    ``directions``, ``rates``: the compiled scalar functions' names; ``x``, ``forms``:
    the closed step's coordinates and forms; ``blocks``, ``pattern``: the artifact's;
    ``dyads``: ``(ia, ib)`` of each RRR dyad whose transmission is measured; ``col``:
    the coordinate whose rate along the steps is bracketed (None: no rate solved).
    The loop fills ``pos_ok``, ``ok`` (n, N), ``tmin`` (dyads, n) and the brackets
    (design, step, rate there, rate at the next step) in row-major order as far as
    the arrays hold them, returning how many there are."""
    pattern = [tuple(p) for p in pattern]
    inner = [f"{directions}(nowhere, nowhere, nowhere, Q[t], QD, QDD, nowhere, P, nowhere, "
             "nowhere, Hd[t], dout)"]
    inner += _position_lines(x, forms, m)
    inner += ["pos_ok[d, t] = valid", "if not valid:", "    ok[d, t] = False",
              "    pok = False", "    continue"]
    for k, (ia, ib) in enumerate(dyads):
        inner += [f"cd = C[{ib}] * C[{ia}] + S[{ib}] * S[{ia}]",
                  f"sd = S[{ib}] * C[{ia}] - C[{ib}] * S[{ia}]",
                  f"r = abs((sd * cc[{k}, d] + cd * sc[{k}, d]) / (cd * cc[{k}, d] - sd * sc[{k}, d]))",
                  f"if r < m{k} or m{k} != m{k}:", f"    m{k} = r"]
    inner.append(f"{rates}(nowhere, nowhere, nowhere, Q[t], QD, QDD, nowhere, P, C, S, Hr[t], rout)")
    inner += [f"a{i}_{j} = rout[{p}]" for p, (i, j) in enumerate(pattern)]
    inner += _screen_lines(blocks, pattern)
    inner += ["if flag and singular(rout, pattern, M, L[d], rows_length, cols_length, cond_max):",
              "    ok[d, t] = False", "    pok = False", "    continue", "ok[d, t] = True"]
    if col is not None:
        inner += _solve_lines(blocks, pattern, m)
        inner += [f"r = x{col}",
                  "if pok and ((pr < 0) != (r < 0) or pr == 0 or r == 0):",
                  "    if nb < cap:", "        bd[nb], bi[nb], bfa[nb], bfb[nb] = d, t - 1, pr, r",
                  "    nb += 1",
                  "pr, pok = r, True"]
    dy = range(len(dyads))
    lines = ["def kernel(Pd, Hd, Hr, Q, QD, QDD, assembled, L, cc, sc, screen, rows_length,",
             "           cols_length, pattern, pos_ok, ok, tmin, bd, bi, bfa, bfb):",
             "    n, N = pos_ok.shape", "    t2, cond_max = screen[0], screen[1]",
             "    dout, rout = np.empty(int(screen[2])), np.empty(int(screen[3]))",
             f"    M = {m}", "    nowhere = np.full(M, np.nan)",
             "    C, S = np.empty(M), np.empty(M)", "    nb, cap = 0, bd.shape[0]", "    for d in range(n):",
             "        P = Pd[d]", "        pok, pr = False, 0.0"]
    lines += [f"        m{k} = nan" for k in dy]
    lines += ["        if not assembled[d]:", "            for t in range(N):",
              "                pos_ok[d, t] = False", "                ok[d, t] = False"]
    lines += [f"            tmin[{k}, d] = nan" for k in dy]
    lines += ["            continue", "        for t in range(N):"]
    lines += [f"            {s}" for s in inner]
    lines += [f"        tmin[{k}, d] = m{k}" for k in dy]
    lines.append("    return nb")
    return "\n".join(lines) + "\n"
