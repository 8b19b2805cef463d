"""The block lower-triangular rate solver of the compiled mechanism's evaluators."""

import numpy as np

from linkage_sym.codegen.blocks import BlockSystem



def _mixed_system(rng, n=4, N=5):
    """A block lower-triangular A over (n, N) entries, blocks 1x1, 2x2 and 3x3, its entries
    of every shape a design sweep passes (a number, a row (N,) shared by the designs, a full
    (n, N) array) and one structural zero inside the 3x3 block."""
    blocks = [(0, 1, 0, 1), (1, 3, 1, 3), (3, 6, 3, 6)]
    entries = {(0, 0): 1.0}
    for r0, r1, c0, c1 in blocks[1:]:
        for i in range(r0, r1):
            for j in range(c1):
                if (i, j) == (4, 5) or (j < c0 and rng.random() < 0.4):
                    continue  # the structural zero, some coupling left out
                shape = [(), (N,), (n, N)][(i + j) % 3]
                v = rng.uniform(-1.0, 1.0, shape) + (3.0 if i == j else 0.0)
                entries[(i, j)] = float(v) if shape == () else v
    return BlockSystem(entries, blocks, 6, (n, N)), entries


def _dense(entries, n, N):
    A = np.zeros((n, N, 6, 6))
    for (i, j), v in entries.items():
        A[..., i, j] = v
    return A


def test_mixed_shapes_solve_as_the_dense_matrices():
    """Entries of every shape (a design sweep keeps a design-independent one unbroadcast)
    solve as numpy.linalg.solve of each entry's dense matrix, to 1e-12 of its size, and each
    block's Hadamard ratio is |det| over the larger product of its row or column norms."""
    rng = np.random.default_rng(7)
    n, N = 4, 5
    A, entries = _mixed_system(rng, n, N)
    rhs = [2.0, rng.normal(size=N)] + [rng.normal(size=(n, N)) for _ in range(4)]
    x = A.solve(rhs)
    dense = _dense(entries, n, N)
    b = np.stack([np.broadcast_to(v, (n, N)) for v in rhs], axis=-1)
    ref = np.linalg.solve(dense, b[..., None])[..., 0]
    np.testing.assert_allclose(np.moveaxis(x, 0, -1), ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    for (r0, r1, c0, c1), ratio in zip(A.blocks, A.ratios()):
        if c1 - c0 == 1:
            assert ratio is None
            continue
        M = dense[..., r0:r1, c0:c1]
        det = np.abs(np.linalg.det(M))
        expect = np.fmin(det / np.prod(np.linalg.norm(M, axis=-1), axis=-1),
                         det / np.prod(np.linalg.norm(M, axis=-2), axis=-1))
        np.testing.assert_allclose(np.broadcast_to(ratio, (n, N)), expect, rtol=1e-12)


def test_rate_system_solves_as_the_dense_matrix():
    """The compiled run's rate solver (``codegen.blocks.BlockSystem``: the generated entries kept
    per coordinate, block by block) against ``numpy.linalg.solve`` of the dense block
    lower-triangular matrix, blocks of 1, 2, 3 (Cramer) and 4 (LU) coordinates with
    coupling entries: 1e-12 relative; the Hadamard ratios against the determinant and norms of the dense
    blocks; ``dense`` and ``take`` against indexing the dense matrix."""
    rng = np.random.default_rng(11)
    K, blocks = 50, [(0, 1, 0, 1), (1, 3, 1, 3), (3, 6, 3, 6), (6, 10, 6, 10)]
    m = 10
    A = np.zeros((K, m, m))
    for r0, r1, c0, c1 in blocks:
        A[:, r0:r1, c0:c1] = rng.normal(size=(K, r1 - r0, c1 - c0)) + 2 * np.eye(r1 - r0)
        A[:, r0:r1, :c0] = rng.normal(size=(K, r1 - r0, c0)) * (rng.random((r1 - r0, c0)) < 0.6)
    pattern = [(i, j) for i in range(m) for j in range(m) if np.any(A[:, i, j])]
    system = BlockSystem.of({(i, j): A[:, i, j] for i, j in pattern}, blocks, m, K)
    rhs = rng.normal(size=(K, m))
    want = np.linalg.solve(A, rhs[..., None])[..., 0]
    got = system.solve(list(rhs.T)).T
    assert np.allclose(got, want, rtol=1e-12, atol=1e-12 * np.abs(want).max())
    ratios = system.ratios()
    assert ratios[0] is None
    for ratio, (r0, r1, c0, c1) in zip(ratios[1:], blocks[1:]):
        M = A[:, r0:r1, c0:c1]
        det = np.abs(np.linalg.det(M))
        expect = np.fmin(det / np.prod(np.linalg.norm(M, axis=2), axis=1),
                         det / np.prod(np.linalg.norm(M, axis=1), axis=1))
        assert np.allclose(ratio, expect, rtol=1e-12)
    steps = np.array([3, 7, 40])
    assert np.array_equal(system.dense(steps), A[steps])
    mask = np.zeros(K, bool)
    mask[steps] = True
    assert np.allclose(system.take(mask).solve(list(rhs[steps].T)).T, want[steps], rtol=1e-12)


def test_the_screen_without_square_roots_flags_as_the_ratios():
    """``BlockSystem.below(t)`` (``det^2 < t^2 norms^2``) flags the entries whose Hadamard
    ratio (``ratios()``) is below ``t``, for blocks of 2 and 3 coordinates with entries of
    every shape, at thresholds away from every ratio by more than 1e-12 relative (the two
    may differ by a few rounding errors at the threshold itself); NaN entries are never
    flagged."""
    rng = np.random.default_rng(11)
    n, N = 4, 5
    A, _ = _mixed_system(rng, n, N)
    ratios = A.ratios()
    every = np.concatenate([np.ravel(r) for r in ratios if r is not None])
    for t in np.quantile(every, [0.1, 0.5, 0.9]) * (1 + 1e-9):
        assert np.all(np.abs(every / t - 1) > 1e-12)
        for ratio, low in zip(ratios, A.below(t)):
            if ratio is None:
                assert low is None
            else:
                np.testing.assert_array_equal(np.broadcast_to(low, (n, N)),
                                              np.broadcast_to(ratio < t, (n, N)))
    nan = BlockSystem({(0, 0): np.nan, (0, 1): 1.0, (1, 0): 1.0, (1, 1): 1.0},
                      [(0, 2, 0, 2)], 2, 3)
    assert not np.any(nan.below(1e-3)[0])


def test_only_the_wanted_columns_solve_as_all():
    """``solve(rhs, only)`` gives the wanted columns exactly as the whole solve (the groups
    they couple to solved as before), NaN for the columns nothing wanted reads."""
    rng = np.random.default_rng(13)
    n, N = 4, 5
    A, _ = _mixed_system(rng, n, N)
    rhs = [2.0, rng.normal(size=N)] + [rng.normal(size=(n, N)) for _ in range(4)]
    every = A.solve(rhs)
    for only, skipped in (([2], [3, 4, 5]), ([1], [2, 3, 4, 5]), ([4], []), ([0, 5], [])):
        got = A.solve(rhs, only)
        for c in only:
            np.testing.assert_array_equal(got[c], every[c])
        for c in skipped:
            assert np.isnan(got[c]).all()
