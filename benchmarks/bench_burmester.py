"""Benchmark: motion generation through five poses (Burmester theory).

Run on demand (not part of the tests)::

    PYTHONPATH=. python3 benchmarks/bench_burmester.py   # writes benchmarks/results/burmester.json

For 20 sets of five poses taken from random known four-bars (a fixed generator), in one run:

* **points**: ``burmester_points`` alone -- the compatibility polynomial, its roots, Newton's
  refinement and the dyads (best of five per problem);
* **designs**: ``motion_synthesis`` -- the dyads, and every pair of them built as a scene and
  driven through the poses by the solver (each design checked in one or two solver runs).

The issue asks for the time per problem of the five-pose synthesis.
"""

from __future__ import annotations

import json
import math
import platform
import time
from pathlib import Path

import numpy as np

from linkage_sym.synthesis.builders import fourbar
from linkage_sym.synthesis.burmester import burmester_points
from linkage_sym.synthesis.common import SynthesisError
from linkage_sym.synthesis.motion import motion_synthesis

ROOT = Path(__file__).resolve().parents[1]


def problems(n: int, rng) -> list:
    out = []
    while len(out) < n:
        lengths = (rng.uniform(0.5, 2.0), *rng.uniform(1.0, 4.0, 3))
        point = tuple(rng.uniform(-2.0, 2.0, 2))
        degs = np.sort(rng.choice(np.arange(0, 360, 10), 5, replace=False))
        try:
            poses = []
            for deg in degs:
                s = fourbar(*lengths, crank_deg=float(deg), coupler_point=point).scene
                j = {x["name"]: x["at"] for x in s["joints"]}
                th = math.atan2(j["C"][1] - j["B"][1], j["C"][0] - j["B"][0])
                poses.append([*s["points"][0]["at"], math.degrees(th)])
        except SynthesisError:
            continue
        out.append(poses)
    return out


def main() -> None:
    rng = np.random.default_rng(2024)
    cases = problems(20, rng)
    points, designs, counts = [], [], []
    for poses in cases:
        best = math.inf
        for _ in range(5):
            t0 = time.perf_counter()
            dyads = burmester_points(poses)
            best = min(best, time.perf_counter() - t0)
        points.append(best)
        counts.append(len(dyads))
        t0 = time.perf_counter()
        motion_synthesis(poses)
        designs.append(time.perf_counter() - t0)
    result = {
        "machine": platform.platform(), "python": platform.python_version(),
        "problems": len(cases), "real_solutions": counts,
        "points_s_median": float(np.median(points)), "points_s_max": float(np.max(points)),
        "designs_s_median": float(np.median(designs)), "designs_s_max": float(np.max(designs)),
    }
    out = ROOT / "benchmarks" / "results" / "burmester.json"
    out.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
