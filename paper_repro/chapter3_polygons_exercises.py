"""Example 3-1's polygon intermediates and exercises 3-5, 3-13, 3-14, 3-23, 3-24 of the textbook
chapter "Kinematic analysis of planar mechanisms" ([4] of the README's Sources; author and
year not shown in the text), with linkage_sym's instant centres and polygon quantities.

Every result is computed twice: by linkage_sym (``linkage_sym.analyze`` with
``linkage_sym.centres``) and by a closed form written out here from the
mechanism's own loop (NumPy only, nothing of linkage_sym), and the two are
compared.  The chapter's figures are missing from the text we have, so each
exercise states the conventions it had to assume; the chapter prints no
answers to its exercises, so only example 3-1 is compared with printed numbers.

Example 3-1 (guide-bar, as the shipped example ``guide_bar_quick_return`` but from the unrounded data;
l_AB = 24 mm, l_AD = 78 mm, l_CD = 48 mm, gamma = 100 deg, omega1 = 10 rad/s
counter-clockwise, phi1 = 60 deg).  The book's numbering: crank 1, block 2,
guide bar 3, frame 4; B2 is the crank pin on the block, B3 the coincident
point of the guide bar.  It solves ``v_B3 = v_B2 + v_B3B2`` (eq. 3-3) and
``a_B3 = a_B3D^n + a_B3D^t = a_B2 + a_B3B2^k + a_B3B2^r`` (eq. 3-4) on
drawings at mu_l = 0.001 m/mm, mu_v = 0.01 (m/s)/mm, mu_a = 0.1 (m/s^2)/mm
and prints the intermediates ``v_B2 = 0.24`` m/s, ``v_B3 = 27 mm * mu_v``,
``BD = 69 mm``, ``omega3 = 3.91`` rad/s (clockwise), ``v_B3B2 = 32 mm * mu_v``,
``a_B2 = 2.4`` m/s^2, ``a^k = 2 omega2 v_B3B2 = 2.5`` m/s^2, ``a_B3D^n = 1.05``
m/s^2, ``a_B3D^t = 43 mm * mu_a``, ``alpha3 = 62.3`` rad/s^2.  A length read
off a drawing is good to half a millimetre: +-0.005 m/s, +-0.05 m/s^2,
+-0.5 mm; omega3 and alpha3 are quotients of two readings (+-2.6 %, +-1.9 %).
linkage_sym's slip velocity is the block's relative to the guide bar, so
``v_B3B2 = -slip``; ``a^k_B3B2 = 2 omega2 x v_B3B2`` (omega2 = omega3).

Exercise 3-5 (crank and oscillating block; l_AB = 30 mm, l_AC = 100 mm,
l_BD = 50 mm, l_DE = 40 mm, omega1 = 10 rad/s, phi1 = 45 deg: D, E, omega2,
alpha2).  Assumed: A = (0, 0), C = (100, 0) mm, phi1 counter-clockwise from AC,
omega1 counter-clockwise; link 2 is a straight bar through B that slides in
block 3, pivoted on the ground at C; D lies on the bar 50 mm from B toward C;
E lies 40 mm from D normal to the bar, to the left of the direction B -> C.

Exercise 3-13 (four-bar, l_AB = 60 mm, l_CD = 90 mm, l_AD = l_BC = 120 mm,
omega2 = 10 rad/s; by instant centres: (1) v_C at phi = 165 deg; (2) the
point E of line BC with the least speed and its speed; (3) phi where v_C = 0,
two solutions).  Assumed: the numbering of the chapter's Fig. 3-4 (frame 1,
crank AB 2, coupler BC 3, rocker CD 4), A = (0, 0), D = (120, 0) mm, phi the
angle of AB from AD, counter-clockwise, omega2 counter-clockwise, C above AD
at phi = 165 deg (that assembly mode kept over the turn).  (2): every point
of the coupler turns about P13, so the least speed on line BC is at the foot
of the perpendicular from P13, ``omega3 |P13 E|``; (3): v_C = 0 when P13 is at
C, i.e. when A, B, C are in line: closed form from triangle ACD with
``AC = AB + BC`` or ``BC - AB``.

Exercise 3-14 (scissors: l_AC = l_BC = l_CD = l_CE = l_DF = l_EF = 20 mm;
sliders 1 and 2 move in opposite directions at v1 = v2 = 0.002 m/s; v_F / v1
at theta3 = 45 deg, by instant centres).  Assumed: the sliders run on one
horizontal guide through A and B; bar 3 is A-C-D and bar 4 is B-C-E, crossing
at their middles C; links 5 (D-F) and 6 (E-F) meet at F above; theta3 is bar
3's angle to the guide; the sliders move apart.  Two degrees of freedom:
Kennedy's three-centre lines do not reach the centres, which come from the
velocities.  Closed form: ``y_F = 3 l sin(theta3)``, ``x_A = -l cos(theta3)``,
so ``v_F / v1 = 3 cot(theta3)`` = 3 at 45 deg.

Exercise 3-23 (offset slider-crank; l_AB = 100 mm, l_BC = 300 mm, e = 30 mm,
omega1 = 10 rad/s counter-clockwise; at phi1 = 60, 120, 220 deg: theta2,
omega2, alpha2, v3, a3, by complex numbers).  Assumed: A = (0, 0), the slider
C on the line y = -e (30 mm below A), to the right of B; phi1 from +x.  With
the offset above A the results are those of -phi1, mirrored.

Exercise 3-24 (oscillating guide bar; l_AB = 100 mm, l_AC = 200 mm, the guide
line 40 mm from the pivot C -- the OCR prints "l_cx = 40 mm"; omega1 = 10
rad/s; at phi1 = 30, 120 deg: omega3, alpha3).  Assumed: C = (0, 0), A = (0,
200) mm above it, phi1 from +x, omega1 counter-clockwise; the guide line of
bar 3 runs 40 mm from C, on the left of its direction (``e = +40``) or on its
right (``e = -40``): both are given.

Run:  python3 paper_repro/chapter3_polygons_exercises.py   (from the repository root)
"""

from __future__ import annotations

import math

import numpy as np

import linkage_sym
from linkage_sym.centres import instant_centres, polygon_quantities

MM = 1e-3


def _rot(v):
    """``J v``: ``v`` turned by +90 degrees."""
    return np.array([-v[1], v[0]])


def _analyze(scene_dict):
    scene = linkage_sym.load_scene(scene_dict)
    return scene, linkage_sym.analyze(scene)


def _r(name, a, b, at):
    return {"name": name, "type": "R", "links": [a, b], "at": [float(at[0]), float(at[1])]}


# ------------------------------------------------------------------ example 3-1

PRINTED_3_1 = {  # name: (printed value, half a unit of the drawing it was read from)
    "v_B2": (0.24, 0.0),          # omega1 l_AB, computed in the text
    "v_B3": (0.27, 0.005),        # mu_v * pb3 = 0.01 * 27
    "BD": (0.069, 0.0005),        # measured on the drawing
    "omega3": (-3.91, 0.10),      # 0.01 * 27 / (0.001 * 69), clockwise
    "v_B3B2": (0.32, 0.005),      # mu_v * b2b3 = 0.01 * 32
    "a_B2": (2.4, 0.0),           # omega1^2 l_AB
    "a_k": (2.5, 0.05),           # 2 * 3.91 * 0.01 * 32
    "a_n_B3D": (1.05, 0.05),      # 3.91^2 * 0.001 * 69
    "a_t_B3D": (4.3, 0.05),       # mu_a * n3'b3' = 0.1 * 43
    "alpha3": (62.3, 1.2),        # 0.1 * 43 / (0.001 * 69)
}


def example_3_1() -> dict:
    """The intermediates of example 3-1 at phi1 = 60 deg: ``{name: (linkage_sym, closed form)}``.

    The closed form is the guide-bar's own loop (example 3-6): ``s2``, the
    position of B along the guide from C, and its rates.
    """
    closed = _guide_bar_closed()
    B = 0.024 * np.array([math.cos(math.radians(60.0)), math.sin(math.radians(60.0))])
    scene, res = _analyze({  # the shipped example with its printed data unrounded
        "name": "example 3-1",
        "links": [{"name": "crank"}, {"name": "block"}, {"name": "guide_bar"}],
        "joints": [_r("A", "ground", "crank", (0, 0)), _r("B", "crank", "block", B),
                   {"name": "B_slide", "type": "P", "links": ["guide_bar", "block"],
                    "at": B.tolist(), "axis_deg": math.degrees(closed["th2"])},
                   _r("D", "guide_bar", "ground", (0.078, 0))],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 60, "stop_deg": 60, "steps": 1,
                     "speed": 10.0}],
        "outputs": ["kinematics"],
    })
    pq = polygon_quantities(scene, res, 0)
    s = pq.sliding[0]
    B = res.joints["B"].position[0]
    D = res.joints["D"].position[0]
    b_guide = next(p for p in pq.points if p.name == "B" and p.link == "guide_bar")
    b_block = next(p for p in pq.points if p.name == "B" and p.link == "block")
    rel = next(r for r in pq.relative if r.link == "guide_bar" and r.point == "B" and r.about == "D")
    v_b3b2 = b_guide.velocity - b_block.velocity                 # = -slip
    a_k = 2.0 * pq.omega["block"] * _rot(v_b3b2)                  # 2 omega2 x v_B3B2
    ours = {
        "v_B2": float(np.hypot(*b_block.velocity)),
        "v_B3": float(np.hypot(*b_guide.velocity)),
        "BD": float(np.hypot(*(B - D))),
        "omega3": pq.omega["guide_bar"],
        "v_B3B2": float(np.hypot(*v_b3b2)),
        "a_B2": float(np.hypot(*b_block.acceleration)),
        "a_k": float(np.hypot(*a_k)),
        "a_n_B3D": float(np.hypot(*rel.normal)),
        "a_t_B3D": float(np.hypot(*rel.tangential)),
        "alpha3": pq.alpha["guide_bar"],
    }
    assert np.allclose(s.coriolis, -a_k, rtol=0, atol=1e-12)  # the block's term is the opposite
    return {k: (ours[k], closed[k]) for k in ours}


def _guide_bar_closed() -> dict:
    """Example 3-1/3-6 from its loop l1 e^{i th1} = l4 + l3 e^{i th3} + s2 e^{i th2}."""
    l1, l3, l4, gamma, w1 = 0.024, 0.048, 0.078, math.radians(100.0), 10.0
    th1 = math.radians(60.0)
    B = np.array([l1 * math.cos(th1), l1 * math.sin(th1)])
    D = np.array([l4, 0.0])
    d = float(np.hypot(*(B - D)))
    # |B - D|^2 = l3^2 + 2 l3 s2 cos(gamma) + s2^2, the root of the book's configuration
    s2 = -l3 * math.cos(gamma) + math.sqrt(d * d - (l3 * math.sin(gamma)) ** 2)
    th3 = math.atan2(B[1] - D[1], B[0] - D[0]) - math.atan2(s2 * math.sin(gamma), l3 + s2 * math.cos(gamma))
    th2 = th3 + gamma
    den = s2 + l3 * math.cos(gamma)
    w3 = l1 * w1 * math.cos(th1 - th2) / den                       # example 3-6
    ds2 = -l1 * w1 * math.sin(th1 - th2) - l3 * w3 * math.sin(gamma)
    a3 = (-l1 * w1**2 * math.sin(th1 - th2) - l3 * w3**2 * math.sin(gamma) - 2 * ds2 * w3) / den
    return {
        "v_B2": l1 * w1, "v_B3": abs(w3) * d, "BD": d, "omega3": w3, "v_B3B2": abs(ds2),
        "a_B2": l1 * w1**2, "a_k": abs(2 * w3 * ds2), "a_n_B3D": w3**2 * d,
        "a_t_B3D": abs(a3) * d, "alpha3": a3, "th2": th2,
    }


# ------------------------------------------------------------------ exercise 3-5


def exercise_3_5() -> dict:
    """Crank and oscillating block at phi1 = 45 deg: ``{name: (linkage_sym, closed form)}``."""
    l1, lac, lbd, lde, w1, phi = 30 * MM, 100 * MM, 50 * MM, 40 * MM, 10.0, math.radians(45.0)
    A, C = np.zeros(2), np.array([lac, 0.0])
    B = l1 * np.array([math.cos(phi), math.sin(phi)])
    u = (C - B) / np.hypot(*(C - B))
    D = B + lbd * u
    E = D + lde * _rot(u)
    scene = {
        "name": "exercise 3-5",
        "links": [{"name": "crank"}, {"name": "bar"}, {"name": "block"}],
        "joints": [
            _r("A", "ground", "crank", A), _r("B", "crank", "bar", B), _r("C", "ground", "block", C),
            {"name": "C_slide", "type": "P", "links": ["block", "bar"], "at": [float(C[0]), float(C[1])],
             "axis_deg": math.degrees(math.atan2(u[1], u[0]))},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 45, "stop_deg": 45, "steps": 1,
                     "speed": w1}],
        "points": [{"name": "D", "link": "bar", "at": D.tolist()},
                   {"name": "E", "link": "bar", "at": E.tolist()}],
        "outputs": ["kinematics"],
    }
    sc, res = _analyze(scene)
    pq = polygon_quantities(sc, res, 0)
    s = pq.sliding[0]
    ours = {
        "omega2": pq.omega["bar"], "alpha2": pq.alpha["bar"],
        "v_D": res.points["D"].velocity[0], "a_D": res.points["D"].acceleration[0],
        "v_E": res.points["E"].velocity[0], "a_E": res.points["E"].acceleration[0],
        "slip": s.speed, "coriolis": s.coriolis,
    }
    # closed form: C = B + s u2 with the bar through C; s' and omega2 from the rates
    vB = l1 * w1 * np.array([-math.sin(phi), math.cos(phi)])
    aB = -l1 * w1**2 * np.array([math.cos(phi), math.sin(phi)])
    sdist = float(np.hypot(*(C - B)))
    n = _rot(u)
    w2 = -(vB @ n) / sdist
    ds = -(vB @ u)
    a2 = -((aB @ n) + 2 * ds * w2) / sdist
    rD, rE = lbd * u, lbd * u + lde * n
    closed = {
        "omega2": w2, "alpha2": a2,
        "v_D": vB + w2 * _rot(rD), "a_D": aB + a2 * _rot(rD) - w2**2 * rD,
        "v_E": vB + w2 * _rot(rE), "a_E": aB + a2 * _rot(rE) - w2**2 * rE,
        # the bar slides through the block: its point at C moves along u at -ds relative to it
        "slip": -ds, "coriolis": 2 * w2 * _rot(-ds * u),
    }
    return {k: (ours[k], closed[k]) for k in ours}


# ------------------------------------------------------------------ exercise 3-13


def _fourbar_3_13(phi_deg, steps=1, stop=None):
    lab, lbc, lcd, lad = 60 * MM, 120 * MM, 90 * MM, 120 * MM
    phi = math.radians(phi_deg)
    A, D = np.zeros(2), np.array([lad, 0.0])
    B = lab * np.array([math.cos(phi), math.sin(phi)])
    d = float(np.hypot(*(D - B)))
    ex = (D - B) / d
    x = (lbc**2 - lcd**2 + d * d) / (2 * d)
    h = math.sqrt(lbc**2 - x * x)
    C = max((B + x * ex + h * _rot(ex), B + x * ex - h * _rot(ex)), key=lambda c: c[1])  # C above AD
    return {
        "name": "exercise 3-13",
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [_r("A", "ground", "crank", A), _r("B", "crank", "coupler", B),
                   _r("C", "coupler", "rocker", C), _r("D", "rocker", "ground", D)],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": phi_deg,
                     "stop_deg": phi_deg if stop is None else stop, "steps": steps, "speed": 10.0}],
        "outputs": ["kinematics", "instant_centres"],
    }


def exercise_3_13() -> dict:
    """(1) v_C at 165 deg, (2) the slowest point E of line BC, (3) the angles where v_C = 0."""
    scene, res = _analyze(_fourbar_3_13(165.0))
    ic = res.instant_centres
    P = {f"P{a}{b}": ic.position[0, ic.index(x, y)]
         for a, x in enumerate(ic.links, 1) for b, y in enumerate(ic.links, 1) if a < b}
    w2 = 10.0
    B, C = res.joints["B"].position[0], res.joints["C"].position[0]
    # the chapter's transmission ratio: omega4 / omega2 = P12P24 / P14P24 (signed along the line)
    w4 = w2 * (P["P24"] - P["P12"]) @ (P["P24"] - P["P14"]) / float(np.hypot(*(P["P24"] - P["P14"]))) ** 2
    w3 = w2 * float(np.hypot(*(B - P["P12"]))) / float(np.hypot(*(B - P["P13"])))  # |v_B| = w3 |P13 B|
    u = (C - B) / np.hypot(*(C - B))
    E = B + ((P["P13"] - B) @ u) * u                                  # foot of the perpendicular
    centres = {
        "v_C": abs(w4) * float(np.hypot(*(C - P["P14"]))),
        "E": E, "BE": float((E - B) @ u), "v_E": abs(w3) * float(np.hypot(*(E - P["P13"]))),
    }
    solver = {
        "v_C": float(np.hypot(*res.joints["C"].velocity[0])),
        "omega4_ratio": res.links["rocker"].omega[0] / w2,
        "v_E": float(np.hypot(*res.links["coupler"].point_velocity(tuple(E))[0])),
    }
    centres["omega4_ratio"] = w4 / w2
    # (3) v_C = 0: the rocker's omega changes sign; roots refined by bisection on solved steps
    sweep_scene, sweep = _analyze(_fourbar_3_13(0.0, steps=721, stop=360.0))
    w = sweep.links["rocker"].omega
    q = np.degrees(sweep.drivers["A"]["q"])
    plan = linkage_sym.compile_plan(sweep_scene)
    roots = []
    for k in np.flatnonzero(np.sign(w[:-1]) != np.sign(w[1:])):
        lo, hi = q[k], q[k + 1]
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            r = plan.run(q={"A": [math.radians(mid)]}, qd={"A": [10.0]}, qdd={"A": [0.0]})
            if np.sign(r.links["rocker"].omega[0]) == np.sign(w[k]):
                lo = mid
            else:
                hi = mid
        roots.append(0.5 * (lo + hi))
    # closed form: A, B, C in line, AC = AB + BC (extended) or BC - AB (folded, B opposite C)
    def angle(ac):
        return math.degrees(math.acos((ac**2 + 120.0**2 - 90.0**2) / (2 * ac * 120.0)))
    closed_roots = sorted([angle(180.0), (180.0 + angle(60.0)) % 360.0])
    return {"centres": centres, "solver": solver, "roots": roots, "closed_roots": closed_roots,
            "P13": P["P13"], "P24": P["P24"]}


# ------------------------------------------------------------------ exercise 3-14


def exercise_3_14() -> dict:
    """Scissors at theta3 = 45 deg: v_F / v1 from the solver, from the centres and closed form."""
    l, th, v = 20 * MM, math.radians(45.0), 0.002
    A = np.array([-l * math.cos(th), 0.0])
    B = np.array([l * math.cos(th), 0.0])
    C = np.array([0.0, l * math.sin(th)])
    D, E = 2 * C - A, 2 * C - B
    F = np.array([0.0, D[1] + math.sqrt(l * l - D[0] ** 2)])
    scene = {
        "name": "exercise 3-14",
        "links": [{"name": n} for n in ("slider1", "slider2", "bar3", "bar4", "link5", "link6")],
        "joints": [
            {"name": "S1", "type": "P", "links": ["ground", "slider1"], "at": A.tolist(), "axis_deg": 0},
            {"name": "S2", "type": "P", "links": ["ground", "slider2"], "at": B.tolist(), "axis_deg": 0},
            _r("A", "slider1", "bar3", A), _r("B", "slider2", "bar4", B), _r("C", "bar3", "bar4", C),
            _r("D", "bar3", "link5", D), _r("E", "bar4", "link6", E), _r("F", "link5", "link6", F),
        ],
        "drivers": [{"joint": "S1", "start": 0, "stop": 0, "steps": 1, "speed": -v},
                    {"joint": "S2", "start": 0, "stop": 0, "steps": 1, "speed": v}],
        "outputs": ["kinematics", "instant_centres"],
    }
    sc, res = _analyze(scene)
    ic = res.instant_centres
    vF = res.joints["F"].velocity[0]
    # from the centres: F on link 5 turns about P(ground, link5) at omega5
    P05 = ic.position[0, ic.index("ground", "link5")]
    w5 = res.links["link5"].omega[0]
    vF_centre = w5 * _rot(F - P05)
    return {
        "ratio_solver": float(np.hypot(*vF)) / v,
        "ratio_centres": float(np.hypot(*vF_centre)) / v,
        "ratio_closed": 3.0 / math.tan(th),
        "filled_from_velocities": int(ic.from_velocities[0].sum()),
        "pairs": len(ic.pairs),
        "P(ground, bar3)": ic.position[0, ic.index("ground", "bar3")],
        "P(ground, bar3) closed": np.array([A[0], C[1]]),  # A moves along x, C along y
    }


# ------------------------------------------------------------------ exercise 3-23


def exercise_3_23() -> dict:
    """Offset slider-crank at 60, 120, 220 deg: ``{phi: {name: (linkage_sym, closed form)}}``."""
    l1, l2, e, w1 = 100 * MM, 300 * MM, 30 * MM, 10.0
    out = {}
    for phi_deg in (60.0, 120.0, 220.0):
        phi = math.radians(phi_deg)
        yg = -e
        th2 = math.asin((yg - l1 * math.sin(phi)) / l2)               # slider right of B
        x = l1 * math.cos(phi) + l2 * math.cos(th2)
        w2 = -l1 * w1 * math.cos(phi) / (l2 * math.cos(th2))
        v3 = -l1 * w1 * math.sin(phi) - l2 * w2 * math.sin(th2)
        a2 = (l1 * w1**2 * math.sin(phi) + l2 * w2**2 * math.sin(th2)) / (l2 * math.cos(th2))
        a3 = -l1 * w1**2 * math.cos(phi) - l2 * a2 * math.sin(th2) - l2 * w2**2 * math.cos(th2)
        B = l1 * np.array([math.cos(phi), math.sin(phi)])
        C = np.array([x, yg])
        scene = {
            "name": "exercise 3-23",
            "links": [{"name": "crank"}, {"name": "rod"}, {"name": "slider"}],
            "joints": [_r("A", "ground", "crank", (0, 0)), _r("B", "crank", "rod", B),
                       _r("C", "rod", "slider", C),
                       {"name": "G", "type": "P", "links": ["ground", "slider"], "at": C.tolist(),
                        "axis_deg": 0.0}],
            "drivers": [{"joint": "A", "toward": "B", "start_deg": phi_deg, "stop_deg": phi_deg,
                         "steps": 1, "speed": w1}],
            "outputs": ["kinematics"],
        }
        sc, res = _analyze(scene)
        rod = res.links["rod"]
        th2_ours = math.atan2(*(res.joints["C"].position[0] - res.joints["B"].position[0])[::-1])
        out[phi_deg] = {
            "theta2_deg": (math.degrees(th2_ours), math.degrees(th2)),
            "omega2": (rod.omega[0], w2), "alpha2": (rod.alpha[0], a2),
            "v3": (res.joints["C"].velocity[0][0], v3), "a3": (res.joints["C"].acceleration[0][0], a3),
        }
    return out


# ------------------------------------------------------------------ exercise 3-24


def exercise_3_24() -> dict:
    """Oscillating guide bar with the guide 40 mm from C: ``{(e_mm, phi): {name: (ours, closed)}}``."""
    l1, l6, w1 = 100 * MM, 200 * MM, 10.0
    out = {}
    for e_mm in (40.0, -40.0):
        e = e_mm * MM
        for phi_deg in (30.0, 120.0):
            phi = math.radians(phi_deg)
            B = np.array([l1 * math.cos(phi), l6 + l1 * math.sin(phi)])
            d = float(np.hypot(*B))
            s = math.sqrt(d * d - e * e)                                # B - C = e n3 + s u3
            th3 = math.atan2(B[1], B[0]) - math.atan2(e, s)
            u3 = np.array([math.cos(th3), math.sin(th3)])
            n3 = _rot(u3)
            vB = l1 * w1 * np.array([-math.sin(phi), math.cos(phi)])
            aB = -l1 * w1**2 * np.array([math.cos(phi), math.sin(phi)])
            w3 = (vB @ n3) / s
            ds = vB @ u3 + e * w3
            a3 = (aB @ n3 + e * w3**2 - 2 * ds * w3) / s
            scene = {
                "name": "exercise 3-24",
                "links": [{"name": "crank"}, {"name": "block"}, {"name": "guide_bar"}],
                "joints": [_r("A", "ground", "crank", (0, l6)), _r("B", "crank", "block", B),
                           {"name": "B_slide", "type": "P", "links": ["guide_bar", "block"],
                            "at": B.tolist(), "axis_deg": math.degrees(th3)},
                           _r("C", "guide_bar", "ground", (0, 0))],
                "drivers": [{"joint": "A", "toward": "B", "start_deg": phi_deg, "stop_deg": phi_deg,
                             "steps": 1, "speed": w1}],
                "outputs": ["kinematics"],
            }
            sc, res = _analyze(scene)
            g = res.links["guide_bar"]
            out[e_mm, phi_deg] = {"omega3": (g.omega[0], w3), "alpha3": (g.alpha[0], a3),
                                  "slip": (polygon_quantities(sc, res, 0).sliding[0].speed, ds)}
    return out


# ------------------------------------------------------------------ report


def _num(x):
    x = np.asarray(x, dtype=float)
    if x.ndim == 0:
        return f"{float(x):.6g}"
    return "(" + ", ".join(f"{float(c):.6g}" for c in x) + ")"


def main():
    print("Example 3-1 at phi1 = 60 deg: linkage_sym | closed form | printed (drawing precision)")
    for k, (ours, closed) in example_3_1().items():
        printed, half = PRINTED_3_1[k]
        ok = "ok" if abs(abs(ours) - abs(printed)) <= half + 1e-9 * abs(printed) else "OFF"
        print(f"  {k:8s} {ours:10.5g} {closed:10.5g}   {printed:g} +- {half:g}  {ok}")
    print("\nExercise 3-5 (phi1 = 45 deg): linkage_sym | closed form  (SI units)")
    for k, (ours, closed) in exercise_3_5().items():
        print(f"  {k:8s} {_num(ours):34s} {_num(closed)}")
    r = exercise_3_13()
    print("\nExercise 3-13: by the instant centres | from the solver")
    print(f"  P13 = {_num(np.array(r['P13']) / MM)} mm, P24 = {_num(np.array(r['P24']) / MM)} mm")
    print(f"  (1) v_C = {r['centres']['v_C']:.6g} m/s | {r['solver']['v_C']:.6g} m/s "
          f"(omega4/omega2 = {r['centres']['omega4_ratio']:.6g} | {r['solver']['omega4_ratio']:.6g})")
    print(f"  (2) E = {_num(r['centres']['E'] / MM)} mm, BE = {r['centres']['BE'] / MM:.6g} mm along "
          f"B->C, v_E = {r['centres']['v_E']:.6g} | {r['solver']['v_E']:.6g} m/s")
    print(f"  (3) v_C = 0 at phi = {', '.join(f'{x:.6f}' for x in r['roots'])} deg "
          f"(closed form {', '.join(f'{x:.6f}' for x in r['closed_roots'])})")
    r = exercise_3_14()
    print("\nExercise 3-14 (theta3 = 45 deg):")
    print(f"  v_F/v1 = {r['ratio_solver']:.12g} (solver), {r['ratio_centres']:.12g} (centres), "
          f"{r['ratio_closed']:.12g} (3 cot theta3); {r['filled_from_velocities']} of {r['pairs']} "
          "centres from the velocities (two degrees of freedom)")
    print("\nExercise 3-23 (e = 30 mm below A): linkage_sym | closed form")
    for phi, vals in exercise_3_23().items():
        print(f"  phi1 = {phi:g} deg: " + ", ".join(f"{k} {a:.6g} | {b:.6g}" for k, (a, b) in vals.items()))
    print("\nExercise 3-24 (guide 40 mm from C, both sides): linkage_sym | closed form")
    for (e, phi), vals in exercise_3_24().items():
        print(f"  e = {e:+g} mm, phi1 = {phi:g} deg: "
              + ", ".join(f"{k} {a:.6g} | {b:.6g}" for k, (a, b) in vals.items()))


if __name__ == "__main__":
    main()
