"""Items of the scripts that have no ``items()`` of their own (paper_repro/items.py protocol).

``four_bar_design.py`` ([2]: the design by K, examples 2-9 and 2-10) and
``chapter3_polygons_exercises.py`` ([4]: example 3-1's polygon intermediates, exercises 3-5,
3-13, 3-14, 3-23, 3-24) were written by their own authors; this module reads their public
functions and turns each comparison into an :class:`~items.Item`.  ``run_all`` uses a script's
own ``items()`` when it has one, so these adapters give way as soon as a script grows its own.

Where the source prints no value (the design by K is a procedure without numbers; the chapter's
exercises have no printed answers) the row is a self-check (``items.SELF_CHECK``): it claims no
source and no printed value, and checks that the script's two independent computations agree
(linkage_sym against a closed form or a construction written out in the script, which the row
names): 1e-9 relative, because both solve the same equations and only rounding separates them.
"""

from __future__ import annotations

import math

import numpy as np

from items import AGREES, ERRATUM, NONE, PRINTED, REPRODUCED, ROUNDING, SELF_CHECK, Item, half_unit

REL = 1e-9  # two computations of the same equations: rounding only


def _agree(a, b, rel=REL) -> bool:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return bool(np.all(np.abs(a - b) <= rel * np.maximum(1.0, np.abs(b))))


def _pair(where, name, ours, other, other_name, unit="", ours_name="linkage_sym"):
    """A self-check for a value no source prints: ours against the script's other computation."""
    ours_arr = np.atleast_1d(np.asarray(ours, dtype=float))
    shown = float(ours_arr[0]) if ours_arr.size == 1 else "(" + ", ".join(f"{v:.6g}" for v in ours_arr) + ")"
    return Item(SELF_CHECK, None, where, name, NONE, shown, AGREES, holds=_agree(ours, other), unit=unit,
                against=other_name,
                why=f"{ours_name} against {other_name} to {REL:g} relative (two computations of the same "
                    "quantity: rounding only)")


# --------------------------------------------------------------------------- [2] four_bar_design.py
def four_bar_design_items():
    import four_bar_design as fb

    out = []
    p = fb.part1()
    h, d = p["by_hand"], p["design"]
    w = "K design, crank-rocker"
    mine = (f"our numbers (the section prints none): K = {fb.K}, CD = {fb.ROCKER} m, psi = {fb.SWING_DEG} deg, "
            f"AD = {fb.GROUND} m; ")
    hand = "the auxiliary-circle construction written out in the script"
    out.append(_pair(w, "theta (eq. 2-2)", math.degrees(h["theta"]), 180 * (fb.K - 1) / (fb.K + 1),
                     "180 (K - 1)/(K + 1)", "deg", mine + hand))
    out.append(_pair(w, "crank", h["crank"], d.lengths["crank"], "linkage_sym.synthesis.crank_rocker", "m", hand))
    out.append(_pair(w, "coupler", h["coupler"], d.lengths["coupler"], "linkage_sym.synthesis.crank_rocker", "m",
                     hand))
    out.append(_pair(w, "K", p["solver_K"], fb.K, "the K designed for", "",
                     "the solver's extreme positions (rocker's omega = 0, bisected)"))
    out.append(_pair(w, "swing", math.degrees(p["solver_swing"]), fb.SWING_DEG, "the swing designed for", "deg",
                     "the solver's extreme positions (rocker's omega = 0, bisected)"))
    w = "K design, offset slider-crank"
    ext = "the solver's extreme positions (our numbers: K = 1.4, H = 0.1 m, e = 0.02 m)"
    out.append(_pair(w, "K", p["solver_K_slider"], 1.4, "the K designed for", "", ext))
    out.append(_pair(w, "stroke", p["solver_stroke"], 0.1, "the stroke designed for", "m", ext))
    w = "K design, guide-bar"
    out.append(_pair(w, "K", p["solver_K_guide"], 2.0, "the K designed for", "",
                     "the solver's extreme positions (our numbers: K = 2, AD = 0.4 m)"))

    e9 = fb.example_2_9()
    w = "example 2-9 (force solver)"
    for key in ("F_N", "F_T"):
        out.append(Item(PRINTED, 2, w, f"{key} [kN]", f"{fb.EX_2_9_PRINTED[key]}", e9[key] / 1e3, REPRODUCED,
                        holds=_agree(e9[key], e9[key + "_closed"]),
                        why="G sin(alpha)/sin(alpha + beta) and G sin(beta)/sin(alpha + beta) agree with the solver"))
    ok_kn = all(abs(e9[k] / 1e3 - fb.EX_2_9_PRINTED[k]) <= half_unit(str(fb.EX_2_9_PRINTED[k])) for k in ("F_N", "F_T"))
    out.append(Item(PRINTED, 2, w, "unit of F_N, F_T", "N", "kN", ERRATUM, corrected="kN", holds=ok_kn,
                    why="with G = 2 kN the printed 1.414 and 0.732 are kN (1.41421, 0.73205)"))
    e10 = fb.example_2_10()
    w = "example 2-10 (force solver)"
    for key, text in (("F_NB", "0.133"), ("F_Ox", "0.133"), ("F_Oy", "0.4")):
        out.append(Item(PRINTED, 2, w, f"{key} [kN]", text, e10[key] / 1e3, REPRODUCED))
    out.append(Item(PRINTED, 2, w, "M = F_NB x 400", "53.2", e10["M"], ERRATUM, unit="N m",
                    corrected=f"{e10['M_exact']:.1f}",
                    holds=_agree(e10["M"], e10["M_exact"]) and abs(e10["M_from_rounded_F_NB"] - 53.2) < 1e-9,
                    why="computed from the rounded F_NB = 0.133 kN; F_NB = F_Q tan(alpha) = 0.13333 kN gives "
                        f"{e10['M_exact']:.3f} N m (the solver's driving moment)"))
    return out


# --------------------------------------------------------------------------- [4] chapter3_polygons_exercises.py
def chapter3_polygons_exercises_items():
    import chapter3_polygons_exercises as c3

    out = []
    units = {"v_B2": "m/s", "v_B3": "m/s", "BD": "m", "omega3": "rad/s", "v_B3B2": "m/s", "a_B2": "m/s^2",
             "a_k": "m/s^2", "a_n_B3D": "m/s^2", "a_t_B3D": "m/s^2", "alpha3": "rad/s^2"}
    for k, (ours, closed) in c3.example_3_1().items():
        printed, half = c3.PRINTED_3_1[k]
        text = f"{printed:g}"
        w = "example 3-1, polygons (phi1 = 60 deg)"
        d = abs(abs(ours) - abs(printed))
        agree = _agree(ours, closed)
        if d <= half_unit(text):
            out.append(Item(PRINTED, 4, w, k, text, abs(ours) * math.copysign(1, printed), REPRODUCED,
                            unit=units[k],
                            holds=agree, why="linkage_sym's polygon quantities (and the closed form of example 3-6)"))
        else:
            out.append(Item(PRINTED, 4, w, k, text, abs(ours) * math.copysign(1, printed), ROUNDING, tol=half,
                            unit=units[k],
                            holds=agree,
                            why="read off the book's drawing: half a millimetre at its scale (mu_v = 0.01 (m/s)/mm, "
                                "mu_a = 0.1 (m/s^2)/mm); a quotient of two readings adds their relative errors"))
    for k, (ours, closed) in c3.exercise_3_5().items():
        out.append(_pair("exercise 3-5 (phi1 = 45 deg)", k, ours, closed, "the closed form of the script"))
    r = c3.exercise_3_13()
    w = "exercise 3-13"
    out.append(_pair(w, "(1) v_C at phi = 165 deg by P13", r["centres"]["v_C"], r["solver"]["v_C"],
                     "the solver's velocity", "m/s"))
    out.append(_pair(w, "(2) least speed on BC by P13", r["centres"]["v_E"], r["solver"]["v_E"],
                     "the solver's velocity", "m/s"))
    for i, (a, b) in enumerate(zip(r["roots"], r["closed_roots"]), 1):
        out.append(_pair(w, f"(3) phi with v_C = 0, root {i}", a, b, "the closed form (A, B, C in line)", "deg"))
    r = c3.exercise_3_14()
    out.append(_pair("exercise 3-14 (theta3 = 45 deg)", "v_F / v1 by the centres", r["ratio_centres"],
                     r["ratio_closed"], "3 cot(theta3)"))
    out.append(_pair("exercise 3-14 (theta3 = 45 deg)", "v_F / v1 by the solver", r["ratio_solver"],
                     r["ratio_closed"], "3 cot(theta3)"))
    for phi, vals in c3.exercise_3_23().items():
        for k, (a, b) in vals.items():
            out.append(_pair(f"exercise 3-23 (phi1 = {phi:g} deg)", k, a, b, "the closed form of the script"))
    for (e, phi), vals in c3.exercise_3_24().items():
        for k, (a, b) in vals.items():
            out.append(_pair(f"exercise 3-24 (e = {e:+g} mm, {phi:g} deg)", k, a, b,
                             "the closed form of the script"))
    return out


ADAPTERS = {
    "four_bar_design": four_bar_design_items,
    "chapter3_polygons_exercises": chapter3_polygons_exercises_items,
}
