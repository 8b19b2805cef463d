"""Cam contacts (``cam`` joints, issue 20): format, kinematics, forces, per-step reports.

Independent checks, none sharing code with the solver:

* an eccentric circle cam (the textbooks' standard): a flat-faced translating
  follower moves in simple harmonic motion, ``s = e sin(theta)``, with its
  rates in closed form; a roller follower's centre is at
  ``e sin(theta) + sqrt((R + rho)^2 - (delta - e cos(theta))^2)`` from the
  cam's pivot (offset ``delta``), its pressure angle
  ``asin(|delta - e cos(theta)| / (R + rho))``; 1e-10 over a full turn;
* the direct contact equations (the follower's element on the profile or its
  offset, or the face tangent to it, with the profile parameter as an extra
  unknown), solved here by Newton's method in truncated Taylor arithmetic of
  the driver's time, so that the follower's rate and acceleration come from
  the first and second Taylor coefficients (implicit differentiation, exact to
  rounding): the solver's replacement-method rates must agree to 1e-10;
* finite differences of the solver's own positions (third check): central
  differences with a step h have a truncation error ``h^2 s'''/6`` ~ 1e-7
  relative at h = 1e-3 rad, hence a 1e-6 tolerance;
* forces: the global solve, each link's equilibrium and the power balance
  (``force_checks``, 1e-9 as in the contract test), the contact force along
  the normal and pushing.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from linkage_sym import compile_plan, load_scene
from linkage_sym.errors import SceneError
from tests.support.force_checks import dyad_and_global_checked

TOL_KIN = 1e-10
TOL_F = 1e-9
E, R, RHO = 0.015, 0.04, 0.01


def eccentric(follower="flat", offset=0.0, steps=73, speed=10.0, accel=3.0, load=-50.0):
    """A cam turning about O = (0, 0), an eccentric circle (centre (E, 0), radius R) and a
    follower translating along x = offset: a flat face or a roller of radius RHO."""
    if follower == "flat":
        at, fol = [offset, R], {"kind": "flat", "face_deg": 0}
    else:
        at = [offset, math.sqrt((R + RHO) ** 2 - (offset - E) ** 2)]
        fol = {"kind": "roller", "radius": RHO}
    return {
        "name": "eccentric",
        "links": [
            {"name": "cam", "mass": 1.0, "com": [0.005, 0.0], "inertia": 1e-3},
            {"name": "fol", "mass": 0.5, "com": [offset, 0.08], "inertia": 5e-4},
        ],
        "joints": [
            {"name": "O", "type": "R", "links": ["ground", "cam"], "at": [0.0, 0.0]},
            {"name": "S", "type": "P", "links": ["ground", "fol"], "at": [offset, 0.08], "axis_deg": 90},
            {"name": "K", "type": "cam", "links": ["cam", "fol"], "at": at,
             "profile": {"circle": {"centre": [E, 0.0], "radius": R}}, "follower": fol},
        ],
        "drivers": [{"joint": "O", "toward": "K", "start_deg": 90, "stop_deg": 450, "steps": steps,
                     "speed": speed, "acceleration": accel}],
        "loads": [{"link": "fol", "force": [0.0, load], "at": [offset, 0.08]}],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
    }


def test_flat_faced_follower_is_simple_harmonic():
    a = compile_plan(load_scene(eccentric("flat"))).run()
    cam, fol = a.links["cam"], a.links["fol"]
    th, w, al = cam.rotation, cam.omega, cam.alpha
    s, v, acc = fol.origin[:, 1], fol.origin_velocity[:, 1], fol.origin_acceleration[:, 1]
    assert np.ptp(th) == pytest.approx(2 * math.pi)
    assert np.max(np.abs(s - E * np.sin(th))) <= TOL_KIN * E
    assert np.max(np.abs(v - E * np.cos(th) * w)) <= TOL_KIN * E * np.max(np.abs(w))
    scale = E * np.max(w**2 + np.abs(al))
    assert np.max(np.abs(acc - (-E * np.sin(th) * w**2 + E * np.cos(th) * al))) <= TOL_KIN * scale
    assert np.max(a.joints["K"].pressure_angle) <= 1e-15  # a face normal to the stroke
    assert np.all(np.abs(fol.origin[:, 0]) <= 1e-17) and np.all(a.status == "ok")


@pytest.mark.parametrize("offset", [0.0, 0.012])
def test_roller_follower_closed_form_and_pressure_angle(offset):
    a = compile_plan(load_scene(eccentric("roller", offset))).run()
    th = a.links["cam"].rotation
    y0 = math.sqrt((R + RHO) ** 2 - (offset - E) ** 2)
    y = y0 + a.links["fol"].origin[:, 1]
    exact = E * np.sin(th) + np.sqrt((R + RHO) ** 2 - (offset - E * np.cos(th)) ** 2)
    assert np.max(np.abs(y - exact)) <= TOL_KIN * R
    alpha = np.arcsin(np.abs(offset - E * np.cos(th)) / (R + RHO))
    assert np.max(np.abs(a.joints["K"].pressure_angle - alpha)) <= TOL_KIN
    # the contact point: on the circle and on the line of centres
    c = a.joints["K"].position
    centre = np.stack([E * np.cos(th), E * np.sin(th)], axis=-1)
    assert np.max(np.abs(np.hypot(*(c - centre).T) - R)) <= TOL_KIN * R


# -- the direct contact equations in truncated Taylor arithmetic ----------------------------
class T2:
    """A truncated Taylor series ``c0 + c1 t + c2 t^2`` (arrays over the steps)."""

    def __init__(self, c0, c1=0.0, c2=0.0):
        self.c = (c0, c1, c2)

    @staticmethod
    def of(x):
        return x if isinstance(x, T2) else T2(x)

    def __add__(self, o):
        o = T2.of(o)
        return T2(*(a + b for a, b in zip(self.c, o.c)))

    __radd__ = __add__

    def __neg__(self):
        return T2(*(-a for a in self.c))

    def __sub__(self, o):
        return self + -T2.of(o)

    def __rsub__(self, o):
        return T2.of(o) - self

    def __mul__(self, o):
        o = T2.of(o)
        a, b = self.c, o.c
        return T2(a[0] * b[0], a[0] * b[1] + a[1] * b[0], a[0] * b[2] + a[1] * b[1] + a[2] * b[0])

    __rmul__ = __mul__

    def apply(self, f0, f1, f2):
        """``f(self)`` from ``f, f', f''`` at ``c0``."""
        _, a1, a2 = self.c
        return T2(f0, f1 * a1, f1 * a2 + 0.5 * f2 * a1 * a1)

    def cos(self):
        c, s = np.cos(self.c[0]), np.sin(self.c[0])
        return self.apply(c, -s, -c)

    def sin(self):
        c, s = np.cos(self.c[0]), np.sin(self.c[0])
        return self.apply(s, c, -s)

    def inv_sqrt(self):
        x = self.c[0]
        return self.apply(x**-0.5, -0.5 * x**-1.5, 0.75 * x**-2.5)


class Spline:
    """A closed profile as the format defines it, written here with SciPy's splines."""

    def __init__(self, kind, data):
        self.kind = kind
        if kind == "polar":
            centre, phi, r = data
            self.centre = centre
            phi = np.radians(phi)
            self.s = CubicSpline(np.append(phi, phi[0] + 2 * np.pi), np.append(r, r[0]),
                                 bc_type="periodic")
        else:
            P = np.asarray(data, float)
            P = np.vstack([P, P[:1]])
            t = np.concatenate([[0], np.cumsum(np.hypot(*np.diff(P, axis=0).T))])
            t *= 2 * np.pi / t[-1]
            self.x = CubicSpline(t, P[:, 0], bc_type="periodic")
            self.y = CubicSpline(t, P[:, 1], bc_type="periodic")

    def xy(self, u: T2):
        """``(x(u), y(u))`` and ``(x'(u), y'(u))`` as Taylor series."""
        u0 = u.c[0]
        if self.kind == "polar":
            r = u.apply(*(self.s(u0, k) for k in range(3)))
            r1 = u.apply(*(self.s(u0, k) for k in range(1, 4)))
            c, s = u.cos(), u.sin()
            return ((self.centre[0] + r * c, self.centre[1] + r * s),
                    (r1 * c - r * s, r1 * s + r * c))
        fx = [self.x(u0, k) for k in range(4)]
        fy = [self.y(u0, k) for k in range(4)]
        return (u.apply(*fx[:3]), u.apply(*fy[:3])), (u.apply(*fx[1:]), u.apply(*fy[1:]))


def contact_equations(prof, kind, pivot, rho, z, theta):
    """The two contact conditions in the cam's frame (cam on the origin), Taylor series.

    ``z = (c, u)``: the follower's coordinate (rotation about ``pivot['Y']``, or
    slide along ``pivot['a']``) and the profile parameter.
    """
    c, u = z
    (x, y), (x1, y1) = prof.xy(u)
    k = (x1 * x1 + y1 * y1).inv_sqrt()
    nx, ny = y1 * k, -1.0 * x1 * k  # outward normal (counterclockwise profile)
    ct, st = theta.cos(), theta.sin()
    P0 = pivot["P0"]

    def to_cam(px, py):
        return ct * px + st * py, -1.0 * st * px + ct * py

    if pivot["type"] == "R":
        Y = pivot["Y"]
        cc, sc = c.cos(), c.sin()
        dx, dy = P0[0] - Y[0], P0[1] - Y[1]
        W = (Y[0] + cc * dx - sc * dy, Y[1] + sc * dx + cc * dy)
        m0 = pivot.get("m0")
        m = None if m0 is None else (cc * m0[0] - sc * m0[1], sc * m0[0] + cc * m0[1])
    else:
        ax, ay = pivot["a"]
        W = (P0[0] + c * ax, P0[1] + c * ay)
        m = pivot.get("m0")
        m = None if m is None else (T2(m[0]), T2(m[1]))
    wx, wy = to_cam(*W)
    if kind == "flat":
        mx, my = to_cam(*m)
        return nx * my - ny * mx, mx * (x - wx) + my * (y - wy)
    return wx - x - rho * nx, wy - y - rho * ny


def direct_solve(prof, kind, pivot, rho, theta, w, al, z0):
    """Newton on the contact equations, followed from the assembly configuration
    (``theta = 0``, ``z0``) in small steps of the cam's angle; then, at each step, the
    Taylor coefficients of the follower's coordinate: ``(c, c', c'')`` in time."""
    c, u = z0
    out = []
    prev = 0.0
    for th, om, a in zip(theta, w, al):
        for sub in np.linspace(prev, th, 9)[1:]:
            c, u = _newton(prof, kind, pivot, rho, sub, c, u)
        prev = th

        def F(c0, u0, c1=0.0, u1=0.0, c2=0.0, u2=0.0):
            return contact_equations(prof, kind, pivot, rho, (T2(c0, c1, c2), T2(u0, u1, u2)),
                                     T2(th, om, 0.5 * a))

        J = np.column_stack([_lin1(F, c, u, 0), _lin1(F, c, u, 1)])
        r1 = np.array([float(np.asarray(e.c[1])) for e in F(c, u)])
        c1, u1 = np.linalg.solve(J, -r1)
        r2 = np.array([float(np.asarray(e.c[2])) for e in F(c, u, c1, u1)])
        c2, _ = np.linalg.solve(J, -r2)
        out.append((c, c1, 2 * c2))
    return np.array(out)


def _newton(prof, kind, pivot, rho, th, c, u):
    def F(c0, u0, c1=0.0, u1=0.0):
        return contact_equations(prof, kind, pivot, rho, (T2(c0, c1), T2(u0, u1)), T2(th))

    for _ in range(50):
        f0 = np.array([float(np.asarray(e.c[0])) for e in F(c, u)])
        J = np.column_stack([_lin1(F, c, u, 0), _lin1(F, c, u, 1)])
        step = np.linalg.solve(J, -f0)
        c, u = c + step[0], u + step[1]
        if np.max(np.abs(step)) < 1e-15:
            break
    return c, u


def _lin1(F, c, u, k):
    """Column ``k`` of the Jacobian: the order-1 coefficient's change per unit rate of z_k
    with the driver's rate taken out (the order-1 coefficient is linear in the rates)."""
    base = [float(np.asarray(e.c[1])) for e in F(c, u)]
    unit = [1.0, 0.0] if k == 0 else [0.0, 1.0]
    got = [float(np.asarray(e.c[1])) for e in F(c, u, *unit)]
    return np.array(got) - np.array(base)


def ellipse_points(a=0.05, b=0.035, n=24, shift=(0.01, 0.004)):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return [[shift[0] + a * math.cos(v), shift[1] + b * math.sin(v)] for v in t]


def polar_profile():
    phi = np.arange(0, 360, 20.0)
    r = 0.04 + 0.008 * np.cos(np.radians(phi) - 0.4) + 0.002 * np.sin(2 * np.radians(phi))
    return {"centre": [0.0, 0.0], "phi_deg": phi.tolist(), "r": r.tolist()}


def cam_scene(profile, follower, pivot, at, face_deg=None, steps=61):
    """A cam turning about the origin and a follower on ``pivot`` ("R" at (0.09, 0.03), or
    "P" along y at x = 0.006), touching the profile at ``at``."""
    fol = {"kind": follower}
    if follower == "roller":
        fol["radius"] = 0.012
    if follower == "flat":
        fol["face_deg"] = face_deg
    if pivot == "R":
        pj = {"name": "D", "type": "R", "links": ["ground", "fol"], "at": [0.11, 0.05]}
    else:
        pj = {"name": "D", "type": "P", "links": ["ground", "fol"], "at": [at[0], 0.09], "axis_deg": 90}
    return {
        "name": "cam",
        "links": [{"name": "cam", "mass": 1.2, "com": [0.003, 0.001], "inertia": 1e-3},
                  {"name": "fol", "mass": 0.4, "com": [0.06, 0.05], "inertia": 4e-4}],
        "joints": [
            {"name": "O", "type": "R", "links": ["ground", "cam"], "at": [0.0, 0.0]},
            pj,
            {"name": "K", "type": "cam", "links": ["cam", "fol"], "at": list(at),
             "profile": profile, "follower": fol},
        ],
        "drivers": [{"joint": "O", "toward": "K", "start_deg": 0, "stop_deg": 360, "steps": steps,
                     "speed": 8.0, "acceleration": -5.0}],
        "loads": [{"link": "fol", "torque": 3.0}] if pivot == "R" else
                 [{"link": "fol", "force": [0.0, -40.0], "at": [at[0], 0.09]}],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
    }


def _touching(profile, follower, pivot):
    """A follower element touching the profile in the assembly configuration."""
    prof = Spline(*profile_args(profile))
    u = np.linspace(0, 2 * np.pi, 20001)
    (x, y), (x1, y1) = prof.xy(T2(u))
    x, y, x1, y1 = (np.asarray(v.c[0]) for v in (x, y, x1, y1))
    sp = np.hypot(x1, y1)
    nx, ny = y1 / sp, -x1 / sp
    rho = 0.012 if follower == "roller" else 0.0
    qx, qy = x + rho * nx, y + rho * ny
    if follower == "flat":  # the face touching the top: normal (0, 1) at the highest point
        k = np.argmax(y)
        return [float(x[k]) + 0.01, float(y[k])], 0.0, prof
    if pivot == "R":  # the roller/knife on top, its arm about horizontal
        k = np.argmax(qy)
    else:
        k = np.argmax(np.where(np.abs(qx - 0.006) < 2e-4, qy, -1))
    return [float(qx[k]), float(qy[k])], None, prof


def profile_args(profile):
    if "polar" in profile:
        p = profile["polar"]
        return "polar", (p["centre"], np.asarray(p["phi_deg"]), np.asarray(p["r"]))
    return "points", profile["points"]


CASES = [
    ("roller", "R", {"polar": polar_profile()}),
    ("knife", "P", {"points": ellipse_points()}),
    ("flat", "R", {"points": ellipse_points()}),
    ("flat", "P", {"polar": polar_profile()}),
]


@pytest.mark.slow
@pytest.mark.parametrize("follower,pivot,profile", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_replacement_rates_agree_with_the_direct_contact_solution(follower, pivot, profile):
    at, face, prof = _touching(profile, follower, pivot)
    d = cam_scene(profile, follower, pivot, at, face)
    # the assembly contact: a grid point of _touching; snap the follower onto the profile
    scene = load_scene_snapped(d, follower)
    a = compile_plan(scene).run()
    assert np.all(a.status == "ok"), a.messages
    cam, fol = a.links["cam"], a.links["fol"]
    at = scene.joint("K").at
    piv = {"type": pivot, "P0": at, "Y": (0.11, 0.05), "a": (0.0, 1.0)}
    if follower == "flat":
        piv["m0"] = (0.0, 1.0)
    rho = 0.012 if follower == "roller" else 0.0
    u0 = _u_of(prof, follower, at, rho)
    got = direct_solve(prof, follower, piv, rho, cam.rotation, cam.omega, cam.alpha, (0.0, u0))
    if pivot == "R":
        mine = np.stack([fol.rotation, fol.omega, fol.alpha], axis=-1)
    else:
        mine = np.stack([fol.origin[:, 1], fol.origin_velocity[:, 1], fol.origin_acceleration[:, 1]],
                        axis=-1)
    scale = np.max(np.abs(got), axis=0) + (0.0 if pivot == "R" else 0.01)
    err = np.max(np.abs(mine - got), axis=0) / scale
    assert np.all(err <= TOL_KIN), err


def load_scene_snapped(d, follower):
    """The scene, with ``at`` moved onto the profile (the scene reader's tolerance is 1e-6)."""
    from linkage_sym.numeric.kinematics.cam_profile import CamProfile

    prof = d["joints"][2]["profile"]
    kind, data = profile_args(prof)
    if kind == "polar":
        data = (data[0], np.radians(data[1]), data[2])
    else:
        data = (data,)
    p = CamProfile(kind, data)
    at = np.asarray(d["joints"][2]["at"], float)
    if follower == "flat":
        u = p.support(0.0, 1.0)
        (x, y), = p.evaluate(u, 0)
        at[1] = y[0]
    else:
        rho = 0.012 if follower == "roller" else 0.0
        for _ in range(3):
            u = p.nearest(*at)
            (x, y), _, (nx, ny), _ = p.frame(u)
            at = np.array([x[0] + rho * nx[0], y[0] + rho * ny[0]])
        if d["joints"][1]["type"] == "P":
            d["joints"][1]["at"] = [float(at[0]), 0.09]
            d["loads"][0]["at"] = [float(at[0]), 0.09]
    d = copy.deepcopy(d)
    d["joints"][2]["at"] = [float(at[0]), float(at[1])]
    return load_scene(d)


def _u_of(prof, follower, at, rho):
    u = np.linspace(0, 2 * np.pi, 40001)
    (x, y), (x1, y1) = prof.xy(T2(u))
    x, y, x1, y1 = (np.asarray(v.c[0]) for v in (x, y, x1, y1))
    if follower == "flat":
        return float(u[np.argmax(y)])
    sp = np.hypot(x1, y1)
    return float(u[np.argmin(np.hypot(x + rho * y1 / sp - at[0], y - rho * x1 / sp - at[1]))])


def test_rates_against_finite_differences_of_positions():
    """Third check: central differences of the solver's own positions (h = 1e-3 rad)."""
    at, face, _ = _touching(CASES[0][2], "roller", "R")
    scene = load_scene_snapped(cam_scene(CASES[0][2], "roller", "R", at), "roller")
    plan = compile_plan(scene)
    th = np.linspace(0.3, 5.9, 9)
    h = 1e-3
    runs = [plan.run({"O": th + k * h}, {"O": np.ones(9)}, {"O": np.zeros(9)}) for k in (-1, 0, 1)]
    psi = [r.links["fol"].rotation for r in runs]
    fd_w = (psi[2] - psi[0]) / (2 * h)
    fd_a = (psi[2] - 2 * psi[1] + psi[0]) / h**2
    w, al = runs[1].links["fol"].omega, runs[1].links["fol"].alpha
    assert np.max(np.abs(fd_w - w)) <= 1e-6 * np.max(np.abs(w))
    assert np.max(np.abs(fd_a - al)) <= 1e-5 * np.max(np.abs(al))  # h^2 / 12 of the 4th derivative


# -- forces --------------------------------------------------------------------------------
@pytest.mark.parametrize("case", ["flat", "roller", "rocker"])
def test_forces_global_equilibrium_power_and_push(case):
    if case == "rocker":
        at, _, _ = _touching(CASES[0][2], "roller", "R")
        scene = load_scene_snapped(cam_scene(CASES[0][2], "roller", "R", at), "roller")
    else:
        scene = load_scene(eccentric(case, 0.01 if case == "roller" else 0.0))
    a, g = dyad_and_global_checked(scene, compile_plan(scene), TOL_F)
    # the contact force: along the normal at the contact point, pushing the follower
    F = a.forces.reactions["K"]
    c = a.joints["K"].position
    th = a.links["cam"].rotation
    if case != "rocker":  # the circle's normal: from its centre through the contact point
        n = c - np.stack([E * np.cos(th), E * np.sin(th)], axis=-1)
        n /= np.hypot(*n.T)[:, None]
        assert np.max(np.abs(n[:, 0] * F[:, 1] - n[:, 1] * F[:, 0])) <= TOL_F * np.max(np.abs(F))
        assert np.all(np.sum(n * F, axis=1) > 0)
    assert not a.warnings


def test_flat_follower_driving_torque_closed_form():
    """Quasi-static (no inertia, no gravity): T = P e cos(theta) for a load P on the face."""
    d = eccentric("flat", load=-50.0)
    d["effects"] = {"inertia": False, "gravity": False, "loads": True}
    a = compile_plan(load_scene(d)).run()
    th = a.links["cam"].rotation
    assert np.max(np.abs(a.forces.driving["O"] - 50.0 * E * np.cos(th))) <= TOL_F * 50 * E


# -- per-step reports -----------------------------------------------------------------------
def test_a_follower_accelerated_away_loses_contact_and_is_warned():
    d = eccentric("flat", speed=60.0, accel=0.0, load=0.0)  # no spring: inertia throws it off
    d["effects"]["gravity"] = False
    a = compile_plan(load_scene(d)).run()
    Fn = a.forces.reactions["K"][:, 1]
    assert (Fn < 0).any() and (Fn > 0).any()
    (note,) = [w for w in a.warnings if "cam contact K" in w]
    assert "loses contact" in note and f"{int((Fn < 0).sum())} step(s)" in note
    assert np.all(a.status == "ok")  # the kinematics of every step is solved


def test_a_roller_too_big_for_a_concave_part_is_reported_per_step():
    """A peanut-shaped profile, concave at its waist (phi = 90 and 270 deg), and a roller
    sliding along the x axis whose radius exceeds the waist's radius of curvature."""
    from linkage_sym.numeric.kinematics.cam_profile import CamProfile

    phi = np.arange(0, 360, 10.0)
    r = 0.034 + 0.012 * np.cos(2 * np.radians(phi))
    rho = 0.03
    p = CamProfile("polar", ((0.0, 0.0), np.radians(phi), r))
    *_, kappa = p.frame(np.array([math.pi / 2]))
    assert kappa[0] < 0 and -1 / kappa[0] < rho  # concave there, tighter than the roller
    u = np.linspace(-0.5, 0.5, 200001)  # assembled on the convex side, the slide at y = 0.006
    (x, y), _, (nx, ny), _ = p.frame(u)
    k = np.argmin(np.abs(y + rho * ny - 0.006))
    at = [float(x[k] + rho * nx[k]), float(y[k] + rho * ny[k])]
    d = cam_scene({"polar": {"centre": [0, 0], "phi_deg": phi.tolist(), "r": r.tolist()}},
                  "roller", "P", at)
    d["joints"][1] = {"name": "D", "type": "P", "links": ["ground", "fol"], "at": [0.09, at[1]],
                      "axis_deg": 0}
    d["joints"][2]["follower"]["radius"] = rho
    d["loads"] = [{"link": "fol", "force": [-40.0, 0.0], "at": [0.09, at[1]]}]
    a = compile_plan(load_scene(d)).run()
    bad = a.status != "ok"
    assert bad.any() and (~bad).any()
    msgs = {m for m in np.asarray(a.messages, dtype=object)[bad] if m}
    assert msgs and all("cam contact K" in m and "undercut" in m for m in msgs), msgs
    assert np.all(np.isfinite(a.links["fol"].origin[~bad]))
    assert np.all(np.isnan(a.links["fol"].origin[bad]))


# -- validation: one test per field ---------------------------------------------------------
def _bad(change):
    d = eccentric("roller")
    change(d["joints"][2])
    with pytest.raises(SceneError) as e:
        load_scene(d)
    return str(e.value)


@pytest.mark.parametrize("change,field,words", [
    (lambda j: j.pop("follower"), "joints[2].follower", "required key is missing"),
    (lambda j: j.pop("profile"), "joints[2].profile", "required key is missing"),
    (lambda j: j["follower"].update(kind="spring"), "joints[2].follower.kind", "must be one of"),
    (lambda j: j["follower"].update(radius=-0.01), "joints[2].follower.radius", "must be > 0"),
    (lambda j: j["follower"].pop("radius"), "joints[2].follower.radius", "required key is missing"),
    (lambda j: j["follower"].update(kind="knife"), "joints[2].follower.radius", "only a roller"),
    (lambda j: j["follower"].update(kind="flat", radius=None) or j["follower"].pop("radius"),
     "joints[2].follower.face_deg", "required key is missing"),
    (lambda j: j.update(at=[0.0, 0.06]), "joints[2].at", "0.0118466 m off the profile"),
    (lambda j: j["profile"].update(points=[[0, 0], [1, 0], [1, 1]]), "joints[2].profile",
     "exactly one of"),
    (lambda j: j["profile"]["circle"].update(radius=-1), "joints[2].profile.circle.radius", "> 0"),
    (lambda j: j.update(profile={"points": [[0, 0], [1, 0], [0, 1], [1, 1]]}),
     "joints[2].profile.points", "crosses itself"),
    (lambda j: j.update(profile={"points": [[0, 0], [1, 0]]}), "joints[2].profile.points",
     "at least 4"),
    (lambda j: j.update(profile={"polar": {"centre": [0, 0], "phi_deg": [0, 90, 180, 270, 360],
                                           "r": [0.05, 0.05, 0.05, 0.05, 0.06]}}),
     "joints[2].profile.polar.r", "not closed"),
    (lambda j: j.update(profile={"polar": {"centre": [0, 0], "phi_deg": [0, 90, 80, 270],
                                           "r": [0.05] * 4}}),
     "joints[2].profile.polar.phi_deg[2]", "must increase"),
    (lambda j: j.update(profile={"polar": {"centre": [0, 0], "phi_deg": [0, 90, 180, 270],
                                           "r": [0.05, -0.01, 0.05, 0.05]}}),
     "joints[2].profile.polar.r[1]", "> 0"),
    (lambda j: j.update(profile={"polar": {"centre": [0, 0], "phi_deg": [0, 90, 180, 270, 400],
                                           "r": [0.05] * 5}}),
     "joints[2].profile.polar.phi_deg", "one turn"),
    (lambda j: j["profile"].update(pitch=1), "joints[2].profile.pitch", "true or false"),
    (lambda j: j.update(axis_deg=3), "joints[2].axis_deg", "not allowed on a cam contact"),
])
def test_validation_names_each_field(change, field, words):
    msg = _bad(change)
    line = next((ln for ln in msg.splitlines() if ln.strip().startswith(field + ":")), None)
    assert line is not None, msg
    assert words in line, line


def test_validation_flat_face_needs_a_convex_profile_and_to_touch():
    d = eccentric("flat")
    phi = np.arange(0, 360, 10.0)
    r = 0.034 + 0.012 * np.cos(2 * np.radians(phi))
    d["joints"][2]["profile"] = {"polar": {"centre": [0, 0], "phi_deg": phi.tolist(), "r": r.tolist()}}
    with pytest.raises(SceneError, match=r"joints\[2\]\.profile\.polar: a flat-faced follower needs a "
                                         r"convex profile"):
        load_scene(d)
    d = eccentric("flat")
    d["joints"][2]["at"] = [0.0, 0.05]
    with pytest.raises(SceneError, match=r"joints\[2\]\.at: the flat face .* misses the profile: it "
                                         r"is 0\.01 m from touching"):
        load_scene(d)


def test_validation_collects_every_problem_and_refuses_driving_a_cam():
    d = eccentric("roller")
    d["joints"][2]["follower"]["radius"] = -1
    d["joints"][2]["profile"]["circle"]["radius"] = 0
    d["drivers"][0]["joint"] = "K"
    with pytest.raises(SceneError) as e:
        load_scene(d)
    text = str(e.value)
    for field in ("joints[2].follower.radius", "joints[2].profile.circle.radius", "drivers[0].joint"):
        assert field in text


def test_mobility_counts_a_cam_contact_as_one_constraint():
    d = eccentric("roller")
    d["joints"].append({"name": "X", "type": "R", "links": ["ground", "fol"], "at": [0.0, 0.1]})
    with pytest.raises(SceneError, match=r"M = 3\*2 - 2\*3 - 1 = -1 .*1 cam contacts \(higher pairs\)"):
        load_scene(d)


def test_the_result_records_the_pressure_angle():
    a = compile_plan(load_scene(eccentric("roller", 0.01))).run()
    rec = a.to_dict()["steps"][5]["joints"]["K"]
    assert set(rec) == {"position", "pressure_angle", "velocity", "acceleration", "reaction"}
    assert rec["pressure_angle"] == pytest.approx(float(a.joints["K"].pressure_angle[5]), abs=0)
    names = [n for n, _, _ in a.columns()]
    assert "joints.K.pressure_angle" in names


def test_symbolic_layer_refuses_cams_by_name():
    from linkage_sym.symbolic.mechanism import MechanismEquations

    with pytest.raises(SceneError, match=r"joints\[2\]: the symbolic method does not support cam "
                                         r"contacts yet \(joint 'K'"):
        MechanismEquations(load_scene(eccentric("roller")))


def test_kennedy_puts_the_cam_centre_on_the_contact_normal():
    from linkage_sym.centres.kennedy import kennedy_centres

    scene = load_scene(eccentric("roller", 0.01))
    a = compile_plan(scene).run()
    k = kennedy_centres(scene, a)
    P = k.position[:, k.index("cam", "fol")]
    C, n = a.joints["K"].position, a.joints["K"].normal
    d = P - C
    assert np.max(np.abs(d[:, 0] * n[:, 1] - d[:, 1] * n[:, 0])) <= 1e-12
    # and the relative velocity of the two links vanishes there (it is their instant centre)
    vc = a.links["cam"].omega[:, None] * np.stack([-P[:, 1], P[:, 0]], axis=-1)
    vf = a.links["fol"].origin_velocity
    assert np.max(np.abs(vc - vf)) <= 1e-10 * np.max(np.abs(vf))
