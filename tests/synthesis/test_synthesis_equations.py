"""The SymPy design equations (``linkage_sym.synthesis.equations``).

Each derived relation is evaluated with the numbers of designs made by the
numeric synthesis (NumPy code that never imports this module) and must agree
to 1e-12; the LaTeX is parsed by ``latex2mathml`` (no TeX on CI).
"""

import functools
import math
import re

import pytest
import sympy as sp

from linkage_sym.synthesis import kratio
from linkage_sym.synthesis.equations import (
    H, K, R, a, alpha, b, c, chord, d, design_equations, e, l1, l2, latex_document, phi,
    plain_text, psi, theta,
)

REL = 1e-12



@functools.cache
def equations():
    """The derived relations by label: derived on first use, not at import (a few seconds of
    SymPy that collecting the tests, in every xdist worker, would otherwise pay)."""
    return {eq.label: eq for eq in design_equations()}


def value(label, **subs):
    eq = equations()[label]
    return float(eq.rhs.subs({sp.Symbol(k) if isinstance(k, str) else k: v for k, v in subs.items()}))


def test_theta_from_K_is_eq_2_2():
    assert sp.simplify(equations()["theta_K"].rhs - sp.pi * (K - 1) / (K + 1)) == 0
    for k in (1.2, 1.5, 2.0, 3.0):
        assert float(equations()["theta_K"].rhs.subs(K, k)) == pytest.approx(
            kratio.extreme_position_angle(k), rel=REL)


@pytest.mark.parametrize("kw", [{"ground": 0.1}, {"crank": 0.02}, {}])
def test_crank_rocker_relations_against_the_numeric_design(kw):
    Kv, cv, psiv = 1.5, 0.075, 45.0
    dsg = kratio.crank_rocker(Kv, cv, psiv, **kw)
    t, p, al = dsg.theta, math.radians(psiv), dsg.extra["alpha"]
    ch = float(equations()["chord"].rhs.subs({c: cv, psi: p}))
    Rv = float(equations()["radius"].rhs.subs({chord: ch, theta: t}))
    sub = {R: Rv, theta: t, alpha: al}
    assert float(equations()["crank_circle"].rhs.subs(sub)) == pytest.approx(dsg.lengths["crank"], rel=REL)
    assert float(equations()["coupler_circle"].rhs.subs(sub)) == pytest.approx(dsg.lengths["coupler"], rel=REL)
    L1, L2 = float(equations()["AC1"].rhs.subs(sub)), float(equations()["AC2"].rhs.subs(sub))
    assert float(equations()["crank"].rhs.subs({l1: L1, l2: L2})) == pytest.approx(dsg.lengths["crank"], rel=REL)
    if dsg.extra["arc"] == "far":  # the frame relation is written for the arc away from D
        d2 = float(equations()["frame"].rhs.subs({l1: L1, c: cv, alpha: al, psi: p}))
        assert math.sqrt(d2) == pytest.approx(dsg.lengths["ground"], rel=REL)
    # the minimum transmission angle: the worse of the two extremes
    L = {a: dsg.lengths["crank"], b: dsg.lengths["coupler"], c: cv, d: dsg.lengths["ground"]}
    g = [math.acos(float(equations()[k].rhs.subs(L))) for k in ("transmission_0", "transmission_pi")]
    assert min(min(x, math.pi - x) for x in g) == pytest.approx(dsg.gamma_min, rel=REL)
    assert float(equations()["transmission"].rhs.subs({**L, phi: 0})) == pytest.approx(
        float(equations()["transmission_0"].rhs.subs(L)), rel=REL)


@pytest.mark.parametrize("kw", [{"offset": 0.02}, {"crank": 0.04}, {}])
def test_slider_crank_relations_against_the_numeric_design(kw):
    Kv, Hv = 1.4, 0.1
    dsg = kratio.slider_crank(Kv, Hv, **kw)
    L = {a: dsg.lengths["crank"], b: dsg.lengths["coupler"], e: abs(dsg.lengths["offset"])}
    assert float(equations()["stroke"].rhs.subs(L)) == pytest.approx(Hv, rel=REL)
    Rv = Hv / (2 * math.sin(dsg.theta))
    assert float(equations()["stroke_circle"].rhs.subs({R: Rv, theta: dsg.theta})) == pytest.approx(Hv, rel=REL)
    assert float(equations()["offset"].rhs.subs({R: Rv, theta: dsg.theta, alpha: dsg.extra["alpha"]})) == \
        pytest.approx(L[e], rel=REL)
    assert float(equations()["offset_max"].rhs.subs({H: Hv, theta: dsg.theta})) == pytest.approx(
        Hv / math.tan(dsg.theta), rel=REL)
    assert math.acos(float(equations()["slider_transmission"].rhs.subs(L))) == pytest.approx(
        dsg.gamma_min, rel=REL)


def test_guide_bar_relations():
    dsg = kratio.guide_bar(2.0, 0.4)
    assert float(equations()["guide_crank"].rhs.subs({d: 0.4, theta: dsg.theta})) == pytest.approx(
        dsg.lengths["crank"], rel=REL)
    assert equations()["guide_swing"].rhs == theta


@pytest.mark.slow
def test_every_check_reduces_to_zero():
    """design_equations asserts it; here again, by a second route (numbers at random points)."""
    import random

    rnd = random.Random(1)
    for eq in design_equations():
        if eq.check is None:
            continue
        for _ in range(5):
            vals = {s: sp.Rational(rnd.randint(200, 1200), 1000) for s in eq.check.free_symbols}
            assert abs(complex(eq.check.subs(vals).evalf(30))) <= 1e-25, eq.label


latex2mathml = pytest.importorskip("latex2mathml.converter")


@pytest.mark.slow
def test_latex_parses_and_labels_are_unique():
    doc = latex_document()
    bodies = re.findall(r"\\begin\{equation\}(.*?)\\end\{equation\}", doc, re.S)
    assert len(bodies) == len(design_equations())
    for body in bodies:
        tex = re.sub(r"\\label\{[^}]*\}", "", body)
        mathml = latex2mathml.convert(tex)
        assert "\\" not in mathml.replace("\\\\", ""), tex
    labels = re.findall(r"\\label\{([^}]*)\}", doc)
    assert len(labels) == len(set(labels))
    for inline in re.findall(r"\$([^$]+)\$", doc):
        latex2mathml.convert(inline)
    assert doc.count("\\begin{itemize}") == doc.count("\\end{itemize}") == 1
    assert "seed" not in doc.lower() and "seed" not in plain_text().lower()
