"""Benchmark: what ``simulate`` costs per turn of the crank (issue 29).

Run on demand (not part of the tests)::

    python benchmarks/bench_simulate.py     # writes benchmarks/results/simulate.json

Each evaluation of the equation of motion solves the mechanism at one state: the numeric
plan's effort at ``qdd = 0`` and ``J``, both from one solve of the plan
(:func:`linkage_sym.motion.lean.effort_inertia_at`).  Timed: the whole ``simulate`` of the crank-rocker with its
motor (``crank_rocker_motor``, 3 s from rest) and of the shaper with its flywheel
(``shaper_flywheel``, 12 s from rest), LSODA at rtol 1e-10 (the default); CPU time
(``time.process_time``) of one run after a first run that compiles and caches, with one
core's worth of BLAS threads, and the time of one evaluation at 200 states of a turn.
With Exudyn installed, the crank-rocker with a constant rocker torque and the shaper with its
flywheel against Exudyn's forward dynamics of the same machines as well (:func:`exudyn_cases`).
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.examples import example_dict  # noqa: E402
from linkage_sym.motion.equations import MotionEquations  # noqa: E402
from linkage_sym.motion.simulate import simulate  # noqa: E402

HERE = Path(__file__).resolve().parent
CASES = ("crank_rocker_motor", "shaper_flywheel")


def per_evaluation(scene, n=200) -> float:
    """CPU seconds of one evaluation of ``qdd`` (mean over ``n`` states of a turn)."""
    eq = MotionEquations(scene, require_simulate=False)
    qs = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    eq.acceleration(0.1, 10.0)
    t = time.process_time()
    for q in qs:
        eq.acceleration(float(q), 10.0 + q)
    return (time.process_time() - t) / n


def case(name) -> dict:
    scene = linkage_sym.load_scene(example_dict(name))
    simulate(scene)  # compiles (and caches) the mechanism's equations
    t = time.process_time()
    res = simulate(scene)
    cpu = time.process_time() - t
    q = res.analysis.drivers[scene.drivers[0].joint]["q"]
    turns = abs(float(q[-1] - q[0])) / (2 * math.pi)
    integ = res.trajectory.integrator()
    return {"scene": name, "duration_s": scene.simulate.duration, "turns": turns,
            "cpu_s": cpu, "cpu_per_turn_s": cpu / turns, "steps": integ["steps"],
            "evaluations": integ["evaluations"],
            "evaluations_per_turn": integ["evaluations"] / turns,
            "cpu_per_evaluation_ms": 1e3 * per_evaluation(scene),
            "end": integ["end"], "method": integ["method"]}


def exudyn_case(data, label, step=5e-5, newton=(1e-12, 1e-14)) -> dict | None:
    """The scene ``data`` in ``simulate`` and in Exudyn's forward dynamics
    (:mod:`tests.support.exudyn_model`: generalized-alpha at a fixed ``step``, its Newton at
    the tolerances ``newton``): the CPU time per turn of each and the driven link's speeds'
    largest difference over the run, relative to the largest speed; ``None`` without Exudyn."""
    try:
        import exudyn
    except ImportError:
        return None
    sys.path.insert(0, str(HERE.parent))
    from tests.support.exudyn_model import driver_speed

    scene = linkage_sym.load_scene(data)
    joint = scene.drivers[0].joint
    simulate(scene)
    t = time.process_time()
    res = simulate(scene)
    ours = time.process_time() - t
    t = time.process_time()
    te, we = driver_speed(data, scene.simulate.duration, step, newton)
    theirs = time.process_time() - t
    q = res.analysis.drivers[joint]["qd"]
    turns = abs(float(res.analysis.drivers[joint]["q"][-1] - res.analysis.drivers[joint]["q"][0])) / (2 * math.pi)
    return {"scene": label, "exudyn": exudyn.__version__, "exudyn_step_s": step,
            "duration_s": scene.simulate.duration, "turns": turns,
            "cpu_per_turn_s": {"linkage_sym": ours / turns, "exudyn": theirs / turns},
            "max_speed_difference_relative": float(np.max(np.abs(np.interp(res.time, te, we) - q))
                                                   / np.max(np.abs(q)))}


def exudyn_cases() -> list:
    """The crank-rocker with a constant torque on the rocker (tests/motion/test_exudyn.py) and
    the shaper with its flywheel, its cutting force and motor table as shipped, over 3 s from
    rest (its cutting force switches on and off with the crank's angle: Exudyn's fixed step
    crosses the switch with a first-order error, so the speeds agree less closely there)."""
    rocker = example_dict("crank_rocker_motor")
    load = rocker["loads"][0]
    del load["active_deg"], load["driver"]
    load["torque"] = -0.5
    rocker["simulate"]["samples"] = 301
    shaper = example_dict("shaper_flywheel")
    shaper["simulate"].update(duration=3.0, samples=301)
    out = [exudyn_case(rocker, "crank_rocker_motor, rocker torque -0.5 N m throughout"),
           # loads of hundreds of newtons: Exudyn's Newton needs an absolute tolerance in newtons
           exudyn_case(shaper, "shaper_flywheel, 3 s from rest", newton=(1e-10, 1e-8))]
    return None if out[0] is None else out


def main() -> dict:
    out = {"python": sys.version.split()[0], "machine": platform.machine(),
           "numpy": np.__version__, "cases": [case(n) for n in CASES],
           "exudyn": exudyn_cases()}
    for c in out["cases"]:
        print(f"{c['scene']}: {c['turns']:.2f} turns, {c['cpu_s']:.2f} s CPU, "
              f"{c['cpu_per_turn_s']:.3f} s/turn, {c['evaluations_per_turn']:.0f} "
              f"evaluations/turn, {c['cpu_per_evaluation_ms']:.2f} ms/evaluation")
    for e in out["exudyn"] or ():
        print(f"{e['scene']} against Exudyn {e['exudyn']}: {e['cpu_per_turn_s']}, speeds "
              f"within {e['max_speed_difference_relative']:.2g}")
    return out


if __name__ == "__main__":
    result = main()
    if "--no-write" not in sys.argv:
        (HERE / "results" / "simulate.json").write_text(json.dumps(result, indent=2) + "\n")
