"""Reconstruct the semi-automatic printing mechanism of Dang and Zhang (undated), section 4.

Source: Dang Zuqi, Zhang Qixian, "A simplified force analysis of complex planar
multi-bar linkages" (year and journal not shown in the text; only its OCR text
was available to us; [1] of the README's Sources).  Fig. 6 is missing;
the text gives lengths, four link angles, joint and centre-of-mass coordinates,
weights, inertia forces and the final reactions.  This script works out which
joints connect which links and where the fixed pivots and the guide are, checks
every printed number it can against the reconstruction, and prints the
assembly configuration used by ``linkage_sym/examples/printing_mechanism.json``.

Run:  python3 paper_repro/printing_mechanism.py      (plain python3 + numpy)

``scene_dict(printed)`` builds the scene (the example's JSON as a dict) from
a dict of printed inputs shaped like PRINTED; ``paper_repro/printing_forces.py``
uses it to perturb the printed inputs within their rounding.

Reconstruction (each step is checked below):

* A = (0, 0) is the crank pivot: B = A + l_AB (cos 300 deg, sin 300 deg) = (0.1, -0.1732).
* Link 2 is the coupler BC: C = B + l_BC (cos 176.98 deg, sin 176.98 deg).
* Link 3 is a ternary lever with its three joints D, C, F on one straight line:
  theta3 = 85.59 deg is the direction of D->C and of D->F, |DC| = l_CD = 0.294,
  |DF| = l_DF = 0.62.
* Link 4 is the binary rocker ED, pivoted on the ground at E = (x_E, y_E):
  theta4 = 218.07 deg is the direction of E->D and |ED| = 0.37.  The printed
  "l_AE = 0.37" can only be l_ED (|AE| = 0.628): an OCR/typesetting slip.
* Link 5 is the slider (the bed): pinned to the lever at F and translating on a
  horizontal guide (the paper's force balance (12) is along x).  The guide line
  is y = l_AH = 0.248 (H = foot of the perpendicular from A), and F' is the
  slider's point on the guide right above F: l_FF' = 0.045, so y_F = 0.248 -
  0.045 = 0.203, exactly the printed y_F.
* Group 2-3-4-5 is then the class-III group (ternary lever 3 joined to the
  binary links 2, 4, 5, whose outer joints are B on the crank, E on the ground
  and the slider's guide on the ground).
* Centres of mass: the printed labels are shifted by one link.  "S1" =
  (-0.3843, -0.1476) is the midpoint of BC, i.e. S2; "S2 = C" is S3; "S3" =
  (0.7204, -0.2813) with its sign of x restored, (-0.7204, -0.2813), lies on ED
  (0.1529 m from E), i.e. S4; "S4" = (-0.7836, 0.288) is the slider's S5.  The
  printed inertia forces and moments carry the same shift: the crank turns
  uniformly with its centre of mass on its axis (no inertia force, no inertia
  moment), and "F_S1, M_E1" are link 2's, "F_S2, M_E2" link 3's, "F_S3, M_E3"
  link 4's -- their magnitudes are reproduced below from the kinematics.
* g = 9.8, as the paper uses: every printed weight is a round mass times 9.8 (294 N = 30 kg,
  139.65 N = 14.25 kg, 167.58 N = 17.1 kg, 110.25 N = 11.25 kg, 1719.9 N = 175.5 kg).  With it
  the lever's inertia force, the rocker's y component and the printing force come out to their
  last printed digit (``items()``); with 9.81 they do not.
* "F_S4x = 451" is not the slider's inertia force (that is m5 a5 = 85.9 N):
  the force balance (12) along x closes with -R53x + F5x + F'5 cos 20deg with
  F'5 = 451 N (450.995) exactly when F5x is the slider's computed inertia force.  So 451 N
  is the force F'5 acting on the slider at 20 deg to the guide (printing
  resistance); its sign of y and point of application are not determined by
  anything printed.
"""

from __future__ import annotations

import math

import numpy as np

G_ACC = 9.8  # the paper's: every printed weight is a round mass times 9.8 (294 N = 30 kg)
OMEGA1 = 30 * 2 * math.pi / 60  # 30 rpm = pi rad/s

PRINTED = {
    "lengths": {"AB": 0.2, "BC": 0.97, "DF": 0.62, "CD": 0.294, "ED (printed l_AE)": 0.37, "FF'": 0.045,
                "AH": 0.248, "L": 0.45},
    "E": (-0.6, -0.187),
    "theta_deg": {1: 300.0, 2: 176.98, 3: 85.59, 4: 218.07},
    "points": {"B": (0.1, -0.1732), "C": (-0.8687, -0.122), "D": (-0.8913, -0.4152), "F": (-0.8436, 0.203)},
    # as printed (labels as printed, S3's x as printed)
    "S_printed": {"S1": (-0.3843, -0.1476), "S2": "C", "S3": (0.7204, -0.2813), "S4": (-0.7836, 0.288)},
    "weights": {1: 294.0, 2: 139.65, 3: 167.58, 4: 110.25, 5: 1719.9},
    # printed inertia forces (magnitudes of components; directions were in the figure)
    "inertia_printed": {"F_S1": (13.67, 22.98), "M_E1": 0.2432, "F_S2": (15.84, 25.91), "M_E2": 3.679,
                        "F_S3": (10.25, 13.40), "M_E3": 1.617, "F_S4x": 451.0},
    "results": {"R34n": 47.219, "R34nx": -29.1176, "R34ny": 37.1728, "eq13": (0.3762, 0.9436, 312.3463),
                "eq14": (0.325, -0.025, 13.0601), "R53n'": 63.69, "R53t'": 305.60, "Fx_bar": -573.40,
                "R43t_unit": (-0.7872, -0.6166), "R53n''": -0.6139, "R53t''": 0.6906, "K": 0.6139,
                "R34t": 934.03, "R53n": -509.71, "R53t": 950.64},
    # the angle of the force F'5 to the guide, printed in eq. (12) as "F'5x cos 20deg"
    "F5_angle_deg": 20.0,
}



def dims_from(printed):
    """The dimensions the reconstruction uses, read from a dict shaped like PRINTED.

    Keys: the lengths AB, BC, CD, DF, ED, FF', AH, the pivot E and the guide
    heights y_guide = AH (line of F') and y_F = AH - FF' (path of the pin F).
    """
    ln = printed["lengths"]
    d = {"AB": ln["AB"], "BC": ln["BC"], "CD": ln["CD"], "DF": ln["DF"], "ED": ln["ED (printed l_AE)"],
         "FF": ln["FF'"], "AH": ln["AH"], "E": np.array(printed["E"], dtype=float)}
    d["y_guide"] = d["AH"]
    d["y_F"] = d["AH"] - d["FF"]
    return d


DIMS = dims_from(PRINTED)
L_AB, L_BC, L_CD, L_DF, L_ED, L_FF, L_AH = (DIMS[k] for k in ("AB", "BC", "CD", "DF", "ED", "FF", "AH"))
A = np.array([0.0, 0.0])
E = DIMS["E"]
Y_GUIDE = DIMS["y_guide"]  # guide line of the slider's point F'
Y_F = DIMS["y_F"]  # path of the pin F


def u(angle):
    return np.array([math.cos(angle), math.sin(angle)])


def cross(a, b):
    return float(a[0] * b[1] - a[1] * b[0])


# --------------------------------------------------------------------------- positions


def closure(q, t1, dims=DIMS):
    """Closure of the reconstructed mechanism; q = (theta2, theta3, theta4, x_F)."""
    t2, t3, t4, xf = q
    b = A + dims["AB"] * u(t1)
    c = b + dims["BC"] * u(t2)
    d = dims["E"] + dims["ED"] * u(t4)
    return np.array([*(d + dims["CD"] * u(t3) - c), *(d + dims["DF"] * u(t3) - np.array([xf, dims["y_F"]]))])


def du(angle):
    return np.array([-math.sin(angle), math.cos(angle)])


def jac(q, t1, dims=DIMS):
    """d closure / d q (analytic)."""
    t2, t3, t4, xf = q
    J = np.zeros((4, 4))
    J[0:2, 0] = -dims["BC"] * du(t2)
    J[0:2, 1] = dims["CD"] * du(t3)
    J[2:4, 1] = dims["DF"] * du(t3)
    J[0:2, 2] = dims["ED"] * du(t4)
    J[2:4, 2] = dims["ED"] * du(t4)
    J[2:4, 3] = [-1.0, 0.0]
    return J


def solve(q, t1, dims=DIMS):
    for _ in range(50):
        r = closure(q, t1, dims)
        if np.max(np.abs(r)) < 1e-15:
            break
        q = q - np.linalg.solve(jac(q, t1, dims), r)
    return q


def points(q, t1, dims=DIMS):
    t2, t3, t4, xf = q
    b = A + dims["AB"] * u(t1)
    c = b + dims["BC"] * u(t2)
    d = dims["E"] + dims["ED"] * u(t4)
    f = d + dims["DF"] * u(t3)
    return {"A": A, "B": b, "C": c, "D": d, "E": dims["E"], "F": f, "F'": np.array([f[0], dims["y_guide"]])}


def rates(q, t1, w1=OMEGA1, dims=DIMS):
    """q' and q'' for a crank turning at the constant speed w1 (analytic).

    closure = E + l_ED u(t4) + l_CD u(t3) - l_AB u(t1) - l_BC u(t2)   (rows 0-1)
              E + l_ED u(t4) + l_DF u(t3) - (x_F, y_F)                 (rows 2-3)
    Velocity: J q' = l_AB u'(t1) w1 (rows 0-1).  Acceleration: every term
    s L u(t) contributes s L (u'(t) t'' - u(t) t'^2), so J q'' = sum s L u(t) t'^2.
    """
    t2, t3, t4, xf = q
    L = dims
    J = jac(q, t1, dims)
    rhs_v = np.concatenate([L["AB"] * du(t1) * w1, [0.0, 0.0]])
    qd = np.linalg.solve(J, rhs_v)
    w2, w3, w4, _ = qd
    rhs_a = np.concatenate([
        L["ED"] * u(t4) * w4**2 + L["CD"] * u(t3) * w3**2 - L["AB"] * u(t1) * w1**2 - L["BC"] * u(t2) * w2**2,
        L["ED"] * u(t4) * w4**2 + L["DF"] * u(t3) * w3**2,
    ])
    qdd = np.linalg.solve(J, rhs_a)
    return qd, qdd


def point_acc(a_ref, ref, p, omega, alpha):
    """Acceleration of point p of a link: a_ref + alpha k x (p - ref) - omega^2 (p - ref)."""
    r = p - ref
    return a_ref + alpha * np.array([-r[1], r[0]]) - omega**2 * r


def assembly(printed=PRINTED):
    """The printed position theta1 = 300 deg, solved exactly from the printed lengths."""
    th = printed["theta_deg"]
    t1 = math.radians(th[1])
    q0 = np.array([math.radians(th[2]), math.radians(th[3]), math.radians(th[4]), printed["points"]["F"][0]])
    return t1, solve(q0, t1, dims_from(printed))


# --------------------------------------------------------------------------- centres, masses

S4_T = None  # fraction of ED at which S4 lies, from the (sign-corrected) printed S3


def centres(pts, printed=PRINTED):
    """Centres of mass in the printed position (labels shifted back, see module doc)."""
    sp = printed["S_printed"]
    s4 = np.array([-sp["S3"][0], sp["S3"][1]])
    return {
        "crank": A.copy(),  # uniform rotation, no inertia force printed: centre on the axis
        "coupler": np.array(sp["S1"]),
        "lever": pts["C"].copy(),
        "rocker": s4,
        "slider": np.array(sp["S4"]),
    }


LINK_NAMES = ["crank", "coupler", "lever", "rocker", "slider"]


def masses(printed=PRINTED, g=G_ACC):
    """Masses G/g of links 1-5 (kg): 30, 14.25, 17.1, 11.25 and 175.5 kg with the paper's g = 9.8."""
    return {name: printed["weights"][k] / g for k, name in enumerate(LINK_NAMES, start=1)}


MASSES = masses()


J_ASSUMED = {"crank": 0.6, "slider": 3.104644}  # not printed; neither matters (see linkage_sym/examples/README.md)
INERTIA_KEYS = {"coupler": "M_E1", "lever": "M_E2", "rocker": "M_E3"}  # shifted labels, see module doc


def scene_dict(printed=PRINTED, start_deg=None, stop_deg=None, steps=361, g=G_ACC):
    """The scene (a dict in the scene format) that the reconstruction gives for ``printed``.

    ``printed`` is shaped like PRINTED; what is read from it: the lengths, E,
    theta1 (the position; theta2-4 and x_F only seed Newton), the centres of
    mass S1, S3, S4 (shifted labels, S3's sign of x restored), the weights, the
    inertia moments M_E1-3 (J = M / |alpha| with alpha from the kinematics at
    30 rpm), the magnitude "F_S4x" of the printing force F'5 and its angle
    F5_angle_deg to the guide.  F'5 points backwards and down (direction
    180 deg + angle) and acts at S5; neither the sign of its y component nor
    its point matters for the reactions at D and F (the guide takes them).

    The driver sweeps start_deg..stop_deg (default theta1..theta1 + 360) in
    ``steps`` steps at pi rad/s; masses G/g and gravity g (default the paper's 9.8).  With
    PRINTED this is the shipped
    linkage_sym/examples/printing_mechanism.json, up to the rounding of the
    numbers in that file.  Plain dicts and floats: no linkage_sym import.
    """
    dims = dims_from(printed)
    t1, q = assembly(printed)
    pts = points(q, t1, dims)
    qd, qdd = rates(q, t1, OMEGA1, dims)
    cen = centres(pts, printed)
    mass = masses(printed, g)
    alpha = {"coupler": qdd[0], "lever": qdd[1], "rocker": qdd[2]}
    inertia = dict(J_ASSUMED)
    for link, key in INERTIA_KEYS.items():
        inertia[link] = printed["inertia_printed"][key] / abs(alpha[link])
    xy = lambda v: [float(v[0]), float(v[1])]
    f5 = printed["inertia_printed"]["F_S4x"]
    phi = math.radians(180.0 + printed["F5_angle_deg"])
    th1 = printed["theta_deg"][1]
    joints = [("A", "R", "ground", "crank", "A"), ("B", "R", "crank", "coupler", "B"),
              ("C", "R", "coupler", "lever", "C"), ("D", "R", "lever", "rocker", "D"),
              ("E", "R", "rocker", "ground", "E"), ("F", "R", "lever", "slider", "F")]
    return {
        "name": "printing-mechanism",
        "links": [{"name": n, "mass": float(mass[n]), "com": xy(cen[n]), "inertia": float(inertia[n])}
                  for n in LINK_NAMES],
        "joints": [{"name": n, "type": t, "links": [a, b], "at": xy(pts[p])} for n, t, a, b, p in joints]
        + [{"name": "F_guide", "type": "P", "links": ["ground", "slider"], "at": xy(pts["F'"]), "axis_deg": 0.0}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": th1 if start_deg is None else start_deg,
                     "stop_deg": th1 + 360.0 if stop_deg is None else stop_deg, "steps": steps,
                     "speed": OMEGA1, "acceleration": 0.0}],
        "loads": [{"link": "slider", "force": [f5 * math.cos(phi), f5 * math.sin(phi)], "at": xy(cen["slider"])}],
        "effects": {"inertia": True, "gravity": [0.0, -g], "loads": True},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }


def report():
    out = []
    pr = PRINTED
    P = {k: np.array(v) for k, v in pr["points"].items()}
    fmt = lambda v: "(" + ", ".join(f"{float(c):g}" for c in v) + ")"
    out.append("== 1. printed lengths against printed coordinates (residual = from coordinates - printed)")
    checks = [
        ("l_AB", np.linalg.norm(P["B"] - A), 0.2),
        ("l_BC", np.linalg.norm(P["C"] - P["B"]), 0.97),
        ("l_CD", np.linalg.norm(P["C"] - P["D"]), 0.294),
        ("l_DF", np.linalg.norm(P["F"] - P["D"]), 0.62),
        ("l_ED (printed as l_AE)", np.linalg.norm(P["D"] - E), 0.37),
        ("|AE| (for comparison)", np.linalg.norm(E - A), 0.37),
        ("l_FF' = y_H - y_F", L_AH - P["F"][1], 0.045),
    ]
    for name, got, want in checks:
        out.append(f"  {name:26s} {got:9.5f}  printed {want:7.4f}  residual {got - want:+.5f}")
    ang = lambda p, q: math.degrees(math.atan2(q[1] - p[1], q[0] - p[0])) % 360
    for name, got, want in [("theta1 = dir A->B", ang(A, P["B"]), 300.0), ("theta2 = dir B->C", ang(P["B"], P["C"]), 176.98),
                            ("theta3 = dir D->C", ang(P["D"], P["C"]), 85.59), ("theta3'= dir D->F", ang(P["D"], P["F"]), 85.59),
                            ("theta4 = dir E->D", ang(E, P["D"]), 218.07)]:
        out.append(f"  {name:26s} {got:9.3f}  printed {want:7.2f}  residual {got - want:+.3f} deg")
    out.append(f"  D, C, F collinear: distance of C from line DF = "
               f"{abs(cross(P['F'] - P['D'], P['C'] - P['D'])) / np.linalg.norm(P['F'] - P['D']):.2e} m")

    out.append("== 2. centres of mass (printed labels are shifted by one link)")
    mid_bc = (P["B"] + P["C"]) / 2
    out.append(f"  midpoint of BC = ({mid_bc[0]:.5f}, {mid_bc[1]:.5f})  printed 'S1' = {pr['S_printed']['S1']}")
    s3 = np.array(pr["S_printed"]["S3"])
    s3f = np.array([-s3[0], s3[1]])
    t = (s3f - E) @ (P["D"] - E) / np.linalg.norm(P["D"] - E) ** 2
    off = abs(cross(P["D"] - E, s3f - E)) / np.linalg.norm(P["D"] - E)
    out.append(f"  printed 'S3' = {fmt(s3)}: off link 3 by {abs(s3[0] - P['C'][0]):.2f} m in x; with x -> -x it lies on ED "
               f"at t = {t:.4f} of E->D ({t * L_ED:.4f} m from E), {off:.1e} m off the line: S4")
    s5 = np.array(pr["S_printed"]["S4"])
    out.append(f"  printed 'S4' = {fmt(s5)}: {np.linalg.norm(s5 - P['F']):.4f} m from F, "
               f"{np.linalg.norm(s5 - np.array([P['F'][0], Y_GUIDE])):.4f} m from F' -> the slider's S5")

    t1, q = assembly()
    pts = points(q, t1)
    out.append("== 3. exact assembly from the printed lengths at theta1 = 300 deg (vs printed coordinates)")
    for k in ("B", "C", "D", "F"):
        dv = pts[k] - P[k]
        out.append(f"  {k}: ({pts[k][0]:+.6f}, {pts[k][1]:+.6f})  printed {fmt(P[k])}  diff ({dv[0]:+.6f}, {dv[1]:+.6f})")
    out.append(f"  angles: theta2 {math.degrees(q[0]):.4f}, theta3 {math.degrees(q[1]):.4f}, "
               f"theta4 {math.degrees(q[2]) % 360:.4f} deg")

    out.append("== 4. kinematics at 30 rpm and the printed inertia forces")
    qd, qdd = rates(q, t1)
    out.append(f"  omega2,3,4 = {qd[0]:+.5f}, {qd[1]:+.5f}, {qd[2]:+.5f} rad/s;  alpha2,3,4 = "
               f"{qdd[0]:+.5f}, {qdd[1]:+.5f}, {qdd[2]:+.5f} rad/s^2;  slider: v = {qd[3]:+.5f} m/s, a = {qdd[3]:+.5f} m/s^2")
    cen = centres(pts)

    a_b = -L_AB * u(t1) * OMEGA1**2
    a_d = point_acc(np.zeros(2), E, pts["D"], qd[2], qdd[2])
    a_s2 = point_acc(a_b, pts["B"], cen["coupler"], qd[0], qdd[0])
    a_s3 = point_acc(a_d, pts["D"], cen["lever"], qd[1], qdd[1])
    a_s4 = point_acc(np.zeros(2), E, cen["rocker"], qd[2], qdd[2])
    # check the analytic rates against finite differences of the positions
    h = 1e-5
    qp, qm = solve(q + qd / OMEGA1 * h, t1 + h), solve(q - qd / OMEGA1 * h, t1 - h)
    assert np.allclose((qp - qm) / (2 * h) * OMEGA1, qd, atol=1e-7)
    assert np.allclose((qp - 2 * q + qm) / h**2 * OMEGA1**2, qdd, atol=1e-3)
    pi_ = pr["inertia_printed"]
    inertia = {}
    for link, a_s, alpha, fkey, mkey in (("coupler", a_s2, qdd[0], "F_S1", "M_E1"), ("lever", a_s3, qdd[1], "F_S2", "M_E2"),
                                         ("rocker", a_s4, qdd[2], "F_S3", "M_E3")):
        f = -MASSES[link] * a_s
        j = pi_[mkey] / abs(alpha)
        inertia[link] = (f, -j * alpha, j)
        out.append(f"  {link:8s} m = {MASSES[link]:7.3f} kg  -m a = ({f[0]:+8.3f}, {f[1]:+8.3f}) N   printed '{fkey}' = "
                   f"{pi_[fkey]};  printed '{mkey}' = {pi_[mkey]} -> J = M/|alpha| = {j:.4f} kg m^2")
    f5 = -MASSES["slider"] * qdd[3]
    out.append(f"  slider   m = {MASSES['slider']:7.3f} kg  -m a = {f5:+.3f} N (x)   printed 'F_S4x' = 451: does NOT match")

    out.append("== 5. force analysis (one linear system of links 2-5; gravity and inertia as above)")
    g = {k: np.array([0.0, -MASSES[k] * G_ACC]) for k in MASSES}
    F2 = inertia["coupler"][0] + g["coupler"]
    M2 = inertia["coupler"][1]
    F3 = inertia["lever"][0] + g["lever"]
    M3 = inertia["lever"][1]
    F4 = inertia["rocker"][0] + g["rocker"]
    M4 = inertia["rocker"][1]
    B_, C_, D_, F_ = pts["B"], pts["C"], pts["D"], pts["F"]
    S2, S3, S4 = cen["coupler"], cen["lever"], cen["rocker"]
    # the x-balance of the slider, -R53x + F5x + F'5x = 0, gives R53x once F'5x is known;
    # first find R53x from the paper's own value, then what F'5 that means
    # unknowns: R12(0,1) R32(2,3) R43(4,5) R53(6,7) R04(8,9)  (Rij = force of i on j)
    M = np.zeros((9, 10))
    rhs = np.zeros(9)
    # link 2
    M[0, [0, 2]] = 1
    rhs[0] = -F2[0]
    M[1, [1, 3]] = 1
    rhs[1] = -F2[1]
    M[2, 2], M[2, 3] = -(C_ - B_)[1], (C_ - B_)[0]
    rhs[2] = -(cross(S2 - B_, F2) + M2)
    # link 3 (moments about C)
    M[3, [2, 4, 6]] = [-1, 1, 1]
    rhs[3] = -F3[0]
    M[4, [3, 5, 7]] = [-1, 1, 1]
    rhs[4] = -F3[1]
    M[5, 4], M[5, 5], M[5, 6], M[5, 7] = -(D_ - C_)[1], (D_ - C_)[0], -(F_ - C_)[1], (F_ - C_)[0]
    rhs[5] = -(cross(S3 - C_, F3) + M3)
    # link 4 (moments about E)
    M[6, [4, 8]] = [-1, 1]
    rhs[6] = -F4[0]
    M[7, [5, 9]] = [-1, 1]
    rhs[7] = -F4[1]
    M[8, 4], M[8, 5] = (D_ - E)[1], -(D_ - E)[0]
    rhs[8] = -(cross(S4 - E, F4) + M4)
    # close with the slider's x balance: R53x = F5x + F'5x
    res = pr["results"]
    Fp5x = res["R53n"] - f5
    Mfull = np.vstack([M, np.eye(10)[6]])
    sol = np.linalg.solve(Mfull, np.append(rhs, f5 + Fp5x))
    R34 = -sol[4:6]
    R53 = sol[6:8]
    # the paper's directions: t along the rocker from D to E, n normal to it
    # (fixed by its printed components of R34n and of R43t for R34t = 1)
    e_t = (E - D_) / L_ED
    e_n = np.array([-e_t[1], e_t[0]])
    out.append(f"  F5x (slider inertia, computed) = {f5:+.2f} N;  paper: -R53n' + F5x + F'5x cos20 = Fx_bar with "
               f"R53n = -509.71  =>  F'5 cos20 = {Fp5x:+.2f} N  =>  |F'5| = {abs(Fp5x) / math.cos(math.radians(20)):.2f} N "
               f"(printed 451)")
    out.append(f"  R34 normal to ED = {R34 @ e_n:+.3f}  (printed R34n = 47.219 with components ({R34 @ e_n * e_n[0]:+.4f}, "
               f"{R34 @ e_n * e_n[1]:+.4f}), printed (-29.1176, 37.1728))")
    out.append(f"  R34 along DE     = {R34 @ e_t:+.3f}  (printed R34t = 934.03)")
    out.append(f"  R53 = ({R53[0]:+.2f}, {R53[1]:+.2f})  (printed R53n = -509.71 [imposed], R53t = 950.64)")
    r43n = -(R34 @ e_n) * e_n
    out.append(f"  R43t for R34t = 1: ({-e_t[0]:+.4f}, {-e_t[1]:+.4f})  (printed (-0.7872, -0.6166))")
    known13 = cross(S2 - B_, F2) + M2 + cross(S3 - B_, F3) + M3 + cross(D_ - B_, r43n)
    known14 = cross(D_ - C_, r43n) + M3
    out.append(f"  eq.(13): coefficients ({-(F_ - B_)[1]:.4f}, {(F_ - B_)[0]:.4f}) [printed 0.3762, 0.9436 up to sign], "
               f"known moment {known13:.4f} (printed 312.3463)")
    out.append(f"  eq.(14): coefficients ({-(F_ - C_)[1]:.4f}, {(F_ - C_)[0]:.4f}) [printed 0.325, -0.025 up to sign], "
               f"known moment {known14:.4f} (printed 13.0601)")

    a13, b13, c13 = res["eq13"]
    a14, b14, c14 = res["eq14"]
    rn1, rt1 = np.linalg.solve([[a13, b13], [a14, b14]], [c13, c14])
    out.append(f"  printed eqs (13),(14) solved: (R53n)' = {rn1:.2f}, (R53t)' = {rt1:.2f}  (printed 63.69, 305.60)")
    rn_p = res["R53n'"]
    out.append(f"  printed chain: -(R53n)' + [F5x + F'5x cos20] = {-rn_p:.2f} + ({res['R53n']:.2f}) = "
               f"{-rn_p + res['R53n']:.2f} (printed Fx_bar = -573.40); R34t = -Fx_bar/K = "
               f"{573.40 / 0.6139:.2f} (printed 934.03); R53t = 305.60 + 0.6906 * 934.03 = {305.60 + 0.6906 * 934.03:.2f} "
               f"(printed 950.64)")

    out.append("== 6. does the crank turn fully?  (continuation in 1 deg steps from the printed position)")
    qq = q.copy()
    worst = np.inf
    for k in range(1, 361):
        qq = solve(qq, t1 + math.radians(k))
        worst = min(worst, abs(np.linalg.det(jac(qq, t1 + math.radians(k)))))
        assert np.max(np.abs(closure(qq, t1 + math.radians(k)))) < 1e-12
    end = points(qq, t1 + 2 * math.pi)
    back = max(np.linalg.norm(end[k] - pts[k]) for k in pts)
    out.append(f"  yes: assembled at every degree, smallest |det J| = {worst:.3e}, back to the start within {back:.1e} m")

    out.append("== 7. the scene's assembly configuration (m)")
    for k, v in pts.items():
        out.append(f"  {k:3s} ({v[0]:+.9f}, {v[1]:+.9f})")
    for k, v in cen.items():
        out.append(f"  com {k:8s} ({v[0]:+.6f}, {v[1]:+.6f})  mass {MASSES[k]:.4f} kg")
    return "\n".join(out)


# --------------------------------------------------------------------------- rounding of the inputs
LENGTH_HALF = 0.00005  # lengths and E to 0.1 mm, as the printed coordinates (see printing_forces.py)

# (path into PRINTED, half a unit of the last printed digit); the first 9 are the lengths and E
ROUNDING = [(("lengths", k), LENGTH_HALF) for k in ("AB", "BC", "CD", "DF", "ED (printed l_AE)", "FF'", "AH")]
ROUNDING += [(("E", 0), LENGTH_HALF), (("E", 1), LENGTH_HALF)]
N_LENGTHS = 9
ROUNDING += [(("S_printed", s, i), 0.00005) for s in ("S1", "S3") for i in (0, 1)]
ROUNDING += [(("S_printed", "S4", 0), 0.00005), (("S_printed", "S4", 1), 0.0005)]
ROUNDING += [(("weights", 1), 0.5), (("weights", 2), 0.005), (("weights", 3), 0.005), (("weights", 4), 0.005),
             (("weights", 5), 0.05)]
ROUNDING += [(("inertia_printed", "M_E1"), 0.00005), (("inertia_printed", "M_E2"), 0.0005),
             (("inertia_printed", "M_E3"), 0.0005), (("inertia_printed", "F_S4x"), 0.5)]


def _get(d, path):
    for k in path:
        d = d[k]
    return d


def _set(d, path, value):
    *head, last = path
    parent = _get(d, head)
    if isinstance(parent, tuple):
        items_ = list(parent)
        items_[last] = value
        _set(d, head, tuple(items_))
    else:
        parent[last] = value


def perturbed(deltas, printed=PRINTED):
    """A copy of ``printed`` with ``deltas[i]`` added to the input ``ROUNDING[i]``."""
    import copy

    out = copy.deepcopy(printed)
    for (path, _), dv in zip(ROUNDING, deltas):
        _set(out, path, _get(out, path) + dv)
    return out


def half_units(length_half=LENGTH_HALF):
    half = np.array([h for _, h in ROUNDING])
    half[:N_LENGTHS] = length_half
    return half


# --------------------------------------------------------------------------- items
def kinematic_values(printed=PRINTED, g=G_ACC) -> dict:
    """What the reconstruction computes for the printed position (no force analysis).

    Coordinates of B, C, D, F and the angles theta2-4 of the exact assembly; the midpoint of BC
    (the printed "S1"); the inertia forces -m a of links 2, 3, 4 at their centres of mass, with
    m = G/g (the printed magnitudes carry the labels F_S1-F_S3); the slider's -m5 a5 along x;
    and the printing force |F'5| that closes the slider's x balance (12) with the printed
    R53n: R53n = F5x + F'5 cos 20 deg.
    """
    dims = dims_from(printed)
    t1, q = assembly(printed)
    pts = points(q, t1, dims)
    qd, qdd = rates(q, t1, OMEGA1, dims)
    cen = centres(pts, printed)
    m = masses(printed, g)
    out = {}
    for k in "BCDF":
        out[f"x_{k}"], out[f"y_{k}"] = (float(v) for v in pts[k])
    for i, name in ((0, "theta2"), (1, "theta3"), (2, "theta4")):
        out[name] = math.degrees(q[i]) % 360.0
    mid = (pts["B"] + pts["C"]) / 2
    out["x_S1"], out["y_S1"] = float(mid[0]), float(mid[1])
    a_b = -dims["AB"] * u(t1) * OMEGA1**2
    a_d = point_acc(np.zeros(2), dims["E"], pts["D"], qd[2], qdd[2])
    acc = {"coupler": point_acc(a_b, pts["B"], cen["coupler"], qd[0], qdd[0]),
           "lever": point_acc(a_d, pts["D"], cen["lever"], qd[1], qdd[1]),
           "rocker": point_acc(np.zeros(2), dims["E"], cen["rocker"], qd[2], qdd[2])}
    for link, key in (("coupler", "F_S1"), ("lever", "F_S2"), ("rocker", "F_S3")):
        f = -m[link] * acc[link]
        out[f"{key}x"], out[f"{key}y"] = abs(float(f[0])), abs(float(f[1]))
    et = (dims["E"] - pts["D"]) / np.linalg.norm(dims["E"] - pts["D"])
    out["R43t_x"], out["R43t_y"] = (float(v) for v in -et)  # unit force of the rocker on the lever, along E->D
    out["F5x"] = float(-m["slider"] * qdd[3])
    out["F'5"] = abs((printed["results"]["R53n"] - out["F5x"]) / math.cos(math.radians(printed["F5_angle_deg"])))
    return out


def kinematic_spread(samples=200, seed=0) -> dict:
    """Largest |deviation| of each kinematic_values entry over a seeded Monte Carlo of the printed
    inputs, each uniform within half a unit of its last printed digit (lengths and E: +-0.05 mm)."""
    rng = np.random.default_rng(seed)
    half = half_units()
    nominal = kinematic_values()
    dev = {k: 0.0 for k in nominal}
    for _ in range(samples):
        got = kinematic_values(perturbed(rng.uniform(-half, half)))
        for k in dev:
            dev[k] = max(dev[k], abs(got[k] - nominal[k]))
    return dev


def _eq_13_14_bound():
    """First-order worst change of the solution of the printed eqs. 13-14 when each printed
    coefficient and constant moves by half a unit of its last digit."""
    res = PRINTED["results"]
    (a, b, c), (d, e, f) = res["eq13"], res["eq14"]
    base = np.linalg.solve([[a, b], [d, e]], [c, f])
    halves = (0.00005, 0.00005, 0.00005, 0.0005, 0.0005, 0.00005)
    total = np.zeros(2)
    for i, h in enumerate(halves):
        v = [a, b, c, d, e, f]
        v[i] += h
        got = np.linalg.solve([[v[0], v[1]], [v[3], v[4]]], [v[2], v[5]])
        total += np.abs(got - base)
    return base, total


def items(samples=200, seed=0):
    """Dang and Zhang's printed geometry, inertia forces, printing force and their own arithmetic
    (paper_repro/items.py), from the reconstruction with the paper's g = 9.8 (no linkage_sym).

    Tolerances: half a unit of the printed last digit ("reproduced"), else the Monte-Carlo spread
    of ``samples`` seeded samples of the printed inputs within their rounding (kinematic_spread;
    lengths and E to 0.1 mm, as the printed coordinates show).  The paper's own arithmetic
    (eqs. 13-14 solved, R34t = -F_x/K, ...) is redone from its printed intermediates; where that
    misses the last digit, the tolerance is the first-order effect of the rounding of the printed
    coefficients it starts from.
    """
    from items import ERRATUM, NOT_REPRODUCIBLE, REPRODUCED, ROUNDING as ROUND, Item
    from items import PRINTED as PRINTED_ITEM

    pr = PRINTED
    val = kinematic_values()
    spread = kinematic_spread(samples, seed)
    mc = (f"spread of {samples} seeded samples of the printed inputs within their rounding "
          f"(lengths and E +-0.05 mm, centres of mass 0.1 mm, weights, M_E1-3 and 451 N to their last digit)")
    out = []

    def graded(where, name, printed, key, unit, why_round=mc, extra=""):
        got = val[key]
        d = abs(got - float(printed))
        from items import half_unit

        if d <= half_unit(printed):
            out.append(Item(PRINTED_ITEM, 1, where, name, printed, got, REPRODUCED, unit=unit, why=extra))
        elif d <= spread[key]:
            out.append(Item(PRINTED_ITEM, 1, where, name, printed, got, ROUND, tol=spread[key], why=why_round, unit=unit))
        else:
            out.append(Item(PRINTED_ITEM, 1, where, name, printed, got, NOT_REPRODUCIBLE, unit=unit,
                            why=f"off by {d:.3g}, {d / max(spread[key], 1e-300):.1f} times the {mc}" + extra))

    pts_text = {"B": ("0.1", "-0.1732"), "C": ("-0.8687", "-0.122"), "D": ("-0.8913", "-0.4152"),
                "F": ("-0.8436", "0.203")}
    for k, (tx, ty) in pts_text.items():
        graded("sec. 4, coordinates", f"x_{k}", tx, f"x_{k}", "m")
        graded("sec. 4, coordinates", f"y_{k}", ty, f"y_{k}", "m")
    for name, text in (("theta2", "176.98"), ("theta3", "85.59"), ("theta4", "218.07")):
        graded("sec. 4, angles", name, text, name, "deg")
    graded("sec. 4, 'S1' = S2", "x of the midpoint of BC", "-0.3843", "x_S1", "m")
    graded("sec. 4, 'S1' = S2", "y of the midpoint of BC", "-0.1476", "y_S1", "m")
    g_note = ("m = G/9.8, the paper's g (294 N is 30 kg, 1719.9 N is 175.5 kg); with g = 9.81 every inertia "
              "force is 0.1 % smaller and F_S2x, F_S2y, F_S3y miss their last digit")
    for key, link in (("F_S1", "coupler"), ("F_S2", "lever"), ("F_S3", "rocker")):
        for i, ax in enumerate("xy"):
            extra = ""
            if key == "F_S2" and ax == "x":
                extra = g_note
            elif key == "F_S1" and ax == "x":
                extra = ("; every other component comes within the rounding (a typo for 13.63 would fit, but "
                         "nothing else printed shows it)")
            graded("sec. 4, inertia forces", f"{key}{ax} (|{ax}| of -m a, {link})",
                   f"{pr['inertia_printed'][key][i]:g}" if key != "F_S3" or ax != "y" else "13.40",
                   f"{key}{ax}", "N", extra=extra)
    f5_981 = abs((pr["results"]["R53n"] - val["F5x"] * G_ACC / 9.81) / math.cos(math.radians(20)))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, 'F_S4x'", "|F'5| from R53n = F5x + F'5 cos 20 deg", "451", val["F'5"], REPRODUCED,
                    unit="N", why=f"F5x = -m5 a5 = {val['F5x']:.3f} N with m5 = 1719.9/9.8 = 175.5 kg; with g = "
                                  f"9.81 it would be {f5_981:.2f} N"))

    # errata of the printed data, each shown by the reconstruction
    P = {k: np.array(v) for k, v in pr["points"].items()}
    ed, ae = float(np.linalg.norm(P["D"] - E)), float(np.linalg.norm(E - A))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, lengths", "l_AE", "0.37", ae, ERRATUM, corrected="l_ED = 0.37",
                    holds=abs(ed - 0.37) < 1e-4 < 0.1 < abs(ae - 0.37), unit="m",
                    why=f"|AE| = {ae:.4f} from the printed E; |ED| = {ed:.5f} from the printed coordinates"))
    s3 = np.array(pr["S_printed"]["S3"])
    s3f = np.array([-s3[0], s3[1]])
    off = abs(cross(P["D"] - E, s3f - E)) / ed
    far = min(np.linalg.norm(s3 - p) for p in (*P.values(), E, A))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, centres of mass", "x_S3", "0.7204", float(s3f[0]), ERRATUM, corrected="-0.7204",
                    holds=off < 1e-4 and far > 0.5, unit="m",
                    why=f"(0.7204, -0.2813) is {far:.2f} m from the nearest joint, off every link; (-0.7204, -0.2813) lies on ED "
                        f"({off:.1e} m off the line): the rocker's centre"))
    mid_ok = abs(val["x_S1"] - (-0.3843)) < 1e-4 and abs(val["y_S1"] - (-0.1476)) < 1e-4
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, labels", "S1-S4, F_S1-F_S3, M_E1-M_E3",
                    "link 1-4", "link 2-5", ERRATUM, corrected="S2-S5, F_S2-F_S4, M_E2-M_E4 (shifted by one link)",
                    holds=mid_ok and off < 1e-4,
                    why="printed S1 is the midpoint of BC (link 2), S2 = C is on the lever 3, S3 on the rocker 4, S4 "
                        "near the slider 5; the crank turns uniformly about its centre and has no inertia load"))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, inertia forces", "F_S4x labelled an inertia force", "451", val["F5x"], ERRATUM,
                    corrected="F'5 = 451 N, the printing force at 20 deg to the guide (eq. 12's F'5x cos 20)",
                    holds=abs(val["F'5"] - 451) <= 0.5 and abs(abs(val["F5x"]) - 451) > 100, unit="N",
                    why="the slider's inertia force is -m5 a5 (computed); 451 N at 20 deg closes eq. 12 with the "
                        "printed R53n"))
    for key in ("M_E1", "M_E2", "M_E3"):
        out.append(Item(PRINTED_ITEM, 1, "sec. 4, inertia moments", key, f"{pr['inertia_printed'][key]:g}", "(input)",
                        NOT_REPRODUCIBLE, unit="N m",
                        why="the paper prints no moments of inertia: J = M/|alpha| is derived from these, so they "
                            "are inputs, not checks"))

    # the paper's own arithmetic, from its printed intermediates
    res = pr["results"]
    base, bound = _eq_13_14_bound()
    why_c = ("the printed coefficients of eqs. 13-14 are rounded (0.025 stands for 0.0251); the tolerance is "
             "the first-order effect of half a unit of each printed coefficient and constant")
    for i, (name, text) in enumerate((("(R53n)'", "63.69"), ("(R53t)'", "305.60"))):
        d = abs(base[i] - float(text))
        st = REPRODUCED if d <= 0.005 else ROUND
        out.append(Item(PRINTED_ITEM, 1, "sec. 4, eqs. 13-14 solved", name, text, float(base[i]), st, unit="N",
                        tol=None if st == REPRODUCED else float(bound[i]), why="" if st == REPRODUCED else why_c))
    fx = -res["R53n'"] + val["F5x"] + (-pr["inertia_printed"]["F_S4x"] * math.cos(math.radians(20)))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, eq. 12", "F_x = -(R53n)' + F5x + F'5x cos 20", "-573.40", fx, REPRODUCED, unit="N",
                    why="printed (R53n)' = 63.69, computed F5x (g = 9.8) and F'5 = 451 N"))
    th4 = math.radians(pr["theta_deg"][4])
    unit_note = (f"the printed pair is not a unit vector to its digits (x^2 + y^2 = {0.7872**2 + 0.6166**2:.5f}); "
                 f"cos, sin of the printed theta4 give ({math.cos(th4):.5f}, {math.sin(th4):.5f}), the printed "
                 f"coordinates D, E ({-(E - P['D'])[0] / ed:.5f}, {-(E - P['D'])[1] / ed:.5f})")
    graded("sec. 4, unit run", "R43t_x for R34t = 1 (-(E - D)/|ED|)", "-0.7872", "R43t_x", "")
    graded("sec. 4, unit run", "R43t_y for R34t = 1 (-(E - D)/|ED|)", "-0.6166", "R43t_y", "", why_round=mc + "; " + unit_note)
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, eq. 12", "R34t = -F_x / K", "934.03", -res["Fx_bar"] / res["K"], REPRODUCED,
                    unit="N", why="printed F_x = -573.40 and K = 0.6139"))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, eq. 7", "R53n = (R53n)' + (R53n)'' R34t", "-509.71",
                    res["R53n'"] + res["R53n''"] * res["R34t"], REPRODUCED, unit="N", why="printed intermediates"))
    out.append(Item(PRINTED_ITEM, 1, "sec. 4, eq. 7", "R53t = (R53t)' + (R53t)'' R34t", "950.64",
                    res["R53t'"] + res["R53t''"] * res["R34t"], REPRODUCED, unit="N", why="printed intermediates"))
    return out


if __name__ == "__main__":
    print(report())
