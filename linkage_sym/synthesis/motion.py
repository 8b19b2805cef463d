"""Motion generation: linkages whose coupler passes through four or five given poses.

The dyads come from Burmester theory (:mod:`~linkage_sym.synthesis.burmester`):
for five poses every Burmester point pair, for four poses dyads sampled along
the centre-point curve.  Every ordered pair of dyads (the first the crank,
the second the rocker) is a four-bar candidate.  The slider dyads -- coupler
points whose positions lie on a line, the centre point at infinity
(:mod:`~linkage_sym.synthesis.burmester_slider`) -- each with every dyad as
its crank, are slider-crank candidates (the guide that line); the guide
dyads -- fixed pivots that a line of the coupler passes through in every
pose, the circle point at infinity (:mod:`~linkage_sym.synthesis.burmester_rp`)
-- each with every dyad as its crank, are inverted slider-crank candidates
(the coupler sliding through a block pinned at the pivot); each guide with
each slider is a guide-slider candidate (the block at the guide's pivot
driven: it turns the coupler with it).  Each is written as a scene
(pivots in the poses' own coordinates, assembled in pose 1, the coupler frame's
origin the traced point ``P``, the driver turning the crank from pose 1 to
the last pose through the others) and driven through the poses by the
solver (:func:`~linkage_sym.synthesis.defects.check_motion`), which reports
its branch, order and dead-centre defects, its Grashof class and its
minimum transmission angle over the motion.  Designs without a defect come
first, then by decreasing minimum transmission angle.

Examples
--------
>>> poses = [[0.0, 0.0, 0.0], [1.0, 0.2, 10.0], [1.8, 0.7, 25.0], [2.3, 1.5, 45.0], [2.5, 2.4, 70.0]]
>>> result = motion_synthesis(poses)
>>> len(result.dyads), len(result.designs) == len(result.dyads) * (len(result.dyads) - 1)
(2, True)
"""

from __future__ import annotations

import cmath
import itertools
import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.synthesis.burmester import Curves, Dyad, burmester_curves, burmester_points, read_poses
from linkage_sym.synthesis.burmester_rp import GuideDyad, guide_points
from linkage_sym.synthesis.burmester_slider import SliderDyad, slider_points
from linkage_sym.synthesis.common import SynthesisError, scene_name, sweep_options
from linkage_sym.synthesis.defects import MotionCheck, check_motion

REACH = 10.0
"""Four poses: dyads whose centre or circle point lies farther than this many spreads of
the poses (the largest distance of a pose's origin from pose 1's) from pose 1 are not
sampled."""

APART = 1e-6
"""Two pivots closer than this fraction of the poses' spread make no four-bar."""


@dataclass(frozen=True)
class MotionDesign:
    """A four-bar or (inverted) slider-crank candidate through the poses, as the solver found it.

    Attributes
    ----------
    scene : dict
        The scene (``linkage_sym.load_scene`` reads it).
    crank, rocker : int
        Indices of its dyads in :attr:`MotionSynthesis.dyads`; a slider-crank's
        ``rocker`` indexes :attr:`MotionSynthesis.sliders`, an inverted
        slider-crank's :attr:`MotionSynthesis.guides`; a guide-slider's ``crank``
        indexes the guides, its ``rocker`` the sliders.
    lengths : dict of str to float
        ``crank``, ``coupler``, ``rocker``, ``ground`` (m; a slider-crank's
        ``rocker`` and ``ground`` NaN; an inverted slider-crank's ``coupler`` the
        distance from its pin ``B`` to the block's pivot ``D`` in pose 1, its
        ``rocker`` NaN; a guide-slider's ``coupler`` the distance from the block's pivot
        ``A`` to the slider's pin ``C`` in pose 1, the others NaN).
    check : MotionCheck
        The solver's findings (defects, Grashof class, transmission angle, errors).
    kind : str
        ``four-bar``, ``slider-crank``, ``inverted slider-crank`` or ``guide-slider``.
    """

    scene: dict
    crank: int
    rocker: int
    lengths: dict
    check: MotionCheck
    kind: str = "four-bar"


@dataclass(frozen=True)
class MotionSynthesis:
    """Every four-bar of a motion generation, best first.

    Attributes
    ----------
    poses : ndarray, shape (n, 3)
        The poses (m, m, rad).
    dyads : list of Dyad
        The dyads combined (Burmester point pairs, or samples of the curves).
    curves : Curves or None
        Four poses: the centre-point and circle-point curves.
    designs : list of MotionDesign
        Defect-free designs first, then by decreasing minimum transmission angle.
    skipped : int
        Pairs of dyads that make no linkage (a shared pivot).
    sliders : list of SliderDyad
        The slider dyads (coupler points on a line) combined with the dyads.
    guides : list of GuideDyad
        The guide dyads (fixed pivots on a coupler line) combined with the dyads.
    """

    poses: np.ndarray
    dyads: list
    curves: Curves | None
    designs: list
    skipped: int
    sliders: list = ()
    guides: list = ()


def _sample(curves: Curves, count: int, poses: np.ndarray) -> list[Dyad]:
    """``count`` dyads spread evenly along the curves' samples within :data:`REACH`."""
    spread = float(np.max(np.hypot(*(poses[:, :2] - poses[0, :2]).T)))
    near = [d for branch in curves.dyads for d in branch
            if max(math.dist(d.centre, poses[0, :2]), math.dist(d.circle, poses[0, :2]))
            <= REACH * spread]
    if len(near) < 2:
        raise SynthesisError("poses", f"fewer than two dyads have their pivots within {REACH:g} "
                                      "spreads of the poses")
    idx = np.unique(np.linspace(0, len(near) - 1, min(count, len(near))).round().astype(int))
    return [near[i] for i in idx]


def _scene(name, crank: Dyad, rocker: Dyad, poses, steps, speed) -> dict:
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    A, B, C, D = crank.centre, crank.circle, rocker.circle, rocker.centre
    start = math.degrees(math.atan2(B[1] - A[1], B[0] - A[0]))
    return {
        "name": name,
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": xy(C)},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": xy(D)},
        ],
        "points": [{"name": "P", "link": "coupler", "at": xy(poses[0, :2])}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": start, "stop_deg": start + 360.0,
                     "steps": steps, "speed": speed, "acceleration": 0.0}],
        "outputs": ["kinematics"],
    }


def _slider_scene(name, crank: Dyad, slider: SliderDyad, poses, steps, speed) -> dict:
    """A slider-crank: the crank ``A B`` of ``crank``, the slider's pin ``C`` and its guide."""
    scene = _scene(name, crank, crank, poses, steps, speed)
    C = [float(v) for v in slider.circle]
    scene["links"][2] = {"name": "slider"}
    scene["joints"][2] = {"name": "C", "type": "R", "links": ["coupler", "slider"], "at": C}
    scene["joints"][3] = {"name": "C_guide", "type": "P", "links": ["ground", "slider"], "at": C,
                          "axis_deg": math.degrees(slider.angle)}
    return scene


def _guide_scene(name, crank: Dyad, guide: GuideDyad, poses, steps, speed) -> dict:
    """An inverted slider-crank: the crank ``A B`` of ``crank``, the coupler's line sliding
    through the block (link ``slider``) pinned to the ground at the guide's pivot ``D``."""
    scene = _scene(name, crank, crank, poses, steps, speed)
    D = [float(v) for v in guide.pivot]
    scene["links"][2] = {"name": "slider"}
    scene["joints"][2] = {"name": "D_slide", "type": "P", "links": ["coupler", "slider"], "at": D,
                          "axis_deg": math.degrees(guide.axis)}
    scene["joints"][3] = {"name": "D", "type": "R", "links": ["slider", "ground"], "at": D}
    return scene


def _guide_slider_scene(name, guide: GuideDyad, slider: SliderDyad, poses, steps, speed) -> dict:
    """A guide-slider: the block (link ``crank``) pinned at the guide's pivot ``A`` and driven,
    the coupler's line sliding through it (the slide ``B``, its point of the block the foot of
    the slider's pin on that line, or a spread along it), the slider's pin ``C`` and guide."""
    G, C = np.asarray(guide.pivot), np.asarray(slider.circle)
    u = np.array([math.cos(guide.axis), math.sin(guide.axis)])
    spread = float(np.max(np.hypot(*(poses[:, :2] - poses[0, :2]).T)))
    arm = float((C - G) @ u)
    B = G + (arm if abs(arm) > APART * spread else spread) * u
    start = math.degrees(math.atan2(B[1] - G[1], B[0] - G[0]))
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    return {
        "name": name,
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(G)},
            {"name": "B", "type": "P", "links": ["coupler", "crank"], "at": xy(B),
             "axis_deg": math.degrees(guide.axis)},
            {"name": "C", "type": "R", "links": ["coupler", "slider"], "at": xy(C)},
            {"name": "C_guide", "type": "P", "links": ["ground", "slider"], "at": xy(C),
             "axis_deg": math.degrees(slider.angle)},
        ],
        "points": [{"name": "P", "link": "coupler", "at": xy(poses[0, :2])}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": start, "stop_deg": start + 360.0,
                     "steps": steps, "speed": speed, "acceleration": 0.0}],
        "outputs": ["kinematics"],
    }


_SCENES = {"four-bar": _scene, "slider-crank": _slider_scene,
           "inverted slider-crank": _guide_scene, "guide-slider": _guide_slider_scene}


def _pins(kind, first, second) -> tuple:
    """The design's pivots and pins at pose 1, in loop order from the driven pivot."""
    if kind == "guide-slider":
        return first.pivot, second.circle
    if kind == "inverted slider-crank":
        return first.centre, first.circle, second.pivot
    if kind == "slider-crank":
        return first.centre, first.circle, second.circle
    return first.centre, first.circle, second.circle, second.centre


def _design(name, kind, first, second, k, l, poses, steps, speed) -> MotionDesign | None:
    """The linkage ``kind`` of the dyads ``first`` (the driven one: a crank dyad, a guide for a
    guide-slider) and ``second``, numbered ``k`` and ``l`` in their lists; None where two of
    its pivots coincide."""
    spread = float(np.max(np.hypot(*(poses[:, :2] - poses[0, :2]).T)))
    pts = _pins(kind, first, second)
    if min(math.dist(p, q) for i, p in enumerate(pts) for q in pts[i + 1:]) <= APART * spread:
        return None
    scene = _SCENES[kind](name, first, second, poses, steps, speed)
    if kind == "guide-slider":  # the block turns with the coupler
        drv = scene["drivers"][0]["start_deg"]
        phi = [drv + math.degrees(t - poses[0, 2]) for t in poses[:, 2]]
    else:
        W = complex(*first.circle) - complex(*first.centre)
        phi = [math.degrees(cmath.phase(W) + bj) for bj in first.beta]
    check = check_motion(scene, phi, point="P", targets=poses[:, :2].tolist(),
                         rotations=(poses[:, 2] - poses[0, 2]).tolist())
    drv = scene["drivers"][0]
    drv["stop_deg"] = drv["start_deg"] + math.degrees(check.crank_angles[-1] - check.crank_angles[0])
    lengths = {"crank": math.dist(pts[0], pts[1]), "coupler": math.dist(pts[1], pts[-1]),
               "rocker": math.nan, "ground": math.nan}
    if kind == "four-bar":
        lengths.update(coupler=math.dist(pts[1], pts[2]), rocker=math.dist(pts[2], pts[3]),
                       ground=math.dist(pts[3], pts[0]))
    elif kind == "inverted slider-crank":
        lengths.update(ground=math.dist(pts[2], pts[0]))
    elif kind == "guide-slider":
        lengths.update(crank=math.nan, coupler=math.dist(pts[0], pts[1]))
    return MotionDesign(scene, k, l, lengths, check, check.kind)


def motion_synthesis(poses, *, dyads: int = 12, samples: int = 720, name: str = "motion",
                     steps: int = 361, speed: float = 1.0) -> MotionSynthesis:
    """Four-bars, slider-cranks and inverted slider-cranks whose coupler frame passes through
    four or five poses.

    Parameters
    ----------
    poses : sequence of 4 or 5 ``[x, y, angle_deg]``
        The coupler frame's origin (m) and angle (degrees) in each pose, in the
        order the linkage is to reach them.
    dyads : int
        Four poses: how many dyads to sample along the curves (every ordered
        pair is a candidate: ``dyads * (dyads - 1)`` of them).
    samples : int
        Four poses: samples of the curves over a turn of the crank's rotation to pose 2.
    name : str
        The scenes' name stem (``name-01`` ...).
    steps, speed
        Each scene's sweep: steps from pose 1 to the last pose, the crank's speed (rad/s).

    Returns
    -------
    MotionSynthesis

    Raises
    ------
    SynthesisError
        Malformed poses, degenerate poses, fewer than two dyads (five poses
        with no real Burmester point pair, say) and no slider or guide to pair
        with one.
    """
    P = read_poses(poses)
    steps, speed = sweep_options(steps, speed)
    name = scene_name(name)
    if isinstance(dyads, bool) or not isinstance(dyads, int) or dyads < 2:
        raise SynthesisError("dyads", f"an integer >= 2 is expected, got {dyads!r}")
    curves = None
    sliders = slider_points(poses)
    if len(P) == 5:
        found = burmester_points(poses)
        guides = guide_points(poses)
        if len(found) < 2 and not (found and (sliders or guides)) and not (sliders and guides):
            raise SynthesisError("poses", f"the five poses have {len(found)} real Burmester point "
                                          f"pairs, {len(sliders)} slider dyads and {len(guides)} "
                                          "guide dyads: no four-bar or (inverted) slider-crank "
                                          "meets them (move a pose, or give four)")
    else:
        curves = burmester_curves(poses, samples)
        found = _sample(curves, dyads, P)
        guides = guide_points(poses)
    designs, skipped = [], 0
    pairs = [("four-bar", found, found), ("slider-crank", found, sliders),
             ("inverted slider-crank", found, guides), ("guide-slider", guides, sliders)]
    for kind, firsts, seconds in pairs:
        for k, l in itertools.product(range(len(firsts)), range(len(seconds))):
            if kind == "four-bar" and k == l:
                continue
            d = _design(name, kind, firsts[k], seconds[l], k, l, P, steps, speed)
            if d is None:
                skipped += 1
            else:
                designs.append(d)
    designs.sort(key=lambda d: (not d.check.defect_free, -np.nan_to_num(d.check.gamma_min, nan=-1)))
    for i, d in enumerate(designs, 1):
        d.scene["name"] = f"{name}-{i:02d}"
    return MotionSynthesis(P, found, curves, designs, skipped, sliders, guides)


def _guide(scene) -> tuple:
    """``(offset, guide_deg)`` of a slider-crank scene (the guide's signed distance from ``A``,
    m, and direction) or an inverted slider-crank's (its coupler line's signed distance from
    ``B``, in pose 1), NaN for a four-bar."""
    j = {x["name"]: x for x in scene["joints"]}
    if "D_slide" in j:
        t = math.radians(j["D_slide"]["axis_deg"])
        B, D = j["B"]["at"], j["D"]["at"]
        return math.cos(t) * (D[1] - B[1]) - math.sin(t) * (D[0] - B[0]), j["D_slide"]["axis_deg"]
    if "C_guide" not in j:
        return math.nan, math.nan
    t = math.radians(j["C_guide"]["axis_deg"])
    A, C = j["A"]["at"], j["C_guide"]["at"]
    return math.cos(t) * (C[1] - A[1]) - math.sin(t) * (C[0] - A[0]), j["C_guide"]["axis_deg"]


def table(result: MotionSynthesis) -> list[dict]:
    """One row per design, best first: what the console and the CSV show.

    Examples
    --------
    >>> poses = [[0.0, 0.0, 0.0], [1.0, 0.2, 10.0], [1.8, 0.7, 25.0], [2.3, 1.5, 45.0], [2.5, 2.4, 70.0]]
    >>> list(table(motion_synthesis(poses))[0])[:6]
    ['design', 'Ax', 'Ay', 'Dx', 'Dy', 'crank']
    """
    rows = []
    for i, d in enumerate(result.designs, 1):
        j = {x["name"]: x["at"] for x in d.scene["joints"]}
        c = d.check
        finite = [e for e in c.errors if math.isfinite(e)]
        D = j.get("D", (math.nan, math.nan))  # a slider-crank has no D (an inverted one's: the block)
        offset, guide_deg = _guide(d.scene)
        rows.append({
            "design": f"design-{i:02d}", "Ax": j["A"][0], "Ay": j["A"][1], "Dx": D[0],
            "Dy": D[1], **d.lengths, "grashof": c.grashof, "branch": c.branch,
            "circuit": c.circuit, "order": c.order, "dead_centre": c.dead_centre,
            "defect_free": c.defect_free,
            "gamma_min_deg": math.degrees(c.gamma_min) if math.isfinite(c.gamma_min) else math.nan,
            "error": max(finite) / d.lengths["coupler"] if finite else math.inf,
            "linkage": d.kind, "offset": offset, "guide_deg": guide_deg,
        })
    return rows


__all__ = ["MotionDesign", "MotionSynthesis", "motion_synthesis", "table"]
