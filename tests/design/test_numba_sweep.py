"""The numba backend of the design sweep against the NumPy backend, design by design.

Every metric column (``assemblable``, ``grashof``, ``K``, ``K_note``,
``min_transmission_deg``), each design's status at each step (``pos_ok``: positions;
``ok``: positions and not singular) and the limit positions (the brackets of the output's
rate along the steps and the roots located in them) of the crank-rocker, an offset
slider-crank and a Watt six-bar, over grids holding designs that cannot be assembled at
all, designs that lose their positions over part of the turn, and change-point designs
(flat at a step: a dead centre, singular).  Tolerance: 1e-12 relative (the same formulas
in the same order, one entry at a time instead of over arrays; observed: equal bit for
bit).  Skipped without numba (the ``numba`` extra).
"""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.design import Execution, SweepError
from linkage_sym.design.execute import Spec, compiled_state
from linkage_sym.design.limits import roots
from linkage_sym.examples import example_path

numba = pytest.importorskip("numba", reason="the numba backend needs numba (the numba extra)")

RTOL = 1e-12
NUMBA = Execution(backend="numba")


def _crank_rocker():
    scene = linkage_sym.load_example("crank_rocker")
    d = scene.drivers[0]
    return dataclasses.replace(scene, drivers=(dataclasses.replace(d, start=0.0,
                                                                   stop=2 * math.pi, steps=361),))


# l_CD = 0.039 with l_BC = 0.063: 0.024 + 0.078 = 0.063 + 0.039, a change point (flat, a dead
# centre at a step); small rockers: not assembled at the scene's driver values; long ones:
# assembled over part of the turn only
CRANK_AXES = {"l_BC": [0.045, 0.055, 0.063, 0.07, 0.085],
              "l_CD": [0.02, 0.025, 0.039, 0.045, 0.0485, 0.06, 0.075, 0.1]}


def _same(a, b):
    """The NumPy backend's table ``a`` and the numba backend's ``b``: the same columns, text
    equal, numbers within RTOL (NaN at the same designs)."""
    assert list(a.columns) == list(b.columns)
    for c in a.columns:
        x, y = np.asarray(a[c]), np.asarray(b[c])
        if x.dtype.kind != "f":
            assert (x == y).all(), c
            continue
        assert np.array_equal(np.isnan(x), np.isnan(y)), c
        f = np.isfinite(x)
        assert np.all(np.abs(x[f] - y[f]) <= RTOL * np.abs(x[f])), c


def _around(scene, names, lo, hi, k):
    """``k`` values of each of ``names`` from ``lo`` to ``hi`` times the scene's."""
    rows = {n: v for n, v, _ in linkage_sym.design.scene_parameters(scene)}
    return {n: rows[n] * np.linspace(lo, hi, k) for n in names}


CASES = [
    ("crank_rocker", _crank_rocker, lambda scene: CRANK_AXES,
     ["assemblable", "grashof", "K", "min_transmission_deg"], None),
    ("slider_crank_offset", lambda: linkage_sym.load_example("slider_crank_offset"),
     lambda scene: {"l_AB": np.linspace(0.01, 0.2, 12), "l_BC": np.linspace(0.02, 0.3, 12)},
     ["assemblable", "K"], "connecting_rod"),
    ("watt_sixbar", lambda: linkage_sym.load_example("watt_sixbar"),
     lambda scene: _around(scene, ("l_AB", "l_BC"), 0.4, 3.0, 8),
     ["assemblable", "grashof", "K", "min_transmission_deg"], None),
]


@pytest.mark.slow
@pytest.mark.parametrize("name, make, axes, metrics, output", CASES, ids=[c[0] for c in CASES])
def test_metrics_statuses_and_limit_positions_equal_numpy(name, make, axes, metrics, output):
    scene = make()
    axes = axes(scene)
    a = linkage_sym.sweep(scene, axes, metrics, output=output)
    b = linkage_sym.sweep(scene, axes, metrics, output=output, execution=NUMBA)
    _same(a, b)
    assm = np.asarray(a["assemblable"])
    # the grids hold designs not assembled, assembled over part of the turn, and whole
    assert (assm == 0).any() and ((assm > 0) & (assm < 1)).any() and (assm == 1).any()
    assert (np.asarray(a["K"], float) > 0).any()
    # statuses per design and step, and the limit positions, from one chunk of each backend
    names = tuple(axes)
    values = np.array(np.meshgrid(*axes.values(), indexing="ij")).reshape(len(names), -1).T
    sols = []
    for backend in ("numpy", "numba"):
        model, plan = compiled_state(Spec(scene, names, tuple(metrics), output,
                                          backend=backend))
        P = model.design_params(names, values)
        sol = model.solve(P, len(values), plan.need, plan.unwrap(model), rates=plan.rates(model))
        col = model.angle_of[plan.output]
        lim = plan.begin(model, sol)[1]
        t, kind = roots(lambda k, x: model.rate_at(lim.P, k, x, col), lim.i.astype(float),
                        lim.fa, lim.fb)
        sols.append((sol, lim, t, kind))
    (s0, l0, t0, k0), (s1, l1, t1, k1) = sols
    assert np.array_equal(s0.pos_ok, s1.pos_ok) and np.array_equal(s0.ok, s1.ok)
    assert np.array_equal(s0.assembled, s1.assembled)
    assert np.array_equal(l0.d, l1.d) and np.array_equal(l0.i, l1.i)
    assert np.allclose(l0.fa, l1.fa, rtol=RTOL, atol=0) and np.allclose(l0.fb, l1.fb, rtol=RTOL, atol=0)
    assert np.array_equal(np.isnan(t0), np.isnan(t1)) and np.array_equal(k0, k1)
    f = np.isfinite(t0)
    assert np.all(np.abs(t0[f] - t1[f]) <= RTOL * np.abs(t0[f]))
    # the numba backend's own Newton (compiled) on its brackets: NumPy's roots and kinds
    tc, kc = model.compiled_roots(l1.P, l1.i.astype(float), l1.fa, l1.fb, col)
    assert np.array_equal(kc, k0) and np.array_equal(np.isnan(tc), np.isnan(t0))
    assert np.all(np.abs(tc[f] - t0[f]) <= RTOL * np.abs(t0[f]))
    if name == "crank_rocker":  # the change point: singular at a step, ok elsewhere
        flat = np.flatnonzero((values[:, 0] == 0.063) & (values[:, 1] == 0.039))[0]
        assert s0.pos_ok[flat].all() and not s0.ok[flat].all() and s0.ok[flat].any()


@pytest.mark.slow
def test_rare_entries_past_the_first_block():
    # the compiled loop takes the designs in blocks of numba_block.BLOCK (64); the change point
    # (l_BC 0.063, l_CD 0.039: flat at a step, where the screen flags and the condition
    # number decides) is design 65 here, in the second block, at its second design
    from linkage_sym.design.numba_block import BLOCK

    scene = _crank_rocker()
    axes = {"l_BC": [0.045, 0.048, 0.05, 0.053, 0.055, 0.058, 0.06, 0.063, 0.07],
            "l_CD": [0.02, 0.03, 0.039, 0.045, 0.05, 0.055, 0.06, 0.075, 0.1]}
    metrics = ["assemblable", "K", "min_transmission_deg"]
    a = linkage_sym.sweep(scene, axes, metrics)
    b = linkage_sym.sweep(scene, axes, metrics, execution=NUMBA)
    _same(a, b)
    flat = 7 * 9 + 2
    assert flat > BLOCK and np.asarray(a["K_note"])[flat] != ""  # singular at a step: no K
    assert 0 < np.asarray(a["assemblable"])[flat] < 1


@pytest.mark.parametrize("example, metrics, why", [
    ("sixbar_class3", ["assemblable"], "groups without one (triad (class III)"),
    ("shaper", ["assemblable"], "read the angles themselves"),
    ("crank_rocker", ["assemblable", "swing"], "not swing"),
])
def test_refusals_say_why(example, metrics, why):
    with pytest.raises(SweepError) as err:
        linkage_sym.sweep(linkage_sym.load_example(example), {"l_AB": [0.02, 0.05]}, metrics,
                          execution=NUMBA)
    assert err.value.field == "backend"
    assert why in err.value.reason and "use the NumPy backend" in err.value.reason
    assert "--" not in err.value.reason


def test_default_metrics_refusal_names_the_metric():
    # no metric named: the default metrics include swing, which the numba backend does not
    # compute; the refusal says so, and that naming the metrics is the way
    with pytest.raises(SweepError) as err:
        linkage_sym.sweep(linkage_sym.load_example("crank_rocker"), {"l_AB": [0.02, 0.03]},
                          execution=NUMBA)
    assert err.value.field == "backend"
    assert ("the numba backend computes assemblable, grashof, K, min_transmission_deg; not "
            "swing, which the default metrics include: name the metrics, or use the NumPy "
            "backend") in err.value.reason


def test_unknown_backend_and_missing_numba(monkeypatch, capsys):
    scene = linkage_sym.load_example("crank_rocker")
    with pytest.raises(SweepError, match="backend: unknown backend 'jax'; the backends are numpy, numba"):
        linkage_sym.sweep(scene, {"l_AB": [0.02]}, ["K"], execution=Execution(backend="jax"))
    monkeypatch.setitem(sys.modules, "numba", None)
    with pytest.raises(SweepError, match=r"needs numba, which is not installed: pip install "
                                         r"'linkage_sym\[numba\]'"):
        linkage_sym.sweep(scene, {"l_AB": [0.02]}, ["K"], execution=NUMBA)
    assert main(["sweep", str(example_path("crank_rocker")), "--vary", "l_AB=0.02:0.03:2",
                 "--metrics", "K", "--backend", "numba"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("linkage-sym sweep: --backend: the numba backend needs numba"), err


@pytest.mark.slow
def test_command_line_backend(tmp_path, capsys):
    args = ["sweep", str(example_path("crank_rocker")), "--vary", "l_BC=0.05:0.07:3",
            "--vary", "l_CD=0.03:0.06:3", "--metrics", "assemblable,K,min_transmission_deg"]
    tables = []
    for backend in ("numpy", "numba"):
        out = tmp_path / f"{backend}.csv"
        assert main(args + ["-o", str(out), "--backend", backend]) == 0
        tables.append(out.read_text())
    assert tables[0] == tables[1]
    assert main(args[:2] + ["--vary", "l_AB=0.02:0.03:2", "--backend", "numba"]) == 2
    err = capsys.readouterr().err
    assert "--backend: the numba backend computes assemblable, grashof, K, min_transmission_deg; " \
           "not swing" in err, err
