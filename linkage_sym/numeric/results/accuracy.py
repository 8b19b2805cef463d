"""How many digits a step carries: an accuracy estimate from the condition numbers.

Every ``ok`` step of a result gets four relative accuracies (``Analysis.accuracy``;
``"accuracy"`` in the result JSON, an extension of the format):

==============  ===============================================================
``position``    joint, traced-point and centre-of-mass coordinates over the
                mechanism's size ``L``; link rotations in radians
``velocity``    point velocities over the step's largest point speed ``V``
                (``|omega| L`` counted among them); ``omega`` times ``L / V``
``acceleration`` likewise with accelerations
``forces``      reactions, efforts (torques over ``L``) and frame loads over the
                step's largest reaction or effort (moments over ``L``, and the
                frame moment about the origin over ``L`` times the mechanism's
                largest distance from the origin in sizes, at least 1)
==============  ===============================================================

Each is a bound on the error of every such value at that step, from the machine
epsilon ``eps`` and the dimensionless condition number ``K`` of the full constraint
Jacobian (poses of all links; the one the singularity screen uses)::

    position      C_POSITION     eps K
    velocity      C_VELOCITY     eps K^2
    acceleration  C_ACCELERATION eps K^2
    forces        C_FORCES       eps K (K + a)      a: the superposition's amplification

Why ``K^2`` for rates: the positions carry ``eps K``, and near a dead centre the
rates' sensitivity to the configuration grows like ``K`` too (the computed
configuration is an exact one of a mechanism off by ``eps`` in its lengths; the
rates of that one differ by ``eps K^2`` relative).  Measured against 50-digit references
(``tests/numeric/test_accuracy.py``: every step of the shipped examples, four-bars from 0.1 to
1e-10 degrees of a dead centre with ``K`` up to 7e6, the change-point four-bar, random
crank-rockers, slider-cranks and class-III triads with masses, for the numeric solver
with both force methods and the compiled symbolic runtime) no error exceeded 0.54 of its
estimate (typically 0.05 to 0.3), and on steps with ``K <= 100`` the estimate was at most
4100 times the error (typically 30 to 1000).

``K`` is exact (an SVD) where the solver computed it: where a group's cheap indicator
fell below the screen, or everywhere with ``exact_condition``.  Elsewhere it comes from
the indicators: ``K ~ G / indicator`` with ``G`` the largest ``K * indicator`` at
:data:`CALIBRATION_STEPS` steps spread over the scene's own sweep where ``K`` is computed
exactly for this purpose (the product varies by less than a factor 2 along the shipped
examples' sweeps), times :data:`SAFETY`.  A plan computes ``G`` once, on its first run,
and uses it for every run (so a sweep solved in chunks gets the estimate of the whole).
The compiled symbolic runtime uses the same pose Jacobian (built from its result's link
rotations and origins), calibrated on its blocks' Hadamard ratios.
"""

from __future__ import annotations

import numpy as np

EPS = float(np.finfo(float).eps)
C_POSITION = 1.0
C_VELOCITY = 0.075
C_ACCELERATION = 0.25
C_FORCES = 0.35
SAFETY = 1.5
"""Factor on the calibrated indicator-to-condition ratio at steps without an exact ``K``."""
CALIBRATION_STEPS = 16
FIELDS = ("position", "velocity", "acceleration", "forces")


def calibration_steps(n_steps: int) -> np.ndarray:
    """The steps of a sweep of ``n_steps`` where ``K`` is computed to calibrate ``G``.

    Increasing and distinct (``np.unique`` of the sorted steps, without it: its check for a
    masked array imports ``numpy.ma``, a sixth of a kinematics-only ``analyze``'s start-up).
    """
    steps = np.linspace(0, n_steps - 1, min(CALIBRATION_STEPS, n_steps)).astype(int)
    first = np.ones(steps.size, dtype=bool)
    first[1:] = steps[1:] != steps[:-1]
    return steps[first]


def calibration(K, ok, indicator=None) -> float | None:
    """``G``: the largest ``K * indicator`` (``K`` where no group has an indicator) over the
    ``ok`` entries; ``None`` if there is none."""
    K = np.asarray(K, float)
    ind = np.full(len(K), np.inf) if indicator is None else np.asarray(indicator, float)
    use = np.asarray(ok, bool) & np.isfinite(K)
    if not use.any():
        return None
    with np.errstate(invalid="ignore"):
        prod = np.where(np.isfinite(ind[use]), K[use] * ind[use], K[use])
    return float(np.max(prod))


def condition_estimate(condition, ok, indicator=None, G=None) -> np.ndarray:
    """``K`` at every ``ok`` step (NaN elsewhere): exact where ``condition`` has it, else
    ``SAFETY * G / indicator`` (``SAFETY * G`` where no group has an indicator).

    ``G`` comes from :func:`calibration` on the plan's own sweep at
    :func:`calibration_steps` (computed once per plan, so every run and every chunk of a
    sweep gets the same estimate); ``None`` (no ``ok`` step to calibrate on) leaves the
    other steps' ``K`` unknown: infinite.  Indicators are at most 1 (sines, ratios,
    reciprocal condition numbers); an infinite one (no indicator) counts as 1.
    """
    g = SAFETY * (np.inf if G is None else G)
    if indicator is None:
        est = np.full(len(condition), g)
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            est = g / np.minimum(indicator, 1.0)
    K = np.where(np.isnan(condition), est, condition)
    if not ok.all():
        K[~ok] = np.nan
    return K


def accuracy(K, ok, stages, amplification=None, unit=EPS, floor=0.0) -> dict:
    """The four relative accuracies (arrays (N,), NaN where not ``ok`` or not computed).

    ``K`` from :func:`condition_estimate` (NaN where not ``ok``); ``unit``: the precision
    of the arithmetic (float64's ``eps``, or ``10^-digits``); ``floor``: an error every
    value carries anyway (rounding an mpmath value to float64), a number or
    ``{field: number or array}``.
    """
    K = np.maximum(K, 1.0)  # NaN stays NaN
    if not ok.all():
        K[~ok] = np.nan

    def fl(name, v):
        f = floor.get(name, 0.0) if isinstance(floor, dict) else floor
        if np.any(f):
            v += f
        return v

    out = {"position": fl("position", K * (C_POSITION * unit))}
    K2 = K * K
    if "velocity" in stages:
        out["velocity"] = fl("velocity", K2 * (C_VELOCITY * unit))
    if "acceleration" in stages:
        out["acceleration"] = fl("acceleration", K2 * (C_ACCELERATION * unit))
    if "forces" in stages:
        f = K2 if amplification is None else K * (K + np.nan_to_num(amplification, nan=0.0))
        out["forces"] = fl("forces", f * (C_FORCES * unit))
    return out


def magnitude_floor(res, L: float, unit: float = EPS) -> np.ndarray:
    """The rounding each step's positions carry in their own representation: ``unit``
    times the largest of 1, its coordinates over the mechanism's size ``L`` and its
    rotations (rad).  A coordinate far from the origin, or a gear's rotation after several
    turns (20 rad: an ulp is 3.6e-15), is no more exact than that, however well
    conditioned the step; the position estimate adds it."""
    big = np.ones(len(res.status))
    for jk in res.joints.values():  # fmax skips the NaN of steps without a solution
        p = np.abs(np.asarray(jk.position))
        big = np.fmax(big, np.fmax(p[:, 0], p[:, 1]) / L)
    for lk in res.links.values():
        big = np.fmax(big, np.abs(np.asarray(lk.rotation)))
    return unit * big


def condition_of(acc: dict) -> np.ndarray:
    """The ``K`` an :func:`accuracy` result was computed from (inverse of its position entry)."""
    return acc["position"] / (C_POSITION * EPS)


def worst(acc: dict, ok) -> dict:
    """``{field: (step, value)}`` of the largest estimate of each field over ``ok`` steps."""
    out = {}
    for name, v in acc.items():
        v = np.where(ok, v, np.nan)
        if np.isfinite(v).any():
            i = int(np.nanargmax(v))
            out[name] = (i, float(v[i]))
    return out


def amplification_of(forces) -> np.ndarray | None:
    """The largest superposition amplification of any group at each step, or None."""
    if forces is None:
        return None
    amps = [g.amplification for g in forces.groups if g.amplification is not None]
    if not amps:
        return None
    return np.fmax.reduce([np.nan_to_num(a, nan=0.0) for a in amps])
