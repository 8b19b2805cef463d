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
# # The crank-rocker and the offset slider-crank, derived with SymPy
#
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
#
# `linkage_sym.derive` writes each mechanism's closed vector loop in the
# kinematics textbook chapter's complex form (README, Sources [4]) (eq. 3-8), its projections (3-9), the explicit dyad
# positions and the velocity equation $A\,\omega = B\,\dot q$ (3-28).
# `linkage_sym.compile_mechanism` lambdifies them; we check the generated
# functions against the numeric dyad solver `linkage_sym.analyze`.

# %%
# %matplotlib inline
import numpy as np
import sympy as sp

import linkage_sym
from linkage_sym.symbolic.latex import latex_document

SCENES = ("crank_rocker", "slider_crank_offset")
TOL = 1e-10  # relative to each quantity's largest magnitude over the sweep

# %%
for name in SCENES:
    eqs = linkage_sym.derive(linkage_sym.load_example(name))
    print(f"=== {name}: coordinates {eqs.x}, drivers {eqs.q}")
    for joint, loop in eqs.loops:
        print(f"loop closed at {joint} (eq. 3-8):")
        sp.pprint(sp.Eq(loop.complex(), 0), use_unicode=False, wrap_line=False)
        print("projections (eq. 3-9):")
        sp.pprint(sp.Eq(loop.x, 0), use_unicode=False, wrap_line=False)
        sp.pprint(sp.Eq(loop.y, 0), use_unicode=False, wrap_line=False)

# %% [markdown]
# Closed forms, solving order (the slider-crank's RRP dyad first fixes the
# slider's constant angle; $\sigma_i = \pm 1$ picks the assembly mode):

# %%
for name in SCENES:
    eqs = linkage_sym.derive(linkage_sym.load_example(name))
    print(f"=== {name}")
    for sym, expr in eqs.closed_forms:
        print(f"{sym} = {expr}")

# %% [markdown]
# As a textbook prints them (`linkage-sym derive --latex`): each dyad's distance $d$
# between its outer joints, the projection $a$ and the half-chord $h$ of its inner joint
# named once, then the angles.

# %%
from IPython.display import Math, display  # noqa: E402

from linkage_sym.symbolic.latex_notation import Namer  # noqa: E402

eqs = linkage_sym.derive(linkage_sym.load_example("crank_rocker"))
nm = Namer(eqs)
display(Math(r"\begin{aligned}" + r" \\ ".join(
    f"{nm(s)} &= {nm(e)}" for s, e in eqs.position_steps) + r"\end{aligned}"))

# %% [markdown]
# The velocity equation as matrices, $A\,\dot x = B\,\dot q$, and its LaTeX
# (the full document fragment is `latex_document(eqs)`, or
# `linkage-sym derive SCENE.json --latex`):

# %%
for name in SCENES:
    eqs = linkage_sym.derive(linkage_sym.load_example(name))
    velocity = sp.Eq(sp.MatMul(eqs.A, sp.Matrix(eqs.xd)), sp.MatMul(eqs.B, sp.Matrix(eqs.qd)))
    print(f"=== {name}")
    sp.pprint(velocity, use_unicode=False, wrap_line=False)
tex = latex_document(eqs)
start = tex.index(r"\paragraph{Velocities.}")
print(tex[start : tex.index(r"\paragraph{Accelerations.}")])

# %% [markdown]
# Lambdified (`compile_mechanism`) against the numeric solver (`analyze`):
# link rotations, angular velocities and accelerations and the driving
# effort, as the largest difference relative to each quantity's largest
# magnitude.

# %%
for name in SCENES:
    scene = linkage_sym.load_example(name)
    cm = linkage_sym.compile_mechanism(scene)
    sym, num = cm.run(), linkage_sym.analyze(scene)
    assert sym.ok.all() and num.ok.all()
    worst = {}
    for link in num.links:
        for q in ("rotation", "omega", "alpha"):
            a, b = getattr(sym.links[link], q), getattr(num.links[link], q)
            worst[f"{link}.{q}"] = np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)
    for joint, effort in num.forces.driving.items():
        a = sym.forces.driving[joint]
        worst[f"driving {joint}"] = np.max(np.abs(a - effort)) / np.max(np.abs(effort))
    print(f"=== {name}: {num.n_steps} steps")
    for k, v in worst.items():
        print(f"  {k:32s} {v:.1e}")
        assert v < TOL, k  # (a quantity identically 0, the slider's rotation, gives 0/tiny = 0)

# %% [markdown]
# The two methods over the crank-rocker's turn: the rocker's angular velocity from the
# generated code and from the dyad solver, and their difference (rounding).

# %%
from linkage_sym.plotting.style import new_figure  # noqa: E402

scene = linkage_sym.load_example("crank_rocker")
sym, num = linkage_sym.compile_mechanism(scene).run(), linkage_sym.analyze(scene)
q = np.degrees(num.drivers["A"]["q"])
fig = new_figure(7, 4.5)
ax1, ax2 = fig.subplots(2, 1, sharex=True)
ax1.plot(q, num.links["rocker"].omega, label="dyad solver")
ax1.plot(q, sym.links["rocker"].omega, "--", label="generated (SymPy)")
ax1.set_ylabel("rocker omega (rad/s)")
ax1.legend()
ax2.semilogy(q, np.abs(sym.links["rocker"].omega - num.links["rocker"].omega) + 1e-18)
ax2.set_ylabel("|difference| (rad/s)")
ax2.set_xlabel("crank angle (deg)")
display(fig)

# %% [markdown]
# The generated functions carry their argument order in their docstring:

# %%
print(cm.functions["rates"].__doc__)
