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

R53n is not an independent check: the reconstruction took the 451 N printing
force from it (paper_repro/printing_mechanism.py).  R34t and R53t are.

Rounding spread.  The paper prints its inputs rounded.  ``ROUNDING`` lists
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
result.  ``linear_bound`` gives the worst corner of the same box to first
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

COMPONENTS = ("R34n", "R34t", "R53n", "R53t")
PRINTED_R = {k: pm.PRINTED["results"][k] for k in COMPONENTS}

LENGTH_HALF = 0.00005  # half-unit of the lengths and of E: 0.1 mm, as the printed coordinates (see above)
LENGTH_HALF_AS_PRINTED = 0.0005  # 1 mm, the last digit of 0.294, 0.248, 0.187

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
        items = list(parent)
        items[last] = value
        _set(d, head, tuple(items))
    else:
        parent[last] = value


def perturbed(deltas, printed=pm.PRINTED):
    """A copy of ``printed`` with ``deltas[i]`` added to the input ``ROUNDING[i]``."""
    out = copy.deepcopy(printed)
    for (path, _), dv in zip(ROUNDING, deltas):
        _set(out, path, _get(out, path) + dv)
    return out


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


def reactions_of(printed):
    return components(run(one_step(printed)))


def half_units(length_half=LENGTH_HALF):
    half = np.array([h for _, h in ROUNDING])
    half[:N_LENGTHS] = length_half
    return half


def rounding_spread(samples=200, seed=0, length_half=LENGTH_HALF):
    """Largest |deviation| of each component over a seeded Monte Carlo of the printed rounding.

    Returns (spread, nominal, deviations) with deviations an array (samples, 4).
    """
    rng = np.random.default_rng(seed)
    half = half_units(length_half)
    nominal = reactions_of(pm.PRINTED)
    dev = np.empty((samples, len(COMPONENTS)))
    for i in range(samples):
        got = reactions_of(perturbed(rng.uniform(-half, half)))
        dev[i] = [got[k] - nominal[k] for k in COMPONENTS]
    spread = dict(zip(COMPONENTS, np.abs(dev).max(axis=0)))
    return spread, nominal, dev


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
               + ", ".join(f"{k} {v:.3f}" for k, v in wide.items()))
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
    p = copy.deepcopy(pm.PRINTED)
    p["inertia_printed"]["F_S4x"] = 451.09
    f09 = reactions_of(p)
    out.append("   with |F'5| = 451.09 N (the value that reproduces the printed R53n): "
               + ", ".join(f"{k} {f09[k]:.3f} ({f09[k] - PRINTED_R[k]:+.3f})" for k in COMPONENTS))
    t1, q = pm.assembly()
    k_exact = k_factor(pm.points(q, t1))
    k_printed = k_factor({**pm.PRINTED["points"], "E": pm.PRINTED["E"]})
    out.append(f"   K (R34t = -F_x / K): exact assembly {k_exact:.5f}, printed (rounded) coordinates {k_printed:.5f},"
               f" printed K {pm.PRINTED['results']['K']}; R34t scales as 1/K: {k_exact / k_printed - 1:+.2e}"
               f" = {ours['R34t'] * (k_exact / k_printed - 1):+.3f} N")
    return "\n".join(out)


if __name__ == "__main__":
    print(report())
