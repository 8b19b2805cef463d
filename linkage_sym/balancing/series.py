"""Shaking force and moment over a sweep, from the lambdified module expressions.

The assembled expressions (:mod:`~.assembly`: the shaking force
``-sum m_j a_sj`` of eq. 3 and the moment ``-sum M_i D_i`` of eq. 12) are
lambdified once, with ``cse``, into one NumPy function; the pins' positions
and accelerations come from the numeric kinematics of the scene's sweep (no
force solver).  The kinetostatic solver's frame force and moment are the
independent check (``tests/balancing/test_balancing.py``).

Examples
--------
>>> from linkage_sym.examples import load_example
>>> scene = load_example("crank_rocker")
>>> s = module_series(scene)
>>> s.force.shape, s.moment.shape
((361, 2), (361,))
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import sympy as sp

from linkage_sym.balancing.assembly import ShakingMoment, shaking_moment
from linkage_sym.balancing.pins import BalanceModel
from linkage_sym.model import Effects, Scene


@dataclass
class BalanceSeries:
    """Shaking force (N, 2) and moment about the origin (N,) over a sweep.

    ``q`` holds the first driver's values, ``status`` each step's status;
    force and moment are NaN where the status is not ``ok``.
    """

    label: str
    q: np.ndarray
    status: np.ndarray
    force: np.ndarray
    moment: np.ndarray

    def to_dict(self) -> dict:
        ok = self.status == "ok"
        return {
            "label": self.label,
            "driver": self.q.tolist(),
            "status": self.status.tolist(),
            "shaking_force": [[float(x), float(y)] if g else None for (x, y), g in zip(self.force, ok)],
            "shaking_moment": [float(m) if g else None for m, g in zip(self.moment, ok)],
        }


class ModuleFunctions:
    """One lambdified function ``f(POS, ACC, PAR) -> (F_x, F_y, M_0)``.

    Argument order (fixed, also in ``f.__doc__``): ``POS`` the ``x, y`` of
    every pin in :attr:`position_symbols` order, ``ACC`` the ``x'', y''`` of
    every moving pin (:attr:`acceleration_symbols`), ``PAR`` the link
    parameters (:attr:`parameter_symbols`); each entry a scalar or an array
    over the steps.
    """

    def __init__(self, sm: ShakingMoment):
        self.model = sm.model
        m = sm.model
        pos, acc = [], []
        for name in m.pins:
            x, y, ax, ay = m.pin_symbols(name)
            pos += [s for s in (x, y) if isinstance(s, sp.Symbol)]
            acc += [s for s in (ax, ay) if isinstance(s, sp.Symbol)]
        exprs = [sm.force[0], sm.force[1], sm.explicit]
        free = set().union(*(e.free_symbols for e in exprs))
        par = sorted((s for s in free if s not in set(pos) | set(acc)), key=lambda s: s.name)
        self.position_symbols, self.acceleration_symbols, self.parameter_symbols = pos, acc, par
        self.function = sp.lambdify([pos, acc, par], exprs, modules="numpy", cse=True)
        self.function.__doc__ = (
            "f(POS, ACC, PAR) -> [F_x, F_y, M_0]\n"
            f"POS = {[s.name for s in pos]}\nACC = {[s.name for s in acc]}\nPAR = {[s.name for s in par]}"
        )

    def evaluate(self, analysis, model: BalanceModel) -> tuple:
        """Shaking force (N, 2) and moment (N,) for the motion in ``analysis``
        and the parameter values of ``model``'s scene (same topology)."""
        values = model.values()
        n = analysis.n_steps
        pos, acc = [], []
        for name in self.model.pins:
            P = self.model.pins[name]
            x, y, ax, ay = self.model.pin_symbols(name)
            if P.ground:
                xy = [np.full(n, P.at[0]), np.full(n, P.at[1])]
            else:
                jk = analysis.joints[P.joints[0]]
                xy = [jk.position[:, 0], jk.position[:, 1]]
                acc += [jk.acceleration[:, 0], jk.acceleration[:, 1]]
            pos += [c for s, c in zip((x, y), xy) if isinstance(s, sp.Symbol)]
        par = [values[s.name] for s in self.parameter_symbols]
        fx, fy, m0 = (np.broadcast_to(np.asarray(v, float), (n,)) for v in self.function(pos, acc, par))
        force = np.stack([fx, fy], axis=-1)
        ok = analysis.ok
        force = np.where(ok[:, None], force, np.nan)
        return force, np.where(ok, m0, np.nan)


def kinematics(scene: Scene):
    """The scene's sweep solved for kinematics only (numeric dyad solver)."""
    from linkage_sym.numeric.plan import compile_plan

    kin = dataclasses.replace(scene, outputs=("kinematics",),
                              effects=Effects(inertia=True, gravity=None, loads=False))
    return compile_plan(kin).run()


def solver_series(scene: Scene, label: str = "") -> BalanceSeries:
    """Shaking force and moment at every step of ``scene``'s sweep, from the force solver.

    The frame force and moment of the numeric kinetostatics with inertia as
    the only effect (spec: then they are the shaking force and moment).  It
    needs no module, so it serves scenes with prismatic joints too, and it is
    the independent check of :func:`module_series`.
    """
    from linkage_sym.numeric.plan import compile_plan

    sh = dataclasses.replace(scene, outputs=("frame",),
                             effects=Effects(inertia=True, gravity=None, loads=False))
    res = compile_plan(sh).run()
    d0 = scene.drivers[0].joint
    return BalanceSeries(label or scene.name, np.asarray(res.drivers[d0]["q"]),
                         np.asarray(res.status), res.forces.frame_force, res.forces.frame_moment)


def module_series(scene: Scene, sm: ShakingMoment | None = None, functions: ModuleFunctions | None = None,
                  analysis=None, label: str = "") -> BalanceSeries:
    """Shaking force and moment at every step of ``scene``'s sweep, from the modules."""
    model = BalanceModel(scene)
    if functions is None:
        functions = ModuleFunctions(sm or shaking_moment(scene, model))
    analysis = analysis if analysis is not None else kinematics(scene)
    force, moment = functions.evaluate(analysis, model)
    d0 = scene.drivers[0].joint
    return BalanceSeries(label or scene.name, np.asarray(analysis.drivers[d0]["q"]),
                         np.asarray(analysis.status), force, moment)
