"""Bookkeeping of a sweep that both runtimes share (NumPy only).

The numeric plan (:mod:`linkage_sym.numeric.plan`) and the compiled symbolic
mechanism (:mod:`linkage_sym.codegen.runtime`) solve a sweep by different
methods; what a step's status means, how it is worded, and the path they both
follow are one thing, kept here:

* the scene's sweep and the stages its outputs call for;
* the solving path from the assembly configuration through the steps, and the
  unwrapping of angles along it;
* the singularity threshold of the scene format and its message;
* the warnings of a finished run (``ok`` steps that lose digits, force
  superpositions that cancel).

The Newton continuation policy both runtimes use lives beside it, in
:mod:`linkage_sym.numeric.continuation`.
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.numeric.result import OK, Analysis
from linkage_sym.numeric.superposition import AMPLIFICATION_LIMIT

SINGULAR_COND = 1e10
"""Spec: a step is singular when the dimensionless condition number exceeds this."""
SCREEN = 1e-3
"""A group indicator below this triggers the exact condition number at that step."""
WARN_COND = 1e6
"""An ``ok`` step whose computed condition number exceeds this is named in ``Analysis.warnings``."""
MAX_ANGLE_STEP = math.radians(2.0)
"""Largest driver increment (R drivers) between two points of the solving path."""
MAX_SLIDE_STEP = 0.02
"""Largest driver increment (P drivers) along the path, as a fraction of the mechanism size."""


def singular_message(cond: float) -> str:
    """The message of a ``singular`` step (both runtimes word it alike)."""
    return (
        f"singular position: condition number {cond:.3g} of the dimensionless constraint "
        f"Jacobian exceeds {SINGULAR_COND:.0e}; velocities and accelerations have no unique "
        "solution"
    )


def _unwrap(th: np.ndarray) -> np.ndarray:
    """Remove the 2 pi jumps of an angle sequence (as ``np.unwrap``, with a fast exit).

    Consecutive path points are at most a few degrees apart, so a jump of more
    than half a turn can only be a wrap of ``atan2``.
    """
    d = np.diff(th)
    jump = np.abs(d) > math.pi
    if not jump.any():
        return th
    k = np.zeros_like(th)
    k[1:] = np.cumsum(np.where(jump, np.round(d / (2 * math.pi)), 0.0))
    return th - 2 * math.pi * k


def solving_path(scene: Scene, names, q0: dict, L: float, Q: np.ndarray):
    """Driver values along the solving path (see the module docstring).

    Parameters
    ----------
    names : list of str
        The driven joints, in the order of the rows of ``Q``.
    q0 : dict
        Each driver's value in the assembly configuration.
    L : float
        Size of the mechanism (a slide's largest increment is a fraction of it).
    Q : ndarray (D, N)
        The steps' driver values.

    Returns
    -------
    P : ndarray (D, K)
        The assembly configuration, intermediate points up to the first step,
        then the steps, refined where consecutive steps are far apart.
    out : ndarray (N,)
        The path index of each step.
    n_ref : int
        Path intervals between consecutive steps (1: the steps are contiguous).
    """
    q0 = np.array([q0[n] for n in names])
    lim = np.array(
        [MAX_ANGLE_STEP if scene.joint(n).type == "R" else MAX_SLIDE_STEP * L for n in names]
    )
    n_pre = max(1, int(math.ceil(np.max(np.abs(Q[:, 0] - q0) / lim))))
    pre = q0[:, None] + (Q[:, :1] - q0[:, None]) * (np.arange(n_pre) / n_pre)[None, :]
    N = Q.shape[1]
    n_ref = max(1, int(math.ceil(np.max(np.abs(np.diff(Q, axis=1)) / lim[:, None])))) if N > 1 else 1
    if n_ref > 1:
        f = np.arange(n_ref) / n_ref
        seg = Q[:, :-1, None] + np.diff(Q, axis=1)[:, :, None] * f
        body = np.concatenate([seg.reshape(len(names), -1), Q[:, -1:]], axis=1)
    else:
        body = Q
    return np.concatenate([pre, body], axis=1), n_pre + np.arange(N) * n_ref, n_ref


def scene_sweep(scene: Scene):
    """Driver values ``(q, qd, qdd)`` of a scene's sweep: dicts of (N,) arrays."""
    q, qd, qdd = {}, {}, {}
    for d in scene.drivers:
        q[d.joint] = np.linspace(d.start, d.stop, d.steps)
        qd[d.joint] = np.full(d.steps, float(d.speed))
        qdd[d.joint] = np.full(d.steps, float(d.acceleration))
    return q, qd, qdd


def needed_stages(scene: Scene) -> tuple[str, ...]:
    """The stages a scene's outputs and effects call for, in order.

    Kinematics output needs positions, velocities and accelerations (so does
    the ``instant_centres`` extension: velocities, and accelerations for the
    polygons); forces need velocities and accelerations only when inertia acts
    on a link with mass.
    """
    outs = set(scene.outputs)
    forces = bool(outs & {"reactions", "driving", "frame"})
    inertia = scene.effects.inertia and any(
        link.mass > 0 or link.inertia > 0 for link in scene.links
    )
    stages = ["position"]
    if "kinematics" in outs or "instant_centres" in outs or (forces and inertia):
        stages += ["velocity", "acceleration"]
    if forces:
        stages.append("forces")
    return tuple(stages)


def _steps_text(idx) -> str:
    idx = [int(i) for i in idx]
    return ", ".join(map(str, idx[:5])) + (f" and {len(idx) - 5} more" if len(idx) > 5 else "")


def run_warnings(res: Analysis) -> list[str]:
    """What a caller must know that no step's status says: ``ok`` steps that lose digits.

    * ``ok`` steps whose computed condition number exceeds :data:`WARN_COND`
      (near a dead centre or a limit position): rates there carry about
      ``log10(cond)`` fewer significant digits than positions.
    * Groups whose force superposition still cancels beyond
      ``AMPLIFICATION_LIMIT`` with the best disconnection available.
    """
    out = []
    ok = res.status == OK
    with np.errstate(invalid="ignore"):
        ill = np.flatnonzero(ok & (res.condition > WARN_COND))
    if len(ill):
        worst = int(ill[np.argmax(res.condition[ill])])
        out.append(
            f"{len(ill)} ok step(s) have a condition number above {WARN_COND:.0e} (steps "
            f"{_steps_text(ill)}; largest {res.condition[worst]:.3g} at step {worst}): their "
            f"velocities and accelerations carry about {np.log10(res.condition[worst]):.0f} "
            "fewer significant digits than their positions"
        )
    if res.forces is not None:
        for g in res.forces.groups:
            if g.amplification is None:
                continue
            with np.errstate(invalid="ignore"):
                bad = np.flatnonzero(ok & (g.amplification > AMPLIFICATION_LIMIT))
            if len(bad):
                worst = int(bad[np.argmax(g.amplification[bad])])
                out.append(
                    f"group ({', '.join(g.links)}): the superposition cancels at {len(bad)} "
                    f"step(s) (steps {_steps_text(bad)}; amplification up to "
                    f"{g.amplification[worst]:.3g} at step {worst}) with every disconnection: "
                    f"its reactions lose about {np.log10(g.amplification[worst]):.0f} digits there"
                )
    return out
