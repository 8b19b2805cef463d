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


class _Rows:
    """Rows of the block's array ``W`` (rows x designs) that pass values from one loop over
    the block's designs to the next (after the ``N`` rates and the dyads' smallest
    ratios)."""

    def __init__(self, first: str):
        self.first, self.count = first, 0

    def put(self, names) -> tuple[list, list]:
        """``(stores, loads)`` of ``names`` through rows of their own."""
        at = [f"{self.first} + {self.count + k}" for k in range(len(names))]
        self.count += len(names)
        return ([f"W[{r}, j] = {v}" for r, v in zip(at, names)],
                [f"{v} = W[{r}, j]" for r, v in zip(at, names)])


def _loops(fns, directions, rates, x, forms, blocks, pattern, m, dyads, col, n_p) -> tuple:
    """The bodies of the loops over a block's designs at a step, and the rows they use."""
    k_dy = len(dyads)

    def reads(name):
        def read(arg, k):
            if arg in _STEP:
                return f"{arg}_{k}"
            return {"P": f"D[{k}, d]", "H": f"{name}_H{k}", "CX": f"C{k}",
                    "SX": f"S{k}"}.get(arg, "nan")  # the positions read no coordinate
        return read

    rows = _Rows(f"N + {k_dy}")
    d_lines, d_out = inline_lines(fns[directions], "dn_", reads("dn"))
    r_lines, r_out = inline_lines(fns[rates], "rt_", reads("rt"))
    at = "d = np.uint64(d0 + j)"  # unsigned: no wrap-around of a negative index
    # the directions' outputs (a number the derivation prints stays a constant)
    const = {o: v for o, v in (ln.split(" = ", 1) for ln in d_lines) if o in d_out and _is_number(v)}
    varying = [o for o in d_out if o not in const]
    put, get = rows.put(varying)
    loops = [[at] + d_lines + put]
    # the unit vectors, whether the entry has positions, whether it is rare
    cs = [v for c in range(m) for v in (f"C{c}", f"S{c}")]
    put, get_cs = rows.put(cs + ["fvalid", "frare"])
    loops.append([at, f"asm = D[{n_p + 2 * k_dy}, d] != 0.0"] + get
                 + [f"{o} = {v}" for o, v in const.items()] + _positions(x, forms, m, d_out)
                 + ["fvalid = 1.0 if valid else 0.0", "frare = 1.0 if rare else 0.0"] + put)
    head = [at] + get_cs + ["valid = fvalid != 0.0", "rare = frare != 0.0"]
    if dyads:  # the transmission ratios' running smallest value
        trans = head + ["use = valid & (not rare)"]
        for k, (ia, ib) in enumerate(dyads):
            trans += [f"cd = C{ib} * C{ia} + S{ib} * S{ia}",
                      f"sd = S{ib} * C{ia} - C{ib} * S{ia}",
                      f"occ = D[{n_p + k}, d]", f"osc = D[{n_p + k_dy + k}, d]",
                      "r = abs((sd * occ + cd * osc) / (cd * occ - sd * osc))",
                      f"mk = W[N + {k}, j]",
                      f"W[N + {k}, j] = r if use & ((r < mk) | (mk != mk)) else mk"]
        loops.append(trans)
    # the rate matrix, the screen, the output's rate, each entry's code
    rest = head + r_lines + [f"a{i}_{j} = {r_out[p]}" for p, (i, j) in enumerate(pattern)]
    rest += screen_lines(blocks, pattern, "fmax_select")
    if col is not None:
        rest += solve_lines(blocks, pattern, lambda i: r_out[len(pattern) + i])
        rest += [f"r = x{col}", "W[t, j] = r"]
    else:
        rest.append("r = 1.0")
    rest += ["good = valid & (not flag)",
             "rare = rare | (valid & flag)",
             "nrare += rare",
             "code[t, j] = valid + 2 * good + 4 * rare + 8 * (r < 0.0) + 16 * (r == 0.0)"]
    loops.append(rest)
    return loops, k_dy + rows.count


def block_source(fns, directions, rates, x, forms, blocks, pattern, m, dyads, col, n_p,
                 n_q) -> str:
    """Source of ``kernel(D, Pd, Hd, Hr, Q, QD, QDD, assembled, L, cc, sc, screen,
    rows_length, cols_length, pattern, pos_ok, ok, tmin, bd, bi, bfa, bfb) -> brackets``.

    ``fns``: ``{name: ScalarFunction}`` of ``directions`` and ``rates``; ``n_p``, ``n_q``:
    how many parameters and drivers; the other arguments as
    :func:`~linkage_sym.design.numba_kernel.entry_source`'s.  ``D`` (``n_p + 2 * dyads +
    1``, designs): the parameters, the transmission offsets' cosines ``cc`` and sines
    ``sc`` and whether assembled (1.0 or 0.0), one array read by the loop over designs;
    ``Pd``: the parameters (design, parameter).  The loop fills ``pos_ok``, ``ok``
    (designs, steps), ``tmin`` (dyads, designs) and the brackets (design, step, rate there,
    rate at the next step) in row-major order as far as the arrays hold them, returning
    how many there are.

    The first pass is several loops over the block's designs, each passing its values to
    the next through rows of the block's array ``W``: a loop's chain of square roots and
    divisions is then short enough for the processor to overlap several designs' (one
    loop of all: about 19 ns a design-position, four: 14 ns, measured on the
    crank-rocker)."""
    k_dy = len(dyads)
    loops, extra = _loops(fns, directions, rates, x, forms, blocks, pattern, m, dyads, col, n_p)
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
             f"    W = np.zeros((N + {extra}, {BLOCK}))",
             f"    code = np.zeros((N, {BLOCK}), np.uint8)",
             "    nb, cap = 0, bd.shape[0]",
             f"    for d0 in range(0, n, {BLOCK}):",
             f"        nj = n - d0 if n - d0 < {BLOCK} else {BLOCK}",
             "        for j in range(nj):"]
    lines += [f"            W[N + {k}, j] = nan" for k in range(k_dy)] or ["            pass"]
    lines += ["        nrare = 0", "        for t in range(N):"]
    lines += [f"            {s}" for s in step]
    for body in loops:
        lines += ["            for j in range(nj):"] + [f"                {s}" for s in body]
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
