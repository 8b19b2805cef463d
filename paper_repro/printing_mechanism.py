"""Reconstruct the semi-automatic printing mechanism of Dang and Zhang (undated), section 4.

Source: Dang Zuqi, Zhang Qixian, "A simplified force analysis of complex planar
multi-bar linkages" (year and journal not shown in the text; OCR text in
shared/seeds/000_*.txt; [1] of the README's Sources).  Fig. 6 is missing;
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
* "F_S4x = 451" is not the slider's inertia force (that is m5 a5 = 85.8 N):
  the force balance (12) along x closes with -R53x + F5x + F'5 cos 20deg with
  F'5 = 451 N exactly when F5x is the slider's computed inertia force.  So 451 N
  is the force F'5 acting on the slider at 20 deg to the guide (printing
  resistance); its sign of y and point of application are not determined by
  anything printed.
"""

from __future__ import annotations

import math

import numpy as np

G_ACC = 9.81
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


def masses(printed=PRINTED):
    """Masses G/g of links 1-5 (kg)."""
    return {name: printed["weights"][k] / G_ACC for k, name in enumerate(LINK_NAMES, start=1)}


MASSES = masses()


J_ASSUMED = {"crank": 0.6, "slider": 3.104644}  # not printed; neither matters (see linkage_sym/examples/README.md)
INERTIA_KEYS = {"coupler": "M_E1", "lever": "M_E2", "rocker": "M_E3"}  # shifted labels, see module doc


def scene_dict(printed=PRINTED, start_deg=None, stop_deg=None, steps=361):
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
    ``steps`` steps at pi rad/s.  With PRINTED this is the shipped
    linkage_sym/examples/printing_mechanism.json, up to the rounding of the
    numbers in that file.  Plain dicts and floats: no linkage_sym import.
    """
    dims = dims_from(printed)
    t1, q = assembly(printed)
    pts = points(q, t1, dims)
    qd, qdd = rates(q, t1, OMEGA1, dims)
    cen = centres(pts, printed)
    mass = masses(printed)
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
        "effects": {"inertia": True, "gravity": [0.0, -G_ACC], "loads": True},
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


if __name__ == "__main__":
    print(report())
