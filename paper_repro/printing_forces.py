"""Dang and Zhang's printed reactions of the printing mechanism against linkage_sym.

Dang Zuqi, Zhang Qixian, "A simplified method for the force analysis of complex planar
multi-bar mechanisms" (year not shown in the text; [1] of the README's Sources), section 4,
prints at its one position (theta1 = 300 deg, omega1 = pi rad/s) the reactions

* R34n = 47.219, R34t = 934.03: the force of the lever 3 on the rocker 4 at D,
  normal to and along the rocker; t points from D to E, n is t turned by
  +90 deg (the printed components R34n (x, y) = (-29.1176, 37.1728) and the
  unit R43t = (-0.7872, -0.6166) fix both directions and signs);
* R53n = -509.71, R53t = 950.64: the force of the slider 5 on the lever 3 at
  the pin F, along x (the guide, eq. (12)) and along y.

linkage_sym's ``reactions[j]`` is the force of ``links[0]`` on ``links[1]``:
joint D is (lever, rocker), so R34 = reactions["D"]; joint F is (lever,
slider), so R53 = -reactions["F"].

R53n is not an independent check of the force analysis: it is the slider's x
balance, R53n = F5x + F'5 cos 20 deg, and the reading of the printed 451 N as
the printing force F'5 came from it (paper_repro/printing_mechanism.py; with
the paper's g = 9.8 it closes to 450.995 N).  R34t and R53t are.

The paper's route.  The paper removes the rocker 4 and makes the slider the
hypothetical input (choice PAPER_CHOICE = 3 of ``linkage-sym structure``),
with the unknown R34t at D.  ``paper_quantities`` solves that disconnection
with linkage_sym and, from ``superposition_terms``, rewrites the solver's
runs (whose unknown is the force on the rocker at E) in R34t: R34n, the
constants of eqs. 13-14, (R53n)', (R53t)', F_x, (R53n)'', (R53t)'', K.
``items()`` compares each with the printed value (python -m paper_repro).

Rounding spread.  The paper prints its inputs rounded.  ``ROUNDING`` (from
printing_mechanism.py) lists
every printed number that the reconstruction reads, with half a unit of its
last printed digit:

* the lengths AB, BC, CD, DF, ED, FF', AH and the pivot E (x_E, y_E) are
  design dimensions in m with at most three decimals (0.2 is read as 0.200).
  They are taken to 0.1 mm, +-0.05 mm (LENGTH_HALF), not to their last
  printed digit: the printed coordinates, which the paper computed from its
  lengths and prints to 0.1 mm, reproduce every printed length to 0.07 mm or
  better, so lengths off by several tenths of a mm are ruled out.  The report
  also shows the spread for +-0.5 mm (LENGTH_HALF_AS_PRINTED): about ten
  times larger, too wide to test anything;
* the centres of mass S1, S3 (x, y) and x_S4 are printed to 0.1 mm: +-0.05 mm;
  y_S4 = 0.288 to 1 mm: +-0.5 mm;
* the weights G1..G5 to their last digit (294 +-0.5, 139.65 +-0.005, ...,
  1719.9 +-0.05 N);
* the inertia moments M_E1..3 to their last digit (0.2432 +-0.00005, 3.679
  and 1.617 +-0.0005 N m);
* the printing force "F_S4x" = 451 +-0.5 N.

Held exact: theta1 = 300 deg and 30 rpm (they define the position analysed)
and the 20 deg of the printing force (a nominal angle; +-0.5 deg would move
R34t by about 2 N, see ``angle_effect``).  theta2-4 and the printed
coordinates of B, C, D, F are not inputs: the reconstruction solves the
assembly from the lengths (they only seed Newton).  The printed inertia
forces are not inputs either: linkage_sym computes them from the masses and
the kinematics.  They differ from the paper's by up to 0.05 N (0.4 %);
``paper_inertia_effect`` shows what applying the paper's own values would
change.

``rounding_spread`` rebuilds the scene with
``printing_mechanism.scene_dict`` from ``samples`` printed-input sets drawn
uniformly within those half-units (a seeded Monte Carlo), runs linkage_sym on
each and returns, per component, the largest deviation from the nominal
result, for every quantity of ``paper_quantities``.  ``linear_bound`` gives the worst corner of the same box to first
order (sum over the inputs of |d output / d input| * half-unit, from central
differences), an upper bound for the Monte-Carlo maximum.

Run:  python3 paper_repro/printing_forces.py     (needs linkage_sym: run from the repository root)
"""

from __future__ import annotations

import copy
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
for _p in (str(HERE), str(HERE.parent)):
    if _p not in sys.path:
        sys.path.insert(0, _p)

import printing_mechanism as pm  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.numeric.forces.superposition import superposition_terms  # noqa: E402

COMPONENTS = ("R34n", "R34t", "R53n", "R53t")
PRINTED_R = {k: pm.PRINTED["results"][k] for k in COMPONENTS}

# the paper's route (section 4, way 2): remove the rocker 4 (joints D, E), the slider 5 is the
# hypothetical input sliding along its guide, dyad (coupler 2, lever 3); as `linkage-sym structure`
# lists the choices of the printing mechanism's class-III group
PAPER_CHOICE = 3

LENGTH_HALF = pm.LENGTH_HALF
LENGTH_HALF_AS_PRINTED = 0.0005  # 1 mm, the last digit of 0.294, 0.248, 0.187
ROUNDING, N_LENGTHS, perturbed, half_units = pm.ROUNDING, pm.N_LENGTHS, pm.perturbed, pm.half_units
_get, _set = pm._get, pm._set

def one_step(printed=pm.PRINTED):
    """The scene dict for ``printed``, restricted to the one step theta1 (300 deg)."""
    th1 = printed["theta_deg"][1]
    return pm.scene_dict(printed, start_deg=th1, stop_deg=th1, steps=1)


def components(a, step=0):
    """The paper's components of R34 (n, t w.r.t. the rocker) and R53 (x, y) at ``step``."""
    d = a.joints["D"].position[step]
    e = a.joints["E"].position[step]
    et = (e - d) / np.linalg.norm(e - d)
    en = np.array([-et[1], et[0]])
    r34 = a.forces.reactions["D"][step]
    r53 = -a.forces.reactions["F"][step]
    return {"R34n": float(r34 @ en), "R34t": float(r34 @ et), "R53n": float(r53[0]), "R53t": float(r53[1])}


def run(scene_dict, method="dyad", disconnection=None):
    """linkage_sym's analysis of ``scene_dict``."""
    return compile_plan(linkage_sym.load_scene(scene_dict), disconnection=disconnection).run(method=method)


def paper_quantities(printed=pm.PRINTED, scene=None) -> dict:
    """The reactions and Dang and Zhang's intermediates with the unknown where the paper puts it.

    linkage_sym solves the one step at the paper's disconnection (PAPER_CHOICE) and
    ``superposition_terms`` gives its runs.  The solver's unknown is the force on the rocker at
    E along D->E; the paper's is R34t, the force of the lever on the rocker at D along D->E.
    Both are linear in each other (R34t = p + u X_E, p and u from the runs' reactions at D), so
    the residual M_bar + K X_E and every reaction R' + R'' X_E are rewritten in R34t.  The
    paper's sum of x forces on the slider is minus the solver's residual along the guide, so
    F_x = -M_bar and K = -K (eq. 12: sum F_x = F_x + K R34t).
    """
    d = one_step(printed) if scene is None else scene
    plan = compile_plan(linkage_sym.load_scene(d), disconnection=PAPER_CHOICE)
    a = plan.run()
    t = superposition_terms(plan, a, PAPER_CHOICE)
    P = {j: a.joints[j].position[0] for j in "BCDEF"}
    et = (P["E"] - P["D"]) / np.linalg.norm(P["E"] - P["D"])
    en = np.array([-et[1], et[0]])

    def vec(parts, j):
        return np.array([parts[j][0][0], parts[j][1][0]])

    Rp, Ru = t.particular, t.units[0]
    p, u = float(vec(Rp, "D") @ et), float(vec(Ru, "D") @ et)
    K_E, M_E = float(t.coefficients[0, 0, 0]), float(t.residual[0, 0])
    K_D, M_D = K_E / u, M_E - K_E * p / u
    r53p = -(vec(Rp, "F") - vec(Ru, "F") * p / u)  # slider on lever at F, R34t = 0
    r53u = -vec(Ru, "F") / u  # per unit R34t
    fb, fc = P["F"] - P["B"], P["F"] - P["C"]
    out = components(a)
    r34n = float(vec(Rp, "D") @ en)
    out.update({
        "R34n_x": r34n * en[0], "R34n_y": r34n * en[1],
        "eq13_n": fb[1], "eq13_t": -fb[0], "eq14_n": fc[1], "eq14_t": -fc[0],
        "eq13_c": fb[1] * r53p[0] - fb[0] * r53p[1], "eq14_c": fc[1] * r53p[0] - fc[0] * r53p[1],
        "R53n'": r53p[0], "R53t'": r53p[1], "Fx_bar": -M_D, "R53n''": r53u[0], "R53t''": r53u[1], "K": -K_D,
        "X_E": float(t.X[0, 0]), "M_E": M_E, "K_E": K_E,
        "R34t_superposed": -(-M_D) / (-K_D),
    })
    return {k: float(v) for k, v in out.items()}


def reactions_of(printed):
    return components(run(one_step(printed)))


def rounding_spread(samples=200, seed=0, length_half=LENGTH_HALF):
    """Largest |deviation| of every paper quantity over a seeded Monte Carlo of the printed rounding.

    Each sample draws every printed input of ``ROUNDING`` uniformly within its half unit
    (lengths and E: ``length_half``), rebuilds the scene and solves it at the paper's
    disconnection.  Returns (spread, nominal, deviations): dicts over the quantities of
    ``paper_quantities`` and an array (samples, 4) of the four reactions' deviations.
    """
    rng = np.random.default_rng(seed)
    half = half_units(length_half)
    nominal = paper_quantities()
    keys = list(nominal)
    dev = np.empty((samples, len(keys)))
    for i in range(samples):
        got = paper_quantities(perturbed(rng.uniform(-half, half)))
        dev[i] = [got[k] - nominal[k] for k in keys]
    spread = dict(zip(keys, np.abs(dev).max(axis=0)))
    return spread, nominal, dev[:, [keys.index(k) for k in COMPONENTS]]


def linear_bound(length_half=LENGTH_HALF):
    """First-order worst corner: sum_i |out(x + h_i) - out(x - h_i)| / 2, and the largest terms."""
    total = dict.fromkeys(COMPONENTS, 0.0)
    terms = []
    for i, ((path, _), h) in enumerate(zip(ROUNDING, half_units(length_half))):
        dp = np.zeros(len(ROUNDING))
        dp[i] = h
        up, dn = reactions_of(perturbed(dp)), reactions_of(perturbed(-dp))
        t = {k: abs(up[k] - dn[k]) / 2 for k in COMPONENTS}
        for k in COMPONENTS:
            total[k] += t[k]
        terms.append((path, h, t))
    return total, terms


def angle_effect(dangle=0.5):
    """Change of each component when the printing force's 20 deg moves by +dangle deg."""
    p = copy.deepcopy(pm.PRINTED)
    p["F5_angle_deg"] += dangle
    base, got = reactions_of(pm.PRINTED), reactions_of(p)
    return {k: got[k] - base[k] for k in COMPONENTS}


def paper_inertia_effect():
    """Change of each component when the paper's printed inertia forces replace the computed ones.

    The printed magnitudes get the signs of the computed components (the figure
    with the directions is missing); the difference is added as a load at each
    centre of mass.  The printed inertia moments are already used as they are.
    """
    scene = one_step()
    a = run(scene)
    printed = pm.PRINTED["inertia_printed"]
    mass = {lk["name"]: lk["mass"] for lk in scene["links"]}
    extra = []
    for link, key in (("coupler", "F_S1"), ("lever", "F_S2"), ("rocker", "F_S3")):
        lk = a.links[link]
        f = -mass[link] * lk.com_acceleration[0]
        want = np.sign(f) * np.array(printed[key])
        extra.append({"link": link, "force": [float(v) for v in want - f], "at": [float(v) for v in lk.com[0]]})
    d = copy.deepcopy(scene)
    d["loads"] += extra
    base, got = components(a), components(run(d))
    return {k: got[k] - base[k] for k in COMPONENTS}, extra


def k_factor(pts):
    """The paper's K = -(R53n)'' : x force of the slider on the lever per unit R34t, no other load.

    Lever 3 under R43 = -t (t = D->E unit), the coupler's force along CB (the
    coupler carries no load) and R53; moments about C.
    """
    p = {k: np.asarray(v, dtype=float) for k, v in pts.items()}
    et = (p["E"] - p["D"]) / np.linalg.norm(p["E"] - p["D"])
    ub = (p["C"] - p["B"]) / np.linalg.norm(p["C"] - p["B"])
    r43, dc, fc = -et, p["D"] - p["C"], p["F"] - p["C"]
    m = np.array([[ub[0], 1.0, 0.0], [ub[1], 0.0, 1.0], [0.0, -fc[1], fc[0]]])
    rhs = np.array([-r43[0], -r43[1], -(dc[0] * r43[1] - dc[1] * r43[0])])
    return -float(np.linalg.solve(m, rhs)[1])


DEFAULT_CHOICE = 0  # the solver's default disconnection of this group (remove the coupler)

# (key of paper_quantities, name, as printed) in the paper's order
PAPER_STEPS = (
    ("R34n", "R34n (eq. 1, about E)", "47.219"),
    ("R34n_x", "R34n, x component", "-29.1176"),
    ("R34n_y", "R34n, y component", "37.1728"),
    ("eq13_n", "eq. 13, coeff. of (R53n)'", "0.3762"),
    ("eq13_t", "eq. 13, coeff. of (R53t)'", "0.9436"),
    ("eq13_c", "eq. 13, constant", "312.3463"),
    ("eq14_n", "eq. 14, coeff. of (R53n)'", "0.325"),
    ("eq14_t", "eq. 14, coeff. of (R53t)'", "-0.025"),
    ("eq14_c", "eq. 14, constant", "13.0601"),
    ("R53n'", "(R53n)'", "63.69"),
    ("R53t'", "(R53t)'", "305.60"),
    ("Fx_bar", "F_x (eq. 12, R34t = 0)", "-573.40"),
    ("R53n''", "(R53n)'' (R34t = 1)", "-0.6139"),
    ("R53t''", "(R53t)'' (R34t = 1)", "0.6906"),
    ("K", "K = -(R53n)''", "0.6139"),
    ("R34t", "R34t = -F_x/K", "934.03"),
    ("R53n", "R53n", "-509.71"),
    ("R53t", "R53t", "950.64"),
)


def items(samples=200, seed=0):
    """Dang and Zhang's superposition, step by step, against linkage_sym (paper_repro/items.py).

    Every intermediate of section 4 with the unknown R34t at D, as the paper has it, from
    linkage_sym's solver at the paper's disconnection (paper_quantities), and the final
    reactions.  Status: reproduced when the value rounds to the printed one; else within input
    rounding when inside the Monte-Carlo spread of ``samples`` seeded samples of the printed
    inputs (rounding_spread; 200 by default); else not reproducible.
    """
    from items import NOT_REPRODUCIBLE, REPRODUCED, ROUNDING as ROUND, PRINTED, Item, half_unit

    spread, q, _ = rounding_spread(samples, seed)
    why_mc = (f"linkage_sym at the paper's disconnection, unknown at D; tolerance: the largest deviation over "
              f"{samples} seeded samples of the printed inputs within their rounding (lengths and E +-0.05 mm)")
    t1, qa = pm.assembly()
    k_exact = k_factor(pm.points(qa, t1))
    k_printed = k_factor({**pm.PRINTED["points"], "E": pm.PRINTED["E"]})
    notes = {
        "R34t": f"the paper's K = 0.6139 is what its rounded coordinates give ({k_printed:.5f}); the exact "
                f"assembly gives {k_exact:.5f}, which alone accounts for {q['R34t'] * (1 - k_exact / k_printed):+.2f} N",
        "eq14_c": "the paper's coefficient -0.025 is -0.0251 rounded",
        "R53n": "not independent of the 451 N: that force's reading (at 20 deg to the guide) came from this value",
    }
    out = []
    for key, name, printed in PAPER_STEPS:
        d = abs(q[key] - float(printed))
        where = "sec. 4, superposition at D"
        note = notes.get(key, "")
        if d <= half_unit(printed):
            out.append(Item(PRINTED, 1, where, name, printed, q[key], REPRODUCED, why=note or
                            "linkage_sym at the paper's disconnection, unknown at D"))
        elif d <= spread[key]:
            out.append(Item(PRINTED, 1, where, name, printed, q[key], ROUND, tol=spread[key],
                            why=why_mc + ("; " + note if note else "")))
        else:
            out.append(Item(PRINTED, 1, where, name, printed, q[key], NOT_REPRODUCIBLE,
                            why=f"off by {d:.3g}, beyond the rounding spread {spread[key]:.3g}"))
    return out


def _shipped_one_step():
    from linkage_sym.examples import example_dict
    d = example_dict("printing_mechanism")
    d["drivers"][0].update(start_deg=300, stop_deg=300, steps=1)
    return d


def report(samples=200, seed=0):
    out = []
    ours = components(run(_shipped_one_step()))
    spread, nominal, dev = rounding_spread(samples, seed)
    bound, terms = linear_bound()
    wide, _, _ = rounding_spread(samples, seed, LENGTH_HALF_AS_PRINTED)
    out.append("== Dang and Zhang (undated), printing mechanism at theta1 = 300 deg: reactions at D and F (N)")
    out.append("   R34 = force of lever 3 on rocker 4 at D (n normal to, t along D->E);"
               " R53 = force of slider 5 on lever 3 at F (n = x, t = y)")
    out.append(f"   {'':5s} {'linkage_sym':>12s} {'printed':>10s} {'difference':>11s} {'MC spread':>10s}"
               f" {'3 sigma':>8s} {'lin. bound':>10s}  within spread")
    sig = dev.std(axis=0)
    for i, k in enumerate(COMPONENTS):
        diff = ours[k] - PRINTED_R[k]
        note = " (not independent: 451 N was inferred from it)" if k == "R53n" else ""
        out.append(f"   {k:5s} {ours[k]:12.3f} {PRINTED_R[k]:10.3f} {diff:+11.3f} {spread[k]:10.3f} {3 * sig[i]:8.3f}"
                   f" {bound[k]:10.3f}  {'yes' if abs(diff) <= spread[k] else 'NO'}{note}")
    out.append(f"   linkage_sym on the shipped example.  MC spread = largest |deviation| over {samples} seeded samples"
               f" (seed {seed})\n   of the printed inputs, each uniform within half a unit of its last printed digit"
               f" (lengths and E: +-{LENGTH_HALF * 1e3:g} mm);\n   3 sigma of the same samples; lin. bound = worst"
               f" corner of the same box to first order.")
    out.append(f"   with lengths and E to +-{LENGTH_HALF_AS_PRINTED * 1e3:g} mm instead, the MC spread would be "
               + ", ".join(f"{k} {wide[k]:.3f}" for k in COMPONENTS))
    out.append(f"== the superposition at the paper's disconnection ({PAPER_CHOICE}: remove the rocker at D and E; the"
               " slider is the hypothetical input along its guide; dyad (coupler, lever)), unknown R34t at D")
    out.append(f"   {'':24s} {'linkage_sym':>12s} {'printed':>10s} {'difference':>11s} {'MC spread':>10s}")
    q = paper_quantities()
    for key, name, printed in PAPER_STEPS:
        out.append(f"   {name:24s} {q[key]:12.5f} {printed:>10s} {q[key] - float(printed):+11.5f} {spread[key]:10.5f}")
    out.append(f"   the solver's own unknown there is the force on the rocker at E along D->E: X_E = {q['X_E']:.3f} N, "
               f"M_bar = {q['M_E']:.4f} N, K = {q['K_E']:.5f}")
    a0 = run(one_step())
    plan0 = compile_plan(linkage_sym.load_scene(one_step()))
    t0 = superposition_terms(plan0, a0, DEFAULT_CHOICE)
    out.append(f"   at the solver's default disconnection ({DEFAULT_CHOICE}: {t0.choice.describe()}): unknown = "
               f"{t0.unknowns[0]}: X = {t0.X[0, 0]:.3f} N, M_bar = {t0.residual[0, 0]:.4f} N m, "
               f"K = {t0.coefficients[0, 0, 0]:.5f} m; the same reactions to 1e-9")
    out.append("== largest contributions to the first-order bound (N)")
    for k in ("R34t", "R53t", "R34n"):
        top = sorted(terms, key=lambda t: -t[2][k])[:4]
        out.append(f"   {k}: " + ", ".join(f"{'/'.join(map(str, p))} +-{h:g}: {t[k]:.3f}" for p, h, t in top))
    out.append("== what the printed rounding does not cover")
    ae = angle_effect()
    out.append("   the 20 deg of the printing force moved by +0.5 deg: "
               + ", ".join(f"{k} {v:+.3f}" for k, v in ae.items()))
    pe, extra = paper_inertia_effect()
    out.append("   the paper's printed inertia forces instead of the computed ones (extra loads "
               + ", ".join(f"{e['link']} ({e['force'][0]:+.3f}, {e['force'][1]:+.3f})" for e in extra) + "): "
               + ", ".join(f"{k} {v:+.3f}" for k, v in pe.items()))
    th1 = pm.PRINTED["theta_deg"][1]
    f981 = components(run(pm.scene_dict(start_deg=th1, stop_deg=th1, steps=1, g=9.81)))
    out.append("   with g = 9.81 instead of the paper's 9.8 (masses G/9.81): "
               + ", ".join(f"{k} {f981[k]:.3f} ({f981[k] - PRINTED_R[k]:+.3f})" for k in COMPONENTS))
    t1, q = pm.assembly()
    k_exact = k_factor(pm.points(q, t1))
    k_printed = k_factor({**pm.PRINTED["points"], "E": pm.PRINTED["E"]})
    out.append(f"   K (R34t = -F_x / K): exact assembly {k_exact:.5f}, printed (rounded) coordinates {k_printed:.5f},"
               f" printed K {pm.PRINTED['results']['K']}; R34t scales as 1/K: {k_exact / k_printed - 1:+.2e}"
               f" = {ours['R34t'] * (k_exact / k_printed - 1):+.3f} N")
    return "\n".join(out)


if __name__ == "__main__":
    print(report())
