"""The generated functions printed as scalar code (linkage_sym.codegen.scalar) give the
NumPy functions' values, entry by entry, with the drivers' terms hoisted per step.

The scalar code runs here as plain Python (no numba): each entry of a NumPy call over
designs x steps (the designs' parameters (n, 1), the driver values (N,)) against the
scalar function at that design and step.  Tolerance: 1e-14 relative to each output's
largest magnitude (the same operations in the same order; observed: equal).
"""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.evaluator import numpy_namespace
from linkage_sym.codegen.scalar import ScalarPrintError, scalar_function, scalar_helpers
from linkage_sym.design.evaluate import Model
from linkage_sym.numeric.kinematics.loci import _EPS, TANGENT_ULPS


def _scalar(art, name):
    s = scalar_function(art.functions[name], name)
    ns = numpy_namespace()
    ns.update(TANGENT_ULPS=TANGENT_ULPS, EPS=_EPS, nan=np.nan)
    exec(scalar_helpers(s.arities), ns)
    exec(s.source, ns)
    exec(s.pre_source, ns)
    return s, ns[name], ns["pre_" + name]


# the six-bar and the shaper (a derivation each, about 1 s) in the default run only
@pytest.mark.parametrize("example", ["crank_rocker", "slider_crank_offset",
                                     pytest.param("watt_sixbar", marks=pytest.mark.slow),
                                     pytest.param("shaper", marks=pytest.mark.slow)])
def test_scalar_functions_equal_numpy_entry_by_entry(example):
    model = Model(linkage_sym.load_example(example))
    art, m = model.art, model.m
    rng = np.random.default_rng(3)
    n = 6
    P = [np.asarray(v, float) * rng.uniform(0.7, 1.3, (n, 1)) if i < art.n_params else v
         for i, v in enumerate(model.params)]  # the signs stay
    Q = [row[::40] for row in model.Q]
    N = len(Q[0])
    X = [rng.uniform(-3, 3, (n, N)) for _ in range(m)]
    C, S = [np.cos(x) for x in X], [np.sin(x) for x in X]
    QD = [np.full(N, 0.7)] * len(Q)
    names = [n_ for n_ in ("positions_0", "directions_0", "rates", "accelerations")
             if n_ in art.functions]
    for name in names:
        with np.errstate(invalid="ignore", divide="ignore"):
            ref = model.call(name, P, X=X, XD=X, XDD=X, Q=Q, QD=QD, QDD=QD, CS=(C, S))
        s, f, pre = _scalar(art, name)
        assert s.outputs == len(ref)
        H = np.zeros(max(s.hoisted, 1))
        out = np.empty(s.outputs)
        for t in range(N):
            q = np.array([r[t] for r in Q])
            qd = np.array([r[t] for r in QD])
            pre(q, qd, qd, H)
            for d in range(n):
                Pd = np.array([np.broadcast_to(v, (n, 1))[d, 0] for v in P])
                Xd = np.array([x[d, t] for x in X])
                with np.errstate(invalid="ignore", divide="ignore"):
                    f(Xd, Xd, Xd, q, qd, qd, np.zeros(0), Pd, np.cos(Xd), np.sin(Xd), H, out)
                for k, v in enumerate(ref):
                    want = np.broadcast_to(v, (n, N))[d, t]
                    scale = np.nanmax(np.abs(np.broadcast_to(v, (n, N))))
                    assert (np.isnan(want) and np.isnan(out[k])) or \
                        abs(out[k] - want) <= 1e-14 * max(scale, 1e-300), (example, name, k)


def test_hoisting_leaves_design_terms_and_refuses_unknown_statements():
    src = ("def f(X, XD, XDD, Q, QD, QDD, FORCES, P, CX=None, SX=None):\n"
           "    [q_A] = Q\n    [l] = P\n    x0 = cos(q_A)*l + sin(l)\n    return [x0, sqrt(q_A)]\n")
    s = scalar_function(src, "f")
    assert "H[0] * l + sin(l)" in s.source and "out[1] = H[1]" in s.source
    assert s.hoisted == 2
    with pytest.raises(ScalarPrintError, match="a statement the derivation does not print"):
        scalar_function(src.replace("    x0 =", "    for i in X: pass\n    x0 ="), "f")
