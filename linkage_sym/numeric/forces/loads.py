"""Loads reduced to each link: d'Alembert inertia, weight and the scene's loads.

A :class:`Wrench` holds the resultant force ``(fx, fy)`` on one link and its
moment ``m`` about a *reference point* ``(rx, ry)`` that moves with the link
(its centre of mass when it has one, else one of its joints).  Keeping each
link's moment about a point of the link (rather than the global origin)
keeps every lever arm as short as the link, so no digits are lost when a
mechanism sits far from the origin.  The ground's wrench has its reference
at the origin: what the moving links put on it is the frame force and
moment of the scene format.

All fields are arrays over the steps (or Python floats that broadcast).
"""

from __future__ import annotations

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.model.scene import Load
from linkage_sym.numeric.forces.springs import add_spring_wrenches


class Wrench:
    """Resultant force and moment (about a reference point) acting on one link.

    Examples
    --------
    A force of 2 N along y at (1, 0) has a moment of 2 N·m about the origin:

    >>> w = Wrench(0.0, 0.0)
    >>> w.add_force(0.0, 2.0, 1.0, 0.0)
    >>> (w.fx, w.fy, w.m, w.moment_about(1.0, 0.0))
    (0.0, 2.0, 2.0, 0.0)
    """

    __slots__ = ("fx", "fy", "m", "rx", "ry")

    def __init__(self, rx, ry, fx=0.0, fy=0.0, m=0.0):
        self.rx, self.ry = rx, ry
        self.fx, self.fy, self.m = fx, fy, m

    def add_force(self, gx, gy, px, py):
        """Add the force ``(gx, gy)`` applied at the point ``(px, py)``."""
        self.fx = self.fx + gx
        self.fy = self.fy + gy
        self.m = self.m + ((px - self.rx) * gy - (py - self.ry) * gx)

    def add_couple(self, c):
        """Add a pure couple ``c`` (counter-clockwise positive)."""
        self.m = self.m + c

    def moment_about(self, cx, cy):
        """Moment of the wrench about the point ``(cx, cy)``."""
        return self.m + ((self.rx - cx) * self.fy - (self.ry - cy) * self.fx)

    def copy(self) -> "Wrench":
        return Wrench(self.rx, self.ry, self.fx, self.fy, self.m)


def reference_local(scene: Scene) -> dict:
    """Local point of each moving link used as its wrench reference.

    The centre of mass for a link that has one, else the ``at`` point of the
    link's first joint in scene order.
    """
    out = {}
    for link in scene.links:
        if link.com is not None:
            out[link.name] = tuple(link.com)
            continue
        for j in scene.joints:
            if link.name in j.links and j.type != "G":  # a mesh's pitch point is the carrier's
                out[link.name] = tuple(j.at)
                break
    return out


ACTIVE_END = 64 * float(np.finfo(float).eps)
"""How near an end of a load's ``active`` range a driver value counts as on it (ends
included), relative to the period (a ``P`` driver: to the range's largest value): a step
whose value is an end, computed with rounding (``start + k (stop - start) / (steps - 1)``,
``mod`` by the period), is never left out by a few ulps."""


def load_factor(load: Load, q: dict | None):
    """The factor of a load's force and torque at the driver values ``q`` (an extension of
    the format: loads over the cycle, :mod:`linkage_sym.scene.schedules`).

    ``1.0`` for a load that acts alike at every step; else an array over the
    steps: the table's factor, linearly interpolated (for an ``R`` driver
    periodically, with the load's period), times 0 outside its ``active``
    range (the range's ends included).

    Examples
    --------
    >>> import math
    >>> from linkage_sym.model import Load, LoadTable
    >>> press = Load("ram", torque=1.0, driver="A", period=2 * math.pi,
    ...              table=LoadTable((0.0, math.pi), (0.0, 1.0)), active=(0.0, math.pi))
    >>> load_factor(press, {"A": np.radians([45.0, 90.0, 270.0, 405.0])}).tolist()
    [0.25, 0.5, 0.0, 0.25]
    """
    if load.driver is None:
        return 1.0
    if q is None or load.driver not in q:
        raise ValueError(f"load on {load.link}: its factor follows driver {load.driver}, whose "
                         "values were not given")
    x = np.asarray(q[load.driver], dtype=float)
    f = np.ones_like(x)
    if load.table is not None:
        tq, ts = load.table.q, load.table.scale
        if load.period is not None:
            f = np.interp(x, tq, ts, period=load.period)
        else:
            outside = (x < tq[0]) | (x > tq[-1])
            if outside.any():
                raise ValueError(
                    f"load on {load.link}: driver {load.driver} at {x[outside][0]:g} m is outside "
                    f"its table ({tq[0]:g} to {tq[-1]:g} m), where the factor is not defined")
            f = np.interp(x, tq, ts)
    if load.active is not None:
        lo, hi = load.active
        if load.period is not None:
            # ends included: a value on an end, up to rounding, is in the range
            tol = ACTIVE_END * load.period
            d = np.mod(x - lo, load.period)
            inside = (d <= hi - lo + tol) | (d >= load.period - tol)
        else:
            tol = ACTIVE_END * max(abs(lo), abs(hi), hi - lo)
            inside = (x >= lo - tol) & (x <= hi + tol)
        f = np.where(inside, f, 0.0)
    return f


def applied_wrenches(scene: Scene, S, *, inertia=None, gravity=None, loads=None, q=None) -> dict:
    """The known loads of every moving link, as one :class:`Wrench` per link.

    Parameters
    ----------
    scene : Scene
    S : dict of LinkState
        Solved link states over the steps (accelerations are read only when
        inertia acts).
    inertia, gravity, loads
        Override the scene's ``effects`` (``None``: as the scene says).
    q : dict of ndarray, optional
        Driver values at the steps of ``S``, for loads that vary over the cycle
        (:func:`load_factor`); needed only by those.

    Returns
    -------
    dict of str to Wrench
        Also holds ``"ground"``: an empty wrench with its reference at the
        origin, to collect what the links put on the frame.

    Notes
    -----
    The scene's acting springs (``effects.springs``) are loads too
    (:mod:`~linkage_sym.numeric.forces.springs`); the part of a spring
    anchored on the ground goes into the ground's wrench.

    Only what acts is computed: a massless link gets no inertia or weight
    term, and accelerations are not touched without inertia.  The
    d'Alembert terms are ``-m a_G`` at the centre of mass and the couple
    ``-I_G alpha``.
    """
    eff = scene.effects
    inertia = eff.inertia if inertia is None else inertia
    gravity = eff.gravity if gravity is None else (gravity or None)
    loads = eff.loads if loads is None else loads
    ref = reference_local(scene)
    W = {GROUND: Wrench(0.0, 0.0)}
    for link in scene.links:
        st = S[link.name]
        rx, ry = st.point(ref[link.name])
        w = W[link.name] = Wrench(rx, ry)
        if link.com is not None and link.mass > 0:
            fx = fy = 0.0
            if inertia:
                ax, ay = st.point_acceleration(link.com)
                fx, fy = -link.mass * ax, -link.mass * ay
            if gravity is not None:
                fx = fx + link.mass * gravity[0]
                fy = fy + link.mass * gravity[1]
            w.fx, w.fy = fx, fy  # applied at the centre of mass, the reference point
        if inertia and link.inertia > 0:
            w.m = -link.inertia * st.al
    if loads:
        for load in scene.loads:
            st = S[load.link]
            w = W[load.link]
            k = load_factor(load, q)
            if load.force is not None:
                px, py = st.point(load.at)
                w.add_force(k * load.force[0], k * load.force[1], px, py)
            if load.torque:
                w.add_couple(k * load.torque)
    if scene.active_springs:  # the contract's springs and dampers, the ground's end included
        add_spring_wrenches(scene, S, W)
    return W
