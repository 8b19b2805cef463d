"""Song and Wang (1992), equation by equation: what the derivation confirms and every erratum.

Song Liqun, Wang Bingle, "Mass and acceleration parameter equations of the inertia moment of
planar hinged linkages, and a module 'assembly' balancing algorithm", J. Chongqing Inst. Archit.
Eng. 14(2), 1992 ([3] of the README's Sources).  Only OCR text of it is available, so "printed"
below means what that text shows; an erratum may be the paper's or the OCR's, and either way a
reader copying the printed formula gets a wrong result.

Each printed equation is written here as a SymPy expression and compared with a derivation:

* the link module (eqs. 1-8) from ``linkage_sym.balancing.link_module``, which derives the
  inertia moment of a link from eqs. 1-3 and reads the mass parameters off it (it does not copy
  eq. 6), and from eqs. 2-3 differentiated here;
* the six-bar (eqs. 9-18) from ``linkage_sym.balancing.shaking_moment`` and ``derive_balance``
  on the shipped ``song_wang_sixbar`` example, whose links are the paper's: 1 = AB (A at the
  origin), 2 = BC, 3 = DC (D on the x-axis), 4 = CE, 5 = FE, with C a pin of 2, 3 and 4.
  linkage_sym merges acceleration parameters that are one quantity (eq. 11) under the name of
  the first; ``ALIASES`` maps the paper's names onto those;
* the designs' kinematic claims from the positions of a parallelogram and a kite, symbolically.

Errata found (each an ``erratum`` row of ``items()``, shown by its derivation):

1. eq. 4: the dots are lost; as printed the numerator is identically zero.  It is
   phi'' = [(y_v'' - y_u'')(x_v - x_u) - (x_v'' - x_u'')(y_v - y_u)] / a^2.
2. eq. 6, first line: "m/a^2 - [...]" is the product m/a^2 [(a - p)^2 + q^2 + k^2].
3. eq. 9: link 3 is written CD (origin C); eqs. 10-12, 16 and 17 use DC (origin D, the fixed
   pivot), which eq. 10's D_DC1 = 0 needs.
4. before eq. 10: B is listed among the points with zero acceleration; B is the crank pin.
   D_AB1 = D_AB2 = D_AB3 = 0 because A is fixed at the origin, whatever B does.
5. eq. 11 omits D_CE1 = D_DC4 (C is the origin of CE and the end of DC), which eq. 12 uses.
6. eq. 13: M_CE3 = m4 q4 / a2; the length of CE is a4.
7. eq. 16: the last term repeats M_CE2 D_CE2; it is M_FE2 D_FE2 (eq. 12's term, untouched by
   q = 0).
8. eq. 17: the term of link 2 has + D_BC2; eq. 8 gives phi2'' = (D_BC1 + D_BC4 - D_BC2)/a2^2 (the
   list after eq. 17 prints it right).
9. design 2: "phi1'' = phi'' = phi3'' = 0" lacks the subscript 2: in the parallelogram ABCD,
   BC keeps the direction of AD, so phi2'' = 0.

Confirmed (``reproduced`` rows): eqs. 3, 5-8 (the identity M_0 = -sum M_i D_i), eq. 6's other
three lines, eqs. 10 and 12, eq. 14 (the mass centre's coefficients of the moving pins B, C, E;
these are linkage_sym's force conditions), eq. 15, eq. 18 (with eq. 14 and q = 0 the moment is
exactly -sum_j m_j (p_j^2 + k_j^2 - a_j p_j) phi_j''), design 1 (every phi'' = 0), design 2's
phi4'' = -phi5'' (the kite is symmetric about DE: phi4 + phi5 = phi3 + const) and design 3's
residual.

Run:  python3 paper_repro/song_wang_errata.py     (needs linkage_sym and SymPy: run from the repository root)
"""

from __future__ import annotations

import functools
import pathlib
import sys

import sympy as sp

HERE = pathlib.Path(__file__).resolve().parent
for _p in (str(HERE), str(HERE.parent)):
    if _p not in sys.path:
        sys.path.insert(0, _p)

import linkage_sym  # noqa: E402
from linkage_sym.balancing import derive_balance, link_module, shaking_moment  # noqa: E402

LINKS = {"1": "AB", "2": "BC", "3": "DC", "4": "CE", "5": "FE"}


def same(a, b) -> bool:
    """``a - b`` simplifies to zero."""
    return sp.simplify(sp.expand(a - b)) == 0


# --------------------------------------------------------------------------- the link module
@functools.lru_cache(maxsize=1)
def module():
    """The link module (eqs. 1-8) derived by linkage_sym, with its symbols."""
    return link_module()


def eq3_check() -> bool:
    """Eq. 3 is eq. 2 differentiated twice (joint coordinates as functions of time)."""
    t = sp.Symbol("t")
    p, q, a = sp.symbols("p q a", positive=True)
    xu, yu, xv, yv = (sp.Function(n)(t) for n in ("x_u", "y_u", "x_v", "y_v"))
    xs = p / a * (xv - xu) - q / a * (yv - yu) + xu  # eq. 2
    ys = p / a * (yv - yu) + q / a * (xv - xu) + yu
    d2 = lambda f: sp.diff(f, t, 2)  # noqa: E731
    printed_x = (1 - p / a) * d2(xu) + q / a * d2(yu) + p / a * d2(xv) - q / a * d2(yv)  # eq. 3
    printed_y = (1 - p / a) * d2(yu) - q / a * d2(xu) + q / a * d2(xv) + p / a * d2(yv)
    return same(d2(xs), printed_x) and same(d2(ys), printed_y)


def eq4():
    """(printed, derived) phi'' of a link: the printed numerator lost its dots."""
    mod = module()
    xu, yu, axu, ayu = mod.u
    xv, yv, axv, ayv = mod.v
    a = mod.a
    printed = ((yv - yu) * (xv - xu) - (xv - xu) * (yv - yu)) / a**2
    corrected = ((ayv - ayu) * (xv - xu) - (axv - axu) * (yv - yu)) / a**2
    return printed, corrected, mod.phidd


def eq6():
    """[(printed, derived)] for M_uv1..M_uv4."""
    mod = module()
    m, a, p, q, k = mod.m, mod.a, mod.p, mod.q, mod.k
    printed = [
        m / a**2 - ((a - p) ** 2 + q**2 + k**2),  # as printed: a difference
        m / a**2 * (a * p - (p**2 + q**2 + k**2)),
        m * q / a,
        m / a**2 * (p**2 + q**2 + k**2),
    ]
    corrected_first = m / a**2 * ((a - p) ** 2 + q**2 + k**2)
    return printed, corrected_first, list(mod.mass_parameters)


def eq8_check() -> bool:
    """Eq. 8, phi'' = (D1 + D4 - D2)/a^2, equals the angular acceleration of eq. 4 (corrected)."""
    mod = module()
    D1, D2, D3, D4 = mod.acceleration_parameters
    _, corrected, _ = eq4()
    return same((D1 + D4 - D2) / mod.a**2, corrected)


def identity_check() -> bool:
    """Eqs. 5-7: M_0 + sum_i M_i D_i == 0 identically (M_0 from eqs. 1-3)."""
    mod = module()
    return sp.expand(mod.M0 + sum(M * D for M, D in zip(mod.mass_parameters, mod.acceleration_parameters))) == 0


# --------------------------------------------------------------------------- the six-bar
@functools.lru_cache(maxsize=1)
def sixbar():
    """linkage_sym's assembly and balance of the paper's six-bar (the shipped example)."""
    scene = linkage_sym.load_example("song_wang_sixbar")
    return scene, shaking_moment(scene), derive_balance(scene)


def symbols_of(expr) -> dict:
    return {s.name: s for s in expr.free_symbols}


@functools.lru_cache(maxsize=1)
def names() -> dict:
    """The paper's parameter names (``M_AB1``, ``D_DC4``) as linkage_sym's symbols (merged per eq. 11)."""
    _, sm, _ = sixbar()
    sy = symbols_of(sm.expression)
    alias = {}
    for kept, equal in sm.merged:
        for e in equal:
            alias[e.lstrip("-")] = -sy[kept] if e.startswith("-") else sy[kept]
    out = {}
    for name in sm.mass_parameters:  # linkage_sym's M_AB_1 is the paper's M_AB1
        out[name[:-2] + name[-1]] = sy.get(name, sp.Symbol(name))
    for uv in LINKS.values():
        for i in range(1, 5):
            lk = f"D_{uv}_{i}"
            out[f"D_{uv}{i}"] = alias.get(lk, sy.get(lk, sp.Integer(0)))  # 0: vanishing (eq. 10)
    return out


def P(expr_text: str) -> sp.Expr:
    """A printed expression in the paper's names (``M_AB4``, ``D_DC4``), as linkage_sym's symbols."""
    return sp.sympify(expr_text, locals=names())


EQ12 = ("(M_AB4 + M_BC1)*D_AB4 + M_BC2*D_BC2 + M_BC3*D_BC3 + (M_BC4 + M_DC4 + M_CE1)*D_DC4 + M_DC2*D_DC2"
        " + M_DC3*D_DC3 + M_CE2*D_CE2 + M_CE3*D_CE3 + (M_CE4 + M_FE4)*D_FE4 + M_FE2*D_FE2 + M_FE3*D_FE3")
EQ16 = ("(M_AB4 + M_BC1)*D_AB4 + M_BC2*D_BC2 + M_DC2*D_DC2 + (M_BC4 + M_DC4 + M_CE1)*D_DC4 + M_CE2*D_CE2"
        " + (M_CE4 + M_FE4)*D_FE4 + M_CE2*D_CE2")
EQ16_CORRECTED = EQ16[: EQ16.rindex("M_CE2*D_CE2")] + "M_FE2*D_FE2"


def eq12():
    """(printed, assembled): M_0 = -[...] of eq. 12 and linkage_sym's assembly."""
    _, sm, _ = sixbar()
    return -P(EQ12), sm.expression


def eq16():
    """(printed, corrected, derived): eq. 12 with M_BC3 = M_CE3 = M_DC3 = M_FE3 = 0 (q = 0)."""
    _, sm, _ = sixbar()
    zero = {P(n): 0 for n in ("M_BC3", "M_CE3", "M_DC3", "M_FE3")}
    return -P(EQ16), -P(EQ16_CORRECTED), sm.expression.xreplace(zero)


def eq17():
    """(printed, corrected, derived) phi2'' in acceleration parameters (eq. 17's term of link 2)."""
    _, sm, b = sixbar()
    a2 = b.model.link_symbols("2")[1]
    printed = (P("D_BC1") + P("D_BC4") + P("D_BC2")) / a2**2
    corrected = (P("D_BC1") + P("D_BC4") - P("D_BC2")) / a2**2
    return printed, corrected, sm.phidd_in_D("2")


def eq17_others() -> bool:
    """Eq. 17's terms of links 1, 3, 4, 5 are eq. 8 with eq. 10's zeros (and the list after it)."""
    _, sm, _ = sixbar()
    printed = {"1": "D_AB4", "3": "D_DC4 - D_DC2", "4": "D_CE1 + D_CE4 - D_CE2", "5": "D_FE4 - D_FE2"}
    _, _, b = sixbar()
    return all(same(P(text) / b.model.link_symbols(link)[1] ** 2, sm.phidd_in_D(link))
               for link, text in printed.items())


def eq13():
    """(printed, derived) M_CE3 = m4 q4 / a (printed a2; link CE's length is a4)."""
    _, sm, _ = sixbar()
    derived = sm.mass_parameters["M_CE_3"]
    sy = symbols_of(derived)
    printed = sy["m_4"] * sy["yG_4"] / sp.Symbol("a_2", positive=True)  # the paper's q_4 is yG_4
    return printed, derived


def eq9_link3():
    """D_1 of link 3 with origin C (eq. 9's CD) and with origin D (eqs. 10-12's DC), D fixed on the x-axis."""
    xC, yC, axC, ayC, xD = sp.symbols("x_C y_C xdd_C ydd_C x_D", real=True)
    from linkage_sym.balancing.module import acceleration_parameters

    fixed_D = (xD, 0, 0, 0)
    moving_C = (xC, yC, axC, ayC)
    return acceleration_parameters(moving_C, fixed_D)[0], acceleration_parameters(fixed_D, moving_C)[0]


def eq10():
    """D_AB1..3 with A fixed at the origin and B moving, and the vanishing list of linkage_sym."""
    from linkage_sym.balancing.module import acceleration_parameters

    B = sp.symbols("x_B y_B xdd_B ydd_B", real=True)
    at_origin = acceleration_parameters((0, 0, 0, 0), B)[:3]
    _, sm, _ = sixbar()
    return at_origin, sm.vanishing


def eq14():
    """(printed rows, derived rows): the coefficients of the moving pins in the mass centre.

    sum_j m_j s_j with s_j = u + (p/a)(v - u) + (q/a) J (v - u) (eq. 2); the real rows are the
    coefficients of x_P in the x sum, the imaginary ones those of y_P in it (J turns by +90 deg).
    """
    m = sp.symbols("m_1:6", positive=True)
    a = sp.symbols("a_1:6", positive=True)
    p = sp.symbols("p_1:6", real=True)
    q = sp.symbols("q_1:6", real=True)
    pts = {n: sp.symbols(f"x_{n} y_{n}", real=True) for n in "ABCDEF"}
    x_total = 0
    for j, (u, v) in enumerate(LINKS.values()):
        (xu, yu), (xv, yv) = pts[u], pts[v]
        x_total += m[j] * (xu + p[j] / a[j] * (xv - xu) - q[j] / a[j] * (yv - yu))
    derived = []
    for pin in "BCE":
        x, y = pts[pin]
        derived.append((sp.expand(x_total).coeff(x), -sp.expand(x_total).coeff(y)))
    m1, m2, m3, m4, m5 = m
    a1, a2, a3, a4, a5 = a
    p1, p2, p3, p4, p5 = p
    q1, q2, q3, q4, q5 = q
    printed = [
        m1 * q1 / a1 - m2 * q2 / a2,
        m4 * q4 / a4 + m5 * q5 / a5,
        m2 * q2 / a2 + m3 * q3 / a3 - m4 * q4 / a4,
        m1 * p1 / a1 + m2 * (a2 - p2) / a2,
        m2 * p2 / a2 + m3 * p3 / a3 + m4 * (a4 - p4) / a4,
        m4 * p4 / a4 + m5 * p5 / a5,
    ]
    # derived rows in the printed order: Im B, Im E, Im C, Re B, Re C, Re E
    rows = [derived[0][1], derived[2][1], derived[1][1], derived[0][0], derived[1][0], derived[2][0]]
    return printed, rows, (m, a, p, q)


def eq14_matches_linkage_sym() -> bool:
    """Eq. 14's six rows are linkage_sym's force conditions of the example (the same expressions)."""
    _, _, b = sixbar()
    printed, _, (m, a, p, q) = eq14()
    got = {c.name: c.expr for c in b.force.conditions}
    sy = {}
    for e in got.values():
        sy.update(symbols_of(e))
    sy = {paper_name(n): s for n, s in sy.items()}  # the paper's p_j, q_j are xG_j, yG_j
    rep = {s: sy[s.name] for group in (m, a, p, q) for s in group if s.name in sy}
    order = ["Im_1", "Im_5", "Im_3", "Re_1", "Re_3", "Re_5"]
    return all(same(pr.xreplace(rep), got[k]) for pr, k in zip(printed, order))


def eq15() -> bool:
    """q2 = q4 = 0 (eq. 13) in eq. 14's first three rows leaves m_j q_j / a_j = 0 for 1, 5, 3."""
    printed, _, (m, a, p, q) = eq14()
    zero = {q[1]: 0, q[3]: 0}
    sols = [sp.solve(row.xreplace(zero), s) for row, s in zip(printed[:3], (q[0], q[4], q[2]))]
    return all(s == [0] for s in sols)


def eq18():
    """(printed, derived): the moment left by eqs. 13-15 and force balance (derive_balance's)."""
    _, _, b = sixbar()
    model = b.model
    printed = 0
    for link in "12345":
        m, a, p, q, k = model.link_symbols(link)
        printed += -m * (p**2 + k**2 - a * p) * model.phidd(link)
    return printed, b.remaining, b.pin_residuals


def designs():
    """The designs' kinematic claims, from symbolic positions (crank angle th, D at the origin).

    Parallelogram ABCD: B = A + a1 e^{i th}, C = B + (D - A): C - B is constant, so phi2'' = 0,
    and C - D = B - A, so phi3 = th.  Design 1 adds the parallelogram DCEF: E - C = F - D
    (phi4 const) and E - F = C - D (phi5 = th).  Design 2's kite DCEF (DC = DF, CE = FE, F on
    the x-axis) has E on the bisector of CDF: E = D + r e^{i th/2}; then
    (E - C)(E - F) e^{-i th} is real, i.e. phi4 + phi5 = th (mod pi): phi4'' = -phi5''.
    Returns a dict of verdicts.
    """
    th, a1, r, AD = sp.symbols("theta a_1 r AD", positive=True)
    I = sp.I
    A = -AD  # D at the origin, A on the x-axis
    B = A + a1 * sp.exp(I * th)
    C = B + (0 - A)
    phi2_const = sp.simplify(sp.diff(C - B, th)) == 0
    phi3_is_th = sp.simplify((C - 0) - a1 * sp.exp(I * th)) == 0
    E = r * sp.exp(I * th / 2)
    F = a1
    prod = sp.expand((E - C) * (E - F) * sp.exp(-I * th))
    kite_sym = sp.simplify(sp.im(prod.rewrite(sp.cos))) == 0
    return {"phi2'' = 0 (parallelogram ABCD)": phi2_const, "phi3 = theta": phi3_is_th,
            "phi4 + phi5 = theta (kite)": kite_sym}


# --------------------------------------------------------------------------- items
def paper_name(name: str) -> str:
    """linkage_sym's ``D_AB_4`` as the paper's ``D_AB4``, its centre of mass ``xG_4, yG_4`` as
    the paper's ``p_4, q_4``."""
    head, _, i = name.rpartition("_")
    if head in ("xG", "yG"):
        return f"{'p' if head == 'xG' else 'q'}_{i}"
    return head + i if i.isdigit() and head[:2] in ("D_", "M_") else name


def _s(e) -> str:
    if isinstance(e, sp.Basic):
        e = e.xreplace({s: sp.Symbol(paper_name(s.name)) for s in e.free_symbols})
    return sp.sstr(e)


def items():
    """Every checked equation of Song and Wang 1992 as a row (paper_repro/items.py)."""
    from items import ERRATUM, PRINTED, REPRODUCED, Item

    out = []
    W = "eq. "

    def ok(where, name, printed, computed, holds, why=""):
        out.append(Item(PRINTED, 3, where, name, printed, computed, REPRODUCED, holds=bool(holds), why=why))

    def err(where, name, printed, computed, corrected, holds, why):
        out.append(Item(PRINTED, 3, where, name, printed, computed, ERRATUM, corrected=corrected, holds=bool(holds), why=why))

    ok(W + "3", "centre-of-mass acceleration", "eq. 2 differentiated twice", "same", eq3_check(),
       "SymPy: eq. 2 with joint coordinates as functions of time, differentiated twice")
    pr4, corr4, mod_phidd = eq4()
    err(W + "4", "phi'' of a link", "[(y_v - y_u)(x_v - x_u) - (x_v - x_u)(y_v - y_u)]/a^2", _s(sp.simplify(pr4)),
        "[(y_v'' - y_u'')(x_v - x_u) - (x_v'' - x_u'')(y_v - y_u)]/a^2",
        sp.simplify(pr4) == 0 and same(corr4, mod_phidd) and mod_phidd != 0,
        "as printed the numerator is identically 0 (the accelerations' dots are lost); the corrected form is "
        "the derivative of phi' = (dx dy' - dy dx')/a^2 for a rigid link (linkage_sym.balancing.link_module)")
    pr6, corr6, der6 = eq6()
    err(W + "6", "M_uv1", "m/a^2 - [(a - p)^2 + q^2 + k^2]", _s(der6[0]), "m/a^2 [(a - p)^2 + q^2 + k^2]",
        not same(pr6[0], der6[0]) and same(corr6, der6[0]),
        "the coefficient of x_u y_u'' in -M_0 (eqs. 1-3): a product, not a difference")
    texts = ("m/a^2 [a p - (p^2 + q^2 + k^2)]", "m q / a", "m/a^2 (p^2 + q^2 + k^2)")
    for i in (1, 2, 3):
        ok(W + "6", f"M_uv{i + 1}", texts[i - 1], _s(der6[i]), same(pr6[i], der6[i]),
           "the coefficients of -M_0 derived from eqs. 1-3 (linkage_sym.balancing.link_module)")
    ok(W + "5-7", "M_0 = -sum M_uvi D_uvi", "identity", "identity", identity_check(),
       "M_0 of eq. 1 minus the module expands to 0")
    ok(W + "8", "phi'' = (D_uv1 + D_uv4 - D_uv2)/a^2", "eq. 8", "eq. 4 corrected", eq8_check())
    cd, dc = eq9_link3()
    err(W + "9", "link 3's module", "M_CD1 D_CD1 + ... + M_CD4 D_CD4", f"D_CD1 = {_s(cd)}",
        "M_DC1 D_DC1 + ... + M_DC4 D_DC4 (origin D, as eqs. 10-12, 16, 17)", cd != 0 and dc == 0,
        f"with origin C, D_CD1 = {_s(cd)} does not vanish; with origin D (fixed on the x-axis) D_DC1 = 0, as eq. 10 "
        "has it")
    at_origin, vanishing = eq10()
    err(W + "10", "fixed points", "x_A'', y_A'', x_B'', y_B'', x_D'', y_D'', x_F'', y_F'' all zero",
        "A, D, F fixed; B moves", "x_A'', y_A'', x_D'', y_D'', x_F'', y_F'' (A, D, F are the fixed pivots)",
        all(d == 0 for d in at_origin),
        "B is the crank pin, its acceleration is a1 omega^2 toward A; D_AB1 = D_AB2 = D_AB3 = 0 hold because A is "
        "fixed at the origin, with B's acceleration left symbolic")
    ok(W + "10", "vanishing parameters", "D_AB1, D_AB2, D_AB3, D_DC1, D_FE1",
       ", ".join(paper_name(v) for v in vanishing),
       set(vanishing) == {"D_AB_1", "D_AB_2", "D_AB_3", "D_DC_1", "D_FE_1"}, "linkage_sym.balancing.shaking_moment")
    _, sm, _ = sixbar()
    merged = {k: set(v) for k, v in sm.merged}
    err(W + "11", "merged parameters", "D_AB4 = D_BC1, D_BC4 = D_DC4, D_CE4 = D_FE4",
        "; ".join(" = ".join(paper_name(n) for n in (k, *sorted(v))) for k, v in merged.items()),
        "D_AB4 = D_BC1, D_BC4 = D_DC4 = D_CE1, D_CE4 = D_FE4",
        merged.get("D_BC_4") == {"D_DC_4", "D_CE_1"},
        "an omission: C is the origin of CE and the end of DC, so D_CE1 = D_DC4; eq. 12 uses it, (M_BC4 + M_DC4 + "
        "M_CE1) D_DC4")
    pr12, der12 = eq12()
    ok(W + "12", "assembled moment", "M_0 = -[(M_AB4 + M_BC1) D_AB4 + ... + M_FE3 D_FE3]", "same",
       same(pr12, der12), "linkage_sym.balancing.shaking_moment: modules summed (eq. 9) and merged (eqs. 10-11)")
    pr13, der13 = eq13()
    err(W + "13", "M_CE3", "m4 q4 / a2", _s(der13), "m4 q4 / a4", not same(pr13, der13),
        "eq. 6's M_uv3 = m q / a for link 4 = CE, of length a4 (a2 is BC)")
    pr14, der14, _ = eq14()
    ok(W + "14", "force balance (ref. [1])", "six rows", "same", all(same(x, y) for x, y in zip(pr14, der14))
       and eq14_matches_linkage_sym(),
       "the coefficients of x_B, x_C, x_E (p rows) and y_B, y_C, y_E (q rows) in the mass centre sum m_j s_j; "
       "they are linkage_sym.balancing.force_balance's conditions of the example")
    ok(W + "15", "q1 = q3 = q5 = 0", "q1 = q3 = q5 = 0", "q1 = q3 = q5 = 0", eq15(),
       "eq. 13's q2 = q4 = 0 in eq. 14's first three rows")
    pr16, corr16, der16 = eq16()
    err(W + "16", "moment with q = 0", "... + (M_CE4 + M_FE4) D_FE4 + M_CE2 D_CE2]", _s(sp.expand(pr16 - der16)),
        "... + (M_CE4 + M_FE4) D_FE4 + M_FE2 D_FE2]", not same(pr16, der16) and same(corr16, der16),
        "the last term repeats M_CE2 D_CE2; eq. 12 with M_BC3 = M_CE3 = M_DC3 = M_FE3 = 0 keeps M_FE2 D_FE2 "
        "(computed: printed - derived)")
    pr17, corr17, der17 = eq17()
    err(W + "17", "link 2's term", "m2 (p2^2 + k2^2 - a2 p2) (D_BC1 + D_BC4 + D_BC2)/a2^2", _s(der17),
        "m2 (p2^2 + k2^2 - a2 p2) (D_BC1 + D_BC4 - D_BC2)/a2^2", not same(pr17, der17) and same(corr17, der17),
        "eq. 8 for link 2 (the list of phi'' after eq. 17 prints it right; computed in linkage_sym's merged names)")
    ok(W + "17", "links 1, 3, 4, 5", "D_AB4/a1^2, (D_DC4 - D_DC2)/a3^2, ...", "same", eq17_others(),
       "eq. 8 with eq. 10's zeros")
    pr18, der18, residual = eq18()
    ok(W + "18", "M_0 = -sum m_j (p_j^2 + k_j^2 - a_j p_j) phi_j''", "eq. 18", "same",
       same(pr18, der18) and not residual,
       "linkage_sym.balancing.derive_balance: with eq. 14 and q = 0 every pin's mass share cancels")
    kin = designs()
    ok("design 1", "phi1'' = ... = phi5'' = 0", "all zero", "all zero",
       kin["phi2'' = 0 (parallelogram ABCD)"] and kin["phi3 = theta"],
       "two parallelograms: BC and CE keep their directions, DC and FE turn with the crank")
    err("design 2", "zero angular accelerations", "phi1'' = phi'' = phi3'' = 0", "phi1'' = phi2'' = phi3'' = 0",
        "phi1'' = phi2'' = phi3'' = 0", kin["phi2'' = 0 (parallelogram ABCD)"] and kin["phi3 = theta"],
        "the subscript 2 is lost: BC keeps the direction of AD in the parallelogram ABCD")
    ok("design 2", "phi4'' = -phi5''", "phi4'' = -phi5''", "phi4 + phi5 = phi3 + const",
       kin["phi4 + phi5 = theta (kite)"], "the kite DCEF is symmetric about DE, whose direction is phi3/2 + const")
    _, _, b = sixbar()
    K = {j: sp.factor(b.moment.X[j].xreplace({b.model.link_symbols(j)[3]: 0})) for j in "12345"}  # m (p^2+k^2-ap)
    m2, a2, p2, q2, k2 = b.model.link_symbols("2")
    ok("design 3", "a2 = (p2^2 + k2^2)/p2 makes K2 = 0", "K2 = 0", "K2 = 0",
       sp.simplify(K["2"].xreplace({a2: (p2**2 + k2**2) / p2})) == 0,
       "then eq. 18 leaves -(m3 K3 phi3'' + m5 K5 phi5'') with phi1'' = 0 and the same for link 4")
    return out


def report() -> str:
    from items import table

    return table(items())


if __name__ == "__main__":
    print(report())
