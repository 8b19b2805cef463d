"""Benchmark: what joint friction (contract part two, issue 29) costs the force analysis.

Run on demand (not part of the tests)::

    python benchmarks/bench_friction.py     # writes benchmarks/results/friction.json

With friction each group's equilibrium is nonlinear in its reactions: the group
routines solve it by Newton's method around the group's linear routine (one extra
linear solve per joint with friction, a few batched iterations), the global method by
Newton on the whole system (dense per step), and with one driver the frictionless
efforts are solved as well (for the efficiency).  Timed, over 3600 steps, with every
output: the slider-crank press with friction in every joint and the class-III six-bar
with friction in every joint (superposition inside the Newton), each with
``effects.friction`` true and false; one core's worth of BLAS threads, the best of
several repeats, ratios within one run (the machines are shared and noisy).
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import copy  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from bench_kinematics import best_time, steady_heap  # noqa: E402  (same folder)
from linkage_sym.examples import example_dict  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))  # the tests' scenes (tests.support)
from tests.support import friction_scenes  # noqa: E402


def with_friction(name):
    """Example ``name`` as shipped where it has friction, else with friction in every R and P
    joint (tests.support.friction_scenes, as the friction tests take it)."""
    d = example_dict(name)
    return d if d["effects"].get("friction") else friction_scenes.with_friction(name)


def case(name, steps=3600, repeats=5):
    d = with_friction(name)
    d["drivers"][0]["steps"] = steps
    off = copy.deepcopy(d)
    off["effects"]["friction"] = False
    on, plain = compile_plan(linkage_sym.load_scene(d)), compile_plan(linkage_sym.load_scene(off))
    a, g = on.run(), on.run(method="global")
    err = max(float(np.nanmax(np.abs(a.forces.reactions[j] - g.forces.reactions[j])))
              / float(np.nanmax(np.abs(g.forces.reactions[j]))) for j in a.forces.reactions)
    assert err < 1e-9, err
    us = 1e6 / steps
    t = {f"{m}_{k}_us_per_position": best_time(lambda p=p, m=m: p.run(method=m), repeats) * us
         for m in ("dyad", "global") for k, p in (("friction", on), ("frictionless", plain))}
    for m in ("dyad", "global"):
        t[f"{m}_friction_over_frictionless"] = (t[f"{m}_friction_us_per_position"]
                                                / t[f"{m}_frictionless_us_per_position"])
    return {"steps": steps, **t, "dyad_vs_global_max_relative_difference": err}


def main():
    results = {"python": sys.version.split()[0], "numpy": np.__version__,
               "machine": platform.machine(), "processor": platform.processor() or "unknown",
               "cases": {}}
    steady_heap()
    results["cases"]["press_3600"] = case("slider_crank_press_friction")
    results["cases"]["class3_sixbar_3600"] = case("sixbar_class3")
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "friction.json").write_text(json.dumps(results, indent=2) + "\n")
    print(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()
