"""Hard cases of the kinetostatics (joint reactions, driver efforts, frame loads)
against independent 50-digit mpmath references.

The reference (:func:`equilibrium_mp`) writes the three equilibrium equations
(Fx, Fy, moment about the origin) of every moving link with every joint
reaction and driver effort as unknowns and solves them with ``mpmath.lu_solve``
at 50 digits.  It shares no code with linkage_sym.  Its geometry comes from one
of two places, and each answers a different question:

* **exact mechanism** -- positions solved in mpmath from the mechanism's
  dimensions (read in 50 digits off the scene's double assembly points) at the
  driver value the solver was given (a double, hence exact).  This is the end-to-end
  error.  Near a dead centre it is dominated by the *position* error, which is
  inherent: a backward-stable position solver moves the joints by
  ``~eps*kappa`` (see test_kinematics_hard_cases), and the reactions, which are
  proportional to ``kappa``, are sensitive to the geometry with another factor
  ``kappa``.  Bound: ``C_EXACT * eps * kappa**2``.
* **the solver's own geometry** -- the joint points and centres of mass the
  solver reports (``a.joints[*].position``, ``a.links[*].com``), read exactly as
  mpf.  These are precisely the numbers the force routines use (a joint's point
  on ``links[1]``, the wrench reference at the centre of mass; the test scenes
  apply their forces at centres of mass), so this isolates the force solve, whose
  matrix is the transpose of the constraint Jacobian: a backward-stable solve
  gives ``C_SOLVE * eps * kappa``.

``kappa`` is ``a.condition`` from ``compile_plan(scene).run(exact_condition=True)``:
the dimensionless condition number of the full constraint Jacobian
(linkage_sym/numeric/plan.py, lengths divided by the largest joint distance).
Each near-dead-centre test checks that this kappa is honest -- ``kappa * sin(psi)``
(psi: the mpmath angle between the two links that line up) stays between 1 and
100 -- so that the bounds are not loosened by an inflated kappa.

Errors are normwise: ``max |got - ref| / max |ref|`` over every reaction
component, ``reaction_moment / L``, driver effort (torques ``/ L``) and the frame
force and ``moment / L`` (``L`` = characteristic length).

``C_SOLVE = 0.5`` and ``C_EXACT = 0.05``: the observed worst ratios are 0.04 and
0.008 (kappa * sin(psi) is about 17-20 in these mechanisms, which the constants
absorb); the margin is for other platforms' libm, not for a less stable method.

Extreme link ratios (3): ``C_RATIO * eps * kappa`` normwise (observed <= 0.26
of it); the driving torque of a crank ``L/l1`` times shorter than the mechanism
relative to its own size gets ``L/l1`` more: the solver takes a joint's point on
its ``links[1]`` (the coupler), which carries an absolute error ``eps * L``, as the
crank's lever arm.  Class-III group (4): the superposition's cancellation factor
``amp`` multiplies the force-solve error (``_superposition_tol``).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.numeric.forces.superposition import AMPLIFICATION_LIMIT

from tests.support import scenes  # noqa: E402

EPS = float(np.finfo(float).eps)
C_SOLVE = 0.5
C_EXACT = 0.05
METHODS = ("dyad", "global")


@pytest.fixture(autouse=True)
def _digits():
    with mp.workdps(50):
        yield


# ---------------------------------------------------------------------------
# mpmath reference: geometry helpers and the global equilibrium
# ---------------------------------------------------------------------------


def mpt(p):
    return (mp.mpf(p[0]), mp.mpf(p[1]))


def dist(p, q):
    return mp.hypot(q[0] - p[0], q[1] - p[1])


def cross3(a, b, c):
    """cross(b - a, c - a)."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def circle_meet(p1, r1, p2, r2, sigma):
    """The point X with |X - p1| = r1, |X - p2| = r2 and sign cross(p2 - p1, X - p1) = sigma."""
    dx, dy = p2[0] - p1[0], p2[1] - p1[1]
    d = mp.hypot(dx, dy)
    a = (r1 ** 2 - r2 ** 2 + d ** 2) / (2 * d)
    h2 = r1 ** 2 - a ** 2
    assert h2 > 0, "reference: the dyad cannot be assembled at this driver value"
    h = mp.sqrt(h2)
    ux, uy = dx / d, dy / d
    return (p1[0] + a * ux - sigma * h * uy, p1[1] + a * uy + sigma * h * ux)


def carried(a0, b0, a1, b1, p0):
    """Point ``p0`` of the assembly configuration moved rigidly with a0 -> a1, b0 -> b1."""
    ang = mp.atan2(b1[1] - a1[1], b1[0] - a1[0]) - mp.atan2(b0[1] - a0[1], b0[0] - a0[0])
    c, s = mp.cos(ang), mp.sin(ang)
    x, y = p0[0] - a0[0], p0[1] - a0[1]
    return (a1[0] + c * x - s * y, a1[1] + s * x + c * y)


def sin_between(p, q, r):
    """|sin| of the angle between q - p and r - q (0 when p, q, r are in line)."""
    return abs(cross3(p, q, r)) / (dist(p, q) * dist(q, r))


def equilibrium_mp(d, P, com, normal=None, load_at=None):
    """Every link's equilibrium in one 50-digit linear system.

    ``d``: scene dict; ``P``: joint points; ``com``: centres of mass;
    ``normal``: slide normal ``n`` (fixed on links[0]) of each P joint, the axis
    being ``t = (n_y, -n_x)``; ``load_at``: point of load ``i`` (default the
    link's centre of mass).  Returns ``(reactions {joint: (fx, fy, m)},
    efforts {joint: e}, frame (fx, fy, m about the origin))`` with the scene
    format's signs: reaction and effort by links[0] on links[1]; frame = what
    the moving links exert on the ground.
    """
    normal = normal or {}
    load_at = load_at or {}
    links = [lk["name"] for lk in d["links"]]
    row = {n: 3 * i for i, n in enumerate(links)}
    col, c = {}, 0
    for j in d["joints"]:
        col[j["name"]] = c
        c += 2
    drivers = [x["joint"] for x in d["drivers"]]
    for x in drivers:
        col["drv:" + x] = c
        c += 1
    n = 3 * len(links)
    assert c == n
    A = mp.matrix(n, n)
    b = mp.matrix(n, 1)

    def add(link, k, fx, fy, p, couple):
        if link == "ground":
            return
        r = row[link]
        A[r, k] += fx
        A[r + 1, k] += fy
        A[r + 2, k] += p[0] * fy - p[1] * fx + couple

    jd = {j["name"]: j for j in d["joints"]}
    for j in d["joints"]:
        name, k = j["name"], col[j["name"]]
        for link, s in ((j["links"][1], 1), (j["links"][0], -1)):
            if j["type"] == "R":
                add(link, k, s, 0, P[name], 0)
                add(link, k + 1, 0, s, P[name], 0)
            else:
                nx, ny = normal[name]
                add(link, k, s * nx, s * ny, P[name], 0)
                add(link, k + 1, 0, 0, P[name], s)
    for x in drivers:
        j, k = jd[x], col["drv:" + x]
        for link, s in ((j["links"][1], 1), (j["links"][0], -1)):
            if j["type"] == "R":
                add(link, k, 0, 0, P[x], s)
            else:
                nx, ny = normal[x]
                add(link, k, s * ny, -s * nx, P[x], 0)

    def applied(link, fx, fy, p):
        r = row[link]
        b[r] -= fx
        b[r + 1] -= fy
        b[r + 2] -= p[0] * fy - p[1] * fx

    g = d.get("effects", {}).get("gravity") or (0.0, 0.0)
    for lk in d["links"]:
        if lk.get("mass", 0) > 0:
            m = mp.mpf(lk["mass"])
            applied(lk["name"], m * mp.mpf(g[0]), m * mp.mpf(g[1]), com[lk["name"]])
    if d.get("effects", {}).get("loads", True):
        for i, ld in enumerate(d.get("loads", [])):
            if "force" in ld:
                f = mpt(ld["force"])
                applied(ld["link"], f[0], f[1], load_at.get(i) or com[ld["link"]])
            if ld.get("torque"):
                b[row[ld["link"]] + 2] -= mp.mpf(ld["torque"])
    z = mp.lu_solve(A, b)
    reactions, efforts = {}, {}
    for j in d["joints"]:
        k = col[j["name"]]
        if j["type"] == "R":
            reactions[j["name"]] = (z[k], z[k + 1], mp.mpf(0))
        else:
            nx, ny = normal[j["name"]]
            reactions[j["name"]] = (z[k] * nx, z[k] * ny, z[k + 1])
    for x in drivers:
        efforts[x] = z[col["drv:" + x]]
    Fx = Fy = M = mp.mpf(0)
    for j in d["joints"]:
        if "ground" not in j["links"]:
            continue
        name = j["name"]
        rx, ry, rm = reactions[name]
        if name in efforts:
            if j["type"] == "R":
                rm = rm + efforts[name]
            else:
                nx, ny = normal[name]
                rx, ry = rx + efforts[name] * ny, ry - efforts[name] * nx
        s = 1 if j["links"][1] == "ground" else -1
        px, py = P[name]
        Fx += s * rx
        Fy += s * ry
        M += s * (px * ry - py * rx + rm)
    return reactions, efforts, (Fx, Fy, M)


def ref_vector(d, ref, L):
    """The reference as one list in the layout of :func:`got_vector`."""
    reactions, efforts, frame = ref
    L = mp.mpf(L)
    v = []
    for j in d["joints"]:
        fx, fy, m = reactions[j["name"]]
        v += [fx, fy, m / L]
    for x in d["drivers"]:
        e = efforts[x["joint"]]
        v.append(e / L if "toward" in x else e)
    return v + [frame[0], frame[1], frame[2] / L]


def got_vector(d, a, i, L):
    f = a.forces
    v = []
    for j in d["joints"]:
        v += [f.reactions[j["name"]][i][0], f.reactions[j["name"]][i][1],
              f.reaction_moments[j["name"]][i] / L]
    for x in d["drivers"]:
        e = f.driving[x["joint"]][i]
        v.append(e / L if "toward" in x else e)
    return v + [f.frame_force[i][0], f.frame_force[i][1], f.frame_moment[i] / L]


def normwise(got, ref):
    """``(max |got - ref| / max |ref|, max |ref|)``; NaN in ``got`` gives inf."""
    scale = max(abs(r) for r in ref)
    if not all(math.isfinite(g) for g in got):
        return math.inf, scale
    return float(max(abs(mp.mpf(g) - r) for g, r in zip(got, ref)) / scale), scale


def run_both(scene, q, **kw):
    """Both force methods at driver values ``q`` ({joint: array}), zero rates, exact kappa."""
    zeros = {k: np.zeros_like(v) for k, v in q.items()}
    plan = compile_plan(scene, **kw)
    return {m: plan.run(q=q, qd=zeros, qdd=zeros, exact_condition=True, method=m) for m in METHODS}


def solver_geometry(d, a, i):
    """Joint points and centres of mass the solver used at step ``i``, as exact mpf."""
    P = {j["name"]: mpt(a.joints[j["name"]].position[i]) for j in d["joints"]}
    com = {lk["name"]: mpt(a.links[lk["name"]].com[i]) for lk in d["links"] if "com" in lk}
    return P, com


def _link(name, com, mass):
    return {"name": name, "mass": mass, "com": [float(com[0]), float(com[1])], "inertia": 1e-4}


def _off(p, q, t, h):
    """Point at fraction t from p to q, moved h along the left normal."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    n = math.hypot(dx, dy)
    return [p[0] + t * dx - h * dy / n, p[1] + t * dy + h * dx / n]


# ---------------------------------------------------------------------------
# (1) approaching a dead centre: reactions grow like 1/sin(psi) and stay accurate
# ---------------------------------------------------------------------------

# relative distance of the driver from its dead-centre value (metres / L for the
# slider, radians for the rocker); psi ~ sqrt(delta): 0.3 ... 3e-7
DELTAS = (1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14)


def slider_driven_slider_crank():
    """Offset slider-crank driven by its slider (P driver on S): crank and rod
    in line at the dead centre x* = sqrt((l1 + l2)^2 - e^2), where the RRR dyad
    (crank, rod) has a vanishing determinant.  Torque on the crank (the output),
    a force on the rod, three masses under gravity."""
    l1, l2, e = 0.05, 0.17, 0.013
    th = math.radians(50.0)
    B = [l1 * math.cos(th), l1 * math.sin(th)]
    C = [B[0] + math.sqrt(l2 ** 2 - (e - B[1]) ** 2), e]
    Gc, Rc = _off([0, 0], B, 0.5, 0.004), _off(B, C, 0.6, 0.003)
    return {
        "name": "slider-driven slider-crank",
        "links": [_link("crank", Gc, 0.3), _link("rod", Rc, 0.8), _link("slider", C, 1.2)],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": B},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": C},
            {"name": "S", "type": "P", "links": ["ground", "slider"], "at": C, "axis_deg": 0.0},
        ],
        "drivers": [{"joint": "S", "start": 0.0, "stop": 0.01, "steps": 2, "speed": 0.0}],
        "loads": [{"link": "crank", "torque": -2.5},
                  {"link": "rod", "force": [3.0, -7.0], "at": Rc}],
        "effects": {"inertia": False, "gravity": [0.0, -9.81], "loads": True},
        "outputs": ["reactions", "driving", "frame"],
    }


def slider_crank_case():
    """(scene dict, q values, exact reference geometry per step, psi per step)."""
    d = slider_driven_slider_crank()
    J = {j["name"]: mpt(j["at"]) for j in d["joints"]}
    A0, B0, C0 = J["A"], J["B"], J["C"]
    l1, l2, e = dist(A0, B0), dist(B0, C0), C0[1]
    sigma = int(mp.sign(cross3(A0, C0, B0)))
    L = linkage_sym.load_scene(d).characteristic_length()
    xstar = mp.sqrt((l1 + l2) ** 2 - e ** 2)
    q = np.array([float(xstar - mp.mpf(dl) * mp.mpf(L) - C0[0]) for dl in DELTAS])
    lk = {x["name"]: mpt(x["com"]) for x in d["links"]}
    geo, psi = [], []
    for qi in q:
        C = (C0[0] + mp.mpf(qi), e)  # exact: the driver value is a double
        B = circle_meet(A0, l1, C, l2, sigma)
        P = {"A": A0, "B": B, "C": C, "S": C}
        com = {"crank": carried(A0, B0, A0, B, lk["crank"]),
               "rod": carried(B0, C0, B, C, lk["rod"]),
               "slider": (C[0] + lk["slider"][0] - C0[0], lk["slider"][1])}
        geo.append((P, com))
        psi.append(sin_between(A0, B, C))
    return d, {"S": q}, geo, psi, {"S": (mp.mpf(0), mp.mpf(1))}


def rocker_driven_fourbar():
    """Crank-rocker (example 3-1 of [4]: 24, 63, 48, 78 mm) driven at its rocker
    (R driver on D, ground -> rocker): crank and coupler stretched in line at the
    rocker's extreme angle, where the RRR dyad (crank, coupler) is singular.
    Torque on the crank (the output), a force on the coupler, masses, gravity."""
    l1, l2, l3, l4 = 0.024, 0.063, 0.048, 0.078
    alpha = math.pi - math.acos((l3 ** 2 + l4 ** 2 - (l1 + l2) ** 2) / (2 * l3 * l4)) + 0.5
    C = [l4 + l3 * math.cos(alpha), l3 * math.sin(alpha)]
    r, ang = math.hypot(*C), math.atan2(C[1], C[0])
    b = ang - math.acos((l1 ** 2 + r ** 2 - l2 ** 2) / (2 * l1 * r))
    B = [l1 * math.cos(b), l1 * math.sin(b)]
    D = [l4, 0.0]
    Gc, Kc, Rc = _off([0, 0], B, 0.5, 0.0), _off(B, C, 0.45, 0.01), _off(C, D, 0.5, 0.003)
    return {
        "name": "rocker-driven four-bar",
        "links": [_link("crank", Gc, 0.2), _link("coupler", Kc, 0.5), _link("rocker", Rc, 0.3)],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": B},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": C},
            {"name": "D", "type": "R", "links": ["ground", "rocker"], "at": D},
        ],
        "drivers": [{"joint": "D", "toward": "C", "start_deg": math.degrees(alpha),
                     "stop_deg": math.degrees(alpha) + 1.0, "steps": 2, "speed": 0.0}],
        "loads": [{"link": "crank", "torque": 0.8},
                  {"link": "coupler", "force": [-4.0, 6.0], "at": Kc}],
        "effects": {"gravity": [0.0, -9.81]},
        "outputs": ["reactions", "driving", "frame"],
    }


def fourbar_case():
    d = rocker_driven_fourbar()
    J = {j["name"]: mpt(j["at"]) for j in d["joints"]}
    A0, B0, C0, D0 = J["A"], J["B"], J["C"], J["D"]
    l1, l2, l3 = dist(A0, B0), dist(B0, C0), dist(D0, C0)
    sigma = int(mp.sign(cross3(A0, C0, B0)))
    # exact extreme rocker angle: |AC| = l1 + l2 (the assembly sits 0.5 rad above it)
    a0 = mp.atan2(C0[1] - D0[1], C0[0] - D0[0])
    star = mp.findroot(lambda a: dist(A0, (D0[0] + l3 * mp.cos(a), D0[1] + l3 * mp.sin(a)))
                       - (l1 + l2), a0 - mp.mpf("0.5"))
    q = np.array([float(star + mp.mpf(dl)) for dl in DELTAS])
    lk = {x["name"]: mpt(x["com"]) for x in d["links"]}
    geo, psi = [], []
    for qi in q:
        C = (D0[0] + l3 * mp.cos(mp.mpf(qi)), D0[1] + l3 * mp.sin(mp.mpf(qi)))
        B = circle_meet(A0, l1, C, l2, sigma)
        P = {"A": A0, "B": B, "C": C, "D": D0}
        com = {"crank": carried(A0, B0, A0, B, lk["crank"]),
               "coupler": carried(B0, C0, B, C, lk["coupler"]),
               "rocker": carried(D0, C0, D0, C, lk["rocker"])}
        geo.append((P, com))
        psi.append(sin_between(A0, B, C))
    return d, {"D": q}, geo, psi, {}


@pytest.mark.parametrize("case", [slider_crank_case, fourbar_case],
                         ids=["slider-driven-slider-crank", "rocker-driven-fourbar"])
def test_reactions_near_dead_centre(case):
    """Steps at relative driver distances 1e-2 ... 1e-14 from the dead centre
    (psi from 0.3 down to ~3e-7, kappa from ~60 to ~6e7), both force methods:

    * vs the exact mechanism: ``err <= C_EXACT * eps * kappa^2`` (position error
      times force sensitivity; module docstring);
    * vs the solver's own geometry: ``err <= C_SOLVE * eps * kappa``;
    * the reactions really grow: ``max|R| * sin(psi)`` stays within 25% of its
      value at the first step while max|R| grows by more than 1e5, and kappa
      tracks 1/sin(psi) (1 <= kappa sin(psi) <= 100).
    """
    d, q, geo, psi, normal = case()
    scene = linkage_sym.load_scene(d)
    L = scene.characteristic_length()
    res = run_both(scene, q)
    fails, growth = [], []
    for m, a in res.items():
        assert list(a.status) == ["ok"] * len(DELTAS), f"{m}: {a.status} {a.messages}"
        for i, dl in enumerate(DELTAS):
            kappa = float(a.condition[i])
            sp = float(psi[i])
            assert 1.0 <= kappa * sp <= 100.0, f"step {i}: kappa {kappa:.3g} vs 1/sin psi {1 / sp:.3g}"
            got = got_vector(d, a, i, L)
            err, scale = normwise(got, ref_vector(d, equilibrium_mp(d, *geo[i], normal), L))
            tol = C_EXACT * EPS * kappa ** 2
            if not err <= tol:
                fails.append(f"{m} delta {dl:g}: vs exact mechanism err {err:.3g} > {tol:.3g}")
            P, com = solver_geometry(d, a, i)
            err2, _ = normwise(got, ref_vector(d, equilibrium_mp(d, P, com, normal), L))
            tol2 = C_SOLVE * EPS * kappa
            if not err2 <= tol2:
                fails.append(f"{m} delta {dl:g}: vs solver geometry err {err2:.3g} > {tol2:.3g}")
            if m == "dyad":
                growth.append(float(scale) * sp)
                if i == 0:
                    first = float(scale)
    assert not fails, f"{d['name']} (mpmath 50 digits): " + "; ".join(fails)
    assert max(growth) <= 1.25 * growth[0] and min(growth) >= 0.8 * growth[0], growth
    assert float(max(abs(v) for v in ref_vector(d, equilibrium_mp(d, *geo[-1], normal), L))) \
        > 1e5 * first


# ---------------------------------------------------------------------------
# (2) a step exactly at a dead centre is flagged, not answered with garbage
# ---------------------------------------------------------------------------


def change_point_fourbar():
    """Grashof change point 7 + 17 = 10 + 14 with integer assembly points (as in
    test_kinematics_hard_cases): at th1 = 0 (step 18 of 37) B = (7, 0), C = (24, 0),
    all four joints in line, the dyad determinant is exactly 0 in doubles; the
    sweep goes through it with ok steps on both sides.  Loads: torque on the
    rocker, force on the coupler, masses, gravity."""
    return {
        "name": "change point with loads",
        "links": [_link("crank", [-3.5, 0.5], 1.0), _link("coupler", [0.5, 4.5], 2.0),
                  _link("rocker", [11.0, 4.0], 1.5)],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [-7.0, 0.0]},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [8.0, 8.0]},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [14.0, 0.0]},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": -180, "stop_deg": 180,
                     "steps": 37, "speed": 10.0}],
        "loads": [{"link": "rocker", "torque": -30.0},
                  {"link": "coupler", "force": [5.0, -20.0], "at": [0.5, 4.5]}],
        "effects": {"gravity": [0.0, -9.81]},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }, 18, [k for k in range(37) if k != 18]


def slider_to_its_limit():
    """Slider-driven slider-crank, crank (0,0)-(3,4), rod (3,4)-(6,0): the slide
    reaches x = 10 = l1 + l2 exactly at q = 4 (step 4 of 9): crank and rod in
    line, singular; beyond it (x > 10) unassemblable."""
    return {
        "name": "slider to its limit",
        "links": [_link("crank", [1.5, 2.0], 1.0), _link("rod", [4.5, 2.0], 2.0),
                  _link("slider", [6.0, 0.0], 3.0)],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [3.0, 4.0]},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [6.0, 0.0]},
            {"name": "S", "type": "P", "links": ["ground", "slider"], "at": [6.0, 0.0],
             "axis_deg": 0.0},
        ],
        "drivers": [{"joint": "S", "start": -4.0, "stop": 8.0, "steps": 13, "speed": 1.0}],
        "loads": [{"link": "crank", "torque": 12.0},
                  {"link": "rod", "force": [0.0, -10.0], "at": [4.5, 2.0]}],
        "effects": {"gravity": [0.0, -9.81]},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }, 8, list(range(8))


@pytest.mark.parametrize("build", [change_point_fourbar, slider_to_its_limit],
                         ids=["change-point-fourbar", "slider-at-its-limit"])
@pytest.mark.parametrize("method", METHODS)
def test_exactly_singular_step_is_flagged(build, method):
    """The exactly singular step: status ``singular``, a message naming the
    condition number; its reactions, efforts and frame loads NaN in the arrays
    and absent from to_dict() (positions kept); every other assemblable step is
    ok with finite forces (the neighbours included)."""
    d, i, ok_steps = build()
    scene = linkage_sym.load_scene(d)
    a = compile_plan(scene).run(method=method)
    assert a.status[i] == "singular", f"step {i}: {a.status[i]!r} ({a.messages[i]})"
    assert "condition number" in a.messages[i], a.messages[i]
    f = a.forces
    for name in f.reactions:
        assert np.all(np.isnan(f.reactions[name][i])) and np.isnan(f.reaction_moments[name][i]), name
    for name in f.driving:
        assert np.isnan(f.driving[name][i]), name
    assert np.all(np.isnan(f.frame_force[i])) and np.isnan(f.frame_moment[i])
    step = a.to_dict()["steps"][i]
    assert step["status"] == "singular" and "condition number" in step["message"]
    assert "driving" not in step and "frame" not in step
    for name, rec in step["joints"].items():
        assert "position" in rec and "reaction" not in rec and "reaction_moment" not in rec, name
    assert i - 1 in ok_steps  # a neighbour on the approach side
    for k in ok_steps:
        assert a.status[k] == "ok", f"step {k}: {a.status[k]} ({a.messages[k]})"
        vals = [f.reactions[n][k] for n in f.reactions] + [f.frame_force[k]]
        vals += [[f.driving[n][k]] for n in f.driving] + [[f.frame_moment[k]]]
        assert all(np.all(np.isfinite(v)) for v in vals), f"step {k}: non-finite forces"
        rec = a.to_dict()["steps"][k]
        assert "driving" in rec and "frame" in rec and all(
            "reaction" in r for r in rec["joints"].values())
    for k in set(range(len(a.status))) - set(ok_steps) - {i}:
        assert a.status[k] == "unassemblable", f"step {k}: {a.status[k]}"


# ---------------------------------------------------------------------------
# (3) extreme link ratios 1e-3 and 1e3
# ---------------------------------------------------------------------------


def _with_loads(d, out_link, mid_link, g=(0.0, -9.81)):
    """Masses on every link (centre of mass off the line of its joints), a torque
    on the output link, a force on the middle link at its centre of mass."""
    at = {j["name"]: j["at"] for j in d["joints"]}
    ends = {"crank": ("A", "B"), "coupler": ("B", "C"), "rod": ("B", "C"),
            "rocker": ("C", "D"), "slider": ("C", "C")}
    links = []
    for i, lk in enumerate(d["links"]):
        p, q = (at[k] for k in ends[lk["name"]])
        com = _off(p, q, 0.4, 0.1 * math.dist(p, q)) if p != q else list(p)
        links.append(_link(lk["name"], com, 1.0 + i))
    d["links"] = links
    size = max(math.dist(p, q) for p in at.values() for q in at.values())
    mid = next(lk for lk in links if lk["name"] == mid_link)
    d["loads"] = [{"link": out_link, "torque": -3.0 * size},
                  {"link": mid_link, "force": [2.0, -5.0], "at": mid["com"]}]
    d["effects"] = {"gravity": list(g)}
    d["outputs"] = ["reactions", "driving", "frame"]
    return d


def _fourbar_ratio(lengths):
    d, _ = scenes.fourbar(*lengths, steps=25, speed=10.0)
    d = _with_loads(d, "rocker", "coupler")
    J = {j["name"]: mpt(j["at"]) for j in d["joints"]}
    A0, B0, C0, D0 = J["A"], J["B"], J["C"], J["D"]
    assert A0 == (0, 0)
    l1, l2, l3 = dist(A0, B0), dist(B0, C0), dist(D0, C0)
    sigma = int(mp.sign(cross3(B0, D0, C0)))
    lk = {x["name"]: mpt(x["com"]) for x in d["links"]}

    def geometry(q):
        B = (l1 * mp.cos(q), l1 * mp.sin(q))
        C = circle_meet(B, l2, D0, l3, sigma)
        P = {"A": A0, "B": B, "C": C, "D": D0}
        return P, {"crank": carried(A0, B0, A0, B, lk["crank"]),
                   "coupler": carried(B0, C0, B, C, lk["coupler"]),
                   "rocker": carried(D0, C0, D0, C, lk["rocker"])}, {}
    return d, geometry


def _slider_ratio(l1, l2, e):
    d, _ = scenes.slider_crank(l1, l2, e, steps=25, speed=10.0)
    d = _with_loads(d, "slider", "rod")
    d["loads"][0] = {"link": "crank", "torque": 2.0 * l1}
    d["loads"].append({"link": "slider", "force": [-40.0, 0.0], "at": d["links"][2]["com"]})
    J = {j["name"]: mpt(j["at"]) for j in d["joints"]}
    A0, B0, C0 = J["A"], J["B"], J["C"]
    assert A0 == (0, 0)
    L1, L2, E = dist(A0, B0), dist(B0, C0), C0[1]
    sigma = mp.sign(C0[0] - B0[0])
    lk = {x["name"]: mpt(x["com"]) for x in d["links"]}

    def geometry(q):
        B = (L1 * mp.cos(q), L1 * mp.sin(q))
        C = (B[0] + sigma * mp.sqrt(L2 ** 2 - (E - B[1]) ** 2), E)
        P = {"A": A0, "B": B, "C": C, "S": C}
        return P, {"crank": carried(A0, B0, A0, B, lk["crank"]),
                   "rod": carried(B0, C0, B, C, lk["rod"]),
                   "slider": (C[0] + lk["slider"][0] - C0[0], lk["slider"][1])}, \
            {"S": (mp.mpf(0), mp.mpf(1))}
    return d, geometry


C_RATIO = 1.0


@pytest.mark.parametrize("build", [
    pytest.param(lambda: _fourbar_ratio((1e-3, 1.0, 0.8, 0.9)), id="fourbar-crank-1e-3"),
    pytest.param(lambda: _fourbar_ratio((1.0, 1e3, 800.0, 900.0)), id="fourbar-others-1e3"),
    pytest.param(lambda: _slider_ratio(1e-3, 1.0, 0.2), id="slider-crank-crank-1e-3"),
    pytest.param(lambda: _slider_ratio(1.0, 1e3, 0.5), id="slider-crank-rod-1e3"),
])
def test_extreme_link_ratios(build):
    """A 25-step turn of mechanisms whose links differ by 1e3, both methods, vs
    the exact mechanism in mpmath: normwise ``err <= C_RATIO * eps * kappa``
    (kappa = a.condition, which carries the length ratio), and the driving torque
    -- 1e3 times smaller than force x size when the crank is tiny -- to
    ``C_RATIO * eps * kappa`` relative to its own largest value over the turn."""
    d, geometry = build()
    scene = linkage_sym.load_scene(d)
    L = scene.characteristic_length()
    q = np.radians(np.linspace(0.0, 360.0, 25))
    res = run_both(scene, {"A": q})
    refs = [equilibrium_mp(d, *geometry(mp.mpf(qi))) for qi in q]
    torque_scale = max(abs(r[1]["A"]) for r in refs)
    crank = math.dist(*(j["at"] for j in d["joints"][:2]))
    ratio = L / crank
    fails, worst = [], 0.0
    for m, a in res.items():
        assert np.all(a.status == "ok"), a.messages
        for i in range(len(q)):
            kappa = float(a.condition[i])
            err, _ = normwise(got_vector(d, a, i, L), ref_vector(d, refs[i], L))
            tol = C_RATIO * EPS * kappa
            terr = float(abs(mp.mpf(a.forces.driving["A"][i]) - refs[i][1]["A"]) / torque_scale)
            ttol = tol * ratio
            worst = max(worst, err / tol, terr / ttol)
            if not (err <= tol and terr <= ttol):
                fails.append(f"{m} step {i}: err {err:.3g} (tol {tol:.3g}), torque err "
                             f"{terr:.3g} (tol {ttol:.3g})")
    assert not fails, f"{d['name']}: " + "; ".join(fails[:6])
    print(f"{d['name']}: worst error / tolerance {worst:.3g}")


# ---------------------------------------------------------------------------
# (4) a class-III group: superposition vs global vs mpmath, amplification
# ---------------------------------------------------------------------------


def sixbar_dict(crank_scale=1.0):
    """The shipped sixbar_class3 (crank A-B, triad link_BC / ternary lever /
    rocker_DE / rocker_FG) without inertia (the reference is static); with
    ``crank_scale`` the crank is lengthened (B moved along the crank, link_BC
    follows) so that the triad reaches its own singular position."""
    d = example_dict("sixbar_class3")
    d["effects"]["inertia"] = False
    B = d["joints"][1]
    assert B["name"] == "B" and d["joints"][0]["at"] == [0.0, 0.0]
    B["at"] = [B["at"][0] * crank_scale, B["at"][1] * crank_scale]
    return d


def triad_exact(d, q, guess):
    """Exact positions of the sixbar at crank angle ``q``: Newton in 50 digits on
    the triad's three loop equations |BC| = l_BC, |DE| = l_DE, |FG| = l_FG for
    the lever's pose (phi, ox, oy) (lever point X at R(phi) X + o), started from
    ``guess`` (the solver's pose: it only picks the branch; the root is that of
    the exact equations, checked to lie within 1e-6 of the guess).  Returns the
    reference ``equilibrium_mp`` result and the lever's Jacobian determinant."""
    J = {j["name"]: mpt(j["at"]) for j in d["joints"]}
    A, B0, C0, D0, E, F0, G = (J[k] for k in "ABCDEFG")
    q = mp.mpf(q)
    lab = dist(A, B0)
    B = (A[0] + lab * mp.cos(q), A[1] + lab * mp.sin(q))
    pairs = ((C0, B, dist(B0, C0)), (D0, E, dist(D0, E)), (F0, G, dist(F0, G)))
    x = mp.matrix([mp.mpf(float(v)) for v in guess])

    def pose(X):
        c, s = mp.cos(x[0]), mp.sin(x[0])
        return (c * X[0] - s * X[1] + x[1], s * X[0] + c * X[1] + x[2])

    for _ in range(50):
        f, Jm = mp.matrix(3, 1), mp.matrix(3, 3)
        for k, (X, Q, ln) in enumerate(pairs):
            p = pose(X)
            ux, uy = p[0] - Q[0], p[1] - Q[1]
            dpx, dpy = -(p[1] - x[2]), p[0] - x[1]
            f[k] = ux * ux + uy * uy - ln * ln
            Jm[k, 0], Jm[k, 1], Jm[k, 2] = 2 * (ux * dpx + uy * dpy), 2 * ux, 2 * uy
        step = mp.lu_solve(Jm, -f)
        x += step
        if mp.norm(step) < mp.mpf(10) ** -40:
            break
    else:  # pragma: no cover
        raise AssertionError(f"reference Newton did not converge at q = {q}")
    assert abs(x[0] - guess[0]) < 1e-6, "reference converged to another branch"
    C, D, F = pose(C0), pose(D0), pose(F0)
    P = {"A": A, "B": B, "C": C, "D": D, "E": E, "F": F, "G": G}
    lk = {x_["name"]: mpt(x_["com"]) for x_ in d["links"]}
    com = {"crank": carried(A, B0, A, B, lk["crank"]),
           "link_BC": carried(B0, C0, B, C, lk["link_BC"]),
           "lever": pose(lk["lever"]),
           "rocker_DE": carried(E, D0, E, D, lk["rocker_DE"]),
           "rocker_FG": carried(G, F0, G, F, lk["rocker_FG"])}
    load_at = {i: pose(mpt(ld["at"])) for i, ld in enumerate(d["loads"]) if "force" in ld}
    assert all(ld["link"] == "lever" for ld in d["loads"])
    return equilibrium_mp(d, P, com, {}, load_at), mp.det(Jm)


def _guess(a, i):
    return (a.links["lever"].rotation[i], *a.links["lever"].origin[i])


def _triad_error(d, a, i, L, guess_from=None):
    ref, det = triad_exact(d, a.drivers["A"]["q"][i], _guess(guess_from or a, i))
    err, scale = normwise(got_vector(d, a, i, L), ref_vector(d, ref, L))
    return err, scale, det


def _superposition_tol(kappa, amp):
    """Position error as in (1) plus the superposition's own loss: the force
    solve's ``eps * kappa`` times its cancellation factor ``amp`` (about
    log10(amp) digits, superposition.py)."""
    return C_EXACT * EPS * kappa ** 2 + EPS * kappa * max(1.0, amp)


@pytest.mark.slow
def test_class3_sixbar_all_steps_default_choice():
    """The shipped sixbar_class3 (inertia off) over a full turn, 361 steps, every
    step: the dyad method (superposition, default disconnection) and the global
    method both match the 50-digit reference to ``_superposition_tol``, the
    amplification stays below AMPLIFICATION_LIMIT and the default choice is used
    throughout.  (Observed: err <= 0.3 eps kappa, kappa <= 50, amplification <= 1.8.)"""
    d = sixbar_dict()
    scene = linkage_sym.load_scene(d)
    L = scene.characteristic_length()
    q = np.radians(np.linspace(0.0, 360.0, 361))
    res = run_both(scene, {"A": q})
    g = res["dyad"].forces.groups[1]
    assert g.method == "disconnection" and set(g.links) == {"link_BC", "lever", "rocker_DE",
                                                             "rocker_FG"}
    assert np.all(res["dyad"].ok) and np.all(res["global"].ok)
    assert np.all(g.amplification <= AMPLIFICATION_LIMIT), np.nanmax(g.amplification)
    assert np.all(g.used == g.used[0])
    fails = []
    for i in range(len(q)):
        ref, _ = triad_exact(d, q[i], _guess(res["dyad"], i))
        rv = ref_vector(d, ref, L)
        for m, a in res.items():
            err, _ = normwise(got_vector(d, a, i, L), rv)
            amp = g.amplification[i] if m == "dyad" else 1.0
            tol = _superposition_tol(float(a.condition[i]), amp)
            if not err <= tol:
                fails.append(f"{m} step {i}: err {err:.3g} > {tol:.3g}")
    assert not fails, "sixbar_class3 vs mpmath: " + "; ".join(fails[:6])


@pytest.mark.parametrize("choice", [2, 8])
def test_class3_forced_poor_choice_switches_where_it_must(choice):
    """Disconnections 2 and 8 of the sixbar's triad have a singular point of
    their own near 172.1 deg (their superposition's K vanishes there; the
    amplification climbs past 250 on both sides).  Forced with
    ``compile_plan(scene, disconnection=k)`` over 171.5 ... 172.7 deg: the step
    where the forced choice exceeds AMPLIFICATION_LIMIT switches to another
    choice (``used != k`` there, and only there), the amplification actually
    used stays below the limit at every step, and every step -- switched or
    not -- matches the mpmath reference and the global method."""
    d = sixbar_dict()
    scene = linkage_sym.load_scene(d)
    L = scene.characteristic_length()
    q = np.radians(np.linspace(171.5, 172.7, 25))
    res = run_both(scene, {"A": q}, disconnection=choice)
    a = res["dyad"]
    g = a.forces.groups[1]
    switched = np.flatnonzero(g.used != choice)
    assert len(switched) >= 1 and len(switched) <= 3, g.used
    assert np.all(g.used >= 0) and np.all(g.amplification <= AMPLIFICATION_LIMIT), \
        (g.used, g.amplification)
    assert np.max(np.delete(g.amplification, switched)) > 200, "not near the choice's singularity"
    fails = []
    for i in range(len(q)):
        ref, _ = triad_exact(d, q[i], _guess(a, i))
        rv = ref_vector(d, ref, L)
        for m, r in res.items():
            err, _ = normwise(got_vector(d, r, i, L), rv)
            amp = g.amplification[i] if m == "dyad" else 1.0
            tol = _superposition_tol(float(r.condition[i]), amp)
            if not err <= tol:
                fails.append(f"{m} step {i} (used {g.used[i]}): err {err:.3g} > {tol:.3g}")
    assert not fails, f"disconnection {choice} forced: " + "; ".join(fails[:6])


@pytest.mark.slow
def test_class3_near_its_own_singular_position():
    """The sixbar with its crank 1.8 times longer cannot turn fully: the crank
    angle reaches a maximum th* = 197.75 deg where the triad's loop Jacobian is
    singular (lines BC, DE, FG concurrent).  th* is found in 50 digits (loop
    equations + det = 0 by mpmath.findroot); steps at th* - 1e-2 ... 1e-10 rad
    (kappa up to ~1e6).  Both methods vs the mpmath reference within
    ``_superposition_tol``; the amplification stays below the limit (the group's
    own singularity makes R and X large together, not a cancellation); the
    reactions grow like 1/|det| of the loop Jacobian (max|R| |det| within 25%)
    by more than 1e3."""
    d = sixbar_dict(1.8)
    scene = linkage_sym.load_scene(d)
    L = scene.characteristic_length()
    plan = compile_plan(scene)
    one = {"A": np.radians([197.0])}
    a0 = plan.run(q=one, qd={"A": np.zeros(1)}, qdd={"A": np.zeros(1)})
    assert a0.status[0] == "ok"
    J = {j["name"]: mpt(j["at"]) for j in d["joints"]}
    lab = dist(J["A"], J["B"])
    pairs = ((J["C"], None, dist(J["B"], J["C"])), (J["D"], J["E"], dist(J["D"], J["E"])),
             (J["F"], J["G"], dist(J["F"], J["G"])))

    def loop_and_det(th, ph, ox, oy):
        B = (lab * mp.cos(th), lab * mp.sin(th))
        c, s = mp.cos(ph), mp.sin(ph)
        out, Jm = [], mp.matrix(3, 3)
        for k, (X, Q, ln) in enumerate(pairs):
            Q = B if Q is None else Q
            p = (c * X[0] - s * X[1] + ox, s * X[0] + c * X[1] + oy)
            ux, uy = p[0] - Q[0], p[1] - Q[1]
            out.append(ux * ux + uy * uy - ln * ln)
            Jm[k, 0] = 2 * (-ux * (p[1] - oy) + uy * (p[0] - ox))
            Jm[k, 1], Jm[k, 2] = 2 * ux, 2 * uy
        return out + [mp.det(Jm)]

    star = mp.findroot(loop_and_det, (mp.radians(197.5), *[mp.mpf(float(v)) for v in _guess(a0, 0)]))
    th_star = star[0]
    assert abs(mp.degrees(th_star) - mp.mpf("197.755")) < mp.mpf("0.01")
    fails, growth = [], []
    for dl in CLASS3_DELTAS:
        # one run per step: see test_class3_sweep_toward_its_singular_position
        q = np.array([float(th_star - mp.mpf(dl))])
        res = {m: plan.run(q={"A": q}, qd={"A": np.zeros(1)}, qdd={"A": np.zeros(1)},
                           exact_condition=True, method=m) for m in METHODS}
        g = res["dyad"].forces.groups[1]
        for m, a in res.items():
            assert a.status[0] == "ok", f"{m} delta {dl:g}: {a.status[0]} {a.messages[0]}"
        assert g.amplification[0] <= AMPLIFICATION_LIMIT, (dl, g.amplification[0])
        ref, det = triad_exact(d, q[0], _guess(res["dyad"], 0))
        rv = ref_vector(d, ref, L)
        for m, a in res.items():
            err, scale = normwise(got_vector(d, a, 0, L), rv)
            amp = g.amplification[0] if m == "dyad" else 1.0
            tol = _superposition_tol(float(a.condition[0]), amp)
            if not err <= tol:
                fails.append(f"{m} delta {dl:g}: err {err:.3g} > {tol:.3g}")
        growth.append((float(scale), float(abs(det)), float(res["dyad"].condition[0])))
    assert not fails, "class-III near its singular position: " + "; ".join(fails)
    prod = [s * dt for s, dt, _ in growth]
    assert max(prod) <= 1.25 * prod[0] and min(prod) >= 0.8 * prod[0], prod
    assert growth[-1][0] > 1e3 * growth[0][0], growth
    assert growth[-1][2] > 1e5, growth


CLASS3_DELTAS = (1e-2, 1e-4, 1e-6, 1e-8, 1e-10)
TH_STAR_DEG = 197.75489324687886768  # the 50-digit th* of the test above, to 20 digits


def test_class3_sweep_toward_its_singular_position():
    """One sweep through the driver values of the test above (th* - 1e-2 ... 1e-10
    rad): every one of them is assemblable in the assembly configuration's mode
    (each alone solves ok, and the mpmath Newton from a neighbouring solved step
    converges there), so the spec (continuous motion, assembly mode kept)
    wants every step ok and equal to the one-step result."""
    d = sixbar_dict(1.8)
    plan = compile_plan(linkage_sym.load_scene(d))
    q = math.radians(TH_STAR_DEG) - np.array(CLASS3_DELTAS)
    z = np.zeros_like(q)
    a = plan.run(q={"A": q}, qd={"A": z}, qdd={"A": z})
    alone = [plan.run(q={"A": q[i:i + 1]}, qd={"A": z[:1]}, qdd={"A": z[:1]})
             for i in range(len(q))]
    assert all(b.status[0] == "ok" for b in alone)
    assert list(a.status) == ["ok"] * len(q), list(zip(a.status, a.messages))
    for i, b in enumerate(alone):
        assert abs(a.links["lever"].rotation[i] - b.links["lever"].rotation[0]) < 1e-6
