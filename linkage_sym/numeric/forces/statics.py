"""Closed-form force routines of input links and of the five dyad types.

Conventions (scene format)
--------------------------
A joint's *reaction* is what its ``links[0]`` exerts on its ``links[1]``:

* ``R`` joint: a force ``(fx, fy)`` at the joint; no couple;
* ``P`` joint: a force ``N n`` normal to the slide (``n`` fixed on
  ``links[0]``) applied at the joint's reference point (fixed on
  ``links[1]``), and a couple ``m`` about that point.

Reactions are carried as triples ``(fx, fy, m)`` of arrays over the steps.
A driver's effort (torque of an ``R`` driver, axial force of a ``P`` driver
along the slide, applied at the reference point) is separate.

Each routine solves its group's own equilibrium (three equations per link)
under the known wrenches of its links (:class:`~linkage_sym.numeric.forces.loads.Wrench`:
applied loads plus the reactions of the groups solved after it), with no
linear-algebra call: every dyad type reduces to one 2x2 Cramer solve whose
determinant is, up to a length, the group's kinematic Jacobian determinant
(it vanishes exactly at the dyad's dead-centre positions).

Internally a routine works with the forces acting *on the dyad's links*:
``f0, c0`` on ``b0`` at the first external joint, ``fi, ci`` on ``b1`` from
``b0`` at the internal joint, ``f1, c1`` on ``b1`` at the second external
joint; :meth:`Geometry.reaction` turns them into reactions.
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.numeric.kinematics.cams import cam_geometry
from linkage_sym.numeric.kinematics.gears import mesh_direction
from linkage_sym.structure import Group


class Geometry:
    """Joint points and slide directions at the solved steps (computed once, cached).

    Parameters
    ----------
    scene : Scene
    S : dict of LinkState
    """

    def __init__(self, scene: Scene, S, flank=None):
        self.scene = scene
        self.S = S
        self._p = {}
        self._n = {}
        self.joint = {j.name: j for j in scene.joints}
        self.flank = {} if flank is None else flank
        """Gear mesh -> the flank (sign of the tangential force, +1 or -1 per step; default +1)."""

    def point(self, name):
        """Position of joint ``name`` (its point fixed on ``links[1]``; a mesh's pitch point)."""
        p = self._p.get(name)
        if p is None:
            j = self.joint[name]
            if j.type == "cam":  # the contact point
                self._cam(name)
                return self._p[name]
            p = self._p[name] = self.S[j.moves_with].point(j.at)
        return p

    def _cam(self, name):
        _, C, N, *_ = cam_geometry(self.joint[name]).contact(self.S)
        self._p[name], self._n[name] = C, N

    def contact_normal(self, name):
        """Unit normal ``(nx, ny)`` at cam contact ``name``'s contact point, from the cam
        towards the follower: the direction of the force the cam exerts on the follower."""
        if name not in self._n:
            self._cam(name)
        return self._n[name]

    def line_of_action(self, name):
        """Unit direction ``(ux, uy)`` of the force gear ``links[0]`` exerts on ``links[1]``
        of mesh ``name`` (:func:`~linkage_sym.numeric.kinematics.gears.mesh_direction`)."""
        n = self._n.get(name)
        if n is None:
            j = self.joint[name]
            n = self._n[name] = mesh_direction(
                self.scene, j, self.S[j.carrier], self.flank.get(name, 1.0))
        return n

    def normal(self, name):
        """Unit normal ``n`` and axis ``t`` of the slide of P joint ``name``: ``(nx, ny, tx, ty)``."""
        n = self._n.get(name)
        if n is None:
            j = self.joint[name]
            st = self.S[j.links[0]]
            tx, ty = st.rot((math.cos(j.axis), math.sin(j.axis)))
            n = self._n[name] = (-ty, tx, tx, ty)
        return n


def reaction_on(joint, link, fx, fy, m):
    """Convert a force and couple acting on ``link`` at ``joint`` into the joint's reaction."""
    if joint.links[1] == link:
        return fx, fy, m
    return -fx, -fy, -m


def push(W, joint, geo: Geometry, reaction, effort=None, only=None):
    """Apply a solved joint's reaction (and driver effort) to the wrenches of its links.

    ``links[1]`` receives the reaction, ``links[0]`` its opposite.  ``only``
    restricts the update to a set of link names.
    """
    fx, fy, m = reaction
    px, py = geo.point(joint.name)
    if effort is not None:
        if joint.type == "R":
            m = m + effort
        else:
            _, _, tx, ty = geo.normal(joint.name)
            fx, fy = fx + effort * tx, fy + effort * ty
    for link, s in ((joint.links[1], 1.0), (joint.links[0], -1.0)):
        if (only is not None and link not in only) or link not in W:
            continue
        w = W[link]
        if s > 0:
            w.add_force(fx, fy, px, py)
            w.add_couple(m)
        else:
            w.add_force(-fx, -fy, px, py)
            w.add_couple(-m)


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


class InputForces:
    """A link turning about (R) or sliding along (P) a joint to a known link.

    For a real input link the joint carries a driver and the routine returns
    its effort; for a *hypothetical* input link (Dang and Zhang) the same number is
    the equilibrium residual that the superposition drives to zero.
    """

    def __init__(self, scene: Scene, link: str, joint: str):
        self.link = link
        self.joint = scene.joint(joint)

    def solve(self, W, geo: Geometry):
        """``(reaction, effort)`` of the joint; the effort in the joint's own orientation."""
        j = self.joint
        w = W[self.link]
        px, py = geo.point(j.name)
        Mp = w.moment_about(px, py)
        if j.type == "R":
            f = (-w.fx, -w.fy, 0.0)
            effort_on_link = -Mp
        else:
            nx, ny, tx, ty = geo.normal(j.name)
            N = -(w.fx * nx + w.fy * ny)
            effort_on_link = -(w.fx * tx + w.fy * ty)
            f = (N * nx, N * ny, -Mp)
        sign = 1.0 if j.links[1] == self.link else -1.0
        return reaction_on(j, self.link, *f), sign * effort_on_link


class DyadForces:
    """Closed-form reactions of a dyad (RRR, RRP, RPR, PRP, RPP) from its own equilibrium."""

    def __init__(self, scene: Scene, group: Group):
        self.group = group
        self.type = group.dyad_type
        self.b0, self.b1 = group.links
        self.e0, self.ji, self.e1 = (scene.joint(n) for n in group.joints)

    def solve(self, W, geo: Geometry):
        """Reactions ``{joint: (fx, fy, m)}`` of the dyad's three joints."""
        t = self.type
        w0, w1 = W[self.b0], W[self.b1]
        e0, ji, e1 = self.e0.name, self.ji.name, self.e1.name
        P = geo.point(e0), geo.point(ji), geo.point(e1)
        if t not in _DYAD_SOLVERS:  # pragma: no cover - structure refuses other types
            raise ValueError(t)
        with np.errstate(divide="ignore", invalid="ignore"):
            f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci = _DYAD_SOLVERS[t](w0, w1, P, geo, (e0, ji, e1))
        return {
            e0: reaction_on(self.e0, self.b0, f0x, f0y, c0),
            ji: reaction_on(self.ji, self.b1, fix, fiy, ci),
            e1: reaction_on(self.e1, self.b1, f1x, f1y, c1),
        }


def _rrr(w0, w1, P, geo, names) -> tuple:
    """RRR dyad: moments of each link about the internal joint and the dyad's force balance.

    Returns ``(f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci)``: the forces on ``links[0]`` at its
    outer joint, on ``links[1]`` at its outer joint and at the inner joint, and the couples.
    """
    e0, ji, e1 = names
    Pe0, Pi, Pe1 = P
    F0x, F0y, F1x, F1y = w0.fx, w0.fy, w1.fx, w1.fy
    Fx, Fy = F0x + F1x, F0y + F1y
    zero = 0.0
    # moments of each link about the internal joint and the dyad's force balance
    ux, uy = Pe0[0] - Pi[0], Pe0[1] - Pi[1]
    vx, vy = Pe1[0] - Pi[0], Pe1[1] - Pi[1]
    r1 = -w0.moment_about(*Pi)  # u x f0 = r1
    # v x f1 = -M1 with f1 = -F - f0:  v x f0 = M1 - v x F = r2
    r2 = w1.moment_about(*Pi) - _cross(vx, vy, Fx, Fy)
    det = _cross(ux, uy, vx, vy)
    f0x = (r1 * vx - ux * r2) / det
    f0y = (vy * r1 - uy * r2) / det
    f1x, f1y = -Fx - f0x, -Fy - f0y
    fix, fiy = f0x + F0x, f0y + F0y
    c0 = c1 = ci = zero
    return f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci


def _rrp(w0, w1, P, geo, names) -> tuple:
    """RRP dyad: the first link's moment about the inner joint, the second's slide.

    Returns ``(f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci)``: the forces on ``links[0]`` at its
    outer joint, on ``links[1]`` at its outer joint and at the inner joint, and the couples.
    """
    e0, ji, e1 = names
    Pe0, Pi, Pe1 = P
    F0x, F0y, F1x, F1y = w0.fx, w0.fy, w1.fx, w1.fy
    Fx, Fy = F0x + F1x, F0y + F1y
    zero = 0.0
    ux, uy = Pe0[0] - Pi[0], Pe0[1] - Pi[1]
    n1x, n1y, t1x, t1y = geo.normal(e1)
    r1 = -w0.moment_about(*Pi)  # u x f0 = r1
    r2 = -(Fx * t1x + Fy * t1y)  # f0 . t1 = r2
    det = -(ux * t1x + uy * t1y)
    f0x = (r1 * t1y - ux * r2) / det
    f0y = (-uy * r2 - t1x * r1) / det
    N1 = -((Fx + f0x) * n1x + (Fy + f0y) * n1y)
    f1x, f1y = N1 * n1x, N1 * n1y
    c0 = ci = zero
    fix, fiy = f0x + F0x, f0y + F0y
    # b1 about the slide's reference point: (Pi - Pe1) x fi + c1 + M1 = 0
    c1 = -_cross(Pi[0] - Pe1[0], Pi[1] - Pe1[1], fix, fiy) - w1.moment_about(*Pe1)
    return f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci


def _rpr(w0, w1, P, geo, names) -> tuple:
    """RPR dyad: moments about the first outer joint, the force along the inner slide.

    Returns ``(f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci)``: the forces on ``links[0]`` at its
    outer joint, on ``links[1]`` at its outer joint and at the inner joint, and the couples.
    """
    e0, ji, e1 = names
    Pe0, Pi, Pe1 = P
    F0x, F0y, F1x, F1y = w0.fx, w0.fy, w1.fx, w1.fy
    Fx, Fy = F0x + F1x, F0y + F1y
    zero = 0.0
    nix, niy, tix, tiy = geo.normal(ji)
    wx, wy = Pe1[0] - Pe0[0], Pe1[1] - Pe0[1]
    r1 = -(w0.moment_about(*Pe0) + w1.moment_about(*Pe0))  # w x f1 = r1
    r2 = -(F1x * tix + F1y * tiy)  # f1 . ti = r2
    det = -(wx * tix + wy * tiy)
    f1x = (r1 * tiy - wx * r2) / det
    f1y = (-wy * r2 - tix * r1) / det
    f0x, f0y = -Fx - f1x, -Fy - f1y
    fix, fiy = -f1x - F1x, -f1y - F1y
    Ni = fix * nix + fiy * niy
    fix, fiy = Ni * nix, Ni * niy
    ci = -_cross(Pe1[0] - Pi[0], Pe1[1] - Pi[1], f1x, f1y) - w1.moment_about(*Pi)
    c0 = c1 = zero
    return f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci


def _prp(w0, w1, P, geo, names) -> tuple:
    """PRP dyad: two slides, their normal forces from the dyad's force balance.

    Returns ``(f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci)``: the forces on ``links[0]`` at its
    outer joint, on ``links[1]`` at its outer joint and at the inner joint, and the couples.
    """
    e0, ji, e1 = names
    Pe0, Pi, Pe1 = P
    F0x, F0y, F1x, F1y = w0.fx, w0.fy, w1.fx, w1.fy
    Fx, Fy = F0x + F1x, F0y + F1y
    zero = 0.0
    n0x, n0y, _, _ = geo.normal(e0)
    n1x, n1y, _, _ = geo.normal(e1)
    det = _cross(n0x, n0y, n1x, n1y)
    N0 = _cross(-Fx, -Fy, n1x, n1y) / det
    N1 = _cross(-Fx, -Fy, n0x, n0y) / -det
    f0x, f0y = N0 * n0x, N0 * n0y
    f1x, f1y = N1 * n1x, N1 * n1y
    fix, fiy = f0x + F0x, f0y + F0y
    # b0 about Pe0: c0 - (Pi - Pe0) x fi + M0 = 0
    c0 = _cross(Pi[0] - Pe0[0], Pi[1] - Pe0[1], fix, fiy) - w0.moment_about(*Pe0)
    c1 = -_cross(Pi[0] - Pe1[0], Pi[1] - Pe1[1], fix, fiy) - w1.moment_about(*Pe1)
    ci = zero
    return f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci


def _rpp(w0, w1, P, geo, names) -> tuple:
    """RPP dyad: the inner and outer slides' normal forces from the second link's balance.

    Returns ``(f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci)``: the forces on ``links[0]`` at its
    outer joint, on ``links[1]`` at its outer joint and at the inner joint, and the couples.
    """
    e0, ji, e1 = names
    Pe0, Pi, Pe1 = P
    F0x, F0y, F1x, F1y = w0.fx, w0.fy, w1.fx, w1.fy
    zero = 0.0
    nix, niy, _, _ = geo.normal(ji)
    n1x, n1y, _, _ = geo.normal(e1)
    det = _cross(nix, niy, n1x, n1y)
    Ni = _cross(-F1x, -F1y, n1x, n1y) / det
    N1 = _cross(-F1x, -F1y, nix, niy) / -det
    fix, fiy = Ni * nix, Ni * niy
    f1x, f1y = N1 * n1x, N1 * n1y
    f0x, f0y = fix - F0x, fiy - F0y
    # b0 about Pe0: -(Pi - Pe0) x fi - ci + M0 = 0
    ci = w0.moment_about(*Pe0) - _cross(Pi[0] - Pe0[0], Pi[1] - Pe0[1], fix, fiy)
    c1 = -(
        _cross(Pi[0] - Pe1[0], Pi[1] - Pe1[1], fix, fiy) + ci + w1.moment_about(*Pe1)
    )
    c0 = zero
    return f0x, f0y, f1x, f1y, fix, fiy, c0, c1, ci


_DYAD_SOLVERS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}
"""The reactions of each dyad type, by :attr:`Group.dyad_type` (see :class:`DyadStatics`)."""
