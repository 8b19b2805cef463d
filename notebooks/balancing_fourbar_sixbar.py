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
# # Balancing the four-bar and Song and Wang's (1992) six-bar
#
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
#
# Song Liqun and Wang Bingle (1992; README, Sources [3]) write the inertia moment of one
# link about the origin as $M_0 = -\sum_{i=1}^4 M_{uvi} D_{uvi}$: mass
# parameters times acceleration parameters. linkage_sym derives that module,
# assembles it over a hinged linkage, and derives the shaking-force balance
# conditions by linearly independent vectors. Here we do it for a four-bar
# (and recover Berkof and Lowen's conditions) and for the six-bar of their
# Fig. 2 (and recover its eqs. 13-15 and 18).

# %%
# %matplotlib inline
import dataclasses

import numpy as np
import sympy as sp

import linkage_sym
from linkage_sym.balancing import with_counterweights
from linkage_sym.balancing.conditions import derive_balance
from linkage_sym.balancing.force_counterweights import force_balancing_counterweights
from linkage_sym.balancing.module import check_identity, link_module
from linkage_sym.model import Effects

# %% [markdown]
# ## The module of one link
# Derived from eqs. 1-4 (not copied from the printed eq. 6, whose first line
# the OCR garbled). The identity $M_0 + \sum M_i D_i \equiv 0$ is proved by
# expansion.

# %%
mod = link_module()
for i, M in enumerate(mod.mass_parameters, 1):
    print(f"M_uv{i} =", sp.factor(M))
print("identity holds:", check_identity(mod))
print("phi'' =", mod.phidd)
assert check_identity(mod)

# %% [markdown]
# ## The four-bar
# The crank-rocker example: its assembled moment (eq. 12 form), the force
# conditions, and the moment left once the force is balanced (eq. 18 form).
# A link's centre of mass in its frame is `xG_<link>, yG_<link>` (Song and Wang's `p, q`;
# `linkage-sym derive --latex` prints it $x^G, y^G$), its length `a_<link>`.

# %%
fourbar = linkage_sym.load_example("crank_rocker")
b4 = derive_balance(fourbar)
print("M_0 =", b4.moment.expression)
print("vanishing (eq. 10):", b4.moment.vanishing)
print("merged (eq. 11):", b4.moment.merged)
for c in b4.force.conditions:
    print(f"{c.name}: {c.expr} = 0")
print("remaining moment:", b4.remaining)

# %% [markdown]
# Berkof and Lowen: with the coupler's vector eliminated, the crank's and the
# rocker's coefficients must vanish. Solving our conditions for the crank's
# and rocker's centres of mass gives their counterweighted positions.

# %%
for s, e in b4.force_solution.items():
    print(s, "=", e)

# %% [markdown]
# Counterweights from these conditions, checked with the force solver.

# %%
inertia_only = Effects(inertia=True, gravity=None, loads=False)
cws = force_balancing_counterweights(fourbar, b4)
balanced = linkage_sym.load_scene(with_counterweights(fourbar, cws))
F0 = linkage_sym.analyze(dataclasses.replace(fourbar, effects=inertia_only)).forces.frame_force
F1 = linkage_sym.analyze(dataclasses.replace(balanced, effects=inertia_only)).forces.frame_force
print(cws)
print("peak shaking force: %.4g N before, %.3g N after" % (np.abs(F0).max(), np.abs(F1).max()))
assert np.abs(F1).max() <= 1e-9 * np.abs(F0).max()

# %% [markdown]
# The shaking force polar diagram and the shaking moment before and after: the force
# vanishes, the moment grows (force balance typically raises it).

# %%
from IPython.display import Math, display  # noqa: E402

from linkage_sym.balancing.series import solver_series  # noqa: E402
from linkage_sym.plotting.balance import shaking_force_polar_figure, shaking_moment_figure  # noqa: E402

series = [solver_series(fourbar, "original"), solver_series(balanced, "force-balanced")]
display(shaking_force_polar_figure(series, "crank-rocker"))
display(shaking_moment_figure(series, "crank-rocker"))

# %% [markdown]
# The force conditions, rendered:

# %%
display(Math(r"\begin{aligned}" + r" \\ ".join(
    f"{sp.latex(c.expr)} &= 0" for c in b4.force.conditions) + r"\end{aligned}"))

# %% [markdown]
# ## Song and Wang's six-bar
# Links 1 = AB (crank), 2 = BC, 3 = DC, 4 = CE, 5 = FE; the pin C of links 2,
# 3 and 4 is two joints C and C2 at one point (the scene format's rule), which
# linkage_sym merges into one pin.

# %%
six = linkage_sym.load_example("song_wang_sixbar")
b6 = derive_balance(six)
print("seconds:", b6.seconds)
print("M_0 =", b6.moment.expression)
print("merged (eq. 11):", b6.moment.merged)
print("force conditions (eq. 14):")
for c in b6.force.conditions:
    print(f"  {c.expr} = 0")
print("moment conditions:")
for c in b6.moment_conditions:
    print(f"  {c.expr} = 0   <- {c.reason}")
print("remaining moment (eq. 18):", b6.remaining)
assert not b6.pin_residuals

# %% [markdown]
# The conditions are *sufficient*. Song and Wang's three designs are simulated in
# `paper_repro/song_wang_designs.py` (and `tests/paper/test_song_wang_designs.py`): the
# two designs built on parallelograms cancel the moment between their change
# points, and the third leaves the residual the paper itself states.
