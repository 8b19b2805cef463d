"""Benchmark: how long the command line takes to start, in fresh interpreters.

Run on demand (not part of the tests)::

    python benchmarks/bench_startup.py            # writes benchmarks/results/startup.json
    python benchmarks/bench_startup.py --repeats 3   # a quicker look

Three commands, each run ``--repeats`` times (default 7) in a fresh process,
the best run kept:

* ``python -c pass``: the interpreter alone, the unit of the ratios;
* ``python -m linkage_sym --version``: the parser is built, no library is
  imported (no NumPy, SciPy, SymPy, Matplotlib, nor the design package);
* ``python -m linkage_sym analyze SCENE``: the shipped crank-rocker
  (``linkage_sym/examples/crank_rocker.json``, 361 steps) with its ``outputs``
  set to ``kinematics`` only, written to a temporary scene: NumPy and SciPy,
  the numeric plan and the summary, no SymPy and no Matplotlib.

Time is CPU time (user + system) of the child, the difference of
``resource.getrusage(RUSAGE_CHILDREN)`` around it, so that a busy shared
machine slows the figures less than wall time would; wall time is recorded
too.  The children run with one BLAS thread; one unrecorded run of each command
first warms the bytecode caches, as a user's are.  The children write their
bytecode to a cache of their own (``PYTHONPYCACHEPREFIX``, a temporary folder),
whatever ``PYTHONDONTWRITEBYTECODE`` says: with it set (as in some shells and
CI images) every run compiled the package's sources again, which no installed
package does (pip compiles them), and that compiling was a third of the
``analyze`` figure.

Targets (issue 28): ``--version`` within 3x of ``python -c pass``; the
kinematics-only ``analyze`` of the crank-rocker within 10x.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
TARGETS = {"version": 3.0, "analyze_kinematics": 10.0}


def run_child(args: list, env: dict) -> dict:
    """One fresh process: its CPU time (user + system, s) and wall time; it must succeed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env, cwd=ROOT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(args)}: exit {p.returncode}\n{p.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"cpu_seconds": cpu, "wall_seconds": wall}


def best_of(args: list, env: dict, repeats: int) -> dict:
    runs = [run_child(args, env) for _ in range(repeats)]
    return {"cpu_seconds": min(r["cpu_seconds"] for r in runs),
            "wall_seconds": min(r["wall_seconds"] for r in runs),
            "runs": repeats}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7, help="fresh runs of each command (best kept)")
    opts = ap.parse_args(argv)
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), env.get("PYTHONPATH")) if p)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    scene = json.loads((ROOT / "linkage_sym" / "examples" / "crank_rocker.json").read_text())
    scene["outputs"] = ["kinematics"]
    with tempfile.TemporaryDirectory(prefix="bench_startup_") as tmp:
        env["PYTHONPYCACHEPREFIX"] = str(Path(tmp) / "bytecode")
        path = Path(tmp) / "crank_rocker_kinematics.json"
        path.write_text(json.dumps(scene))
        commands = {
            "python_pass": ["-c", "pass"],
            "version": ["-m", "linkage_sym", "--version"],
            "analyze_kinematics": ["-m", "linkage_sym", "analyze", str(path)],
        }
        results = {
            "python": sys.version.split()[0],
            "machine": platform.machine(),
            "processor": platform.processor() or "unknown",
            "cpus": os.cpu_count(),
            "load_average_at_start": os.getloadavg()[0],
            "scene": "crank_rocker (linkage_sym/examples), outputs kinematics only, 361 steps",
            "time": "CPU time (user + system) of the child, best of the runs",
            "bytecode": "cached (a private PYTHONPYCACHEPREFIX, warmed by one unrecorded run)",
            "targets_ratio_to_python_pass": TARGETS,
            "commands": {},
        }
        for name, args in commands.items():
            run_child(args, env)  # warm the bytecode caches and the file system
            rec = best_of(args, env, opts.repeats)
            rec["command"] = "python " + " ".join(
                a if a != str(path) else "crank_rocker_kinematics.json" for a in args)
            results["commands"][name] = rec
        base = results["commands"]["python_pass"]["cpu_seconds"]
        for name, rec in results["commands"].items():
            rec["ratio_to_python_pass"] = rec["cpu_seconds"] / base
            if name in TARGETS:
                rec["meets_target"] = rec["ratio_to_python_pass"] <= TARGETS[name]
            print(f"{name:20s} {rec['cpu_seconds'] * 1000:8.1f} ms CPU  "
                  f"{rec['wall_seconds'] * 1000:8.1f} ms wall  {rec['ratio_to_python_pass']:6.2f}x",
                  flush=True)
        results["load_average_at_end"] = os.getloadavg()[0]
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    name = "startup.json" if opts.repeats == 7 else f"startup_{opts.repeats}.json"
    (out / name).write_text(json.dumps(results, indent=2) + "\n")
    print(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()
