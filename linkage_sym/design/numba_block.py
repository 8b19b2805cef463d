"""The numba backend's loop over a chunk: steps outer, designs inner, in blocks of designs.

:func:`block_source` writes, for one artifact and one set of metrics, the loop that
:mod:`linkage_sym.design.numba_sweep` compiles.  For a block of designs it runs two
passes:

1. for every step, over the block's designs: the artifact's directions and rates
   (pasted in as statements, :func:`~linkage_sym.codegen.scalar_inline.inline_lines`:
   locals only, no call, no array written but the results), the positions' cosines and
   sines, the transmission ratios' running smallest value, the singularity screen and
   the output's rate, in the formulas and order of
   :func:`~linkage_sym.design.numba_kernel.entry_source` (the NumPy backend's), with no
   branch: the terms that depend on the step only (the crank's cosine and sine, the
   hoisted terms) are read once per step, and a choice is a selection between two
   values, so that the compiler vectorises the loop over designs (several designs' square
   roots and divisions in one instruction).  Each entry's outcome is kept: the rate, and
   whether it has positions, passes the screen, or is *rare* -- a direction of length 0
   or infinite (the NumPy backend takes its angle by ``atan2`` there) or a step the
   screen flags (decided by the condition number, a singular value decomposition);
2. design by design along the steps: the rare entries evaluated by ``entry`` (one design
   at one step, as the NumPy backend does), then the brackets of the output's rate's sign
   changes between consecutive ok steps (:class:`~linkage_sym.design.limits.Limits`).

A rare entry's own transmission ratio is taken in the second pass; the running smallest
ratio does not depend on the order in which the ratios come (a NaN ratio never replaces a
number, a number replaces a NaN), so the result is the one-loop order's.
"""

from __future__ import annotations

from linkage_sym.codegen.scalar_inline import inline_lines
from linkage_sym.design.numba_kernel import screen_lines, solve_lines

__all__ = ["block_source", "BLOCK"]

BLOCK = 64
"""Designs per block: the second pass reads the block's rates (steps x designs) back, and
they stay in the processor's cache."""


def _positions(x, forms, m, outs) -> list:
    """``C<c>``, ``S<c>``, ``valid`` and ``rare`` from the directions' outputs ``outs``
    (as :func:`~linkage_sym.design.numba_kernel.unit_direction`, without its ``atan2``
    branch: a length 0 or infinite makes the entry rare)."""
    lines, finite, at = ["rare = False"], [], 0
    for c, form in zip(x, forms):
        if form == "unit":
            lines += [f"C{c} = {outs[at]}", f"S{c} = {outs[at + 1]}"]
            finite.append(f"C{c}")
            at += 2
        elif form == "atan2":
            Y, X, cr, sr = outs[at:at + 4]
            lines += [f"half = ({sr} == 0.0) & (abs({cr}) == 1.0)",
                      f"sign = {cr} if half else 1.0",
                      f"h = {X} * {X} + {Y} * {Y}",
                      "rare = rare | (h == 0.0) | (h == inf)",
                      "h = sign / sqrt(h)",
                      f"c = {X} * h", f"s = {Y} * h",
                      f"C{c} = c if half else c * {cr} - s * {sr}",
                      f"S{c} = s if half else s * {cr} + c * {sr}"]
            finite.append(f"C{c}")
            at += 4
        else:
            lines += [f"C{c} = nan", f"S{c} = nan"]
            finite.append(outs[at])
            at += 1
    given = set(x)
    for c in range(m):
        if c not in given:
            lines += [f"C{c} = nan", f"S{c} = nan"]
    lines.append("valid = asm" + "".join(f" & (abs({v}) < inf)" for v in finite))
    lines.append("rare = valid & rare")  # no positions there or in the exact evaluation
    return lines


_STEP = ("Q", "QD", "QDD")


def _is_number(text) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def block_source(fns, directions, rates, x, forms, blocks, pattern, m, dyads, col, n_p,
                 n_q) -> str:
    """Source of ``kernel(D, Pd, Hd, Hr, Q, QD, QDD, assembled, L, cc, sc, screen,
    rows_length, cols_length, pattern, pos_ok, ok, tmin, bd, bi, bfa, bfb) -> brackets``.

    ``fns``: ``{name: ScalarFunction}`` of ``directions`` and ``rates``; ``n_p``, ``n_q``:
    how many parameters and drivers; the other arguments as
    :func:`~linkage_sym.design.numba_kernel.entry_source`'s.  ``D`` (``n_p + 2 * dyads +
    1``, designs): the parameters, the transmission offsets' cosines ``cc`` and sines
    ``sc`` and whether assembled (1.0 or 0.0), one array read by the loop over designs;
    ``Pd``: the parameters (design, parameter).  The loop fills
    ``pos_ok``, ``ok`` (designs, steps), ``tmin`` (dyads, designs) and the brackets
    (design, step, rate there, rate at the next step) in row-major order as far as the
    arrays hold them, returning how many there are."""
    pattern = [tuple(p) for p in pattern]
    k_dy = len(dyads)

    def reads(name):
        def read(arg, k):
            if arg in _STEP:
                return f"{arg}_{k}"
            if arg == "P":
                return f"D[{k}, d]"
            if arg == "H":
                return f"{name}_H{k}"
            if arg == "CX":
                return f"C{k}"
            if arg == "SX":
                return f"S{k}"
            return "nan"  # the positions' own functions read no coordinate
        return read

    d_lines, d_out = inline_lines(fns[directions], "dn_", reads("dn"))
    r_lines, r_out = inline_lines(fns[rates], "rt_", reads("rt"))
    # two loops over the block's designs: the positions, then the rest; each loop's chain
    # of square roots and divisions is short enough for the processor to overlap designs
    s0 = f"N + {k_dy}"  # the rows of W that pass the positions from one loop to the next
    # (the directions' outputs pass through rows of W from a loop of their own, too)
    s1 = f"N + {k_dy + 2 * m + 2}"
    const = {o: v for o, v in (ln.split(" = ", 1) for ln in d_lines if ln.split(" = ", 1)[0] in d_out)
             if _is_number(v)}
    zero = ["d = np.uint64(d0 + j)"] + d_lines
    zero += [f"W[{s1} + {k}, j] = {o}" for k, o in enumerate(d_out) if o not in const]
    first = ["d = np.uint64(d0 + j)", f"asm = D[{n_p + 2 * k_dy}, d] != 0.0"]
    first += [f"{o} = {const[o]}" if o in const else f"{o} = W[{s1} + {k}, j]"
              for k, o in enumerate(d_out)]
    first += _positions(x, forms, m, d_out)
    first += [f"W[{s0} + {2 * c}, j] = C{c}\nW[{s0} + {2 * c + 1}, j] = S{c}" for c in range(m)]
    first += [f"W[{s0} + {2 * m}, j] = 1.0 if valid else 0.0",
              f"W[{s0} + {2 * m + 1}, j] = 1.0 if rare else 0.0"]
    first = [t for s in first for t in s.split("\n")]
    inner = ["d = np.uint64(d0 + j)"]
    inner += [f"C{c} = W[{s0} + {2 * c}, j]\nS{c} = W[{s0} + {2 * c + 1}, j]" for c in range(m)]
    inner += [f"valid = W[{s0} + {2 * m}, j] != 0.0", f"rare = W[{s0} + {2 * m + 1}, j] != 0.0"]
    inner = [t for s in inner for t in s.split("\n")]
    inner.append("use = valid & (not rare)")
    for k, (ia, ib) in enumerate(dyads):
        inner += [f"cd = C{ib} * C{ia} + S{ib} * S{ia}",
                  f"sd = S{ib} * C{ia} - C{ib} * S{ia}",
                  f"occ = D[{n_p + k}, d]", f"osc = D[{n_p + k_dy + k}, d]",
                  "r = abs((sd * occ + cd * osc) / (cd * occ - sd * osc))",
                  f"mk = W[N + {k}, j]",
                  f"W[N + {k}, j] = r if use & ((r < mk) | (mk != mk)) else mk"]
    inner += r_lines
    inner += [f"a{i}_{j} = {r_out[p]}" for p, (i, j) in enumerate(pattern)]
    inner += screen_lines(blocks, pattern, "fmax_select")
    if col is not None:
        inner += solve_lines(blocks, pattern, lambda i: r_out[len(pattern) + i])
        inner += [f"r = x{col}", "W[t, j] = r"]
    else:
        inner.append("r = 1.0")
    inner += ["good = valid & (not flag)",
              "rare = rare | (valid & flag)",
              "nrare += rare",
              "code[t, j] = valid + 2 * good + 4 * rare + 8 * (r < 0.0) + 16 * (r == 0.0)"]
    hd, hr = fns[directions].hoisted, fns[rates].hoisted
    step = [f"dn_H{k} = Hd[t, {k}]" for k in range(hd)] + [f"rt_H{k} = Hr[t, {k}]" for k in range(hr)]
    step += [f"Q_{k} = Q[t, {k}]" for k in range(n_q)]
    step += [f"{a}_{k} = {a}[{k}]" for a in ("QD", "QDD") for k in range(n_q)]
    lines = ["def kernel(D, Pd, Hd, Hr, Q, QD, QDD, assembled, L, cc, sc, screen, rows_length,",
             "           cols_length, pattern, pos_ok, ok, tmin, bd, bi, bfa, bfb):",
             "    n, N = pos_ok.shape",
             "    t2 = screen[0]",
             "    dout, rout = np.empty(int(screen[2])), np.empty(int(screen[3]))",
             f"    nowhere = np.full({m}, np.nan)",
             f"    C, S = np.empty({m}), np.empty({m})",
             f"    tr = np.empty({max(k_dy, 1)})",
             f"    W = np.zeros((N + {k_dy + 2 * m + 2 + len(d_out)}, {BLOCK}))",
             f"    code = np.zeros((N, {BLOCK}), np.uint8)"]
    lines += ["    nb, cap = 0, bd.shape[0]",
              f"    for d0 in range(0, n, {BLOCK}):",
              f"        nj = n - d0 if n - d0 < {BLOCK} else {BLOCK}",
              "        for j in range(nj):"]
    lines += [f"            W[N + {k}, j] = nan" for k in range(k_dy)] or ["            pass"]
    lines += ["        nrare = 0", "        for t in range(N):"]
    lines += [f"            {s}" for s in step]
    lines += ["            for j in range(nj):"]
    lines += [f"                {s}" for s in zero]
    lines += ["            for j in range(nj):"]
    lines += [f"                {s}" for s in first]
    lines += ["            for j in range(nj):"]
    lines += [f"                {s}" for s in inner]
    lines += _second_pass(k_dy, col)
    lines.append("    return nb")
    return "\n".join(lines) + "\n"


def _second_pass(k_dy, col) -> list:
    """The rare entries evaluated exactly (:func:`~linkage_sym.design.numba_kernel.entry_source`),
    then design by design along the steps the statuses and the brackets (from the entries'
    codes: 1 positions, 2 ok, 4 rare, 8 a rate below 0, 16 a rate of 0)."""
    out = ["        for j in range(nj if nrare else 0):",
           "            d = d0 + j",
           "            for t in range(N):",
           "                if not code[t, j] & 4:",
           "                    continue",
           "                c, r = entry(Pd[d], Q[t], QD, QDD, Hd[t], Hr[t], cc, sc, d, L[d], "
           "screen, rows_length, cols_length, pattern, tr, dout, rout, C, S, nowhere)",
           "                W[t, j] = r",
           "                code[t, j] = (c > 0) + 2 * (c == 3) + 8 * (r < 0.0) + 16 * (r == 0.0)",
           "                if c > 0:"]
    for k in range(k_dy):
        out += [f"                    if tr[{k}] < W[N + {k}, j] or W[N + {k}, j] != W[N + {k}, j]:",
                f"                        W[N + {k}, j] = tr[{k}]"]
    out += ["                    pass",
            "        for j in range(nj):",
            "            d = d0 + j",
            "            pc = 0",
            "            for t in range(N):",
            "                c = code[t, j]",
            "                pos_ok[d, t] = c & 1",
            "                ok[d, t] = c & 2"]
    if col is not None:  # a bracket: two ok steps, the rate's signs differ or one is 0
        out += ["                if c & pc & 2 and ((c ^ pc) & 8 or (c | pc) & 16):",
                "                    if nb < cap:",
                "                        bd[nb], bi[nb], bfa[nb], bfb[nb] = d, t - 1, W[t - 1, j], W[t, j]",
                "                    nb += 1",
                "                pc = c"]
    out += [f"            tmin[{k}, d] = W[N + {k}, j]" for k in range(k_dy)]
    return out
