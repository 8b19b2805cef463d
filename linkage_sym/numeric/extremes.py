"""Exact extremes over a sweep: roots of the rate between samples, not the largest sample.

:func:`find_extremes` reports, for every link rotation, joint coordinate, driving effort
and reaction magnitude, its maximum and minimum over the sweep with the driver values
where they occur, and each group's limit positions (rocker extremes: rotations of the
group's links pivoted on the ground; slider dead centres: slides of its ``P`` joints on
the ground), and the driver values where the mechanism stops being assemblable.

How
---
The sweep's steps are points ``t = 0, 1, ..., N-1`` of a parameter along which every
driver moves linearly (the format's sweeps are ``linspace``), ``q(t)``.

* **Kinematic quantities** (rotations, joint coordinates, slides): their rate along
  ``t`` is exact -- the plan's velocity solve with ``qd = dq/dt`` and ``qdd = 0``.
  Where it changes sign between two ``ok`` steps, Brent's method (:func:`brent`: inverse
  quadratic interpolation safeguarded by bisection, as ``scipy.optimize.brentq``) finds
  the root to :data:`XTOL` steps.
* **Forces** (efforts, reaction magnitudes; they depend on the scene's own ``qd, qdd``
  through inertia): their rate is a central difference with ``h =`` :data:`FD_STEP`
  steps, whose root Brent locates between the samples around a sampled extreme.  The
  value at an extreme is flat in the location (an error ``d`` in ``t`` changes it by
  ``f'' d^2 / 2``), so the difference's ``O(h^2)`` error does not show in it.

Every Brent iteration of every bracket is evaluated in one run of the plan at all the
brackets' current points at once (the path from the assembly configuration through
them, as the sweep is solved: the same branch).  The maximum (minimum) is the largest
(smallest) of the located stationary values and the samples (a sample wins at the
sweep's ends and at the edges of gaps).  A sampled extreme of ``N`` steps is off by
``f'' (Delta t)^2 / 8`` at most: ``O(1/N^2)`` (tested).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from linkage_sym.numeric.results.result import OK, UNASSEMBLABLE
from linkage_sym.numeric.results.wording import driver_number

XTOL = 1e-11
"""Brent's tolerance on the location, in steps (kinematic rates)."""
XTOL_FD = 1e-9
"""The same for forces, whose rate is a difference quotient."""
FD_STEP = 1e-4
"""Central-difference step of the force rates, in steps."""
BISECT_TOL = 1e-10
"""Assembly limits located to this many steps."""
MAX_ITER = 100
EPS = float(np.finfo(float).eps)
FULL_TURN_TOL = 1e-9
"""A rotation whose range over the sweep is at least ``2 pi (1 - FULL_TURN_TOL)`` turns fully:
its extremes are not limit positions."""
NOISE = 1e-12
"""Printed values below ``NOISE`` times their scale are rounding noise and print as 0: lengths
and slides against the mechanism's characteristic length (the largest distance between two
joints), angles against 1 rad, efforts and reactions against the largest magnitude of the same
quantity over the sweep (the results keep the values as computed)."""


def brent(a, b, fa, fb, xtol, rtol=4 * EPS, maxiter=MAX_ITER):
    """Brent's root finder on ``[a, b]`` (``fa * fb <= 0``) as a generator.

    Yields the next point to evaluate and receives ``f`` there (``send``); its
    ``StopIteration.value`` is the root.  The algorithm of ``scipy.optimize.brentq``
    (Brent 1973: inverse quadratic or secant steps, bisection when they are slow).
    """
    xpre, xcur, fpre, fcur = a, b, fa, fb
    xblk = fblk = spre = scur = 0.0
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and (fpre < 0) != (fcur < 0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre = scur = sbis
        else:
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        xcur = xcur + (scur if abs(scur) > delta else (delta if sbis > 0 else -delta))
        fcur = yield xcur
        if not math.isfinite(fcur):
            return None
    return xcur


# ------------------------------------------------------------------ quantities


@dataclass
class _Quantity:
    """One scalar of the result: its value, and (kinematic ones) its rate along ``t``."""

    group: str  # "links", "joints", "driving", "reactions", "slides"
    name: str
    field: str
    kinematic: bool
    value: object  # (res) -> (N,)
    rate: object = None  # (res) -> (N,) with qd = dq/dt


def _slide(scene, j):
    """Value and rate of ``P`` joint ``j``'s slide: ``u . (p_b - p_a)``, ``u`` its axis on
    ``links[0]`` (0 in the assembly configuration)."""
    a, b = j.links
    X = j.at

    def parts(res):
        if a == "ground":
            th = 0.0
            pa, va, w = np.asarray(X, float)[None, :], 0.0, 0.0
        else:
            lk = res.links[a]
            th, pa = lk.rotation, lk.point(X)
            va, w = (lk.point_velocity(X), lk.omega) if lk.omega is not None else (0.0, 0.0)
        pb = res.links[b].point(X) if b != "ground" else np.asarray(X, float)[None, :]
        n = max(len(pa), len(pb), np.size(th))
        ang = np.broadcast_to(th + j.axis, (n,))
        u = np.stack([np.cos(ang), np.sin(ang)], axis=-1)
        return pa, pb, va, w, u

    def value(res):
        pa, pb, _, _, u = parts(res)
        return np.sum(u * (pb - pa), axis=-1)

    def rate(res):
        pa, pb, va, w, u = parts(res)
        vb = res.links[b].point_velocity(X) if b != "ground" else 0.0
        perp = np.stack([-u[:, 1], u[:, 0]], axis=-1)
        return np.sum(u * (vb - va), axis=-1) + w * np.sum(perp * (pb - pa), axis=-1)

    return value, rate


def quantities(scene, with_forces: bool) -> list[_Quantity]:
    """Every quantity whose extremes are reported, in the order of the report."""
    out = []
    for link in scene.links:
        n = link.name
        out.append(_Quantity("links", n, "rotation", True,
                             lambda r, n=n: r.links[n].rotation, lambda r, n=n: r.links[n].omega))
    for j in scene.joints:
        for k, axis in enumerate(("x", "y")):
            out.append(_Quantity("joints", j.name, axis, True,
                                 lambda r, n=j.name, k=k: r.joints[n].position[:, k],
                                 lambda r, n=j.name, k=k: r.joints[n].velocity[:, k]))
    for j in scene.joints:
        if j.type == "P":
            v, rt = _slide(scene, j)
            out.append(_Quantity("slides", j.name, "slide", True, v, rt))
    if with_forces:
        for d in scene.drivers:
            out.append(_Quantity("driving", d.joint, "effort", False,
                                 lambda r, n=d.joint: r.forces.driving[n]))
        for j in scene.joints:
            out.append(_Quantity("reactions", j.name, "magnitude", False,
                                 lambda r, n=j.name: np.hypot(*r.forces.reactions[n].T)))
    return out


# ------------------------------------------------------------------ results


@dataclass
class Extreme:
    """One located maximum or minimum."""

    value: float
    t: float  # position along the sweep, in steps (fractional)
    drivers: dict  # driver values there
    located: str  # "rate root" (Brent between samples) or "sample" (an end, a gap's edge)
    sampled: float  # the largest (smallest) sample, for comparison

    def to_dict(self) -> dict:
        return {"value": self.value, "step": self.t, "drivers": self.drivers,
                "located": self.located, "sampled": self.sampled}


@dataclass
class Extremes:
    """What :func:`find_extremes` found (see the module docstring).

    ``values[(group, name, field)] = {"max": Extreme, "min": Extreme}``; ``limits``: per
    group, the extremes of its limit coordinates; ``assembly``: driver values where the
    sweep leaves or enters the assemblable range (bisected between two steps).
    """

    values: dict = field(default_factory=dict)
    limits: list = field(default_factory=list)
    assembly: list = field(default_factory=list)
    evaluations: int = 0
    n_steps: int = 0

    def to_dict(self) -> dict:
        out: dict = {}
        for (grp, name, fld), mm in self.values.items():
            out.setdefault(grp, {}).setdefault(name, {})[fld] = {k: e.to_dict() for k, e in mm.items()}
        out["limits"] = self.limits
        out["assembly_limits"] = self.assembly
        return out


# ------------------------------------------------------------------ the search


class FractionalSweep:
    """Evaluate a plan at fractional steps ``t`` of the scene's sweep."""

    def __init__(self, scene, plan, q, qd, qdd, disconnection):
        from linkage_sym.numeric.plan import compile_plan

        self.plan = plan
        kin_scene = dataclasses.replace(scene, outputs=("kinematics",))
        self.kin = compile_plan(kin_scene, disconnection)
        self.names = list(q)
        self.Q = {n: np.asarray(q[n], float) for n in self.names}
        self.QD = {n: np.asarray(qd[n], float) for n in self.names}
        self.QDD = {n: np.asarray(qdd[n], float) for n in self.names}
        self.N = len(self.Q[self.names[0]])
        self.runs = 0

    def q_at(self, t, arrays):
        t = np.asarray(t, float)
        i = np.clip(np.floor(t).astype(int), 0, max(self.N - 2, 0))
        f = t - i
        out = {}
        for n, v in arrays.items():
            if self.N == 1:
                out[n] = np.full(t.shape, v[0])
            else:
                out[n] = v[i] + f * (v[np.minimum(i + 1, self.N - 1)] - v[i])
        return out

    def dq_dt(self, t):
        t = np.asarray(t, float)
        out = {}
        for n, v in self.Q.items():
            slope = 0.0 if self.N == 1 else (v[-1] - v[0]) / (self.N - 1)
            out[n] = np.full(t.shape, slope)
        return out

    def kinematics(self, t):
        """Run the kinematics plan at sorted ``t`` with rates along ``t``."""
        self.runs += 1
        q = self.q_at(t, self.Q)
        return self.kin.run(q, self.dq_dt(t), {n: np.zeros(len(t)) for n in self.names})

    def forces(self, t):
        """Run the scene's plan at sorted ``t`` with the scene's rates."""
        self.runs += 1
        return self.plan.run(self.q_at(t, self.Q), self.q_at(t, self.QD), self.q_at(t, self.QDD))


def _batch(evaluate, points):
    """Evaluate at the unique sorted ``points``; returns ``(result, index of each point)``."""
    pts = np.asarray(points, float)
    uniq, inv = np.unique(pts, return_inverse=True)
    return evaluate(uniq), inv


def _drivers_at(sw, t) -> dict:
    q = sw.q_at(np.array([t]), sw.Q)
    return {n: float(v[0]) for n, v in q.items()}


def find_extremes(scene, plan, res, disconnection=None, q=None, qd=None, qdd=None) -> Extremes:
    """Extremes of every quantity of ``res`` (the plan's run of its sweep); see the module
    docstring.  ``q, qd, qdd``: that sweep's driver values (default: the scene's)."""
    if q is None:
        q, qd, qdd = plan.sweep()
    sw = FractionalSweep(scene, plan, q, qd, qdd, disconnection)
    ok = res.status == OK
    qs = quantities(scene, res.forces is not None)
    tasks = _brackets(sw, qs, res, ok)
    _force_brackets(sw, qs, tasks)
    tasks = [tk for tk in tasks if tk.get("a") is not None]
    roots = _rate_roots(sw, qs, tasks)
    root_vals = _root_values(sw, qs, roots)
    out = Extremes()
    for k, qu in enumerate(qs):
        v = np.asarray(qu.value(res), float)
        okv = ok & np.isfinite(v)
        if not okv.any():
            continue
        cands = [(float(i), float(v[i]), "sample") for i in np.flatnonzero(okv)]
        cands += [(t, val, "rate root") for t, val in root_vals.get(k, []) if math.isfinite(val)]
        mm = {}
        for kind, pick in (("max", max), ("min", min)):
            t, val, how = pick(cands, key=lambda c: c[1] if kind == "max" else c[1])
            samp = float(np.max(v[okv]) if kind == "max" else np.min(v[okv]))
            mm[kind] = Extreme(val, t, _drivers_at(sw, t), how, samp)
        out.values[(qu.group, qu.name, qu.field)] = mm
    out.limits = _group_limits(scene, plan, out)
    out.assembly = _assembly_limits(sw, res)
    out.evaluations = sw.runs
    out.n_steps = sw.N
    return out


def _brackets(sw, qs, res, ok) -> list:
    """The steps between which a quantity may have an extreme: a sign change of a kinematic
    quantity's rate between two samples, or a sample of a force that is a local extreme
    (its rate bracketed later, :func:`_force_brackets`)."""
    N = sw.N
    t_samples = np.arange(N, dtype=float)
    kin_samples = sw.kinematics(t_samples) if ok.any() else None
    # brackets: (quantity index, kind, generator state)
    tasks = []  # dicts: q, a, b, gen, pending
    for k, qu in enumerate(qs):
        if qu.kinematic:
            r = np.asarray(qu.rate(kin_samples), float) if kin_samples is not None else np.zeros(N)
            for i in range(N - 1):
                if not (ok[i] and ok[i + 1]):
                    continue
                ra, rb = r[i], r[i + 1]
                if ra == 0 or rb == 0 or (ra < 0) != (rb < 0):
                    tasks.append({"q": k, "a": float(i), "b": float(i + 1), "fa": ra, "fb": rb,
                                  "xtol": XTOL})
        else:
            v = np.asarray(qu.value(res), float)
            for i in range(1, N - 1):
                if not (ok[i - 1] and ok[i] and ok[i + 1]):
                    continue
                d0, d1 = v[i] - v[i - 1], v[i + 1] - v[i]
                if d0 == 0 or d1 == 0 or (d0 < 0) != (d1 < 0):
                    tasks.append({"q": k, "around": i, "xtol": XTOL_FD})
    return tasks


def _force_brackets(sw, qs, tasks) -> None:
    """Force brackets: the difference quotient at the three samples around the extreme; a
    task without a sign change of the rate gets ``a = None`` (the sample stands)."""
    fd = [tk for tk in tasks if "around" in tk]
    if fd:
        pts = []
        for tk in fd:
            i = tk["around"]
            pts += [i - 1 - FD_STEP, i - 1 + FD_STEP, i - FD_STEP, i + FD_STEP,
                    i + 1 - FD_STEP, i + 1 + FD_STEP]
        resf, inv = _batch(sw.forces, pts)
        for n_tk, tk in enumerate(fd):
            vals = np.asarray(qs[tk["q"]].value(resf), float)[inv[6 * n_tk: 6 * n_tk + 6]]
            g = (vals[1::2] - vals[0::2]) / (2 * FD_STEP)  # rates at i-1, i, i+1
            i = tk["around"]
            if (g[0] < 0) != (g[1] < 0) or g[1] == 0:
                tk.update(a=float(i - 1), b=float(i), fa=g[0], fb=g[1])
            elif (g[1] < 0) != (g[2] < 0) or g[2] == 0:
                tk.update(a=float(i), b=float(i + 1), fa=g[1], fb=g[2])
            else:
                tk["a"] = None  # no sign change of the rate: the sample stands


def _rate_roots(sw, qs, tasks) -> list:
    """``(quantity index, t)`` of every rate root, by Brent's method run on all brackets at
    once (one kinematics run and one force run per iteration)."""
    roots = []  # (quantity index, t)
    for tk in tasks:
        tk["gen"] = brent(tk["a"], tk["b"], tk["fa"], tk["fb"], tk["xtol"])
        try:
            tk["x"] = next(tk["gen"])
        except StopIteration as stop:
            if stop.value is not None:
                roots.append((tk["q"], float(stop.value)))
            tk["done"] = True
    active = [tk for tk in tasks if not tk.get("done")]
    while active:
        kin_tasks = [tk for tk in active if qs[tk["q"]].kinematic]
        fd_tasks = [tk for tk in active if not qs[tk["q"]].kinematic]
        values = {}
        if kin_tasks:
            resk, inv = _batch(sw.kinematics, [tk["x"] for tk in kin_tasks])
            for n_tk, tk in enumerate(kin_tasks):
                values[id(tk)] = float(np.asarray(qs[tk["q"]].rate(resk), float)[inv[n_tk]])
        if fd_tasks:
            pts = [x for tk in fd_tasks for x in (tk["x"] - FD_STEP, tk["x"] + FD_STEP)]
            resf, inv = _batch(sw.forces, pts)
            for n_tk, tk in enumerate(fd_tasks):
                v = np.asarray(qs[tk["q"]].value(resf), float)[inv[2 * n_tk: 2 * n_tk + 2]]
                values[id(tk)] = float((v[1] - v[0]) / (2 * FD_STEP))
        still = []
        for tk in active:
            try:
                tk["x"] = tk["gen"].send(values[id(tk)])
                still.append(tk)
            except StopIteration as stop:
                if stop.value is not None:
                    roots.append((tk["q"], float(stop.value)))
        active = still
    return roots


def _root_values(sw, qs, roots) -> dict:
    """The quantities' values at their rate roots (one kinematics run and one force run):
    ``{quantity index: [(t, value), ...]}``."""
    root_vals = {}
    kin_roots = [(k, t) for k, t in roots if qs[k].kinematic]
    f_roots = [(k, t) for k, t in roots if not qs[k].kinematic]
    if kin_roots:
        resk, inv = _batch(sw.kinematics, [t for _, t in kin_roots])
        for n_r, (k, t) in enumerate(kin_roots):
            root_vals.setdefault(k, []).append((t, float(np.asarray(qs[k].value(resk), float)[inv[n_r]])))
    if f_roots:
        resf, inv = _batch(sw.forces, [t for _, t in f_roots])
        for n_r, (k, t) in enumerate(f_roots):
            root_vals.setdefault(k, []).append((t, float(np.asarray(qs[k].value(resf), float)[inv[n_r]])))
    return root_vals



def _group_limits(scene, plan, ext: Extremes) -> list:
    """Per group: the extremes of its links pivoted on the ground (rocker extremes) and of
    its ``P`` joints on the ground (slider dead centres).  A rotation item says whether the
    link turns fully over the sweep (``turns_fully``: its range is a full turn or more, within
    :data:`FULL_TURN_TOL`), when its extremes are not limit positions."""
    out = []
    for g in plan.decomposition.groups:
        items = []
        for n in g.links:
            for j in scene.joints:
                if n in j.links and "ground" in j.links and j.type == "R" and j.name not in g.drivers:
                    mm = ext.values.get(("links", n, "rotation"))
                    if mm:
                        span = mm["max"].value - mm["min"].value
                        items.append({"coordinate": f"rotation of {n} about {j.name}",
                                      **{k: e.to_dict() for k, e in mm.items()},
                                      "turns_fully": bool(span >= 2 * math.pi * (1 - FULL_TURN_TOL))})
                    break
        for jn in g.joints:
            j = scene.joint(jn)
            if j.type == "P" and "ground" in j.links and jn not in g.drivers:
                mm = ext.values.get(("slides", jn, "slide"))
                if mm:
                    items.append({"coordinate": f"slide of {jn}",
                                  **{k: e.to_dict() for k, e in mm.items()}})
        if items:
            out.append({"group": g.label, "links": list(g.links), "limits": items})
    return out


def _assembly_limits(sw: FractionalSweep, res) -> list:
    """Driver values where the sweep leaves or enters the assemblable steps (bisection on
    whether the positions solve, to :data:`BISECT_TOL` steps)."""
    pos = res.status != UNASSEMBLABLE
    out = []
    for i in range(sw.N - 1):
        if pos[i] == pos[i + 1]:
            continue
        a, b = float(i), float(i + 1)  # a: assemblable side
        if not pos[i]:
            a, b = b, a
        while abs(b - a) > BISECT_TOL:
            m = 0.5 * (a + b)
            r = sw.kinematics(np.array([m]))
            if r.status[0] != UNASSEMBLABLE:
                a = m
            else:
                b = m
        bad = i + 1 if pos[i] else i
        out.append({"step": a, "drivers": _drivers_at(sw, a),
                    "leaves" if pos[i] else "enters": True, "message": res.messages[bad]})
    return out


def _shown(value: float, tiny: float) -> float:
    """``value``, or 0 when it is rounding noise (``|value| <= tiny``); never -0."""
    return 0.0 if abs(value) <= tiny else float(value) + 0.0


def summary_lines(scene, ext: Extremes) -> list[str]:
    """What ``analyze --extremes`` prints: limit positions, effort and reaction extremes.

    Values below :data:`NOISE` times their scale print as 0, and no value prints as -0.  A
    link that turns fully has no limit position: its line names the extremes as the ends of
    the sweep (where they are there).

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.synthesis.builders import guide_bar
    >>> scene = linkage_sym.load_scene(guide_bar(0.05, 0.02).scene)  # the guide turns fully
    >>> plan = linkage_sym.compile_plan(scene)
    >>> for line in summary_lines(scene, find_extremes(scene, plan, plan.run())):
    ...     print(line)
    dyad RPR (slider, rocker): rotation of rocker about D turns fully, no limit position: 0.000000° at A = 0.000000° and 360.000000° at A = 360.000000°, the ends of the sweep
    """
    L = scene.characteristic_length() or 1.0

    def deg(v):  # -1e-9° shows as 0
        return driver_number(_shown(v, NOISE), "R", decimals=6)

    def at(drivers):
        return ", ".join(f"{n} = {deg(v)}" if scene.joint(n).type == "R"
                         else f"{n} = {driver_number(_shown(v, NOISE * L), 'P')}"
                         for n, v in drivers.items())

    def end(e) -> bool:
        return e["located"] == "sample" and e["step"] in (0.0, float(ext.n_steps - 1))

    lines = []
    for g in ext.limits:
        for it in g["limits"]:
            c = it["coordinate"]
            rotation = c.startswith("rotation")

            def value(e, rotation=rotation):
                return deg(e["value"]) if rotation else driver_number(_shown(e["value"], NOISE * L), "P")

            if it.get("turns_fully"):
                first, last = sorted((it["min"], it["max"]), key=lambda e: e["step"])
                ends = ("the ends of the sweep" if end(first) and end(last)
                        else "its smallest and largest rotation over the sweep")
                lines.append(f"{g['group']} ({', '.join(g['links'])}): {c} turns fully, no limit "
                             f"position: {value(first)} at {at(first['drivers'])} and "
                             f"{value(last)} at {at(last['drivers'])}, {ends}")
                continue
            for kind in ("min", "max"):
                e = it[kind]
                lines.append(f"limit position of the {g['group']} ({', '.join(g['links'])}): "
                             f"{c} {kind} {value(e)} at {at(e['drivers'])}")
    for (grp, name, _), mm in ext.values.items():
        if grp == "driving":
            unit = "N·m" if scene.joint(name).type == "R" else "N"
            tiny = NOISE * max(abs(mm["max"].value), abs(mm["min"].value),
                               abs(mm["max"].sampled), abs(mm["min"].sampled))
            for kind, which in (("max", "largest"), ("min", "smallest")):
                e = mm[kind]
                lines.append(f"driving effort at {name} {kind}: {_shown(e.value, tiny):.6g} {unit} "
                             f"at {at(e.drivers)} ({e.located}; {which} sample "
                             f"{_shown(e.sampled, tiny):.6g})")
        elif grp == "reactions":
            e = mm["max"]
            lines.append(f"largest reaction at {name}: {_shown(e.value, 0.0):.6g} N at "
                         f"{at(e.drivers)} ({e.located})")
    for a in ext.assembly:
        what = "leaves" if a.get("leaves") else "enters"
        lines.append(f"the sweep {what} the assemblable range at {at(a['drivers'])}")
    return lines
