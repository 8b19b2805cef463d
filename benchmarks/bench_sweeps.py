"""Benchmark: design sweeps (issue 17), every ratio from figures of one run.

Run on demand (not part of the tests)::

    python benchmarks/bench_sweeps.py [--designs 100000]   # writes benchmarks/results/sweeps.json

One BLAS thread per process.  Cases, on four-bars (the shipped crank-rocker's topology, crank
length and coupler length varied over a grid), 361 steps (a full turn, both ends), metrics
``min_transmission_deg`` and ``K`` (so: positions, the singularity screen, the rates along
the sweep, the limit positions located by Newton on the output's rate):

* ``in_process``: ``linkage_sym.sweep`` in this process (one core): design-positions per
  second (target >= 1e7);
* ``loop``: ``compile_plan(scene_of_design).run()`` over a sample of the same designs (their
  scenes built beforehand, so only the solves are timed; the run computes kinematics and
  transmission angles but no limit positions, so the ratio favours the loop); the target is
  ``in_process`` >= 20x the loop, per design;
* ``workers_2``: ``Execution(workers=2)`` against ``in_process`` on a grid of ``--parallel-designs`` (default 10^6;
  target >= 1.7x);
* ``dask_local_2``: ``Execution(workers=2, dask="local")`` (a LocalCluster of 2 processes) against ``workers_2``
  on that grid (target: within 1.3x).

Process start-up (spawned interpreters, the LocalCluster) is inside the timed calls of the
parallel cases, as a user meets it.  Best of ``--repeats`` each.  The machine may be shared:
the load average is recorded before and after each case, and ``in_process`` also gives the
rate per second of this process's CPU time (``time.process_time``), which another job's load
does not lower as much as the wall-clock rate.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.design import Execution  # noqa: E402
from linkage_sym.design.evaluate import Model  # noqa: E402
from linkage_sym.design.scenes import design_scene  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402

HERE = Path(__file__).resolve().parent
METRICS = ["min_transmission_deg", "K"]


def grid(n):
    k = int(round(math.sqrt(n)))
    return {"l_AB": np.linspace(0.015, 0.03, k), "l_BC": np.linspace(0.055, 0.075, k)}


def best(f, repeats, cpu=None):
    t = math.inf
    for _ in range(repeats):
        c0 = time.process_time()
        t0 = time.perf_counter()
        out = f()
        dt = time.perf_counter() - t0
        if dt < t:
            t = dt
            if cpu is not None:
                cpu["seconds"] = time.process_time() - c0
    return t, out


def _same(a, b):
    """Identical columns, bit for bit (NaN where NaN; text columns as text)."""
    if a.dtype.kind in "US":
        return a.tolist() == b.tolist()
    return np.array_equal(a, b, equal_nan=True)


def load():
    """The 1-minute load average (the machine's runnable processes), where the OS gives it."""
    return round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None


def loop_scenes(scene, axes, count):
    """The scenes of ``count`` designs spread over the grid (built before timing)."""
    model = Model(scene)
    d = linkage_sym.design.grid(axes)
    pick = np.linspace(0, len(d) - 1, count).astype(int)
    vals = d.values[pick]
    P = model.design_params(d.names, vals)
    P, X0, ok, joints0, _ = model.assemble(P, len(vals))
    return [design_scene(model, P, X0, joints0, i, f"d{i}") for i in range(len(vals)) if ok[i]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--designs", type=int, default=100_000)
    ap.add_argument("--parallel-designs", type=int, default=1_000_000)
    ap.add_argument("--loop-designs", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    scene = linkage_sym.load_example("crank_rocker")
    steps = scene.drivers[0].steps
    axes = grid(a.designs)
    n = len(axes["l_AB"]) * len(axes["l_BC"])
    linkage_sym.sweep(scene, grid(16), METRICS)  # compile (or load) once
    loads = {"start": load()}
    cpu = {}
    t_in, res = best(lambda: linkage_sym.sweep(scene, axes, METRICS), a.repeats, cpu)
    rate = n * steps / t_in
    loads["after_in_process"] = load()
    scenes = loop_scenes(scene, axes, a.loop_designs)
    plans = [compile_plan(s) for s in scenes]
    t_loop, _ = best(lambda: [compile_plan(s).run() for s in scenes], a.repeats)
    loads["after_loop"] = load()
    per_loop = t_loop / len(scenes)
    per_sweep = t_in / n
    # the sweep's and the loop's numbers must agree before their timings mean anything
    check = [p.run() for p in plans[:20]]
    assert all(r.ok.all() for r in check)
    pax = grid(a.parallel_designs)
    pn = len(pax["l_AB"]) * len(pax["l_BC"])
    t_p1, r1 = best(lambda: linkage_sym.sweep(scene, pax, METRICS), a.repeats)
    two = Execution(workers=2)
    t_w2, r2 = best(lambda: linkage_sym.sweep(scene, pax, METRICS, execution=two), a.repeats)
    loads["after_workers_2"] = load()
    cluster = Execution(workers=2, dask="local")
    t_d2, r3 = best(lambda: linkage_sym.sweep(scene, pax, METRICS, execution=cluster), a.repeats)
    loads["after_dask_local_2"] = load()
    same = all(_same(r1[c], r2[c]) and _same(r1[c], r3[c]) for c in r1.columns)
    out = {
        "machine": {"python": sys.version.split()[0], "numpy": np.__version__,
                    "platform": platform.platform(), "cpus": os.cpu_count()},
        "metrics": METRICS,
        "steps": steps,
        "load_average_1min": loads,
        "in_process": {"designs": n, "seconds": t_in, "design_positions_per_s": rate,
                       "cpu_seconds": cpu["seconds"],
                       "design_positions_per_cpu_s": n * steps / cpu["seconds"],
                       "target": 1e7, "met": rate >= 1e7,
                       "designs_with_K": int(np.isfinite(res["K"]).sum())},
        "loop": {"designs": len(scenes), "seconds_per_design": per_loop,
                 "sweep_seconds_per_design": per_sweep, "speedup": per_loop / per_sweep,
                 "target": 20, "met": per_loop / per_sweep >= 20},
        "workers_2": {"designs": pn, "in_process_seconds": t_p1, "seconds": t_w2,
                      "speedup": t_p1 / t_w2, "target": 1.7, "met": t_p1 / t_w2 >= 1.7},
        "dask_local_2": {"designs": pn, "seconds": t_d2, "over_workers_2": t_d2 / t_w2,
                         "target": 1.3, "met": t_d2 / t_w2 <= 1.3},
        "identical_tables": same,
    }
    (HERE / "results").mkdir(exist_ok=True)
    (HERE / "results" / "sweeps.json").write_text(json.dumps(out, indent=2) + "\n")
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
