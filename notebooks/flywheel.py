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
# # Sizing a flywheel: the energy method, then the simulated motion
#
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
#
# A flywheel problem of the kind the textbook course sets after kinetostatics (its chapter on
# speed fluctuation is not among the sources we have, so the numbers are ours; the method is
# the textbook's energy method): a machine's main shaft meets a resisting moment
# $M_r = 300$ N·m over the first half of each turn and none over the second; the motor's
# moment $M_d$ is constant; the mean speed is $\omega_m = 100$ rad/s and the coefficient of
# speed fluctuation may be at most $[\delta] = 0.02$. Worked by hand: over a cycle the work
# balances, $M_d \cdot 2\pi = 300 \cdot \pi$, so $M_d = 150$ N·m; the surplus of the driving
# over the resisting work is $-150\,\varphi$ over the first half turn and climbs back over the
# second, so the largest energy surplus is $\Delta W_{max} = 150\,\pi = 471.2$ J and
# $$J_F = \frac{\Delta W_{max}}{\omega_m^2 [\delta]} = \frac{471.2}{100^2 \cdot 0.02}
# = 2.356\ \text{kg·m}^2$$
# (the mechanism's own inertia neglected).

# %%
# %matplotlib inline
import copy
import math

import matplotlib.pyplot as plt
import numpy as np

import linkage_sym
from linkage_sym.examples import example_dict

by_hand = 150 * math.pi / (100**2 * 0.02)
print(f"J_F by hand: {by_hand:.4f} kg m^2")

# %% [markdown]
# The main shaft is the crank of the crank-rocker of the scene format (its light coupler and
# rocker add a little inertia of their own). The resisting moment is a load on the crank that
# acts over $0$ to $180°$ (the format's *loads over the cycle*). The problem's constant driving
# moment is a motor whose moment falls steeply through 150 N·m at 100 rad/s: so the machine has
# a steady mean speed, 100 rad/s.

# %%
d = copy.deepcopy(example_dict("crank_rocker"))
d["name"] = "main-shaft"
d["loads"] = [{"link": "crank", "torque": -300.0, "active_deg": [0, 180], "driver": "A"}]
d["effects"]["gravity"] = False
d["drivers"][0]["motor"] = {"torque": [[90.0, 450.0], [110.0, -150.0]]}
scene = linkage_sym.load_scene(d)
fly = linkage_sym.flywheel(scene, 0.02)
e = fly.energy
print(f"energy method: dW_max = {e['delta_E_max']:.4f} J at {e['mean_speed']:.4f} rad/s, "
      f"J_F = {fly.estimate:.4f} kg m^2 (by hand {by_hand:.4f}); its simulated "
      f"fluctuation {fly.estimate_fluctuation:.5f}")
print(f"refined by simulation: J_F = {fly.inertia:.4f} kg m^2, fluctuation "
      f"{fly.fluctuation:.5f} at the mean speed {fly.mean_speed:.4f} rad/s")
assert abs(e["delta_E_max"] - 150 * math.pi) < 2e-3 * 150 * math.pi  # trapezoidal rule, 7200 points

# %% [markdown]
# The energy method assumes the speed constant in the efforts and $\omega_{max}^2 -
# \omega_{min}^2 = 2\delta\omega_m^2$; the simulated periodic motion with that flywheel shows
# how close it comes. The energy diagram (the work surplus over the turn) and the speed over
# the turn with the refined flywheel:

# %%
fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.5))
a.plot(np.degrees(e["q"]), e["energy"])
a.set_xlabel("crank angle (degrees)")
a.set_ylabel("work surplus ΔW (J)")
a.set_title(f"energy diagram: ΔW_max = {e['delta_E_max']:.1f} J")
traj = fly.orbit["trajectory"]
t = np.linspace(traj.t[0], traj.t_end, 1000)
q, w = traj(t)
b.plot(np.degrees(q), w)
b.axhline(fly.mean_speed, ls="--", color="0.5")
b.set_xlabel("crank angle (degrees)")
b.set_ylabel("speed (rad/s)")
b.set_title(f"J_F = {fly.inertia:.3f} kg·m²: δ = {fly.fluctuation:.4f}")
fig.tight_layout()
