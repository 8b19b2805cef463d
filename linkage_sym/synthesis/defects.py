"""Branch, order and dead-centre defects of a crank-driven four-bar or (inverted) slider-crank.

The one defect checker of the syntheses: motion generation (four or five
poses, :mod:`~linkage_sym.synthesis.motion`) and path generation
(:mod:`~linkage_sym.synthesis.path_check`) both call :func:`check_motion`.

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
``crank``, ``coupler``, ``rocker``; or a slider-crank: joints ``A``, ``B``,
``C`` (coupler-slider) and the slide ``C_guide`` (P, ground-slider, its
``axis_deg`` the guide's direction), links ``crank``, ``coupler``, ``slider``.
Its own sweep is not used.  A slider-crank's assembly modes are the slider
on either side of the foot of the crank pin on the guide (the sign of
``(C - B) . u``, ``u`` along the guide; the other mode is ``C`` reflected in
the normal to the guide through ``B``); its transmission angle is the angle
between the coupler and the normal to the guide; its crank turns fully when
``crank + |offset| < coupler`` (class ``slider-crank``, else
``slider-rocker``), and then its two modes are its two circuits.

Or an inverted slider-crank (the coupler the guide, sliding through a block
pinned to the ground): joints ``A``, ``B``, the slide ``D_slide`` (P,
coupler-slider, its ``axis_deg`` the coupler line's direction in the
assembly, its ``at`` the block's pivot) and ``D`` (R, slider-ground, at the
same point), links ``crank``, ``coupler``, ``slider``.  Its assembly modes
are the crank pin ahead of or behind the block along the coupler's line (the
sign of ``(B - D) . u``, ``u`` along the line; the other mode is the coupler
turned about ``B`` until its line passes through ``D`` again, at the same
offset of ``B``).  Its transmission angle is the angle between ``DB`` and the
normal to the coupler's line (the pin's force on the guide is along that
normal, the velocity of the guide's point at ``B`` turning about ``D`` is
normal to ``DB``): ``acos(|offset| / |DB|)``, 90° for a line through ``B``,
0 where ``|DB|`` falls to the offset and the linkage cannot be assembled.
Its crank turns fully when ``crank + |offset| < frame`` (class
``oscillating-guide``, the coupler swings) or ``crank - |offset| > frame``
(``rotating-guide``, the coupler turns fully too), else it rocks
(``guide-rocker``); turning fully, its two modes are its two circuits.  Its
"coupler length", the scale of the tolerance, is ``|DB|`` in the assembly.

Or a guide-slider (a slider on a fixed line and a block pinned to the ground that
the coupler's line slides through, the block driven): joints ``A`` (R,
ground-crank, the block's pivot, driven), ``B`` (P, coupler-crank: the coupler's
line, its ``at`` a point of the block on that line), ``C`` (R, coupler-slider)
and ``C_guide`` (P, ground-slider), links ``crank`` (the block), ``coupler``,
``slider``.  The block turns the coupler with it: each angle has one
configuration (no other mode, no branch), and none where the coupler's line
runs parallel to the guide (a dead centre: the slider runs off to infinity; the
solver's steps may pass it, the sign of the lines' cross product then changes).  Its transmission angle is the
angle between the coupler's line and the guide; its class ``guide-slider``,
its "coupler length" ``|AC|`` in the assembly.

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
    """What the solver finds when the crank drives a four-bar or (inverted) slider-crank through its
    targets.

    Attributes
    ----------
    grashof : str
        The Grashof class (``crank-rocker``, ``double-crank``, ``double-rocker``,
        ``triple-rocker``, ``change point``; a slider-crank: ``slider-crank`` when
        its crank turns fully, else ``slider-rocker``; an inverted slider-crank:
        ``oscillating-guide``, ``rotating-guide`` or ``guide-rocker``; a guide-slider:
        ``guide-slider``).
    branch : bool
        A target is met only in the other assembly mode, or the mode changes between
        two solved steps of the motion (see the module docstring).
    order : bool
        The crank meets the targets out of order, turning either way (``unwrapped``:
        the given angles are not monotone within one turn).
    dead_centre : bool
        The crank's motion from the first target to the last passes a dead centre.
    circuit : bool
        A target met only in the other assembly mode lies on the other circuit of
        a Grashof four-bar, or of an (inverted) slider-crank whose crank turns fully (see the
        module docstring); False for one with a single circuit.
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
    kind : str
        ``four-bar``, ``slider-crank``, ``inverted slider-crank`` or ``guide-slider``.
    coupler : float
        The coupler's length ``|BC|`` (m; an inverted slider-crank's ``|DB|``, a
        guide-slider's ``|AC|``, in the assembly).
    full_turn : bool
        The crank turns fully (a Grashof crank; a slider-crank's crank with
        ``crank + |offset| < coupler``; an inverted slider-crank's with ``|crank - frame| >
        |offset|``).
    solved : bool
        Every step of the motion (the targets' crank angles among them) solved.
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
    kind: str = "four-bar"
    coupler: float = math.nan
    full_turn: bool = False
    solved: bool = True

    @property
    def defect_free(self) -> bool:
        """True when every target is met, in order, on one branch, without a dead centre."""
        return not (self.branch or self.order or self.dead_centre or self.missed)


def _joint(scene: dict, name: str) -> np.ndarray:
    for j in scene["joints"]:
        if j["name"] == name:
            return np.array(j["at"], dtype=float)
    raise ValueError(f"the scene has no joint {name!r} (joints A, B, C, D of a four-bar, "
                     "A, B, C, C_guide of a slider-crank or A, B, D_slide, D of an inverted "
                     "slider-crank are expected)")


def kind_of(scene: dict) -> str:
    """``slider-crank`` when the scene has the slide ``C_guide`` (``guide-slider`` when its
    ``B`` is a slide too), ``inverted slider-crank`` when it has the slide ``D_slide``, else
    ``four-bar``.

    Examples
    --------
    >>> from linkage_sym.synthesis.builders import slider_crank
    >>> kind_of(slider_crank(0.05, 0.2, 0.01).scene)
    'slider-crank'
    """
    names = {j["name"]: j.get("type") for j in scene["joints"]}
    if "C_guide" in names:
        return "guide-slider" if names.get("B") == "P" else "slider-crank"
    return "inverted slider-crank" if "D_slide" in names else "four-bar"


def guide_direction(scene: dict) -> np.ndarray:
    """The unit vector along a slider-crank's guide (its slide ``C_guide``'s ``axis_deg``) or an
    inverted slider-crank's coupler line in the assembly (``D_slide``'s)."""
    for j in scene["joints"]:
        if j["name"] in ("C_guide", "D_slide"):
            t = math.radians(float(j["axis_deg"]))
            return np.array([math.cos(t), math.sin(t)])
    raise ValueError("the slider-crank scene has no slide C_guide or D_slide")


def _guide_turn(scene: dict) -> float:
    """How far the other mode of an inverted slider-crank turns its coupler about ``B`` (rad):
    its line through ``D`` at ``B``'s offset, turned from ``psi`` to ``2 alpha - pi - psi``
    (``alpha`` the direction of ``B - D``)."""
    r = _joint(scene, "B") - _joint(scene, "D")
    u = guide_direction(scene)
    return math.remainder(2 * math.atan2(r[1], r[0]) - math.pi - 2 * math.atan2(u[1], u[0]),
                          2 * math.pi)


def _other_c(scene: dict) -> np.ndarray:
    """``C`` of the other assembly mode (see :func:`mirrored`)."""
    B, C = _joint(scene, "B"), _joint(scene, "C")
    r = C - B
    if kind_of(scene) == "slider-crank":
        u = guide_direction(scene)
        return C - 2 * (r @ u) * u
    D = _joint(scene, "D")
    u = (D - B) / np.linalg.norm(D - B)
    return B + 2 * (r @ u) * u - r


def mirrored(scene: dict) -> dict:
    """The same four-bar assembled in the other mode: ``C`` reflected in the line ``BD``,
    the coupler's traced points turned with it about ``B`` (the coupler stays rigid).
    A slider-crank: ``C`` (and its slide) reflected in the normal to the guide through ``B``.
    An inverted slider-crank: the coupler (its line ``D_slide``) turned about ``B`` until the
    line passes through ``D`` on the other side of ``B``'s foot on it.

    Examples
    --------
    >>> s = {"joints": [{"name": "A", "at": [0, 0]}, {"name": "B", "at": [0, 1]},
    ...                 {"name": "C", "at": [2, 2]}, {"name": "D", "at": [2, 0]}],
    ...      "points": [{"name": "P", "link": "coupler", "at": [2, 2]}]}
    >>> m = mirrored(s)
    >>> [round(v, 12) for v in m["joints"][2]["at"]], [round(v, 12) for v in m["points"][0]["at"]]
    ([0.4, -1.2], [0.4, -1.2])
    """
    B = _joint(scene, "B")
    out = dict(scene)
    if kind_of(scene) == "inverted slider-crank":
        turn = _guide_turn(scene)
        out["joints"] = [dict(j, axis_deg=float(j["axis_deg"]) + math.degrees(turn))
                         if j["name"] == "D_slide" else dict(j) for j in scene["joints"]]
    else:
        r = _joint(scene, "C") - B
        C2 = _other_c(scene)
        turn = math.atan2(r[0] * (C2 - B)[1] - r[1] * (C2 - B)[0], r @ (C2 - B))
        out["joints"] = [dict(j, at=[float(v) for v in C2]) if j["name"] in ("C", "C_guide")
                         else dict(j) for j in scene["joints"]]
    rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])

    def moved(p):
        return [float(v) for v in B + rot @ (np.asarray(p, dtype=float) - B)]

    if "points" in scene:
        out["points"] = [dict(p, at=moved(p["at"])) if p["link"] == "coupler" else dict(p)
                         for p in scene["points"]]
    return out


def _turn(scene: dict, other: dict, link: str) -> float:
    """How much farther ``link`` is turned in ``other``'s assembly than in ``scene``'s (rad)."""
    if kind_of(scene) == "inverted slider-crank":
        if link != "coupler":
            return 0.0
        return math.radians(math.remainder(_slide_deg(other) - _slide_deg(scene), 360.0))
    ends = {"coupler": "BC", "rocker": "DC"}.get(link)
    if ends is None:
        return 0.0
    u = _joint(scene, ends[1]) - _joint(scene, ends[0])
    v = _joint(other, ends[1]) - _joint(other, ends[0])
    return math.atan2(u[0] * v[1] - u[1] * v[0], u @ v)


def _slide_deg(scene: dict, name: str = "D_slide", rad: bool = False) -> float:
    deg = next(float(j["axis_deg"]) for j in scene["joints"] if j["name"] == name)
    return math.radians(deg) if rad else deg


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


def _as_given(phi) -> tuple[int, list, bool]:
    """``(sense, angles, order_defect)`` of crank angles (rad) taken as the motion itself: an
    order defect unless they are monotone and within one turn."""
    phi = [float(x) for x in phi]
    steps = np.diff(phi)
    monotone = bool(np.all(steps > 0) or np.all(steps < 0))
    order = not (monotone and abs(phi[-1] - phi[0]) < 2 * math.pi)
    return (-1 if phi[-1] < phi[0] else 1), phi, order


def _grid(angles, steps_per_turn) -> tuple[np.ndarray, list]:
    """The crank angles of the motion (first target to the farthest) with every target's
    angle a step; the targets' indices in it."""
    lo, hi = min(angles), max(angles)
    n = max(2, int(math.ceil(abs(hi - lo) / (2 * math.pi) * steps_per_turn)) + 1)
    q = np.union1d(np.linspace(lo, hi, n), np.array(angles))
    if angles[-1] < angles[0]:
        q = q[::-1]
    return q, [int(np.flatnonzero(q == a)[0]) for a in angles]


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


def _cross(u, v) -> np.ndarray:
    return u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]


def _geometry(scene, res, kind, guide) -> tuple[np.ndarray, np.ndarray]:
    """``(gamma, mode)`` at the solved steps: the transmission angle (rad, 0..pi/2) and the
    assembly mode's sign (see the module docstring)."""
    ok = res.status == "ok"
    if kind == "guide-slider":
        t = _slide_deg(scene, "B", rad=True) + np.asarray(res.links["coupler"].rotation)[ok]
        cross = np.cos(t) * guide[1] - np.sin(t) * guide[0]
        return np.arcsin(np.clip(np.abs(cross), 0.0, 1.0)), np.sign(cross)
    if kind == "inverted slider-crank":
        B, D = (np.asarray(res.joints[n].position)[ok] for n in "BD")
        t = math.atan2(guide[1], guide[0]) + np.asarray(res.links["coupler"].rotation)[ok]
        u, r = np.column_stack([np.cos(t), np.sin(t)]), B - D
        normal = np.column_stack([-u[:, 1], u[:, 0]])
        cos = np.abs(np.einsum("ij,ij->i", r, normal)) / np.linalg.norm(r, axis=1)
        return np.arccos(np.clip(cos, 0.0, 1.0)), np.sign(np.einsum("ij,ij->i", r, u))
    B, C = (np.asarray(res.joints[n].position)[ok] for n in "BC")
    r = C - B
    if kind == "slider-crank":
        normal = np.array([-guide[1], guide[0]])
        g = np.arccos(np.clip(r @ normal / np.linalg.norm(r, axis=1), -1.0, 1.0))
        return np.minimum(g, math.pi - g), np.sign(r @ guide)
    D = np.asarray(res.joints["D"].position)[ok]
    u, v = B - C, D - C
    cos = np.einsum("ij,ij->i", u, v) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
    g = np.arccos(np.clip(cos, -1.0, 1.0))
    return np.minimum(g, math.pi - g), np.sign(_cross(D - B, r))


def _classify(scene: dict, kind: str) -> tuple[str, bool, list, float]:
    """``(class, full_turn, loop lengths or [], coupler)`` of the scene's linkage."""
    from linkage_sym.structure.grashof import classify

    if kind == "guide-slider":
        return kind, False, [], float(np.linalg.norm(_joint(scene, "C") - _joint(scene, "A")))
    if kind == "inverted slider-crank":
        A, B, D = (_joint(scene, n) for n in "ABD")
        a, g, b = (float(np.linalg.norm(v)) for v in (B - A, D - A, B - D))
        offset = abs(float(_cross((B - D)[None], guide_direction(scene)[None])[0]))
        name = ("oscillating-guide" if a + offset < g else
                "rotating-guide" if a - offset > g else "guide-rocker")
        return name, name != "guide-rocker", [], b
    A, B, C = (_joint(scene, n) for n in "ABC")
    a, b = float(np.linalg.norm(B - A)), float(np.linalg.norm(C - B))
    if kind == "slider-crank":
        u = guide_direction(scene)
        offset = abs(float(_cross((A - C)[None], u[None])[0]))
        full = a + offset < b
        return ("slider-crank" if full else "slider-rocker"), full, [], b
    D = _joint(scene, "D")
    c, d = float(np.linalg.norm(C - D)), float(np.linalg.norm(D - A))
    g = classify([d, a, b, c], fixed=0, names=["ground", "crank", "coupler", "rocker"])
    full = g.name == "double-crank" or (g.name == "crank-rocker" and g.shortest == 1)
    return g.name, full, [d, a, b, c], b


def _other_mode(scene, q, idx, res, errs, bad, args, grashof, full, lengths) -> tuple:
    """``(branch, circuit, missed, dead)`` of the targets ``bad`` missed in the solver's mode."""
    point, targets, link, rotations, tol, b = args
    if kind_of(scene) == "guide-slider":  # one configuration at each angle: no other mode
        return (False, False, [k for k in bad if math.isfinite(errs[k])],
                any(not math.isfinite(errs[k]) for k in bad))
    other = mirrored(scene)
    if rotations is not None:  # the other mode's assembly turns the coupler and the rocker
        rotations = [r - _turn(scene, other, link) for r in rotations]
    res_other = _run(other, q)
    errs_other = _errors(res_other, idx, point, targets, link, rotations, b)
    branch, circuit, missed, dead = False, False, [], False
    for k in bad:
        if errs_other[k] <= tol * b:
            branch = True
            if not lengths:  # a slider-crank: two circuits when its crank turns fully
                circuit |= full
            elif grashof in ("crank-rocker", "double-crank", "double-rocker"):
                circuit |= (_circuit(res_other, idx[k], lengths) != _circuit(res, idx[0], lengths))
        elif math.isfinite(errs[k]) or math.isfinite(errs_other[k]):
            missed.append(k)
        else:
            dead = True  # the crank cannot reach the target's angle at all
    return branch, circuit, missed, dead


def _notes(order, branch, circuit, dead, missed) -> tuple:
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
    return tuple(notes)


def check_motion(scene: dict, crank_deg, *, point=None, targets=None, link="coupler",
                 rotations=None, tol=TOLERANCE, steps_per_turn=STEPS_PER_TURN,
                 unwrapped=False, unit="deg") -> MotionCheck:
    """Drive a four-bar or (inverted) slider-crank by its crank through its targets with the solver.

    Parameters
    ----------
    scene : dict
        A four-bar scene (joints ``A B C D``, links ``crank coupler rocker``) or a
        slider-crank scene (joints ``A B C C_guide``, links ``crank coupler
        slider``), an inverted slider-crank scene (joints ``A B D_slide D``, links
        ``crank coupler slider``) or a guide-slider scene (joints ``A B C C_guide``, ``B`` a
        slide), the driver on ``A``, assembled in target 1.
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
    tol : float or None
        A target is met within ``tol`` times the coupler length; None: the
        targets are not precision points (a fit) and a target is not looked
        for in the other assembly mode (a branch defect is then a change of
        mode along the motion only).
    steps_per_turn : int
        Solver steps per crank turn between the targets.
    unwrapped : bool
        Take ``crank_deg`` as the motion itself (the crank turns from the first
        to the last through the others, no multiple of a turn added): an order
        defect unless they are monotone within one turn.  By default each is
        taken modulo a turn and either sense of turning is tried.
    unit : str
        ``deg`` (default) or ``rad`` (with ``unwrapped``: the angles used as given, to
        the last bit): the unit of ``crank_deg``.

    Returns
    -------
    MotionCheck
    """
    kind = kind_of(scene)
    grashof, full, lengths, b = _classify(scene, kind)
    if unit not in ("deg", "rad") or (unit == "rad" and not unwrapped):
        raise ValueError(f"unit: 'deg', or 'rad' with unwrapped angles, is expected, got {unit!r}")
    if unwrapped:
        sense, angles, order = _as_given(np.radians(crank_deg) if unit == "deg" else crank_deg)
    else:
        sense, angles, order = _unwrap(crank_deg)
    q, idx = _grid(angles, steps_per_turn)
    res = _run(scene, q)
    errs = _errors(res, idx, point, targets, link, rotations, b)
    lo, hi = min(idx), max(idx)
    dead = bool(np.any(res.status[lo:hi + 1] != "ok"))
    guide = guide_direction(scene) if kind != "four-bar" else None
    gamma, modes = _geometry(scene, res, kind, guide)
    branch, circuit, missed = len(set(modes.tolist()) - {0.0}) > 1, False, []
    if kind == "guide-slider":  # the line crossed the guide's direction: the slider ran off
        dead, branch = dead or branch, False
    bad = [] if tol is None else [k for k, e in enumerate(errs) if not e <= tol * b]
    if bad:
        other = _other_mode(scene, q, idx, res, errs, bad,
                            (point, targets, link, rotations, tol, b), grashof, full, lengths)
        branch, circuit, missed, dead = branch or other[0], other[1], other[2], dead or other[3]
    return MotionCheck(grashof, branch, order, dead, circuit, tuple(missed), sense, tuple(angles),
                       tuple(errs), float(np.min(gamma)) if len(gamma) else math.nan,
                       _notes(order, branch, circuit, dead, missed), kind, b, full,
                       bool(np.all(res.status == "ok")))


__all__ = ["MotionCheck", "STEPS_PER_TURN", "TOLERANCE", "check_motion", "guide_direction",
           "kind_of", "mirrored"]
