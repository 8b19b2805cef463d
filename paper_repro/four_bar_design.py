"""The textbook section *Design of four-bar mechanisms* ([2] of the README's Sources), worked.

The section (Figs. 2-65 to 2-78; title, author, publisher and year of the book not shown in
the text we have, nor its figures) gives

1. the design by the stroke-time ratio K as a *procedure* (eq. 2-2 and the auxiliary circle
   of Fig. 2-65) without numbers, and says that the offset slider-crank and the guide-bar
   "are designed likewise";
2. two statics examples with numbers: example 2-9 (a ball on a smooth incline held by a
   rope) and example 2-10 (an engine's crank-slider in equilibrium).

Part 1 runs the procedure step by step on numbers of our own (the section prints none) with
the construction written out here in NumPy -- the auxiliary circle from the two lines at
90 deg - theta to the chord, the pivot A where the circle of the ground length about D meets it
-- and compares each step with ``linkage_sym.synthesis`` and the finished linkage with the
solver's own extreme positions (roots of the rocker's angular velocity, bisected here).

Part 2 builds each statics example as a scene and solves it with linkage_sym's force solver,
then prints the results against the section's:

* example 2-9 prints F_N = 1.414 N and F_T = 0.732 N for a 2 kN ball: the unit is kN (an
  erratum: with G = 2 kN the forces are G sin(alpha)/sin(alpha + beta) = 1.41421 kN and
  G sin(beta)/sin(alpha + beta) = 0.73205 kN);
* example 2-10 prints F_NB = 0.133 kN and M = F_NB x 400 = 53.2 N m: the moment was computed
  from the rounded force; with F_NB = F_Q tan(alpha) = 0.4/3 kN = 0.13333 kN it is 53.333 N m.

Modelling (the figures are missing):

* 2-9: the ball (centre at the origin) slides on the incline: a P joint ground-ball along the
  incline, beta = 15 deg below +x (so its normal reaction has the equations' components
  (F_N sin beta, F_N cos beta)); the rope pulls up and to the left at alpha = 30 deg from the
  vertical, as ``F_T sin alpha`` in the x equation says.  A rope is a link whose length is
  held: two links with a driven P joint between them (an actuator of fixed length, speed 0),
  so the rope tension is that driver's effort.  Weight as a 2000 N load.
* 2-10: the cylinder is vertical through the crank pivot O; the piston B at OB = 400 mm
  (the "x 400" of the printed moment), the rod AB at tan(alpha) = 1/3 from the cylinder's axis;
  the working resistance F_Q = 0.4 kN pushes the piston down.  The crank and rod lengths are
  not given and do not matter: two crank pins on the rod's line are solved and agree.

Run from the repository root:

    python3 paper_repro/four_bar_design.py
"""

from __future__ import annotations

import math

import numpy as np

import linkage_sym
from linkage_sym.synthesis import crank_rocker, guide_bar_by_K, slider_crank_by_K

# ------------------------------------------------------------------ part 1: design by K

K, ROCKER, SWING_DEG, GROUND = 1.5, 0.075, 45.0, 0.100
"""Worked numbers (ours): K, rocker CD (m), swing psi (deg), frame AD (m)."""


def auxiliary_circle_design(K=K, c=ROCKER, psi_deg=SWING_DEG, d=GROUND) -> dict:
    """The section's steps 1-5, written out: theta, the rocker's extremes, the auxiliary circle,
    the pivot A at the ground length from D (on the side of C1C2 away from D, as drawn), and the
    crank and coupler from AC1 = b + a, AC2 = b - a."""
    theta = math.pi * (K - 1) / (K + 1)                     # step 1, eq. 2-2
    psi = math.radians(psi_deg)
    D = np.array([0.0, 0.0])                                # step 2: D anywhere
    C1 = D + c * np.array([math.cos(math.pi / 2 + psi / 2), math.sin(math.pi / 2 + psi / 2)])
    C2 = D + c * np.array([math.cos(math.pi / 2 - psi / 2), math.sin(math.pi / 2 - psi / 2)])
    # step 3: lines through C1 and C2 at 90 deg - theta to C1C2 meet at O (angle C1 O C2 = 2 theta)
    u = (C2 - C1) / np.linalg.norm(C2 - C1)
    n = np.array([-u[1], u[0]])                             # away from D
    w = math.pi / 2 - theta
    d1 = math.cos(w) * u + math.sin(w) * n                  # from C1, turned by 90 - theta
    d2 = -math.cos(w) * u + math.sin(w) * n                 # from C2, the mirror image
    s = np.linalg.solve(np.column_stack([d1, -d2]), C2 - C1)
    O = C1 + s[0] * d1
    R = float(np.linalg.norm(O - C1))
    # step 4: A on the circle, |AD| = d (two points, mirror images in the bisector: take one)
    r = float(np.linalg.norm(O - D))
    x = (d * d - R * R + r * r) / (2 * r)
    h = math.sqrt(d * d - x * x)
    e = (O - D) / r
    A = D + x * e + h * np.array([-e[1], e[0]])
    l1, l2 = float(np.linalg.norm(A - C1)), float(np.linalg.norm(A - C2))
    if l1 < l2:  # C1 is the extended position by name
        C1, C2, l1, l2 = C2, C1, l2, l1
    seen = math.acos(float((C1 - A) @ (C2 - A)) / (l1 * l2))
    side = lambda P: float((A - D)[0] * (P - D)[1] - (A - D)[1] * (P - D)[0])  # noqa: E731
    return {"theta": theta, "chord": float(np.linalg.norm(C2 - C1)), "R": R,
            "angle_C1OC2": math.acos(float((C1 - O) @ (C2 - O)) / R**2), "angle_C1AC2": seen,
            "AC1": l1, "AC2": l2, "crank": (l1 - l2) / 2, "coupler": (l1 + l2) / 2,
            "admissible": side(C1) * side(C2) > 0}


def _bisect(f, lo, hi, tol=1e-15):
    flo = f(lo)
    while hi - lo > tol * max(1.0, abs(lo)):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def solver_extremes(scene_dict, rate, value, grid=720) -> tuple[float, float]:
    """``(output range, K)`` of a scene from linkage_sym's solver: roots of the output's rate."""
    scene = linkage_sym.load_scene(scene_dict)
    plan = linkage_sym.compile_plan(scene)
    start = scene.drivers[0].start

    def at(phi):
        res = plan.run(q={"A": np.array([phi])}, qd={"A": np.ones(1)}, qdd={"A": np.zeros(1)})
        return res

    phis = start + (np.arange(grid) + 0.5) * 2 * math.pi / grid
    res = plan.run(q={"A": phis}, qd={"A": np.ones(grid)}, qdd={"A": np.zeros(grid)})
    w = rate(res)
    roots = []
    for i in range(grid):
        j = (i + 1) % grid
        if np.sign(w[i]) != np.sign(w[j]):
            hi = phis[j] + (2 * math.pi if j == 0 else 0.0)
            roots.append(_bisect(lambda p: float(rate(at(p))[0]), phis[i], hi))
    r1, r2 = sorted(roots)
    v1, v2 = (float(value(at(r))[0]) for r in (r1, r2))
    span = r2 - r1
    return abs(v2 - v1), max(span, 2 * math.pi - span) / min(span, 2 * math.pi - span)


def part1() -> dict:
    """The worked crank-rocker, slider-crank and guide-bar: construction, synthesis, solver."""
    by_hand = auxiliary_circle_design()
    design = crank_rocker(K, ROCKER, SWING_DEG, ground=GROUND)
    psi, k = solver_extremes(design.scene, lambda r: r.links["rocker"].omega,
                             lambda r: r.links["rocker"].rotation)
    slider = slider_crank_by_K(1.4, 0.100, offset=0.020)
    H, k_s = solver_extremes(slider.scene, lambda r: r.joints["C"].velocity[:, 0],
                             lambda r: r.joints["C"].position[:, 0])
    best = crank_rocker(K, ROCKER, SWING_DEG)  # no frame condition: the best transmission
    guide = guide_bar_by_K(2.0, 0.400)
    psi_g, k_g = solver_extremes(guide.scene, lambda r: r.links["rocker"].omega,
                                 lambda r: r.links["rocker"].rotation)
    return {"by_hand": by_hand, "design": design, "best": best, "solver_swing": psi, "solver_K": k,
            "slider": slider, "solver_stroke": H, "solver_K_slider": k_s,
            "guide": guide, "solver_swing_guide": psi_g, "solver_K_guide": k_g}


# ------------------------------------------------------------------ part 2: statics examples

G, ALPHA_DEG, BETA_DEG = 2000.0, 30.0, 15.0
"""Example 2-9: the ball's weight (N; 2 kN) and the rope's and incline's angles."""

EX_2_9_PRINTED = {"F_N": 1.414, "F_T": 0.732}
"""As printed, with the unit N where kN is meant."""


def ball_scene(G=G, alpha_deg=ALPHA_DEG, beta_deg=BETA_DEG, rope=1.0) -> dict:
    al, be = math.radians(alpha_deg), math.radians(beta_deg)
    up = np.array([-math.sin(al), math.cos(al)])          # from the ball toward the rope's anchor
    anchor, mid = rope * up, 0.5 * rope * up
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    return {
        "name": "example 2-9 ball on an incline",
        "links": [{"name": "ball"}, {"name": "rope_top"}, {"name": "rope_end"}],
        "joints": [
            {"name": "N", "type": "P", "links": ["ground", "ball"], "at": [0.0, 0.0],
             "axis_deg": -beta_deg},
            {"name": "Q", "type": "R", "links": ["ground", "rope_top"], "at": xy(anchor)},
            {"name": "T", "type": "P", "links": ["rope_top", "rope_end"], "at": xy(mid),
             "axis_deg": 90.0 + alpha_deg},
            {"name": "O", "type": "R", "links": ["rope_end", "ball"], "at": [0.0, 0.0]},
        ],
        "drivers": [{"joint": "T", "start": 0.0, "stop": 0.0, "steps": 1, "speed": 0.0}],
        "loads": [{"link": "ball", "force": [0.0, -G], "at": [0.0, 0.0]}],
        "effects": {"inertia": False, "loads": True},
        "outputs": ["reactions", "driving", "frame"],
    }


def example_2_9() -> dict:
    """F_N and F_T (N) by the force solver, and the closed forms of the section's two equations."""
    res = linkage_sym.analyze(linkage_sym.load_scene(ball_scene()))
    assert res.status[0] == "ok", res.messages[0]
    N = res.forces.reactions["N"][0]
    al, be = math.radians(ALPHA_DEG), math.radians(BETA_DEG)
    return {
        "F_N": float(np.hypot(*N)), "F_N_direction_deg": math.degrees(math.atan2(N[0], N[1])),
        "N_moment": float(res.forces.reaction_moments["N"][0]),
        "F_T": float(res.forces.driving["T"][0]),
        "F_N_closed": G * math.sin(al) / math.sin(al + be),
        "F_T_closed": G * math.sin(be) / math.sin(al + be),
    }


F_Q, TAN_ALPHA, OB = 400.0, 1.0 / 3.0, 0.400
"""Example 2-10: working resistance (N; 0.4 kN), tan(alpha) of the rod, piston height (m)."""

EX_2_10_PRINTED = {"F_NB": 0.133e3, "F_Ox": 0.133e3, "F_Oy": 0.4e3, "M": 53.2}
"""As printed (N, N m)."""


def engine_scene(rod_run=0.3) -> dict:
    """The crank-slider with the piston at (0, OB) and the crank pin A on the rod's line below it,
    ``rod_run`` (m) lower (so A = (rod_run tan(alpha), OB - rod_run))."""
    B = np.array([0.0, OB])
    A = B + np.array([rod_run * TAN_ALPHA, -rod_run])
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    return {
        "name": "example 2-10 engine crank-slider",
        "links": [{"name": "crank"}, {"name": "rod"}, {"name": "piston"}],
        "joints": [
            {"name": "O", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "A", "type": "R", "links": ["crank", "rod"], "at": xy(A)},
            {"name": "B", "type": "R", "links": ["rod", "piston"], "at": xy(B)},
            {"name": "B_cyl", "type": "P", "links": ["ground", "piston"], "at": xy(B),
             "axis_deg": 90.0},
        ],
        "drivers": [{"joint": "O", "toward": "A", "start_deg": math.degrees(math.atan2(A[1], A[0])),
                     "stop_deg": math.degrees(math.atan2(A[1], A[0])), "steps": 1, "speed": 0.0}],
        "loads": [{"link": "piston", "force": [0.0, -F_Q], "at": xy(B)}],
        "effects": {"inertia": False, "loads": True},
        "outputs": ["reactions", "driving", "frame"],
    }


def example_2_10(rod_run=0.3) -> dict:
    """F_NB, F_Ox, F_Oy (N) and M (N m) by the force solver; the exact values of the section's
    equations (F_NB = F_Q tan(alpha), M = F_NB OB)."""
    res = linkage_sym.analyze(linkage_sym.load_scene(engine_scene(rod_run)))
    assert res.status[0] == "ok", res.messages[0]
    O = res.forces.reactions["O"][0]
    return {
        "F_NB": float(np.hypot(*res.forces.reactions["B_cyl"][0])),
        "F_Ox": float(abs(O[0])), "F_Oy": float(O[1]),
        "M": float(res.forces.driving["O"][0]),
        "F_NB_exact": F_Q * TAN_ALPHA, "M_exact": F_Q * TAN_ALPHA * OB,
        "M_from_rounded_F_NB": 0.133e3 * OB,
    }


# ------------------------------------------------------------------ report


def main() -> None:
    p = part1()
    h, d = p["by_hand"], p["design"]
    print("Part 1. Design by the stroke-time ratio (procedure of Fig. 2-65, our numbers):")
    print(f"  K = {K}, rocker CD = {ROCKER} m, swing psi = {SWING_DEG} deg, frame AD = {GROUND} m")
    print(f"  1) theta = 180 (K - 1)/(K + 1) = {math.degrees(h['theta']):.6f} deg")
    print(f"  2) chord C1C2 = 2 CD sin(psi/2) = {h['chord']:.9f} m")
    print(f"  3) auxiliary circle: angle C1 O C2 = {math.degrees(h['angle_C1OC2']):.9f} deg "
          f"(2 theta), R = {h['R']:.9f} m")
    print(f"  4) A at {GROUND} m from D: angle C1 A C2 = {math.degrees(h['angle_C1AC2']):.9f} deg; "
          f"AC1 = {h['AC1']:.9f} m, AC2 = {h['AC2']:.9f} m; admissible: {h['admissible']}")
    print(f"  5) crank = (AC1 - AC2)/2 = {h['crank']:.9f} m, coupler = (AC1 + AC2)/2 = "
          f"{h['coupler']:.9f} m")
    print(f"     linkage_sym.synthesis.crank_rocker: crank {d.lengths['crank']:.9f} m, coupler "
          f"{d.lengths['coupler']:.9f} m (difference {abs(d.lengths['crank'] - h['crank']):.1e}, "
          f"{abs(d.lengths['coupler'] - h['coupler']):.1e} m)")
    print(f"     solver: rocker swing {math.degrees(p['solver_swing']):.12f} deg, K = "
          f"{p['solver_K']:.12f}; minimum transmission angle "
          f"{math.degrees(d.gamma_min):.4f} deg at {d.gamma_min_where}")
    b = p["best"]
    print(f"     a minimum transmission angle that small is poor (40 deg is a common floor); without "
          f"the frame condition the best pivot gives {math.degrees(b.gamma_min):.4f} deg with AD = "
          f"{b.lengths['ground']:.6f} m ({b.extra['arc']} arc)")
    s, g = p["slider"], p["guide"]
    print(f"  slider-crank K = 1.4, H = 0.1 m, e = 0.02 m: crank {s.lengths['crank']:.9f} m, rod "
          f"{s.lengths['coupler']:.9f} m; solver stroke {p['solver_stroke']:.12f} m, K = "
          f"{p['solver_K_slider']:.12f}")
    print(f"  guide-bar K = 2, AD = 0.4 m: crank {g.lengths['crank']:.9f} m; solver swing "
          f"{math.degrees(p['solver_swing_guide']):.12f} deg, K = {p['solver_K_guide']:.12f}")
    e9 = example_2_9()
    print("\nPart 2. Example 2-9 (ball on a smooth incline, G = 2 kN, alpha = 30, beta = 15 deg):")
    print(f"  F_N = {e9['F_N'] / 1e3:.6f} kN (closed form {e9['F_N_closed'] / 1e3:.6f}); "
          f"printed {EX_2_9_PRINTED['F_N']} 'N': the unit is kN (erratum)")
    print(f"  F_T = {e9['F_T'] / 1e3:.6f} kN (closed form {e9['F_T_closed'] / 1e3:.6f}); "
          f"printed {EX_2_9_PRINTED['F_T']} 'N': the unit is kN (erratum)")
    print(f"  F_N at {e9['F_N_direction_deg']:.9f} deg from the vertical (beta); its moment about "
          f"the centre {abs(e9['N_moment']):.1e} N m (the forces meet at the centre)")
    print("\nExample 2-10 (crank-slider in equilibrium, F_Q = 0.4 kN, tan alpha = 1/3, OB = 400 mm):")
    for run in (0.3, 0.15):
        e10 = example_2_10(run)
        print(f"  crank pin {run} m below the piston on the rod's line: F_NB = {e10['F_NB']:.6f} N, "
              f"F_Ox = {e10['F_Ox']:.6f} N, F_Oy = {e10['F_Oy']:.6f} N, M = {e10['M']:.6f} N m")
    print(f"  printed: F_NB = F_Ox = 0.133 kN, F_Oy = 0.4 kN, M = F_NB x 400 = 53.2 N m")
    print(f"  exact: F_NB = F_Q tan(alpha) = {e10['F_NB_exact']:.6f} N, M = {e10['M_exact']:.6f} N m; "
          f"the printed M = {e10['M_from_rounded_F_NB']:.1f} N m is 0.133 kN x 0.4 m, computed from "
          "the rounded F_NB (erratum)")


if __name__ == "__main__":
    main()
