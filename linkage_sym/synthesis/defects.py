"""Branch, order and dead-centre defects of a crank-driven four-bar, found by the solver.

A synthesis meets its targets (coupler poses, output angles, path points) at
given crank angles, each target on its own; whether one linkage, driven by
its crank, actually passes through them all is another question.  This
module asks the numeric solver (:func:`linkage_sym.compile_plan`), not the
synthesis that made the design:

* the scene is assembled in target 1; the solver turns the crank from there
  through the other targets' crank angles, following the assembly mode
  continuously as it always does;
* **order defect**: turning the crank one way (either sense), the targets'
  crank angles do not come in the given order within one turn;
* **dead centre**: between the first and the last target the crank meets a
  position it cannot drive through (coupler and rocker in line: the solver
  reports steps ``unassemblable`` or ``singular``) -- the linkage would
  have to be driven through by its rocker, a branch change of the crank's
  motion;
* **branch defect**: at a target's crank angle the solver's linkage misses
  the target while the same linkage assembled in the other assembly mode
  (``C`` mirrored in the line ``BD``) meets it: the target lies on the
  other branch (or circuit) and the crank cannot bring the linkage there;
* **circuit defect**: a branch defect of a Grashof four-bar whose target lies
  on the other of its two circuits (Chase and Mirth, "Circuits and branches
  of single-degree-of-freedom planar linkages", 1993): no driver, not only
  the crank, brings the linkage there without taking it apart.  The circuit
  is the sign of the triangle of the link opposite the shortest, the next
  link and the diagonal to the shortest link's far joint -- constant on each
  circuit, as that triangle never flattens while the shortest link turns fully;
* a target missed in both modes is reported as *missed* (a wrong design).

Also the Grashof class (:func:`linkage_sym.structure.grashof.classify`) and
the minimum transmission angle (``min(gamma, pi - gamma)`` of the angle at
``C`` between coupler and rocker) over the steps of the motion from the
first target to the last.

The scene is a four-bar as :mod:`~linkage_sym.synthesis.builders` writes
them: joints ``A`` (ground-crank, driven), ``B``, ``C``, ``D``, links
``crank``, ``coupler``, ``rocker``; its own sweep is not used.

Examples
--------
A crank-rocker's own coupler-point positions at four crank angles:

>>> import math
>>> from linkage_sym.synthesis.builders import fourbar
>>> def scene_at(deg):
...     return fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=deg, coupler_point=(1.0, 0.5)).scene
>>> targets = [scene_at(deg)["points"][0]["at"] for deg in (30, 80, 150, 220)]
>>> r = check_motion(scene_at(30), [30, 80, 150, 220], point="P", targets=targets)
>>> r.grashof, r.branch, r.order, r.dead_centre, r.defect_free
('crank-rocker', False, False, False, True)
>>> max(r.errors) < 1e-12
True
>>> swapped = [targets[0], targets[2], targets[1], targets[3]]
>>> r = check_motion(scene_at(30), [30, 150, 80, 220], point="P", targets=swapped)
>>> r.order, r.defect_free
(True, False)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

STEPS_PER_TURN = 720
"""Solver steps per turn of the crank between the targets (the targets' own crank
angles are always steps): a dead centre between targets shows as unassemblable
or singular steps, and the transmission angle's minimum is taken over them."""

TOLERANCE = 1e-9
"""A target is met when the solver's point is within this fraction of the coupler
length of it (and a link's rotation within this many radians)."""


@dataclass(frozen=True)
class MotionCheck:
    """What the solver finds when the crank drives a four-bar through its targets.

    Attributes
    ----------
    grashof : str
        The Grashof class (``crank-rocker``, ``double-crank``, ``double-rocker``,
        ``triple-rocker``, ``change point``).
    branch : bool
        A target is met only in the other assembly mode (see the module docstring).
    order : bool
        The crank meets the targets out of order, turning either way.
    dead_centre : bool
        The crank's motion from the first target to the last passes a dead centre.
    circuit : bool
        A target met only in the other assembly mode lies on the other circuit of
        a Grashof four-bar (see the module docstring); False for one that is not
        Grashof (it has one circuit).
    missed : tuple of int
        Targets (0-based) met in neither assembly mode at their crank angle.
    sense : int
        +1 when the crank turns counter-clockwise from target 1 to the last, -1
        clockwise (+1 with an order defect).
    crank_angles : tuple of float
        The targets' crank angles (rad), unwrapped along the motion.
    errors : tuple of float
        Per target: the solver's distance from the target point (m, when a point
        is checked) plus its rotation error times the coupler length (when
        rotations are checked); ``inf`` where the step did not solve.
    gamma_min : float
        Minimum transmission angle (rad, 0..pi/2) over the solved steps of the
        motion.
    notes : tuple of str
        The defects in words.
    """

    grashof: str
    branch: bool
    order: bool
    dead_centre: bool
    circuit: bool
    missed: tuple
    sense: int
    crank_angles: tuple
    errors: tuple
    gamma_min: float
    notes: tuple

    @property
    def defect_free(self) -> bool:
        """True when every target is met, in order, on one branch, without a dead centre."""
        return not (self.branch or self.order or self.dead_centre or self.missed)


def _joint(scene: dict, name: str) -> np.ndarray:
    for j in scene["joints"]:
        if j["name"] == name:
            return np.array(j["at"], dtype=float)
    raise ValueError(f"the four-bar scene has no joint {name!r} (joints A, B, C, D are expected)")


def mirrored(scene: dict) -> dict:
    """The same four-bar assembled in the other mode: ``C`` reflected in the line ``BD``,
    the coupler's traced points turned with it about ``B`` (the coupler stays rigid).

    Examples
    --------
    >>> s = {"joints": [{"name": "A", "at": [0, 0]}, {"name": "B", "at": [0, 1]},
    ...                 {"name": "C", "at": [2, 2]}, {"name": "D", "at": [2, 0]}],
    ...      "points": [{"name": "P", "link": "coupler", "at": [2, 2]}]}
    >>> m = mirrored(s)
    >>> [round(v, 12) for v in m["joints"][2]["at"]], [round(v, 12) for v in m["points"][0]["at"]]
    ([0.4, -1.2], [0.4, -1.2])
    """
    B, C, D = _joint(scene, "B"), _joint(scene, "C"), _joint(scene, "D")
    u = (D - B) / np.linalg.norm(D - B)
    r = C - B
    C2 = B + 2 * (r @ u) * u - r
    turn = math.atan2(r[0] * (C2 - B)[1] - r[1] * (C2 - B)[0], r @ (C2 - B))
    rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])

    def moved(p):
        return [float(v) for v in B + rot @ (np.asarray(p, dtype=float) - B)]

    out = dict(scene)
    out["joints"] = [dict(j, at=[float(v) for v in C2]) if j["name"] == "C" else dict(j)
                     for j in scene["joints"]]
    if "points" in scene:
        out["points"] = [dict(p, at=moved(p["at"])) if p["link"] == "coupler" else dict(p)
                         for p in scene["points"]]
    return out


def _turn(scene: dict, other: dict, link: str) -> float:
    """How much farther ``link`` is turned in ``other``'s assembly than in ``scene``'s (rad)."""
    ends = {"coupler": "BC", "rocker": "DC"}.get(link)
    if ends is None:
        return 0.0
    u = _joint(scene, ends[1]) - _joint(scene, ends[0])
    v = _joint(other, ends[1]) - _joint(other, ends[0])
    return math.atan2(u[0] * v[1] - u[1] * v[0], u @ v)


def _unwrap(crank_deg) -> tuple[int, list, bool]:
    """``(sense, angles, order_defect)``: the targets' crank angles (rad) unwrapped from
    the first along the sense in which they come in order (counter-clockwise when
    neither does)."""
    phi = [math.radians(float(x)) for x in crank_deg]
    two_pi = 2 * math.pi
    for sense in (1, -1):
        rel = [((p - phi[0]) * sense) % two_pi for p in phi[1:]]
        if all(r > 0 for r in rel) and all(b > a for a, b in zip(rel, rel[1:])):
            return sense, [phi[0]] + [phi[0] + sense * r for r in rel], False
    rel = [(p - phi[0]) % two_pi for p in phi[1:]]
    return 1, [phi[0]] + [phi[0] + r for r in rel], True


def _grid(angles, steps_per_turn) -> tuple[np.ndarray, list]:
    """The crank angles of the motion (first target to the farthest) with every target's
    angle a step; the targets' indices in it."""
    lo, hi = min(angles), max(angles)
    n = max(2, int(math.ceil(abs(hi - lo) / (2 * math.pi) * steps_per_turn)) + 1)
    q = np.union1d(np.linspace(lo, hi, n), np.array(angles))
    if angles[-1] < angles[0]:
        q = q[::-1]
    return q, [int(np.argmin(np.abs(q - a))) for a in angles]


def _run(scene: dict, q: np.ndarray):
    from linkage_sym import compile_plan, load_scene  # the solver loads SciPy: only when checking

    plan = compile_plan(load_scene(scene))
    zero = np.zeros_like(q)
    return plan.run({"A": q}, {"A": zero}, {"A": zero})


def _errors(res, idx, point, targets, link, rotations, b) -> list:
    errs = []
    for k, i in enumerate(idx):
        if res.status[i] != "ok":
            errs.append(math.inf)
            continue
        e = 0.0
        if point is not None:
            e += float(np.linalg.norm(res.points[point].position[i] - np.asarray(targets[k])))
        if rotations is not None:
            d = float(res.links[link].rotation[i]) - float(rotations[k])
            e += abs(math.remainder(d, 2 * math.pi)) * b
        errs.append(e)
    return errs


def _circuit(res, i, lengths) -> float:
    """The circuit sign of the solver's configuration at step ``i`` (see the module docstring):
    ``lengths`` in loop order ground, crank, coupler, rocker."""
    J = [res.joints[n].position[i] for n in "ABCD"]  # J[k]: between link k and link k + 1
    k = int(np.argmin(lengths))  # the shortest link spans J[k - 1] and J[k]
    o, far, near = J[(k - 2) % 4], J[(k + 1) % 4], J[k]
    u, v = far - o, near - o
    return float(np.sign(u[0] * v[1] - u[1] * v[0]))


def _gamma_min(res) -> float:
    ok = res.status == "ok"
    if not ok.any():
        return math.nan
    B, C, D = (res.joints[n].position[ok] for n in "BCD")
    u, v = B - C, D - C
    cos = np.einsum("ij,ij->i", u, v) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
    g = np.arccos(np.clip(cos, -1.0, 1.0))
    return float(np.min(np.minimum(g, math.pi - g)))


def check_motion(scene: dict, crank_deg, *, point=None, targets=None, link="coupler",
                 rotations=None, tol=TOLERANCE, steps_per_turn=STEPS_PER_TURN) -> MotionCheck:
    """Drive a four-bar by its crank through its targets with the solver; its defects.

    Parameters
    ----------
    scene : dict
        A four-bar scene (joints ``A B C D``, links ``crank coupler rocker``,
        the driver on ``A``) assembled in target 1.
    crank_deg : sequence of float
        The crank angle (degrees, from ``+x``) at which each target is to be met,
        in the order the targets are to be met; the first is the assembly's.
    point : str, optional
        A traced point of the scene that must pass through ``targets``.
    targets : sequence of (x, y), optional
        Its positions (m), one per crank angle.
    link : str
        The link whose rotation is checked against ``rotations``.
    rotations : sequence of float, optional
        That link's rotation from the assembly configuration at each target (rad).
    tol : float
        A target is met within ``tol`` times the coupler length.
    steps_per_turn : int
        Solver steps per crank turn between the targets.

    Returns
    -------
    MotionCheck
    """
    from linkage_sym.structure.grashof import classify

    A, B, C, D = (_joint(scene, n) for n in "ABCD")
    a, b, c, d = (float(np.linalg.norm(p - q)) for p, q in ((A, B), (B, C), (C, D), (D, A)))
    grashof = classify([d, a, b, c], fixed=0, names=["ground", "crank", "coupler", "rocker"]).name
    sense, angles, order = _unwrap(crank_deg)
    q, idx = _grid(angles, steps_per_turn)
    res = _run(scene, q)
    errs = _errors(res, idx, point, targets, link, rotations, b)
    lo, hi = min(idx), max(idx)
    dead = bool(np.any(res.status[lo:hi + 1] != "ok"))
    bad = [k for k, e in enumerate(errs) if not e <= tol * b]
    branch, circuit, missed = False, False, []
    if bad:
        other = mirrored(scene)
        if rotations is not None:  # the other mode's assembly turns the coupler and the rocker
            rotations = [r - _turn(scene, other, link) for r in rotations]
        res_other = _run(other, q)
        errs_other = _errors(res_other, idx, point, targets, link, rotations, b)
        for k in bad:
            if errs_other[k] <= tol * b:
                branch = True
                if grashof in ("crank-rocker", "double-crank", "double-rocker"):
                    circuit |= (_circuit(res_other, idx[k], [d, a, b, c])
                                != _circuit(res, idx[0], [d, a, b, c]))
            elif math.isfinite(errs[k]) or math.isfinite(errs_other[k]):
                missed.append(k)
            else:
                dead = True  # the crank cannot reach the target's angle at all
    notes = []
    if order:
        notes.append("order defect: turning either way the crank meets the targets out of order")
    if branch:
        notes.append("branch defect: a target is met only in the other assembly mode"
                     + (", on the other circuit" if circuit else ""))
    if dead:
        notes.append("dead centre: the crank cannot drive the linkage from the first target to "
                     "the last (coupler and rocker come in line)")
    if missed:
        notes.append(f"targets {[k + 1 for k in missed]} are missed in both assembly modes")
    return MotionCheck(grashof, branch, order, dead, circuit, tuple(missed), sense, tuple(angles),
                       tuple(errs), _gamma_min(res), tuple(notes))


__all__ = ["MotionCheck", "STEPS_PER_TURN", "TOLERANCE", "check_motion", "mirrored"]
