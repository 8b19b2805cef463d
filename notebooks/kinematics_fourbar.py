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
# # Kinematics of a crank-rocker, checked two ways
#
# Kept as text (jupytext py:percent); `tests/test_notebooks.py` executes it.
# Open it in Jupyter with `jupytext --to notebook kinematics_fourbar.py`.
#
# We solve the crank-rocker of the scene-format spec with linkage_sym's dyad
# solver, then check the rocker's angular velocity against seed 003's
# eq. 3-13, written out here by hand.

# %%
import numpy as np

import linkage_sym
from linkage_sym.structure import structure_report

scene = linkage_sym.load_example("crank_rocker")
print(structure_report(scene, linkage_sym.decompose(scene)))
res = linkage_sym.analyze(scene)

# %% [markdown]
# Absolute link angles: the angle in the assembly configuration plus the
# rotation from it.  Then eq. 3-13:
# $\omega_3 = \omega_1 l_1 \sin(\theta_1-\theta_2) / (l_3 \sin(\theta_3-\theta_2))$.

# %%
A, B, C, D = (np.array(scene.joint(n).at) for n in "ABCD")
l1, l3 = np.linalg.norm(B - A), np.linalg.norm(C - D)
th1 = res.drivers["A"]["q"]
th2 = np.arctan2(*(C - B)[::-1]) + res.links["coupler"].rotation
th3 = np.arctan2(*(C - D)[::-1]) + res.links["rocker"].rotation
w1 = res.drivers["A"]["qd"]
w3 = w1 * l1 * np.sin(th1 - th2) / (l3 * np.sin(th3 - th2))
err = np.max(np.abs(w3 - res.links["rocker"].omega)) / np.max(np.abs(w3))
print(f"max relative difference from eq. 3-13: {err:.1e}")
assert err < 1e-12

# %% [markdown]
# The rocker swings between two limit positions; the crank angles at which
# its angular velocity changes sign are the extreme positions.

# %%
w = res.links["rocker"].omega
flips = np.flatnonzero(np.sign(w[1:]) != np.sign(w[:-1]))
print("rocker reverses near crank angles (deg):", np.round(np.degrees(th1[flips]), 1))
