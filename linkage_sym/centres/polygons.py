"""The quantities of the graphical (polygon) method at one step.

The textbook chapter *Kinematic analysis of planar mechanisms* (README Sources [4], section 3-2)
draws a velocity polygon and an acceleration polygon from two kinds of
vector equations:

* two points of one link (eqs. 3-1, 3-2): ``v_C = v_B + v_CB`` and
  ``a_C = a_B + a_CB^n + a_CB^t``, with ``v_CB = w x BC`` (normal to BC),
  ``a_CB^n = -w^2 BC`` (from C toward B) and ``a_CB^t = alpha x BC``;
* coincident points of two links joined by a sliding pair (eqs. 3-3, 3-4):
  ``v_B3 = v_B2 + v_B3B2`` and ``a_B3 = a_B2 + a_B3B2^k + a_B3B2^r``, with the
  relative (slip) velocity and acceleration along the slide and the Coriolis
  term ``a^k = 2 w x v_rel``, ``w`` the angular velocity of the link that
  carries the slide.

:func:`polygon_quantities` evaluates every such term from a solved step: the
absolute motion of every point of every link, each point relative to each
pivot of its link, and each sliding pair between two moving links.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkage_sym.model import GROUND

__all__ = ["PointMotion", "Polygons", "RelativeMotion", "Sliding", "polygon_quantities"]

SAME_POINT = 1e-9
"""Points of one link closer than this fraction of the mechanism's size are one point."""


@dataclass
class PointMotion:
    """A point of a link: ``name`` (a joint's or traced point's), ``link`` and its motion.

    ``label`` is the polygon vertex's name: the point's name, followed by the
    link's number (the ground 1) when the point belongs to several links
    (``B2``, ``B3``: coincident points).  Vectors are arrays of shape (2,).
    """

    name: str
    link: str
    label: str
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


@dataclass
class RelativeMotion:
    """Point ``point`` relative to ``about`` (a pivot of the same ``link``).

    ``velocity`` is ``v_point - v_about = w J r`` (``r`` from ``about`` to
    ``point``, ``J`` the rotation by +90 degrees), ``normal`` is ``-w^2 r``
    (toward the pivot), ``tangential`` is ``alpha J r``.
    """

    link: str
    point: str
    about: str
    velocity: np.ndarray
    normal: np.ndarray
    tangential: np.ndarray


@dataclass
class Sliding:
    """A sliding pair between two moving links at one step.

    ``point`` names the coincident points in :attr:`Polygons.points` (the
    name of an ``R`` joint at the slider's reference point, else the joint's).

    The slider's point (the joint's reference point, fixed on ``slider``, the
    joint's ``links[1]``) moves relative to the coincident point of the
    ``guide`` (``links[0]``, which carries the slide):

    ``velocity`` (slip velocity ``v_rel``) and ``acceleration`` (slip
    acceleration ``a_rel``) are along ``axis`` (the slide's direction at that
    step); ``speed`` and ``rate`` are their signed components along it;
    ``coriolis`` is ``2 w_guide J v_rel``, so that
    ``a_slider = a_guide + coriolis + acceleration``.
    """

    joint: str
    point: str
    guide: str
    slider: str
    axis: np.ndarray
    velocity: np.ndarray
    speed: float
    acceleration: np.ndarray
    rate: float
    coriolis: np.ndarray


@dataclass
class Polygons:
    """Everything the polygons of one step are drawn from.

    Attributes
    ----------
    step : int
    numbers : dict
        Link numbers (the ground 1, then scene order).
    omega, alpha : dict
        Angular velocity (rad/s) and acceleration (rad/s^2) of each moving link.
    points : list of PointMotion
    relative : list of RelativeMotion
        Each point of a link about each pivot (``R`` joint) of it; two pivots
        once, the later about the earlier (the other way round is its negative).
    sliding : list of Sliding
        One per ``P`` joint between two moving links.
    """

    step: int
    numbers: dict
    omega: dict
    alpha: dict
    points: list = field(default_factory=list)
    relative: list = field(default_factory=list)
    sliding: list = field(default_factory=list)

    def point(self, label: str) -> PointMotion:
        """The point whose vertex label is ``label``.

        Examples
        --------
        >>> import linkage_sym
        >>> scene = linkage_sym.load_example("crank_rocker")
        >>> pq = polygon_quantities(scene, linkage_sym.analyze(scene), 0)
        >>> [p.label for p in pq.points]
        ['A', 'B2', 'B3', 'C3', 'P', 'C4', 'D']
        >>> pq.point("B2").link, round(float(pq.point("B2").velocity[1]), 6)
        ('crank', 0.24)
        """
        for p in self.points:
            if p.label == label:
                return p
        raise KeyError(label)

    def to_dict(self) -> dict:
        """JSON-ready: vectors as ``[x, y]`` lists (SI units).

        Examples
        --------
        >>> import linkage_sym
        >>> scene = linkage_sym.load_example("guide_bar_quick_return")
        >>> d = polygon_quantities(scene, linkage_sym.analyze(scene), 0).to_dict()
        >>> sorted(d), sorted(d["sliding"][0])
        (['alpha', 'omega', 'points', 'relative', 'sliding', 'step'], ['axis', 'coriolis', 'guide', 'joint', 'point', 'slider', 'slip_acceleration', 'slip_rate', 'slip_speed', 'slip_velocity'])
        """
        vec = lambda v: [float(v[0]) + 0.0, float(v[1]) + 0.0]  # noqa: E731
        return {
            "step": self.step,
            "omega": {k: float(v) for k, v in self.omega.items()},
            "alpha": {k: float(v) for k, v in self.alpha.items()},
            "points": [{"point": p.name, "link": p.link, "label": p.label,
                        "position": vec(p.position), "velocity": vec(p.velocity),
                        "acceleration": vec(p.acceleration)} for p in self.points],
            "relative": [{"link": r.link, "point": r.point, "about": r.about,
                          "velocity": vec(r.velocity), "normal_acceleration": vec(r.normal),
                          "tangential_acceleration": vec(r.tangential)} for r in self.relative],
            "sliding": [{"joint": s.joint, "point": s.point, "guide": s.guide, "slider": s.slider,
                         "axis": vec(s.axis), "slip_velocity": vec(s.velocity),
                         "slip_speed": float(s.speed), "slip_acceleration": vec(s.acceleration),
                         "slip_rate": float(s.rate), "coriolis": vec(s.coriolis)}
                        for s in self.sliding],
        }


def _motion(analysis, link, p, i):
    """Velocity and acceleration (2,) of the point of ``link`` at ``p`` (global) at step ``i``."""
    if link == GROUND:
        return np.zeros(2), np.zeros(2)
    lk = analysis.links[link]
    r = np.asarray(p, dtype=float) - np.asarray(lk.origin[i], dtype=float)
    w, a = float(lk.omega[i]), float(lk.alpha[i])
    jr = np.array([-r[1], r[0]])
    return (np.asarray(lk.origin_velocity[i], dtype=float) + w * jr,
            np.asarray(lk.origin_acceleration[i], dtype=float) + a * jr - w * w * r)


def polygon_quantities(scene, analysis, step: int) -> Polygons:
    """Velocity- and acceleration-polygon quantities of one step.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        A sweep solved with velocities and accelerations.
    step : int
        An ``ok`` step.

    Returns
    -------
    Polygons

    Raises
    ------
    ValueError
        If the step has no accelerations.

    Examples
    --------
    The guide-bar of the textbook chapter's example 3-1 at its first step
    (phi1 = 60 deg): the block B slides on the guide bar, which turns at
    w3 = -3.92 rad/s; the slip velocity is 0.321 m/s (the book, measured on its
    drawing: 0.32 m/s) and the Coriolis term 2 w v_rel 2.51 m/s^2 (the book: 2.5).

    >>> import numpy as np, linkage_sym
    >>> scene = linkage_sym.load_example("guide_bar_quick_return")
    >>> pq = polygon_quantities(scene, linkage_sym.analyze(scene), 0)
    >>> s = pq.sliding[0]
    >>> s.joint, s.guide, s.slider
    ('B_slide', 'guide_bar', 'block')
    >>> round(abs(s.speed), 3), round(float(np.hypot(*s.coriolis)), 2)
    (0.321, 2.51)
    >>> [p.label for p in pq.points if p.name == "B"]
    ['B2', 'B3', 'B4']
    """
    i = int(step)
    if not ("acceleration" in analysis.stages and str(analysis.status[i]) == "ok"):
        raise ValueError(f"step {i} has no accelerations (status {analysis.status[i]}, "
                         f"stages {', '.join(analysis.stages)})")
    L = scene.characteristic_length() or 1.0
    names = (GROUND, *scene.link_names)
    numbers = {n: k + 1 for k, n in enumerate(names)}
    r_name, per_link = _points_per_link(scene, analysis, i, L)
    count: dict = {}
    for entries in per_link.values():
        for name, *_ in entries:
            count[name] = count.get(name, 0) + 1
    points = []
    for link, entries in per_link.items():
        for name, _, p, _ in entries:
            v, a = _motion(analysis, link, p, i)
            label = f"{name}{numbers[link]}" if count[name] > 1 else name
            points.append(PointMotion(name, link, label, p, v, a))

    omega = {n: float(analysis.links[n].omega[i]) for n in scene.link_names}
    alpha = {n: float(analysis.links[n].alpha[i]) for n in scene.link_names}
    relative = _relative_motions(per_link, omega, alpha)
    sliding = _slidings(scene, analysis, i, omega, r_name)
    return Polygons(i, numbers, omega, alpha, points, relative, sliding)


def _points_per_link(scene, analysis, i: int, L: float) -> tuple:
    """``(r_name, per_link)``: the name of the ``R`` joint at each ``P`` joint's point (a
    ``P`` joint's point takes it), and per link its points ``[name, link, global position,
    is a pivot]`` at step ``i`` without repeats."""
    r_name = {}  # a P joint's point takes the name of an R joint at the same place
    for j in scene.joints:
        if j.type == "P":
            for q in scene.joints:
                if q.type == "R" and j.links[1] in q.links and np.hypot(
                        q.at[0] - j.at[0], q.at[1] - j.at[1]) <= SAME_POINT * L:
                    r_name[j.name] = q.name
                    break

    def where(jname):
        return np.asarray(analysis.joints[jname].position[i], dtype=float)

    # (name, link, global position, is a pivot) per link, without repeats
    per_link: dict = {n: [] for n in scene.link_names}

    def add(name, link, p, pivot):
        if link == GROUND:
            return
        for entry in per_link[link]:
            if np.hypot(*(entry[2] - p)) <= SAME_POINT * L:
                entry[3] = entry[3] or pivot
                return
        per_link[link].append([name, link, p, pivot])

    for j in scene.joints:
        if j.type == "R":
            for link in j.links:
                add(j.name, link, where(j.name), True)
    for j in scene.joints:
        if j.type == "P":
            name = r_name.get(j.name, j.name)
            add(name, j.links[1], where(j.name), False)
            add(name, j.links[0], where(j.name), False)  # the guide's coincident point
    for pt in scene.points:
        add(pt.name, pt.link, np.asarray(analysis.points[pt.name].position[i], dtype=float), False)
    return r_name, per_link


def _relative_motions(per_link: dict, omega: dict, alpha: dict) -> list:
    """Each pivot pair's relative motion on its link (each pair of pivots once, the later
    about the earlier): normal and tangential terms."""
    relative = []
    for link, entries in per_link.items():
        w, al = omega[link], alpha[link]
        for a, (pname, _, P, pivot) in enumerate(entries):
            if not pivot:
                continue
            for b, (qname, _, Q, q_pivot) in enumerate(entries):
                if b == a or (q_pivot and b < a):  # each pair of pivots once: later about earlier
                    continue
                r = Q - P
                jr = np.array([-r[1], r[0]])
                relative.append(RelativeMotion(link, qname, pname, w * jr, -w * w * r, al * jr))
    return relative


def _slidings(scene, analysis, i: int, omega: dict, r_name: dict) -> list:
    """Each ``P`` joint between moving links: slip velocity and acceleration, Coriolis term."""
    def where(jname):
        return np.asarray(analysis.joints[jname].position[i], dtype=float)

    sliding = []
    for j in scene.joints:
        guide, slider = j.links
        if j.type != "P" or GROUND in j.links:
            continue
        p = where(j.name)
        vs, as_ = _motion(analysis, slider, p, i)
        vg, ag = _motion(analysis, guide, p, i)
        th = j.axis + float(analysis.links[guide].rotation[i])
        u = np.array([np.cos(th), np.sin(th)])
        vrel = vs - vg
        cor = 2.0 * omega[guide] * np.array([-vrel[1], vrel[0]])
        arel = as_ - ag - cor
        sliding.append(Sliding(j.name, r_name.get(j.name, j.name), guide, slider, u, vrel,
                               float(vrel @ u), arel, float(arel @ u), cor))
    return sliding
