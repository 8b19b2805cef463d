"""The tangency test of the closed forms (``loci.clamp_tangent``) gathers its negative
entries by index (``loci.Entries``): the same numbers as the masks it replaced, written
here again from the rule (a factor within ``TANGENT_ULPS`` rounding errors of the
coordinates' size above zero is a tangency, 0; any other negative product NaN)."""

from __future__ import annotations

import numpy as np
import pytest

from linkage_sym.numeric.kinematics.loci import TANGENT_ULPS, Entries, Size, clamp_tangent

EPS = np.finfo(float).eps


def _by_masks(prod, factors, size):
    prod = np.array(prod, dtype=float)
    neg = prod < 0
    full = [np.broadcast_to(np.asarray(f, float), prod.shape) for f in factors]
    tol = TANGENT_ULPS * EPS * np.broadcast_to(size, prod.shape)
    worst = np.min([f[neg] for f in full], axis=0) if neg.any() else np.zeros(0)
    prod[neg] = np.where(worst >= -tol[neg], 0.0, np.nan)
    return prod


SHAPES = [((6, 7), (6, 1), (7,), ()), ((7,), (7,), (), ()), ((), (), (), ()),
          ((3, 4, 5), (4, 1), (3, 1, 1), (5,))]


@pytest.mark.parametrize("shapes", SHAPES)
def test_clamp_gathers_as_the_masks(shapes):
    rng = np.random.default_rng(len(shapes[0]))
    for trial in range(20):
        fs = [rng.uniform(-1.0, 1.0, s) for s in shapes]
        # some factors a rounding error below zero: tangencies
        fs[0] = np.where(rng.random(shapes[0]) < 0.3, -rng.uniform(0, 4, shapes[0]) * EPS, fs[0])
        values = (rng.uniform(0.5, 2.0, shapes[1]), rng.uniform(-3.0, 3.0, shapes[2]), 0.7)
        prod = fs[0] * fs[1] * fs[2] * fs[3]
        shape = np.shape(prod)
        size = np.maximum(np.maximum(np.abs(values[0]), np.abs(values[1])), 0.7)
        want = _by_masks(prod, fs, np.broadcast_to(size, shape))
        for scale in (Size(values), lambda: size):
            got = clamp_tangent(prod, fs, scale)
            np.testing.assert_array_equal(got, want)


def test_entries_take_and_put_as_a_mask():
    rng = np.random.default_rng(2)
    mask = rng.random((4, 5, 6)) < 0.4
    at = Entries(mask)
    for v in (rng.normal(size=(4, 5, 6)), rng.normal(size=(5, 1)), rng.normal(size=6),
              rng.normal(size=(4, 1, 6)), 2.5, rng.normal(size=(4, 5, 6))[:, ::-1]):
        np.testing.assert_array_equal(at.take(v), np.broadcast_to(v, mask.shape)[mask])
    a = np.zeros((4, 5, 6))
    at.put(a, np.arange(mask.sum(), dtype=float) + 1)
    b = np.zeros((4, 5, 6))
    b[mask] = np.arange(mask.sum()) + 1
    np.testing.assert_array_equal(a, b)


def test_clamp_in_place_gives_the_same_numbers():
    """``inplace=True`` (the caller's own product) clamps the array itself, to the same
    numbers; a product that is not C-contiguous is copied all the same."""
    rng = np.random.default_rng(9)
    f1 = rng.uniform(-1.0, 1.0, (5, 6))
    f2 = rng.uniform(0.5, 1.0, (5, 6))
    want = clamp_tangent(f1 * f2, (f1, f2), lambda: 1.0)
    prod = f1 * f2
    got = clamp_tangent(prod, (f1, f2), lambda: 1.0, inplace=True)
    assert got is prod
    np.testing.assert_array_equal(got, want)
    tp = (f1 * f2).T  # F-ordered: clamped in a copy
    got = clamp_tangent(tp, (f1.T, f2.T), lambda: 1.0, inplace=True)
    np.testing.assert_array_equal(got, want.T)
