"""The closed steps' directions functions (``directions_<k>``: the coordinates without the
angles' arctangents) and ``unit_direction``, against the positions functions' angles put
through NumPy's ``cos`` and ``sin``."""

from __future__ import annotations

import numpy as np
import pytest

from linkage_sym.codegen.evaluator import unit_direction
from linkage_sym.design.evaluate import compiled
from linkage_sym.examples import load_example
from tests.support.marks import slow_cases

EXAMPLES = ["crank_rocker", "slider_crank_offset", "stephenson_sixbar", "watt_sixbar", "shaper"]


# the six-bars and the shaper (a derivation each, about 0.5 s) in the default run only
@pytest.mark.parametrize("name", slow_cases(EXAMPLES, {"stephenson_sixbar", "watt_sixbar", "shaper"}))
def test_directions_give_the_cosines_and_sines_of_the_positions_angles(name):
    """At 50 driver values around the scene's, every closed step's directions function gives
    each angle's cosine and sine within 2e-15 of ``cos``/``sin`` of the positions function's
    angle (that angle carries the rounding of ``arctan2`` and of its offset, up to an ulp of
    2 pi, 8.9e-16, before ``cos`` and ``sin``; the unit vector a few ulps of 1), each slide's
    value within 8 ulps of the positions function's (the same expression, its common
    subexpressions grouped otherwise), and NaN exactly where the positions are."""
    scene = load_example(name)
    cm = compiled(scene)
    art = cm.art
    rng = np.random.default_rng(3)
    Q = [cm.q0[k] + rng.uniform(-2.0, 2.0, 50) for k in art.q]
    X = [None] * len(art.x)
    P = [float(v) for v in cm.params]
    for step in art.steps:
        assert step.directions is not None
        with np.errstate(invalid="ignore"):
            pos = cm.functions[step.function](X, None, None, Q, None, None, None, P)
            out = iter(cm.functions[step.directions](X, None, None, Q, None, None, None, P))
        for c, form, x in zip(step.x, step.forms, pos):
            x = np.broadcast_to(np.asarray(x, float), (50,))
            X[c] = x
            if form == "value":  # the same expression, its common subexpressions in other orders
                v = np.broadcast_to(next(out), (50,))
                np.testing.assert_array_equal(np.isnan(v), np.isnan(x))
                ok = np.isfinite(x)
                np.testing.assert_allclose(v[ok], x[ok], rtol=0, atol=8 * np.finfo(float).eps
                                           * np.abs(x[ok]).max())
                continue
            if form == "unit":
                cos, sin = next(out), next(out)
            else:
                cos, sin = unit_direction(*(next(out) for _ in range(4)))
            cos, sin = (np.broadcast_to(np.asarray(v, float), (50,)) for v in (cos, sin))
            np.testing.assert_array_equal(np.isnan(cos), np.isnan(x))
            ok = np.isfinite(x)
            np.testing.assert_allclose(cos[ok], np.cos(x[ok]), rtol=0, atol=2e-15)
            np.testing.assert_allclose(sin[ok], np.sin(x[ok]), rtol=0, atol=2e-15)


def test_unit_direction_is_arctan2s_direction_turned():
    """``unit_direction(Y, X, cos r, sin r)`` is ``(cos, sin)`` of ``arctan2(Y, X) + r``: within
    1e-15 for random vectors and turns, r a multiple of pi and not (the reference's angle
    rounded to an ulp of up to 4, 8.9e-16, then cos and sin), exactly ``arctan2``'s own
    for a zero vector (its signed zeros included) and one whose length overflows, NaN where
    ``Y`` or ``X`` is NaN; ``out`` receives the same numbers."""
    rng = np.random.default_rng(5)
    Y, X = rng.normal(size=(2, 7, 9)) * 10.0 ** rng.integers(-8, 8, size=(2, 7, 9))
    Y[0, :4] = [0.0, -0.0, 0.0, 1e300]
    X[0, :4] = [-0.0, -0.0, 0.0, 1e300]
    Y[1, 0] = np.nan
    for r in (0.0, -np.pi, 0.7, np.array([[0.3]] * 7)):
        cr, sr = (np.cos(r), np.sin(r)) if np.ndim(r) else (float(np.cos(r)), float(np.sin(r)))
        if np.ndim(r) == 0 and float(r) in (0.0, -np.pi):
            cr, sr = (1, 0) if r == 0 else (-1, 0)  # the generated code's exact turns
        c, s = unit_direction(Y, X, cr, sr)
        a = np.arctan2(Y, X) + r
        np.testing.assert_allclose(c, np.cos(a), rtol=0, atol=1e-15)
        np.testing.assert_allclose(s, np.sin(a), rtol=0, atol=1e-15)
        assert np.isnan(c[1, 0]) and np.isnan(s[1, 0])
        out = (np.empty((7, 9)), np.empty((7, 9)))
        c2, s2 = unit_direction(Y, X, cr, sr, out=out)
        assert c2 is out[0] and s2 is out[1]
        np.testing.assert_array_equal(c2, c)
        np.testing.assert_array_equal(s2, s)
    c, s = unit_direction(Y, X, 1, 0)
    a = np.arctan2(Y[0, :4], X[0, :4])
    np.testing.assert_array_equal(c[0, :4], np.cos(a))
    np.testing.assert_array_equal(s[0, :4], np.sin(a))
