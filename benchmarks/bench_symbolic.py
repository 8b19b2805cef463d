"""Benchmark: the symbolic layer -- derive + compile, load from the cache, evaluate.

Run on demand (not part of the tests)::

    PYTHONPATH=. python3 benchmarks/bench_symbolic.py   # writes benchmarks/results/symbolic.json

For the shipped crank-rocker (four-bar) and Watt six-bar, 3600 steps, each
in two variants: ``kinematics`` (outputs ``["kinematics"]``) and ``forces``
(outputs kinematics, reactions, driving, frame -- the examples' own).

Measured, all in one run:

* **derive + compile from scratch**, each in a fresh subprocess with an
  empty cache directory (``$LINKAGE_SYM_CACHE`` set to a temporary folder)
  so neither SymPy's own cache nor ours is warm:

  - ``derive``: ``derive(scene, forces=...)`` alone, in its own subprocess;
  - ``compile``: ``compile_mechanism(scene)`` in another subprocess -- the
    derivation again, ``lambdify(cse=True)`` of every stage, writing the
    artifact to disk, binding it to the scene;
  - ``generate`` = ``compile - derive`` (the code generation and the rest).

  SymPy's import time is reported apart (not in these figures).

* **load from the disk cache** in a fresh subprocess (``python -c``):
  ``load_compiled(scene)`` timed in the process, plus the whole subprocess's
  wall time (interpreter start, imports, load); whether ``sympy`` ended up in
  ``sys.modules``.  Best of several subprocesses.

* **evaluation**, µs per position, in this process (which never imports
  SymPy: it loads the artifacts the subprocesses wrote), glibc's heap in its
  steady state (``steady_heap()``, see ``bench_kinematics.py``), one BLAS
  thread, best of several repeats, contenders timed interleaved:
  ``CompiledMechanism.run()`` (and, for kinematics, ``CompiledMechanism.
  evaluate()``: the lambdified functions alone, without the run's path,
  unwrapping, singularity screen and Analysis) vs the numeric
  ``compile_plan(scene).run()``,
  and for the four-bar's kinematics the hand-written NumPy closed form of
  ``bench_kinematics.py``.  Results are checked to agree before timing.

Targets (from the issue): derive + compile the six-bar's kinematics and
forces < 10 s; the same from the cache < 0.5 s; the four-bar's lambdified
kinematics within 1.5x the hand-written closed form.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import json  # noqa: E402
import platform  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from bench_kinematics import best_time, handwritten_fourbar, steady_heap, with_steps  # noqa: E402
from linkage_sym.codegen.cache import sympy_version  # noqa: E402
from linkage_sym.codegen.runtime import load_compiled  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
STEPS = 3600
ALL = ("kinematics", "reactions", "driving", "frame")
MECHANISMS = {"fourbar": "crank_rocker", "sixbar": "watt_sixbar"}
VARIANTS = {"kinematics": ("kinematics",), "forces": ALL}
LOAD_REPEATS = 5

# prelude of every child: the scene, built as with_steps does (without importing
# this module, which would import the numeric solver too)
_SCENE = """
import dataclasses, json, sys, time
t_imp = time.perf_counter()
import linkage_sym
t_imp = time.perf_counter() - t_imp
s = linkage_sym.load_example({example!r})
s = dataclasses.replace(
    s, drivers=tuple(dataclasses.replace(d, steps={steps}) for d in s.drivers),
    outputs={outputs!r})
"""

_DERIVE = """
t = time.perf_counter(); import sympy; t_sympy = time.perf_counter() - t
from linkage_sym.symbolic.mechanism import derive
t = time.perf_counter(); derive(s, forces={forces}); t = time.perf_counter() - t
print(json.dumps({{"seconds": t, "sympy_import_seconds": t_sympy}}))
"""

_COMPILE = """
t = time.perf_counter(); import sympy; t_sympy = time.perf_counter() - t
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.codegen import cache
assert cache.load(cache.key_of(cache.signature(s))) is None, "cache not empty"
t = time.perf_counter(); compile_mechanism(s); t = time.perf_counter() - t
print(json.dumps({{"seconds": t, "sympy_import_seconds": t_sympy}}))
"""

_LOAD = """
from linkage_sym.codegen.runtime import load_compiled
t = time.perf_counter(); cm = load_compiled(s); t = time.perf_counter() - t
assert cm is not None, "not in the cache"
print(json.dumps({{"seconds": t, "import_seconds": t_imp, "sympy_imported": "sympy" in sys.modules}}))
"""


def child(code: str, cache_dir: str) -> tuple[dict, float]:
    """Run ``code`` in a fresh interpreter; its JSON line and the wall time."""
    env = dict(os.environ, LINKAGE_SYM_CACHE=cache_dir, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=ROOT, capture_output=True, text=True
    )
    wall = time.perf_counter() - t0
    if out.returncode:
        raise RuntimeError(out.stderr)
    return json.loads(out.stdout.strip().splitlines()[-1]), wall


def scene_of(mech: str, variant: str):
    s = with_steps(linkage_sym.load_example(MECHANISMS[mech]), STEPS)
    import dataclasses

    return dataclasses.replace(s, outputs=VARIANTS[variant])


def build_and_load(mech: str, variant: str, cache_dir: str) -> dict:
    fill = dict(example=MECHANISMS[mech], steps=STEPS, outputs=VARIANTS[variant])
    prelude = _SCENE.format(**fill)
    forces = variant == "forces"
    d, _ = child(prelude + _DERIVE.format(forces=forces), tempfile.mkdtemp(dir=cache_dir))
    c, _ = child(prelude + _COMPILE.format(), cache_dir)
    loads = [child(prelude + _LOAD.format(), cache_dir) for _ in range(LOAD_REPEATS)]
    return {
        "derive_s": d["seconds"],
        "derive_plus_compile_s": c["seconds"],
        "generate_s": c["seconds"] - d["seconds"],
        "sympy_import_s": min(d["sympy_import_seconds"], c["sympy_import_seconds"]),
        "cache_load_in_process_s": min(r["seconds"] for r, _ in loads),
        "cache_load_subprocess_wall_s": min(w for _, w in loads),
        "cache_load_linkage_sym_import_s": min(r["import_seconds"] for r, _ in loads),
        "cache_load_imported_sympy": any(r["sympy_imported"] for r, _ in loads),
    }


def git_state() -> str:
    """The commit measured, ``+dirty`` if linkage_sym/ has uncommitted changes."""
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "linkage_sym"], cwd=ROOT,
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+dirty" if dirty else "")


def interleaved(fns: dict, repeats: int) -> dict:
    """Best time of each function, timed in turn (so slow spells hit all alike)."""
    best = {k: np.inf for k in fns}
    for _ in range(repeats):
        for k, fn in fns.items():
            best[k] = min(best[k], best_time(fn, 1))
    return best


def rel_err(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = np.nanmax(np.abs(b)) if np.any(np.isfinite(b)) else 0.0
    if scale == 0.0:
        return float(np.nanmax(np.abs(a))) if np.any(np.isfinite(a)) else 0.0
    return float(np.nanmax(np.abs(a - b)) / scale)


def evaluate_case(mech: str, variant: str) -> dict:
    scene = scene_of(mech, variant)
    sym = load_compiled(scene)
    num = compile_plan(scene)
    a, b = sym.run(), num.run()
    err = max(rel_err(a.links[n].omega, b.links[n].omega) for n in b.links)
    err = max(err, max(rel_err(a.links[n].alpha, b.links[n].alpha) for n in b.links))
    if variant == "forces":
        err = max(err, max(rel_err(a.forces.reactions[j], b.forces.reactions[j]) for j in b.forces.reactions))
    assert err < 1e-9, (mech, variant, err)
    fns = {"symbolic": sym.run, "numeric": num.run}
    if variant == "kinematics" and hasattr(sym, "evaluate"):
        # the lambdified kinematics alone (no path, unwrapping, screening or Analysis)
        fns["symbolic_evaluate"] = lambda: sym.evaluate(*sym.sweep())
    if mech == "fourbar" and variant == "kinematics":
        hand = handwritten_fourbar(scene)
        ref = hand()
        assert rel_err(a.links["rocker"].omega, ref["rocker"][1]) < 1e-9
        fns["handwritten"] = hand
    t = interleaved(fns, repeats=15)
    us = 1e6 / STEPS
    out = {f"{k}_us_per_position": v * us for k, v in t.items()}
    out["symbolic_over_numeric"] = t["symbolic"] / t["numeric"]
    if "handwritten" in t:
        out["symbolic_over_handwritten"] = t["symbolic"] / t["handwritten"]
        if "symbolic_evaluate" in t:
            out["symbolic_evaluate_over_handwritten"] = t["symbolic_evaluate"] / t["handwritten"]
        out["numeric_over_handwritten"] = t["numeric"] / t["handwritten"]
    out["max_rel_difference_symbolic_vs_numeric"] = err
    return out


def main():
    results = {
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "sympy": sympy_version(),
        "machine": platform.machine(),
        "processor": platform.processor() or "unknown",
        "cpus": os.cpu_count(),
        "steps": STEPS,
        "commit": git_state(),
        "heap_state": "steady (steady_heap() before evaluation timings)",
        "build": {},
        "evaluation": {},
    }
    with tempfile.TemporaryDirectory(prefix="linkage_sym_bench_") as tmp:
        for mech in MECHANISMS:
            for variant in VARIANTS:
                print(f"building {mech} {variant} ...", flush=True)
                results["build"][f"{mech}_{variant}"] = build_and_load(mech, variant, tmp)
        os.environ["LINKAGE_SYM_CACHE"] = tmp
        steady_heap()
        for mech in MECHANISMS:
            for variant in VARIANTS:
                print(f"evaluating {mech} {variant} ...", flush=True)
                results["evaluation"][f"{mech}_{variant}"] = evaluate_case(mech, variant)
    results["sympy_imported_by_this_process"] = "sympy" in sys.modules
    six = results["build"]["sixbar_forces"]
    four = results["evaluation"]["fourbar_kinematics"]
    results["targets"] = {
        "sixbar_forces_derive_plus_compile_lt_10s": {
            "measured_s": six["derive_plus_compile_s"], "met": six["derive_plus_compile_s"] < 10},
        "sixbar_forces_cache_load_lt_0.5s_in_process": {
            "measured_s": six["cache_load_in_process_s"], "met": six["cache_load_in_process_s"] < 0.5},
        "sixbar_forces_cache_load_lt_0.5s_subprocess_wall": {
            "measured_s": six["cache_load_subprocess_wall_s"],
            "met": six["cache_load_subprocess_wall_s"] < 0.5},
        "fourbar_kinematics_within_1.5x_handwritten": {
            "measured_ratio": four["symbolic_over_handwritten"],
            "met": four["symbolic_over_handwritten"] <= 1.5},
        "fourbar_kinematics_evaluate_only_within_1.5x_handwritten": {
            "measured_ratio": four.get("symbolic_evaluate_over_handwritten", float("nan")),
            "met": four.get("symbolic_evaluate_over_handwritten", np.inf) <= 1.5},
    }
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "symbolic.json").write_text(json.dumps(results, indent=2) + "\n")

    print(f"\nbuild (s) -- sympy import {six['sympy_import_s']:.2f} s, not included")
    print(f"{'case':22s} {'derive':>8s} {'generate':>9s} {'total':>8s} {'load':>8s} {'load wall':>10s} sympy?")
    for k, b in results["build"].items():
        print(f"{k:22s} {b['derive_s']:8.2f} {b['generate_s']:9.2f} {b['derive_plus_compile_s']:8.2f} "
              f"{b['cache_load_in_process_s']:8.3f} {b['cache_load_subprocess_wall_s']:10.3f} "
              f"{b['cache_load_imported_sympy']}")
    print("\nevaluation, µs per position (steady heap)")
    print(f"{'case':22s} {'symbolic':>9s} {'numeric':>9s} {'hand':>7s} {'sym/num':>8s} {'sym/hand':>9s}")
    for k, e in results["evaluation"].items():
        if "symbolic_evaluate_us_per_position" in e:
            print(f"  ({k}: evaluate() only {e['symbolic_evaluate_us_per_position']:.3f})")
        h = e.get("handwritten_us_per_position")
        r = e.get("symbolic_over_handwritten")
        print(f"{k:22s} {e['symbolic_us_per_position']:9.3f} {e['numeric_us_per_position']:9.3f} "
              f"{'' if h is None else f'{h:7.3f}':>7s} {e['symbolic_over_numeric']:8.2f} "
              f"{'' if r is None else f'{r:9.2f}':>9s}")
    print("\ntargets")
    for k, t in results["targets"].items():
        v = t.get("measured_s", t.get("measured_ratio"))
        print(f"  {k}: {v:.3f} -> {'met' if t['met'] else 'MISSED'}")


if __name__ == "__main__":
    main()
