"""A path-generation design as a scene, and its check by the solver (the defects by
:func:`linkage_sym.synthesis.defects.check_motion`, the one checker of the syntheses).

The scene puts the design at the first target's crank angle; its driver turns
the crank through the targets' crank angles, first to last; the coupler point
is the traced point ``P``.  :func:`check` analyses that scene with the solver
(``linkage_sym.compile_plan``) -- not with the synthesis's closed forms -- and
measures what a path design is judged by: the distance of ``P`` from each
target at its crank angle, the assembly mode at every step between the first
and the last target (a *branch defect* if it changes), whether the solver
solves every step (a dead centre or a position beyond reach otherwise), whether
the crank angles are in order (an *order defect* if the crank must turn back),
the minimum transmission angle over that motion and the Grashof class.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.synthesis.path_model import pins

CHECK_STEPS = 721
"""Crank angles at which the solver checks the motion from the first to the last target."""


def scene_of(z, sigma, thetas, name="path-generator", steps=181, speed=1.0) -> dict:
    """The design ``z`` (see :mod:`~linkage_sym.synthesis.path_model`) as a scene at ``thetas[0]``."""
    t = np.array([thetas[0]])
    B, C, P, _ = (v[0, 0] for v in pins(np.asarray(z)[None, :], t[None, :], sigma))
    xy = lambda w: [float(w.real), float(w.imag)]  # noqa: E731
    joints = [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [float(z[0]), float(z[1])]},
        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": xy(C)},
        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [float(z[2]), float(z[3])]},
    ]
    drv = {"joint": "A", "toward": "B", "start_deg": math.degrees(thetas[0]),
           "stop_deg": math.degrees(thetas[-1]), "steps": steps, "speed": speed,
           "acceleration": 0.0}
    return {"name": name, "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
            "joints": joints, "points": [{"name": "P", "link": "coupler", "at": xy(P)}],
            "drivers": [drv], "outputs": ["kinematics"]}


@dataclass
class Check:
    """What the solver measured of a path design (lengths in m, angles in degrees).

    Attributes
    ----------
    error : float
        Largest distance of the coupler point from a target at its crank angle.
    errors : ndarray
        Each target's distance.
    coupler : float
        The coupler's length ``|BC|`` (the scale of the exactness checks).
    solved : bool
        Every step from the first to the last target solved (no dead centre, none beyond reach).
    branch : bool
        One assembly mode at every step (no branch defect).
    order : bool
        The crank angles monotone within one turn (no order defect).
    gamma_min_deg : float
        Minimum transmission angle over that motion.
    grashof : str
        The Grashof class.
    full_turn : bool
        The crank turns fully.
    """

    error: float
    errors: np.ndarray
    coupler: float
    solved: bool
    branch: bool
    order: bool
    gamma_min_deg: float
    grashof: str
    full_turn: bool

    @property
    def defects(self) -> str:
        """``""`` or the defects' names, comma-separated."""
        names = [n for n, ok in (("dead-centre", self.solved), ("branch", self.branch),
                                 ("order", self.order)) if not ok]
        return ",".join(names)


def check(scene_dict, targets, thetas) -> Check:
    """Analyse the scene by the solver against the targets at the crank angles ``thetas`` (rad).

    The defects are :func:`linkage_sym.synthesis.defects.check_motion`'s, the crank angles
    taken as the motion itself (``unwrapped``) and the targets as a fit (no precision
    points: ``tol=None``); a four-bar or a slider-crank scene.
    """
    from linkage_sym.synthesis.defects import check_motion

    thetas = np.asarray(thetas, dtype=float)
    T = np.asarray(targets, dtype=float)
    span = abs(float(thetas[-1] - thetas[0])) / (2 * np.pi)
    m = check_motion(scene_dict, thetas, point="P", targets=T, tol=None,
                     steps_per_turn=max(2, int(math.ceil((CHECK_STEPS - 1) / max(span, 1e-12)))),
                     unwrapped=True, unit="rad")
    errors = np.array(m.errors, dtype=float)
    return Check(float(np.max(errors)), errors, m.coupler, m.solved and not m.dead_centre,
                 m.solved and not m.branch, not m.order,
                 float(np.degrees(m.gamma_min)) if m.solved else 0.0, m.grashof, m.full_turn)


def curves(scene_dict, thetas, samples=361):
    """The coupler point's curve by the solver: over a full turn from the first target (NaN
    where the solver solves no configuration), from the first target to the last, and the
    joints and ``P`` at the first target.

    Returns
    -------
    full, motion : ndarray (k, 2)
    joints : dict of str to (float, float)
        The joints' positions; a slider-crank's also ``guide``: its unit direction.
    """
    import linkage_sym

    plan = linkage_sym.compile_plan(linkage_sym.load_scene(scene_dict))
    out = []
    for q in (thetas[0] + np.linspace(0.0, 2 * np.pi, samples),
              np.linspace(thetas[0], thetas[-1], samples)):
        res = plan.run(q={"A": q}, qd={"A": np.ones(len(q))}, qdd={"A": np.zeros(len(q))})
        P = np.array(res.points["P"].position, dtype=float)
        P[res.status != "ok"] = np.nan
        out.append(P)
    joints = {j["name"]: tuple(j["at"]) for j in scene_dict["joints"]}
    joints["P"] = tuple(scene_dict["points"][0]["at"])
    for j in scene_dict["joints"]:
        if j["name"] == "C_guide":  # a slider-crank: the guide's direction
            joints["guide"] = (math.cos(math.radians(j["axis_deg"])),
                               math.sin(math.radians(j["axis_deg"])))
    return out[0], out[1], joints
