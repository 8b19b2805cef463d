"""Benchmark: µs per position of the kinematics (positions, velocities, accelerations).

Run on demand (not part of the tests)::

    python benchmarks/bench_kinematics.py            # writes benchmarks/results/kinematics.json

Pinned to one core's worth of BLAS threads.  Every figure of one run is
measured in that run, so ratios are comparable even on a noisy shared
machine; each timing is the best of several repeats.

Compared
--------
Allocator state.  NumPy temporaries come from glibc's heap.  In a fresh
process glibc trims the heap top back to the system whenever more than
128 kB is free there, so every run page-faults its temporaries in again;
once the process has freed one block above the mmap threshold, glibc raises
both thresholds and the heap is kept.  A ``Plan.run`` writes all its result
arrays into one block (see ``Plan._analysis``), so its first run in a
process does this; a one-off formula with small arrays never does.
Three states are measured:

* ``fresh``: each contender alone in its own new interpreter: the first
  (cold) call and the best of the following calls, with the minor page
  faults of the first and of a warm call, and the bytes a call allocates
  (tracemalloc: what the result keeps, and the peak).  ``compile_plan``
  warms the memory a run takes (:func:`linkage_sym.numeric.engine.block.warm`);
  ``linkage_sym_unwarmed`` is the same plan compiled without that, so the
  compile time it adds and the first call it saves are measured in one run.  Whether glibc keeps the heap depends on
  its layout after the imports, which varies between interpreters, so each
  contender runs in ``FRESH_RUNS`` interpreters; medians and ranges.
  ``fresh_memory``, in the same interpreter state as a first ``Plan.run``
  (imports done, plan compiled): writing one array of that run's result
  block's size, the first touch of fresh memory no later call pays.
* ``steady``: both contenders in one process after it has freed a large
  block (as any session that imported Matplotlib or SymPy has), their
  calls alternating, best of ``STEADY_CALLS`` each;
  ``MALLOC_TRIM_THRESHOLD_`` in the environment gives this state from the
  start.

Contenders:

* ``linkage_sym`` four-bar: ``Plan.run`` over 3600 steps, producing every
  link's rotation/omega/alpha and origin motion, every joint's and centre
  of mass's position, velocity and acceleration (what the result file
  holds), with validity and singularity screening.
* hand-written four-bar: the links' and centres of mass's motion and the
  moving joints' motion from a vectorised NumPy closed form written for
  this one mechanism (circle intersection, eqs. 3-13/3-14/3-16 of the textbook
  chapter 3 on kinematic analysis, [4] of the README's Sources),
  no checks.
* six-bar (the shipped Watt six-bar), 3600 and 100,000 steps.
* the class-III six-bar (a Newton group), 3600 steps, in both runtimes
  (``Plan.run`` and ``CompiledMechanism.run``): the batched continuation
  (:mod:`linkage_sym.numeric.continuation.batched_path`) and the point-by-point walk, in
  the same run, against the Watt six-bar in the same runtime (target: within
  10x of it);
* the printing mechanism, the hydraulic boom and the planetary train (3600
  steps): their Newton groups in loop-closure coordinates (the default) and
  in pose coordinates, against the Watt six-bar;
* the root searches at the unassemblable steps of a knee linkage's Newton
  group (two turns of the knee, 721 steps), batched and point by point: their
  time per unassemblable step.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import dataclasses  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tracemalloc  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.numeric.engine import block  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402

HERE = Path(__file__).resolve().parent
FRESH_RUNS = 7
STEADY_CALLS = 40


def best_time(fn, repeats=7):
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def steady_heap():
    """Free one 16 MB block so glibc raises its trim threshold (see the module docstring).

    16 MB stays below glibc's 32 MB cap on the dynamic threshold.
    """
    block = np.ones(2_000_000)
    del block


def with_steps(scene, steps):
    drivers = tuple(dataclasses.replace(d, steps=steps) for d in scene.drivers)
    return dataclasses.replace(scene, drivers=drivers, outputs=("kinematics",))


def handwritten_fourbar(scene):
    """A vectorised closed form of the crank-rocker, written for this mechanism only."""
    A, B, C, D = (np.array(scene.joint(n).at) for n in "ABCD")
    l1, l2, l3 = np.linalg.norm(B - A), np.linalg.norm(C - B), np.linalg.norm(C - D)
    t10 = np.arctan2(*(B - A)[::-1])
    t20 = np.arctan2(*(C - B)[::-1])
    t30 = np.arctan2(*(C - D)[::-1])
    coms = {lk.name: np.array(lk.com) for lk in scene.links}
    local = {
        "crank": coms["crank"] - A,
        "coupler": coms["coupler"] - B,
        "rocker": coms["rocker"] - D,
    }
    d = scene.drivers[0]

    def run():
        th1 = np.linspace(d.start, d.stop, d.steps)
        w1, a1 = d.speed, d.acceleration
        c1, s1 = np.cos(th1), np.sin(th1)
        bx, by = A[0] + l1 * c1, A[1] + l1 * s1
        ex, ey = D[0] - bx, D[1] - by
        dd = np.hypot(ex, ey)
        a = (dd * dd + l2 * l2 - l3 * l3) / (2 * dd)
        h = np.sqrt(l2 * l2 - a * a)
        cx = bx + (a * ex - h * ey) / dd
        cy = by + (a * ey + h * ex) / dd
        th2 = np.arctan2(cy - by, cx - bx)
        th3 = np.arctan2(cy - D[1], cx - D[0])
        s12, s32 = np.sin(th1 - th2), np.sin(th3 - th2)
        w3 = w1 * l1 * s12 / (l3 * s32)
        w2 = -w1 * l1 * np.sin(th1 - th3) / (l2 * np.sin(th2 - th3))
        al3 = (w1**2 * l1 * np.cos(th1 - th2) + w2**2 * l2 - w3**2 * l3 * np.cos(th3 - th2)
               + a1 * l1 * s12) / (l3 * s32)
        al2 = (-w1**2 * l1 * np.cos(th1 - th3) - w2**2 * l2 * np.cos(th2 - th3) + w3**2 * l3
               - a1 * l1 * np.sin(th1 - th3)) / (l2 * np.sin(th2 - th3))
        # joint velocities/accelerations of B and C
        vb = (-w1 * l1 * s1, w1 * l1 * c1)
        vc = (-w3 * (cy - D[1]), w3 * (cx - D[0]))
        ab = (-a1 * l1 * s1 - w1 * w1 * l1 * c1, a1 * l1 * c1 - w1 * w1 * l1 * s1)
        ac = (-al3 * (cy - D[1]) - w3 * w3 * (cx - D[0]), al3 * (cx - D[0]) - w3 * w3 * (cy - D[1]))
        # a centre of mass moves with its link's origin (the coupler's is B, which moves)
        zero = (0.0, 0.0)
        out = {
            "crank": rigid_motion(th1 - t10, w1, a1, (A[0], A[1]), zero, zero, local["crank"]),
            "coupler": rigid_motion(th2 - t20, w2, al2, (bx, by), vb, ab, local["coupler"]),
            "rocker": rigid_motion(th3 - t30, w3, al3, (D[0], D[1]), zero, zero, local["rocker"]),
        }
        out["joints"] = (bx, by, cx, cy, vb, vc, ab, ac)
        return out

    return run


def rigid_motion(r, w, al, O, vO, aO, local):
    """A link's rotation ``r`` from its assembly angle, ``w``, ``al``, and the position,
    velocity and acceleration of its point at ``local`` (assembly frame, relative to the
    point ``O`` whose motion is ``O, vO, aO``) -- the hand-written contenders' rigid body."""
    c, s = np.cos(r), np.sin(r)
    x, y = local
    rx, ry = c * x - s * y, s * x + c * y
    return (
        r, w, al,
        O[0] + rx, O[1] + ry,
        vO[0] - w * ry, vO[1] + w * rx,
        aO[0] - al * ry - w * w * rx, aO[1] + al * rx - w * w * ry,
    )


def with_outputs(scene, steps, outputs):
    drivers = tuple(dataclasses.replace(d, steps=steps) for d in scene.drivers)
    return dataclasses.replace(scene, drivers=drivers, outputs=tuple(outputs))


def _runtimes(scene):
    """``{runtime: run}``: the numeric plan and the compiled symbolic mechanism."""
    return {"numeric": compile_plan(scene).run,
            "symbolic": linkage_sym.compile_mechanism(scene).run}


def _agree(a, b, size, what):
    """Statuses equal, positions within 1e-10 of the size: timings compare like with like."""
    assert np.array_equal(a.status, b.status), what
    for name, j in a.joints.items():
        err = float(np.nanmax(np.abs(j.position - b.joints[name].position), initial=0.0))
        assert err <= 1e-10 * size, (what, name, err)


def newton_groups(outputs, steps=3600, repeats=5, slow_repeats=2):
    """The class-III six-bar (a Newton group) against the Watt six-bar (dyads), both runtimes.

    For each runtime (``Plan.run``, ``CompiledMechanism.run``): the class-III
    six-bar with the batched continuation (the default) and point by point
    (``continuation.BATCHED = False``, what every version before it did), and
    the Watt six-bar, all ``steps`` steps with ``outputs``; the batched and
    point-by-point results are checked to agree first.  The batched and Watt
    calls alternate, best of ``repeats`` each.
    """
    from linkage_sym.numeric import continuation

    tri = with_outputs(linkage_sym.load_example("sixbar_class3"), steps, outputs)
    six = with_outputs(linkage_sym.load_example("watt_sixbar"), steps, outputs)
    tri_runs, six_runs = _runtimes(tri), _runtimes(six)
    out = {"steps": steps, "outputs": list(outputs)}
    for runtime, run in tri_runs.items():
        continuation.BATCHED = False
        seq = run()
        continuation.BATCHED = True
        _agree(seq, run(), tri.characteristic_length(), runtime)
        t_bat = t_six = np.inf
        for _ in range(repeats):
            t_bat = min(t_bat, best_time(run, 1))
            t_six = min(t_six, best_time(six_runs[runtime], 1))
        continuation.BATCHED = False
        t_seq = best_time(run, slow_repeats)
        continuation.BATCHED = True
        us = 1e6 / steps
        out[runtime] = {
            "class3_batched_us_per_position": t_bat * us,
            "class3_point_by_point_us_per_position": t_seq * us,
            "watt_sixbar_us_per_position": t_six * us,
            "batched_speedup": t_seq / t_bat,
            "class3_batched_over_watt": t_bat / t_six,
            "target_within_10x_watt_met": bool(t_bat / t_six <= 10.0),
        }
    return out


def loop_versus_pose(name, steps=3600, repeats=5):
    """A shipped example with a Newton group (the printing mechanism of Dang and Zhang: a
    triad with a slider; the hydraulic boom: an actuator group with its driven slide; the
    planetary train: arm and planet, two mesh rows): its
    group in loop-closure coordinates (angles and slides, the default) and in pose
    coordinates, against the Watt six-bar, kinematics, calls alternating, best of
    ``repeats``; the two formulations are checked to agree first."""
    from linkage_sym.numeric.kinematics import loop_closure

    scene = with_outputs(linkage_sym.load_example(name), steps, ("kinematics",))
    six = compile_plan(with_outputs(linkage_sym.load_example("watt_sixbar"), steps,
                                    ("kinematics",)))
    loop = compile_plan(scene)
    applies = loop_closure.applies
    loop_closure.applies = lambda *a: False
    try:
        pose = compile_plan(scene)
    finally:
        loop_closure.applies = applies
    _agree(pose.run(), loop.run(), scene.characteristic_length(), name)
    t_loop = t_pose = t_six = np.inf
    for _ in range(repeats):
        t_loop = min(t_loop, best_time(loop.run, 1))
        t_pose = min(t_pose, best_time(pose.run, 1))
        t_six = min(t_six, best_time(six.run, 1))
    us = 1e6 / steps
    return {
        "steps": steps,
        "loop_closure_us_per_position": t_loop * us,
        "pose_coordinates_us_per_position": t_pose * us,
        "watt_sixbar_us_per_position": t_six * us,
        "loop_closure_over_watt": t_loop / t_six,
        "pose_over_loop_closure": t_pose / t_loop,
    }


def knee_scene(steps=721):
    """A knee linkage (thigh on a hip pivot, shin driven at the knee, a rocker from the ankle
    to the ground: one driven Newton group) over two turns of the knee: limit positions and
    unassemblable stretches (the tests' ``scenes.knee_scene``)."""
    K, A, G = (0.3, 0.5), (0.7, 0.2), (0.6, -0.2)
    mid = lambda p, q: [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]  # noqa: E731
    return linkage_sym.load_scene({
        "name": "knee",
        "links": [{"name": "thigh", "mass": 1.0, "com": mid((0, 0), K), "inertia": 0.01},
                  {"name": "shin", "mass": 1.0, "com": mid(K, A), "inertia": 0.01},
                  {"name": "rocker", "mass": 0.5, "com": mid(A, G), "inertia": 0.005}],
        "joints": [{"name": "H", "type": "R", "links": ["ground", "thigh"], "at": [0.0, 0.0]},
                   {"name": "K", "type": "R", "links": ["thigh", "shin"], "at": list(K)},
                   {"name": "A", "type": "R", "links": ["shin", "rocker"], "at": list(A)},
                   {"name": "G", "type": "R", "links": ["rocker", "ground"], "at": list(G)}],
        "drivers": [{"joint": "K", "toward": "A", "start_deg": -180, "stop_deg": 540,
                     "steps": steps, "speed": 1.0, "acceleration": 0.5}],
        "outputs": ["kinematics"],
    })


def newton_gaps(repeats=2):
    """What unassemblable steps of a Newton group cost: the root searches of the knee
    linkage's gaps (time inside them over the number of unassemblable steps), batched and
    point by point, both runtimes; and the whole run."""
    from linkage_sym.numeric.continuation import batched_path
    from linkage_sym.numeric import continuation

    scene = knee_scene()
    spent = {"search": 0.0}

    def timed(f):
        def g(*a, **k):
            t0 = time.perf_counter()
            try:
                return f(*a, **k)
            finally:
                spent["search"] += time.perf_counter() - t0
        return g

    originals = (continuation.roots_near, batched_path.search_gap)
    continuation.roots_near, batched_path.search_gap = (timed(f) for f in originals)
    out = {"steps": 721}
    try:
        for runtime, run in _runtimes(scene).items():
            res = run()
            n_gap = int((res.status == "unassemblable").sum())
            out["unassemblable_steps"] = n_gap
            for mode, batched in (("point_by_point", False), ("batched", True)):
                continuation.BATCHED = batched
                best = (np.inf, np.inf)
                for _ in range(repeats):
                    spent["search"] = 0.0
                    t0 = time.perf_counter()
                    run()
                    best = min(best, (time.perf_counter() - t0, spent["search"]))
                out[f"{runtime}_{mode}"] = {
                    "run_ms": 1e3 * best[0],
                    "search_ms_per_unassemblable_step": 1e3 * best[1] / n_gap,
                }
    finally:
        continuation.roots_near, batched_path.search_gap = originals
        continuation.BATCHED = True
    return out


def fourbar_contenders():
    four = with_steps(linkage_sym.load_example("crank_rocker"), 3600)
    plan = compile_plan(four)
    return four, {"linkage_sym": plan.run, "handwritten": handwritten_fourbar(four)}


def fresh_plan(warm):
    """The four-bar's plan compiled in this (fresh) interpreter, with or without warming
    the memory of its runs; returns ``(run, compile seconds)``."""
    if not warm:
        block.ResultLayout.warm = lambda self, n_steps, runtime: 0
    four = with_steps(linkage_sym.load_example("crank_rocker"), 3600)
    t0 = time.perf_counter()
    plan = compile_plan(four)
    return plan.run, time.perf_counter() - t0


def fresh_memory():
    """In this (fresh) interpreter, in the state a first ``Plan.run`` of a plan compiled
    without warming meets (imports done, the plan compiled): the time and minor page faults
    of writing one array of the size of that run's result block -- the first touch of fresh
    memory that no later call pays, and that ``compile_plan`` now does instead."""
    run, _ = fresh_plan(warm=False)
    n = run.__self__.layout.n_rows * 3600
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0 = time.perf_counter()
    a = np.empty(n)
    a.fill(1.0)
    t = time.perf_counter() - t0
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    return {"us_per_position": 1e6 * t / 3600, "minor_page_faults": faults, "MB": 8 * n / 1e6}


def fresh(name):
    """Measure one contender alone in this (fresh) interpreter; returns a dict."""
    if name == "fresh_memory":
        return fresh_memory()
    compiled = {}
    if name.startswith("linkage_sym"):
        fn, t_compile = fresh_plan(warm=name == "linkage_sym")
        compiled = {"compile_ms": 1e3 * t_compile}
    else:
        fn = fourbar_contenders()[1][name]
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0 = time.perf_counter()
    fn()
    cold = time.perf_counter() - t0
    cold_faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    t0 = time.perf_counter()
    fn()
    second = time.perf_counter() - t0
    warm = best_time(fn)
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    fn()
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    tracemalloc.reset_peak()
    res = fn()
    kept, peak = tracemalloc.get_traced_memory()
    del res
    tracemalloc.stop()
    return {
        **compiled,
        "cold_us_per_position": 1e6 * cold / 3600,
        "second_us_per_position": 1e6 * second / 3600,
        "us_per_position": 1e6 * warm / 3600,
        "minor_page_faults_first_call": cold_faults,
        "minor_page_faults_per_call": faults,
        "result_MB": (kept - base) / 1e6,
        "peak_MB": (peak - base) / 1e6,
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

    four, contenders = fourbar_contenders()
    plan = compile_plan(four)
    # check the two agree before timing means anything
    ref = contenders["handwritten"]()
    res = plan.run()
    err = np.max(np.abs(res.links["rocker"].omega - ref["rocker"][1]))
    assert err < 1e-9 * np.max(np.abs(ref["rocker"][1])), err
    del res, ref

    # fresh: each contender in its own new interpreter, FRESH_RUNS times (alternating):
    # whether glibc keeps the heap depends on the heap's layout after the imports, so
    # one interpreter is one sample; medians and ranges are reported
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    samples = {name: [] for name in [*contenders, "linkage_sym_unwarmed", "fresh_memory"]}
    for _ in range(FRESH_RUNS):
        for name in samples:
            out = subprocess.run(
                [sys.executable, __file__, "--fresh", name],
                capture_output=True, text=True, check=True, env=env,
            )
            samples[name].append(json.loads(out.stdout))
    fr = {"interpreters_per_contender": FRESH_RUNS}
    for name, runs in samples.items():
        fr[name] = {
            key: {"median": float(np.median([r[key] for r in runs])),
                  "min": float(np.min([r[key] for r in runs])),
                  "max": float(np.max([r[key] for r in runs]))}
            for key in runs[0]
        }
    lib, hand = fr["linkage_sym"], fr["handwritten"]
    fr["ratio_of_medians"] = lib["us_per_position"]["median"] / hand["us_per_position"]["median"]
    fr["ratio_of_medians_cold"] = (
        lib["cold_us_per_position"]["median"] / hand["cold_us_per_position"]["median"]
    )
    # the first call against later ones
    first = lib["cold_us_per_position"]["median"]
    later = lib["us_per_position"]["median"]
    fr["first_over_later"] = first / later
    fr["target_first_within_2x_met"] = bool(first / later <= 2.0)
    # the same plan compiled without warming its runs' memory: what warming moves; and that
    # first call without the first touch of its result block's fresh memory (measured alone
    # in the same interpreter state)
    cold = fr["linkage_sym_unwarmed"]
    first_cold = cold["cold_us_per_position"]["median"]
    later_cold = cold["us_per_position"]["median"]
    touch = fr["fresh_memory"]["us_per_position"]["median"]
    fr["unwarmed_first_over_later"] = first_cold / later_cold
    fr["unwarmed_first_less_fresh_memory_over_later"] = (first_cold - touch) / later_cold
    fr["warming_adds_to_compile_ms"] = lib["compile_ms"]["median"] - cold["compile_ms"]["median"]
    # compile, first and second call (a 3600-step call's ms is 3.6 times its us per position)
    fr["compile_and_first_two_calls_ms"] = {
        k: fr[k]["compile_ms"]["median"] + 3.6 * (
            fr[k]["cold_us_per_position"]["median"] + fr[k]["second_us_per_position"]["median"])
        for k in ("linkage_sym", "linkage_sym_unwarmed")
    }
    cases["fourbar_3600_fresh"] = fr

    # steady: both in this process after a large block was freed
    steady_heap()
    # calls alternate, best of STEADY_CALLS each: a busy spell of the shared machine
    # slows both contenders alike instead of one of them
    t_lib = t_hand = np.inf
    for _ in range(STEADY_CALLS):
        t_lib = min(t_lib, best_time(contenders["linkage_sym"], 1))
        t_hand = min(t_hand, best_time(contenders["handwritten"], 1))
    cases["fourbar_3600_steady"] = {
        "linkage_sym_us_per_position": 1e6 * t_lib / 3600,
        "handwritten_us_per_position": 1e6 * t_hand / 3600,
        "ratio": t_lib / t_hand,
    }
    t_compile = best_time(lambda: compile_plan(four), repeats=5)
    cases["fourbar_compile_ms"] = 1e3 * t_compile

    six = linkage_sym.load_example("watt_sixbar")
    for n in (3600, 100_000):
        p = compile_plan(with_steps(six, n))
        t = best_time(p.run, repeats=5)
        cases[f"sixbar_{n}"] = {"us_per_position": 1e6 * t / n, "seconds": t}

    cases["class3_sixbar_3600_newton"] = newton_groups(("kinematics",))
    cases["printing_mechanism_3600"] = loop_versus_pose("printing_mechanism")
    cases["hydraulic_boom_3600"] = loop_versus_pose("hydraulic_boom")
    cases["planetary_train_3600"] = loop_versus_pose("planetary_train")
    cases["knee_gaps_newton"] = newton_gaps()

    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "kinematics.json").write_text(json.dumps(results, indent=2) + "\n")
    print(json.dumps(results, indent=2))


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--fresh":
        print(json.dumps(fresh(sys.argv[2])))
    else:
        main()
