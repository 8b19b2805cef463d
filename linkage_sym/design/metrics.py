"""What a sweep reports about each design: the metrics, from one chunk's solution.

==========================  ===============================================================
``assemblable``             fraction of the sweep's steps that are ``ok`` (assembled and
                            not singular); 0 for a design that cannot be assembled at the
                            scene's driver values
``grashof``                 Grashof class of each loop of four links and four ``R`` joints
                            (:func:`linkage_sym.structure.grashof.classify` on the design's
                            lengths, from its parameters: also for a design that cannot be
                            assembled, the class being a property of the lengths): one of
                            ``crank-rocker``, ``double-crank``, ``double-rocker`` (Grashof,
                            the shortest link opposite the frame), ``triple-rocker`` (not
                            Grashof: no link turns fully) or ``change point`` for a loop
                            through the ground; ``Grashof``, ``not Grashof`` or ``change
                            point`` for one without it (a column ``grashof_<joints>`` per
                            loop when the scene has several)
``K``, ``swing``            the output's limit positions (roots of its rate along the sweep,
                            located between ``ok`` samples as ``analyze --extremes`` does):
                            ``swing_deg`` its largest minus smallest rotation (degrees) over
                            the ``ok`` steps the design has and the limit positions between
                            them (a sample wins at the ends of a partial sweep and at the
                            edges of gaps, as in :func:`~linkage_sym.numeric.extremes.find_extremes`);
                            ``K`` the stroke-time ratio, the larger over the smaller driver
                            interval between the two limit positions of the driver's first
                            turn, for a scene driven by one ``R`` joint.  ``K`` needs the
                            sweep to turn the driver fully, every step of that turn ``ok``
                            and exactly two limit positions in it, a maximum and a minimum:
                            where it has no value, ``K_note`` says which of
                            :data:`K_NOTES` failed (empty where ``K`` has a value)
``min_transmission_deg``    the smallest ``min(gamma, 180 - gamma)`` of every RRR dyad's
                            transmission angle (:mod:`linkage_sym.numeric.results.transmission`) over
                            the steps with positions (degrees)
``peak_driving``            per driver: largest ``|effort|`` over the ``ok`` steps (N m or N)
``rms_driving``             per driver: root mean square of the effort over the cycle (the
                            ``ok`` steps, a whole period's repeated end point once)
``peak_reaction``           per joint: largest reaction magnitude over the ``ok`` steps (N)
``rms_shaking_force``       RMS over the cycle of ``|sum m a_G|`` (N): the frame force
                            with inertia as the only effect
``rms_shaking_moment``      RMS of the shaking moment about the origin, ``-dH_O/dt`` (N m)
``path``                    a traced point's ``x``, ``y`` at every step with positions: ``ok``
                            and singular steps (whose positions are defined, as ``analyze``
                            keeps them); NaN at unassemblable steps
==========================  ===============================================================

Forces are those of the scene's effects (inertia, gravity, loads) at its
speeds; each design's masses, loads and dimensions are its own.  A metric is
empty (NaN) only where the design has no step it is computed from: every metric
but ``grashof`` and ``K_note`` of a design that cannot be assembled (``assemblable``
0), the force, shaking and path metrics of a design without an ``ok`` step, ``K``
for the reason ``K_note`` gives.

The ``rms_*`` metrics are cycle averages
(:func:`~linkage_sym.numeric.results.cycle_average.cycle_rms`): when the sweep is a whole period
(:func:`~linkage_sym.numeric.results.cycle_average.whole_period`, e.g. 0 to 360 degrees) its last
step repeats its first and is counted once; any other sweep is averaged over its steps as
given.
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.design.errors import SweepError
from linkage_sym.design.names import DEFAULT_METRICS, METRICS
from linkage_sym.errors import POINTERS
from linkage_sym.model import GROUND
from linkage_sym.numeric.results.cycle_average import cycle_rms, whole_period
from linkage_sym.numeric.results.transmission import rrr_dyads
from linkage_sym.structure.grashof import classify, four_bar_loops
from linkage_sym.structure.parameters import ParameterTable, evaluate

__all__ = ["METRICS", "DEFAULT_METRICS", "MetricPlan", "check_choices"]


_NEEDS = {"K": {"rate_t"}, "swing": {"rate_t"}, "peak_driving": {"forces"},
          "rms_driving": {"forces"}, "peak_reaction": {"forces"},
          "rms_shaking_force": {"points"}, "rms_shaking_moment": {"points"}, "path": {"points"}}

K_NOTES = {
    "assembly": "not assembled at the scene's driver values",
    "no ok step": "no step is ok",
    "partial": "the sweep does not turn the driver a full turn",
    "steps": "a step of the driver's turn is not ok (unassemblable or singular)",
    "not located": "a limit position was not located (Newton on the output's rate did not converge)",
    "count": "the output has not exactly two limit positions in the driver's turn",
    "kinds": "the two limit positions are both maxima or both minima",
}
"""Why ``K`` has no value: the ``K_note`` column holds one of these (empty where ``K`` has a
value)."""

XTOL = 1e-12
"""Limit positions are located to this many steps (plus 4 ulp of the position)."""
MAX_ITER = 100


def _fmax(a):
    return np.fmax.reduce(a, axis=1) if a.shape[1] else np.full(len(a), np.nan)


def _fmin(a):
    return np.fmin.reduce(a, axis=1) if a.shape[1] else np.full(len(a), np.nan)


def refuse_meshes(scene) -> None:
    """Design sweeps do not take gear meshes or cam contacts yet: refuse them by name."""
    if scene.meshes:
        raise SweepError("scene", f"scene {scene.name!r} has gear meshes "
                                  f"({', '.join(j.name for j in scene.meshes)}): design sweeps "
                                  "do not take them yet (a design's radii and pivots must keep "
                                  "each mesh's centre distance, and each step's flank is chosen "
                                  f"from its tooth load); {POINTERS['analyze']}")
    if scene.cams:
        raise SweepError("scene", f"scene {scene.name!r} has cam contacts "
                                  f"({', '.join(j.name for j in scene.cams)}): design sweeps "
                                  "do not take them yet (they run on the symbolic layer's "
                                  f"functions, which do not derive cams); {POINTERS['analyze']}")


def check_choices(scene, output=None, trace=None) -> None:
    """Refuse an ``output`` link or ``trace`` points the scene does not have, listing its
    own, whether or not the metrics that use them are asked for (a misspelt name is an
    error, not a choice that happens to go unused)."""
    if output is not None and output not in scene.link_names:
        raise SweepError("output", f"unknown link {output!r}; the moving links are "
                                   f"{', '.join(scene.link_names)}")
    if trace is not None:
        names = [p.name for p in scene.points]
        for t in ([trace] if isinstance(trace, str) else list(trace)):
            if t not in names:
                raise SweepError("trace", f"unknown traced point {t!r}; the scene's are "
                                          f"{', '.join(names) if names else 'none (it has no points section)'}")


class MetricPlan:
    """The metrics asked for, checked against the scene: their columns and what the
    solution must hold for them.

    Parameters
    ----------
    scene : Scene
    metrics : sequence of str
        Names from :data:`METRICS`.
    output : str, optional
        The link whose limit positions give ``K`` and ``swing``; default the last link
        of the scene pivoted on the ground by an ``R`` joint that is not driven.
    trace : sequence of str, optional
        The traced points (scene ``points``) of ``path``; default all.

    Attributes
    ----------
    output : str or None
        The link of ``K`` and ``swing``: ``output`` or the default one when a metric asked
        for measures a link's limit positions; None when none does.
    """

    def __init__(self, scene, metrics=DEFAULT_METRICS, output=None, trace=None):
        self.scene = scene
        metrics = [metrics] if isinstance(metrics, str) else list(metrics)
        if not metrics:
            raise SweepError("metrics", f"no metric asked for; choose from {', '.join(METRICS)}")
        for m in metrics:
            if m not in METRICS:
                raise SweepError("metrics", f"unknown metric {m!r}; the metrics are "
                                            f"{', '.join(METRICS)}")
        self.metrics = list(dict.fromkeys(metrics))
        check_choices(scene, output, trace)
        self.need = set().union(*(_NEEDS.get(m, set()) for m in self.metrics))
        self.forces = "forces" in self.need
        refuse_meshes(scene)
        self.output = self._output(output) if "rate_t" in self.need else None
        if "K" in self.metrics and not (len(scene.drivers) == 1
                                        and scene.joint(scene.drivers[0].joint).type == "R"):
            raise SweepError("metrics", f"K: the stroke-time ratio of a driver turning at a "
                                        f"constant speed; scene {scene.name!r} is not driven by "
                                        "one R joint")
        self.dyads = []
        if "min_transmission_deg" in self.metrics:
            for inner, e1, e2 in rrr_dyads(scene):
                a = _common(scene, inner, e1)
                b = _common(scene, inner, e2)
                self.dyads.append((inner, e1, e2, a, b))
            if not self.dyads:
                raise SweepError("metrics", f"min_transmission_deg: scene {scene.name!r} has no "
                                            "RRR dyad, whose transmission angle it measures")
        self.loops = four_bar_loops(scene) if "grashof" in self.metrics else []
        if "grashof" in self.metrics and not self.loops:
            raise SweepError("metrics", f"grashof: scene {scene.name!r} has no loop of four links "
                                        "and four R joints")
        self.trace = []
        if "path" in self.metrics:
            names = [p.name for p in scene.points]
            if not names:
                raise SweepError("metrics", f"path: scene {scene.name!r} has no traced point "
                                            "(its `points` section)")
            trace = names if trace is None else ([trace] if isinstance(trace, str) else list(trace))
            for t in trace:
                if t not in names:
                    raise SweepError("trace", f"unknown traced point {t!r}; the scene's are "
                                              f"{', '.join(names)}")
            self.trace = trace
        if "rms_shaking_force" in self.metrics or "rms_shaking_moment" in self.metrics:
            if not any(lk.com is not None and (lk.mass > 0 or lk.inertia > 0) for lk in scene.links):
                raise SweepError("metrics", f"rms_shaking_force/rms_shaking_moment: no link of "
                                            f"scene {scene.name!r} has a mass")

    def _output(self, output):
        scene = self.scene
        driven = {d.joint for d in scene.drivers}
        if output is None:
            cands = [lk for lk in scene.link_names
                     if any(j.type == "R" and GROUND in j.links and lk in j.links
                            and j.name not in driven for j in scene.joints)]
            if not cands:
                raise SweepError("output", f"K/swing: scene {scene.name!r} has no link pivoted "
                                           "on the ground besides the driven one; name the "
                                           "output link")
            return cands[-1]
        if output not in scene.link_names:
            raise SweepError("output", f"unknown link {output!r}; the moving links are "
                                       f"{', '.join(scene.link_names)}")
        return output

    def unwrap(self, model) -> list:
        """The coordinates whose angles must be continuous along the sweep: the output's,
        for ``swing`` (``K`` reads only the output's rate)."""
        return [model.angle_of[self.output]] if "swing" in self.metrics else []

    def columns(self, N: int) -> list[str]:
        """The metric columns of the table, in order."""
        out = []
        for m in self.metrics:
            if m == "grashof":
                out += self._grashof_names()
            elif m == "swing":
                out.append("swing_deg")
            elif m == "K":
                out += ["K", "K_note"]
            elif m in ("peak_driving", "rms_driving"):
                out += [f"{m}_{d.joint}" for d in self.scene.drivers]
            elif m == "peak_reaction":
                out += [f"peak_reaction_{j.name}" for j in self.scene.joints]
            elif m == "path":
                out += [f"path_{p}_{c}_{i}" for p in self.trace for c in "xy" for i in range(N)]
            else:
                out.append(m)
        return out

    def _grashof_names(self):
        if len(self.loops) == 1:
            return ["grashof"]
        return ["grashof_" + "".join(lp.joints) for lp in self.loops]

    # -- computing -----------------------------------------------------------------------------
    def compute(self, model, sol) -> dict:
        """The metric columns (arrays of the chunk's designs) of a :class:`Solution`."""
        cols = {}
        ok = sol.ok
        periodic = whole_period(self.scene)
        for m in self.metrics:
            if m == "assemblable":
                cols[m] = ok.sum(axis=1) / sol.N
            elif m == "grashof":
                cols.update(self._grashof(model, sol))
            elif m in ("K", "swing"):
                if "swing_deg" not in cols:
                    cols["K"], cols["swing_deg"], cols["K_note"] = self._limits(model, sol)
            elif m == "min_transmission_deg":
                cols[m] = self._transmission(model, sol)
            elif m in ("peak_driving", "rms_driving"):
                for d in self.scene.drivers:
                    e = np.where(ok, sol.effort(d.joint), np.nan)
                    cols[f"{m}_{d.joint}"] = (_fmax(np.abs(e)) if m == "peak_driving"
                                              else cycle_rms(e, ok, periodic))
            elif m == "peak_reaction":
                for j in self.scene.joints:
                    cols[f"peak_reaction_{j.name}"] = _fmax(np.where(ok, sol.reaction(j.name), np.nan))
            elif m in ("rms_shaking_force", "rms_shaking_moment"):
                if "rms_shaking_force" not in cols:
                    fx, fy, mz = self._shaking(model, sol)
                    cols["rms_shaking_force"] = cycle_rms(np.hypot(fx, fy), ok, periodic)
                    cols["rms_shaking_moment"] = cycle_rms(mz, ok, periodic)
            elif m == "path":
                cols.update(self._path(model, sol))
        return {c: cols[c] for c in self.columns(sol.N)}

    def _grashof(self, model, sol) -> dict:
        """The class of each loop from the design's lengths (its parameters: a property of
        the lengths, given also for a design that cannot be assembled)."""
        out = {}
        for name, lp in zip(self._grashof_names(), self.loops):
            lengths = np.array([np.broadcast_to(_distance_on(model, sol.P, lp.links[i],
                                                             lp.joints[i - 1], lp.joints[i]),
                                                (sol.n,)) for i in range(4)])  # (4, n)
            fixed = 0 if lp.links[0] == GROUND else None
            col = np.empty(sol.n, dtype=object)
            for d in range(sol.n):
                col[d] = (classify(lengths[:, d], fixed, lp.links).name
                          if np.isfinite(lengths[:, d]).all() else "")
            out[name] = col.astype(str)
        return out

    def _transmission(self, model, sol):
        """``min(gamma, pi - gamma) = atan(|sin gamma| / |cos gamma|)``, smallest over the steps:
        the angle of ``J -> E1`` is link ``a``'s angle plus a constant of the design, so
        ``gamma``'s sine and cosine come from the coordinates' (no trigonometric call per step)."""
        best = np.full(sol.n, np.inf)
        for inner, e1, e2, a, b in self.dyads:
            J = sol.joints0[inner]
            ia, ib = model.angle_of[a], model.angle_of[b]
            c1 = np.arctan2(*(sol.joints0[e1] - J)[::-1]) - sol.X0[ia]
            c2 = np.arctan2(*(sol.joints0[e2] - J)[::-1]) - sol.X0[ib]
            cc, sc = np.cos(c2 - c1)[:, None], np.sin(c2 - c1)[:, None]
            ca, sa, cb, sb = sol.C[ia], sol.S[ia], sol.C[ib], sol.S[ib]
            cd = cb * ca + sb * sa  # cos, sin of X_b - X_a
            sd = sb * ca - cb * sa
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = np.abs(sd * cc + cd * sc) / np.abs(cd * cc - sd * sc)
            best = np.fmin(best, _fmin(ratio))
        best[~np.isfinite(best) & ~(best == np.inf)] = np.nan
        out = np.degrees(np.arctan(best))
        out[~sol.pos_ok.any(axis=1)] = np.nan
        return out

    def _shaking(self, model, sol):
        fx = np.zeros((sol.n, sol.N))
        fy = np.zeros((sol.n, sol.N))
        mz = np.zeros((sol.n, sol.N))
        for lk in self.scene.links:
            if lk.com is None:
                continue
            m = _col(model.value(sol.P, ("m", lk.name), lk.mass))
            inertia = _col(model.value(sol.P, ("I", lk.name), lk.inertia))
            rx, ry, ax, ay = sol.com(lk.name)
            alpha = sol.alpha(lk.name)
            fx -= m * ax
            fy -= m * ay
            mz -= m * (rx * ay - ry * ax) + inertia * alpha
        return fx, fy, mz

    def _path(self, model, sol) -> dict:
        out = {}
        for p in self.trace:
            x, y = sol.traced(p)
            for name, v in (("x", x), ("y", y)):
                for i in range(sol.N):
                    out[f"path_{p}_{name}_{i}"] = v[:, i]
        return out

    def _swing(self, sol, col, d, i, t):
        """The output's swing (degrees): its largest minus smallest rotation over the ``ok``
        steps and the limit positions ``t`` of designs ``d`` (between steps ``i``)."""
        rot = sol.X[col] - sol.X0[col][:, None]
        # values at the roots, continuous with the sample before
        raw = sol.rate_at(d, t, col)[2] if len(d) else np.zeros(0)
        v = raw - sol.X0[col][d]
        v = v + 2 * math.pi * np.round((rot[d, i] - v) / (2 * math.pi))
        # the positions are NaN where a step has none: only singular steps need masking
        rot_ok = rot if sol.ok is sol.pos_ok else np.where(sol.ok, rot, np.nan)
        hi = _fmax(rot_ok)
        lo = _fmin(rot_ok)
        good = np.isfinite(v)
        np.fmax.at(hi, d[good], v[good])
        np.fmin.at(lo, d[good], v[good])
        return np.degrees(hi - lo)

    def _limits(self, model, sol):
        """``K`` and the swing (degrees) of the output link (see the module docstring)."""
        n, N = sol.n, sol.N
        col = model.angle_of[self.output]
        r = sol.rate_t[col]
        ok = sol.ok
        both = ok[:, :-1] & ok[:, 1:]
        ra, rb = r[:, :-1], r[:, 1:]
        with np.errstate(invalid="ignore"):
            change = both & ((ra == 0) | (rb == 0) | ((ra < 0) != (rb < 0)))
        d, i = np.nonzero(change)
        t, kind = _roots(sol, d, i.astype(float), ra[d, i], rb[d, i], col)
        good = np.isfinite(t)
        swing = self._swing(sol, col, d, i, t) if "swing" in self.metrics else None
        K = np.full(n, np.nan)
        note = np.full(n, K_NOTES["no ok step"], dtype=object)
        note[~sol.assembled] = K_NOTES["assembly"]
        step = abs(model.slope[0]) if N > 1 else 0.0
        if not (step > 0 and step * (N - 1) >= 2 * math.pi * (1 - 1e-12)):
            note[ok.any(axis=1)] = K_NOTES["partial"]
            return K, swing, note.astype(str)
        T = 2 * math.pi / step  # steps of one turn
        last = min(N - 1, int(math.ceil(T)))
        full = ok[:, : last + 1].all(axis=1)
        note[ok.any(axis=1) & ~full] = K_NOTES["steps"]
        in_turn = i < T
        first = good & (t < T)
        cnt = np.bincount(d[first], minlength=n)
        lost = np.bincount(d[in_turn & ~good], minlength=n) > 0
        note[full & lost] = K_NOTES["not located"]
        note[full & ~lost & (cnt != 2)] = K_NOTES["count"]
        # the roots come design by design (np.nonzero is row-major): a design's two are
        # consecutive among those of the first turn
        sel = np.flatnonzero(first)
        start = np.concatenate([[0], np.cumsum(cnt)[:-1]])
        ks = np.flatnonzero(full & ~lost & (cnt == 2))
        j0, j1 = sel[start[ks]], sel[start[ks] + 1]
        same = kind[j0] == kind[j1]
        note[ks[same]] = K_NOTES["kinds"]
        ks, j0, j1 = ks[~same], j0[~same], j1[~same]
        a = np.abs(t[j1] - t[j0]) * step
        b = 2 * math.pi - a
        K[ks] = np.maximum(a, b) / np.minimum(a, b)
        note[ks] = ""
        return K, swing, note.astype(str)


def _in_frame(model, P, link, joint):
    """Coordinates of ``joint`` in ``link``'s frame (the ground's: global) from the designs'
    parameters (:class:`~linkage_sym.structure.parameters.ParameterTable`'s recipes; the
    scene's values where the derivation keeps a constant)."""
    scene = model.scene
    if link == GROUND:
        at = scene.joint(joint).at
        return model.value(P, ("x", joint), at[0]), model.value(P, ("y", joint), at[1])
    names = ParameterTable(scene).point(link, joint)
    if names is None:  # the frame's origin
        return 0.0, 0.0
    recipe = ("l", link, joint)
    length = model.value(P, recipe, evaluate(scene, recipe))
    angle = 0.0
    if names[1] is not None:
        recipe = ("beta", link, joint)
        angle = model.value(P, recipe, evaluate(scene, recipe))
    return length * np.cos(angle), length * np.sin(angle)


def _distance_on(model, P, link, j1, j2):
    """Distance between joints ``j1`` and ``j2`` of ``link`` in the designs ``P``."""
    x1, y1 = _in_frame(model, P, link, j1)
    x2, y2 = _in_frame(model, P, link, j2)
    return np.hypot(np.subtract(x2, x1), np.subtract(y2, y1))


def _col(v):
    return v[:, None] if np.ndim(v) else v


def _common(scene, j1, j2):
    a = set(scene.joint(j1).links) & set(scene.joint(j2).links)
    return next(lk for lk in scene.joint(j1).links if lk in a and lk != GROUND)


def _roots(sol, d, a, fa, fb, col):
    """Roots of the output's rate between steps ``a`` and ``a + 1`` of designs ``d``, every
    bracket at once: Newton on the rate (its derivative from the accelerations), kept in
    the bracket by bisection.  Returns ``(t, kind)``, ``kind`` +1 at a maximum, -1 at a
    minimum, ``t`` NaN where the rate is not defined or does not converge."""
    b = a + 1.0
    kind = np.where((fa > 0) | (fb < 0), 1, -1)
    t = np.where(fa == 0, a, b)
    act = np.flatnonzero(~((fa == 0) | (fb == 0)))
    lo, hi = a.copy(), b.copy()
    flo = fa.copy()
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(fb != fa, b - fb * (b - a) / (fb - fa), 0.5 * (a + b))  # secant start
        for _ in range(MAX_ITER):
            if not len(act):
                break
            X = x[act]
            f, df, _ = sol.rate_at(d[act], X, col)
            bad = ~np.isfinite(f)
            t[act[bad]] = np.nan
            same = (f < 0) == (flo[act] < 0)  # the root lies above X
            lo[act] = np.where(same, X, lo[act])
            flo[act] = np.where(same, f, flo[act])
            hi[act] = np.where(same, hi[act], X)
            step = f / df
            xn = X - step
            L, H = lo[act], hi[act]
            conv = (f == 0) | (np.abs(step) <= XTOL + 4 * np.finfo(float).eps * np.abs(X))
            t[act] = np.where(f == 0, X, xn)
            xn = np.where((xn > L) & (xn < H), xn, 0.5 * (L + H))
            x[act] = xn
            act = act[~(conv | bad)]
    t[act] = np.nan  # no convergence
    return t, kind
