"""Benchmark: µs per position of kinematics + kinetostatics, dyad solver vs global method.

Run on demand (not part of the tests)::

    python benchmarks/bench_kinetostatics.py     # writes benchmarks/results/kinetostatics.json

One core's worth of BLAS threads; glibc's heap in its steady state (see
``bench_kinematics.py``); each figure is the best of several repeats,
and every ratio is between figures of the same run (the machines are shared
and noisy).

Compared, for the shipped crank-rocker and Watt six-bar over 3600 steps
(and the six-bar over 100,000 steps):

* ``kinematics``: positions, velocities, accelerations only;
* ``dyad``: kinematics + reactions, efforts, frame loads by the group
  routines (closed-form dyads);
* ``global``: the same with one sparse system for all links and steps;
* ``exact_condition``: the dyad run with the exact condition number at
  every step instead of only where a cheap indicator flags it -- what the
  extra certainty costs.

The class-III six-bar (Newton positions, superposition forces) over 3600
steps is listed too, and against the Watt six-bar in both runtimes
(``Plan.run`` and ``CompiledMechanism.run``) with every output: the batched
continuation and the point-by-point walk in the same run
(``bench_kinematics.newton_groups``; target: within 10x of the Watt six-bar).
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import dataclasses  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from bench_kinematics import best_time, newton_groups, steady_heap  # noqa: E402  (same folder)
from linkage_sym.numeric.plan import compile_plan  # noqa: E402

HERE = Path(__file__).resolve().parent
ALL = ("kinematics", "reactions", "driving", "frame")


def variant(scene, steps, outputs):
    drivers = tuple(dataclasses.replace(d, steps=steps) for d in scene.drivers)
    return dataclasses.replace(scene, drivers=drivers, outputs=outputs)


def case(scene, steps, repeats=7):
    kin = compile_plan(variant(scene, steps, ("kinematics",)))
    full = compile_plan(variant(scene, steps, ALL))
    # the two methods must agree before their timings mean anything
    a, g = full.run(), full.run(method="global")
    err = max(
        float(np.nanmax(np.abs(a.forces.reactions[j] - g.forces.reactions[j])))
        / float(np.nanmax(np.abs(g.forces.reactions[j])))
        for j in a.forces.reactions
    )
    assert err < 1e-9, err
    t_kin = best_time(kin.run, repeats)
    t_dyad = best_time(lambda: full.run(), repeats)
    t_glob = best_time(lambda: full.run(method="global"), max(2, repeats // 2))
    t_exact = best_time(lambda: full.run(exact_condition=True), max(2, repeats // 2))
    us = 1e6 / steps
    return {
        "steps": steps,
        "kinematics_us_per_position": t_kin * us,
        "dyad_us_per_position": t_dyad * us,
        "global_us_per_position": t_glob * us,
        "exact_condition_us_per_position": t_exact * us,
        "dyad_positions_per_second": steps / t_dyad,
        "forces_share_of_dyad_run": 1 - t_kin / t_dyad,
        "global_over_dyad": t_glob / t_dyad,
        "exact_condition_over_dyad": t_exact / t_dyad,
        "dyad_vs_global_max_relative_difference": err,
    }


def main():
    results = {
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "machine": platform.machine(),
        "processor": platform.processor() or "unknown",
        "cases": {},
    }
    cases = results["cases"]
    # steady allocator state from the start (see bench_kinematics.py): otherwise
    # whichever variant runs after the first large free looks twice as fast
    steady_heap()
    results["allocator_state"] = "steady"
    four = linkage_sym.load_example("crank_rocker")
    six = linkage_sym.load_example("watt_sixbar")
    cases["fourbar_3600"] = case(four, 3600)
    cases["sixbar_3600"] = case(six, 3600)
    cases["sixbar_100000"] = case(six, 100_000, repeats=3)
    cases["class3_sixbar_3600"] = case(linkage_sym.load_example("sixbar_class3"), 3600, repeats=5)
    cases["class3_sixbar_3600_newton"] = newton_groups(ALL)
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "kinetostatics.json").write_text(json.dumps(results, indent=2) + "\n")
    print(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()
