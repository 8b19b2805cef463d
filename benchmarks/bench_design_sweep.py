"""Benchmark: the design sweep against a four-bar sweep written by hand in NumPy, one run.

Run on demand (not part of the tests)::

    python benchmarks/bench_design_sweep.py [--grid 200] [--repeats 3]
    # writes benchmarks/results/design_sweep.json

One BLAS thread per process.  The shipped crank-rocker (``load_example("crank_rocker")``),
its sweep made 361 steps over a full turn of the crank (``dataclasses.replace`` of its
driver), coupler ``l_BC`` and rocker ``l_CD`` varied over a ``--grid`` x ``--grid`` grid
(0.045..0.085 and 0.025..0.075 m around the scene's 0.063 and 0.049; the crank 0.024, the
ground 0.078: crank-rockers, and designs that do not close at every step or at all),
metrics ``K`` and ``min_transmission_deg``.  Contenders, timed in this run, best of
``--repeats``:

* ``package``: ``linkage_sym.sweep(scene, grid, ["K", "min_transmission_deg"])`` in this
  process (one worker): the compiled mechanism's positions, the singularity screen, the
  rates along the sweep, the limit positions located by Newton between steps;
* ``numba``: the same call with ``execution=Execution(backend="numba")``: the generated
  closed forms printed as scalar code and compiled with numba, one loop over blocks of
  designs, steps outer and designs inner, vectorised by the compiler
  (linkage_sym/design/numba_block.py), and the limit positions' Newton compiled
  (linkage_sym/design/numba_newton.py); one process, one thread (no ``prange``); its
  compilation (the first, small sweep, numba's import included) is timed apart,
  ``numba_compile``, and kept out of its rate;
* ``numpy``: ``sweep_fourbar`` of tests/support/fourbar_sweep_numpy.py, written from the
  textbook's formulas (closed-form positions of C at every step, the transmission angle at
  every step, ``K`` from the two toggle positions in closed form), blocks of 1024 designs.

The rate is design-positions (designs x steps) per second of this process's CPU time
(``time.process_time``: the machine is shared, and another job's load lowers it less than
the wall-clock rate); wall-clock seconds and the load average are recorded too.  Targets
(issue): the package within 1.5x of the hand-written sweep, and >= 4e7 design-positions per
CPU-second.

Before any timing counts, the contenders must agree: the numba backend with the package's
NumPy backend, ``K`` and the smallest transmission angle within 1e-12 relative and ``K_note``
equal, design by design (tests/design/test_numba_sweep.py); the package with the
hand-written sweep: ``K`` within 1e-12 relative where both give
it, the smallest transmission angle within 1e-10 degrees where both call every step
assembled (see tests/design/test_design_sweep_reference.py for the tolerances' reasons).
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests" / "support"))

from fourbar_sweep_numpy import sweep_fourbar  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.design import Execution  # noqa: E402

METRICS = ["K", "min_transmission_deg"]
STEPS = 361
COUPLER = (0.045, 0.085)
ROCKER = (0.025, 0.075)
K_RTOL = 1e-12
MU_ATOL_DEG = 1e-10


def scene_361():
    """The shipped crank-rocker swept over one full turn of its crank in 361 steps."""
    scene = linkage_sym.load_example("crank_rocker")
    d = scene.drivers[0]
    drv = dataclasses.replace(d, start=0.0, stop=2 * math.pi, steps=STEPS)
    return dataclasses.replace(scene, drivers=(drv,))


def axes(k):
    return {"l_BC": np.linspace(*COUPLER, k), "l_CD": np.linspace(*ROCKER, k)}


def fixed(scene):
    """Crank length, the rocker's pivot and the assembly mode of the scene (A at the
    origin): the hand-written sweep's inputs besides the varied lengths."""
    j = {x.name: np.array(x.at) for x in scene.joints}
    A, B, C, D = j["A"], j["B"], j["C"], j["D"]
    assert not A.any()
    u, v = D - B, C - B
    sigma = 1 if u[0] * v[1] - u[1] * v[0] > 0 else -1
    return float(np.hypot(*(B - A))), float(D[0]), float(D[1]), sigma


def reference(scene, ax):
    a, xd, yd, sigma = fixed(scene)
    B, C = np.meshgrid(ax["l_BC"], ax["l_CD"], indexing="ij")  # the grid's order
    d = scene.drivers[0]
    theta = np.linspace(d.start, d.stop, d.steps)
    return sweep_fourbar(a, B.ravel(), C.ravel(), xd, yd, theta, sigma)


def best(f, repeats):
    """``(cpu seconds, wall seconds, result)`` of the run with the least CPU time."""
    cpu, wall, out = math.inf, math.inf, None
    for _ in range(repeats):
        c0, t0 = time.process_time(), time.perf_counter()
        res = f()
        c, t = time.process_time() - c0, time.perf_counter() - t0
        if c < cpu:
            cpu, wall, out = c, t, res
    return cpu, wall, out


def load():
    return round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None


def agreement(res, ref):
    """How far the package's K and smallest transmission angle are from the hand-written
    sweep's, on the designs both give them for; and the designs only one gives them for."""
    asm, mu, K = ref
    Kp = np.asarray(res["K"], float)
    mp = np.asarray(res["min_transmission_deg"], float)
    both_k = np.isfinite(Kp) & np.isfinite(K)
    both_mu = asm & np.isfinite(mp)
    return {
        "designs_with_K_both": int(both_k.sum()),
        "designs_with_K_package_only": int((np.isfinite(Kp) & ~np.isfinite(K)).sum()),
        "designs_with_K_numpy_only": int((~np.isfinite(Kp) & np.isfinite(K)).sum()),
        "K_max_relative_difference": float(np.max(np.abs(Kp[both_k] - K[both_k]) / K[both_k])),
        "designs_closed_at_every_step_numpy": int(asm.sum()),
        "min_transmission_max_abs_difference_deg": float(np.max(np.abs(mp[both_mu] - mu[both_mu]))),
        "K_rtol": K_RTOL, "min_transmission_atol_deg": MU_ATOL_DEG,
    }


def same_as_package(res, pkg):
    """The numba backend's table against the NumPy backend's: the largest relative
    differences of ``K`` and the smallest transmission angle, NaN at the same designs."""
    out = {}
    for c in METRICS:
        a, b = np.asarray(pkg[c], float), np.asarray(res[c], float)
        assert np.array_equal(np.isnan(a), np.isnan(b)), c
        f = np.isfinite(a)
        out[f"{c}_max_relative_difference"] = float(np.max(np.abs(a[f] - b[f]) / np.abs(a[f])))
    assert (np.asarray(pkg["K_note"]) == np.asarray(res["K_note"])).all()
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--grid", type=int, default=200, help="values per varied length")
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    scene = scene_361()
    ax = axes(a.grid)
    n = a.grid * a.grid
    work = n * STEPS
    linkage_sym.sweep(scene, axes(4), METRICS)  # compile (or load from the cache) once
    reference(scene, axes(4))
    numba = Execution(backend="numba")
    c0, t0 = time.process_time(), time.perf_counter()
    linkage_sym.sweep(scene, axes(4), METRICS, execution=numba)  # numba compiles, once
    c_comp, w_comp = time.process_time() - c0, time.perf_counter() - t0
    loads = {"start": load()}
    c_pkg, w_pkg, res = best(lambda: linkage_sym.sweep(scene, ax, METRICS), a.repeats)
    loads["after_package"] = load()
    c_nb, w_nb, res_nb = best(lambda: linkage_sym.sweep(scene, ax, METRICS, execution=numba),
                              a.repeats)
    loads["after_numba"] = load()
    c_np, w_np, ref = best(lambda: reference(scene, ax), a.repeats)
    loads["after_numpy"] = load()
    agree = agreement(res, ref)
    assert agree["K_max_relative_difference"] <= K_RTOL, agree
    assert agree["min_transmission_max_abs_difference_deg"] <= MU_ATOL_DEG, agree
    assert agree["designs_with_K_package_only"] == agree["designs_with_K_numpy_only"] == 0, agree
    agree_nb = same_as_package(res_nb, res)
    assert max(agree_nb.values()) <= K_RTOL, agree_nb
    rate_pkg, rate_np, rate_nb = work / c_pkg, work / c_np, work / c_nb
    out = {
        "machine": {"python": sys.version.split()[0], "numpy": np.__version__,
                    "platform": platform.platform(), "cpus": os.cpu_count()},
        "scene": "crank_rocker", "varied": {"l_BC": list(COUPLER), "l_CD": list(ROCKER)},
        "designs": n, "steps": STEPS, "metrics": METRICS,
        "load_average_1min": loads,
        "package": {"cpu_seconds": c_pkg, "wall_seconds": w_pkg,
                    "design_positions_per_cpu_s": rate_pkg},
        "numba": {"cpu_seconds": c_nb, "wall_seconds": w_nb,
                  "design_positions_per_cpu_s": rate_nb,
                  "compile_cpu_seconds": c_comp, "compile_wall_seconds": w_comp,
                  "numba": _numba_version()},
        "numpy": {"cpu_seconds": c_np, "wall_seconds": w_np,
                  "design_positions_per_cpu_s": rate_np},
        "package_over_numpy_cpu": c_pkg / c_np,
        "numba_speedup_over_numpy_cpu": c_np / c_nb,
        "numba_speedup_over_package_cpu": c_pkg / c_nb,
        "targets": {"within_1.5x": c_pkg / c_np <= 1.5, "rate_4e7": rate_pkg >= 4e7,
                    "numba_rate_4e7": rate_nb >= 4e7},
        "agreement": agree,
        "agreement_numba_with_package": {**agree_nb, "rtol": K_RTOL},
    }
    (HERE / "results").mkdir(exist_ok=True)
    (HERE / "results" / "design_sweep.json").write_text(json.dumps(out, indent=2) + "\n")
    print(json.dumps(out, indent=2))


def _numba_version():
    import numba

    return numba.__version__


if __name__ == "__main__":
    main()
