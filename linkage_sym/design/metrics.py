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
``through_infinity``        (a column of every sweep of a scene with a dyad of two slides,
                            ``PRP`` or ``RPP``) how many times the joint of such a dyad
                            passes through infinity between two steps, its slides parallel
                            there (:mod:`linkage_sym.design.parallels`): a design with
                            passages has metrics over the sweep (efforts, shaking) read from
                            steps on both sides of an unbounded motion
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

import numpy as np

from linkage_sym.design.errors import SweepError
from linkage_sym.design.limits import K_NOTES, Limits, locate
from linkage_sym.design.names import DEFAULT_METRICS, METRICS
from linkage_sym.design.parallels import passages
from linkage_sym.errors import POINTERS
from linkage_sym.model import GROUND
from linkage_sym.numeric.results.cycle_average import cycle_rms, whole_period
from linkage_sym.numeric.results.transmission import rrr_dyads
from linkage_sym.structure import decompose
from linkage_sym.structure.grashof import classify, four_bar_loops
from linkage_sym.structure.parameters import ParameterTable, evaluate

__all__ = ["METRICS", "DEFAULT_METRICS", "K_NOTES", "MetricPlan", "check_choices"]


_NEEDS = {"K": {"rate_t"}, "swing": {"rate_t"}, "peak_driving": {"forces"},
          "rms_driving": {"forces"}, "peak_reaction": {"forces"},
          "rms_shaking_force": {"points"}, "rms_shaking_moment": {"points"}, "path": {"points"}}

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
        # joint friction acts: a design may self-lock at a step, its column says at how many
        self.locks = self.forces and scene.effects.friction and any(
            j.friction is not None for j in scene.joints)
        refuse_meshes(scene)
        # a dyad of two slides may pass through infinity: its column says how many times
        self.two_slides = any(g.dyad_type in ("PRP", "RPP") for g in decompose(scene).groups)
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

    def rates(self, model) -> list:
        """The coordinates whose rates along the steps the metrics read (the output's)."""
        return [model.angle_of[self.output]] if "rate_t" in self.need else []

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
        if self.locks:
            out.append("self_locking")
        if self.two_slides:
            out.append("through_infinity")
        return out

    def _grashof_names(self):
        if len(self.loops) == 1:
            return ["grashof"]
        return ["grashof_" + "".join(lp.joints) for lp in self.loops]

    # -- computing -----------------------------------------------------------------------------
    def compute(self, model, sol) -> dict:
        """The metric columns (arrays of the chunk's designs) of a :class:`Solution`."""
        return self.finish(model, [self.begin(model, sol)])[0]

    def finish(self, model, begun) -> list:
        """The metric columns of chunks :meth:`begin` started: their limit positions
        located together (:func:`~linkage_sym.design.limits.locate`), the same numbers
        as chunk by chunk."""
        limits = [lim for _, lim, _ in begun if lim is not None]
        located = iter(locate(model, limits) if limits else ())
        out = []
        for cols, lim, N in begun:
            if lim is not None:
                cols["K"], cols["swing_deg"], cols["K_note"] = next(located)
            out.append({c: cols[c] for c in self.columns(N)})
        return out

    def begin(self, model, sol) -> tuple:
        """A chunk's metric columns but its limit positions', and its
        :class:`~linkage_sym.design.limits.Limits` (None when no metric reads them), and
        its number of steps: what :meth:`finish` takes."""
        cols = {}
        lim = None
        ok = sol.ok
        periodic = whole_period(self.scene)
        locked = np.zeros(ok.shape, bool) if sol.locked is None else sol.locked
        if self.locks:
            cols["self_locking"] = locked.sum(axis=1) / sol.N
        if self.two_slides:
            cols["through_infinity"] = passages(model, sol)
        # no finite effort drives a design through a self-locking step: its efforts and
        # reactions over the cycle are unbounded (never the largest of its other steps)
        unbounded = locked.any(axis=1)
        for m in self.metrics:
            if m == "assemblable":
                cols[m] = ok.sum(axis=1) / sol.N
            elif m == "grashof":
                cols.update(self._grashof(model, sol))
            elif m in ("K", "swing"):
                if lim is None:
                    lim = Limits(model, sol, model.angle_of[self.output], "swing" in self.metrics)
            elif m == "min_transmission_deg":
                cols[m] = self._transmission(model, sol)
            elif m in ("peak_driving", "rms_driving"):
                for d in self.scene.drivers:
                    e = np.where(ok, sol.effort(d.joint), np.nan)
                    v = (_fmax(np.abs(e)) if m == "peak_driving" else cycle_rms(e, ok, periodic))
                    cols[f"{m}_{d.joint}"] = np.where(unbounded, np.inf, v)
            elif m == "peak_reaction":
                for j in self.scene.joints:
                    v = _fmax(np.where(ok, sol.reaction(j.name), np.nan))
                    cols[f"peak_reaction_{j.name}"] = np.where(unbounded, np.inf, v)
            elif m in ("rms_shaking_force", "rms_shaking_moment"):
                if "rms_shaking_force" not in cols:
                    fx, fy, mz = self._shaking(model, sol)
                    cols["rms_shaking_force"] = cycle_rms(np.hypot(fx, fy), ok, periodic)
                    cols["rms_shaking_moment"] = cycle_rms(mz, ok, periodic)
            elif m == "path":
                cols.update(self._path(model, sol))
        return cols, lim, sol.N

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

    def transmission_offsets(self, model, joints0, X0) -> list:
        """``(ia, ib, cos c, sin c)`` of each RRR dyad: its links' coordinates and the
        cosine and sine (n,) of the constant ``c`` by which ``gamma`` is their angles'
        difference, from the designs' assembly configurations (``joints0``, ``X0``)."""
        out = []
        for inner, e1, e2, a, b in self.dyads:
            J = joints0[inner]
            ia, ib = model.angle_of[a], model.angle_of[b]
            c1 = np.arctan2(*(joints0[e1] - J)[::-1]) - X0[ia]
            c2 = np.arctan2(*(joints0[e2] - J)[::-1]) - X0[ib]
            out.append((ia, ib, np.cos(c2 - c1), np.sin(c2 - c1)))
        return out

    def _transmission(self, model, sol):
        """``min(gamma, pi - gamma) = atan(|sin gamma| / |cos gamma|)``, smallest over the steps:
        the angle of ``J -> E1`` is link ``a``'s angle plus a constant of the design, so
        ``gamma``'s sine and cosine come from the coordinates' (no trigonometric call per step).
        A solution with :attr:`~linkage_sym.design.solution.Solution.transmission` (the
        compiled loop's) gives each dyad's smallest ratio already."""
        best = np.full(sol.n, np.inf)
        if sol.transmission is not None:
            ratios = list(sol.transmission)
        else:
            ratios = [self._ratio(sol, *dy) for dy in self.transmission_offsets(model, sol.joints0,
                                                                                 sol.X0)]
        for r in ratios:
            best = np.fmin(best, r)
        best[~np.isfinite(best) & ~(best == np.inf)] = np.nan
        out = np.degrees(np.arctan(best))
        out[~sol.pos_ok.any(axis=1)] = np.nan
        return out

    @staticmethod
    def _ratio(sol, ia, ib, cc, sc):
        """A dyad's smallest ``|sin gamma| / |cos gamma|`` over the steps (n,)."""
        cc, sc = cc[:, None], sc[:, None]
        ca, sa, cb, sb = sol.C[ia], sol.S[ia], sol.C[ib], sol.S[ib]
        cd = cb * ca + sb * sa  # cos, sin of X_b - X_a
        sd = sb * ca - cb * sa
        with np.errstate(divide="ignore", invalid="ignore"):
            num = sd * cc
            num += cd * sc
            cd *= cc
            sd *= sc
            cd -= sd
            ratio = np.abs(np.divide(num, cd, out=num), out=num)  # |a|/|b| = |a/b|
        return _fmin(ratio)

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

