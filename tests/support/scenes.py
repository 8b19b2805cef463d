"""Scene dicts for the kinematics tests, built from lengths and angles.

Every builder places the mechanism in the canonical frame of
:mod:`reference_kinematics` (crank pivot A at the origin, see there), computes
the assembly configuration with the reference closed forms at the crank angle
``assembly_deg`` (default: ``start_deg``) in the assembly mode ``sigma``, and
then optionally rotates the whole drawing by ``rotate_deg`` about the origin
and shifts it by ``origin``, so that the same mechanism can be checked in a
general position.  Crank angles passed to the builders (``start_deg`` ...)
are canonical; the scene's driver values include ``rotate_deg``.

Only plain dicts come out: the tests load them with ``linkage_sym.load_scene``.
"""

from __future__ import annotations

import math

import numpy as np

from tests.support import reference_kinematics as ref


class Placement:
    """Rigid placement of the canonical frame: ``x_global = origin + R(rot) x``."""

    def __init__(self, rotate_deg=0.0, origin=(0.0, 0.0)):
        self.rot = math.radians(rotate_deg)
        self.rotate_deg = float(rotate_deg)
        self.origin = np.asarray(origin, dtype=float)
        c, s = math.cos(self.rot), math.sin(self.rot)
        self.R = np.array([[c, -s], [s, c]])

    def point(self, p):
        """Canonical point(s) (..., 2) -> global."""
        return np.asarray(p, dtype=float) @ self.R.T + self.origin

    def vector(self, v):
        """Canonical vector(s) (velocity, acceleration) -> global."""
        return np.asarray(v, dtype=float) @ self.R.T

    def angle(self, a):
        return np.asarray(a, dtype=float) + self.rot

    def xy(self, p):
        q = self.point(p)
        return [float(q[0]), float(q[1])]


def _driver(joint, toward, start_deg, stop_deg, steps, speed, acceleration, rotate_deg):
    return {
        "joint": joint,
        "toward": toward,
        "start_deg": start_deg + rotate_deg,
        "stop_deg": stop_deg + rotate_deg,
        "steps": steps,
        "speed": speed,
        "acceleration": acceleration,
    }


def _link(name, com=None, mass=1.0):
    if com is None:
        return {"name": name}
    return {"name": name, "mass": mass, "com": [float(com[0]), float(com[1])], "inertia": 1e-3}


def fourbar_points(l1, l2, l3, l4, th1, sigma=1):
    """Canonical A, B, C, D of the four-bar at crank angle ``th1`` (rad)."""
    th2, th3 = ref.fourbar_position(l1, l2, l3, l4, th1, sigma)
    if not np.isfinite(th3):
        raise ValueError(f"four-bar {l1, l2, l3, l4} cannot be assembled at {th1} rad")
    A = np.array([0.0, 0.0])
    B = np.array([l1 * math.cos(th1), l1 * math.sin(th1)])
    D = np.array([float(l4), 0.0])
    C = D + l3 * np.array([math.cos(th3), math.sin(th3)])
    return A, B, C, D


def fourbar(l1, l2, l3, l4, *, start_deg=0.0, stop_deg=360.0, steps=361, speed=10.0,
            acceleration=0.0, assembly_deg=None, sigma=1, rotate_deg=0.0, origin=(0.0, 0.0),
            coupler_com=None, name="fourbar"):
    """Four-bar ``crank`` (A-B), ``coupler`` (B-C), ``rocker`` (C-D) on ground.

    ``coupler_com`` = ``(a, b)`` gives the coupler a mass with its centre at
    ``a`` along BC and ``b`` normal to it (the point E of eq. 3-18).
    Returns ``(scene_dict, placement)``.
    """
    pl = Placement(rotate_deg, origin)
    th1a = math.radians(start_deg if assembly_deg is None else assembly_deg)
    A, B, C, D = fourbar_points(l1, l2, l3, l4, th1a, sigma)
    com = None
    if coupler_com is not None:
        a, b = coupler_com
        u = (C - B) / np.linalg.norm(C - B)
        com = pl.point(B + a * u + b * np.array([-u[1], u[0]]))
    scene = {
        "name": name,
        "links": [_link("crank"), _link("coupler", com), _link("rocker")],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": pl.xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": pl.xy(B)},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": pl.xy(C)},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": pl.xy(D)},
        ],
        "drivers": [_driver("A", "B", start_deg, stop_deg, steps, speed, acceleration,
                            rotate_deg)],
        "outputs": ["kinematics"],
    }
    return scene, pl


def slider_crank(l1, l2, e, *, start_deg=0.0, stop_deg=360.0, steps=361, speed=10.0,
                 acceleration=0.0, assembly_deg=None, sigma=1, rotate_deg=0.0,
                 origin=(0.0, 0.0), name="slider_crank"):
    """Offset slider-crank: ``crank`` (A-B), ``rod`` (B-C), ``slider`` (C) on
    the ground line ``y = e`` (P joint ``S``, axis along canonical +x)."""
    pl = Placement(rotate_deg, origin)
    th1a = math.radians(start_deg if assembly_deg is None else assembly_deg)
    r = ref.slider_crank(l1, l2, e, th1a, 0.0, 0.0, sigma)
    if not np.isfinite(r["x"]):
        raise ValueError("slider-crank cannot be assembled at the assembly angle")
    A = np.array([0.0, 0.0])
    B = np.array([l1 * math.cos(th1a), l1 * math.sin(th1a)])
    C = np.array([float(r["x"]), float(e)])
    scene = {
        "name": name,
        "links": [_link("crank"), _link("rod"), _link("slider")],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": pl.xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": pl.xy(B)},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": pl.xy(C)},
            {"name": "S", "type": "P", "links": ["ground", "slider"], "at": pl.xy(C),
             "axis_deg": rotate_deg},
        ],
        "drivers": [_driver("A", "B", start_deg, stop_deg, steps, speed, acceleration,
                            rotate_deg)],
        "outputs": ["kinematics"],
    }
    return scene, pl


def guide_bar(l1, l3, l4, gamma_deg, *, start_deg=0.0, stop_deg=360.0, steps=361,
              speed=10.0, acceleration=0.0, assembly_deg=None, sigma=1, rotate_deg=0.0,
              origin=(0.0, 0.0), name="guide_bar"):
    """Guide-bar of examples 3-1/3-6 of [4]: ``crank`` (A-B), ``block``
    pinned at B and sliding (P joint ``S``, axis on ``guide``) on the guide
    line through C at ``gamma`` from the arm DC; ``guide`` turns about D."""
    pl = Placement(rotate_deg, origin)
    th1a = math.radians(start_deg if assembly_deg is None else assembly_deg)
    g = math.radians(gamma_deg)
    r = ref.guide_bar(l1, l3, l4, g, th1a, 0.0, 0.0, sigma)
    if not np.isfinite(r["th3"]):
        raise ValueError("guide-bar cannot be assembled at the assembly angle")
    A = np.array([0.0, 0.0])
    B = np.array([l1 * math.cos(th1a), l1 * math.sin(th1a)])
    D = np.array([float(l4), 0.0])
    scene = {
        "name": name,
        "links": [_link("crank"), _link("block"), _link("guide")],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": pl.xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "block"], "at": pl.xy(B)},
            {"name": "S", "type": "P", "links": ["guide", "block"], "at": pl.xy(B),
             "axis_deg": math.degrees(float(r["th2"])) + rotate_deg},
            {"name": "D", "type": "R", "links": ["guide", "ground"], "at": pl.xy(D)},
        ],
        "drivers": [_driver("A", "B", start_deg, stop_deg, steps, speed, acceleration,
                            rotate_deg)],
        "outputs": ["kinematics"],
    }
    return scene, pl, np.asarray(r["C"], dtype=float)


def shaper(l1=0.125, l3=0.600, l4=0.150, l6=0.275, l6p=0.575, *, start_deg=0.0,
           stop_deg=360.0, steps=361, speed=1.0, acceleration=0.0, assembly_deg=None,
           sigma4=-1, name="shaper"):
    """Shaper of example 3-7 of [4] (fig. 3-13), in the frame of
    :func:`reference_kinematics.shaper_position`: guide pivot C at the origin,
    crank pivot A at ``(0, l6)``, ram line ``y = l6p``.  Links ``crank``,
    ``block`` (slides on ``guide``: P joint ``S``), ``guide`` (C-D), ``rod``
    (D-E), ``ram`` (P joint ``R`` on ground, horizontal).

    ``l6 = 0.275`` and ``l6p = 0.575`` are not printed in the OCR (the figure is
    missing); they follow from Table 3-1's first row:
    ``l1 tan(65.5561 deg) = 0.27500`` and ``l3 sin th3 + l4 sin th4 = 0.57500``.
    """
    th1a = math.radians(start_deg if assembly_deg is None else assembly_deg)
    s3, th3, th4, sE = (float(v) for v in ref.shaper_position(l1, l3, l4, l6, l6p, th1a, sigma4))
    A = [0.0, l6]
    B = [l1 * math.cos(th1a), l6 + l1 * math.sin(th1a)]
    C = [0.0, 0.0]
    D = [l3 * math.cos(th3), l3 * math.sin(th3)]
    E = [sE, l6p]
    scene = {
        "name": name,
        "links": [_link("crank"), _link("block"), _link("guide"), _link("rod"), _link("ram")],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": A},
            {"name": "B", "type": "R", "links": ["crank", "block"], "at": B},
            {"name": "S", "type": "P", "links": ["guide", "block"], "at": B,
             "axis_deg": math.degrees(th3)},
            {"name": "C", "type": "R", "links": ["ground", "guide"], "at": C},
            {"name": "D", "type": "R", "links": ["guide", "rod"], "at": D},
            {"name": "E", "type": "R", "links": ["rod", "ram"], "at": E},
            {"name": "R", "type": "P", "links": ["ground", "ram"], "at": E, "axis_deg": 0.0},
        ],
        "drivers": [_driver("A", "B", start_deg, stop_deg, steps, speed, acceleration, 0.0)],
        "outputs": ["kinematics"],
    }
    return scene


def watt_dyad_lengths(l1, l2, l3, l4, e_len, e_ang_deg, G, sigma=1, spread=0.5, reach=0.25):
    """Lengths l5, l6 of the Watt six-bar's second dyad that assemble over the
    whole crank turn with margin: with dmin, dmax the extreme distances |EG|
    over the turn, ``l5 + l6 = (1 + reach) dmax`` and ``|l5 - l6| = spread dmin``
    (0 < spread < 1), so |EG| stays inside (|l5 - l6|, l5 + l6)."""
    th = np.linspace(0, 2 * np.pi, 721)
    th2, th3 = ref.fourbar_position(l1, l2, l3, l4, th, sigma)
    ang = th3 + math.radians(e_ang_deg)
    E = np.stack([l4 + e_len * np.cos(ang), e_len * np.sin(ang)], -1)
    dist = np.hypot(*(E - np.asarray(G, dtype=float)).T)
    s, dlt = (1 + reach) * dist.max(), spread * dist.min()
    return (s + dlt) / 2, (s - dlt) / 2


def watt_sixbar(l1, l2, l3, l4, *, e_len, e_ang_deg, G, l5=None, l6=None, sigma=1, sigma2=1,
                start_deg=0.0, stop_deg=360.0, steps=73, speed=10.0, acceleration=0.0,
                name="watt_sixbar"):
    """Watt six-bar: the four-bar A-B-C-D whose rocker is ternary (point E at
    ``e_len`` from D, ``e_ang_deg`` from the arm D->C), and the RRR dyad
    ``link5`` (E-F) + ``link6`` (F-G) to the ground pivot G.  ``sigma2`` is
    ``sign cross(G - E, F - E)`` (see :func:`reference_kinematics.dyad_rrr`).
    ``l5``, ``l6`` default to :func:`watt_dyad_lengths`.
    Returns ``(scene_dict, points)`` with the canonical assembly points."""
    if l5 is None or l6 is None:
        l5, l6 = watt_dyad_lengths(l1, l2, l3, l4, e_len, e_ang_deg, G, sigma)
    th1a = math.radians(start_deg)
    A, B, C, D = fourbar_points(l1, l2, l3, l4, th1a, sigma)
    th3 = math.atan2(C[1] - D[1], C[0] - D[0])
    ang = th3 + math.radians(e_ang_deg)
    E = D + e_len * np.array([math.cos(ang), math.sin(ang)])
    G = np.asarray(G, dtype=float)
    z = np.zeros(2)
    F, _, _ = ref.dyad_rrr(E, G, z, z, z, z, l5, l6, sigma2)
    if not np.all(np.isfinite(F)):
        raise ValueError("second dyad cannot be assembled")
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    scene = {
        "name": name,
        "links": [_link(n) for n in ("crank", "coupler", "rocker", "link5", "link6")],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": xy(C)},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": xy(D)},
            {"name": "E", "type": "R", "links": ["rocker", "link5"], "at": xy(E)},
            {"name": "F", "type": "R", "links": ["link5", "link6"], "at": xy(F)},
            {"name": "G", "type": "R", "links": ["link6", "ground"], "at": xy(G)},
        ],
        "drivers": [_driver("A", "B", start_deg, stop_deg, steps, speed, acceleration, 0.0)],
        "outputs": ["kinematics"],
    }
    return scene, dict(A=A, B=B, C=C, D=D, E=E, F=F, G=G)


def change_point_fourbar(name="change point", speed=10.0, acceleration=0.0):
    """A change-point four-bar (7 + 17 = 10 + 14) whose doubles *are* the mechanism.

    Integer assembly points (Pythagorean: BC = (15, 8), DC = (-6, 8)); at the crank
    angle 0 (step 18 of the sweep -180..180 deg in 37 steps) B = (7, 0), |BD| = 7 =
    l2 - l3 exactly, all four joints in line with C = (24, 0).
    """
    return {
        "name": name,
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [-7.0, 0.0]},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [8.0, 8.0]},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [14.0, 0.0]},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": -180, "stop_deg": 180,
                     "steps": 37, "speed": speed, "acceleration": acceleration}],
        "outputs": ["kinematics"],
    }


def run(scene_dict):
    """Load a scene dict and analyse it: ``(scene, analysis)``."""
    import linkage_sym

    scene = linkage_sym.load_scene(scene_dict)
    return scene, linkage_sym.analyze(scene)


def unwrap_from_assembly(theta, theta_assembly):
    """Rotation from the assembly configuration, continuous along the sweep,
    as the contract defines ``links.*.rotation`` when the sweep starts at the
    assembly configuration: first value within (-pi, pi]."""
    r = np.unwrap(np.asarray(theta, dtype=float) - theta_assembly)
    return r - 2 * np.pi * np.round(r[0] / (2 * np.pi))


def assert_close(actual, expected, rtol, what, scale=None, atol=None):
    """``|actual - expected| <= rtol * scale`` at every step (``scale``: the
    largest magnitude of ``expected`` over the sweep unless given), or
    ``<= atol`` (array or scalar) if given.  NaN in ``actual`` where
    ``expected`` is finite fails.  The message names the worst step."""
    a = np.asarray(actual, dtype=float)
    e = np.asarray(expected, dtype=float)
    assert a.shape == e.shape, f"{what}: shape {a.shape} != {e.shape}"
    if atol is None:
        if scale is None:
            scale = float(np.nanmax(np.abs(e))) if np.any(np.isfinite(e)) else 0.0
        tol = np.full(e.shape, rtol * scale)
    else:
        tol = np.broadcast_to(np.asarray(atol, dtype=float), e.shape)
    err = np.abs(a - e)
    bad = np.isfinite(e) & ~(err <= tol)
    if np.any(bad):
        idx = np.unravel_index(np.nanargmax(np.where(bad, err / np.maximum(tol, 1e-300), 0)),
                               e.shape)
        raise AssertionError(
            f"{what}: {int(bad.sum())} value(s) off; worst at index {idx}: "
            f"got {a[idx]!r}, expected {e[idx]!r}, |err| = {err[idx]:.3e} > tol {tol[idx]:.3e}")


# -- Newton groups (tests/numeric/test_newton_groups.py, tests/output/test_output_formats.py) --

def knee_scene(K, A, G, start_deg=-60.0, stop_deg=120.0, steps=37):
    """Knee linkage: hip H at the origin, knee K, ankle A, rocker pivot G; the knee driven."""
    H = (0.0, 0.0)
    return {
        "name": "knee",
        "links": [
            {"name": "thigh", "mass": 1.0, "com": [K[0] / 2, K[1] / 2], "inertia": 0.01},
            {"name": "shin", "mass": 1.0, "com": [(K[0] + A[0]) / 2, (K[1] + A[1]) / 2],
             "inertia": 0.01},
            {"name": "rocker", "mass": 0.5, "com": [(A[0] + G[0]) / 2, (A[1] + G[1]) / 2],
             "inertia": 0.005},
        ],
        "joints": [
            {"name": "H", "type": "R", "links": ["ground", "thigh"], "at": list(H)},
            {"name": "K", "type": "R", "links": ["thigh", "shin"], "at": list(K)},
            {"name": "A", "type": "R", "links": ["shin", "rocker"], "at": list(A)},
            {"name": "G", "type": "R", "links": ["rocker", "ground"], "at": list(G)},
        ],
        "drivers": [{"joint": "K", "toward": "A", "start_deg": start_deg, "stop_deg": stop_deg,
                     "steps": steps, "speed": 1.0, "acceleration": 0.5}],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }


def triad_scene(P, steps=37):
    """The shipped class-III six-bar's topology with joints at ``P``."""
    links = [("crank", "B"), ("link_BC", "C"), ("lever", "D"), ("rocker_DE", "E"),
             ("rocker_FG", "F")]
    return {
        "name": "triad",
        "links": [{"name": n, "mass": 0.2, "com": list(P[c]), "inertia": 1e-4} for n, c in links],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "link_BC"], "at": list(P["B"])},
            {"name": "C", "type": "R", "links": ["link_BC", "lever"], "at": list(P["C"])},
            {"name": "D", "type": "R", "links": ["lever", "rocker_DE"], "at": list(P["D"])},
            {"name": "E", "type": "R", "links": ["rocker_DE", "ground"], "at": list(P["E"])},
            {"name": "F", "type": "R", "links": ["lever", "rocker_FG"], "at": list(P["F"])},
            {"name": "G", "type": "R", "links": ["rocker_FG", "ground"], "at": list(P["G"])},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360,
                     "steps": steps, "speed": 10.0, "acceleration": 1.0}],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }


TRIAD_BASE = {"B": (0.0, 0.05), "C": (0.187, 0.12), "D": (0.127, 0.03), "E": (0.12, -0.09),
              "F": (0.257, 0.03), "G": (0.265, -0.1)}


def triad_jump():
    """A random triad whose branch ends at a limit at step 14 and goes on in another
    configuration of the same determinant sign (both runtimes warn; found by a search over seeds)."""
    rng = np.random.default_rng(19)
    P = {k: tuple(np.array(v) + rng.normal(0, 0.03, 2)) for k, v in TRIAD_BASE.items()}
    return triad_scene(P, steps=73)
