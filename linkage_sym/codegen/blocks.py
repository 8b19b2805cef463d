"""The rate matrix ``A`` kept as its generated entries, solved block by block (NumPy).

``A`` of the rate problems ``A xd = B qd`` and ``A xdd = rhs`` is block lower-triangular
(one block per Assur group, in solving order) and sparse; the generated ``rates``
function gives its non-zero entries, each an array over the entries of a run (the steps
of a sweep, or designs x steps).  :class:`BlockSystem` keeps them coordinate-major: a
group's 2x2 or 3x3 block is contiguous arrays, its determinant formed once serves the
singularity screen (:meth:`BlockSystem.ratios`) and the solves (Cramer's rule for 1x1,
2x2 and 3x3 blocks, LU for larger ones); the coupling to earlier groups is a sum over
the pattern's entries.  A dense matrix is formed only for the entries whose condition
number is computed (:meth:`BlockSystem.dense`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["BlockSystem", "full"]


def _shape(shape) -> tuple:
    return (shape,) if isinstance(shape, (int, np.integer)) else tuple(shape)


def full(v, shape):
    """A generated function's output as an array of the entries' ``shape`` (a constant
    output comes back as a scalar: broadcast, read-only)."""
    shape = _shape(shape)
    if isinstance(v, np.ndarray) and v.shape == shape and v.dtype == np.float64:
        return v
    return np.broadcast_to(np.asarray(v, float), shape)


class BlockSystem:
    """``A`` of the rate problems over the entries of a run, kept as its generated entries.

    Parameters
    ----------
    entries : dict
        ``{(i, j): value}``, the non-zero entries; each value an array of the entries'
        ``shape`` or anything broadcasting to it (a design-independent entry of a design
        sweep stays (N,), a constant a number).
    blocks : list of tuple
        Each group's ``(r0, r1, c0, c1)``, in solving order.
    m : int
        Number of coordinates.
    shape : int or tuple
        The entries' shape: steps ``K``, or designs x steps ``(n, N)``.
    """

    def __init__(self, entries: dict, blocks, m: int, shape):
        self.entries, self.blocks, self.m = entries, blocks, m
        self.shape = _shape(shape)
        zero = 0.0  # a structural zero: broadcasts, no array of the entries' shape
        self._solvers = []
        for r0, r1, c0, c1 in blocks:
            n = c1 - c0
            get = lambda i, j: entries.get((i, j), zero)  # noqa: E731
            coupling = [(i - r0, j, v) for (i, j), v in entries.items() if r0 <= i < r1 and j < c0]
            if n == 1:
                own = (get(r0, c0),)
            elif n == 2:
                a, b, c, d = get(r0, c0), get(r0, c0 + 1), get(r0 + 1, c0), get(r0 + 1, c0 + 1)
                with np.errstate(invalid="ignore", over="ignore"):
                    own = (a, b, c, d, a * d - b * c)
            elif n == 3:  # the rows, and the adjugate's first column with the determinant
                R = [[get(r0 + i, c0 + j) for j in range(3)] for i in range(3)]
                (a, b, c), (d, e, f), (g, h, k) = R
                with np.errstate(invalid="ignore", over="ignore"):
                    co = (e * k - f * h, f * g - d * k, d * h - e * g)
                    own = (R, co, a * co[0] + b * co[1] + c * co[2])
            else:
                M = np.empty(self.shape + (n, n))
                for i in range(n):
                    for j in range(n):
                        M[..., i, j] = get(r0 + i, c0 + j)
                own = (M,)
            self._solvers.append((c0, n, coupling, own))

    @property
    def K(self) -> int:
        """The number of entries."""
        return int(np.prod(self.shape))

    @classmethod
    def of(cls, entries: dict, blocks, m, shape):
        """From the generated function's outputs by entry, every one made an array of
        ``shape`` (views: a constant is broadcast, not copied)."""
        return cls({ij: full(v, shape) for ij, v in entries.items()}, blocks, m, shape)

    def take(self, sel) -> "BlockSystem":
        """The system at the entries ``sel`` (a boolean mask or indices over ``shape``)."""
        got = {ij: np.broadcast_to(v, self.shape)[sel] for ij, v in self.entries.items()}
        shape = np.empty(self.shape, bool)[sel].shape
        return BlockSystem(got, self.blocks, self.m, shape)

    def ratios(self) -> list:
        """Each group block's Hadamard ratio (``|det|`` over the product of its row norms,
        and of its column norms, whichever is smaller) at every step; ``None`` for a 1x1
        block."""
        out = []
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for c0, n, _, own in self._solvers:
                if n == 1:
                    out.append(None)
                elif n == 2:
                    # a row that vanishes as a whole (every term of a loop projection zero)
                    # leaves the row ratio near one, the column ratio catches it, and the
                    # other way round
                    a, b, c, d, det = own
                    a2, b2, c2, d2 = a * a, b * b, c * c, d * d
                    out.append(np.abs(det) / np.sqrt(np.fmax((a2 + b2) * (c2 + d2),
                                                             (a2 + c2) * (b2 + d2))))
                elif n == 3:
                    R, _, det = own
                    sq = [[v * v for v in row] for row in R]
                    rows = np.sqrt((sq[0][0] + sq[0][1] + sq[0][2]) * (sq[1][0] + sq[1][1] + sq[1][2])
                                   * (sq[2][0] + sq[2][1] + sq[2][2]))
                    cols = np.sqrt((sq[0][0] + sq[1][0] + sq[2][0]) * (sq[0][1] + sq[1][1] + sq[2][1])
                                   * (sq[0][2] + sq[1][2] + sq[2][2]))
                    out.append(np.abs(det) / np.fmax(rows, cols))
                else:
                    M = own[0]
                    det = np.abs(np.linalg.det(M))
                    out.append(np.fmin(det / np.prod(np.linalg.norm(M, axis=-1), axis=-1),
                                       det / np.prod(np.linalg.norm(M, axis=-2), axis=-1)))
        return out

    def below(self, threshold) -> list:
        """Whether each group block's Hadamard ratio (:meth:`ratios`) is below
        ``threshold``, at every entry: ``det^2 < threshold^2 * norms^2``, without the
        square root and the division (False where the ratio is not a number); ``None``
        for a 1x1 block.  The same entries as ``ratio < threshold`` but within a few
        rounding errors of the threshold."""
        out, ratios = [], None
        t2 = threshold * threshold
        with np.errstate(invalid="ignore", over="ignore"):
            for c0, n, _, own in self._solvers:
                if n == 1:
                    out.append(None)
                    continue
                if n == 2:
                    a, b, c, d, det = own
                    a2, b2, c2, d2 = a * a, b * b, c * c, d * d
                    norms = np.fmax((a2 + b2) * (c2 + d2), (a2 + c2) * (b2 + d2))
                elif n == 3:
                    R, _, det = own
                    sq = [[v * v for v in row] for row in R]
                    rows = ((sq[0][0] + sq[0][1] + sq[0][2]) * (sq[1][0] + sq[1][1] + sq[1][2])
                            * (sq[2][0] + sq[2][1] + sq[2][2]))
                    cols = ((sq[0][0] + sq[1][0] + sq[2][0]) * (sq[0][1] + sq[1][1] + sq[2][1])
                            * (sq[0][2] + sq[1][2] + sq[2][2]))
                    norms = np.fmax(rows, cols)
                else:
                    if ratios is None:
                        ratios = self.ratios()
                    out.append(ratios[len(out)] < threshold)
                    continue
                out.append(det * det < t2 * norms)
        return out

    def dense(self, sel) -> np.ndarray:
        """``A`` (k, m, m) at the entries ``sel`` (indices, or a boolean mask over ``shape``)."""
        k = len(np.empty(self.shape, bool)[sel])
        A = np.zeros((k, self.m, self.m))
        for (i, j), v in self.entries.items():
            A[:, i, j] = np.broadcast_to(v, self.shape)[sel]
        return A

    def _needed(self, only):
        """The columns to solve for ``only`` (None: all): those, and the earlier groups'
        columns that the coupling of a group solved reads."""
        if only is None:
            return None
        need = set(only)
        for (c0, n, coupling, _) in reversed(self._solvers):
            if need & set(range(c0, c0 + n)):
                need |= {j for _, j, _ in coupling}
        return need

    def solve(self, rhs, only=None) -> np.ndarray:
        """``x`` (m, *shape) of ``A x = rhs``, ``rhs`` a sequence of ``m`` arrays over the
        entries (or broadcasting to them).  ``only``: the columns wanted (default all);
        the others are NaN where nothing wanted needs them (a group after the last one
        wanted is not solved, nor a 2x2 block's row not wanted)."""
        need = self._needed(only)
        covered = sum(n for _, n, _, _ in self._solvers) == self.m
        x = (np.empty if covered else np.zeros)((self.m,) + self.shape)
        xs = list(x)  # each solved coordinate as computed: a driver's row keeps its shape
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for (r0, r1, _, _), (c0, n, coupling, own) in zip(self.blocks, self._solvers):
                if need is not None and not need & set(range(c0, c0 + n)):
                    continue
                b = [rhs[r0 + i] for i in range(r1 - r0)]
                for i, j, v in coupling:
                    b[i] = b[i] - v * xs[j]
                if n == 1:  # over the right-hand side's own shape (a driver's row: the steps')
                    got = (np.divide(b[0], own[0]),)
                elif n == 2:  # into x's rows: no copy of a result
                    a, bb, c, d, det = own
                    got = (np.divide(np.subtract(b[0] * d, b[1] * bb, out=x[c0]), det, out=x[c0])
                           if need is None or c0 in need else x[c0],
                           np.divide(np.subtract(a * b[1], c * b[0], out=x[c0 + 1]), det,
                                     out=x[c0 + 1]) if need is None or c0 + 1 in need else x[c0 + 1])
                elif n == 3:  # Cramer: x = adj(M) b / det
                    ((a, bb, c), (d, e, f), (g, h, k)), co, det = own
                    got = ((co[0] * b[0] + (c * h - bb * k) * b[1] + (bb * f - c * e) * b[2]) / det,
                           (co[1] * b[0] + (a * k - c * g) * b[1] + (c * d - a * f) * b[2]) / det,
                           (co[2] * b[0] + (bb * g - a * h) * b[1] + (a * e - bb * d) * b[2]) / det)
                else:
                    bb = np.stack([np.broadcast_to(v, self.shape) for v in b], axis=-1)
                    got = np.moveaxis(np.linalg.solve(own[0], bb[..., None])[..., 0], -1, 0)
                for k, v in enumerate(got):
                    if not (isinstance(v, np.ndarray) and v.base is x):  # not written in place
                        x[c0 + k] = v
                    xs[c0 + k] = v
        if need is not None:
            for c in range(self.m):
                if c not in need:
                    x[c] = np.nan
        return x
