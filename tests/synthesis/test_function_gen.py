"""Function generation (Freudenstein): precision points met exactly by the written scene as the
solver analyses it; a function taken from a known four-bar gives that four-bar back; the safe
expression parser refuses what is not arithmetic of x."""

import math

import numpy as np
import pytest

from linkage_sym.synthesis.common import SynthesisError
from linkage_sym.synthesis.expression import parse
from linkage_sym.synthesis.function_gen import (
    chebyshev,
    function_generator,
    structural_error,
    table_function,
)
from tests.support.funcpath_reference import random_crank_rocker, rocker_angle

EXACT = 1e-12
"""Output angle error (rad) at the precision points, measured by the solver."""


def _solver_error_at_points(d):
    ex = d.extra
    got = rocker_angle(d.scene, ex["phi"] + ex["crank_offset"]) - ex["psi_offset"]
    return np.abs(np.angle(np.exp(1j * (got - ex["psi"]))))


@pytest.mark.parametrize("text,ranges", [
    ("log10(x)", ((1.0, 10.0), (30.0, 120.0), (240.0, 330.0))),
    ("x**2", ((0.0, 1.0), (60.0, 150.0), (100.0, 40.0))),
    ("exp(x)", ((0.0, 1.0), (45.0, 135.0), (200.0, 290.0))),
    ("sin(pi*x/2)", ((0.0, 1.0), (30.0, 100.0), (250.0, 310.0))),
])
def test_three_precision_points_are_met_by_the_solver(text, ranges):
    f = parse(text)
    try:
        d = function_generator(f, *ranges)
    except SynthesisError as err:  # a range with no four-bar is refused, never returned
        pytest.skip(str(err))
    assert _solver_error_at_points(d).max() <= EXACT
    x, err = structural_error(d, f)
    xs = d.extra["x_points"]
    # the solver's error curve changes sign at the precision points (it vanishes there)
    assert np.nanmax(np.abs(err)) > 1e-6
    assert np.allclose(xs, chebyshev(*ranges[0], 3), rtol=0, atol=1e-15)


def test_the_function_of_a_known_four_bar_gives_it_back():
    rng = np.random.default_rng(7)
    for _ in range(5):
        known = random_crank_rocker(rng)
        a, b, c, d = (known.lengths[k] for k in ("crank", "coupler", "rocker", "ground"))
        phis = np.radians(np.linspace(20.0, 140.0, 121))
        psis = np.unwrap(rocker_angle(known.scene, phis))
        f = table_function(np.degrees(phis), np.degrees(psis))
        rng_x = (20.0, 140.0)
        for at in ([20.0, 80.0, 140.0], list(np.linspace(20.0, 140.0, 7))):  # exact and least squares
            got = function_generator(f, rng_x, rng_x, (math.degrees(psis[0]), math.degrees(psis[-1])),
                                     x_points=at, ground=d)
            for k, v in (("crank", a), ("coupler", b), ("rocker", c)):
                assert got.lengths[k] == pytest.approx(v, rel=1e-9)
            assert got.extra["equation_residual"] <= 1e-12


def test_least_squares_with_more_points():
    f = parse("log10(x)")
    d = function_generator(f, (1.0, 10.0), (30.0, 120.0), (240.0, 330.0), precision_points=7)
    assert len(d.extra["x_points"]) == 7
    x, err = structural_error(d, f)
    assert np.isfinite(err).all()


@pytest.mark.parametrize("text", ["__import__('os')", "x.real", "y + 1", "(lambda: 1)()",
                                  "x[0]", "open('f')", "sin(x, x)", "x if x else 1", "'a'"])
def test_expressions_outside_the_grammar_are_refused(text):
    with pytest.raises(SynthesisError):
        parse(text)


def test_expression_values():
    assert parse("2*x**2 - 3/x + pi")(np.array([2.0]))[0] == pytest.approx(8 - 1.5 + math.pi,
                                                                            rel=1e-15)


def test_refusals():
    f = parse("x")
    with pytest.raises(SynthesisError, match="precision_points"):
        function_generator(f, (0.0, 1.0), (0.0, 90.0), (90.0, 180.0), precision_points=2)
    with pytest.raises(SynthesisError, match="x_range"):
        function_generator(f, (1.0, 1.0), (0.0, 90.0), (90.0, 180.0))
    with pytest.raises(SynthesisError, match="function"):
        function_generator(parse("1 + 0*x"), (0.0, 1.0), (0.0, 90.0), (90.0, 180.0))
