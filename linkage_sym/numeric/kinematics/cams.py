"""Cam contacts (``cam`` joints): positions, the instantaneous replacement, records.

A cam contact keeps a follower element on link ``links[1]`` -- a knife-edge
point, a roller's centre at the roller's radius from the profile, or a flat
face tangent to it -- in contact with the profile ``C(u)`` of the cam
``links[0]`` (:class:`~linkage_sym.numeric.kinematics.cam_profile.CamProfile`, in the
cam's frame).  It is a higher pair: one equation.

Positions
---------
A follower turning on a pivot or sliding on a slide of a known link, touching
a known cam, is a one-link group (kind ``"cam"``, :class:`CamSolver`).  Its
position comes from the contact conditions with the profile parameter ``u``
as the extra unknown: written in the cam's frame, the follower's coordinate
is eliminated and one equation ``f(u) = 0`` is left (the roller centre
``C + rho N`` at the arm's length from the pivot, or on the slide's line; the
flat face's normal ``N(u)`` at the face's distance from the pivot, or along
the slide's face normal).  Its roots are bracketed on a grid of ``u`` and
bisected to rounding; of the two roots a convex profile gives, the branch is
the one whose ``f'`` has the sign it has in the assembly configuration (the
assembly mode), as a dyad keeps the sign of its closed form.

Velocities and accelerations: the instantaneous replacement
-------------------------------------------------------------
As the textbook chapter 3 (kinematic analysis of planar mechanisms) does
for higher pairs (Fig. 3-5 and the replacement passage), the contact is
replaced at each instant by lower pairs: the profile's centre of curvature
``K = C - N / kappa`` becomes a pivot fixed on the cam, joined by a binary
link of length ``1/kappa + rho`` to the roller's centre (``rho = 0`` for a
knife-edge: its point); for a flat face, ``K`` slides in a slot of the
follower parallel to the face at ``1/kappa`` from it.  The replacement's
velocity and acceleration rows (:class:`CamContact`) are those of that
binary link (a distance row) or slider (a ``P`` joint's offset row), so the
follower's rates are those of the replacement four-bar or slider mechanism.
They are checked in ``tests/numeric/test_cams.py`` against an independent solve of
the direct contact equations (implicit differentiation) and closed forms.

Reported per step
-----------------
A step where the follower cannot reach the profile, or where it would have
to follow what it cannot (a roller larger than a concave part's radius of
curvature, a roller larger than a convex part of its pitch curve: an
undercut working profile, a flat face on a part that is not convex), is
unassemblable with that reason (:meth:`CamSolver.failure`); the other steps
are solved.  A contact force that would pull is a warning of the force
solve (``kinetostatics.pulling_notes``): a cam can only push.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.kinematics.cam_profile import GRID, TWO_PI, CamProfile
from linkage_sym.numeric.kinematics.constraints import Constraint
from linkage_sym.structure import Group

STRAIGHT = 1e-9
"""``|kappa| L`` below which the profile counts as straight at the contact: the centre
of curvature is at infinity and the replacement is a slider."""

BISECTIONS = 60
"""Bisections of a grid interval: its width ``2 pi / GRID`` below rounding of ``u``."""


@functools.lru_cache(maxsize=64)
def cam_geometry(joint) -> "CamGeometry":
    """The :class:`CamGeometry` of a ``cam`` joint (made once per joint)."""
    return CamGeometry(joint)


def _to_local(st, x, y):
    """Global point(s) ``(x, y)`` in the frame of a link state."""
    dx, dy = x - st.dx, y - st.dy
    return st.c * dx + st.s * dy, -st.s * dx + st.c * dy


def _rot(st, x, y):
    return st.c * x - st.s * y, st.s * x + st.c * y


def _vel(st, x, y):
    """Velocity of the link's material point at global ``(x, y)``."""
    return st.vx - st.w * (y - st.dy), st.vy + st.w * (x - st.dx)


def _acc(st, x, y):
    """Acceleration of the link's material point at global ``(x, y)``."""
    rx, ry = x - st.dx, y - st.dy
    w2 = st.w * st.w
    return st.ax - st.al * ry - w2 * rx, st.ay + st.al * rx - w2 * ry


class CamGeometry:
    """A cam joint's profile and follower element (see the module docstring)."""

    def __init__(self, joint):
        spec = joint.cam
        self.name = joint.name
        self.cam, self.follower = joint.links
        self.profile = CamProfile(spec.profile, spec.data)
        self.kind = spec.follower
        self.pitch = spec.pitch
        self.radius = spec.radius
        self.rho = spec.radius if spec.follower == "roller" and not spec.pitch else 0.0
        self.P0 = joint.at
        self.m0 = None
        if self.kind == "flat":  # the face normal, pointing away from the cam
            mx, my = -math.sin(spec.face), math.cos(spec.face)
            h = mx * joint.at[0] + my * joint.at[1]
            hi, lo = (
                float(mx * c[0][0] + my * c[1][0])
                for c in (self.profile.evaluate(self.profile.support(d * mx, d * my), 0)[0]
                          for d in (1.0, -1.0))
            )
            if abs(h - hi) > abs(h - lo):  # the face touches the profile's other side
                mx, my = -mx, -my
            self.m0 = (mx, my)

    def contact(self, S):
        """The contact at the states ``S``: parameter, point, normal, tangent, curvature.

        Returns ``(u, (cx, cy), (nx, ny), (tx, ty), kappa, (px, py))``, global
        vectors; ``N`` is the profile's outward normal (from the cam towards the
        follower), ``P`` the follower's element point (roller centre, knife
        point; the contact point for a flat face).
        """
        c, f = S[self.cam], S[self.follower]
        if self.kind == "flat":
            mx, my = _rot(f, *self.m0)
            lx, ly = _rot_inv(c, mx, my)
            u = self.profile.support(lx, ly)
        else:
            px, py = f.point(self.P0)
            lx, ly = _to_local(c, px, py)
            u = self.profile.nearest(lx, ly)
        (x, y), (tx, ty), (nx, ny), kappa = self.profile.frame(u)
        cx, cy = _point(c, x, y)
        tx, ty = _rot(c, tx, ty)
        nx, ny = _rot(c, nx, ny)
        if self.kind == "flat":
            px, py = cx, cy
        return u, (cx, cy), (nx, ny), (tx, ty), kappa, (px, py)


def _rot_inv(st, x, y):
    return st.c * x + st.s * y, -st.s * x + st.c * y


def _point(st, x, y):
    rx, ry = _rot(st, x, y)
    return st.dx + rx, st.dy + ry


class CamContact(Constraint):
    """The rows of a cam contact: the gap (positions) and the replacement's rates.

    ``residual`` is the signed gap along the normal (roller: minus its radius);
    ``rate`` and ``accel`` are the rows of the instantaneous replacement (see
    the module docstring); ``jac`` their coefficients.
    """

    rows = 1
    length_rows = (True,)

    def __init__(self, joint, L: float = 1.0):
        self.geo = cam_geometry(joint)
        self.links = (self.geo.cam, self.geo.follower)
        self.L = L

    def _parts(self, S):
        g = self.geo
        u, C, N, T, kappa, P = g.contact(S)
        straight = np.abs(kappa) * self.L < STRAIGHT
        rc = 1.0 / np.where(straight, 1.0, kappa)  # signed radius of curvature
        K = (C[0] - rc * N[0], C[1] - rc * N[1])  # the centre of curvature, on the cam
        return C, N, kappa, P, straight, rc, K

    def residual(self, S, q):
        C, N, _, P, *_ = self._parts(S)
        if self.geo.kind == "flat":
            px, py = S[self.geo.follower].point(self.geo.P0)
            return [N[0] * (px - C[0]) + N[1] * (py - C[1])]
        return [N[0] * (P[0] - C[0]) + N[1] * (P[1] - C[1]) - self.geo.rho]

    def rate(self, S, qd):
        C, N, kappa, P, straight, rc, K = self._parts(S)
        c, f = S[self.geo.cam], S[self.geo.follower]
        X = K if self.geo.kind == "flat" else P
        va, vb = _vel(f, *X), _vel(c, *(X if self.geo.kind == "flat" else K))
        if self.geo.kind == "flat":  # the slider: N . (v_K,cam - v_K,follower)
            return [N[0] * (vb[0] - va[0]) + N[1] * (vb[1] - va[1])]
        # the binary link K-P: N . (v_P,follower - v_K,cam) (K anywhere on the normal)
        return [N[0] * (va[0] - vb[0]) + N[1] * (va[1] - vb[1])]

    def accel(self, S, qdd):
        C, N, kappa, P, straight, rc, K = self._parts(S)
        c, f = S[self.geo.cam], S[self.geo.follower]
        nx, ny = N
        if self.geo.kind == "flat":
            # K on the cam slides in a slot of the follower: n . r = const with n fixed on
            # the follower and r = K_cam - K_follower (zero now): 2 n' . r' + n . r''
            vc, vf = _vel(c, *K), _vel(f, *K)
            ac, af = _acc(c, *K), _acc(f, *K)
            rvx, rvy = vc[0] - vf[0], vc[1] - vf[1]
            return [2 * f.w * (-ny * rvx + nx * rvy) + nx * (ac[0] - af[0]) + ny * (ac[1] - af[1])]
        vP, aP = _vel(f, *P), _acc(f, *P)
        ell = rc + self.geo.rho  # the binary link's signed length
        vK, aK = _vel(c, *K), _acc(c, *K)
        rvx, rvy = vP[0] - vK[0], vP[1] - vK[1]
        tang = (-ny * rvx + nx * rvy) ** 2  # |v_rel|^2 - (N . v_rel)^2
        link = nx * (aP[0] - aK[0]) + ny * (aP[1] - aK[1]) + tang / np.where(straight, 1.0, ell)
        # a straight part: the replacement is a slider along the tangent, fixed on the cam
        vC, aC = _vel(c, *P), _acc(c, *P)
        sx, sy = vP[0] - vC[0], vP[1] - vC[1]
        slide = nx * (aP[0] - aC[0]) + ny * (aP[1] - aC[1]) - 2 * c.w * (-ny * sx + nx * sy)
        return [np.where(straight, slide, link)]

    def jac(self, S, link):
        C, N, kappa, P, straight, rc, K = self._parts(S)
        st = S[link]
        is_cam = link == self.geo.cam
        X = K if (self.geo.kind == "flat" or is_cam) else P
        sign = 1.0 if (link == self.geo.follower) != (self.geo.kind == "flat") else -1.0
        rx, ry = X[0] - st.dx, X[1] - st.dy
        return [(sign * N[0], sign * N[1], sign * (-N[0] * ry + N[1] * rx))]


class CamSolver:
    """A follower on a pivot (R) or slide (P) of a known link, touching a known cam.

    See the module docstring: positions from the contact conditions (one
    equation in the profile parameter), rates and accelerations from the
    replacement's rows of :class:`CamContact`.
    """

    wraps = True
    """A pivoted follower's rotation comes from an ``atan2``: unwrapped by the plan."""
    notes = ()
    """Jumps worth a warning: none (the branch is kept by its sign, as a dyad's)."""

    def __init__(self, scene: Scene, group: Group, L: float):
        self.group = group
        self.scene = scene
        if len(group.links) != 1:
            names = ", ".join(j for j in group.joints if scene.joint(j).type == "cam")
            raise SceneError([
                f"joints: cam contact(s) {names} in a group of {len(group.links)} links "
                f"({', '.join(group.links)}): a cam's follower must be a link turning on a pivot "
                "or sliding on a slide of a link known before it (a disc cam's rocker or "
                "translating follower); other arrangements are not supported yet"])
        (self.link,) = group.links
        cam_joint = next(scene.joint(n) for n in group.joints if scene.joint(n).type == "cam")
        pivot = next(scene.joint(n) for n in group.joints if scene.joint(n).type != "cam")
        if cam_joint.links[1] != self.link:
            raise SceneError([f"joints: the follower of cam contact '{cam_joint.name}' is "
                              f"'{cam_joint.links[1]}', but the cam '{cam_joint.links[0]}' is "
                              "solved after it: a cam must be known before its follower"])
        self.joint, self.pivot = cam_joint, pivot
        self.geo = cam_geometry(cam_joint)
        self.row = CamContact(cam_joint, L)
        self.L = L
        self.known = pivot.links[0] if pivot.links[1] == self.link else pivot.links[1]
        self.case = ("flat" if self.geo.kind == "flat" else "point") + "-" + pivot.type
        self.Y = pivot.at
        if pivot.type == "P":
            self.a0 = (math.cos(pivot.axis), math.sin(pivot.axis))
            if self.geo.kind == "flat":
                m = self.geo.m0
                if abs(m[0] * self.a0[0] + m[1] * self.a0[1]) < 1e-9:
                    raise SceneError([f"joints: the flat face of cam contact '{cam_joint.name}' "
                                      f"is parallel to the slide of joint '{pivot.name}': the "
                                      "cam cannot move the follower along it"])
        else:
            self.l = math.dist(self.geo.P0, self.Y)
            if self.l == 0.0 and self.geo.kind != "flat":
                raise SceneError([f"joints[{scene.joints.index(cam_joint)}].at: the follower's "
                                  f"point is on its pivot '{pivot.name}': the cam cannot turn it"])
            if self.geo.kind == "flat":
                m = self.geo.m0
                self.d = m[0] * (self.geo.P0[0] - self.Y[0]) + m[1] * (self.geo.P0[1] - self.Y[1])
        ground = {n: _Still() for n in (GROUND, self.known, cam_joint.links[0])}
        self.sigma = self._assembly_sign(ground)
        self._why = None

    # -- positions -----------------------------------------------------------
    def _params(self, S):
        """Per-step data of ``f(u)`` in the cam's frame."""
        c, k = S[self.joint.links[0]], S[self.known]
        Yx, Yy = k.point(self.Y)
        out = {"Y": (Yx, Yy)}
        if self.pivot.type == "R":
            out["Yc"] = _to_local(c, Yx, Yy)
        else:
            ax, ay = _rot(k, *self.a0)
            out["a"] = (ax, ay)
            out["ac"] = _rot_inv(c, ax, ay)
            bx, by = k.point(self.geo.P0)  # the element point with the slide at zero
            out["b"] = (bx, by)
            out["bc"] = _to_local(c, bx, by)
            if self.geo.kind == "flat":
                mx, my = _rot(k, *self.geo.m0)
                out["mc"] = _rot_inv(c, mx, my)
        return out

    def _f(self, u, p, e=lambda v: v):
        """``f(u)`` (see the module docstring); ``e`` shapes per-step values against ``u``."""
        (x, y), _, (nx, ny), _ = self.geo.profile.frame(u)
        rho = self.geo.rho
        if self.case == "point-R":
            qx, qy = x + rho * nx - e(p["Yc"][0]), y + rho * ny - e(p["Yc"][1])
            return (qx * qx + qy * qy - self.l**2) / self.L
        if self.case == "point-P":
            ax, ay = e(p["ac"][0]), e(p["ac"][1])
            return ax * (y + rho * ny - e(p["bc"][1])) - ay * (x + rho * nx - e(p["bc"][0]))
        if self.case == "flat-R":
            return (nx * (x - e(p["Yc"][0])) + ny * (y - e(p["Yc"][1])) - self.d) / self.L
        mx, my = e(p["mc"][0]), e(p["mc"][1])
        return nx * my - ny * mx

    def _assembly_sign(self, S0):
        p = self._params(S0)
        g = self.geo
        if g.kind == "flat":
            u0 = float(g.profile.support(*g.m0)[0])
        else:
            u0 = float(g.profile.nearest(*g.P0)[0])
        h = 1e-6
        s = np.sign(self._f(np.array([u0 + h]), p) - self._f(np.array([u0 - h]), p))
        if not s:
            raise SceneError([f"joints: cam contact '{self.joint.name}' is singular in the "
                              "assembly configuration (the follower's path is tangent to the "
                              "profile there): its branch is undefined"])
        self.u0 = u0
        return float(s[0])

    def position(self, S, q):
        c, k, f = S[self.joint.links[0]], S[self.known], S[self.link]
        n = len(next(iter(q.values())))
        p = self._params(S)
        p = {key: tuple(np.broadcast_to(np.asarray(v, float), (n,)) for v in val)
             for key, val in p.items()}
        grid = np.linspace(0.0, TWO_PI, GRID + 1)
        F = self.sigma * self._f(grid[None, :], p, lambda v: v[:, None])  # (n, GRID + 1)
        up = (F[:, :-1] <= 0) & (F[:, 1:] > 0)
        count = up.sum(axis=1)
        first = np.argmax(up, axis=1)
        lo, hi = grid[first], grid[first + 1]
        for i in np.flatnonzero(count > 1):  # several contacts: the one nearest the previous
            cand = grid[np.flatnonzero(up[i])]
            prev = self.u0 if i == 0 else lo[i - 1]
            dist = np.abs(np.angle(np.exp(1j * (cand - prev))))
            lo[i] = cand[np.argmin(dist)]
            hi[i] = lo[i] + TWO_PI / GRID
        for _ in range(BISECTIONS):
            mid = 0.5 * (lo + hi)
            right = self.sigma * self._f(mid, p) > 0
            hi = np.where(right, mid, hi)
            lo = np.where(right, lo, mid)
        u = 0.5 * (lo + hi)
        (x, y), _, (nx, ny), kappa = self.geo.profile.frame(u)
        rho = self.geo.rho
        if self.case == "point-R":
            qx, qy = _point(c, x + rho * nx, y + rho * ny)
            Yx, Yy = p["Y"]
            th = np.arctan2(qy - Yy, qx - Yx) - math.atan2(self.geo.P0[1] - self.Y[1],
                                                            self.geo.P0[0] - self.Y[0])
        elif self.case == "flat-R":
            mx, my = _rot(c, nx, ny)
            th = np.arctan2(my, mx) - math.atan2(self.geo.m0[1], self.geo.m0[0])
        else:
            th = k.th
            ac = p["ac"]
            if self.case == "point-P":
                s = ac[0] * (x + rho * nx - p["bc"][0]) + ac[1] * (y + rho * ny - p["bc"][1])
            else:
                mc = p["mc"]
                s = (mc[0] * (x - p["bc"][0]) + mc[1] * (y - p["bc"][1])) / (
                    mc[0] * ac[0] + mc[1] * ac[1])
        L = self.L
        why = np.where(count == 0, 1, 0)
        if self.geo.kind == "roller" and not self.geo.pitch:
            # the roller cannot reach a concave part tighter than itself: there its centre
            # would be nearer another part of the profile than its radius (it rests on two)
            qx, qy = x + rho * nx, y + rho * ny
            near = self.geo.profile.nearest(qx, qy)
            (ex, ey), = self.geo.profile.evaluate(near, 0)
            inside = np.hypot(qx - ex, qy - ey) < rho * (1.0 - 1e-9)
            why = np.where((count > 0) & (((kappa < 0) & (1 + rho * kappa <= 0)) | inside), 2, why)
        elif self.geo.kind == "roller":
            why = np.where((count > 0) & (kappa > 0) & (self.geo.radius * kappa >= 1), 3, why)
        elif self.geo.kind == "flat":
            why = np.where((count > 0) & (kappa * L < STRAIGHT), 4, why)
        self._why, self._kappa = why, kappa
        if self.pivot.type == "R":
            f.set_pose(np.where(why == 0, th, np.nan), 0.0, 0.0)
            rx, ry = f.rot(self.Y)
            Yx, Yy = p["Y"]
            f.dx, f.dy = Yx - rx, Yy - ry
        else:
            s = np.where(why == 0, s, np.nan)
            ax, ay = p["a"]
            f.set_pose(np.broadcast_to(th, (n,)) + 0.0 * s, k.dx + s * ax, k.dy + s * ay)
        ind = np.abs(self._cos_pressure(S))
        return np.where(why == 0, ind, np.nan)

    def _direction(self, S, P):
        """Unit direction of the follower's element point's velocity in its own motion."""
        k = S[self.known]
        if self.pivot.type == "P":
            return _rot(k, *self.a0)
        Yx, Yy = k.point(self.Y)
        dx, dy = P[0] - Yx, P[1] - Yy
        r = np.hypot(dx, dy)
        r = np.where(r > 0, r, 1.0)
        return -dy / r, dx / r

    def _cos_pressure(self, S, sine=False):
        _, C, N, _, _, P = self.geo.contact(S)
        vx, vy = self._direction(S, P)
        cos = N[0] * vx + N[1] * vy
        return (cos, N[0] * vy - N[1] * vx) if sine else cos

    def pressure_angle(self, S):
        """The pressure angle (rad, 0 to pi/2) at the states ``S``: between the contact
        normal and the velocity of the follower's element point (its own motion)."""
        cos, sin = self._cos_pressure(S, sine=True)
        return np.arctan2(np.abs(sin), np.abs(cos))

    def failure(self, S, i):
        why = int(np.asarray(self._why)[i]) if self._why is not None else 1
        name = self.joint.name
        kappa = float(np.asarray(self._kappa)[i])
        r = abs(1.0 / kappa) if kappa else math.inf
        if why == 2:
            return (f"cam contact {name}: the roller (radius {self.geo.radius:g} m) cannot reach "
                    "the profile's contact: a concave part of the profile is tighter than the "
                    f"roller there (radius of curvature {r:.4g} m at the contact point, or the "
                    "roller resting on two points of it): undercut")
        if why == 3:
            return (f"cam contact {name}: the pitch curve's radius of curvature {r:.4g} m is "
                    f"smaller than the roller's radius {self.geo.radius:g} m at the contact: the "
                    "working profile is undercut there")
        if why == 4:
            return (f"cam contact {name}: the profile is not convex at the contact (curvature "
                    f"{kappa:.4g} 1/m): a flat face cannot follow it there")
        return (f"cam contact {name}: the follower on '{self.pivot.name}' cannot reach the "
                "cam's profile (no contact position on its branch)")

    # -- rates: the replacement's rows, linear in the follower's own rate -----
    def _solve_rate(self, S, set_rate, row):
        set_rate(0.0)
        r0 = row()
        set_rate(1.0)
        r1 = row()
        x = -r0 / (r1 - r0)
        set_rate(x)

    def velocity(self, S, q, qd):
        k, f = S[self.known], S[self.link]
        if self.pivot.type == "R":
            vY = k.point_velocity(self.Y)

            def set_rate(x):
                f.w = k.w + x
                rx, ry = f.rot(self.Y)
                f.vx, f.vy = vY[0] + f.w * ry, vY[1] - f.w * rx
        else:
            ax, ay = _rot(k, *self.a0)
            s = ax * (f.dx - k.dx) + ay * (f.dy - k.dy)

            def set_rate(x):
                f.w = k.w
                f.vx = k.vx + x * ax - s * k.w * ay
                f.vy = k.vy + x * ay + s * k.w * ax
                self._sdot = x
        self._solve_rate(S, set_rate, lambda: self.row.rate(S, qd)[0])

    def acceleration(self, S, q, qd, qdd):
        k, f = S[self.known], S[self.link]
        if self.pivot.type == "R":
            aY = k.point_acceleration(self.Y)

            def set_rate(x):
                f.al = k.al + x
                rx, ry = f.rot(self.Y)
                w2 = f.w * f.w
                f.ax = aY[0] + f.al * ry + w2 * rx
                f.ay = aY[1] - f.al * rx + w2 * ry
        else:
            ax, ay = _rot(k, *self.a0)
            s = ax * (f.dx - k.dx) + ay * (f.dy - k.dy)
            # the slide rate from the velocities: v_f - v_k = sd a + s w perp(a)
            sd = ax * (f.vx - k.vx) + ay * (f.vy - k.vy)
            w, al = k.w, k.al

            def set_rate(x):
                f.al = k.al
                f.ax = k.ax + x * ax + 2 * sd * w * -ay + s * (al * -ay - w * w * ax)
                f.ay = k.ay + x * ay + 2 * sd * w * ax + s * (al * ax - w * w * ay)
        self._solve_rate(S, set_rate, lambda: self.row.accel(S, qdd)[0])


class _Still:
    """A link state at rest in the assembly configuration (scalars)."""

    th = dx = dy = s = 0.0
    c = 1.0

    def point(self, X):
        return X

    def rot(self, X):
        return X


def cam_records(solvers, S, joints, status) -> None:
    """Write each cam contact's record: the contact point and its pressure angle.

    A cam joint's ``position`` is the contact point, its ``velocity`` and
    ``acceleration`` those of the follower's material point there (``links[1]``,
    as for every joint), ``pressure_angle`` the pressure angle (rad), ``normal`` the
    contact normal (from the cam towards the follower).  Positions
    and the angle at ``ok`` and ``singular`` steps, rates at ``ok`` steps; NaN
    elsewhere, as the other records.
    """
    placed = (status == "ok") | (status == "singular")
    ok = status == "ok"
    for sv in solvers:
        if not isinstance(sv, CamSolver):
            continue
        rec = joints[sv.joint.name]
        n = len(status)
        _, C, Nv, _, _, _ = sv.geo.contact(S)
        f = S[sv.link]
        rec.normal = np.stack([np.where(placed, np.broadcast_to(Nv[k], (n,)), np.nan)
                               for k in (0, 1)], axis=-1)
        for out, value, mask in ((rec.position, C, placed), (rec.velocity, None, ok),
                                 (rec.acceleration, None, ok)):
            if out is None:
                continue
            if value is None:
                value = (_vel if out is rec.velocity else _acc)(f, *C)
            for k in (0, 1):
                out[:, k] = np.where(mask, np.broadcast_to(value[k], (n,)), np.nan)
        angle = np.broadcast_to(sv.pressure_angle(S), (n,))
        rec.pressure_angle = np.where(placed, angle, np.nan)
