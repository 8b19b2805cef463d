"""The numba backend's limit positions: Newton on the output's rate, bracket by bracket,
compiled.

:func:`newton_source` writes, for one artifact, ``rate_at`` -- the output's rate along the
steps and its own rate at a fractional step, as
:meth:`~linkage_sym.design.evaluate.Model.rate_at` computes them: the driver values
linear between the steps, the positions by the closed forms (angles), their cosines and
sines, the rate system solved for the velocities, the accelerations' right-hand side
solved with the same matrix -- and ``newton``, the iteration of
:func:`~linkage_sym.design.limits.roots` on one bracket at a time (the same start, steps,
bisection and stopping rule; :data:`~linkage_sym.design.limits.XTOL`,
:data:`~linkage_sym.design.limits.MAX_ITER`).  The same operations in the same order as
the NumPy backend's arrays, one bracket at a time (observed: the same roots bit for bit).
"""

from __future__ import annotations

import numpy as np

from linkage_sym.design.limits import MAX_ITER, XTOL
from linkage_sym.design.numba_kernel import solve_lines

__all__ = ["newton_source"]


def newton_source(positions, x, blocks, pattern, m, col, n_q) -> str:
    """Source of ``rate_at`` and ``newton(PB, a, fa, fb, Qs, QD, QDD, t, kind, work) ->
    None`` (the roots ``t`` and their kinds ``kind`` of the brackets: designs' parameters
    ``PB`` (bracket, parameter), steps ``a``, rates ``fa`` there and ``fb`` at the next
    step; :func:`~linkage_sym.design.limits.roots`).  The compiled scalar functions
    ``positions`` (the closed step's, of the coordinates ``x``), ``rates``,
    ``accelerations`` and their ``pre_`` functions must be defined where it runs;
    ``blocks``, ``pattern``, ``m``: the artifact's; ``col``: the output's coordinate;
    ``n_q``: how many drivers."""
    pattern = [tuple(p) for p in pattern]
    np_ = len(pattern)
    body = ["if x != x:", "    return nan, nan",
            "N = Qs.shape[0]",
            "i = int(np.floor(x))",
            "top = N - 2 if N > 2 else 0",
            "i = 0 if i < 0 else (top if i > top else i)",
            "j = i + 1 if i + 1 < N - 1 else N - 1",
            "f = x - i"]
    body += [f"qv[{r}] = Qs[i, {r}] + f * (Qs[j, {r}] - Qs[i, {r}])" for r in range(n_q)]
    body += [f"pre_{positions}(qv, QD, QDD, Hd)", "pre_rates(qv, QD, QDD, Hr)",
             "pre_accelerations(qv, QD, QDD, Ha)",
             f"{positions}(nowhere, nowhere, nowhere, qv, QD, QDD, nowhere, P, nowhere, "
             "nowhere, Hd, dout)"]
    given = dict(zip(x, range(len(x))))
    for c in range(m):
        if c in given:
            body += [f"X[{c}] = dout[{given[c]}]", f"C[{c}] = np.cos(X[{c}])",
                     f"S[{c}] = np.sin(X[{c}])"]
        else:
            body += [f"X[{c}] = nan", f"C[{c}] = nan", f"S[{c}] = nan"]
    body.append("rates(X, nowhere, nowhere, qv, QD, QDD, nowhere, P, C, S, Hr, rout)")
    body += [f"a{i}_{j} = rout[{p}]" for p, (i, j) in enumerate(pattern)]
    body += solve_lines(blocks, pattern, lambda i: f"rout[{np_ + i}]", "v")
    body += [f"XD[{c}] = v{c}" for c in range(m)]
    body.append("accelerations(X, XD, nowhere, qv, QD, QDD, nowhere, P, C, S, Ha, aout)")
    body += solve_lines(blocks, pattern, lambda i: f"aout[{i}]", "w")
    body.append(f"return v{col}, w{col}")
    lines = ["def rate_at(P, x, Qs, QD, QDD, qv, Hd, Hr, Ha, dout, rout, aout, X, C, S, XD, nowhere):"]
    lines += [f"    {s}" for s in body]
    lines += ["", "", _NEWTON.format(m=m, n_q=max(n_q, 1), xtol=repr(XTOL), max_iter=MAX_ITER,
                                     eps4=repr(4 * float(np.finfo(float).eps)))]
    return "\n".join(lines)


_NEWTON = '''def newton(PB, a, fa, fb, Qs, QD, QDD, t, kind, sizes):
    qv = np.empty({n_q})
    Hd, Hr, Ha = np.zeros(sizes[0]), np.zeros(sizes[1]), np.zeros(sizes[2])
    dout, rout, aout = np.empty(sizes[3]), np.empty(sizes[4]), np.empty(sizes[5])
    X, C, S, XD = np.empty({m}), np.empty({m}), np.empty({m}), np.empty({m})
    nowhere = np.full({m}, np.nan)
    for k in range(a.shape[0]):
        A, FA, FB = a[k], fa[k], fb[k]
        B = A + 1.0
        kind[k] = 1 if (FA > 0) or (FB < 0) else -1
        if FA == 0 or FB == 0:
            t[k] = A if FA == 0 else B
            continue
        lo, hi, flo = A, B, FA
        x = B - FB * (B - A) / (FB - FA) if FB != FA else 0.5 * (A + B)
        tk = nan
        for _ in range({max_iter}):
            f, df = rate_at(PB[k], x, Qs, QD, QDD, qv, Hd, Hr, Ha, dout, rout, aout, X, C, S,
                            XD, nowhere)
            if not np.isfinite(f):
                tk = nan
                break
            if (f < 0) == (flo < 0):  # the root lies above x
                lo, flo = x, f
            else:
                hi = x
            step = f / df
            xn = x - step
            conv = f == 0 or abs(step) <= {xtol} + {eps4} * abs(x)
            tk = x if f == 0 else xn
            if not (xn > lo and xn < hi):
                xn = 0.5 * (lo + hi)
            x = xn
            if conv:
                break
            tk = nan  # not converged (yet)
        t[k] = tk
'''
