"""The output link's limit positions in a design sweep: ``K`` and the swing.

A limit position is a root of the output's rate along the steps between two ``ok``
steps where the rate changes sign (as ``analyze --extremes`` locates them).  A chunk's
solution gives its brackets (:class:`Limits`); :func:`locate` finds the roots of many
chunks' brackets at once -- one Newton iteration over all of them, on the rate and its
own rate from the compiled mechanism's functions (:meth:`~linkage_sym.design.evaluate.Model.rate_at`)
-- and :meth:`Limits.finish` gives each chunk's ``K``, swing and notes.  Newton acts on
each bracket alone (every operation elementwise), so a design's roots do not depend on
the brackets located with it: locating the chunks of a run together costs one call of
the generated functions per iteration instead of one per chunk and iteration.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["K_NOTES", "MAX_ITER", "XTOL", "Limits", "locate", "roots"]

K_NOTES = {
    "assembly": "not assembled at the scene's driver values",
    "no ok step": "no step is ok",
    "partial": "the sweep does not turn the driver a full turn",
    "steps": "a step of the driver's turn is not ok (unassemblable or singular)",
    "not located": "a limit position was not located (Newton on the output's rate did not converge)",
    "count": "the output has not exactly two limit positions in the driver's turn",
    "kinds": "the two limit positions are both maxima or both minima",
}
"""Why ``K`` has no value: the ``K_note`` column holds one of these (empty where ``K`` has a
value)."""

XTOL = 1e-12
"""Limit positions are located to this many steps (plus 4 ulp of the position)."""
MAX_ITER = 100


def _per_design(v) -> bool:
    return isinstance(v, np.ndarray) and v.ndim > 0


def _fmax(a):
    return np.fmax.reduce(a, axis=1) if a.shape[1] else np.full(len(a), np.nan)


def _fmin(a):
    return np.fmin.reduce(a, axis=1) if a.shape[1] else np.full(len(a), np.nan)


class Limits:
    """One chunk's limit positions before they are located: its brackets and what ``K``
    and the swing read besides the roots (per design and per bracket: no array over the
    steps is kept).

    Parameters
    ----------
    model : Model
    sol : Solution
        The chunk, with its rates along the steps (``rate_t``), or the brackets of their
        sign changes (``brackets``).
    col : int
        The output link's coordinate.
    swing : bool
        The swing is asked for (it reads the output's angles).
    """

    def __init__(self, model, sol, col, swing):
        n, N = sol.n, sol.N
        self.n, self.col, self.assembled = n, col, sol.assembled
        ok = sol.ok
        if sol.brackets is not None:  # found by the solver (the numba backend's loop)
            d, i, self.fa, self.fb = sol.brackets
        else:
            r = np.ascontiguousarray(sol.rate_t[col])
            # a bracket: two ok steps between which the rate changes sign (or is 0 at one)
            with np.errstate(invalid="ignore"):
                neg, zero = r < 0, r == 0
            change = (neg[:, :-1] != neg[:, 1:]) | zero[:, :-1] | zero[:, 1:]
            change &= ok[:, :-1]
            change &= ok[:, 1:]
            d, i = np.divmod(np.flatnonzero(change), N - 1)  # row-major, as np.nonzero
            at = d * N + i
            self.fa, self.fb = r.ravel()[at], r.ravel()[at + 1]
        self.d, self.i = d, i
        self.ok_any = ok.any(axis=1)
        step = abs(model.slope[0]) if N > 1 else 0.0
        self.step = step
        self.turn = step > 0 and step * (N - 1) >= 2 * math.pi * (1 - 1e-12)
        if self.turn:
            self.T = 2 * math.pi / step  # steps of one turn
            self.full = ok[:, : min(N - 1, int(math.ceil(self.T))) + 1].all(axis=1)
        # the brackets' designs' parameters: the roots of a run's chunks are located at once
        self.P = [v[d] if _per_design(v) else v for v in sol.P]
        # the solution's own rate where it is not the compiled functions' (one at a time)
        self.own_rate = None if sol.model_rates else (lambda k, t: sol.rate_at(d[k], t, col))
        self.rot = None
        if swing:
            rot = sol.X[col] - sol.X0[col][:, None]
            # the positions are NaN where a step has none: only singular steps need masking
            rot_ok = rot if sol.ok is sol.pos_ok else np.where(sol.ok, rot, np.nan)
            self.hi, self.lo = _fmax(rot_ok), _fmin(rot_ok)
            self.rot, self.x0 = rot[d, i], sol.X0[col][d]

    def finish(self, t, kind, raw):
        """``(K, swing, note)`` of the chunk's designs from the roots ``t`` (fractional
        steps, NaN where not located), their ``kind`` (+1 a maximum, -1 a minimum) and the
        output's angle ``raw`` there (for the swing; None when not asked for)."""
        n, d, i, step = self.n, self.d, self.i, self.step
        good = np.isfinite(t)
        swing = None
        if self.rot is not None:  # the values at the roots, continuous with the sample before
            v = raw - self.x0
            v = v + 2 * math.pi * np.round((self.rot - v) / (2 * math.pi))
            hi, lo = self.hi.copy(), self.lo.copy()
            fin = np.isfinite(v)
            np.fmax.at(hi, d[fin], v[fin])
            np.fmin.at(lo, d[fin], v[fin])
            swing = np.degrees(hi - lo)
        K = np.full(n, np.nan)
        note = np.full(n, K_NOTES["no ok step"], dtype=object)
        note[~self.assembled] = K_NOTES["assembly"]
        if not self.turn:
            note[self.ok_any] = K_NOTES["partial"]
            return K, swing, note.astype(str)
        T, full = self.T, self.full
        note[self.ok_any & ~full] = K_NOTES["steps"]
        in_turn = i < T
        first = good & (t < T)
        cnt = np.bincount(d[first], minlength=n)
        lost = np.bincount(d[in_turn & ~good], minlength=n) > 0
        note[full & lost] = K_NOTES["not located"]
        note[full & ~lost & (cnt != 2)] = K_NOTES["count"]
        # the roots come design by design (np.nonzero is row-major): a design's two are
        # consecutive among those of the first turn
        sel = np.flatnonzero(first)
        start = np.concatenate([[0], np.cumsum(cnt)[:-1]])
        ks = np.flatnonzero(full & ~lost & (cnt == 2))
        j0, j1 = sel[start[ks]], sel[start[ks] + 1]
        same = kind[j0] == kind[j1]
        note[ks[same]] = K_NOTES["kinds"]
        ks, j0, j1 = ks[~same], j0[~same], j1[~same]
        a = np.abs(t[j1] - t[j0]) * step
        b = 2 * math.pi - a
        K[ks] = np.maximum(a, b) / np.minimum(a, b)
        note[ks] = ""
        return K, swing, note.astype(str)


def _joined(items):
    """The parameters of every bracket of ``items``, in order (a number shared by all
    stays a number)."""
    P = []
    for vals in zip(*(it.P for it in items)):
        if not any(_per_design(v) for v in vals) and all(v == vals[0] for v in vals):
            P.append(vals[0])
        else:
            P.append(np.concatenate([np.broadcast_to(v, (len(it.d),))
                                     for v, it in zip(vals, items)]))
    return P


def locate(model, items) -> list:
    """Each of ``items`` (:class:`Limits`) finished: ``(K, swing, note)``.  The brackets of
    the items solved by the compiled functions are located together (one Newton over all),
    the others each by its solution's own rate."""
    out = [None] * len(items)
    batch = [k for k, it in enumerate(items) if it.own_rate is None]
    groups = [(batch, None)] if batch else []
    groups += [([k], items[k].own_rate) for k, it in enumerate(items) if it.own_rate is not None]
    for ks, own in groups:
        its = [items[k] for k in ks]
        col = its[0].col
        if own is None:
            P = _joined(its)
            rate = lambda k, t: model.rate_at(P, k, t, col)  # noqa: E731
        else:
            rate = own
        a = np.concatenate([it.i for it in its]).astype(float)
        fa, fb = np.concatenate([it.fa for it in its]), np.concatenate([it.fb for it in its])
        # a model with its own compiled Newton (the numba backend's) locates them itself
        own_newton = getattr(model, "compiled_roots", None) if own is None else None
        got = None if own_newton is None else own_newton(P, a, fa, fb, col)
        t, kind = roots(rate, a, fa, fb) if got is None else got
        swing = any(it.rot is not None for it in its)
        raw = (rate(np.arange(len(t)), t)[2] if len(t) else np.zeros(0)) if swing else None
        at = np.cumsum([0] + [len(it.d) for it in its])
        for k, it, a0, a1 in zip(ks, its, at[:-1], at[1:]):
            out[k] = it.finish(t[a0:a1], kind[a0:a1], None if raw is None else raw[a0:a1])
    return out


def roots(rate, a, fa, fb):
    """Roots of a rate between steps ``a`` and ``a + 1`` of brackets (arrays over them),
    every bracket at once: Newton on the rate (its derivative from the accelerations),
    kept in the bracket by bisection.  ``rate(k, t)`` gives the rate, its own rate and
    the coordinate of brackets ``k`` at fractional steps ``t``.  Returns ``(t, kind)``,
    ``kind`` +1 at a maximum, -1 at a minimum, ``t`` NaN where the rate is not defined or
    does not converge."""
    b = a + 1.0
    kind = np.where((fa > 0) | (fb < 0), 1, -1)
    t = np.where(fa == 0, a, b)
    act = np.flatnonzero(~((fa == 0) | (fb == 0)))
    lo, hi = a.copy(), b.copy()
    flo = fa.copy()
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(fb != fa, b - fb * (b - a) / (fb - fa), 0.5 * (a + b))  # secant start
        for _ in range(MAX_ITER):
            if not len(act):
                break
            X = x[act]
            f, df, _ = rate(act, X)
            bad = ~np.isfinite(f)
            t[act[bad]] = np.nan
            same = (f < 0) == (flo[act] < 0)  # the root lies above X
            lo[act] = np.where(same, X, lo[act])
            flo[act] = np.where(same, f, flo[act])
            hi[act] = np.where(same, hi[act], X)
            step = f / df
            xn = X - step
            L, H = lo[act], hi[act]
            conv = (f == 0) | (np.abs(step) <= XTOL + 4 * np.finfo(float).eps * np.abs(X))
            t[act] = np.where(f == 0, X, xn)
            xn = np.where((xn > L) & (xn < H), xn, 0.5 * (L + H))
            x[act] = xn
            act = act[~(conv | bad)]
    t[act] = np.nan  # no convergence
    return t, kind
