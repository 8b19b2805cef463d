"""Gear meshes (``G`` joints): the closed form of a gear on its pivot, and its forces.

A mesh joins gears ``a`` and ``b`` turning on pivots of a carrier ``c``;
rolling without slip, ``ra (theta_a - theta_c) = -+ rb (theta_b - theta_c)``
(minus external, plus internal), angles being rotations from the assembly
configuration.  A gear whose pivot link and whose mate are known is a
one-link group (kind ``"gear"``): its rotation is linear in the known angles
and its pose follows from its pivot, in closed form (:class:`GearSolver`).
Groups of several links with meshes (a planet and its carrier driven through
the sun) are solved by the Newton solver on the mesh rows of
:class:`~linkage_sym.numeric.kinematics.constraints.GMesh`.

Forces
------
The mesh force acts at the pitch point along the *line of action*, tilted
by the pressure angle ``phi`` from the common tangent: the force gear ``a``
exerts on gear ``b`` is ``Fn u`` with ``u = s cos(phi) t + rho sin(phi) e``,
``e`` the unit vector from ``a``'s centre to ``b``'s, ``t`` it turned by
+90 degrees, ``rho`` +1 for an external mesh and -1 for an internal one (the
radial part presses each gear's teeth into its body, whichever the flank)
and ``s`` the *flank*: the sign of the tangential force.  The flank is what
makes the tooth load ``Fn`` non-negative; :func:`mesh_direction` gives ``u`` for given flanks
and :class:`GearForces` solves a one-link gear group's equilibrium in closed
form (moments about the pivot give ``Fn``, the force balance the pivot's
reaction).
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.numeric.results.wording import steps_text
from linkage_sym.structure import Group


def mesh_axes(scene: Scene, mesh):
    """Unit vector ``e0`` from gear a's centre to gear b's in the assembly
    configuration (fixed on the carrier) and ``rho`` (+1 external, -1 internal)."""
    pa, pb = (j.at for j in scene.gear_pivots(mesh))
    d = math.dist(pa, pb)
    return ((pb[0] - pa[0]) / d, (pb[1] - pa[1]) / d), (-1.0 if mesh.internal else 1.0)


def pulling_note(name: str, steps, solves: int) -> str:
    """The warning of a mesh whose tooth load still pulls at ``steps`` after ``solves``
    force solves with either flank (both runtimes)."""
    return (f"gear mesh {name}: the tooth load still pulls at {len(steps)} step(s) (steps "
            f"{steps_text(steps, len(steps))}) after {solves} force solves with either flank: "
            "the mesh force reported there is not one its teeth can carry")


def mesh_direction(scene: Scene, mesh, carrier_state, flank):
    """Unit line of action ``(ux, uy)`` of the force of gear a on gear b.

    ``carrier_state`` is the carrier's :class:`LinkState`, ``flank`` the sign
    (+1 or -1, an array over the steps) of the tangential force.
    """
    e0, rho = mesh_axes(scene, mesh)
    ex, ey = carrier_state.rot(e0)
    cp, sp = math.cos(mesh.pressure_angle), math.sin(mesh.pressure_angle)
    return flank * cp * -ey + rho * sp * ex, flank * cp * ex + rho * sp * ey


class GearSolver:
    """A gear turning on a pivot of a known link, meshing with a known gear.

    Its rotation ``theta = theta_c + k (theta_m - theta_c)`` (``m`` the mate,
    ``c`` the carrier, ``k = -+ r_m / r``), its origin placed so that its
    pivot point is where the pivot's other link has it.
    """

    notes = ()
    wraps = False  # linear in rotations from the assembly configuration
    """Jumps worth a warning: none (the gear's rotation is linear in the known angles)."""

    def __init__(self, scene: Scene, group: Group):
        (self.link,) = group.links
        self.group = group
        mesh = next(scene.joint(n) for n in group.joints if scene.joint(n).type == "G")
        pivot = next(scene.joint(n) for n in group.joints if scene.joint(n).type == "R")
        self.mesh, self.pivot = mesh.name, pivot.name
        self.carrier = mesh.carrier
        k = 0 if mesh.links[0] == self.link else 1
        self.mate = mesh.links[1 - k]
        r_self, r_mate = mesh.radii[k], mesh.radii[1 - k]
        self.k = (1.0 if mesh.internal else -1.0) * r_mate / r_self
        self.base = pivot.links[0] if pivot.links[1] == self.link else pivot.links[1]
        self.X = pivot.at

    def _angle(self, S, field):
        c, m = getattr(S[self.carrier], field), getattr(S[self.mate], field)
        return c + self.k * (m - c)

    def position(self, S, q):
        u = S[self.link]
        u.set_pose(self._angle(S, "th"), 0.0, 0.0)
        Y = S[self.base].point(self.X)
        rx, ry = u.rot(self.X)
        u.dx, u.dy = Y[0] - rx, Y[1] - ry
        return None  # assemblable wherever its mate and carrier are, never singular

    def failure(self, S, i) -> str:  # pragma: no cover - position never fails
        return f"gear {self.link}: cannot be placed"

    def velocity(self, S, q, qd):
        u = S[self.link]
        u.w = self._angle(S, "w")
        vx, vy = S[self.base].point_velocity(self.X)
        rx, ry = u.rot(self.X)
        u.vx, u.vy = vx + u.w * ry, vy - u.w * rx

    def acceleration(self, S, q, qd, qdd):
        u = S[self.link]
        u.al = self._angle(S, "al")
        ax, ay = S[self.base].point_acceleration(self.X)
        rx, ry = u.rot(self.X)
        w2 = u.w * u.w
        u.ax = ax + u.al * ry + w2 * rx
        u.ay = ay - u.al * rx + w2 * ry


class GearForces:
    """Closed-form forces of a one-link gear group: the tooth load and the pivot's reaction."""

    def __init__(self, scene: Scene, group: Group):
        (self.link,) = group.links
        self.mesh = next(scene.joint(n) for n in group.joints if scene.joint(n).type == "G")
        self.pivot = next(scene.joint(n) for n in group.joints if scene.joint(n).type == "R")
        # the force on this gear is sign * Fn * u
        self.sign = 1.0 if self.mesh.links[1] == self.link else -1.0

    def solve(self, W, geo, L, K):
        """Reactions ``{joint: (fx, fy, m)}`` of the mesh and the pivot over ``K`` steps."""
        w = W[self.link]
        ox, oy = geo.point(self.pivot.name)
        px, py = geo.point(self.mesh.name)
        ux, uy = geo.line_of_action(self.mesh.name)
        s = self.sign
        # moments about the pivot: M + (P - O) x (s Fn u) = 0
        arm = (px - ox) * uy - (py - oy) * ux
        Fn = -w.moment_about(ox, oy) / (s * arm)
        gx, gy = -(w.fx + s * Fn * ux), -(w.fy + s * Fn * uy)  # the pivot's force on the gear
        zero = np.zeros(K)
        if self.pivot.links[1] == self.link:
            pivot = (gx + zero, gy + zero, zero)
        else:
            pivot = (-gx + zero, -gy + zero, zero)
        return {self.mesh.name: (Fn * ux, Fn * uy, zero), self.pivot.name: pivot}
