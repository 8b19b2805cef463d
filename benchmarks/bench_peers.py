"""Benchmark: linkage_sym against its peers, µs per position, all in one run.

Run on demand (not part of the tests); needs the ``bench`` extra (pylinkage
with numba)::

    pip install -e '.[bench]'
    python benchmarks/bench_peers.py         # writes benchmarks/results/peers.json

The shipped crank-rocker (four-bar) and offset slider-crank, 3600 steps of
the crank over one turn, one BLAS thread.  Conventions as in
``bench_kinematics.py`` (whose module docstring explains the allocator
states): every contender is checked against ``Plan.run`` before anything is
timed; every ratio is between figures of the same run.

Contenders
----------
* ``plan``: ``compile_plan(scene).run()``, kinematics: every link's rotation,
  angular velocity and acceleration and origin motion, every joint's, centre
  of mass's and traced point's position, velocity and acceleration, each
  step's status, the validity and singularity screen, the accuracy estimate.
* ``plan_forces``: the same with the examples' own outputs (reactions,
  driving effort, frame loads) by the dyad routines.
* ``symbolic`` / ``symbolic_forces``: the compiled mechanism of
  ``linkage_sym.codegen`` (lambdified functions loaded from the cache, which
  this benchmark fills in a temporary folder) and its ``run()``: the same
  result as ``plan`` / ``plan_forces``.
* ``pylinkage_numba``: pylinkage's numba-compiled solver,
  ``Linkage.step_fast_with_kinematics``: every joint's position, velocity
  and acceleration (no links, centres of mass or checks; an unbuildable step
  gives NaN).  ``pylinkage_numba_positions``: ``Linkage.step_fast``,
  positions only.
* ``pylinkage_python``: pylinkage as installed without its numba extra (its
  solver functions are then plain Python): ``Linkage.step_with_derivatives``
  (positions, velocities, accelerations), and ``pylinkage_python_positions``:
  ``Linkage.step`` (positions only).  So that it runs in the same process as
  the others, a second copy of the package is imported under another name
  while ``numba`` is hidden (see :func:`pylinkage_without_numba`).
* ``handwritten``: a vectorised NumPy closed form written for the one
  mechanism: the links' angles and rates, centres of mass and moving joints,
  no checks (the four-bar's is ``bench_kinematics.handwritten_fourbar``).
* ``sympy_lambdify``: the same quantities derived with SymPy by hand
  (positions as closed forms in the crank angle, velocities and
  accelerations by differentiation), ``lambdify(cse=True)`` once; only the
  evaluation is timed.

Each pylinkage call first puts its linkage back in the start position (a
run moves it); the cranks advance by a constant angle per step, set so
their positions are linkage_sym's sweep.

Measured
--------
* ``steady``: in this process after it has freed a large block
  (``steady_heap``), each contender head to head with ``plan``: the two
  calls alternating, best of ``STEADY_ROUNDS`` each (see
  :func:`head_to_head` for why in pairs); ``plan``'s own figure is its
  calls back to back.
* ``fresh``: each contender alone in a new interpreter (``FRESH_RUNS`` each,
  alternating; medians and ranges): importing its library and building it
  (``setup_s``), its first call, the best of the following calls.
  pylinkage's first call loads its compiled kernels from numba's on-disk
  cache (filled by a discarded run first); ``numba_empty_cache`` is the same
  first call with an empty cache (``NUMBA_CACHE_DIR``), i.e. numba compiling.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import dataclasses  # noqa: E402
import importlib  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from bench_kinematics import best_time, handwritten_fourbar, rigid_motion, steady_heap  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
STEPS = 3600
ALL = ("kinematics", "reactions", "driving", "frame")
MECHANISMS = {"fourbar": "crank_rocker", "slider_crank": "slider_crank_offset"}
CONTENDERS = (
    "plan", "plan_forces", "symbolic", "symbolic_forces",
    "pylinkage_numba", "pylinkage_numba_positions",
    "pylinkage_python", "pylinkage_python_positions",
    "handwritten", "sympy_lambdify",
)
WHAT = {
    "plan": "linkage_sym Plan.run, kinematics: links, joints, centres of mass, traced points "
            "(position, velocity, acceleration), status, screens, accuracy estimate",
    "plan_forces": "the same + reactions, driving effort, frame loads",
    "symbolic": "linkage_sym compiled (lambdified) mechanism's run(): the same result as plan",
    "symbolic_forces": "the same result as plan_forces",
    "pylinkage_numba": "pylinkage Linkage.step_fast_with_kinematics (numba): every joint's "
                       "position, velocity, acceleration",
    "pylinkage_numba_positions": "pylinkage Linkage.step_fast (numba): every joint's position",
    "pylinkage_python": "pylinkage without numba, Linkage.step_with_derivatives: every joint's "
                        "position, velocity, acceleration",
    "pylinkage_python_positions": "pylinkage without numba, Linkage.step: every joint's position",
    "handwritten": "NumPy closed form for this mechanism: links' angles and rates, centres of "
                   "mass and moving joints (position, velocity, acceleration), no checks",
    "sympy_lambdify": "the same quantities derived with SymPy, lambdify(cse=True), evaluation only",
}
FRESH_RUNS = 7
STEADY_ROUNDS = 40
NUMBA_EMPTY_RUNS = 2
TOLERANCE = 1e-9
EXTRA = "the 'bench' extra (pylinkage with numba): pip install -e '.[bench]'"


def require_peers():
    """Stop with a message naming the extra when pylinkage or numba is missing."""
    missing = [m for m in ("pylinkage", "numba") if importlib.util.find_spec(m) is None]
    if missing:
        sys.exit(f"bench_peers.py needs {' and '.join(missing)}: install {EXTRA}")


# ---------------------------------------------------------------- scenes


def scene_of(mech: str, outputs=("kinematics",)):
    s = linkage_sym.load_example(MECHANISMS[mech])
    drivers = tuple(dataclasses.replace(d, steps=STEPS) for d in s.drivers)
    return dataclasses.replace(s, drivers=drivers, outputs=outputs)


def joints_at(scene) -> dict:
    return {j.name: np.array(j.at, dtype=float) for j in scene.joints}


def size_of(scene) -> float:
    """The mechanism's size: the largest distance between two of its joints as assembled."""
    p = np.array([j.at for j in scene.joints], dtype=float)
    return float(np.max(np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1))))


# ---------------------------------------------------------------- hand-written slider-crank


def handwritten_slider_crank(scene):
    """A vectorised closed form of the offset slider-crank, written for this mechanism only.

    The slider's joint C lies on the guide (point G, unit direction u) at
    distance l2 from the crank pin B: with B - G = p u + q n (n = u turned by
    -90°), C = G + s u, s = p + sqrt(l2² - q²).  Rates from the derivatives
    in the crank angle: the connecting rod's angle φ has φ' = (r × r')/l2²
    and φ'' = (r × r'')/l2² (r = C - B, of constant length).
    """
    J = joints_at(scene)
    A, B, C = J["A"], J["B"], J["C"]
    guide = scene.joint("C_guide")
    G = np.array(guide.at, dtype=float)
    ux, uy = math.cos(guide.axis), math.sin(guide.axis)
    l1, l2 = float(np.hypot(*(B - A))), float(np.hypot(*(C - B)))
    t10, t20 = math.atan2(*(B - A)[::-1]), math.atan2(*(C - B)[::-1])
    coms = {lk.name: np.array(lk.com, dtype=float) for lk in scene.links}
    local = {"crank": coms["crank"] - A, "connecting_rod": coms["connecting_rod"] - B,
             "slider": coms["slider"] - C}
    d = scene.drivers[0]

    def run():
        th1 = np.linspace(d.start, d.stop, d.steps)
        w1, a1 = d.speed, d.acceleration
        c1, s1 = np.cos(th1), np.sin(th1)
        bx, by = A[0] + l1 * c1, A[1] + l1 * s1
        ex, ey = bx - G[0], by - G[1]
        p, q = ex * ux + ey * uy, ex * uy - ey * ux
        w = np.sqrt(l2 * l2 - q * q)
        s = p + w
        cx, cy = G[0] + s * ux, G[1] + s * uy
        # derivatives in the crank angle
        dbx, dby = -l1 * s1, l1 * c1
        dp, dq = dbx * ux + dby * uy, dbx * uy - dby * ux
        ddp, ddq = -(bx - A[0]) * ux - (by - A[1]) * uy, -(bx - A[0]) * uy + (by - A[1]) * ux
        ds = dp - q * dq / w
        dds = ddp - (dq * dq + q * ddq) / w - (q * dq) ** 2 / w**3
        rx, ry = cx - bx, cy - by
        drx, dry = ds * ux - dbx, ds * uy - dby
        ddrx, ddry = dds * ux + (bx - A[0]), dds * uy + (by - A[1])
        th2 = np.arctan2(ry, rx)
        dphi = (rx * dry - ry * drx) / (l2 * l2)
        ddphi = (rx * ddry - ry * ddrx) / (l2 * l2)
        w2, al2 = dphi * w1, ddphi * w1 * w1 + dphi * a1
        vs, as_ = ds * w1, dds * w1 * w1 + ds * a1
        vb = (dbx * w1, dby * w1)
        ab = (-(bx - A[0]) * w1 * w1 + dbx * a1, -(by - A[1]) * w1 * w1 + dby * a1)
        vc, ac = (vs * ux, vs * uy), (as_ * ux, as_ * uy)
        zero = (0.0, 0.0)
        out = {
            "crank": rigid_motion(th1 - t10, w1, a1, (A[0], A[1]), zero, zero, local["crank"]),
            "connecting_rod": rigid_motion(th2 - t20, w2, al2, (bx, by), vb, ab,
                                           local["connecting_rod"]),
        }
        x, y = local["slider"]
        out["slider"] = (0.0, 0.0, 0.0, cx + x, cy + y, vc[0], vc[1], ac[0], ac[1])
        out["joints"] = (bx, by, cx, cy, vb, vc, ab, ac)
        return out

    return run


# ---------------------------------------------------------------- SymPy by hand


def sympy_closed_form(scene, mech: str):
    """Derive the mechanism's closed form with SymPy, lambdify once (cse=True).

    Positions as closed forms in the crank angle θ (circle-circle or
    circle-line intersection, the assembled branch); velocity = f'(θ) ω,
    acceleration = f''(θ) ω² + f'(θ) α.  Returns the evaluation, in the
    layout of the hand-written closed forms (links, then ``joints``).
    """
    import sympy as sp

    th, w, al = sp.symbols("theta omega alpha", real=True)
    J = {k: sp.Matrix([sp.Float(v[0]), sp.Float(v[1])]) for k, v in joints_at(scene).items()}
    A, B0, C0 = J["A"], J["B"], J["C"]
    l1, l2 = sp.sqrt((B0 - A).dot(B0 - A)), sp.sqrt((C0 - B0).dot(C0 - B0))
    B = A + l1 * sp.Matrix([sp.cos(th), sp.sin(th)])
    if mech == "fourbar":
        D = J["D"]
        l3 = sp.sqrt((C0 - D).dot(C0 - D))
        e = D - B
        dd = sp.sqrt(e.dot(e))
        a = (dd**2 + l2**2 - l3**2) / (2 * dd)
        h = sp.sqrt(l2**2 - a**2)
        C = B + (a * e + h * sp.Matrix([-e[1], e[0]])) / dd
        links = (("crank", th, A, A), ("coupler", sp.atan2(C[1] - B[1], C[0] - B[0]), B, B0),
                 ("rocker", sp.atan2(C[1] - D[1], C[0] - D[0]), D, D))
        t0 = {"crank": B0 - A, "coupler": C0 - B0, "rocker": C0 - D}
    else:
        guide = scene.joint("C_guide")
        G = J["C_guide"]
        u = sp.Matrix([sp.cos(sp.Float(guide.axis)), sp.sin(sp.Float(guide.axis))])
        e = B - G
        p, q = e.dot(u), e[0] * u[1] - e[1] * u[0]
        C = G + (p + sp.sqrt(l2**2 - q**2)) * u
        links = (("crank", th, A, A), ("connecting_rod", sp.atan2(C[1] - B[1], C[0] - B[0]), B, B0),
                 ("slider", sp.Integer(0), C, C0))
        t0 = {"crank": B0 - A, "connecting_rod": C0 - B0, "slider": None}

    def rates(f):
        f1 = sp.diff(f, th)
        return f1 * w, sp.diff(f1, th) * w**2 + f1 * al

    outputs = []
    coms = {lk.name: sp.Matrix([sp.Float(lk.com[0]), sp.Float(lk.com[1])]) for lk in scene.links}
    for name, angle, origin, origin0 in links:
        ref = t0[name]
        r = angle - (sp.atan2(ref[1], ref[0]) if ref is not None else 0)
        local = coms[name] - origin0
        com = origin + sp.Matrix([[sp.cos(r), -sp.sin(r)], [sp.sin(r), sp.cos(r)]]) * local
        (vx, ax), (vy, ay), (wr, ar) = rates(com[0]), rates(com[1]), rates(r)
        outputs.append([r, wr, ar, com[0], com[1], vx, vy, ax, ay])
    (vbx, abx), (vby, aby) = rates(B[0]), rates(B[1])
    (vcx, acx), (vcy, acy) = rates(C[0]), rates(C[1])
    outputs.append([B[0], B[1], C[0], C[1], vbx, vby, vcx, vcy, abx, aby, acx, acy])
    # one flat list: lambdify's cse (SymPy 1.14) leaves nested lists alone
    f = sp.lambdify((th, w, al), sum(outputs, []), modules="numpy", cse=True)
    names = [n for n, *_ in links]
    d = scene.drivers[0]

    def run():
        got = f(np.linspace(d.start, d.stop, d.steps), d.speed, d.acceleration)
        out = {n: tuple(got[9 * k:9 * k + 9]) for k, n in enumerate(names)}
        bx, by, cx, cy, vbx, vby, vcx, vcy, abx, aby, acx, acy = got[9 * len(names):]
        out["joints"] = (bx, by, cx, cy, (vbx, vby), (vcx, vcy), (abx, aby), (acx, acy))
        return out

    return run


# ---------------------------------------------------------------- pylinkage


_NOJIT = "_pylinkage_without_numba"


def pylinkage_without_numba():
    """pylinkage as it runs without its numba extra, beside the numba one in this process.

    The package's ``_numba_compat`` falls back to a no-op ``njit`` when
    ``import numba`` fails.  A second copy of the package is imported under
    another name with ``numba`` hidden, and its solver modules with it, so
    its solver functions are plain Python; the copy's relative imports (also
    those made lazily inside its methods) stay inside the copy.
    """
    if _NOJIT in sys.modules:
        return sys.modules[_NOJIT]
    import pylinkage

    pkg = Path(pylinkage.__file__).parent
    saved = sys.modules.get("numba")
    sys.modules["numba"] = None  # `import numba` raises ImportError meanwhile
    try:
        spec = importlib.util.spec_from_file_location(
            _NOJIT, pkg / "__init__.py", submodule_search_locations=[str(pkg)])
        mod = importlib.util.module_from_spec(spec)
        sys.modules[_NOJIT] = mod
        spec.loader.exec_module(mod)
        for sub in ("_numba_compat", "solver.joints", "solver.velocity", "solver.acceleration",
                    "solver.simulation", "geometry.core", "geometry.secants"):
            importlib.import_module(f"{_NOJIT}.{sub}")
    finally:
        if saved is None:
            del sys.modules["numba"]
        else:
            sys.modules["numba"] = saved
    compat = sys.modules[f"{_NOJIT}._numba_compat"]
    solve = sys.modules[f"{_NOJIT}.solver.joints"].solve_revolute
    assert not compat.HAS_NUMBA and type(solve).__name__ == "function", "numba leaked into the copy"
    return mod


def pylinkage_model(scene, mech: str, lib):
    """The mechanism as a pylinkage ``Linkage`` (``lib``: the package, with or without numba).

    Returns the linkage, a function that puts it back in its start position,
    and the indices of joints B and C among its components.
    """
    J = joints_at(scene)
    d = scene.drivers[0]
    dq = (d.stop - d.start) / (d.steps - 1)
    A = lib.Ground(*J["A"], name="A")
    crank = lib.Crank(anchor=A, radius=float(np.hypot(*(J["B"] - J["A"]))),
                      angular_velocity=dq, initial_angle=d.start - dq, name="B")
    l2 = float(np.hypot(*(J["C"] - J["B"])))
    if mech == "fourbar":
        D = lib.Ground(*J["D"], name="D")
        C = lib.RRRDyad(crank.output, D, l2, float(np.hypot(*(J["C"] - J["D"]))),
                        x=J["C"][0], y=J["C"][1], name="C")
        parts = [A, D, crank, C]
    else:
        guide = scene.joint("C_guide")
        G = J["C_guide"]
        G1 = lib.Ground(*G, name="G1")
        G2 = lib.Ground(G[0] + math.cos(guide.axis), G[1] + math.sin(guide.axis), name="G2")
        C = lib.RRPDyad(crank.output, G1, G2, l2, x=J["C"][0], y=J["C"][1], name="C")
        parts = [A, G1, G2, crank, C]
    lk = lib.Linkage(parts, name=mech)
    lk.set_input_velocity(crank, omega=d.speed, alpha=d.acceleration)
    start = [c.position for c in lk.components]

    def reset():
        for c, pos in zip(lk.components, start):
            c.set_coord(*pos)

    return lk, reset, (parts.index(crank), parts.index(C))


# ---------------------------------------------------------------- contenders


def build(mech: str, name: str):
    """The contender's call (what is timed) and a function of its output giving
    ``{joint: (position, velocity or None, acceleration or None)}`` for B and C."""
    if name in ("plan", "plan_forces"):
        from linkage_sym.numeric.plan import compile_plan

        fn = compile_plan(scene_of(mech, ALL if name == "plan_forces" else ("kinematics",))).run
        return fn, lambda r: {j: (r.joints[j].position, r.joints[j].velocity,
                                  r.joints[j].acceleration) for j in "BC"}
    if name in ("symbolic", "symbolic_forces"):
        from linkage_sym.codegen.runtime import load_compiled

        cm = load_compiled(scene_of(mech, ALL if name == "symbolic_forces" else ("kinematics",)))
        assert cm is not None, "the compiled mechanism is not in the cache"
        return cm.run, lambda r: {j: (r.joints[j].position, r.joints[j].velocity,
                                      r.joints[j].acceleration) for j in "BC"}
    if name.startswith("pylinkage"):
        import pylinkage

        lib = pylinkage_without_numba() if name.startswith("pylinkage_python") else pylinkage
        lk, reset, (ib, ic) = pylinkage_model(scene_of(mech), mech, lib)
        full = not name.endswith("_positions")
        if name.startswith("pylinkage_numba"):
            step = lk.step_fast_with_kinematics if full else lk.step_fast

            def fn():
                reset()
                return step(iterations=STEPS)

            if full:
                return fn, lambda r: {j: (r[0][:, i], r[1][:, i], r[2][:, i])
                                      for j, i in (("B", ib), ("C", ic))}
            return fn, lambda r: {j: (r[:, i], None, None) for j, i in (("B", ib), ("C", ic))}
        step = lk.step_with_derivatives if full else lk.step

        def fn():
            reset()
            return list(step(iterations=STEPS))

        if full:
            return fn, lambda r: {j: tuple(np.array([s[k][i] for s in r], dtype=float)
                                           for k in range(3)) for j, i in (("B", ib), ("C", ic))}
        return fn, lambda r: {j: (np.array([s[i] for s in r], dtype=float), None, None)
                              for j, i in (("B", ib), ("C", ic))}
    if name in ("handwritten", "sympy_lambdify"):
        scene = scene_of(mech)
        if name == "sympy_lambdify":
            fn = sympy_closed_form(scene, mech)
        else:
            fn = (handwritten_fourbar if mech == "fourbar" else handwritten_slider_crank)(scene)

        def joints(r):
            bx, by, cx, cy, vb, vc, ab, ac = r["joints"]
            st = lambda x, y: np.column_stack(np.broadcast_arrays(x, y))  # noqa: E731
            return {"B": (st(bx, by), st(*vb), st(*ab)), "C": (st(cx, cy), st(*vc), st(*ac))}

        return fn, joints
    raise KeyError(name)


def check(mech: str, calls: dict) -> dict:
    """Every contender's joints B and C against Plan.run's; raises if one disagrees.

    Positions to TOLERANCE of the mechanism's size, velocities and
    accelerations to TOLERANCE of their largest magnitude; for the closed
    forms also the links' angular velocities and accelerations and the
    centres of mass's positions, velocities and accelerations.
    """
    scene = scene_of(mech)
    ref = calls["plan"][0]()
    size = size_of(scene)
    out = {}
    for name, (fn, joints) in calls.items():
        got = joints(fn())
        errs = {"position": 0.0, "velocity": None, "acceleration": None}
        for j in "BC":
            p, v, a = got[j]
            r = ref.joints[j]
            errs["position"] = max(errs["position"],
                                   float(np.max(np.abs(p - r.position))) / size)
            for key, mine, theirs in (("velocity", v, r.velocity), ("acceleration", a, r.acceleration)):
                if mine is not None:
                    e = float(np.max(np.abs(mine - theirs))) / float(np.max(np.abs(theirs)))
                    errs[key] = max(errs[key] or 0.0, e)
        if name in ("handwritten", "sympy_lambdify"):
            r = fn()
            for lk in scene.links:
                L = ref.links[lk.name]
                _, w, al, cx, cy, vx, vy, ax, ay = (np.broadcast_to(x, (STEPS,)) for x in r[lk.name])
                pairs = (("link_omega", w, L.omega), ("link_alpha", al, L.alpha),
                         ("com_position", np.column_stack([cx, cy]), L.com),
                         ("com_velocity", np.column_stack([vx, vy]), L.com_velocity),
                         ("com_acceleration", np.column_stack([ax, ay]), L.com_acceleration))
                for key, mine, theirs in pairs:
                    scale = size if key == "com_position" else max(float(np.max(np.abs(theirs))), 1e-300)
                    e = float(np.max(np.abs(mine - theirs))) / scale
                    errs[key] = max(errs.get(key, 0.0), e)
        bad = {k: e for k, e in errs.items() if e is not None and not e < TOLERANCE}
        if bad:
            raise AssertionError(f"{mech}: {name} disagrees with Plan.run: {bad}")
        out[name] = errs
    return out


# ---------------------------------------------------------------- measurements


def fresh(mech: str, name: str) -> dict:
    """One contender alone in this (fresh) interpreter."""
    t0 = time.perf_counter()
    fn, _ = build(mech, name)
    setup = time.perf_counter() - t0
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0 = time.perf_counter()
    fn()
    cold = time.perf_counter() - t0
    cold_faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    warm = best_time(fn, 3 if name.startswith("pylinkage_python") else 7)
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    fn()
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    us = 1e6 / STEPS
    # the first call's page faults: the fresh memory it writes (a fault costs ~2.4 us on
    # the shared virtual machines these figures come from, measured by faulting 12 MB)
    return {"setup_s": setup, "cold_us_per_position": cold * us,
            "us_per_position": warm * us, "minor_page_faults_per_call": faults,
            "cold_minor_page_faults": cold_faults}


def child(mech: str, name: str, **env_extra) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    env.update(env_extra)
    out = subprocess.run([sys.executable, __file__, "--fresh", mech, name],
                         capture_output=True, text=True, env=env)
    if out.returncode:
        raise RuntimeError(f"{mech} {name}:\n{out.stderr}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def summary(runs: list) -> dict:
    return {key: {"median": float(np.median([r[key] for r in runs])),
                  "min": float(np.min([r[key] for r in runs])),
                  "max": float(np.max([r[key] for r in runs]))} for key in runs[0]}


def head_to_head(calls: dict, anchor: str = "plan") -> dict:
    """Each contender against ``anchor``, the two calls alternating, best of STEADY_ROUNDS each.

    In pairs rather than all at once: a call finds the caches as the call
    before it left them, and Plan.run's megabytes of result are slower after
    a contender that went through other memory (the four-bar in one trial:
    0.24 µs a position back to back, 0.34 alternating with all the other
    contenders); pylinkage's numba kernels hardly notice.  Returns, per contender, its time and the anchor's in
    that pair, and the anchor's back to back.
    """
    fa = calls[anchor][0]
    back = best_time(fa, STEADY_ROUNDS)
    out = {anchor: {"seconds": back, "anchor_seconds": back}}
    for name, (fn, _) in calls.items():
        if name == anchor:
            continue
        t_a = t_x = np.inf
        for _ in range(STEADY_ROUNDS):
            t_a = min(t_a, best_time(fa, 1))
            t_x = min(t_x, best_time(fn, 1))
        out[name] = {"seconds": t_x, "anchor_seconds": t_a}
    return out


def git_state() -> str:
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "linkage_sym"], cwd=ROOT,
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+dirty" if dirty else "")


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def main():
    require_peers()
    import numba
    import pylinkage
    import sympy

    from linkage_sym.codegen.compile import compile_mechanism

    results = {
        "python": sys.version.split()[0], "numpy": np.__version__, "sympy": sympy.__version__,
        "pylinkage": getattr(pylinkage, "__version__", "unknown"), "numba": numba.__version__,
        "machine": platform.machine(), "processor": cpu_model(), "cpus": os.cpu_count(),
        "commit": git_state(), "steps": STEPS, "contenders": WHAT,
        "check": {},
        "steady": "each contender alternating with plan (head_to_head); plan's own figure: its calls "
                  "back to back",
        "steady_us_per_position": {}, "steady_plan_us_per_position_in_pair": {},
        "steady_ratio_to_plan": {},
        "fresh": {"interpreters_per_contender": FRESH_RUNS},
        "numba_empty_cache_first_call": {},
    }
    with tempfile.TemporaryDirectory(prefix="linkage_sym_peers_") as tmp:
        os.environ["LINKAGE_SYM_CACHE"] = tmp  # the compiled mechanisms, for this process and children
        for mech in MECHANISMS:
            for outputs in (("kinematics",), ALL):
                compile_mechanism(scene_of(mech, outputs))
        calls = {}
        for mech in MECHANISMS:
            print(f"building and checking {mech} ...", flush=True)
            calls[mech] = {name: build(mech, name) for name in CONTENDERS}
            results["check"][mech] = check(mech, calls[mech])

        # fresh interpreters: one discarded run of each numba contender fills numba's cache
        for mech in MECHANISMS:
            for name in ("pylinkage_numba", "pylinkage_numba_positions"):
                child(mech, name)
        samples = {mech: {name: [] for name in CONTENDERS} for mech in MECHANISMS}
        for k in range(FRESH_RUNS):
            print(f"fresh interpreters, round {k + 1} of {FRESH_RUNS} ...", flush=True)
            for mech in MECHANISMS:
                for name in CONTENDERS:
                    samples[mech][name].append(child(mech, name))
        for mech in MECHANISMS:
            results["fresh"][mech] = {name: summary(runs) for name, runs in samples[mech].items()}
            with tempfile.TemporaryDirectory(prefix="numba_cache_") as ncache:
                runs = [child(mech, "pylinkage_numba", NUMBA_CACHE_DIR=tempfile.mkdtemp(dir=ncache))
                        for _ in range(NUMBA_EMPTY_RUNS)]
                results["numba_empty_cache_first_call"][mech] = summary(runs)

        # steady heap, contenders alternating
        steady_heap()
        for mech in MECHANISMS:
            print(f"steady heap, {mech} ...", flush=True)
            pairs = head_to_head(calls[mech])
            us = 1e6 / STEPS
            results["steady_us_per_position"][mech] = {n: p["seconds"] * us for n, p in pairs.items()}
            results["steady_plan_us_per_position_in_pair"][mech] = {
                n: p["anchor_seconds"] * us for n, p in pairs.items()}
            results["steady_ratio_to_plan"][mech] = {
                n: p["seconds"] / p["anchor_seconds"] for n, p in pairs.items()}

    fr = results["fresh"]["fourbar"]
    ratio_steady = 1 / results["steady_ratio_to_plan"]["fourbar"]["pylinkage_numba"]
    ratio_fresh = fr["plan"]["us_per_position"]["median"] / fr["pylinkage_numba"]["us_per_position"]["median"]
    ratio_cold = (fr["plan"]["cold_us_per_position"]["median"]
                  / fr["pylinkage_numba"]["cold_us_per_position"]["median"])
    results["targets"] = {
        "fourbar_plan_over_pylinkage_numba_steady": {"ratio": ratio_steady, "met": ratio_steady <= 0.5},
        "fourbar_plan_over_pylinkage_numba_fresh_repeated": {"ratio": ratio_fresh, "met": ratio_fresh <= 0.5},
        "fourbar_plan_over_pylinkage_numba_fresh_first_call": {"ratio": ratio_cold, "met": ratio_cold <= 0.5},
    }
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "peers.json").write_text(json.dumps(results, indent=2) + "\n")
    report(results)


def report(results: dict):
    print(f"\nµs per position, {STEPS} steps ({results['processor']}, {results['cpus']} cpus)")
    head = (f"{'contender':28s} {'steady':>8s} {'(plan)':>7s} {'÷ plan':>7s} {'fresh':>8s} "
            f"{'first':>9s} {'setup s':>8s}")
    for mech in MECHANISMS:
        print(f"\n{mech}\n{head}")
        st, pa, ra, fr = (results[k][mech] for k in (
            "steady_us_per_position", "steady_plan_us_per_position_in_pair",
            "steady_ratio_to_plan", "fresh"))
        for name in CONTENDERS:
            f = fr[name]
            print(f"{name:28s} {st[name]:8.3f} {pa[name]:7.3f} {ra[name]:7.2f} "
                  f"{f['us_per_position']['median']:8.3f} {f['cold_us_per_position']['median']:9.2f} "
                  f"{f['setup_s']['median']:8.3f}")
        e = results["numba_empty_cache_first_call"][mech]
        print(f"pylinkage_numba first call, empty numba cache: "
              f"{e['cold_us_per_position']['median']:.0f} µs/pos")
    print("\ntargets")
    for k, t in results["targets"].items():
        print(f"  {k}: {t['ratio']:.2f} -> {'met' if t['met'] else 'MISSED'}")


if __name__ == "__main__":
    require_peers()
    if len(sys.argv) == 4 and sys.argv[1] == "--fresh":
        print(json.dumps(fresh(sys.argv[2], sys.argv[3])))
    else:
        main()
