"""Angles made continuous along a design sweep's steps (NumPy), for
:meth:`linkage_sym.design.evaluate.Model.positions_at_steps`: ``np.unwrap`` over each
design's steps with positions, from its assembly configuration."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["unwrap_fast", "unwrap_rows"]


def unwrap_fast(A, valid, start, every):
    """:func:`unwrap_rows` (the same numbers), skipping the rows with every entry valid
    and no jump of more than half a turn from ``start`` and between steps (the usual case:
    nothing to unwrap)."""
    n, K = A.shape
    rows = np.ones(n, bool) if not every else None
    with np.errstate(invalid="ignore"):
        jump = np.abs(np.diff(A, axis=1)) > math.pi
        if start is not None:
            first = np.abs(A[:, 0] - start) > math.pi
        todo = jump.any(axis=1) | (first if start is not None else False)
    if not every:
        rows = todo | ~valid.all(axis=1)
    else:
        rows = todo
    if not rows.any():
        return A
    out = A.copy()
    out[rows] = unwrap_rows(A[rows], valid[rows], None if start is None else start[rows])
    return out


def unwrap_rows(A, valid, start):
    """``np.unwrap`` of each row of ``A`` over its ``valid`` entries (the others NaN),
    preceded by ``start`` (n,) when given (the assembly configuration)."""
    n, K = A.shape
    pos = np.where(valid, np.arange(K)[None, :], -1)
    last = np.maximum.accumulate(pos, axis=1)
    prev = np.empty_like(last)
    prev[:, 0] = -1
    prev[:, 1:] = last[:, :-1]
    pv = np.take_along_axis(A, np.maximum(prev, 0), axis=1)
    if start is not None:
        pv = np.where(prev >= 0, pv, start[:, None])
        has = valid
    else:
        has = valid & (prev >= 0)
    dd = np.where(has, A - pv, 0.0)
    ddmod = np.mod(dd + math.pi, 2 * math.pi) - math.pi
    ddmod[(ddmod == -math.pi) & (dd > 0)] = math.pi
    corr = ddmod - dd
    corr[np.abs(dd) < math.pi] = 0.0
    out = A + np.cumsum(corr, axis=1)
    out[~valid] = np.nan
    return out
