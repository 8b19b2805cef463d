"""Joint friction in the mpmath backend (``--precision``; contract part two).

:class:`~linkage_sym.codegen.precision.PreciseMechanism` solves each step's friction with
the evaluator's friction solve (:mod:`linkage_sym.codegen.friction`) in mpmath
(:class:`~linkage_sym.codegen.mp_numbers.MpOps`: Newton carried to the working
precision); :func:`friction_record` gives a step's friction values by name (``mpf``),
and :func:`friction_targets` the arrays of a result they are rounded into.  The steps'
statuses, self-locking ones too, are the float64 run's, as the precision's other
statuses are.
"""

from __future__ import annotations

import mpmath as mp

from linkage_sym.structure.parameters import ident

__all__ = ["friction_record", "friction_targets"]


def friction_record(pm, fric, ideal, driving) -> dict:
    """A step's friction values (``mpf``): ``"friction"`` (every joint with a ``friction``
    field; 0 where it does not act), ``"friction_power"``, ``"driving_ideal"`` (the efforts
    with the friction left out: the forces ``ideal``) and, with one driver,
    ``"efficiency"`` (NaN where not defined); ``fric`` the step's
    :class:`~linkage_sym.codegen.friction.FrictionSolution` (``None``: none acts),
    ``driving`` the efforts with it."""
    scene = pm.scene
    mu = {} if fric is None else fric.mu
    fidx = pm.art.force_index()
    out = {"friction": {j.name: mu.get(j.name, mp.mpf(0)) for j in scene.joints
                        if j.friction is not None},
           "friction_power": mp.mpf(0) if fric is None else fric.power(pm.friction_ops()),
           "driving_ideal": {d.joint: ideal[fidx[("tau_" if d.kind == "R" else "f_")
                                                 + ident(d.joint)]] for d in scene.drivers}}
    if len(scene.drivers) == 1:
        (d,) = scene.drivers
        e, e0 = driving[d.joint], out["driving_ideal"][d.joint]
        same = e != 0 and e0 != 0 and mp.sign(e) == mp.sign(e0)
        out["efficiency"] = e0 / e if same else mp.nan
    return out


def friction_targets(fo) -> list:
    """``(array, its value in a step's record, needs rates)`` of the friction's fields of
    the result's forces ``fo`` (none without ``effects.friction``)."""
    if fo.friction is None:
        return []
    out = [(arr, lambda r, n=name: r["friction"][n], True) for name, arr in fo.friction.items()]
    out.append((fo.friction_power, lambda r: r["friction_power"], True))
    out += [(arr, lambda r, n=name: r["driving_ideal"][n], True)
            for name, arr in fo.driving_ideal.items()]
    if fo.efficiency is not None:
        out.append((fo.efficiency, lambda r: r["efficiency"], True))
    return out
