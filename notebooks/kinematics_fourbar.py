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
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
# Open it in Jupyter with `jupytext --to notebook kinematics_fourbar.py`.
#
# We solve the crank-rocker of the scene-format spec with linkage_sym's dyad
# solver, then check the rocker's angular velocity against the kinematics textbook chapter's (README, Sources [4])
# eq. 3-13, written out here by hand.

# %%
# %matplotlib inline
import numpy as np

import linkage_sym
from linkage_sym.structure import structure_report

scene = linkage_sym.load_example("crank_rocker")
print(structure_report(scene, linkage_sym.decompose(scene)))
res = linkage_sym.analyze(scene)

# %% [markdown]
# The motion at a glance: the joints' paths with the coupler curve of the traced point P,
# and the velocities against the crank angle (the textbook's motion diagrams).

# %%
from IPython.display import display  # noqa: E402

from linkage_sym.plotting.motion import motion_figure  # noqa: E402
from linkage_sym.plotting.paths import coupler_curves_figure  # noqa: E402

display(coupler_curves_figure(scene, res))
display(motion_figure(scene, res, "velocity"))

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

# %% [markdown]
# ## Stroke-time ratio K (the four-bar design textbook section, Sources [2])
#
# The rocker's extreme positions are where crank and coupler are in line:
# stretched, $|AC_1| = l_2 + l_1$, and folded, $|AC_2| = l_2 - l_1$.  The
# angle $\theta$ between $AC_1$ and $AC_2$ is the extreme-position angle and
# $K = (180° + \theta)/(180° - \theta)$ (slow stroke over quick stroke).  From the sweep instead: the crank
# angles where $\omega_3$ changes sign (linear interpolation between the 1°
# steps, error $O(h^2)$ of the step) split the turn into the two strokes.

# %%
l2 = np.linalg.norm(C - B)
lAD = np.linalg.norm(D - A)


def angle_at_A(r):  # angle DAC of triangle A, D, C with |AC| = r (law of cosines)
    return np.arccos((r**2 + lAD**2 - l3**2) / (2 * r * lAD))


theta = abs(np.degrees(angle_at_A(l2 - l1) - angle_at_A(l2 + l1)))  # both with C above AD
K_closed = (180 + theta) / (180 - theta)
t = th1[flips] + (th1[flips + 1] - th1[flips]) * w[flips] / (w[flips] - w[flips + 1])
stroke = np.degrees(t[1] - t[0])
K_sweep = max(stroke, 360 - stroke) / min(stroke, 360 - stroke)
print(f"extreme-position angle {theta:.4f} deg; K = {K_closed:.5f} (closed form), "
      f"{K_sweep:.5f} (from the sweep)")
assert abs(K_sweep - K_closed) < 1e-3  # interpolation over 1-deg steps

# %% [markdown]
# ## The coupler point P (kinematics chapter, eq. 3-18)
#
# The scene traces a coupler point `P` (its `points`).  With $(a, b)$ its
# coordinates along and across $BC$, eq. 3-18 gives
# $l_P = l_1 e^{i\theta_1} + (a + i b) e^{i\theta_2}$ from the crank pivot.

# %%
P0 = np.array(scene.points[0].at)
u = (C - B) / l2
a, b = (P0 - B) @ u, u[0] * (P0 - B)[1] - u[1] * (P0 - B)[0]
zP = (A[0] + 1j * A[1]) + l1 * np.exp(1j * th1) + (a + 1j * b) * np.exp(1j * th2)
got = res.points["P"].position
err = np.max(np.abs(got[:, 0] + 1j * got[:, 1] - zP)) / l2
print(f"coupler curve of P: x in [{got[:, 0].min():.4f}, {got[:, 0].max():.4f}] m, "
      f"y in [{got[:, 1].min():.4f}, {got[:, 1].max():.4f}] m; "
      f"max difference from eq. 3-18: {err:.1e} of BC")
assert err < 1e-12
