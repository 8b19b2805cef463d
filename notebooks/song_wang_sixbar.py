# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Song and Wang's six-bar, derived step by step, with the errata
#
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
#
# Song Liqun and Wang Bingle, *Mass and acceleration parameter equations of the inertia moment
# of planar hinged linkages, and a module "assembly" balancing algorithm*, Journal of Chongqing
# Institute of Architecture and Engineering 14(2), 1992 (README, Sources [3]). The paper builds
# the shaking moment of a hinged linkage from one *module* per link and balances its six-bar
# (Fig. 2, missing from the text we have). We follow it: the module (eqs. 1–8), the assembly
# (eqs. 9–12), the conditions (eqs. 13–15), the moment that is left (eqs. 16–18) and the three
# designs. Each printed equation is set beside the derivation; where they differ, the printed
# one is an erratum (ours to show, by the derivation). `python -m paper_repro` lists the same
# checks as rows.

# %%
# %matplotlib inline
import sys
from pathlib import Path

import numpy as np
import sympy as sp
from IPython.display import Math, display

import linkage_sym
from linkage_sym.balancing import link_module, shaking_moment, solver_series
from linkage_sym.plotting.balance import shaking_force_polar_figure, shaking_moment_figure

sys.path.insert(0, str(Path.cwd().parent / "paper_repro"))
import song_wang_designs as designs  # noqa: E402  (paper_repro/song_wang_designs.py)
import song_wang_errata as errata  # noqa: E402  (paper_repro/song_wang_errata.py)


def latex(expr):
    """LaTeX with the accelerations' symbols as dots: xdd_u as x''_u, phidd_2 as phi''_2 (xG_2 as x^G_2)."""
    names = {}
    for s in expr.free_symbols:
        head, _, sub = s.name.partition("_")
        if head in ("xdd", "ydd"):
            names[s] = rf"\ddot {head[0]}_{{{sub}}}"
        elif head == "phidd":
            names[s] = rf"\ddot\varphi_{{{sub}}}"
        elif head in ("xG", "yG"):  # the centre of mass in the link frame
            names[s] = rf"{head[0]}^{{G}}_{{{sub}}}"
    return sp.latex(expr, symbol_names=names)


def show(lhs, rhs, note=""):
    """Render lhs = rhs (SymPy or LaTeX text), with a note in words."""
    r = rhs if isinstance(rhs, str) else latex(rhs)
    display(Math(f"{lhs} = {r}" + (rf"\qquad\text{{{note}}}" if note else "")))


def paper(expr):
    """linkage_sym's symbols M_AB_1, D_AB_4, xG_2, yG_2 under the paper's names M_AB1, D_AB4,
    p_2, q_2 (linkage_sym names the centre of mass xG, yG: its q is a driver coordinate)."""
    return expr.xreplace({s: sp.Symbol(errata.paper_name(s.name)) for s in expr.free_symbols})


# %% [markdown]
# ## 1. The module of one link (eqs. 1–8)
# A link from joint $u$ to joint $v$ (length $a$), centre of mass at $(p, q)$ in the frame with
# origin $u$ and $x$-axis toward $v$, mass $m$, radius of gyration $k$. Its inertia moment about
# the origin is eq. 1, $M_0 = -m(x_s \ddot y_s - y_s \ddot x_s + k^2 \ddot\varphi)$, with the
# centre of mass of eq. 2. Differentiating eq. 2 twice gives eq. 3 as printed:

# %%
print("eq. 3 is eq. 2 differentiated twice:", errata.eq3_check())
assert errata.eq3_check()

# %% [markdown]
# **Eq. 4, erratum.** The text prints the angular acceleration with the dots of the
# accelerations lost; as printed, its numerator cancels to zero. The derivative of
# $\dot\varphi = (\Delta x\, \Delta\dot y - \Delta y\, \Delta\dot x)/a^2$ of a rigid link is the
# corrected form (the velocity products cancel):

# %%
printed4, corrected4, derived4 = errata.eq4()
show(r"\ddot\varphi_{\text{printed}}", sp.simplify(printed4), "(identically zero)")
show(r"\ddot\varphi", corrected4)
assert sp.simplify(printed4) == 0 and errata.same(corrected4, derived4)

# %% [markdown]
# Substituting eqs. 2–4 into eq. 1 gives the module, eq. 5:
# $M_0 = -\sum_{i=1}^4 M_{uvi} D_{uvi}$, with *mass parameters* $M_{uvi}$ and *acceleration
# parameters* $D_{uvi}$ (eq. 7). linkage_sym derives $M_0$ and reads the mass parameters off it as
# the coefficients of the products of a position and an acceleration.
#
# **Eq. 6, erratum in its first line.** The text prints $M_{uv1} = m/a^2 - [\dots]$; the derivation
# gives the product $m/a^2\,[(a-p)^2 + q^2 + k^2]$. The other three lines are right.

# %%
mod = link_module()
printed6, corrected6, derived6 = errata.eq6()
for i, (p_, d_) in enumerate(zip(printed6, derived6), 1):
    verdict = "as printed" if errata.same(p_, d_) else "printed differs: erratum"
    show(f"M_{{uv{i}}}", sp.factor(d_), verdict)
show(r"M_{uv1,\text{printed}}", printed6[0])
for i, D in enumerate(mod.acceleration_parameters, 1):
    show(f"D_{{uv{i}}}", D, "eq. 7")
print("M_0 + sum M_i D_i == 0 identically:", errata.identity_check())
print("eq. 8, phi'' = (D1 + D4 - D2)/a^2:", errata.eq8_check())
assert errata.identity_check() and errata.eq8_check() and not errata.same(printed6[0], derived6[0])

# %% [markdown]
# ## 2. Assembly for the six-bar (eqs. 9–12)
# Links 1 = AB (crank, A at the origin), 2 = BC, 3 = DC (D on the $x$-axis), 4 = CE, 5 = FE; C is a
# pin of links 2, 3 and 4 (in the scene format: two joints C and C2 at one point, merged into one
# pin). The shipped example `song_wang_sixbar` has this numbering.
#
# **Eq. 9, erratum.** The text writes link 3's module as $M_{CD i} D_{CD i}$ (origin C); eqs. 10–12,
# 16 and 17 use DC (origin D, the fixed pivot), and only that makes eq. 10's $D_{DC1} = 0$ true:

# %%
scene = linkage_sym.load_example("song_wang_sixbar")
sm = shaking_moment(scene)
d_cd1, d_dc1 = errata.eq9_link3()
show(r"D_{CD1}", d_cd1, "origin C: not zero")
show(r"D_{DC1}", d_dc1, "origin D, fixed on the x-axis")

# %% [markdown]
# **Eq. 10, erratum in its text.** The paper lists $\ddot x_B, \ddot y_B$ among the zero
# accelerations; B is the crank pin. $D_{AB1} = D_{AB2} = D_{AB3} = 0$ all the same, because A is
# fixed at the origin, whatever B does:

# %%
at_origin, vanishing = errata.eq10()
print("D_AB1..3 with A fixed at the origin and B moving:", at_origin)
print("vanishing parameters (linkage_sym):", ", ".join(errata.paper_name(v) for v in vanishing))

# %% [markdown]
# **Eq. 11, an omission.** A parameter of one link that is the same quantity as one of another
# (at a common pin) is merged. The text lists $D_{AB4} = D_{BC1}$, $D_{BC4} = D_{DC4}$,
# $D_{CE4} = D_{FE4}$ but not $D_{CE1} = D_{DC4}$ (C is the origin of CE), which eq. 12 uses:

# %%
for kept, equal in sm.merged:
    print(" = ".join(errata.paper_name(n) for n in (kept, *equal)))

# %% [markdown]
# The assembled moment, eq. 12 (linkage_sym names a merged parameter after its first member, so
# the paper's $D_{DC4}$ is $D_{BC4}$ and its $D_{FE4}$ is $D_{CE4}$ here), equal to the printed one:

# %%
printed12, derived12 = errata.eq12()
show("M_0", paper(derived12))
print("equal to the printed eq. 12:", errata.same(printed12, derived12))
assert errata.same(printed12, derived12)

# %% [markdown]
# ## 3. The conditions (eqs. 13–15)
# $D_{BC3}$ and $D_{CE3}$ do not vanish (both pins of BC and of CE move), so their mass parameters
# must: $M_{BC3} = m_2 q_2/a_2 = 0$ and $M_{CE3} = m_4 q_4 / a_4 = 0$, i.e. $q_2 = q_4 = 0$ (eq. 13).
#
# **Eq. 13, erratum.** The text prints $M_{CE3} = m_4 q_4 / a_2$; link 4 = CE has the length $a_4$:

# %%
printed13, derived13 = errata.eq13()
show(r"M_{CE3,\text{printed}}", printed13)
show(r"M_{CE3}", derived13)

# %% [markdown]
# The shaking-force conditions (eq. 14, from the paper's ref. [1]) say that the mass centre
# $\sum_j m_j s_j$ does not move: the coefficients of the moving pins B, C, E vanish. Derived here
# from eq. 2, and equal to linkage_sym's force conditions (by linearly independent vectors):

# %%
printed14, derived14, _ = errata.eq14()
display(Math(r"\begin{aligned}" + r" \\ ".join(f"{latex(r)} &= 0" for r in derived14) + r"\end{aligned}"))
print("as printed (eq. 14):", all(errata.same(a, b) for a, b in zip(printed14, derived14)))
print("linkage_sym's conditions are these rows:", errata.eq14_matches_linkage_sym())
print("eq. 15 (q1 = q3 = q5 = 0 from eq. 13 and the first three rows):", errata.eq15())
assert errata.eq14_matches_linkage_sym() and errata.eq15()

# %% [markdown]
# ## 4. The moment left (eqs. 16–18)
# **Eq. 16, erratum.** With $q = 0$ the terms $M_{uv3} D_{uv3}$ drop out of eq. 12. The text's last
# term repeats $M_{CE2} D_{CE2}$, where eq. 12's $M_{FE2} D_{FE2}$ belongs (printed minus derived):

# %%
printed16, corrected16, derived16 = errata.eq16()
show(r"M_{0,\text{printed}} - M_0", paper(sp.expand(printed16 - derived16)))
print("corrected eq. 16 equals the derivation:", errata.same(corrected16, derived16))

# %% [markdown]
# **Eq. 17, erratum.** Substituting eq. 6 and the force conditions regroups eq. 16 into one term
# per link, $m_j (p_j^2 + k_j^2 - a_j p_j)$ times an acceleration-parameter combination over
# $a_j^2$. For link 2 the text prints $+D_{BC2}$; eq. 8 gives $-D_{BC2}$ (the list printed after
# eq. 17 has it right):

# %%
printed17, corrected17, derived17 = errata.eq17()
show(r"\ddot\varphi_{2,\text{printed}}", paper(printed17))
show(r"\ddot\varphi_2", paper(derived17), "eq. 8")
print("links 1, 3, 4, 5 as printed:", errata.eq17_others())

# %% [markdown]
# Each combination is the link's $\ddot\varphi_j$ (eq. 8), so the moment left by force balance and
# $q = 0$ is eq. 18. linkage_sym's `derive_balance` finds every pin's mass share cancelled by
# eq. 14 and this moment exactly:

# %%
printed18, derived18, residual = errata.eq18()
show("M_0", derived18)
print("equal to the printed eq. 18:", errata.same(printed18, derived18), "; pin shares left:", residual or "none")
assert errata.same(printed18, derived18) and not residual

# %% [markdown]
# ## 5. The designs
# Eq. 18 vanishes when each $m_j(p_j^2 + k_j^2 - a_j p_j)\ddot\varphi_j$ does, or when they cancel:
#
# 1. $a_1 = a_3 = a_5$, $a_2 = AD$, $a_4 = DF$: two parallelograms, every $\ddot\varphi_j = 0$ at
#    constant crank speed;
# 2. $a_1 = a_3 = DF$, $a_2 = AD$, $a_4 = a_5$: a parallelogram and a kite,
#    $\ddot\varphi_1 = \ddot\varphi_2 = \ddot\varphi_3 = 0$ and $\ddot\varphi_4 = -\ddot\varphi_5$, so
#    $m_4 K_4 = m_5 K_5$ ($K = p^2 + k^2 - a p$) cancels the rest;
# 3. $a_2 = (p_2^2 + k_2^2)/p_2$, $a_4 = (p_4^2 + k_4^2)/p_4$: $K_2 = K_4 = 0$, leaving
#    $-(m_3 K_3 \ddot\varphi_3 + m_5 K_5 \ddot\varphi_5)$.
#
# **Design 2's text, erratum.** It prints $\ddot\varphi_1 = \ddot\varphi = \ddot\varphi_3 = 0$; the
# subscript 2 is lost (BC keeps the direction of AD in the parallelogram ABCD). The kinematic claims,
# from symbolic positions of the parallelogram and the kite:

# %%
for claim, ok in errata.designs().items():
    print(f"{claim}: {ok}")
assert all(errata.designs().values())

# %% [markdown]
# The paper gives no dimensions; `paper_repro/song_wang_designs.py` chooses them (uniform bars of
# 2 kg/m with counterweight discs, sized from eq. 14 and each design's condition). Simulated with
# the force solver over a half-turn between the parallelograms' change points, inertia only, the
# shaking moment of each balanced design beside its unbalanced reference (same lengths, bare links):

# %%
runs = {}
for name in ("1", "2", "3"):
    d = designs.designs()[name]
    ref = solver_series(linkage_sym.load_scene(designs.scene_dict(d, "first", balanced=False)),
                        f"design {name}, unbalanced")
    bal = solver_series(linkage_sym.load_scene(designs.scene_dict(d, "first")), f"design {name}, balanced")
    runs[name] = (ref, bal)
    print(f"design {name}: peak |M_0| {np.nanmax(np.abs(ref.moment)):.4f} N m unbalanced, "
          f"{np.nanmax(np.abs(bal.moment)):.3g} N m balanced; peak |F| {np.nanmax(np.abs(bal.force)):.2g} N")
display(shaking_moment_figure(list(runs["2"]), "Song and Wang's design 2 (parallelogram and kite)"))
display(shaking_moment_figure(list(runs["3"]), "Song and Wang's design 3: the residual it states"))

# %% [markdown]
# Designs 1 and 2 cancel the moment to rounding; design 3 leaves the residual the paper states,
# which with these choices is larger than the unbalanced moment (the conjugate-point masses on
# links 2 and 4 enlarge the counterweights of the rockers 3 and 5, and with them $K_3$ and $K_5$).
# Its shaking force is balanced all the same (eq. 14):

# %%
display(shaking_force_polar_figure(list(runs["3"]), "Song and Wang's design 3"))
r1, r2 = (np.nanmax(np.abs(runs[n][1].moment)) / np.nanmax(np.abs(runs[n][0].moment)) for n in ("1", "2"))
assert r1 < 1e-8 and r2 < 1e-8
