"""Benchmark: one revision against another on the evaluators' workloads, in one run.

Run on demand (not part of the tests)::

    PYTHONPATH=. python3 benchmarks/bench_revisions.py --before f26d6a9
    # writes benchmarks/results/revisions.json

A restructuring must not slow a runtime down.  This script checks out ``--before`` (a
git revision, with ``git archive``) and ``--after`` (default: this working tree) and
times the same workloads with each, in fresh interpreters that alternate (before, after,
before, ...) so that the machine's load falls on both alike; CPU time of the timed call
(``time.process_time``), best of ``--repeats`` interpreters per revision, one BLAS
thread.  Every interpreter warms its workload once (compiled mechanisms come from a
shared disk cache filled before timing), then times it.

Workloads (the evaluators of the generated code and the numeric plan beside them):

- ``symbolic``: ``CompiledMechanism.run()`` of the crank-rocker and the Watt six-bar,
  kinematics and forces, 3600 steps (µs per position);
- ``plan``: ``compile_plan(scene).run()`` of the same scenes (µs per position);
- ``precision``: ``run_precise`` at 30 digits of the crank-rocker, 37 steps (ms per
  position);
- ``designs``: a design sweep of the crank-rocker, 60 x 60 designs of the coupler and
  rocker lengths, 361 steps, metrics K and the minimum transmission angle (design-positions
  per CPU-second, so higher is better there).

The ratio quoted is after / before (below 1: faster after) for times; before / after for
the design rate.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

_PRELUDE = """
import dataclasses, json, time, warnings
import linkage_sym
warnings.simplefilter("ignore")
def scene(name, steps, outputs=None):
    s = linkage_sym.load_example(name)
    s = dataclasses.replace(s, drivers=tuple(dataclasses.replace(d, steps=steps) for d in s.drivers))
    return s if outputs is None else dataclasses.replace(s, outputs=outputs)
def timed(f, n):
    f()
    best = float("inf")
    for _ in range(3):
        t = time.process_time(); f(); best = min(best, time.process_time() - t)
    return best / n
out = {}
"""

WORKLOADS = {
    "symbolic": """
from linkage_sym.codegen.compile import compile_mechanism
for ex in ("crank_rocker", "watt_sixbar"):
    for var, outs in (("kinematics", ("kinematics",)), ("forces", None)):
        cm = compile_mechanism(scene(ex, 3600, outs))
        out[f"{ex}/{var}"] = timed(cm.run, 3600) * 1e6
""",
    "plan": """
from linkage_sym.numeric.plan import compile_plan
for ex in ("crank_rocker", "watt_sixbar"):
    for var, outs in (("kinematics", ("kinematics",)), ("forces", None)):
        plan = compile_plan(scene(ex, 3600, outs))
        out[f"{ex}/{var}"] = timed(plan.run, 3600) * 1e6
""",
    "precision": """
from linkage_sym.codegen.precision import PreciseMechanism
s = scene("crank_rocker", 37)
pm = PreciseMechanism(s, 30)
t = time.process_time(); pm.run(); out["crank_rocker/30 digits"] = (time.process_time() - t) / 37 * 1e3
""",
    "designs": """
import numpy as np
from linkage_sym.design import sweep
s = linkage_sym.load_example("crank_rocker")
d = s.drivers[0]
s = dataclasses.replace(s, drivers=(dataclasses.replace(d, steps=361),))
grid = {"l_BC": np.linspace(0.05, 0.075, 60), "l_CD": np.linspace(0.04, 0.07, 60)}
sweep(s, {k: v[:3] for k, v in grid.items()}, ["K", "min_transmission_deg"])
t = time.process_time()
sweep(s, grid, ["K", "min_transmission_deg"])
out["crank_rocker 60x60x361"] = 3600 * 361 / (time.process_time() - t) / 1e6
""",
}
UNITS = {"symbolic": "us/position", "plan": "us/position", "precision": "ms/position",
         "designs": "million design-positions per CPU-second"}


def run_child(tree: Path, code: str, cache: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree), LINKAGE_SYM_CACHE=cache, OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    got = subprocess.run([sys.executable, "-c", _PRELUDE + code + "\nprint(json.dumps(out))"],
                         env=env, cwd=tree, capture_output=True, text=True)
    if got.returncode:
        raise SystemExit(f"{tree}: workload failed:\n{got.stderr[-2000:]}")
    return json.loads(got.stdout.strip().splitlines()[-1])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--before", required=True, help="git revision to compare against")
    p.add_argument("--after", default=None, help="git revision (default: this working tree)")
    p.add_argument("--repeats", type=int, default=3, help="interpreters per revision and workload")
    p.add_argument("--only", nargs="*", choices=sorted(WORKLOADS), help="some workloads only")
    p.add_argument("-o", "--output", default=str(HERE / "results" / "revisions.json"))
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        trees = {}
        for label, rev in (("before", args.before), ("after", args.after)):
            if rev is None:
                trees[label] = ROOT
                continue
            d = Path(tmp) / label
            d.mkdir()
            archive = subprocess.run(["git", "archive", rev], cwd=ROOT, capture_output=True, check=True)
            subprocess.run(["tar", "-x", "-C", str(d)], input=archive.stdout, check=True)
            trees[label] = d
        results = {}
        for name in args.only or list(WORKLOADS):
            code = WORKLOADS[name]
            best: dict = {"before": {}, "after": {}}
            for _ in range(args.repeats):
                for label in ("before", "after"):
                    got = run_child(trees[label], code, str(Path(tmp) / f"cache-{label}"))
                    for k, v in got.items():
                        old = best[label].get(k)
                        better = max if name == "designs" else min
                        best[label][k] = v if old is None else better(old, v)
            rows = {}
            for k in best["before"]:
                b, a = best["before"][k], best["after"][k]
                ratio = b / a if name == "designs" else a / b
                rows[k] = {"before": round(b, 4), "after": round(a, 4),
                           "after_over_before" if name != "designs" else "before_over_after":
                           round(ratio, 3)}
                print(f"{name:10s} {k:28s} before {b:10.4g}  after {a:10.4g}  {UNITS[name]}  "
                      f"ratio {ratio:.3f}")
            results[name] = {"unit": UNITS[name], "rows": rows}
    record = {"before": args.before, "after": args.after or "working tree",
              "repeats": args.repeats, "machine": platform.platform(),
              "cpu_count": os.cpu_count(), "load_average": os.getloadavg(),
              "results": results}
    Path(args.output).write_text(json.dumps(record, indent=2) + "\n")
    print(f"written to {args.output}")


if __name__ == "__main__":
    main()
