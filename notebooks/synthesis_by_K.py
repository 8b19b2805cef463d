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
# # A crank-rocker designed by its stroke-time ratio K
#
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
#
# The four-bar design textbook section (README, Sources [2]) designs a crank-rocker with
# quick return from the stroke-time ratio $K$, the rocker's length and its swing $\psi$:
# the extreme-position angle is $\theta = 180°\,(K-1)/(K+1)$ (eq. 2-2), and the crank pivot
# `A` lies on the auxiliary circle through the rocker's extreme positions $C_1$, $C_2$, which
# sees the chord $C_1C_2$ under $\theta$. One more condition fixes the design; here the frame
# length $AD$. `linkage_sym.synthesis.crank_rocker` does this (the command line:
# `linkage-sym synthesize crank-rocker --K 1.45 --rocker 0.08 --swing 50 --ground 0.1`),
# and we check the design by analysing it with the solver.

# %%
# %matplotlib inline
import math

import numpy as np
from numpy.polynomial import Polynomial

import linkage_sym
from linkage_sym.synthesis import crank_rocker, extreme_position_angle

K_REQ, ROCKER, SWING_DEG, GROUND = 1.45, 0.08, 50.0, 0.1
design = crank_rocker(K=K_REQ, rocker=ROCKER, swing_deg=SWING_DEG, ground=GROUND)
print({k: round(v, 6) for k, v in design.lengths.items()})
print("theta = %.6f deg, auxiliary arc: %s" % (math.degrees(design.theta), design.extra["arc"]))
print("minimum transmission angle %.4f deg at %s" % (math.degrees(design.gamma_min),
                                                     design.gamma_min_where))
for note in design.notes:
    print(note)
assert math.isclose(math.degrees(extreme_position_angle(K_REQ)), 180 * (K_REQ - 1) / (K_REQ + 1))

# %% [markdown]
# ## The design from its lengths, by hand
# At the extremes crank and coupler are in line: $AC_1 = b + a$ (extended),
# $AC_2 = b - a$ (overlapping). The law of cosines in the triangles $AC_1D$ and $AC_2D$ gives
# the rocker's two extreme angles at `D`, whose difference is the swing, and the angle at `A`
# between $AC_1$ and $AC_2$, which is $\theta$.

# %%
a, b, c, d = (design.lengths[k] for k in ("crank", "coupler", "rocker", "ground"))


def angle(p, q, r):
    """Angle opposite side r in the triangle with sides p, q, r."""
    return math.acos((p * p + q * q - r * r) / (2 * p * q))


psi_hand = abs(angle(c, d, b + a) - angle(c, d, b - a))
theta_hand = abs(angle(b + a, d, c) - angle(b - a, d, c))
print("swing %.9f deg, theta %.9f deg" % (math.degrees(psi_hand), math.degrees(theta_hand)))
assert math.isclose(math.degrees(psi_hand), SWING_DEG, abs_tol=1e-9)
assert math.isclose(theta_hand, design.theta, abs_tol=1e-12)

# %% [markdown]
# ## Analysed by the solver
# The scene the design returns is a plain scene dict, assembled at the extreme position $C_1$
# and swept over one full turn of the crank (361 steps).

# %%
scene = linkage_sym.load_scene(design.scene)
res = linkage_sym.analyze(scene)
assert (res.status == "ok").all()
q, qd = res.drivers["A"]["q"], res.drivers["A"]["qd"]
rocker = res.links["rocker"]
w, al, rot = rocker.omega, rocker.alpha, rocker.rotation
print("rocker omega at the first step: %.2e rad/s (an extreme position)" % w[0])
assert abs(w[0]) < 1e-12 * np.abs(w).max()

# %% [markdown]
# ## K and the swing from the roots of the rocker's angular velocity
# The rocker's extreme positions are where $\omega_3 = 0$. The first is the assembly
# position (step 0); the other lies between two samples. Between them we interpolate
# $\omega_3(\varphi)$ by a cubic Hermite polynomial (values $\omega_3$, slopes
# $d\omega_3/d\varphi = \alpha_3/\dot\varphi$) and take its root; the rocker's rotation there
# from the Hermite cubic of the rotation (slopes $\omega_3/\dot\varphi$). The crank turns
# through $\varphi_2 - \varphi_1$ in one stroke and the rest of the turn in the other, so
# $K$ is the ratio of the two.

# %%
def hermite(x0, x1, f0, f1, s0, s1):
    """Cubic Hermite interpolant on [x0, x1], as a polynomial in t = (x - x0)/(x1 - x0)."""
    h, t = x1 - x0, Polynomial([0.0, 1.0])
    return (f0 * (2 * t**3 - 3 * t**2 + 1) + h * s0 * (t**3 - 2 * t**2 + t)
            + f1 * (-2 * t**3 + 3 * t**2) + h * s1 * (t**3 - t**2))


i = int(np.flatnonzero(np.sign(w[1:-2]) != np.sign(w[2:-1]))[0]) + 1
pw = hermite(q[i], q[i + 1], w[i], w[i + 1], al[i] / qd[i], al[i + 1] / qd[i + 1])
t = next(r.real for r in pw.roots() if abs(r.imag) < 1e-12 and 0 <= r.real <= 1)
phi2 = q[i] + t * (q[i + 1] - q[i])
rot2 = hermite(q[i], q[i + 1], rot[i], rot[i + 1], w[i] / qd[i], w[i + 1] / qd[i + 1])(t)
stroke = phi2 - q[0]
K_solver = max(stroke, 2 * np.pi - stroke) / min(stroke, 2 * np.pi - stroke)
swing_solver = abs(rot2 - rot[0])
print("extremes at crank angles %.6f and %.6f deg (the second between steps %d and %d)"
      % (math.degrees(q[0]), math.degrees(phi2), i, i + 1))
print("K: requested %.6f, solver %.12f" % (K_REQ, K_solver))
print("swing: requested %.6f deg, solver %.12f deg" % (SWING_DEG, math.degrees(swing_solver)))
assert abs(K_solver - K_REQ) < 1e-8
assert abs(math.degrees(swing_solver) - SWING_DEG) < 1e-7

# %% [markdown]
# Linear interpolation of $\omega_3$ alone would miss by the curvature of
# $\omega_3$ over a 1° step:

# %%
phi2_lin = q[i] - w[i] * (q[i + 1] - q[i]) / (w[i + 1] - w[i])
s_lin = phi2_lin - q[0]
K_lin = max(s_lin, 2 * np.pi - s_lin) / min(s_lin, 2 * np.pi - s_lin)
print("K from linear interpolation: %.9f (error %.1e)" % (K_lin, K_lin - K_REQ))
assert abs(K_solver - K_REQ) < abs(K_lin - K_REQ)

# %% [markdown]
# ## Coupler curves and the transmission angle
# The joints' paths over the turn, and the transmission angle at `C` (between coupler and
# rocker) against the crank angle, its minimum marked.

# %%
from IPython.display import display  # noqa: E402

from linkage_sym.plotting.paths import coupler_curves_figure  # noqa: E402
from linkage_sym.plotting.transmission import transmission_figure  # noqa: E402

display(coupler_curves_figure(scene, res))
display(transmission_figure(scene, res))

# %% [markdown]
# The transmission angle by hand: with the crank angle $\varphi$ from `AD` (the frame lies
# along $+x$), $BD^2 = a^2 + d^2 - 2ad\cos\varphi$ and
# $\cos\gamma = (b^2 + c^2 - BD^2)/(2bc)$. Its smallest deviation from 90° over the
# samples is no smaller than the design's minimum, which sits at a crank angle of 0° or 180°.

# %%
gamma = res.transmission_angles["C"]
BD2 = a * a + d * d - 2 * a * d * np.cos(q)
gamma_hand = np.arccos((b * b + c * c - BD2) / (2 * b * c))
print("largest difference from the solver: %.1e rad" % np.abs(gamma_hand - gamma).max())
assert np.abs(gamma_hand - gamma).max() < 1e-12
g_min_samples = np.minimum(gamma, np.pi - gamma).min()
g_min_exact = min(min(g, np.pi - g) for g in (np.arccos((b * b + c * c - (d - a) ** 2) / (2 * b * c)),
                                              np.arccos((b * b + c * c - (d + a) ** 2) / (2 * b * c))))
print("minimum transmission angle: samples %.6f deg, exact %.6f deg, design %.6f deg"
      % tuple(map(math.degrees, (g_min_samples, g_min_exact, design.gamma_min))))
assert math.isclose(g_min_exact, design.gamma_min, abs_tol=1e-12)
assert g_min_exact <= g_min_samples < g_min_exact + 1e-2
