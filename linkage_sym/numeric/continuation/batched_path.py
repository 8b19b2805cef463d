"""The continuation policy, many path points at once (NumPy only).

:func:`linkage_sym.numeric.continuation.solve_path` walks a group's path
point by point: at each point a predictor, damped Newton, the acceptance
test, and bisection or a root search where that fails.  Along a continuous
stretch almost every point is taken by the first, direct Newton step from its
predictor; walked one at a time, that is a loop of tiny NumPy calls.  This
module gives the same walk the same results with a few calls on whole blocks
of points (:func:`walk_path`):

1. **Roots.**  Every :data:`COARSE`-th point of a block first, by Newton from
   guesses extrapolated along the stretch solved so far
   (:func:`newton_guesses`); then the others from the cubic through the roots
   around them, which puts them within about ``1e-8`` of their roots on a
   smooth stretch: one Newton step takes them to about ``1e-15`` (guesses
   farther off, on the path's coarse first steps or a sharp turn, get
   :func:`newton_guesses` too).  These are only guesses of the walk's
   results; nothing is taken from this step alone.
2. **The walk's own step, checked.**  From those roots each point gets the
   predictor the point-by-point walk gives it (``2 u[i-1] - u[i-2]``, or
   ``u[i-1]`` at the start of a stretch).  Where :func:`certified` proves that
   the walk's damped Newton from that predictor ends, to rounding, on the
   point's root of step 1 (one full step from the predictor lands within
   ``1e-3`` of the predictor's distance of it, the root is well conditioned,
   has the assembly sign and lies well within
   :data:`~linkage_sym.numeric.continuation.roots.MAX_CORRECTION`), that root is
   taken after the walk's last polishing step from it: two evaluations and a
   solve per point instead of the walk's four and three.  Everywhere else
   :func:`newton_points` runs *the same damped Newton iteration* as
   :func:`~linkage_sym.numeric.continuation.roots.newton` from the predictor: same
   steps, same step halving, same stopping rules, row by row, and the point is
   taken only if that iteration passes the walk's acceptance test (scaled
   residual :data:`~linkage_sym.numeric.continuation.roots.TOL`, the assembly
   configuration's determinant sign, within
   :data:`~linkage_sym.numeric.continuation.roots.MAX_CORRECTION` of its predictor).
   For every point but the last of a block, the point taken must also be the
   root of step 1 (within :data:`~linkage_sym.numeric.continuation.roots.SAME_ROOT`)
   that the next points' predictors were made from.  By induction along the
   block, every point taken is the point the walk would have computed (to
   rounding), from the same predictor (to rounding).
3. **Everything else is the walk itself.**  The first point of a block whose
   direct step is not accepted (a limit, a gap, a root of the other sign, a
   correction too large: the walk would bisect there) is solved by
   :meth:`~linkage_sym.numeric.continuation.Walk.step`, the point-by-point
   code, and so are re-entries after a gap and the first point of a gap.
   Limits, re-entries, notes and failures are therefore the point-by-point
   walk's.
4. **Gaps.**  At the points of a gap the walk searches roots from the same
   seeds around the same configurations at each point; :func:`roots_near_points`
   runs those searches for many points at once (the same seeds, fitted by the
   same least-squares call, the same bounded-step Newton row by row).  Points without
   a root of the assembly sign are recorded as the walk records them; the
   first one with such a root is left to :meth:`~.continuation.Walk.step`.

The conditioning indicator of each point taken is the walk's
(:func:`~linkage_sym.numeric.continuation.roots.indicator`).  Block sizes
adapt: doubled after a block taken whole (up to :data:`MAX_BLOCK`), halved
after one whose guesses did not reach its end, back to :data:`MIN_BLOCK`
after a point the walk had to take itself.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from linkage_sym.numeric.continuation.roots import (
    MAX_CORRECTION,
    MAX_ITER,
    MAX_POLISH,
    POLISH_FLOOR,
    SAME_ROOT,
    STALL_ITER,
    TOL,
    indicator,
    inverses,
    distinct_roots,
    search_newton,
    search_seeds,
)

if TYPE_CHECKING:  # the walk whose points this module solves (it calls walk_path)
    from linkage_sym.numeric.continuation import Walk

MIN_BLOCK = 64
"""Smallest block of points solved at once (and the first one after a stop)."""
GRAM_RATIO = 1e-2
"""Reciprocal condition numbers at least this come from the eigenvalues of ``J^T J``."""
MAX_GAP = 64
"""Largest number of points of a gap searched at once."""
MAX_BLOCK = 1024
"""Largest block: the guesses are extrapolated at most this many points ahead."""
ROOT_ITER = 10
"""Iterations of undamped Newton from a guess (:func:`newton_guesses`)."""
COARSE = 8
"""Every this many points of a block are solved first; the others are interpolated from them."""
CERTIFY_RATIO = 1e-2
"""Smallest reciprocal condition number at which :func:`certified` takes a root for the
walk's iteration (below it the walk's own iteration runs)."""
GUESS_RESIDUAL = 1e-6
"""An interpolated guess is taken to its root by one Newton step if its scaled residual is at
most this (the step's error is about its square, times the curvature); else by Newton's
iteration."""


def singular_value_ratio(J: np.ndarray) -> np.ndarray:
    """``sigma_min / sigma_max`` of every matrix of ``J`` (k, n, n), as the SVD gives it.

    From the extreme eigenvalues of ``J^T J`` (``numpy.linalg.eigvalsh``, about
    half the cost of the SVD of small matrices) where the ratio ``r`` is at
    least :data:`GRAM_RATIO`: their rounding (``~n eps lambda_max``) moves it by
    about ``n eps / (2 r^2)`` relative, below ``1e-11`` there (an indicator: it
    decides the rate stages' screen, :func:`linkage_sym.numeric.kinematics.newton.above_ratio`).
    The others, and any non-finite one, by the SVD itself (``eps / r`` relative).
    """
    J = np.asarray(J, dtype=float)
    out = np.full(len(J), np.nan)
    if not len(J):
        return out
    finite = np.isfinite(J).all(axis=(1, 2))
    if finite.any():
        Jf = J[finite]
        lam = np.linalg.eigvalsh(np.matmul(Jf.transpose(0, 2, 1), Jf))
        with np.errstate(invalid="ignore", divide="ignore"):
            out[finite] = np.sqrt(np.maximum(lam[:, 0], 0.0) / lam[:, -1])
    redo = ~(out >= GRAM_RATIO)
    if redo.any():
        sv = np.linalg.svd(J[redo], compute_uv=False)
        with np.errstate(invalid="ignore", divide="ignore"):
            out[redo] = sv[:, -1] / sv[:, 0]
    return out


def _writable(*arrays):
    """The arrays, copied only if they cannot be written to (a broadcast view)."""
    return tuple(a if a.flags.writeable else a.copy() for a in map(np.asarray, arrays))


def _solve_rows(J, R):
    """``J[j]^-1 R[j]`` for every row, and which rows have none (singular or not finite).

    The rows :func:`roots.newton` would give up on (``LinAlgError`` or
    a non-finite step) are marked ``bad``.
    """
    try:
        d = np.linalg.solve(J, R[..., None])[..., 0]
        bad = np.zeros(len(J), bool)
    except np.linalg.LinAlgError:  # a singular matrix among them: row by row
        d = np.zeros_like(R)
        bad = np.zeros(len(J), bool)
        for j in range(len(J)):
            try:
                d[j] = np.linalg.solve(J[j], R[j])
            except np.linalg.LinAlgError:
                bad[j] = True
    bad |= ~np.isfinite(d).all(axis=1)
    return d, bad


def _halve_steps(problem, idx, U, d, res, conv, step, Un, Rn, Jn, resn) -> None:
    """Halve each row's step while it does not decrease the residual (down to a step of
    1e-4); ``step``, ``Un``, ``Rn``, ``Jn`` and ``resn`` are updated in place (``idx``: each
    row's path point)."""
    while True:
        halve = ~((resn < res) | conv | (step < 1e-4))
        if not halve.any():
            break
        h = np.flatnonzero(halve)
        step[h] *= 0.5
        Un[h] = U[h] - step[h, None] * d[h]
        Rh, Jh = problem.evaluate_points(Un[h], idx[h])
        Rn[h], Jn[h] = Rh, Jh
        resn[h] = np.linalg.norm(Rn[h], axis=1)


def newton_points(problem, U, idx):
    """:func:`roots.newton` from every row of ``U`` at its path point ``idx[j]``.

    Row by row the same iteration: the full Newton step, halved while it does
    not decrease the residual (down to a step of 1e-4), stopped when the
    residual stalls over :data:`roots.STALL_ITER` iterations, polishing
    steps after reaching :data:`roots.TOL` while the last one's
    correction exceeds :data:`roots.POLISH_FLOOR` (at most
    :data:`roots.MAX_POLISH`; each kept only if it does not make the
    residual worse), at most :data:`roots.MAX_ITER`
    iterations; a singular Jacobian or a non-finite step gives an infinite
    residual.  Returns ``(U, res, J)``: each row's last iterate, its residual
    norm and its Jacobian there.
    """
    U = np.array(U, dtype=float)
    idx = np.asarray(idx)
    R, J = _writable(*problem.evaluate_points(U, idx))
    res = np.linalg.norm(R, axis=1)
    # rows leaving the iteration are written here
    out_U, out_res, out_J = np.empty_like(U), np.empty_like(res), np.empty_like(J)
    # the rows still iterating, compressed: row j of U, R, J, res is row act[j]
    act = np.arange(len(U))
    history = np.empty((MAX_ITER, len(act)))
    polished = np.zeros(len(act), int)  # polishing steps taken
    last = np.full(len(act), np.inf)  # the last polishing step's correction

    def keep(mask):
        """Write the rows not in ``mask`` out and keep the others."""
        nonlocal act, U, R, J, res, history, polished, last
        if mask.all():
            return
        gone = ~mask
        out_U[act[gone]], out_res[act[gone]], out_J[act[gone]] = U[gone], res[gone], J[gone]
        act, U, R, J, res = act[mask], U[mask], R[mask], J[mask], res[mask]
        history, polished, last = history[:, mask], polished[mask], last[mask]

    for it in range(MAX_ITER):
        if not len(act):
            break
        history[it] = res
        if it >= STALL_ITER:
            # no root here: the residual stalls (roots.newton's history[-STALL_ITER])
            keep(~((res > TOL) & (res > 0.5 * history[it - STALL_ITER + 1])))
        conv = res <= TOL
        # converged and polished: done (roots.newton's rule)
        keep(~(conv & (polished > 0) & ((last <= POLISH_FLOOR) | (polished >= MAX_POLISH))))
        if not len(act):
            break
        conv = res <= TOL
        polished += conv  # one more step: quadratic convergence to ~1e-16
        d, bad = _solve_rows(J, R)
        if bad.any():
            res[bad] = np.inf
            keep(~bad)
            d, conv = d[~bad], conv[~bad]
            if not len(act):
                break
        step = np.ones(len(act))
        Un = U - d
        Rn, Jn = _writable(*problem.evaluate_points(Un, idx[act]))
        resn = np.linalg.norm(Rn, axis=1)
        halve = ~((resn < res) | conv)
        if halve.any():
            _halve_steps(problem, idx[act], U, d, res, conv, step, Un, Rn, Jn, resn)
        # polishing made it worse: keep the converged point
        worse = conv & ~(resn <= res)
        keep(~worse)
        if worse.any():
            Un, Rn, Jn, resn = Un[~worse], Rn[~worse], Jn[~worse], resn[~worse]
            d, conv = d[~worse], conv[~worse]
        if conv.any():
            last[conv] = np.max(np.abs(d[conv]), axis=1)
        U, R, J, res = Un, Rn, Jn, resn
    keep(np.zeros(len(act), bool))
    return out_U, out_res, out_J


def newton_guesses(problem, U, idx):
    """Roots near guesses ``U`` at the path points ``idx``: undamped Newton, row by row.

    A row stops when its full step does not decrease its residual (no root near
    this guess), and after :data:`ROOT_ITER` iterations; a row whose residual is
    within :data:`roots.TOL` takes one more step without evaluating the
    residual after it.  Returns ``(U, res)``: each row's last iterate and its
    residual before that last step (``res <= TOL``: a root).  Guesses only: what
    the walk takes is decided by its own iteration or :func:`certified`.
    """
    U = np.array(U, dtype=float)
    idx = np.asarray(idx)
    out_U, out_res = U.copy(), np.full(len(U), np.inf)
    act = np.arange(len(U))
    R, J = problem.evaluate_points(U, idx)
    res = np.linalg.norm(R, axis=1)
    for _ in range(ROOT_ITER):
        d, bad = _solve_rows(J, R)
        conv = (res <= TOL) & ~bad
        out_U[act[conv]] = U[conv] - d[conv]  # polished without evaluating
        out_res[act[conv]] = res[conv]
        go = ~(conv | bad)
        if not go.any():
            return out_U, out_res
        if not go.all():
            act, U, d, res = act[go], U[go], d[go], res[go]
        Un = U - d
        R, J = problem.evaluate_points(Un, idx[act])
        resn = np.linalg.norm(R, axis=1)
        worse = ~(resn < res)  # no decrease: this row stops where it was
        out_U[act[worse]], out_res[act[worse]] = U[worse], res[worse]
        if worse.all():
            return out_U, out_res
        if worse.any():
            keep = ~worse
            act, Un, R, J, resn = act[keep], Un[keep], R[keep], J[keep], resn[keep]
        U, res = Un, resn
    out_U[act], out_res[act] = U, res
    return out_U, out_res


def _extrapolate(walk: Walk, t: np.ndarray, s: int) -> np.ndarray:
    """Guesses ``t`` points after the last solved one: the stretch solved so far, extrapolated.

    A parabola through the last solved point and two earlier points of its
    continuous stretch (``s`` apart, or closer when the stretch is shorter), a
    line when the stretch is two points long, the last point when it is one.
    """
    i, u0, _ = walk.last
    avail = i - walk.stretch
    t = np.asarray(t, dtype=float)[:, None]
    if avail < 1:
        return np.broadcast_to(u0, (len(t), len(u0))).copy()
    U = walk.sol.u
    if avail < 2:
        return u0 + t * (u0 - U[i - 1])
    s = max(1, min(s, avail // 2))
    x = t / s  # Lagrange through (0, u0), (-s, U[i - s]), (-2 s, U[i - 2 s])
    return (u0 * ((x + 1) * (x + 2) / 2) - U[i - s] * (x * (x + 2))
            + U[i - 2 * s] * (x * (x + 1) / 2))


def _interpolate(X: np.ndarray, V: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Values at ``x`` of the cubic (fewer nodes: lower degree) through the 4 nodes
    of ``X`` (increasing, values ``V``) around each point."""
    deg = min(4, len(X))
    j = np.searchsorted(X, x)
    first = np.clip(j - 2, 0, len(X) - deg)
    nodes = first[:, None] + np.arange(deg)  # (k, deg)
    Xn = X[nodes]
    w = np.ones((len(x), deg))
    for a in range(deg):
        for b in range(deg):
            if a != b:
                w[:, a] *= (x - Xn[:, b]) / (Xn[:, a] - Xn[:, b])
    return np.einsum("ka,kan->kn", w, V[nodes])


def _roots(walk: Walk, idx: np.ndarray) -> np.ndarray:
    """Roots at the block's points, by Newton from guesses; NaN from the first row not solved.

    Every :data:`COARSE`-th point (and the last) first, from guesses
    extrapolated along the stretch; then the others from the cubic through
    the roots around them (and the last solved points), which puts their
    guesses within rounding of the roots on a smooth stretch.
    """
    problem = walk.problem
    i, u0, _ = walk.last
    m, n = len(idx), len(u0)
    A = np.full((m, n), np.nan)
    coarse = np.unique(np.r_[np.arange(COARSE - 1, m, COARSE), m - 1])
    Ac, res = newton_guesses(problem, _extrapolate(walk, coarse + 1, COARSE), idx[coarse])
    good = res <= TOL
    nc = len(coarse) if good.all() else int(np.argmin(good))
    if nc == 0:
        return A
    coarse, Ac = coarse[:nc], Ac[:nc]
    A[coarse] = Ac
    # nodes: the last solved points of the stretch and the coarse roots (block positions)
    back = min(COARSE, i - walk.stretch)
    X = np.r_[([-1 - back] if back else []), -1, coarse].astype(float)
    V = np.vstack([walk.sol.u[[i - back]] if back else np.empty((0, n)), u0[None], Ac])
    rest = np.setdiff1d(np.arange(coarse[-1] + 1), coarse)
    if len(rest):
        # one Newton step from the interpolated guesses close to a root (the step's error
        # is about the square of theirs: rounding on a smooth stretch); Newton's iteration
        # from the others (coarse steps of the path, a sharp turn)
        G = _interpolate(X, V, rest.astype(float))
        R, J = problem.evaluate_points(G, idx[rest])
        d, bad = _solve_rows(J, R)
        Ar = G - d
        far = bad | ~(np.linalg.norm(R, axis=1) <= GUESS_RESIDUAL)
        if far.any():
            Af, res = newton_guesses(problem, G[far], idx[rest[far]])
            Af[~(res <= TOL)] = np.nan
            Ar[far] = Af
        A[rest] = Ar
    return A


def solve_block(walk: Walk, idx: np.ndarray) -> tuple[int, bool]:
    """Solve the points ``idx`` (consecutive, right after ``walk.last``) at once.

    Returns how many of them, from the first, were taken (and recorded), and
    whether the next one is a point where the walk's direct step fails.
    """
    problem, sign = walk.problem, walk.sign
    _, u0, _ = walk.last
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        # 1. the roots
        A = _roots(walk, idx)
        solved = np.isfinite(A).all(axis=1)
        # the walk's predictors need the roots before a point, not the point's own
        n = len(idx) if solved.all() else int(np.argmin(solved)) + 1
        idx, A = idx[:n], A[:n]
        # 2. the walk's own predictors from those roots, and its Newton iteration from them
        prev1 = np.vstack([u0[None], A[:-1]])
        P = 2 * prev1 - np.vstack([[walk.before if walk.before is not None else u0], prev1[:-1]])
        if walk.before is None:
            P[0] = u0  # the start of a stretch: the last point itself
        # 3. where the walk's iteration provably ends on the root of step 1, that root
        #    (see certified); the walk's iteration itself everywhere else
        B, JB, ind, cert = certified(problem, P, A, idx, sign)
        accepted = cert.copy()
        rest = np.flatnonzero(~cert)
        if len(rest):
            B[rest], res_b, JB[rest] = newton_points(problem, P[rest], idx[rest])
            accepted[rest] = (
                (res_b <= TOL)
                & (np.sign(np.linalg.det(JB[rest])) == sign)
                & (np.max(np.abs(B[rest] - P[rest]), axis=1) <= MAX_CORRECTION)
            )
        # a point whose root is not the one its successors' predictors were made from
        # is the last one taken
        same = np.max(np.abs(B - A), axis=1) <= SAME_ROOT
        n = len(idx) if accepted.all() else int(np.argmin(accepted))
        fails = n < len(idx)
        if not same[:n].all():
            n, fails = int(np.argmin(same[:n])) + 1, False
        if n:
            ind = ind[:n]
            todo = np.flatnonzero(~cert[:n])
            if len(todo):
                ind[todo] = indicator(JB[todo])
            walk.accept(idx[:n], B[:n], ind)
    return n, fails


def certified(problem, P, A, idx, sign):
    """Which points' walk would end on their root of step 1; and those roots.

    The walk's damped Newton from the predictor ``P`` of a point ends, to
    rounding, on the root ``A`` (a residual within :data:`roots.TOL`) if
    (i) ``A``'s Jacobian has the assembly sign and a reciprocal condition
    number of at least :data:`CERTIFY_RATIO`, (ii) ``A`` is within half
    :data:`roots.MAX_CORRECTION` of ``P`` and (iii) the full Newton step
    from ``P`` lands within ``1e-3 |P - A| + 1e-14`` of ``A``.  Then that step
    decreases the residual (by (i), at least tenfold: no halving), Newton
    converges quadratically from where it lands, the polishing ends on ``A``
    to rounding, and the walk's acceptance (residual, determinant sign,
    correction) holds there as at ``A``.  Two evaluations and one solve per
    point instead of the walk's four and three.

    Returns ``(B, JB, indicator, certified)``: ``B`` and ``JB`` hold ``A`` and
    its Jacobian (and the indicator its reciprocal condition number) where
    certified; the other rows are the caller's to fill.
    """
    RP, JP = problem.evaluate_points(P, idx)
    d, bad = _solve_rows(JP, RP)
    B = np.array(A)
    ok = np.isfinite(B).all(axis=1)
    JB = np.full((len(idx),) + JP.shape[1:], np.nan)
    ind = np.full(len(idx), np.nan)
    cert = np.zeros(len(idx), bool)
    rows = np.flatnonzero(ok & ~bad)
    if not len(rows):
        return B, JB, ind, cert
    RA, JA = problem.evaluate_points(B[rows], idx[rows])
    JB[rows] = JA
    dist = np.max(np.abs(P[rows] - B[rows]), axis=1)
    landed = np.max(np.abs(P[rows] - d[rows] - B[rows]), axis=1)
    good = (
        (np.linalg.norm(RA, axis=1) <= TOL)
        & (np.sign(np.linalg.det(JA)) == sign)
        & (dist <= 0.5 * MAX_CORRECTION)
        & (landed <= 1e-3 * dist + 1e-14)
    )
    sel = rows[good]
    inv = inverses(JA[good])
    ind[sel] = indicator(JA[good], inv)
    cert[sel] = ind[sel] >= CERTIFY_RATIO
    # the last polishing step the walk takes, from A (A is one Newton step from a guess)
    B[sel] -= np.einsum("kij,kj->ki", inv, RA[good])
    return B, JB, ind, cert


def roots_near_points(problem, idx, ref, others, sign):
    """:func:`roots.roots_near` at each of the path points ``idx``, all at once.

    The same seeds around ``ref``, each with its lengths fitted to its angles
    at its point (the same least-squares call), the same bounded-step Newton row by
    row (:func:`roots.search_newton`), the converged ones polished by
    :func:`newton_points`, and each point's roots sorted and split by
    :func:`roots.distinct_roots`.  Returns one ``(same, other)`` per point.
    """
    angles = problem.angles
    base = search_seeds(ref, others, angles)
    rows = np.repeat(np.asarray(idx), len(base))
    seeds = np.tile(base, (len(idx), 1))
    lin = ~angles
    if lin.any():  # roots._project, row by row
        R, J = problem.evaluate_points(seeds, rows)
        for j in range(len(seeds)):
            d = np.linalg.lstsq(J[j][:, lin], -R[j], rcond=None)[0]
            if np.all(np.isfinite(d)):
                seeds[j, lin] += d
    U, done = search_newton(lambda V, r: problem.evaluate_points(V, rows[r]), seeds)
    V, res, J = newton_points(problem, U[done], rows[done])
    polished = res <= TOL
    point = np.flatnonzero(done) // len(base)
    return [
        distinct_roots(list(zip(V[sel], J[sel])), ref, angles, sign)
        for p in range(len(idx))
        for sel in [polished & (point == p)]
    ]


def search_gap(walk: Walk, idx: np.ndarray) -> int:
    """Points ``idx`` of a gap (the walk cannot continue to them): their root searches at once.

    The leading points without a root of the assembly sign are recorded as
    :meth:`Walk.step` records them; returns how many.  The first point with
    one is left to :meth:`Walk.step` (the re-entry, with its note).
    """
    ref, others = walk.search_from()
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        found = roots_near_points(walk.problem, idx, ref, others, walk.sign)
    for n, (i, (same, other)) in enumerate(zip(idx, found)):
        if same:
            return n
        walk.fail(int(i), ("other_mode", len(other)) if other else ("no_root", None))
    return len(idx)


def walk_path(walk: Walk, n_points: int) -> None:
    """Walk the whole path: blocks of points at once where the walk is continuous, the
    root searches of a gap at once, :meth:`Walk.step` everywhere else (see the module
    docstring)."""
    available = np.asarray(walk.problem.available(), bool)
    missing = np.flatnonzero(~available)
    walk.step(0)
    i, m, g = 1, MIN_BLOCK, 2
    while i < n_points:
        last = walk.last
        # up to the next point whose inputs are missing (an upstream group failed)
        k = np.searchsorted(missing, i)
        stop = min(n_points, int(missing[k]) if k < len(missing) else n_points)
        if not available[i]:
            walk.step(i)
            i += 1
        elif last is None or last[0] != i - 1:
            # a gap: no continuous path from the last solved point
            end = min(stop, i + g)
            n = search_gap(walk, np.arange(i, end))
            i += n
            if i < end:
                walk.step(i)  # a root of the assembly sign: the walk re-enters there
                i += 1
                g = 2
            else:
                g = min(2 * g, MAX_GAP)
        else:
            g = 2
            end = min(stop, i + m)
            n, fails = solve_block(walk, np.arange(i, end))
            i += n
            if fails:
                walk.step(i)  # the point the direct step does not take: the walk's own code
                i += 1
                m = MIN_BLOCK
            elif i < end:
                m = max(MIN_BLOCK, m // 2)  # the guesses did not reach: shorter blocks
            else:
                m = min(2 * m, MAX_BLOCK)
