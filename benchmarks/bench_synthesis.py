"""Benchmark: path synthesis on a few target curves, linkage_sym against pylinkage, one run.

Run on demand (not part of the tests)::

    python benchmarks/bench_synthesis.py      # writes benchmarks/results/synthesis.json

Targets: points taken from two known four-bars (4 and 6 points), five points
on an ellipse's arc, and a drawn bean-shaped curve resampled to 8 points.
For every design of either tool the same measure is taken by linkage_sym's
solver on a scene of that design (``compile_plan``): the largest distance from
a target to the coupler curve over a full crank turn (3600 steps, each target's nearest step refined by
``scipy.optimize.minimize_scalar`` between its neighbours), relative to
the targets' size -- the timing is free in both.  linkage_sym's own error (at
its crank angles, in order, on one branch) is reported beside it.  pylinkage's
``synthesis.path_generation`` (Burmester search over coupler orientations) is
called with its defaults (``require_grashof=True``, ``max_solutions=10``) and
without the Grashof requirement; the time is each call's wall time.
"""

from __future__ import annotations

import json
import math
import platform
import time
import warnings
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

import linkage_sym
from linkage_sym.synthesis.builders import fourbar
from linkage_sym.synthesis.path_gen import resample, synthesize_path

OUT = Path(__file__).parent / "results" / "synthesis.json"
STEPS = 3600


def _known(a, b, c, d, uv, degs):
    s = fourbar(a, b, c, d, coupler_point=uv).scene
    plan = linkage_sym.compile_plan(linkage_sym.load_scene(s))
    q = np.radians(degs)
    res = plan.run(q={"A": q}, qd={"A": np.ones(len(q))}, qdd={"A": np.zeros(len(q))})
    return res.points["P"].position.tolist()


def targets():
    t = np.radians([200, 225, 250, 275, 300])
    bean = [[math.cos(s) * (1 + 0.3 * math.cos(2 * s)), 0.6 * math.sin(s) - 0.2 * math.sin(2 * s)]
            for s in np.linspace(0.0, 1.6 * math.pi, 60)]
    return {
        "fourbar-4": _known(0.5, 1.4, 1.2, 1.5, (0.6, 0.5), [10, 80, 170, 260]),
        "fourbar-6": _known(0.4, 1.3, 1.1, 1.4, (0.9, -0.4), np.linspace(0, 300, 6)),
        "ellipse-5": np.column_stack([1.5 * np.cos(t), np.sin(t)]).tolist(),
        "bean-8": resample(bean, 8).tolist(),
    }


def _size(T):
    T = np.asarray(T)
    return float(np.max(np.hypot(*(T[:, None] - T[None]).transpose(2, 0, 1))))


def curve_error(A, B, C, D, P, T):
    """Largest target distance from the coupler curve of the four-bar at A B C D with point P
    (a full turn, the solver; inf when the scene cannot be solved)."""
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    theta = math.degrees(math.atan2(B[1] - A[1], B[0] - A[0]))
    scene = {"name": "peer", "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
             "joints": [{"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
                        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
                        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": xy(C)},
                        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": xy(D)}],
             "points": [{"name": "P", "link": "coupler", "at": xy(P)}],
             "drivers": [{"joint": "A", "toward": "B", "start_deg": theta, "stop_deg": theta + 360,
                          "steps": 3, "speed": 1.0, "acceleration": 0.0}],
             "outputs": ["kinematics"]}
    try:
        plan = linkage_sym.compile_plan(linkage_sym.load_scene(scene))
    except linkage_sym.SceneError:
        return math.inf
    q = math.radians(theta) + np.linspace(0, 2 * math.pi, STEPS)
    res = plan.run(q={"A": q}, qd={"A": np.ones(STEPS)}, qdd={"A": np.zeros(STEPS)})
    ok = res.status == "ok"
    curve = np.where(ok[:, None], np.asarray(res.points["P"].position), np.nan)
    if not ok.any():
        return math.inf
    T = np.asarray(T)
    dist = np.hypot(*(curve[None] - T[:, None]).transpose(2, 0, 1))
    worst = 0.0
    for i, k in enumerate(np.nanargmin(dist, axis=1)):  # refined between the neighbouring samples
        lo, hi = q[max(k - 1, 0)], q[min(k + 1, STEPS - 1)]

        def f(t, i=i):
            r = plan.run(q={"A": np.array([t])}, qd={"A": np.ones(1)}, qdd={"A": np.zeros(1)})
            if r.status[0] != "ok":
                return math.inf
            return float(np.hypot(*(np.asarray(r.points["P"].position)[0] - T[i])))

        best = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        worst = max(worst, min(float(best.fun), float(dist[i, k])))
    return worst


def ours(T):
    t0 = time.perf_counter()
    ds = synthesize_path(T, min_transmission_deg=20.0)
    dt = time.perf_counter() - t0
    errs = []
    for d in ds:
        J = {j["name"]: j["at"] for j in d.scene["joints"]}
        errs.append(curve_error(J["A"], J["B"], J["C"], J["D"], d.scene["points"][0]["at"], T))
    return {"time_s": dt, "designs": len(ds), "own_error_rel": [d.check.error / _size(T) for d in ds],
            "curve_error_rel": [e / _size(T) for e in errs]}


def peer(T, require_grashof):
    from pylinkage.synthesis import path_generation

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = path_generation([tuple(p) for p in T], require_grashof=require_grashof)
    dt = time.perf_counter() - t0
    errs = [curve_error(s.ground_pivot_a, s.crank_pivot_b, s.coupler_pivot_c, s.ground_pivot_d,
                        s.coupler_point, T) / _size(T)
            for s in res.raw_solutions if s.coupler_point is not None]
    return {"time_s": dt, "designs": len(res.solutions), "raw": len(res.raw_solutions),
            "curve_error_rel": errs}


def main():
    try:
        import pylinkage
        version = pylinkage.__version__
    except ImportError:
        version = None
    out = {"machine": platform.processor() or platform.machine(), "python": platform.python_version(),
           "pylinkage": version, "cases": {}}
    for name, T in targets().items():
        row = {"points": len(T), "linkage_sym": ours(T)}
        if version is not None:
            row["pylinkage_grashof"] = peer(T, True)
            row["pylinkage_any"] = peer(T, False)
        out["cases"][name] = row
        best = lambda r: min(r["curve_error_rel"], default=math.inf)  # noqa: E731
        print(name, {k: (round(v["time_s"], 2), f"{best(v):.2e}", v["designs"])
                     for k, v in row.items() if isinstance(v, dict)})
    OUT.write_text(json.dumps(out, indent=2, default=float) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
