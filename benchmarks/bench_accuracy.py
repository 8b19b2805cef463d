"""Benchmark: what accuracy costs in time -- error against time per position, by method.

Run on demand (not part of the tests)::

    python benchmarks/bench_accuracy.py          # writes benchmarks/results/accuracy.json and .png
    python benchmarks/bench_accuracy.py --plot   # redraws accuracy.png from accuracy.json

One BLAS thread; steady glibc heap (see ``bench_kinematics.py``); times are the best of
several repeats (one or two for the slow arbitrary-precision runs).

Cases (every step of each sweep measured):

* ``fourbar``: the shipped crank-rocker, kinematics only, 361 steps (well conditioned);
* ``toggle``: a triple rocker (2, 3, 2.5, 4) swept over the 20 degrees that end 0.01 degrees
  before its dead centre, kinematics, 361 steps (condition numbers up to ~7e2);
* ``class3``: the shipped class-III six-bar, kinematics, 361 steps (Newton positions);
* ``forces``: the shipped crank-rocker with inertia, gravity, loads and all four outputs.

Points: the numeric solver (``dyad``; ``global`` forces; ``exact condition`` everywhere),
the lambdified equations (``symbolic``), the arbitrary-precision run at 20, 30 and 50
digits (``mpmath``; its float64 output, and its unrounded values in the JSON),
finite-difference rates from positions at ``q`` and ``q +- h`` (what one does by hand) for
several ``h``, and for the class-III six-bar Newton tolerances (``continuation.TOL``).
Separately: the rocker's largest rotation from the largest of 36, 360 and 3600 samples
against ``find_extremes`` (``--extremes``).

Error: every value of every ok step against a 50-digit reference computed by
``tests/support/mp_reference.py`` -- the scene format's own equations solved in mpmath, sharing no
code with any method timed here -- in the scales of the accuracy estimate
(``tests/support/accuracy_checks.py``: positions over the size, rotations in rad, rates over the
step's largest speed or acceleration, forces over its largest reaction); a point's error is
the largest over steps and fields (the fields are in the JSON).  The extremes' reference is
the closed form's rate root (``tests/reference_kinematics.fourbar_mp``, 50 digits).
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import copy  # noqa: E402
import dataclasses  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

import reference_kinematics as ref  # noqa: E402
import scenes  # noqa: E402
from accuracy_checks import measured  # noqa: E402
from mp_reference import Reference  # noqa: E402

import linkage_sym  # noqa: E402
from bench_kinematics import steady_heap  # noqa: E402  (same folder)
from linkage_sym.codegen.compile import compile_mechanism  # noqa: E402
from linkage_sym.codegen.precision import PreciseMechanism  # noqa: E402
from linkage_sym.numeric.results import accuracy  # noqa: E402
from linkage_sym.numeric import continuation  # noqa: E402
from linkage_sym.numeric.continuation import roots  # noqa: E402
from linkage_sym.numeric.extremes import find_extremes  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.scene import load_scene  # noqa: E402

FIELDS = ("position", "velocity", "acceleration", "forces")
FD_STEPS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8)
DIGITS = (20, 30, 50)
TOLERANCES = (1e-6, 1e-9, 1e-11, 1e-13)


def best_time(fn, repeats):
    best, out = math.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def with_steps(scene, steps):
    return dataclasses.replace(scene, drivers=tuple(
        dataclasses.replace(d, steps=steps) for d in scene.drivers))


def kinematics_only(scene):
    return dataclasses.replace(scene, outputs=("kinematics",))


def toggle_scene(gap_deg=0.01, steps=361):
    lengths = (2.0, 3.0, 2.5, 4.0)
    with mp.workdps(30):
        lim = float(mp.degrees(ref.fourbar_limits_mp(*lengths)[0]))
    d, _ = scenes.fourbar(*lengths, start_deg=lim - 20 - gap_deg, stop_deg=lim - gap_deg,
                          steps=steps, speed=10.0, acceleration=3.0, name="toggle")
    return load_scene(d)


# ------------------------------------------------------------------ errors


def references(scene, res):
    """The 50-digit reference of every ok step (Newton from the dyad result's poses)."""
    R = Reference(scene)
    out = {}
    for i in range(res.n_steps):
        if res.status[i] == "ok":
            out[i] = R.solve(res, i)
    return out


def errors(scene, res, refs):
    """Largest measured error per field over the steps, and the worst estimate."""
    worst = {}
    for i, r in refs.items():
        if r is None or res.status[i] != "ok":
            continue
        for name, e in measured(scene, res, i, r).items():
            if e is not None and np.isfinite(e):
                worst[name] = max(worst.get(name, 0.0), e)
            elif e is not None:
                worst[name] = math.inf
    est = {}
    if getattr(res, "accuracy", None):
        est = {k: float(np.nanmax(v)) for k, v in res.accuracy.items()}
    return worst, est


def unrounded_error(pr, refs):
    """Largest error of the arbitrary-precision run's own (unrounded) joint positions over
    the size and link omegas over the step's largest one."""
    L = None
    worst = mp.mpf(0)
    for i, r in refs.items():
        s = pr.steps[i]
        if r is None or s is None:
            continue
        if L is None:
            L = max(mp.hypot(*r["joints"][n]["position"]) for n in r["joints"]) or 1
        for n, j in r["joints"].items():
            for k in (0, 1):
                worst = max(worst, abs(s["joints"][n]["position"][k] - j["position"][k]) / L)
        if "omega" in next(iter(r["links"].values())):
            W = max(abs(v["omega"]) for v in r["links"].values())
            for n, v in r["links"].items():
                worst = max(worst, abs(s["links"][n]["omega"] - v["omega"]) / W)
    return float(worst)


def fd_result(plan, q, qd, qdd, h):
    """Rates by central differences of positions at ``q - h``, ``q``, ``q + h`` (one driver)."""
    (name,) = q
    runs = [plan.run({name: q[name] + s * h}, qd, qdd) for s in (-1, 0, 1)]
    lo, mid, hi = runs
    w, a = qd[name], qdd[name]
    res = copy.deepcopy(mid)

    def d1(x0, x2):
        return (x2 - x0) / (2 * h)

    def d2(x0, x1, x2):
        return (x2 - 2 * x1 + x0) / (h * h)

    for n, jk in res.joints.items():
        p0, p1, p2 = (r.joints[n].position for r in runs)
        jk.velocity = d1(p0, p2) * w[:, None]
        jk.acceleration = d2(p0, p1, p2) * (w * w)[:, None] + d1(p0, p2) * a[:, None]
    for n, lk in res.links.items():
        r0, r1, r2 = (r.links[n].rotation for r in runs)
        lk.omega = d1(r0, r2) * w
        lk.alpha = d2(r0, r1, r2) * w * w + d1(r0, r2) * a
        if lk.com is not None:
            c0, c1, c2 = (r.links[n].com for r in runs)
            lk.com_velocity = d1(c0, c2) * w[:, None]
            lk.com_acceleration = d2(c0, c1, c2) * (w * w)[:, None] + d1(c0, c2) * a[:, None]
    for n, pk in res.points.items():
        p0, p1, p2 = (r.points[n].position for r in runs)
        pk.velocity = d1(p0, p2) * w[:, None]
        pk.acceleration = d2(p0, p1, p2) * (w * w)[:, None] + d1(p0, p2) * a[:, None]
    res.status = np.where((lo.status == "ok") & (hi.status == "ok"), mid.status, "unassemblable")
    res.accuracy = None
    return res


# ------------------------------------------------------------------ one case


def with_tolerance(fn, tol):
    """``fn`` run with the Newton groups' convergence tolerance ``tol``."""

    def run():
        saved = continuation.TOL  # the walk's first point reads it here, Newton in roots
        continuation.TOL = roots.TOL = tol
        try:
            return fn()
        finally:
            continuation.TOL = roots.TOL = saved

    return run


def case(label, scene, newton=False, forces=False, rounds=7):
    """Every contender of one case, timed in rounds (each round calls every contender once,
    so a busy spell of the shared machine slows them alike; best of the rounds)."""
    print(f"-- {label}", flush=True)
    plan = compile_plan(scene)
    N = scene.drivers[0].steps
    base = plan.run()
    t0 = time.perf_counter()
    refs = references(scene, base)
    ref_time = time.perf_counter() - t0
    cm = compile_mechanism(scene)
    cm.run()
    fast = [("double (dyad)", plan.run, {})]
    if forces:
        fast.append(("double, global forces", lambda: plan.run(method="global"), {}))
    fast += [("double + exact condition everywhere", lambda: plan.run(exact_condition=True), {}),
             ("symbolic (lambdified)", cm.run, {})]
    if not forces and len(scene.drivers) == 1:
        q, qd, qdd = plan.sweep()
        fast += [(f"finite differences h = {h:g}", lambda h=h: fd_result(plan, q, qd, qdd, h), {})
                 for h in FD_STEPS]
    if newton:
        for tol in TOLERANCES:
            p2 = compile_plan(scene)
            fast.append((f"Newton tolerance {tol:g}", with_tolerance(p2.run, tol), {"tolerance": tol}))
    slow = []
    for d in DIGITS:
        pm = PreciseMechanism(scene, d)
        slow.append((f"mpmath {d} digits", pm.run, {}))
    best = {}
    results = {}
    for group, n_rounds in ((fast, 3 if newton else rounds), (slow, 2)):
        for _ in range(n_rounds):
            for name, fn, _ in group:
                t0 = time.perf_counter()
                out = fn()
                t = time.perf_counter() - t0
                best[name] = min(best.get(name, math.inf), t)
                results.setdefault(name, out)
    points = []
    for name, _, extra in fast + slow:
        out = results[name]
        res = out.analysis if name.startswith("mpmath") else out
        err, est = errors(scene, res, refs)
        worst = max(err.values()) if err else math.nan
        rec = {"method": name, "us_per_position": best[name] * 1e6 / N, "error": worst,
               "errors": err, "estimate": est, **extra}
        if name.startswith("mpmath"):
            rec["unrounded_error"] = unrounded_error(out, refs)
        if name.startswith("finite"):
            rec["steps_lost"] = int(np.sum(res.status != base.status))
        points.append(rec)
        print(f"   {name:36s} {rec['us_per_position']:12.3f} us/pos   error {worst:.3g}", flush=True)
    return {"steps": N, "reference_seconds": ref_time,
            "largest_condition_estimate": float(np.nanmax(accuracy.condition_of(base.accuracy))),
            "points": points}


# ------------------------------------------------------------------ extremes


def extremes_study():
    """The crank-rocker's largest rocker rotation: sampled maxima against find_extremes."""
    print("-- extremes", flush=True)
    base = kinematics_only(linkage_sym.load_example("crank_rocker"))
    # reference: the closed form's rate root (omega_3 = 0) from the scene's binary64 joints
    with mp.workdps(50):
        J = {j.name: (mp.mpf(j.at[0]), mp.mpf(j.at[1])) for j in base.joints}
        A, B, C, D = J["A"], J["B"], J["C"], J["D"]
        assert A == (0, 0) and D[1] == 0
        ls = (mp.hypot(*B), mp.hypot(C[0] - B[0], C[1] - B[1]),
              mp.hypot(C[0] - D[0], C[1] - D[1]), D[0])
        th3_0 = mp.atan2(C[1] - D[1], C[0] - D[0])
        # the assembly mode: the side of line D -> B that C is on
        sg = 1 if (B[0] - D[0]) * (C[1] - D[1]) - (B[1] - D[1]) * (C[0] - D[0]) > 0 else -1
        sweep = [mp.mpf(float(v)) for v in np.radians(np.linspace(0, 360, 361))]
        w3 = [ref.fourbar_mp(*ls, t, 1, 0, sg)["w3"] for t in sweep]
        exact = None
        for a, b, wa, wb in zip(sweep, sweep[1:], w3, w3[1:]):
            if (wa < 0) != (wb < 0):
                root = mp.findroot(lambda t: ref.fourbar_mp(*ls, t, 1, 0, sg)["w3"], (a, b),
                                   solver="anderson")
                th3 = ref.fourbar_mp(*ls, root, 1, 0, sg)["th3"] - th3_0
                th3 = mp.atan2(mp.sin(th3), mp.cos(th3))
                exact = th3 if exact is None else max(exact, th3)
    rows = []
    for n in (36, 360, 3600):
        scene = with_steps(base, n + 1)
        plan = compile_plan(scene)
        plan.run()
        t, res = best_time(plan.run, 7)
        sampled = float(np.max(res.links["rocker"].rotation))
        # the sampled maximum's error depends on where the samples fall: its worst over 16
        # phases of the sweep (starts shifted by 1/16 of a step, the assembly kept) is the
        # O(1/N^2) figure, f'' Delta^2 / 8
        worst = 0.0
        for k in range(16):
            shift = 360.0 / n * k / 16
            drivers = tuple(dataclasses.replace(d, start=d.start + math.radians(shift),
                                                stop=d.stop + math.radians(shift))
                            for d in scene.drivers)
            r = compile_plan(dataclasses.replace(scene, drivers=drivers)).run()
            worst = max(worst, float(exact - float(np.max(r.links["rocker"].rotation))))
        rows.append({"method": f"largest of {n} samples", "steps": n + 1, "seconds": t,
                     "value": sampled, "error_this_sweep": float(abs(exact - sampled)),
                     "error": worst})
        if n in (36, 360):
            t, ext = best_time(lambda: find_extremes(scene, plan, plan.run()), 3)
            e = ext.values["links", "rocker", "rotation"]["max"]
            rows.append({"method": f"--extremes on {n} steps", "steps": n + 1, "seconds": t,
                         "value": e.value, "error": float(abs(exact - e.value)),
                         "plan_runs": ext.evaluations})
    for r in rows:
        print(f"   {r['method']:28s} {r['seconds'] * 1e3:9.2f} ms   error {r['error']:.3g} rad",
              flush=True)
    return {"quantity": "largest rotation of the crank-rocker's rocker (rad); a sampled "
                        "maximum's error is its worst over 16 phases of the samples",
            "reference": float(exact), "points": rows}


# ------------------------------------------------------------------ plot


def _kind(method):
    for prefix, kind in (("double", "float64 solver"), ("symbolic", "lambdified (float64)"),
                         ("mpmath", "mpmath, digits"), ("finite", "finite-difference rates, h"),
                         ("Newton", "Newton tolerance")):
        if method.startswith(prefix):
            return kind
    return method


STYLE = {"float64 solver": ("o", "C0"), "lambdified (float64)": ("s", "C1"),
         "mpmath, digits": ("D", "C3"), "finite-difference rates, h": ("v", "C2"),
         "Newton tolerance": ("^", "C4")}


def _label(method):
    m = method
    for old, new in (("double (dyad)", "dyad"), ("double + exact condition everywhere", "exact cond."),
                     ("double, global forces", "global forces"), ("symbolic (lambdified)", ""),
                     ("finite differences h = ", "h="), ("mpmath ", ""), (" digits", ""),
                     ("Newton tolerance ", "tol ")):
        m = m.replace(old, new)
    return m


def plot(results, path):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.ticker import NullFormatter

    titles = {"fourbar": "four-bar, well conditioned (kinematics)",
              "toggle": "four-bar, last step 0.01° from a dead centre",
              "class3": "class-III six-bar (kinematics; Newton groups)",
              "forces": "four-bar with inertia, gravity, loads (forces)"}
    fig = Figure(figsize=(14, 9), layout="constrained")
    axes = fig.subplots(2, 3)
    floor = 1e-17
    for ax, (key, title) in zip(axes.flat, titles.items()):
        pts = results["cases"][key]["points"]
        seen = {}
        for p in pts:
            kind = _kind(p["method"])
            marker, color = STYLE.get(kind, ("x", "k"))
            err = p["error"]
            if not np.isfinite(err):
                continue
            x, y = p["us_per_position"], max(err, floor)
            ax.loglog(x, y, marker, color=color, ms=6)
            n = seen.get(kind, 0)
            seen[kind] = n + 1
            dy = {"mpmath, digits": -9 * n, "float64 solver": 3 + 9 * n,
                  "finite-difference rates, h": 2 if n % 2 == 0 else -9}.get(kind, 2)
            label = _label(p["method"])
            if kind == "Newton tolerance":
                # the tolerances land on one point (polishing goes on to rounding): one label
                if n:
                    continue
                tols = [q["method"].split()[-1] for q in pts if _kind(q["method"]) == kind]
                label, dy = f"tol {tols[0]} … {tols[-1]}", -14
            ax.annotate(label, (x, y), fontsize=7, xytext=(5, dy),
                        textcoords="offset points", color=color)
        # the Pareto front: no point both faster and more accurate
        good = sorted((p["us_per_position"], max(p["error"], floor)) for p in pts
                      if np.isfinite(p["error"]))
        front, best = [], math.inf
        for t, e in good:
            if e < best:
                front.append((t, e))
                best = e
        if front:
            xs, ys = zip(*front)
            ax.step(xs, ys, where="post", color="0.65", lw=1, zorder=0)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("time per position (µs)")
        ax.set_ylabel("largest relative error")
        ax.set_ylim(floor / 3, 1e3)
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="major", alpha=0.3)
        ax.axhline(2.2e-16, color="0.75", lw=0.8, ls="--")
    ax = axes.flat[4]
    for p in results["extremes"]["points"]:
        sampled = p["method"].startswith("largest")
        x, y = p["seconds"] * 1e3, max(p["error"], floor)
        ax.loglog(x, y, "o" if sampled else "*", color="C0" if sampled else "C3",
                  ms=6 if sampled else 11)
        ax.annotate(p["method"].replace("largest of ", "largest of ").replace(" samples", ""),
                    (x, y), fontsize=7, xytext=(6, 2), textcoords="offset points")
    ax.set_title("the rocker's largest rotation: largest sample vs --extremes", fontsize=9)
    ax.set_xlabel("time for the sweep (ms)")
    ax.set_ylabel("error (rad)")
    ax.set_ylim(floor / 3, 1e-1)
    ax.grid(True, which="major", alpha=0.3)
    ax = axes.flat[5]
    ax.axis("off")
    handles = [Line2D([], [], ls="", marker=m, color=c, label=k) for k, (m, c) in STYLE.items()]
    handles += [Line2D([], [], ls="", marker="o", color="C0", label="largest of N samples"),
                Line2D([], [], ls="", marker="*", color="C3", ms=11, label="--extremes")]
    ax.legend(handles=handles, loc="upper left", fontsize=8, frameon=False)
    ax.text(0, 0.42, "Error: every value of every ok step against a 50-digit\n"
            "reference (the format's equations solved in mpmath),\n"
            "relative to the mechanism's size (positions), the step's\n"
            "largest speed or acceleration (rates), or its largest\n"
            "reaction (forces); the largest over steps and fields.\n"
            "Dashed: float64's eps; grey steps: the Pareto front;\n"
            "errors below 1e-17 drawn at 1e-17. A sampled maximum's\n"
            "error: its worst over 16 phases of the samples.",
            va="top", fontsize=8, transform=ax.transAxes)
    fig.suptitle("What accuracy costs: largest error against time per position (log-log)")
    fig.savefig(path, dpi=110)


def main():
    out = HERE / "results"
    if sys.argv[1:] == ["--plot"]:  # redraw the figure from the last run's figures
        plot(json.loads((out / "accuracy.json").read_text()), out / "accuracy.png")
        return
    results = {
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "mpmath": mp.__version__,
        "mpmath_backend": mp.libmp.BACKEND,
        "machine": platform.machine(),
        "processor": platform.processor() or "unknown",
        "allocator_state": "steady",
        "cases": {},
    }
    steady_heap()
    crank = linkage_sym.load_example("crank_rocker")
    cases = results["cases"]
    cases["fourbar"] = case("fourbar", kinematics_only(crank))
    cases["toggle"] = case("toggle", toggle_scene())
    cases["class3"] = case("class3", kinematics_only(linkage_sym.load_example("sixbar_class3")),
                           newton=True)
    cases["forces"] = case("forces", crank, forces=True)
    results["extremes"] = extremes_study()
    out.mkdir(exist_ok=True)
    (out / "accuracy.json").write_text(json.dumps(results, indent=2) + "\n")
    plot(results, out / "accuracy.png")
    print(f"wrote {out / 'accuracy.json'} and {out / 'accuracy.png'}")


if __name__ == "__main__":
    main()
