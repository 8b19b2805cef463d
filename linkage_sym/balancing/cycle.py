"""Shaking force, shaking moment and driver efforts over a cycle, for any counterweights (NumPy only).

:class:`CycleModel` solves a scene once and then evaluates any set of
counterweights (:class:`~.counterweight.Counterweight`) without re-solving
the mechanism; the optimiser (:mod:`~.search`) reads it through
:meth:`CycleModel.rms` and :meth:`CycleModel.mean_square_factors`.

How a cycle is evaluated
------------------------
Counterweights change neither the motion nor (with the motion prescribed)
the linearity of the kinetostatics, so the scene's kinematics are solved
once.  A point mass ``mu`` at ``w`` in the frame of link ``j`` (the frame of
:func:`~linkage_sym.structure.parameters.link_frames`: origin at the link's
first joint ``u``, x-axis toward ``v``) is at ``r = r_u + R(phi) w`` and has
the acceleration ``a = a_u + alpha k x (R w) - omega^2 R w``.  It changes

* the shaking force by ``-mu a``,
* the shaking moment about the origin by ``-mu r x a``,
* the effort of driver ``k`` by ``mu (i a - g) . v^(k)`` (virtual power),
  where ``v^(k)`` is the point's partial velocity with respect to the rate of
  driver ``k`` (the velocity when that driver moves at unit rate and the
  others stand still), ``i`` is 1 when the scene's ``inertia`` effect is on,
  else 0, and ``g`` the scene's gravity (zero when off).

Written out, each of these changes is *linear* in the four numbers
``(mu, mu w_x, mu w_y, mu |w|^2)`` of the counterweight (its mass, first and
second moments about ``u`` in the link frame): the term quadratic in ``w``
reduces to ``-alpha mu |w|^2`` in the moment and ``i omega^(k) alpha mu |w|^2``
in the effort.  :class:`CycleModel` stores these linear maps over the steps
(one kinematic run at the scene's speeds, one at unit rate per driver) and
the baseline series of the original scene from the numeric force solver (the
frame force and moment with inertia as the only effect; the efforts with the
scene's effects).  Evaluating a set of counterweights is then one small
matrix product, exact to rounding.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.balancing.counterweight import Counterweight
>>> scene = load_example("crank_rocker")
>>> model = CycleModel(scene)
>>> rms0 = model.rms([])
>>> rms1 = model.rms([Counterweight("crank", 0.3, (-0.02, 0.0))])
>>> bool(rms1["force"] < rms0["force"])
True
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from linkage_sym.balancing.counterweight import as_scene, check_counterweights
from linkage_sym.model import OUTPUTS, Effects
from linkage_sym.numeric.results.cycle_average import counted_steps, whole_period
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.numeric.engine.run import scene_sweep
from linkage_sym.structure.parameters import link_frames

__all__ = ["TERMS", "CycleModel"]

TERMS = {"force": slice(0, 2), "moment": slice(2, 3), "driving": slice(3, None)}
"""The rows of the linear maps that make each term of :meth:`CycleModel.rms`:
the shaking force's x and y, the shaking moment, one row per driver's effort."""


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


class CycleModel:
    """Shaking force, shaking moment and driver efforts over a scene's cycle,
    for any counterweights: compile once, evaluate many.

    Construction runs the numeric solver on the scene (kinematics at the
    scene's speeds, the frame force and moment with inertia as the only
    effect, the driver efforts with the scene's effects) and the velocity
    problem once per driver at unit rate; see the module docstring for the
    linear maps it then stores.

    Parameters
    ----------
    scene : Scene or mapping or path
    disconnection : optional
        Passed to :func:`~linkage_sym.numeric.plan.compile_plan`.

    Attributes
    ----------
    scene : Scene
    links : tuple of str
        The moving links, in scene order (the column blocks of the maps).
    frames : dict
        :func:`~linkage_sym.structure.parameters.link_frames` of the scene.
    drivers : tuple of str
        The driven joints.
    status : ndarray of str (N,)
        Status of every step (``"ok"`` or why not).
    ok : ndarray of bool (N,)
        Steps solved at every stage.
    periodic : bool
        The sweep is a whole period
        (:func:`~linkage_sym.numeric.results.cycle_average.whole_period`): its last
        step repeats its first.
    counted : ndarray of bool (N,)
        The steps every cycle average (:meth:`rms`, :meth:`mean_square_factors`,
        :attr:`gross`) counts: the ``ok`` ones, the repeated end point of a
        whole period once
        (:func:`~linkage_sym.numeric.results.cycle_average.counted_steps`).
    n_steps : int
        Number of steps of the sweep.
    n_excluded : int
        Number of steps that are not ``ok``.
    analysis : Analysis
        The numeric solver's run with inertia as the only effect (the
        kinematics and the baseline shaking force and moment).
    gross : dict
        ``force``, ``moment``, ``driving``: RMS over the cycle of the *sum of
        the magnitudes* of every link's own contribution (and, for the
        efforts, of the baseline); a scale of each quantity that does not
        vanish when the mechanism happens to be balanced.
    """

    def __init__(self, scene, disconnection=None):
        scene = as_scene(scene)
        self.scene = scene
        self.links = scene.link_names
        self.frames = link_frames(scene)
        self.drivers = tuple(d.joint for d in scene.drivers)
        self.gravity = np.array(scene.effects.gravity or (0.0, 0.0), dtype=float)
        self.inertia = 1.0 if scene.effects.inertia else 0.0
        # baselines from the numeric force solver
        shaking = dataclasses.replace(
            scene, effects=Effects(inertia=True, gravity=None, loads=False), outputs=OUTPUTS
        )
        an = compile_plan(shaking, disconnection).run()
        own = compile_plan(dataclasses.replace(scene, outputs=OUTPUTS), disconnection).run()
        # partial velocities: the velocity problem with unit rate of one driver
        kin = compile_plan(dataclasses.replace(scene, effects=Effects(loads=False), outputs=("kinematics",)))
        q, qd, _ = scene_sweep(scene)
        N = len(an.status)
        unit = {}
        for k in self.drivers:
            rates = {j: np.full(N, 1.0 if j == k else 0.0) for j in qd}
            unit[k] = kin.run(q, rates, {j: np.zeros(N) for j in qd})
        ok = an.ok & own.ok
        for u in unit.values():
            ok = ok & u.ok
        self.status = an.status.copy()
        self.status[~ok & (self.status == "ok")] = "inconsistent"
        self.ok = ok
        self.periodic = whole_period(scene)
        self.counted = counted_steps(ok, self.periodic)
        self.n_steps = N
        self.n_excluded = int((~ok).sum())
        self.analysis = an
        self._build(an, unit, own)

    # -- construction of the linear maps -----------------------------------------------
    def _build(self, an, unit, own):
        N, nL, D = self.n_steps, len(self.links), len(self.drivers)
        g, ii = self.gravity, self.inertia
        # rows: force x, force y, moment, then one block per driver
        B = np.zeros((3 + D, N, 4 * nL))
        for i, name in enumerate(self.links):
            fr = self.frames[name]
            lk = an.links[name]
            O = fr.origin
            ph = fr.theta0 + lk.rotation
            c, s = np.cos(ph), np.sin(ph)
            e1x, e1y, e2x, e2y = c, s, -s, c
            w, al = lk.omega, lk.alpha
            w2 = w * w
            rx, ry = lk.point(O).T
            ax, ay = lk.point_acceleration(O).T
            f1x, f1y = al * e2x - w2 * e1x, al * e2y - w2 * e1y
            f2x, f2y = -al * e1x - w2 * e2x, -al * e1y - w2 * e2y
            col = slice(4 * i, 4 * i + 4)
            B[0, :, col] = np.stack([-ax, -f1x, -f2x, np.zeros(N)], axis=1)
            B[1, :, col] = np.stack([-ay, -f1y, -f2y, np.zeros(N)], axis=1)
            B[2, :, col] = np.stack(
                [
                    -_cross(rx, ry, ax, ay),
                    -(_cross(rx, ry, f1x, f1y) + _cross(e1x, e1y, ax, ay)),
                    -(_cross(rx, ry, f2x, f2y) + _cross(e2x, e2y, ax, ay)),
                    -al,
                ],
                axis=1,
            )
            bx, by = ii * ax - g[0], ii * ay - g[1]
            for k, dname in enumerate(self.drivers):
                uk = unit[dname].links[name]
                vx, vy = uk.point_velocity(O).T
                wk = uk.omega
                B[3 + k, :, col] = np.stack(
                    [
                        bx * vx + by * vy,
                        ii * (f1x * vx + f1y * vy) + wk * (bx * e2x + by * e2y),
                        ii * (f2x * vx + f2y * vy) - wk * (bx * e1x + by * e1y),
                        ii * wk * al,
                    ],
                    axis=1,
                )
        Y0 = np.zeros((3 + D, N))
        Y0[0] = an.forces.frame_force[:, 0]
        Y0[1] = an.forces.frame_force[:, 1]
        Y0[2] = an.forces.frame_moment
        for k, dname in enumerate(self.drivers):
            Y0[3 + k] = own.forces.driving[dname]
        self._B, self._Y0 = B, Y0
        okc = self.counted
        self._Bok = B[:, okc, :]
        self._Y0ok = Y0[:, okc]
        # the links' own mass distributions as (mu, s_x, s_y, J) about u: gross scales
        p_own = np.zeros(4 * nL)
        for i, link in enumerate(self.scene.links):
            if link.mass > 0:
                fr = self.frames[link.name]
                dx, dy = link.com[0] - fr.origin[0], link.com[1] - fr.origin[1]
                c, s = math.cos(fr.theta0), math.sin(fr.theta0)
                px, py = c * dx + s * dy, -s * dx + c * dy
                p_own[4 * i: 4 * i + 4] = (link.mass, link.mass * px, link.mass * py,
                                            link.inertia + link.mass * (px * px + py * py))
            elif link.inertia > 0:
                p_own[4 * i + 3] = link.inertia
        contrib = np.abs(self._Bok * p_own)  # (3 + D, Nok, 4 nL)
        per_link = contrib.reshape(3 + D, -1, nL, 4).sum(axis=3)
        fx, fy = per_link[0], per_link[1]
        gross_f = np.hypot(fx, fy).sum(axis=1)
        gross_m = per_link[2].sum(axis=1)
        gross_t = per_link[3:].sum(axis=2) + np.abs(self._Y0ok[3:])
        nok = max(1, int(okc.sum()))
        self.gross = {
            "force": float(np.sqrt(np.sum(gross_f ** 2) / nok)),
            "moment": float(np.sqrt(np.sum(gross_m ** 2) / nok)),
            "driving": float(np.sqrt(np.sum(gross_t ** 2) / nok)),
        }

    # -- parameters ------------------------------------------------------------
    def parameters(self, counterweights) -> np.ndarray:
        """The vector ``(mu, mu w_x, mu w_y, mu |w|^2)`` per link (links in scene order)."""
        cws = check_counterweights(self.scene, counterweights)
        p = np.zeros(4 * len(self.links))
        index = {n: i for i, n in enumerate(self.links)}
        for cw in cws:
            i = 4 * index[cw.link]
            wx, wy = cw.at
            p[i: i + 4] += (cw.mass, cw.mass * wx, cw.mass * wy, cw.mass * (wx * wx + wy * wy))
        return p

    def _series(self, p, ok_only=False):
        B, Y0 = (self._Bok, self._Y0ok) if ok_only else (self._B, self._Y0)
        return Y0 + B @ p

    @staticmethod
    def _rms_of(Y) -> dict:
        n = max(1, Y.shape[1])
        return {
            "force": float(np.sqrt(np.sum(Y[0] ** 2 + Y[1] ** 2) / n)),
            "moment": float(np.sqrt(np.sum(Y[2] ** 2) / n)),
            "driving": float(np.sqrt(np.sum(Y[3:] ** 2) / n)),
        }

    # -- evaluation ------------------------------------------------------------
    def evaluate(self, counterweights) -> dict:
        """Series over every step of the scene with the counterweights added.

        Parameters
        ----------
        counterweights : iterable of Counterweight

        Returns
        -------
        dict
            ``"force"`` (N, 2): shaking force (what the moving links exert on
            the ground, inertia as the only effect); ``"moment"`` (N,): shaking
            moment about the global origin; ``"driving"``: ``{joint: (N,)}``
            driver efforts with the scene's own effects.  NaN at steps that
            are not ``ok``.
        """
        Y = self._series(self.parameters(counterweights))
        return {
            "force": np.stack([Y[0], Y[1]], axis=1),
            "moment": Y[2],
            "driving": {k: Y[3 + i] for i, k in enumerate(self.drivers)},
        }

    def rms(self, counterweights) -> dict:
        """RMS over the cycle (the :attr:`counted` steps) of the series of :meth:`evaluate`.

        Returns
        -------
        dict
            ``force``: ``sqrt(mean |F|^2)``; ``moment``: ``sqrt(mean M^2)``;
            ``driving``: ``sqrt(mean over steps of the sum over drivers of
            effort^2)``.
        """
        return self._rms_of(self._series(self.parameters(counterweights), ok_only=True))

    def mean_square_factors(self, links) -> dict:
        """Each term's mean square over the cycle as a quadratic form in the counterweights.

        Parameters
        ----------
        links : sequence of str
            The links that carry the counterweights, each once.

        Returns
        -------
        dict
            ``{term: R}`` for the terms of :data:`TERMS` (``force``,
            ``moment``, ``driving``): ``R`` is triangular with ``4 n + 1``
            columns, and ``|R @ x|^2`` is the mean over the cycle (the
            :attr:`counted` steps) of the term's square (``|F|^2``, ``M^2``,
            the sum of the efforts' squares) with counterweights whose
            :meth:`parameters` on ``links`` (in that order) are ``p``, where
            ``x = (p, 1)``.  So :meth:`rms` is ``|R @ x|`` at a cost that
            does not depend on the number of steps: the QR factorisation of
            ``[B, Y0] / sqrt(N_c)`` over the ``N_c`` counted steps is done
            once here.
        """
        idx = [self.links.index(n) for n in links]
        cols = np.concatenate([np.arange(4 * i, 4 * i + 4) for i in idx])
        B = self._Bok[:, :, cols]  # (3 + D, Nok, 4 n)
        Y0 = self._Y0ok
        nok = max(1, Y0.shape[1])
        factors = {}
        for term, sl in TERMS.items():
            A = np.concatenate([B[sl], Y0[sl][:, :, None]], axis=2).reshape(-1, B.shape[2] + 1)
            factors[term] = np.linalg.qr(A / math.sqrt(nok), mode="r")
        return factors
